//! The per-revolution harmonic fit (eq. 20) on numpy arrays, and its results as plain
//! Python values and numpy arrays.

use std::f64::consts::{PI, TAU};
use std::time::Instant;

use harmonics::{
    Coefficients, DeclaredRate, FitConfig, HarmonicAnalysis, ProbeDirection, ProbeSignal,
    SpindleAngle,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use recording::{AngleSourceKind, Diagnostic, LengthUnit, OnOutlier, SampleAt};

use crate::errors::{self, Kind, Located};

/// A 1-D float64 array as a slice: borrowed when contiguous (the Python side makes it so),
/// else copied.
pub(crate) enum Samples<'a> {
    Borrowed(&'a [f64]),
    Owned(Vec<f64>),
}

impl Samples<'_> {
    pub(crate) fn of<'a>(array: &'a PyReadonlyArray1<'_, f64>) -> Samples<'a> {
        match array.as_slice() {
            Ok(s) => Samples::Borrowed(s),
            Err(_) => Samples::Owned(array.as_array().to_vec()),
        }
    }

    pub(crate) fn get(&self) -> &[f64] {
        match self {
            Samples::Borrowed(s) => s,
            Samples::Owned(v) => v,
        }
    }
}

/// `{l0, c, s, drift_per_s}` of a set of coefficients.
pub(crate) fn coefficients<'py>(py: Python<'py>, c: &Coefficients) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("l0", c.l0)?;
    d.set_item("c", c.c.clone())?;
    d.set_item("s", c.s.clone())?;
    d.set_item("drift_per_s", c.drift_per_s)?;
    Ok(d)
}

/// The analysis as a dict: the statistics, the first harmonic, and the per-revolution
/// values as numpy arrays (one row per revolution); lengths in µm, the fit's coefficients
/// (in the gap's declared unit) times `um` (µm per that unit), as the study scales them.
pub(crate) fn analysis<'py>(
    py: Python<'py>,
    fit: &HarmonicAnalysis,
    direction: ProbeDirection,
    um: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let scaled_fit;
    let fit = if um == 1.0 {
        fit
    } else {
        scaled_fit = scaled(fit, um);
        &scaled_fit
    };
    let d = PyDict::new(py);
    d.set_item("order", fit.order)?;
    d.set_item("drift", fit.drift)?;
    d.set_item("revolutions_used", fit.revolutions_used())?;
    d.set_item("revolutions_available", fit.revolutions_available)?;
    d.set_item("nominal_interval_s", fit.nominal_interval_s)?;
    d.set_item("mean", coefficients(py, &fit.mean)?)?;
    d.set_item(
        "std",
        fit.std.as_ref().map(|c| coefficients(py, c)).transpose()?,
    )?;
    d.set_item(
        "std_error",
        fit.std_error
            .as_ref()
            .map(|c| coefficients(py, c))
            .transpose()?,
    )?;
    match &fit.incomplete {
        Some(i) => {
            let inc = PyDict::new(py);
            inc.set_item("first_sample", i.samples.start)?;
            inc.set_item("samples", i.samples.len())?;
            inc.set_item("turns", i.turns)?;
            d.set_item("incomplete_revolution", inc)?;
        }
        None => d.set_item("incomplete_revolution", py.None())?,
    }
    let h = fit.first_harmonic().map_err(|e| {
        errors::raise(
            py,
            Kind::Computation,
            errors::chain_message(&e),
            Located::harmonics(&e),
        )
    })?;
    let first = PyDict::new(py);
    first.set_item("c1", h.c1)?;
    first.set_item("s1", h.s1)?;
    first.set_item("amplitude", h.amplitude())?;
    first.set_item("beta_deg", direction.beta_rad(h).to_degrees())?;
    first.set_item(
        "probe_direction",
        match direction {
            ProbeDirection::AgainstO1X1 => "against_o1x1",
            _ => "along_o1x1",
        },
    )?;
    d.set_item("first_harmonic", first)?;

    let revs = &fit.revolutions;
    let k = revs.len();
    let n = fit.order;
    let per = PyDict::new(py);
    let column =
        |f: &dyn Fn(&harmonics::RevolutionFit) -> f64| -> Vec<f64> { revs.iter().map(f).collect() };
    let matrix = |pick: &dyn Fn(&Coefficients) -> &[f64]| -> PyResult<Array2<f64>> {
        let flat: Vec<f64> = revs
            .iter()
            .flat_map(|r| pick(&r.coefficients).iter().copied())
            .collect();
        Array2::from_shape_vec((k, n), flat)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
    };
    per.set_item(
        "first_sample",
        revs.iter()
            .map(|r| r.first_sample as u64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    per.set_item(
        "samples",
        revs.iter()
            .map(|r| r.samples as u64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    per.set_item("l0", column(&|r| r.coefficients.l0).into_pyarray(py))?;
    per.set_item("c", matrix(&|c| &c.c)?.into_pyarray(py))?;
    per.set_item("s", matrix(&|c| &c.s)?.into_pyarray(py))?;
    per.set_item(
        "drift_per_s",
        if fit.drift {
            Some(column(&|r| r.coefficients.drift_per_s.unwrap_or(f64::NAN)).into_pyarray(py))
        } else {
            None
        },
    )?;
    per.set_item("residual_rms", column(&|r| r.residual_rms).into_pyarray(py))?;
    per.set_item("condition", column(&|r| r.condition).into_pyarray(py))?;
    d.set_item("per_revolution", per)?;
    Ok(d)
}

/// `[{code, message}]` of a recording's diagnostics.
pub(crate) fn warnings<'py>(
    py: Python<'py>,
    diagnostics: &[Diagnostic],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for w in diagnostics {
        let d = PyDict::new(py);
        d.set_item("code", w.code())?;
        d.set_item("message", w.to_string())?;
        list.append(d)?;
    }
    Ok(list)
}

/// The analysis with its lengths times `um` (coefficients, spreads, residuals; the
/// condition numbers and sample counts as they are).
fn scaled(fit: &HarmonicAnalysis, um: f64) -> HarmonicAnalysis {
    let mut out = fit.clone();
    out.mean = fit.mean.scaled(um);
    out.std = fit.std.as_ref().map(|c| c.scaled(um));
    out.std_error = fit.std_error.as_ref().map(|c| c.scaled(um));
    for r in &mut out.revolutions {
        r.coefficients = r.coefficients.scaled(um);
        r.residual_rms *= um;
    }
    out
}

/// The encoder's mean rate over samples `from..=to` (unwrapped: a turn for each step
/// beyond ±π), rad/s.
fn encoder_rate(time_s: &[f64], angle: &[f64], from: usize, to: usize) -> Option<f64> {
    let to = to.min(angle.len().checked_sub(1)?);
    if to <= from {
        return None;
    }
    let wraps: i64 = angle[from..=to]
        .windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            i64::from(d < -PI) - i64::from(d > PI)
        })
        .sum();
    let span = angle[to] - angle[from] + TAU * wraps as f64;
    Some(span / (time_s[to] - time_s[from]))
}

/// What the Rust side of `fit_harmonics` computes, before it becomes Python values.
struct ArrayFit {
    analysis: HarmonicAnalysis,
    measured_rate_rad_s: Option<f64>,
    diagnostics: Vec<Diagnostic>,
    seconds: f64,
}

/// A gap unit by its symbol (`nm`, `um` or `µm`, `mm`, `m`), as a format's `unit`.
pub(crate) fn length_unit(py: Python<'_>, symbol: &str) -> PyResult<LengthUnit> {
    Ok(match symbol {
        "nm" => LengthUnit::Nm,
        "um" | "µm" | "μm" => LengthUnit::Um,
        "mm" => LengthUnit::Mm,
        "m" => LengthUnit::M,
        other => {
            return Err(errors::input(
                py,
                "gap_unit",
                format!("gap_unit: {other:?} is not a length unit (nm, um, mm or m)"),
            ));
        }
    })
}

/// Fit eq. 20 to each complete revolution of arrays (the GIL released meanwhile); the gap
/// is in `gap_unit`, the results in µm.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (time_s, gap, angle_rad, rate_rad_s, start_angle_rad, order, drift, revolutions, max_gap_intervals, probe_along, gap_unit, on_outlier))]
pub(crate) fn fit_harmonics<'py>(
    py: Python<'py>,
    time_s: PyReadonlyArray1<'py, f64>,
    gap: PyReadonlyArray1<'py, f64>,
    angle_rad: Option<PyReadonlyArray1<'py, f64>>,
    rate_rad_s: f64,
    start_angle_rad: f64,
    order: usize,
    drift: bool,
    revolutions: Option<usize>,
    max_gap_intervals: f64,
    probe_along: bool,
    gap_unit: &str,
    on_outlier: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let unit = length_unit(py, gap_unit)?;
    // A recording format's `on_outlier`, with the same words and default.
    let on_outlier = match on_outlier {
        "drop_revolution" => OnOutlier::DropRevolution,
        "keep" => OnOutlier::Keep,
        other => {
            return Err(errors::input(
                py,
                "on_outlier",
                format!("on_outlier: {other:?} is not a policy (drop_revolution or keep)"),
            ));
        }
    };
    let t = Samples::of(&time_s);
    let g = Samples::of(&gap);
    let a = angle_rad.as_ref().map(Samples::of);
    let (t, g, a) = (t.get(), g.get(), a.as_ref().map(Samples::get));
    if g.len() != t.len() {
        return Err(errors::input(
            py,
            "gap",
            format!(
                "gap has {} samples and time_s {}: one gap per time is needed",
                g.len(),
                t.len()
            ),
        ));
    }
    if let Some(a) = a
        && a.len() != t.len()
    {
        return Err(errors::input(
            py,
            "angle_rad",
            format!(
                "angle_rad has {} samples and time_s {}: one angle per time is needed",
                a.len(),
                t.len()
            ),
        ));
    }
    let config = FitConfig {
        order,
        drift,
        revolutions,
        max_gap_intervals,
    };
    let outcome = py.detach(|| -> harmonics::Result<ArrayFit> {
        let start = Instant::now();
        let signal = ProbeSignal {
            time_s: t,
            gap: g,
            angle: match a {
                Some(a) => SpindleAngle::Encoder(a),
                None => SpindleAngle::Rate {
                    rate_rad_s,
                    start_angle_rad,
                },
            },
        };
        if a.is_some() {
            harmonics::check_encoder_rate(&signal, DeclaredRate::new(rate_rad_s))?;
        }
        let analysis = harmonics::analyze(&signal, &config)?;
        let measured_rate_rad_s =
            match (a, analysis.revolutions.first(), analysis.revolutions.last()) {
                (Some(a), Some(first), Some(last)) => {
                    encoder_rate(t, a, first.first_sample, last.first_sample + last.samples)
                }
                _ => None,
            };
        // A revolution that fits far worse than the others (a glitch) warned and, by
        // default, left out; residuals alternating in sign warned: as the study does.
        let (analysis, outliers) =
            recording::outlier_check(&signal, analysis, on_outlier, unit, SampleAt::Sample);
        let mut diagnostics = Vec::new();
        if a.is_none() {
            diagnostics.push(Diagnostic::AngleFromRate {
                unread_columns: Vec::new(),
                start_angle_deg: start_angle_rad.to_degrees(),
            });
        }
        if let Some(m) = measured_rate_rad_s
            && (m / rate_rad_s - 1.0).abs() > recording::RATE_WARNING_TOLERANCE
        {
            diagnostics.push(Diagnostic::RateDiffers {
                declared_rad_s: rate_rad_s,
                measured_rad_s: m,
            });
        }
        diagnostics.extend(outliers);
        // drift not fitted, spread beyond white noise: as for a recording read from a file
        let statistics = recording::revolution_statistics(
            &signal,
            &analysis,
            &config,
            if a.is_some() {
                AngleSourceKind::Encoder
            } else {
                AngleSourceKind::DeclaredRate
            },
            measured_rate_rad_s.unwrap_or(rate_rad_s),
        );
        diagnostics.extend(statistics.diagnostics);
        // a gap implausible in its declared unit (mm read as µm): as the study warns
        diagnostics.extend(recording::implausible_gap(unit, &analysis));
        Ok(ArrayFit {
            analysis,
            measured_rate_rad_s,
            diagnostics,
            seconds: start.elapsed().as_secs_f64(),
        })
    });
    let fit = outcome.map_err(|e| {
        let kind = match e {
            harmonics::HarmonicsError::IllConditioned { .. }
            | harmonics::HarmonicsError::NonFiniteResult { .. } => Kind::Computation,
            _ => Kind::Input,
        };
        errors::raise(py, kind, errors::chain_message(&e), Located::harmonics(&e))
    })?;
    let direction = if probe_along {
        ProbeDirection::AlongO1X1
    } else {
        ProbeDirection::AgainstO1X1
    };
    let d = analysis(py, &fit.analysis, direction, unit.um_per_unit())?;
    d.set_item("samples", t.len())?;
    d.set_item(
        "angle_source",
        if a.is_some() {
            "encoder"
        } else {
            "declared_rate"
        },
    )?;
    d.set_item("rate_deg_s", rate_rad_s.to_degrees())?;
    d.set_item(
        "measured_rate_deg_s",
        fit.measured_rate_rad_s.map(f64::to_degrees),
    )?;
    d.set_item("dropped_revolutions", 0)?;
    d.set_item("warnings", warnings(py, &fit.diagnostics)?)?;
    d.set_item("rust_seconds", fit.seconds)?;
    d.set_item("declared_gap_unit", unit.key())?;
    Ok(d)
}
