//! The crate's error type.

use std::path::PathBuf;

/// Errors of writing a study's outputs and of reading and applying expected values.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// The file could not be read or written.
    #[error("{}", path.display())]
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
    /// A figure could not be drawn.
    #[error("drawing {what}: {message}")]
    Plot {
        /// Which figure.
        what: &'static str,
        /// The backend's message.
        message: String,
    },
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
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, ReportError>;
