//! What the certificate certifies, in one place: the method, the coefficients with their
//! stated intervals, their covariance and where they hold. Everything the DCC states of the
//! results is read here and nowhere else.
//!
//! Until `pipeline` records `results.certificate.certified`, the coefficients are the
//! calibration section's (the probe method: eq. 18 on one mounting, k2 compensated with the
//! probe's C_r), their intervals the §8 headline (`results.calibration.headline`), and no
//! covariance or range of validity is stated.

use pipeline::{CalibrationResults, Coefficient, DegreesOfFreedom, Headline, HeadlineMethod};

/// The method whose coefficients are certified.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Method {
    /// Eq. 18 on one mounting, k2 compensated with the probe's C_r (Liu et al. 2025).
    Probe,
}

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
    /// The mounting it belongs to (`ia_in`, `ia_out`), when the certificate has two.
    pub(crate) mounting: Option<String>,
    /// In its native unit (rad/s per g^power).
    pub(crate) native: Stated,
    /// Relative to k1 (k0 in µg, k2 in µg/g², k3 in µg/g³; none for k1).
    pub(crate) relative: Option<Stated>,
    pub(crate) interval: Interval,
    /// Effective degrees of freedom (`None`: infinitely many).
    pub(crate) dof: Option<f64>,
}

/// What the certificate certifies.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Certified {
    pub(crate) method: Method,
    /// k0 and k1 of each mounting, then k2 and k3.
    pub(crate) coefficients: Vec<CertifiedCoefficient>,
    /// Covariance of the coefficients' values (native units), in their order, when known.
    pub(crate) covariance: Option<Vec<Vec<f64>>>,
    /// `g` of the model's specific force, m/s² (1 g).
    pub(crate) g_m_s2: f64,
}

/// What the certificate of a study with calibration `c` certifies.
pub(crate) fn certified(c: &CalibrationResults) -> Certified {
    let gum = [
        &c.coefficients.k0,
        &c.coefficients.k1,
        &c.coefficients.k2,
        &c.coefficients.k3,
    ];
    let heads = [
        &c.headline.k0,
        &c.headline.k1,
        &c.headline.k2,
        &c.headline.k3,
    ];
    let mc = [
        &c.monte_carlo.k0,
        &c.monte_carlo.k1,
        &c.monte_carlo.k2,
        &c.monte_carlo.k3,
    ];
    // as the printed certificate states them relative to k1: the interval scaled by 1e6/k1
    let micro = 1e6 / c.coefficients.k1.value;
    let coefficients = (0..4)
        .map(|power| {
            let (g, h) = (gum[power], heads[power]);
            let (interval, u) = match h.method {
                HeadlineMethod::Gum => (Interval::Gum { k: g.k }, g.u),
                HeadlineMethod::MonteCarlo => (Interval::MonteCarlo, mc[power].u),
            };
            let native = stated(h, u, g, 1.0);
            CertifiedCoefficient {
                power,
                mounting: None,
                native,
                relative: (power != 1).then(|| stated(h, u, g, micro)),
                interval,
                dof: match g.dof {
                    DegreesOfFreedom::Finite(n) => Some(n),
                    DegreesOfFreedom::Infinite(_) => None,
                },
            }
        })
        .collect();
    Certified {
        method: Method::Probe,
        coefficients,
        covariance: None,
        g_m_s2: c.g_m_s2,
    }
}

/// The headline `h` with standard uncertainty `u`, scaled by `scale` (the interval's ends
/// scaled as they are, so that a scale of 1 keeps them exactly).
fn stated(h: &Headline, u: f64, gum: &Coefficient, scale: f64) -> Stated {
    let value = h.value * scale;
    // a negative scale turns the interval round
    let (low95, high95) = if scale < 0.0 {
        (h.high95 * scale, h.low95 * scale)
    } else {
        (h.low95 * scale, h.high95 * scale)
    };
    Stated {
        value,
        u: u * scale.abs(),
        low95,
        high95,
        expanded: match h.method {
            HeadlineMethod::Gum => gum.u95 * scale.abs(),
            HeadlineMethod::MonteCarlo => (value - low95).max(high95 - value),
        },
    }
}
