//! The study file's format: data-transfer types read from RON (`docs/CONFIGURATION.md`).
//!
//! These types define the file format and nothing else: they hold what the file says,
//! unvalidated. [`crate::Inputs::new`] turns them into the validated inputs of a study; the
//! library types (`harmonics::LeverGeometry`, `harmonics::FitConfig`, `identify::RadiusModel`)
//! are built there, so renaming a library field cannot change the file format.

use std::path::{Path, PathBuf};

use recording::RecordingFormat;
use serde::{Deserialize, Serialize};

use crate::error::{PipelineError, Result};

mod certificate;
mod direction;
mod mountings;
mod profile;
mod table;
mod two_orientation;
pub use certificate::*;
pub use direction::*;
pub use mountings::*;
pub use profile::*;
pub use table::*;
pub use two_orientation::*;

/// A whole study: one centrifuge, one PIGA, and any number of named probe phases (before
/// balancing, with a trial weight, after balancing, ...).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyConfig {
    /// A short name for the study, used in reports.
    pub name: String,
    /// The lab profile (`lab.ron`, `docs/PROFILE.md`), relative to the study file's folder:
    /// what it states (the centrifuge's radius and probe geometry, g, the Type B inputs, the
    /// certificate's laboratory, equipment, traceability, signatory) the study need not
    /// repeat; a value the study states overrides it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<PathBuf>,
    /// The centrifuge used, by its name in the profile (required with a profile).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centrifuge: Option<String>,
    /// The probe used, by its name in the profile (default: the one the centrifuge names).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probe: Option<String>,
    /// Static working radius `R` (PIGA centre of mass to spindle axis), m (from the profile's
    /// centrifuge when left out).
    #[serde(default)]
    pub radius_m: Option<f64>,
    /// Gravity used to express specific force in g, m/s² (from the profile when left out).
    #[serde(default)]
    pub g_m_s2: Option<f64>,
    /// PIGA scale factor `k1`, rad/(s·g).
    pub k1_rad_s_g: f64,
    /// Heights that carry the probe's first harmonic to the PIGA plane, and the probe
    /// direction (each from the profile's centrifuge when left out).
    #[serde(default)]
    pub lever: LeverConfig,
    /// Model of the radius error against rate (default: the paper's `a + C_r·ω²`).
    #[serde(default)]
    pub radius_model: RadiusModelName,
    /// The probe phases, in the order they are reported (at least one; names unique).
    pub phases: Vec<PhaseConfig>,
    /// A PIGA calibration simulated with each phase's measured C_r, identified with and
    /// without compensation (absent: not run).
    #[serde(default)]
    pub mechanism: Option<MechanismConfig>,
    /// The PIGA's calibration on measured data, compensated with a phase's C_r (absent: none).
    #[serde(default)]
    pub calibration: Option<CalibrationConfig>,
    /// Type B standard uncertainties of the calibration's inputs (absent: all zero, and the
    /// budget says so).
    #[serde(default)]
    pub uncertainty: Option<UncertaintyConfig>,
    /// The balance advisor: from the probe phases to a correction mass and azimuth, and the
    /// k2 error it leaves (absent: not run; `docs/BALANCING.md`).
    #[serde(default)]
    pub balance: Option<BalanceConfig>,
    /// The counterweight one published change of radius error stands for (the paper check:
    /// a `radius_change` phase and a stated radial stiffness; absent: not run).
    #[serde(default)]
    pub counterweight: Option<CounterweightConfig>,
    /// The calibration certificate's statements (absent: no `certificate.pdf`; needs a
    /// calibration section; `docs/CERTIFICATE.md`).
    #[serde(default)]
    pub certificate: Option<CertificateConfig>,
    /// The two-orientation (IA in / IA out) calibration: k2 and the total radius growth C
    /// from the PIGA alone, compared with a probe phase's C_r (absent: not run;
    /// `docs/TWO_ORIENTATION.md`).
    #[serde(default)]
    pub two_orientation: Option<TwoOrientationConfig>,
    /// The IEEE 836 model identified jointly from several mountings, each with its table
    /// (absent: not run; `docs/MODEL.md`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mountings: Option<MountingsConfig>,
    /// The former name of `two_orientation` (`symmetric: (...)`), read as it with a
    /// `deprecated_key` warning naming the new key; both at once is an error.
    #[serde(default, rename = "symmetric", skip_serializing_if = "Option::is_none")]
    pub symmetric_deprecated: Option<TwoOrientationConfig>,
    /// Several units calibrated from this study's one spindle characterisation, each with its
    /// own k1, calibration data and certificate (absent: the study is of one unit, stated by
    /// the top-level sections). With it, the top-level `calibration`, `certificate`,
    /// `two_orientation` and `mountings` are refused.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<Vec<UnitConfig>>,
}

// ---- several units (issue 30 part 4, docs/CONFIGURATION.md "Several units") ----

/// One unit of a several-unit study (`units: [(label: "A", …), …]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitConfig {
    /// The unit's label: letters, digits, `_` and `-`, at most 64 characters, unique in the
    /// study (compared without regard to case): its outputs go to `units/<label>/`.
    pub label: String,
    /// The unit's scale factor `k1`, rad/(s·g): its Δk2 = k1·C_r·g/R² (eq. 19).
    pub k1_rad_s_g: f64,
    /// The unit's static working radius, m (default: the study's `radius_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_m: Option<f64>,
    /// The unit's calibration on its own table or raw output recordings, compensated with a
    /// phase of the study.
    pub calibration: CalibrationConfig,
    /// Its two-orientation calibration (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub two_orientation: Option<TwoOrientationConfig>,
    /// Its certificate's statements (absent: no certificate for this unit). The
    /// identification must differ from every other unit's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub certificate: Option<CertificateConfig>,
}

/// The top-level sections a several-unit study refuses beside `units`: each is a unit's
/// own, stated inside each unit (or, for `mountings`, not yet available per unit).
const BESIDE_UNITS: [(&str, &str); 5] = [
    (
        "calibration",
        "each unit states its own calibration: move it into `units[…].calibration`",
    ),
    (
        "certificate",
        "each unit states its own certificate: move it into `units[…].certificate`",
    ),
    (
        "two_orientation",
        "each unit states its own two-orientation data: move it into \
         `units[…].two_orientation`",
    ),
    (
        "symmetric",
        "each unit states its own two-orientation data: move it into \
         `units[…].two_orientation`",
    ),
    (
        "mountings",
        "the mountings section is not available per unit yet: run a study of that unit on \
         its own",
    ),
];

impl StudyConfig {
    /// The top-level sections given beside `units` that a several-unit study refuses, each
    /// with what to do instead (empty for a study without units).
    pub(crate) fn beside_units(&self) -> Vec<(&'static str, &'static str)> {
        if self.units.is_none() {
            return Vec::new();
        }
        let given = [
            self.calibration.is_some(),
            self.certificate.is_some(),
            self.two_orientation.is_some(),
            self.symmetric_deprecated.is_some(),
            self.mountings.is_some(),
        ];
        BESIDE_UNITS
            .iter()
            .zip(given)
            .filter_map(|(&what, given)| given.then_some(what))
            .collect()
    }

    /// The study of the shared part of a several-unit study: its probe phases and what goes
    /// with them (mechanism, balance, counterweight), without any unit.
    #[must_use]
    pub fn without_units(&self) -> Self {
        Self {
            units: None,
            ..self.clone()
        }
    }

    /// The single-unit study of unit `index`: the study with that unit's k1, radius (when it
    /// states one), calibration, two-orientation section and certificate, named
    /// `<name>: unit <label>`. A several-unit study computes each unit as this study (the
    /// same code on the same values: the numbers of a unit equal those of its single-unit
    /// study). `None` when there is no such unit.
    #[must_use]
    pub fn for_unit(&self, index: usize) -> Option<Self> {
        let unit = self.units.as_ref()?.get(index)?;
        Some(Self {
            name: format!("{}: unit {}", self.name, unit.label),
            radius_m: unit.radius_m.or(self.radius_m),
            k1_rad_s_g: unit.k1_rad_s_g,
            calibration: Some(unit.calibration.clone()),
            certificate: unit.certificate.clone(),
            two_orientation: unit.two_orientation.clone(),
            units: None,
            ..self.clone()
        })
    }
}

/// The counterweight section (`counterweight: (...)`): what a `radius_change` phase, one
/// number, determines of the correction (eq. 1, 19), with a stated radial stiffness.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CounterweightConfig {
    /// The `radius_change` phase, by name.
    pub phase: String,
    /// Radial stiffness `k_r` of the spindle bearing, N/m (an input: the paper gives none).
    pub radial_stiffness_n_m: f64,
    /// Where that stiffness comes from (shown beside it in the report; required, not
    /// blank).
    pub stiffness_source: String,
    /// Radius at which the counterweight would be mounted, m.
    pub correction_radius_m: f64,
}

/// The balance section (`balance: (...)`): which phases were run without and with a trial
/// mass, the trial mass, where the correction goes, and optionally the bearing's radial
/// stiffness (the stiffness-model correction of eq. 1) and a check run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BalanceConfig {
    /// The phase run as found (no trial mass), by name.
    pub initial: String,
    /// The phase run with the trial mass added, by name (with `trial_mass`: the
    /// influence-coefficient correction).
    #[serde(default)]
    pub trial: Option<String>,
    /// The trial mass of the trial phase.
    #[serde(default)]
    pub trial_mass: Option<TrialMassConfig>,
    /// Radial stiffness `k_r` of the spindle bearing, N/m: the stiffness-model correction
    /// (eq. 1), alone or beside the influence coefficient.
    #[serde(default)]
    pub radial_stiffness_n_m: Option<f64>,
    /// Radius at which the correction mass is mounted, m.
    pub correction_radius_m: f64,
    /// Azimuths of fixed mounting positions, deg (default none: any azimuth).
    #[serde(default)]
    pub fixed_azimuths_deg: Vec<f64>,
    /// Mass of the rotor, kg, for the ISO 21940-11 grade (absent: no grade).
    #[serde(default)]
    pub rotor_mass_kg: Option<f64>,
    /// A phase run after the correction, by name, compared with the prediction.
    #[serde(default)]
    pub check: Option<String>,
    /// A second probe at another height (absent: one probe, the cone assumption of eq. 22):
    /// its height and, for each phase above, the phase that holds its first harmonics.
    #[serde(default)]
    pub second_probe: Option<SecondProbeConfig>,
    /// Angular stiffness `k_θ` of the spindle bearing, N·m/rad: with `radial_stiffness_n_m`
    /// and a second probe, the couple unbalance (eq. 2) and the stiffness-model two-plane
    /// correction.
    #[serde(default)]
    pub angular_stiffness_n_m_rad: Option<f64>,
    /// The two-plane correction's planes and its second trial run (needs `second_probe`).
    #[serde(default)]
    pub two_plane: Option<TwoPlaneConfig>,
}

/// The second probe of a balance section (`second_probe: (...)`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SecondProbeConfig {
    /// Height from the second probe's plane up to the PIGA plane, mm (positive below it, as
    /// `lever.probe_to_piga_mm`; it must differ from the first probe's).
    pub probe_to_piga_mm: f64,
    /// Its measuring direction (default: against O1X1).
    #[serde(default)]
    pub probe_direction: ProbeDirectionName,
    /// For each phase the advisor uses (`initial`, `trial`, `check`, `two_plane.trial`), by
    /// name, the phase of the same run seen by the second probe, e.g.
    /// `{"before": "before_lower"}`.
    pub phases: std::collections::BTreeMap<String, String>,
}

/// The two-plane correction (`two_plane: (...)`): planes A and B, and the trial run in B
/// (the balance section's `trial` and `trial_mass` are the trial run in A).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwoPlaneConfig {
    /// Heights of correction planes A and B above the PIGA plane, m (distinct).
    pub heights_m: (f64, f64),
    /// Radius at which masses go in plane B, m (default: `correction_radius_m`).
    #[serde(default)]
    pub radius_b_m: Option<f64>,
    /// The phase run with `trial_mass` in plane B (alone), by name.
    #[serde(default)]
    pub trial: Option<String>,
    /// The trial mass of that run.
    #[serde(default)]
    pub trial_mass: Option<TrialMassConfig>,
}

/// A trial mass: mass, radius from the axis and azimuth in `O2` (from `O2X2`, the arm, towards
/// `O2Y2`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrialMassConfig {
    /// Mass, kg (> 0).
    pub mass_kg: f64,
    /// Radius, m (> 0).
    pub radius_m: f64,
    /// Azimuth, deg.
    pub azimuth_deg: f64,
    /// Height of the trial mass above the PIGA plane, m (recorded; the two-plane correction
    /// takes its planes' heights from `two_plane.heights_m`).
    #[serde(default)]
    pub height_m: Option<f64>,
}

/// The calibration section: the PIGA's mean output at several rates, identified by eq. 18
/// with and without the compensation of eq. 19.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationConfig {
    /// The PIGA table: one row per measurement, the rate and the mean output (exactly one
    /// of `table` and `recordings`).
    #[serde(default)]
    pub table: Option<PigaTableConfig>,
    /// Raw PIGA output recordings, one file per rate, each reduced to its mean output over
    /// whole spindle revolutions with its standard error (exactly one of `table` and
    /// `recordings`).
    #[serde(default)]
    pub recordings: Option<PigaRecordingSet>,
    /// The phase whose C_r is removed (eq. 19), by name.
    pub compensate_with: String,
    /// Where k1 comes from (default: fitted, from the ω² coefficient).
    #[serde(default)]
    pub k1: K1Config,
    /// Seed of the Monte Carlo evaluation (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Number of Monte Carlo trials: `adaptive` (default, JCGM 101 §7.9, two significant
    /// digits) or `fixed(N)` (at least 2000).
    #[serde(default)]
    pub trials: TrialsConfig,
}

const fn default_seed() -> u64 {
    1
}

/// Where the calibration's k1 comes from.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum K1Config {
    /// From the fit's ω² coefficient, `c₂·g/R`, with its uncertainty and correlations.
    #[default]
    Fitted,
    /// Known from elsewhere, e.g. a static multi-position test.
    Given {
        /// k1, rad/(s·g).
        k1_rad_s_g: f64,
        /// Its standard uncertainty, rad/(s·g) (Type B; default 0).
        #[serde(default)]
        u_rad_s_g: f64,
    },
}

/// Type B standard uncertainties of the calibration's inputs (JCGM 100 §4.3). Each is a
/// standard uncertainty (one standard deviation), not a tolerance or a bound. Every input is
/// stated: a field left out is an error naming it, and a zero needs its reason in
/// `zero_reasons` (nothing is assumed exact without a word). The probe gain is stated once:
/// here, or by the compensating phase's recordings in volts with their sensitivity's
/// uncertainty (then it must not be given here).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UncertaintyConfig {
    /// u(R), m.
    #[serde(default)]
    pub radius_u_m: Option<f64>,
    /// u(g), m/s².
    #[serde(default)]
    pub g_u_m_s2: Option<f64>,
    /// Where the study's value of g comes from (shown beside it in the report).
    #[serde(default)]
    pub g_source: String,
    /// Relative standard uncertainty of the rate (a scale error common to every rate).
    #[serde(default)]
    pub rate_u_relative: Option<f64>,
    /// u of the height from the tilt pivot to the probe plane, mm.
    #[serde(default)]
    pub pivot_to_probe_u_mm: Option<f64>,
    /// u of the height from the probe plane to the PIGA plane, mm.
    #[serde(default)]
    pub probe_to_piga_u_mm: Option<f64>,
    /// Relative standard uncertainty of the probe's gain (sensitivity); left out when the
    /// compensating phase's recordings are in volts with a stated sensitivity.
    #[serde(default)]
    pub probe_gain_u_relative: Option<f64>,
    /// Why an input given as 0 is negligible, by its field's name
    /// (`{"rate_u_relative": "encoder against the frequency standard, 1e-9"}`).
    #[serde(default)]
    pub zero_reasons: std::collections::BTreeMap<String, String>,
}

impl StudyConfig {
    /// Moves a section written under a former name to its current one, returning the
    /// former names read (`symmetric` for `two_orientation`), for the study's warnings.
    ///
    /// # Errors
    /// [`PipelineError::StatedTwice`] when a section is written under both names.
    pub fn take_deprecated_keys(&mut self, path: &Path) -> Result<Vec<DeprecatedKey>> {
        let mut read = Vec::new();
        if let Some(section) = self.symmetric_deprecated.take() {
            if self.two_orientation.is_some() {
                return Err(PipelineError::StatedTwice {
                    path: path.to_owned(),
                    field: "two_orientation".into(),
                    other: "symmetric".into(),
                    what: "the two-orientation calibration",
                });
            }
            self.two_orientation = Some(section);
            read.push(DeprecatedKey {
                old: "symmetric",
                new: "two_orientation",
            });
        }
        Ok(read)
    }

    /// The probe gain's relative standard uncertainty stated by the compensating phase's
    /// recordings (a gap in volts with its sensitivity's uncertainty), with the field that
    /// states it; `None` when the calibration's phase is not recorded in volts (or its
    /// sensitivity is invalid: the reader refuses it).
    pub(crate) fn stated_probe_gain(&self) -> Option<(f64, String)> {
        let name = &self.calibration.as_ref()?.compensate_with;
        let (i, phase) = self
            .phases
            .iter()
            .enumerate()
            .find(|(_, p)| &p.name == name)?;
        phase.stated_probe_gain(i)
    }
}

impl PhaseConfig {
    /// The probe gain's relative standard uncertainty this phase's recordings state (a gap in
    /// volts with its sensitivity's uncertainty), with the field that states it (`index`: the
    /// phase's place in `phases`); `None` when the phase is not recorded in volts (or its
    /// sensitivity is invalid: the reader refuses it).
    pub(crate) fn stated_probe_gain(&self, index: usize) -> Option<(f64, String)> {
        let Points::Recordings(set) = &self.points else {
            return None;
        };
        let s = set.format.gap.unit.sensitivity().ok()??;
        Some((
            s.relative_u(),
            format!("phases[{index}].points.format.gap.unit (u_sensitivity)"),
        ))
    }
}

/// The probe's lever geometry (eq. 22): heights in mm and the measuring direction. Each is
/// required unless the study's lab profile gives it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LeverConfig {
    /// Height from the tilt pivot to the probe plane, mm.
    pub pivot_to_probe_mm: Option<f64>,
    /// Height from the probe plane to the PIGA centre-of-mass plane, mm.
    pub probe_to_piga_mm: Option<f64>,
    /// The probe's measuring direction: against O1X1 (the paper's set-up) when its reading
    /// falls as the spindle moves towards the PIGA. Default: against O1X1, when neither the
    /// study nor its lab profile's centrifuge states it.
    pub probe_direction: Option<ProbeDirectionName>,
    /// The angle zero of eq. 20–21, deg: what the spindle encoder reads (or how far the
    /// spindle has turned past the index pulse's rising edge) when the arm's PIGA end
    /// points at the probe (the arm along O1X1). Measured angles are taken less it before
    /// the fit. Absent from the study and its lab profile's centrifuge: taken as 0, and
    /// `check`, the report and results.json say so (`docs/YOUR-DATA.md`). An angle from the
    /// declared rate is not moved by it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_zero_deg: Option<f64>,
}

/// A radius-error model, as the study file and `results.json` name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RadiusModelName {
    /// `Δr = a + C_r·ω²`, the paper's model.
    #[default]
    TwoTerm,
    /// `Δr = a + b·ω + C_r·ω²`.
    ThreeTerm,
}

/// The measurements of one named phase.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhaseConfig {
    /// The phase's name: letters, digits, `_` and `-` (it names output files), unique in the
    /// study, e.g. `pre_balance`, `trial_weight`, `post_balance`.
    pub name: String,
    /// What was measured at each rate.
    pub points: Points,
    /// How the radius-error fit weighs the points (default: unweighted, the paper's).
    #[serde(default)]
    pub weighting: Weighting,
}

/// How the radius-error fit weighs its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Weighting {
    /// Ordinary least squares: every point counts the same (the paper's fit).
    #[default]
    Unweighted,
    /// Each point weighted by `1/σ²` of its radius error, σ from its recording's per-revolution
    /// fit residuals (recordings only). Right when the rates were recorded with different
    /// numbers of samples or noise.
    InverseVariance,
}

/// What a phase provides at its rate points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[allow(
    clippy::large_enum_variant,
    reason = "a configuration value, read once; boxing would change every match on it"
)]
pub enum Points {
    /// First-harmonic probe coefficients per rate (Table 1 of the paper).
    FirstHarmonic(Vec<HarmonicPoint>),
    /// Radius errors at the PIGA plane per rate.
    RadiusError(Vec<RadiusPoint>),
    /// Probe recordings, one per rate, fitted per revolution (eq. 20) for their first harmonic.
    Recordings(RecordingSet),
    /// Only the change of radius error between two rates, as the paper publishes for the
    /// pre-balance phase. It determines `C_r` exactly, with no standard error.
    RadiusChange {
        /// The lower rate, deg/s.
        from_rate_deg_s: f64,
        /// The higher rate, deg/s.
        to_rate_deg_s: f64,
        /// Radius error at `to_rate_deg_s` minus that at `from_rate_deg_s`, µm.
        change_um: f64,
    },
}

/// First-harmonic probe coefficients at one rate (eq. 21).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HarmonicPoint {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Cosine coefficient of the probe's first harmonic, µm.
    pub dc1_um: f64,
    /// Sine coefficient of the probe's first harmonic, µm.
    pub ds1_um: f64,
    /// Standard uncertainty of `dc1_um` and of `ds1_um` (each; taken equal and independent,
    /// as for white noise), µm (> 0; absent: unknown). The balance advisor's phasor fit weighs
    /// by `1/σ²` when every point of a phase has one, and `inverse_variance` weighting of the
    /// radius-error fit may use them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_um: Option<f64>,
}

/// Radius error at the PIGA plane at one rate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RadiusPoint {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Radius error `Δr_xd + Δr_xs`, µm.
    pub radius_error_um: f64,
}

/// Probe recordings of one phase, one file per rate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordingSet {
    /// Layout of the files (delimiter, decimal mark, columns and units, angle source, gaps
    /// and non-finite samples); defaults to `time_s,gap_um[,angle_deg]`.
    #[serde(default)]
    pub format: RecordingFormat,
    /// Settings of the per-revolution fit (order 4 by default, as in the paper).
    #[serde(default)]
    pub fit: FitSettings,
    /// The recordings.
    pub files: Vec<RecordingPoint>,
}

/// Settings of the per-revolution harmonic fit (eq. 20).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FitSettings {
    /// Highest Fourier order fitted (1 to 8; the paper uses 4).
    pub order: usize,
    /// Also fit a linear drift in time within each revolution (default true: unbiased with
    /// or without drift; see docs/YOUR-DATA.md for the measurement).
    pub drift: bool,
    /// Use only the first this many complete revolutions (all when absent).
    pub revolutions: Option<usize>,
}

impl Default for FitSettings {
    fn default() -> Self {
        let d = harmonics::FitConfig::default();
        Self {
            order: d.order,
            // Chosen by measurement (docs/YOUR-DATA.md): a drift term costs a little
            // variance on drift-free data and removes the bias of drifting data.
            drift: true,
            revolutions: d.revolutions,
        }
    }
}

/// The mechanism section (`mechanism: (...)` in the study file): a PIGA calibration simulated
/// through the exact chain with the C_r each phase measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MechanismConfig {
    /// The phases whose C_r is simulated, by name (default: every phase, in study order).
    #[serde(default)]
    pub phases: Option<Vec<String>>,
    /// PIGA bias k0 of the simulated instrument, rad/s (k1 is the study's `k1_rad_s_g`).
    #[serde(default)]
    pub k0_rad_s: f64,
    /// True second-order coefficient k2, rad/(s·g²).
    pub k2_rad_s_g2: f64,
    /// Third-order coefficient k3, rad/(s·g³).
    #[serde(default)]
    pub k3_rad_s_g3: f64,
    /// Latitude of the centrifuge, degrees (default 45).
    #[serde(default = "default_latitude")]
    pub latitude_deg: f64,
    /// Earth rotation rate, rad/s (default `kinematics::EARTH_RATE_RAD_S`).
    #[serde(default = "default_earth_rate")]
    pub earth_rate_rad_s: f64,
    /// Calibration rates, deg/s: at least seven distinct (six unknowns and a residual degree
    /// of freedom).
    pub rates_deg_s: Vec<f64>,
    /// Standard deviation of the noise added to each per-rate mean output, rad/s (default 0:
    /// noise-free).
    #[serde(default)]
    pub output_noise_rad_s: f64,
    /// Seed of the output noise.
    #[serde(default)]
    pub seed: u64,
}

const fn default_latitude() -> f64 {
    45.0
}

const fn default_earth_rate() -> f64 {
    kinematics::EARTH_RATE_RAD_S
}

impl StudyConfig {
    /// Parses RON text into the file's data-transfer types, unvalidated; `path` only names the
    /// source in errors, which name the configuration's own keys (`calibration.table`), never
    /// a type of this crate. Optional sections are written without `Some(...)`.
    pub fn from_ron(text: &str, path: &Path) -> Result<Self> {
        edge_io::from_ron(text, path).map_err(parse_error)
    }
}

/// A RON parser's error as the configuration's own words, located in `path`.
pub(crate) fn parse_error(e: edge_io::RonError) -> PipelineError {
    PipelineError::Parse {
        message: parse_message(&e.code),
        path: e.path,
        line: e.line,
        column: e.column,
    }
}

/// A section of the study file written under a former name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeprecatedKey {
    /// The name written.
    pub old: &'static str,
    /// The name it now has.
    pub new: &'static str,
}

/// The configuration key a data-transfer type of the study file stands for, as a person
/// writes it (`calibration.table`); `None` for the top level.
fn config_key(type_name: &str) -> Option<&'static str> {
    Some(match type_name {
        "StudyConfig" => return None,
        "LeverConfig" => "lever",
        "ProbeDirectionName" => "lever.probe_direction (or balance.second_probe.probe_direction)",
        "RadiusModelName" => "radius_model",
        "PhaseConfig" => "phases[…]",
        "Weighting" => "phases[…].weighting",
        "Points" => "phases[…].points",
        "HarmonicPoint" => "phases[…].points (first_harmonic)",
        "RadiusPoint" => "phases[…].points (radius_error)",
        "RecordingSet" => "phases[…].points (recordings)",
        "RecordingPoint" => {
            "phases[…].points.files[…] (or calibration.recordings.files[…], \
             two_orientation.orientations[…].recordings.files[…])"
        }
        "FitSettings" => "phases[…].points.fit",
        "MechanismConfig" => "mechanism",
        "CalibrationConfig" => "calibration",
        "PigaTableConfig" => "calibration.table (or two_orientation.orientations[…].table)",
        "OutputSigma" => {
            "calibration.table.output_sigma_rad_s (or \
             two_orientation.orientations[…].table.output_sigma_rad_s)"
        }
        "PigaRecordingSet" => {
            "calibration.recordings (or two_orientation.orientations[…].recordings)"
        }
        "K1Config" => "calibration.k1",
        "TrialsConfig" => "calibration.trials (or two_orientation.trials)",
        "UncertaintyConfig" => "uncertainty",
        "BalanceConfig" => "balance",
        "TrialMassConfig" => "balance.trial_mass (or balance.two_plane.trial_mass)",
        "SecondProbeConfig" => "balance.second_probe",
        "TwoPlaneConfig" => "balance.two_plane",
        "CounterweightConfig" => "counterweight",
        "RecordingFormat" | "PigaRecordingFormat" => "format",
        "PigaTableFormat" => "calibration.table.format",
        "CertificateConfig" => "certificate",
        "LaboratoryConfig" => "certificate.laboratory",
        "PartyConfig" => "certificate.customer",
        "ItemConfig" => "certificate.item",
        "EquipmentConfig" => "certificate.equipment[…]",
        "DatesConfig" => "certificate.dates",
        "ConditionConfig" => "certificate.conditions[…]",
        "TraceabilityConfig" => "certificate.traceability[…]",
        "TypeBInputName" => "certificate.traceability[…].input",
        "LimitConfig" => "certificate.limits[…]",
        "CoefficientName" => "certificate.limits[…].coefficient",
        "LimitUnitName" => "certificate.limits[…].unit",
        "DecisionRuleName" => "certificate.decision_rule",
        "CertifyName" => "certificate.certify",
        "AuthorisationConfig" => "certificate.authorisation",
        "TwoOrientationConfig" => "two_orientation",
        "UnitConfig" => "units[…]",
        // the lab profile (lab.ron)
        "ProfileConfig" => return None,
        "ProfileLaboratory" => "laboratory",
        "PersonConfig" => "signatories[…]",
        "InstrumentConfig" => "daqs[…]",
        "CentrifugeConfig" => "centrifuges[…]",
        "ProfileLever" => "centrifuges[…].lever",
        "CentrifugeTraceability" => "centrifuges[…].traceability",
        "ProbeConfig" => "probes[…]",
        "GravityConfig" => "gravity",
        "OrientationConfig" => "two_orientation.orientations[…]",
        "OrientationName" => "two_orientation.orientations[…].orientation",
        _ => "this section",
    })
}

/// `in `key``, or nothing at the top level.
fn in_key(outer: Option<&String>) -> String {
    match outer.and_then(|o| config_key(o)) {
        Some(key) => format!(" in `{key}`"),
        None if outer.is_none() => String::new(),
        None => " at the top level".to_owned(),
    }
}

/// `one of `a`, `b``.
fn one_of(names: &[&str]) -> String {
    match names {
        [] => "none".to_owned(),
        [one] => format!("`{one}`"),
        _ => format!(
            "one of {}",
            names
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The parser's error in the configuration's words: the keys it concerns, not the types
/// that read them.
fn parse_message(code: &ron::Error) -> String {
    use ron::Error as E;
    match code {
        E::NoSuchStructField {
            expected,
            found,
            outer,
        } => format!(
            "unknown field `{found}`{}; expected {}",
            in_key(outer.as_ref()),
            one_of(expected)
        ),
        E::MissingStructField { field, outer } => {
            format!("missing field `{field}`{}", in_key(outer.as_ref()))
        }
        E::DuplicateStructField { field, outer } => {
            format!("field `{field}` given twice{}", in_key(outer.as_ref()))
        }
        E::NoSuchEnumVariant { found, outer, .. }
            if outer.as_deref() == Some("ProbeDirectionName") =>
        {
            format!(
                "unknown choice `{found}`{}; expected `against_o1_x1` (also written \
             `reading_falls_towards_piga`: {}) or `along_o1_x1` (also written \
             `reading_rises_towards_piga`: {})",
                in_key(outer.as_ref()),
                ProbeDirectionName::AgainstO1X1.words(),
                ProbeDirectionName::AlongO1X1.words(),
            )
        }
        E::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => format!(
            "unknown choice `{found}`{}; expected {}",
            in_key(outer.as_ref()),
            one_of(expected)
        ),
        E::ExpectedDifferentStructName { expected, found } => format!(
            "`{found}(…)` where `{}` is expected: write the section as `(…)`",
            config_key(expected).unwrap_or("the study")
        ),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(text: &str) -> String {
        match StudyConfig::from_ron(text, Path::new("s.ron")) {
            Err(PipelineError::Parse { message, .. }) => message,
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn parse_errors_name_the_configuration_keys_not_rust_types() {
        let m = message(
            "(name: \"x\", radius_m: 1.0, g_m_s2: 9.8, k1_rad_s_g: 1.0, lever: (pivot_to_probe_mm: 1.0, probe_to_piga_mm: 1.0), phases: [], uncertainty: (radius_u_mm: 1.0))",
        );
        assert!(
            m.contains("`radius_u_mm`") && m.contains("in `uncertainty`"),
            "{m}"
        );
        assert!(!m.contains("UncertaintyConfig"), "{m}");
        let m = message(
            "(name: \"x\", radius_m: 1.0, g_m_s2: 9.8, k1_rad_s_g: 1.0, lever: (pivot_to_probe_mm: 1.0, probe_to_piga_mm: 1.0), phases: [], calibration: (compensate_with: \"a\", table: (rate_column: \"r\", output_column: \"y\")))",
        );
        assert!(
            m.contains(
                "missing field `file` in `calibration.table (or two_orientation.orientations[…].table)`"
            ),
            "{m}"
        );
        assert!(!m.contains("PigaTableConfig"), "{m}");
        let m = message(
            "(name: \"x\", radius_m: 1.0, g_m_s2: 9.8, k1_rad_s_g: 1.0, lever: (pivot_to_probe_mm: 1.0, probe_to_piga_mm: 1.0), radius_model: four_term, phases: [])",
        );
        assert!(m.contains("`four_term` in `radius_model`"), "{m}");
        assert!(!m.contains("RadiusModelName"), "{m}");
    }

    /// A probe direction the file misnames is answered with both names of each choice and
    /// the words a person checks at the machine; the self-describing names are read.
    #[test]
    fn a_bad_probe_direction_is_answered_in_words() {
        let study = |direction: &str| {
            format!(
                "(name: \"x\", radius_m: 1.0, g_m_s2: 9.8, k1_rad_s_g: 1.0, lever: \
                 (pivot_to_probe_mm: 1.0, probe_to_piga_mm: 1.0, probe_direction: {direction}), \
                 phases: [])"
            )
        };
        let m = message(&study("towards_the_probe"));
        assert_eq!(
            m,
            "unknown choice `towards_the_probe` in `lever.probe_direction (or \
             balance.second_probe.probe_direction)`; expected `against_o1_x1` (also written \
             `reading_falls_towards_piga`: the probe's gap closes (its reading falls) when the \
             spindle moves towards the PIGA (probe measuring against O1X1, the paper's set-up)) \
             or `along_o1_x1` (also written `reading_rises_towards_piga`: the probe's reading \
             rises when the spindle moves towards the PIGA (probe measuring along O1X1))"
        );
        for (name, direction) in [
            (
                "reading_falls_towards_piga",
                ProbeDirectionName::AgainstO1X1,
            ),
            ("reading_rises_towards_piga", ProbeDirectionName::AlongO1X1),
        ] {
            let config = StudyConfig::from_ron(&study(name), Path::new("s.ron")).unwrap();
            assert_eq!(config.lever.probe_direction, Some(direction));
        }
    }
}
