//! The report of the paper's study, as a snapshot: a renamed or lost field changes the text
//! (an em dash where a number was) and fails this test.

use std::path::Path;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
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
