//! The recommended calibration interval by the variables method, reliability target
//! (Castrup 2005; NCSLI RP-1; NASA-HDBK-8739.19-5 §7; SUNCAL's "variables" interval).
//!
//! After a calibration the unit's coefficient is known to `u₀` (the certificate's standard
//! uncertainty) and then drifts at `b` per year, known to `u_b`. A time `T` later its
//! deviation from the value certified is predicted as `b·T` with standard uncertainty
//! `u(T) = √(u₀² + u_b²·T²)`. The interval is the longest `T` for which the deviation stays
//! within the tolerance `±L` with probability `R` (the reliability target), the drift's
//! direction being known:
//!
//! ```text
//! |b|·T + z_R·√(u₀² + u_b²·T²) = L,     z_R = Φ⁻¹(R) (one-sided normal quantile)
//! ```
//!
//! Squaring gives `(b² − z²u_b²)·T² − 2L|b|·T + (L² − z²u₀²) = 0`, whose root on the
//! left-hand side's rising branch is, in a form that neither cancels nor divides by zero
//! when `b² = z²u_b²`,
//!
//! ```text
//! T = C / (L|b| + z·√(b²u₀² + u_b²·C)),     C = L² − z²u₀²
//! ```
//!
//! `C ≤ 0` means the tolerance is not held even on the day of calibration (`z·u₀ ≥ L`): no
//! interval. With neither drift nor drift uncertainty (`b = u_b = 0`) nothing limits it.
//!
//! Assumptions, stated with every interval: the drift is linear in time over the interval;
//! the certificates' uncertainties are independent and normal; the tolerance applies to the
//! deviation from the value certified at the latest calibration; the interval counts from
//! that calibration's date.

use crate::error::{RecordsError, Result};

/// What the interval is asked for.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct IntervalRequest {
    /// The tolerance `L` on the deviation from the value certified, in the quantity's unit.
    pub tolerance: f64,
    /// The reliability target `R` (0.5 ≤ R < 1): the probability of being within tolerance at
    /// the end of the interval.
    pub reliability: f64,
}

/// The interval recommended.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Interval {
    /// The request.
    pub request: IntervalRequest,
    /// `z_R`, the one-sided normal quantile of the reliability target.
    pub z: f64,
    /// `u₀`: the latest certificate's standard uncertainty.
    pub u0: f64,
    /// `|b|`: the drift rate per year used.
    pub rate_per_year: f64,
    /// `u_b`: its standard uncertainty.
    pub u_rate_per_year: f64,
    /// The interval in years; `None` when nothing limits it (no drift, known exactly).
    pub years: Option<f64>,
    /// False when the tolerance is not held even on the day of calibration (`z·u₀ ≥ L`).
    pub attainable: bool,
}

/// The method in a sentence, for the outputs.
pub const METHOD: &str = "variables method, reliability target (Castrup 2005; NCSLI RP-1; NASA-HDBK-8739.19-5 §7): the longest time T after the latest calibration for which |b|·T + z_R·√(u₀² + u_b²·T²) ≤ L";

/// The assumptions in a sentence, for the outputs.
pub const ASSUMPTIONS: &str = "the drift is linear in time; the certificates' uncertainties are independent and normal; the tolerance applies to the deviation from the value certified at the latest calibration; the interval counts from that calibration";

/// The interval for a drift `rate_per_year ± u_rate_per_year` after a calibration known to
/// `u0`.
///
/// # Errors
/// [`RecordsError::Invalid`] for a tolerance that is not > 0, a reliability outside [0.5, 1),
/// or a rate or uncertainty that is not finite (or negative).
pub fn variables_interval(
    request: IntervalRequest,
    u0: f64,
    rate_per_year: f64,
    u_rate_per_year: f64,
) -> Result<Interval> {
    let l = units::positive("--tolerance", request.tolerance)?;
    let r = units::require(
        "--reliability",
        request.reliability,
        units::Requirement::OpenUnitInterval,
    )?;
    let r = units::require("--reliability", r, units::Requirement::AtLeast(0.5))?;
    let u0 = units::non_negative("the latest certificate's u", u0)?;
    let b = units::finite("the drift rate", rate_per_year)?.abs();
    let ub = units::non_negative("the drift rate's u", u_rate_per_year)?;
    let z = uncertainty::student_t_quantile(r, uncertainty::Dof::Infinite).map_err(|source| {
        RecordsError::Coverage {
            quantity: "the reliability target".to_owned(),
            source,
        }
    })?;
    let c = l * l - z * z * u0 * u0;
    let (years, attainable) = if c <= 0.0 {
        (Some(0.0), false)
    } else {
        let denominator = l * b + z * (b * b * u0 * u0 + ub * ub * c).sqrt();
        if denominator > 0.0 {
            (Some(c / denominator), true)
        } else {
            (None, true)
        }
    };
    Ok(Interval {
        request,
        z,
        u0,
        rate_per_year: b,
        u_rate_per_year: ub,
        years,
        attainable,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn the_interval_meets_the_tolerance_at_its_end() {
        let req = IntervalRequest {
            tolerance: 2.0,
            reliability: 0.9,
        };
        for (u0, b, ub) in [
            (0.3, 0.5, 0.1),
            (0.3, 0.01, 0.4),
            (0.1, -1.0, 0.0),
            (0.3, 0.2, 0.2 / 1.2816),
        ] {
            let i = variables_interval(req, u0, b, ub).unwrap();
            let t = i.years.unwrap();
            let at_end = b.abs() * t + i.z * (u0 * u0 + ub * ub * t * t).sqrt();
            assert_relative_eq!(at_end, 2.0, max_relative = 1e-12);
        }
    }

    #[test]
    fn unattainable_and_unlimited() {
        let req = IntervalRequest {
            tolerance: 1.0,
            reliability: 0.95,
        };
        let i = variables_interval(req, 1.0, 0.1, 0.1).unwrap();
        assert!(!i.attainable);
        assert_eq!(i.years, Some(0.0));
        assert_eq!(variables_interval(req, 0.1, 0.0, 0.0).unwrap().years, None);
        assert!(matches!(
            variables_interval(
                IntervalRequest {
                    tolerance: 1.0,
                    reliability: 1.5
                },
                0.1,
                0.0,
                0.0
            ),
            Err(RecordsError::Invalid { field, .. }) if field == "--reliability"
        ));
    }
}
