//! One calibration, one voice (issue 31): a weighted PIGA table whose points scatter three
//! times their stated σ gives the same k0…k3, u, Birge ratio, τ, residuals and warnings from
//! `centrifuge-cal identify --from` as from the study it reads (both call
//! `calibration::calibrate_compensated`); and `identify` refuses what the study refuses (a
//! rate of 0, a σ of 1e300), naming the same line.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("runs")
}

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

/// A scratch folder for this test, removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("cli-one-voice-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The stated σ of every row, rad/s.
const SIGMA_RAD_S: f64 = 1e-9;

/// A PIGA table at twelve rates: eq. 18 with k1 = 0.56, k2 = 5e-7, k3 = 2e-8 and the
/// compensating phase's Δk2, plus a deterministic scatter of about three times the stated σ
/// (a fixed pattern of ±1…±4.5 σ, RMS ≈ 3 σ) that the σ column does not hold.
fn table(rates_deg_s: &[f64]) -> String {
    let (r, g, k1, k2, k3) = (2.5, 9.8, 0.56, 5e-7, 2e-8);
    let pattern = [
        3.0, -2.5, 4.5, -3.5, 1.0, -4.0, 2.5, -1.5, 3.5, -3.0, 2.0, -4.0,
    ];
    let mut text = String::from("rate_deg_s,output_rad_s,sigma_rad_s\n");
    for (d, p) in rates_deg_s.iter().zip(pattern) {
        let w = d.to_radians();
        let a = r * w * w / g;
        let y = 1e-5 + k1 * a + k2 * a * a + k3 * a * a * a + p * SIGMA_RAD_S;
        text.push_str(&format!("{d},{y:.17e},{SIGMA_RAD_S:e}\n"));
    }
    text
}

const RATES_DEG_S: [f64; 12] = [
    20.0, 35.0, 50.0, 65.0, 80.0, 95.0, 110.0, 125.0, 140.0, 155.0, 170.0, 185.0,
];

/// The study: the paper's post-balance phase (first-harmonic points) compensates, the table
/// is weighted by its σ column; no `uncertainty` section, so the coefficients' u are the
/// fit's and C_r's alone.
const STUDY: &str = r#"(
    name: "one-voice",
    radius_m: 2.5,
    g_m_s2: 9.8,
    k1_rad_s_g: 0.56,
    lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0, probe_direction: against_o1_x1),
    radius_model: two_term,
    phases: [
        (
            name: "post_balance",
            points: first_harmonic([
                (rate_deg_s: 10.0,     dc1_um: -3.2385, ds1_um: -1.1406),
                (rate_deg_s: 60.0,     dc1_um: -3.2081, ds1_um: -1.1911),
                (rate_deg_s: 80.1234,  dc1_um: -3.1877, ds1_um: -1.2270),
                (rate_deg_s: 110.1234, dc1_um: -3.1385, ds1_um: -1.2737),
                (rate_deg_s: 160.1234, dc1_um: -3.0390, ds1_um: -1.3650),
                (rate_deg_s: 200.1234, dc1_um: -2.9550, ds1_um: -1.4140),
            ]),
        ),
    ],
    calibration: (
        table: (file: "piga.csv", sigma_column: "sigma_rad_s"),
        compensate_with: "post_balance",
        seed: 7,
        trials: fixed(2000),
    ),
)"#;

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Equal to 1e-12 relative.
fn same(what: &str, a: &Value, b: &Value) {
    let (a, b) = (f(a), f(b));
    assert!(
        (a - b).abs() <= 1e-12 * b.abs().max(a.abs()),
        "{what}: identify {a:e}, study {b:e}"
    );
}

#[test]
fn identify_and_the_study_give_the_same_calibration_of_a_3_sigma_scatter_table() {
    let dir = Scratch::new("same");
    std::fs::write(dir.0.join("piga.csv"), table(&RATES_DEG_S)).unwrap();
    std::fs::write(dir.0.join("study.ron"), STUDY).unwrap();
    ok(&run(
        &dir.0,
        &["study", "--config", "study.ron", "--out", "out"],
    ));
    let study: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.0.join("out/results.json")).unwrap())
            .unwrap();
    let identified: Value = serde_json::from_str(&ok(&run(
        &dir.0,
        &[
            "identify",
            "piga.csv",
            "--sigma-column",
            "sigma_rad_s",
            "--from",
            "out/results.json",
            "--json",
        ],
    )))
    .unwrap();
    let c = &study["calibration"];
    let i = &identified;
    // the table scatters about three times its σ: a τ is added (Paule–Mandel)
    let birge = f(&i["birge_ratio"]);
    assert!((2.0..4.5).contains(&birge), "Birge ratio {birge}");
    same("Birge ratio", &i["birge_ratio"], &c["birge_ratio"]);
    same("τ", &i["excess_u_rad_s"], &c["excess_u_rad_s"]);
    // k0…k3 as measured, and their u
    let measured = [
        ("k0", &i["coefficients"]["bias_rad_s"]),
        ("k1", &i["k1_implied_rad_s_g"]),
        ("k2", &i["coefficients"]["k2_apparent_rad_s_g2"]),
        ("k3", &i["coefficients"]["k3_rad_s_g3"]),
    ];
    for (name, v) in measured {
        let s = &c["uncompensated"][name];
        same(&format!("{name} (as measured)"), &v["value"], &s["value"]);
        same(&format!("u({name}) (as measured)"), &v["sigma"], &s["u"]);
    }
    // the compensated k2 and its u (the fit's and C_r's: the study has no Type B inputs)
    let k2 = &i["compensated"];
    same("k2", &k2["k2_rad_s_g2"], &c["coefficients"]["k2"]["value"]);
    same(
        "u(k2)",
        &k2["k2_sigma_rad_s_g2"],
        &c["coefficients"]["k2"]["u"],
    );
    same("Δk2", &k2["delta_k2_rad_s_g2"], &c["delta_k2"]["value"]);
    same(
        "k0",
        &i["coefficients"]["bias_rad_s"]["value"],
        &c["coefficients"]["k0"]["value"],
    );
    same(
        "k3",
        &i["coefficients"]["k3_rad_s_g3"]["value"],
        &c["coefficients"]["k3"]["value"],
    );
    // the residuals in rad/s, their SD, and the degrees of freedom the coefficients carry
    same(
        "residual SD",
        &i["residual_sd_rad_s"],
        &c["residual_sd_rad_s"],
    );
    let rows = c["residuals"].as_array().unwrap();
    let residuals = i["residuals_rad_s"].as_array().unwrap();
    assert_eq!(residuals.len(), rows.len());
    for (a, row) in residuals.iter().zip(rows) {
        same("residual", a, &row["residual_rad_s"]);
    }
    assert_eq!(f(&i["coefficients_dof"]), 6.0);
    assert_eq!(
        c["budget"]["k2"].as_array().unwrap().last().unwrap()["dof"],
        6.0
    );
    // the warnings: identify's, word for word, among the study's (its lack of fit)
    let warnings = i["warnings"].as_array().unwrap();
    let codes: Vec<&str> = warnings
        .iter()
        .map(|w| w["code"].as_str().unwrap())
        .collect();
    assert_eq!(codes, ["calibration_lack_of_fit"]);
    let study_warnings = study["warnings"].as_array().unwrap();
    for w in warnings {
        assert!(
            study_warnings
                .iter()
                .any(|s| s["code"] == w["code"] && s["message"] == w["message"]),
            "{w} not among the study's warnings: {study_warnings:#?}"
        );
    }
    // the words a person reads: the Birge ratio is called that, and is dimensionless
    let text = ok(&run(
        &dir.0,
        &[
            "identify",
            "piga.csv",
            "--sigma-column",
            "sigma_rad_s",
            "--from",
            "out/results.json",
        ],
    ));
    assert!(
        text.contains(&format!("Birge ratio √(χ²/ν) {birge:.4} (dimensionless)")),
        "{text}"
    );
    assert!(text.contains("warning: the eq. 18 residuals are"), "{text}");
}

#[test]
fn identify_refuses_what_the_study_refuses() {
    for (case, line, replace, with) in [
        ("rate-zero", 4, "50,", "0,"),
        ("sigma-huge", 6, "1e-9\n", "1e300\n"),
    ] {
        let dir = Scratch::new(case);
        let text = table(&RATES_DEG_S);
        // the value on the table's `line` (the header is line 1)
        let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
        let target = &mut lines[line - 1];
        let edited = format!("{target}\n").replacen(replace, with, 1);
        assert_ne!(
            edited.trim_end(),
            target.as_str(),
            "{case}: nothing replaced"
        );
        *target = edited.trim_end().to_owned();
        std::fs::write(dir.0.join("piga.csv"), lines.join("\n") + "\n").unwrap();
        std::fs::write(dir.0.join("study.ron"), STUDY).unwrap();
        let study = run(&dir.0, &["study", "--config", "study.ron", "--out", "out"]);
        let identify = run(
            &dir.0,
            &[
                "identify",
                "piga.csv",
                "--sigma-column",
                "sigma_rad_s",
                "--radius-m",
                "2.5",
                "--g",
                "9.8",
            ],
        );
        for (who, out) in [("study", &study), ("identify", &identify)] {
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{case}: {who}: {stderr}");
            assert!(
                stderr.contains(&format!("piga.csv:{line}:")),
                "{case}: {who} names the line: {stderr}"
            );
            let words = if case == "rate-zero" {
                "a rate must be finite and > 0"
            } else {
                "a standard uncertainty must lie in [1e-150, 1e150] rad/s"
            };
            assert!(stderr.contains(words), "{case}: {who}: {stderr}");
        }
    }
}
