//! The commands as a lab engineer chains them: simulate a calibration, identify k2 from its
//! `piga.csv` with and without compensation; run and regress a study; bad input exits non-zero
//! naming the file and line.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn xtask(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .output()
        .expect("runs")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xtask-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

#[test]
fn simulate_then_identify_with_and_without_compensation() {
    let dir = temp_dir("simulate");
    let scenario = root().join("fixtures/scenarios/pre-balance.ron");
    ok(&xtask(&[
        "simulate",
        "--config",
        scenario.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]));
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).unwrap()).unwrap();
    let k2_true = truth["scenario"]["piga"]["coefficients"]["k2_rad_s_g2"]
        .as_f64()
        .unwrap();
    let c_r = truth["c_r_m_s2"].as_f64().unwrap();
    let delta_k2 = truth["delta_k2_predicted_rad_s_g2"].as_f64().unwrap();
    let piga = dir.join("piga.csv");
    let c_r_arg = c_r.to_string();
    let json = ok(&xtask(&[
        "identify",
        piga.to_str().unwrap(),
        "--radius-m",
        "2.5",
        "--g",
        "9.8",
        "--k1",
        "0.56",
        "--c-r-m-s2",
        &c_r_arg,
        "--c-r-sigma-m-s2",
        "1e-9",
        "--json",
    ]));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let apparent = v["coefficients"]["k2_apparent_rad_s_g2"]["value"]
        .as_f64()
        .unwrap();
    let compensated = v["compensated"]["k2_rad_s_g2"].as_f64().unwrap();
    assert!(
        (apparent - k2_true - delta_k2).abs() < 0.02 * delta_k2.abs(),
        "apparent k2 {apparent} vs {k2_true} + {delta_k2}"
    );
    assert!(
        (compensated - k2_true).abs() < 0.02 * delta_k2.abs(),
        "compensated k2 {compensated} vs {k2_true}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn study_writes_its_outputs_and_regress_passes() {
    let dir = temp_dir("study");
    let stdout = ok(&xtask(&["study", "--out", dir.to_str().unwrap()]));
    assert!(
        stdout.contains("regression:") && stdout.contains("pass"),
        "{stdout}"
    );
    for file in ["results.json", "report.md", "radius_error.svg"] {
        assert!(dir.join(file).is_file(), "{file} missing");
    }
    ok(&xtask(&["regress"]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn regress_fails_on_a_changed_expectation() {
    let dir = temp_dir("regress");
    let text = std::fs::read_to_string(root().join("fixtures/expected/paper-2025.ron"))
        .unwrap()
        .replace("value: -4.0526e-8,", "value: -4.0626e-8,");
    let expected = dir.join("paper-2025.ron");
    std::fs::write(&expected, text).unwrap();
    let out = xtask(&["regress", "--expected", expected.to_str().unwrap()]);
    assert!(!out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("FAIL  phases[post_balance].c_r_m_s2"),
        "{stdout}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bad_study_exits_non_zero_naming_the_file_and_line() {
    let dir = temp_dir("bad-study");
    let text = std::fs::read_to_string(root().join("fixtures/studies/paper-2025.ron"))
        .unwrap()
        .replace("radius_m: 2.5,", "radius_m: 2.5,\n    radius_mm: 2500.0,");
    let bad = dir.join("bad.ron");
    std::fs::write(&bad, text).unwrap();
    let out = xtask(&["study", "--config", bad.to_str().unwrap(), "--no-compare"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("bad.ron:7:"), "{stderr}");
    assert!(stderr.contains("radius_mm"), "{stderr}");
    let out = xtask(&["study", "--config", "/nonexistent/study.ron"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/study.ron"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn identify_takes_r_g_k1_and_c_r_from_a_studys_results() {
    let dir = temp_dir("identify-from");
    ok(&xtask(&[
        "study",
        "--config",
        root()
            .join("fixtures/studies/campaign.ron")
            .to_str()
            .unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]));
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    let phase = &results["phases"][0];
    let json = ok(&xtask(&[
        "identify",
        root().join("fixtures/campaign/piga.csv").to_str().unwrap(),
        "--from",
        dir.join("results.json").to_str().unwrap(),
        "--phase",
        "spindle",
        "--json",
    ]));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let c = &v["compensated"];
    // serde_json's default float parsing may differ from the written value by an ulp.
    let same = |a: &serde_json::Value, b: &serde_json::Value| {
        let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
        assert!((a - b).abs() <= 4.0 * f64::EPSILON * b.abs(), "{a} vs {b}");
    };
    same(&c["c_r_m_s2"], &phase["c_r_m_s2"]);
    same(&c["c_r_sigma_m_s2"], &phase["c_r_sigma_m_s2"]);
    // k1 as the study chose it: its calibration fitted k1, so identify fits it too (not the
    // configured 0.56).
    assert_eq!(results["calibration"]["k1_source"], "fitted");
    same(&c["k1_used_rad_s_g"], &v["k1_implied_rad_s_g"]["value"]);
    // Without --phase, the phase the study's calibration compensated with (`spindle`).
    assert_eq!(results["calibration"]["compensate_with"], "spindle");
    let json = ok(&xtask(&[
        "identify",
        root().join("fixtures/campaign/piga.csv").to_str().unwrap(),
        "--from",
        dir.join("results.json").to_str().unwrap(),
    ]));
    assert!(
        json.contains(
            "phase `spindle` of the study, the one the study's calibration compensated with"
        ),
        "{json}"
    );
    assert!(
        json.contains("fitted, as the study's calibration chose"),
        "{json}"
    );
    // An unknown phase is named, with the study's phases.
    let out = xtask(&[
        "identify",
        root().join("fixtures/campaign/piga.csv").to_str().unwrap(),
        "--from",
        dir.join("results.json").to_str().unwrap(),
        "--phase",
        "trial",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("no phase named `trial` (the study's phases: spindle)"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Results that would not be finite are errors naming the quantity and the inputs, with short
/// numbers; never a NaN, an inf or a `null` on standard output. Before: `identify --radius-m
/// 1e-80` printed σ(k2) = NaN, and a recording with one huge sample gave `--drift` std = inf
/// and a residual RMS of 0.
#[test]
fn results_out_of_double_range_are_named_errors() {
    let dir = temp_dir("nonfinite");
    let piga = dir.join("piga.csv");
    let rows: String = (1..=8)
        .map(|i| {
            let w = f64::from(25 * i).to_radians();
            let a = 2.5 * w * w / 9.8;
            format!(
                "{},{}\n",
                25 * i,
                1e-5 + 0.56 * a + 3e-6 * a * a + 1e-9 * f64::from(i % 3)
            )
        })
        .collect();
    std::fs::write(&piga, format!("rate_deg_s,output_rad_s\n{rows}")).unwrap();
    for json in [false, true] {
        let mut args = vec![
            "identify",
            piga.to_str().unwrap(),
            "--radius-m",
            "1e-80",
            "--g",
            "9.8",
        ];
        if json {
            args.push("--json");
        }
        let out = xtask(&args);
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stdout}{stderr}");
        assert!(
            !stdout.contains("NaN") && !stdout.contains("null"),
            "{stdout}"
        );
        assert!(stderr.contains("not finite"), "{stderr}");
        assert!(stderr.contains("radius_m = 1e-80"), "{stderr}");
        assert!(!stderr.contains("00000000000"), "{stderr}");
    }

    let text =
        std::fs::read_to_string(root().join("fixtures/recordings/probe_120deg_s.csv")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut fields: Vec<&str> = lines[40].split(',').collect();
    fields[1] = "1e155";
    lines[40] = fields.join(",");
    let huge = dir.join("huge.csv");
    std::fs::write(&huge, lines.join("\n")).unwrap();
    for json in [false, true] {
        let mut args = vec![
            "harmonics",
            huge.to_str().unwrap(),
            "--rate-deg-s",
            "120",
            "--drift",
        ];
        if json {
            args.push("--json");
        }
        let out = xtask(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(out.stdout.is_empty());
        assert!(
            stderr.contains("not finite") && stderr.contains("1e155"),
            "{stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A PIGA-table value that takes the eq. 18 design out of range is named by its line in the
/// file, not by a row and column of the design matrix.
#[test]
fn a_design_row_out_of_range_names_the_file_line() {
    let dir = temp_dir("designrow");
    let piga = dir.join("piga.csv");
    let mut text = String::from("# PIGA 7\nrate_deg_s,output_rad_s\n");
    for i in 1..=8 {
        if i == 5 {
            text.push_str("\n# a blank line and a comment before the bad row\n");
            text.push_str("1e60,0.5\n");
        } else {
            text.push_str(&format!("{},{}\n", 25 * i, 0.01 * f64::from(i * i)));
        }
    }
    std::fs::write(&piga, text).unwrap();
    let out = xtask(&[
        "identify",
        piga.to_str().unwrap(),
        "--radius-m",
        "2.5",
        "--g",
        "9.8",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let expected = format!("{}:9: column `rate_deg_s` = 1e60", piga.display());
    assert!(stderr.contains(&expected), "{stderr}");
    assert!(!stderr.contains("row 4"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}
