//! The certificate section's results: the certificate's statements, validated, with the
//! traceability of each Type B input beside its standard uncertainty and the statements of
//! conformity (ILAC-G8:09/2019) read from the calibration's stated intervals.

use serde::{Deserialize, Serialize};

use super::calibration::HeadlineMethod;
use super::common::DegreesOfFreedom;

/// A party named on a certificate: the customer.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Party {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
}

/// The laboratory issuing the certificate.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Laboratory {
    /// Name.
    pub name: String,
    /// Postal address, one line.
    pub address: String,
    /// Accreditation body and number, if accredited.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accreditation: Option<String>,
    /// The laboratory's country (ISO 3166-1 alpha-2), if stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub country: Option<String>,
}

/// The item calibrated.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Item {
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

/// An instrument used in the calibration.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Equipment {
    /// Its role.
    pub role: String,
    /// Make and model.
    pub description: String,
    /// Its identity (serial or asset number).
    pub identity: String,
    /// When its calibration falls due.
    pub calibration_due: String,
}

/// The dates of a calibration.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Dates {
    /// Receipt of the item.
    pub received: String,
    /// The measurement.
    pub measured: String,
    /// Issue of the certificate.
    pub issued: String,
}

/// An environmental condition during the measurement.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Condition {
    /// The quantity.
    pub quantity: String,
    /// Its value as measured.
    pub value: String,
}

/// How one Type B input of the budget is traceable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Traceability {
    /// The input quantity, as the budget names it.
    pub input: String,
    /// The unit of its value and uncertainty, as the budget shows it (empty in a
    /// results.json written before it was recorded).
    #[serde(default)]
    pub unit: String,
    /// Its standard uncertainty as the k2 budget uses it (absent when the budget has no
    /// line for it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u: Option<f64>,
    /// Where its value and uncertainty come from.
    pub statement: String,
}

/// Who authorises the certificate.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Authorisation {
    /// Name.
    pub name: String,
    /// Role.
    pub role: String,
}

/// The certificate a certificate follows.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct PreviousCertificate {
    /// Its unique identification.
    pub id: String,
    /// SHA-256 of its file, 64 lowercase hexadecimal digits, when stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sha256: Option<String>,
}

/// The decision rule of the statements of conformity (ILAC-G8:09/2019 §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecisionRule {
    /// Binary statement, simple acceptance (guard band w = 0).
    SimpleAcceptance,
    /// Non-binary statement with a guard band w = U.
    GuardBand,
}

/// A statement of conformity (ILAC-G8:09/2019 §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Within the acceptance zone.
    Pass,
    /// Within the tolerance, but the interval reaches beyond it.
    ConditionalPass,
    /// Outside the tolerance, but the interval reaches into it.
    ConditionalFail,
    /// Outside the tolerance by more than the interval.
    Fail,
}

impl Verdict {
    /// The statement in words.
    pub const fn words(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::ConditionalPass => "conditional pass",
            Self::ConditionalFail => "conditional fail",
            Self::Fail => "fail",
        }
    }

    /// The verdict for a value with interval half-widths `(below, above)` against limits.
    pub fn of(
        value: f64,
        (below, above): (f64, f64),
        lower: Option<f64>,
        upper: Option<f64>,
        rule: DecisionRule,
    ) -> Self {
        let upper_verdict = |tu: f64| match rule {
            DecisionRule::SimpleAcceptance if value <= tu => Self::Pass,
            DecisionRule::SimpleAcceptance => Self::Fail,
            DecisionRule::GuardBand if value + above <= tu => Self::Pass,
            DecisionRule::GuardBand if value <= tu => Self::ConditionalPass,
            DecisionRule::GuardBand if value - below <= tu => Self::ConditionalFail,
            DecisionRule::GuardBand => Self::Fail,
        };
        let lower_verdict = |tl: f64| match rule {
            DecisionRule::SimpleAcceptance if value >= tl => Self::Pass,
            DecisionRule::SimpleAcceptance => Self::Fail,
            DecisionRule::GuardBand if value - below >= tl => Self::Pass,
            DecisionRule::GuardBand if value >= tl => Self::ConditionalPass,
            DecisionRule::GuardBand if value + above >= tl => Self::ConditionalFail,
            DecisionRule::GuardBand => Self::Fail,
        };
        upper
            .map_or(Self::Pass, upper_verdict)
            .max(lower.map_or(Self::Pass, lower_verdict))
    }
}

/// One coefficient's statement of conformity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConformityStatement {
    /// The coefficient: `k0` … `k3`, or `k0/k1`, `k2/k1`, `k3/k1` relative to k1.
    pub coefficient: String,
    /// Index of the coefficient (0 for k0 … 3 for k3).
    pub index: usize,
    /// Whether the limits are relative to k1 (µg, µg/g², µg/g³).
    pub relative_to_k1: bool,
    /// The unit of the value and the limits.
    pub unit: String,
    /// The value in that unit.
    pub value: f64,
    /// Lower end of its stated 95 % interval, in that unit.
    pub low95: f64,
    /// Upper end.
    pub high95: f64,
    /// Lower tolerance limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    /// Upper tolerance limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
    /// Where the limit comes from (customer specification, contract, data sheet), as the
    /// study file states it for this limit, else the certificate's `limits_source`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// The statement.
    pub verdict: Verdict,
}

/// The certificate's statements of conformity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Conformity {
    /// The decision rule.
    pub rule: DecisionRule,
    /// Where the limits come from (a customer's specification, a data sheet), when stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits_source: Option<String>,
    /// One statement per limit, in the file's order.
    pub statements: Vec<ConformityStatement>,
}

/// The certificate section's results: what the certificate states beside the calibration
/// (ISO/IEC 17025:2017 §7.8.2.1 and §7.8.4.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CertificateResults {
    /// The certificate's unique identification.
    pub id: String,
    /// The issuing laboratory.
    pub laboratory: Laboratory,
    /// Where the calibration was performed.
    pub location: String,
    /// The customer.
    pub customer: Party,
    /// The item calibrated.
    pub item: Item,
    /// The equipment used.
    pub equipment: Vec<Equipment>,
    /// Receipt, measurement and issue.
    pub dates: Dates,
    /// Who performed the calibration.
    pub operator: String,
    /// Environmental conditions.
    pub conditions: Vec<Condition>,
    /// The procedure followed.
    pub procedure: String,
    /// Departures from the procedure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deviations: Option<String>,
    /// How each Type B input is traceable.
    pub traceability: Vec<Traceability>,
    /// Statements of conformity (absent: no limits given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conformity: Option<Conformity>,
    /// Who authorises the certificate.
    pub authorisation: Authorisation,
    /// What the certificate certifies: the method, why, and the coefficients with their
    /// stated intervals, covariance and range of validity.
    pub certified: Certified,
    /// The certificate this one follows (absent: none stated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub previous_certificate: Option<PreviousCertificate>,
}

/// Which method's coefficients a certificate certifies, as configured
/// (`certificate.certify`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CertifyPolicy {
    /// The two-orientation method when both mountings were measured, else the probe method.
    Auto,
    /// The probe method.
    Probe,
    /// The two-orientation method.
    TwoOrientation,
}

/// A calibration method whose coefficients a certificate can certify.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CertifiedMethod {
    /// Eq. 18 on one mounting (input axis towards the spindle axis), k2 compensated for the
    /// spindle's pseudo-second-order term with the probe's C_r (Liu et al. 2025).
    Probe,
    /// Eq. 23 on two mountings (input axis towards and away from the spindle axis), k2 from
    /// the PIGA alone (Sun et al. 2022).
    TwoOrientation,
}

impl CertifiedMethod {
    /// The method's name in words.
    pub const fn words(self) -> &'static str {
        match self {
            Self::Probe => "the probe method",
            Self::TwoOrientation => "the two-orientation method",
        }
    }
}

/// A coefficient's value relative to k1 (k0 in µg, k2 in µg/g², k3 in µg/g³).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RelativeValue {
    /// The unit: `µg`, `µg/g²` or `µg/g³`.
    pub unit: String,
    /// The value.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Lower end of the stated 95 % interval.
    pub low95: f64,
    /// Upper end.
    pub high95: f64,
    /// The expanded uncertainty (for a Monte Carlo interval, its larger half-width).
    pub expanded: f64,
}

/// One certified coefficient.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CertifiedCoefficient {
    /// `k0`, `k1`, `k2` or `k3`.
    pub name: String,
    /// The mounting it belongs to (`ia_in`, `ia_out`); absent for a coefficient the
    /// mountings share.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mounting: Option<String>,
    /// Its unit: `rad/s`, `rad/(s·g)`, `rad/(s·g²)` or `rad/(s·g³)`.
    pub unit: String,
    /// The value.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Lower end of the stated 95 % coverage interval (the GUM's when the Monte Carlo
    /// method validates it, else the Monte Carlo method's).
    pub low95: f64,
    /// Upper end.
    pub high95: f64,
    /// The expanded uncertainty U = k·u of a GUM interval; for a Monte Carlo interval, its
    /// larger half-width.
    pub expanded: f64,
    /// The coverage factor of a GUM interval (absent for a Monte Carlo interval).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<f64>,
    /// Effective degrees of freedom.
    pub dof: DegreesOfFreedom,
    /// The method the interval comes from.
    pub interval_method: HeadlineMethod,
    /// The same relative to k1 (absent for k1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative: Option<RelativeValue>,
}

/// The other method's k2, as a check of the certified one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MethodCheck {
    /// The method checked against (the one not certified).
    pub method: CertifiedMethod,
    /// Its k2, rad/(s·g²).
    pub k2: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Its expanded uncertainty for 95 % coverage.
    pub expanded: f64,
    /// z of the two methods' radius growths, (C − C_r)/u(C − C_r): |z| > 3 is a
    /// disagreement.
    pub z: f64,
    /// Whether |z| ≤ 3.
    pub agrees: bool,
}

/// Where the certified coefficients hold: one mounting's rates and the specific force along
/// the input axis they give.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValidityRange {
    /// `ia_in` or `ia_out`.
    pub mounting: String,
    /// The mounting in words.
    pub mounting_words: String,
    /// Its static radius, m.
    pub radius_m: f64,
    /// The lowest rate fitted, deg/s.
    pub rate_low_deg_s: f64,
    /// The highest.
    pub rate_high_deg_s: f64,
    /// The specific force along the input axis at the lowest rate, g (R·ω²/g, negative
    /// with the input axis away from the spindle axis).
    pub specific_force_low_g: f64,
    /// At the highest rate.
    pub specific_force_high_g: f64,
    /// Points fitted (table rows or recordings).
    pub points: usize,
}

/// What a certificate certifies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Certified {
    /// The configuration's choice.
    pub policy: CertifyPolicy,
    /// The method whose coefficients are certified.
    pub method: CertifiedMethod,
    /// Why, in a sentence a customer understands.
    pub reason: String,
    /// The other method's k2 as a check, when both were run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<MethodCheck>,
    /// Whether the certified value is one the study's own check refutes (|z| > 3),
    /// certified because the configuration says so (`certify_despite_check`).
    pub refuted_by_check: bool,
    /// The laboratory's reason for certifying a refuted value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub despite_check_reason: Option<String>,
    /// The certified coefficients: k0 and k1 of each mounting (IA in first), then k2 and k3.
    pub coefficients: Vec<CertifiedCoefficient>,
    /// The covariance matrix of the coefficients' values (native units), in the order of
    /// `coefficients`.
    pub covariance: Vec<Vec<f64>>,
    /// One range of validity per mounting fitted.
    pub validity: Vec<ValidityRange>,
}
