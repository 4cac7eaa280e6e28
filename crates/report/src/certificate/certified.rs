//! What the certificate certifies, as the study decided it (`results.certificate.certified`,
//! `pipeline::Certified`: the method, why, the coefficients with their uncertainties, the other
//! method as a check, where the coefficients hold), with what the page adds to it: whether
//! each coefficient's GUM validation was borderline (from the section whose results it is).

use pipeline::{
    CalibrationResults, CertifiedMethod, DegreesOfFreedom, HeadlineMethod, StudyResults,
};

/// The method whose coefficients are certified.
pub(crate) type Method = CertifiedMethod;

/// A certified coefficient (native unit), with its value relative to k1.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Coefficient {
    /// `k0` … `k3`.
    pub name: String,
    /// `ia_in`, `ia_out`, or `None` when shared by the mountings.
    pub mounting: Option<String>,
    pub unit: String,
    pub value: f64,
    /// Standard uncertainty.
    pub u: f64,
    pub low95: f64,
    pub high95: f64,
    /// Expanded uncertainty (the larger half-width of a Monte Carlo interval).
    pub expanded: f64,
    /// Coverage factor of a GUM interval; `None` for a Monte Carlo one.
    pub k: Option<f64>,
    pub dof: DegreesOfFreedom,
    pub interval_method: HeadlineMethod,
    /// The GUM validation is borderline (the Monte Carlo interval is stated for that).
    pub borderline: bool,
    pub relative: Option<pipeline::RelativeValue>,
}

/// What is certified.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Certified {
    pub method: Method,
    /// Why this method, in a customer's words (the study's sentence; it may hold the
    /// laboratory's own reason).
    pub reason: String,
    pub check: Option<pipeline::MethodCheck>,
    /// The certified value is one the study's own check refutes.
    pub refuted_by_check: bool,
    /// The laboratory's reason for certifying it nonetheless.
    pub despite_check_reason: Option<String>,
    pub coefficients: Vec<Coefficient>,
    pub validity: Vec<pipeline::ValidityRange>,
}

/// The mounting in words.
pub(crate) fn mounting_words(mounting: &str) -> &'static str {
    match mounting {
        "ia_out" => "input axis pointing away from the spindle axis",
        _ => "input axis pointing towards the spindle axis",
    }
}

/// What the certificate certifies: the study's `results.certificate.certified`.
pub(crate) fn certified(
    results: &StudyResults,
    c: &CalibrationResults,
    stated: &pipeline::Certified,
) -> Certified {
    let borderline = |name: &str, shared: bool| -> bool {
        let h = match (stated.method, name) {
            (CertifiedMethod::TwoOrientation, "k2") if shared => {
                results.two_orientation.as_ref().map(|s| s.headline.k2)
            }
            (CertifiedMethod::TwoOrientation, "k3") if shared => {
                results.two_orientation.as_ref().map(|s| s.headline.k3)
            }
            (CertifiedMethod::TwoOrientation, _) => None,
            (CertifiedMethod::Probe, "k0") => Some(c.headline.k0),
            (CertifiedMethod::Probe, "k1") => Some(c.headline.k1),
            (CertifiedMethod::Probe, "k2") => Some(c.headline.k2),
            (CertifiedMethod::Probe, "k3") => Some(c.headline.k3),
            (CertifiedMethod::Probe, _) => None,
        };
        h.is_some_and(|h| h.borderline)
    };
    Certified {
        method: stated.method,
        reason: stated.reason.clone(),
        check: stated.check,
        refuted_by_check: stated.refuted_by_check,
        despite_check_reason: stated.despite_check_reason.clone(),
        coefficients: stated
            .coefficients
            .iter()
            .map(|x| Coefficient {
                name: x.name.clone(),
                mounting: x.mounting.clone(),
                unit: x.unit.clone(),
                value: x.value,
                u: x.u,
                low95: x.low95,
                high95: x.high95,
                expanded: x.expanded,
                k: x.k,
                dof: x.dof,
                interval_method: x.interval_method,
                borderline: x.interval_method == HeadlineMethod::MonteCarlo
                    && borderline(&x.name, x.mounting.is_none()),
                relative: x.relative.clone(),
            })
            .collect(),
        validity: stated.validity.clone(),
    }
}
