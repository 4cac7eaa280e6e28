//! The crate's error type.

use std::path::PathBuf;

use harmonics::HarmonicsError;

mod binary;

pub use binary::{BinaryDefect, BinaryFormat, BinaryPart, Unsupported};

/// What a lab engineer probably has to change when a recording is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Hint {
    /// A number like `1,5`.
    #[error("decimal comma? set `decimal: comma` (with a delimiter other than `,`, e.g. `;`)")]
    DecimalComma,
    /// A number like `1.5` in a format with a decimal comma.
    #[error("decimal point? set `decimal: point`")]
    DecimalPoint,
    /// A field holds another delimiter.
    #[error("another delimiter? set `delimiter` to the character between the fields")]
    Delimiter,
    /// The header was not split, or split where it should not be.
    #[error(
        "the header looks separated by {found:?}: set `delimiter: {found:?}` (or `whitespace` for runs of blanks)"
    )]
    HeaderDelimiter {
        /// The separator seen in the header.
        found: char,
    },
    /// The header line is not the first line.
    #[error(
        "metadata lines above the header? set `skip_lines` to their number, or name the columns the header has"
    )]
    SkipLines,
    /// A NaN or infinite sample.
    #[error("to fit the other revolutions, set `on_non_finite: drop_revolution`")]
    OnNonFinite,
    /// Missing samples.
    #[error(
        "to fit the other revolutions, set `on_gap: drop_revolution` (or raise `max_gap_intervals`)"
    )]
    OnGap,
    /// An encoder in counts read as an angle.
    #[error("encoder in counts? set `angle: encoder(column: ..., unit: counts(per_rev: N))`")]
    EncoderCounts,
    /// The time column is in another unit.
    #[error("time in another unit? set `time: (column: ..., unit: ms)` (s | ms | us | ns)")]
    TimeUnit,
}

impl Hint {
    /// The key of the configuration's `format` block the hint asks to set (`decimal`,
    /// `delimiter`, `skip_lines`, `on_non_finite`, `on_gap`, `angle`, `time`): a reader
    /// gives the hint only when its format has that key ([`TableFormat::hint_keys`]).
    ///
    /// [`TableFormat::hint_keys`]: crate::TableFormat::hint_keys
    pub const fn key(self) -> &'static str {
        match self {
            Self::DecimalComma | Self::DecimalPoint => "decimal",
            Self::Delimiter | Self::HeaderDelimiter { .. } => "delimiter",
            Self::SkipLines => "skip_lines",
            Self::OnNonFinite => "on_non_finite",
            Self::OnGap => "on_gap",
            Self::EncoderCounts => "angle",
            Self::TimeUnit => "time",
        }
    }

    /// Whether the hint names one of `keys`.
    pub fn is_for(self, keys: &[&str]) -> bool {
        keys.contains(&self.key())
    }
}

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
    /// The path names something other than a regular file (a folder, a FIFO, a device, a
    /// socket): refused unread, since reading it could block or never end.
    #[error(
        "{} is {kind}, not a regular file: a recording or table must be a file on disk (a pipe \
         or a device could block or never end, so it is not read)",
        path.display()
    )]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it names, in words ("a named pipe (FIFO)").
        kind: &'static str,
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
    /// A probe sensitivity, or its uncertainty, that is not finite and positive.
    #[error(
        "format: `volts({field}: {value_c})` must be finite and > 0 (the probe's sensitivity \
         and its standard uncertainty, from its calibration certificate)",
        value_c = units::Compact(*value)
    )]
    InvalidSensitivity {
        /// `sensitivity` or `u_sensitivity`.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// An encoder in counts with 0 counts per revolution.
    #[error("format: `counts(per_rev: 0)`: an encoder has at least 1 count per revolution")]
    InvalidCountsPerRev,
    /// A start angle that is not finite.
    #[error("format: `rate(start_angle_deg: {value})` must be finite")]
    InvalidStartAngle {
        /// The value given.
        value: f64,
    },
    /// An index-pulse column with fewer than two rising edges: no revolution is measured.
    #[error("{}: index-pulse column `{column}` rises {edges} time(s); at least 2 rising edges (0 → 1) are needed to measure a revolution", path.display())]
    TooFewIndexPulses {
        /// The file.
        path: PathBuf,
        /// The column.
        column: String,
        /// Rising edges found.
        edges: usize,
    },
    /// The largest sample interval of a probe-recording format is not a finite value of at
    /// least 1.
    #[error("format: `max_gap_intervals` = {value_c} must be finite and at least 1", value_c = units::Compact(*value))]
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
    #[error("{}:{line}: no column `{column}` in the header (columns: {}){}", path.display(), header.join(", "), hint_text(hint))]
    MissingColumn {
        /// The file.
        path: PathBuf,
        /// Line of the header.
        line: usize,
        /// The column looked for.
        column: String,
        /// The header's columns.
        header: Vec<String>,
        /// What to change, when known.
        hint: Option<Hint>,
    },
    /// A column's header states another unit than the format declares for it.
    #[error(
        "{}:{line}: column `{column}` states its unit as {stated:?} in the header, but the \
         format declares `unit: {declared}` (hint: set `unit: {suggested}`, or name the \
         column whose unit is {declared})",
        path.display()
    )]
    ColumnUnit {
        /// The file.
        path: PathBuf,
        /// Line of the header.
        line: usize,
        /// The column.
        column: String,
        /// The unit as the header writes it.
        stated: String,
        /// The unit the format declares (its configuration name).
        declared: &'static str,
        /// The configuration name of the unit the header states.
        suggested: &'static str,
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
    #[error("{}:{line}: column `{column}`: cannot parse {text:?} as a number{}", path.display(), hint_text(hint))]
    Parse {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The column.
        column: String,
        /// The field's text.
        text: String,
        /// What to change, when known.
        hint: Option<Hint>,
    },
    /// A field is NaN or infinite.
    #[error("{}:{line}: column `{column}` is not finite ({value_c}){}", path.display(), hint_text(hint), value_c = units::Compact(*value))]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// The line.
        line: usize,
        /// The column.
        column: String,
        /// The value.
        value: f64,
        /// What to change, when known.
        hint: Option<Hint>,
    },
    /// The time does not increase.
    #[error("{}:{line}: time {time_s_c} s does not increase (previous row at {previous_s_c} s)", path.display(), time_s_c = units::Compact(*time_s), previous_s_c = units::Compact(*previous_s))]
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
        "{}:{line}: gap of {interval_s_c} s before this sample, more than {max_intervals_c} nominal \
         sample intervals of {nominal_interval_s_c} s; {}",
        path.display(), Hint::OnGap, interval_s_c = units::Compact(*interval_s), max_intervals_c = units::Compact(*max_intervals), nominal_interval_s_c = units::Compact(*nominal_interval_s)
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
    #[error("{}{}: cannot analyse the samples{}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default(), hint_text(hint))]
    Samples {
        /// The file.
        path: PathBuf,
        /// The line of the sample concerned, when the error names one.
        line: Option<usize>,
        /// What to change, when known.
        hint: Option<Hint>,
        /// The check's or the analysis's error.
        source: HarmonicsError,
    },
    /// A binary file (TDMS or MAT) ends inside a structure.
    #[error("{}: {format} file ends inside {what} of {needed} bytes at byte {offset}", path.display())]
    Truncated {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// Byte offset where the structure starts.
        offset: u64,
        /// What was being read.
        what: BinaryPart,
        /// Bytes it needs.
        needed: u64,
    },
    /// A binary file does not start with its format's signature.
    #[error("{}: not a {format} file (no {format} signature at byte {offset})", path.display())]
    BadMagic {
        /// The file.
        path: PathBuf,
        /// The format expected.
        format: BinaryFormat,
        /// Byte offset of the signature looked for.
        offset: u64,
    },
    /// A MAT file of version 7.3, which is HDF5.
    #[error(
        "{}: MAT-file version 7.3 (HDF5) is not read; save with -v7 or older          (`save(file, ..., '-v7')`, or scipy.io.savemat)",
        path.display()
    )]
    MatV73 {
        /// The file.
        path: PathBuf,
    },
    /// A structure of a binary file is invalid.
    #[error("{}: {format} byte {offset}: {defect}", path.display())]
    Malformed {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// Byte offset of the structure (in the decompressed element for a compressed MAT
        /// variable: see [`BinaryDefect::InCompressed`]).
        offset: u64,
        /// What is wrong.
        defect: BinaryDefect,
    },
    /// A channel or variable to read has a data type or shape the reader does not convert.
    #[error("{}: {format} `{channel}`: unsupported {what}", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// The channel or variable.
        channel: String,
        /// What is not supported.
        what: Unsupported,
    },
    /// A channel or variable to read is not in the file.
    #[error("{}: no {format} {} `{channel}` (available: {})", path.display(), format.item(), available.join(", "))]
    MissingChannel {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// The channel or variable looked for.
        channel: String,
        /// The channels or variables the file has.
        available: Vec<String>,
    },
    /// Two channels to read have different lengths.
    #[error("{}: {format} `{channel}` has {found} samples, `{reference}` {expected}", path.display())]
    ChannelLength {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// The channel whose length differs.
        channel: String,
        /// The channel it is compared with.
        reference: String,
        /// Samples of `reference`.
        expected: usize,
        /// Samples of `channel`.
        found: usize,
    },
    /// A sample of a binary channel is NaN or infinite.
    #[error(
        "{}: {format} `{channel}` sample {index} is not finite ({value}) (hint: {})",
        path.display(),
        Hint::OnNonFinite
    )]
    NonFiniteSample {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// The channel or variable.
        channel: String,
        /// The 0-based sample index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// No time channel was given, and the gap channel has no `wf_increment` property to
    /// give the sample times (a MAT file always needs a time variable).
    #[error(
        "{}: `{channel}`: no time channel given, and no `wf_increment` property (TDMS) to give \
         the sample times",
        path.display()
    )]
    NoTimeBase {
        /// The file.
        path: PathBuf,
        /// The gap channel.
        channel: String,
    },
    /// A recording format's setting that does not apply to the kind of file read.
    #[error(
        "{}: the format's `{setting}` applies to {applies_to} only",
        path.display()
    )]
    SettingNotForFile {
        /// The file.
        path: PathBuf,
        /// The setting.
        setting: &'static str,
        /// The files it applies to, in words.
        applies_to: &'static str,
    },
    /// The time axis of a binary recording fails a check (order, gaps); the source names
    /// the sample index.
    #[error(
        "{}: {format} `{channel}`: bad time axis{}",
        path.display(),
        match source {
            HarmonicsError::SampleGap { .. } => format!(" (hint: {})", Hint::OnGap),
            _ => String::new(),
        }
    )]
    TimeAxis {
        /// The file.
        path: PathBuf,
        /// The format.
        format: BinaryFormat,
        /// The time channel (or the gap channel whose `wf_increment` gave the times).
        channel: String,
        /// The check's error, naming the sample index.
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
    /// A PIGA output recording's output angle moves by more than a quarter turn between two
    /// samples: too far to unwrap or to tell its direction.
    #[error("{}:{line}: the PIGA output angle moves by {step_c} rad from the previous sample, more than a quarter turn: the sampling is too slow to follow it, or the column or its unit is wrong (hint: check `output` and its unit: deg, rad or counts(per_rev))", path.display(), step_c = units::Compact(*step_rad))]
    OutputStep {
        /// The file.
        path: PathBuf,
        /// The line of the later sample.
        line: usize,
        /// The step after unwrapping whole turns, rad.
        step_rad: f64,
    },
    /// A PIGA output recording holds fewer than two whole spindle revolutions: its mean
    /// output has no standard error across revolutions.
    #[error("{}: {revolutions} whole spindle revolution(s) usable; the mean output rate needs at least 2 for its standard error across revolutions (hint: record longer)", path.display())]
    TooFewRevolutions {
        /// The file.
        path: PathBuf,
        /// Revolutions usable.
        revolutions: usize,
    },
    /// A value given to the probe-recording writer is NaN or infinite (the reader would
    /// refuse the file).
    #[error("probe column `{column}` to write: value {value_c} at index {index} is not finite", value_c = units::Compact(*value))]
    NonFiniteValue {
        /// The column (`time_s`, `gap_um` or `angle_deg`).
        column: &'static str,
        /// The 0-based index of the value.
        index: usize,
        /// The value.
        value: f64,
    },
}

/// ` (hint: …)` after a message, when there is a hint.
fn hint_text(hint: &Option<Hint>) -> String {
    hint.map(|h| format!(" (hint: {h})")).unwrap_or_default()
}

/// Result alias of this crate.
pub type Result<T, E = RecordingError> = std::result::Result<T, E>;

impl RecordingError {
    /// Takes the error's hint out of it (its message then ends without one), for a caller
    /// that words the hint in its own options (`centrifuge-cal identify`'s flags instead of
    /// a configuration's keys).
    pub fn take_hint(&mut self) -> Option<Hint> {
        match self {
            Self::MissingColumn { hint, .. }
            | Self::Parse { hint, .. }
            | Self::NonFinite { hint, .. }
            | Self::Samples { hint, .. } => hint.take(),
            _ => None,
        }
    }

    /// The error with its line moved by `offset` (for a piece parsed apart).
    pub(crate) fn with_line_offset(mut self, offset: usize) -> Self {
        match &mut self {
            Self::MissingField { line, .. }
            | Self::FieldCount { line, .. }
            | Self::Parse { line, .. }
            | Self::NonFinite { line, .. }
            | Self::TimeNotIncreasing { line, .. }
            | Self::SampleGap { line, .. }
            | Self::OutputStep { line, .. }
            | Self::NoRows { line, .. }
            | Self::MissingColumn { line, .. }
            | Self::ColumnUnit { line, .. }
            | Self::LineTooLong { line, .. } => *line += offset,
            Self::Samples { line, .. } => {
                if let Some(l) = line {
                    *l += offset;
                }
            }
            Self::Io { .. }
            | Self::NotAFile { .. }
            | Self::InvalidDelimiter { .. }
            | Self::DuplicateColumn { .. }
            | Self::InvalidColumns { .. }
            | Self::InvalidGapLimit { .. }
            | Self::InvalidCountsPerRev
            | Self::InvalidSensitivity { .. }
            | Self::InvalidStartAngle { .. }
            | Self::TooFewIndexPulses { .. }
            | Self::Empty { .. }
            | Self::TooFewRevolutions { .. }
            | Self::ColumnLengths { .. }
            | Self::NonFiniteValue { .. }
            | Self::Truncated { .. }
            | Self::BadMagic { .. }
            | Self::MatV73 { .. }
            | Self::Malformed { .. }
            | Self::Unsupported { .. }
            | Self::MissingChannel { .. }
            | Self::ChannelLength { .. }
            | Self::NonFiniteSample { .. }
            | Self::NoTimeBase { .. }
            | Self::SettingNotForFile { .. }
            | Self::TimeAxis { .. } => {}
        }
        self
    }
}
