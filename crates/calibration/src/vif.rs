//! Variance inflation factors of the eq. 18 fit's terms.

use identify::CompensatedCalibration;

use crate::{TERMS, design_row};

/// A variance inflation factor above which terms are reported as hard to separate.
pub const VIF_LIMIT: f64 = 1e3;

/// Variance inflation factors of the five non-constant eq. 18 columns, from the fit's
/// unscaled covariance `(XᵀWX)⁻¹` and the columns' weighted sums of squares about their
/// weighted means (`VIF_j = [(XᵀWX)⁻¹]_jj · Σᵢ wᵢ(x_ij − x̄_j)²`, valid with an intercept
/// column; `wᵢ = 1/σᵢ²`, or 1 unweighted).
#[must_use]
pub fn variance_inflation(
    cal: &CompensatedCalibration,
    rates_rad_s: &[f64],
    sigma_rad_s: Option<&[f64]>,
) -> [f64; TERMS - 1] {
    let fit = &cal.uncompensated.fit;
    let geometry = cal.uncompensated.geometry;
    let rows: Vec<[f64; TERMS]> = rates_rad_s
        .iter()
        .map(|&w| design_row(w, geometry))
        .collect();
    let weights: Vec<f64> = match sigma_rad_s {
        Some(s) => s.iter().map(|s| 1.0 / (s * s)).collect(),
        None => vec![1.0; rates_rad_s.len()],
    };
    let total: f64 = weights.iter().sum();
    std::array::from_fn(|k| {
        let j = k + 1;
        let mean = rows
            .iter()
            .zip(&weights)
            .map(|(x, w)| x[j] * w)
            .sum::<f64>()
            / total;
        let ss: f64 = rows
            .iter()
            .zip(&weights)
            .map(|(x, w)| w * (x[j] - mean) * (x[j] - mean))
            .sum();
        fit.unscaled_covariance[(j, j)] * ss
    })
}
