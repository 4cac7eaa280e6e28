//! The joint fit of the IEEE 836 model over several mountings (issue 29 part 3,
//! `docs/MODEL.md`): one least-squares fit through `identify`'s column-scaled QR with its
//! covariance, weighted by the calibration's one policy (the points' σ, the Paule–Mandel τ),
//! with the probe's C_r compensated along each mounting's axes and the arm stretch fitted
//! where the mountings allow it; and, before any fit, the separability analysis: the rank,
//! the chosen terms the chosen mountings cannot tell apart, the u inflation against a design
//! that separates them, and the mounting that would.
//!
//! Eq. 18 and eq. 23 are its special cases: eq. 18 is one IA-in mounting with k0…k3, the
//! mounting's ω term and the shared ω³ term; eq. 23 is IA in and IA out with k0…k3, IA out's
//! own bias and k1, both mountings' ω terms, the ω³ term and the arm stretch. The same data
//! give the same coefficients (tests in `crates/calibration/tests`).
//!
//! Read in this order: `spec` (what the lab declares: the kind, the terms, each mounting's
//! data and nuisance terms), `column` (the design's columns and their words), `report` (what
//! the separability analysis finds, in words), `error`, `check`, `design` (the design, once),
//! `separability` (the analysis before any fit), `fit` (the joint fit and its results),
//! `type_b` (the radii, g, the rate scale and the fixtures' angles propagated to every term).

mod check;
mod column;
mod design;
mod error;
mod fit;
mod report;
mod separability;
mod spec;
mod type_b;

pub use column::Column;
pub use design::{JointDesign, joint_design};
pub use error::MountingsError;
pub use fit::{ArmStretchEstimate, MountingsFit, NuisanceEstimate, TermEstimate, fit_mountings};
pub use report::{Confounded, PoorlySeparated, Separability, SeparabilityWarning};
pub use separability::{RANK_TOLERANCE, separability};
pub use spec::{ArmStretch, JointSpec, MountingData, Nuisances, ProbeCompensation};
pub use type_b::{CaseAxis, MountingsTypeB, TypeBContribution, TypeBInput, type_b_contributions};
