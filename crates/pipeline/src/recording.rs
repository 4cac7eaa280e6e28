//! Probe recordings: delimited text files of time, probe gap and, optionally, the spindle
//! encoder's angle, one sample per row (the raw data behind eq. 20).
//!
//! A file is streamed through one reused buffer of about a megabyte and parsed in a single
//! pass without an allocation per row: fields are parsed in place by a fast decimal parser
//! (exact for up to 19 significant digits and exponents within ±22, the standard library's
//! parser otherwise). Lines end with LF, CRLF, or (in a file whose first line end is one) a
//! lone CR; a leading UTF-8 byte-order mark is skipped; fields may be quoted. Errors name the
//! file and the 1-based line.
//!
//! ```
//! use pipeline::{parse_recording, RecordingFormat};
//! let text = "# probe at 10 deg/s\ntime_s,gap_um,angle_deg\n0.000,12.5,359.9\n0.001,12.6,0.1\n";
//! let rec = parse_recording(text.as_bytes(), "probe.csv".as_ref(), &RecordingFormat::default())?;
//! assert_eq!(rec.time_s, [0.0, 0.001]);
//! approx::assert_relative_eq!(rec.angle_rad.as_ref().unwrap()[1], 0.1f64.to_radians());
//! # Ok::<(), pipeline::RecordingError>(())
//! ```

use std::path::{Path, PathBuf};

use harmonics::{HarmonicsError, ProbeSignal, SpindleAngle};
use serde::{Deserialize, Serialize};

/// Length unit of the gap column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LengthUnit {
    /// Micrometres (the paper's unit).
    #[default]
    Um,
    /// Millimetres.
    Mm,
    /// Metres.
    M,
}

impl LengthUnit {
    /// Micrometres per unit.
    pub const fn um_per_unit(self) -> f64 {
        match self {
            Self::Um => 1.0,
            Self::Mm => 1e3,
            Self::M => 1e6,
        }
    }

    /// The unit's symbol (`um`, `mm`, `m`).
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::Um => "um",
            Self::Mm => "mm",
            Self::M => "m",
        }
    }
}

/// Angle unit of the encoder column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AngleUnit {
    /// Degrees.
    #[default]
    Deg,
    /// Radians.
    Rad,
}

impl AngleUnit {
    /// Radians per unit.
    pub const fn rad_per_unit(self) -> f64 {
        match self {
            Self::Deg => std::f64::consts::PI / 180.0,
            Self::Rad => 1.0,
        }
    }
}

/// Layout of a probe-recording file; every field has a default, so a study configuration
/// names only what differs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RecordingFormat {
    /// Header name of the time column, seconds (default `time_s`).
    pub time_column: String,
    /// Header name of the gap column (default `gap_um`).
    pub gap_column: String,
    /// Header name of the encoder-angle column (default `angle_deg`), used when the header
    /// has it; zero at the O1X1 reference, may wrap.
    pub angle_column: String,
    /// Unit of the gap column (default µm).
    pub gap_unit: LengthUnit,
    /// Unit of the angle column (default degrees).
    pub angle_unit: AngleUnit,
    /// Field delimiter, one ASCII character (default `,`). With `' '` or `'\t'`, runs of
    /// blanks separate fields.
    pub delimiter: char,
    /// Largest interval between samples, in nominal (median) sample intervals, before the
    /// file is refused as having a gap (default 3).
    pub max_gap_intervals: f64,
}

impl Default for RecordingFormat {
    fn default() -> Self {
        Self {
            time_column: "time_s".into(),
            gap_column: "gap_um".into(),
            angle_column: "angle_deg".into(),
            gap_unit: LengthUnit::Um,
            angle_unit: AngleUnit::Deg,
            delimiter: ',',
            max_gap_intervals: 3.0,
        }
    }
}

/// A probe recording in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// The file it was read from.
    pub path: PathBuf,
    /// Sample times, s (strictly increasing, no gap above the format's limit).
    pub time_s: Vec<f64>,
    /// Probe gap of each sample, in [`Recording::gap_unit`].
    pub gap: Vec<f64>,
    /// Unit of [`Recording::gap`].
    pub gap_unit: LengthUnit,
    /// Encoder angle of each sample, rad, when the file has the angle column.
    pub angle_rad: Option<Vec<f64>>,
}

impl Recording {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no samples (never true for a loaded recording).
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// The samples as a [`ProbeSignal`]: angles from the encoder column when present, else
    /// `θ = ω·(t − t₀) + θ₀` from the given rate and first-sample angle.
    pub fn signal(&self, rate_rad_s: f64, start_angle_rad: f64) -> ProbeSignal<'_> {
        let angle = match &self.angle_rad {
            Some(a) => SpindleAngle::Encoder(a),
            None => SpindleAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            },
        };
        ProbeSignal {
            time_s: &self.time_s,
            gap: &self.gap,
            angle,
        }
    }
}

/// Errors of reading a probe recording; each names the file and, where it applies, the
/// 1-based line.
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
        /// The offending field of [`RecordingFormat`].
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
}

/// A synthetic probe recording with known coefficients, written in the default
/// [`RecordingFormat`]: for fixtures, benchmarks and demonstrations (see the
/// `synth_recording` example).
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticSpec {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// Sample rate, Hz.
    pub sample_rate_hz: f64,
    /// Turns recorded (a fraction leaves an incomplete last revolution).
    pub revolutions: f64,
    /// Write the encoder-angle column.
    pub encoder: bool,
    /// Standard deviation of the gap noise, µm.
    pub noise_um: f64,
    /// Non-uniform part of the spindle angle, rad (see [`harmonics::SyntheticRecording`]).
    pub wobble_rad: f64,
    /// Angle of the first sample from O1X1, deg.
    pub start_angle_deg: f64,
    /// Seed of the noise.
    pub seed: u64,
    /// The coefficients of eq. 20, µm.
    pub coefficients: harmonics::Coefficients,
}

impl Default for SyntheticSpec {
    fn default() -> Self {
        Self {
            rate_deg_s: 120.0,
            sample_rate_hz: 500.0,
            revolutions: 2.5,
            encoder: true,
            noise_um: 0.02,
            wobble_rad: 0.05,
            start_angle_deg: 30.0,
            seed: 20_250_101,
            coefficients: harmonics::Coefficients {
                l0: 50.0,
                c: vec![-3.0, 0.4, -0.15, 0.05],
                s: vec![-1.2, 0.25, 0.1, -0.03],
                drift_per_s: None,
            },
        }
    }
}

impl SyntheticSpec {
    /// Number of samples.
    pub fn samples(&self) -> usize {
        (self.revolutions * 360.0 / self.rate_deg_s * self.sample_rate_hz).round() as usize
    }

    /// The generator of the samples.
    pub fn recording(&self) -> harmonics::SyntheticRecording {
        harmonics::SyntheticRecording {
            rate_rad_s: self.rate_deg_s.to_radians(),
            sample_rate_hz: self.sample_rate_hz,
            samples: self.samples(),
            start_time_s: 0.0,
            start_angle_rad: self.start_angle_deg.to_radians(),
            coefficients: self.coefficients.clone(),
            noise_std: self.noise_um,
            wobble_rad: self.wobble_rad,
            seed: self.seed,
        }
    }

    /// The CSV text: `time_s,gap_um[,angle_deg]`, six decimals.
    pub fn csv(&self) -> String {
        use std::fmt::Write as _;
        let data = self.recording().generate();
        let mut out = String::with_capacity(data.time_s.len() * 32 + 128);
        let _ = writeln!(
            out,
            "# synthetic probe recording: {} deg/s, {} Hz, {} turns, noise {} um, seed {}",
            self.rate_deg_s, self.sample_rate_hz, self.revolutions, self.noise_um, self.seed
        );
        out += if self.encoder {
            "time_s,gap_um,angle_deg\n"
        } else {
            "time_s,gap_um\n"
        };
        for i in 0..data.time_s.len() {
            let _ = write!(out, "{:.6},{:.6}", data.time_s[i], data.gap[i]);
            if self.encoder {
                let _ = write!(out, ",{:.6}", data.angle_rad[i].to_degrees());
            }
            out.push('\n');
        }
        out
    }
}

/// Fits eq. 20 per revolution to a loaded recording ([`harmonics::analyze`]), with the angle
/// from the encoder column when present, else from the rate; an error naming a sample is
/// given the sample's line in the file.
///
/// With an encoder column, the encoder's mean rate must match `rate_rad_s` within
/// [`harmonics::ENCODER_RATE_TOLERANCE`] (2 %), else [`HarmonicsError::RateMismatch`]: a
/// study fits with the declared rate, so a file attached to the wrong rate point is refused.
pub fn analyze_recording(
    recording: &Recording,
    rate_rad_s: f64,
    start_angle_rad: f64,
    config: &harmonics::FitConfig,
) -> Result<harmonics::HarmonicAnalysis, RecordingError> {
    let located = |source: HarmonicsError| {
        let line = sample_index(&source).and_then(|row| {
            let text = std::fs::read(&recording.path).ok()?;
            Some(line_of_row(&text, row))
        });
        RecordingError::Samples {
            path: recording.path.clone(),
            line,
            error: source,
        }
    };
    let signal = recording.signal(rate_rad_s, start_angle_rad);
    let analysis = harmonics::analyze(&signal, config).map_err(located)?;
    // The encoder gives the angle, but the declared rate is the ω a study fits with.
    harmonics::check_encoder_rate(&signal, rate_rad_s, harmonics::ENCODER_RATE_TOLERANCE)
        .map_err(located)?;
    Ok(analysis)
}

/// The sample an analysis error names, if any.
fn sample_index(error: &HarmonicsError) -> Option<usize> {
    match error {
        HarmonicsError::NonFinite { index, .. }
        | HarmonicsError::NonFiniteInterval { index, .. }
        | HarmonicsError::TimeNotIncreasing { index, .. }
        | HarmonicsError::SampleGap { index, .. }
        | HarmonicsError::AngleNotIncreasing { index, .. } => Some(*index),
        HarmonicsError::TooFewSamples { first_sample, .. } => Some(*first_sample),
        HarmonicsError::Aliasing { after_sample, .. } => Some(*after_sample),
        _ => None,
    }
}

/// Pieces of text at least this long are parsed on two threads.
const PARALLEL_BYTES: usize = 256 * 1024;

impl RecordingError {
    /// The error with its line moved by `offset` (for a piece parsed apart).
    fn with_line_offset(mut self, offset: usize) -> Self {
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
            Self::Io { .. } | Self::InvalidFormat { .. } | Self::Empty { .. } => {}
        }
        self
    }
}

/// Bytes read from the file at a time by [`load_recording`].
const CHUNK_BYTES: usize = 1 << 20;

/// Longest line [`load_recording`] accepts, bytes (16 MiB): a file without a line end
/// within it is refused rather than read whole.
pub(crate) const MAX_LINE_BYTES: usize = 16 << 20;

/// The UTF-8 byte-order mark, skipped at the start of a file.
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Whether a text's line ends are lone CRs: its first line end is a CR not followed by LF.
/// `None` while the text read so far does not tell.
fn lone_cr_line_ends(text: &[u8], complete: bool) -> Option<bool> {
    match text.iter().position(|&b| b == b'\n' || b == b'\r') {
        Some(i) if text[i] == b'\n' => Some(false),
        Some(i) if i + 1 < text.len() => Some(text[i + 1] != b'\n'),
        // A CR as the last byte read: a lone CR only if nothing follows.
        Some(_) => complete.then_some(true),
        None => complete.then_some(false),
    }
}

/// The text without a leading byte-order mark and with lone-CR line ends turned into LF
/// (copied only then).
fn normalized(text: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    if lone_cr_line_ends(text, true) == Some(true) {
        text.iter()
            .map(|&b| if b == b'\r' { b'\n' } else { b })
            .collect::<Vec<u8>>()
            .into()
    } else {
        text.into()
    }
}

/// Reads a probe recording from a file, streaming it through one reused buffer of about
/// a megabyte (whole lines are parsed; a partial last line waits for the next read). A
/// line longer than 16 MiB is refused ([`RecordingError::LineTooLong`]).
pub fn load_recording(path: &Path, format: &RecordingFormat) -> Result<Recording, RecordingError> {
    use std::io::Read as _;
    let io = |error| RecordingError::Io {
        path: path.to_owned(),
        error,
    };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_or(0, |m| m.len() as usize);
    let mut parser = RowParser::new(path, format, size)?;
    let mut buf: Vec<u8> = Vec::with_capacity(CHUNK_BYTES + 64 * 1024);
    let mut eof = false;
    let mut start = true;
    // Whether line ends are lone CRs (decided at the first line end), and how much of the
    // buffer is known to hold no line end (so that a long line is scanned once).
    let mut lone_cr = None;
    let mut scanned: usize = 0;
    while !eof {
        // Top the buffer up to a chunk, or double it while one line is longer than that.
        let target = if scanned > 0 {
            (2 * buf.len()).max(CHUNK_BYTES)
        } else {
            CHUNK_BYTES
        };
        while buf.len() < target {
            let old = buf.len();
            buf.resize(target, 0);
            let got = file.read(&mut buf[old..]).map_err(io)?;
            buf.truncate(old + got);
            if got == 0 {
                eof = true;
                break;
            }
        }
        if start {
            if buf.starts_with(BOM) {
                buf.drain(..BOM.len());
            }
            start = false;
        }
        if lone_cr.is_none() {
            lone_cr = lone_cr_line_ends(&buf, eof);
        }
        // A CR at the end of the part already scanned may just have been found lone.
        let from = scanned.saturating_sub(1);
        if lone_cr == Some(true) {
            for b in &mut buf[from..] {
                if *b == b'\r' {
                    *b = b'\n';
                }
            }
        }
        let last_end = buf[from..]
            .iter()
            .rposition(|&b| b == b'\n')
            .map(|i| from + i + 1);
        if last_end.is_none() && buf.len() > MAX_LINE_BYTES {
            return Err(RecordingError::LineTooLong {
                path: path.to_owned(),
                line: parser.line + 1,
                max_bytes: MAX_LINE_BYTES,
            });
        }
        let complete = match (eof, last_end) {
            (true, _) => buf.len(),
            (false, Some(end)) => end,
            (false, None) => {
                scanned = buf.len();
                continue;
            }
        };
        parser.feed(&buf[..complete])?;
        buf.drain(..complete);
        scanned = 0;
    }
    parser.finish(None)
}

/// Parses a probe recording held in memory; `path` names it in errors.
pub fn parse_recording(
    text: &[u8],
    path: &Path,
    format: &RecordingFormat,
) -> Result<Recording, RecordingError> {
    let text = normalized(text);
    let mut parser = RowParser::new(path, format, text.len())?;
    parser.feed(&text)?;
    parser.finish(Some(&text))
}

/// The columns a header names.
struct Columns {
    /// `(field index, destination)` of time (0), gap (1) and angle (2, `usize::MAX` field
    /// when absent), sorted by field.
    wanted: [(usize, usize); 3],
    /// Last field index needed.
    last_needed: usize,
    /// Destination of each field up to `last_needed` ([`SKIP`] for others).
    dest_of: Vec<u8>,
    /// Whether the angle column is present.
    has_angle: bool,
}

/// The state of a parse fed with whole lines.
struct RowParser<'a> {
    path: &'a Path,
    format: &'a RecordingFormat,
    delimiter: u8,
    /// Lines seen so far.
    line: usize,
    header_line: usize,
    columns: Option<Columns>,
    time_s: Vec<f64>,
    gap: Vec<f64>,
    angle: Vec<f64>,
    previous_s: f64,
    size_hint: usize,
    /// Line of the first data row parsed.
    first_row_line: Option<usize>,
}

impl<'a> RowParser<'a> {
    fn new(
        path: &'a Path,
        format: &'a RecordingFormat,
        size_hint: usize,
    ) -> Result<Self, RecordingError> {
        Ok(Self {
            path,
            format,
            delimiter: delimiter_byte(format)?,
            line: 0,
            header_line: 0,
            columns: None,
            time_s: Vec::new(),
            gap: Vec::new(),
            angle: Vec::new(),
            previous_s: f64::NEG_INFINITY,
            size_hint,
            first_row_line: None,
        })
    }

    fn column_name(&self, dest: usize) -> String {
        match dest {
            0 => self.format.time_column.clone(),
            1 => self.format.gap_column.clone(),
            _ => self.format.angle_column.clone(),
        }
    }

    fn header(&mut self, line: usize, header: &[u8]) -> Result<Columns, RecordingError> {
        let format = self.format;
        let names: Vec<String> = split_fields(header, self.delimiter)
            .map(|f| String::from_utf8_lossy(trim_quotes(f)).into_owned())
            .collect();
        let find = |name: &str| names.iter().position(|n| n == name);
        let missing = |column: &str| RecordingError::MissingColumn {
            path: self.path.to_owned(),
            line,
            column: column.to_owned(),
            header: names.clone(),
        };
        let time_col = find(&format.time_column).ok_or_else(|| missing(&format.time_column))?;
        let gap_col = find(&format.gap_column).ok_or_else(|| missing(&format.gap_column))?;
        let angle_col = find(&format.angle_column);
        let mut wanted = [
            (time_col, 0_usize),
            (gap_col, 1),
            (angle_col.unwrap_or(usize::MAX), 2),
        ];
        wanted.sort_unstable();
        let last_needed = wanted
            .iter()
            .filter(|w| w.0 != usize::MAX)
            .map(|w| w.0)
            .max()
            .unwrap_or(0);
        let mut dest_of = vec![SKIP; last_needed + 1];
        for &(field, dest) in wanted.iter().filter(|w| w.0 != usize::MAX) {
            dest_of[field] = dest as u8;
        }
        // Columns reserved from the text's size (rows are rarely shorter than 16 bytes).
        let estimate = self.size_hint / 16;
        self.time_s.reserve(estimate);
        self.gap.reserve(estimate);
        if angle_col.is_some() {
            self.angle.reserve(estimate);
        }
        self.header_line = line;
        Ok(Columns {
            wanted,
            last_needed,
            dest_of,
            has_angle: angle_col.is_some(),
        })
    }

    /// Parses whole lines (the text ends at a line end, or is the file's last piece).
    fn feed(&mut self, text: &[u8]) -> Result<(), RecordingError> {
        let mut lines = Lines {
            text,
            pos: 0,
            line: self.line,
        };
        let columns = match self.columns.take() {
            Some(c) => c,
            None => match lines.next_content() {
                Some((line, header)) => self.header(line, header)?,
                None => {
                    self.line = lines.line;
                    return Ok(());
                }
            },
        };
        let result = self.rows_maybe_parallel(&mut lines, &columns);
        self.columns = Some(columns);
        self.line = lines.line;
        result
    }

    /// A parser for a later piece of the same file: same columns, no rows, lines counted
    /// from 0 (shifted when the pieces are joined).
    fn fork(&self, size_hint: usize) -> Self {
        let mut p = Self::new(self.path, self.format, size_hint).expect("format already checked");
        let estimate = size_hint / 16;
        p.time_s.reserve(estimate);
        p.gap.reserve(estimate);
        p.angle.reserve(if self.angle.capacity() > 0 {
            estimate
        } else {
            0
        });
        p
    }

    /// Parses the rows of `lines`; a large piece is cut at a line end near its middle and
    /// the halves are parsed on two threads (rayon), then joined in order.
    fn rows_maybe_parallel(
        &mut self,
        lines: &mut Lines<'_>,
        c: &Columns,
    ) -> Result<(), RecordingError> {
        let text = lines.text;
        let rest = text.len() - lines.pos;
        let cut = (rest >= PARALLEL_BYTES)
            .then(|| {
                let mid = lines.pos + rest / 2;
                text[mid..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map(|o| mid + o + 1)
            })
            .flatten()
            .filter(|&cut| cut < text.len());
        let Some(cut) = cut else {
            return self.rows(lines, c);
        };
        let mut first = Lines {
            text: &text[..cut],
            pos: lines.pos,
            line: lines.line,
        };
        let mut later = Lines {
            text: &text[cut..],
            pos: 0,
            line: 0,
        };
        let mut second = self.fork(text.len() - cut);
        let (r1, r2) = rayon::join(|| self.rows(&mut first, c), || second.rows(&mut later, c));
        r1?;
        let offset = first.line;
        lines.pos = text.len();
        lines.line = offset + later.line;
        // The first row of the second half must follow the last of the first half.
        if let (Some(&t), Some(line)) = (second.time_s.first(), second.first_row_line) {
            if t <= self.previous_s {
                return Err(RecordingError::TimeNotIncreasing {
                    path: self.path.to_owned(),
                    line: offset + line,
                    previous_s: self.previous_s,
                    time_s: t,
                });
            }
        }
        r2.map_err(|e| e.with_line_offset(offset))?;
        self.time_s.extend_from_slice(&second.time_s);
        self.gap.extend_from_slice(&second.gap);
        self.angle.extend_from_slice(&second.angle);
        self.previous_s = second.previous_s;
        Ok(())
    }

    fn rows(&mut self, lines: &mut Lines<'_>, c: &Columns) -> Result<(), RecordingError> {
        let text = lines.text;
        let angle_scale = self.format.angle_unit.rad_per_unit();
        let mut values = [0.0_f64; 3];
        loop {
            // Fast path: a plain row parsed in place; else the line is parsed field by field.
            let line = if let Some(next) =
                fast_row(text, lines.pos, self.delimiter, &c.dest_of, &mut values)
            {
                lines.pos = next;
                lines.line += 1;
                lines.line
            } else {
                let Some((line, row)) = lines.next_content() else {
                    return Ok(());
                };
                parse_row_slowly(row, self.delimiter, &c.wanted, c.last_needed, &mut values)
                    .map_err(|e| e.located(self.path, line, &|d| self.column_name(d)))?;
                line
            };
            if values[0] <= self.previous_s {
                return Err(RecordingError::TimeNotIncreasing {
                    path: self.path.to_owned(),
                    line,
                    previous_s: self.previous_s,
                    time_s: values[0],
                });
            }
            if self.time_s.is_empty() {
                self.first_row_line = Some(line);
            }
            self.previous_s = values[0];
            self.time_s.push(values[0]);
            self.gap.push(values[1]);
            if c.has_angle {
                self.angle.push(values[2] * angle_scale);
            }
        }
    }

    /// Checks the time axis and returns the recording; `text` (or else the file, read again
    /// only on error) gives the line of a sample named by an error.
    fn finish(self, text: Option<&[u8]>) -> Result<Recording, RecordingError> {
        let path = self.path;
        let Some(columns) = self.columns else {
            return Err(RecordingError::Empty {
                path: path.to_owned(),
            });
        };
        if self.time_s.is_empty() {
            return Err(RecordingError::NoSamples {
                path: path.to_owned(),
                line: self.header_line,
            });
        }
        // The rows are finite and increasing already; what is left is a gap, or intervals
        // that overflow (a single row has no interval to check).
        let check = match self.time_s.len() {
            1 => Ok(()),
            _ => harmonics::check_time_axis(&self.time_s, self.format.max_gap_intervals).map(drop),
        };
        check.map_err(|e| {
            let line = sample_index(&e).map(|row| match text {
                Some(t) => line_of_row(t, row),
                None => std::fs::read(path).map_or(0, |t| line_of_row(&t, row)),
            });
            match (e, line) {
                (
                    HarmonicsError::SampleGap {
                        interval_s,
                        nominal_interval_s,
                        max_intervals,
                        ..
                    },
                    Some(line),
                ) => RecordingError::SampleGap {
                    path: path.to_owned(),
                    line,
                    interval_s,
                    nominal_interval_s,
                    max_intervals,
                },
                (error, line) => RecordingError::Samples {
                    path: path.to_owned(),
                    line,
                    error,
                },
            }
        })?;
        Ok(Recording {
            path: path.to_owned(),
            time_s: self.time_s,
            gap: self.gap,
            gap_unit: self.format.gap_unit,
            angle_rad: columns.has_angle.then_some(self.angle),
        })
    }
}

/// What went wrong in a row, before the file and line are attached.
enum RowError {
    MissingField { dest: usize },
    Parse { dest: usize, text: String },
    NonFinite { dest: usize, value: f64 },
}

impl RowError {
    fn located(
        self,
        path: &Path,
        line: usize,
        column_name: &dyn Fn(usize) -> String,
    ) -> RecordingError {
        let path = path.to_owned();
        match self {
            Self::MissingField { dest } => RecordingError::MissingField {
                path,
                line,
                column: column_name(dest),
            },
            Self::Parse { dest, text } => RecordingError::Parse {
                path,
                line,
                column: column_name(dest),
                text,
            },
            Self::NonFinite { dest, value } => RecordingError::NonFinite {
                path,
                line,
                column: column_name(dest),
                value,
            },
        }
    }
}

/// Parses one row field by field: blanks around fields, quoted fields, any number the
/// standard library reads; finite values only.
fn parse_row_slowly(
    row: &[u8],
    delimiter: u8,
    wanted: &[(usize, usize); 3],
    last_needed: usize,
    values: &mut [f64; 3],
) -> Result<(), RowError> {
    let mut fields = split_fields(row, delimiter);
    let mut next_wanted = 0;
    for index in 0..=last_needed {
        let Some(field) = fields.next() else {
            return Err(RowError::MissingField {
                dest: wanted[next_wanted].1,
            });
        };
        if wanted[next_wanted].0 != index {
            continue;
        }
        let dest = wanted[next_wanted].1;
        next_wanted += 1;
        let field = trim_quotes(field);
        let value = parse_f64(field).ok_or_else(|| RowError::Parse {
            dest,
            text: String::from_utf8_lossy(field).into_owned(),
        })?;
        if !value.is_finite() {
            return Err(RowError::NonFinite { dest, value });
        }
        values[dest] = value;
    }
    Ok(())
}

fn delimiter_byte(format: &RecordingFormat) -> Result<u8, RecordingError> {
    let d = format.delimiter;
    if !d.is_ascii()
        || d == '\n'
        || d == '\r'
        || d == '#'
        || d == '"'
        || d.is_ascii_digit()
        || "+-.eE".contains(d)
    {
        return Err(RecordingError::InvalidFormat {
            field: "delimiter",
            reason: "must be one ASCII character that cannot occur in a number, a comment or a line end",
        });
    }
    if format.gap_column == format.time_column {
        return Err(RecordingError::InvalidFormat {
            field: "gap_column",
            reason: "must differ from `time_column`",
        });
    }
    if format.angle_column == format.time_column || format.angle_column == format.gap_column {
        return Err(RecordingError::InvalidFormat {
            field: "angle_column",
            reason: "must differ from `time_column` and `gap_column`",
        });
    }
    if !format.max_gap_intervals.is_finite() || format.max_gap_intervals < 1.0 {
        return Err(RecordingError::InvalidFormat {
            field: "max_gap_intervals",
            reason: "must be finite and at least 1",
        });
    }
    Ok(d as u8)
}

/// Lines of a text with their 1-based numbers; `next_content` skips blank lines and
/// `#` comments.
struct Lines<'a> {
    text: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lines<'a> {
    fn next_line(&mut self) -> Option<(usize, &'a [u8])> {
        if self.pos >= self.text.len() {
            return None;
        }
        let rest = &self.text[self.pos..];
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        // Past the line end, or at the text's end when the last line has none.
        self.pos = (self.pos + end + 1).min(self.text.len());
        self.line += 1;
        let mut line = &rest[..end];
        if let [head @ .., b'\r'] = line {
            line = head;
        }
        Some((self.line, line))
    }

    fn next_content(&mut self) -> Option<(usize, &'a [u8])> {
        while let Some((n, line)) = self.next_line() {
            let t = line.trim_ascii_start();
            if t.is_empty() || t[0] == b'#' {
                continue;
            }
            return Some((n, line));
        }
        None
    }
}

/// Line number of data row `row` (0-based): the `row + 1`-th content line after the header.
fn line_of_row(text: &[u8], row: usize) -> usize {
    let text = normalized(text);
    let mut lines = Lines {
        text: &text,
        pos: 0,
        line: 0,
    };
    lines.next_content(); // header
    for _ in 0..row {
        lines.next_content();
    }
    lines.next_content().map_or(lines.line, |(n, _)| n)
}

/// Fields of a line. A blank delimiter (space or tab) treats any run of blanks as one.
fn split_fields(line: &[u8], delimiter: u8) -> impl Iterator<Item = &[u8]> {
    let blank = delimiter == b' ' || delimiter == b'\t';
    let mut rest = Some(if blank { line.trim_ascii() } else { line });
    std::iter::from_fn(move || {
        let r = rest?;
        if blank {
            match r.iter().position(|&b| b == b' ' || b == b'\t') {
                Some(i) => {
                    rest = Some(r[i..].trim_ascii_start());
                    Some(&r[..i])
                }
                None => {
                    rest = None;
                    Some(r)
                }
            }
        } else {
            match r.iter().position(|&b| b == delimiter) {
                Some(i) => {
                    rest = Some(&r[i + 1..]);
                    Some(&r[..i])
                }
                None => {
                    rest = None;
                    Some(r)
                }
            }
        }
    })
}

fn trim_quotes(field: &[u8]) -> &[u8] {
    let f = field.trim_ascii();
    match f {
        [b'"', inner @ .., b'"'] => inner,
        _ => f,
    }
}

/// Exact powers of ten representable in `f64`.
const POW10: [f64; 23] = {
    let mut p = [1.0; 23];
    let mut i = 1;
    while i < 23 {
        p[i] = p[i - 1] * 10.0;
        i += 1;
    }
    p
};

/// Parses a decimal number (surrounding blanks allowed). Fast path: up to 19 significant
/// digits with a decimal exponent within ±22 are exact (Clinger's fast path: an exactly
/// representable mantissa times or over an exact power of ten is correctly rounded);
/// everything else (more digits, large exponents, `nan`, `inf`) goes to the standard
/// library's parser. `None` if the field is not a number.
fn parse_f64(field: &[u8]) -> Option<f64> {
    let f = field.trim_ascii();
    fast_f64(f).or_else(|| std::str::from_utf8(f).ok()?.parse().ok())
}

/// `fast_prefix` over the whole field.
fn fast_f64(s: &[u8]) -> Option<f64> {
    fast_prefix(s).and_then(|(v, used)| (used == s.len()).then_some(v))
}

/// The fast path of [`parse_f64`] on the number at the start of `s`: its value and length,
/// or `None` when it is not a plain decimal number the fast path computes exactly.
#[inline(always)]
fn fast_prefix(s: &[u8]) -> Option<(f64, usize)> {
    let mut i = 0;
    let negative = match s.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    // Integer and fraction digits; leading zeros count too (a field of more than 19 digits
    // goes to the standard parser, which is rare and still correct).
    let int_start = i;
    let mut mantissa: u64 = 0;
    while let Some(four) = four_digits(s, i) {
        mantissa = mantissa.wrapping_mul(10_000).wrapping_add(u64::from(four));
        i += 4;
    }
    while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|d| *d <= 9) {
        mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
        i += 1;
    }
    let mut digits = i - int_start;
    let mut exponent: i32 = 0;
    if s.get(i) == Some(&b'.') {
        i += 1;
        let frac_start = i;
        while let Some(four) = four_digits(s, i) {
            mantissa = mantissa.wrapping_mul(10_000).wrapping_add(u64::from(four));
            i += 4;
        }
        while let Some(d) = s.get(i).map(|b| b.wrapping_sub(b'0')).filter(|d| *d <= 9) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
            i += 1;
        }
        digits += i - frac_start;
        exponent = -((i - frac_start) as i32);
    }
    if digits == 0 || digits > 19 {
        return None;
    }
    if i < s.len() && (s[i] == b'e' || s[i] == b'E') {
        i += 1;
        let mut exp_negative = false;
        if i < s.len() && (s[i] == b'-' || s[i] == b'+') {
            exp_negative = s[i] == b'-';
            i += 1;
        }
        let start = i;
        let mut e: i32 = 0;
        while i < s.len() && s[i].is_ascii_digit() && e < 10_000 {
            e = e * 10 + i32::from(s[i] - b'0');
            i += 1;
        }
        if i == start {
            return None;
        }
        exponent += if exp_negative { -e } else { e };
    }
    if mantissa > (1 << 53) || !(-22..=22).contains(&exponent) {
        return None;
    }
    let m = mantissa as f64;
    let v = if exponent < 0 {
        m / POW10[(-exponent) as usize]
    } else {
        m * POW10[exponent as usize]
    };
    Some((if negative { -v } else { v }, i))
}

/// The value of four ASCII digits at `s[i..i + 4]`, if they are all digits (SWAR: one
/// 32-bit word, two multiplications).
#[inline(always)]
fn four_digits(s: &[u8], i: usize) -> Option<u32> {
    let bytes: [u8; 4] = s.get(i..i + 4)?.try_into().ok()?;
    let v = u32::from_le_bytes(bytes);
    // Every byte in '0'..='9': high nibble 3, and adding 6 keeps it below 0x40.
    if (v & 0xF0F0_F0F0) | ((v.wrapping_add(0x0606_0606) & 0xF0F0_F0F0) >> 4) != 0x3333_3333 {
        return None;
    }
    let v = v - 0x3030_3030;
    // Byte 0 becomes 10·d0 + d1 and byte 2 becomes 10·d2 + d3 (no byte exceeds 99).
    let v = v.wrapping_mul(10).wrapping_add(v >> 8);
    // (a + c·2¹⁶)·(1 + 100·2¹⁶) holds 100·a + c in bits 16…31.
    let w = u64::from(v & 0x00FF_00FF);
    Some((((w * (1 + (100 << 16))) >> 16) & 0xFFFF) as u32)
}

/// Sentinel of [`fast_row`]'s field map: a column that is not stored.
const SKIP: u8 = u8::MAX;

/// Parses a plain row `number,number,…` starting at `pos` straight from the text: stores
/// the wanted fields (`dest_of[field]` is the destination in `values`, or [`SKIP`]) and
/// returns where the next line starts. `None` on anything else (comment, blank line, blanks
/// around fields, quotes, short row, a value the fast path does not take): the caller then
/// parses the line the slow way, which also reports errors.
#[inline(always)]
fn fast_row(
    text: &[u8],
    mut pos: usize,
    delimiter: u8,
    dest_of: &[u8],
    values: &mut [f64; 3],
) -> Option<usize> {
    let last = dest_of.len() - 1;
    let blank = delimiter == b' ' || delimiter == b'\t';
    for (f, &dest) in dest_of.iter().enumerate() {
        if dest == SKIP {
            // The skipped field ends at the delimiter; with a blank delimiter at either
            // blank (the slow path's rule), and an empty field there is a run of blanks.
            let off = text.get(pos..)?.iter().position(|&b| {
                b == delimiter || b == b'\n' || (blank && (b == b' ' || b == b'\t'))
            })?;
            if text[pos + off] != delimiter || (blank && off == 0) {
                return None;
            }
            // A comment line is not a row.
            if f == 0 && text[pos..pos + off].trim_ascii_start().first() == Some(&b'#') {
                return None;
            }
            pos += off + 1;
            continue;
        }
        let (v, used) = fast_prefix(text.get(pos..)?)?;
        values[usize::from(dest)] = v;
        pos += used;
        if f < last {
            if text.get(pos) != Some(&delimiter) {
                return None;
            }
            pos += 1;
        } else {
            return match text.get(pos) {
                None => Some(pos),
                Some(b'\n') => Some(pos + 1),
                Some(b'\r') if text.get(pos + 1) == Some(&b'\n') => Some(pos + 2),
                Some(&b) if b == delimiter => {
                    let off = text[pos..].iter().position(|&b| b == b'\n');
                    Some(off.map_or(text.len(), |o| pos + o + 1))
                }
                _ => None,
            };
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Recording, RecordingError> {
        parse_recording(
            text.as_bytes(),
            Path::new("rec.csv"),
            &RecordingFormat::default(),
        )
    }

    fn rows(n: usize) -> String {
        let mut s = String::from("time_s,gap_um\n");
        for i in 0..n {
            s += &format!("{},{}\n", i as f64 * 0.001, 10.0 + (i as f64).sin());
        }
        s
    }

    #[test]
    fn default_columns_comments_blank_lines_and_crlf() {
        let text = "# a comment\r\n\r\n time_s , gap_um ,angle_deg\r\n0.0,1.5,359.0\r\n# mid comment\r\n0.001,-2e-1,1.0\r\n0.002,3,2";
        let rec = parse(text).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001, 0.002]);
        assert_eq!(rec.gap, [1.5, -0.2, 3.0]);
        let a = rec.angle_rad.unwrap();
        approx::assert_relative_eq!(a[0], 359f64.to_radians(), max_relative = 1e-15);
        approx::assert_relative_eq!(a[2], 2f64.to_radians(), max_relative = 1e-15);
        assert_eq!(rec.gap_unit, LengthUnit::Um);
    }

    #[test]
    fn configured_names_units_delimiter_and_column_order() {
        let format = RecordingFormat {
            time_column: "t".into(),
            gap_column: "d".into(),
            angle_column: "phi".into(),
            gap_unit: LengthUnit::Mm,
            angle_unit: AngleUnit::Rad,
            delimiter: ';',
            ..RecordingFormat::default()
        };
        let text = "phi;extra;d;t\n0.5;x;0.0125;10\n0.6;y;0.0126;10.001\n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.time_s, [10.0, 10.001]);
        assert_eq!(rec.gap, [0.0125, 0.0126]);
        assert_eq!(rec.gap_unit.um_per_unit(), 1e3);
        assert_eq!(rec.angle_rad.unwrap(), [0.5, 0.6]);
        // Blank-separated, runs of blanks count once.
        let format = RecordingFormat {
            delimiter: ' ',
            ..RecordingFormat::default()
        };
        let text = "time_s   gap_um\n 0.0   1.0\n0.001\t 2.0  \n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.gap, [1.0, 2.0]);
        assert!(rec.angle_rad.is_none());
    }

    #[test]
    fn ron_format_with_defaults() {
        let f: RecordingFormat = ron::from_str("(gap_unit: mm, delimiter: ';')").unwrap();
        assert_eq!(f.gap_unit, LengthUnit::Mm);
        assert_eq!(f.time_column, "time_s");
        assert!(ron::from_str::<RecordingFormat>("(gap_units: mm)").is_err());
    }

    #[test]
    fn fast_parser_agrees_with_std() {
        let cases = [
            "0",
            "-0",
            "1",
            "+1.5",
            "0.001",
            "123456.789",
            "-3.2385",
            "1e-3",
            "2.5E+2",
            "00012.50",
            "1234567890123456789",
            "12345678901234567890",
            "0.1234567890123456789",
            "1e22",
            "1e23",
            "1e-22",
            "1e-23",
            "9007199254740993",
            "4.9e-324",
            "1.7976931348623157e308",
            ".5",
            "5.",
            "nan",
            "NaN",
            "inf",
            "-inf",
            "infinity",
        ];
        for c in cases {
            let want: f64 = c.parse().unwrap();
            let got = parse_f64(c.as_bytes()).unwrap();
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "{c}: {got} vs {want}"
            );
        }
        for bad in ["", "-", ".", "e5", "1e", "1.2.3", "12a", "0x10", "1,5"] {
            assert_eq!(parse_f64(bad.as_bytes()), None, "{bad:?}");
        }
    }

    #[test]
    fn fast_parser_is_exact_on_random_decimals() {
        // A deterministic walk over mantissas and exponents.
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let digits = (x % 17) as u32 + 1;
            let m = (x >> 8) % 10u64.pow(digits);
            let e = (x >> 40) % 30;
            let s = format!("{m}e-{e}");
            let want: f64 = s.parse().unwrap();
            assert_eq!(
                parse_f64(s.as_bytes()).unwrap().to_bits(),
                want.to_bits(),
                "{s}"
            );
        }
    }

    #[test]
    fn empty_file() {
        for text in ["", "\n\n", "# only a comment\n  \n"] {
            assert!(
                matches!(parse(text), Err(RecordingError::Empty { .. })),
                "{text:?}"
            );
        }
        assert!(matches!(
            parse("time_s,gap_um\n# nothing\n"),
            Err(RecordingError::NoSamples { line: 1, .. })
        ));
    }

    #[test]
    fn missing_columns() {
        let e = parse("time_s,gap_mm\n0,1\n").unwrap_err();
        match &e {
            RecordingError::MissingColumn {
                line: 1,
                column,
                header,
                ..
            } => {
                assert_eq!(column, "gap_um");
                assert_eq!(header, &["time_s", "gap_mm"]);
            }
            e => panic!("{e}"),
        }
        assert!(
            e.to_string().starts_with("rec.csv:1: no column `gap_um`"),
            "{e}"
        );
        assert!(matches!(
            parse("t,gap_um\n0,1\n"),
            Err(RecordingError::MissingColumn { .. })
        ));
        let e = parse("time_s,gap_um\n0,1\n0.001\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::MissingField { line: 3, column, .. } if column == "gap_um"),
            "{e}"
        );
    }

    #[test]
    fn unparsable_numbers() {
        let e = parse("time_s,gap_um\n0,1\n0.001,1.2.3\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::Parse { line: 3, column, text, .. } if column == "gap_um" && text == "1.2.3"),
            "{e}"
        );
        assert_eq!(
            e.to_string(),
            "rec.csv:3: column `gap_um`: cannot parse \"1.2.3\" as a number"
        );
        let e = parse("# c\ntime_s,gap_um\n0,1\nzero,1\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::Parse { line: 4, column, .. } if column == "time_s"),
            "{e}"
        );
    }

    #[test]
    fn nan_and_infinite_values() {
        let e = parse("time_s,gap_um\n0,1\n0.001,NaN\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::NonFinite { line: 3, column, .. } if column == "gap_um"),
            "{e}"
        );
        let e = parse("time_s,gap_um,angle_deg\n0,1,0\n0.001,1,inf\n").unwrap_err();
        assert!(
            matches!(&e, RecordingError::NonFinite { line: 3, column, .. } if column == "angle_deg"),
            "{e}"
        );
        let e = parse("time_s,gap_um\n-inf,1\n").unwrap_err();
        assert!(
            matches!(e, RecordingError::NonFinite { line: 2, .. }),
            "{e}"
        );
    }

    #[test]
    fn time_not_increasing() {
        let e = parse("time_s,gap_um\n0,1\n0.001,1\n# c\n0.001,1\n").unwrap_err();
        assert!(
            matches!(e, RecordingError::TimeNotIncreasing { line: 5, .. }),
            "{e}"
        );
        let e = parse("time_s,gap_um\n0,1\n-0.001,1\n").unwrap_err();
        assert!(
            matches!(e, RecordingError::TimeNotIncreasing { line: 3, .. }),
            "{e}"
        );
    }

    #[test]
    fn gap_of_several_sample_intervals() {
        let mut text = String::from("time_s,gap_um\n# header comment\n");
        for i in 0..100 {
            let t = if i < 60 {
                i as f64 * 0.001
            } else {
                (i + 4) as f64 * 0.001
            };
            text += &format!("{t},1\n");
        }
        let e = parse(&text).unwrap_err();
        match e {
            // Row 60 (0-based) is on line 2 + 1 + 60 = 63.
            RecordingError::SampleGap {
                line,
                interval_s,
                nominal_interval_s,
                ..
            } => {
                assert_eq!(line, 63);
                approx::assert_relative_eq!(interval_s, 0.005, max_relative = 1e-9);
                approx::assert_relative_eq!(nominal_interval_s, 0.001, max_relative = 1e-9);
            }
            e => panic!("{e}"),
        }
        assert!(parse(&rows(100)).is_ok());
    }

    #[test]
    fn streamed_file_equals_in_memory_parse() {
        // Over two chunks of comments before the header, then rows with CRLF, comments,
        // blank lines and rows the fast path declines, crossing several chunk boundaries.
        let mut text = String::new();
        while text.len() < CHUNK_BYTES + CHUNK_BYTES / 2 {
            text += "# a long preamble of comments ............................................\n";
        }
        text += "time_s,gap_um,angle_deg\r\n";
        for i in 0..120_000 {
            let t = i as f64 * 0.001;
            match i % 1000 {
                7 => text += "# comment\n\n",
                8 => text += &format!(" {t} , {} ,{}\r\n", -1.5e-3 * i as f64, (i % 360) as f64),
                _ => {
                    text += &format!(
                        "{t:.6},{:.6},{:.4}\n",
                        50.0 + (i as f64).sin(),
                        (i % 360) as f64
                    )
                }
            }
        }
        text += "120.0,1.0,2.0"; // no final line end
        let dir = std::env::temp_dir().join(format!("recording-stream-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.csv");
        std::fs::write(&path, &text).unwrap();
        let loaded = load_recording(&path, &RecordingFormat::default()).unwrap();
        let parsed = parse_recording(text.as_bytes(), &path, &RecordingFormat::default()).unwrap();
        assert_eq!(loaded, parsed);
        assert_eq!(loaded.len(), 120_000 - 120 + 1); // every thousandth row is a comment
        // An error deep in the file names its line when streamed too.
        let bad = text.replacen("99.999000,", "99.999000x,", 1);
        std::fs::write(&path, &bad).unwrap();
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        let header_line = text.lines().position(|l| l.starts_with("time_s")).unwrap() + 1;
        let line = bad
            .lines()
            .position(|l| l.starts_with("99.999000x"))
            .unwrap()
            + 1;
        assert!(line > header_line);
        assert!(
            matches!(e, RecordingError::Parse { line: l, .. } if l == line),
            "{e}"
        );
        // A gap, found after the parse, is located by reading the file again.
        let gap: String = text
            .split_inclusive('\n')
            .filter(|l| {
                !["100.000", "100.001", "100.002", "100.003", "100.004"]
                    .iter()
                    .any(|p| l.starts_with(p))
            })
            .collect();
        std::fs::write(&path, &gap).unwrap();
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        let line = gap
            .lines()
            .position(|l| l.starts_with("100.005000,"))
            .unwrap()
            + 1;
        assert!(
            matches!(e, RecordingError::SampleGap { line: l, .. } if l == line),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Fixed-width rows, so that editing a value keeps every byte offset.
    fn fixed_rows(n: usize, time_of: impl Fn(usize) -> f64) -> String {
        let mut text = String::from("time_s,gap_um\n");
        for i in 0..n {
            text += &format!(
                "{:014.6},{:09.6}\n",
                time_of(i),
                50.0 + (i as f64 * 0.01).sin()
            );
        }
        text
    }

    #[test]
    fn parallel_halves_join_in_order_and_locate_errors() {
        let n = 40_000; // 1 MB: parsed in two halves
        let text = fixed_rows(n, |i| i as f64 * 0.001);
        assert!(text.len() >= 2 * PARALLEL_BYTES);
        let rec = parse(&text).unwrap();
        assert_eq!(rec.len(), n);
        assert!(rec.time_s.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(rec.time_s[n - 1], (n - 1) as f64 * 0.001);
        // Where the halves meet: the row starting after the line end past the middle.
        let header_end = text.find('\n').unwrap() + 1;
        let mid = header_end + (text.len() - header_end) / 2;
        let cut = mid + text[mid..].find('\n').unwrap() + 1;
        let row_at_cut = text[header_end..cut].matches('\n').count();
        let line_at_cut = row_at_cut + 2;
        // A time that steps back exactly at the join, inside the second half, and inside
        // the first half: each names its own line.
        for row in [row_at_cut, row_at_cut + 1000, row_at_cut - 1000] {
            let bad = fixed_rows(n, |i| {
                if i >= row {
                    i as f64 * 0.001 - 1.0
                } else {
                    i as f64 * 0.001
                }
            });
            let e = parse(&bad).unwrap_err();
            assert!(
                matches!(e, RecordingError::TimeNotIncreasing { line, .. } if line == row + 2),
                "row {row}: {e}"
            );
        }
        // Parse errors and non-finite values in the second half name their line.
        let lines: Vec<&str> = text.lines().collect();
        let target = line_at_cut + 500;
        let broken = text.replacen(lines[target - 1], &lines[target - 1].replace(',', ";"), 1);
        let e = parse(&broken).unwrap_err();
        assert!(
            matches!(e, RecordingError::Parse { line, .. } if line == target),
            "{e}"
        );
        let nan = text.replacen(
            lines[target - 1],
            &format!("{},NaN", &lines[target - 1][..14]),
            1,
        );
        let e = parse(&nan).unwrap_err();
        assert!(
            matches!(e, RecordingError::NonFinite { line, .. } if line == target),
            "{e}"
        );
    }

    #[test]
    fn io_error_names_the_file() {
        let e = load_recording(
            Path::new("/nonexistent/rec.csv"),
            &RecordingFormat::default(),
        )
        .unwrap_err();
        assert!(matches!(e, RecordingError::Io { .. }));
        assert!(e.to_string().starts_with("/nonexistent/rec.csv: "), "{e}");
    }

    #[test]
    fn bad_format() {
        let format = RecordingFormat {
            delimiter: '.',
            ..RecordingFormat::default()
        };
        let e = parse_recording(b"time_s.gap_um\n", Path::new("r"), &format).unwrap_err();
        assert!(matches!(
            e,
            RecordingError::InvalidFormat {
                field: "delimiter",
                ..
            }
        ));
    }

    #[test]
    fn fixture_is_the_generator_output_and_gives_its_coefficients() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fixtures/recordings/probe_120deg_s.csv");
        let spec = SyntheticSpec::default();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            text,
            spec.csv(),
            "regenerate with the synth_recording example"
        );
        assert!(text.len() < 300_000);
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        let fit = analyze_recording(
            &rec,
            120f64.to_radians(),
            0.0,
            &harmonics::FitConfig::default(),
        )
        .unwrap();
        assert_eq!(fit.revolutions_used(), 2);
        assert!(fit.incomplete.is_some());
        let n = fit.revolutions.iter().map(|r| r.samples).sum::<usize>() as f64;
        let bound = 6.0 * spec.noise_um * (2.0 / n).sqrt();
        for k in 0..4 {
            approx::assert_abs_diff_eq!(fit.mean.c[k], spec.coefficients.c[k], epsilon = bound);
            approx::assert_abs_diff_eq!(fit.mean.s[k], spec.coefficients.s[k], epsilon = bound);
        }
    }

    #[test]
    fn analysis_errors_name_the_line() {
        let dir = std::env::temp_dir().join(format!("recording-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // Half a revolution: no complete revolution.
        let spec = SyntheticSpec {
            revolutions: 0.5,
            ..SyntheticSpec::default()
        };
        let path = dir.join("half.csv");
        std::fs::write(&path, spec.csv()).unwrap();
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        let e = analyze_recording(
            &rec,
            120f64.to_radians(),
            0.0,
            &harmonics::FitConfig::default(),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::Samples {
                    error: HarmonicsError::NoCompleteRevolution { .. },
                    ..
                }
            ),
            "{e}"
        );
        // An encoder stepping back at row 100, line 103 (after the comment and the header).
        let mut text = SyntheticSpec::default().csv();
        let lines: Vec<&str> = text.lines().collect();
        let fields: Vec<&str> = lines[102].split(',').collect();
        let back = format!(
            "{},{},{}",
            fields[0],
            fields[1],
            fields[2].parse::<f64>().unwrap() - 1.0
        );
        text = text.replacen(lines[102], &back, 1);
        let path = dir.join("back.csv");
        std::fs::write(&path, &text).unwrap();
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        let e = analyze_recording(
            &rec,
            120f64.to_radians(),
            0.0,
            &harmonics::FitConfig::default(),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::Samples {
                    line: Some(103),
                    error: HarmonicsError::AngleNotIncreasing { index: 100, .. },
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("back.csv:103: sample 100"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn encoder_file_at_another_rate_than_declared_is_refused() {
        let spec = SyntheticSpec::default(); // 120 deg/s, with an encoder and speed ripple
        let rec = parse(&spec.csv()).unwrap();
        let config = harmonics::FitConfig::default();
        assert!(analyze_recording(&rec, 120f64.to_radians(), 0.0, &config).is_ok());
        assert!(analyze_recording(&rec, 118f64.to_radians(), 0.0, &config).is_ok());
        let e = analyze_recording(&rec, 10f64.to_radians(), 0.0, &config).unwrap_err();
        match &e {
            RecordingError::Samples {
                line: None,
                error:
                    HarmonicsError::RateMismatch {
                        declared_rad_s,
                        encoder_rad_s,
                        ..
                    },
                ..
            } => {
                approx::assert_relative_eq!(*declared_rad_s, 10f64.to_radians());
                approx::assert_relative_eq!(
                    *encoder_rad_s,
                    120f64.to_radians(),
                    max_relative = 1e-2 // the ripple moves the mean by 0.3 %
                );
            }
            e => panic!("{e}"),
        }
        assert!(
            e.to_string().starts_with("rec.csv: declared spindle rate"),
            "{e}"
        );
        // Without the encoder column the rate gives the angle and nothing is compared.
        let no_encoder = SyntheticSpec {
            encoder: false,
            ..spec
        };
        let rec = parse(&no_encoder.csv()).unwrap();
        assert!(analyze_recording(&rec, 120f64.to_radians(), 0.0, &config).is_ok());
    }

    #[test]
    fn overflowing_time_intervals_are_an_error() {
        let e = parse("time_s,gap_um\n-1e308,1\n1e308,1\n").unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::Samples {
                    line: Some(3),
                    error: HarmonicsError::NonFiniteInterval { index: 1, .. },
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn signal_uses_the_encoder_when_present() {
        let rec = parse("time_s,gap_um,angle_deg\n0,1,10\n0.001,1,11\n").unwrap();
        assert!(matches!(
            rec.signal(1.0, 0.0).angle,
            SpindleAngle::Encoder(_)
        ));
        let rec = parse("time_s,gap_um\n0,1\n0.001,1\n").unwrap();
        assert_eq!(
            rec.signal(2.0, 0.5).angle,
            SpindleAngle::Rate {
                rate_rad_s: 2.0,
                start_angle_rad: 0.5
            }
        );
    }

    #[test]
    fn header_as_last_line_without_line_end_is_no_samples() {
        for text in [
            "time_s,gap_um",
            "# c\ntime_s,gap_um\r",
            "# c\r\ntime_s,gap_um\r\n",
        ] {
            let e = parse(text).unwrap_err();
            assert!(
                matches!(e, RecordingError::NoSamples { .. }),
                "{text:?}: {e}"
            );
        }
    }

    #[test]
    fn comment_is_not_data_when_the_first_column_is_skipped() {
        let text = "label,time_s,gap_um\nx,0,1\n#note,0.0005,999\n  #note,0.0007,999\nx,0.001,2\n";
        let rec = parse(text).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [1.0, 2.0]);
    }

    #[test]
    fn utf8_byte_order_mark_is_skipped() {
        let rec = parse("\u{feff}time_s,gap_um\n0,1\n0.001,2\n").unwrap();
        assert_eq!(rec.gap, [1.0, 2.0]);
        let rec = parse("\u{feff}# c\ntime_s,gap_um\n0,1\n0.001,2\n").unwrap();
        assert_eq!(rec.gap, [1.0, 2.0]);
    }

    #[test]
    fn lone_carriage_returns_end_lines() {
        let text = "# c\rtime_s,gap_um\r0,1\r\r0.001,2\r0.002,3";
        let rec = parse(text).unwrap();
        assert_eq!(rec.gap, [1.0, 2.0, 3.0]);
        let e = parse("time_s,gap_um\r0,1\r0.001,x\r").unwrap_err();
        assert!(matches!(e, RecordingError::Parse { line: 3, .. }), "{e}");
    }

    #[test]
    fn fast_and_slow_paths_split_blank_delimited_fields_alike() {
        let format = RecordingFormat {
            delimiter: ' ',
            ..RecordingFormat::default()
        };
        // A tab inside the skipped first field, and a run of blanks after it.
        let text = "idx\ttime_s gap_um\n0\t0.000 47.0 0\n1\t0.001 48.0 0\n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [47.0, 48.0]);
        // A run of blanks after a skipped field is one separator, not an empty field.
        let text = "a b time_s gap_um\nx  5 0 1\nx  6 0.001 2\n";
        let rec = parse_recording(text.as_bytes(), Path::new("r.txt"), &format).unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [1.0, 2.0]);
    }

    #[test]
    fn quoted_numbers_are_read() {
        let rec =
            parse("\"time_s\",\"gap_um\"\n\"0.000000\",\"1.5\"\n\"0.001\", \"2\" \n").unwrap();
        assert_eq!(rec.time_s, [0.0, 0.001]);
        assert_eq!(rec.gap, [1.5, 2.0]);
    }

    #[test]
    fn overlapping_column_names_are_refused() {
        for (time, gap, angle, field) in [
            ("t", "t", "a", "gap_column"),
            ("t", "g", "t", "angle_column"),
            ("t", "g", "g", "angle_column"),
        ] {
            let format = RecordingFormat {
                time_column: time.into(),
                gap_column: gap.into(),
                angle_column: angle.into(),
                ..RecordingFormat::default()
            };
            let e = parse_recording(b"t,g\n0,1\n", Path::new("r"), &format).unwrap_err();
            assert!(
                matches!(e, RecordingError::InvalidFormat { field: f, .. } if f == field),
                "{e}"
            );
        }
    }

    #[test]
    fn file_without_line_feeds_loads_in_linear_time() {
        let dir = std::env::temp_dir().join(format!("recording-cr-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // CR-only line ends over several chunks: read once, lines ended by CR.
        let mut text = String::from("time_s,gap_um\r");
        let mut i = 0;
        while text.len() < 3 * CHUNK_BYTES {
            text += &format!("{:.6},{:.6}\r", i as f64 * 0.001, (i as f64).sin());
            i += 1;
        }
        let path = dir.join("cr.csv");
        std::fs::write(&path, &text).unwrap();
        let start = std::time::Instant::now();
        let rec = load_recording(&path, &RecordingFormat::default()).unwrap();
        assert_eq!(rec.len(), i);
        assert_eq!(
            rec,
            parse_recording(text.as_bytes(), &path, &RecordingFormat::default()).unwrap()
        );
        // A file with no line end at all is refused once the longest line is exceeded.
        let binary = vec![b'x'; MAX_LINE_BYTES + 10];
        std::fs::write(&path, &binary).unwrap();
        let e = load_recording(&path, &RecordingFormat::default()).unwrap_err();
        assert!(
            matches!(e, RecordingError::LineTooLong { line: 1, .. }),
            "{e}"
        );
        assert!(e.to_string().contains("cr.csv"), "{e}");
        assert!(start.elapsed().as_secs_f64() < 5.0);
        // BOM in a streamed file too.
        std::fs::write(&path, "\u{feff}time_s,gap_um\n0,1\n0.001,2\n").unwrap();
        assert_eq!(
            load_recording(&path, &RecordingFormat::default())
                .unwrap()
                .gap,
            [1.0, 2.0]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
