//! The PIGA's data of a calibration (or of one orientation of a two-orientation one) — a
//! table, or raw output recordings — and the Monte Carlo trial count: shared by the study
//! file's sections, so they live apart from the study's own configuration.

use std::path::PathBuf;

use recording::{Column, Delimiter, PigaTableFormat, RateUnit, RecordingError, TableFormat};
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
    /// The standard uncertainty of each mean output, stated rather than read from a σ
    /// column (`constant(1e-9)` for every row, or `per_rate([(20.0, 1e-9), ...])`), rad/s.
    /// Weighted exactly as a σ column of those values; stating both this and a σ column
    /// (`sigma_column`, or `sigma` in `format`) is an error.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output_sigma_rad_s: Option<OutputSigma>,
    /// The table as the laboratory exported it (delimiter, decimal comma, lines to skip,
    /// named columns with their units, σ and label columns), the same `format` block as
    /// `recording`'s PIGA-table reader takes; with it, the columns are named in it and not
    /// by the keys above (`docs/CONFIGURATION.md`).
    #[serde(default)]
    pub format: Option<recording::PigaTableFormat>,
}

/// A PIGA table's output noise stated in the study file (`output_sigma_rad_s`), for a table
/// without a σ column.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OutputSigma {
    /// One standard uncertainty for every row, rad/s (> 0).
    Constant(f64),
    /// One per rate: `(rate_deg_s, sigma_rad_s)` pairs; every row's rate must be listed
    /// (rates equal to a relative 1e-9, as read from the table in deg/s); a listed rate no
    /// row has is not used.
    PerRate(Vec<(f64, f64)>),
}

/// Relative tolerance within which a table row's rate is the rate of an `output_sigma_rad_s:
/// per_rate(...)` entry (rates are read in the table's own unit and converted to deg/s).
pub const SIGMA_RATE_TOLERANCE: f64 = 1e-9;

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
#[derive(Debug, thiserror::Error)]
pub enum TableLayoutError {
    /// Column keys given beside a `format` block (which names the columns itself).
    #[error(
        "column keys (`rate_column`, `output_column`, `delimiter`, `sigma_column`, \
         `label_column`) beside a `format` block, which names the columns itself"
    )]
    FormatAndColumns,
    /// The `format` block itself is not a readable format.
    #[error(transparent)]
    Recording(RecordingError),
}

impl PigaTableConfig {
    /// The table's layout as `recording`'s PIGA-table reader takes it: the exported table's
    /// `format` block when given (then no column key may be set beside it), else the named
    /// columns (rates in deg/s, outputs and σ in rad/s) and the delimiter (a blank or a tab:
    /// runs of blanks). The one conversion of a configuration's table settings, used by the
    /// calibration section, the two-orientation one and `centrifuge-cal identify`.
    ///
    /// # Errors
    /// [`TableLayoutError::FormatAndColumns`] for column keys beside a `format` block.
    pub fn piga_format(&self) -> Result<PigaTableFormat, TableLayoutError> {
        if let Some(f) = &self.format {
            if self.rate_column != default_rate_column()
                || self.output_column != default_output_column()
                || self.delimiter != ','
                || self.sigma_column.is_some()
                || self.label_column.is_some()
            {
                return Err(TableLayoutError::FormatAndColumns);
            }
            return Ok(f.clone());
        }
        Ok(PigaTableFormat {
            delimiter: if matches!(self.delimiter, ' ' | '\t') {
                Delimiter::Whitespace
            } else {
                Delimiter::Char(self.delimiter)
            },
            rate: Column {
                column: self.rate_column.clone(),
                unit: RateUnit::DegS,
            },
            output: Column {
                column: self.output_column.clone(),
                unit: RateUnit::RadS,
            },
            sigma: self.sigma_column.clone().map(|column| Column {
                column,
                unit: RateUnit::RadS,
            }),
            label: self.label_column.clone(),
            ..PigaTableFormat::default()
        })
    }

    /// The text-table reader's format of [`piga_format`](Self::piga_format), checked.
    ///
    /// # Errors
    /// As [`piga_format`](Self::piga_format), and [`TableLayoutError::Recording`] for a
    /// delimiter that cannot separate numbers with the decimal mark or a column named twice.
    pub fn reader_format(&self) -> Result<TableFormat, TableLayoutError> {
        self.piga_format()?
            .table_format()
            .map_err(TableLayoutError::Recording)
    }
}

/// Raw PIGA output recordings, one per rate (`docs/YOUR-DATA.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PigaRecordingSet {
    /// Layout of the files: time, the output angle (`output`: deg, rad or
    /// `counts(per_rev)`), the spindle's angle source, delimiter, decimal mark, gaps and
    /// non-finite samples; defaults to `time_s,output_rad[,angle_deg]`.
    #[serde(default)]
    pub format: recording::PigaRecordingFormat,
    /// Harmonics of the spindle angle removed from the output angle in each revolution
    /// with its slope (1 to 8, default 2).
    #[serde(default = "default_piga_order")]
    pub order: usize,
    /// The recordings.
    pub files: Vec<RecordingPoint>,
}

const fn default_piga_order() -> usize {
    2
}

/// One recording and the rate it was taken at.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordingPoint {
    /// Spindle rate, deg/s.
    pub rate_deg_s: f64,
    /// The CSV file, relative to the configuration file's folder unless absolute.
    pub file: PathBuf,
}
