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

/// The study file at `name` under fixtures/studies with `from` replaced by `to`, parsed as if
/// it were there (its data files resolve).
fn fixture_with(name: &str, from: &str, to: &str) -> Result<pipeline::Inputs, PipelineError> {
    let path = super::root().join("fixtures/studies").join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(from), "{from} not in {name}");
    pipeline::parse_study(&text.replacen(from, to, 1), &path)
}

#[test]
fn a_billion_fixed_trials_is_refused_at_check_with_its_cost() {
    // Before issue 32 this passed `check` and the study aborted on an 8 GB allocation.
    for (name, from, field) in [
        ("campaign.ron", "k1: fitted,", "calibration.trials"),
        (
            "two_orientation.ron",
            "compare_with: \"spindle\",",
            "two_orientation.trials",
        ),
    ] {
        let to = format!("{from} trials: fixed(1000000000),");
        let e = fixture_with(name, from, &to).unwrap_err();
        let text = super::chain(&e);
        let error = match &e {
            PipelineError::Several { errors } => errors
                .iter()
                .find(|e| matches!(e, PipelineError::Uncertainty { .. }))
                .unwrap_or_else(|| panic!("{text}")),
            other => other,
        };
        match error {
            PipelineError::Uncertainty {
                field: f, source, ..
            } => {
                assert_eq!(f, field);
                assert!(
                    matches!(
                        **source,
                        uncertainty::UncertaintyError::TooManyTrials {
                            trials: 1_000_000_000,
                            max: uncertainty::MAX_TRIALS,
                            ..
                        }
                    ),
                    "{source:?}"
                );
            }
            other => panic!("{name}: {other:?}"),
        }
        assert!(
            text.contains("trials = 1000000000: at most 10000000 Monte Carlo trials are drawn")
                && text.contains("GiB) of model values")
                && text.contains("s of CPU"),
            "{text}"
        );
        // At the cap it is accepted (the calibration's 6 outputs keep 480 MB).
        let to = format!("{from} trials: fixed(10000000),");
        assert!(fixture_with(name, from, &to).is_ok(), "{name} at the cap");
    }
}

#[test]
fn one_recording_at_two_rates_is_refused_at_check() {
    // The 20 deg/s recording listed again at 40 deg/s: its encoder says 20.
    let e = fixture_with(
        "recordings-small.ron",
        "probe_040.0000deg_s.csv",
        "probe_020.0000deg_s.csv",
    )
    .unwrap_err();
    let text = super::chain(&e);
    assert!(
        text.contains("phases[0].points.files[1]")
            && text
                .contains("is the same recording as `phases[0].points.files[0]` (the same file)"),
        "{text}"
    );
    // Two files with the same bytes under two names: the same.
    let scratch = test_support::Scratch::new("pipeline-same-bytes");
    let recordings = super::root().join("fixtures/recordings/pre-balance-small");
    let copy = scratch.0.join("copy_of_020.csv");
    std::fs::copy(recordings.join("probe_020.0000deg_s.csv"), &copy).unwrap();
    let e = fixture_with(
        "recordings-small.ron",
        "../recordings/pre-balance-small/probe_040.0000deg_s.csv",
        copy.to_str().unwrap(),
    );
    // Through files on disk the digest tells the same bytes (`parse_study` reads through
    // `pipeline::Files`); the encoder's rate alone would refuse it too.
    let text = super::chain(&e.unwrap_err());
    assert!(
        text.contains("is the same recording as `phases[0].points.files[0]` (the same bytes)"),
        "{text}"
    );
}

#[test]
fn an_encoder_that_disagrees_with_the_declared_rate_is_refused_at_check() {
    // What the analysis found only when the study ran (issue 32), found at loading.
    let e = fixture_with(
        "recordings-small.ron",
        "(rate_deg_s: 40.0,",
        "(rate_deg_s: 45.0,",
    )
    .unwrap_err();
    let text = super::chain(&e);
    assert!(
        text.contains("phases[0].points.files[1]") && text.contains("differs from the encoder"),
        "{text}"
    );
}

#[test]
fn an_implausible_g_is_refused() {
    for g in ["1e300", "1.0", "9.81e-3"] {
        let text = paper_text().replace("g_m_s2: 9.8,", &format!("g_m_s2: {g},"));
        let e = parse(&text).unwrap_err();
        match &e {
            PipelineError::InvalidField { field, .. } => assert_eq!(field, "g_m_s2"),
            other => panic!("{g}: {other:?}"),
        }
        let message = e.to_string();
        assert!(
            message.contains("must lie within 9.7…9.9 m/s²"),
            "{message}"
        );
        assert!(!message.contains("0000000000"), "{message}");
    }
}
