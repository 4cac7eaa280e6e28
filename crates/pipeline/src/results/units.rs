//! The summary of a several-unit study (`units` of the top folder's results.json): each unit
//! by its label, where its own complete results are, and its main numbers.

use serde::{Deserialize, Serialize};

use super::calibration::Coefficient;
use super::common::Estimate;

/// One unit of a several-unit study, as the top folder's results.json lists it. The unit's
/// complete results (a single-unit study's results.json, report and certificate) are in
/// `folder`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitSummary {
    /// The unit's label (`units[…].label`).
    pub label: String,
    /// Its results' folder, relative to the top folder (`units/<label>`).
    pub folder: String,
    /// Its study's name (`<study>: unit <label>`).
    pub study: String,
    /// Its k1, rad/(s·g), as stated.
    pub k1_rad_s_g: f64,
    /// Its working radius, m.
    pub radius_m: f64,
    /// Its certificate's identification (absent: no certificate section).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub certificate: Option<String>,
    /// Its model and serial number, from its certificate's item.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub item: Option<String>,
    /// The phase its calibration is compensated with.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compensate_with: Option<String>,
    /// Δk2 removed from its k2 (eq. 19), rad/(s·g²).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub delta_k2: Option<Estimate>,
    /// Its compensated k2, rad/(s·g²), with its uncertainty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k2: Option<Coefficient>,
    /// How many warnings its results hold.
    pub warnings: usize,
}
