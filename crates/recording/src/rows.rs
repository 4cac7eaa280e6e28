//! Parsing rows: the fast in-place path, the field-by-field path and the parallel split.

use std::path::Path;

use harmonics::HarmonicsError;

use super::format::delimiter_byte;
use super::lines::{Lines, line_of_row, split_fields, trim_quotes};
use super::number::{fast_prefix, parse_f64};
use super::sample_index;
use super::{Recording, RecordingError, RecordingFormat};

/// Pieces of text at least this long are parsed on two threads.
pub(super) const PARALLEL_BYTES: usize = 256 * 1024;

/// The columns a header names.
pub(super) struct Columns {
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
pub(super) struct RowParser<'a> {
    path: &'a Path,
    format: &'a RecordingFormat,
    delimiter: u8,
    /// Lines seen so far.
    pub(super) line: usize,
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
    pub(super) fn new(
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
    pub(super) fn feed(&mut self, text: &[u8]) -> Result<(), RecordingError> {
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
        if let (Some(&t), Some(line)) = (second.time_s.first(), second.first_row_line)
            && t <= self.previous_s
        {
            return Err(RecordingError::TimeNotIncreasing {
                path: self.path.to_owned(),
                line: offset + line,
                previous_s: self.previous_s,
                time_s: t,
            });
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
    pub(super) fn finish(self, text: Option<&[u8]>) -> Result<Recording, RecordingError> {
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
pub(super) enum RowError {
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
pub(super) fn parse_row_slowly(
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

/// Sentinel of [`fast_row`]'s field map: a column that is not stored.
pub(super) const SKIP: u8 = u8::MAX;

/// Parses a plain row `number,number,…` starting at `pos` straight from the text: stores
/// the wanted fields (`dest_of[field]` is the destination in `values`, or [`SKIP`]) and
/// returns where the next line starts. `None` on anything else (comment, blank line, blanks
/// around fields, quotes, short row, a value the fast path does not take): the caller then
/// parses the line the slow way, which also reports errors.
#[inline(always)]
pub(super) fn fast_row(
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
