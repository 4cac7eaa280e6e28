//! Recordings as labs export them (issue 10): one simulated campaign of known C_r, written
//! in each variant, run as a study in memory. Every variant either gives C_r within 3σ of
//! the truth, or a warning that says the number may be wrong, or an error that names the
//! file, the line and the fix. Run with `--nocapture` to see the numbers quoted in
//! docs/YOUR-DATA.md.

// The measurements are printed for the documentation; only the assertions decide.
#![allow(clippy::print_stdout)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use pipeline::{Inputs, PipelineError, StudyConfig, StudyResults};
use recording::{AngleSourceKind, Hint, RecordingError};
use simulate::{Scenario, SimulatedRecording};

/// The C_r of the simulated spindle, m·s².
const C_R_TRUE: f64 = 1.2e-6;
/// Declared rates, deg/s (not commensurate with the 200 Hz sampling, as real ones are not).
const RATES: [f64; 6] = [20.1234, 40.1234, 80.1234, 110.1234, 160.1234, 200.1234];

/// The campaign, its spindle turning `rate_factor` times the declared rates.
fn campaign(rate_factor: f64) -> Vec<SimulatedRecording> {
    let rates: Vec<String> = RATES
        .iter()
        .map(|r| format!("{}", r * rate_factor))
        .collect();
    let text = format!(
        r#"(
    name: "lab", seed: 11,
    centrifuge: (radius_m: 2.5, site: (latitude_deg: 39.9, earth_rate_rad_s: 7.292115e-5, gravity_m_s2: 9.8)),
    error_motion: Coefficients((dr_xs_m: 5.6e-6, dr_ys_m: -1.97e-6, c_r_m_s2: {C_R_TRUE:e}, c_r_y_m_s2: 0.3e-6)),
    probe: (
        lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0, probe_direction: against_o1_x1),
        sample_rate_hz: 200.0, noise_um: 0.05, l0_um: 50.0,
        sleeve_harmonics: [(order: 2, c_um: 0.35, s_um: -0.12)],
        encoder_angle: true, start_angle_deg: 40.0,
    ),
    piga: (coefficients: (k0_rad_s: 0.0, k1_rad_s_g: 0.56, k2_rad_s_g2: 5.0e-7, k3_rad_s_g3: 0.0)),
    rates_deg_s: [{}], revolutions: 2, min_duration_s: 72.0,
)"#,
        rates.join(", ")
    );
    let scenario = Scenario::parse(&text, Path::new("lab.ron")).unwrap();
    simulate::simulate(&scenario).unwrap().recordings
}

/// One row's text from (index, time s, gap µm, encoder angle deg).
type Row<'a> = &'a dyn Fn(usize, f64, f64, f64) -> String;

/// A recording written as `header` then one row per sample.
fn write(rec: &SimulatedRecording, header: &str, row: Row<'_>) -> Vec<u8> {
    let mut out = String::from(header);
    out.push('\n');
    let angle = rec.angle_deg.as_ref().unwrap();
    for (i, ((&t, &g), &a)) in rec.time_s.iter().zip(&rec.gap_um).zip(angle).enumerate() {
        out += &row(i, t, g, a);
        out.push('\n');
    }
    out.into_bytes()
}

/// The study of the files with this format and fit, run in memory.
fn study(
    recs: &[SimulatedRecording],
    format: &str,
    fit: &str,
    header: &str,
    row: Row<'_>,
) -> Result<StudyResults, PipelineError> {
    let files: HashMap<PathBuf, Vec<u8>> = recs
        .iter()
        .enumerate()
        .map(|(i, r)| {
            (
                PathBuf::from(format!("/nonexistent/f{i}.csv")),
                write(r, header, row),
            )
        })
        .collect();
    let list: Vec<String> = RATES
        .iter()
        .enumerate()
        .map(|(i, r)| format!("(rate_deg_s: {r}, file: \"f{i}.csv\")"))
        .collect();
    let text = format!(
        r#"(name: "lab", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
    lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0, probe_direction: against_o1_x1),
    phases: [(name: "pre_balance", points: recordings((format: {format}, fit: {fit}, files: [{}])))])"#,
        list.join(", ")
    );
    let source = Path::new("/nonexistent/lab.ron");
    let config = StudyConfig::from_ron(&text, source).unwrap();
    let inputs = Inputs::new(config, source, &Texts(files))?;
    pipeline::run(&inputs)
}

/// Files held in memory as text, parsed as the study asks.
use test_support::MemoryFiles as Texts;

/// C_r, its σ and the warning codes.
fn c_r(results: &StudyResults) -> (f64, f64, Vec<String>) {
    let fit = &results.phases[0].fit;
    let codes = results
        .warnings
        .iter()
        .map(|w| w.code.to_string())
        .collect();
    (fit.c_r_m_s2, fit.c_r_sigma_m_s2.unwrap(), codes)
}

/// C_r within 3σ of the truth, and the given warning codes exactly.
fn assert_right(results: &StudyResults, codes: &[&str], what: &str) {
    let (c, s, got) = c_r(results);
    println!("{what}: C_r = {c:e} ± {s:e} (truth {C_R_TRUE:e}), warnings {got:?}");
    assert!(
        (c - C_R_TRUE).abs() < 3.0 * s,
        "{what}: C_r = {c:e} ± {s:e}, truth {C_R_TRUE:e}"
    );
    let mut got = got;
    got.dedup();
    assert_eq!(got, codes, "{what}");
}

/// The study refused with the recording error of file `f{index}.csv` that `check` accepts.
fn assert_error(
    result: Result<StudyResults, PipelineError>,
    what: &str,
    check: &dyn Fn(&RecordingError) -> bool,
) {
    let e = result.err().unwrap_or_else(|| panic!("{what}: no error"));
    let first = match &e {
        PipelineError::Several { errors } => &errors[0],
        e => e,
    };
    let PipelineError::Recording { field, source, .. } = first else {
        panic!("{what}: {e}")
    };
    println!("{what}: {field}: {source}");
    assert_eq!(field, "phases[0].points.files[0]", "{what}");
    assert!(
        source.to_string().contains("/nonexistent/f0.csv:"),
        "{source}"
    );
    assert!(check(source), "{what}: {source}");
}

const DEFAULT: &str = "()";
const NO_DRIFT: &str = "(drift: false)";

fn documented(_: usize, t: f64, g: f64, a: f64) -> String {
    format!("{t:.6},{g:.5},{a:.5}")
}

#[test]
fn documented_format() {
    let recs = campaign(1.0);
    let r = study(
        &recs,
        DEFAULT,
        NO_DRIFT,
        "time_s,gap_um,angle_deg",
        &documented,
    )
    .unwrap();
    assert_right(&r, &[], "documented");
    for p in &r.phases[0].points {
        assert_eq!(p.angle_source, Some(AngleSourceKind::Encoder));
        let m = p.measured_rate_deg_s.unwrap();
        assert!((m / p.rate_deg_s - 1.0).abs() < 1e-6, "{m}");
    }
}

/// A marker that is 1 for the first 4 samples of each revolution.
fn pulse(a_prev: f64, a: f64) -> u8 {
    u8::from(a < a_prev || a < 4.0 * 0.36)
}

#[test]
fn index_pulse() {
    let recs = campaign(1.0);
    let row = |i: usize, t: f64, g: f64, a: f64| {
        let prev = if i == 0 { a } else { a - 1.0 };
        format!("{t:.6},{g:.5},{}", pulse(prev, a))
    };
    // Read with the default format, the marker is not an angle: the angle comes from the
    // declared rate with a start angle of 0 (the truth starts at 40°), and a warning says
    // so and names the column.
    let r = study(&recs, DEFAULT, NO_DRIFT, "time_s,gap_um,index", &row).unwrap();
    let (c, s, codes) = c_r(&r);
    println!("index pulse, default format: C_r = {c:e} ± {s:e}, warnings {codes:?}");
    assert!(codes.contains(&"angle_from_rate".to_string()));
    assert!(
        r.warnings[0].message.contains("`index`"),
        "{}",
        r.warnings[0].message
    );
    // Named as an index pulse: right.
    let r = study(
        &recs,
        r#"(angle: index_pulse(column: "index"))"#,
        NO_DRIFT,
        "time_s,gap_um,index",
        &row,
    )
    .unwrap();
    assert_right(&r, &[], "index pulse");
    assert_eq!(
        r.phases[0].points[0].angle_source,
        Some(AngleSourceKind::IndexPulse)
    );
}

fn counts(a_deg: f64) -> u64 {
    (a_deg / 360.0 * 1_048_576.0).round() as u64 % 1_048_576
}

#[test]
fn encoder_counts() {
    let recs = campaign(1.0);
    let row = |_: usize, t: f64, g: f64, a: f64| format!("{t:.6},{g:.5},{}", counts(a));
    // Default format: the column is not read; the warning says the angle is from the rate.
    let r = study(&recs, DEFAULT, NO_DRIFT, "time_s,gap_um,encoder", &row).unwrap();
    let (c, s, codes) = c_r(&r);
    println!("counts, default format: C_r = {c:e} ± {s:e}, warnings {codes:?}");
    assert!(codes.contains(&"angle_from_rate".to_string()));
    // Counts in a column the default format reads as degrees: refused, with the fix.
    assert_error(
        study(&recs, DEFAULT, NO_DRIFT, "time_s,gap_um,angle_deg", &row),
        "counts read as degrees",
        &|e| {
            matches!(
                e,
                RecordingError::Samples {
                    hint: Some(Hint::EncoderCounts),
                    ..
                }
            )
        },
    );
    let r = study(
        &recs,
        r#"(angle: encoder(column: "encoder", unit: counts(per_rev: 1048576)))"#,
        NO_DRIFT,
        "time_s,gap_um,encoder",
        &row,
    )
    .unwrap();
    assert_right(&r, &[], "counts");
}

#[test]
fn rate_off_nominal() {
    let recs = campaign(1.003);
    // With an encoder, the measured rate is used, and the difference is reported.
    let r = study(
        &recs,
        DEFAULT,
        NO_DRIFT,
        "time_s,gap_um,angle_deg",
        &documented,
    )
    .unwrap();
    assert_right(&r, &["rate_differs"], "rate +0.3 %, encoder");
    let p = &r.phases[0].points[2];
    assert!((p.measured_rate_deg_s.unwrap() / (80.1234 * 1.003) - 1.0).abs() < 1e-6);
    // Without one, the angle drifts against the truth: warned, with the likely cause.
    let row = |_: usize, t: f64, g: f64, _: f64| format!("{t:.6},{g:.5}");
    let r = study(
        &recs,
        "(angle: rate(start_angle_deg: 40.0))",
        NO_DRIFT,
        "time_s,gap_um",
        &row,
    )
    .unwrap();
    let (c, s, codes) = c_r(&r);
    println!("rate +0.3 %, no encoder: C_r = {c:e} ± {s:e}, warnings {codes:?}");
    assert!(
        codes.contains(&"revolution_spread".to_string()),
        "{codes:?}"
    );
    let spread = r
        .warnings
        .iter()
        .find(|w| w.code == "revolution_spread")
        .unwrap();
    assert!(
        spread.message.contains("declared rate"),
        "{}",
        spread.message
    );
}

/// 0.002 µm/s of thermal drift.
fn drifting(_: usize, t: f64, g: f64, a: f64) -> String {
    format!("{t:.6},{:.5},{a:.5}", g + 0.002 * t)
}

/// The default of `drift`, by measurement: C_r with and without a drift term, on
/// drift-free and drifting recordings (the numbers in docs/YOUR-DATA.md).
#[test]
fn drift_default_by_measurement() {
    let recs = campaign(1.0);
    for (data, row) in [
        ("drift-free", &documented as Row<'_>),
        ("drifting", &drifting),
    ] {
        for fit in ["(drift: false)", "(drift: true)"] {
            let r = study(&recs, DEFAULT, fit, "time_s,gap_um,angle_deg", row).unwrap();
            let (c, s, codes) = c_r(&r);
            println!(
                "drift measurement: {data}, {fit}: C_r − truth = {:+.3e} = {:+.2}σ, σ = {s:.3e}, warnings {codes:?}",
                c - C_R_TRUE,
                (c - C_R_TRUE) / s
            );
            if fit == "(drift: true)" {
                assert!((c - C_R_TRUE).abs() < 3.0 * s, "{data} {fit}");
            }
        }
    }
}

#[test]
fn thermal_drift() {
    let recs = campaign(1.0);
    let r = study(
        &recs,
        DEFAULT,
        NO_DRIFT,
        "time_s,gap_um,angle_deg",
        &drifting,
    )
    .unwrap();
    let (c, s, codes) = c_r(&r);
    println!("drift, drift: false: C_r = {c:e} ± {s:e}, warnings {codes:?}");
    assert!(codes.contains(&"drift_not_fitted".to_string()), "{codes:?}");
    // The default fits the drift.
    let r = study(
        &recs,
        DEFAULT,
        DEFAULT,
        "time_s,gap_um,angle_deg",
        &drifting,
    )
    .unwrap();
    assert_right(&r, &[], "drift, default fit");
}

#[test]
fn european_export() {
    let recs = campaign(1.0);
    let header = "Messgerät: XY-3000\nDatum: 23.11.2026\n\nKanal 1: Spalt\nAbtastrate: 200 Hz\nZeit [s];Spalt [mm];Winkel";
    let row = |_: usize, t: f64, g: f64, a: f64| {
        format!("{t:.6};{:.8};{}", g / 1000.0, counts(a)).replace('.', ",")
    };
    let format = r#"(
        delimiter: ';', decimal: comma, skip_lines: 5,
        time: (column: "Zeit [s]", unit: s),
        gap: (column: "Spalt [mm]", unit: mm),
        angle: encoder(column: "Winkel", unit: counts(per_rev: 1048576)),
    )"#;
    let r = study(&recs, format, NO_DRIFT, header, &row).unwrap();
    assert_right(&r, &[], "european");
    // Without `decimal: comma`: the line and the fix.
    let point = format.replace("decimal: comma,", "");
    assert_error(
        study(&recs, &point, NO_DRIFT, header, &row),
        "decimal comma",
        &|e| {
            matches!(
                e,
                RecordingError::Parse {
                    line: 7,
                    hint: Some(Hint::DecimalComma),
                    ..
                }
            )
        },
    );
    // Without `skip_lines`: the metadata line is taken for the header.
    let unskipped = format.replace("skip_lines: 5,", "");
    assert_error(
        study(&recs, &unskipped, NO_DRIFT, header, &row),
        "metadata lines",
        &|e| {
            matches!(
                e,
                RecordingError::MissingColumn {
                    line: 1,
                    hint: Some(Hint::SkipLines),
                    ..
                }
            )
        },
    );
}

#[test]
fn tab_separated_with_spaces_in_names() {
    let recs = campaign(1.0);
    let row = |_: usize, t: f64, g: f64, a: f64| format!("{t:.6}\t{g:.5}\t{a:.5}");
    let format = r#"(delimiter: '\t', time: (column: "Time [s]", unit: s),
        gap: (column: "Gap [um]", unit: um), angle: encoder(column: "Angle [deg]", unit: deg))"#;
    let r = study(
        &recs,
        format,
        NO_DRIFT,
        "Time [s]\tGap [um]\tAngle [deg]",
        &row,
    )
    .unwrap();
    assert_right(&r, &[], "tab");
}

#[test]
fn time_in_milliseconds() {
    let recs = campaign(1.0);
    let row = |_: usize, t: f64, g: f64, a: f64| format!("{:.3},{g:.5},{a:.5}", t * 1e3);
    let format = r#"(time: (column: "time_ms", unit: ms))"#;
    let r = study(&recs, format, NO_DRIFT, "time_ms,gap_um,angle_deg", &row).unwrap();
    assert_right(&r, &[], "ms");
    // Milliseconds read as seconds: the encoder's rate is 1000 times too slow.
    let format = r#"(time: (column: "time_ms", unit: s))"#;
    assert_error(
        study(&recs, format, NO_DRIFT, "time_ms,gap_um,angle_deg", &row),
        "ms read as s",
        &|e| {
            matches!(
                e,
                RecordingError::Samples {
                    hint: Some(Hint::TimeUnit),
                    ..
                }
            )
        },
    );
}

/// The recording without samples `from..from + count` (a dropout).
fn dropout(from: usize, count: usize) -> impl Fn(usize, f64, f64, f64) -> String {
    move |i, t, g, a| {
        if (from..from + count).contains(&i) {
            "# dropped".into()
        } else {
            documented(i, t, g, a)
        }
    }
}

#[test]
fn dropout_of_40_ms() {
    let recs = campaign(1.0);
    let row = dropout(5000, 8);
    assert_error(
        study(&recs, DEFAULT, NO_DRIFT, "time_s,gap_um,angle_deg", &row),
        "dropout",
        &|e| matches!(e, RecordingError::SampleGap { line: 5010, .. }),
    );
    let r = study(
        &recs,
        "(on_gap: drop_revolution)",
        NO_DRIFT,
        "time_s,gap_um,angle_deg",
        &row,
    )
    .unwrap();
    assert_right(&r, &["dropped_revolutions"], "dropout");
    assert!(
        r.phases[0]
            .points
            .iter()
            .all(|p| p.dropped_revolutions == Some(1))
    );
}

#[test]
fn nan_samples() {
    let recs = campaign(1.0);
    let row = |i: usize, t: f64, g: f64, a: f64| {
        if i == 3000 {
            format!("{t:.6},NaN,{a:.5}")
        } else {
            documented(i, t, g, a)
        }
    };
    assert_error(
        study(&recs, DEFAULT, NO_DRIFT, "time_s,gap_um,angle_deg", &row),
        "NaN",
        &|e| {
            matches!(
                e,
                RecordingError::NonFinite {
                    line: 3002,
                    hint: Some(Hint::OnNonFinite),
                    ..
                }
            )
        },
    );
    let r = study(
        &recs,
        "(on_non_finite: drop_revolution)",
        NO_DRIFT,
        "time_s,gap_um,angle_deg",
        &row,
    )
    .unwrap();
    assert_right(&r, &["dropped_revolutions"], "NaN dropped");
}

#[test]
fn every_error_in_configuration_order() {
    let recs = campaign(1.0);
    // Every file has a bad line: six errors, in the files' order, every run.
    let row = |i: usize, t: f64, g: f64, a: f64| {
        if i == 10 {
            format!("{t:.6},{:.5},{a:.5}", g).replace(',', ";")
        } else {
            documented(i, t, g, a)
        }
    };
    for _ in 0..3 {
        let e = study(&recs, DEFAULT, NO_DRIFT, "time_s,gap_um,angle_deg", &row).unwrap_err();
        let PipelineError::Several { errors } = &e else {
            panic!("{e}")
        };
        let fields: Vec<String> = errors
            .iter()
            .map(|e| match e {
                PipelineError::Recording { field, .. } => field.clone(),
                e => panic!("{e}"),
            })
            .collect();
        let want: Vec<String> = (0..6)
            .map(|i| format!("phases[0].points.files[{i}]"))
            .collect();
        assert_eq!(fields, want);
        assert!(e.to_string().contains("f5.csv:12"), "{e}");
    }
}
