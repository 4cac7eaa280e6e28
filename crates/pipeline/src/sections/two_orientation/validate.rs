//! The two-orientation section's validation: every missing or contradictory field of its
//! data sets at once, in the configuration's keys, the probe phase it compares with, the
//! Type B inputs it carries, and the reading of its data (a PIGA table or raw PIGA output
//! recordings per orientation, through the calibration section's readers in `piga_data`).

use std::path::Path;

use ::calibration::{MIN_RATES_PER_ORIENTATION, Orientation, TwoOrientationError};

use crate::config::{TrialsConfig, TwoOrientationConfig};
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, DataSource, InputFile, PhaseNames};
use crate::piga_data::{self, PigaData};
use crate::resolved::Resolved;

/// Least number of Monte Carlo trials for a 95 % coverage interval (JCGM 101 §7.2).
const MIN_TRIALS: u64 = 2000;

/// One orientation's data set, validated and read.
#[derive(Debug, Clone)]
pub(crate) struct OrientationSet {
    /// `two_orientation.orientations[i]`.
    pub(crate) field: String,
    pub(crate) orientation: Orientation,
    pub(crate) radius_m: f64,
    /// Its PIGA table, or its raw output recordings (reduced to points by the run).
    pub(crate) data: PigaData,
}

/// The validated two-orientation section.
#[derive(Debug, Clone)]
pub(crate) struct TwoOrientationInputs {
    /// The two data sets, in the configuration's order.
    pub(crate) sets: Vec<OrientationSet>,
    /// The probe phase compared with, and how it was chosen.
    pub(crate) phase: usize,
    pub(crate) chosen_by: &'static str,
    /// The field stating the compared phase's gap unit, and what it states (for the
    /// disagreement warning).
    pub(crate) gap_unit: (String, String),
    pub(crate) seed: u64,
    /// `None`: adaptive.
    pub(crate) trials: Option<u64>,
    /// The Type B standard uncertainties (the `uncertainty` section's, every input stated;
    /// all 0 without the section): u(R) applies to each mounting's radius, the two
    /// independent.
    pub(crate) type_b: ::calibration::TypeB,
    /// What the budget says beside an input (by its index in `calibration::input`): that the
    /// study states no Type B input, the reason for a zero, or where the probe gain's
    /// uncertainty comes from.
    pub(crate) type_b_notes: Vec<(usize, String)>,
    /// The Earth rate about the spindle axis as stated or taken, in results' words (its value
    /// is `type_b.axial_earth_rate`).
    pub(crate) earth_rate: crate::results::AxialEarthRateResult,
}

impl TwoOrientationInputs {
    /// Every data file the section read, with its digest, in the configuration's order.
    pub(crate) fn input_files(&self) -> impl Iterator<Item = InputFile<'_>> {
        self.sets.iter().flat_map(|s| s.data.input_files())
    }
}

fn two_orientation_error(check: &Check<'_>, source: TwoOrientationError) -> PipelineError {
    PipelineError::TwoOrientation {
        path: check.path.to_owned(),
        source: Box::new(source),
    }
}

/// Validates the section and reads its tables. Every problem that can be found is reported
/// at once, in the configuration's order: a missing orientation or radius, both data sets
/// with the same orientation, one orientation only, a table that cannot be read, fewer
/// distinct rates than the joint model needs. Without `compare_with`, the probe phase is the
/// study's compensating phase (`resolved`).
pub(crate) fn validate(
    check: &Check<'_>,
    config: &TwoOrientationConfig,
    resolved: &Resolved<'_>,
    names: &PhaseNames<'_>,
    base: &Path,
    load: &dyn DataSource,
) -> Result<TwoOrientationInputs> {
    let mut errors = Vec::new();
    let field = |i: usize| format!("two_orientation.orientations[{i}]");
    // the fields of each data set
    for (i, o) in config.orientations.iter().enumerate() {
        if o.orientation.is_none() {
            errors.push(two_orientation_error(
                check,
                TwoOrientationError::MissingOrientation {
                    field: format!("{}.orientation", field(i)),
                },
            ));
        }
        match o.radius_m {
            None => errors.push(two_orientation_error(
                check,
                TwoOrientationError::MissingRadius {
                    field: format!("{}.radius_m", field(i)),
                },
            )),
            Some(r) if !(r.is_finite() && r > 0.0) => errors.push(check.invalid(
                format!("{}.radius_m", field(i)),
                r,
                InvalidReason::NotPositive,
            )),
            Some(_) => {}
        }
    }
    // one data set per orientation
    let declared: Vec<(usize, Orientation)> = config
        .orientations
        .iter()
        .enumerate()
        .filter_map(|(i, o)| o.orientation.map(|n| (i, n.orientation())))
        .collect();
    let mut same = false;
    for (k, &(i, o)) in declared.iter().enumerate() {
        if let Some(&(j, _)) = declared[..k].iter().find(|(_, p)| *p == o) {
            same = true;
            errors.push(two_orientation_error(
                check,
                TwoOrientationError::SameOrientation {
                    field: format!("{}.orientation", field(i)),
                    first: format!("{}.orientation", field(j)),
                    orientation: o.label(),
                },
            ));
        }
    }
    let has = |o: Orientation| declared.iter().any(|(_, p)| *p == o);
    let undeclared = declared.len() < config.orientations.len();
    // an undeclared orientation is reported as missing, not as a second one absent
    let both = undeclared || same || (has(Orientation::IaIn) && has(Orientation::IaOut));
    if config.orientations.len() > 2 || !both {
        let words: Vec<&str> = config
            .orientations
            .iter()
            .map(|o| {
                o.orientation
                    .map_or("undeclared", |n| n.orientation().label())
            })
            .collect();
        errors.push(two_orientation_error(
            check,
            TwoOrientationError::OneOrientationOnly {
                field: "two_orientation.orientations".to_owned(),
                got: if words.is_empty() {
                    "no data set".to_owned()
                } else {
                    format!("{} data set(s): {}", words.len(), words.join(", "))
                },
            },
        ));
    }
    // the probe phase and the Monte Carlo settings
    let (phase, chosen_by) = match &config.compare_with {
        Some(name) => (
            names.index(check, "two_orientation.compare_with", name),
            "compare_with",
        ),
        None => (
            Ok(resolved.compensation.index),
            resolved.compensation.chosen_by,
        ),
    };
    let phase = match phase {
        Ok(p) if names.second_probe.contains(&p) => {
            errors.push(PipelineError::Unsupported {
                path: check.path.to_owned(),
                field: "two_orientation.compare_with".to_owned(),
                reason: UnsupportedReason::SecondProbeData,
            });
            p
        }
        Ok(p) => p,
        Err(e) => {
            errors.push(e);
            0
        }
    };
    let trials = match config.trials {
        TrialsConfig::Adaptive => None,
        TrialsConfig::Fixed(n) => {
            if n < MIN_TRIALS {
                errors.push(check.invalid(
                    "two_orientation.trials".to_owned(),
                    n as f64,
                    InvalidReason::TooFewTrials,
                ));
            }
            // Refused here, at `check`, with the memory and time it would take (issue 32).
            if let Err(e) =
                uncertainty::check_trials(n, ::calibration::TWO_ORIENTATION_OUTPUTS.len())
            {
                errors.push(PipelineError::Uncertainty {
                    path: check.path.to_owned(),
                    field: "two_orientation.trials".to_owned(),
                    source: Box::new(e),
                });
            }
            Some(n)
        }
    };
    let (mut type_b, type_b_notes) = type_b(check, resolved, phase, &mut errors);
    let earth_rate = earth_rate(check, config, &mut errors);
    type_b.axial_earth_rate = ::calibration::AxialEarthRate {
        value_rad_s: earth_rate.value_rad_s,
        half_width_rad_s: earth_rate.half_width_rad_s,
    };
    // the data sets (a table or raw recordings), then their rates
    let mut sets = Vec::with_capacity(config.orientations.len());
    for (i, o) in config.orientations.iter().enumerate() {
        match read_data(o, &field(i), base, check.path, load) {
            Ok(data) => {
                let distinct = distinct(&data.declared_rates_deg_s());
                let o_label = o
                    .orientation
                    .map_or("undeclared", |n| n.orientation().label());
                if distinct < MIN_RATES_PER_ORIENTATION {
                    let (named, file) = data.named();
                    errors.push(two_orientation_error(
                        check,
                        TwoOrientationError::TooFewRates {
                            field: format!("{named} ({})", file.display()),
                            orientation: o_label,
                            distinct,
                            need: MIN_RATES_PER_ORIENTATION,
                        },
                    ));
                }
                if let (Some(n), Some(r)) = (o.orientation, o.radius_m) {
                    sets.push(OrientationSet {
                        field: field(i),
                        orientation: n.orientation(),
                        radius_m: r,
                        data,
                    });
                }
            }
            Err(e) => errors.push(e),
        }
    }
    PipelineError::from_list(errors)?;
    Ok(TwoOrientationInputs {
        sets,
        gap_unit: resolved.gap_unit(phase),
        phase,
        chosen_by,
        seed: config.seed,
        trials,
        type_b,
        type_b_notes,
        earth_rate,
    })
}

/// The Earth rate about the spindle axis from the section's latitude and spin: both stated,
/// `±Ω·sin L`; the latitude alone, 0 ± `Ω·|sin L|`; else 0 ± Ω (rectangular), what any site
/// and spin allow — each said in words. A latitude outside ±90° goes to `errors`.
fn earth_rate(
    check: &Check<'_>,
    config: &crate::config::TwoOrientationConfig,
    errors: &mut Vec<PipelineError>,
) -> crate::results::AxialEarthRateResult {
    use ::calibration::AxialEarthRate;
    let latitude = config.latitude_deg.filter(|lat| {
        let ok = lat.is_finite() && lat.abs() <= 90.0;
        if !ok {
            errors.push(check.invalid(
                "two_orientation.latitude_deg".to_owned(),
                *lat,
                crate::error::InvalidReason::NotALatitude,
            ));
        }
        ok
    });
    let spin = config.spin_seen_from_above;
    // µrad/s to 0.1: what a person compares with Ω = 72.9 µrad/s
    let micro = |x: f64| format!("{:.1} µrad/s", x * 1e6);
    let (taken, words) = match (latitude, spin) {
        (Some(lat), Some(s)) => {
            let e = AxialEarthRate::stated(lat, s.spin());
            let words = format!(
                "stated: latitude {}°, spin {}: Ω·sin L = {}",
                units::Compact(lat),
                s.words(),
                micro(e.value_rad_s)
            );
            (e, words)
        }
        (Some(lat), None) => {
            let e = AxialEarthRate::latitude_only(lat);
            let words = format!(
                "the spin is not stated: 0 ± {} (rectangular), the Earth rate at latitude {}° \
                 either way",
                micro(e.half_width_rad_s),
                units::Compact(lat)
            );
            (e, words)
        }
        (None, _) => {
            let e = AxialEarthRate::not_stated();
            let words = format!(
                "the site's latitude and the spin are not stated: 0 ± {} (rectangular), the \
                 Earth rate at any site, either spin",
                micro(e.half_width_rad_s)
            );
            (e, words)
        }
    };
    crate::results::AxialEarthRateResult {
        latitude_deg: latitude,
        spin: spin.map(|s| s.words().to_owned()),
        value_rad_s: taken.value_rad_s,
        half_width_rad_s: taken.half_width_rad_s,
        words,
    }
}

/// The Type B inputs of the two-orientation budget: the `uncertainty` section read as the
/// calibration section reads it (`Resolved::type_b_at`: every input stated, or 0 with its reason;
/// each finite and ≥ 0), with the probe gain stated by the compared phase's recordings in
/// volts instead when they state it (stating it in both places is refused). Without an
/// `uncertainty` section every input is 0 and the budget says so beside each. Problems go to
/// `errors`.
fn type_b(
    check: &Check<'_>,
    resolved: &Resolved<'_>,
    phase: usize,
    errors: &mut Vec<PipelineError>,
) -> (::calibration::TypeB, Vec<(usize, String)>) {
    use ::calibration::input;
    let unstated = |notes: &mut Vec<(usize, String)>| {
        for index in [
            input::RADIUS,
            input::G,
            input::RATE_SCALE,
            input::PIVOT_TO_PROBE,
            input::PROBE_TO_PIGA,
            input::PROBE_GAIN,
        ] {
            if !notes.iter().any(|(i, _)| *i == index) {
                notes.push((
                    index,
                    "not stated (the study has no `uncertainty` section): taken as 0".to_owned(),
                ));
            }
        }
    };
    match resolved.type_b_at(check, phase) {
        Ok(Some(t)) => {
            let mut notes = t.notes;
            if !t.from_section {
                unstated(&mut notes);
            }
            (t.values, notes)
        }
        Ok(None) => {
            let mut notes = Vec::new();
            unstated(&mut notes);
            (::calibration::TypeB::default(), notes)
        }
        Err(e) => {
            errors.push(e);
            (::calibration::TypeB::default(), Vec::new())
        }
    }
}

fn distinct(rates: &[f64]) -> usize {
    let mut v: Vec<u64> = rates.iter().map(|r| r.to_bits()).collect();
    v.sort_unstable();
    v.dedup();
    v.len()
}

/// Reads one data set: its PIGA table or its raw recordings (exactly one), with the
/// calibration section's readers, errors naming `two_orientation.orientations[i].table` or
/// `….recordings.files[j]`.
fn read_data(
    o: &crate::config::OrientationConfig,
    field: &str,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<PigaData> {
    match (&o.table, &o.recordings) {
        (Some(table), None) => Ok(PigaData::Table(piga_data::load_piga_table(
            table,
            &format!("{field}.table"),
            base,
            source,
            load,
        )?)),
        (None, Some(set)) => {
            piga_data::load_piga_recordings(set, &format!("{field}.recordings"), base, source, load)
        }
        _ => Err(PipelineError::Unsupported {
            path: source.to_owned(),
            field: field.to_owned(),
            reason: UnsupportedReason::CalibrationNeedsOneSource,
        }),
    }
}
