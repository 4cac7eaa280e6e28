//! The crate's error type.

use std::path::PathBuf;

/// Errors of loading, validating and running a study.
///
/// Every variant names the file it concerns and, where it applies, the field (as a path such
/// as `post_balance.points[2].rate_deg_s`) or the line and column.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// The file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
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
    #[error("{}: field `{field}` = {value}: {reason}", path.display())]
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
    #[error("{}: field `{field}`: rate {rate_deg_s} deg/s appears twice (first at `{first}`)", path.display())]
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
        source: kinematics::Error,
    },
    /// The PIGA model was refused.
    #[error("{}: `{field}`: {source}", path.display())]
    AccelModel {
        /// The file concerned.
        path: PathBuf,
        /// The field concerned.
        field: String,
        /// The PIGA model's error.
        source: accel_model::Error,
    },
    /// A probe recording named by the configuration could not be read or analysed.
    #[error("{}: `{field}`: {source}", path.display())]
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
        reason: &'static str,
    },
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, PipelineError>;
