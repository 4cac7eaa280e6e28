//! Writing a study's outputs into a directory.

use std::path::{Path, PathBuf};

use crate::error::{ReportError, Result};
use crate::expected::{CheckOutcome, Expected};
use crate::markdown::render;
use crate::plot::{probe_signals_svg as probe_signals_svg_text, radius_error_svg};
use pipeline::StudyResults;

/// The files a study wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenFiles {
    /// `results.json`.
    pub results_json: PathBuf,
    /// `report.md`.
    pub report_md: PathBuf,
    /// `radius_error.svg` (the paper's Fig. 5): the last phase whose fit has residual degrees
    /// of freedom.
    pub radius_error_svg: PathBuf,
    /// `probe_signals_<phase>.svg` (the paper's Fig. 4), for each phase given as recordings.
    pub probe_signals_svg: Vec<PathBuf>,
}

fn write(path: PathBuf, contents: &str) -> Result<PathBuf> {
    std::fs::write(&path, contents).map_err(|source| ReportError::Io {
        path: path.clone(),
        source,
    })?;
    Ok(path)
}

/// Serialises results as pretty JSON.
pub fn results_json(results: &StudyResults) -> Result<String> {
    serde_json::to_string_pretty(results).map_err(|e| ReportError::Serialize {
        what: "results.json",
        message: e.to_string(),
    })
}

/// Writes `results.json`, `report.md`, `radius_error.svg` and, for phases given as
/// recordings, `probe_signals_<phase>.svg` into `dir` (created if needed).
pub fn write_outputs(
    dir: &Path,
    results: &StudyResults,
    expected: Option<&Expected>,
    outcomes: Option<&[CheckOutcome]>,
) -> Result<WrittenFiles> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
        path: dir.to_owned(),
        source,
    })?;
    let mut probe_signals_svg = Vec::new();
    for phase in &results.phases {
        let key = &phase.name;
        let title = format!("{}: probe signal over one revolution, {key}", results.study);
        if let Some(svg) = probe_signals_svg_text(phase, &title)? {
            probe_signals_svg.push(write(dir.join(format!("probe_signals_{key}.svg")), &svg)?);
        }
    }
    // Fig. 5: the last phase whose fit has residual degrees of freedom (the paper's: after
    // balancing), else the last phase.
    let figure = results
        .phases
        .iter()
        .rev()
        .find(|p| p.fit.dof > 0)
        .or(results.phases.last())
        .ok_or(ReportError::NoPhase)?;
    let title = format!("{}: radius error, phase {}", results.study, figure.name);
    Ok(WrittenFiles {
        results_json: write(dir.join("results.json"), &results_json(results)?)?,
        report_md: write(dir.join("report.md"), &render(results, expected, outcomes))?,
        radius_error_svg: write(
            dir.join("radius_error.svg"),
            &radius_error_svg(figure, &title)?,
        )?,
        probe_signals_svg,
    })
}
