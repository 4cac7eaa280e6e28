//! The crate's error type.

use std::path::PathBuf;

use harmonics::HarmonicsError;

/// Errors of reading a table or probe recording, and of the probe-recording writer's
/// input. A reading error names the file and, where it applies, the 1-based line; an error
/// with an underlying cause returns it from [`source`](std::error::Error::source) rather
/// than repeating it in its message.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RecordingError {
    /// The file could not be opened or read.
    #[error("{}: cannot read", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The delimiter of a format cannot separate numeric fields.
    #[error(
        "format: delimiter {delimiter:?} must be one ASCII character that cannot occur in a \
         number, a comment or a line end"
    )]
    InvalidDelimiter {
        /// The delimiter given.
        delimiter: char,
    },
    /// Two columns of a format have the same name.
    #[error("format: `{field}` names column `{name}`, which another column of the format has")]
    DuplicateColumn {
        /// The format's field (`gap_column`, `angle_column`, or `columns` of a
        /// [`TableFormat`](crate::TableFormat)).
        field: &'static str,
        /// The name.
        name: String,
    },
    /// A table format names no column, too many, or only optional ones.
    #[error(
        "format: {count} columns, {required} of them required; a table needs 1 to {max} \
         columns, at least one of them required"
    )]
    InvalidColumns {
        /// Columns named.
        count: usize,
        /// Of these, required.
        required: usize,
        /// Most columns a format may name.
        max: usize,
    },
    /// The largest sample interval of a probe-recording format is not a finite value of at
    /// least 1.
    #[error("format: `max_gap_intervals` = {value} must be finite and at least 1")]
    InvalidGapLimit {
        /// The value given.
        value: f64,
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
    NoRows {
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
    /// A row ends before a column that is read.
    #[error("{}:{line}: row has no field for column `{column}`", path.display())]
    MissingField {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The column.
        column: String,
    },
    /// A row of a table that is not [`flexible`](crate::TableFormat::flexible) has another
    /// number of fields than its header.
    #[error("{}:{line}: row has {found} fields, the header {expected}", path.display())]
    FieldCount {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// Fields of the header.
        expected: usize,
        /// Fields of the row.
        found: usize,
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
    #[error("{}{}: cannot analyse the samples", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Samples {
        /// The file.
        path: PathBuf,
        /// The line of the sample concerned, when the error names one.
        line: Option<usize>,
        /// The check's or the analysis's error.
        source: HarmonicsError,
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
    pub(crate) fn with_line_offset(mut self, offset: usize) -> Self {
        match &mut self {
            Self::MissingField { line, .. }
            | Self::FieldCount { line, .. }
            | Self::Parse { line, .. }
            | Self::NonFinite { line, .. }
            | Self::TimeNotIncreasing { line, .. }
            | Self::SampleGap { line, .. }
            | Self::NoRows { line, .. }
            | Self::MissingColumn { line, .. }
            | Self::LineTooLong { line, .. } => *line += offset,
            Self::Samples { line, .. } => {
                if let Some(l) = line {
                    *l += offset;
                }
            }
            Self::Io { .. }
            | Self::InvalidDelimiter { .. }
            | Self::DuplicateColumn { .. }
            | Self::InvalidColumns { .. }
            | Self::InvalidGapLimit { .. }
            | Self::Empty { .. }
            | Self::ColumnLengths { .. }
            | Self::NonFiniteValue { .. } => {}
        }
        self
    }
}
