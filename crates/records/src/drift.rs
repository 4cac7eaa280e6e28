//! The drift of a recorded quantity: a straight line against the date, weighted by the
//! certificates' (or probe phases') standard uncertainties, its rate per year with its
//! uncertainty and significance, and the value predicted at a date.
//!
//! Model: `y(t) = a + b·t`, `t` in years since the first record. Each record enters with the
//! weight `1/u_i` of its own standard uncertainty (the records are independent calibrations:
//! the covariance a certificate states couples its coefficients, not two certificates, so
//! each coefficient is fitted on its own). With three records or more the line is fitted by
//! `identify::lstsq` (QR with column scaling) on the weighted rows, and the covariance of
//! `(a, b)` is the one for the stated uncertainties (`(XᵀWX)⁻¹`), enlarged by the Birge ratio
//! `√(χ²/ν)` when the records scatter more than their uncertainties say (then the coverage
//! factor is Student's t with ν = n − 2, else the normal 1.96). With two records the line
//! passes through both and its covariance follows from theirs exactly.

use nalgebra::DMatrix;

use crate::date::Date;
use crate::error::{RecordsError, Result};

/// One recorded value of a quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    /// The date it was measured.
    pub date: Date,
    /// The value.
    pub value: f64,
    /// Its standard uncertainty (> 0).
    pub u: f64,
}

/// A fitted drift.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Drift {
    /// `t = 0`: the first record's date.
    pub origin: Date,
    /// The value at the origin, `a`.
    pub intercept: f64,
    /// The drift rate `b`, per year (of 365.2425 days).
    pub rate_per_year: f64,
    /// Its standard uncertainty.
    pub u_rate_per_year: f64,
    /// The covariance of `(a, b)`.
    pub covariance: [[f64; 2]; 2],
    /// `√(χ²/ν)` of the weighted residuals (absent with two records).
    pub birge_ratio: Option<f64>,
    /// Whether the uncertainties were enlarged by the Birge ratio (it exceeded 1).
    pub scaled_by_scatter: bool,
    /// The coverage factor of the 95 % intervals.
    pub k95: f64,
    /// `k95 · u(b)`.
    pub expanded_rate_per_year: f64,
    /// Whether `|b| > k95·u(b)`: a drift at the 95 % level.
    pub significant: bool,
    /// The records fitted.
    pub points: usize,
}

/// The value of a drifting quantity predicted at a date.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Prediction {
    /// The date.
    pub date: Date,
    /// The predicted value `a + b·t`.
    pub value: f64,
    /// Its standard uncertainty from the fit, `√([1 t]·C·[1 t]ᵀ)`.
    pub u: f64,
    /// The standard uncertainty of what a calibration on that date would read: the fit's and
    /// the latest record's own, `√(u² + u_last²)`.
    pub u_reading: f64,
    /// The coverage factor (the drift's).
    pub k95: f64,
}

impl Drift {
    /// The value predicted at `date`, with `u_last` the standard uncertainty a new
    /// measurement is taken to have (the latest record's).
    pub fn predict(&self, date: Date, u_last: f64) -> Prediction {
        let t = date.years_since(self.origin);
        let c = &self.covariance;
        let var = c[0][0] + 2.0 * t * c[0][1] + t * t * c[1][1];
        let u = var.max(0.0).sqrt();
        Prediction {
            date,
            value: self.intercept + self.rate_per_year * t,
            u,
            u_reading: u.hypot(u_last),
            k95: self.k95,
        }
    }
}

/// The drift of `quantity` through `observations` (any order); `None` with fewer than two
/// dates.
///
/// # Errors
/// [`RecordsError::NonFinite`] for a value or uncertainty that is not finite or a `u` ≤ 0;
/// [`RecordsError::Fit`] when the solver fails; [`RecordsError::Coverage`] for the t quantile.
pub fn fit_drift(quantity: &str, observations: &[Observation]) -> Result<Option<Drift>> {
    for (i, o) in observations.iter().enumerate() {
        if !(o.value.is_finite() && o.u.is_finite() && o.u > 0.0) {
            return Err(RecordsError::NonFinite {
                what: format!("{quantity}: record {} (value or its u > 0)", i + 1),
            });
        }
    }
    let Some(origin) = observations.iter().map(|o| o.date).min() else {
        return Ok(None);
    };
    let distinct = {
        let mut d: Vec<Date> = observations.iter().map(|o| o.date).collect();
        d.sort_unstable();
        d.dedup();
        d.len()
    };
    if distinct < 2 {
        return Ok(None);
    }
    let t: Vec<f64> = observations
        .iter()
        .map(|o| o.date.years_since(origin))
        .collect();
    let n = observations.len();
    let (a, b, cov, birge) = if n == 2 {
        // The line through both records: a = y₁ + b·(0 − t₁), b = (y₂ − y₁)/(t₂ − t₁).
        let (o1, o2) = (observations[0], observations[1]);
        let (t1, t2) = (t[0], t[1]);
        let dt = t2 - t1;
        let b = (o2.value - o1.value) / dt;
        let a = o1.value - b * t1;
        // ∂(a, b)/∂(y₁, y₂) = [[t₂/dt, −t₁/dt], [−1/dt, 1/dt]]
        let j = [[t2 / dt, -t1 / dt], [-1.0 / dt, 1.0 / dt]];
        let v = [o1.u * o1.u, o2.u * o2.u];
        let mut cov = [[0.0; 2]; 2];
        for (r, row) in cov.iter_mut().enumerate() {
            for (c, cell) in row.iter_mut().enumerate() {
                *cell = j[r][0] * j[c][0] * v[0] + j[r][1] * j[c][1] * v[1];
            }
        }
        (a, b, cov, None)
    } else {
        let design = DMatrix::from_fn(n, 2, |i, j| {
            if j == 0 {
                1.0 / observations[i].u
            } else {
                t[i] / observations[i].u
            }
        });
        let y: Vec<f64> = observations.iter().map(|o| o.value / o.u).collect();
        let fit = identify::lstsq(&design, &y).map_err(|source| RecordsError::Fit {
            quantity: quantity.to_owned(),
            source,
        })?;
        let unscaled = &fit.unscaled_covariance;
        let cov = [
            [unscaled[(0, 0)], unscaled[(0, 1)]],
            [unscaled[(1, 0)], unscaled[(1, 1)]],
        ];
        (
            fit.coefficients[0],
            fit.coefficients[1],
            cov,
            Some(fit.residual_sd),
        )
    };
    let scaled = birge.is_some_and(|r| r > 1.0);
    let scale = if scaled {
        birge.unwrap_or(1.0).powi(2)
    } else {
        1.0
    };
    let cov = cov.map(|row| row.map(|c| c * scale));
    #[allow(clippy::cast_precision_loss)] // a count of records
    let dof = if scaled {
        uncertainty::Dof::Finite((n - 2) as f64)
    } else {
        uncertainty::Dof::Infinite
    };
    let k95 = uncertainty::coverage_factor(0.95, dof).map_err(|source| RecordsError::Coverage {
        quantity: quantity.to_owned(),
        source,
    })?;
    let u_rate = cov[1][1].max(0.0).sqrt();
    let drift = Drift {
        origin,
        intercept: a,
        rate_per_year: b,
        u_rate_per_year: u_rate,
        covariance: cov,
        birge_ratio: birge,
        scaled_by_scatter: scaled,
        k95,
        expanded_rate_per_year: k95 * u_rate,
        significant: b.abs() > k95 * u_rate,
        points: n,
    };
    if ![a, b, u_rate, cov[0][0], cov[0][1]]
        .iter()
        .all(|x| x.is_finite())
    {
        return Err(RecordsError::NonFinite {
            what: format!("the drift of {quantity}"),
        });
    }
    Ok(Some(drift))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn obs(day: i64, value: f64, u: f64) -> Observation {
        Observation {
            date: Date::from_days(day),
            value,
            u,
        }
    }

    #[test]
    fn two_records_give_the_line_through_them_and_its_exact_covariance() {
        let year = crate::date::DAYS_PER_YEAR;
        #[allow(clippy::cast_possible_truncation)]
        let d = year as i64;
        let o = [obs(0, 1.0, 0.1), obs(d, 2.0, 0.2)];
        let drift = fit_drift("x", &o).unwrap().unwrap();
        let dt = o[1].date.years_since(o[0].date);
        assert_relative_eq!(drift.rate_per_year, 1.0 / dt, max_relative = 1e-12);
        assert_relative_eq!(
            drift.u_rate_per_year,
            (0.01_f64 + 0.04).sqrt() / dt,
            max_relative = 1e-12
        );
        // extrapolating one interval on: 2y₂ − y₁ with variance 4u₂² + u₁²
        let p = drift.predict(Date::from_days(2 * d), 0.0);
        assert_relative_eq!(p.value, 3.0, max_relative = 1e-12);
        assert_relative_eq!(p.u, (4.0 * 0.04 + 0.01_f64).sqrt(), max_relative = 1e-9);
    }

    #[test]
    fn weighted_fit_equals_the_closed_form() {
        // Weighted straight line, the textbook sums (Bevington 6.12): Δ = S·Sxx − Sx².
        let o = [
            obs(0, 1.0, 0.1),
            obs(400, 1.9, 0.2),
            obs(700, 3.2, 0.1),
            obs(1100, 4.1, 0.3),
        ];
        let drift = fit_drift("x", &o).unwrap().unwrap();
        let (mut s, mut sx, mut sxx, mut sy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for p in &o {
            let w = 1.0 / (p.u * p.u);
            let t = p.date.years_since(o[0].date);
            s += w;
            sx += w * t;
            sxx += w * t * t;
            sy += w * p.value;
            sxy += w * t * p.value;
        }
        let delta = s * sxx - sx * sx;
        let b = (s * sxy - sx * sy) / delta;
        assert_relative_eq!(drift.rate_per_year, b, max_relative = 1e-12);
        let chi2: f64 = o
            .iter()
            .map(|p| {
                let t = p.date.years_since(o[0].date);
                ((p.value - drift.intercept - b * t) / p.u).powi(2)
            })
            .sum();
        let birge = (chi2 / 2.0).sqrt();
        assert_relative_eq!(drift.birge_ratio.unwrap(), birge, max_relative = 1e-9);
        let scale = birge.max(1.0).powi(2);
        assert_relative_eq!(
            drift.u_rate_per_year,
            (s / delta * scale).sqrt(),
            max_relative = 1e-9
        );
    }

    #[test]
    fn one_date_has_no_drift_and_bad_values_are_refused() {
        assert_eq!(fit_drift("x", &[obs(3, 1.0, 0.1)]).unwrap(), None);
        assert_eq!(
            fit_drift("x", &[obs(3, 1.0, 0.1), obs(3, 1.1, 0.1)]).unwrap(),
            None
        );
        assert!(matches!(
            fit_drift("k2", &[obs(3, f64::NAN, 0.1), obs(9, 1.0, 0.1)]),
            Err(RecordsError::NonFinite { .. })
        ));
    }
}
