//! The calibration section's validation: the compensating phase, k1, the Monte Carlo
//! trials, the `uncertainty` section's Type B inputs, and the reading of its data.

use std::path::Path;

use crate::config::{CalibrationConfig, K1Config, TrialsConfig, UncertaintyConfig};
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, DataSource, InputFile, MIN_CALIBRATION_RATES, PhaseNames};
use crate::piga_data::{self as data, PigaData};

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

/// Type B standard uncertainties, validated (all finite and ≥ 0), and where g comes from.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct TypeB {
    pub(crate) values: ::calibration::TypeB,
    pub(crate) g_source: String,
    /// What the budget says beside an input (by its index in `calibration::input`): the
    /// reason for a zero, or where the probe gain's uncertainty comes from.
    pub(crate) notes: Vec<(usize, String)>,
    /// Whether the study has an `uncertainty` section (else only the recordings' stated
    /// probe gain).
    pub(crate) from_section: bool,
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

/// The calibration's references and numbers: the phase it compensates with, and k1.
pub(crate) fn validate(
    check: &Check<'_>,
    c: &CalibrationConfig,
    names: &PhaseNames<'_>,
) -> Result<(usize, K1Choice)> {
    let phase = names.index(check, "calibration.compensate_with", &c.compensate_with)?;
    if names.second_probe.contains(&phase) {
        return Err(PipelineError::Unsupported {
            path: check.path.to_owned(),
            field: "calibration.compensate_with".to_owned(),
            reason: UnsupportedReason::SecondProbeData,
        });
    }
    if let TrialsConfig::Fixed(n) = c.trials
        && n < MIN_TRIALS
    {
        return Err(check.invalid(
            "calibration.trials".to_owned(),
            n as f64,
            InvalidReason::TooFewTrials,
        ));
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

/// The Type B uncertainties of the `uncertainty` section `u` (absent: none given) and the
/// probe gain stated by the compensating phase's recordings in volts (`stated_gain`: its
/// relative u and the field stating it): every input stated, each finite and ≥ 0, a zero
/// with its reason, the probe gain stated once. `None` when neither states anything. Every
/// problem at once.
pub(crate) fn type_b(
    check: &Check<'_>,
    u: Option<&UncertaintyConfig>,
    stated_gain: Option<(f64, String)>,
) -> Result<Option<TypeB>> {
    use ::calibration::input;
    let Some(u) = u else {
        // Only the recordings state something: the probe gain.
        return Ok(stated_gain.map(|(gain, field)| TypeB {
            values: ::calibration::TypeB {
                probe_gain_u_relative: gain,
                ..::calibration::TypeB::default()
            },
            g_source: String::new(),
            notes: vec![(
                input::PROBE_GAIN,
                format!("from the probe's stated sensitivity ({field})"),
            )],
            from_section: false,
        }));
    };
    let mut errors = Vec::new();
    let mut notes = Vec::new();
    let mut values = [0.0; 6];
    let fields = [
        ("radius_u_m", u.radius_u_m, input::RADIUS),
        ("g_u_m_s2", u.g_u_m_s2, input::G),
        ("rate_u_relative", u.rate_u_relative, input::RATE_SCALE),
        (
            "pivot_to_probe_u_mm",
            u.pivot_to_probe_u_mm,
            input::PIVOT_TO_PROBE,
        ),
        (
            "probe_to_piga_u_mm",
            u.probe_to_piga_u_mm,
            input::PROBE_TO_PIGA,
        ),
        (
            "probe_gain_u_relative",
            u.probe_gain_u_relative,
            input::PROBE_GAIN,
        ),
    ];
    for (slot, (name, value, index)) in fields.into_iter().enumerate() {
        let field = format!("uncertainty.{name}");
        if index == input::PROBE_GAIN
            && let Some((gain, stated)) = &stated_gain
        {
            if value.is_some() {
                errors.push(PipelineError::StatedTwice {
                    path: check.path.to_owned(),
                    field: field.clone(),
                    other: stated.clone(),
                    what: "the probe gain's uncertainty",
                });
            }
            values[slot] = *gain;
            notes.push((
                index,
                format!("from the probe's stated sensitivity ({stated})"),
            ));
            continue;
        }
        let Some(v) = value else {
            errors.push(PipelineError::MissingField {
                path: check.path.to_owned(),
                field,
                hint: "every Type B input of the budget is stated: its standard uncertainty, or 0 \
                       with the reason in `zero_reasons`"
                    .to_owned(),
            });
            continue;
        };
        if let Err(e) = check.non_negative(&field, v) {
            errors.push(e);
            continue;
        }
        values[slot] = v;
        if v == 0.0 {
            match u.zero_reasons.get(name).filter(|r| !r.trim().is_empty()) {
                Some(reason) => notes.push((index, format!("taken as 0: {reason}"))),
                None => errors.push(PipelineError::MissingField {
                    path: check.path.to_owned(),
                    field: format!("uncertainty.zero_reasons.{name}"),
                    hint: format!(
                        "`{field}` is 0: say why it is negligible (`zero_reasons: {{\"{name}\": \"…\"}}`)"
                    ),
                }),
            }
        }
    }
    for key in u.zero_reasons.keys() {
        if !fields.iter().any(|(name, ..)| name == key) {
            errors.push(PipelineError::UnknownKey {
                path: check.path.to_owned(),
                field: "uncertainty.zero_reasons".to_owned(),
                key: key.clone(),
                known: fields.iter().map(|(n, ..)| (*n).to_owned()).collect(),
            });
        }
    }
    PipelineError::from_list(errors)?;
    Ok(Some(TypeB {
        values: ::calibration::TypeB {
            radius_u_m: values[0],
            g_u_m_s2: values[1],
            rate_u_relative: values[2],
            pivot_to_probe_u_mm: values[3],
            probe_to_piga_u_mm: values[4],
            probe_gain_u_relative: values[5],
        },
        g_source: u.g_source.clone(),
        notes,
        from_section: true,
    }))
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
