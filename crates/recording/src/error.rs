//! The reader's error type.

use std::path::PathBuf;

use harmonics::HarmonicsError;

/// Errors of reading a probe recording, each naming the file and, where it applies, the
/// 1-based line; and of the probe-recording writer's input.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RecordingError {
    /// The file could not be read.
    #[error("{}: {error}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error (its message is part of this one's).
        error: std::io::Error,
    },
    /// The format itself is unusable.
    #[error("recording format: `{field}` {reason}")]
    InvalidFormat {
        /// The offending field of [`RecordingFormat`](super::RecordingFormat).
        field: &'static str,
        /// What is wrong.
        reason: &'static str,
    },
    /// No line end within 16 MiB (a binary file, or not a text table).
    #[error("{}:{line}: no line end within {max_bytes} bytes", path.display())]
    LineTooLong {
        /// The file.
        path: PathBuf,
        /// The line that does not end.
        line: usize,
        /// The longest line read, bytes.
        max_bytes: usize,
    },
    /// The file has no header line (it is empty, blank or only comments).
    #[error("{}: empty file (no header line)", path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// The file has a header but no data rows.
    #[error("{}:{line}: header but no data rows", path.display())]
    NoSamples {
        /// The file.
        path: PathBuf,
        /// Line of the header.
        line: usize,
    },
    /// A required column is not in the header.
    #[error("{}:{line}: no column `{column}` in the header (columns: {})", path.display(), header.join(", "))]
    MissingColumn {
        /// The file.
        path: PathBuf,
        /// Line of the header.
        line: usize,
        /// The column looked for.
        column: String,
        /// The header's columns.
        header: Vec<String>,
    },
    /// A row ends before a required column.
    #[error("{}:{line}: row has no field for column `{column}`", path.display())]
    MissingField {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The column.
        column: String,
    },
    /// A field is not a number.
    #[error("{}:{line}: column `{column}`: cannot parse {text:?} as a number", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The column.
        column: String,
        /// The field's text.
        text: String,
    },
    /// A field is NaN or infinite.
    #[error("{}:{line}: column `{column}` is not finite ({value})", path.display())]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The column.
        column: String,
        /// The value.
        value: f64,
    },
    /// The time does not increase.
    #[error("{}:{line}: time {time_s} s does not increase (previous row at {previous_s} s)", path.display())]
    TimeNotIncreasing {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// Time of the previous row, s.
        previous_s: f64,
        /// Time of this row, s.
        time_s: f64,
    },
    /// Samples are missing: the interval before this line is too long.
    #[error(
        "{}:{line}: gap of {interval_s} s before this sample, more than {max_intervals} nominal \
         sample intervals of {nominal_interval_s} s",
        path.display()
    )]
    SampleGap {
        /// The file.
        path: PathBuf,
        /// The line after the gap.
        line: usize,
        /// The interval, s.
        interval_s: f64,
        /// The nominal (median) sample interval, s.
        nominal_interval_s: f64,
        /// The allowed gap in nominal intervals.
        max_intervals: f64,
    },
    /// Another check of the samples, or the harmonic analysis, failed.
    #[error("{}{}: {error}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Samples {
        /// The file.
        path: PathBuf,
        /// The line of the sample concerned, when the error names one.
        line: Option<usize>,
        /// The check's error (its message is part of this one's).
        error: HarmonicsError,
    },
    /// Columns given to the probe-recording writer differ in length.
    #[error(
        "probe columns to write differ in length: {time} times, {gap} gaps{}",
        angle.map(|a| format!(", {a} angles")).unwrap_or_default()
    )]
    ColumnLengths {
        /// Length of the time column.
        time: usize,
        /// Length of the gap column.
        gap: usize,
        /// Length of the angle column, when there is one.
        angle: Option<usize>,
    },
    /// A value given to the probe-recording writer is NaN or infinite (the reader would
    /// refuse the file).
    #[error("probe column `{column}` to write: value {value} at index {index} is not finite")]
    NonFiniteValue {
        /// The column (`time_s`, `gap_um` or `angle_deg`).
        column: &'static str,
        /// The 0-based index of the value.
        index: usize,
        /// The value.
        value: f64,
    },
}

/// Result alias of this crate.
pub type Result<T, E = RecordingError> = std::result::Result<T, E>;

impl RecordingError {
    /// The error with its line moved by `offset` (for a piece parsed apart).
    pub(super) fn with_line_offset(mut self, offset: usize) -> Self {
        match &mut self {
            Self::MissingField { line, .. }
            | Self::Parse { line, .. }
            | Self::NonFinite { line, .. }
            | Self::TimeNotIncreasing { line, .. }
            | Self::SampleGap { line, .. }
            | Self::NoSamples { line, .. }
            | Self::MissingColumn { line, .. }
            | Self::LineTooLong { line, .. } => *line += offset,
            Self::Samples { line, .. } => {
                if let Some(l) = line {
                    *l += offset;
                }
            }
            Self::Io { .. }
            | Self::InvalidFormat { .. }
            | Self::Empty { .. }
            | Self::ColumnLengths { .. }
            | Self::NonFiniteValue { .. } => {}
        }
        self
    }
}
