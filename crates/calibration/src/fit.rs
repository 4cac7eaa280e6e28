//! The eq. 18 fit with and without compensation (eq. 19), and how its points are weighted.

use identify::{
    CompensatedCalibration, Compensation, CrEstimate, Geometry, IdentifyError, K1Source,
};
use uncertainty::Dof;

/// How the eq. 18 fit weighted its points, and the degrees of freedom that follow.
#[derive(Debug, Clone, PartialEq)]
pub struct Weighting {
    /// Residual degrees of freedom of the fit.
    pub noise_dof: usize,
    /// Degrees of freedom of the fit's coefficients as an input group: infinite when the
    /// points' σ are taken as known (a weighted fit whose residuals stay within them), else
    /// `noise_dof`.
    pub group_dof: Dof,
    /// The standard deviation τ common to every point that the points' σ miss
    /// (Paule–Mandel), rad/s, when a weighted fit's χ²/ν exceeded 1.
    pub excess_u_rad_s: Option<f64>,
    /// Whether no τ bringing χ²/ν to 1 was found (the covariance is then Birge-scaled).
    pub tau_not_found: bool,
    /// The σ the fit was weighted by (with τ), rad/s, when weighted.
    pub sigma_used: Option<Vec<f64>>,
    /// The Birge ratio `√(χ²/ν)` of the weighted fit with the points' own σ.
    pub birge_ratio: Option<f64>,
}

/// The eq. 18 fit of a calibration's points and its weighting.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    /// The fit as measured and compensated (`identify`).
    pub calibration: CompensatedCalibration,
    /// How its points were weighted.
    pub weighting: Weighting,
}

/// The compensation of a C_r (m·s², with its standard uncertainty) with k1 fitted or given,
/// for `identify`.
#[must_use]
pub fn compensation(
    c_r_m_s2: f64,
    c_r_sigma_m_s2: f64,
    k1_given_rad_s_g: Option<f64>,
) -> Compensation {
    Compensation {
        c_r: CrEstimate {
            c_r_m_s2,
            c_r_sigma_m_s2,
        },
        k1: match k1_given_rad_s_g {
            None => K1Source::Fitted,
            Some(k1_rad_s_g) => K1Source::Given { k1_rad_s_g },
        },
    }
}

/// Fits eq. 18 to the outputs at `rates_rad_s`, as measured and compensated by
/// `compensation` (eq. 19), weighted by `1/σᵢ` when `sigma_rad_s` is given.
///
/// Points that scatter more than their σ say (χ²/ν > 1) miss a variation common to every
/// point (from run to run). Its variance τ² is the one that makes χ²/ν = 1 with σᵢ² + τ² (the
/// Paule–Mandel estimate, found by bisection); the fit is then weighted by those. When no
/// such τ is found the fit keeps the points' σ and its covariance is scaled by the Birge
/// ratio ([`Weighting::tau_not_found`]).
///
/// # Errors
/// Those of [`identify::identify_compensated`] and
/// [`identify::identify_compensated_weighted`].
pub fn fit(
    rates_rad_s: &[f64],
    outputs_rad_s: &[f64],
    sigma_rad_s: Option<&[f64]>,
    geometry: Geometry,
    compensation: &Compensation,
) -> Result<Fitted, IdentifyError> {
    let fit_with = |sigma: Option<&[f64]>| match sigma {
        None => identify::identify_compensated(rates_rad_s, outputs_rad_s, geometry, compensation),
        Some(sigma) => identify::identify_compensated_weighted(
            rates_rad_s,
            outputs_rad_s,
            sigma,
            geometry,
            compensation,
        ),
    };
    let mut cal = fit_with(sigma_rad_s)?;
    let first_birge = cal.uncompensated.birge_ratio;
    let mut excess_u_rad_s = None;
    let mut tau_not_found = false;
    let mut sigma_used = sigma_rad_s.map(<[f64]>::to_vec);
    if let (Some(sigma), Some(birge)) = (sigma_rad_s, cal.uncompensated.birge_ratio)
        && birge > 1.0
    {
        let combined =
            |tau: f64| -> Vec<f64> { sigma.iter().map(|s| s.hypot(tau)).collect::<Vec<_>>() };
        let birge_at = |tau: f64| {
            fit_with(Some(&combined(tau)))
                .ok()
                .and_then(|c| c.uncompensated.birge_ratio)
        };
        // χ²/ν falls towards 0 as τ grows: double τ from the largest residual until it is
        // below 1 (with few degrees of freedom the largest residual may not be enough).
        let mut low = 0.0;
        let mut high = cal
            .uncompensated
            .residuals_rad_s
            .iter()
            .fold(0.0_f64, |m, r| m.max(r.abs()))
            .max(f64::MIN_POSITIVE);
        let mut bracketed = false;
        for _ in 0..200 {
            match birge_at(high) {
                Some(b) if b < 1.0 => {
                    bracketed = true;
                    break;
                }
                Some(_) => {
                    low = high;
                    high *= 2.0;
                }
                None => break,
            }
        }
        tau_not_found = !bracketed;
        if bracketed {
            for _ in 0..60 {
                let mid = 0.5 * (low + high);
                match birge_at(mid) {
                    Some(b) if b > 1.0 => low = mid,
                    _ => high = mid,
                }
            }
            let tau = high;
            let widened = combined(tau);
            cal = fit_with(Some(&widened))?;
            excess_u_rad_s = Some(tau);
            sigma_used = Some(widened);
        }
    }
    let noise_dof = cal.uncompensated.fit.dof;
    // The group's degrees of freedom: the σᵢ taken as known (a weighted fit whose residuals
    // stay within them, its covariance (XᵀWX)⁻¹ not scaled by them) have as many as their
    // own estimates, many; a covariance scaled by the residuals (unweighted, or with τ
    // estimated from them) has n − 6.
    let group_dof = match (first_birge, excess_u_rad_s, tau_not_found) {
        (Some(b), None, false) if b <= 1.0 => Dof::Infinite,
        _ => Dof::Finite(noise_dof as f64),
    };
    Ok(Fitted {
        calibration: cal,
        weighting: Weighting {
            noise_dof,
            group_dof,
            excess_u_rad_s,
            tau_not_found,
            sigma_used,
            birge_ratio: first_birge,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Outputs of eq. 18 at twelve rates, with an alternating error of ±`bump` rad/s.
    fn points(bump: f64) -> (Vec<f64>, Vec<f64>, Geometry) {
        let geometry = Geometry {
            radius_m: 2.5,
            g_m_s2: 9.8,
        };
        let rates: Vec<f64> = (1..=12)
            .map(|i| units::deg_s_to_rad_s(16.0 * f64::from(i)))
            .collect();
        let outputs = rates
            .iter()
            .enumerate()
            .map(|(i, &w)| {
                let a = geometry.input_g(w);
                let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                1e-5 + 0.56 * a + 5e-7 * a * a + sign * bump
            })
            .collect();
        (rates, outputs, geometry)
    }

    #[test]
    fn paule_mandel_tau_brings_the_birge_ratio_to_one() {
        let (rates, outputs, geometry) = points(1e-7);
        let sigma = vec![1e-8; rates.len()];
        let c = compensation(1e-6, 1e-8, None);
        let f = fit(&rates, &outputs, Some(&sigma), geometry, &c).unwrap();
        let tau = f.weighting.excess_u_rad_s.expect("scatter 10× σ needs a τ");
        assert!(f.weighting.birge_ratio.unwrap() > 5.0);
        let used = f.weighting.sigma_used.as_ref().unwrap();
        let again =
            identify::identify_calibration_weighted(&rates, &outputs, used, geometry).unwrap();
        assert!((again.birge_ratio.unwrap() - 1.0).abs() < 1e-9, "{tau}");
        assert_eq!(f.weighting.group_dof, Dof::Finite(6.0));
    }

    #[test]
    fn points_within_their_sigma_are_known_weights() {
        let (rates, outputs, geometry) = points(1e-9);
        let sigma = vec![1e-8; rates.len()];
        let c = compensation(1e-6, 1e-8, Some(0.56));
        let f = fit(&rates, &outputs, Some(&sigma), geometry, &c).unwrap();
        assert_eq!(f.weighting.excess_u_rad_s, None);
        assert!(!f.weighting.tau_not_found);
        assert_eq!(f.weighting.group_dof, Dof::Infinite);
        let unweighted = fit(&rates, &outputs, None, geometry, &c).unwrap();
        assert_eq!(unweighted.weighting.group_dof, Dof::Finite(6.0));
        assert_eq!(unweighted.weighting.sigma_used, None);
    }
}
