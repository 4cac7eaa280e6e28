//! The terminal summary of a study whose only calibration is one section (the
//! two-orientation one, the mountings one): the study's name, the section's lines, then every
//! warning of the study.

use std::fmt::Write as _;

use pipeline::StudyResults;

/// The study's heading, the lines `body` writes, then every warning of the study (or `no
/// warnings`).
pub(crate) fn summary(results: &StudyResults, body: impl FnOnce(&mut String)) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Study `{}`", results.study);
    body(&mut out);
    if results.warnings.is_empty() {
        let _ = writeln!(out, "no warnings");
    } else {
        for w in &results.warnings {
            let _ = writeln!(out, "warning: [{}] {}: {}", w.code, w.location, w.message);
        }
    }
    out
}
