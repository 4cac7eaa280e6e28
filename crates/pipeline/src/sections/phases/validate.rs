//! The phases' validation: each phase's numbers checked in the file's order, its
//! recordings loaded through the data source.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use harmonics::FitConfig;
use identify::RadiusModel;
use rayon::prelude::*;
use recording::{FileDigest, Recording};

use crate::config::{
    FitSettings, HarmonicPoint, PhaseConfig, Points, RadiusModelName, RadiusPoint, Weighting,
};
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, DataSource, InputFile, InputRole, PhaseNames, rates_of};
use crate::results::{AngleZero, FitWeighting};

/// The validated phases and the radius-error model they are fitted by.
#[derive(Debug, Clone)]
pub(crate) struct Phases {
    /// The model of the study (`radius_model`).
    pub(crate) model: RadiusModel,
    pub(crate) list: Vec<Phase>,
}

/// One validated phase.
#[derive(Debug, Clone)]
pub(crate) struct Phase {
    /// The phase's name.
    pub(crate) name: String,
    /// `phases[i]`: the section named in errors.
    pub(crate) key: String,
    pub(crate) weighting: FitWeighting,
    pub(crate) data: PhaseData,
}

/// What a validated phase holds.
#[derive(Debug, Clone)]
pub(crate) enum PhaseData {
    FirstHarmonic(Vec<HarmonicPoint>),
    RadiusError(Vec<RadiusPoint>),
    Recordings(RecordingPhase),
    RadiusChange {
        from_rate_deg_s: f64,
        to_rate_deg_s: f64,
        change_um: f64,
    },
}

/// A phase given as recordings, loaded.
#[derive(Debug, Clone)]
pub(crate) struct RecordingPhase {
    pub(crate) fit: FitConfig,
    pub(crate) files: Vec<LoadedRecording>,
}

/// One recording of a phase, in memory.
#[derive(Debug, Clone)]
pub(crate) struct LoadedRecording {
    pub(crate) rate_deg_s: f64,
    /// Where it came from, as resolved against the configuration's folder.
    pub(crate) file: PathBuf,
    pub(crate) recording: Recording,
    /// The file's size and SHA-256 as read, when the data source keeps them.
    pub(crate) digest: Option<FileDigest>,
}

/// The phases of a study checked, before their recordings are loaded: the names other
/// sections refer to, and each phase's validated numbers.
pub(crate) struct Checked<'a> {
    pub(crate) names: HashMap<&'a str, usize>,
    model: RadiusModel,
    phases: Vec<(FitWeighting, CheckedData)>,
}

/// Checks every phase of the `phases` section (`configs`, fitted by the study's
/// `radius_model`) in the file's order: a valid and unique name, valid numbers, enough
/// points for the model.
pub(crate) fn check<'a>(
    check: &Check<'_>,
    model: RadiusModelName,
    configs: &'a [PhaseConfig],
) -> Result<Checked<'a>> {
    let model = radius_model(model);
    if configs.is_empty() {
        return Err(PipelineError::EmptyList {
            path: check.path.to_owned(),
            field: "phases".to_owned(),
        });
    }
    let mut names: HashMap<&str, usize> = HashMap::with_capacity(configs.len());
    let mut phases = Vec::with_capacity(configs.len());
    for (i, phase) in configs.iter().enumerate() {
        let key = format!("phases[{i}]");
        phase_name(check, &key, &phase.name)?;
        if let Some(j) = names.insert(&phase.name, i) {
            return Err(PipelineError::DuplicateName {
                path: check.path.to_owned(),
                field: format!("{key}.name"),
                first: format!("phases[{j}].name"),
                name: phase.name.clone(),
            });
        }
        phases.push(self::phase(check, &key, phase, model)?);
    }
    Ok(Checked {
        names,
        model,
        phases,
    })
}

impl Checked<'_> {
    /// Loads the recordings of every phase (through `load`, in parallel) and assembles them.
    pub(crate) fn load(
        self,
        configs: &[PhaseConfig],
        base: &Path,
        source: &Path,
        load: &dyn DataSource,
        angle_zero: &AngleZero,
    ) -> Result<Phases> {
        Ok(Phases {
            model: self.model,
            list: load_phases(configs, self.phases, base, source, load, angle_zero)?,
        })
    }

    /// The names, with the phases `second_probe` names hold.
    pub(crate) fn names(&self, second_probe: Vec<usize>) -> PhaseNames<'_> {
        PhaseNames {
            names: self.names.clone(),
            second_probe,
        }
    }
}

impl Phases {
    /// Every recording the phases read, in the configuration's order.
    pub(crate) fn recording_files(&self) -> impl Iterator<Item = &Path> {
        self.list
            .iter()
            .flat_map(|phase| match &phase.data {
                PhaseData::Recordings(set) => set.files.as_slice(),
                _ => &[],
            })
            .map(|f| f.file.as_path())
    }

    /// Every recording the phases read, with its digest, in the configuration's order.
    pub(crate) fn input_files(&self) -> impl Iterator<Item = InputFile<'_>> {
        self.list.iter().enumerate().flat_map(|(p, phase)| {
            let files = match &phase.data {
                PhaseData::Recordings(set) => set.files.as_slice(),
                _ => &[],
            };
            files.iter().enumerate().map(move |(i, f)| InputFile {
                path: &f.file,
                role: InputRole::ProbeRecording,
                field: format!("phases[{p}].points.files[{i}]"),
                digest: f.digest.as_ref(),
            })
        })
    }

    /// Whether a recording of the phases measures its angle (an encoder or an index pulse),
    /// which the angle zero then moves.
    pub(crate) fn measure_angles(&self) -> bool {
        self.list.iter().any(|phase| match &phase.data {
            PhaseData::Recordings(set) => set.files.iter().any(|f| f.recording.angle_rad.is_some()),
            _ => false,
        })
    }

    /// Number of recordings to analyse.
    pub(crate) fn recordings(&self) -> usize {
        self.list
            .iter()
            .map(|phase| match &phase.data {
                PhaseData::Recordings(set) => set.files.len(),
                _ => 0,
            })
            .sum()
    }
}

/// The solver's model from the file's name of it.
const fn radius_model(name: RadiusModelName) -> RadiusModel {
    match name {
        RadiusModelName::TwoTerm => RadiusModel::TwoTerm,
        RadiusModelName::ThreeTerm => RadiusModel::ThreeTerm,
    }
}

/// The library's fit settings from the file's.
fn fit_config(fit: FitSettings) -> FitConfig {
    FitConfig {
        order: fit.order,
        drift: fit.drift,
        revolutions: fit.revolutions,
        ..FitConfig::default()
    }
}

/// What makes two listed recordings one: the path, or the bytes' SHA-256.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum SameKey {
    Path(std::path::PathBuf),
    Bytes(String),
}

/// A phase whose numbers are valid, before its recordings are loaded.
enum CheckedData {
    Ready(PhaseData),
    Recordings { fit: FitConfig },
}

/// Loads the recordings of every phase in parallel and assembles the phases; every loading
/// error is reported, in the configuration's order. Each measured angle is taken from the
/// angle zero (`lever.angle_zero_deg`) before anything is fitted.
fn load_phases(
    configs: &[PhaseConfig],
    checked: Vec<(FitWeighting, CheckedData)>,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
    angle_zero: &AngleZero,
) -> Result<Vec<Phase>> {
    let angle_zero_rad = angle_zero.angle_zero_deg.to_radians();
    // (phase index, file index, rate, resolved path, format)
    let mut jobs = Vec::new();
    for (p, config) in configs.iter().enumerate() {
        if let Points::Recordings(set) = &config.points {
            for (i, point) in set.files.iter().enumerate() {
                jobs.push((p, i, point.rate_deg_s, base.join(&point.file), &set.format));
            }
        }
    }
    let loaded: Vec<_> = jobs
        .par_iter()
        .map(|(_, _, _, file, format)| {
            let _span = tracing::info_span!("load", file = %file.display()).entered();
            load.read_recording(file, format).map(|mut read| {
                read.value.shift_angle_zero(angle_zero_rad);
                read
            })
        })
        .collect();
    let mut errors = Vec::new();
    let mut files: Vec<Vec<LoadedRecording>> = vec![Vec::new(); configs.len()];
    // The first file of each phase by its path and by its bytes: one recording at two rates
    // is refused here, at `check`, not only when its analysis finds the rate wrong.
    let mut seen: HashMap<(usize, SameKey), usize> = HashMap::new();
    for ((p, i, rate_deg_s, file, _), result) in jobs.iter().zip(loaded) {
        let field = format!("phases[{p}].points.files[{i}]");
        let read = match result {
            Ok(read) => read,
            Err(error) => {
                errors.push(PipelineError::Recording {
                    path: source.to_owned(),
                    field,
                    source: Box::new(error),
                });
                continue;
            }
        };
        let keys = [
            Some(SameKey::Path(file.clone())),
            read.digest
                .as_ref()
                .map(|d| SameKey::Bytes(d.sha256.clone())),
        ];
        if let Some((j, same_bytes)) = keys.into_iter().flatten().find_map(|key| {
            let bytes = matches!(key, SameKey::Bytes(_));
            seen.get(&(*p, key.clone()))
                .map(|&j| (j, bytes))
                .or_else(|| {
                    seen.insert((*p, key), *i);
                    None
                })
        }) {
            errors.push(PipelineError::SameRecording {
                path: source.to_owned(),
                field,
                first: format!("phases[{p}].points.files[{j}]"),
                file: file.clone(),
                same_bytes,
            });
            continue;
        }
        // What the analysis checks first, checked at loading (so by `check` too): an encoder
        // or index pulse whose mean rate is not the declared one.
        if let Err(error) =
            recording::check_declared_rate(&read.value, units::deg_s_to_rad_s(*rate_deg_s))
        {
            errors.push(PipelineError::Recording {
                path: source.to_owned(),
                field,
                source: Box::new(error),
            });
            continue;
        }
        files[*p].push(LoadedRecording {
            rate_deg_s: *rate_deg_s,
            file: file.clone(),
            recording: read.value,
            digest: read.digest,
        });
    }
    PipelineError::from_list(errors)?;
    Ok(configs
        .iter()
        .zip(checked)
        .zip(files)
        .enumerate()
        .map(|(p, ((config, (weighting, checked)), files))| Phase {
            name: config.name.clone(),
            key: format!("phases[{p}]"),
            weighting,
            data: match checked {
                CheckedData::Ready(data) => data,
                CheckedData::Recordings { fit } => {
                    PhaseData::Recordings(RecordingPhase { fit, files })
                }
            },
        })
        .collect())
}

/// A phase name: non-empty letters, digits, `_` and `-` (it names output files).
fn phase_name(check: &Check<'_>, key: &str, name: &str) -> Result<()> {
    let valid = !name.is_empty()
        && name.len() <= 64
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
    if valid {
        Ok(())
    } else {
        Err(PipelineError::InvalidName {
            path: check.path.to_owned(),
            field: format!("{key}.name"),
            name: name.to_owned(),
        })
    }
}

fn phase(
    check: &Check<'_>,
    section: &str,
    phase: &PhaseConfig,
    model: RadiusModel,
) -> Result<(FitWeighting, CheckedData)> {
    let list = format!("{section}.points");
    let every_sigma = match &phase.points {
        Points::Recordings(_) => true,
        Points::FirstHarmonic(points) => points.iter().all(|p| p.sigma_um.is_some()),
        Points::RadiusError(_) | Points::RadiusChange { .. } => false,
    };
    let weighting = match phase.weighting {
        Weighting::Unweighted => FitWeighting::Unweighted,
        Weighting::InverseVariance => FitWeighting::InverseVariance,
    };
    if weighting == FitWeighting::InverseVariance && !every_sigma {
        return Err(PipelineError::Unsupported {
            path: check.path.to_owned(),
            field: format!("{section}.weighting"),
            reason: UnsupportedReason::WeightingNeedsRecordings,
        });
    }
    let (rates, checked): (Vec<f64>, CheckedData) = match &phase.points {
        Points::FirstHarmonic(points) => {
            for (i, p) in points.iter().enumerate() {
                check.rate(format!("{list}[{i}].rate_deg_s"), p.rate_deg_s)?;
                check.finite(format!("{list}[{i}].dc1_um"), p.dc1_um)?;
                check.finite(format!("{list}[{i}].ds1_um"), p.ds1_um)?;
                if let Some(sigma) = p.sigma_um {
                    check.positive(&format!("{list}[{i}].sigma_um"), sigma)?;
                }
            }
            check.unique_rates(&list, &rates_of(points, |p| p.rate_deg_s))?;
            (
                rates_of(points, |p| p.rate_deg_s),
                CheckedData::Ready(PhaseData::FirstHarmonic(points.clone())),
            )
        }
        Points::RadiusError(points) => {
            for (i, p) in points.iter().enumerate() {
                check.rate(format!("{list}[{i}].rate_deg_s"), p.rate_deg_s)?;
                check.finite(format!("{list}[{i}].radius_error_um"), p.radius_error_um)?;
            }
            check.unique_rates(&list, &rates_of(points, |p| p.rate_deg_s))?;
            (
                rates_of(points, |p| p.rate_deg_s),
                CheckedData::Ready(PhaseData::RadiusError(points.clone())),
            )
        }
        Points::Recordings(set) => {
            if set.files.is_empty() {
                return Err(PipelineError::EmptyList {
                    path: check.path.to_owned(),
                    field: format!("{list}.files"),
                });
            }
            let fit = fit_config(set.fit);
            fit.validate().map_err(|source| PipelineError::Harmonics {
                path: check.path.to_owned(),
                field: format!("{list}.fit"),
                source,
            })?;
            for (i, p) in set.files.iter().enumerate() {
                check.rate(format!("{list}.files[{i}].rate_deg_s"), p.rate_deg_s)?;
            }
            let rates = rates_of(&set.files, |p| p.rate_deg_s);
            check.unique_rates(&format!("{list}.files"), &rates)?;
            (rates, CheckedData::Recordings { fit })
        }
        Points::RadiusChange {
            from_rate_deg_s,
            to_rate_deg_s,
            change_um,
        } => {
            check.rate(format!("{list}.from_rate_deg_s"), *from_rate_deg_s)?;
            check.rate(format!("{list}.to_rate_deg_s"), *to_rate_deg_s)?;
            check.finite(format!("{list}.change_um"), *change_um)?;
            if from_rate_deg_s == to_rate_deg_s {
                return Err(PipelineError::DuplicateRate {
                    path: check.path.to_owned(),
                    field: format!("{list}.to_rate_deg_s"),
                    first: format!("{list}.from_rate_deg_s"),
                    rate_deg_s: *to_rate_deg_s,
                });
            }
            let data = PhaseData::RadiusChange {
                from_rate_deg_s: *from_rate_deg_s,
                to_rate_deg_s: *to_rate_deg_s,
                change_um: *change_um,
            };
            return Ok((FitWeighting::Unweighted, CheckedData::Ready(data)));
        }
    };
    // One point more than the unknowns, so that the fit has a standard error.
    let need = model.unknowns() + 1;
    if rates.len() < need {
        return Err(PipelineError::TooFewPoints {
            path: check.path.to_owned(),
            field: list,
            got: rates.len(),
            need,
            model: match model {
                RadiusModel::TwoTerm => crate::results::RadiusModel::TwoTerm,
                RadiusModel::ThreeTerm => crate::results::RadiusModel::ThreeTerm,
            }
            .formula(),
        });
    }
    Ok((weighting, checked))
}
