//! NIST StRD linear-regression datasets: LRE ≥ 12 for coefficients, ≥ 10 for standard errors
//! and the residual standard deviation. Files are read from `../shared/reference/nist-strd/`
//! relative to the workspace root; the test is skipped with a notice when they are absent.

// The skip notice and the per-dataset table go to the test output.
#![allow(clippy::print_stderr)]

use std::path::PathBuf;

use identify::LstsqOptions;
use identify::strd;

const DATASETS: [&str; 11] = [
    "Norris", "Pontius", "NoInt1", "NoInt2", "Filip", "Longley", "Wampler1", "Wampler2",
    "Wampler3", "Wampler4", "Wampler5",
];

fn strd_dir() -> PathBuf {
    // crates/identify → workspace root → ../shared/reference/nist-strd
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/reference/nist-strd")
}

#[test]
fn all_datasets_reach_the_lre_targets() {
    let dir = strd_dir();
    if !dir.is_dir() {
        eprintln!(
            "NIST StRD files not found at {}: test skipped",
            dir.display()
        );
        return;
    }
    let mut failures = Vec::new();
    for name in DATASETS {
        let path = dir.join(format!("{name}.dat"));
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let dataset = strd::parse(&text).unwrap();
        let a = dataset.check(&LstsqOptions::default()).unwrap();
        eprintln!(
            "{:<9} coef {:5.2}  se {:5.2}  sd {:5.2}  cond {:.2e}  iters {} warnings {:?}",
            a.name,
            a.min_lre_coef,
            a.min_lre_se,
            a.lre_residual_sd,
            a.fit.condition_number,
            a.fit.refinement_iterations,
            a.fit.warnings
        );
        if a.min_lre_coef < 12.0 || a.min_lre_se < 10.0 || a.lre_residual_sd < 10.0 {
            failures.push(a.name.clone());
        }
    }
    assert!(failures.is_empty(), "below target: {failures:?}");
}
