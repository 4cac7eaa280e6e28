//! The validated inputs of a study: the one place where a configuration is checked.
//!
//! [`Inputs::new`] takes the file's data-transfer types ([`StudyConfig`]) and the recordings
//! they name (through a loader the caller supplies, so a study can run on recordings held in
//! memory) and returns inputs whose fields are private and valid by construction ("parse,
//! don't validate"); [`crate::run`] computes on them without checking them again.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use accel_model::PigaCoefficients;
use harmonics::{FitConfig, LeverGeometry, ProbeDirection};
use identify::RadiusModel;
use rayon::prelude::*;
use recording::{
    PigaRecording, PigaRecordingFormat, Recording, RecordingError, RecordingFormat, Table,
    TableColumn, TableFormat,
};

use crate::calibration::{
    CalibrationInputs, K1Choice, LoadedPigaRecording, PigaData, PigaTableRows, TypeB,
};
use crate::config::{
    CalibrationConfig, FitSettings, HarmonicPoint, K1Config, LeverConfig, MechanismConfig,
    PhaseConfig, PigaRecordingSet, PigaTableConfig, Points, ProbeDirectionName, RadiusModelName,
    RadiusPoint, StudyConfig, TrialsConfig, UncertaintyConfig, Weighting,
};
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};

/// The caller's access to the data files a study names: files at the edge
/// ([`crate::load_study`]), or data held in memory (a test, another program).
pub trait DataSource: Sync {
    /// The probe recording at `path`, read in `format`.
    fn recording(
        &self,
        path: &Path,
        format: &RecordingFormat,
    ) -> std::result::Result<Recording, RecordingError>;

    /// The table at `path`, read in `format`.
    fn table(
        &self,
        path: &Path,
        format: &TableFormat,
    ) -> std::result::Result<Table, RecordingError>;

    /// The raw PIGA output recording at `path`, read in `format`: by default, the file read
    /// as a probe recording ([`DataSource::recording`]) with the output angle in the gap's
    /// place, converted and unwrapped.
    fn piga_recording(
        &self,
        path: &Path,
        format: &PigaRecordingFormat,
    ) -> std::result::Result<PigaRecording, RecordingError> {
        let samples = self.recording(path, &format.probe_format()?)?;
        PigaRecording::from_recording(samples, format.output.unit)
    }
}

/// Least number of Monte Carlo trials for a 95 % coverage interval (JCGM 101 §7.2: 100/(1 − p)).
const MIN_TRIALS: u64 = 2000;

/// Least number of distinct mechanism calibration rates: six unknowns plus one degree of
/// freedom.
pub(crate) const MIN_MECHANISM_RATES: usize = identify::MIN_DISTINCT_RATES + 1;

/// The validated inputs of a study.
#[derive(Debug, Clone)]
pub struct Inputs {
    pub(crate) source: PathBuf,
    pub(crate) name: String,
    pub(crate) radius_m: f64,
    pub(crate) g_m_s2: f64,
    pub(crate) k1_rad_s_g: f64,
    pub(crate) lever: LeverGeometry,
    pub(crate) lever_ratio: f64,
    pub(crate) radius_model: RadiusModelName,
    pub(crate) phases: Vec<Phase>,
    pub(crate) mechanism: Option<Mechanism>,
    pub(crate) calibration: Option<CalibrationInputs>,
    /// Type B uncertainties (all zero when the study has no `uncertainty` section).
    pub(crate) type_b: TypeB,
    /// Whether the study has an `uncertainty` section.
    pub(crate) type_b_given: bool,
    /// The balance section, validated.
    pub(crate) balance: Option<crate::balancing::BalanceInputs>,
    /// The counterweight section, validated.
    pub(crate) counterweight: Option<crate::balancing::CounterweightInputs>,
}

/// One validated phase.
#[derive(Debug, Clone)]
pub(crate) struct Phase {
    /// The phase's name.
    pub(crate) name: String,
    /// `phases[i]`: the section named in errors.
    pub(crate) key: String,
    pub(crate) weighting: Weighting,
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
}

/// The validated mechanism section.
#[derive(Debug, Clone)]
pub(crate) struct Mechanism {
    /// Indices of the phases simulated, in the order given.
    pub(crate) phases: Vec<usize>,
    pub(crate) piga: PigaCoefficients,
    pub(crate) latitude_deg: f64,
    pub(crate) earth_rate_rad_s: f64,
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) output_noise_rad_s: f64,
    pub(crate) seed: u64,
}

impl Inputs {
    /// The radius and g that turn a rate into the nominal input `a = R·ω²/g`.
    pub(crate) const fn geometry(&self) -> identify::Geometry {
        identify::Geometry {
            radius_m: self.radius_m,
            g_m_s2: self.g_m_s2,
        }
    }

    /// Validates a configuration read from `source` (named in every error; relative recording
    /// paths are resolved against its folder) and loads the recordings it names through
    /// `load`, in parallel.
    ///
    /// # Errors
    /// The first invalid field in the file's order; for recordings, every recording that could
    /// not be loaded, in the configuration's order ([`PipelineError::Several`] when more than
    /// one).
    pub fn new(config: StudyConfig, source: &Path, load: &dyn DataSource) -> Result<Self> {
        let check = Check { path: source };
        check.positive("radius_m", config.radius_m)?;
        check.positive("g_m_s2", config.g_m_s2)?;
        check.positive("k1_rad_s_g", config.k1_rad_s_g)?;
        let lever = lever_geometry(config.lever);
        let lever_ratio = lever
            .lever_ratio()
            .map_err(|source_error| PipelineError::Harmonics {
                path: source.to_owned(),
                field: "lever".to_owned(),
                source: source_error,
            })?;
        let model = config.radius_model;
        if config.phases.is_empty() {
            return Err(PipelineError::EmptyList {
                path: source.to_owned(),
                field: "phases".to_owned(),
            });
        }
        let mut names: HashMap<&str, usize> = HashMap::with_capacity(config.phases.len());
        let mut checked = Vec::with_capacity(config.phases.len());
        for (i, phase) in config.phases.iter().enumerate() {
            let key = format!("phases[{i}]");
            check.phase_name(&key, &phase.name)?;
            if let Some(j) = names.insert(&phase.name, i) {
                return Err(PipelineError::DuplicateName {
                    path: source.to_owned(),
                    field: format!("{key}.name"),
                    first: format!("phases[{j}].name"),
                    name: phase.name.clone(),
                });
            }
            checked.push(check.phase(&key, phase, model)?);
        }
        // Phases holding a second probe's data: read with the first probe's lever, their C_r
        // is not the PIGA plane's (docs/BALANCING.md).
        let second_probe_phases: Vec<usize> = config
            .balance
            .iter()
            .flat_map(|b| b.second_probe.iter())
            .flat_map(|q| q.phases.values())
            .filter_map(|name| names.get(name.as_str()).copied())
            .collect();
        let mechanism = config
            .mechanism
            .as_ref()
            .map(|m| check.mechanism(m, config.k1_rad_s_g, &names, &second_probe_phases))
            .transpose()?;
        let base = source.parent().unwrap_or_else(|| Path::new("."));
        let type_b = config
            .uncertainty
            .as_ref()
            .map(|u| check.type_b(u))
            .transpose()?;
        let calibration_config = config
            .calibration
            .as_ref()
            .map(|c| check.calibration(c, &names, &second_probe_phases))
            .transpose()?;
        let balance = config
            .balance
            .as_ref()
            .map(|b| check.balance(b, &config.phases, &names, config.lever.probe_to_piga_mm))
            .transpose()?;
        let counterweight = config
            .counterweight
            .as_ref()
            .map(|c| check.counterweight(c, &config.phases, &names))
            .transpose()?;
        let phases = load_phases(&config.phases, checked, base, source, load)?;
        let calibration = match (config.calibration.as_ref(), calibration_config) {
            (Some(c), Some((phase, k1))) => {
                Some(load_calibration(c, phase, k1, base, source, load)?)
            }
            _ => None,
        };
        Ok(Self {
            source: source.to_owned(),
            name: config.name,
            radius_m: config.radius_m,
            g_m_s2: config.g_m_s2,
            k1_rad_s_g: config.k1_rad_s_g,
            lever,
            lever_ratio,
            radius_model: model,
            phases,
            mechanism,
            calibration,
            type_b_given: type_b.is_some(),
            type_b: type_b.unwrap_or_default(),
            balance,
            counterweight,
        })
    }

    /// The study's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The configuration file the inputs came from.
    pub fn source(&self) -> &Path {
        &self.source
    }

    /// Every recording the study read, in the configuration's order.
    pub fn recording_files(&self) -> impl Iterator<Item = &Path> {
        self.phases
            .iter()
            .flat_map(|phase| match &phase.data {
                PhaseData::Recordings(set) => set.files.as_slice(),
                _ => &[],
            })
            .map(|f| f.file.as_path())
    }
}

/// The library's lever geometry from the file's.
fn lever_geometry(lever: LeverConfig) -> LeverGeometry {
    LeverGeometry {
        pivot_to_probe_mm: lever.pivot_to_probe_mm,
        probe_to_piga_mm: lever.probe_to_piga_mm,
        probe_direction: match lever.probe_direction {
            ProbeDirectionName::AgainstO1X1 => ProbeDirection::AgainstO1X1,
            ProbeDirectionName::AlongO1X1 => ProbeDirection::AlongO1X1,
        },
    }
}

/// The solver's model from the file's name of it.
pub(crate) const fn radius_model(name: RadiusModelName) -> RadiusModel {
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

/// A phase whose numbers are valid, before its recordings are loaded.
enum Checked {
    Ready(PhaseData),
    Recordings { fit: FitConfig },
}

/// Loads the recordings of every phase in parallel and assembles the phases; every loading
/// error is reported, in the configuration's order.
fn load_phases(
    configs: &[PhaseConfig],
    checked: Vec<(Weighting, Checked)>,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<Vec<Phase>> {
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
            load.recording(file, format)
        })
        .collect();
    let mut errors = Vec::new();
    let mut files: Vec<Vec<LoadedRecording>> = vec![Vec::new(); configs.len()];
    for ((p, i, rate_deg_s, file, _), result) in jobs.iter().zip(loaded) {
        match result {
            Ok(recording) => files[*p].push(LoadedRecording {
                rate_deg_s: *rate_deg_s,
                file: file.clone(),
                recording,
            }),
            Err(error) => errors.push(PipelineError::Recording {
                path: source.to_owned(),
                field: format!("phases[{p}].points.files[{i}]"),
                source: Box::new(error),
            }),
        }
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
                Checked::Ready(data) => data,
                Checked::Recordings { fit } => PhaseData::Recordings(RecordingPhase { fit, files }),
            },
        })
        .collect())
}

/// Reads the calibration's data — a PIGA table (rates > 0, σ > 0 when given) or raw output
/// recordings (read in parallel) — and checks that it has at least [`MIN_MECHANISM_RATES`]
/// distinct rates (six unknowns and a residual degree of freedom).
fn load_calibration(
    config: &CalibrationConfig,
    phase: usize,
    k1: K1Choice,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<CalibrationInputs> {
    let (data, rates, field, file) = match (&config.table, &config.recordings) {
        (Some(table), None) => {
            let rows = load_piga_table(table, base, source, load)?;
            let rates = rows.rates_deg_s.clone();
            let file = rows.file.clone();
            (PigaData::Table(rows), rates, "calibration.table", file)
        }
        (None, Some(set)) => {
            let files = load_piga_recordings(set, base, source, load)?;
            let rates = files.iter().map(|f| f.rate_deg_s).collect();
            (
                PigaData::Recordings {
                    order: set.order,
                    files,
                },
                rates,
                "calibration.recordings.files",
                PathBuf::from("the recordings"),
            )
        }
        _ => {
            return Err(PipelineError::Unsupported {
                path: source.to_owned(),
                field: "calibration".to_owned(),
                reason: UnsupportedReason::CalibrationNeedsOneSource,
            });
        }
    };
    let mut distinct: Vec<u64> = rates.iter().map(|r: &f64| r.to_bits()).collect();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() < MIN_MECHANISM_RATES {
        return Err(PipelineError::TooFewRates {
            path: source.to_owned(),
            field: field.to_owned(),
            file,
            distinct: distinct.len(),
            need: MIN_MECHANISM_RATES,
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
    })
}

/// Reads a PIGA table: rate and output columns, the σ and label columns when named.
fn load_piga_table(
    config: &PigaTableConfig,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<PigaTableRows> {
    let file = base.join(&config.file);
    let mut columns = vec![
        TableColumn::required(config.rate_column.clone()),
        TableColumn::required(config.output_column.clone()),
    ];
    if let Some(sigma) = &config.sigma_column {
        columns.push(TableColumn::required(sigma.clone()));
    }
    let format = TableFormat {
        delimiter: config.delimiter,
        // A blank delimiter keeps its meaning here: runs of blanks separate fields.
        whitespace: matches!(config.delimiter, ' ' | '\t'),
        label: config.label_column.clone(),
        ..TableFormat::new(columns, true)
    };
    let table = load
        .table(&file, &format)
        .map_err(|e| PipelineError::Recording {
            path: source.to_owned(),
            field: "calibration.table".to_owned(),
            source: Box::new(e),
        })?;
    let column = |name: &str| table.column(name).unwrap_or(&[]).to_vec();
    let rates = column(&config.rate_column);
    let outputs = column(&config.output_column);
    let sigma = config.sigma_column.as_deref().map(column);
    let lines: Vec<usize> = (0..rates.len()).map(|i| table.line_of_row(i)).collect();
    let bad =
        |i: usize, column: &str, value: f64, reason: InvalidReason| PipelineError::TableValue {
            path: source.to_owned(),
            field: "calibration.table".to_owned(),
            file: file.clone(),
            line: lines[i],
            column: column.to_owned(),
            value,
            reason,
        };
    if let Some(i) = rates.iter().position(|r| !(r.is_finite() && *r > 0.0)) {
        return Err(bad(
            i,
            &config.rate_column,
            rates[i],
            InvalidReason::RateNotPositive,
        ));
    }
    if let (Some(name), Some(sigma)) = (&config.sigma_column, &sigma)
        && let Some(i) = sigma.iter().position(|s| !(s.is_finite() && *s > 0.0))
    {
        return Err(bad(i, name, sigma[i], InvalidReason::SigmaNotPositive));
    }
    Ok(PigaTableRows {
        file: file.clone(),
        rates_deg_s: rates,
        outputs_rad_s: outputs,
        sigma_rad_s: sigma,
        labels: table.labels().map(<[String]>::to_vec),
        lines,
    })
}

/// Reads raw PIGA output recordings in parallel, after checking their rates and the
/// harmonic order.
fn load_piga_recordings(
    set: &PigaRecordingSet,
    base: &Path,
    source: &Path,
    load: &dyn DataSource,
) -> Result<Vec<LoadedPigaRecording>> {
    let check = Check { path: source };
    if !(1..=harmonics::MAX_ORDER).contains(&set.order) {
        return Err(check.invalid(
            "calibration.recordings.order".to_owned(),
            set.order as f64,
            InvalidReason::HarmonicOrder,
        ));
    }
    for (i, point) in set.files.iter().enumerate() {
        if !(point.rate_deg_s.is_finite() && point.rate_deg_s > 0.0) {
            return Err(check.invalid(
                format!("calibration.recordings.files[{i}].rate_deg_s"),
                point.rate_deg_s,
                InvalidReason::RateNotPositive,
            ));
        }
    }
    let loaded: Vec<_> = set
        .files
        .par_iter()
        .map(|point| {
            let file = base.join(&point.file);
            let _span = tracing::info_span!("load", file = %file.display()).entered();
            let result = load.piga_recording(&file, &set.format);
            (point.rate_deg_s, file, result)
        })
        .collect();
    let mut errors = Vec::new();
    let mut files = Vec::with_capacity(loaded.len());
    for (i, (rate_deg_s, file, result)) in loaded.into_iter().enumerate() {
        match result {
            Ok(recording) => files.push(LoadedPigaRecording {
                rate_deg_s,
                file,
                recording,
            }),
            Err(error) => errors.push(PipelineError::Recording {
                path: source.to_owned(),
                field: format!("calibration.recordings.files[{i}]"),
                source: Box::new(error),
            }),
        }
    }
    PipelineError::from_list(errors)?;
    Ok(files)
}

/// Field checks that name the configuration file.
struct Check<'a> {
    path: &'a Path,
}

impl Check<'_> {
    fn invalid(&self, field: String, value: f64, reason: InvalidReason) -> PipelineError {
        PipelineError::InvalidField {
            path: self.path.to_owned(),
            field,
            value,
            reason,
        }
    }

    fn positive(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field.to_owned(), value, InvalidReason::NotPositive))
        }
    }

    fn finite(&self, field: String, value: f64) -> Result<()> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(self.invalid(field, value, InvalidReason::NotFinite))
        }
    }

    fn rate(&self, field: String, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field, value, InvalidReason::RateNotPositive))
        }
    }

    /// Refuses a rate that appears twice, naming both places (linear time).
    fn unique_rates(&self, items: &str, rates: &[f64]) -> Result<()> {
        let mut seen: HashMap<u64, usize> = HashMap::with_capacity(rates.len());
        for (i, r) in rates.iter().enumerate() {
            // Rates are finite and > 0 here, so equal values have equal bits.
            if let Some(j) = seen.insert(r.to_bits(), i) {
                return Err(PipelineError::DuplicateRate {
                    path: self.path.to_owned(),
                    field: format!("{items}[{i}].rate_deg_s"),
                    first: format!("{items}[{j}].rate_deg_s"),
                    rate_deg_s: *r,
                });
            }
        }
        Ok(())
    }

    /// A phase name: non-empty letters, digits, `_` and `-` (it names output files).
    fn phase_name(&self, key: &str, name: &str) -> Result<()> {
        let valid = !name.is_empty()
            && name.len() <= 64
            && name
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
        if valid {
            Ok(())
        } else {
            Err(PipelineError::InvalidName {
                path: self.path.to_owned(),
                field: format!("{key}.name"),
                name: name.to_owned(),
            })
        }
    }

    fn phase(
        &self,
        section: &str,
        phase: &PhaseConfig,
        model: RadiusModelName,
    ) -> Result<(Weighting, Checked)> {
        let list = format!("{section}.points");
        let every_sigma = match &phase.points {
            Points::Recordings(_) => true,
            Points::FirstHarmonic(points) => points.iter().all(|p| p.sigma_um.is_some()),
            Points::RadiusError(_) | Points::RadiusChange { .. } => false,
        };
        if phase.weighting == Weighting::InverseVariance && !every_sigma {
            return Err(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: format!("{section}.weighting"),
                reason: UnsupportedReason::WeightingNeedsRecordings,
            });
        }
        let (rates, checked): (Vec<f64>, Checked) = match &phase.points {
            Points::FirstHarmonic(points) => {
                for (i, p) in points.iter().enumerate() {
                    self.rate(format!("{list}[{i}].rate_deg_s"), p.rate_deg_s)?;
                    self.finite(format!("{list}[{i}].dc1_um"), p.dc1_um)?;
                    self.finite(format!("{list}[{i}].ds1_um"), p.ds1_um)?;
                    if let Some(sigma) = p.sigma_um {
                        self.positive(&format!("{list}[{i}].sigma_um"), sigma)?;
                    }
                }
                self.unique_rates(&list, &rates_of(points, |p| p.rate_deg_s))?;
                (
                    rates_of(points, |p| p.rate_deg_s),
                    Checked::Ready(PhaseData::FirstHarmonic(points.clone())),
                )
            }
            Points::RadiusError(points) => {
                for (i, p) in points.iter().enumerate() {
                    self.rate(format!("{list}[{i}].rate_deg_s"), p.rate_deg_s)?;
                    self.finite(format!("{list}[{i}].radius_error_um"), p.radius_error_um)?;
                }
                self.unique_rates(&list, &rates_of(points, |p| p.rate_deg_s))?;
                (
                    rates_of(points, |p| p.rate_deg_s),
                    Checked::Ready(PhaseData::RadiusError(points.clone())),
                )
            }
            Points::Recordings(set) => {
                if set.files.is_empty() {
                    return Err(PipelineError::EmptyList {
                        path: self.path.to_owned(),
                        field: format!("{list}.files"),
                    });
                }
                let fit = fit_config(set.fit);
                fit.validate().map_err(|source| PipelineError::Harmonics {
                    path: self.path.to_owned(),
                    field: format!("{list}.fit"),
                    source,
                })?;
                for (i, p) in set.files.iter().enumerate() {
                    self.rate(format!("{list}.files[{i}].rate_deg_s"), p.rate_deg_s)?;
                }
                let rates = rates_of(&set.files, |p| p.rate_deg_s);
                self.unique_rates(&format!("{list}.files"), &rates)?;
                (rates, Checked::Recordings { fit })
            }
            Points::RadiusChange {
                from_rate_deg_s,
                to_rate_deg_s,
                change_um,
            } => {
                self.rate(format!("{list}.from_rate_deg_s"), *from_rate_deg_s)?;
                self.rate(format!("{list}.to_rate_deg_s"), *to_rate_deg_s)?;
                self.finite(format!("{list}.change_um"), *change_um)?;
                if from_rate_deg_s == to_rate_deg_s {
                    return Err(PipelineError::DuplicateRate {
                        path: self.path.to_owned(),
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
                return Ok((Weighting::Unweighted, Checked::Ready(data)));
            }
        };
        // One point more than the unknowns, so that the fit has a standard error.
        let need = radius_model(model).unknowns() + 1;
        if rates.len() < need {
            return Err(PipelineError::TooFewPoints {
                path: self.path.to_owned(),
                field: list,
                got: rates.len(),
                need,
                model: crate::config::model_name(model),
            });
        }
        Ok((phase.weighting, checked))
    }

    /// The calibration's references and numbers: the phase it compensates with, and k1.
    fn calibration(
        &self,
        c: &CalibrationConfig,
        names: &HashMap<&str, usize>,
        second_probe_phases: &[usize],
    ) -> Result<(usize, K1Choice)> {
        let Some(&phase) = names.get(c.compensate_with.as_str()) else {
            return Err(PipelineError::UnknownPhase {
                path: self.path.to_owned(),
                field: "calibration.compensate_with".to_owned(),
                name: c.compensate_with.clone(),
                known: sorted_names(names),
            });
        };
        if second_probe_phases.contains(&phase) {
            return Err(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: "calibration.compensate_with".to_owned(),
                reason: UnsupportedReason::SecondProbeData,
            });
        }
        if let TrialsConfig::Fixed(n) = c.trials
            && n < MIN_TRIALS
        {
            return Err(self.invalid(
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
                self.positive("calibration.k1.k1_rad_s_g", k1_rad_s_g)?;
                self.non_negative("calibration.k1.u_rad_s_g", u_rad_s_g)?;
                K1Choice::Given {
                    k1_rad_s_g,
                    u_rad_s_g,
                }
            }
        };
        Ok((phase, k1))
    }

    /// The balance section: known phases with first harmonics and enough rates, a trial mass
    /// with its phase, positive lengths and masses.
    fn balance(
        &self,
        b: &crate::config::BalanceConfig,
        phases: &[crate::config::PhaseConfig],
        names: &HashMap<&str, usize>,
        first_probe_to_piga_mm: f64,
    ) -> Result<crate::balancing::BalanceInputs> {
        let phase = |field: &str, name: &str| -> Result<usize> {
            let Some(&i) = names.get(name) else {
                return Err(PipelineError::UnknownPhase {
                    path: self.path.to_owned(),
                    field: field.to_owned(),
                    name: name.to_owned(),
                    known: sorted_names(names),
                });
            };
            let count = match &phases[i].points {
                Points::FirstHarmonic(p) => p.len(),
                Points::Recordings(set) => set.files.len(),
                Points::RadiusError(_) | Points::RadiusChange { .. } => {
                    return Err(PipelineError::Unsupported {
                        path: self.path.to_owned(),
                        field: field.to_owned(),
                        reason: UnsupportedReason::BalanceNeedsFirstHarmonic,
                    });
                }
            };
            if count < balance::MIN_RATES {
                return Err(PipelineError::TooFewPoints {
                    path: self.path.to_owned(),
                    field: format!("phases[{i}].points"),
                    got: count,
                    need: balance::MIN_RATES,
                    model: "the balance advisor's static/dynamic phasor fit",
                });
            }
            Ok(i)
        };
        let initial = phase("balance.initial", &b.initial)?;
        let trial = match (&b.trial, &b.trial_mass) {
            (Some(name), Some(m)) => {
                let i = phase("balance.trial", name)?;
                self.positive("balance.trial_mass.mass_kg", m.mass_kg)?;
                self.positive("balance.trial_mass.radius_m", m.radius_m)?;
                self.finite("balance.trial_mass.azimuth_deg".to_owned(), m.azimuth_deg)?;
                if let Some(h) = m.height_m {
                    self.finite("balance.trial_mass.height_m".to_owned(), h)?;
                }
                Some((
                    i,
                    balance::TrialMass {
                        mass_kg: m.mass_kg,
                        radius_m: m.radius_m,
                        azimuth_deg: m.azimuth_deg,
                    },
                ))
            }
            (None, None) => None,
            (Some(_), None) | (None, Some(_)) => {
                return Err(PipelineError::Unsupported {
                    path: self.path.to_owned(),
                    field: if b.trial.is_some() {
                        "balance.trial_mass"
                    } else {
                        "balance.trial"
                    }
                    .to_owned(),
                    reason: UnsupportedReason::TrialNeedsTrialMass,
                });
            }
        };
        if let Some(k) = b.radial_stiffness_n_m {
            self.positive("balance.radial_stiffness_n_m", k)?;
        }
        if trial.is_none() && b.radial_stiffness_n_m.is_none() {
            return Err(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: "balance".to_owned(),
                reason: UnsupportedReason::BalanceNeedsMethod,
            });
        }
        self.positive("balance.correction_radius_m", b.correction_radius_m)?;
        for (i, &a) in b.fixed_azimuths_deg.iter().enumerate() {
            self.finite(format!("balance.fixed_azimuths_deg[{i}]"), a)?;
        }
        if let Some(m) = b.rotor_mass_kg {
            self.positive("balance.rotor_mass_kg", m)?;
        }
        let check = b
            .check
            .as_deref()
            .map(|name| phase("balance.check", name))
            .transpose()?;
        if let Some(k) = b.angular_stiffness_n_m_rad {
            self.positive("balance.angular_stiffness_n_m_rad", k)?;
        }
        let unsupported = |field: &str, reason| PipelineError::Unsupported {
            path: self.path.to_owned(),
            field: field.to_owned(),
            reason,
        };
        let two_plane = b
            .two_plane
            .as_ref()
            .map(|t| {
                if b.second_probe.is_none() {
                    return Err(unsupported(
                        "balance.two_plane",
                        UnsupportedReason::TwoPlaneNeedsSecondProbe,
                    ));
                }
                let (za, zb) = t.heights_m;
                self.finite("balance.two_plane.heights_m.0".to_owned(), za)?;
                self.finite("balance.two_plane.heights_m.1".to_owned(), zb)?;
                // A trial mass goes in its correction plane: the influence coefficients
                // hold for masses at that height only.
                for (field, mass, plane) in [
                    ("balance.trial_mass.height_m", b.trial_mass.as_ref(), za),
                    (
                        "balance.two_plane.trial_mass.height_m",
                        t.trial_mass.as_ref(),
                        zb,
                    ),
                ] {
                    if let Some(h) = mass.and_then(|m| m.height_m)
                        && h != plane
                    {
                        return Err(unsupported(field, UnsupportedReason::TrialOutOfPlane));
                    }
                }
                if za == zb {
                    return Err(unsupported(
                        "balance.two_plane.heights_m",
                        UnsupportedReason::PlanesAtOneHeight,
                    ));
                }
                let radius_b = t.radius_b_m.unwrap_or(b.correction_radius_m);
                self.positive("balance.two_plane.radius_b_m", radius_b)?;
                let trial_b = match (&t.trial, &t.trial_mass) {
                    (Some(name), Some(m)) => {
                        let i = phase("balance.two_plane.trial", name)?;
                        self.positive("balance.two_plane.trial_mass.mass_kg", m.mass_kg)?;
                        self.positive("balance.two_plane.trial_mass.radius_m", m.radius_m)?;
                        self.finite(
                            "balance.two_plane.trial_mass.azimuth_deg".to_owned(),
                            m.azimuth_deg,
                        )?;
                        Some((
                            i,
                            balance::TrialMass {
                                mass_kg: m.mass_kg,
                                radius_m: m.radius_m,
                                azimuth_deg: m.azimuth_deg,
                            },
                        ))
                    }
                    (None, None) => None,
                    (Some(_), None) | (None, Some(_)) => {
                        return Err(unsupported(
                            if t.trial.is_some() {
                                "balance.two_plane.trial_mass"
                            } else {
                                "balance.two_plane.trial"
                            },
                            UnsupportedReason::TrialNeedsTrialMass,
                        ));
                    }
                };
                let influence = trial_b.is_some() && trial.is_some();
                let stiffness =
                    b.radial_stiffness_n_m.is_some() && b.angular_stiffness_n_m_rad.is_some();
                if !influence && !stiffness {
                    return Err(unsupported(
                        "balance.two_plane",
                        UnsupportedReason::TwoPlaneNeedsMethod,
                    ));
                }
                let plane = |height_m: f64, radius_m: f64| balance::HeightPlane {
                    height_m,
                    plane: balance::CorrectionPlane {
                        radius_m,
                        fixed_azimuths_deg: b.fixed_azimuths_deg.clone(),
                    },
                };
                Ok(crate::balancing::TwoPlaneInputs {
                    planes: [plane(za, b.correction_radius_m), plane(zb, radius_b)],
                    trial: trial_b,
                })
            })
            .transpose()?;
        let second =
            b.second_probe
                .as_ref()
                .map(|q| {
                    let field = "balance.second_probe.probe_to_piga_mm";
                    self.finite(field.to_owned(), q.probe_to_piga_mm)?;
                    if q.probe_to_piga_mm == first_probe_to_piga_mm {
                        return Err(unsupported(
                            field,
                            UnsupportedReason::SecondProbeAtFirstHeight,
                        ));
                    }
                    let mut of = HashMap::new();
                    for (key, value) in &q.phases {
                        let first = phase(&format!("balance.second_probe.phases[{key:?}]"), key)?;
                        let second =
                            phase(&format!("balance.second_probe.phases[{key:?}]"), value)?;
                        of.insert(first, second);
                    }
                    let used: Vec<usize> = [Some(initial), trial.map(|t| t.0), check]
                        .into_iter()
                        .chain([two_plane.as_ref().and_then(|t| t.trial.map(|x| x.0))])
                        .flatten()
                        .collect();
                    // The second probe's data is another phase than any the first probe gives.
                    if let Some((key, _)) = q.phases.iter().find(|(_, value)| {
                        names.get(value.as_str()).is_some_and(|i| used.contains(i))
                    }) {
                        return Err(unsupported(
                            &format!("balance.second_probe.phases[{key:?}]"),
                            UnsupportedReason::SecondProbePhaseIsFirst,
                        ));
                    }
                    for i in used {
                        if !of.contains_key(&i) {
                            return Err(unsupported(
                                "balance.second_probe.phases",
                                UnsupportedReason::SecondProbeNeedsPhase,
                            ));
                        }
                    }
                    Ok(crate::balancing::SecondProbeInputs {
                        probe_to_piga_mm: q.probe_to_piga_mm,
                        probe_direction: match q.probe_direction {
                            ProbeDirectionName::AgainstO1X1 => ProbeDirection::AgainstO1X1,
                            ProbeDirectionName::AlongO1X1 => ProbeDirection::AlongO1X1,
                        },
                        phase_of: of,
                    })
                })
                .transpose()?;
        Ok(crate::balancing::BalanceInputs {
            second,
            angular_stiffness_n_m_rad: b.angular_stiffness_n_m_rad,
            two_plane,
            initial,
            trial,
            radial_stiffness_n_m: b.radial_stiffness_n_m,
            plane: balance::CorrectionPlane {
                radius_m: b.correction_radius_m,
                fixed_azimuths_deg: b.fixed_azimuths_deg.clone(),
            },
            rotor_mass_kg: b.rotor_mass_kg,
            check,
        })
    }

    /// The counterweight section: a known `radius_change` phase, a positive stiffness and
    /// radius.
    fn counterweight(
        &self,
        c: &crate::config::CounterweightConfig,
        phases: &[crate::config::PhaseConfig],
        names: &HashMap<&str, usize>,
    ) -> Result<crate::balancing::CounterweightInputs> {
        let Some(&i) = names.get(c.phase.as_str()) else {
            return Err(PipelineError::UnknownPhase {
                path: self.path.to_owned(),
                field: "counterweight.phase".to_owned(),
                name: c.phase.clone(),
                known: sorted_names(names),
            });
        };
        let Points::RadiusChange {
            from_rate_deg_s,
            to_rate_deg_s,
            change_um,
        } = phases[i].points
        else {
            return Err(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: "counterweight.phase".to_owned(),
                reason: UnsupportedReason::CounterweightNeedsRadiusChange,
            });
        };
        self.positive("counterweight.radial_stiffness_n_m", c.radial_stiffness_n_m)?;
        self.positive("counterweight.correction_radius_m", c.correction_radius_m)?;
        // The mass scales with k_r, which no measurement here gives: its provenance is part
        // of the result.
        if c.stiffness_source.trim().is_empty() {
            return Err(PipelineError::Unsupported {
                path: self.path.to_owned(),
                field: "counterweight.stiffness_source".to_owned(),
                reason: UnsupportedReason::StiffnessNeedsSource,
            });
        }
        Ok(crate::balancing::CounterweightInputs {
            phase: i,
            from_rate_deg_s,
            to_rate_deg_s,
            change_um,
            radial_stiffness_n_m: c.radial_stiffness_n_m,
            stiffness_source: c.stiffness_source.clone(),
            correction_radius_m: c.correction_radius_m,
        })
    }

    /// The Type B uncertainties: each finite and ≥ 0.
    fn type_b(&self, u: &UncertaintyConfig) -> Result<TypeB> {
        for (field, value) in [
            ("uncertainty.radius_u_m", u.radius_u_m),
            ("uncertainty.g_u_m_s2", u.g_u_m_s2),
            ("uncertainty.rate_u_relative", u.rate_u_relative),
            ("uncertainty.pivot_to_probe_u_mm", u.pivot_to_probe_u_mm),
            ("uncertainty.probe_to_piga_u_mm", u.probe_to_piga_u_mm),
            ("uncertainty.probe_gain_u_relative", u.probe_gain_u_relative),
        ] {
            self.non_negative(field, value)?;
        }
        Ok(TypeB {
            radius_u_m: u.radius_u_m,
            g_u_m_s2: u.g_u_m_s2,
            g_source: u.g_source.clone(),
            rate_u_relative: u.rate_u_relative,
            pivot_to_probe_u_mm: u.pivot_to_probe_u_mm,
            probe_to_piga_u_mm: u.probe_to_piga_u_mm,
            probe_gain_u_relative: u.probe_gain_u_relative,
        })
    }

    fn non_negative(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field.to_owned(), value, InvalidReason::Negative))
        }
    }

    fn mechanism(
        &self,
        m: &MechanismConfig,
        k1_rad_s_g: f64,
        names: &HashMap<&str, usize>,
        second_probe_phases: &[usize],
    ) -> Result<Mechanism> {
        let phases = match &m.phases {
            // Every phase of the first probe.
            None => {
                let mut all: Vec<usize> = names
                    .values()
                    .copied()
                    .filter(|p| !second_probe_phases.contains(p))
                    .collect();
                all.sort_unstable();
                all
            }
            Some(list) => {
                let mut phases = Vec::with_capacity(list.len());
                for (i, name) in list.iter().enumerate() {
                    let field = format!("mechanism.phases[{i}]");
                    let Some(&p) = names.get(name.as_str()) else {
                        return Err(PipelineError::UnknownPhase {
                            path: self.path.to_owned(),
                            field,
                            name: name.clone(),
                            known: sorted_names(names),
                        });
                    };
                    if second_probe_phases.contains(&p) {
                        return Err(PipelineError::Unsupported {
                            path: self.path.to_owned(),
                            field,
                            reason: UnsupportedReason::SecondProbeData,
                        });
                    }
                    if phases.contains(&p) {
                        return Err(PipelineError::DuplicateName {
                            path: self.path.to_owned(),
                            field,
                            first: format!(
                                "mechanism.phases[{}]",
                                phases.iter().position(|&q| q == p).unwrap_or(0)
                            ),
                            name: name.clone(),
                        });
                    }
                    phases.push(p);
                }
                phases
            }
        };
        for (field, value) in [
            ("mechanism.k0_rad_s", m.k0_rad_s),
            ("mechanism.k2_rad_s_g2", m.k2_rad_s_g2),
            ("mechanism.k3_rad_s_g3", m.k3_rad_s_g3),
        ] {
            self.finite(field.to_owned(), value)?;
        }
        if !(m.latitude_deg.is_finite() && m.latitude_deg.abs() <= 90.0) {
            return Err(self.invalid(
                "mechanism.latitude_deg".to_owned(),
                m.latitude_deg,
                InvalidReason::NotALatitude,
            ));
        }
        for (field, value) in [
            ("mechanism.earth_rate_rad_s", m.earth_rate_rad_s),
            ("mechanism.output_noise_rad_s", m.output_noise_rad_s),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(self.invalid(field.to_owned(), value, InvalidReason::Negative));
            }
        }
        for (i, &rate) in m.rates_deg_s.iter().enumerate() {
            self.rate(format!("mechanism.rates_deg_s[{i}]"), rate)?;
        }
        let mut seen: HashMap<u64, usize> = HashMap::with_capacity(m.rates_deg_s.len());
        for (i, &rate) in m.rates_deg_s.iter().enumerate() {
            if let Some(j) = seen.insert(rate.to_bits(), i) {
                return Err(PipelineError::DuplicateRate {
                    path: self.path.to_owned(),
                    field: format!("mechanism.rates_deg_s[{i}]"),
                    first: format!("mechanism.rates_deg_s[{j}]"),
                    rate_deg_s: rate,
                });
            }
        }
        if m.rates_deg_s.len() < MIN_MECHANISM_RATES {
            return Err(PipelineError::TooFewPoints {
                path: self.path.to_owned(),
                field: "mechanism.rates_deg_s".to_owned(),
                got: m.rates_deg_s.len(),
                need: MIN_MECHANISM_RATES,
                model: "eq. 18 calibration",
            });
        }
        Ok(Mechanism {
            phases,
            piga: PigaCoefficients {
                k0_rad_s: m.k0_rad_s,
                k1_rad_s_g,
                k2_rad_s_g2: m.k2_rad_s_g2,
                k3_rad_s_g3: m.k3_rad_s_g3,
            },
            latitude_deg: m.latitude_deg,
            earth_rate_rad_s: m.earth_rate_rad_s,
            rates_deg_s: m.rates_deg_s.clone(),
            output_noise_rad_s: m.output_noise_rad_s,
            seed: m.seed,
        })
    }
}

/// The phase names in the study's order, for a hint.
fn sorted_names(names: &HashMap<&str, usize>) -> Vec<String> {
    let mut list: Vec<(usize, &str)> = names.iter().map(|(n, i)| (*i, *n)).collect();
    list.sort_unstable();
    list.into_iter().map(|(_, n)| n.to_owned()).collect()
}

fn rates_of<T>(items: &[T], rate: impl Fn(&T) -> f64) -> Vec<f64> {
    items.iter().map(rate).collect()
}
