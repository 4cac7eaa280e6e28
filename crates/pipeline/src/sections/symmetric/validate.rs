//! The two-orientation section's validation: every missing or contradictory field of its
//! data sets at once, in the configuration's keys, the probe phase it compares with, the
//! Type B inputs it carries, and the reading of its PIGA tables.

use std::path::{Path, PathBuf};

use ::calibration::{MIN_RATES_PER_ORIENTATION, Orientation, SymmetricError};
use recording::FileDigest;

use crate::config::{
    OrientationName, PigaTableConfig, StudyConfig, SymmetricConfig, TableLayoutError, TrialsConfig,
};
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, DataSource, InputFile, InputRole, PhaseNames};

/// Least number of Monte Carlo trials for a 95 % coverage interval (JCGM 101 §7.2).
const MIN_TRIALS: u64 = 2000;

/// One orientation's data set, validated and read.
#[derive(Debug, Clone)]
pub(crate) struct OrientationSet {
    /// `symmetric.orientations[i]`.
    pub(crate) field: String,
    pub(crate) orientation: Orientation,
    pub(crate) radius_m: f64,
    pub(crate) file: PathBuf,
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) outputs_rad_s: Vec<f64>,
    pub(crate) sigma_rad_s: Option<Vec<f64>>,
    /// The table's size and SHA-256 as read, when the data source keeps them.
    pub(crate) digest: Option<FileDigest>,
}

/// The validated two-orientation section.
#[derive(Debug, Clone)]
pub(crate) struct SymmetricInputs {
    /// The two data sets, in the configuration's order.
    pub(crate) sets: Vec<OrientationSet>,
    /// The probe phase compared with, and how it was chosen.
    pub(crate) phase: usize,
    pub(crate) chosen_by: &'static str,
    pub(crate) seed: u64,
    /// `None`: adaptive.
    pub(crate) trials: Option<u64>,
    /// u(g), m/s² (the `uncertainty` section's; 0 without one).
    pub(crate) g_u_m_s2: f64,
    /// The `uncertainty` section's non-zero inputs the two-orientation model does not carry.
    pub(crate) omitted_type_b: Vec<&'static str>,
}

impl SymmetricInputs {
    /// Every data file the section read, with its digest, in the configuration's order.
    pub(crate) fn input_files(&self) -> impl Iterator<Item = InputFile<'_>> {
        self.sets.iter().map(|s| InputFile {
            path: &s.file,
            role: InputRole::PigaTable,
            field: format!("{}.table", s.field),
            digest: s.digest.as_ref(),
        })
    }
}

fn symmetric_error(check: &Check<'_>, source: SymmetricError) -> PipelineError {
    PipelineError::Symmetric {
        path: check.path.to_owned(),
        source: Box::new(source),
    }
}

/// Validates the section and reads its tables. Every problem that can be found is reported
/// at once, in the configuration's order: a missing orientation or radius, both data sets
/// with the same orientation, one orientation only, a table that cannot be read, fewer
/// distinct rates than the joint model needs.
pub(crate) fn validate(
    check: &Check<'_>,
    config: &SymmetricConfig,
    study: &StudyConfig,
    names: &PhaseNames<'_>,
    base: &Path,
    load: &dyn DataSource,
) -> Result<SymmetricInputs> {
    let mut errors = Vec::new();
    let field = |i: usize| format!("symmetric.orientations[{i}]");
    // the fields of each data set
    for (i, o) in config.orientations.iter().enumerate() {
        if o.orientation.is_none() {
            errors.push(symmetric_error(
                check,
                SymmetricError::MissingOrientation {
                    field: format!("{}.orientation", field(i)),
                },
            ));
        }
        match o.radius_m {
            None => errors.push(symmetric_error(
                check,
                SymmetricError::MissingRadius {
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
        .filter_map(|(i, o)| o.orientation.map(|n| (i, orientation(n))))
        .collect();
    let mut same = false;
    for (k, &(i, o)) in declared.iter().enumerate() {
        if let Some(&(j, _)) = declared[..k].iter().find(|(_, p)| *p == o) {
            same = true;
            errors.push(symmetric_error(
                check,
                SymmetricError::SameOrientation {
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
                    .map_or("undeclared", |n| orientation(n).label())
            })
            .collect();
        errors.push(symmetric_error(
            check,
            SymmetricError::OneOrientationOnly {
                field: "symmetric.orientations".to_owned(),
                got: if words.is_empty() {
                    "no data set".to_owned()
                } else {
                    format!("{} data set(s): {}", words.len(), words.join(", "))
                },
            },
        ));
    }
    // the probe phase and the Monte Carlo settings
    let (phase, chosen_by) = match (&config.compare_with, &study.calibration) {
        (Some(name), _) => (
            names.index(check, "symmetric.compare_with", name),
            "compare_with",
        ),
        (None, Some(c)) => (
            names.index(check, "calibration.compensate_with", &c.compensate_with),
            "calibration.compensate_with",
        ),
        (None, None) => (Ok(0), "first phase"),
    };
    let phase = match phase {
        Ok(p) if names.second_probe.contains(&p) => {
            errors.push(PipelineError::Unsupported {
                path: check.path.to_owned(),
                field: "symmetric.compare_with".to_owned(),
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
                    "symmetric.trials".to_owned(),
                    n as f64,
                    InvalidReason::TooFewTrials,
                ));
            }
            Some(n)
        }
    };
    let (g_u_m_s2, omitted_type_b) = match &study.uncertainty {
        None => (0.0, Vec::new()),
        Some(u) => {
            let g_u = u.g_u_m_s2.unwrap_or(0.0);
            if let Err(e) = check.non_negative("uncertainty.g_u_m_s2", g_u) {
                errors.push(e);
            }
            let omitted: Vec<&'static str> = [
                ("u(R)", u.radius_u_m.unwrap_or(0.0)),
                ("the rate scale", u.rate_u_relative.unwrap_or(0.0)),
                (
                    "the lever heights",
                    u.pivot_to_probe_u_mm.unwrap_or(0.0) + u.probe_to_piga_u_mm.unwrap_or(0.0),
                ),
                ("the probe gain", u.probe_gain_u_relative.unwrap_or(0.0)),
            ]
            .into_iter()
            .filter(|(_, v)| *v > 0.0)
            .map(|(n, _)| n)
            .collect();
            (g_u.max(0.0), omitted)
        }
    };
    // the tables, then their rates
    let mut sets = Vec::with_capacity(config.orientations.len());
    for (i, o) in config.orientations.iter().enumerate() {
        match read_table(&o.table, &field(i), base, check.path, load) {
            Ok((file, rates_deg_s, outputs_rad_s, sigma_rad_s, digest)) => {
                let distinct = distinct(&rates_deg_s);
                let o_label = o
                    .orientation
                    .map_or("undeclared", |n| orientation(n).label());
                if distinct < MIN_RATES_PER_ORIENTATION {
                    errors.push(symmetric_error(
                        check,
                        SymmetricError::TooFewRates {
                            field: format!("{}.table ({})", field(i), file.display()),
                            orientation: o_label,
                            distinct,
                            need: MIN_RATES_PER_ORIENTATION,
                        },
                    ));
                }
                if let (Some(n), Some(r)) = (o.orientation, o.radius_m) {
                    sets.push(OrientationSet {
                        field: field(i),
                        orientation: orientation(n),
                        radius_m: r,
                        file,
                        rates_deg_s,
                        outputs_rad_s,
                        sigma_rad_s,
                        digest,
                    });
                }
            }
            Err(e) => errors.push(e),
        }
    }
    PipelineError::from_list(errors)?;
    Ok(SymmetricInputs {
        sets,
        phase,
        chosen_by,
        seed: config.seed,
        trials,
        g_u_m_s2,
        omitted_type_b,
    })
}

const fn orientation(n: OrientationName) -> Orientation {
    match n {
        OrientationName::IaIn => Orientation::IaIn,
        OrientationName::IaOut => Orientation::IaOut,
    }
}

fn distinct(rates: &[f64]) -> usize {
    let mut v: Vec<u64> = rates.iter().map(|r| r.to_bits()).collect();
    v.sort_unstable();
    v.dedup();
    v.len()
}

/// Columns read from a PIGA table: the file, rates (deg/s), outputs (rad/s), σ, and the
/// file's digest.
type TableColumns = (
    PathBuf,
    Vec<f64>,
    Vec<f64>,
    Option<Vec<f64>>,
    Option<FileDigest>,
);

/// Reads one data set's PIGA table with the calibration section's format options (rate and
/// output columns, delimiter, σ column); rates must be > 0 and σ > 0.
fn read_table(
    config: &PigaTableConfig,
    field: &str,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<TableColumns> {
    let field = format!("{field}.table");
    let file = base.join(&config.file);
    let recording_error = |e: recording::RecordingError| PipelineError::Recording {
        path: source.to_owned(),
        field: field.clone(),
        source: Box::new(e),
    };
    let layout_error = |e| match e {
        TableLayoutError::FormatAndColumns => PipelineError::Unsupported {
            path: source.to_owned(),
            field: field.clone(),
            reason: UnsupportedReason::TableFormatAndColumns,
        },
        TableLayoutError::Recording(e) => recording_error(e),
    };
    let layout = config.piga_format().map_err(layout_error)?;
    let format = config.reader_format().map_err(layout_error)?;
    let read = load.read_table(&file, &format).map_err(recording_error)?;
    let digest = read.digest.clone();
    let t = recording::PigaTable::from_table(read.value, &layout).map_err(recording_error)?;
    let lines: Vec<usize> = (0..t.len()).map(|i| t.line_of_row(i)).collect();
    let (rates, outputs, sigma) = (t.rate_deg_s, t.output_rad_s, t.sigma_rad_s);
    let rate_name = layout.rate.column.trim().to_owned();
    let output_name = layout.output.column.trim().to_owned();
    let sigma_name = layout.sigma.as_ref().map(|c| c.column.trim().to_owned());
    let bad =
        |i: usize, column: &str, value: f64, reason: InvalidReason| PipelineError::TableValue {
            path: source.to_owned(),
            field: field.clone(),
            file: file.clone(),
            line: lines[i],
            column: column.to_owned(),
            value,
            reason,
        };
    if let Some(i) = rates.iter().position(|r| !(r.is_finite() && *r > 0.0)) {
        return Err(bad(i, &rate_name, rates[i], InvalidReason::RateNotPositive));
    }
    if let Some(i) = outputs.iter().position(|y| !y.is_finite()) {
        return Err(bad(i, &output_name, outputs[i], InvalidReason::NotFinite));
    }
    if let (Some(name), Some(sigma)) = (&sigma_name, &sigma)
        && let Some(i) = sigma.iter().position(|s| !(s.is_finite() && *s > 0.0))
    {
        return Err(bad(i, name, sigma[i], InvalidReason::SigmaNotPositive));
    }
    Ok((file, rates, outputs, sigma, digest))
}
