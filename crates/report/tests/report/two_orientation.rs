//! The two-orientation section of the report and its lines in the terminal summary, on the
//! simulated campaign of `fixtures/studies/two_orientation.ron` (arm stretch C_a = 0.3·C_r).

use std::path::Path;

/// The study, read through a path relative to this crate (the test's working directory) so
/// that the snapshots hold no absolute path.
fn results() -> pipeline::StudyResults {
    let inputs =
        pipeline::load_study(Path::new("../../fixtures/studies/two_orientation.ron")).unwrap();
    pipeline::run(&inputs).unwrap()
}

#[test]
fn the_two_orientation_report_and_summary_are_unchanged() {
    let results = results();
    let text = report::render(&results, None, None);
    let start = text
        .find("## Two-orientation calibration")
        .expect("a two-orientation section");
    let rest = &text[start + 3..];
    let end = rest.find("\n## ").map_or(text.len(), |e| start + 3 + e);
    let section = &text[start..end];
    insta::assert_snapshot!("two_orientation_report_md", section);
    let summary = report::summary_text(&results).expect("a summary without a calibration section");
    insta::assert_snapshot!("two_orientation_summary", summary);
    // words for people: no Rust names, no configuration codes where words belong
    for text in [section, summary.as_str()] {
        for word in ["| ia_in", "| ia_out", "TwoOrientation", "Some(", "None"] {
            assert!(!text.contains(word), "`{word}` in:\n{text}");
        }
    }
    // the disagreement with the probe is stated, with both candidates
    assert!(summary.contains("C − C_r"));
    assert!(summary.contains("they disagree"));
    assert!(summary.contains("warning: [probe_disagrees]"));
    assert!(summary.contains("does not see"));
    assert!(summary.contains("`lever.probe_direction`"));
}
