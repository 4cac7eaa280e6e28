//! The calibration section's validation: the compensating phase, k1, the Monte Carlo
//! trials, the `uncertainty` section's Type B inputs, and the reading of its data.

use std::path::Path;

use crate::config::{CalibrationConfig, K1Config, TrialsConfig};
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, DataSource, InputFile, MIN_CALIBRATION_RATES};
use crate::piga_data::{self as data, PigaData};
use crate::resolved::Resolved;
pub(crate) use crate::type_b::TypeB;

/// Least number of Monte Carlo trials for a 95 % coverage interval (JCGM 101 §7.2: 100/(1 − p)).
const MIN_TRIALS: u64 = 2000;

/// The validated calibration section.
#[derive(Debug, Clone)]
pub(crate) struct CalibrationInputs {
    pub(crate) data: PigaData,
    /// Index of the phase whose C_r compensates.
    pub(crate) phase: usize,
    pub(crate) k1: K1Choice,
    pub(crate) seed: u64,
    /// `None`: adaptive; `Some(n)`: exactly n trials.
    pub(crate) trials: Option<u64>,
    /// Type B uncertainties (all zero when the study has no `uncertainty` section).
    pub(crate) type_b: TypeB,
    /// Whether the study has an `uncertainty` section.
    pub(crate) type_b_given: bool,
}

/// Where k1 comes from, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum K1Choice {
    Fitted,
    Given { k1_rad_s_g: f64, u_rad_s_g: f64 },
}

impl CalibrationInputs {
    /// Every data file the section read: the PIGA table, or each raw recording.
    pub(crate) fn files(&self) -> Vec<&Path> {
        self.input_files().into_iter().map(|f| f.path).collect()
    }

    /// Every data file the section read, with its digest: the PIGA table, or each raw
    /// recording, in the configuration's order.
    pub(crate) fn input_files(&self) -> Vec<InputFile<'_>> {
        self.data.input_files()
    }
}

/// The calibration's references and numbers: the phase it compensates with (its
/// `compensate_with` as the study resolved it, `resolved`), the Monte Carlo trials and k1.
pub(crate) fn validate(
    check: &Check<'_>,
    c: &CalibrationConfig,
    resolved: &Resolved<'_>,
) -> Result<(usize, K1Choice)> {
    let phase = resolved.compensation.index;
    if let TrialsConfig::Fixed(n) = c.trials {
        if n < MIN_TRIALS {
            return Err(check.invalid(
                "calibration.trials".to_owned(),
                n as f64,
                InvalidReason::TooFewTrials,
            ));
        }
        // Refused here, at `check`, with the memory and time it would take (issue 32).
        uncertainty::check_trials(n, ::calibration::output::NAMES.len()).map_err(|e| {
            PipelineError::Uncertainty {
                path: check.path.to_owned(),
                field: "calibration.trials".to_owned(),
                source: Box::new(e),
            }
        })?;
    }
    let k1 = match c.k1 {
        K1Config::Fitted => K1Choice::Fitted,
        K1Config::Given {
            k1_rad_s_g,
            u_rad_s_g,
        } => {
            check.positive("calibration.k1.k1_rad_s_g", k1_rad_s_g)?;
            check.non_negative("calibration.k1.u_rad_s_g", u_rad_s_g)?;
            K1Choice::Given {
                k1_rad_s_g,
                u_rad_s_g,
            }
        }
    };
    Ok((phase, k1))
}

/// Reads the calibration's data — a PIGA table (rates > 0, σ > 0 when given) or raw output
/// recordings (read in parallel) — and checks that it has at least [`MIN_CALIBRATION_RATES`]
/// distinct rates (six unknowns and a residual degree of freedom). `type_b`: the validated
/// `uncertainty` section, if any.
pub(crate) fn load(
    config: &CalibrationConfig,
    (phase, k1): (usize, K1Choice),
    type_b: Option<TypeB>,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<CalibrationInputs> {
    let data = match (&config.table, &config.recordings) {
        (Some(table), None) => PigaData::Table(data::load_piga_table(
            table,
            "calibration.table",
            base,
            source,
            load,
        )?),
        (None, Some(set)) => {
            data::load_piga_recordings(set, "calibration.recordings", base, source, load)?
        }
        _ => {
            return Err(PipelineError::Unsupported {
                path: source.to_owned(),
                field: "calibration".to_owned(),
                reason: UnsupportedReason::CalibrationNeedsOneSource,
            });
        }
    };
    let rates = data.declared_rates_deg_s();
    let mut distinct: Vec<u64> = rates.iter().map(|r: &f64| r.to_bits()).collect();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() < MIN_CALIBRATION_RATES {
        let (field, file) = data.named();
        return Err(PipelineError::TooFewRates {
            path: source.to_owned(),
            field,
            file,
            distinct: distinct.len(),
            need: MIN_CALIBRATION_RATES,
        });
    }
    Ok(CalibrationInputs {
        data,
        phase,
        k1,
        seed: config.seed,
        trials: match config.trials {
            TrialsConfig::Adaptive => None,
            TrialsConfig::Fixed(n) => Some(n),
        },
        type_b_given: type_b.as_ref().is_some_and(|t| t.from_section),
        type_b: type_b.unwrap_or_default(),
    })
}
