//! Delimited text tables of named numeric columns: the format, the table read, and the one
//! parser behind every reader of this crate.

use std::path::{Path, PathBuf};

use super::line_table::LineTable;
use super::lines::{Lines, field_text, normalized, split_fields, trim_quotes};
use super::rows::{SKIP, Syntax, fast_row, parse_row_slowly};
use super::stream::{CHUNK_BYTES, LineSink, stream_file};
use crate::digest::{FileDigest, Hasher};
use crate::error::{Hint, RecordingError, Result};

/// Most columns a [`TableFormat`] may name.
pub const MAX_COLUMNS: usize = 8;

/// Pieces of text at least this long are parsed on two threads.
pub(crate) const PARALLEL_BYTES: usize = 256 * 1024;

/// Most rows reserved before any is read: a chunk's worth (rows are rarely shorter than 16
/// bytes). Columns then grow with the rows actually read.
const RESERVED_ROWS: usize = CHUNK_BYTES / 16;

/// A numeric column of a [`TableFormat`], found in the header by name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TableColumn {
    /// The header's name of the column.
    pub name: String,
    /// Whether a header without the column is an error ([`RecordingError::MissingColumn`]);
    /// an optional column absent from the header is read as absent.
    pub required: bool,
}

impl TableColumn {
    /// A column the header must have.
    pub fn required(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            required: true,
        }
    }

    /// A column read when the header has it.
    pub fn optional(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            required: false,
        }
    }
}

/// Layout of a delimited text table: a header line naming the columns, then one row of
/// fields per line. The columns named here are read as finite numbers; other columns are
/// skipped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TableFormat {
    /// The columns read, 1 to [`MAX_COLUMNS`], at least one required, names distinct.
    pub columns: Vec<TableColumn>,
    /// Field delimiter, one ASCII character that cannot occur in a number, a comment or a
    /// line end (unused with `whitespace`).
    pub delimiter: char,
    /// Whether a row may have more fields than the header (they are ignored). When false,
    /// every row has exactly as many fields as the header ([`RecordingError::FieldCount`]).
    pub flexible: bool,
    /// Runs of blanks (spaces and tabs) separate fields, instead of `delimiter`.
    pub whitespace: bool,
    /// Numbers are written with a decimal comma (`1,5`).
    pub decimal_comma: bool,
    /// Lines before the header, blank and comment lines included.
    pub skip_lines: usize,
    /// NaN and infinite values are read rather than refused.
    pub allow_non_finite: bool,
    /// A text column read as each row's label (a repeat number, an orientation), which the
    /// header must have when one is named; its field is trimmed and unquoted, an absent
    /// field is an empty label. With a label, rows are parsed field by field (tables with
    /// labels are small).
    pub label: Option<String>,
    /// The keys of the configuration's `format` block behind this table (`delimiter`,
    /// `decimal`, `skip_lines`, `on_non_finite`, …): an error's [`Hint`] is given only when
    /// it names one of them ([`Hint::key`]), so that a hint never suggests a key the
    /// user's format does not accept. [`TableFormat::new`] gives none.
    pub hint_keys: &'static [&'static str],
}

impl TableFormat {
    /// A table of these columns, comma-separated, decimal point, nothing skipped, finite
    /// values only.
    pub fn new(columns: Vec<TableColumn>, flexible: bool) -> Self {
        Self {
            columns,
            delimiter: ',',
            flexible,
            whitespace: false,
            decimal_comma: false,
            skip_lines: 0,
            allow_non_finite: false,
            label: None,
            hint_keys: &[],
        }
    }

    /// The hint, if the format has the key it names.
    pub(crate) fn accepted(&self, hint: Option<Hint>) -> Option<Hint> {
        hint.filter(|h| h.is_for(self.hint_keys))
    }
}

impl TableFormat {
    /// The row syntax, after checking the format.
    fn check(&self) -> Result<Syntax> {
        let delimiter = match self.whitespace {
            true => b' ',
            false => delimiter_byte(self.delimiter)?,
        };
        if self.decimal_comma && delimiter == b',' {
            return Err(RecordingError::InvalidDelimiter { delimiter: ',' });
        }
        let required = self.columns.iter().filter(|c| c.required).count();
        if self.columns.len() > MAX_COLUMNS || required == 0 {
            return Err(RecordingError::InvalidColumns {
                count: self.columns.len(),
                required,
                max: MAX_COLUMNS,
            });
        }
        if let Some(label) = &self.label
            && self.columns.iter().any(|c| c.name == *label)
        {
            return Err(RecordingError::DuplicateColumn {
                field: "label",
                name: label.clone(),
            });
        }
        for (i, c) in self.columns.iter().enumerate() {
            if self.columns[..i].iter().any(|d| d.name == c.name) {
                return Err(RecordingError::DuplicateColumn {
                    field: "columns",
                    name: c.name.clone(),
                });
            }
        }
        Ok(Syntax {
            delimiter,
            blank: self.whitespace,
            comma: self.decimal_comma,
            allow_non_finite: self.allow_non_finite,
        })
    }
}

/// A table read from a file: the columns of its [`TableFormat`], each row's line in the
/// file, at least one row.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub(crate) path: PathBuf,
    /// Names of the format's columns.
    pub(crate) names: Vec<String>,
    /// Values of the format's columns, in its order; `None` for an optional column the
    /// header lacks.
    pub(crate) columns: Vec<Option<Vec<f64>>>,
    pub(crate) header_line: usize,
    /// The header's column names, trimmed.
    pub(crate) header: Vec<String>,
    pub(crate) lines: LineTable,
    /// Each row's label, when the format names a label column.
    pub(crate) labels: Option<Vec<String>>,
}

impl Table {
    /// The file it was read from (or the name given to [`parse_table`]).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.columns.iter().flatten().next().map_or(0, Vec::len)
    }

    /// Whether there are no rows (never true for a table read by [`load_table`] or
    /// [`parse_table`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The values of a column of the format, `None` if the format has no column of that name
    /// or the header lacked it (an optional column).
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        let k = self.names.iter().position(|n| n == name)?;
        self.columns[k].as_deref()
    }

    /// The header's column names (trimmed, quotes removed).
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// The 1-based line of the header.
    pub fn header_line(&self) -> usize {
        self.header_line
    }

    /// The 1-based line of row `row` (0-based) in the file; a row past the last one is
    /// counted on from it.
    pub fn line_of_row(&self, row: usize) -> usize {
        self.lines.line_of(row)
    }

    /// Each row's label, when the format names a label column ([`TableFormat::label`]).
    pub fn labels(&self) -> Option<&[String]> {
        self.labels.as_deref()
    }
}

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

impl Table {
    /// A table held in memory as named columns (a caller's arrays: the Python package's), read
    /// as [`parse_table`] reads a file of them: the format's required columns present, every
    /// column as long as the first, at least one row, values finite unless the format allows
    /// otherwise, a label for each row when the format names a label column. `path` names the
    /// table in errors, whose "line" is the 1-based row (a column shorter than the longest is
    /// [`RecordingError::MissingField`] at the row after its last).
    ///
    /// ```
    /// use recording::{Table, TableColumn, TableFormat};
    /// let format = TableFormat::new(
    ///     vec![TableColumn::required("rate_deg_s"), TableColumn::optional("sigma")],
    ///     false,
    /// );
    /// let columns = vec![("rate_deg_s".to_owned(), vec![10.0, 20.0])];
    /// let table = Table::from_columns("<arrays>".as_ref(), &format, columns, None)?;
    /// assert_eq!(table.column("rate_deg_s"), Some(&[10.0, 20.0][..]));
    /// assert_eq!(table.column("sigma"), None);
    /// assert_eq!(table.line_of_row(1), 2);
    /// # Ok::<(), recording::RecordingError>(())
    /// ```
    pub fn from_columns(
        path: &Path,
        format: &TableFormat,
        mut columns: Vec<(String, Vec<f64>)>,
        labels: Option<Vec<String>>,
    ) -> Result<Table> {
        format.check()?;
        let header: Vec<String> = columns
            .iter()
            .map(|(name, _)| name.clone())
            .chain(labels.as_ref().and(format.label.clone()))
            .collect();
        let rows = columns.iter().map(|(_, v)| v.len()).max().unwrap_or(0);
        let mut lines = LineTable::default();
        lines.record(0, 1);
        let missing = |column: &str| RecordingError::MissingColumn {
            path: path.to_owned(),
            line: 0,
            column: column.to_owned(),
            header: header.clone(),
            hint: None,
        };
        let mut values: Vec<Option<Vec<f64>>> = Vec::with_capacity(format.columns.len());
        for c in &format.columns {
            match columns.iter().position(|(name, _)| *name == c.name) {
                Some(k) => values.push(Some(std::mem::take(&mut columns[k].1))),
                None if c.required => return Err(missing(&c.name)),
                None => values.push(None),
            }
        }
        if rows == 0 {
            return Err(RecordingError::NoRows {
                path: path.to_owned(),
                line: 0,
            });
        }
        for (c, column) in format.columns.iter().zip(&values) {
            let Some(column) = column else { continue };
            if column.len() < rows {
                return Err(RecordingError::MissingField {
                    path: path.to_owned(),
                    line: column.len() + 1,
                    column: c.name.clone(),
                });
            }
            if !format.allow_non_finite
                && let Some(i) = column.iter().position(|v| !v.is_finite())
            {
                return Err(RecordingError::NonFinite {
                    path: path.to_owned(),
                    line: i + 1,
                    column: c.name.clone(),
                    value: column[i],
                    hint: None,
                });
            }
        }
        let labels = match (&format.label, labels) {
            (None, _) => None,
            (Some(label), None) => return Err(missing(label)),
            (Some(label), Some(l)) if l.len() != rows => {
                return Err(RecordingError::MissingField {
                    path: path.to_owned(),
                    line: l.len().min(rows) + 1,
                    column: label.clone(),
                });
            }
            (Some(_), Some(l)) => Some(l),
        };
        Ok(Table {
            path: path.to_owned(),
            names: format.columns.iter().map(|c| c.name.clone()).collect(),
            columns: values,
            header_line: 0,
            header,
            lines,
            labels,
        })
    }
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

/// The delimiter as a byte, if it can separate numeric fields: one ASCII character that
/// cannot occur in a number, a comment or a line end.
pub(crate) fn delimiter_byte(delimiter: char) -> Result<u8, RecordingError> {
    let d = delimiter;
    if !d.is_ascii()
        || d == '\n'
        || d == '\r'
        || d == '#'
        || d == '"'
        || d.is_ascii_digit()
        || "+-.eE".contains(d)
    {
        return Err(RecordingError::InvalidDelimiter { delimiter: d });
    }
    Ok(d as u8)
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
