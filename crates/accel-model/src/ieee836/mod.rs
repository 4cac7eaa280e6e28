//! The accelerometer model of IEEE Std 836 on the centrifuge (issue 29, `docs/MODEL.md`): one
//! model for a PIGA and for a pendulous (force-rebalance) accelerometer, with the terms a lab
//! chooses, driven by the specific force along the case axes IA, PA, OA of a mounting that
//! may lie any way on the arm.
//!
//! ```text
//! E = k0 + k1·(a_i + δ_o·a_p − δ_p·a_o) + k2·a_i² + k3·a_i³ + k4·a_i⁴ + k_oq·a_i·|a_i|
//!     + k_ip·a_i·a_p + k_io·a_i·a_o + k_pp·a_p² + k_oo·a_o² + k_po·a_p·a_o  [− ω_i, PIGA]  + ε
//! ```
//!
//! Read in this order: `terms` (the terms, the kinds and their units, the coefficients and
//! the output of one instant), `mounting` (how the case axes lie on the arm: the presets and
//! general angles, and the nominal inputs `a_j = c_j·a + z_j` the fit's columns use) and
//! `exact` (the mounting on the exact chain of `kinematics`, eq. 5–13, averaged over whole
//! revolutions: what a simulator writes). Eq. 15 is the PIGA with the terms k0…k3 mounted
//! IA in; eq. 23 is the same PIGA mounted IA in and IA out.

mod exact;
mod mounting;
mod terms;

pub use exact::{CaseInputs, MountedPoint, MountedSpindle, NODES_PER_REVOLUTION, mounted_point};
pub use mounting::{CaseAxes, Mounting, MountingAngles, MountingPreset, NominalAxis};
pub use terms::{AccelKind, ModelCoefficients, OutputUnit, TERM_COUNT, Term};
