//! Which of a study's values came from its lab profile (`lab.ron`) and which the study
//! stated itself, overriding the profile.

use serde::{Deserialize, Serialize};

/// The lab profile a study used, and where each value it could give came from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ProfileResults {
    /// The profile's file, as the study read it.
    pub file: String,
    /// The centrifuge the study used, by its name in the profile.
    pub centrifuge: String,
    /// The probe, by its name in the profile (absent: the profile names none for it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probe: Option<String>,
    /// The data acquisition, by its name in the profile.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub daq: Option<String>,
    /// Each value the profile gives for the study, in the study file's order.
    pub values: Vec<ValueOrigin>,
}

/// Where one value of the study came from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ValueOrigin {
    /// The study's field (`radius_m`, `uncertainty.g_u_m_s2`, `certificate.equipment`).
    pub field: String,
    /// The profile, or the study (which then overrides the profile).
    pub from: ValueSource,
    /// The profile's field that gives it (or that the study overrides), with the profile's
    /// file (`lab.ron: centrifuges[0].radius_m`).
    pub profile_field: String,
}

/// Which file a value came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ValueSource {
    /// The lab profile.
    Profile,
    /// The study file, overriding the profile.
    Study,
}
