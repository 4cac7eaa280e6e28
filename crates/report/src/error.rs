//! The crate's error type.

use std::path::PathBuf;

/// Errors of writing a study's outputs and of reading and applying expected values.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// A file could not be read (or is too large, or not UTF-8), or an output could not be
    /// written or moved into place.
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
    /// An expected-values file has no check with `regress: true`: a regression against it
    /// would pass whatever the results.
    #[error(
        "{}: `checks`: no check with `regress: true` among {checks}; a regression against this \
         file would pass whatever the results",
        path.display()
    )]
    NoRegressionChecks {
        /// The file concerned.
        path: PathBuf,
        /// How many checks it has (all with `regress: false`, or none).
        checks: usize,
    },
    /// A check's value or tolerance is not a finite number, or its tolerance is negative.
    #[error("{}: `{field}` = {value_c}: {reason}", path.display(), value_c = units::Compact(*value))]
    InvalidCheckNumber {
        /// The file concerned.
        path: PathBuf,
        /// The field, e.g. `checks[3].tolerance`.
        field: String,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A check's results path is empty or malformed (an empty segment, a bad `[index]`).
    #[error("{}: `checks[{index}].path` = {check_path:?}: {reason}", path.display())]
    InvalidCheckPath {
        /// The file concerned.
        path: PathBuf,
        /// Index of the check.
        index: usize,
        /// The path given.
        check_path: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// Two checks of the same kind (published, or not) name the same results path.
    #[error(
        "{}: `checks[{index}].path` = {check_path:?}: already checked by `checks[{first}]` \
         (a path takes at most one published value and one other check)",
        path.display()
    )]
    DuplicateCheckPath {
        /// The file concerned.
        path: PathBuf,
        /// Index of the second check.
        index: usize,
        /// Index of the first check with the same path and kind.
        first: usize,
        /// The path they share.
        check_path: String,
    },
    /// A figure could not be drawn.
    #[error("drawing {what}: {message}")]
    Plot {
        /// Which figure.
        what: &'static str,
        /// The backend's message.
        message: String,
    },
    /// A certificate was asked of results without a certificate (and calibration) section.
    #[error(
        "a certificate needs a study with a `calibration` and a `certificate` section; this study lacks one"
    )]
    NoCertificate,
    /// The date of issue is not a calendar date, which a PDF/A document must state.
    #[error(
        "the certificate's date of issue {issued:?} is not a calendar date (hint: write `certificate.dates.issued` as ISO 8601 does, `2026-11-24`)"
    )]
    IssueDate {
        /// The date as the study states it.
        issued: String,
    },
    /// The certificate could not be typeset.
    #[error("typesetting the certificate: {0}")]
    Typeset(#[from] typeset::TypesetError),
    /// A results file is not what a study writes.
    #[error("{}: {message} (hint: give the folder a study wrote, holding its results.json)", path.display())]
    Results {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The digital calibration certificate (`certificate.dcc.xml`) cannot be written.
    #[error("certificate.dcc.xml: {0}")]
    Dcc(#[from] dcc::DccError),
    /// The results have no phase to draw.
    #[error("the results have no phase")]
    NoPhase,
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
}

impl ReportError {
    /// The error of [`edge_io::to_json_pretty`] for the output `what`.
    pub(crate) fn json(what: &'static str, e: edge_io::JsonError) -> Self {
        e.into_error(
            |field, value| Self::NonFiniteOutput { what, field, value },
            |message| Self::Serialize { what, message },
        )
    }
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, ReportError>;
