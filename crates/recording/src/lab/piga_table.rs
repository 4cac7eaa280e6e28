//! PIGA tables: the mean PIGA output at each centrifuge rate (the data of eq. 18), read as
//! labs export them — the same `format` block as a probe recording's (delimiter, decimal
//! mark, lines before the header, named columns with their units), an optional σ column
//! and a label column.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::format::{Column, DecimalMark, Delimiter, header_unit, text_syntax};
use crate::error::{RecordingError, Result};
use crate::text::line_table::LineTable;
use crate::text::parser::{load_table, parse_table};
use crate::text::table::{Table, TableColumn, TableFormat};

/// Header name of a PIGA table's rate column, deg/s.
pub const PIGA_RATE_COLUMN: &str = "rate_deg_s";
/// Header name of a PIGA table's output column, rad/s.
pub const PIGA_OUTPUT_COLUMN: &str = "output_rad_s";

/// The unit of a rate column: the centrifuge's rate, or the PIGA's output rate and its σ.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RateUnit {
    /// Degrees per second (`°/s`).
    DegS,
    /// Radians per second.
    RadS,
    /// Revolutions per minute (`U/min`).
    Rpm,
    /// Degrees per hour (`°/h`).
    DegH,
}

impl RateUnit {
    /// Radians per second per unit.
    pub fn rad_s_per_unit(self) -> f64 {
        match self {
            Self::DegS => std::f64::consts::PI / 180.0,
            Self::RadS => 1.0,
            Self::Rpm => std::f64::consts::TAU / 60.0,
            Self::DegH => std::f64::consts::PI / 180.0 / 3600.0,
        }
    }

    /// The name in a configuration (`deg_s`, `rad_s`, `rpm`, `deg_h`).
    pub const fn key(self) -> &'static str {
        match self {
            Self::DegS => "deg_s",
            Self::RadS => "rad_s",
            Self::Rpm => "rpm",
            Self::DegH => "deg_h",
        }
    }

    /// The unit a column's header states in brackets or parentheses at its end, when it
    /// is one of these (`Drehrate [°/s]`, `rate (deg/s)`, `Ausgang [rad/s]`, `n [U/min]`);
    /// `None` for a header without a recognised unit.
    ///
    /// ```
    /// use recording::RateUnit;
    /// assert_eq!(RateUnit::in_header("Drehrate [°/s]"), Some(RateUnit::DegS));
    /// assert_eq!(RateUnit::in_header("Drehzahl (U/min)"), Some(RateUnit::Rpm));
    /// assert_eq!(RateUnit::in_header("output_rad_s"), None);
    /// ```
    pub fn in_header(header: &str) -> Option<Self> {
        let unit = header_unit(header)?;
        let unit: String = unit
            .chars()
            .filter(|c| !c.is_whitespace())
            .flat_map(char::to_lowercase)
            .collect();
        let unit = unit
            .replace("grad", "°")
            .replace("deg", "°")
            .replace("sec", "s");
        Some(match unit.as_str() {
            "°/s" | "°s^-1" | "°s-1" => Self::DegS,
            "rad/s" | "rads^-1" | "rads-1" => Self::RadS,
            "rpm" | "u/min" | "1/min" | "min^-1" | "min-1" | "r/min" | "rev/min" => Self::Rpm,
            "°/h" | "°h^-1" | "°h-1" => Self::DegH,
            _ => return None,
        })
    }
}

/// Layout of a PIGA table file: the same pieces as a probe recording's
/// [`RecordingFormat`](crate::RecordingFormat) — delimiter, decimal mark, lines
/// before the header, named columns with units — for the centrifuge rate, the PIGA's mean
/// output, optionally the output's standard uncertainty, and a label column. Every field
/// has a default (the documented `rate_deg_s,output_rad_s`, comma-separated), so a
/// configuration names only what differs.
///
/// A column's header may state its unit at its end (`Drehrate [°/s]`); when it names
/// another rate unit than the one declared, the table is refused
/// ([`RecordingError::ColumnUnit`]) rather than read 57 times too large.
///
/// ```
/// let ron_text = r#"(
///     delimiter: ';', decimal: comma, skip_lines: 4,
///     rate: (column: "Drehrate [°/s]", unit: deg_s),
///     output: (column: "Ausgang [rad/s]", unit: rad_s),
///     sigma: Some((column: "u(Ausgang) [rad/s]", unit: rad_s)),
///     label: Some("Lage"),
/// )"#;
/// let format: recording::PigaTableFormat = ron::from_str(ron_text).unwrap();
/// let text = "Messung 12\nPIGA SN 0042\nDatum 24.11.2026\n\n\
///             Drehrate [°/s];Ausgang [rad/s];u(Ausgang) [rad/s];Lage\n\
///             20,0;0,0174214;1,2e-6;oben\n30,0;0,0391822;1,1e-6;unten\n";
/// let table = recording::parse_piga_table_with(text.as_bytes(), "piga.csv".as_ref(), &format)?;
/// assert_eq!(table.rate_deg_s, [20.0, 30.0]);
/// assert_eq!(table.output_rad_s, [0.0174214, 0.0391822]);
/// assert_eq!(table.sigma_rad_s.as_deref(), Some(&[1.2e-6, 1.1e-6][..]));
/// assert_eq!(table.labels.as_deref(), Some(&["oben".to_string(), "unten".to_string()][..]));
/// assert_eq!(table.line_of_row(1), 7);
/// # Ok::<(), recording::RecordingError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PigaTableFormat {
    /// Field delimiter (default `,`; `whitespace`: runs of blanks and tabs).
    pub delimiter: Delimiter,
    /// Decimal mark (default point).
    pub decimal: DecimalMark,
    /// Lines before the header, blank ones included (export metadata); `#` lines are
    /// comments anywhere.
    pub skip_lines: usize,
    /// The centrifuge-rate column (default `rate_deg_s`, deg/s).
    pub rate: Column<RateUnit>,
    /// The PIGA's mean-output column (default `output_rad_s`, rad/s).
    pub output: Column<RateUnit>,
    /// A column holding each mean output's standard uncertainty (default none: the fit is
    /// unweighted).
    pub sigma: Option<Column<RateUnit>>,
    /// A text column labelling each row (a repeat, an orientation); default none.
    pub label: Option<String>,
}

impl Default for PigaTableFormat {
    fn default() -> Self {
        Self {
            delimiter: Delimiter::default(),
            decimal: DecimalMark::Point,
            skip_lines: 0,
            rate: Column {
                column: PIGA_RATE_COLUMN.into(),
                unit: RateUnit::DegS,
            },
            output: Column {
                column: PIGA_OUTPUT_COLUMN.into(),
                unit: RateUnit::RadS,
            },
            sigma: None,
            label: None,
        }
    }
}

/// The keys of a PIGA table's `format` block that a hint may name.
const PIGA_TABLE_KEYS: &[&str] = &["delimiter", "decimal", "skip_lines"];

impl PigaTableFormat {
    /// The table the format describes (rate and output required, the σ column when named,
    /// the label column; rows may have more fields than those read, e.g. after a trailing
    /// delimiter). Checks the format.
    ///
    /// # Errors
    /// [`RecordingError::InvalidDelimiter`] for a delimiter that cannot separate numbers
    /// with the decimal mark, [`RecordingError::DuplicateColumn`] for a column named twice.
    pub fn table_format(&self) -> Result<TableFormat> {
        let (delimiter, whitespace) = text_syntax(self.delimiter, self.decimal)?;
        let mut columns = vec![
            TableColumn::required(self.rate.column.trim()),
            TableColumn::required(self.output.column.trim()),
        ];
        if let Some(sigma) = &self.sigma {
            columns.push(TableColumn::required(sigma.column.trim()));
        }
        for (field, k) in [("output", 1), ("sigma", 2)] {
            if let Some(c) = columns.get(k)
                && columns[..k].iter().any(|d| d.name == c.name)
            {
                return Err(RecordingError::DuplicateColumn {
                    field,
                    name: c.name.clone(),
                });
            }
        }
        Ok(TableFormat {
            columns,
            delimiter,
            flexible: true,
            whitespace,
            decimal_comma: self.decimal == DecimalMark::Comma,
            skip_lines: self.skip_lines,
            allow_non_finite: false,
            label: self.label.as_ref().map(|l| l.trim().to_owned()),
            hint_keys: PIGA_TABLE_KEYS,
        })
    }
}

/// A PIGA table: one row per rate point, the centrifuge rate and the PIGA's mean output
/// over whole revolutions, in deg/s and rad/s whatever the file's units, with each output's
/// standard uncertainty and each row's label when the format names them.
///
/// The documented file is comma-separated with the header `rate_deg_s,output_rad_s`
/// (columns found by name; other columns are skipped), `#` comments and blank lines skipped
/// (see [`load_table`](crate::load_table)); [`PigaTableFormat`] reads any other layout.
///
/// ```
/// let text = "# PIGA 7, run 2\nrate_deg_s,output_rad_s\n10, 0.5\n20,1.5e-1\n";
/// let table = recording::parse_piga_table(text.as_bytes(), "piga.csv".as_ref())?;
/// assert_eq!(table.rate_deg_s, [10.0, 20.0]);
/// assert_eq!(table.output_rad_s, [0.5, 0.15]);
/// assert_eq!(table.line_of_row(1), 4);
/// # Ok::<(), recording::RecordingError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PigaTable {
    /// The file it was read from.
    pub path: PathBuf,
    /// Centrifuge rate of each row, deg/s.
    pub rate_deg_s: Vec<f64>,
    /// Mean PIGA output of each row, rad/s.
    pub output_rad_s: Vec<f64>,
    /// Standard uncertainty of each row's mean output, rad/s, when the format names a σ
    /// column.
    pub sigma_rad_s: Option<Vec<f64>>,
    /// Each row's label, when the format names a label column.
    pub labels: Option<Vec<String>>,
    /// The line of each row in the file.
    lines: LineTable,
}

impl PigaTable {
    /// The documented table's format: the two columns, comma-separated.
    /// Every row has as many fields as the header.
    pub fn format() -> TableFormat {
        TableFormat {
            hint_keys: PIGA_TABLE_KEYS,
            ..TableFormat::new(
                vec![
                    TableColumn::required(PIGA_RATE_COLUMN),
                    TableColumn::required(PIGA_OUTPUT_COLUMN),
                ],
                false,
            )
        }
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rate_deg_s.len()
    }

    /// Whether there are no rows (never true for a table read from a file).
    pub fn is_empty(&self) -> bool {
        self.rate_deg_s.is_empty()
    }

    /// The 1-based line of row `row` (0-based) in the file.
    pub fn line_of_row(&self, row: usize) -> usize {
        self.lines.line_of(row)
    }

    /// The PIGA table in a table read with [`PigaTableFormat::table_format`] (e.g. through
    /// a study's own data source): the columns converted to deg/s and rad/s, the header's
    /// stated units checked against the declared ones.
    ///
    /// # Errors
    /// [`RecordingError::ColumnUnit`] when a column's header states another rate unit than
    /// the format declares; [`RecordingError::MissingColumn`] for a table read with
    /// another format.
    pub fn from_table(table: Table, format: &PigaTableFormat) -> Result<Self> {
        let mut declared = vec![&format.rate, &format.output];
        declared.extend(&format.sigma);
        for column in &declared {
            check_header_unit(&table, column)?;
        }
        let take = |column: &Column<RateUnit>, to_unit: f64| -> Result<Vec<f64>> {
            let values = table.column(column.column.trim()).ok_or_else(|| {
                RecordingError::MissingColumn {
                    path: table.path().to_owned(),
                    line: table.header_line(),
                    column: column.column.trim().to_owned(),
                    header: table.header().to_vec(),
                    hint: None,
                }
            })?;
            let scale = column.unit.rad_s_per_unit() / to_unit;
            Ok(values.iter().map(|v| v * scale).collect())
        };
        let rate_deg_s = take(&format.rate, RateUnit::DegS.rad_s_per_unit())?;
        let output_rad_s = take(&format.output, 1.0)?;
        let sigma_rad_s = format.sigma.as_ref().map(|s| take(s, 1.0)).transpose()?;
        let labels = table.labels().map(<[String]>::to_vec);
        // A conversion of finite values can overflow only for absurd ones: refuse them.
        for (name, values) in [
            (&format.rate.column, &rate_deg_s),
            (&format.output.column, &output_rad_s),
        ]
        .into_iter()
        .chain(
            format
                .sigma
                .as_ref()
                .map(|s| &s.column)
                .zip(sigma_rad_s.as_ref()),
        ) {
            if let Some(i) = values.iter().position(|v| !v.is_finite()) {
                return Err(RecordingError::NonFinite {
                    path: table.path().to_owned(),
                    line: table.line_of_row(i),
                    column: name.trim().to_owned(),
                    value: values[i],
                    hint: None,
                });
            }
        }
        Ok(Self {
            path: table.path().to_owned(),
            rate_deg_s,
            output_rad_s,
            sigma_rad_s,
            labels,
            lines: table.lines,
        })
    }
}

/// Refuses a column whose header states another rate unit than the one declared.
fn check_header_unit(table: &Table, column: &Column<RateUnit>) -> Result<()> {
    let name = column.column.trim();
    match RateUnit::in_header(name) {
        Some(stated) if stated != column.unit => Err(RecordingError::ColumnUnit {
            path: table.path().to_owned(),
            line: table.header_line(),
            column: name.to_owned(),
            stated: header_unit(name).unwrap_or_default().to_owned(),
            declared: column.unit.key(),
            suggested: stated.key(),
        }),
        _ => Ok(()),
    }
}

/// Reads a PIGA table in the documented format (`rate_deg_s,output_rad_s`, comma-separated,
/// every row as many fields as the header) from a file; errors name the file and line.
pub fn load_piga_table(path: &Path) -> Result<PigaTable> {
    let table = load_table(path, &PigaTable::format())?;
    PigaTable::from_table(table, &PigaTableFormat::default())
}

/// Parses a PIGA table in the documented format held in memory; `path` names it in errors.
pub fn parse_piga_table(text: &[u8], path: &Path) -> Result<PigaTable> {
    let table = parse_table(text, path, &PigaTable::format())?;
    PigaTable::from_table(table, &PigaTableFormat::default())
}

/// Reads a PIGA table laid out as `format` says from a file; errors name the file and
/// line, and their hints name only keys of [`PigaTableFormat`].
pub fn load_piga_table_with(path: &Path, format: &PigaTableFormat) -> Result<PigaTable> {
    let table = load_table(path, &format.table_format()?)?;
    PigaTable::from_table(table, format)
}

/// Parses a PIGA table laid out as `format` says, held in memory; `path` names it in
/// errors.
pub fn parse_piga_table_with(
    text: &[u8],
    path: &Path,
    format: &PigaTableFormat,
) -> Result<PigaTable> {
    let table = parse_table(text, path, &format.table_format()?)?;
    PigaTable::from_table(table, format)
}
