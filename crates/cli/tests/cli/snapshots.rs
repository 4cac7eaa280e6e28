//! Snapshots of each command's `--json` output, so that a renamed or lost field fails a test.
//! The file path (machine-dependent) is removed before the comparison.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `cargo xtask ARGS` and returns its stdout as JSON, without the `file` key.
fn json(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    if let Some(map) = value.as_object_mut() {
        map.remove("file");
    }
    serde_json::to_string_pretty(&value).unwrap()
}

#[test]
fn harmonics_json() {
    insta::assert_snapshot!(json(&[
        "harmonics",
        "fixtures/recordings/probe_120deg_s.csv",
        "--rate-deg-s",
        "120",
        "--json",
    ]));
}

#[test]
fn identify_json() {
    let dir = std::env::temp_dir().join(format!("xtask-snapshot-{}", std::process::id()));
    let status = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args([
            "simulate",
            "--config",
            "fixtures/scenarios/post-balance.ron",
            "--out",
        ])
        .arg(&dir)
        .current_dir(root())
        .output()
        .expect("runs");
    assert!(status.status.success());
    let table = dir.join("piga.csv");
    let text = json(&[
        "identify",
        table.to_str().unwrap(),
        "--radius-m",
        "2.5",
        "--g",
        "9.8",
        "--c-r-m-s2=-4.05e-8",
        "--c-r-sigma-m-s2",
        "1e-9",
        "--json",
    ]);
    std::fs::remove_dir_all(&dir).unwrap();
    insta::assert_snapshot!(text);
}

#[test]
fn accuracy_json() {
    let dir = root().join("../shared/reference/nist-strd");
    // The certified datasets live in ../shared (present in CI), not in the repository.
    if !dir.is_dir() {
        return;
    }
    let text = json(&["accuracy", "--json", "--dir", dir.to_str().unwrap()]);
    // A condition number's last digits depend on the machine's vector instructions (faer
    // picks AVX-512 or AVX2 at run time: Filip's differed at 2e-8 between two machines);
    // six significant digits are the machine's, not the code's.
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    round_condition_numbers(&mut value);
    insta::assert_snapshot!(serde_json::to_string_pretty(&value).unwrap());
}

/// Every `condition_number` rounded to six significant digits.
fn round_condition_numbers(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(map) => {
            for (key, x) in map.iter_mut() {
                match x.as_f64() {
                    Some(c) if key == "condition_number" => {
                        let rounded: f64 = format!("{c:.5e}").parse().unwrap();
                        *x = serde_json::json!(rounded);
                    }
                    _ => round_condition_numbers(x),
                }
            }
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(round_condition_numbers),
        _ => {}
    }
}
