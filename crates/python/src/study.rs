//! Whole studies and plans, as the command line computes them, their results as Python
//! objects of `results.json`'s and `plan.json`'s shape (built from the Rust results, no
//! text in between); the radius-error fit with Δk2; the study's defaults.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;

use crate::errors::{self, Kind, Located};
use crate::fit::Samples;
use crate::interrupt::interruptible;
use crate::to_python::{ToPythonError, to_python};
use crate::values::value;

/// A table given as arrays: its columns by name, and each row's label.
#[derive(Debug, Clone)]
struct ArrayTable {
    columns: Vec<(String, Vec<f64>)>,
    labels: Option<Vec<String>>,
}

/// A study's data files: tables given as arrays by their name (the Python API's), every
/// other file from disk.
struct Memory {
    tables: HashMap<PathBuf, ArrayTable>,
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
            Some(t) => {
                recording::Table::from_columns(path, format, t.columns.clone(), t.labels.clone())
            }
            None => pipeline::Files.table(path, format),
        }
    }
}

/// An error met while the GIL was released, raised as the package's exception after.
enum Failure {
    Pipeline(pipeline::PipelineError),
    Report(report::ReportError),
    Planning(planning::PlanningError),
}

impl From<pipeline::PipelineError> for Failure {
    fn from(e: pipeline::PipelineError) -> Self {
        Self::Pipeline(e)
    }
}

impl From<report::ReportError> for Failure {
    fn from(e: report::ReportError) -> Self {
        Self::Report(e)
    }
}

impl From<planning::PlanningError> for Failure {
    fn from(e: planning::PlanningError) -> Self {
        Self::Planning(e)
    }
}

impl Failure {
    fn raise(self, py: Python<'_>) -> PyErr {
        match self {
            Self::Pipeline(e) => errors::pipeline(py, &e),
            Self::Report(e) => errors::raise(
                py,
                Kind::Computation,
                errors::chain_message(&e),
                Located::default(),
            ),
            Self::Planning(e) => errors::planning(py, &e),
        }
    }
}

/// A result as a Python object; a number that is not finite is a [`Kind::Computation`]
/// error naming it.
fn native<'py, T: Serialize + ?Sized>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    to_python(py, value).map_err(|e| match e {
        ToPythonError::Python(e) => e,
        e @ ToPythonError::NonFinite { .. } => {
            errors::raise(py, Kind::Computation, e.to_string(), Located::default())
        }
        e @ ToPythonError::Custom(_) => {
            errors::raise(py, Kind::Computation, e.to_string(), Located::default())
        }
    })
}

/// results.json's document: `provenance` first, then the results.
#[derive(Serialize)]
struct WithProvenance<'a> {
    provenance: &'a report::Provenance,
    #[serde(flatten)]
    results: &'a pipeline::StudyResults,
}

/// Runs the study file at `path` as `cargo xtask study --config PATH` does; returns what
/// its `results.json` holds (with `provenance`). The GIL is released; Ctrl-C stops it.
#[pyfunction]
pub(crate) fn run_study_file(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyAny>> {
    let (results, provenance) = interruptible(py, move || -> Result<_, Failure> {
        let inputs = pipeline::load_study(&path)?;
        let results = pipeline::run(&inputs)?;
        let provenance = report::Provenance::of_study(&inputs, None)?;
        Ok((results, provenance))
    })?
    .map_err(|e| e.raise(py))?;
    native(
        py,
        &WithProvenance {
            provenance: &provenance,
            results: &results,
        },
    )
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
    interruptible(py, move || -> Result<String, Failure> {
        let written = report::write_certificate(&results, out.as_deref())?;
        Ok(written.display().to_string())
    })?
    .map_err(|e| e.raise(py))
}

/// The tables of a study given as arrays: `{name: {"columns": {column: array}, "labels":
/// [str] | None}}`.
fn array_tables(tables: &Bound<'_, PyDict>) -> PyResult<HashMap<PathBuf, ArrayTable>> {
    let py = tables.py();
    let mut out = HashMap::new();
    for (name, table) in tables.iter() {
        let name: PathBuf = name.extract()?;
        let table = table.cast::<PyDict>()?;
        let mut columns = Vec::new();
        if let Some(given) = table.get_item("columns")? {
            for (column, values) in given.cast::<PyDict>()?.iter() {
                let values: PyReadonlyArray1<'_, f64> = values.extract().map_err(|_| {
                    errors::input(
                        py,
                        &column.to_string(),
                        format!("{column}: a 1-D float64 array is needed"),
                    )
                })?;
                columns.push((column.extract()?, values.as_array().to_vec()));
            }
        }
        let labels = match table.get_item("labels")? {
            Some(l) if !l.is_none() => Some(l.extract::<Vec<String>>()?),
            _ => None,
        };
        out.insert(name, ArrayTable { columns, labels });
    }
    Ok(out)
}

/// Runs a study given as a dict of the configuration's shape; `source` names it in errors
/// and its folder is where relative data files are found; `tables` are tables given as
/// arrays, by the file name the configuration gives them. Returns what `results.json`
/// holds (without provenance). The GIL is released; Ctrl-C stops it.
#[pyfunction]
#[pyo3(signature = (config, source, tables))]
pub(crate) fn run_study_dict<'py>(
    py: Python<'py>,
    config: Bound<'py, PyAny>,
    source: PathBuf,
    tables: Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    let config: pipeline::StudyConfig = serde_json::from_value(value(py, &config, "study")?)
        .map_err(|e| serde_error(py, "study", &e))?;
    let memory = Memory {
        tables: array_tables(&tables)?,
    };
    let results = interruptible(py, move || -> Result<_, Failure> {
        let inputs = pipeline::Inputs::new(config, &source, &memory)?;
        Ok(pipeline::run(&inputs)?)
    })?
    .map_err(|e| e.raise(py))?;
    native(py, &results)
}

/// A dict that serde refuses, in serde's words without JSON's line and column (the dict
/// has none).
pub(crate) fn serde_error(py: Python<'_>, what: &str, e: &serde_json::Error) -> PyErr {
    let text = e.to_string();
    let text = text
        .rfind(" at line ")
        .map_or(text.as_str(), |at| &text[..at])
        .to_owned();
    let field = errors::serde_field(&text);
    errors::raise(
        py,
        Kind::Config,
        format!("{what}: {text}"),
        Located {
            field,
            ..Located::default()
        },
    )
}

/// Plans a campaign from a plan file (RON, as `cargo xtask plan --config FILE`) or a dict
/// of the same shape; returns `plan.json`'s `plan` (or `{"two_orientation": …}` for a plan
/// with that section). The GIL is released; Ctrl-C stops it.
#[pyfunction]
#[pyo3(signature = (ron_path=None, dict=None))]
pub(crate) fn plan<'py>(
    py: Python<'py>,
    ron_path: Option<PathBuf>,
    dict: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let inputs: planning::PlanInputs = match (ron_path, dict) {
        (Some(path), _) => {
            let text = edge_io::read_text_capped(&path, edge_io::CONFIG_MAX_BYTES)
                .map_err(|e| errors::edge(py, &e))?;
            edge_io::from_ron(&text, &path).map_err(|e| {
                let code = e.code.to_string();
                errors::raise(
                    py,
                    Kind::Config,
                    e.to_string(),
                    Located {
                        file: Some(path.display().to_string()),
                        line: Some(e.line),
                        field: errors::serde_field(&code),
                        hint: None,
                    },
                )
            })?
        }
        (None, Some(d)) => serde_json::from_value(value(py, &d, "plan")?)
            .map_err(|e| serde_error(py, "plan", &e))?,
        (None, None) => {
            return Err(errors::input(
                py,
                "config",
                "a plan needs a file or a dict".to_owned(),
            ));
        }
    };
    enum Planned {
        One(Box<planning::Plan>),
        Two(Box<planning::TwoOrientationPlan>),
    }
    let planned = interruptible(py, move || -> Result<Planned, Failure> {
        // A plan file with `two_orientation` plans both mountings, as the command does.
        Ok(if inputs.two_orientation.is_some() {
            Planned::Two(Box::new(planning::plan_two_orientation(&inputs)?))
        } else {
            Planned::One(Box::new(planning::plan(&inputs)?))
        })
    })?
    .map_err(|e| e.raise(py))?;
    match planned {
        Planned::One(p) => native(py, &*p),
        Planned::Two(p) => {
            let d = PyDict::new(py);
            d.set_item("two_orientation", native(py, &*p)?)?;
            Ok(d.into_any())
        }
    }
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
    .map_err(|e| {
        errors::raise(
            py,
            Kind::Computation,
            errors::chain_message(&e),
            Located::default(),
        )
    })?;
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
    .map_err(|e| {
        errors::raise(
            py,
            Kind::Input,
            errors::chain_message(&e),
            Located::default(),
        )
    })?;
    Ok((p.delta_k2_rad_s_g2, p.sigma_rad_s_g2))
}

/// The study's defaults, from where the study takes them: the harmonic fit's
/// (`pipeline::FitSettings::default()`: order, drift, revolutions), a recording format's
/// gap limit (`recording::RecordingFormat::default()`), a calibration section's Monte
/// Carlo seed and trials (a section that states only what it must, read by the study's own
/// reader), and the most trials the Monte Carlo method runs (`uncertainty::MAX_TRIALS`).
#[pyfunction]
pub(crate) fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let fit = pipeline::FitSettings::default();
    let format = recording::RecordingFormat::default();
    let calibration: pipeline::CalibrationConfig =
        serde_json::from_value(serde_json::json!({ "compensate_with": "" }))
            .map_err(|e| errors::raise(py, Kind::Config, e.to_string(), Located::default()))?;
    let d = PyDict::new(py);
    d.set_item("order", fit.order)?;
    d.set_item("drift", fit.drift)?;
    d.set_item("revolutions", fit.revolutions)?;
    d.set_item("max_gap_intervals", format.max_gap_intervals)?;
    d.set_item("seed", calibration.seed)?;
    d.set_item("trials", native(py, &calibration.trials)?)?;
    d.set_item("k1", native(py, &calibration.k1)?)?;
    // the Monte Carlo method's cap, which it refuses beyond
    d.set_item("max_trials", uncertainty::MAX_TRIALS)?;
    Ok(d)
}
