//! The calibration section's run: its points, their evaluation and the results, with the
//! section's warnings; and the same set-up handed to a benchmark.

use ::calibration::CalibrationModel;

use super::evaluate::{CalibrationFailure, Nominal, Setting, evaluate, setup};
use super::report;
use super::validate::CalibrationInputs;
use crate::error::{PipelineError, Result};
use crate::inputs::Core;
use crate::piga_data as data;
use crate::results::{CalibrationResults, PhaseResults, Warning};

/// Runs the calibration section, compensating with `phase` (its radius-error fit): the
/// points, the evaluation and its results, with the section's warnings (the recordings'
/// diagnostics, then those about the data).
pub(crate) fn run(
    inputs: &Core,
    c: &CalibrationInputs,
    phase: &PhaseResults,
) -> Result<(CalibrationResults, Vec<Warning>)> {
    let _span = tracing::info_span!("calibration").entered();
    let setting = setting(inputs, c, phase);
    let (points, mut warnings) = data::points(&c.data, &inputs.source)?;
    let evaluated = evaluate(c, &points, &setting).map_err(|e| calibration_error(inputs, e))?;
    let results = report::results(c, &points, &setting, &phase.name, &evaluated);
    let phase_rates: Vec<f64> = phase.points.iter().map(|p| p.rate_deg_s).collect();
    warnings.extend(report::data_warnings(
        &results,
        &evaluated.fit_warnings,
        &phase_rates,
    ));
    Ok((results, warnings))
}

/// The measurement model with its validated input quantities and the Monte Carlo options,
/// set up as [`run`] sets them up before its GUM and Monte Carlo evaluations, with the
/// compensating `phase`.
pub(crate) fn measurement(
    inputs: &Core,
    c: &CalibrationInputs,
    phase: &PhaseResults,
) -> Result<CalibrationMeasurement> {
    let setting = setting(inputs, c, phase);
    let (points, _) = data::points(&c.data, &inputs.source)?;
    let setup = setup(c, &points, &setting).map_err(|e| calibration_error(inputs, e))?;
    Ok(CalibrationMeasurement {
        model: setup.model,
        inputs: setup.set,
        options: setup.options,
    })
}

/// The calibration's uncertainty evaluation as [`crate::calibration_measurement`] sets it up.
#[derive(Debug, Clone)]
pub struct CalibrationMeasurement {
    /// The measurement model (14 inputs, 6 outputs; see [`CalibrationModel`]).
    pub model: CalibrationModel,
    /// Its input quantities, validated, with the eq. 18 fit's coefficients as one correlated
    /// Type A group.
    pub inputs: uncertainty::Inputs,
    /// The Monte Carlo options the study asks for (its seed and trials).
    pub options: uncertainty::McOptions,
}

/// The nominal values and uncertainties of the calibration, with the compensating `phase`.
fn setting<'a>(inputs: &Core, c: &'a CalibrationInputs, phase: &PhaseResults) -> Setting<'a> {
    Setting {
        nominal: Nominal {
            radius_m: inputs.radius_m,
            g_m_s2: inputs.g_m_s2,
            pivot_to_probe_mm: inputs.lever.pivot_to_probe_mm,
            probe_to_piga_mm: inputs.lever.probe_to_piga_mm,
            c_r_m_s2: phase.fit.c_r_m_s2,
        },
        type_b: &c.type_b,
        c_r_sigma: phase.fit.c_r_sigma_m_s2.map(|s| (s, phase.fit.dof)),
        probe_direction: inputs.lever.probe_direction,
    }
}

/// A calibration failure located in the study file.
fn calibration_error(inputs: &Core, e: CalibrationFailure) -> PipelineError {
    match e {
        CalibrationFailure::Calibration(::calibration::CalibrationError::Fit(source)) => {
            PipelineError::Identify {
                path: inputs.source.clone(),
                field: "calibration".to_owned(),
                source,
            }
        }
        CalibrationFailure::Calibration(source) => PipelineError::Calibration {
            path: inputs.source.clone(),
            field: "calibration".to_owned(),
            source,
        },
        CalibrationFailure::Uncertainty(source) => PipelineError::Uncertainty {
            path: inputs.source.clone(),
            field: "calibration".to_owned(),
            source: Box::new(source),
        },
    }
}
