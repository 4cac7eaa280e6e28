//! The two-orientation plan's predicted u(k2) checked against simulated campaigns, each
//! fitted by the calibration's own joint fit (`calibration::fit_two_orientation`, as the study).

use crate::check::{CampaignKind, SimulationCheck, spread_of_k2};
use crate::error::Result;
use crate::two_orientation_plan::{TwoOrientationPlan, fit_points};

/// Simulates the two-orientation plan's campaign `campaigns` times: each point's mean output
/// is `noise_free_rad_s[k][i]` (IA in, IA out, in the plan's order) plus a normal draw of the
/// point's σ (campaign `c` draws from its own stream, `units::stream_seed` of the seed and `c`, in parallel,
/// so the result does not depend on the number of threads), fitted by
/// `calibration::fit_two_orientation` with the points' σ — the fit the study makes of a PIGA table
/// with a σ column — and compares the spread of k2 with the plan's u(k2).
///
/// # Errors
/// [`TooFewCampaigns`](crate::PlanningError::TooFewCampaigns),
/// [`TooManyCampaigns`](crate::PlanningError::TooManyCampaigns) (see
/// [`check_campaigns`](crate::check_campaigns)),
/// [`OutputCount`](crate::PlanningError::OutputCount), and
/// [`TwoOrientation`](crate::PlanningError::TwoOrientation) from the fit.
pub fn simulate_two_orientation_plan(
    plan: &TwoOrientationPlan,
    noise_free_rad_s: [&[f64]; 2],
    campaigns: usize,
    seed: u64,
) -> Result<SimulationCheck> {
    let sigma = plan.mountings.each_ref().map(|m| {
        m.points
            .iter()
            .map(|q| q.sigma_mean_rad_s)
            .collect::<Vec<f64>>()
    });
    spread_of_k2(
        &[
            (noise_free_rad_s[0], &sigma[0]),
            (noise_free_rad_s[1], &sigma[1]),
        ],
        CampaignKind::TwoOrientations,
        campaigns,
        seed,
        plan.u_k2_rad_s_g2,
        |y| fit_points(&plan.mountings, plan.g_m_s2, [y[0], y[1]]).map(|f| f.k2_rad_s_g2.0),
    )
}
