//! Validation of a plan's predicted u(k2) by simulating its campaign many times.

use nalgebra::DMatrix;
use rand::{SeedableRng, rngs::StdRng};
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

use crate::error::{PlanningError, Result};
use crate::inputs::{K2, PlanInputs, UNKNOWNS, regressors};
use crate::plan::Plan;

/// The least number of simulated campaigns.
pub const MIN_CAMPAIGNS: usize = 10;

/// The most simulated campaigns a check runs (issue 32: `plan --simulate 1e7` took about
/// five minutes, 2⁶⁴ − 1 would never end). 10⁶ estimate the ratio of spreads to 0.07 %,
/// far below anything a plan decides on, in about 30 s of CPU for a one-orientation plan and
/// 2.5 min for a two-orientation one ([`CampaignKind::seconds_per_campaign`]).
pub const MAX_CAMPAIGNS: usize = 1_000_000;

/// Which simulation a number of campaigns is asked of: what one campaign costs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CampaignKind {
    /// [`simulate_plan`]: one weighted eq. 18 fit per campaign.
    OneOrientation,
    /// [`simulate_two_orientation_plan`](crate::simulate_two_orientation_plan): one joint
    /// eq. 23 fit per campaign.
    TwoOrientations,
}

impl CampaignKind {
    /// CPU time of one campaign, s: docs/PERFORMANCE.md's criterion medians of 10⁴
    /// campaigns (`simulate_10000_campaigns` 0.26–0.31 s, `simulate_two_orientations_10000_campaigns`
    /// 1.5–2.6 s) rounded up, for the estimate a refusal states.
    #[must_use]
    pub const fn seconds_per_campaign(self) -> f64 {
        match self {
            Self::OneOrientation => 3.0e-5,
            Self::TwoOrientations => 1.5e-4,
        }
    }
}

/// Refuses a number of simulated campaigns below [`MIN_CAMPAIGNS`] or above
/// [`MAX_CAMPAIGNS`], before any work: what `plan --simulate N`, the Python package and the
/// simulations themselves call.
///
/// # Errors
/// [`PlanningError::TooFewCampaigns`]; [`PlanningError::TooManyCampaigns`] with the CPU time
/// the campaigns would take.
pub fn check_campaigns(campaigns: usize, kind: CampaignKind) -> Result<()> {
    if campaigns < MIN_CAMPAIGNS {
        return Err(PlanningError::TooFewCampaigns {
            campaigns,
            need: MIN_CAMPAIGNS,
        });
    }
    if campaigns > MAX_CAMPAIGNS {
        return Err(PlanningError::TooManyCampaigns {
            campaigns,
            max: MAX_CAMPAIGNS,
            seconds_per_campaign: kind.seconds_per_campaign(),
        });
    }
    Ok(())
}

/// The spread of k2 over simulated campaigns against the prediction.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SimulationCheck {
    /// Campaigns simulated.
    pub campaigns: usize,
    /// The seed of the campaigns (campaign `c` draws the stream `units::stream_seed(seed, …, c)`).
    pub seed: u64,
    /// The predicted u(k2) of the fit, rad/(s·g²).
    pub predicted_u_rad_s_g2: f64,
    /// The sample standard deviation of the fitted k2, rad/(s·g²).
    pub simulated_sd_rad_s_g2: f64,
    /// `simulated_sd / predicted_u`.
    pub ratio: f64,
    /// The relative standard error of a sample SD from this many campaigns,
    /// `1/√(2(n − 1))` (normal errors).
    pub ratio_standard_error: f64,
    /// The mean of the fitted (apparent) k2, rad/(s·g²).
    pub mean_k2_rad_s_g2: f64,
    /// The apparent k2 of the noise-free outputs, rad/(s·g²).
    pub noise_free_k2_rad_s_g2: f64,
}

/// The plan's noise-free mean outputs by the closed form of eq. 17 (`k0 + k1·a + k2·a² +
/// k3·a³ + k1·C_r·ω⁴/g`), one per point. A caller with the exact chain
/// (`simulate::piga_table` with zero noise) passes its own instead.
pub fn expected_outputs(inputs: &PlanInputs, plan: &Plan) -> Vec<f64> {
    let p = &inputs.piga;
    let c_r = inputs.c_r.expected_m_s2;
    plan.points
        .iter()
        .map(|q| {
            let w = units::deg_s_to_rad_s(q.rate_deg_s);
            let a = plan.radius_m * w * w / plan.g_m_s2;
            p.k0_rad_s
                + p.k1_rad_s_g * a
                + p.k2_rad_s_g2 * a * a
                + p.k3_rad_s_g3 * a * a * a
                + p.k1_rad_s_g * c_r * w.powi(4) / plan.g_m_s2
        })
        .collect()
}

/// Simulates the plan's campaign `campaigns` times: each point's mean output is
/// `noise_free_rad_s[i]` plus a normal draw of the point's σ (fresh per campaign and point;
/// campaign `c` draws from its own stream (`campaign_rng`: `units::stream_seed` of the seed and
/// `c`), in parallel, so the result does not depend on the number of threads), then fits eq. 18 by weighted least squares
/// (`identify::lstsq` on the rows divided by σ_i) and compares the spread of the apparent k2
/// with the plan's u(k2) of the fit.
///
/// # Errors
/// [`PlanningError::TooFewCampaigns`], [`PlanningError::TooManyCampaigns`] (see
/// [`check_campaigns`]), [`PlanningError::OutputCount`], and the solver's errors.
pub fn simulate_plan(
    plan: &Plan,
    noise_free_rad_s: &[f64],
    campaigns: usize,
    seed: u64,
) -> Result<SimulationCheck> {
    let sigma: Vec<f64> = plan.points.iter().map(|q| q.sigma_mean_rad_s).collect();
    let rows: Vec<[f64; UNKNOWNS]> = plan
        .points
        .iter()
        .map(|q| {
            regressors(
                units::deg_s_to_rad_s(q.rate_deg_s),
                plan.radius_m,
                plan.g_m_s2,
            )
        })
        .collect();
    let x = DMatrix::from_fn(rows.len(), UNKNOWNS, |r, j| rows[r][j] / sigma[r]);
    let fit = |y: &[&[f64]]| -> Result<f64> {
        let yw: Vec<f64> = y[0].iter().zip(&sigma).map(|(y, s)| y / s).collect();
        identify::lstsq(&x, &yw)
            .map(|f| f.coefficients[K2])
            .map_err(PlanningError::Identify)
    };
    spread_of_k2(
        &[(noise_free_rad_s, &sigma)],
        CampaignKind::OneOrientation,
        campaigns,
        seed,
        plan.u_k2_fit_rad_s_g2,
        fit,
    )
}

/// The label of the simulated campaigns' streams (`units::stream_seed`).
const CAMPAIGN_STREAM: u64 = 0xCA4B_A167;

/// The random stream of simulated campaign `c` under the user's `seed`: the seed and the
/// campaign through `units::stream_seed`, so that no two (seed, campaign) pairs share a stream
/// (with `seed + c`, seed 1's campaign 1 drew seed 2's campaign 0).
pub(crate) fn campaign_rng(seed: u64, c: usize) -> StdRng {
    StdRng::seed_from_u64(units::stream_seed(seed, CAMPAIGN_STREAM, c as u64))
}

/// The spread of k2 over `campaigns` simulated campaigns against `predicted_u_rad_s_g2`:
/// `parts` holds each part's (a mounting's) noise-free mean outputs and their σ; campaign
/// `c` adds a normal draw of each point's σ to its output (from its own stream,
/// [`campaign_rng`], in parallel, so the result does not depend on the number of threads) and
/// `fit_k2` fits the parts' outputs. Shared by [`simulate_plan`] and
/// [`simulate_two_orientation_plan`](crate::simulate_two_orientation_plan).
pub(crate) fn spread_of_k2(
    parts: &[(&[f64], &[f64])],
    kind: CampaignKind,
    campaigns: usize,
    seed: u64,
    predicted_u_rad_s_g2: f64,
    fit_k2: impl Fn(&[&[f64]]) -> Result<f64> + Sync,
) -> Result<SimulationCheck> {
    check_campaigns(campaigns, kind)?;
    for (noise_free, sigma) in parts {
        if noise_free.len() != sigma.len() {
            return Err(PlanningError::OutputCount {
                got: noise_free.len(),
                expected: sigma.len(),
            });
        }
    }
    let noise_free: Vec<&[f64]> = parts.iter().map(|p| p.0).collect();
    let noise_free_k2 = fit_k2(&noise_free)?;
    let k2: Vec<f64> = (0..campaigns)
        .into_par_iter()
        .map(|c| {
            let mut rng = campaign_rng(seed, c);
            let y: Vec<Vec<f64>> = parts
                .iter()
                .map(|(noise_free, sigma)| {
                    noise_free
                        .iter()
                        .zip(*sigma)
                        .map(|(m, s)| {
                            let z: f64 = StandardNormal.sample(&mut rng);
                            m + s * z
                        })
                        .collect()
                })
                .collect();
            fit_k2(&y.iter().map(Vec::as_slice).collect::<Vec<_>>())
        })
        .collect::<Result<_>>()?;
    let mean = k2.iter().sum::<f64>() / campaigns as f64;
    let var = k2.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (campaigns - 1) as f64;
    let sd = var.sqrt();
    Ok(SimulationCheck {
        campaigns,
        seed,
        predicted_u_rad_s_g2,
        simulated_sd_rad_s_g2: sd,
        ratio: sd / predicted_u_rad_s_g2,
        ratio_standard_error: 1.0 / (2.0 * (campaigns - 1) as f64).sqrt(),
        mean_k2_rad_s_g2: mean,
        noise_free_k2_rad_s_g2: noise_free_k2,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No campaign of one seed draws the stream of a campaign of a neighbouring seed.
    #[test]
    fn campaign_streams_do_not_depend_on_the_seed_plus_the_campaign() {
        let first =
            |seed: u64, c: usize| -> f64 { StandardNormal.sample(&mut campaign_rng(seed, c)) };
        let seed1: Vec<u64> = (1..200).map(|c| first(1, c).to_bits()).collect();
        let seed2: Vec<u64> = (0..199).map(|c| first(2, c).to_bits()).collect();
        assert!(seed1.iter().all(|x| !seed2.contains(x)));
        // and the same (seed, campaign) gives the same stream
        assert_eq!(first(7, 3).to_bits(), first(7, 3).to_bits());
    }
}
