//! The IEEE 836 model from several mountings in the report and the terminal summary, on the
//! simulated five-mounting campaign of `fixtures/studies/mountings.ron`.

use std::path::Path;

/// The study, read through a path relative to this crate (the test's working directory) so
/// that the snapshots hold no absolute path.
fn results() -> pipeline::StudyResults {
    let inputs = pipeline::load_study(Path::new("../../fixtures/studies/mountings.ron")).unwrap();
    pipeline::run(&inputs).unwrap()
}

#[test]
fn the_mountings_report_and_summary_read_as_words() {
    let results = results();
    let text = report::render(&results, None, None);
    let start = text
        .find("## The IEEE 836 model")
        .expect("a mountings section");
    let rest = &text[start + 3..];
    let end = rest.find("\n## ").map_or(text.len(), |e| start + 3 + e);
    let section = &text[start..end];
    insta::assert_snapshot!("mountings_report_md", section);
    let summary = report::summary_text(&results).expect("a summary of the mountings section");
    insta::assert_snapshot!("mountings_summary", summary);
    for text in [section, summary.as_str()] {
        for word in [
            "ia_in",
            "ia_45",
            "Some(",
            "None",
            "DeltaO",
            "Koq",
            "MountingPreset",
        ] {
            assert!(!text.contains(word), "`{word}` in:\n{text}");
        }
    }
    // every table row of the section has the table's number of cells (a `|` inside a cell
    // would split it)
    for line in section.lines().filter(|l| l.starts_with("| k")) {
        assert_eq!(line.matches(" | ").count(), 4, "{line}");
    }
    // the fixture states its uncertainty: the Type B inputs are in the U95, and said to be
    assert!(
        summary.contains("Type B (infinite degrees of freedom): each mounting's radius"),
        "{summary}"
    );
    assert!(!summary.contains("do not certify these terms"), "{summary}");
}
