//! Behaviour of the report crate: the report of the paper's study as a snapshot (a renamed or
//! lost field changes the text, an em dash where a number was, and fails the test), the
//! expected-value files and the study's output directory.

mod expected;
mod outputs;

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
