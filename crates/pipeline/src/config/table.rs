//! The PIGA table of a calibration (or of one orientation of a two-orientation one) and the
//! Monte Carlo trial count: shared by the study file's sections, so they live apart from the
//! study's own configuration.

use std::path::PathBuf;

use recording::{RecordingError, TableColumn, TableFormat};
use serde::{Deserialize, Serialize};

/// How many Monte Carlo trials the uncertainty evaluation draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TrialsConfig {
    /// Until the results are stable to two significant digits (JCGM 101 §7.9).
    #[default]
    Adaptive,
    /// Exactly this many (at least 2000: JCGM 101 §7.2 asks for 100/(1 − p)).
    Fixed(u64),
}

/// A PIGA table file and its columns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PigaTableConfig {
    /// The file, relative to the study file's folder unless absolute.
    pub file: PathBuf,
    /// Header name of the rate column, deg/s (default `rate_deg_s`).
    #[serde(default = "default_rate_column")]
    pub rate_column: String,
    /// Header name of the mean-output column, rad/s (default `output_rad_s`).
    #[serde(default = "default_output_column")]
    pub output_column: String,
    /// Field delimiter (default `,`).
    #[serde(default = "default_delimiter")]
    pub delimiter: char,
    /// Header name of a column holding each mean output's standard uncertainty, rad/s
    /// (absent: the fit is unweighted). With it, the fit is weighted by `1/σᵢ`.
    #[serde(default)]
    pub sigma_column: Option<String>,
    /// Header name of a text column labelling each row (a repeat, an orientation), shown
    /// with its residual; rows with the same label are compared.
    #[serde(default)]
    pub label_column: Option<String>,
    /// The table as the laboratory exported it (delimiter, decimal comma, lines to skip,
    /// named columns with their units, σ and label columns), the same `format` block as
    /// `recording`'s PIGA-table reader takes; with it, the columns are named in it and not
    /// by the keys above (`docs/CONFIGURATION.md`).
    #[serde(default)]
    pub format: Option<recording::PigaTableFormat>,
}

pub(crate) fn default_rate_column() -> String {
    "rate_deg_s".to_owned()
}

pub(crate) fn default_output_column() -> String {
    "output_rad_s".to_owned()
}

const fn default_delimiter() -> char {
    ','
}

/// Why a PIGA table's settings give no reader format.
#[derive(Debug)]
pub(crate) enum TableLayoutError {
    /// Column keys given beside a `format` block (which names the columns itself).
    FormatAndColumns,
    /// The `format` block itself is not a readable format.
    Recording(RecordingError),
}

impl PigaTableConfig {
    /// The table reader's format: the exported table's `format` block when given (then no
    /// column key may be set beside it), else the named columns and delimiter. One for the
    /// calibration section and the two-orientation one.
    pub(crate) fn reader_format(&self) -> Result<TableFormat, TableLayoutError> {
        if let Some(f) = &self.format {
            if self.rate_column != default_rate_column()
                || self.output_column != default_output_column()
                || self.delimiter != ','
                || self.sigma_column.is_some()
                || self.label_column.is_some()
            {
                return Err(TableLayoutError::FormatAndColumns);
            }
            return f.table_format().map_err(TableLayoutError::Recording);
        }
        let mut columns = vec![
            TableColumn::required(self.rate_column.clone()),
            TableColumn::required(self.output_column.clone()),
        ];
        if let Some(sigma) = &self.sigma_column {
            columns.push(TableColumn::required(sigma.clone()));
        }
        Ok(TableFormat {
            delimiter: self.delimiter,
            // A blank delimiter keeps its meaning here: runs of blanks separate fields.
            whitespace: matches!(self.delimiter, ' ' | '\t'),
            label: self.label_column.clone(),
            ..TableFormat::new(columns, true)
        })
    }
}
