//! Default locations, relative to the workspace root.

use std::path::{Path, PathBuf};

/// The workspace root (the parent of this crate's directory).
pub(crate) fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// The paper's study configuration.
pub(crate) fn paper_study() -> PathBuf {
    workspace_root().join("fixtures/studies/paper-2025.ron")
}

/// The expected-values file that goes with a study configuration, if there is one:
/// `fixtures/expected/<same file name>`.
pub(crate) fn expected_for(config: &Path) -> Option<PathBuf> {
    let candidate = workspace_root()
        .join("fixtures/expected")
        .join(config.file_name()?);
    candidate.is_file().then_some(candidate)
}

/// Default output directory of the study.
pub(crate) fn study_out() -> PathBuf {
    workspace_root().join("target/study")
}
