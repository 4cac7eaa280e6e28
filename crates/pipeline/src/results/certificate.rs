//! The certificate section's results: the certificate's statements, validated, with the
//! traceability of each Type B input beside its standard uncertainty and the statements of
//! conformity (ILAC-G8:09/2019) read from the calibration's stated intervals.

use serde::{Deserialize, Serialize};

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
    /// Where the limits come from (customer specification, contract, data sheet), as the
    /// study file states it.
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
}
