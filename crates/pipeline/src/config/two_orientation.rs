//! The `two_orientation` section of the study file (`docs/TWO_ORIENTATION.md`): the two-orientation
//! (IA in / IA out) calibration of issue 20, one data set per orientation: a PIGA table, or
//! raw PIGA output recordings one per rate.
//!
//! The orientation and the radius of each data set are optional in the file so that the
//! section's validation can name every one that is missing at once (the parser would stop at
//! the first).

use serde::{Deserialize, Serialize};

use super::table::{PigaRecordingSet, PigaTableConfig, TrialsConfig};

/// The two-orientation calibration (`two_orientation: (...)`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwoOrientationConfig {
    /// One data set per orientation: exactly two, one with the IA in and one with it out.
    pub orientations: Vec<OrientationConfig>,
    /// The probe phase whose C_r is compared with the PIGA's C, by name (absent: the
    /// calibration section's `compensate_with` phase when there is one, else the study's first
    /// phase; the results say which).
    #[serde(default)]
    pub compare_with: Option<String>,
    /// Seed of the Monte Carlo evaluation (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Number of Monte Carlo trials: `adaptive` (default) or `fixed(N)` (at least 2000).
    #[serde(default)]
    pub trials: TrialsConfig,
    /// The site's latitude, degrees (north positive). With `spin_seen_from_above` it gives
    /// the Earth rate about the spindle axis, whose term with k2 (`4·k2·R²·Ω·sin L·ω³/g²`,
    /// the same in both mountings) eq. 23 has no column for; not stated, it is an
    /// uncertainty of k2 (docs/TWO_ORIENTATION.md).
    #[serde(default)]
    pub latitude_deg: Option<f64>,
    /// Which way the spindle turns seen from above at the table's (positive) rates:
    /// `counterclockwise` or `clockwise`.
    #[serde(default)]
    pub spin_seen_from_above: Option<SpinName>,
}

/// The spin of the spindle seen from above, as the study file names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpinName {
    /// Counterclockwise seen from above (the Earth's sense in the northern hemisphere).
    Counterclockwise,
    /// Clockwise seen from above.
    Clockwise,
}

impl SpinName {
    /// The spin as the calibration takes it.
    #[must_use]
    pub const fn spin(self) -> ::calibration::Spin {
        match self {
            Self::Counterclockwise => ::calibration::Spin::CounterclockwiseFromAbove,
            Self::Clockwise => ::calibration::Spin::ClockwiseFromAbove,
        }
    }

    /// In words.
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::Counterclockwise => "counterclockwise seen from above",
            Self::Clockwise => "clockwise seen from above",
        }
    }
}

const fn default_seed() -> u64 {
    1
}

/// One orientation's data set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientationConfig {
    /// Which way the PIGA's input axis points: `ia_in` (towards the spindle axis, the
    /// paper's mounting) or `ia_out`.
    #[serde(default)]
    pub orientation: Option<OrientationName>,
    /// The static radius of this mounting (PIGA centre of mass to the spindle axis), m.
    #[serde(default)]
    pub radius_m: Option<f64>,
    /// The PIGA table of this mounting, read as the calibration section reads its table
    /// (exactly one of `table` and `recordings`).
    #[serde(default)]
    pub table: Option<PigaTableConfig>,
    /// Raw PIGA output recordings of this mounting, one file per rate, each reduced to its
    /// mean output over whole spindle revolutions as the calibration section reduces its
    /// recordings (exactly one of `table` and `recordings`).
    #[serde(default)]
    pub recordings: Option<PigaRecordingSet>,
}

/// An orientation as the study file names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OrientationName {
    /// The input axis towards the spindle axis.
    IaIn,
    /// The input axis away from the spindle axis.
    IaOut,
}

impl OrientationName {
    /// The orientation as the calibration takes it ([`::calibration::Orientation::label`]
    /// is its words).
    #[must_use]
    pub const fn orientation(self) -> ::calibration::Orientation {
        match self {
            Self::IaIn => ::calibration::Orientation::IaIn,
            Self::IaOut => ::calibration::Orientation::IaOut,
        }
    }
}
