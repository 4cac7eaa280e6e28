//! Snapshots of every command's human output (what a person reads on the terminal), and the
//! check that none holds a Rust identifier (`TwoTerm`, `RefinementNotConverged { … }`,
//! `K2`, a configuration type's name). Paths that depend on the machine are replaced by
//! `<root>` and `<tmp>`.

use std::path::{Path, PathBuf};
use std::process::Command;
use test_support::Scratch;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

/// Runs `centrifuge-cal ARGS` in the workspace root; its standard output with the machine's
/// paths replaced, and whether it succeeded.
pub(crate) fn run(args: &[&str], scratch: &Path) -> (String, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("runs");
    let text = String::from_utf8(out.stdout).unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    let tidy = |s: &str| {
        s.replace(&scratch.display().to_string(), "<tmp>")
            .replace(&root().display().to_string(), "<root>")
    };
    let both = format!(
        "{}{}",
        tidy(&text),
        if stderr.is_empty() {
            String::new()
        } else {
            format!("--- stderr ---\n{}", tidy(&stderr))
        }
    );
    (both, out.status.success())
}

/// The Rust identifiers in a text: CamelCase words, `Some(`/`None`, `Name { field:` (a
/// derived Debug), and the planning criterion's variant `K2`.
pub(crate) fn rust_identifiers(text: &str) -> Vec<String> {
    // Names that are not Rust's: the NIST datasets and binary units.
    const ALLOWED: [&str; 6] = ["StRD", "NoInt1", "NoInt2", "MiB", "KiB", "GiB"];
    let mut found = Vec::new();
    for token in text.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
        let chars: Vec<char> = token.chars().collect();
        let camel = chars.first().is_some_and(|c| c.is_ascii_uppercase())
            && chars
                .windows(2)
                .any(|w| w[0].is_ascii_lowercase() && w[1].is_ascii_uppercase());
        if (camel && !ALLOWED.contains(&token)) || token == "K2" {
            found.push(token.to_owned());
        }
    }
    for pattern in ["Some(", "None,", "None)", ": None"] {
        if text.contains(pattern) {
            found.push(pattern.to_owned());
        }
    }
    // `Name { field: ...`
    let bytes: Vec<&str> = text.split(" { ").collect();
    for pair in bytes.windows(2) {
        let before = pair[0]
            .rsplit(|c: char| !c.is_alphanumeric())
            .next()
            .unwrap_or("");
        let after = pair[1].split(':').next().unwrap_or("");
        if before.chars().next().is_some_and(char::is_uppercase)
            && !after.is_empty()
            && after.chars().all(|c| c.is_ascii_lowercase() || c == '_')
        {
            found.push(format!("{before} {{ {after}:"));
        }
    }
    found
}

#[track_caller]
pub(crate) fn assert_words(name: &str, text: &str) {
    let found = rust_identifiers(text);
    assert!(
        found.is_empty(),
        "{name}: Rust identifiers {found:?} in\n{text}"
    );
}

#[test]
fn the_identifier_check_catches_what_it_must() {
    assert_eq!(rust_identifiers("phase pre  TwoTerm  1.6e-6"), ["TwoTerm"]);
    assert_eq!(rust_identifiers("criterion K2;"), ["K2"]);
    assert!(!rust_identifiers("warning: RefinementNotConverged { iterations: 3 }").is_empty());
    assert_eq!(rust_identifiers("in PigaTableConfig"), ["PigaTableConfig"]);
    assert!(rust_identifiers("C_r = 1.6e-6 m·s², Δk2, k2, NIST StRD, O1X1, PIGA").is_empty());
}

#[test]
fn study_regress_and_harmonics() {
    let tmp = Scratch::new("cli-human-study");
    let out = tmp.0.join("study");
    let (text, ok) = run(&["study", "--out", out.to_str().unwrap()], &tmp.0);
    assert!(ok, "{text}");
    assert_words("study", &text);
    insta::assert_snapshot!("study_paper", text);

    let (text, ok) = run(&["regress"], &tmp.0);
    assert!(ok, "{text}");
    assert_words("regress", &text);
    insta::assert_snapshot!("regress_paper", text);

    let (text, ok) = run(
        &[
            "harmonics",
            "fixtures/recordings/probe_120deg_s.csv",
            "--rate-deg-s",
            "120",
        ],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("harmonics", &text);
    insta::assert_snapshot!("harmonics_fixture", text);
}

#[test]
fn recordings_study() {
    let tmp = Scratch::new("cli-human-recordings");
    let out = tmp.0.join("study");
    let (text, ok) = run(
        &[
            "study",
            "--config",
            "fixtures/studies/recordings-small.ron",
            "--out",
            out.to_str().unwrap(),
        ],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("study recordings-small", &text);
    insta::assert_snapshot!("study_recordings_small", text);
}

/// `check` on the two-orientation study recorded raw: what the study will do, with the
/// two-orientation section's data sets in words.
#[test]
fn check_two_orientations_recorded_raw() {
    let tmp = Scratch::new("cli-human-check-two_orientation");
    let (text, ok) = run(
        &["check", "fixtures/studies/two_orientation_recordings.ron"],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("check two_orientation_recordings", &text);
    assert!(
        text.contains("IA in at R = 2.5 m from 12 raw PIGA output recordings"),
        "{text}"
    );
    insta::assert_snapshot!("check_two_orientation_recordings", text);
}

/// `check` and `study` of the two-unit fixture: the units in words (each unit's k1, radius,
/// data and certificate), and the study's summary naming each unit with its calibration.
#[test]
fn check_and_study_of_several_units() {
    let tmp = Scratch::new("cli-human-units");
    let (text, ok) = run(&["check", "fixtures/studies/units.ron"], &tmp.0);
    assert!(ok, "{text}");
    assert_words("check units", &text);
    assert!(
        text.contains("2 units calibrated from these probe phases, measured once"),
        "{text}"
    );
    assert!(
        text.contains("unit B: k1 = 0.61 rad/(s·g), R = 2.5 m (the study's)"),
        "{text}"
    );
    insta::assert_snapshot!("check_units", text);
    let out = tmp.0.join("study");
    let (text, ok) = run(
        &[
            "study",
            "--config",
            "fixtures/studies/units.ron",
            "--out",
            out.to_str().unwrap(),
        ],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("study units", &text);
    insta::assert_snapshot!("study_units", text);
    // the top report's table of the units (report.md, Markdown)
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    let start = report.find("## Units").expect("the units' section");
    let section = &report[start..];
    let end = section[3..].find("\n## ").map_or(section.len(), |i| i + 4);
    insta::assert_snapshot!("report_units", &section[..end]);
}

#[test]
fn simulate_then_identify() {
    let tmp = Scratch::new("cli-human-simulate");
    let sim = tmp.0.join("sim");
    let (text, ok) = run(
        &[
            "simulate",
            "--config",
            "fixtures/scenarios/post-balance.ron",
            "--out",
            sim.to_str().unwrap(),
        ],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("simulate", &text);
    insta::assert_snapshot!("simulate_post_balance", text);

    let table = sim.join("piga.csv");
    let (text, ok) = run(
        &[
            "identify",
            table.to_str().unwrap(),
            "--radius-m",
            "2.5",
            "--g",
            "9.8",
            "--c-r-m-s2=-4.05e-8",
            "--c-r-sigma-m-s2",
            "1e-9",
        ],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("identify", &text);
    insta::assert_snapshot!("identify_compensated", text);
}

#[test]
fn plan_and_accuracy() {
    let tmp = Scratch::new("cli-human-plan");
    let out = tmp.0.join("plan");
    let (text, ok) = run(
        &[
            "plan",
            "--config",
            "fixtures/plans/paper-centrifuge.ron",
            "--out",
            out.to_str().unwrap(),
        ],
        &tmp.0,
    );
    assert!(ok, "{text}");
    assert_words("plan", &text);
    insta::assert_snapshot!("plan_fixture", text);

    let nist = root().join("../shared/reference/nist-strd");
    // The certified datasets live in ../shared (present in CI), not in the repository.
    if nist.is_dir() {
        let (text, ok) = run(&["accuracy", "--dir", nist.to_str().unwrap()], &tmp.0);
        assert!(ok, "{text}");
        let text = text.replace(&nist.display().to_string(), "<nist>");
        assert_words("accuracy", &text);
        insta::assert_snapshot!("accuracy_nist", text);
    }
}
