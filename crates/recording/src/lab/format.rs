//! The layout of a recording file: delimiter, decimal mark, lines before the header, the
//! time and gap columns with their units, where the spindle angle comes from, and what to do
//! with gaps and non-finite samples.

use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::volts::GapUnit;
pub use super::volts::LengthUnit;
use crate::error::RecordingError;
use crate::text::table::{TableColumn, TableFormat, delimiter_byte};

/// Time unit of the time column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeUnit {
    /// Seconds.
    #[default]
    S,
    /// Milliseconds.
    Ms,
    /// Microseconds.
    Us,
    /// Nanoseconds.
    Ns,
}

impl TimeUnit {
    /// Seconds per unit.
    pub const fn s_per_unit(self) -> f64 {
        match self {
            Self::S => 1.0,
            Self::Ms => 1e-3,
            Self::Us => 1e-6,
            Self::Ns => 1e-9,
        }
    }

    /// The unit as a configuration writes it (`s`, `ms`, `us`, `ns`).
    pub const fn key(self) -> &'static str {
        match self {
            Self::S => "s",
            Self::Ms => "ms",
            Self::Us => "us",
            Self::Ns => "ns",
        }
    }

    /// The unit as a person reads it (`s`, `ms`, `µs`, `ns`).
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::Us => "µs",
            other => other.key(),
        }
    }
}

/// Angle unit of an encoder column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AngleUnit {
    /// Degrees.
    #[default]
    Deg,
    /// Radians.
    Rad,
    /// Raw encoder counts, `per_rev` counts per revolution (they may wrap at `per_rev` or
    /// anywhere: steps are unwrapped).
    Counts {
        /// Counts per revolution (> 0).
        per_rev: u64,
    },
}

impl AngleUnit {
    /// Radians per unit.
    pub fn rad_per_unit(self) -> f64 {
        match self {
            Self::Deg => std::f64::consts::PI / 180.0,
            Self::Rad => 1.0,
            Self::Counts { per_rev } => std::f64::consts::TAU / per_rev as f64,
        }
    }

    /// The unit as a person reads it: the configuration's own words (`deg`, `rad`, `counts`).
    pub const fn symbol(self) -> &'static str {
        self.key()
    }

    /// The unit as a configuration writes it (`deg`, `rad`, `counts`; the counts per
    /// revolution are the caller's to say).
    pub const fn key(self) -> &'static str {
        match self {
            Self::Deg => "deg",
            Self::Rad => "rad",
            Self::Counts { .. } => "counts",
        }
    }
}

/// A column and its unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Column<U> {
    /// The header's name of the column (compared after trimming blanks and quotes).
    pub column: String,
    /// Its unit.
    pub unit: U,
}

/// Where each sample's spindle angle comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum AngleSource {
    /// The spindle encoder's angle, zero at the O1X1 reference; wraps are unwrapped.
    Encoder {
        /// The header's name of the column.
        column: String,
        /// Its unit.
        #[serde(default)]
        unit: AngleUnit,
        /// When true, a header without the column is read with the declared rate and a
        /// start angle of 0 (with the warning `angle_from_rate`); when false (the default
        /// in a configuration), it is an error.
        #[serde(default)]
        optional: bool,
    },
    /// A once-per-revolution marker (0/1): the angle is 0 at each rising edge (the middle
    /// of the sample interval in which it rises) and grows in proportion to time between
    /// two edges; before the first and after the last edge, the neighbouring revolution's
    /// period is extended.
    IndexPulse {
        /// The header's name of the column.
        column: String,
    },
    /// The declared rate: `θ = ω·(t − t₀) + θ₀`, no measured angle (warning
    /// `angle_from_rate`).
    Rate {
        /// Angle of the first sample from O1X1, degrees.
        #[serde(default)]
        start_angle_deg: f64,
    },
}

impl Default for AngleSource {
    fn default() -> Self {
        Self::Encoder {
            column: ANGLE_COLUMN.into(),
            unit: AngleUnit::Deg,
            optional: true,
        }
    }
}

/// The field delimiter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Delimiter {
    /// One ASCII character that cannot occur in a number, a comment or a line end (blanks
    /// around fields are trimmed). `'\t'` splits at tabs only, so header names may contain
    /// spaces.
    Char(char),
    /// Runs of blanks (spaces and tabs) separate fields.
    Whitespace,
}

impl Default for Delimiter {
    fn default() -> Self {
        Self::Char(',')
    }
}

impl Serialize for Delimiter {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Char(c) => s.serialize_char(*c),
            Self::Whitespace => s.serialize_unit_variant("Delimiter", 1, "whitespace"),
        }
    }
}

impl<'de> Deserialize<'de> for Delimiter {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = Delimiter;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("one character, e.g. ';', or `whitespace`")
            }
            // RON hands a bare word such as `whitespace` over as a unit value.
            fn visit_unit<E: serde::de::Error>(self) -> Result<Delimiter, E> {
                Ok(Delimiter::Whitespace)
            }
            fn visit_char<E: serde::de::Error>(self, c: char) -> Result<Delimiter, E> {
                Ok(Delimiter::Char(c))
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Delimiter, E> {
                let mut chars = s.chars();
                match (chars.next(), chars.next()) {
                    _ if s == "whitespace" => Ok(Delimiter::Whitespace),
                    (Some(c), None) => Ok(Delimiter::Char(c)),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(s), &self)),
                }
            }
            fn visit_enum<A: serde::de::EnumAccess<'de>>(
                self,
                a: A,
            ) -> Result<Delimiter, A::Error> {
                use serde::de::VariantAccess;
                let (name, variant): (String, _) = a.variant()?;
                variant.unit_variant()?;
                self.visit_str(&name)
            }
        }
        d.deserialize_any(V)
    }
}

/// The decimal mark of the numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecimalMark {
    /// `1.5` (the default).
    #[default]
    Point,
    /// `1,5`, as European DAQ software exports; the delimiter must then not be `,`.
    Comma,
}

/// What to do with samples a revolution cannot be fitted through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnBadSamples {
    /// Refuse the recording, naming the line (the default).
    #[default]
    Error,
    /// Drop every revolution the bad samples touch, fit the others, and count the dropped
    /// ones.
    DropRevolution,
}

/// What to do with a revolution whose residual RMS is far above the others'
/// (`harmonics::residual_outliers`: a glitch, a dropout to zero).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnOutlier {
    /// Leave it out of the mean and say so (the default): one glitch sample otherwise moves
    /// the rate's first harmonic by its share of the revolution.
    #[default]
    DropRevolution,
    /// Keep it in the mean and say so.
    Keep,
}

/// Default name of the time column, s; the writer's header name.
pub(crate) const TIME_COLUMN: &str = "time_s";
/// Default name of the gap column, µm; the writer's header name.
pub(crate) const GAP_COLUMN: &str = "gap_um";
/// Default name of the encoder-angle column, deg; the writer's header name.
pub(crate) const ANGLE_COLUMN: &str = "angle_deg";

/// Layout of a probe-recording file; every field has a default (the documented
/// `time_s,gap_um[,angle_deg]`), so a study configuration names only what differs.
///
/// ```
/// let ron_text = r#"(
///     delimiter: ';', decimal: comma, skip_lines: 5,
///     time: (column: "Zeit [s]", unit: s),
///     gap: (column: "Spalt [mm]", unit: mm),
///     angle: encoder(column: "Winkel", unit: counts(per_rev: 1048576)),
/// )"#;
/// let format: recording::RecordingFormat = ron::from_str(ron_text).unwrap();
/// assert_eq!(format.skip_lines, 5);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RecordingFormat {
    /// Field delimiter (default `,`).
    pub delimiter: Delimiter,
    /// Decimal mark (default point).
    pub decimal: DecimalMark,
    /// Lines before the header, blank ones included (instrument metadata); `#` lines are
    /// comments anywhere.
    pub skip_lines: usize,
    /// The time column (default `time_s`, seconds).
    pub time: Column<TimeUnit>,
    /// The gap column (default `gap_um`, µm).
    pub gap: Column<GapUnit>,
    /// Where the spindle angle comes from (default: the encoder column `angle_deg` in
    /// degrees when the header has it, else the declared rate).
    pub angle: AngleSource,
    /// Largest interval between samples, in nominal (median) sample intervals, before it
    /// counts as a gap (default 3): the one place this is set.
    pub max_gap_intervals: f64,
    /// A gap: refuse the file (default) or drop the revolutions it touches.
    pub on_gap: OnBadSamples,
    /// A NaN or infinite value: refuse the file (default) or drop the revolutions it
    /// touches.
    pub on_non_finite: OnBadSamples,
    /// A revolution whose residual RMS is far above the others': drop it from the mean
    /// (default) or keep it; warned either way.
    pub on_outlier: OnOutlier,
    /// TDMS and MAT files (read by their extension, `.tdms`, `.mat`; the columns above are
    /// then channels or variables): the TDMS group or MAT struct variable holding them
    /// (default: the first group that has them; top-level variables).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// TDMS files: the sample times are the gap channel's waveform timing
    /// (`wf_start_offset + i·wf_increment`, as NI loggers write them) and `time` is not read.
    #[serde(skip_serializing_if = "is_false")]
    pub waveform_time: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

impl Default for RecordingFormat {
    fn default() -> Self {
        Self {
            delimiter: Delimiter::default(),
            decimal: DecimalMark::Point,
            skip_lines: 0,
            time: Column {
                column: TIME_COLUMN.into(),
                unit: TimeUnit::S,
            },
            gap: Column {
                column: GAP_COLUMN.into(),
                unit: GapUnit::Um,
            },
            angle: AngleSource::default(),
            max_gap_intervals: 3.0,
            on_gap: OnBadSamples::Error,
            on_non_finite: OnBadSamples::Error,
            on_outlier: OnOutlier::DropRevolution,
            group: None,
            waveform_time: false,
        }
    }
}

/// The table parser's delimiter and whether runs of blanks separate fields, after checking
/// that the delimiter can separate numbers written with the decimal mark.
pub(crate) fn text_syntax(
    delimiter: Delimiter,
    decimal: DecimalMark,
) -> Result<(char, bool), RecordingError> {
    let (delimiter, whitespace) = match delimiter {
        Delimiter::Char(c) => (c, false),
        Delimiter::Whitespace => (' ', true),
    };
    delimiter_byte(delimiter)?;
    if decimal == DecimalMark::Comma && delimiter == ',' {
        return Err(RecordingError::InvalidDelimiter { delimiter });
    }
    Ok((delimiter, whitespace))
}

/// The text in the last `[…]` or `(…)` at the end of a header name, trimmed.
pub(crate) fn header_unit(header: &str) -> Option<&str> {
    let h = header.trim();
    let (open, close) = match h.chars().last()? {
        ']' => ('[', ']'),
        ')' => ('(', ')'),
        _ => return None,
    };
    let start = h.rfind(open)?;
    let inner = &h[start + open.len_utf8()..h.len() - close.len_utf8()];
    Some(inner.trim())
}

/// The keys of a recording's `format` block that a hint may name.
const RECORDING_KEYS: &[&str] = &[
    "delimiter",
    "decimal",
    "skip_lines",
    "on_non_finite",
    "on_gap",
    "on_outlier",
    "angle",
    "time",
];

/// Index of the angle column in [`RecordingFormat::table_format`]'s columns, when read.
pub(crate) const ANGLE_SLOT: usize = 2;

impl RecordingFormat {
    /// The table the format describes: time and gap required, the angle column (encoder or
    /// index pulse) when there is one, rows may have more fields than those read. Checks the
    /// format.
    pub(crate) fn table_format(&self) -> Result<TableFormat, RecordingError> {
        let (delimiter, whitespace) = text_syntax(self.delimiter, self.decimal)?;
        self.gap.unit.sensitivity()?;
        let mut columns = vec![
            TableColumn::required(self.time.column.trim()),
            TableColumn::required(self.gap.column.trim()),
        ];
        match &self.angle {
            AngleSource::Encoder {
                column,
                unit,
                optional,
            } => {
                if let AngleUnit::Counts { per_rev: 0 } = unit {
                    return Err(RecordingError::InvalidCountsPerRev);
                }
                columns.push(TableColumn {
                    name: column.trim().into(),
                    required: !optional,
                });
            }
            AngleSource::IndexPulse { column } => {
                columns.push(TableColumn::required(column.trim()));
            }
            AngleSource::Rate { start_angle_deg } => {
                if !start_angle_deg.is_finite() {
                    return Err(RecordingError::InvalidStartAngle {
                        value: *start_angle_deg,
                    });
                }
            }
        }
        for (field, k) in [("gap", 1), ("angle", 2)] {
            if let Some(c) = columns.get(k)
                && columns[..k].iter().any(|d| d.name == c.name)
            {
                return Err(RecordingError::DuplicateColumn {
                    field,
                    name: c.name.clone(),
                });
            }
        }
        if !self.max_gap_intervals.is_finite() || self.max_gap_intervals < 1.0 {
            return Err(RecordingError::InvalidGapLimit {
                value: self.max_gap_intervals,
            });
        }
        Ok(TableFormat {
            columns,
            delimiter,
            flexible: true,
            whitespace,
            decimal_comma: self.decimal == DecimalMark::Comma,
            skip_lines: self.skip_lines,
            allow_non_finite: self.on_non_finite == OnBadSamples::DropRevolution,
            label: None,
            hint_keys: RECORDING_KEYS,
        })
    }
}
