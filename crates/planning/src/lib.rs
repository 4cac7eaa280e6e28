//! Test planning for the centrifuge calibration of a PIGA (issue 13): which rates, how many
//! revolutions at each, and how well balanced the spindle must be, for a target U95(k2).
//!
//! * [`plan`]: chooses the rate points from a candidate grid by a coordinate-exchange
//!   algorithm (seeded random restarts) for the eq. 18 design `1, ω, ω², ω³, a², a³`
//!   (`a = R·ω²/g`), c-optimal for var(k2), the a² coefficient (or D-optimal), with the
//!   recording time allocated to the points by a multiplicative algorithm under the time
//!   budget and rounded to whole revolutions. It predicts u(k2) of the weighted fit
//!   (`[(XᵀWX)⁻¹]_{a²,a²}`, `W = diag(1/σ_i²)`), U95(k2) with and without compensation of the
//!   pseudo-second-order term `Δk2 = k1·C_r·g/R²` (eq. 19) through a GUM budget with the
//!   study's Type B inputs, the largest |C_r| whose uncompensated Δk2 stays below a fraction
//!   of U95, and the test-uncertainty ratio.
//! * [`simulate_plan`]: the prediction checked against the spread of k2 over simulated
//!   campaigns.
//! * [`evaluate_rates`]: the fit part of u(k2) of given rates (e.g. the paper's six), and
//!   [`exhaustive_k2`]: the exhaustive optimum on a small grid.
//! * [`plan_two_orientation`] (issue 20): with [`TwoOrientationPlanInputs`] in the inputs, the rates
//!   and revolutions in both mountings (IA in and IA out) for the smallest u(k2) of the joint
//!   fit of eq. 23 (`calibration::fit_two_orientation`, rows `calibration::two_orientation_row`), the time
//!   split between them, on a round rate grid ([`RateGrid`]) with a lack-of-fit reserve
//!   ([`LackOfFitReserve`]) and their costs in u(k2), beside the probe method's plan in the
//!   same budget; [`simulate_two_orientation_plan`] checks it against simulated campaigns
//!   fitted by the calibration's own joint fit.
//!
//! ```
//! use planning::*;
//! let inputs = PlanInputs {
//!     centrifuge: CentrifugeSpec {
//!         radius_m: 2.5, g_m_s2: 9.8, min_rate_deg_s: 10.0, max_rate_deg_s: 200.0,
//!         max_acceleration_g: None,
//!         candidates: Candidates::Grid { from_deg_s: 10.0, to_deg_s: 200.0, count: 40 },
//!     },
//!     piga: PigaSpec {
//!         k0_rad_s: 0.0, k1_rad_s_g: 0.56, k2_rad_s_g2: 5e-7, k3_rad_s_g3: 0.0,
//!         k1_u_rad_s_g: 0.0, noise: NoiseSpec::PerRevolution { sigma_rad_s: 2e-8 },
//!     },
//!     probe: ProbeSpec {
//!         noise_um: 0.05, sample_rate_hz: 1000.0, pivot_to_probe_mm: 700.0,
//!         probe_to_piga_mm: 510.0,
//!     },
//!     c_r: CrSpec { expected_m_s2: -4.05e-8, u_m_s2: None },
//!     type_b: TypeB::default(),
//!     schedule: Schedule {
//!         points: 8, budget_s: 3600.0, settling_s: 60.0, min_revolutions: 2,
//!         allow_repeats: false,
//!     },
//!     target: Target {
//!         u95_k2_rad_s_g2: 1e-6, tolerance_k2_rad_s_g2: 5e-6, bias_fraction: 0.1,
//!     },
//!     search: Search::default(),
//!     two_orientation: None,
//! };
//! let p = plan(&inputs)?;
//! assert_eq!(p.points.len(), 8);
//! assert!(p.total_time_s <= 3600.0);
//! assert!(p.compensated.u95_rad_s_g2 <= 1e-6);
//! // The prediction against 500 simulated campaigns (the SD's relative error is ≈ 3 %).
//! let check = simulate_plan(&p, &expected_outputs(&inputs, &p), 500, 1)?;
//! approx::assert_relative_eq!(check.ratio, 1.0, max_relative = 0.12);
//! // One hour cannot reach a hundred times that.
//! let tight = PlanInputs { target: Target { u95_k2_rad_s_g2: 1e-8, ..inputs.target }, ..inputs };
//! assert!(matches!(plan(&tight), Err(PlanningError::TargetUnreachable { .. })));
//! # Ok::<(), PlanningError>(())
//! ```
//!
//! Values in, values out: no files. `docs/PLANNING.md` documents the model and the plan file
//! of `cargo xtask plan`.
//!
//! # Features
//! - `serde`: `Serialize`/`Deserialize` on the inputs and the results.
//!
//! # References
//! Liu Y. et al. (2025), eq. 17–19; eq. 23 of `docs/theory.md` section 11 (two
//! orientations); JCGM 100:2008; IEEE Std 836 (test-uncertainty ratio);
//! Fedorov (1972) and Meyer & Nachtsheim (1995) for exchange algorithms; Silvey, Titterington
//! & Torsney (1978) for the multiplicative algorithm.

mod check;
mod design;
mod error;
mod exchange;
mod grid;
mod inputs;
mod plan;
mod two_orientation_check;
mod two_orientation_inputs;
mod two_orientation_plan;
mod two_orientation_space;

pub use check::{
    CampaignKind, MAX_CAMPAIGNS, MIN_CAMPAIGNS, SimulationCheck, check_campaigns, expected_outputs,
    simulate_plan,
};
pub use error::{PlanningError, Result};
pub use inputs::{
    Candidates, CentrifugeSpec, CrSpec, Criterion, K2, NoiseSpec, PigaSpec, PlanInputs, ProbeSpec,
    Schedule, Search, Target, TypeB, UNKNOWNS,
};
pub use plan::{
    Allocation, BudgetLine, ExhaustiveComparison, Expanded, Plan, PlanPoint, RateEvaluation,
    evaluate_rates, exhaustive_k2, plan,
};
pub use two_orientation_check::simulate_two_orientation_plan;
pub use two_orientation_inputs::{
    DEFAULT_STEP_DEG_S, LackOfFitReserve, MountingPlan, RateGrid, TwoOrientationPlanInputs,
};
pub use two_orientation_plan::{
    MountingSchedule, OrientationPoint, ReserveCost, RoundingCost, TwoOrientationPlan,
    expected_two_orientation_outputs, plan_two_orientation,
};
