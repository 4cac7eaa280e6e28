//! The radius-error model `Δr(ω) = a + C_r·ω²` and the pseudo-second-order error of eq. 19.

use nalgebra::DMatrix;

use crate::error::{IdentifyError, Result};
use crate::geometry::Geometry;
use crate::lstsq::{Fit, lstsq};

/// Model fitted to the working-radius error as a function of the spindle rate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum RadiusModel {
    /// `Δr = a + C_r·ω²`: static offset plus the dynamic (imbalance) drift. The paper's model.
    TwoTerm,
    /// `Δr = a + b·ω + C_r·ω²`: adds a term linear in ω (the fit the paper's ±0.39e-8 belongs to).
    ThreeTerm,
}

impl RadiusModel {
    /// Number of coefficients.
    #[must_use]
    pub const fn unknowns(self) -> usize {
        match self {
            Self::TwoTerm => 2,
            Self::ThreeTerm => 3,
        }
    }
}

/// Result of [`fit_radius_error`].
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusFit {
    /// Model fitted.
    pub model: RadiusModel,
    /// Dynamic radius-error coefficient C_r (m·s²), the coefficient of ω².
    pub c_r_m_s2: f64,
    /// Standard error of C_r from this fit's own covariance (m·s²).
    pub c_r_sigma_m_s2: f64,
    /// Static offset a (m).
    pub offset_m: f64,
    /// Coefficient b of ω (m·s) for [`RadiusModel::ThreeTerm`], `None` for the two-term model.
    pub linear_m_s: Option<f64>,
    /// Standard error of b (m·s), when fitted.
    pub linear_sigma_m_s: Option<f64>,
    /// Residuals `measured − fitted` in metres, one per point (for a weighted fit these are
    /// not `fit.residuals`, which are divided by each point's σ).
    pub residuals_m: Vec<f64>,
    /// Whether the rows were weighted by `1/σᵢ` ([`fit_radius_error_weighted`]).
    pub weighted: bool,
    /// The underlying least-squares fit; coefficients in the order a, (b,) C_r.
    pub fit: Fit,
}

impl RadiusFit {
    /// `C_r` and its standard error from this fit.
    #[must_use]
    pub const fn c_r(&self) -> CrEstimate {
        CrEstimate {
            c_r_m_s2: self.c_r_m_s2,
            c_r_sigma_m_s2: self.c_r_sigma_m_s2,
        }
    }

    /// Radius error predicted by the fitted model at `rate_rad_s` (m).
    #[must_use]
    pub fn predict_m(&self, rate_rad_s: f64) -> f64 {
        self.offset_m
            + self.linear_m_s.unwrap_or(0.0) * rate_rad_s
            + self.c_r_m_s2 * rate_rad_s * rate_rad_s
    }
}

/// Fits the radius error `Δr(ω)` by least squares ([`lstsq`]).
///
/// ```text
/// Δr(ω) = a + C_r·ω²    or    Δr(ω) = a + b·ω + C_r·ω²
/// ```
///
/// `rate_rad_s[i]` is the spindle rate (rad/s) and `radius_error_m[i]` the measured radius error
/// (m, the sum Δr_xd + Δr_xs of eq. 22) at point i.
///
/// # Errors
/// [`IdentifyError::DimensionMismatch`] when the slices differ in length; the errors of
/// [`lstsq`] otherwise (too few points, non-finite input, rank deficiency, e.g. repeated rates).
///
/// # Example
/// ```
/// use approx::assert_relative_eq;
/// use identify::{fit_radius_error, RadiusModel};
/// let rate_rad_s = [1.0, 2.0, 3.0];
/// let err_m: Vec<f64> = rate_rad_s.iter().map(|w| 1e-6 - 2e-8 * w * w).collect();
/// let fit = fit_radius_error(&rate_rad_s, &err_m, RadiusModel::TwoTerm)?;
/// assert_relative_eq!(fit.c_r_m_s2, -2e-8, max_relative = 1e-10);
/// assert_relative_eq!(fit.predict_m(4.0), 1e-6 - 32e-8, max_relative = 1e-10);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn fit_radius_error(
    rate_rad_s: &[f64],
    radius_error_m: &[f64],
    model: RadiusModel,
) -> Result<RadiusFit> {
    fit(rate_rad_s, radius_error_m, None, model)
}

/// [`fit_radius_error`] by weighted least squares: row i is divided by `sigma_m[i]`, the
/// standard error of that point's radius error (e.g. from the spread of the per-revolution
/// first harmonics), so points measured less precisely count less.
///
/// `fit.residual_sd` is `s = √(Σ(rᵢ/σᵢ)²/(m − n))`, the square root of the reduced χ² (the
/// Birge ratio), about 1 when the σᵢ describe the scatter. The standard errors of `C_r` and
/// `b` are those of the σᵢ taken as known, enlarged by `s` when `s > 1` (scatter beyond the
/// σᵢ) and never shrunk by `s < 1`, the metrology convention: a small scatter of a few points
/// is not evidence that the σᵢ are too large. `fit.covariance` and `fit.std_errors` keep the
/// plain least-squares scaling by `s²`.
///
/// # Errors
/// As [`fit_radius_error`]; [`IdentifyError::DimensionMismatch`] for a `sigma_m` of another
/// length and [`IdentifyError::InvalidParameter`] for a σ that is not finite and positive.
///
/// ```
/// use approx::assert_relative_eq;
/// use identify::{fit_radius_error_weighted, RadiusModel};
/// let rate_rad_s = [1.0, 2.0, 3.0, 4.0];
/// let err_m: Vec<f64> = rate_rad_s.iter().map(|w| 1e-6 - 2e-8 * w * w).collect();
/// let sigma_m = [1e-9, 1e-9, 2e-9, 4e-9];
/// let fit = fit_radius_error_weighted(&rate_rad_s, &err_m, &sigma_m, RadiusModel::TwoTerm)?;
/// assert_relative_eq!(fit.c_r_m_s2, -2e-8, max_relative = 1e-10);
/// assert!(fit.weighted);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn fit_radius_error_weighted(
    rate_rad_s: &[f64],
    radius_error_m: &[f64],
    sigma_m: &[f64],
    model: RadiusModel,
) -> Result<RadiusFit> {
    if sigma_m.len() != rate_rad_s.len() {
        return Err(IdentifyError::DimensionMismatch {
            what: "sigma_m",
            got: sigma_m.len(),
            expected: rate_rad_s.len(),
        });
    }
    for &sigma in sigma_m {
        units::positive("sigma_m", sigma)?;
    }
    fit(rate_rad_s, radius_error_m, Some(sigma_m), model)
}

fn fit(
    rate_rad_s: &[f64],
    radius_error_m: &[f64],
    sigma_m: Option<&[f64]>,
    model: RadiusModel,
) -> Result<RadiusFit> {
    if rate_rad_s.len() != radius_error_m.len() {
        return Err(IdentifyError::DimensionMismatch {
            what: "radius_error_m",
            got: radius_error_m.len(),
            expected: rate_rad_s.len(),
        });
    }
    let m = rate_rad_s.len();
    let weight = |i: usize| sigma_m.map_or(1.0, |s| 1.0 / s[i]);
    let design = match model {
        RadiusModel::TwoTerm => {
            DMatrix::from_fn(m, 2, |i, j| rate_rad_s[i].powi(2 * j as i32) * weight(i))
        }
        RadiusModel::ThreeTerm => {
            DMatrix::from_fn(m, 3, |i, j| rate_rad_s[i].powi(j as i32) * weight(i))
        }
    };
    let y: Vec<f64> = (0..m).map(|i| radius_error_m[i] * weight(i)).collect();
    let fit = lstsq(&design, &y)?;
    let last = model.unknowns() - 1;
    // Unweighted: the ordinary standard errors. Weighted: those of the σᵢ taken as known,
    // `√[(XᵀWX)⁻¹]ₖₖ`, times the Birge ratio when it exceeds 1.
    let sigma = |k: usize| match sigma_m {
        None => fit.std_errors[k],
        Some(_) => fit.unscaled_covariance[(k, k)].sqrt() * fit.residual_sd.max(1.0),
    };
    let (linear_m_s, linear_sigma_m_s) = match model {
        RadiusModel::TwoTerm => (None, None),
        RadiusModel::ThreeTerm => (Some(fit.coefficients[1]), Some(sigma(1))),
    };
    let c_r_sigma_m_s2 = sigma(last);
    let mut radius_fit = RadiusFit {
        model,
        c_r_m_s2: fit.coefficients[last],
        c_r_sigma_m_s2,
        offset_m: fit.coefficients[0],
        linear_m_s,
        linear_sigma_m_s,
        residuals_m: Vec::new(),
        weighted: sigma_m.is_some(),
        fit,
    };
    radius_fit.residuals_m = match sigma_m {
        None => radius_fit.fit.residuals.clone(),
        Some(s) => (0..m).map(|i| radius_fit.fit.residuals[i] * s[i]).collect(),
    };
    let inputs: &[(&'static str, f64)] = &[];
    result_finite("c_r_sigma_m_s2", radius_fit.c_r_sigma_m_s2, inputs)?;
    if let Some(sigma) = radius_fit.linear_sigma_m_s {
        result_finite("linear_sigma_m_s", sigma, inputs)?;
    }
    if let Some(r) = radius_fit.residuals_m.iter().find(|r| !r.is_finite()) {
        result_finite("residuals_m", *r, inputs)?;
    }
    Ok(radius_fit)
}

/// The dynamic radius-error coefficient `C_r` with its standard deviation, as measured by the
/// probe ([`RadiusFit::c_r`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct CrEstimate {
    /// `C_r`, m·s² (finite).
    pub c_r_m_s2: f64,
    /// Its standard deviation σ(C_r), m·s² (finite and ≥ 0; 0 for an exact value).
    pub c_r_sigma_m_s2: f64,
}

impl CrEstimate {
    /// Checks that `C_r` is finite and σ(C_r) finite and not negative.
    ///
    /// # Errors
    /// [`IdentifyError::InvalidParameter`] naming `c_r_m_s2` or `c_r_sigma_m_s2`.
    pub fn validate(&self) -> Result<()> {
        units::finite("c_r_m_s2", self.c_r_m_s2)?;
        units::non_negative("c_r_sigma_m_s2", self.c_r_sigma_m_s2)?;
        Ok(())
    }
}

/// Pseudo-second-order error of eq. 19 and its standard deviation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PseudoSecondOrder {
    /// Δk2 = k1·C_r·g/R² (rad/(s·g²)).
    pub delta_k2_rad_s_g2: f64,
    /// Standard deviation of Δk2 propagated from σ(C_r): |k1·g/R²|·σ(C_r) (rad/(s·g²)).
    pub sigma_rad_s_g2: f64,
}

/// Pseudo-second-order coefficient error caused by the dynamic radius error (eq. 19).
///
/// ```text
/// Δk2 = k1·C_r·g/R²,    σ(Δk2) = |k1·g/R²|·σ(C_r)
/// ```
///
/// k1 in rad/(s·g), C_r and σ(C_r) in m·s², g in m/s², R in m; the result is in rad/(s·g²).
/// Only σ(C_r) is propagated (k1, g and R are taken as exact).
///
/// # Errors
/// [`IdentifyError::InvalidParameter`] for non-finite inputs, a negative σ(C_r), or a
/// non-positive g or radius.
///
/// # Example
/// ```
/// use approx::assert_relative_eq;
/// use identify::{CrEstimate, Geometry, pseudo_second_order};
/// let c_r = CrEstimate { c_r_m_s2: 2e-8, c_r_sigma_m_s2: 1e-9 };
/// let p = pseudo_second_order(0.5, c_r, Geometry { radius_m: 2.0, g_m_s2: 10.0 })?;
/// assert_relative_eq!(p.delta_k2_rad_s_g2, 0.5 * 2e-8 * 10.0 / 4.0, max_relative = 1e-15);
/// assert_relative_eq!(p.sigma_rad_s_g2, 0.5 * 1e-9 * 10.0 / 4.0, max_relative = 1e-15);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn pseudo_second_order(
    k1_rad_s_g: f64,
    c_r: CrEstimate,
    geometry: Geometry,
) -> Result<PseudoSecondOrder> {
    units::finite("k1_rad_s_g", k1_rad_s_g)?;
    c_r.validate()?;
    geometry.validate()?;
    let Geometry { radius_m, g_m_s2 } = geometry;
    let result = PseudoSecondOrder {
        delta_k2_rad_s_g2: delta_k2_rad_s_g2(k1_rad_s_g, c_r.c_r_m_s2, radius_m, g_m_s2),
        sigma_rad_s_g2: delta_k2_rad_s_g2(k1_rad_s_g, c_r.c_r_sigma_m_s2, radius_m, g_m_s2).abs(),
    };
    let inputs = [
        ("k1_rad_s_g", k1_rad_s_g),
        ("c_r_m_s2", c_r.c_r_m_s2),
        ("c_r_sigma_m_s2", c_r.c_r_sigma_m_s2),
        ("g_m_s2", g_m_s2),
        ("radius_m", radius_m),
    ];
    result_finite("delta_k2_rad_s_g2", result.delta_k2_rad_s_g2, &inputs)?;
    result_finite("delta_k2_sigma_rad_s_g2", result.sigma_rad_s_g2, &inputs)?;
    Ok(result)
}

/// `Δk2 = k1·C_r·g/R²` of eq. 19 on plain values (k1 in rad/(s·g), C_r in m·s², R in m, g in
/// m/s²; the result in rad/(s·g²)), unchecked: the one home of the formula, which
/// [`pseudo_second_order`] (validated, with σ) and the measurement models, the planner and the
/// simulator evaluate. A C_r of several causes (the probe's, the arm's stretch) is their sum.
///
/// ```
/// approx::assert_relative_eq!(identify::delta_k2_rad_s_g2(0.5, 2e-8, 2.0, 10.0),
///                             0.5 * 2e-8 * 10.0 / 4.0, max_relative = 1e-15);
/// ```
#[inline]
#[must_use]
pub fn delta_k2_rad_s_g2(k1_rad_s_g: f64, c_r_m_s2: f64, radius_m: f64, g_m_s2: f64) -> f64 {
    k1_rad_s_g * c_r_m_s2 * g_m_s2 / (radius_m * radius_m)
}

/// `Ok` when a result is finite, [`IdentifyError::NonFiniteResult`] naming it and the inputs
/// otherwise: no function of this crate returns an `Ok` holding NaN or ±∞.
pub(crate) fn result_finite(
    quantity: &'static str,
    value: f64,
    inputs: &[(&'static str, f64)],
) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(IdentifyError::NonFiniteResult {
            quantity,
            value,
            inputs: inputs.to_vec(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn two_term_by_hand() {
        // ω² = 0, 1, 4 with Δr = 1, 2, 4 (µm): the 3-point line of the lstsq test in ω².
        // Over u = ω²: ū = 5/3, ȳ = 7/3, Sxx = (25 + 4 + 49)/9 = 26/3,
        // Sxy = (−5/3)(−4/3) + (−2/3)(−1/3) + (7/3)(5/3) = 57/9 = 19/3, slope = 19/26.
        let fit =
            fit_radius_error(&[0.0, 1.0, 2.0], &[1.0, 2.0, 4.0], RadiusModel::TwoTerm).unwrap();
        assert_relative_eq!(fit.c_r_m_s2, 19.0 / 26.0, max_relative = 1e-13);
        assert_relative_eq!(
            fit.offset_m,
            7.0 / 3.0 - 19.0 / 26.0 * 5.0 / 3.0,
            max_relative = 1e-13
        );
        assert!(fit.linear_m_s.is_none());
        assert_relative_eq!(
            fit.predict_m(1.0),
            fit.offset_m + fit.c_r_m_s2,
            max_relative = 1e-15
        );
    }

    #[test]
    fn three_term_exact_quadratic() {
        let w = [0.5, 1.0, 1.5, 2.0, 3.0];
        let e: Vec<f64> = w.iter().map(|w| 2e-6 + 3e-7 * w - 4e-8 * w * w).collect();
        let fit = fit_radius_error(&w, &e, RadiusModel::ThreeTerm).unwrap();
        assert_relative_eq!(fit.c_r_m_s2, -4e-8, max_relative = 1e-10);
        assert_relative_eq!(fit.linear_m_s.unwrap(), 3e-7, max_relative = 1e-10);
        assert_relative_eq!(fit.offset_m, 2e-6, max_relative = 1e-10);
    }

    #[test]
    fn eq19_by_hand_and_errors() {
        let c_r = |c_r_m_s2, c_r_sigma_m_s2| CrEstimate {
            c_r_m_s2,
            c_r_sigma_m_s2,
        };
        let geometry = |radius_m, g_m_s2| Geometry { radius_m, g_m_s2 };
        let p = pseudo_second_order(-2.0, c_r(3e-8, 1e-8), geometry(3.0, 9.0)).unwrap();
        assert_relative_eq!(p.delta_k2_rad_s_g2, -6e-8, max_relative = 1e-15);
        assert_relative_eq!(p.sigma_rad_s_g2, 2e-8, max_relative = 1e-15);
        assert!(matches!(
            pseudo_second_order(0.56, c_r(1e-8, 1e-9), geometry(0.0, 9.8)),
            Err(IdentifyError::InvalidParameter {
                name: "radius_m",
                ..
            })
        ));
        // Finite inputs whose Δk2 overflows (R² underflows to 0): an error naming Δk2 and R.
        let err = pseudo_second_order(
            0.56,
            CrEstimate {
                c_r_m_s2: -4e-8,
                c_r_sigma_m_s2: 1e-9,
            },
            Geometry {
                radius_m: 1e-160,
                g_m_s2: 9.8,
            },
        )
        .unwrap_err();
        assert!(matches!(
            err,
            IdentifyError::NonFiniteResult {
                quantity: "delta_k2_rad_s_g2",
                ..
            }
        ));
        assert_eq!(
            err.to_string(),
            "delta_k2_rad_s_g2 is not finite (-inf) for k1_rad_s_g = 0.56, c_r_m_s2 = -4e-8, \
             c_r_sigma_m_s2 = 1e-9, g_m_s2 = 9.8, radius_m = 1e-160"
        );
        assert!(matches!(
            pseudo_second_order(0.56, c_r(1e-8, -1e-9), geometry(2.5, 9.8)),
            Err(IdentifyError::InvalidParameter {
                name: "c_r_sigma_m_s2",
                ..
            })
        ));
        assert!(matches!(
            pseudo_second_order(f64::NAN, c_r(1e-8, 1e-9), geometry(2.5, 9.8)),
            Err(IdentifyError::InvalidParameter {
                name: "k1_rad_s_g",
                ..
            })
        ));
    }

    #[test]
    fn mismatched_lengths() {
        assert!(matches!(
            fit_radius_error(&[1.0, 2.0, 3.0], &[1.0, 2.0], RadiusModel::TwoTerm),
            Err(IdentifyError::DimensionMismatch { .. })
        ));
    }

    /// Six rates and radius errors `2e-6 − 3e-8·ω²` with a ±1e-9 m alternating scatter.
    fn alternating_scatter() -> ([f64; 6], Vec<f64>) {
        let w = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0];
        let e = w
            .iter()
            .enumerate()
            .map(|(i, w)| 2e-6 - 3e-8 * w * w + if i % 2 == 0 { 1e-9 } else { -1e-9 })
            .collect();
        (w, e)
    }

    #[test]
    fn weighted_fit_with_equal_sigmas_is_the_ordinary_fit() {
        let (w, e) = alternating_scatter();
        let plain = fit_radius_error(&w, &e, RadiusModel::TwoTerm).unwrap();
        // Equal σᵢ below the scatter (Birge ratio > 1): the weighted fit is the ordinary one.
        let weighted =
            fit_radius_error_weighted(&w, &e, &[1e-10; 6], RadiusModel::TwoTerm).unwrap();
        assert!((plain.c_r_m_s2 - weighted.c_r_m_s2).abs() < 1e-12 * plain.c_r_m_s2.abs());
        assert!(
            (plain.c_r_sigma_m_s2 - weighted.c_r_sigma_m_s2).abs() < 1e-9 * plain.c_r_sigma_m_s2
        );
        for (a, b) in plain.residuals_m.iter().zip(&weighted.residuals_m) {
            assert!((a - b).abs() < 1e-20);
        }
        assert!(!plain.weighted && weighted.weighted);
    }

    #[test]
    fn weighted_sigma_is_never_shrunk_by_a_small_scatter() {
        let (w, e) = alternating_scatter();
        // σᵢ ten times the scatter: the Birge ratio is ≈ 0.1 and σ(C_r) is the known-σ value.
        let small = fit_radius_error_weighted(&w, &e, &[1e-8; 6], RadiusModel::TwoTerm).unwrap();
        assert!(small.fit.residual_sd < 1.0);
        // Known σ: var(C_r) = 1/Σwᵢ(uᵢ − ū)² with u = ω², w = 1/σ², equal weights here.
        let u: Vec<f64> = w.iter().map(|w| w * w).collect();
        let mean = u.iter().sum::<f64>() / 6.0;
        let known = 1e-8 / u.iter().map(|u| (u - mean).powi(2)).sum::<f64>().sqrt();
        assert!((small.c_r_sigma_m_s2 - known).abs() < 1e-12 * known);
        // σᵢ a tenth of the scatter: the Birge ratio is ≈ 10 and σ(C_r) grows with it.
        let large = fit_radius_error_weighted(&w, &e, &[1e-10; 6], RadiusModel::TwoTerm).unwrap();
        assert!(large.fit.residual_sd > 1.0);
        assert!((large.c_r_sigma_m_s2 - large.fit.std_errors[1]).abs() < 1e-12 * known);
    }

    #[test]
    fn a_point_with_a_huge_sigma_is_all_but_ignored() {
        let w = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0];
        let mut e: Vec<f64> = w.iter().map(|w| 2e-6 - 3e-8 * w * w).collect();
        e[5] += 1e-6; // an outlier
        let sigma = [1e-9, 1e-9, 1e-9, 1e-9, 1e-9, 1e-3];
        let fit = fit_radius_error_weighted(&w, &e, &sigma, RadiusModel::TwoTerm).unwrap();
        assert!((fit.c_r_m_s2 + 3e-8).abs() < 1e-14, "{}", fit.c_r_m_s2);
        // Its unweighted residual is still reported in metres.
        assert!((fit.residuals_m[5] - 1e-6).abs() < 1e-12);
    }

    #[test]
    fn weighted_fit_refuses_bad_sigmas() {
        let w = [1.0, 2.0, 3.0];
        let e = [1.0, 2.0, 3.0];
        assert!(matches!(
            fit_radius_error_weighted(&w, &e, &[1.0, 0.0, 1.0], RadiusModel::TwoTerm),
            Err(IdentifyError::InvalidParameter {
                name: "sigma_m",
                ..
            })
        ));
        assert!(matches!(
            fit_radius_error_weighted(&w, &e, &[1.0, f64::NAN, 1.0], RadiusModel::TwoTerm),
            Err(IdentifyError::InvalidParameter {
                name: "sigma_m",
                ..
            })
        ));
        assert!(matches!(
            fit_radius_error_weighted(&w, &e, &[1.0], RadiusModel::TwoTerm),
            Err(IdentifyError::DimensionMismatch {
                what: "sigma_m",
                ..
            })
        ));
    }

    #[test]
    fn weighted_fit_through_exact_points_keeps_the_known_sigma() {
        // Zero residuals: σ(C_r) is still that of the given σᵢ, not zero.
        let w = [0.0, 1.0, 2.0, 3.0];
        let e: Vec<f64> = w.iter().map(|w| 1e-6 + 2e-8 * w * w).collect();
        let fit = fit_radius_error_weighted(&w, &e, &[1e-7; 4], RadiusModel::ThreeTerm).unwrap();
        assert!(fit.c_r_sigma_m_s2 > 0.0);
        assert!(fit.linear_sigma_m_s.unwrap() > 0.0);
        // Closed form for equal σ: same as the unit-variance OLS covariance times σ.
        let plain = fit_radius_error(&w, &e, RadiusModel::ThreeTerm).unwrap();
        let unit = plain.fit.unscaled_covariance[(2, 2)].sqrt();
        assert!((fit.c_r_sigma_m_s2 - 1e-7 * unit).abs() < 1e-9 * 1e-7 * unit);
    }
}
