//! Delimited text tables of named numeric columns: the format and the table read (the
//! parser behind every reader of this crate is `parser`'s).

use std::path::{Path, PathBuf};

use super::line_table::LineTable;
use super::rows::Syntax;
use crate::error::{Hint, RecordingError, Result};

/// Most columns a [`TableFormat`] may name.
pub const MAX_COLUMNS: usize = 8;

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
    pub(crate) fn check(&self) -> Result<Syntax> {
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
    /// The file it was read from (or the name given to [`parse_table`](crate::parse_table)).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.columns.iter().flatten().next().map_or(0, Vec::len)
    }

    /// Whether there are no rows (never true for a table read by [`load_table`](crate::load_table) or
    /// [`parse_table`](crate::parse_table)).
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

impl Table {
    /// A table held in memory as named columns (a caller's arrays: the Python package's), read
    /// as [`parse_table`](crate::parse_table) reads a file of them: the format's required columns present, every
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
