//! Lab files: probe recordings (CSV with a format description, NI TDMS, MATLAB MAT) read as
//! the command line reads them, and their harmonic analysis with the command line's
//! warnings.

use std::path::{Path, PathBuf};

use harmonics::{FitConfig, ProbeDirection};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use recording::RecordingFormat;

use crate::errors::{self, Kind, Located};
use crate::fit;
use crate::study::serde_error;
use crate::values::value;

/// A recording format from a RON file (as `cargo xtask harmonics --format FILE.ron`) or from
/// a Python dict of the same shape; `None`: the default format.
pub(crate) fn format(
    py: Python<'_>,
    ron_path: Option<PathBuf>,
    dict: Option<&Bound<'_, PyAny>>,
) -> PyResult<RecordingFormat> {
    if let Some(path) = ron_path {
        let text = edge_io::read_text_capped(&path, edge_io::CONFIG_MAX_BYTES)
            .map_err(|e| errors::edge(py, &e))?;
        return edge_io::from_ron(&text, &path).map_err(|e| {
            errors::raise(
                py,
                Kind::Config,
                e.to_string(),
                Located {
                    file: Some(path.display().to_string()),
                    line: Some(e.line),
                    field: errors::serde_field(&e.code.to_string()),
                    hint: None,
                },
            )
        });
    }
    match dict {
        Some(d) => serde_json::from_value(value(py, d, "format")?)
            .map_err(|e| serde_error(py, "format", &e)),
        None => Ok(RecordingFormat::default()),
    }
}

/// A probe recording read from a file, held by Rust (its samples are copied into numpy
/// arrays once, by the Python class that wraps it).
#[pyclass(frozen, module = "centrifuge_cal._native")]
pub(crate) struct NativeRecording {
    inner: recording::Recording,
}

#[pymethods]
impl NativeRecording {
    /// `{path, time_s, gap_um, angle_rad, declared_gap_unit, um_per_declared_unit,
    /// angle_source}`: the arrays as numpy arrays, the gap in µm (the study's unit),
    /// converted from the file's declared unit as the study converts it.
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.inner;
        let um = r.gap_unit.um_per_unit();
        let d = PyDict::new(py);
        d.set_item("path", r.path.display().to_string())?;
        d.set_item("time_s", r.time_s.clone().into_pyarray(py))?;
        let gap_um: Vec<f64> = if um == 1.0 {
            r.gap.clone()
        } else {
            r.gap.iter().map(|g| g * um).collect()
        };
        d.set_item("gap_um", gap_um.into_pyarray(py))?;
        d.set_item(
            "angle_rad",
            r.angle_rad.as_ref().map(|a| a.clone().into_pyarray(py)),
        )?;
        d.set_item("declared_gap_unit", r.gap_unit.key())?;
        d.set_item("um_per_declared_unit", um)?;
        d.set_item("volts", r.sensitivity.is_some())?;
        d.set_item("angle_source", r.angle_source.name())?;
        Ok(d)
    }

    /// The per-revolution fit as the study fits a recording (`recording::analyze_recording`),
    /// with its warnings; the lengths in µm as the study scales them.
    #[pyo3(signature = (rate_rad_s, order, drift, revolutions, probe_along))]
    fn analyze<'py>(
        &self,
        py: Python<'py>,
        rate_rad_s: f64,
        order: usize,
        drift: bool,
        revolutions: Option<usize>,
        probe_along: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.inner;
        let config = FitConfig {
            order,
            drift,
            revolutions,
            max_gap_intervals: r.max_gap_intervals,
        };
        let result = py
            .detach(|| recording::analyze_recording(r, rate_rad_s, &config))
            .map_err(|e| errors::recording(py, &e))?;
        let direction = if probe_along {
            ProbeDirection::AlongO1X1
        } else {
            ProbeDirection::AgainstO1X1
        };
        let d = fit::analysis(py, &result.analysis, direction, r.gap_unit.um_per_unit())?;
        d.set_item("declared_gap_unit", r.gap_unit.key())?;
        d.set_item("samples", r.len())?;
        d.set_item("angle_source", result.angle_source.name())?;
        d.set_item("rate_deg_s", rate_rad_s.to_degrees())?;
        d.set_item(
            "measured_rate_deg_s",
            result.measured_rate_rad_s.map(f64::to_degrees),
        )?;
        d.set_item("dropped_revolutions", result.dropped_revolutions)?;
        d.set_item("warnings", fit::warnings(py, &result.diagnostics)?)?;
        Ok(d)
    }
}

/// Reads a probe recording by its extension, as `cargo xtask harmonics FILE` does: `.tdms`
/// (NI TDMS), `.mat` (MATLAB v5/v7), else delimited text in `format`.
#[pyfunction]
#[pyo3(signature = (path, format_ron=None, format_dict=None, group=None, waveform_time=false))]
pub(crate) fn read_recording(
    py: Python<'_>,
    path: PathBuf,
    format_ron: Option<PathBuf>,
    format_dict: Option<Bound<'_, PyAny>>,
    group: Option<String>,
    waveform_time: bool,
) -> PyResult<NativeRecording> {
    let format = format(py, format_ron, format_dict.as_ref())?;
    let inner = py
        .detach(|| load(&path, &format, group, waveform_time))
        .map_err(|e| match e {
            Load::Recording(e) => errors::recording(py, &e),
            Load::Usage(m) => errors::raise(py, Kind::Input, m, Located::field("format")),
        })?;
    Ok(NativeRecording { inner })
}

enum Load {
    Recording(recording::RecordingError),
    Usage(String),
}

/// The command line's choice of reader (`xtask/src/harmonics.rs`, `Harmonics::load`).
fn load(
    path: &Path,
    format: &RecordingFormat,
    group: Option<String>,
    waveform_time: bool,
) -> Result<recording::Recording, Load> {
    // The arguments add to what the format itself says.
    let format = RecordingFormat {
        group: group.or_else(|| format.group.clone()),
        waveform_time: waveform_time || format.waveform_time,
        ..format.clone()
    };
    recording::load_recording(path, &format).map_err(|e| match e {
        recording::RecordingError::SettingNotForFile {
            setting,
            applies_to,
            ..
        } => Load::Usage(format!("{setting} applies to {applies_to} only")),
        e => Load::Recording(e),
    })
}
