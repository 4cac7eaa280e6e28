//! The crate's error type.

use std::path::PathBuf;

/// Errors of loading, validating and running a study.
///
/// Every variant names the file it concerns and, where it applies, the field (as a path such
/// as `post_balance.points[2].rate_deg_s`) or the line and column.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// The RON text is malformed, has an unknown field or lacks a required one.
    #[error("{}:{line}:{column}: {message}", path.display())]
    Parse {
        /// The file concerned.
        path: PathBuf,
        /// 1-based line of the error.
        line: usize,
        /// 1-based column of the error.
        column: usize,
        /// What the parser said.
        message: String,
    },
    /// A field has a value outside its domain.
    #[error("{}: field `{field}` = {value_c}: {reason}", path.display(), value_c = units::Compact(*value))]
    InvalidField {
        /// The file concerned.
        path: PathBuf,
        /// Path of the field within the configuration.
        field: String,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        reason: InvalidReason,
    },
    /// Two points of one phase share a rate.
    #[error("{}: field `{field}`: rate {rate_deg_s_c} deg/s appears twice (first at `{first}`)", path.display(), rate_deg_s_c = units::Compact(*rate_deg_s))]
    DuplicateRate {
        /// The file concerned.
        path: PathBuf,
        /// Path of the second occurrence.
        field: String,
        /// Path of the first occurrence.
        first: String,
        /// The repeated rate.
        rate_deg_s: f64,
    },
    /// One recording listed twice in a phase (the same file, or the same bytes under two
    /// names): one recording cannot be two rate points.
    #[error(
        "{}: field `{field}`: {} is the same recording as `{first}` ({}): one recording \
         cannot be two rate points; name the recording of each rate",
        path.display(),
        file.display(),
        if *same_bytes { "the same bytes" } else { "the same file" }
    )]
    SameRecording {
        /// The file concerned (the configuration).
        path: PathBuf,
        /// Path of the second occurrence.
        field: String,
        /// Path of the first occurrence.
        first: String,
        /// The recording.
        file: PathBuf,
        /// Whether they are two files with the same bytes (else one file named twice).
        same_bytes: bool,
    },
    /// A phase has too few rate points for its radius-error model: a fit needs one more point
    /// than the model has unknowns, to have a standard error.
    #[error("{}: field `{field}`: {got} rate point(s), the {model} model needs at least {need} (one more than its unknowns)", path.display())]
    TooFewPoints {
        /// The file concerned.
        path: PathBuf,
        /// Path of the list.
        field: String,
        /// Number of points given.
        got: usize,
        /// Number of points needed.
        need: usize,
        /// The model's name.
        model: &'static str,
    },
    /// A result of the study is not finite although every input was: the configuration's
    /// numbers take it out of the range of double precision. Nothing is written.
    #[error("{}: result `{field}` is not finite ({value}): the study's inputs take it out of the range of double precision", path.display())]
    NonFiniteResult {
        /// The configuration file.
        path: PathBuf,
        /// The result's path in `results.json` (`phases[0].delta_k2.delta_k2_rad_s_g2`).
        field: String,
        /// The value computed.
        value: f64,
    },
    /// The least-squares identification failed.
    #[error("{}: `{field}`", path.display())]
    Identify {
        /// The file concerned.
        path: PathBuf,
        /// The section whose fit failed.
        field: String,
        /// The solver's error.
        source: identify::IdentifyError,
    },
    /// The calibration refused its points (`calibration::check_points`).
    #[error("{}: `{field}`", path.display())]
    Calibration {
        /// The file concerned.
        path: PathBuf,
        /// The section whose points were refused.
        field: String,
        /// The calibration's error.
        source: ::calibration::CalibrationError,
    },
    /// The uncertainty evaluation failed.
    #[error("{}: `{field}`", path.display())]
    Uncertainty {
        /// The file concerned.
        path: PathBuf,
        /// The section.
        field: String,
        /// The evaluation's error (boxed: it is large).
        source: Box<uncertainty::UncertaintyError>,
    },
    /// The balance advisor refused its input (e.g. a singular influence coefficient).
    #[error("{}: `{field}`", path.display())]
    Balance {
        /// The file concerned.
        path: PathBuf,
        /// The section.
        field: String,
        /// The advisor's error (boxed: it is large).
        source: Box<balance::BalanceError>,
    },
    /// The harmonic geometry was refused.
    #[error("{}: `{field}`", path.display())]
    Harmonics {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The harmonic analysis' error.
        source: harmonics::HarmonicsError,
    },
    /// A list that must not be empty is empty.
    #[error("{}: field `{field}`: the list is empty", path.display())]
    EmptyList {
        /// The file concerned.
        path: PathBuf,
        /// Path of the list.
        field: String,
    },
    /// The kinematic chain (or the error motion it is built from) was refused.
    #[error("{}: `{field}`", path.display())]
    Kinematics {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The chain's error.
        source: kinematics::KinematicsError,
    },
    /// The PIGA model was refused.
    #[error("{}: `{field}`", path.display())]
    AccelModel {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The PIGA model's error.
        source: accel_model::AccelModelError,
    },
    /// A probe recording named by the configuration could not be read or analyzed.
    #[error("{}: `{field}`", path.display())]
    Recording {
        /// The configuration file.
        path: PathBuf,
        /// The field naming the recording.
        field: String,
        /// The recording's own error (it names the recording's file and line); boxed, as it
        /// is large.
        source: Box<recording::RecordingError>,
    },
    /// A setting cannot be used with the rest of the configuration or data.
    #[error("{}: field `{field}`: {reason}", path.display())]
    Unsupported {
        /// The configuration file.
        path: PathBuf,
        /// The setting.
        field: String,
        /// Why it cannot be used.
        reason: UnsupportedReason,
    },
    /// A value in a data table is outside its domain.
    #[error("{}: `{field}`: {}:{line}: {column} = {value}: {reason}", path.display(), file.display())]
    TableValue {
        /// The configuration file.
        path: PathBuf,
        /// The field naming the table.
        field: String,
        /// The table file.
        file: PathBuf,
        /// The line of the value.
        line: usize,
        /// The column.
        column: String,
        /// The value.
        value: f64,
        /// What is wrong with it.
        reason: InvalidReason,
    },
    /// A PIGA table row whose rate has no entry in `output_sigma_rad_s: per_rate(...)`.
    #[error(
        "{}: `{field}`: {}:{line}: rate {rate} deg/s has no standard uncertainty in `per_rate` \
         (rates listed: {listed_text}) (hint: add `({rate}, σ)` to `per_rate`, or give one σ for \
         every row with `constant(σ)`)",
        path.display(),
        file.display(),
        rate = units::Compact(*rate_deg_s),
        listed_text = listed.iter().map(|r| units::Compact(*r).to_string()).collect::<Vec<_>>().join(", ")
    )]
    RateWithoutSigma {
        /// The configuration file.
        path: PathBuf,
        /// The field stating the output noise (`calibration.table.output_sigma_rad_s`).
        field: String,
        /// The table file.
        file: PathBuf,
        /// The row's line.
        line: usize,
        /// The row's rate, deg/s.
        rate_deg_s: f64,
        /// The rates `per_rate` lists, deg/s.
        listed: Vec<f64>,
    },
    /// A calibration table has too few distinct rates for the eq. 18 design.
    #[error("{}: `{field}`: {} has {distinct} distinct rate(s); the eq. 18 calibration needs at least {need} (six unknowns and one degree of freedom)", path.display(), file.display())]
    TooFewRates {
        /// The configuration file.
        path: PathBuf,
        /// The field naming the table.
        field: String,
        /// The table file.
        file: PathBuf,
        /// Distinct rates found.
        distinct: usize,
        /// Distinct rates needed.
        need: usize,
    },
    /// Two items of a list share a name.
    #[error("{}: field `{field}`: the name `{name}` is already used at `{first}`", path.display())]
    DuplicateName {
        /// The file concerned.
        path: PathBuf,
        /// Path of the second occurrence.
        field: String,
        /// Path of the first occurrence.
        first: String,
        /// The repeated name.
        name: String,
    },
    /// A name is empty or has characters other than letters, digits, `_` and `-`.
    #[error("{}: field `{field}`: `{name}` is not a valid name (letters, digits, `_` and `-`, at most 64)", path.display())]
    InvalidName {
        /// The file concerned.
        path: PathBuf,
        /// Path of the name.
        field: String,
        /// The name given.
        name: String,
    },
    /// A reference to a phase that the study does not have.
    #[error("{}: field `{field}`: no phase is named `{name}` (the study's phases: {})", path.display(), known.join(", "))]
    UnknownPhase {
        /// The file concerned.
        path: PathBuf,
        /// Path of the reference.
        field: String,
        /// The name given.
        name: String,
        /// The phases the study has.
        known: Vec<String>,
    },
    /// A required field is missing or blank.
    #[error("{}: field `{field}` is required: {hint}", path.display())]
    MissingField {
        /// The file concerned.
        path: PathBuf,
        /// Path of the field.
        field: String,
        /// What it is for, or how to fill it in.
        hint: String,
    },
    /// One quantity stated in two places.
    #[error("{}: field `{field}` states {what}, and so does `{other}`: state it once", path.display())]
    StatedTwice {
        /// The file concerned.
        path: PathBuf,
        /// The one field.
        field: String,
        /// The other.
        other: String,
        /// The quantity, in words.
        what: &'static str,
    },
    /// A key of a map that names nothing the map can be about.
    #[error("{}: field `{field}`: `{key}` is not one of {}", path.display(), known.join(", "))]
    UnknownKey {
        /// The file concerned.
        path: PathBuf,
        /// The map.
        field: String,
        /// The key given.
        key: String,
        /// The keys it may have.
        known: Vec<String>,
    },
    /// A date that is not written `YYYY-MM-DD` (ISO 8601), or a day that does not exist.
    #[error("{}: field `{field}` = {value:?}: not a date written YYYY-MM-DD (hint: {hint})", path.display())]
    InvalidDate {
        /// The file concerned.
        path: PathBuf,
        /// Path of the field.
        field: String,
        /// The text given.
        value: String,
        /// The same date written as asked, when it can be told.
        hint: String,
    },
    /// A study names a lab profile that was not read with it (built from values without its
    /// profile: [`crate::Inputs::with_profile`] takes it).
    #[error("{}: field `profile` names {}, which was not read with the study (read the study with `load_study` or `parse_study`, or pass the profile to `Inputs::with_profile`)", path.display(), profile.display())]
    ProfileNotRead {
        /// The study file.
        path: PathBuf,
        /// The profile it names.
        profile: PathBuf,
    },
    /// A text field holds a character that hides, reorders or acts instead of showing (a
    /// control character or a bidirectional override).
    #[error("{}: field `{field}` holds the character {hidden}: text that a report or certificate shows must show what it says (control characters and bidirectional overrides can hide, reorder or act on it); write it on one line without them", path.display())]
    HiddenCharacter {
        /// The file concerned.
        path: PathBuf,
        /// The field.
        field: String,
        /// The character and where it is.
        hidden: edge_io::HiddenChar,
    },
    /// A stated standard uncertainty as large as the quantity it is the uncertainty of.
    #[error("{}: field `{field}` = {u_c}: a standard uncertainty as large as the quantity itself (`{quantity_field}` = {quantity_c} {unit}) cannot be meant; check its unit ({unit})", path.display(), u_c = units::Compact(*u), quantity_c = units::Compact(*quantity))]
    ImplausibleUncertainty {
        /// The file concerned.
        path: PathBuf,
        /// The uncertainty's field.
        field: String,
        /// The uncertainty given.
        u: f64,
        /// The quantity's field (or what it is).
        quantity_field: String,
        /// The quantity's value.
        quantity: f64,
        /// The unit both are in.
        unit: &'static str,
    },
    /// A certificate would certify a value that the study's own check refutes.
    #[error("{}: field `certificate.certify`: {message}", path.display())]
    CertifiesRefutedValue {
        /// The configuration file.
        path: PathBuf,
        /// What would be certified and what refutes it, with the way out.
        message: String,
    },
    /// A stated 95 % coverage interval that cannot be stated: it does not contain its
    /// estimate, has zero width while the standard uncertainty is not zero, or is not
    /// finite.
    #[error("{}: {}", path.display(), interval)]
    DegenerateInterval {
        /// The configuration file.
        path: PathBuf,
        /// The quantity, its interval and what is wrong with it.
        interval: Box<DegenerateInterval>,
    },
    /// A study file could not be read: missing, too large, or not UTF-8 text.
    #[error(transparent)]
    File(#[from] edge_io::EdgeIoError),
    /// The two-orientation calibration refuses its data sets or its fit (the source names the
    /// field, `two_orientation.orientations[1].radius_m`).
    #[error("{}", path.display())]
    TwoOrientation {
        /// The configuration file.
        path: PathBuf,
        /// What is wrong.
        source: Box<calibration::TwoOrientationError>,
    },
    /// The joint fit over several mountings refuses its declaration, data or design (the
    /// source names the field, or the terms the mountings cannot separate and the mounting
    /// that would).
    #[error("{}: the mountings section", path.display())]
    Mountings {
        /// The configuration file.
        path: PathBuf,
        /// What is wrong.
        source: Box<calibration::MountingsError>,
    },
    /// A field of the mountings section that cannot be used, with what is wrong in words.
    #[error("{}: field `{field}`: {problem}", path.display())]
    InvalidMountings {
        /// The configuration file.
        path: PathBuf,
        /// The field.
        field: String,
        /// What is wrong, and what to write instead.
        problem: String,
    },
    /// A top-level section that a several-unit study takes from each unit.
    #[error("{}: field `{field}` is given beside `units`: {hint}", path.display())]
    BesideUnits {
        /// The configuration file.
        path: PathBuf,
        /// The top-level section.
        field: String,
        /// What to do instead, in words.
        hint: &'static str,
    },
    /// A value that must differ between the items of a list (a unit's certificate
    /// identification).
    #[error("{}: field `{field}` = {value:?}: {what} is already used at `{first}`", path.display())]
    UsedTwice {
        /// The configuration file.
        path: PathBuf,
        /// The second occurrence.
        field: String,
        /// The first occurrence.
        first: String,
        /// The value.
        value: String,
        /// What it is, in words.
        what: &'static str,
    },
    /// Several errors, each complete, in the configuration's order.
    #[error("{} errors:{}", errors.len(), list(errors))]
    Several {
        /// The errors.
        errors: Vec<PipelineError>,
    },
}

/// Why a field's value is outside its domain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidReason {
    /// The value must be finite.
    #[error("must be finite")]
    NotFinite,
    /// The value must be finite and positive.
    #[error("must be finite and > 0")]
    NotPositive,
    /// The value must be finite and not negative.
    #[error("must be finite and ≥ 0")]
    Negative,
    /// A rate must be finite and positive.
    #[error("a rate must be finite and > 0")]
    RateNotPositive,
    /// A local gravity off the Earth's surface.
    #[error(
        "must lie within {}…{} m/s² (the Earth's surface gravity: 9.780 at the equator to \
         9.832 at the poles, less with altitude); a value in g or another unit is an error",
        units::Compact(*units::GRAVITY_RANGE_M_S2.start()),
        units::Compact(*units::GRAVITY_RANGE_M_S2.end())
    )]
    GravityImplausible,
    /// Too few Monte Carlo trials for a 95 % interval.
    #[error("must be at least 2000 (JCGM 101 §7.2: 100/(1 − p) for p = 95 %)")]
    TooFewTrials,
    /// A latitude must be finite and within ±90°.
    #[error("must be finite and within ±90")]
    NotALatitude,
    /// A standard uncertainty given with a value must be finite and positive.
    #[error(
        "a standard uncertainty must be finite and > 0 (a σ of 0 would give the row infinite weight)"
    )]
    SigmaNotPositive,
    /// A standard uncertainty outside what the fit can weight by.
    #[error(
        "a standard uncertainty must lie in [1e-150, 1e150] rad/s (its weight 1/σ² and σ² \
         itself must be numbers the fit can hold; a point this uncertain carries no \
         information: leave it out)"
    )]
    SigmaOutOfRange,
    /// A harmonic order outside 1 to 8.
    #[error("must be 1 to 8")]
    HarmonicOrder,
}

impl InvalidReason {
    /// Why the calibration refused a value of a point (`calibration::check_points`), in the
    /// words of a table's value: the one mapping the study and `centrifuge-cal identify`
    /// share.
    #[must_use]
    pub fn of_point(point: &::calibration::BadPoint) -> Self {
        use ::calibration::PointValue;
        match point.what {
            PointValue::Rate => Self::RateNotPositive,
            PointValue::Output => Self::NotFinite,
            PointValue::Sigma if point.value.is_finite() && point.value > 0.0 => {
                Self::SigmaOutOfRange
            }
            PointValue::Sigma => Self::SigmaNotPositive,
        }
    }
}

/// Why a setting cannot be used with the rest of the configuration or data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum UnsupportedReason {
    /// Inverse-variance weighting needs each point's σ, which recordings give and
    /// first-harmonic points may (`sigma_um`).
    #[error(
        "inverse_variance weighting needs points given as recordings, or first_harmonic points each with sigma_um"
    )]
    WeightingNeedsRecordings,
    /// A recording's harmonic fit left no residual, so it has no σ to weigh it by.
    #[error(
        "inverse_variance weighting needs a standard error for every recording, and this one's \
         harmonic fit has no residual (noise-free data?)"
    )]
    NoStandardError,
    /// The balance advisor needs each point's first harmonic (`d_c1`, `d_s1`), which only
    /// first-harmonic points and recordings give.
    #[error("the balance advisor needs a phase given as first_harmonic points or recordings")]
    BalanceNeedsFirstHarmonic,
    /// A trial phase without its trial mass, or a trial mass without its phase.
    #[error("`trial` and `trial_mass` go together: give both or neither")]
    TrialNeedsTrialMass,
    /// A stiffness without its provenance.
    #[error(
        "say where the stiffness comes from (`stiffness_source`: a bearing datasheet, a static test, an assumption): the mass scales with it"
    )]
    StiffnessNeedsSource,
    /// A trial mass whose height is not its correction plane's.
    #[error(
        "a trial mass goes in its correction plane: its `height_m` must equal that plane's in `two_plane.heights_m` (or be left out)"
    )]
    TrialOutOfPlane,
    /// A second probe's phase that is also read with the first probe.
    #[error(
        "the second probe's phase must be another phase than those the advisor reads with the first probe (`initial`, `trial`, `check`, `two_plane.trial`)"
    )]
    SecondProbePhaseIsFirst,
    /// A phase measured by the second probe, used where a phase of the first probe's lever is
    /// needed.
    #[error(
        "this phase holds the second probe's data (`balance.second_probe.phases`): its C_r is read with the first probe's lever and direction, so it cannot compensate or be simulated"
    )]
    SecondProbeData,
    /// A calibration with both or neither of a table and raw recordings.
    #[error("give exactly one of `table` and `recordings`")]
    CalibrationNeedsOneSource,
    /// Neither a trial run nor a stiffness: no correction can be computed.
    #[error(
        "give `trial` with `trial_mass` (influence coefficient) or `radial_stiffness_n_m` (stiffness model)"
    )]
    BalanceNeedsMethod,
    /// A run the advisor uses has no phase of the second probe.
    #[error(
        "with a second probe, every phase the advisor uses needs its second-probe phase in `balance.second_probe.phases`"
    )]
    SecondProbeNeedsPhase,
    /// The second probe at the first probe's height sees the same line point.
    #[error("the second probe must be at another height than the first (`lever.probe_to_piga_mm`)")]
    SecondProbeAtFirstHeight,
    /// A two-plane correction without the second probe that separates translation and tilt.
    #[error(
        "`two_plane` needs `second_probe`: one probe plane cannot separate translation from tilt"
    )]
    TwoPlaneNeedsSecondProbe,
    /// A two-plane correction with neither a second trial run nor both stiffnesses.
    #[error(
        "give `two_plane.trial` with `two_plane.trial_mass` and the balance section's `trial` (influence coefficients), or `radial_stiffness_n_m` with `angular_stiffness_n_m_rad` (stiffness model)"
    )]
    TwoPlaneNeedsMethod,
    /// Correction planes A and B at one height.
    #[error("the two correction planes must be at different heights")]
    PlanesAtOneHeight,
    /// A PIGA table's columns named both in its `format` block and beside it.
    #[error(
        "with a `format` block, name the columns and the delimiter in it (`rate`, `output`, `sigma`, `label`, `delimiter`), not beside it (`rate_column`, `output_column`, `sigma_column`, `label_column`, `delimiter`)"
    )]
    TableFormatAndColumns,
    /// A certificate states a calibration's results.
    #[error("a certificate needs a `calibration` section: it states the calibration's results")]
    CertificateNeedsCalibration,
    /// A previous certificate's digest that is not a SHA-256.
    #[error(
        "must be the SHA-256 of the previous certificate's file: 64 hexadecimal digits (as `sha256sum` prints them)"
    )]
    NotSha256,
    /// A country that is not an ISO 3166-1 alpha-2 code.
    #[error("must be a country code of ISO 3166-1: two capital letters (`DE`, `GB`, `US`)")]
    NotCountryCode,
    /// The counterweight section reads one published change of radius error.
    #[error("the counterweight section needs a phase given as radius_change")]
    CounterweightNeedsRadiusChange,
}

impl PipelineError {
    /// `Ok` for no error, the error itself for one, [`PipelineError::Several`] for more.
    pub(crate) fn from_list(errors: Vec<Self>) -> Result<()> {
        // a list of lists is one list: every problem at the same level, in order
        let mut errors: Vec<Self> = errors
            .into_iter()
            .flat_map(|e| match e {
                Self::Several { errors } => errors,
                e => vec![e],
            })
            .collect();
        match errors.len() {
            0 => Ok(()),
            1 => Err(errors.remove(0)),
            _ => Err(Self::Several { errors }),
        }
    }
}

impl PipelineError {
    /// The error of unit `index`'s single-unit study as the several-unit study's file names
    /// it: a field that is the unit's own (`calibration…`, `certificate…`, `two_orientation…`,
    /// `k1_rad_s_g`, `radius_m`) becomes `units[index].…`; a shared field keeps its name.
    #[must_use]
    pub(crate) fn in_unit(self, index: usize) -> Self {
        let own = |field: &mut String| {
            let is_own = ["calibration", "certificate", "two_orientation"]
                .iter()
                .any(|k| {
                    field.strip_prefix(k).is_some_and(|rest| {
                        rest.is_empty() || rest.starts_with('.') || rest.starts_with('[')
                    })
                })
                || field == "k1_rad_s_g"
                || field == "radius_m";
            if is_own {
                *field = format!("units[{index}].{field}");
            }
        };
        let mut e = self;
        match &mut e {
            Self::Several { errors } => {
                let errors = std::mem::take(errors);
                return Self::Several {
                    errors: errors.into_iter().map(|e| e.in_unit(index)).collect(),
                };
            }
            Self::DuplicateName { field, first, .. } | Self::UsedTwice { field, first, .. } => {
                own(field);
                own(first);
            }
            Self::StatedTwice { field, other, .. } => {
                own(field);
                own(other);
            }
            Self::InvalidField { field, .. }
            | Self::DuplicateRate { field, .. }
            | Self::SameRecording { field, .. }
            | Self::TooFewPoints { field, .. }
            | Self::NonFiniteResult { field, .. }
            | Self::Identify { field, .. }
            | Self::Calibration { field, .. }
            | Self::Uncertainty { field, .. }
            | Self::Balance { field, .. }
            | Self::Harmonics { field, .. }
            | Self::EmptyList { field, .. }
            | Self::Kinematics { field, .. }
            | Self::AccelModel { field, .. }
            | Self::Recording { field, .. }
            | Self::Unsupported { field, .. }
            | Self::TableValue { field, .. }
            | Self::RateWithoutSigma { field, .. }
            | Self::TooFewRates { field, .. }
            | Self::InvalidName { field, .. }
            | Self::UnknownPhase { field, .. }
            | Self::MissingField { field, .. }
            | Self::UnknownKey { field, .. }
            | Self::InvalidDate { field, .. }
            | Self::HiddenCharacter { field, .. }
            | Self::ImplausibleUncertainty { field, .. }
            | Self::InvalidMountings { field, .. }
            | Self::BesideUnits { field, .. } => own(field),
            _ => {}
        }
        e
    }
}

/// The errors of a list, in the configuration's order, one per line.
fn list(errors: &[PipelineError]) -> String {
    let mut out = String::new();
    for e in errors {
        out.push_str("\n  ");
        out.push_str(&units::ErrorChain(e).to_string());
    }
    out
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, PipelineError>;

/// A 95 % coverage interval that cannot be stated ([`PipelineError::DegenerateInterval`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{quantity}: its 95 % coverage interval [{low_c}, {high_c}] {problem} (estimate {value_c}, u = {u_c}); the largest contribution to its uncertainty is {dominant}: check that input's stated uncertainty", low_c = units::Compact(*low), high_c = units::Compact(*high), value_c = units::Compact(*value), u_c = units::Compact(*u))]
pub struct DegenerateInterval {
    /// The quantity (`k1 of the calibration`).
    pub quantity: String,
    /// The estimate.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Lower end.
    pub low: f64,
    /// Upper end.
    pub high: f64,
    /// What is wrong with it, in words.
    pub problem: &'static str,
    /// The input whose uncertainty contributes most, with the field that states it where
    /// known.
    pub dominant: String,
}
