//! Centrifuge calibration of a PIGA (eq. 17–18) and its compensation for the spindle's dynamic
//! radius error (eq. 19).

use crate::design::{Design, power};
use crate::error::{IdentifyError, Requirement, Result};
use crate::geometry::Geometry;
use crate::lstsq::{Fit, LstsqOptions, lstsq_design_unchecked};
use crate::radius::{CrEstimate, PseudoSecondOrder, pseudo_second_order, result_finite};

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
fn calibrate(
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
/// Those of [`identify_calibration`]; [`IdentifyError::InvalidParameter`] for a non-finite
/// C_r or k1 or a negative σ(C_r).
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
/// ([`identify_calibration_weighted`]).
///
/// # Errors
/// Those of [`identify_compensated`] and [`identify_calibration_weighted`].
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

/// Number of distinct values (exact comparison).
fn count_distinct(values: &[f64]) -> usize {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    sorted.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lstsq::lstsq_design;
    use approx::assert_relative_eq;

    const R: f64 = 2.5;
    const G: f64 = 9.8;
    const GEOMETRY: Geometry = Geometry {
        radius_m: R,
        g_m_s2: G,
    };

    fn rates(n: usize) -> Vec<f64> {
        (1..=n)
            .map(|i| (200.0 * i as f64 / n as f64).to_radians())
            .collect()
    }

    /// Output of eq. 17 with every term, for given coefficients.
    fn outputs(rates: &[f64], k: [f64; 6], noise: f64) -> Vec<f64> {
        rates
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let a = R * w * w / G;
                k[0] + k[1] * w
                    + k[2] * w * w
                    + k[3] * w.powi(3)
                    + k[4] * a * a
                    + k[5] * a.powi(3)
                    + noise * if i % 2 == 0 { 1.0 } else { -1.0 }
            })
            .collect()
    }

    #[test]
    fn recovers_every_coefficient() {
        let w = rates(9);
        let truth = [1e-4, -2e-6, 0.56 * R / G, 3e-8, 5e-6, -2e-7];
        let cal = identify_calibration(&w, &outputs(&w, truth, 0.0), GEOMETRY).unwrap();
        assert_relative_eq!(cal.bias_rad_s, truth[0], max_relative = 1e-8);
        assert_relative_eq!(cal.omega_coeff, truth[1], max_relative = 1e-7);
        assert_relative_eq!(cal.omega2_coeff_s, truth[2], max_relative = 1e-12);
        assert_relative_eq!(cal.k1_implied_rad_s_g, 0.56, max_relative = 1e-12);
        assert_relative_eq!(cal.omega3_coeff_s2, truth[3], max_relative = 1e-6);
        assert_relative_eq!(cal.k2_apparent_rad_s_g2, truth[4], max_relative = 1e-7);
        assert_relative_eq!(cal.k3_rad_s_g3, truth[5], max_relative = 1e-6);
        assert_eq!(cal.distinct_rates, 9);
        assert_eq!(cal.fit.dof, 3);
    }

    #[test]
    fn a_scaling_is_the_unscaled_fit_rescaled() {
        // The coefficient of a² is (g/R)² times that of ω⁴, and of a³ (g/R)³ times that of ω⁶.
        let w = rates(8);
        let y = outputs(&w, [0.0, 1e-6, 0.1428, 0.0, 4e-6, 1e-7], 1e-9);
        let cal = identify_calibration(&w, &y, GEOMETRY).unwrap();
        let raw = lstsq_design(
            &Design::powers(&w, &[0, 1, 2, 3, 4, 6]),
            &y,
            &LstsqOptions::default(),
        )
        .unwrap();
        assert_relative_eq!(
            cal.k2_apparent_rad_s_g2,
            raw.coefficients[4] * (G / R).powi(2),
            max_relative = 1e-9
        );
        assert_relative_eq!(
            cal.k3_rad_s_g3,
            raw.coefficients[5] * (G / R).powi(3),
            max_relative = 1e-9
        );
        assert_relative_eq!(
            cal.k2_apparent_sigma_rad_s_g2,
            raw.std_errors[4] * (G / R).powi(2),
            max_relative = 1e-9
        );
    }

    #[test]
    fn compensation_removes_delta_k2_and_propagates_sigma() {
        let (k1, k2, c_r, sigma) = (0.56, 5e-6, 1.6e-6, 0.1e-6);
        let w = rates(8);
        let mut y = outputs(&w, [0.0, 0.0, k1 * R / G, 0.0, k2, 0.0], 1e-12);
        for (y, w) in y.iter_mut().zip(&w) {
            *y += k1 * c_r * w.powi(4) / G;
        }
        let dk2 = k1 * c_r * G / (R * R);
        for source in [K1Source::Fitted, K1Source::Given { k1_rad_s_g: k1 }] {
            let comp = Compensation {
                c_r: CrEstimate {
                    c_r_m_s2: c_r,
                    c_r_sigma_m_s2: sigma,
                },
                k1: source,
            };
            let cal = identify_compensated(&w, &y, GEOMETRY, &comp).unwrap();
            // Within a few of the fit's own standard errors (the noise is ±1e-12 rad/s).
            let fit_sigma = cal.compensated.k2_apparent_sigma_rad_s_g2;
            assert!((cal.uncompensated.k2_apparent_rad_s_g2 - (k2 + dk2)).abs() < 5.0 * fit_sigma);
            assert!((cal.k2_rad_s_g2 - k2).abs() < 5.0 * fit_sigma);
            assert_relative_eq!(cal.delta_k2.delta_k2_rad_s_g2, dk2, max_relative = 1e-6);
            assert_relative_eq!(
                cal.k2_sigma_from_c_r_rad_s_g2,
                k1 * G / (R * R) * sigma,
                max_relative = 1e-6
            );
            // The fit alone is far more precise than C_r here: σ(C_r) dominates.
            assert!(fit_sigma < 0.01 * cal.k2_sigma_from_c_r_rad_s_g2);
            assert_relative_eq!(
                cal.k2_sigma_rad_s_g2,
                cal.k2_sigma_from_c_r_rad_s_g2,
                max_relative = 1e-3
            );
            // Residuals are unchanged by the compensation.
            assert_relative_eq!(
                cal.compensated.fit.residual_sd,
                cal.uncompensated.fit.residual_sd,
                max_relative = 1e-6
            );
        }
    }

    /// Monte Carlo check of the reported σ of the compensated k2: the empirical spread over
    /// repeated noisy experiments must match it. A sign error in the cross term
    /// `2·d·cov(c2, c4)`, or a missing term, shifts the reported σ far outside the tolerance.
    #[test]
    fn compensated_k2_sigma_matches_monte_carlo() {
        use rand::SeedableRng;
        use rand::rngs::StdRng;
        use rand_distr::{Distribution, Normal};

        const DRAWS: usize = 2000;
        // C_r is exaggerated (a real one is ~1e-6 m·s²) so that d = −C_r·g²/R³ = −1 and the
        // k1 terms are as large as the fit's own: with these 8 rates corr(c2, c4) = +0.98, and
        // the fitted-k1 fit variance is var(c4) + var(c2) − 2·cov(c2, c4) ≈ 0.18·var(c4).
        // σ(C_r) contributes about as much as the fit. Measured: empirical sd 4.39e-8, reported
        // 4.24e-8 (fitted k1); 7.97e-8 and 8.19e-8 (given k1). With the cross term's sign
        // flipped the reported σ is 1.25e-7 (2.9×), with it dropped 9.4e-8 (2.1×).
        let c_r = R.powi(3) / (G * G);
        let (k1, k2, c_r_sigma, noise_sd) = (0.56, 5e-6, 3e-8, 1e-9);
        let w = rates(8);
        let clean: Vec<f64> = outputs(&w, [1e-4, 2e-6, k1 * R / G, 0.0, k2, 1e-7], 0.0)
            .iter()
            .zip(&w)
            .map(|(y, w)| y + k1 * c_r * w.powi(4) / G)
            .collect();
        let noise = Normal::new(0.0, noise_sd).unwrap();
        let c_r_draw = Normal::new(c_r, c_r_sigma).unwrap();
        for (seed, source) in [
            (1, K1Source::Fitted),
            (2, K1Source::Given { k1_rad_s_g: k1 }),
        ] {
            let mut rng = StdRng::seed_from_u64(seed);
            let (mut sum, mut sum_sq, mut reported_var) = (0.0, 0.0, 0.0);
            for _ in 0..DRAWS {
                let y: Vec<f64> = clean.iter().map(|y| y + noise.sample(&mut rng)).collect();
                let comp = Compensation {
                    c_r: CrEstimate {
                        c_r_m_s2: c_r_draw.sample(&mut rng),
                        c_r_sigma_m_s2: c_r_sigma,
                    },
                    k1: source,
                };
                let cal = identify_compensated(&w, &y, GEOMETRY, &comp).unwrap();
                let dev = cal.k2_rad_s_g2 - k2;
                sum += dev;
                sum_sq += dev * dev;
                reported_var += cal.k2_sigma_rad_s_g2.powi(2);
            }
            let n = DRAWS as f64;
            let mean = sum / n;
            let empirical_sd = ((sum_sq - n * mean * mean) / (n - 1.0)).sqrt();
            // Each draw's σ scales with its own residual variance s² (2 degrees of freedom), whose
            // mean is the true noise variance: compare with the RMS of the reported σ.
            let reported_sd = (reported_var / n).sqrt();
            assert_relative_eq!(empirical_sd, reported_sd, max_relative = 0.1);
            // Unbiased: the mean is within 4 standard errors of the truth.
            assert!(
                mean.abs() < 4.0 * empirical_sd / n.sqrt(),
                "{source:?}: mean {mean:e}"
            );
        }
    }

    #[test]
    fn a_tiny_radius_is_a_named_non_finite_result_not_a_nan_sigma() {
        // R = 1e-80 m: a = R·ω²/g ≈ 1e-80, so the a³ coefficient's variance ≈ 1e480 overflows.
        // Before: Ok with σ(k2) = NaN (`cargo xtask identify --radius-m 1e-80`).
        let w = rates(8);
        let y = outputs(&w, [1e-5, 1e-6, 0.1428, 0.0, 4e-6, 1e-7], 1e-7);
        let tiny = Geometry {
            radius_m: 1e-80,
            g_m_s2: G,
        };
        let err = identify_calibration(&w, &y, tiny).unwrap_err();
        let IdentifyError::NonFiniteResult {
            quantity, inputs, ..
        } = &err
        else {
            panic!("{err:?}");
        };
        assert!(
            quantity.contains("sigma") || quantity.contains("covariance"),
            "{quantity}"
        );
        assert!(inputs.contains(&("radius_m", 1e-80)));
        assert!(err.to_string().contains("radius_m = 1e-80"), "{err}");
        let comp = Compensation {
            c_r: CrEstimate {
                c_r_m_s2: 1e-6,
                c_r_sigma_m_s2: 1e-8,
            },
            k1: K1Source::Fitted,
        };
        assert!(matches!(
            identify_compensated(&w, &y, tiny, &comp),
            Err(IdentifyError::NonFiniteResult { .. })
        ));
        // Further out, (R/g)³ itself leaves the range: the radius is named (before: the
        // internal "factors = inf", or a rank deficiency for a column of zeros).
        for radius_m in [1e-120, 1e120] {
            let err = identify_calibration(
                &w,
                &y,
                Geometry {
                    radius_m,
                    g_m_s2: G,
                },
            )
            .unwrap_err();
            assert!(
                matches!(
                    err,
                    IdentifyError::InvalidParameter {
                        name: "radius_m",
                        ..
                    }
                ),
                "{err:?}"
            );
            assert!(!err.to_string().contains("factors"), "{err}");
        }
    }

    #[test]
    fn typed_errors() {
        let w = rates(5);
        let y = outputs(&w, [0.0, 0.0, 0.1, 0.0, 0.0, 0.0], 0.0);
        assert_eq!(
            identify_calibration(&w, &y, GEOMETRY),
            Err(IdentifyError::TooFewDistinctRates {
                distinct: 5,
                need: 6
            })
        );
        // Ten points but only five distinct rates.
        let w2: Vec<f64> = w.iter().chain(&w).copied().collect();
        let y2: Vec<f64> = y.iter().chain(&y).copied().collect();
        assert_eq!(
            identify_calibration(&w2, &y2, GEOMETRY),
            Err(IdentifyError::TooFewDistinctRates {
                distinct: 5,
                need: 6
            })
        );
        let w = rates(6);
        let y = outputs(&w, [0.0, 0.0, 0.1, 0.0, 0.0, 0.0], 0.0);
        assert_eq!(
            identify_calibration(&w, &y, GEOMETRY),
            Err(IdentifyError::TooFewObservations {
                observations: 6,
                unknowns: 6
            })
        );
        assert!(matches!(
            identify_calibration(
                &w,
                &y,
                Geometry {
                    radius_m: -R,
                    ..GEOMETRY
                }
            ),
            Err(IdentifyError::InvalidParameter {
                name: "radius_m",
                ..
            })
        ));
        assert!(matches!(
            identify_calibration(&w, &y[..5], GEOMETRY),
            Err(IdentifyError::DimensionMismatch { .. })
        ));
        let mut bad = w.clone();
        bad[2] = f64::NAN;
        assert_eq!(
            identify_calibration(&bad, &y, GEOMETRY),
            Err(IdentifyError::NonFinite {
                row: 2,
                column: Some(1)
            })
        );
        let comp = Compensation {
            c_r: CrEstimate {
                c_r_m_s2: f64::NAN,
                c_r_sigma_m_s2: 0.0,
            },
            k1: K1Source::Fitted,
        };
        assert!(matches!(
            identify_compensated(&w, &y, GEOMETRY, &comp),
            Err(IdentifyError::InvalidParameter {
                name: "c_r_m_s2",
                ..
            })
        ));
    }

    #[test]
    fn weighted_fit_with_equal_sigmas_has_the_ordinary_coefficients() {
        let w = rates(9);
        let y = outputs(&w, [1e-4, -2e-6, 0.56 * R / G, 3e-8, 5e-6, -2e-7], 1e-7);
        let plain = identify_calibration(&w, &y, GEOMETRY).unwrap();
        // σ far above the scatter: Birge ratio < 1, the covariance is (XᵀWX)⁻¹ unshrunk.
        let weighted = identify_calibration_weighted(&w, &y, &[1e-5; 9], GEOMETRY).unwrap();
        let birge = weighted.birge_ratio.unwrap();
        assert!(birge < 0.1, "{birge}");
        for k in 0..6 {
            assert_relative_eq!(
                weighted.fit.coefficients[k],
                plain.fit.coefficients[k],
                max_relative = 1e-9,
                epsilon = 1e-20
            );
            // Unweighted σ scales with the residual SD; the weighted one with the given σ.
            assert_relative_eq!(
                weighted.fit.std_errors[k] * plain.fit.residual_sd,
                plain.fit.std_errors[k] * 1e-5,
                max_relative = 1e-9
            );
        }
        for (a, b) in weighted.residuals_rad_s.iter().zip(&plain.residuals_rad_s) {
            assert_relative_eq!(*a, *b, max_relative = 1e-6, epsilon = 1e-15);
        }
        assert_eq!(plain.birge_ratio, None);
        // σ far below the scatter: the covariance grows by the Birge ratio squared, which
        // makes it the ordinary (residual-scaled) one.
        let tight = identify_calibration_weighted(&w, &y, &[1e-10; 9], GEOMETRY).unwrap();
        assert!(tight.birge_ratio.unwrap() > 1.0);
        for k in 0..6 {
            assert_relative_eq!(
                tight.fit.std_errors[k],
                plain.fit.std_errors[k],
                max_relative = 1e-9
            );
        }
    }

    #[test]
    fn a_point_with_a_large_sigma_hardly_counts() {
        let w = rates(10);
        let mut y = outputs(&w, [1e-4, -2e-6, 0.56 * R / G, 3e-8, 5e-6, -2e-7], 1e-9);
        let mut sigma = vec![1e-9; 10];
        // A disturbed point declared as such.
        y[4] += 1e-4;
        sigma[4] = 1e-2;
        let weighted = identify_calibration_weighted(&w, &y, &sigma, GEOMETRY).unwrap();
        let plain = identify_calibration(&w, &y, GEOMETRY).unwrap();
        // The weighted fit is the fit of the other nine points.
        let (w9, y9): (Vec<f64>, Vec<f64>) = w
            .iter()
            .zip(&y)
            .enumerate()
            .filter(|(i, _)| *i != 4)
            .map(|(_, (a, b))| (*a, *b))
            .unzip();
        let without = identify_calibration(&w9, &y9, GEOMETRY).unwrap();
        let from_without =
            |c: &Calibration| (c.k2_apparent_rad_s_g2 - without.k2_apparent_rad_s_g2).abs();
        assert!(
            from_without(&weighted) < 1e-12,
            "{}",
            from_without(&weighted)
        );
        assert!(from_without(&plain) > 1e-6, "{}", from_without(&plain));
    }

    #[test]
    fn a_sigma_that_is_not_positive_is_refused() {
        let w = rates(8);
        let y = outputs(&w, [0.0, 0.0, 0.1, 0.0, 1e-6, 0.0], 1e-9);
        for bad in [0.0, -1e-9, f64::NAN, f64::INFINITY] {
            let mut sigma = vec![1e-9; 8];
            sigma[3] = bad;
            let err = identify_calibration_weighted(&w, &y, &sigma, GEOMETRY).unwrap_err();
            assert!(
                matches!(
                    err,
                    IdentifyError::InvalidParameter {
                        name: "sigma_rad_s",
                        ..
                    }
                ),
                "{err:?}"
            );
        }
        let err = identify_calibration_weighted(&w, &y, &[1e-9; 7], GEOMETRY).unwrap_err();
        assert!(matches!(err, IdentifyError::DimensionMismatch { .. }));
    }
}
