//! The calibration compensated for the spindle's dynamic radius error (eq. 19).

use super::fit::{Calibration, calibrate};
use crate::error::Result;
use crate::geometry::Geometry;
use crate::radius::{CrEstimate, PseudoSecondOrder, pseudo_second_order, result_finite};

/// Which k1 the compensation `k1·C_r·ω⁴/g` uses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum K1Source {
    /// The k1 implied by the uncompensated fit's ω² coefficient, `c₂·g/R`. Its uncertainty and
    /// its correlation with the a² coefficient are propagated.
    Fitted,
    /// A k1 known from elsewhere (e.g. a tumble test), taken as exact (rad/(s·g)).
    Given {
        /// k1 in rad/(s·g).
        k1_rad_s_g: f64,
    },
}

/// The probe's measurement of the dynamic radius error, used to compensate a calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Compensation {
    /// Dynamic radius-error coefficient C_r with its standard deviation, e.g.
    /// [`crate::RadiusFit::c_r`].
    pub c_r: CrEstimate,
    /// The k1 to use.
    pub k1: K1Source,
}

/// Result of [`identify_compensated`].
#[derive(Debug, Clone, PartialEq)]
pub struct CompensatedCalibration {
    /// The plain eq. 18 fit of the outputs as measured.
    pub uncompensated: Calibration,
    /// The eq. 18 fit of the outputs minus `k1·C_r·ω⁴/g`. Its a² coefficient is k2, and its
    /// standard errors are those of the fit alone.
    pub compensated: Calibration,
    /// The compensation applied.
    pub compensation: Compensation,
    /// The k1 used in the compensation (rad/(s·g)).
    pub k1_used_rad_s_g: f64,
    /// The pseudo-second-order error removed, Δk2 = k1·C_r·g/R², with σ from σ(C_r) (eq. 19).
    pub delta_k2: PseudoSecondOrder,
    /// Compensated k2 (rad/(s·g²)): `uncompensated.k2_apparent_rad_s_g2 − delta_k2`, as the
    /// calibration's measurement model forms it (`compensated.k2_apparent_rad_s_g2` equals it
    /// but for rounding).
    pub k2_rad_s_g2: f64,
    /// Total standard deviation of the compensated k2: the fit's and σ(C_r)'s contributions, and
    /// for [`K1Source::Fitted`] also k1's, with its correlation with the a² coefficient.
    pub k2_sigma_rad_s_g2: f64,
    /// The part of the k2 variance that comes from σ(C_r), as a standard deviation.
    pub k2_sigma_from_c_r_rad_s_g2: f64,
}

/// Compensated identification: removes `k1·C_r·ω⁴/g` (eq. 17's imbalance term) from the
/// outputs and fits eq. 18 again. The a² coefficient is then k2 instead of `k2 + Δk2`.
///
/// Since `k1·C_r·ω⁴/g = (k1·C_r·g/R²)·a²` lies in the a² column, the compensated k2 equals
/// `k2_apparent − Δk2` exactly, the other coefficients and the residuals are unchanged, and
///
/// ```text
/// σ²(k2) = σ²_fit(c₄) + (k1·g/R²)²·σ²(C_r)
///          [ + (C_r·g²/R³)²·σ²(c₂) − 2·(C_r·g²/R³)·cov(c₂, c₄) ]   (the bracket for a fitted k1)
/// ```
///
/// with c₂ the ω² and c₄ the a² coefficient. C_r comes from the probe, an independent
/// measurement, so it is uncorrelated with the PIGA fit.
///
/// # Errors
/// Those of [`identify_calibration`](crate::identify_calibration);
/// [`IdentifyError::InvalidParameter`](crate::IdentifyError::InvalidParameter) for a
/// non-finite C_r or k1 or a negative σ(C_r).
///
/// ```
/// use approx::assert_relative_eq;
/// use identify::{identify_compensated, Compensation, CrEstimate, Geometry, K1Source};
/// let (r, g, k1, k2, c_r) = (2.5, 9.8, 0.56, 3e-6, -4e-8);
/// let rates: Vec<f64> = (1..=8).map(|i| (25.0 * f64::from(i)).to_radians()).collect();
/// let out: Vec<f64> = rates.iter().map(|w| {
///     let a = r * w * w / g;
///     k1 * a + k2 * a * a + k1 * c_r * w.powi(4) / g
/// }).collect();
/// let comp = Compensation {
///     c_r: CrEstimate { c_r_m_s2: c_r, c_r_sigma_m_s2: 1e-9 },
///     k1: K1Source::Fitted,
/// };
/// let cal = identify_compensated(&rates, &out, Geometry { radius_m: r, g_m_s2: g }, &comp)?;
/// assert_relative_eq!(cal.k2_rad_s_g2, k2, max_relative = 1e-6);
/// assert_relative_eq!(cal.uncompensated.k2_apparent_rad_s_g2, k2 + k1 * c_r * g / (r * r),
///                     max_relative = 1e-6);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn identify_compensated(
    rate_rad_s: &[f64],
    output_rad_s: &[f64],
    geometry: Geometry,
    compensation: &Compensation,
) -> Result<CompensatedCalibration> {
    compensate(rate_rad_s, output_rad_s, None, geometry, compensation)
}

/// [`identify_compensated`] with both fits weighted by `1/σᵢ`
/// ([`identify_calibration_weighted`](crate::identify_calibration_weighted)).
///
/// # Errors
/// Those of [`identify_compensated`] and
/// [`identify_calibration_weighted`](crate::identify_calibration_weighted).
pub fn identify_compensated_weighted(
    rate_rad_s: &[f64],
    output_rad_s: &[f64],
    sigma_rad_s: &[f64],
    geometry: Geometry,
    compensation: &Compensation,
) -> Result<CompensatedCalibration> {
    compensate(
        rate_rad_s,
        output_rad_s,
        Some(sigma_rad_s),
        geometry,
        compensation,
    )
}

/// The compensated identification, weighted when σ is given.
fn compensate(
    rate_rad_s: &[f64],
    output_rad_s: &[f64],
    sigma_rad_s: Option<&[f64]>,
    geometry: Geometry,
    compensation: &Compensation,
) -> Result<CompensatedCalibration> {
    compensation.c_r.validate()?;
    if let K1Source::Given { k1_rad_s_g } = compensation.k1 {
        units::finite("k1_rad_s_g", k1_rad_s_g)?;
    }
    let uncompensated = calibrate(rate_rad_s, output_rad_s, sigma_rad_s, geometry)?;
    let k1 = match compensation.k1 {
        K1Source::Fitted => uncompensated.k1_implied_rad_s_g,
        K1Source::Given { k1_rad_s_g } => k1_rad_s_g,
    };
    let c_r = compensation.c_r.c_r_m_s2;
    let Geometry { radius_m, g_m_s2 } = geometry;
    let corrected: Vec<f64> = rate_rad_s
        .iter()
        .zip(output_rad_s)
        .map(|(w, y)| y - k1 * c_r * w.powi(4) / g_m_s2)
        .collect();
    let compensated = calibrate(rate_rad_s, &corrected, sigma_rad_s, geometry)?;
    let delta_k2 = pseudo_second_order(k1, compensation.c_r, geometry)?;

    let cov = &compensated.fit.covariance;
    let mut variance = cov[(4, 4)] + delta_k2.sigma_rad_s_g2.powi(2);
    if compensation.k1 == K1Source::Fitted {
        // k2 = c4 − c2·C_r·g²/R³; the derivative with respect to c2 is −C_r·g²/R³.
        let d = -c_r * g_m_s2 * g_m_s2 / (radius_m * radius_m * radius_m);
        variance += d * d * cov[(2, 2)] + 2.0 * d * cov[(2, 4)];
    }
    let k2_sigma_rad_s_g2 = variance.max(0.0).sqrt();
    let inputs = [
        ("radius_m", radius_m),
        ("g_m_s2", g_m_s2),
        ("c_r_m_s2", c_r),
        ("c_r_sigma_m_s2", compensation.c_r.c_r_sigma_m_s2),
        ("k1_rad_s_g", k1),
    ];
    if variance.is_nan() {
        result_finite("k2_sigma_rad_s_g2", f64::NAN, &inputs)?;
    }
    result_finite("k2_sigma_rad_s_g2", k2_sigma_rad_s_g2, &inputs)?;
    // k2 = c₄ − Δk2, as the calibration's measurement model forms it (`calibration::
    // CalibrationModel`): the compensated refit's a² coefficient equals it but for rounding
    // (a few parts in 10⁹ on an ill-conditioned design), and one number is reported
    // everywhere.
    Ok(CompensatedCalibration {
        k2_rad_s_g2: uncompensated.k2_apparent_rad_s_g2 - delta_k2.delta_k2_rad_s_g2,
        k2_sigma_rad_s_g2,
        k2_sigma_from_c_r_rad_s_g2: delta_k2.sigma_rad_s_g2,
        uncompensated,
        compensated,
        compensation: *compensation,
        k1_used_rad_s_g: k1,
        delta_k2,
    })
}
