//! Bad configurations give typed errors naming the file and the field or line.

use std::path::{Path, PathBuf};

use pipeline::PipelineError;

use super::paper_text;

fn parse(text: &str) -> Result<pipeline::Inputs, PipelineError> {
    pipeline::parse_study(text, Path::new("bad.ron"))
}

#[test]
fn unreadable_file_names_the_file() {
    let missing = PathBuf::from("/nonexistent/study.ron");
    match pipeline::load_study(&missing) {
        Err(PipelineError::File(edge_io::EdgeIoError::Read { path, .. })) => {
            assert_eq!(path, missing)
        }
        other => panic!("expected Io, got {other:?}"),
    }
}

#[test]
fn unknown_field_names_the_line() {
    let text = paper_text().replace("radius_m: 2.5,", "radius_m: 2.5,\n    radius_mm: 2500.0,");
    match parse(&text) {
        Err(PipelineError::Parse {
            path,
            line,
            message,
            ..
        }) => {
            assert_eq!(path, Path::new("bad.ron"));
            assert!(line > 1, "line {line}");
            assert!(message.contains("radius_mm"), "{message}");
        }
        other => panic!("expected Parse, got {other:?}"),
    }
}

#[test]
fn missing_field_is_named() {
    let text = paper_text().replace("k1_rad_s_g: 0.56,", "");
    match parse(&text) {
        Err(PipelineError::Parse { message, .. }) => {
            assert!(message.contains("k1_rad_s_g"), "{message}")
        }
        other => panic!("expected Parse, got {other:?}"),
    }
}

#[test]
fn malformed_ron_names_the_line() {
    let text = paper_text().replace("g_m_s2: 9.8,", "g_m_s2: 9.8.1,");
    match parse(&text) {
        Err(PipelineError::Parse { line, .. }) => {
            let want = paper_text()
                .lines()
                .position(|l| l.contains("g_m_s2"))
                .unwrap()
                + 1;
            assert_eq!(line, want);
        }
        other => panic!("expected Parse, got {other:?}"),
    }
}

#[test]
fn negative_radius_is_refused() {
    let text = paper_text().replace("radius_m: 2.5,", "radius_m: -2.5,");
    match parse(&text) {
        Err(PipelineError::InvalidField { field, value, .. }) => {
            assert_eq!(field, "radius_m");
            assert_eq!(value, -2.5);
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
}

#[test]
fn non_finite_number_is_refused_with_its_field() {
    let text = paper_text().replace("dc1_um: -3.1877", "dc1_um: NaN");
    match parse(&text) {
        Err(PipelineError::InvalidField { field, .. }) => {
            assert_eq!(field, "phases[1].points[2].dc1_um");
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
    let text = paper_text().replace("change_um: 19.4640", "change_um: inf");
    match parse(&text) {
        Err(PipelineError::InvalidField { field, .. }) => {
            assert_eq!(field, "phases[0].points.change_um");
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
}

#[test]
fn duplicate_rates_are_refused() {
    let text = paper_text().replace("rate_deg_s: 60.0,", "rate_deg_s: 10.0,");
    match parse(&text) {
        Err(PipelineError::DuplicateRate {
            field,
            first,
            rate_deg_s,
            ..
        }) => {
            assert_eq!(field, "phases[1].points[1].rate_deg_s");
            assert_eq!(first, "phases[1].points[0].rate_deg_s");
            assert_eq!(rate_deg_s, 10.0);
        }
        other => panic!("expected DuplicateRate, got {other:?}"),
    }
}

#[test]
fn fewer_points_than_unknowns_is_refused() {
    let text = r#"(
        name: "few", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56, radius_model: three_term,
        lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
        phases: [(name: "pre_balance", points: radius_error([(rate_deg_s: 10.0, radius_error_um: 0.0),
                                            (rate_deg_s: 20.0, radius_error_um: 0.1),
                                            (rate_deg_s: 30.0, radius_error_um: 0.3),
                                            (rate_deg_s: 40.0, radius_error_um: 0.6)])),
        (name: "post_balance", points: radius_error([(rate_deg_s: 10.0, radius_error_um: 1.0),
                                             (rate_deg_s: 200.0, radius_error_um: 0.9)]))],
    )"#;
    match parse(text) {
        Err(PipelineError::TooFewPoints {
            field, got, need, ..
        }) => {
            assert_eq!(field, "phases[1].points");
            assert_eq!((got, need), (2, 4));
        }
        other => panic!("expected TooFewPoints, got {other:?}"),
    }
}

#[test]
fn zero_or_negative_rate_is_refused() {
    let text = paper_text().replace("rate_deg_s: 60.0,", "rate_deg_s: -60.0,");
    match parse(&text) {
        Err(PipelineError::InvalidField { field, .. }) => {
            assert_eq!(field, "phases[1].points[1].rate_deg_s");
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
}

#[test]
fn bad_lever_geometry_is_refused() {
    let text = paper_text().replace("pivot_to_probe_mm: 700.0", "pivot_to_probe_mm: 0.0");
    match parse(&text) {
        Err(PipelineError::Harmonics { field, .. }) => assert_eq!(field, "lever"),
        other => panic!("expected Harmonics, got {other:?}"),
    }
}

#[test]
fn mechanism_needs_seven_distinct_finite_rates() {
    let text = paper_text().replace(
        "rates_deg_s: [10.0, 40.0, 60.0, 80.1234, 110.1234, 140.0, 160.1234, 200.1234]",
        "rates_deg_s: [10.0, 40.0, 60.0, 80.1234, 110.1234, 200.1234]",
    );
    match parse(&text) {
        Err(PipelineError::TooFewPoints {
            field, got, need, ..
        }) => {
            assert_eq!(field, "mechanism.rates_deg_s");
            assert_eq!((got, need), (6, 7));
        }
        other => panic!("expected TooFewPoints, got {other:?}"),
    }
    let text = paper_text().replace("140.0, 160.1234", "140.0, 140.0");
    match parse(&text) {
        Err(PipelineError::DuplicateRate { field, .. }) => {
            assert_eq!(field, "mechanism.rates_deg_s[6]");
        }
        other => panic!("expected DuplicateRate, got {other:?}"),
    }
    let text = paper_text().replace("k2_rad_s_g2: 2.0e-6", "k2_rad_s_g2: NaN");
    match parse(&text) {
        Err(PipelineError::InvalidField { field, .. }) => {
            assert_eq!(field, "mechanism.k2_rad_s_g2")
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
    let text = paper_text().replace("latitude_deg: 45.0", "latitude_deg: 95.0");
    match parse(&text) {
        Err(PipelineError::InvalidField { field, .. }) => {
            assert_eq!(field, "mechanism.latitude_deg")
        }
        other => panic!("expected InvalidField, got {other:?}"),
    }
}

#[test]
fn phase_names_are_unique_and_valid() {
    let text = paper_text().replace("name: \"post_balance\"", "name: \"pre_balance\"");
    match parse(&text) {
        Err(PipelineError::DuplicateName {
            field, first, name, ..
        }) => {
            assert_eq!(field, "phases[1].name");
            assert_eq!(first, "phases[0].name");
            assert_eq!(name, "pre_balance");
        }
        other => panic!("expected DuplicateName, got {other:?}"),
    }
    let text = paper_text().replace("name: \"post_balance\"", "name: \"after balancing\"");
    match parse(&text) {
        Err(PipelineError::InvalidName { field, .. }) => assert_eq!(field, "phases[1].name"),
        other => panic!("expected InvalidName, got {other:?}"),
    }
}

#[test]
fn a_study_without_phases_is_refused() {
    let text = paper_text();
    let start = text.find("phases: [").unwrap();
    let end = text.find("    ],\n").unwrap() + "    ],\n".len();
    let text = format!("{}phases: [],\n{}", &text[..start], &text[end..]);
    match parse(&text) {
        Err(PipelineError::EmptyList { field, .. }) => assert_eq!(field, "phases"),
        other => panic!("expected EmptyList, got {other:?}"),
    }
}

#[test]
fn the_mechanism_names_known_phases() {
    let text = paper_text().replace(
        "k0_rad_s: 1.0e-4,",
        "k0_rad_s: 1.0e-4,\n        phases: [\"post_balance\", \"trial\"],",
    );
    match parse(&text) {
        Err(PipelineError::UnknownPhase {
            field, name, known, ..
        }) => {
            assert_eq!(field, "mechanism.phases[1]");
            assert_eq!(name, "trial");
            assert_eq!(known, ["pre_balance", "post_balance"]);
        }
        other => panic!("expected UnknownPhase, got {other:?}"),
    }
}

/// `radius_m: 1e-160` is a valid number whose square underflows: before, the study returned
/// Δk2 = −inf (−inf in the summary and report, `null` in results.json); now a typed error
/// names Δk2 and the inputs.
#[test]
fn a_radius_whose_square_underflows_is_a_named_error_not_an_infinite_delta_k2() {
    let text = paper_text().replace("radius_m: 2.5,", "radius_m: 1e-160,");
    let inputs = parse(&text).expect("a tiny radius is a valid configuration");
    let err = pipeline::run(&inputs).unwrap_err();
    let chain = {
        let mut text = err.to_string();
        let mut source = std::error::Error::source(&err);
        while let Some(s) = source {
            text.push_str(&format!(": {s}"));
            source = s.source();
        }
        text
    };
    assert!(
        matches!(
            &err,
            PipelineError::Identify {
                source: identify::IdentifyError::NonFiniteResult {
                    quantity: "delta_k2_rad_s_g2",
                    ..
                },
                ..
            }
        ),
        "{err:?}"
    );
    assert!(chain.contains("radius_m = 1e-160"), "{chain}");
}
