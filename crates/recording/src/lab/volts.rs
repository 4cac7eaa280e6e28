//! The units of a probe's gap: lengths, or volts recorded from the probe's conditioner. The
//! unit of a gap column or channel, and the probe's
//! sensitivity from its own calibration certificate with its standard uncertainty (the
//! study's probe-gain Type B input, stated once, here).

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::error::RecordingError;

/// Length unit of the gap column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LengthUnit {
    /// Nanometres.
    Nm,
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
            Self::Nm => 1e-3,
            Self::Um => 1.0,
            Self::Mm => 1e3,
            Self::M => 1e6,
        }
    }

    /// The unit as a configuration writes it (`nm`, `um`, `mm`, `m`).
    pub const fn key(self) -> &'static str {
        match self {
            Self::Nm => "nm",
            Self::Um => "um",
            Self::Mm => "mm",
            Self::M => "m",
        }
    }

    /// The unit as a person reads it (`nm`, `µm`, `mm`, `m`), as [`GapUnit`]'s display writes
    /// it.
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::Um => "µm",
            other => other.key(),
        }
    }
}

/// The unit in which a probe sensitivity is stated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensitivityUnit {
    /// Micrometres of gap per volt.
    UmPerV,
    /// Millimetres of gap per volt.
    MmPerV,
    /// Volts per millimetre of gap (as many eddy-current probe certificates state it).
    VPerMm,
}

impl SensitivityUnit {
    /// As a person writes it.
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::UmPerV => "µm/V",
            Self::MmPerV => "mm/V",
            Self::VPerMm => "V/mm",
        }
    }
}

/// The unit of a probe's gap column or channel: a length, or volts from the probe's
/// conditioner converted with its stated sensitivity. In a configuration: `nm`, `um`, `mm`,
/// `m`, or `volts(sensitivity: 8.0, sensitivity_unit: v_per_mm, u_sensitivity: 0.04)`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum GapUnit {
    /// Nanometres.
    Nm,
    /// Micrometres (the paper's unit).
    #[default]
    Um,
    /// Millimetres.
    Mm,
    /// Metres.
    M,
    /// Volts, converted to µm by the reader with the probe's sensitivity.
    Volts {
        /// The sensitivity, from the probe's calibration certificate (finite, > 0).
        sensitivity: f64,
        /// Its unit.
        sensitivity_unit: SensitivityUnit,
        /// Its standard uncertainty (k = 1), same unit (finite, > 0: a calibrated
        /// sensitivity has one). It is the study's probe-gain Type B input.
        u_sensitivity: f64,
    },
}

impl From<LengthUnit> for GapUnit {
    fn from(unit: LengthUnit) -> Self {
        match unit {
            LengthUnit::Nm => Self::Nm,
            LengthUnit::Um => Self::Um,
            LengthUnit::Mm => Self::Mm,
            LengthUnit::M => Self::M,
        }
    }
}

impl GapUnit {
    /// The values' length unit after reading: the length unit itself, µm for volts.
    pub const fn length_unit(self) -> LengthUnit {
        match self {
            Self::Nm => LengthUnit::Nm,
            Self::Um | Self::Volts { .. } => LengthUnit::Um,
            Self::Mm => LengthUnit::Mm,
            Self::M => LengthUnit::M,
        }
    }

    /// The sensitivity of a volts column, checked; `None` for a length unit.
    ///
    /// # Errors
    /// [`RecordingError::InvalidSensitivity`] for a sensitivity or uncertainty that is not
    /// finite and positive.
    pub fn sensitivity(self) -> Result<Option<ProbeSensitivity>, RecordingError> {
        let Self::Volts {
            sensitivity,
            sensitivity_unit,
            u_sensitivity,
        } = self
        else {
            return Ok(None);
        };
        for (field, value) in [
            ("sensitivity", sensitivity),
            ("u_sensitivity", u_sensitivity),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(RecordingError::InvalidSensitivity { field, value });
            }
        }
        Ok(Some(ProbeSensitivity {
            stated: sensitivity,
            stated_u: u_sensitivity,
            unit: sensitivity_unit,
        }))
    }
}

impl fmt::Display for GapUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Volts { .. } => f.write_str("V"),
            length => f.write_str(length.length_unit().symbol()),
        }
    }
}

/// A probe's sensitivity as stated on its certificate, with its standard uncertainty: the
/// reader's conversion of volts to µm, and the probe-gain Type B input of the study (its
/// relative standard uncertainty scales the first harmonic, hence C_r, one-to-one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeSensitivity {
    /// The stated value, in [`ProbeSensitivity::unit`].
    pub stated: f64,
    /// Its stated standard uncertainty, same unit.
    pub stated_u: f64,
    /// The unit it is stated in.
    pub unit: SensitivityUnit,
}

impl ProbeSensitivity {
    /// Micrometres of gap per volt.
    pub fn um_per_v(&self) -> f64 {
        match self.unit {
            SensitivityUnit::UmPerV => self.stated,
            SensitivityUnit::MmPerV => 1e3 * self.stated,
            SensitivityUnit::VPerMm => 1e3 / self.stated,
        }
    }

    /// The relative standard uncertainty of the conversion (the same for a sensitivity in
    /// V/mm and its reciprocal, to first order): the probe gain's relative u.
    pub fn relative_u(&self) -> f64 {
        self.stated_u / self.stated
    }
}

impl fmt::Display for ProbeSensitivity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {} ± {} (k = 1)",
            self.stated,
            self.unit.symbol(),
            self.stated_u
        )
    }
}

/// Converts volts to µm in place.
pub(crate) fn volts_to_um(values: &mut [f64], sensitivity: &ProbeSensitivity) {
    let k = sensitivity.um_per_v();
    for v in values {
        *v *= k;
    }
}
