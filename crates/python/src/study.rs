//! Whole studies, plans, and the radius-error fit with Δk2, as the command line computes
//! them; results as the JSON text `results.json` / `plan.json` hold.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors::{self, Kind, Located};
use crate::files::{json_error, unknown_field, value};
use crate::fit::Samples;

/// A study's data files: tables given in memory by their path (the Python API's arrays),
/// everything else from disk.
struct Memory {
    tables: HashMap<PathBuf, Vec<u8>>,
}

impl pipeline::DataSource for Memory {
    fn recording(
        &self,
        path: &Path,
        format: &recording::RecordingFormat,
    ) -> Result<recording::Recording, recording::RecordingError> {
        pipeline::Files.recording(path, format)
    }

    fn table(
        &self,
        path: &Path,
        format: &recording::TableFormat,
    ) -> Result<recording::Table, recording::RecordingError> {
        match self.tables.get(path) {
            Some(text) => recording::parse_table(text, path, format),
            None => pipeline::Files.table(path, format),
        }
    }
}

fn pipeline_error(py: Python<'_>, e: &pipeline::PipelineError) -> PyErr {
    let kind = match e {
        pipeline::PipelineError::Recording { .. } => Kind::Recording,
        pipeline::PipelineError::Identify { .. }
        | pipeline::PipelineError::Uncertainty { .. }
        | pipeline::PipelineError::NonFiniteResult { .. } => Kind::Computation,
        _ => Kind::Config,
    };
    let message = errors::chain_message(e);
    let mut located = Located::of(&format!("{e:?}"), &message);
    if located.field.is_none() {
        located.field = unknown_field(&message);
    }
    errors::raise(py, kind, message, located)
}

/// Runs the study file at `path` as `cargo xtask study --config PATH` does; returns the
/// text of its `results.json` (with `provenance`, without the comparison with expected
/// values).
#[pyfunction]
pub(crate) fn run_study_file(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    py.detach(|| -> Result<String, PyErrLater> {
        let inputs = pipeline::load_study(&path)?;
        let results = pipeline::run(&inputs)?;
        let provenance = report::Provenance::of_study(&inputs, None)?;
        Ok(report::results_json_with_provenance(&results, &provenance)?)
    })
    .map_err(|e| e.into_py(py))
}

/// Runs a study given as a dict of the configuration's shape; `source` names it in
/// errors and its folder is where relative data files are found; `tables` are files given
/// in memory (path → text). Returns the text of `results.json` (without provenance).
#[pyfunction]
#[pyo3(signature = (config, source, tables))]
pub(crate) fn run_study_dict(
    py: Python<'_>,
    config: Bound<'_, PyAny>,
    source: PathBuf,
    tables: HashMap<PathBuf, Vec<u8>>,
) -> PyResult<String> {
    let config: pipeline::StudyConfig = serde_json::from_value(value(py, &config, "study")?)
        .map_err(|e| json_error(py, "study", &e))?;
    py.detach(|| -> Result<String, PyErrLater> {
        let inputs = pipeline::Inputs::new(config, &source, &Memory { tables })?;
        let results = pipeline::run(&inputs)?;
        Ok(report::results_json(&results)?)
    })
    .map_err(|e| e.into_py(py))
}

/// Writes the calibration certificate (PDF/A-2b) of a study's results folder (or its
/// results.json) to `out` (default: certificate.pdf in the folder), as `centrifuge-cal
/// certificate` does (`report::write_certificate`); returns the path written.
#[pyfunction]
#[pyo3(signature = (results, out = None))]
pub(crate) fn certificate(
    py: Python<'_>,
    results: PathBuf,
    out: Option<PathBuf>,
) -> PyResult<String> {
    py.detach(|| -> Result<String, PyErrLater> {
        let written = report::write_certificate(&results, out.as_deref())?;
        Ok(written.display().to_string())
    })
    .map_err(|e| e.into_py(py))
}

/// An error raised while the GIL was released, turned into a Python exception after.
enum PyErrLater {
    Pipeline(pipeline::PipelineError),
    Report(report::ReportError),
    Planning(planning::PlanningError),
    Config(String, Located),
}

impl From<pipeline::PipelineError> for PyErrLater {
    fn from(e: pipeline::PipelineError) -> Self {
        Self::Pipeline(e)
    }
}

impl From<report::ReportError> for PyErrLater {
    fn from(e: report::ReportError) -> Self {
        Self::Report(e)
    }
}

impl From<planning::PlanningError> for PyErrLater {
    fn from(e: planning::PlanningError) -> Self {
        Self::Planning(e)
    }
}

impl PyErrLater {
    fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            Self::Pipeline(e) => pipeline_error(py, &e),
            Self::Report(e) => errors::from_error(py, Kind::Computation, &e),
            Self::Planning(e) => errors::from_error(py, Kind::Config, &e),
            Self::Config(m, l) => errors::raise(py, Kind::Config, m, l),
        }
    }
}

/// Plans a campaign from a plan file (RON, as `cargo xtask plan --config FILE`) or JSON
/// dict of the same shape; returns the plan as JSON text (`plan.json`'s `plan`, or
/// `{"two_orientation": …}` for a plan file with that section).
#[pyfunction]
#[pyo3(signature = (ron_path=None, dict=None))]
pub(crate) fn plan(
    py: Python<'_>,
    ron_path: Option<PathBuf>,
    dict: Option<Bound<'_, PyAny>>,
) -> PyResult<String> {
    let inputs: planning::PlanInputs = match (ron_path, dict) {
        (Some(path), _) => {
            let text = edge_io::read_text_capped(&path, edge_io::CONFIG_MAX_BYTES)
                .map_err(|e| errors::from_error(py, Kind::Config, &e))?;
            edge_io::ron_options().from_str(&text).map_err(|e| {
                let code = e.code.to_string();
                errors::raise(
                    py,
                    Kind::Config,
                    format!(
                        "{}:{}:{}: {code}",
                        path.display(),
                        e.span.start.line,
                        e.span.start.col
                    ),
                    Located {
                        file: Some(path.display().to_string()),
                        line: Some(e.span.start.line),
                        field: unknown_field(&code),
                        hint: None,
                    },
                )
            })?
        }
        (None, Some(d)) => serde_json::from_value(value(py, &d, "plan")?)
            .map_err(|e| json_error(py, "plan", &e))?,
        (None, None) => {
            return Err(errors::input(
                py,
                "config",
                "a plan needs a file or a dict".to_owned(),
            ));
        }
    };
    py.detach(|| -> Result<String, PyErrLater> {
        // A plan file with `two_orientation` plans both mountings, as the command does.
        if inputs.two_orientation.is_some() {
            let plan = planning::plan_two_orientation(&inputs)?;
            return edge_io::to_json_pretty(&serde_json::json!({ "two_orientation": plan }))
                .map_err(|e| PyErrLater::Config(format!("plan: {e}"), Located::default()));
        }
        let plan = planning::plan(&inputs)?;
        edge_io::to_json_pretty(&plan)
            .map_err(|e| PyErrLater::Config(format!("plan: {e}"), Located::default()))
    })
    .map_err(|e| e.into_py(py))
}

/// The radius-error fit `Δr = a (+ b·ω) + C_r·ω²` (eq. 16) by QR least squares, weighted
/// when σ is given.
#[pyfunction]
#[pyo3(signature = (rate_rad_s, radius_error_m, sigma_m, three_term))]
pub(crate) fn fit_radius_error<'py>(
    py: Python<'py>,
    rate_rad_s: PyReadonlyArray1<'py, f64>,
    radius_error_m: PyReadonlyArray1<'py, f64>,
    sigma_m: Option<PyReadonlyArray1<'py, f64>>,
    three_term: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let model = if three_term {
        identify::RadiusModel::ThreeTerm
    } else {
        identify::RadiusModel::TwoTerm
    };
    let w = Samples::of(&rate_rad_s);
    let r = Samples::of(&radius_error_m);
    let s = sigma_m.as_ref().map(Samples::of);
    let fit = match &s {
        Some(s) => identify::fit_radius_error_weighted(w.get(), r.get(), s.get(), model),
        None => identify::fit_radius_error(w.get(), r.get(), model),
    }
    .map_err(|e| errors::from_error(py, Kind::Computation, &e))?;
    let d = PyDict::new(py);
    d.set_item("model", if three_term { "three_term" } else { "two_term" })?;
    d.set_item("c_r_m_s2", fit.c_r_m_s2)?;
    d.set_item("c_r_sigma_m_s2", fit.c_r_sigma_m_s2)?;
    d.set_item("offset_m", fit.offset_m)?;
    d.set_item("linear_m_s", fit.linear_m_s)?;
    d.set_item("linear_sigma_m_s", fit.linear_sigma_m_s)?;
    d.set_item("residuals_m", fit.residuals_m.clone().into_pyarray(py))?;
    d.set_item("weighted", fit.weighted)?;
    d.set_item("dof", fit.fit.dof)?;
    d.set_item("residual_sd", fit.fit.residual_sd)?;
    d.set_item("condition_number", fit.fit.condition_number)?;
    // `{code, message}` as the other warnings, the message in the command line's words
    let warnings = PyList::empty(py);
    for w in &fit.fit.warnings {
        let item = PyDict::new(py);
        item.set_item(
            "code",
            match w {
                identify::FitWarning::RefinementNotConverged { .. } => "refinement_not_converged",
                _ => "fit_warning",
            },
        )?;
        item.set_item("message", w.to_string())?;
        warnings.append(item)?;
    }
    d.set_item("warnings", warnings)?;
    Ok(d)
}

/// Δk2 = k1·C_r·g/R² and σ(Δk2) = |k1·g/R²|·σ(C_r) (eq. 19).
#[pyfunction]
pub(crate) fn delta_k2(
    py: Python<'_>,
    k1_rad_s_g: f64,
    c_r_m_s2: f64,
    c_r_sigma_m_s2: f64,
    radius_m: f64,
    g_m_s2: f64,
) -> PyResult<(f64, f64)> {
    let p = identify::pseudo_second_order(
        k1_rad_s_g,
        identify::CrEstimate {
            c_r_m_s2,
            c_r_sigma_m_s2,
        },
        identify::Geometry { radius_m, g_m_s2 },
    )
    .map_err(|e| errors::from_error(py, Kind::Input, &e))?;
    Ok((p.delta_k2_rad_s_g2, p.sigma_rad_s_g2))
}
