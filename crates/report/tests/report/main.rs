//! Behaviour of the report crate: the report of the paper's study as a snapshot (a renamed or
//! lost field changes the text, an em dash where a number was, and fails the test), the
//! expected-value files and the study's output directory.

mod certificate;
mod expected;
mod hostile;
mod mountings;
mod outputs;
mod two_orientation;

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// A fresh directory under the system temp directory, removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("report-{name}-{}", std::process::id()));
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

#[test]
fn the_paper_report_is_unchanged() {
    let inputs = pipeline::load_study(&root().join("fixtures/studies/paper-2025.ron")).unwrap();
    let results = pipeline::run(&inputs).unwrap();
    let expected =
        report::Expected::load(&root().join("fixtures/expected/paper-2025.ron")).unwrap();
    let outcomes = expected.compare(&results).unwrap();
    let text = report::render(&results, Some(&expected), Some(&outcomes));
    insta::assert_snapshot!("paper_report_md", text);
}

#[test]
fn the_recordings_report_is_unchanged() {
    let inputs =
        pipeline::load_study(&root().join("fixtures/studies/recordings-small.ron")).unwrap();
    let results = pipeline::run(&inputs).unwrap();
    let expected =
        report::Expected::load(&root().join("fixtures/expected/recordings-small.ron")).unwrap();
    let outcomes = expected.compare(&results).unwrap();
    let text = report::render(&results, Some(&expected), Some(&outcomes));
    insta::assert_snapshot!("recordings_report_md", text);
}

/// The balance section of the simulated balancing study, as a snapshot, and its figure.
#[test]
fn the_balance_report_is_unchanged() {
    let inputs =
        pipeline::load_study(&root().join("fixtures/studies/balance-simulated.ron")).unwrap();
    let results = pipeline::run(&inputs).unwrap();
    let text = report::render(&results, None, None);
    let section = &text[text.find("## Balance advisor").expect("a balance section")..];
    insta::assert_snapshot!("balance_report_md", section);
    let dir = Scratch::new("balance");
    let files = report::write_outputs(&dir.0, &results, None, None, None).unwrap();
    let svg = std::fs::read_to_string(files.balance_polar_svg.expect("a balance figure")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("correction: 31.99"));
    // one probe: the cone assumption of eq. 22 is stated, and there is no two-plane part
    assert!(section.contains("Assumption: one probe plane"));
    assert!(section.contains("cone about the tilt pivot (eq. 22)"));
    assert!(!section.contains("### Two probe planes"));
}

/// The two-plane part of the balance section (two probes, masses at two heights), as a
/// snapshot, and its figure.
#[test]
fn the_two_plane_balance_report_is_unchanged() {
    let inputs =
        pipeline::load_study(&root().join("fixtures/studies/balance-two-plane.ron")).unwrap();
    let results = pipeline::run(&inputs).unwrap();
    let text = report::render(&results, None, None);
    let section = &text[text.find("### Two probe planes").expect("a two-plane part")..];
    insta::assert_snapshot!("balance_two_plane_report_md", section);
    assert!(text.contains("Assumption: two probe planes"));
    let dir = Scratch::new("balance-two-plane");
    let files = report::write_outputs(&dir.0, &results, None, None, None).unwrap();
    let svg = std::fs::read_to_string(files.balance_polar_svg.expect("a balance figure")).unwrap();
    assert!(svg.contains("translation at the PIGA plane (two planes, no cone)"));
}

/// A study without a balance section writes no balance figure and no section.
#[test]
fn no_balance_section_without_its_configuration() {
    let inputs = pipeline::load_study(&root().join("fixtures/studies/paper-2025.ron")).unwrap();
    let results = pipeline::run(&inputs).unwrap();
    assert!(!report::render(&results, None, None).contains("Balance advisor"));
    let json = report::results_json(&results).unwrap();
    assert!(!json.contains("\"balance\""));
}
