//! The one calibration entry (eq. 17–19): a PIGA's points checked, fitted by eq. 18 with the
//! Paule–Mandel weighting, with and without the compensation of eq. 19, and the warnings
//! about the fit. The study (`pipeline`), `centrifuge-cal identify`, the planner and Python
//! (through the study) call it, so the same points give the same numbers and the same words
//! everywhere.

use identify::{
    Calibration, CompensatedCalibration, Compensation, CrEstimate, Geometry, IdentifyError,
    K1Source,
};
use uncertainty::Dof;
use units::{Compact, Requirement};

use crate::vif::{CoefficientInflation, INFLATION_LIMIT, coefficient_inflation};

/// Smallest standard uncertainty of a point the fit takes, rad/s: its weight `1/σ²` must be a
/// finite double.
pub const SIGMA_MIN_RAD_S: f64 = 1e-150;

/// Largest standard uncertainty of a point the fit takes, rad/s: `σ²` must be a finite
/// double (the covariance of a fit holds it). A σ this large says the point carries no
/// information: leave the point out instead.
pub const SIGMA_MAX_RAD_S: f64 = 1e150;

/// A PIGA's points as a calibration takes them: one per rate point (a table row or a raw
/// recording reduced over whole revolutions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Points<'a> {
    /// Spindle rates, rad/s: finite and > 0.
    pub rates_rad_s: &'a [f64],
    /// Mean PIGA outputs, rad/s: finite.
    pub outputs_rad_s: &'a [f64],
    /// Each output's standard uncertainty, rad/s (the fit is then weighted by `1/σᵢ`),
    /// within [`SIGMA_MIN_RAD_S`] … [`SIGMA_MAX_RAD_S`]; `None`: unweighted.
    pub sigma_rad_s: Option<&'a [f64]>,
}

/// Which value of a point is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointValue {
    /// The rate.
    Rate,
    /// The mean output.
    Output,
    /// The output's standard uncertainty σ.
    Sigma,
}

impl std::fmt::Display for PointValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Rate => "rate",
            Self::Output => "output",
            Self::Sigma => "standard uncertainty σ",
        })
    }
}

/// A value of a point the calibration refuses: its row (0-based, in the points' order), which
/// value, the value and what it must be.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("point {}: {what} = {} {requirement}", row + 1, Compact(*value))]
pub struct BadPoint {
    /// Row of the point, 0-based.
    pub row: usize,
    /// Which of its values.
    pub what: PointValue,
    /// The value (rad/s).
    pub value: f64,
    /// What it must be.
    pub requirement: Requirement,
}

/// Why a calibration was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CalibrationError {
    /// Points whose values the fit cannot take, every one of them.
    #[error("{} point value(s) refused: {}", bad.len(), list(bad))]
    Points {
        /// The refused values, in row order.
        bad: Vec<BadPoint>,
    },
    /// The σ slice has another length than the rates.
    #[error("{got} standard uncertainties for {expected} points")]
    SigmaLength {
        /// σ values given.
        got: usize,
        /// Points.
        expected: usize,
    },
    /// The fit itself failed (too few rates, a rank-deficient design, a non-finite result).
    #[error(transparent)]
    Fit(#[from] IdentifyError),
}

fn list(bad: &[BadPoint]) -> String {
    bad.iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

/// Checks the points as every calibration checks them: each rate finite and > 0, each output
/// finite, each σ within [`SIGMA_MIN_RAD_S`] … [`SIGMA_MAX_RAD_S`]; every refused value at
/// once, in row order.
///
/// # Errors
/// [`CalibrationError::Points`] listing the refused values; [`CalibrationError::SigmaLength`];
/// [`IdentifyError::DimensionMismatch`] (as [`CalibrationError::Fit`]) for outputs of
/// another length than the rates.
pub fn check_points(points: &Points<'_>) -> Result<(), CalibrationError> {
    let n = points.rates_rad_s.len();
    if points.outputs_rad_s.len() != n {
        return Err(IdentifyError::DimensionMismatch {
            what: "output_rad_s",
            got: points.outputs_rad_s.len(),
            expected: n,
        }
        .into());
    }
    if let Some(s) = points.sigma_rad_s
        && s.len() != n
    {
        return Err(CalibrationError::SigmaLength {
            got: s.len(),
            expected: n,
        });
    }
    let sigma_range = Requirement::InRange {
        min: SIGMA_MIN_RAD_S,
        max: SIGMA_MAX_RAD_S,
    };
    let mut bad = Vec::new();
    for row in 0..n {
        let mut check = |what, value: f64, requirement: Requirement| {
            if !requirement.holds(value) {
                bad.push(BadPoint {
                    row,
                    what,
                    value,
                    requirement,
                });
            }
        };
        check(
            PointValue::Rate,
            points.rates_rad_s[row],
            Requirement::Positive,
        );
        check(
            PointValue::Output,
            points.outputs_rad_s[row],
            Requirement::Finite,
        );
        if let Some(s) = points.sigma_rad_s {
            check(PointValue::Sigma, s[row], sigma_range);
        }
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(CalibrationError::Points { bad })
    }
}

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
    /// The Birge ratio `√(χ²/ν)` of the weighted fit with the points' own σ (dimensionless).
    pub birge_ratio: Option<f64>,
}

/// What the calibration says of its fit (the words are the study's and `identify`'s alike).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum CalibrationWarning {
    /// The weighted fit's residuals exceed the points' σ: the Birge ratio is above
    /// [`crate::lack_of_fit_limit`].
    LackOfFit {
        /// The Birge ratio `√(χ²/ν)` with the points' own σ.
        birge_ratio: f64,
        /// Residual degrees of freedom.
        dof: usize,
    },
    /// The points scatter more than their σ say and no common τ brings χ²/ν to 1.
    TauNotFound,
    /// The rates make u(k0…k3) more than [`INFLATION_LIMIT`] times an evenly spread design's.
    RatesBunched {
        /// The inflation factors.
        inflation: CoefficientInflation,
        /// The number of points.
        points: usize,
        /// The lowest and top rates, deg/s.
        range_deg_s: (f64, f64),
    },
}

impl CalibrationWarning {
    /// The study's code for the warning (`results.json`).
    #[must_use]
    pub const fn code(&self) -> &'static str {
        match self {
            Self::LackOfFit { .. } => "calibration_lack_of_fit",
            Self::TauNotFound => "calibration_tau_not_found",
            Self::RatesBunched { .. } => "calibration_rates_bunched",
        }
    }
}

/// A factor as a person writes it: 2.7, 36, 7139.
fn times(f: f64) -> String {
    if f < 10.0 {
        format!("{f:.1}")
    } else {
        format!("{f:.0}")
    }
}

impl std::fmt::Display for CalibrationWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::LackOfFit { birge_ratio, dof } => write!(
                f,
                "the eq. 18 residuals are {birge_ratio:.1}× the points' standard uncertainties \
                 (Birge ratio √(χ²/ν), {dof} degrees of freedom): the points scatter more than \
                 their σ say — run-to-run variation the within-run σ do not hold, an unmodelled \
                 term, or a rate error. A variation τ common to every point (Paule–Mandel) is \
                 added to each σ, which widens the coefficients' σ"
            ),
            Self::TauNotFound => f.write_str(
                "the points scatter more than their σ say (Birge ratio above 1), and no variation \
                 τ common to every point brings χ²/ν to 1: the fit keeps the points' σ as weights \
                 and its covariance is scaled by the Birge ratio",
            ),
            Self::RatesBunched {
                inflation,
                points,
                range_deg_s: (lo, hi),
            } => {
                let over: Vec<String> = CoefficientInflation::NAMES
                    .iter()
                    .zip(&inflation.versus_spread)
                    .filter(|(_, f)| **f > INFLATION_LIMIT)
                    .map(|(n, f)| format!("u({n}) is {} times", times(*f)))
                    .collect();
                write!(
                    f,
                    "the rates cannot separate the coefficients well: {} what the same {points} \
                     rates spread evenly from {} to {} deg/s would give (limit {INFLATION_LIMIT}). \
                     Over {}–{} deg/s the a² and a³ terms are hard to tell apart from the ω and ω³ \
                     nuisance terms and from each other; spread the rates over 10–100 % of the top \
                     rate",
                    over.join(", "),
                    times(inflation.reference_rad_s.0.to_degrees()),
                    times(inflation.reference_rad_s.1.to_degrees()),
                    times(*lo),
                    times(*hi),
                )
            }
        }
    }
}

/// k0…k3, the apparent k2 and Δk2 of a compensated calibration ([`crate::output`]'s order)
/// through the measurement model ([`crate::CalibrationModel`]) by the GUM, with no Type B
/// input (R, g, the rate scale, the lever heights and the probe gain exact, a given k1
/// exact): the fit's coefficients as one Type A group with [`Weighting::group_dof`], and C_r
/// with `c_r_dof` degrees of freedom (`None`: infinitely many). The study evaluates the same
/// model with its Type B inputs; with none it gives these numbers, so `centrifuge-cal
/// identify` reports the study's k2 and u(k2) — the u by the same numerical sensitivities.
///
/// # Errors
/// Those of [`crate::measurement_inputs`] and [`uncertainty::gum`].
pub fn without_type_b(
    calibrated: &Calibrated<CompensatedCalibration>,
    c_r_dof: Option<usize>,
) -> Result<uncertainty::GumResult, uncertainty::UncertaintyError> {
    use crate::{CalibrationModel, CrInput, K1Input, K1Mode, Nominal, TypeB};
    let c = &calibrated.calibration;
    let geometry = c.uncompensated.geometry;
    // lever heights enter as their ratio to the nominal one, exactly 1 here: any pair will do
    let nominal = Nominal {
        radius_m: geometry.radius_m,
        g_m_s2: geometry.g_m_s2,
        pivot_to_probe_mm: 1.0,
        probe_to_piga_mm: 1.0,
    };
    let (mode, k1) = match c.compensation.k1 {
        K1Source::Fitted => (K1Mode::Fitted, K1Input::Fitted),
        K1Source::Given { k1_rad_s_g } => (
            K1Mode::Given,
            K1Input::Given {
                k1_rad_s_g,
                u_rad_s_g: 0.0,
            },
        ),
    };
    let sigma = c.compensation.c_r.c_r_sigma_m_s2;
    let c_r = CrInput {
        c_r_m_s2: c.compensation.c_r.c_r_m_s2,
        sigma: (sigma > 0.0).then(|| (sigma, c_r_dof.unwrap_or(usize::MAX))),
    };
    let (_, inputs) = crate::measurement_inputs(
        &nominal,
        &TypeB::default(),
        c_r,
        k1,
        &c.uncompensated.fit,
        calibrated.weighting.group_dof,
    )?;
    uncertainty::gum(
        &CalibrationModel::new(nominal, mode),
        &inputs,
        &uncertainty::GumOptions::default(),
    )
}

/// The budget line of a fit's coefficients as one Type A group, in words: `fit` names the fit
/// (`the eq. 18 fit`), `group_dof` says where their u comes from — the points' stated σ
/// (infinite degrees of freedom) or the fit's residuals. The one-mounting and the
/// two-orientation budgets both use it.
#[must_use]
pub fn noise_budget_line(fit: &str, group_dof: Dof) -> String {
    match group_dof {
        Dof::Infinite => format!("PIGA mean outputs: {fit} (noise, from the points' stated σ)"),
        Dof::Finite(_) => format!("PIGA mean outputs: {fit} (noise, from its residuals)"),
    }
}

/// The PIGA calibration of a set of points: the eq. 18 fit (`calibration`: [`Calibration`],
/// or [`CompensatedCalibration`] with eq. 19's compensation), how its points were weighted,
/// the residual standard deviation in rad/s, what the rates cost the coefficients, and the
/// warnings.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibrated<C> {
    /// The fit (as measured, or as measured and compensated).
    pub calibration: C,
    /// How its points were weighted.
    pub weighting: Weighting,
    /// The residuals' standard deviation `√(Σrᵢ²/ν)` in rad/s, the residuals `rᵢ` being
    /// `output − fitted` (unweighted, also for a weighted fit).
    pub residual_sd_rad_s: f64,
    /// How much wider u(k0…k3) are than an evenly spread design's (`None`: not computable).
    pub inflation: Option<CoefficientInflation>,
    /// What the calibration says of its fit.
    pub warnings: Vec<CalibrationWarning>,
}

/// The fit as measured, of a calibration with or without compensation.
pub trait AsMeasured {
    /// The eq. 18 fit as measured (uncompensated).
    fn as_measured(&self) -> &Calibration;
}

impl AsMeasured for Calibration {
    fn as_measured(&self) -> &Calibration {
        self
    }
}

impl AsMeasured for CompensatedCalibration {
    fn as_measured(&self) -> &Calibration {
        &self.uncompensated
    }
}

/// The compensation of a C_r (m·s², with its standard uncertainty) with k1 fitted or given,
/// for [`calibrate_compensated`].
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

/// Calibrates a PIGA from its points (eq. 17–18): [`check_points`], then the eq. 18 fit
/// weighted by `1/σᵢ` when σ is given. Points that scatter more than their σ say (χ²/ν > 1)
/// miss a variation common to every point (from run to run): its variance τ² is the one that
/// makes χ²/ν = 1 with σᵢ² + τ² (the Paule–Mandel estimate, found by bisection), and the fit
/// is weighted by those. When no such τ is found the fit keeps the points' σ and its
/// covariance is scaled by the Birge ratio ([`Weighting::tau_not_found`]).
///
/// ```
/// use calibration::{Points, calibrate};
/// use identify::Geometry;
/// let geometry = Geometry { radius_m: 2.5, g_m_s2: 9.8 };
/// let rates: Vec<f64> = (1..=10).map(|i| (20.0 * f64::from(i)).to_radians()).collect();
/// let outputs: Vec<f64> = rates
///     .iter()
///     .enumerate()
///     .map(|(i, &w)| {
///         let a = geometry.input_g(w);
///         1e-5 + 0.56 * a + 5e-7 * a * a + if i % 2 == 0 { 3e-9 } else { -3e-9 }
///     })
///     .collect();
/// let sigma = vec![1e-9; 10];
/// let points = Points { rates_rad_s: &rates, outputs_rad_s: &outputs, sigma_rad_s: Some(&sigma) };
/// let c = calibrate(&points, geometry)?;
/// // The points scatter 3× their σ: a common τ is added, and the study's warning is given.
/// assert!(c.weighting.excess_u_rad_s.is_some());
/// assert_eq!(c.warnings[0].code(), "calibration_lack_of_fit");
/// # Ok::<(), calibration::CalibrationError>(())
/// ```
///
/// # Errors
/// Those of [`check_points`], and the fit's ([`identify::identify_calibration`]).
pub fn calibrate(
    points: &Points<'_>,
    geometry: Geometry,
) -> Result<Calibrated<Calibration>, CalibrationError> {
    calibrate_with(points, geometry, |sigma| match sigma {
        None => identify::identify_calibration(points.rates_rad_s, points.outputs_rad_s, geometry),
        Some(s) => identify::identify_calibration_weighted(
            points.rates_rad_s,
            points.outputs_rad_s,
            s,
            geometry,
        ),
    })
}

/// [`calibrate`] with the compensation of eq. 19 (`compensation`: C_r with its standard
/// uncertainty, k1 fitted or given): the same fit and weighting, the same warnings.
///
/// # Errors
/// Those of [`calibrate`] and [`identify::identify_compensated`].
pub fn calibrate_compensated(
    points: &Points<'_>,
    geometry: Geometry,
    compensation: &Compensation,
) -> Result<Calibrated<CompensatedCalibration>, CalibrationError> {
    calibrate_with(points, geometry, |sigma| match sigma {
        None => identify::identify_compensated(
            points.rates_rad_s,
            points.outputs_rad_s,
            geometry,
            compensation,
        ),
        Some(s) => identify::identify_compensated_weighted(
            points.rates_rad_s,
            points.outputs_rad_s,
            s,
            geometry,
            compensation,
        ),
    })
}

/// The weighting policy of every calibration, once: the fit `fit_with` (given the σ to weight
/// by, `None` unweighted) weighted by the points' σ; when its Birge ratio (`birge`) exceeds 1,
/// the Paule–Mandel τ common to every point that brings χ²/ν to 1 with σᵢ² + τ² (found by
/// bisection from the largest residual, `residuals` in the output's unit), or, when none is
/// found, the points' σ kept (the fit's covariance scaled by the Birge ratio); and the
/// coefficients' degrees of freedom that follow ([`Weighting::group_dof`]). The eq. 18
/// calibration and the joint fit over several mountings (`crate::fit_mountings`) both use
/// it, so the same points get the same weights and ν everywhere. The search for τ reads only
/// each trial fit's Birge ratio: it fits with `search_with`, which may skip what the ratio
/// does not need (the joint fit's covariance refinement) but must give the same residuals as
/// `fit_with`.
///
/// # Errors
/// The fit's own.
pub(crate) fn weigh<T, E>(
    sigma_rad_s: Option<&[f64]>,
    fit_with: impl Fn(Option<&[f64]>) -> Result<T, E>,
    search_with: impl Fn(Option<&[f64]>) -> Result<T, E>,
    birge: impl Fn(&T) -> Option<f64>,
    residuals: impl Fn(&T) -> Vec<f64>,
    dof: impl Fn(&T) -> usize,
) -> Result<(T, Weighting), E> {
    let mut cal = fit_with(sigma_rad_s)?;
    let first_birge = birge(&cal);
    let mut excess_u_rad_s = None;
    let mut tau_not_found = false;
    let mut sigma_used = sigma_rad_s.map(<[f64]>::to_vec);
    if let (Some(sigma), Some(b)) = (sigma_rad_s, first_birge)
        && b > 1.0
    {
        let combined =
            |tau: f64| -> Vec<f64> { sigma.iter().map(|s| s.hypot(tau)).collect::<Vec<_>>() };
        let birge_at = |tau: f64| {
            search_with(Some(&combined(tau)))
                .ok()
                .and_then(|c| birge(&c))
        };
        // χ²/ν falls towards 0 as τ grows: double τ from the largest residual until it is
        // below 1 (with few degrees of freedom the largest residual may not be enough).
        let mut low = 0.0;
        let mut high = residuals(&cal)
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
    let noise_dof = dof(&cal);
    // The group's degrees of freedom: the σᵢ taken as known (a weighted fit whose residuals
    // stay within them, its covariance (XᵀWX)⁻¹ not scaled by them) have as many as their
    // own estimates, many; a covariance scaled by the residuals (unweighted, or with τ
    // estimated from them) has the fit's n − p.
    let group_dof = match (first_birge, excess_u_rad_s, tau_not_found) {
        (Some(b), None, false) if b <= 1.0 => Dof::Infinite,
        _ => Dof::Finite(noise_dof as f64),
    };
    Ok((
        cal,
        Weighting {
            noise_dof,
            group_dof,
            excess_u_rad_s,
            tau_not_found,
            sigma_used,
            birge_ratio: first_birge,
        },
    ))
}

/// The calibration with the fit `fit_with` (given the σ to weight by).
fn calibrate_with<C: AsMeasured>(
    points: &Points<'_>,
    geometry: Geometry,
    fit_with: impl Fn(Option<&[f64]>) -> Result<C, IdentifyError>,
) -> Result<Calibrated<C>, CalibrationError> {
    check_points(points)?;
    let (cal, weighting) = weigh(
        points.sigma_rad_s,
        &fit_with,
        &fit_with,
        |c| c.as_measured().birge_ratio,
        |c| c.as_measured().residuals_rad_s.clone(),
        |c| c.as_measured().fit.dof,
    )?;
    let measured = cal.as_measured();
    let noise_dof = weighting.noise_dof;
    let first_birge = weighting.birge_ratio;
    let tau_not_found = weighting.tau_not_found;
    let sigma_used = weighting.sigma_used.clone();
    let ss: f64 = measured.residuals_rad_s.iter().map(|r| r * r).sum();
    #[allow(clippy::cast_precision_loss)]
    let residual_sd_rad_s = (ss / noise_dof.max(1) as f64).sqrt();
    // a design the fit accepted gives these too; should one not, the results say so by
    // leaving them out
    let inflation = coefficient_inflation(points.rates_rad_s, sigma_used.as_deref(), geometry).ok();
    let mut warnings = Vec::new();
    if let Some(i) = inflation.as_ref().filter(|i| i.degraded()) {
        let (lo, hi) = points
            .rates_rad_s
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &r| {
                (a.min(r), b.max(r))
            });
        warnings.push(CalibrationWarning::RatesBunched {
            inflation: *i,
            points: points.rates_rad_s.len(),
            range_deg_s: (lo.to_degrees(), hi.to_degrees()),
        });
    }
    if tau_not_found {
        warnings.push(CalibrationWarning::TauNotFound);
    }
    if let Some(b) = first_birge
        && noise_dof > 0
        && b > crate::lack_of_fit_limit(noise_dof)
    {
        warnings.push(CalibrationWarning::LackOfFit {
            birge_ratio: b,
            dof: noise_dof,
        });
    }
    Ok(Calibrated {
        calibration: cal,
        weighting,
        residual_sd_rad_s,
        inflation,
        warnings,
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
        let p = Points {
            rates_rad_s: &rates,
            outputs_rad_s: &outputs,
            sigma_rad_s: Some(&sigma),
        };
        let f = calibrate_compensated(&p, geometry, &c).unwrap();
        let tau = f.weighting.excess_u_rad_s.expect("scatter 10× σ needs a τ");
        assert!(f.weighting.birge_ratio.unwrap() > 5.0);
        let used = f.weighting.sigma_used.as_ref().unwrap();
        let again =
            identify::identify_calibration_weighted(&rates, &outputs, used, geometry).unwrap();
        assert!((again.birge_ratio.unwrap() - 1.0).abs() < 1e-9, "{tau}");
        assert_eq!(f.weighting.group_dof, Dof::Finite(6.0));
        assert_eq!(
            f.warnings
                .iter()
                .map(CalibrationWarning::code)
                .collect::<Vec<_>>(),
            ["calibration_lack_of_fit"]
        );
        // Without the compensation: the same fit as measured, the same weighting and words.
        let plain = calibrate(&p, geometry).unwrap();
        assert_eq!(plain.calibration, f.calibration.uncompensated);
        assert_eq!(plain.weighting, f.weighting);
        assert_eq!(plain.warnings, f.warnings);
    }

    #[test]
    fn points_within_their_sigma_are_known_weights() {
        let (rates, outputs, geometry) = points(1e-9);
        let sigma = vec![1e-8; rates.len()];
        let c = compensation(1e-6, 1e-8, Some(0.56));
        let mut p = Points {
            rates_rad_s: &rates,
            outputs_rad_s: &outputs,
            sigma_rad_s: Some(&sigma),
        };
        let f = calibrate_compensated(&p, geometry, &c).unwrap();
        assert_eq!(f.weighting.excess_u_rad_s, None);
        assert!(!f.weighting.tau_not_found);
        assert_eq!(f.weighting.group_dof, Dof::Infinite);
        assert!(f.warnings.is_empty());
        p.sigma_rad_s = None;
        let unweighted = calibrate_compensated(&p, geometry, &c).unwrap();
        assert_eq!(unweighted.weighting.group_dof, Dof::Finite(6.0));
        assert_eq!(unweighted.weighting.sigma_used, None);
        // Unweighted, the residual SD in rad/s is the fit's own.
        assert!(
            (unweighted.residual_sd_rad_s / unweighted.calibration.uncompensated.fit.residual_sd
                - 1.0)
                .abs()
                < 1e-12
        );
    }

    #[test]
    fn a_rate_of_zero_and_an_absurd_sigma_are_refused_all_at_once() {
        let (mut rates, mut outputs, geometry) = points(1e-9);
        let mut sigma = vec![1e-8; rates.len()];
        rates[2] = 0.0;
        outputs[4] = f64::NAN;
        sigma[7] = 1e300;
        sigma[8] = 0.0;
        let p = Points {
            rates_rad_s: &rates,
            outputs_rad_s: &outputs,
            sigma_rad_s: Some(&sigma),
        };
        let err = calibrate(&p, geometry).unwrap_err();
        let CalibrationError::Points { bad } = &err else {
            panic!("{err:?}");
        };
        let found: Vec<(usize, PointValue)> = bad.iter().map(|b| (b.row, b.what)).collect();
        assert_eq!(
            found,
            [
                (2, PointValue::Rate),
                (4, PointValue::Output),
                (7, PointValue::Sigma),
                (8, PointValue::Sigma)
            ]
        );
        let text = err.to_string();
        assert!(
            text.contains("point 3: rate = 0 must be finite and > 0"),
            "{text}"
        );
        assert!(
            text.contains("point 8: standard uncertainty σ = 1e300 must lie in"),
            "{text}"
        );
        let short = [1e-8; 3];
        let p = Points {
            sigma_rad_s: Some(&short),
            ..p
        };
        assert_eq!(
            calibrate(&p, geometry).unwrap_err(),
            CalibrationError::SigmaLength {
                got: 3,
                expected: 12
            }
        );
    }
}
