//! Progress is drawn on standard error only when it is a terminal: a piped run (as in a
//! script or CI log) shows none, and its standard error holds no escape sequence or carriage
//! return.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs the command with standard output and standard error piped; its standard error.
fn piped_stderr(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .current_dir(root())
        .env_remove("RUST_LOG")
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[track_caller]
fn assert_no_progress(args: &[&str]) {
    let stderr = piped_stderr(args);
    for sign in [
        "recordings analyzed",
        "running the study",
        "Monte Carlo",
        "simulating",
        "reading and checking",
        "\r",
        "\u{1b}[",
    ] {
        assert!(
            !stderr.contains(sign),
            "{args:?} printed {sign:?}:\n{stderr}"
        );
    }
}

#[test]
fn a_piped_run_prints_no_progress() {
    let out = std::env::temp_dir().join(format!("cli-progress-{}", std::process::id()));
    let (study, plan) = (out.join("study"), out.join("plan"));
    // Many recordings, fits and the Monte Carlo of the calibration's uncertainty.
    assert_no_progress(&[
        "study",
        "--config",
        "fixtures/studies/campaign.ron",
        "--out",
        study.to_str().unwrap(),
        "--no-compare",
    ]);
    assert_no_progress(&["check", "fixtures/studies/campaign.ron"]);
    assert_no_progress(&[
        "plan",
        "--config",
        "fixtures/plans/paper-centrifuge.ron",
        "--simulate",
        "20",
        "--out",
        plan.to_str().unwrap(),
    ]);
    let _ = std::fs::remove_dir_all(&out);
}
