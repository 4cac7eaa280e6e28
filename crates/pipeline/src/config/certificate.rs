//! The `certificate` section of the study file (`docs/CERTIFICATE.md`): what a calibration
//! certificate states beside the study's results (ISO/IEC 17025:2017 §7.8.2.1 and §7.8.4.1).
//!
//! Every text field defaults to empty so that the section's validation can name every
//! missing required field at once (the parser would stop at the first).

use serde::{Deserialize, Serialize};

/// The certificate section (`certificate: (...)`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CertificateConfig {
    /// The certificate's unique identification, printed on every page.
    pub id: String,
    /// The issuing laboratory.
    pub laboratory: LaboratoryConfig,
    /// Where the calibration was performed.
    pub location: String,
    /// The customer.
    pub customer: PartyConfig,
    /// The item calibrated.
    pub item: ItemConfig,
    /// The equipment used (centrifuge, probe, data acquisition; at least one).
    pub equipment: Vec<EquipmentConfig>,
    /// Receipt, measurement and issue.
    pub dates: DatesConfig,
    /// Who performed the calibration.
    pub operator: String,
    /// Environmental conditions during the measurement (at least one).
    pub conditions: Vec<ConditionConfig>,
    /// The procedure followed (its reference and title).
    pub procedure: String,
    /// Departures from the procedure (absent: none stated).
    pub deviations: Option<String>,
    /// How each Type B input of the budget is traceable (every input with a non-zero
    /// uncertainty needs one).
    pub traceability: Vec<TraceabilityConfig>,
    /// Specification limits for coefficients (none: no statement of conformity).
    pub limits: Vec<LimitConfig>,
    /// The decision rule for the limits (required with limits).
    pub decision_rule: Option<DecisionRuleName>,
    /// Where the limits come from (a customer's specification as agreed at contract review,
    /// a data sheet; ISO/IEC 17025:2017 §7.8.6.2).
    pub limits_source: Option<String>,
    /// Who authorises the certificate.
    pub authorisation: AuthorisationConfig,
    /// Which method's coefficients the certificate certifies: `auto` (default: the
    /// two-orientation method when both mountings were measured, else the probe method),
    /// `probe` or `two_orientation`.
    pub certify: CertifyName,
    /// The laboratory's reason for certifying a value that the study's own check refutes
    /// (|z| > 3 between the two methods); without it such a certificate is refused. The
    /// certificate prints the reason.
    pub certify_despite_check: Option<String>,
    /// The certificate this one follows (the item's previous calibration certificate), when
    /// there is one: the digital certificate (`certificate.dcc.xml`) names it as its
    /// `previousReport`.
    pub previous_certificate: Option<PreviousCertificateConfig>,
}

/// The certificate a certificate follows (`certificate.previous_certificate`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PreviousCertificateConfig {
    /// Its unique identification.
    pub id: String,
    /// SHA-256 of its file (its `certificate.dcc.xml`, or the PDF issued), 64 hexadecimal
    /// digits, when known.
    pub sha256: Option<String>,
}

/// Which method's coefficients a certificate certifies (`certificate.certify`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CertifyName {
    /// The two-orientation method when the study has both mountings, else the probe method.
    #[default]
    Auto,
    /// The probe method: eq. 18 on the calibration section's data, k2 compensated with the
    /// probe's C_r.
    Probe,
    /// The two-orientation method: eq. 23 on both mountings, k2 from the PIGA alone.
    TwoOrientation,
}

/// The laboratory (`certificate.laboratory`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LaboratoryConfig {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
    /// Accreditation body and number, if accredited.
    pub accreditation: Option<String>,
    /// The laboratory's country, as ISO 3166-1 writes it (two capital letters: `DE`, `GB`);
    /// the digital certificate states it (`ZZ`, "not stated", without it).
    pub country: Option<String>,
}

/// The customer (`certificate.customer`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PartyConfig {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
}

/// The item calibrated (`certificate.item`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ItemConfig {
    /// What it is.
    pub description: String,
    /// Its manufacturer.
    pub manufacturer: String,
    /// Its model.
    pub model: String,
    /// Its serial number.
    pub serial: String,
    /// Its condition on receipt.
    pub condition: String,
}

/// An instrument used (`certificate.equipment[…]`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EquipmentConfig {
    /// Its role (`precision centrifuge`, `displacement probe`, `data acquisition`).
    pub role: String,
    /// Make and model.
    pub description: String,
    /// Its identity (serial or asset number).
    pub identity: String,
    /// When its calibration falls due.
    pub calibration_due: String,
}

/// The dates (`certificate.dates`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DatesConfig {
    /// Receipt of the item.
    pub received: String,
    /// The measurement (a day or a span).
    pub measured: String,
    /// Issue of the certificate.
    pub issued: String,
}

/// An environmental condition (`certificate.conditions[…]`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ConditionConfig {
    /// The quantity.
    pub quantity: String,
    /// Its value as measured, with unit and range.
    pub value: String,
}

/// A Type B input of the calibration's budget, as the certificate's traceability names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TypeBInputName {
    /// The working radius R (`uncertainty.radius_u_m`).
    Radius,
    /// Gravity g (`uncertainty.g_u_m_s2`).
    G,
    /// The rate scale (`uncertainty.rate_u_relative`).
    RateScale,
    /// The pivot-to-probe height (`uncertainty.pivot_to_probe_u_mm`).
    PivotToProbe,
    /// The probe-to-PIGA height (`uncertainty.probe_to_piga_u_mm`).
    ProbeToPiga,
    /// The probe's gain (`uncertainty.probe_gain_u_relative`, or the recordings' stated
    /// sensitivity).
    ProbeGain,
    /// k1 when given (`calibration.k1`).
    K1,
}

impl TypeBInputName {
    /// Its name in a study or profile file (`input: radius`), as serde reads it.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Self::Radius => "radius",
            Self::G => "g",
            Self::RateScale => "rate_scale",
            Self::PivotToProbe => "pivot_to_probe",
            Self::ProbeToPiga => "probe_to_piga",
            Self::ProbeGain => "probe_gain",
            Self::K1 => "k1",
        }
    }
}

/// How one Type B input is traceable (`certificate.traceability[…]`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TraceabilityConfig {
    /// The input.
    pub input: TypeBInputName,
    /// Where its value and uncertainty come from (a certificate number, a standard).
    pub statement: String,
}

/// A coefficient a limit applies to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CoefficientName {
    /// Bias.
    K0,
    /// Scale factor.
    K1,
    /// Second-order coefficient.
    K2,
    /// Third-order coefficient.
    K3,
}

/// The unit of a limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitUnitName {
    /// The coefficient's own unit.
    Native,
    /// Relative to k1: µg, µg/g², µg/g³ (k0, k2, k3).
    Micro,
}

/// A specification limit (`certificate.limits[…]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitConfig {
    /// The coefficient.
    pub coefficient: CoefficientName,
    /// The unit of `lower` and `upper`.
    pub unit: LimitUnitName,
    /// Lower tolerance limit.
    #[serde(default)]
    pub lower: Option<f64>,
    /// Upper tolerance limit.
    #[serde(default)]
    pub upper: Option<f64>,
    /// Where the limit comes from (ISO/IEC 17025 §7.8.6.2): `customer specification`, a
    /// contract, the manufacturer's data sheet; printed beside it on the certificate.
    #[serde(default)]
    pub source: Option<String>,
}

/// The decision rule (ILAC-G8:09/2019 §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecisionRuleName {
    /// Simple acceptance (guard band w = 0).
    SimpleAcceptance,
    /// Guard band w = U.
    GuardBand,
}

/// Who authorises the certificate (`certificate.authorisation`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AuthorisationConfig {
    /// Name.
    pub name: String,
    /// Role.
    pub role: String,
}
