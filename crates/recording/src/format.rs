//! The layout of a recording file: column names, units, delimiter.

use serde::{Deserialize, Serialize};

use crate::error::RecordingError;
use crate::table::{TableColumn, TableFormat};

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

/// Default name of the time column, s; the writer's header name.
pub(crate) const TIME_COLUMN: &str = "time_s";
/// Default name of the gap column, µm; the writer's header name.
pub(crate) const GAP_COLUMN: &str = "gap_um";
/// Default name of the encoder-angle column, deg; the writer's header name.
pub(crate) const ANGLE_COLUMN: &str = "angle_deg";

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
            time_column: TIME_COLUMN.into(),
            gap_column: GAP_COLUMN.into(),
            angle_column: ANGLE_COLUMN.into(),
            gap_unit: LengthUnit::Um,
            angle_unit: AngleUnit::Deg,
            delimiter: ',',
            max_gap_intervals: 3.0,
        }
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

impl RecordingFormat {
    /// The table the format describes: time and gap required, the angle column optional,
    /// rows may have more fields than those read. Checks the format.
    pub(crate) fn table_format(&self) -> Result<TableFormat, RecordingError> {
        delimiter_byte(self.delimiter)?;
        if self.gap_column == self.time_column {
            return Err(RecordingError::DuplicateColumn {
                field: "gap_column",
                name: self.gap_column.clone(),
            });
        }
        if self.angle_column == self.time_column || self.angle_column == self.gap_column {
            return Err(RecordingError::DuplicateColumn {
                field: "angle_column",
                name: self.angle_column.clone(),
            });
        }
        if !self.max_gap_intervals.is_finite() || self.max_gap_intervals < 1.0 {
            return Err(RecordingError::InvalidGapLimit {
                value: self.max_gap_intervals,
            });
        }
        Ok(TableFormat {
            columns: vec![
                TableColumn::required(&self.time_column),
                TableColumn::required(&self.gap_column),
                TableColumn::optional(&self.angle_column),
            ],
            delimiter: self.delimiter,
            flexible: true,
        })
    }
}
