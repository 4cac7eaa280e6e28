//! The study: its validated [`Inputs`] and [`run`], which orders the sections and nothing
//! else. Each section validates its own part of the configuration and runs on values
//! (`crate::sections`); this module only says in which order, and what one section hands the
//! next.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::config::{DeprecatedKey, StudyConfig};
use crate::error::{PipelineError, Result};
use recording::FileDigest;

use crate::inputs::{Core, DataSource, InputFile};
use crate::profile::Profile;
use crate::resolved::Resolved;
use crate::results::{ProfileResults, StudyInputs, StudyResults, UnitSummary, Warning};
use crate::sections::balance::counterweight::{self, CounterweightInputs};
use crate::sections::balance::{self, BalanceInputs};
use crate::sections::calibration::{self, CalibrationInputs, CalibrationMeasurement};
use crate::sections::certificate::{self, Certificate};
use crate::sections::mechanism::{self, Mechanism};
use crate::sections::mountings::{self, MountingsInputs};
use crate::sections::phases::{self, Phases, Progress};
use crate::sections::two_orientation::{self, TwoOrientationInputs};

/// The validated inputs of a study.
#[derive(Debug, Clone)]
pub struct Inputs {
    core: Core,
    /// Shared by the units of a several-unit study: their phases are the study's.
    phases: Arc<Phases>,
    mechanism: Option<Mechanism>,
    calibration: Option<CalibrationInputs>,
    balance: Option<BalanceInputs>,
    counterweight: Option<CounterweightInputs>,
    certificate: Option<Certificate>,
    /// The configuration file's size and SHA-256 as the edge read it.
    config_digest: Option<FileDigest>,
    two_orientation: Option<TwoOrientationInputs>,
    mountings: Option<MountingsInputs>,
    /// Sections written under a former name (each a `deprecated_key` warning).
    deprecated: Vec<DeprecatedKey>,
    /// The lab profile the study named: which values came from it, and the file it was read
    /// from with its size and SHA-256.
    profile: Option<(ProfileResults, PathBuf, Option<FileDigest>)>,
    /// A several-unit study's units, each as its single-unit study (empty: one unit, or
    /// none).
    units: Vec<Unit>,
}

/// One unit of a several-unit study: its label and its single-unit study's inputs
/// ([`StudyConfig::for_unit`]), whose phases are the study's own.
#[derive(Debug, Clone)]
struct Unit {
    label: String,
    inputs: Inputs,
}

impl Inputs {
    /// Validates a configuration read from `source` (named in every error; relative data
    /// paths are resolved against its folder) and loads the data files it names through
    /// `load`, in parallel. A study that names a lab profile is built with
    /// [`Inputs::with_profile`] ([`crate::load_study`] reads the profile).
    ///
    /// # Errors
    /// The first invalid field in the file's order; for data files, every file that could
    /// not be loaded, in the configuration's order ([`PipelineError::Several`] when more than
    /// one).
    pub fn new(config: StudyConfig, source: &Path, load: &dyn DataSource) -> Result<Self> {
        Self::with_profile(config, None, source, load)
    }

    /// [`Inputs::new`] for a study with its lab profile (`profile`, read by the edge: the
    /// file the study's `profile` names). The profile is validated, and what the study leaves
    /// out is taken from it; the results say which value came from where.
    ///
    /// # Errors
    /// Those of [`Inputs::new`]; the profile's own problems ([`Profile::validate`]); a study
    /// that names a profile without one given here, or names a centrifuge without a profile;
    /// a centrifuge, probe or signatory the profile does not have.
    pub fn with_profile(
        config: StudyConfig,
        profile: Option<&Profile>,
        source: &Path,
        load: &dyn DataSource,
    ) -> Result<Self> {
        if config.units.is_some() {
            return Self::with_units(&config, profile, source, load);
        }
        Self::build(config, profile, source, load, None)
    }

    /// A several-unit study: its shared part ([`StudyConfig::without_units`]) with its phases
    /// read once, then each unit's single-unit study ([`StudyConfig::for_unit`]) on those
    /// phases. Every unit's problems at once, each naming the unit's field
    /// (`units[1].calibration.table`); a problem of a shared field is named once.
    fn with_units(
        config: &StudyConfig,
        profile: Option<&Profile>,
        source: &Path,
        load: &dyn DataSource,
    ) -> Result<Self> {
        PipelineError::from_list(units_problems(config, source))?;
        let mut top = Self::build(config.without_units(), profile, source, load, None)?;
        let mut errors: Vec<PipelineError> = Vec::new();
        let mut units = Vec::new();
        let count = config.units.as_ref().map_or(0, Vec::len);
        for index in 0..count {
            let Some(unit_config) = config.for_unit(index) else {
                continue;
            };
            let label = config
                .units
                .as_ref()
                .map_or_else(String::new, |u| u[index].label.clone());
            match Self::build(unit_config, profile, source, load, Some(&top.phases)) {
                Ok(inputs) => units.push(Unit { label, inputs }),
                Err(e) => {
                    // a shared field's problem is the same in every unit: named once
                    let e = e.in_unit(index);
                    let flat = match e {
                        PipelineError::Several { errors } => errors,
                        e => vec![e],
                    };
                    for e in flat {
                        let text = e.to_string();
                        if !errors.iter().any(|known| known.to_string() == text) {
                            errors.push(e);
                        }
                    }
                }
            }
        }
        PipelineError::from_list(errors)?;
        top.units = units;
        Ok(top)
    }

    /// The inputs of one study (a single-unit study, or a several-unit study's shared part
    /// or one unit); `shared`: the phases of the several-unit study, read once, which a
    /// unit uses instead of reading them again.
    fn build(
        mut config: StudyConfig,
        profile: Option<&Profile>,
        source: &Path,
        load: &dyn DataSource,
        shared: Option<&Arc<Phases>>,
    ) -> Result<Self> {
        let deprecated = config.take_deprecated_keys(source)?;
        let profile = match (&config.profile, profile) {
            (Some(_), Some(p)) => {
                let used = p.apply(&mut config, source)?;
                Some((used, p.source().to_owned(), p.digest().cloned()))
            }
            (Some(named), None) => {
                return Err(PipelineError::ProfileNotRead {
                    path: source.to_owned(),
                    profile: named.clone(),
                });
            }
            (None, Some(p)) => {
                return Err(PipelineError::MissingField {
                    path: source.to_owned(),
                    field: "profile".to_owned(),
                    hint: format!(
                        "a lab profile ({}) was given for a study that names none: name it \
                         (`profile: \"…\"`)",
                        p.source().display()
                    ),
                });
            }
            (None, None) => {
                for (field, named) in [
                    ("centrifuge", config.centrifuge.is_some()),
                    ("probe", config.probe.is_some()),
                ] {
                    if named {
                        return Err(PipelineError::MissingField {
                            path: source.to_owned(),
                            field: "profile".to_owned(),
                            hint: format!(
                                "`{field}` names an instrument of a lab profile: name the profile \
                                 too (`profile: \"lab.ron\"`, docs/PROFILE.md)"
                            ),
                        });
                    }
                }
                None
            }
        };
        let mut core = Core::new(&config, source)?;
        let check = core.check();
        let checked = phases::check(&check, config.radius_model, &config.phases)?;
        let second_probe = balance::second_probe_phases(config.balance.as_ref(), &checked.names);
        let names = checked.names(second_probe);
        let mechanism = config
            .mechanism
            .as_ref()
            .map(|m| mechanism::validate(&check, m, config.k1_rad_s_g, &names))
            .transpose()?;
        PipelineError::from_list(crate::type_b::implausible(&check, &config))?;
        // What several sections depend on, settled once: each section validates its own part
        // of the configuration with these beside it.
        let resolved = Resolved::new(&check, &config, &names)?;
        let calibration_refs = config
            .calibration
            .as_ref()
            .map(|c| calibration::validate(&check, c, &resolved))
            .transpose()?;
        let balance = config
            .balance
            .as_ref()
            .map(|b| {
                balance::validate(
                    &check,
                    b,
                    &resolved,
                    &names.names,
                    core.lever.probe_to_piga_mm,
                )
            })
            .transpose()?;
        let counterweight = config
            .counterweight
            .as_ref()
            .map(|c| counterweight::validate(&check, c, &resolved, &names.names))
            .transpose()?;
        let certificate = config
            .certificate
            .as_ref()
            .map(|c| certificate::validate(&check, c, &resolved))
            .transpose()?;
        let two_orientation = config
            .two_orientation
            .as_ref()
            .map(|s| two_orientation::validate(&check, s, &resolved, &names, core.base(), load))
            .transpose()?;
        let mountings = config
            .mountings
            .as_ref()
            .map(|s| mountings::validate(&check, s, &resolved, &names, &core, load))
            .transpose()?;
        let base = core.base().to_owned();
        let phases = match shared {
            Some(phases) => Arc::clone(phases),
            None => {
                Arc::new(checked.load(&config.phases, &base, source, load, &core.angle_zero)?)
            }
        };
        core.angle_zero.measured_angles = phases.measure_angles();
        let calibration = match (config.calibration.as_ref(), calibration_refs) {
            (Some(c), Some(refs)) => Some(calibration::load(
                c,
                refs,
                resolved.type_b(),
                &base,
                source,
                load,
            )?),
            _ => None,
        };
        Ok(Self {
            core,
            phases,
            mechanism,
            calibration,
            balance,
            counterweight,
            certificate,
            config_digest: None,
            two_orientation,
            mountings,
            deprecated,
            profile,
            units: Vec::new(),
        })
    }

    /// A several-unit study's units, each with its label and its single-unit study's
    /// inputs (empty for a study of one unit).
    pub fn units(&self) -> impl Iterator<Item = (&str, &Self)> {
        self.units.iter().map(|u| (u.label.as_str(), &u.inputs))
    }

    /// The lab profile's file and its size and SHA-256 as read (`None`: the study names no
    /// profile, or it was built from values).
    pub fn profile_file(&self) -> Option<(&Path, Option<&FileDigest>)> {
        self.profile
            .as_ref()
            .map(|(_, path, digest)| (path.as_path(), digest.as_ref()))
    }

    /// Which values came from the lab profile and which the study states (`None`: no
    /// profile).
    pub fn profile_values(&self) -> Option<&ProfileResults> {
        self.profile.as_ref().map(|(p, ..)| p)
    }

    /// What the study can say before it runs that may make a certificate wrong: equipment
    /// past its calibration due date on the measurement date, or due dates that cannot be
    /// compared with it. `run` states the same among its warnings.
    pub fn warnings(&self) -> Vec<Warning> {
        let mut warnings = self
            .certificate
            .as_ref()
            .map(Certificate::warnings)
            .unwrap_or_default();
        for unit in &self.units {
            warnings.extend(unit.inputs.warnings());
        }
        warnings
    }

    /// [`Inputs::warnings`] of this study alone (not its units').
    fn own_warnings(&self) -> Vec<Warning> {
        self.certificate
            .as_ref()
            .map(Certificate::warnings)
            .unwrap_or_default()
    }

    /// The inputs, with the size and SHA-256 of the configuration's bytes as the edge read
    /// them ([`crate::load_study`] records them; a caller that reads the file itself passes
    /// [`FileDigest::of`] its bytes).
    #[must_use]
    pub fn with_config_digest(mut self, digest: FileDigest) -> Self {
        for unit in &mut self.units {
            unit.inputs.config_digest = Some(digest.clone());
        }
        self.config_digest = Some(digest);
        self
    }

    /// The configuration file's size and SHA-256 as read (`None` for inputs built from text
    /// or values).
    pub const fn config_digest(&self) -> Option<&FileDigest> {
        self.config_digest.as_ref()
    }

    /// Every data file the study read, in the configuration's order: the phases' probe
    /// recordings, then the calibration's PIGA table or raw PIGA output recordings, then the
    /// two-orientation section's PIGA tables; each with its role, the field naming it and its
    /// size and SHA-256 as read.
    pub fn input_files(&self) -> Vec<InputFile<'_>> {
        let mut files: Vec<InputFile<'_>> = self.phases.input_files().collect();
        if let Some(c) = &self.calibration {
            files.extend(c.input_files());
        }
        if let Some(s) = &self.two_orientation {
            files.extend(s.input_files());
        }
        if let Some(s) = &self.mountings {
            files.extend(s.input_files());
        }
        files
    }

    /// The study's name.
    pub fn name(&self) -> &str {
        &self.core.name
    }

    /// The configuration file the inputs came from.
    pub fn source(&self) -> &Path {
        &self.core.source
    }

    /// Every probe recording the study read, in the configuration's order.
    pub fn recording_files(&self) -> impl Iterator<Item = &Path> {
        self.phases.recording_files()
    }

    /// Every data file of the calibration section: the PIGA table, or the raw PIGA output
    /// recordings, in the configuration's order (empty without a calibration section).
    pub fn calibration_files(&self) -> Vec<&Path> {
        self.calibration
            .as_ref()
            .map(CalibrationInputs::files)
            .unwrap_or_default()
    }
}

/// What a several-unit study's `units` list and top level may not hold, every problem at
/// once: an empty list; a label that is not a name (it names a folder) or that another unit
/// has (compared without regard to case, as some file systems compare folder names); a
/// certificate identification another unit has; a top-level section that is each unit's own.
fn units_problems(config: &StudyConfig, source: &Path) -> Vec<PipelineError> {
    let mut errors = Vec::new();
    for (field, hint) in config.beside_units() {
        errors.push(PipelineError::BesideUnits {
            path: source.to_owned(),
            field: field.to_owned(),
            hint,
        });
    }
    let Some(units) = &config.units else {
        return errors;
    };
    if units.is_empty() {
        errors.push(PipelineError::EmptyList {
            path: source.to_owned(),
            field: "units".to_owned(),
        });
    }
    for (i, unit) in units.iter().enumerate() {
        let label = &unit.label;
        let valid = !label.is_empty()
            && label.len() <= 64
            && label
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
        if !valid {
            errors.push(PipelineError::InvalidName {
                path: source.to_owned(),
                field: format!("units[{i}].label"),
                name: label.clone(),
            });
        } else if let Some(first) = units[..i]
            .iter()
            .position(|u| u.label.eq_ignore_ascii_case(label))
        {
            errors.push(PipelineError::DuplicateName {
                path: source.to_owned(),
                field: format!("units[{i}].label"),
                first: format!("units[{first}].label"),
                name: label.clone(),
            });
        }
        if let Some(id) = unit.certificate.as_ref().map(|c| c.id.trim())
            && let Some(first) = units[..i].iter().position(|u| {
                u.certificate
                    .as_ref()
                    .is_some_and(|c| !id.is_empty() && c.id.trim() == id)
            })
        {
            errors.push(PipelineError::UsedTwice {
                path: source.to_owned(),
                field: format!("units[{i}].certificate.id"),
                first: format!("units[{first}].certificate.id"),
                value: id.to_owned(),
                what: "a certificate's identification (each certificate has its own)",
            });
        }
    }
    errors
}

/// Runs a study: each phase with its per-point geometry, its radius-error fit and the
/// pseudo-second-order error `Δk2` it implies, then the mechanism, calibration, balance and
/// counterweight sections when configured.
///
/// The computation reads only the inputs; published values are never consulted.
pub fn run(inputs: &Inputs) -> Result<StudyResults> {
    run_with_progress(inputs, &|_| {})
}

/// [`run`], reporting progress through `progress` (called from several threads while
/// recordings are analyzed in parallel).
pub fn run_with_progress(
    inputs: &Inputs,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<StudyResults> {
    let core = &inputs.core;
    let _study = tracing::info_span!("study", name = %core.name).entered();
    let total = inputs.phases.recordings();
    if total > 0 {
        progress(Progress::Recordings { total });
    }
    // Each phase measured once (the recordings analysed); a several-unit study fits them for
    // each unit, with its k1 and radius.
    let measured = inputs
        .phases
        .list
        .iter()
        .map(|phase| phases::measure_phase(core, phase, progress))
        .collect::<Result<Vec<_>>>()?;
    let mut results = run_sections(inputs, &measured)?;
    if inputs.units.is_empty() {
        return Ok(results);
    }
    let mut summaries = Vec::with_capacity(inputs.units.len());
    let mut studies = Vec::with_capacity(inputs.units.len());
    for (index, unit) in inputs.units.iter().enumerate() {
        let _unit = tracing::info_span!("unit", label = %unit.label).entered();
        let r = run_sections(&unit.inputs, &measured).map_err(|e| e.in_unit(index))?;
        summaries.push(unit_summary(&unit.label, &unit.inputs, &r));
        studies.push(r);
    }
    results.units = Some(summaries);
    results.unit_studies = studies;
    Ok(results)
}

/// The top folder's line of a unit.
fn unit_summary(label: &str, inputs: &Inputs, r: &StudyResults) -> UnitSummary {
    UnitSummary {
        label: label.to_owned(),
        folder: format!("units/{label}"),
        study: r.study.clone(),
        k1_rad_s_g: inputs.core.k1_rad_s_g,
        radius_m: inputs.core.radius_m,
        certificate: r.certificate.as_ref().map(|c| c.id.clone()),
        item: r
            .certificate
            .as_ref()
            .map(|c| format!("{} {}", c.item.model, c.item.serial)),
        compensate_with: r.calibration.as_ref().map(|c| c.compensate_with.clone()),
        delta_k2: r.calibration.as_ref().map(|c| c.delta_k2),
        k2: r.calibration.as_ref().map(|c| c.coefficients.k2),
        warnings: r.warnings.len(),
    }
}

/// The sections of one study (a single-unit study, or a several-unit study's shared part or
/// one unit) on its measured phases.
fn run_sections(inputs: &Inputs, measured: &[phases::Measured]) -> Result<StudyResults> {
    let core = &inputs.core;
    let mut warnings: Vec<Warning> = inputs
        .deprecated
        .iter()
        .map(|d| Warning::deprecated_key(d.old, d.new))
        .collect();
    warnings.extend(inputs.own_warnings());
    let mut phases = Vec::with_capacity(inputs.phases.list.len());
    // Phases holding a second probe's data are fitted like the others, through the first
    // probe's lever and direction: their C_r is not the PIGA plane's, and they say so.
    let second_probe = inputs
        .balance
        .as_ref()
        .map(BalanceInputs::second_probe_phases)
        .unwrap_or_default();
    for (p, (phase, m)) in inputs.phases.list.iter().zip(measured).enumerate() {
        let (results, more) = phases::fit_phase(core, inputs.phases.model, phase, m)?;
        if second_probe.contains(&p) {
            warnings.push(Warning::second_probe_phase(&phase.name, &phase.key));
        }
        phases.push(results);
        warnings.extend(more);
    }
    let mechanism = inputs
        .mechanism
        .as_ref()
        .map(|m| mechanism::run(core, m, &phases))
        .transpose()?;
    let calibration = match inputs.calibration.as_ref() {
        Some(c) => {
            let (results, more) = calibration::run(core, c, &phases[c.phase])?;
            crate::intervals::check_calibration(&core.source, &results)?;
            warnings.extend(more);
            Some(results)
        }
        None => None,
    };
    let balance = match inputs.balance.as_ref() {
        Some(b) => {
            let (results, more) = balance::run(core, b, &phases)?;
            warnings.extend(more);
            Some(results)
        }
        None => None,
    };
    let counterweight = inputs
        .counterweight
        .as_ref()
        .map(|c| counterweight::run(core, c, &phases[c.phase].name))
        .transpose()?;
    let two_orientation = match inputs.two_orientation.as_ref() {
        Some(s) => {
            let (results, more) = two_orientation::run(core, s, &phases)?;
            crate::intervals::check_two_orientation(&core.source, &results)?;
            warnings.extend(more);
            Some(results)
        }
        None => None,
    };
    let mountings = match inputs.mountings.as_ref() {
        Some(s) => {
            let (results, more) = mountings::run(core, s, &phases)?;
            warnings.extend(more);
            Some(results)
        }
        None => None,
    };
    // after the two-orientation section: the certificate may certify its coefficients
    let certificate = match (inputs.certificate.as_ref(), calibration.as_ref()) {
        (Some(cert), Some(c)) => Some(certificate::run(
            &core.source,
            cert,
            c,
            two_orientation.as_ref(),
            core.radius_m,
        )?),
        _ => None,
    };
    let results = StudyResults {
        study: core.name.clone(),
        inputs: StudyInputs {
            radius_m: core.radius_m,
            g_m_s2: core.g_m_s2,
            k1_rad_s_g: core.k1_rad_s_g,
            lever_ratio: core.lever_ratio,
            probe_direction: crate::inputs::probe_sign(core.lever.probe_direction),
            angle_zero: core.angle_zero,
        },
        phases,
        mechanism,
        calibration,
        warnings,
        balance,
        counterweight,
        certificate,
        two_orientation,
        mountings,
        profile: inputs.profile_values().cloned(),
        units: None,
        unit_studies: Vec::new(),
    };
    // The libraries refuse their own non-finite results; this catches what is combined here.
    edge_io::check_finite(&results).map_err(|e| PipelineError::NonFiniteResult {
        path: core.source.clone(),
        field: e.path,
        value: e.value,
    })?;
    Ok(results)
}

/// The calibration's measurement model with its validated input quantities and the Monte
/// Carlo options, set up as [`run`] sets them up before its GUM and Monte Carlo evaluations
/// (the compensating phase's C_r fit, the calibration's points, then the eq. 18 fit), for a
/// benchmark or an outside check of the uncertainty evaluation. `None` when the study has no
/// calibration section.
///
/// Errors: those of [`run`] for the compensating phase and the calibration.
pub fn calibration_measurement(inputs: &Inputs) -> Result<Option<CalibrationMeasurement>> {
    let Some(c) = inputs.calibration.as_ref() else {
        return Ok(None);
    };
    let core = &inputs.core;
    let (phase, _) = phases::run_phase(
        core,
        inputs.phases.model,
        &inputs.phases.list[c.phase],
        &|_| {},
    )?;
    calibration::measurement(core, c, &phase).map(Some)
}
