//! What the rates of a two-orientation design cost k2 and C: u(k2) and u(γ) of the joint fit
//! over those of the same number of points per mounting spread evenly from 10 % of the top
//! rate to the top rate — the single-orientation calibration's rate-spread measure
//! ([`crate::coefficient_inflation`]) applied to eq. 23.
//!
//! The correlation warning ([`TwoOrientationFit::k2_inflation`](crate::TwoOrientationFit)) does not
//! see a design whose mountings are both bunched: k2 and C are then both poorly known but
//! not correlated, and only the stated U says how poorly. This measure does: seven rates per
//! mounting bunched at 150–180 °/s widen u(k2) hundreds of times over the spread design.
//! Like the single-orientation one, it is a property of the rates, radii, weights and g alone
//! (the outputs play no part), computed through `identify`'s QR with column scaling.

use identify::{IdentifyError, LstsqOptions, lstsq_with};

use super::terms::{GAMMA_TERM, K2_TERM, Orientation, TWO_ORIENTATION_TERMS, two_orientation_row};
use crate::vif::{REFERENCE_LOW_FRACTION, interpolate, sigma_curve};

/// One mounting's design: its orientation, radius, rates and the σ its points were weighted
/// by (`None`: unweighted).
#[derive(Debug, Clone, Copy)]
pub struct MountingDesign<'a> {
    /// IA in or out.
    pub orientation: Orientation,
    /// Its static radius, m.
    pub radius_m: f64,
    /// Its rates, rad/s.
    pub rates_rad_s: &'a [f64],
    /// Its points' σ, rad/s (`None`: unweighted).
    pub sigma_rad_s: Option<&'a [f64]>,
}

/// u(k2) and u(γ) (hence u(C)) of a two-orientation design over the spread reference
/// design's: as many points in each mounting, evenly spread from
/// [`REFERENCE_LOW_FRACTION`] of the top rate of both mountings to that top rate, each with
/// the σ its mounting's points show at that rate (linear in the rate between them, constant
/// beyond). Above [`INFLATION_LIMIT`](crate::INFLATION_LIMIT) the study warns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoOrientationSpread {
    /// u(k2) over the reference design's.
    pub k2: f64,
    /// u(γ) over the reference design's (C = γ·g/k̄1: the same factor for C, to first order).
    pub c: f64,
    /// The reference design's lowest and top rates, rad/s.
    pub reference_rad_s: (f64, f64),
}

impl TwoOrientationSpread {
    /// Whether u(k2) or u(C) exceeds the reference design's by more than
    /// [`INFLATION_LIMIT`](crate::INFLATION_LIMIT).
    #[must_use]
    pub fn degraded(&self) -> bool {
        self.k2 > crate::INFLATION_LIMIT || self.c > crate::INFLATION_LIMIT
    }
}

/// The diagonal of `(XᵀWX)⁻¹` of eq. 23's design for the k2 and γ columns.
fn variances(designs: &[MountingDesign<'_>], g_m_s2: f64) -> Result<(f64, f64), IdentifyError> {
    let rows: usize = designs.iter().map(|d| d.rates_rad_s.len()).sum();
    let mut x = nalgebra::DMatrix::zeros(rows, TWO_ORIENTATION_TERMS);
    let mut r = 0;
    for d in designs {
        for (i, &w) in d.rates_rad_s.iter().enumerate() {
            let wt = d.sigma_rad_s.map_or(1.0, |s| 1.0 / s[i]);
            let row = two_orientation_row(d.orientation, d.radius_m, g_m_s2, w);
            for (j, v) in row.iter().enumerate() {
                x[(r, j)] = v * wt;
            }
            r += 1;
        }
    }
    let fit = lstsq_with(&x, &vec![0.0; rows], &LstsqOptions::default())?;
    Ok((
        fit.unscaled_covariance[(K2_TERM, K2_TERM)],
        fit.unscaled_covariance[(GAMMA_TERM, GAMMA_TERM)],
    ))
}

/// How much wider u(k2) and u(C) are than the evenly spread reference design's (see
/// [`TwoOrientationSpread`]). The σ of a mounting are used only when both mountings give them, as
/// [`fit_two_orientation`](crate::fit_two_orientation) weights.
///
/// # Errors
/// Those of [`identify::lstsq_with`] (a rank-deficient design: too few distinct rates).
pub fn two_orientation_spread(
    designs: &[MountingDesign<'_>; 2],
    g_m_s2: f64,
) -> Result<TwoOrientationSpread, IdentifyError> {
    let weighted = designs.iter().all(|d| d.sigma_rad_s.is_some());
    let actual: [MountingDesign<'_>; 2] = designs.map(|d| MountingDesign {
        sigma_rad_s: if weighted { d.sigma_rad_s } else { None },
        ..d
    });
    let top = designs
        .iter()
        .flat_map(|d| d.rates_rad_s)
        .fold(0.0_f64, |m, w| m.max(w.abs()));
    let low = REFERENCE_LOW_FRACTION * top;
    let reference: Vec<(Vec<f64>, Option<Vec<f64>>)> = actual
        .iter()
        .map(|d| {
            let n = d.rates_rad_s.len();
            let rates: Vec<f64> = (0..n)
                .map(|i| low + (top - low) * i as f64 / (n.max(2) - 1) as f64)
                .collect();
            let sigma = d.sigma_rad_s.map(|s| {
                let curve = sigma_curve(d.rates_rad_s, s);
                rates.iter().map(|&w| interpolate(&curve, w)).collect()
            });
            (rates, sigma)
        })
        .collect();
    let reference_designs: Vec<MountingDesign<'_>> = actual
        .iter()
        .zip(&reference)
        .map(|(d, (rates, sigma))| MountingDesign {
            rates_rad_s: rates,
            sigma_rad_s: sigma.as_deref(),
            ..*d
        })
        .collect();
    let (k2, gamma) = variances(&actual, g_m_s2)?;
    let (k2_ref, gamma_ref) = variances(&reference_designs, g_m_s2)?;
    Ok(TwoOrientationSpread {
        k2: (k2 / k2_ref).sqrt(),
        c: (gamma / gamma_ref).sqrt(),
        reference_rad_s: (low, top),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spread(in_deg: &[f64], out_deg: &[f64]) -> TwoOrientationSpread {
        let rin: Vec<f64> = in_deg.iter().map(|d| d.to_radians()).collect();
        let rout: Vec<f64> = out_deg.iter().map(|d| d.to_radians()).collect();
        two_orientation_spread(
            &[
                MountingDesign {
                    orientation: Orientation::IaIn,
                    radius_m: 2.5,
                    rates_rad_s: &rin,
                    sigma_rad_s: None,
                },
                MountingDesign {
                    orientation: Orientation::IaOut,
                    radius_m: 2.54,
                    rates_rad_s: &rout,
                    sigma_rad_s: None,
                },
            ],
            9.8,
        )
        .expect("a full-rank design")
    }

    #[test]
    fn the_ordinary_design_is_not_degraded() {
        // the worked campaign: 12 rates 35–200 °/s in both mountings
        let twelve: Vec<f64> = (0..12).map(|i| 35.0 + 15.0 * f64::from(i)).collect();
        let s = spread(&twelve, &twelve);
        assert!(!s.degraded(), "{s:?}");
        assert!(s.k2 < 2.0 && s.c < 2.0, "{s:?}");
        assert!((s.reference_rad_s.1 - 200.0_f64.to_radians()).abs() < 1e-12);
        assert!((s.reference_rad_s.0 - 20.0_f64.to_radians()).abs() < 1e-12);
    }

    #[test]
    fn the_reference_design_compares_as_one() {
        let deg: Vec<f64> = (0..9).map(|i| 20.0 + 22.5 * f64::from(i)).collect();
        let s = spread(&deg, &deg);
        assert!(
            (s.k2 - 1.0).abs() < 1e-9 && (s.c - 1.0).abs() < 1e-9,
            "{s:?}"
        );
    }

    #[test]
    fn both_mountings_bunched_are_degraded_with_the_figure() {
        // the case the correlation warning cannot see: k2 and C both poorly known
        let bunched = [150.0, 155.0, 160.0, 165.0, 170.0, 175.0, 180.0];
        let s = spread(&bunched, &bunched);
        assert!(s.degraded(), "{s:?}");
        assert!(s.k2 > 100.0, "{s:?}");
    }

    #[test]
    fn one_mounting_low_only_costs_c() {
        // IA out only at 35–60 °/s: the reference spreads it to the common top rate
        let wide: Vec<f64> = (0..12).map(|i| 35.0 + 15.0 * f64::from(i)).collect();
        let low: Vec<f64> = (0..12).map(|i| 35.0 + 25.0 * f64::from(i) / 11.0).collect();
        let s = spread(&wide, &low);
        assert!(s.degraded(), "{s:?}");
    }
}
