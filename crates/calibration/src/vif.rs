//! How separable the eq. 18 fit's terms are: the variance inflation factors (a diagnostic)
//! and the widening of the reported coefficients' uncertainties by the nuisance terms (what
//! the calibration warns on).
//!
//! A polynomial design in ω is intrinsically collinear: over 20–200 °/s every column of
//! `[1, ω, ω², ω³, a², a³]` is close to a combination of the others, and every VIF is large
//! (ω² 3e4, a² 6e4, ω³ 1e5 on the campaign fixture). A VIF compares a column with a fit
//! that has no other columns at all, so it says nothing about what a lab can act on. What
//! matters is how much wider u(k2) (and u of the other reported coefficients) is than it need
//! be: [`coefficient_inflation`] gives two measures, both properties of the rates, weights and
//! R/g alone, computed through `identify`'s QR with column scaling.
//!
//! - **The nuisance terms' price** ([`CoefficientInflation::nuisance`]): u in the full fit over
//!   u in the same fit without the ω and ω³ columns (tilt, Coriolis, the cross-coupling C_φ of
//!   eq. 17). It is large on every design (u(k2) 25 times on the campaign fixture, 10 times
//!   for the ω³ column alone) because those terms are genuinely in the PIGA's output: dropping
//!   them would bias the coefficients. A diagnostic, not a warning: no choice of rates brings
//!   it near 1.
//! - **The rates' price** ([`CoefficientInflation::versus_spread`]): u over the u the same
//!   number of points, with the noise the points show at each rate, would give spread evenly
//!   from 10 % of the top rate to the top rate (the span of the paper's and the campaign's designs). This is
//!   what a lab can act on, and what the calibration warns on above [`INFLATION_LIMIT`]:
//!   1.0 on the campaign fixture (20–200 °/s), 1.6 on twelve rates 35–200 °/s, 7000 on seven
//!   rates bunched at 150–180 °/s.

use identify::{CompensatedCalibration, Design, Geometry, IdentifyError, LstsqOptions};

use crate::{A2_TERM, OMEGA2_TERM, TERMS, design_row};

/// A variance inflation factor above which terms were once reported as hard to separate; kept
/// as a reference for the diagnostic (no warning uses it: every polynomial design in ω
/// exceeds it).
pub const VIF_LIMIT: f64 = 1e3;

/// The factor by which a reported coefficient's standard uncertainty may exceed that of the
/// evenly spread reference design ([`CoefficientInflation::versus_spread`]) before the
/// calibration warns. Three: the design then holds less than one ninth of the information on
/// that coefficient that the same number of rates, spread over 10–100 % of the top rate,
/// would give — nine times the centrifuge time to reach the same u — while ordinary lab
/// designs stay below 2 (1.0 for 20 rates over 20–200 °/s, 1.6 for 12 rates over
/// 35–200 °/s, 2.7 for seven rates over 40–160 °/s).
pub const INFLATION_LIMIT: f64 = 3.0;

/// The lowest rate of the reference design, as a fraction of the top rate.
pub const REFERENCE_LOW_FRACTION: f64 = 0.1;

/// The columns of the eq. 18 design that are nuisance terms (ω and ω³): in the fit so the
/// reported coefficients are unbiased, not reported themselves.
pub const NUISANCE_TERMS: [usize; 2] = [1, 3];

/// The columns of the eq. 18 design that give the reported coefficients, in the order k0,
/// k1, k2, k3 (the constant, ω², a² and a³ columns).
pub const REPORTED_TERMS: [usize; 4] = [0, OMEGA2_TERM, A2_TERM, TERMS - 1];

/// Variance inflation factors of the five non-constant eq. 18 columns, from the fit's
/// unscaled covariance `(XᵀWX)⁻¹` and the columns' weighted sums of squares about their
/// weighted means (`VIF_j = [(XᵀWX)⁻¹]_jj · Σᵢ wᵢ(x_ij − x̄_j)²`, valid with an intercept
/// column; `wᵢ = 1/σᵢ²`, or 1 unweighted). A diagnostic: see the module's documentation for
/// why no warning is based on it.
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

/// How much wider the reported coefficients' standard uncertainties are than they need be
/// (see the module's documentation). Each array is in the order k0, k1, k2, k3 (the constant,
/// ω², a² and a³ columns, [`REPORTED_TERMS`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoefficientInflation {
    /// `u(β_j)` in the full eq. 18 fit over `u(β_j)` in the same fit without the ω and ω³
    /// columns (≥ 1): the nuisance terms' price, a diagnostic.
    pub nuisance: [f64; 4],
    /// `u(β_j)` over `u(β_j)` of the reference design: as many points, evenly spread from
    /// [`REFERENCE_LOW_FRACTION`] of the top rate to the top rate, each with the σ the points
    /// show at that rate (interpolated linearly in the rate between the points' rates,
    /// constant beyond them; unweighted when the fit is). Above [`INFLATION_LIMIT`] the
    /// calibration warns.
    pub versus_spread: [f64; 4],
    /// The reference design's lowest and top rates, rad/s.
    pub reference_rad_s: (f64, f64),
}

impl CoefficientInflation {
    /// The reported coefficients' names, in the order of the arrays.
    pub const NAMES: [&'static str; 4] = ["k0", "k1", "k2", "k3"];

    /// The coefficient whose u is furthest above the reference design's: its name and factor.
    #[must_use]
    pub fn worst_versus_spread(&self) -> (&'static str, f64) {
        let mut worst = (Self::NAMES[0], self.versus_spread[0]);
        for (name, &f) in Self::NAMES.iter().zip(&self.versus_spread) {
            if f > worst.1 {
                worst = (name, f);
            }
        }
        worst
    }

    /// Whether a reported coefficient's u exceeds the reference design's by more than
    /// [`INFLATION_LIMIT`].
    #[must_use]
    pub fn degraded(&self) -> bool {
        self.versus_spread.iter().any(|&f| f > INFLATION_LIMIT)
    }
}

/// The diagonal of `(XᵀWX)⁻¹` for the columns of eq. 18 with the given powers of ω, rows
/// weighted by `1/σᵢ`, from `identify`'s QR (the outputs play no part).
fn unscaled_variances(
    rates_rad_s: &[f64],
    sigma_rad_s: Option<&[f64]>,
    geometry: Geometry,
    powers: &[u32],
) -> Result<Vec<f64>, IdentifyError> {
    let k = geometry.radius_m / geometry.g_m_s2;
    let factors: Vec<f64> = powers
        .iter()
        .map(|&p| match p {
            4 => k * k,
            6 => k * k * k,
            _ => 1.0,
        })
        .collect();
    let mut design = Design::powers(rates_rad_s, powers).scale_columns(&factors)?;
    if let Some(s) = sigma_rad_s {
        let w: Vec<f64> = s.iter().map(|s| 1.0 / s).collect();
        design = design.scale_rows(&w)?;
    }
    let zeros = vec![0.0; rates_rad_s.len()];
    let fit = identify::lstsq_design(&design, &zeros, &LstsqOptions::default())?;
    Ok((0..powers.len())
        .map(|j| fit.unscaled_covariance[(j, j)])
        .collect())
}

/// The points' σ as a function of the rate: one σ per distinct rate (`1/√(mean 1/σ²)` over
/// its points), in increasing rate.
pub(crate) fn sigma_curve(rates_rad_s: &[f64], sigma_rad_s: &[f64]) -> Vec<(f64, f64)> {
    let mut points: Vec<(f64, f64)> = rates_rad_s
        .iter()
        .zip(sigma_rad_s)
        .map(|(&w, &s)| (w.abs(), 1.0 / (s * s)))
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut curve: Vec<(f64, f64, usize)> = Vec::new();
    for (w, weight) in points {
        match curve.last_mut() {
            Some(last) if last.0 == w => {
                last.1 += weight;
                last.2 += 1;
            }
            _ => curve.push((w, weight, 1)),
        }
    }
    curve
        .into_iter()
        .map(|(w, total, count)| (w, 1.0 / (total / count as f64).sqrt()))
        .collect()
}

/// The σ at rate `w` on the curve, linear between its rates and constant beyond them.
pub(crate) fn interpolate(curve: &[(f64, f64)], w: f64) -> f64 {
    let i = curve.partition_point(|p| p.0 < w);
    match (i.checked_sub(1).map(|j| curve[j]), curve.get(i)) {
        (Some(a), Some(b)) if b.0 > a.0 => a.1 + (b.1 - a.1) * (w - a.0) / (b.0 - a.0),
        (_, Some(b)) => b.1,
        (Some(a), None) => a.1,
        (None, None) => 1.0,
    }
}

/// The powers of ω of the eq. 18 columns ([`crate::TERM_NAMES`]).
const POWERS: [u32; TERMS] = [0, 1, 2, 3, 4, 6];

/// How much wider u(k0…k3) are than they need be: against the same fit without the nuisance
/// columns ω and ω³, and against the evenly spread reference design (see
/// [`CoefficientInflation`]). `sigma_rad_s` are the σ the fit was weighted by (`None`:
/// unweighted).
///
/// # Errors
/// Those of [`identify::lstsq_design`] (e.g. fewer rates than the design's six columns, or a
/// rank-deficient design) and of [`Design::scale_rows`] (a σ that is zero or not finite).
pub fn coefficient_inflation(
    rates_rad_s: &[f64],
    sigma_rad_s: Option<&[f64]>,
    geometry: Geometry,
) -> Result<CoefficientInflation, IdentifyError> {
    let full = unscaled_variances(rates_rad_s, sigma_rad_s, geometry, &POWERS)?;
    let reduced = unscaled_variances(rates_rad_s, sigma_rad_s, geometry, &[0, 2, 4, 6])?;
    let n = rates_rad_s.len();
    let top = rates_rad_s.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    let low = REFERENCE_LOW_FRACTION * top;
    let reference_rates: Vec<f64> = (0..n)
        .map(|i| low + (top - low) * i as f64 / (n.max(2) - 1) as f64)
        .collect();
    let reference_sigma: Option<Vec<f64>> = sigma_rad_s.map(|s| {
        let curve = sigma_curve(rates_rad_s, s);
        reference_rates
            .iter()
            .map(|&w| interpolate(&curve, w))
            .collect()
    });
    let reference = unscaled_variances(
        &reference_rates,
        reference_sigma.as_deref(),
        geometry,
        &POWERS,
    )?;
    let nuisance = std::array::from_fn(|r| {
        let j = REPORTED_TERMS[r];
        (full[j] / reduced[r]).sqrt().max(1.0)
    });
    let versus_spread = std::array::from_fn(|r| {
        let j = REPORTED_TERMS[r];
        (full[j] / reference[j]).sqrt()
    });
    Ok(CoefficientInflation {
        nuisance,
        versus_spread,
        reference_rad_s: (low, top),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GEOMETRY: Geometry = Geometry {
        radius_m: 2.5,
        g_m_s2: 9.8,
    };

    fn inflation(deg: &[f64]) -> CoefficientInflation {
        let rad: Vec<f64> = deg.iter().map(|d| d.to_radians()).collect();
        coefficient_inflation(&rad, None, GEOMETRY).expect("a full-rank design")
    }

    #[test]
    fn well_spread_designs_are_not_degraded_though_their_nuisance_price_is_large() {
        // the campaign fixture's 20 rates and an unrelated 12-rate campaign
        let campaign: Vec<f64> = (2..=20)
            .map(|i| f64::from(i) * 10.0)
            .chain([195.0])
            .collect();
        let twelve: Vec<f64> = (0..12).map(|i| 35.0 + 15.0 * f64::from(i)).collect();
        for rates in [campaign, twelve] {
            let i = inflation(&rates);
            assert!(!i.degraded(), "{rates:?}: {i:?}");
            assert!(i.versus_spread[2] < 2.0, "{i:?}");
            // the ω and ω³ terms widen u(k2) more than tenfold on any design: why the
            // warning does not use them
            assert!(i.nuisance[2] > 10.0, "{i:?}");
        }
    }

    #[test]
    fn the_points_noise_at_each_rate_carries_to_the_reference() {
        // σ growing with the rate, as raw recordings of equal length give: the reference
        // design carries the same growth, so an evenly spread design still compares as one
        let deg: Vec<f64> = (0..10).map(|i| 20.0 + 20.0 * f64::from(i)).collect();
        let rad: Vec<f64> = deg.iter().map(|d| d.to_radians()).collect();
        let sigma: Vec<f64> = deg.iter().map(|d| 1e-11 * d).collect();
        let i = coefficient_inflation(&rad, Some(&sigma), GEOMETRY).expect("full rank");
        for f in i.versus_spread {
            assert!((f - 1.0).abs() < 1e-9, "{i:?}");
        }
        assert_eq!(interpolate(&[(1.0, 2.0), (3.0, 4.0)], 2.0), 3.0);
        assert_eq!(interpolate(&[(1.0, 2.0), (3.0, 4.0)], 0.5), 2.0);
        assert_eq!(interpolate(&[(1.0, 2.0), (3.0, 4.0)], 5.0), 4.0);
        let curve = sigma_curve(&[2.0, 1.0, 2.0], &[1.0, 3.0, 1.0]);
        assert_eq!(curve, vec![(1.0, 3.0), (2.0, 1.0)]);
    }

    #[test]
    fn bunched_rates_are_degraded_with_the_figure() {
        let i = inflation(&[150.0, 155.0, 160.0, 165.0, 170.0, 175.0, 180.0]);
        assert!(i.degraded());
        let (name, f) = i.worst_versus_spread();
        assert!(f > 1000.0, "{name} {f}");
        assert!(i.versus_spread[2] > 1000.0, "{i:?}");
        assert!((i.reference_rad_s.0 - 18.0_f64.to_radians()).abs() < 1e-12);
        assert!((i.reference_rad_s.1 - 180.0_f64.to_radians()).abs() < 1e-12);
    }

    #[test]
    fn the_reference_design_compares_as_one() {
        // the reference design itself, weighted by equal σ
        let deg: Vec<f64> = (0..9).map(|i| 20.0 + 22.5 * f64::from(i)).collect();
        let rad: Vec<f64> = deg.iter().map(|d| d.to_radians()).collect();
        let sigma = vec![1e-6; deg.len()];
        let i = coefficient_inflation(&rad, Some(&sigma), GEOMETRY).expect("full rank");
        for f in i.versus_spread {
            assert!((f - 1.0).abs() < 1e-9, "{i:?}");
        }
    }
}
