//! Writing a study's outputs into a directory.

use std::path::{Path, PathBuf};

use crate::error::{PipelineError, Result};
use crate::expected::{CheckOutcome, Expected};
use crate::plot::radius_error_svg;
use crate::report::render;
use crate::results::StudyResults;

/// The files a study wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenFiles {
    /// `results.json`.
    pub results_json: PathBuf,
    /// `report.md`.
    pub report_md: PathBuf,
    /// `radius_error.svg` (the paper's Fig. 5).
    pub radius_error_svg: PathBuf,
}

fn write(path: PathBuf, contents: &str) -> Result<PathBuf> {
    std::fs::write(&path, contents).map_err(|source| PipelineError::Io {
        path: path.clone(),
        source,
    })?;
    Ok(path)
}

/// Serialises results as pretty JSON.
pub fn results_json(results: &StudyResults) -> Result<String> {
    serde_json::to_string_pretty(results).map_err(|e| PipelineError::Serialize {
        what: "results.json",
        message: e.to_string(),
    })
}

/// Writes `results.json`, `report.md` and `radius_error.svg` into `dir` (created if needed).
pub fn write_outputs(
    dir: &Path,
    results: &StudyResults,
    expected: Option<&Expected>,
    outcomes: Option<&[CheckOutcome]>,
) -> Result<WrittenFiles> {
    std::fs::create_dir_all(dir).map_err(|source| PipelineError::Io {
        path: dir.to_owned(),
        source,
    })?;
    let title = format!("{}: radius error after balancing", results.study);
    Ok(WrittenFiles {
        results_json: write(dir.join("results.json"), &results_json(results)?)?,
        report_md: write(dir.join("report.md"), &render(results, expected, outcomes))?,
        radius_error_svg: write(
            dir.join("radius_error.svg"),
            &radius_error_svg(&results.post_balance, &title)?,
        )?,
    })
}
