//! Behaviour of the study: the paper's numbers from its inputs, typed errors on bad
//! configuration, recordings, and the closed loop simulate → harmonics → C_r fit →
//! compensated identification.

mod bad_config;
mod balancing;
mod baseline;
mod calibration;
mod certificate;
mod certify;
mod declared_sigma;
mod exported_table;
mod in_memory;
mod lab_variants;
mod mechanism;
mod mountings;
mod paper;
mod profile;
mod provenance;
mod recordings;
mod two_orientation;
mod two_orientation_recordings;
mod two_orientation_study;
mod two_orientation_type_b;
mod type_b;
mod units;

use std::path::{Path, PathBuf};

use test_support::scenarios;

/// The workspace root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The paper's study configuration text.
fn paper_text() -> String {
    std::fs::read_to_string(root().join("fixtures/studies/paper-2025.ron")).unwrap()
}

/// An error and its sources joined by `: `, as the command line prints them.
fn chain(error: &dyn std::error::Error) -> String {
    let mut out = error.to_string();
    let mut cause = error.source();
    while let Some(c) = cause {
        out.push_str(": ");
        out.push_str(&c.to_string());
        cause = c.source();
    }
    out
}
