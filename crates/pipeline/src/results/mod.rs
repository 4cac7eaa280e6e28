//! What a study produces; serialised as `results.json` (schema in `docs/RESULTS.md`).
//!
//! The output format, one file per section: it imports nothing of the configuration's format
//! (`config`) nor of the sections that fill it, so the two formats can change apart.

use serde::{Deserialize, Serialize};

mod balance;
mod calibration;
mod certificate;
mod common;
mod declarations;
mod mechanism;
mod mountings;
mod phases;
mod profile;
mod two_orientation;
mod units;
mod warning;

pub use balance::*;
pub use calibration::*;
pub use certificate::*;
pub use common::{DegreesOfFreedom, Estimate, InfiniteDof, OutputCovariance};
pub use declarations::{AngleZero, ProbeSign};
pub use mechanism::*;
pub use mountings::*;
pub use phases::*;
pub use profile::{ProfileResults, ValueOrigin, ValueSource};
pub use two_orientation::*;
pub use units::UnitSummary;
pub use warning::{ProbeDeclared, Warning, WarningCode};

/// All results of a study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyResults {
    /// Name of the study (from the configuration).
    pub study: String,
    /// The scalar inputs the results depend on, echoed for traceability.
    pub inputs: StudyInputs,
    /// Results of each phase, in the study's order.
    pub phases: Vec<PhaseResults>,
    /// The simulated calibration with and without compensation (when configured).
    pub mechanism: Option<MechanismResults>,
    /// The PIGA's calibration on measured data (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub calibration: Option<CalibrationResults>,
    /// What may make a number wrong, in plain words, in the configuration's order.
    #[serde(default)]
    pub warnings: Vec<Warning>,
    /// The balance advisor (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub balance: Option<BalanceResults>,
    /// The counterweight a published change of radius error stands for (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub counterweight: Option<CounterweightResults>,
    /// The calibration certificate's statements (when configured; `certificate.pdf`).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub certificate: Option<CertificateResults>,
    /// The two-orientation (IA in / IA out) calibration (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub two_orientation: Option<TwoOrientationResults>,
    /// The IEEE 836 model from several mountings (when configured; `docs/MODEL.md`).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub mountings: Option<MountingsResults>,
    /// The lab profile the study named, and which values came from it (absent: none).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub profile: Option<ProfileResults>,
    /// A several-unit study: each unit's label, folder and main numbers (absent: a study of
    /// one unit). Each unit's complete results are in [`StudyResults::unit_studies`].
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub units: Option<Vec<UnitSummary>>,
    /// A several-unit study: each unit's complete results, in `units`' order, as its
    /// single-unit study gives them (written to its own folder, `units/<label>/`, not into
    /// this results.json).
    #[serde(skip)]
    pub unit_studies: Vec<StudyResults>,
}

/// Scalar inputs of the study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StudyInputs {
    /// Working radius `R`, m.
    pub radius_m: f64,
    /// Gravity, m/s².
    pub g_m_s2: f64,
    /// PIGA scale factor, rad/(s·g).
    pub k1_rad_s_g: f64,
    /// Lever ratio from the probe plane to the PIGA plane.
    pub lever_ratio: f64,
    /// The probe's measuring direction (`lever.probe_direction`).
    #[serde(default)]
    pub probe_direction: ProbeSign,
    /// The angle zero (`lever.angle_zero_deg`), and whether the study states it.
    #[serde(default)]
    pub angle_zero: AngleZero,
}

impl StudyResults {
    /// The results of the phase of this name.
    pub fn phase(&self, name: &str) -> Option<&PhaseResults> {
        self.phases.iter().find(|p| p.name == name)
    }
}
