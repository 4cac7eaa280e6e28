//! The two-orientation plan's predicted u(k2) checked against simulated campaigns, each
//! fitted by the calibration's own joint fit (`calibration::fit_symmetric`, as the study).

use rand::{SeedableRng, rngs::StdRng};
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

use crate::check::{MIN_CAMPAIGNS, SimulationCheck};
use crate::error::{PlanningError, Result};
use crate::two_plan::{TwoOrientationPlan, fit_points};

/// Simulates the two-orientation plan's campaign `campaigns` times: each point's mean output
/// is `noise_free_rad_s[k][i]` (IA in, IA out, in the plan's order) plus a normal draw of the
/// point's σ (campaign `c` draws from its own `StdRng` seeded with `seed + c`, in parallel,
/// so the result does not depend on the number of threads), fitted by
/// `calibration::fit_symmetric` with the points' σ — the fit the study makes of a PIGA table
/// with a σ column — and compares the spread of k2 with the plan's u(k2).
///
/// # Errors
/// [`PlanningError::TooFewCampaigns`], [`PlanningError::OutputCount`], and
/// [`PlanningError::Symmetric`] from the fit.
pub fn simulate_two_orientation_plan(
    plan: &TwoOrientationPlan,
    noise_free_rad_s: [&[f64]; 2],
    campaigns: usize,
    seed: u64,
) -> Result<SimulationCheck> {
    if campaigns < MIN_CAMPAIGNS {
        return Err(PlanningError::TooFewCampaigns {
            campaigns,
            need: MIN_CAMPAIGNS,
        });
    }
    for (m, y) in plan.mountings.iter().zip(noise_free_rad_s) {
        if y.len() != m.points.len() {
            return Err(PlanningError::OutputCount {
                got: y.len(),
                expected: m.points.len(),
            });
        }
    }
    let fit_k2 = |y: [&[f64]; 2]| -> Result<f64> {
        fit_points(&plan.mountings, plan.g_m_s2, y).map(|f| f.k2_rad_s_g2.0)
    };
    let noise_free_k2 = fit_k2(noise_free_rad_s)?;
    let k2: Vec<f64> = (0..campaigns)
        .into_par_iter()
        .map(|c| {
            let mut rng = StdRng::seed_from_u64(seed.wrapping_add(c as u64));
            let y = [0, 1].map(|k| {
                plan.mountings[k]
                    .points
                    .iter()
                    .zip(noise_free_rad_s[k])
                    .map(|(q, m)| {
                        let z: f64 = StandardNormal.sample(&mut rng);
                        m + q.sigma_mean_rad_s * z
                    })
                    .collect::<Vec<f64>>()
            });
            fit_k2([&y[0], &y[1]])
        })
        .collect::<Result<_>>()?;
    let mean = k2.iter().sum::<f64>() / campaigns as f64;
    let var = k2.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (campaigns - 1) as f64;
    let sd = var.sqrt();
    Ok(SimulationCheck {
        campaigns,
        seed,
        predicted_u_rad_s_g2: plan.u_k2_rad_s_g2,
        simulated_sd_rad_s_g2: sd,
        ratio: sd / plan.u_k2_rad_s_g2,
        ratio_standard_error: 1.0 / (2.0 * (campaigns - 1) as f64).sqrt(),
        mean_k2_rad_s_g2: mean,
        noise_free_k2_rad_s_g2: noise_free_k2,
    })
}
