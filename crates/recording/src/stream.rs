//! A probe recording analysed as it is read (issue 32): memory bounded by about one
//! revolution and the reader's buffer, whatever the file's size, with the numbers, checks
//! and errors of [`load_recording`](crate::load_recording) then
//! [`analyze_recording`](crate::analyze_recording) to the bit.
//!
//! A delimited-text recording is read twice, never held: first its rows are counted (the
//! nominal sample interval is the median of intervals at places that follow from the
//! count), then they are parsed a chunk at a time into `harmonics`' [`StreamingFit`],
//! which keeps one revolution. Where each chunk starts in the file is noted (a few bytes
//! per megabyte), so the checks after the fit that look at a revolution's residuals (the
//! outlier revolution's largest residual, the alternating-residual test's eight
//! revolutions) read just those samples again. What this path does not stream is read
//! into memory as before ([`StreamedRecording::streamed`] says which): TDMS and MAT files,
//! index-pulse angles, the `drop_revolution` policies for gaps and non-finite samples, and
//! files smaller than [`StreamOptions::stream_from_bytes`].

use std::f64::consts::TAU;
use std::ops::Range;
use std::path::{Path, PathBuf};

use harmonics::{
    DeclaredRate, FitConfig, HarmonicsError, RevolutionSource, SampleWindow, SpindleAngle,
    StreamAngle, StreamError, StreamedAnalysis, StreamingFit,
};

use crate::analysis::diagnostic::SampleAt;
use crate::analysis::probe::{Facts, RecordingAnalysis, finish_with, hint_for};
use crate::error::{RecordingError, Result};
use crate::lab::format::{ANGLE_SLOT, AngleSource, LengthUnit, OnBadSamples, RecordingFormat};
use crate::lab::probe::{AngleSourceKind, check_gap_header_unit, sample_index, time_axis_error};
use crate::text::lines::Lines;
use crate::text::parser::{Layout, TableParser, skip_then_next_content};
use crate::text::stream::{LineSink, Resume, stream_file, stream_file_from};
use crate::text::table::TableFormat;

/// Files smaller than this are read into memory whole (64 MiB): their samples take less
/// memory than a revolution of a long one, and one pass is quicker than two.
pub const STREAM_FROM_BYTES: u64 = 64 << 20;

/// How [`analyze_recording_file`] reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StreamOptions {
    /// The encoder's reading at the angle zero of eq. 20–21, rad
    /// ([`Recording::shift_angle_zero`](crate::Recording::shift_angle_zero)).
    pub angle_zero_rad: f64,
    /// Files of at least this many bytes are streamed; smaller ones are read whole
    /// ([`STREAM_FROM_BYTES`] by default; 0 streams every text recording it can).
    pub stream_from_bytes: u64,
}

impl Default for StreamOptions {
    fn default() -> Self {
        Self {
            angle_zero_rad: 0.0,
            stream_from_bytes: STREAM_FROM_BYTES,
        }
    }
}

/// What [`analyze_recording_file`] is doing, for a progress display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReadStage {
    /// Counting the rows (the first of two passes over a streamed file).
    Counting,
    /// Parsing and fitting the rows (the second pass).
    Fitting,
    /// Reading the file whole (a file that is not streamed).
    Reading,
}

/// Progress of [`analyze_recording_file`]: bytes of the file read in the current stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReadProgress {
    /// The stage.
    pub stage: ReadStage,
    /// Bytes read in it.
    pub bytes_read: u64,
    /// The file's size, bytes.
    pub bytes_total: u64,
}

/// A recording's analysis read from its file, with what a report says of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamedRecording {
    /// The file.
    pub path: PathBuf,
    /// Number of samples.
    pub samples: usize,
    /// Unit of the gap (µm for a gap recorded in volts, converted).
    pub gap_unit: LengthUnit,
    /// The analysis, as [`analyze_recording`](crate::analyze_recording) gives it.
    pub analysis: RecordingAnalysis,
    /// Whether the file was streamed (else read whole into memory).
    pub streamed: bool,
}

/// Reads and analyses a probe recording: [`load_recording`](crate::load_recording),
/// [`Recording::shift_angle_zero`](crate::Recording::shift_angle_zero) and
/// [`analyze_recording`](crate::analyze_recording), with the same numbers, diagnostics and
/// errors, in memory bounded by about one revolution and the reader's buffer for a text
/// recording it can stream (see the module's documentation). `progress` is told how far
/// the reading is (a library prints nothing; the command line draws a bar).
///
/// # Errors
/// Those of [`load_recording`](crate::load_recording) and
/// [`analyze_recording`](crate::analyze_recording).
pub fn analyze_recording_file(
    path: &Path,
    format: &RecordingFormat,
    declared_rate_rad_s: f64,
    config: &FitConfig,
    options: StreamOptions,
    progress: &mut dyn FnMut(ReadProgress),
) -> Result<StreamedRecording> {
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    let streamable = crate::binary::format_of(path).is_none()
        && !matches!(format.angle, AngleSource::IndexPulse { .. })
        && format.on_gap == OnBadSamples::Error
        && format.on_non_finite == OnBadSamples::Error
        && format.group.is_none()
        && !format.waveform_time
        && size >= options.stream_from_bytes;
    if streamable
        && let Some(done) = stream(
            path,
            format,
            declared_rate_rad_s,
            config,
            options,
            (size, progress),
        )?
    {
        return Ok(done);
    }
    in_memory(
        path,
        format,
        declared_rate_rad_s,
        config,
        options,
        (size, progress),
    )
}

/// The recording read whole, then analysed.
fn in_memory(
    path: &Path,
    format: &RecordingFormat,
    declared_rate_rad_s: f64,
    config: &FitConfig,
    options: StreamOptions,
    (size, progress): (u64, &mut dyn FnMut(ReadProgress)),
) -> Result<StreamedRecording> {
    progress(ReadProgress {
        stage: ReadStage::Reading,
        bytes_read: 0,
        bytes_total: size,
    });
    let mut recording = crate::read::load_recording(path, format)?;
    progress(ReadProgress {
        stage: ReadStage::Reading,
        bytes_read: size,
        bytes_total: size,
    });
    recording.shift_angle_zero(options.angle_zero_rad);
    let analysis =
        crate::analysis::probe::analyze_recording(&recording, declared_rate_rad_s, config)?;
    Ok(StreamedRecording {
        path: recording.path.clone(),
        samples: recording.len(),
        gap_unit: recording.gap_unit,
        analysis,
        streamed: false,
    })
}

/// Counts a table's rows: content lines after the skipped lines and the header.
struct RowCounter<'p> {
    skip: usize,
    line: usize,
    header: bool,
    rows: usize,
    total: u64,
    progress: &'p mut dyn FnMut(ReadProgress),
}

impl LineSink for RowCounter<'_> {
    fn feed(&mut self, text: &[u8]) -> Result<()> {
        let mut lines = Lines {
            text,
            pos: 0,
            line: self.line,
        };
        if !self.header {
            self.header = skip_then_next_content(&mut lines, self.skip).is_some();
        }
        if self.header {
            let (rows, line_count) = content_lines(&text[lines.pos..]);
            self.rows += rows;
            lines.line += line_count;
        }
        self.line = lines.line;
        Ok(())
    }

    fn lines_fed(&self) -> usize {
        self.line
    }

    fn at_offset(&mut self, offset: u64) {
        (self.progress)(ReadProgress {
            stage: ReadStage::Counting,
            bytes_read: offset,
            bytes_total: self.total,
        });
    }
}

/// The content lines of a text ([`Lines::next_content`]'s: not blank, not a `#` comment)
/// and all its lines, line ends found by `memchr` (a vector at a time).
fn content_lines(text: &[u8]) -> (usize, usize) {
    let (mut rows, mut lines, mut start) = (0, 0, 0);
    let count = |line: &[u8]| {
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        let t = line.trim_ascii_start();
        usize::from(!t.is_empty() && t[0] != b'#')
    };
    for end in memchr::memchr_iter(b'\n', text) {
        rows += count(&text[start..end]);
        lines += 1;
        start = end + 1;
    }
    if start < text.len() {
        rows += count(&text[start..]);
        lines += 1;
    }
    (rows, lines)
}

/// How the columns read become samples: the recording's units, and the angle zero.
#[derive(Debug, Clone, Copy)]
struct Conversion {
    time_scale: f64,
    um_per_v: Option<f64>,
    angle_scale: f64,
    angle_zero_rad: f64,
}

impl Conversion {
    /// The samples of some rows (format columns), into `t`, `y` and `a` (cleared first;
    /// `a` stays empty without an encoder column).
    fn convert(
        &self,
        columns: &[Option<&[f64]>],
        (t, y, a): (&mut Vec<f64>, &mut Vec<f64>, &mut Vec<f64>),
    ) {
        t.clear();
        y.clear();
        a.clear();
        // As Recording::from_table and shift_angle_zero do it, value by value.
        if let Some(time) = columns[0] {
            t.extend_from_slice(time);
            if self.time_scale != 1.0 {
                t.iter_mut().for_each(|v| *v *= self.time_scale);
            }
        }
        if let Some(gap) = columns[1] {
            y.extend_from_slice(gap);
            if let Some(k) = self.um_per_v {
                y.iter_mut().for_each(|v| *v *= k);
            }
        }
        if let Some(Some(angle)) = columns.get(ANGLE_SLOT) {
            a.extend_from_slice(angle);
            if self.angle_scale != 1.0 {
                a.iter_mut().for_each(|v| *v *= self.angle_scale);
            }
            if self.angle_zero_rad != 0.0 {
                a.iter_mut().for_each(|v| *v -= self.angle_zero_rad);
            }
        }
    }
}

/// Where a chunk of the file starts: the byte, the rows and lines before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Checkpoint {
    offset: u64,
    rows: usize,
    line: usize,
}

/// The second pass: rows parsed a chunk at a time into the streaming fit.
struct FitSink<'a, 'p> {
    parser: TableParser<'a>,
    conversion: Conversion,
    /// The fit, made when the header tells where the angle comes from.
    fit: Option<StreamingFit>,
    make_fit: &'a dyn Fn(bool) -> Result<StreamingFit>,
    error: Option<RecordingError>,
    checkpoints: Vec<Checkpoint>,
    buffers: (Vec<f64>, Vec<f64>, Vec<f64>),
    total: u64,
    progress: &'p mut dyn FnMut(ReadProgress),
}

impl LineSink for FitSink<'_, '_> {
    fn feed(&mut self, text: &[u8]) -> Result<()> {
        self.parser.feed(text)?;
        let (t, y, a) = &mut self.buffers;
        let conversion = self.conversion;
        let mut encoder = false;
        self.parser.drain_rows(|columns| {
            encoder = columns.get(ANGLE_SLOT).is_some_and(Option::is_some);
            conversion.convert(columns, (t, y, a));
        });
        if self.fit.is_none() && self.error.is_none() && self.parser.layout().is_some() {
            match (self.make_fit)(encoder) {
                Ok(fit) => self.fit = Some(fit),
                Err(e) => self.error = Some(e),
            }
        }
        if let Some(fit) = &mut self.fit {
            fit.push(t, y, encoder.then_some(&a[..]));
        }
        Ok(())
    }

    fn lines_fed(&self) -> usize {
        self.parser.line
    }

    fn at_offset(&mut self, offset: u64) {
        if self.parser.layout().is_some() {
            self.checkpoints.push(Checkpoint {
                offset,
                rows: self.parser.rows_read(),
                line: self.parser.line,
            });
        }
        (self.progress)(ReadProgress {
            stage: ReadStage::Fitting,
            bytes_read: offset,
            bytes_total: self.total,
        });
    }
}

/// The recording streamed; `None` when it is better read whole (too few rows to stream, or
/// the two passes disagree on the rows: the file changed between them).
fn stream(
    path: &Path,
    format: &RecordingFormat,
    declared_rate_rad_s: f64,
    config: &FitConfig,
    options: StreamOptions,
    (size, progress): (u64, &mut dyn FnMut(ReadProgress)),
) -> Result<Option<StreamedRecording>> {
    crate::read::text_only(path, format)?;
    let table_format = format.table_format()?;
    let mut counter = RowCounter {
        skip: table_format.skip_lines,
        line: 0,
        header: false,
        rows: 0,
        total: size,
        progress: &mut *progress,
    };
    stream_file(path, &mut counter, None)?;
    let rows = counter.rows;
    if rows < 2 {
        return Ok(None);
    }
    let config = FitConfig {
        max_gap_intervals: format.max_gap_intervals,
        ..config.clone()
    };
    let located_early = |source: HarmonicsError| RecordingError::Samples {
        path: path.to_owned(),
        line: None,
        hint: None,
        source,
    };
    // The declared rate's angle: θ₀ + ω·(t − t₀), the start angle as Recording::signal
    // forms it (θ₀ + ω·0).
    let start_angle_rad = match format.angle {
        AngleSource::Rate { start_angle_deg } => start_angle_deg.to_radians(),
        _ => 0.0,
    };
    let rate_angle = StreamAngle::Rate {
        rate_rad_s: declared_rate_rad_s,
        start_angle_rad: start_angle_rad + declared_rate_rad_s * 0.0,
    };
    let encoder_format = matches!(format.angle, AngleSource::Encoder { .. });
    let make_fit = |encoder_column: bool| {
        let angle = if encoder_format && encoder_column {
            StreamAngle::Encoder
        } else {
            rate_angle
        };
        StreamingFit::new(&config, angle, rows).map_err(located_early)
    };
    let sensitivity = format.gap.unit.sensitivity();
    let conversion = Conversion {
        time_scale: format.time.unit.s_per_unit(),
        um_per_v: sensitivity
            .as_ref()
            .ok()
            .and_then(|s| s.as_ref().map(|s| s.um_per_v())),
        angle_scale: match &format.angle {
            AngleSource::Encoder { unit, .. } => unit.rad_per_unit(),
            _ => 1.0,
        },
        angle_zero_rad: options.angle_zero_rad,
    };
    let mut sink = FitSink {
        parser: TableParser::new(path, &table_format, 0)?,
        conversion,
        fit: None,
        make_fit: &make_fit,
        error: None,
        checkpoints: vec![Checkpoint {
            offset: 0,
            rows: 0,
            line: 0,
        }],
        buffers: (Vec::new(), Vec::new(), Vec::new()),
        total: size,
        progress: &mut *progress,
    };
    let lone_cr = stream_file_from(path, Resume::default(), &mut sink, None)?;
    let FitSink {
        parser,
        fit,
        error,
        checkpoints,
        ..
    } = sink;
    let layout = parser.layout().cloned();
    let rows_parsed = parser.rows_read();
    let table = parser.finish()?;
    let (Some(mut fit), Some(layout)) = (fit, layout) else {
        return match error {
            Some(e) => Err(e),
            None => Ok(None),
        };
    };
    if rows_parsed != rows || fit.samples_seen() != rows {
        return Ok(None);
    }
    check_gap_header_unit(&table.header, path, format, table.header_line)?;
    sensitivity?;
    let unread_columns: Vec<String> = table
        .header
        .iter()
        .filter(|h| !table.names.contains(h))
        .cloned()
        .collect();
    let lines = &table.lines;
    let time_axis = fit.check_time_axis();
    time_axis.map_err(|e| time_axis_error(e, path, lines))?;
    let encoder = table.columns.get(ANGLE_SLOT).is_some_and(Option::is_some) && encoder_format;
    let angle_source = if encoder {
        AngleSourceKind::Encoder
    } else {
        AngleSourceKind::DeclaredRate
    };
    let located = |source: HarmonicsError| RecordingError::Samples {
        path: path.to_owned(),
        line: sample_index(&source).map(|row| lines.line_of(row)),
        hint: hint_for(angle_source, &source),
        source,
    };
    if encoder {
        harmonics::check_measured_rate(
            fit.encoder_rate_rad_s(),
            DeclaredRate::new(declared_rate_rad_s),
        )
        .map_err(located)?;
    }
    let streamed = match fit.finish() {
        Ok(s) => s,
        Err(StreamError::TimeAxis(e)) => return Err(time_axis_error(e, path, lines)),
        Err(StreamError::Analysis(e)) => return Err(located(e)),
    };
    let measured_rate_rad_s = encoder.then(|| measured_rate(&streamed, rows)).flatten();
    let start_angle_rad = if encoder { 0.0 } else { start_angle_rad };
    let facts = Facts {
        angle_source,
        unread_columns: &unread_columns,
        start_angle_rad,
        gap_unit: format.gap.unit.length_unit(),
        on_outlier: format.on_outlier,
    };
    let mut source = FileSource {
        path,
        format: &table_format,
        layout,
        lone_cr,
        checkpoints,
        conversion,
        angle: if encoder { None } else { Some(rate_angle) },
        recording_start_s: streamed.marks.first().map_or(f64::NAN, |m| m.time_s),
        buffers: (Vec::new(), Vec::new(), Vec::new()),
        first_sample: 0,
    };
    let mark = |i: usize| streamed.mark(i);
    let analysis = finish_with(
        &facts,
        &mut source,
        |i| SampleAt::Line(lines.line_of(i)),
        (
            |i| mark(i).map_or(f64::NAN, |m| m.angle_rad),
            |i| mark(i).map_or(f64::NAN, |m| m.time_s),
        ),
        streamed.analysis.clone(),
        (declared_rate_rad_s, measured_rate_rad_s, 0),
        &config,
    )?;
    Ok(Some(StreamedRecording {
        path: path.to_owned(),
        samples: rows,
        gap_unit: format.gap.unit.length_unit(),
        analysis,
        streamed: true,
    }))
}

/// The encoder's mean rate over the whole revolutions fitted
/// ([`Recording::measured_rate_between`](crate::Recording::measured_rate_between) from
/// the first one's first sample to the sample after the last one), from the marks.
fn measured_rate(streamed: &StreamedAnalysis, rows: usize) -> Option<f64> {
    let revolutions = &streamed.analysis.revolutions;
    let (first, last) = (revolutions.first()?, revolutions.last()?);
    let from = first.first_sample;
    let to = (last.first_sample + last.samples).min(rows - 1);
    if to <= from {
        return None;
    }
    let (a, b) = (streamed.mark(from)?, streamed.mark(to)?);
    let span = b.angle_rad - a.angle_rad + TAU * (b.wraps_before - a.wraps_before) as f64;
    Some(span / (b.time_s - a.time_s))
}

/// A streamed recording's file, read again from a noted chunk for the samples of a few
/// revolutions.
struct FileSource<'a> {
    path: &'a Path,
    format: &'a TableFormat,
    layout: Layout,
    lone_cr: Option<bool>,
    checkpoints: Vec<Checkpoint>,
    conversion: Conversion,
    /// `None` with an encoder.
    angle: Option<StreamAngle>,
    recording_start_s: f64,
    buffers: (Vec<f64>, Vec<f64>, Vec<f64>),
    first_sample: usize,
}

/// Rows parsed from a chunk on until `end` rows are read.
struct WindowSink<'a, 'b> {
    parser: TableParser<'a>,
    conversion: Conversion,
    end: usize,
    buffers: &'b mut (Vec<f64>, Vec<f64>, Vec<f64>),
    scratch: (Vec<f64>, Vec<f64>, Vec<f64>),
}

impl LineSink for WindowSink<'_, '_> {
    fn feed(&mut self, text: &[u8]) -> Result<()> {
        self.parser.feed(text)?;
        let conversion = self.conversion;
        let (t, y, a) = &mut self.scratch;
        self.parser
            .drain_rows(|columns| conversion.convert(columns, (t, y, a)));
        self.buffers.0.extend_from_slice(t);
        self.buffers.1.extend_from_slice(y);
        self.buffers.2.extend_from_slice(a);
        Ok(())
    }

    fn lines_fed(&self) -> usize {
        self.parser.line
    }

    fn done(&self) -> bool {
        self.parser.rows_read() >= self.end
    }
}

impl RevolutionSource for FileSource<'_> {
    type Error = RecordingError;

    fn samples(&mut self, range: Range<usize>) -> Result<SampleWindow<'_>> {
        let k = self
            .checkpoints
            .partition_point(|c| c.rows <= range.start)
            .saturating_sub(1);
        let cp = self.checkpoints[k];
        let (parser, resume) = if cp.offset == 0 {
            (
                TableParser::new(self.path, self.format, 0)?,
                Resume::default(),
            )
        } else {
            (
                TableParser::resumed(
                    self.path,
                    self.format,
                    self.layout.clone(),
                    cp.line,
                    cp.rows,
                )?,
                Resume {
                    offset: cp.offset,
                    lone_cr: self.lone_cr,
                },
            )
        };
        self.buffers.0.clear();
        self.buffers.1.clear();
        self.buffers.2.clear();
        let mut sink = WindowSink {
            parser,
            conversion: self.conversion,
            end: range.end,
            buffers: &mut self.buffers,
            scratch: (Vec::new(), Vec::new(), Vec::new()),
        };
        stream_file_from(self.path, resume, &mut sink, None)?;
        if sink.parser.rows_read() < range.end {
            return Err(RecordingError::Io {
                path: self.path.to_owned(),
                source: std::io::Error::new(
                    std::io::ErrorKind::UnexpectedEof,
                    "the file became shorter while it was read",
                ),
            });
        }
        self.first_sample = cp.rows;
        let angle = match self.angle {
            None => SpindleAngle::Encoder(&self.buffers.2),
            Some(StreamAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            }) => SpindleAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            },
            Some(StreamAngle::Encoder) => SpindleAngle::Encoder(&self.buffers.2),
        };
        Ok(SampleWindow {
            first_sample: self.first_sample,
            recording_start_s: self.recording_start_s,
            time_s: &self.buffers.0,
            gap: &self.buffers.1,
            angle,
        })
    }
}
