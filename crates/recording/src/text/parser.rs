//! The one parser behind every reader of this crate: a delimited text table fed in whole
//! lines (from a file streamed through one reused buffer, or from memory) into a [`Table`].

use std::path::Path;

use super::line_table::LineTable;
use super::lines::{Lines, field_text, normalized, split_fields, trim_quotes};
use super::rows::{SKIP, Syntax, fast_row, parse_row_slowly};
use super::stream::{CHUNK_BYTES, LineSink, stream_file};
use super::table::{MAX_COLUMNS, Table, TableFormat};
use crate::digest::{FileDigest, Hasher};
use crate::error::{Hint, RecordingError, Result};

/// Pieces of text at least this long are parsed on two threads.
pub(crate) const PARALLEL_BYTES: usize = 256 * 1024;

/// Most rows reserved before any is read: a chunk's worth (rows are rarely shorter than 16
/// bytes). Columns then grow with the rows actually read.
const RESERVED_ROWS: usize = CHUNK_BYTES / 16;

/// Reads a table from a file, streaming it through one reused buffer of about a megabyte
/// (a line longer than 16 MiB is [`RecordingError::LineTooLong`]); the columns grow with
/// the rows read.
///
/// Lines end with LF, CRLF, or (in a file whose first line end is one) a lone CR; a
/// leading UTF-8 byte-order mark is skipped; blank lines and lines starting with `#` are
/// skipped; the first other line is the header; fields may be quoted and have blanks
/// around them. Errors name the file and the 1-based line.
pub fn load_table(path: &Path, format: &TableFormat) -> Result<Table> {
    let mut parser = TableParser::new(path, format, CHUNK_BYTES)?;
    stream_file(path, &mut parser, None)?;
    parser.finish()
}

/// [`load_table`], with the size and SHA-256 of the bytes it read, taken as it read them
/// (the file is read once).
pub fn load_table_digested(path: &Path, format: &TableFormat) -> Result<(Table, FileDigest)> {
    let mut parser = TableParser::new(path, format, CHUNK_BYTES)?;
    let mut hasher = Hasher::default();
    stream_file(path, &mut parser, Some(&mut hasher))?;
    Ok((parser.finish()?, hasher.finish()))
}

/// Parses a table held in memory (as [`load_table`] reads a file); `path` names it in
/// errors.
///
/// ```
/// use recording::{TableColumn, TableFormat, parse_table};
/// let format = TableFormat {
///     delimiter: ';',
///     ..TableFormat::new(
///         vec![TableColumn::required("rate_deg_s"), TableColumn::optional("temp_c")],
///         false,
///     )
/// };
/// let text = "# run 3\nrate_deg_s;label\n10;a\n\n20;\"b\"\n";
/// let table = parse_table(text.as_bytes(), "t.csv".as_ref(), &format)?;
/// assert_eq!(table.column("rate_deg_s"), Some(&[10.0, 20.0][..]));
/// assert_eq!(table.column("temp_c"), None);
/// assert_eq!(table.line_of_row(1), 5);
/// # Ok::<(), recording::RecordingError>(())
/// ```
pub fn parse_table(text: &[u8], path: &Path, format: &TableFormat) -> Result<Table> {
    let text = normalized(text);
    let mut parser = TableParser::new(path, format, text.len())?;
    parser.feed(&text)?;
    parser.finish()
}

/// [`parse_table`] with every row parsed field by field: the reference path that the fast
/// in-place path must agree with (same table, same error), for the tests and the fuzz
/// targets. Not part of the crate's interface.
#[doc(hidden)]
pub fn parse_table_reference(text: &[u8], path: &Path, format: &TableFormat) -> Result<Table> {
    let text = normalized(text);
    let mut parser = TableParser::new(path, format, text.len())?;
    parser.fast = false;
    parser.feed(&text)?;
    parser.finish()
}

/// Where the format's columns are in the header.
#[derive(Debug, Clone)]
pub(crate) struct Layout {
    /// Format index of each column the header has, in format order; a column's place here
    /// is its slot.
    present: Vec<usize>,
    /// `(field, slot)` of those columns, sorted by field.
    wanted: Vec<(usize, usize)>,
    /// Slot of each field up to the last one the fast path reads ([`SKIP`] for others).
    dest_of: Vec<u8>,
    /// Fields of the header.
    width: usize,
    /// Field of the label column, when the format names one.
    label_field: Option<usize>,
}

/// The state of a parse fed with whole lines.
pub(crate) struct TableParser<'a> {
    path: &'a Path,
    format: &'a TableFormat,
    syntax: Syntax,
    /// Lines seen so far.
    pub(crate) line: usize,
    header_line: usize,
    header: Vec<String>,
    layout: Option<Layout>,
    /// Values of the columns present, by slot.
    data: Vec<Vec<f64>>,
    /// Rows parsed.
    rows: usize,
    lines: LineTable,
    /// Bytes of text expected, for the first reservation of the columns.
    size_hint: usize,
    /// Whether plain rows take the in-place fast path (`false`: every row field by field,
    /// the reference the fast path must agree with).
    fast: bool,
    /// Each row's label, when the format names a label column.
    labels: Vec<String>,
}

impl<'a> TableParser<'a> {
    pub(crate) fn new(path: &'a Path, format: &'a TableFormat, size_hint: usize) -> Result<Self> {
        Ok(Self {
            path,
            format,
            syntax: format.check()?,
            line: 0,
            header_line: 0,
            header: Vec::new(),
            layout: None,
            data: Vec::new(),
            rows: 0,
            lines: LineTable::default(),
            size_hint,
            // A label column is text, which only the field-by-field path reads.
            fast: format.label.is_none(),
            labels: Vec::new(),
        })
    }

    fn header(&mut self, line: usize, header: &[u8]) -> Result<Layout> {
        let names: Vec<String> = split_fields(header, self.syntax.delimiter, self.syntax.blank)
            .map(|f| field_text(trim_quotes(f)))
            .collect();
        let mut present = Vec::new();
        let mut wanted = Vec::new();
        for (k, column) in self.format.columns.iter().enumerate() {
            match names.iter().position(|n| *n == column.name) {
                Some(field) => {
                    wanted.push((field, present.len()));
                    present.push(k);
                }
                None if column.required => {
                    let hint =
                        self.format
                            .accepted(header_hint(&names, &column.name, line, self.format));
                    return Err(RecordingError::MissingColumn {
                        path: self.path.to_owned(),
                        line,
                        column: column.name.clone(),
                        header: names,
                        hint,
                    });
                }
                None => {}
            }
        }
        let label_field = match &self.format.label {
            None => None,
            Some(label) => match names.iter().position(|n| n == label) {
                Some(field) => Some(field),
                None => {
                    let hint = self
                        .format
                        .accepted(header_hint(&names, label, line, self.format));
                    return Err(RecordingError::MissingColumn {
                        path: self.path.to_owned(),
                        line,
                        column: label.clone(),
                        header: names,
                        hint,
                    });
                }
            },
        };
        wanted.sort_unstable();
        let width = names.len();
        // A flexible table's fast path stops at the last field read; a strict one's reads
        // every field, so that the row must end there.
        let last = match self.format.flexible {
            true => wanted.last().map_or(0, |w| w.0),
            false => width.saturating_sub(1),
        };
        let mut dest_of = vec![SKIP; last + 1];
        for &(field, slot) in &wanted {
            // At most MAX_COLUMNS slots, so each fits a byte below SKIP.
            dest_of[field] = slot as u8;
        }
        let reserve = self.size_hint.div_ceil(16).min(RESERVED_ROWS);
        self.data = present
            .iter()
            .map(|_| Vec::with_capacity(reserve))
            .collect();
        self.header_line = line;
        self.header = names;
        Ok(Layout {
            present,
            wanted,
            dest_of,
            width,
            label_field,
        })
    }

    /// A parser that continues a file already read once from a line's start: the same
    /// header (`layout`), the line before it `line` and `rows` rows before it.
    pub(crate) fn resumed(
        path: &'a Path,
        format: &'a TableFormat,
        layout: Layout,
        line: usize,
        rows: usize,
    ) -> Result<Self> {
        let mut parser = Self::new(path, format, 0)?;
        parser.data = layout.present.iter().map(|_| Vec::new()).collect();
        parser.layout = Some(layout);
        parser.line = line;
        parser.rows = rows;
        Ok(parser)
    }

    /// The header's layout, once read.
    pub(crate) fn layout(&self) -> Option<&Layout> {
        self.layout.as_ref()
    }

    /// Rows parsed so far.
    pub(crate) fn rows_read(&self) -> usize {
        self.rows
    }

    /// The values parsed since the last call, by format column (`None` for a column the
    /// header lacks), handed to `f` and then dropped: a streaming reader keeps no rows.
    pub(crate) fn drain_rows(&mut self, f: impl FnOnce(&[Option<&[f64]>])) {
        let Some(layout) = &self.layout else {
            return;
        };
        let mut columns: Vec<Option<&[f64]>> = vec![None; self.format.columns.len()];
        for (&k, values) in layout.present.iter().zip(&self.data) {
            columns[k] = Some(values);
        }
        f(&columns);
        for values in &mut self.data {
            values.clear();
        }
    }

    /// Parses whole lines (the text ends at a line end, or is the file's last piece).
    pub(crate) fn feed(&mut self, text: &[u8]) -> Result<()> {
        let mut lines = Lines {
            text,
            pos: 0,
            line: self.line,
        };
        let layout = match self.layout.take() {
            Some(l) => l,
            None => match skip_then_next_content(&mut lines, self.format.skip_lines) {
                Some((line, header)) => self.header(line, header)?,
                None => {
                    self.line = lines.line;
                    return Ok(());
                }
            },
        };
        let result = self.rows_maybe_parallel(&mut lines, &layout);
        self.layout = Some(layout);
        self.line = lines.line;
        result
    }

    /// A parser for a later piece of the same text: same columns, no rows, lines counted
    /// from 0 (shifted when the pieces are joined).
    fn fork(&self, size_hint: usize) -> Self {
        let reserve = size_hint.div_ceil(16).min(RESERVED_ROWS);
        Self {
            path: self.path,
            format: self.format,
            syntax: self.syntax,
            line: 0,
            header_line: self.header_line,
            header: Vec::new(),
            layout: None,
            data: self
                .data
                .iter()
                .map(|_| Vec::with_capacity(reserve))
                .collect(),
            rows: 0,
            lines: LineTable::default(),
            size_hint,
            fast: self.fast,
            labels: Vec::new(),
        }
    }

    /// Parses the rows of `lines`; a large piece is cut at a line end near its middle and
    /// the halves are parsed on two threads (rayon), then joined in order.
    fn rows_maybe_parallel(&mut self, lines: &mut Lines<'_>, layout: &Layout) -> Result<()> {
        let text = lines.text;
        let rest = text.len() - lines.pos;
        // Labelled tables are read on one thread (they are small).
        let cut = (rest >= PARALLEL_BYTES && layout.label_field.is_none())
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
            return self.rows(lines, layout);
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
        let (r1, r2) = rayon::join(
            || self.rows(&mut first, layout),
            || second.rows(&mut later, layout),
        );
        r1?;
        let offset = first.line;
        lines.pos = text.len();
        lines.line = offset + later.line;
        r2.map_err(|e| e.with_line_offset(offset))?;
        self.lines.append(&second.lines, self.rows, offset);
        self.rows += second.rows;
        for (column, more) in self.data.iter_mut().zip(&second.data) {
            column.extend_from_slice(more);
        }
        Ok(())
    }

    fn rows(&mut self, lines: &mut Lines<'_>, layout: &Layout) -> Result<()> {
        let text = lines.text;
        let flexible = self.format.flexible;
        let width = (!flexible).then_some(layout.width);
        let mut values = [0.0_f64; MAX_COLUMNS];
        let n = self.data.len().min(MAX_COLUMNS);
        let mut row = self.rows;
        // The line the next row is on if it follows the previous one directly.
        let mut expected = self.lines.predicted(row);
        let result = loop {
            // Fast path: a plain row parsed in place; else the line is parsed field by field.
            let fast = if self.fast {
                fast_row(
                    text,
                    lines.pos,
                    self.syntax,
                    &layout.dest_of,
                    flexible,
                    &mut values,
                )
            } else {
                None
            };
            let line = if let Some(next) = fast {
                lines.pos = next;
                lines.line += 1;
                lines.line
            } else {
                let Some((line, fields)) = lines.next_content() else {
                    break Ok(());
                };
                if let Err(e) =
                    parse_row_slowly(fields, self.syntax, &layout.wanted, width, &mut values)
                {
                    let name = |slot: usize| {
                        layout
                            .present
                            .get(slot)
                            .map(|&k| self.format.columns[k].name.clone())
                            .unwrap_or_default()
                    };
                    break Err(e.located(self.path, line, &name, self.format.hint_keys));
                }
                if let Some(field) = layout.label_field {
                    let label = split_fields(fields, self.syntax.delimiter, self.syntax.blank)
                        .nth(field)
                        .map(|f| field_text(trim_quotes(f)))
                        .unwrap_or_default();
                    self.labels.push(label);
                }
                line
            };
            if line != expected {
                self.lines.record(row, line);
            }
            expected = line + 1;
            row += 1;
            for (column, &v) in self.data.iter_mut().zip(&values[..n]) {
                column.push(v);
            }
        };
        self.rows = row;
        result
    }

    /// The table read: an error if there was no header or no row.
    pub(crate) fn finish(self) -> Result<Table> {
        let Some(layout) = self.layout else {
            return Err(RecordingError::Empty {
                path: self.path.to_owned(),
            });
        };
        if self.rows == 0 {
            return Err(RecordingError::NoRows {
                path: self.path.to_owned(),
                line: self.header_line,
            });
        }
        let mut columns: Vec<Option<Vec<f64>>> = vec![None; self.format.columns.len()];
        for (&k, mut values) in layout.present.iter().zip(self.data) {
            values.shrink_to_fit();
            columns[k] = Some(values);
        }
        Ok(Table {
            path: self.path.to_owned(),
            names: self.format.columns.iter().map(|c| c.name.clone()).collect(),
            columns,
            header_line: self.header_line,
            header: self.header,
            lines: self.lines,
            labels: layout.label_field.map(|_| self.labels),
        })
    }
}

impl LineSink for TableParser<'_> {
    fn feed(&mut self, text: &[u8]) -> Result<()> {
        TableParser::feed(self, text)
    }

    fn lines_fed(&self) -> usize {
        self.line
    }
}

/// The first content line after the first `skip` lines of the text (counted from its
/// first line, so a piece fed later continues the count).
pub(crate) fn skip_then_next_content<'t>(
    lines: &mut Lines<'t>,
    skip: usize,
) -> Option<(usize, &'t [u8])> {
    while lines.line < skip {
        lines.next_line()?;
    }
    lines.next_content()
}

/// What a header without a required column probably means.
fn header_hint(names: &[String], column: &str, line: usize, format: &TableFormat) -> Option<Hint> {
    // Split at another separator, the header would have the column.
    let splits_to_column = |c: char| {
        names.iter().any(|n| {
            n.split(c)
                .any(|part| part.trim().trim_matches('"') == column)
        })
    };
    if let Some(found) = [';', '\t', ',']
        .into_iter()
        .filter(|&c| format.whitespace || c != format.delimiter)
        .find(|&c| splits_to_column(c))
    {
        return Some(Hint::HeaderDelimiter { found });
    }
    // Split at blanks, a name with spaces falls apart.
    let blank = format.whitespace || format.delimiter == ' ';
    if blank && column.contains(' ') && names.iter().any(|n| column.starts_with(n.as_str())) {
        return Some(Hint::HeaderDelimiter { found: '\t' });
    }
    let numeric = names.iter().all(|n| n.trim().parse::<f64>().is_ok());
    let _ = line;
    // One name that splits at another separator into several: the header is there, read
    // with the wrong delimiter (`Drehrate [°/s];Ausgang [rad/s]` read at commas), not below
    // metadata lines.
    let filled: Vec<&String> = names.iter().filter(|n| !n.trim().is_empty()).collect();
    if let [one] = filled.as_slice()
        && let Some(found) = [';', '\t', ',', '|']
            .into_iter()
            .filter(|&c| format.whitespace || c != format.delimiter)
            .find(|&c| one.split(c).filter(|p| !p.trim().is_empty()).count() >= 2)
    {
        return Some(Hint::HeaderDelimiter { found });
    }
    // A metadata line has one field, or one and empty ones (an export padding every line
    // with delimiters: `Prüfling: PIGA 16;;;`).
    let filled = names.iter().filter(|n| !n.trim().is_empty()).count();
    (filled <= 1 && !numeric).then_some(Hint::SkipLines)
}
