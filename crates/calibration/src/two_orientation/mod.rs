//! The two-orientation (IA in / IA out) calibration of issue 20 (`docs/theory.md` section
//! 11, `docs/TWO_ORIENTATION.md`): one joint least-squares fit of eq. 23,
//!
//! ```text
//! λ̇_s = k0,s + s·(b1,s·ω + k1,s·a_s + b3·ω³ + γ·ω⁴ + k3·a_s³) + k2·a_s² + ε,   a_s = R_s·ω²/g
//! ```
//!
//! with `s = +1` (IA in) or `−1` (IA out), `γ = k1·C/g`, and `C = C_r + C_a` the total dynamic
//! radius growth at the PIGA. It measures k2 and C from the PIGA's own output, with no probe;
//! with a probe's `C_r` as well, `C − C_r` is the growth the probe does not see (arm stretch)
//! — or a wrong probe declaration.
//!
//! Read in this order: `terms` (the orientations, the coefficients, one design row), `error`,
//! `fit` (the joint fit), `spread` (what the rates cost k2 and C), `evaluate` (its
//! uncertainty and warnings).

#[cfg(test)]
mod earth_rate_tests;
mod error;
mod evaluate;
mod fit;
#[cfg(test)]
mod refit_tests;
mod spread;
mod terms;

pub use error::TwoOrientationError;
pub use evaluate::{
    ProbeCr, TWO_ORIENTATION_OUTPUT_UNITS, TWO_ORIENTATION_OUTPUTS, TwoOrientationEvaluation,
    TwoOrientationModel, TwoOrientationWarning, evaluate_two_orientation, two_orientation_input,
    two_orientation_inputs,
};
pub use fit::{MountingFit, TwoOrientationFit, fit_two_orientation};
pub use spread::{MountingDesign, TwoOrientationSpread, two_orientation_spread};
pub use terms::{
    B3_TERM, GAMMA_TERM, GAMMA_VIF_LIMIT, K2_INFLATION_LIMIT, K2_TERM, K3_TERM,
    MIN_RATES_PER_ORIENTATION, Orientation, OrientationData, TWO_ORIENTATION_TERM_NAMES,
    TWO_ORIENTATION_TERMS, Z_LIMIT, two_orientation_row,
};
