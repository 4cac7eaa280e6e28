//! Standard output that cannot be written: a full device is an error (exit 1, a message on
//! standard error), a pipe closed by its reader a quiet exit with status 141; never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs the command with standard output on `/dev/full`.
fn to_dev_full(args: &[&str]) -> Output {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .stdout(Stdio::from(full))
        .output()
        .expect("runs")
}

/// Asserts exit status 1 with the console's message and no panic.
#[track_caller]
fn assert_fails_cleanly(args: &[&str]) {
    let out = to_dev_full(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    assert!(
        stderr.contains("error: cannot write to standard output: No space left on device"),
        "{args:?}: {stderr}"
    );
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xtask-stdout-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn study_and_regress_to_a_full_device_exit_1() {
    let dir = temp_dir("study");
    assert_fails_cleanly(&["study", "--out", dir.join("out").to_str().unwrap()]);
    assert_fails_cleanly(&["regress"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn simulate_and_identify_to_a_full_device_exit_1() {
    let dir = temp_dir("simulate");
    let out = dir.join("out");
    let scenario = root().join("fixtures/scenarios/pre-balance.ron");
    assert_fails_cleanly(&[
        "simulate",
        "--config",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    // the files were written before the table failed to print
    let piga = out.join("piga.csv");
    assert!(piga.is_file());
    for json in [false, true] {
        let mut args = vec![
            "identify",
            piga.to_str().unwrap(),
            "--radius-m",
            "2.5",
            "--g",
            "9.8",
        ];
        if json {
            args.push("--json");
        }
        assert_fails_cleanly(&args);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn harmonics_and_help_to_a_full_device_exit_1() {
    let fixture = root().join("fixtures/recordings/probe_120deg_s.csv");
    for json in [false, true] {
        let mut args = vec![
            "harmonics",
            fixture.to_str().unwrap(),
            "--rate-deg-s",
            "120",
        ];
        if json {
            args.push("--json");
        }
        assert_fails_cleanly(&args);
    }
    assert_fails_cleanly(&["--help"]);
}

#[test]
fn accuracy_to_a_full_device_exits_1() {
    let dir = root().join("../shared/reference/nist-strd");
    if !dir.join("Norris.dat").is_file() {
        // The datasets live beside the repository (../shared); without them there is
        // nothing to score.
        return;
    }
    assert_fails_cleanly(&["accuracy", "--dir", dir.to_str().unwrap()]);
    assert_fails_cleanly(&["accuracy", "--json", "--dir", dir.to_str().unwrap()]);
}

#[test]
fn a_pipe_closed_by_its_reader_is_a_quiet_exit_141() {
    let fixture = root().join("fixtures/recordings/probe_120deg_s.csv");
    // The pipe's only reader is closed before the command starts, so its first write fails
    // whatever the timing (closing it after the start raced with a fast command, which could
    // write everything into the pipe's buffer first and exit 0).
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let child = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args([
            "harmonics",
            fixture.to_str().unwrap(),
            "--rate-deg-s",
            "120",
        ])
        .stdout(writer)
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    let out = child.wait_with_output().expect("waits");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(141), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}
