//! The lab profile (`lab.ron`, `docs/PROFILE.md`): what a laboratory states once for every
//! study — itself and its accreditation, who signs, the procedure, the equipment (centrifuges
//! with their radius and probe geometry, probes, data acquisition, the gravity survey) with
//! identities and calibration due dates, the standing traceability statement of each Type B
//! input, the decision rule and where limits come from. A study names it (`profile:
//! "lab.ron"`) and the centrifuge it used (`centrifuge: "CF-2"`).
//!
//! These types hold what the file says, unvalidated; `crate::profile` validates them (every
//! problem at once, each naming `lab.ron` and its field) and fills the study's missing values
//! from them. Every text field defaults to empty so that the validation names each missing
//! one (the parser would stop at the first).

use serde::{Deserialize, Serialize};

use super::certificate::DecisionRuleName;
use super::direction::ProbeDirectionName;

/// A lab profile (`lab.ron`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProfileConfig {
    /// The laboratory.
    pub laboratory: ProfileLaboratory,
    /// Who may authorise (sign) a certificate, each with their role (at least one).
    pub signatories: Vec<PersonConfig>,
    /// Who may perform a calibration (optional: with exactly one, a study's operator defaults
    /// to them).
    pub operators: Vec<String>,
    /// The procedure followed: its reference and title.
    pub procedure: String,
    /// The environmental conditions recorded during every calibration (`ambient
    /// temperature`, `relative humidity`): `init` asks for each one's value.
    pub conditions: Vec<String>,
    /// The centrifuges (at least one).
    pub centrifuges: Vec<CentrifugeConfig>,
    /// The displacement probes.
    pub probes: Vec<ProbeConfig>,
    /// The data acquisition systems.
    pub daqs: Vec<InstrumentConfig>,
    /// The local gravity and its survey.
    pub gravity: GravityConfig,
    /// The decision rule for specification limits (ILAC-G8:09/2019).
    pub decision_rule: Option<DecisionRuleName>,
    /// Where the limits a certificate states come from (the customer's specification as
    /// agreed at contract review, a data sheet).
    pub limits_source: String,
}

/// The laboratory (`laboratory`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProfileLaboratory {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
    /// Accreditation body and number, if accredited.
    pub accreditation: Option<String>,
    /// The laboratory's country, as ISO 3166-1 writes it (two capital letters: `DE`, `GB`);
    /// the digital certificate states it.
    pub country: Option<String>,
}

/// A person who signs (`signatories[…]`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PersonConfig {
    /// Name.
    pub name: String,
    /// Role.
    pub role: String,
}

/// An instrument: a data acquisition system (`daqs[…]`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct InstrumentConfig {
    /// The name studies use for it (unique among the profile's instruments of its kind).
    pub name: String,
    /// Make and model.
    pub description: String,
    /// Serial or asset number.
    pub identity: String,
    /// When its calibration falls due, `YYYY-MM-DD`.
    pub calibration_due: String,
}

/// A centrifuge (`centrifuges[…]`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CentrifugeConfig {
    /// The name a study gives (`centrifuge: "CF-2"`).
    pub name: String,
    /// Make and model.
    pub description: String,
    /// Serial or asset number.
    pub identity: String,
    /// When its calibration (radius, rate) falls due, `YYYY-MM-DD`.
    pub calibration_due: String,
    /// Where it stands (the certificate's place of calibration).
    pub location: String,
    /// Static working radius with the PIGA mounted input axis in (towards the spindle axis):
    /// its centre of mass to the spindle axis, m.
    pub radius_m: Option<f64>,
    /// Standard uncertainty of each radius, m.
    pub radius_u_m: Option<f64>,
    /// Static working radius with the PIGA turned input axis out, m (optional: for
    /// two-orientation studies).
    pub radius_ia_out_m: Option<f64>,
    /// Relative standard uncertainty of the rate (a scale error common to every rate).
    pub rate_u_relative: Option<f64>,
    /// The site's latitude, degrees (north positive): with `spin_seen_from_above`, the Earth
    /// rate about the spindle axis a two-orientation study corrects k2 for.
    #[serde(default)]
    pub latitude_deg: Option<f64>,
    /// Which way the spindle turns seen from above at positive rates.
    #[serde(default)]
    pub spin_seen_from_above: Option<super::two_orientation::SpinName>,
    /// The probe's geometry on this centrifuge.
    pub lever: ProfileLever,
    /// The probe mounted on it, by name (`probes[…].name`); a study may name another
    /// (`probe:`).
    pub probe: Option<String>,
    /// The data acquisition used with it, by name (`daqs[…].name`).
    pub daq: Option<String>,
    /// The standing traceability statement of each of its Type B inputs (for an input whose
    /// uncertainty is 0, why it is negligible).
    pub traceability: CentrifugeTraceability,
}

/// A centrifuge's probe geometry (`centrifuges[…].lever`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProfileLever {
    /// Height from the spindle's tilt pivot to the probe plane, mm.
    pub pivot_to_probe_mm: Option<f64>,
    /// Its standard uncertainty, mm.
    pub pivot_to_probe_u_mm: Option<f64>,
    /// Height from the probe plane to the PIGA's centre-of-mass plane, mm.
    pub probe_to_piga_mm: Option<f64>,
    /// Its standard uncertainty, mm.
    pub probe_to_piga_u_mm: Option<f64>,
    /// Which way the probe measures (docs/PROFILE.md says it in words): `against_o1_x1`
    /// (also written `reading_falls_towards_piga`) or `along_o1_x1`
    /// (`reading_rises_towards_piga`).
    pub probe_direction: Option<ProbeDirectionName>,
    /// The angle zero, deg: what the centrifuge's spindle encoder reads (or how far the
    /// spindle has turned past its index pulse's rising edge) when the arm's PIGA end points
    /// at the probe; a study's `lever.angle_zero_deg` overrides it.
    pub angle_zero_deg: Option<f64>,
}

/// A centrifuge's traceability statements (`centrifuges[…].traceability`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CentrifugeTraceability {
    /// Of the radius (and its uncertainty).
    pub radius: String,
    /// Of the rate scale.
    pub rate_scale: String,
    /// Of the pivot-to-probe height.
    pub pivot_to_probe: String,
    /// Of the probe-to-PIGA height.
    pub probe_to_piga: String,
}

/// A displacement probe (`probes[…]`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProbeConfig {
    /// The name the centrifuges and studies use.
    pub name: String,
    /// Make and model.
    pub description: String,
    /// Serial or asset number.
    pub identity: String,
    /// When its calibration falls due, `YYYY-MM-DD`.
    pub calibration_due: String,
    /// Relative standard uncertainty of its gain (sensitivity).
    pub gain_u_relative: Option<f64>,
    /// Where that uncertainty comes from (its calibration certificate).
    pub traceability: String,
}

/// The local gravity (`gravity`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GravityConfig {
    /// g at the centrifuges, m/s².
    pub g_m_s2: Option<f64>,
    /// Its standard uncertainty, m/s².
    pub u_m_s2: Option<f64>,
    /// Where it comes from (the survey, its report and the point it refers to): the
    /// report's `g_source` and the certificate's traceability statement of g.
    pub source: String,
    /// The survey's identity (report number).
    pub identity: String,
    /// When the survey is to be repeated, `YYYY-MM-DD`.
    pub calibration_due: String,
}
