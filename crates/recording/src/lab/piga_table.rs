//! PIGA tables: the mean PIGA output at each centrifuge rate (the data of eq. 18).

use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::text::line_table::LineTable;
use crate::text::table::{Table, TableColumn, TableFormat, load_table, parse_table};

/// Header name of a PIGA table's rate column, deg/s.
pub const PIGA_RATE_COLUMN: &str = "rate_deg_s";
/// Header name of a PIGA table's output column, rad/s.
pub const PIGA_OUTPUT_COLUMN: &str = "output_rad_s";

/// A PIGA table: one row per rate point, the centrifuge rate and the PIGA's mean output
/// over whole revolutions.
///
/// The file is comma-separated with the header `rate_deg_s,output_rad_s` (columns found by
/// name; other columns are skipped), every row as many fields as the header, `#` comments
/// and blank lines skipped (see [`load_table`](crate::load_table)).
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
    /// The line of each row in the file.
    lines: LineTable,
}

impl PigaTable {
    /// The table's format: the two columns, comma-separated, not flexible.
    pub fn format() -> TableFormat {
        TableFormat::new(
            vec![
                TableColumn::required(PIGA_RATE_COLUMN),
                TableColumn::required(PIGA_OUTPUT_COLUMN),
            ],
            false,
        )
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

    fn from_table(table: Table) -> Self {
        let Table {
            path,
            mut columns,
            lines,
            ..
        } = table;
        let mut take = |k: usize| {
            columns
                .get_mut(k)
                .and_then(Option::take)
                .unwrap_or_default()
        };
        // Both columns are required: the table has them.
        let rate_deg_s = take(0);
        let output_rad_s = take(1);
        Self {
            path,
            rate_deg_s,
            output_rad_s,
            lines,
        }
    }
}

/// Reads a PIGA table from a file; errors name the file and line.
pub fn load_piga_table(path: &Path) -> Result<PigaTable> {
    load_table(path, &PigaTable::format()).map(PigaTable::from_table)
}

/// Parses a PIGA table held in memory; `path` names it in errors.
pub fn parse_piga_table(text: &[u8], path: &Path) -> Result<PigaTable> {
    parse_table(text, path, &PigaTable::format()).map(PigaTable::from_table)
}
