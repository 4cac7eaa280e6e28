//! The crate's error type.

use std::path::PathBuf;

/// Errors of reading, validating, running and writing a simulation scenario.
///
/// Every variant names the file it concerns and, where it applies, the field (as a path such
/// as `rates_deg_s[2]`) or the line and column.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimulateError {
    /// The scenario could not be read (or is too large, or not UTF-8), or an output could not
    /// be written or moved into place.
    #[error(transparent)]
    File(#[from] edge_io::EdgeIoError),
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
        reason: &'static str,
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
    /// (the file name keeps four decimals of the rate).
    #[error("{}: field `{field}`: rate {rate_deg_s_c} deg/s and rate {first_rate_deg_s_c} deg/s (`{first}`) would both be recorded as `{file_name}`", path.display(), rate_deg_s_c = units::Compact(*rate_deg_s), first_rate_deg_s_c = units::Compact(*first_rate_deg_s))]
    RecordingNameCollision {
        /// The file concerned.
        path: PathBuf,
        /// Path of the second rate.
        field: String,
        /// Path of the first rate.
        first: String,
        /// The second rate.
        rate_deg_s: f64,
        /// The first rate.
        first_rate_deg_s: f64,
        /// The file name they share.
        file_name: String,
    },
    /// one revolution needs.
    #[error("{}: field `{field}` = {rate_deg_s_c} deg/s: a revolution would hold {samples_per_revolution_c} samples at the probe's sample rate, the harmonic fit needs at least {need} (rate at most {max_rate_deg_s_c} deg/s)", path.display(), rate_deg_s_c = units::Compact(*rate_deg_s), samples_per_revolution_c = units::Compact(*samples_per_revolution), max_rate_deg_s_c = units::Compact(*max_rate_deg_s))]
    RateTooFast {
        /// The file concerned.
        path: PathBuf,
        /// Path of the rate.
        field: String,
        /// The rate given.
        rate_deg_s: f64,
        /// Samples in one revolution at this rate (`sample_rate_hz·360/rate_deg_s`).
        samples_per_revolution: f64,
        /// Samples a revolution needs.
        need: usize,
        /// The fastest rate that gives them.
        max_rate_deg_s: f64,
    },
    /// The least-squares identification failed.
    #[error("{}: `{field}`: {source}", path.display())]
    Identify {
        /// The file concerned.
        path: PathBuf,
        /// The section whose fit failed.
        field: String,
        /// The solver's error.
        source: identify::IdentifyError,
    },
    /// The harmonic geometry was refused.
    #[error("{}: `{field}`: {source}", path.display())]
    Harmonics {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The harmonic analysis' error.
        source: harmonics::HarmonicsError,
    },
    /// Results could not be serialised.
    #[error("serialising {what}: {message}")]
    Serialize {
        /// What was being serialised.
        what: &'static str,
        /// The serialiser's message.
        message: String,
    },
    /// A number of an output is not finite: the file is not written (JSON would hold `null`
    /// where a number belongs).
    #[error("{what}: `{field}` is not finite ({value_c}); nothing was written", value_c = units::Compact(*value))]
    NonFiniteOutput {
        /// The output file (`results.json`, `truth.json`, `piga.csv`).
        what: &'static str,
        /// The path of the value in the output (`phases[0].delta_k2.delta_k2_rad_s_g2`).
        field: String,
        /// The value (NaN or ±∞).
        value: f64,
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
    #[error("{}: `{field}`: {source}", path.display())]
    Kinematics {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The chain's error.
        source: kinematics::KinematicsError,
    },
    /// The PIGA model was refused.
    #[error("{}: `{field}`: {source}", path.display())]
    AccelModel {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The PIGA model's error.
        source: accel_model::AccelModelError,
    },
    /// A multi-mounting campaign (held in memory) was refused by the model.
    #[error("{field}: {source}")]
    Campaign {
        /// The field concerned (`mountings[2]`, `rates[4]`).
        field: String,
        /// The model's error.
        source: accel_model::AccelModelError,
    },
}

impl SimulateError {
    /// The error of [`edge_io::to_json_pretty`] for the output `what`.
    pub(crate) fn json(what: &'static str, e: edge_io::JsonError) -> Self {
        e.into_error(
            |field, value| Self::NonFiniteOutput { what, field, value },
            |message| Self::Serialize { what, message },
        )
    }
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, SimulateError>;
