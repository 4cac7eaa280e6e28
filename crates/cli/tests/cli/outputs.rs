//! A study killed or failing while it writes leaves the previous outputs byte for byte; the
//! next good run replaces them with exactly its own. A file-size limit (`ulimit -f`) makes the
//! write of the recordings study fail at `probe_signals_pre_balance.svg`, its largest file,
//! written after results.json and report.md, for root too: with SIGXFSZ at its default the
//! process is killed there; with SIGXFSZ ignored the write fails (EFBIG).

use std::collections::BTreeMap;
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

/// The recordings study, run by bash with a 16 KiB file-size limit: results.json (about
/// 12 KiB) and report.md (about 4 KiB) fit, probe_signals_pre_balance.svg (about 35 KiB) does
/// not. `trap` decides what SIGXFSZ does: `""` ignores it, `"-"` keeps the default
/// (terminate).
fn study_limited(out: &Path, trap: &str) -> Output {
    let script = format!(
        "trap '{trap}' XFSZ; ulimit -f 16; exec \"$0\" study --config \"$2\" --out \"$1\" --no-compare"
    );
    let recordings = root().join("fixtures/studies/recordings-small.ron");
    Command::new("bash")
        .args([
            "-c",
            &script,
            env!("CARGO_BIN_EXE_centrifuge-cal"),
            out.to_str().unwrap(),
            recordings.to_str().unwrap(),
        ])
        .output()
        .expect("bash runs")
}

fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

/// The names in a folder, without the hidden record of what a run wrote.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != edge_io::OUTPUT_RECORD)
        .collect();
    names.sort();
    names
}

fn ok(out: &Output) {
    assert!(
        out.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_study_killed_or_failing_midway_leaves_the_previous_outputs() {
    let parent = std::env::temp_dir().join(format!("xtask-atomic-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&parent);
    let out = parent.join("study");
    let recordings = root().join("fixtures/studies/recordings-small.ron");
    ok(&xtask(&[
        "study",
        "--config",
        recordings.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    let before = snapshot(&out);
    assert!(before.contains_key("probe_signals_pre_balance.svg"));

    // Killed by SIGXFSZ while writing the last file.
    let killed = study_limited(&out, "-");
    assert!(!killed.status.success());
    assert_eq!(killed.status.code(), None, "killed by a signal");
    assert_eq!(
        snapshot(&out),
        before,
        "the previous outputs, byte for byte"
    );

    // The write fails instead: exit 1 naming the file, and the staging directory the kill
    // left is tidied away.
    let failed = study_limited(&out, "");
    let stderr = String::from_utf8_lossy(&failed.stderr);
    assert_eq!(failed.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "cannot write {}",
            out.join("probe_signals_pre_balance.svg").display()
        )),
        "{stderr}"
    );
    assert_eq!(
        snapshot(&out),
        before,
        "the previous outputs, byte for byte"
    );
    assert_eq!(entries(&parent), ["study"], "no staging directory is left");

    // A good run of another study: exactly its files, the probe figure gone.
    ok(&xtask(&["study", "--out", out.to_str().unwrap()]));
    assert_eq!(
        entries(&out),
        ["radius_error.svg", "report.md", "results.json"]
    );
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(results["provenance"]["tool"], "centrifuge-cal");
    assert!(
        results["provenance"]["config"]["path"]
            .as_str()
            .unwrap()
            .ends_with("paper-2025.ron")
    );
    assert_eq!(entries(&parent), ["study"]);
    std::fs::remove_dir_all(&parent).unwrap();
}

#[test]
fn a_study_refuses_to_replace_a_directory_with_other_files() {
    let dir = std::env::temp_dir().join(format!("xtask-foreign-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("thesis.tex"), "keep").unwrap();
    let out = xtask(&["study", "--out", dir.to_str().unwrap(), "--no-compare"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("thesis.tex"), "{stderr}");
    assert_eq!(entries(&dir), ["thesis.tex"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn regress_refuses_an_expected_file_that_cannot_fail() {
    let dir = std::env::temp_dir().join(format!("xtask-vacuous-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let empty = dir.join("empty.ron");
    std::fs::write(&empty, "(source: \"nothing\", checks: [])").unwrap();
    let out = xtask(&["regress", "--expected", empty.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "{}: `checks`: no check with `regress: true`",
            empty.display()
        )),
        "{stderr}"
    );

    let text = std::fs::read_to_string(root().join("fixtures/expected/paper-2025.ron"))
        .unwrap()
        .replacen("tolerance: 2e-4", "tolerance: inf", 1);
    let infinite = dir.join("infinite.ron");
    std::fs::write(&infinite, text).unwrap();
    let out = xtask(&["regress", "--expected", infinite.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "{}: `checks[1].tolerance` = inf",
            infinite.display()
        )),
        "{stderr}"
    );

    // A byte-order mark at the start of an expected file is no longer a parse error.
    let text = std::fs::read_to_string(root().join("fixtures/expected/paper-2025.ron")).unwrap();
    let bom = dir.join("bom.ron");
    std::fs::write(&bom, format!("\u{FEFF}{text}")).unwrap();
    ok(&xtask(&["regress", "--expected", bom.to_str().unwrap()]));
    std::fs::remove_dir_all(&dir).unwrap();
}
