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
//!
//! Values in, values out: no files. `docs/PLANNING.md` documents the model and the plan file
//! of `cargo xtask plan`.
//!
//! # Features
//! - `serde`: `Serialize`/`Deserialize` on the inputs and the results.
//!
//! # References
//! Liu Y. et al. (2025), eq. 17–19; JCGM 100:2008; IEEE Std 836 (test-uncertainty ratio);
//! Fedorov (1972) and Meyer & Nachtsheim (1995) for exchange algorithms; Silvey, Titterington
//! & Torsney (1978) for the multiplicative algorithm.

mod check;
mod design;
mod error;
mod inputs;
mod plan;

pub use check::{MIN_CAMPAIGNS, SimulationCheck, expected_outputs, simulate_plan};
pub use error::{PlanningError, Result};
pub use inputs::{
    Candidates, CentrifugeSpec, CrSpec, Criterion, K2, NoiseSpec, PigaSpec, PlanInputs, ProbeSpec,
    Schedule, Search, Target, TypeB, UNKNOWNS,
};
pub use plan::{
    Allocation, BudgetLine, ExhaustiveComparison, Expanded, Plan, PlanPoint, RateEvaluation,
    evaluate_rates, exhaustive_k2, plan,
};
