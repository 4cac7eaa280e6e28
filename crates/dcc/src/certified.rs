//! What the certificate certifies, in one place: `results.certificate.certified` (the
//! method, why, the check by the other method, the coefficients with their stated intervals,
//! their covariance and where they hold), read into the values the DCC writes.

use pipeline::{
    CertifiedMethod, DegreesOfFreedom, HeadlineMethod, MethodCheck, StudyResults, ValidityRange,
};

use crate::error::{DccError, Result};

/// Where a coefficient's stated interval comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Interval {
    /// JCGM 100, validated by the Monte Carlo method: symmetric, `U = k·u`.
    Gum {
        /// Coverage factor.
        k: f64,
    },
    /// JCGM 101: the Monte Carlo method's probabilistically symmetric interval.
    MonteCarlo,
}

/// A value with its uncertainty and stated 95 % interval, in one unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stated {
    pub(crate) value: f64,
    /// Standard uncertainty.
    pub(crate) u: f64,
    pub(crate) low95: f64,
    pub(crate) high95: f64,
    /// `k·u` for a GUM interval; the larger half-width for a Monte Carlo one.
    pub(crate) expanded: f64,
}

/// A certified coefficient.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CertifiedCoefficient {
    /// 0 for k0 … 3 for k3.
    pub(crate) power: usize,
    /// The mounting it belongs to (`ia_in`, `ia_out`); none for a coefficient the
    /// mountings share.
    pub(crate) mounting: Option<String>,
    /// In its native unit (rad/s per g^power).
    pub(crate) native: Stated,
    /// Relative to k1 (k0 in µg, k2 in µg/g², k3 in µg/g³; none for k1).
    pub(crate) relative: Option<Stated>,
    pub(crate) interval: Interval,
    /// Effective degrees of freedom.
    pub(crate) dof: DegreesOfFreedom,
}

/// What the certificate certifies.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Certified<'a> {
    pub(crate) method: CertifiedMethod,
    /// Why this method, in a customer's words.
    pub(crate) reason: &'a str,
    /// The other method's k2, when both were run.
    pub(crate) check: Option<&'a MethodCheck>,
    /// The laboratory's reason for certifying a value the study's own check refutes.
    pub(crate) despite_check: Option<&'a str>,
    /// Whether the certified value is one the study's own check refutes.
    pub(crate) refuted_by_check: bool,
    /// k0 and k1 of each mounting, then k2 and k3.
    pub(crate) coefficients: Vec<CertifiedCoefficient>,
    /// Covariance of the coefficients' values (native units), in their order.
    pub(crate) covariance: Option<&'a [Vec<f64>]>,
    /// Where the coefficients hold, per mounting.
    pub(crate) validity: &'a [ValidityRange],
    /// `g` of the model's specific force, m/s² (1 g).
    pub(crate) g_m_s2: f64,
}

const NAMES: [&str; 4] = ["k0", "k1", "k2", "k3"];

/// What the certificate of `results` certifies.
pub(crate) fn certified(results: &StudyResults) -> Result<Certified<'_>> {
    let cert = results
        .certificate
        .as_ref()
        .ok_or(DccError::NoCertificate)?;
    let c = &cert.certified;
    let g_m_s2 = results
        .calibration
        .as_ref()
        .map(|cal| cal.g_m_s2)
        .ok_or(DccError::NoCalibration)?;
    let coefficients =
        c.coefficients
            .iter()
            .map(|k| {
                let power = NAMES.iter().position(|n| *n == k.name).ok_or_else(|| {
                    DccError::OutOfDomain {
                        quantity: "a certified coefficient's name".to_owned(),
                        value: k.name.clone(),
                        requirement: "must be k0, k1, k2 or k3",
                    }
                })?;
                let interval = match (k.interval_method, k.k) {
                    (HeadlineMethod::Gum, Some(k)) => Interval::Gum { k },
                    _ => Interval::MonteCarlo,
                };
                Ok(CertifiedCoefficient {
                    power,
                    mounting: k.mounting.clone(),
                    native: Stated {
                        value: k.value,
                        u: k.u,
                        low95: k.low95,
                        high95: k.high95,
                        expanded: k.expanded,
                    },
                    relative: k.relative.as_ref().map(|r| Stated {
                        value: r.value,
                        u: r.u,
                        low95: r.low95,
                        high95: r.high95,
                        expanded: r.expanded,
                    }),
                    interval,
                    dof: k.dof,
                })
            })
            .collect::<Result<Vec<_>>>()?;
    Ok(Certified {
        method: c.method,
        reason: &c.reason,
        check: c.check.as_ref(),
        despite_check: c.despite_check_reason.as_deref(),
        refuted_by_check: c.refuted_by_check,
        coefficients,
        covariance: (!c.covariance.is_empty()).then_some(c.covariance.as_slice()),
        validity: &c.validity,
        g_m_s2,
    })
}
