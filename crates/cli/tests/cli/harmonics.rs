//! `xtask harmonics`: output on the fixture, and a non-zero exit naming the line on each bad
//! input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use test_support::Scratch;

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/recordings/probe_120deg_s.csv")
}

fn xtask(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .arg("harmonics")
        .args(args)
        .output()
        .expect("runs")
}

/// A file with the given text in its own scratch folder, removed on drop.
struct Temp {
    _dir: Scratch,
    path: PathBuf,
}

impl Temp {
    fn new(name: &str, text: &str) -> Self {
        let dir = Scratch::new(&format!("cli-harmonics-{name}"));
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        Self { _dir: dir, path }
    }

    fn path(&self) -> &str {
        self.path.to_str().unwrap()
    }
}

/// Uniform rows `time_s,gap_um` at 1 kHz covering `turns` at 120 deg/s.
fn rows(turns: f64) -> String {
    let n = (turns * 3000.0) as usize;
    let mut s = String::from("time_s,gap_um\n");
    for i in 0..n {
        let t = i as f64 * 0.001;
        s += &format!("{t:.6},{:.6}\n", 50.0 + (120f64.to_radians() * t).cos());
    }
    s
}

fn fails_with(args: &[&str], expected: &str) {
    let out = xtask(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} succeeded");
    assert!(
        stderr.contains(expected),
        "{args:?}: stderr {stderr:?} lacks {expected:?}"
    );
}

#[test]
fn json_on_the_fixture() {
    let out = xtask(&[fixture().to_str().unwrap(), "--rate-deg-s", "120", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["order"], 4);
    assert_eq!(v["revolutions_used"], 2);
    assert_eq!(v["mean"]["c"].as_array().unwrap().len(), 4);
    assert_eq!(v["std"]["s"].as_array().unwrap().len(), 4);
    let c1 = v["mean"]["c"][0].as_f64().unwrap();
    let s1 = v["mean"]["s"][0].as_f64().unwrap();
    assert!(
        (c1 + 3.0).abs() < 0.01 && (s1 + 1.2).abs() < 0.01,
        "{c1} {s1}"
    );
    let amplitude = v["first_harmonic"]["amplitude"].as_f64().unwrap();
    assert!((amplitude - c1.hypot(s1)).abs() < 1e-12);
    let beta_deg = v["first_harmonic"]["beta_deg"].as_f64().unwrap();
    assert!((beta_deg - s1.atan2(-c1).to_degrees()).abs() < 1e-9);
    assert!(v["mean"]["l0"].as_f64().is_some());
}

#[test]
fn table_on_the_fixture() {
    let out = xtask(&[
        fixture().to_str().unwrap(),
        "--rate-deg-s",
        "120",
        "--order",
        "6",
        "--revolutions",
        "1",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("revolutions used: 1 of 2"), "{text}");
    assert!(text.contains("\ns6 "), "{text}");
    assert!(text.contains("first harmonic: amplitude"), "{text}");
}

#[test]
fn empty_file() {
    let f = Temp::new("empty.csv", "");
    fails_with(&[f.path(), "--rate-deg-s", "120"], "empty file");
}

#[test]
fn missing_column() {
    let f = Temp::new("nocol.csv", "time_s,gap_mm\n0,1\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "nocol.csv:1: no column `gap_um`",
    );
}

#[test]
fn unparsable_number() {
    let f = Temp::new("parse.csv", "time_s,gap_um\n0,1\n0.001,x1\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "parse.csv:3: column `gap_um`: cannot parse \"x1\"",
    );
}

#[test]
fn nan_and_infinite() {
    let f = Temp::new("nan.csv", "time_s,gap_um\n0,1\n0.001,nan\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "nan.csv:3: column `gap_um` is not finite",
    );
    let f = Temp::new("inf.csv", "time_s,gap_um\n0,1\ninf,1\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "inf.csv:3: column `time_s` is not finite",
    );
}

#[test]
fn time_not_increasing() {
    let f = Temp::new("time.csv", "time_s,gap_um\n0,1\n0.002,1\n0.001,1\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "time.csv:4: time 0.001 s does not increase",
    );
}

#[test]
fn gap_in_the_samples() {
    // Samples 500…505 missing: the row after the gap is data row 500, on line 502.
    let text: String = rows(1.5)
        .lines()
        .enumerate()
        .filter(|(i, _)| !(501..=506).contains(i))
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    let f = Temp::new("gap.csv", &text);
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "gap.csv:502: gap of 0.007",
    );
    assert!(
        xtask(&[f.path(), "--rate-deg-s", "120", "--max-gap-intervals", "8"])
            .status
            .success()
    );
}

#[test]
fn less_than_one_revolution() {
    let f = Temp::new("short.csv", &rows(0.8));
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "less than one complete revolution",
    );
}

#[test]
fn too_few_samples_in_a_revolution() {
    // 11 samples per revolution (33° apart, 1 s at 33 deg/s): order 5 needs 12.
    let mut text = String::from("time_s,gap_um\n");
    for i in 0..36 {
        text += &format!("{},{}\n", f64::from(i), 1.0 + f64::from(i).sin());
    }
    let f = Temp::new("sparse.csv", &text);
    fails_with(
        &[f.path(), "--rate-deg-s", "33", "--order", "5"],
        "sparse.csv:2: cannot analyse the samples: revolution 0 (from sample 0): 11 samples, the fit needs at least 12",
    );
    assert!(
        xtask(&[f.path(), "--rate-deg-s", "33", "--order", "4"])
            .status
            .success()
    );
    // At 36° a sample (10 per revolution) the rate itself aliases order 5.
    fails_with(
        &[f.path(), "--rate-deg-s", "36", "--order", "5"],
        "which aliases order 5",
    );
}

#[test]
fn aliasing() {
    // Encoder angle with a 60° hole in each revolution: order 4 is aliased.
    let mut text = String::from("time_s,gap_um,angle_deg\n");
    for i in 0..120 {
        let (r, j) = (i / 40, i % 40);
        let angle = f64::from(r) * 360.0 + f64::from(j) * 300.0 / 39.0;
        text += &format!(
            "{},{},{}\n",
            f64::from(i) * 0.01,
            angle.to_radians().sin(),
            angle % 360.0
        );
    }
    let f = Temp::new("alias.csv", &text);
    // The encoder turns 1020° in 1.19 s: 857 deg/s is the declared rate it matches.
    fails_with(
        &[f.path(), "--rate-deg-s", "857"],
        "alias.csv:41: cannot analyse the samples: revolution 0: angular gap of",
    );
    assert!(
        xtask(&[f.path(), "--rate-deg-s", "857", "--order", "2"])
            .status
            .success()
    );
    fails_with(
        &[f.path(), "--rate-deg-s", "100", "--order", "2"],
        "differs from the encoder's mean rate",
    );
}

#[test]
fn reviewer_reproducers() {
    // A header with no line end and nothing after it: no samples, no panic.
    let f = Temp::new("h.csv", "time_s,gap_um");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "h.csv:1: header but no data rows",
    );
    // Times whose difference overflows.
    let f = Temp::new("overflow.csv", "time_s,gap_um\n-1e308,1\n1e308,1\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "overflow.csv:3: cannot analyse the samples: sample 1: interval of inf s",
    );
    // A rate far too fast for the sampling is refused, not allocated for.
    for rate in ["1e300", "1e12"] {
        fails_with(
            &[
                fixture().to_str().unwrap(),
                "--rate-deg-s",
                rate,
                "--start-angle-deg",
                "0",
            ],
            "aliases order 4",
        );
    }
}

#[test]
fn bad_order() {
    fails_with(
        &[
            fixture().to_str().unwrap(),
            "--rate-deg-s",
            "120",
            "--order",
            "9",
        ],
        "Fourier order 9 is not supported",
    );
}

fn binary_fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/recordings/binary")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

fn json_ok(args: &[&str]) -> serde_json::Value {
    let out = xtask(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Every mean coefficient of two `--json` outputs, paired.
fn mean_pairs(a: &serde_json::Value, b: &serde_json::Value) -> Vec<(f64, f64)> {
    let mut pairs = vec![(
        a["mean"]["l0"].as_f64().unwrap(),
        b["mean"]["l0"].as_f64().unwrap(),
    )];
    for key in ["c", "s"] {
        for (x, y) in a["mean"][key]
            .as_array()
            .unwrap()
            .iter()
            .zip(b["mean"][key].as_array().unwrap())
        {
            pairs.push((x.as_f64().unwrap(), y.as_f64().unwrap()));
        }
    }
    pairs
}

#[test]
fn tdms_and_mat_by_extension_give_the_csv_coefficients() {
    let csv = json_ok(&[fixture().to_str().unwrap(), "--rate-deg-s", "120", "--json"]);
    let cases: [Vec<String>; 3] = [
        vec![
            binary_fixture("probe_120deg_s.tdms"),
            "--group".into(),
            "probe".into(),
        ],
        vec![binary_fixture("probe_120deg_s.mat")],
        vec![
            binary_fixture("probe_120deg_s_v7.mat"),
            "--group".into(),
            "rec".into(),
        ],
    ];
    for case in cases {
        let mut args: Vec<&str> = case.iter().map(String::as_str).collect();
        args.extend(["--rate-deg-s", "120", "--json"]);
        let v = json_ok(&args);
        assert_eq!(v["angle_source"], "encoder", "{args:?}");
        assert_eq!(v["samples"], csv["samples"]);
        assert_eq!(v["revolutions_used"], csv["revolutions_used"]);
        for (x, y) in mean_pairs(&v, &csv) {
            assert!((x - y).abs() <= 1e-12, "{args:?}: {x} vs {y}");
        }
    }
}

#[test]
fn channel_flags_for_binary_files() {
    // Time from the waveform properties; channel names by the --*-channel flags.
    let v = json_ok(&[
        &binary_fixture("probe_120deg_s_interleaved_f32.tdms"),
        "--waveform-time",
        "--gap-channel",
        "gap_um",
        "--angle-channel",
        "angle_deg",
        "--rate-deg-s",
        "120",
        "--json",
    ]);
    assert_eq!(v["samples"], 3750);
    // A channel that is not there names those that are.
    fails_with(
        &[
            &binary_fixture("probe_120deg_s.tdms"),
            "--gap-channel",
            "gap",
            "--rate-deg-s",
            "120",
        ],
        "no TDMS channel `gap` (available: probe/time_s, probe/gap_um, probe/angle_deg)",
    );
    fails_with(
        &[
            &binary_fixture("probe_120deg_s.mat"),
            "--time-channel",
            "t",
            "--rate-deg-s",
            "120",
        ],
        "no MAT variable `t` (available: time_s, gap_um, angle_deg)",
    );
    // A CSV file takes no group.
    fails_with(
        &[
            fixture().to_str().unwrap(),
            "--group",
            "probe",
            "--rate-deg-s",
            "120",
        ],
        "--group applies to TDMS and MAT files only",
    );
    // A CSV file read as TDMS by its extension: not a TDMS file.
    let f = Temp::new("notreally.tdms", "time_s,gap_um\n0,1\n");
    fails_with(
        &[f.path(), "--rate-deg-s", "120"],
        "notreally.tdms: not a TDMS file",
    );
}
