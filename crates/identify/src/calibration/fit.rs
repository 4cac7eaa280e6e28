//! The centrifuge calibration of a PIGA: the eq. 18 design and its fit (eq. 17–18).

use crate::design::{Design, power};
use crate::error::{IdentifyError, Requirement, Result};
use crate::geometry::Geometry;
use crate::lstsq::{Fit, LstsqOptions, lstsq_design_unchecked};
use crate::radius::result_finite;

/// Least number of distinct rates for the six-column design of eq. 18.
pub const MIN_DISTINCT_RATES: usize = 6;

/// The terms of the eq. 18 design, in coefficient order: `1, ω, ω², ω³, a², a³`, with
/// `a = R·ω²/g` the nominal input in g. The one list of them in the workspace.
pub const CALIBRATION_TERMS: [&str; 6] = ["1", "ω", "ω²", "ω³", "a²", "a³"];

/// The power of ω in each eq. 18 column (`a² = (R/g)²·ω⁴`, `a³ = (R/g)³·ω⁶`).
const CALIBRATION_POWERS: [u32; 6] = [0, 1, 2, 3, 4, 6];

/// The factor of each eq. 18 column beyond its power of ω: `(R/g)²` and `(R/g)³` for the a²
/// and a³ columns, 1 for the others.
fn calibration_factors(geometry: Geometry) -> [f64; 6] {
    let k = geometry.radius_m / geometry.g_m_s2;
    [1.0, 1.0, 1.0, 1.0, k * k, k * k * k]
}

/// The eq. 18 design of the rates `rate_rad_s`, its entries formed in double-double: the
/// design [`identify_calibration`] fits. Row i is [`calibration_row`]`(rate_rad_s[i])`.
///
/// # Errors
/// [`IdentifyError::InvalidParameter`] when `(R/g)³` is not finite.
pub fn calibration_design(rate_rad_s: &[f64], geometry: Geometry) -> Result<Design> {
    Design::powers(rate_rad_s, &CALIBRATION_POWERS).scale_columns(&calibration_factors(geometry))
}

/// One row of the eq. 18 design at `rate_rad_s`, each entry formed in double-double and
/// rounded once: `[1, ω, ω², ω³, a², a³]` with `a = R·ω²/g` (the terms
/// [`CALIBRATION_TERMS`]). The planner's information matrices and the calibration's variance
/// inflation factors use it; the fit uses the same entries through [`calibration_design`].
///
/// ```
/// use identify::{Geometry, calibration_row};
/// let geometry = Geometry { radius_m: 2.5, g_m_s2: 9.8 };
/// let w = 3.0_f64;
/// let a = geometry.input_g(w);
/// let row = calibration_row(w, geometry);
/// assert_eq!(row[..4], [1.0, 3.0, 9.0, 27.0]);
/// assert!((row[4] / (a * a) - 1.0).abs() < 1e-15);
/// assert!((row[5] / (a * a * a) - 1.0).abs() < 1e-15);
/// ```
#[must_use]
pub fn calibration_row(rate_rad_s: f64, geometry: Geometry) -> [f64; 6] {
    let factors = calibration_factors(geometry);
    std::array::from_fn(|j| {
        power(rate_rad_s, CALIBRATION_POWERS[j])
            .mul_f64(factors[j])
            .to_f64()
    })
}

/// Result of [`identify_calibration`]: the coefficients of the eq. 18 design
/// `[1, ω, ω², ω³, a², a³]` with `a = R·ω²/g`.
///
/// From eq. 17, `λ̇ = (k0 + k1Δφ_ys) − Δφ_ys·ω − C_φ·ω³ + k1(R + Δr_xs + gC_φ)ω²/g
/// + (k2 + k1C_r·g/R²)·a² + k3·a³`. The coefficient of a² is therefore the **apparent** k2,
/// `k2 + Δk2`, and the ω and ω³ coefficients are nuisance terms. The ω column also absorbs the
/// Coriolis term `2R·ω·ω_ie·sin L/g` that eq. 14 drops.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// Working radius R and gravity g used to form a.
    pub geometry: Geometry,
    /// Number of distinct rates in the data.
    pub distinct_rates: usize,
    /// Coefficient of 1: `k0 + k1·Δφ_ys` (rad/s).
    pub bias_rad_s: f64,
    /// Coefficient of ω: `−Δφ_ys` plus the Coriolis term's `2k1R·ω_ie·sin L/g` (nuisance,
    /// dimensionless).
    pub omega_coeff: f64,
    /// Coefficient of ω²: `k1(R + Δr_xs + g·C_φ)/g` (s).
    pub omega2_coeff_s: f64,
    /// Coefficient of ω³: `−C_φ` (nuisance, s²).
    pub omega3_coeff_s2: f64,
    /// k1 implied by the ω² coefficient, `c₂·g/R` (rad/(s·g)). Its relative bias is
    /// `(Δr_xs + g·C_φ)/R`, of order 1e-6 for a balanced spindle.
    pub k1_implied_rad_s_g: f64,
    /// Standard error of the implied k1.
    pub k1_implied_sigma_rad_s_g: f64,
    /// Coefficient of a²: the apparent second-order coefficient `k2 + Δk2` (rad/(s·g²)).
    pub k2_apparent_rad_s_g2: f64,
    /// Standard error of the apparent k2.
    pub k2_apparent_sigma_rad_s_g2: f64,
    /// Coefficient of a³: k3 (rad/(s·g³)).
    pub k3_rad_s_g3: f64,
    /// Standard error of k3.
    pub k3_sigma_rad_s_g3: f64,
    /// Residuals `output − fitted`, rad/s, one per point (also for a weighted fit, whose
    /// `fit.residuals` are divided by σᵢ).
    pub residuals_rad_s: Vec<f64>,
    /// For a weighted fit ([`identify_calibration_weighted`]), the Birge ratio
    /// `√(χ²/ν)` of the residuals against the given σᵢ; `None` for an unweighted fit.
    pub birge_ratio: Option<f64>,
    /// The least-squares fit, with coefficients in the column order 1, ω, ω², ω³, a², a³, their
    /// covariance, the residuals and the condition number of the column-scaled design. For a
    /// weighted fit the covariance (and the standard errors) are those of the σᵢ taken as
    /// known, `(XᵀWX)⁻¹`, times the squared Birge ratio when it exceeds 1 (never shrunk),
    /// and the residuals are divided by σᵢ.
    pub fit: Fit,
}

/// Fits the eq. 18 calibration model to PIGA outputs measured at several centrifuge rates.
///
/// Columns `1, ω, ω², ω³, a², a³` with `a = R·ω²/g`, the nominal input in g. The paper writes
/// the last two columns as `R²ω⁴/g²` and an unscaled `ω⁶`, although it names the latter's
/// coefficient `k3R³/g³`. Using powers of a for both makes the coefficients k2 and k3
/// themselves, in rad/(s·g²) and rad/(s·g³). The raw columns are also of comparable size: at
/// 200 °/s on a 2.5 m arm, a ≈ 3.1 while ω⁶ ≈ 1.8e3. The solver scales its columns itself, so
/// its accuracy does not depend on this choice; a reader or a solver without column scaling does
/// see the better-conditioned design. The powers are formed in double-double ([`Design`]).
///
/// `rate_rad_s[i]` is the centrifuge rate and `output_rad_s[i]` the PIGA output (mean over
/// whole revolutions) at point i. Repeated rates are allowed.
///
/// # Errors
/// [`IdentifyError::DimensionMismatch`] for slices of different lengths,
/// [`IdentifyError::InvalidParameter`] for a non-positive R or g ([`Geometry::validate`]),
/// [`IdentifyError::NonFinite`] for a non-finite rate (`column: Some(1)`, the ω column) or
/// output (`column: None`),
/// [`IdentifyError::TooFewDistinctRates`] for fewer than six distinct rates, and the errors of
/// [`crate::lstsq`]. In particular, exactly six points give
/// [`IdentifyError::TooFewObservations`]: the standard errors need a residual degree of freedom.
///
/// ```
/// use approx::assert_relative_eq;
/// use identify::{Geometry, identify_calibration};
/// let geometry = Geometry { radius_m: 2.5, g_m_s2: 9.8 };
/// let rates: Vec<f64> = (1..=8).map(|i| (25.0 * f64::from(i)).to_radians()).collect();
/// let out: Vec<f64> = rates.iter().map(|&w| {
///     let a = geometry.input_g(w);
///     1e-4 + 2e-6 * w + 0.56 * a + 3e-6 * a * a + 1e-7 * a.powi(3)
/// }).collect();
/// let cal = identify_calibration(&rates, &out, geometry)?;
/// assert_relative_eq!(cal.k1_implied_rad_s_g, 0.56, max_relative = 1e-12);
/// assert_relative_eq!(cal.k2_apparent_rad_s_g2, 3e-6, max_relative = 1e-7);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn identify_calibration(
    rate_rad_s: &[f64],
    output_rad_s: &[f64],
    geometry: Geometry,
) -> Result<Calibration> {
    calibrate(rate_rad_s, output_rad_s, None, geometry)
}

/// [`identify_calibration`] by weighted least squares: row i is divided by `sigma_rad_s[i]`,
/// the standard uncertainty of the mean output at that point (e.g. the standard error
/// across revolutions of a raw output recording, or a table's σ column).
///
/// The coefficients' covariance is that of the σᵢ taken as known, `(XᵀWX)⁻¹`, enlarged by
/// the squared Birge ratio `χ²/ν` when the residuals scatter more than the σᵢ say, and never
/// shrunk when they scatter less ([`Calibration::birge_ratio`]); the same policy as
/// [`crate::fit_radius_error_weighted`].
///
/// # Errors
/// Those of [`identify_calibration`], and [`IdentifyError::DimensionMismatch`] for a σ slice
/// of another length, [`IdentifyError::InvalidParameter`] for a σᵢ that is not finite and
/// > 0 (`name: "sigma_rad_s"`).
///
/// ```
/// use identify::{Geometry, identify_calibration_weighted};
/// let geometry = Geometry { radius_m: 2.5, g_m_s2: 9.8 };
/// let rates: Vec<f64> = (1..=8).map(|i| (25.0 * f64::from(i)).to_radians()).collect();
/// let out: Vec<f64> = rates.iter().map(|&w| 0.56 * geometry.input_g(w)).collect();
/// let sigma = vec![1e-7; 8];
/// let cal = identify_calibration_weighted(&rates, &out, &sigma, geometry)?;
/// assert!(cal.birge_ratio.unwrap() < 1.0);
/// approx::assert_relative_eq!(cal.k1_implied_rad_s_g, 0.56, max_relative = 1e-12);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn identify_calibration_weighted(
    rate_rad_s: &[f64],
    output_rad_s: &[f64],
    sigma_rad_s: &[f64],
    geometry: Geometry,
) -> Result<Calibration> {
    calibrate(rate_rad_s, output_rad_s, Some(sigma_rad_s), geometry)
}

/// The eq. 18 fit, weighted by `1/σᵢ` when σ is given.
pub(super) fn calibrate(
    rate_rad_s: &[f64],
    output_rad_s: &[f64],
    sigma_rad_s: Option<&[f64]>,
    geometry: Geometry,
) -> Result<Calibration> {
    geometry.validate()?;
    if rate_rad_s.len() != output_rad_s.len() {
        return Err(IdentifyError::DimensionMismatch {
            what: "output_rad_s",
            got: output_rad_s.len(),
            expected: rate_rad_s.len(),
        });
    }
    if let Some(row) = rate_rad_s.iter().position(|w| !w.is_finite()) {
        return Err(IdentifyError::NonFinite {
            row,
            column: Some(1),
        });
    }
    let distinct_rates = count_distinct(rate_rad_s);
    if distinct_rates < MIN_DISTINCT_RATES {
        return Err(IdentifyError::TooFewDistinctRates {
            distinct: distinct_rates,
            need: MIN_DISTINCT_RATES,
        });
    }
    let k = geometry.radius_m / geometry.g_m_s2;
    if !(k * k).is_normal() || !(k * k * k).is_normal() {
        // The a² and a³ columns are scaled by (R/g)² and (R/g)³: out of range, the design
        // would hold ∞ or a column of zeros (reported as a rank deficiency).
        // (R/g)³ a normal double: R/g within 1e-102 … 1e102.
        return Err(IdentifyError::InvalidParameter {
            name: "radius_m",
            value: geometry.radius_m,
            requirement: Requirement::InRange {
                min: 1e-102 * geometry.g_m_s2,
                max: 1e102 * geometry.g_m_s2,
            },
        });
    }
    let design = calibration_design(rate_rad_s, geometry)?;
    let (fit, residuals_rad_s, birge_ratio) = match sigma_rad_s {
        None => {
            let fit = lstsq_design_unchecked(&design, output_rad_s, &LstsqOptions::default())?;
            let residuals = fit.residuals.clone();
            (fit, residuals, None)
        }
        Some(sigma) => {
            if sigma.len() != rate_rad_s.len() {
                return Err(IdentifyError::DimensionMismatch {
                    what: "sigma_rad_s",
                    got: sigma.len(),
                    expected: rate_rad_s.len(),
                });
            }
            if let Some(&bad) = sigma.iter().find(|s| !(s.is_finite() && **s > 0.0)) {
                return Err(IdentifyError::InvalidParameter {
                    name: "sigma_rad_s",
                    value: bad,
                    requirement: Requirement::Positive,
                });
            }
            let weights: Vec<f64> = sigma.iter().map(|s| 1.0 / s).collect();
            let y: Vec<f64> = output_rad_s
                .iter()
                .zip(&weights)
                .map(|(y, w)| y * w)
                .collect();
            let mut fit = lstsq_design_unchecked(
                &design.scale_rows(&weights)?,
                &y,
                &LstsqOptions::default(),
            )?;
            // The σᵢ taken as known, enlarged by the Birge ratio when it exceeds 1.
            let birge = fit.residual_sd;
            let inflation = birge.max(1.0).powi(2);
            fit.covariance = &fit.unscaled_covariance * inflation;
            fit.std_errors = (0..fit.coefficients.len())
                .map(|k| fit.covariance[(k, k)].max(0.0).sqrt())
                .collect();
            let residuals = fit
                .residuals
                .iter()
                .zip(sigma)
                .map(|(r, s)| r * s)
                .collect();
            (fit, residuals, Some(birge))
        }
    };
    let c = &fit.coefficients;
    let s = &fit.std_errors;
    let calibration = Calibration {
        geometry,
        distinct_rates,
        bias_rad_s: c[0],
        omega_coeff: c[1],
        omega2_coeff_s: c[2],
        omega3_coeff_s2: c[3],
        k1_implied_rad_s_g: c[2] / k,
        k1_implied_sigma_rad_s_g: s[2] / k,
        k2_apparent_rad_s_g2: c[4],
        k2_apparent_sigma_rad_s_g2: s[4],
        k3_rad_s_g3: c[5],
        k3_sigma_rad_s_g3: s[5],
        residuals_rad_s,
        birge_ratio,
        fit,
    };
    calibration.check_finite()?;
    Ok(calibration)
}

impl Calibration {
    /// [`IdentifyError::NonFiniteResult`] for the first coefficient or standard error that is
    /// not finite, naming it and the scalar inputs (R, g).
    fn check_finite(&self) -> Result<()> {
        let inputs = [
            ("radius_m", self.geometry.radius_m),
            ("g_m_s2", self.geometry.g_m_s2),
        ];
        for (quantity, value) in [
            ("bias_rad_s", self.bias_rad_s),
            ("omega_coeff", self.omega_coeff),
            ("omega2_coeff_s", self.omega2_coeff_s),
            ("omega3_coeff_s2", self.omega3_coeff_s2),
            ("k1_implied_rad_s_g", self.k1_implied_rad_s_g),
            ("k1_implied_sigma_rad_s_g", self.k1_implied_sigma_rad_s_g),
            ("k2_apparent_rad_s_g2", self.k2_apparent_rad_s_g2),
            (
                "k2_apparent_sigma_rad_s_g2",
                self.k2_apparent_sigma_rad_s_g2,
            ),
            ("k3_rad_s_g3", self.k3_rad_s_g3),
            ("k3_sigma_rad_s_g3", self.k3_sigma_rad_s_g3),
        ] {
            result_finite(quantity, value, &inputs)?;
        }
        if let Some(what) = self.fit.first_non_finite() {
            let value = self
                .fit
                .covariance
                .iter()
                .chain(&self.fit.residuals)
                .copied()
                .find(|v| !v.is_finite())
                .unwrap_or(f64::NAN);
            return Err(IdentifyError::NonFiniteResult {
                quantity: if what == "a residual" {
                    "residual of the eq. 18 fit"
                } else {
                    "covariance of the eq. 18 fit"
                },
                value,
                inputs: inputs.to_vec(),
            });
        }
        Ok(())
    }
}

/// Number of distinct values (exact comparison).
fn count_distinct(values: &[f64]) -> usize {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    sorted.len()
}
