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

/// A recording format from a RON file (as `cargo xtask harmonics --format FILE.ron`) or from
/// JSON text of the same shape (a Python dict); `None`: the default format.
pub(crate) fn format(
    py: Python<'_>,
    ron_path: Option<PathBuf>,
    dict: Option<&Bound<'_, PyAny>>,
) -> PyResult<RecordingFormat> {
    if let Some(path) = ron_path {
        let text = edge_io::read_text_capped(&path, edge_io::CONFIG_MAX_BYTES)
            .map_err(|e| errors::from_error(py, Kind::Config, &e))?;
        return edge_io::ron_options().from_str(&text).map_err(|e| {
            let message = format!("{}: {e}", path.display());
            errors::raise(
                py,
                Kind::Config,
                message,
                Located {
                    file: Some(path.display().to_string()),
                    line: Some(e.span.start.line),
                    field: unknown_field(&e.code.to_string()),
                    hint: None,
                },
            )
        });
    }
    match dict {
        Some(d) => serde_json::from_value(value(py, d, "format")?)
            .map_err(|e| json_error(py, "format", &e)),
        None => Ok(RecordingFormat::default()),
    }
}

/// The field serde names in "unknown field `x`" or "missing field `x`".
pub(crate) fn unknown_field(message: &str) -> Option<String> {
    [
        "unknown field `",
        "missing field `",
        "unknown variant `",
        "Unexpected field named `",
        "Unexpected missing field named `",
        "Unexpected variant named `",
    ]
    .iter()
    .find_map(|k| {
        let rest = &message[message.find(k)? + k.len()..];
        Some(rest[..rest.find('`')?].to_owned())
    })
}

/// A dict that serde refuses, in serde's words without JSON's line and column (the dict
/// has none).
pub(crate) fn json_error(py: Python<'_>, what: &str, e: &serde_json::Error) -> PyErr {
    let text = e.to_string();
    let text = text
        .rfind(" at line ")
        .map_or(text.as_str(), |at| &text[..at])
        .to_owned();
    let field = unknown_field(&text);
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

/// A probe recording read from a file, held by Rust (its samples are copied into numpy
/// arrays once, by the Python class that wraps it).
#[pyclass(frozen, module = "centrifuge_cal._native")]
pub(crate) struct NativeRecording {
    inner: recording::Recording,
}

#[pymethods]
impl NativeRecording {
    /// `{path, time_s, gap, angle_rad, gap_unit, angle_source}` (arrays as numpy arrays).
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.inner;
        let d = PyDict::new(py);
        d.set_item("path", r.path.display().to_string())?;
        d.set_item("time_s", r.time_s.clone().into_pyarray(py))?;
        d.set_item("gap", r.gap.clone().into_pyarray(py))?;
        d.set_item(
            "angle_rad",
            r.angle_rad.as_ref().map(|a| a.clone().into_pyarray(py)),
        )?;
        d.set_item("gap_unit", r.gap_unit.symbol())?;
        d.set_item("angle_source", r.angle_source.name())?;
        Ok(d)
    }

    /// The per-revolution fit as `cargo xtask harmonics` does it, with its warnings.
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
            .map_err(|e| errors::from_error(py, Kind::Recording, &e))?;
        let direction = if probe_along {
            ProbeDirection::AlongO1X1
        } else {
            ProbeDirection::AgainstO1X1
        };
        let d = fit::analysis(py, &result.analysis, direction)?;
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
            Load::Recording(e) => errors::from_error(py, Kind::Recording, &e),
            Load::Usage(m) => errors::raise(py, Kind::Input, m, Located::default()),
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

/// A Python value (dict, list, tuple, str, int, float, bool, None, a path) as a JSON value,
/// floats exactly (no text in between); `at` names where it is in errors.
pub(crate) fn value(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    at: &str,
) -> PyResult<serde_json::Value> {
    use pyo3::types::{PyBool, PyFloat, PyInt, PyList, PyString, PyTuple};
    use serde_json::Value;
    let bad = |what: String| {
        errors::raise(
            py,
            Kind::Config,
            format!("{at}: {what}"),
            Located {
                field: Some(at.to_owned()),
                ..Located::default()
            },
        )
    };
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(Value::from(i));
        }
        if let Ok(u) = obj.extract::<u64>() {
            return Ok(Value::from(u));
        }
        return Err(bad(format!("the integer {obj} is out of range")));
    }
    if obj.is_instance_of::<PyFloat>() {
        let x: f64 = obj.extract()?;
        return serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| bad(format!("{x} is not a finite number")));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(Value::String(obj.extract()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let key: String = k
                .extract()
                .map_err(|_| bad(format!("the key {k} is not a string")))?;
            let inner = value(py, &v, &format!("{at}.{key}"))?;
            map.insert(key, inner);
        }
        return Ok(Value::Object(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            out.push(value(py, &v?, &format!("{at}[{i}]"))?);
        }
        return Ok(Value::Array(out));
    }
    // a path (os.PathLike), or a numpy scalar (float64, int64): by its Python conversion
    let os = py.import("os")?;
    if let Ok(p) = os.call_method1("fspath", (obj,)) {
        return Ok(Value::String(p.extract()?));
    }
    if let Ok(i) = obj.call_method0("__index__") {
        return value(py, &i, at);
    }
    if let Ok(x) = obj.call_method0("__float__") {
        return value(py, &x, at);
    }
    Err(bad(format!(
        "a {} is not a configuration value",
        obj.get_type().name()?
    )))
}
