//! The `mountings` section of the study file (`docs/MODEL.md`, issue 29): the IEEE 836 model
//! identified jointly from several mountings of one accelerometer, each with its table.
//!
//! Terms and presets are written by their tags (`k_ip`, `delta_o`, `ia_45`) and checked by
//! the section's validation, so that every unknown word is named at once with the list of
//! the known ones; a mounting's fields are optional here for the same reason.

use serde::{Deserialize, Serialize};

use super::table::PigaTableConfig;
use super::two_orientation::SpinName;

/// The joint fit over several mountings (`mountings: (...)`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MountingsConfig {
    /// The accelerometer's kind: `piga` (output rad/s, with the gyroscopic −ω_i term) or
    /// `pendulous(unit: milli_ampere | volt | pulses_per_second)`.
    pub kind: accel_model::AccelKind,
    /// The terms the lab identifies, by tag: `k0`, `k1`, `k2`, `k3`, `k4`, `k_oq`, `k_ip`,
    /// `k_io`, `k_pp`, `k_oo`, `k_po`, `delta_o`, `delta_p` (k0 and k1 are always fitted).
    pub terms: Vec<String>,
    /// The ω³ column shared by every mounting (the spindle's dynamic tilt and the Coriolis
    /// term of the radius growth; default `true`).
    #[serde(default = "yes")]
    pub omega3: bool,
    /// The radius growth the probe cannot see (arm stretch): `auto` (default: fitted when
    /// the mountings separate it, else not, and said so), `fit` or `off`.
    #[serde(default)]
    pub arm_stretch: ArmStretchName,
    /// The probe phase whose C_r is compensated along each mounting's axes, by name
    /// (absent: the calibration section's `compensate_with` when there is one, else the
    /// study's first phase; the results say which). `compensate: false` fits without it.
    #[serde(default)]
    pub compensate_with: Option<String>,
    /// Whether the probe's C_r is compensated at all (default `true`).
    #[serde(default = "yes")]
    pub compensate: bool,
    /// The site's latitude, degrees (north positive): with `spin_seen_from_above`, the
    /// vertical Earth rate a PIGA reads when its input axis has a vertical component.
    #[serde(default)]
    pub latitude_deg: Option<f64>,
    /// Which way the spindle turns seen from above at the tables' (positive) rates.
    #[serde(default)]
    pub spin_seen_from_above: Option<SpinName>,
    /// The mountings, the first the reference (its bias is k0, its scale factor k1).
    pub list: Vec<MountingConfig>,
}

const fn yes() -> bool {
    true
}

/// Whether the arm stretch is fitted, as the study file names it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArmStretchName {
    /// Fitted when the mountings separate it from the chosen terms.
    #[default]
    Auto,
    /// Fitted (the mountings must separate it).
    Fit,
    /// Not fitted.
    Off,
}

/// One mounting and its data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MountingConfig {
    /// A name for a reader (absent: the preset's words, or "mounting N").
    #[serde(default)]
    pub label: Option<String>,
    /// A named mounting: `ia_in`, `ia_out`, `ia_tangential`, `ia_axial`, `pa_radial`,
    /// `oa_radial`, `ia_45` (exactly one of `preset` and `angles`).
    #[serde(default)]
    pub preset: Option<String>,
    /// General angles from IA in: azimuth about the spindle axis, elevation of IA towards
    /// the spindle axis, roll of PA about IA (degrees).
    #[serde(default)]
    pub angles: Option<accel_model::MountingAngles>,
    /// The static radius of this mounting (the proof mass to the spindle axis), m.
    #[serde(default)]
    pub radius_m: Option<f64>,
    /// The standard uncertainty of the fixture's angles, degrees (absent: taken as 0, and
    /// the results say so).
    #[serde(default)]
    pub angle_u_deg: Option<f64>,
    /// This mounting's own bias (remounting shifts it; default: yes for every mounting but
    /// the first).
    #[serde(default)]
    pub own_bias: Option<bool>,
    /// This mounting's own scale factor (default: no).
    #[serde(default)]
    pub own_scale: Option<bool>,
    /// This mounting's own ω term (tilt, Coriolis; default: yes).
    #[serde(default)]
    pub tilt_rate: Option<bool>,
    /// Its table: rates in deg/s and mean outputs in the kind's unit (a PIGA's in rad/s),
    /// read as the calibration section reads its table.
    #[serde(default)]
    pub table: Option<PigaTableConfig>,
}
