//! The probe phases: what was measured at each rate (first harmonics, radius errors, probe
//! recordings, a published change of radius error), validated and loaded here, then carried
//! to the PIGA plane (eq. 21–22) and fitted by the radius-error model (eq. 16) with the
//! pseudo-second-order error Δk2 it implies (eq. 19) in [`run`].

mod analysis;
mod run;
mod validate;

pub use analysis::Progress;
pub(crate) use run::{Measured, fit_phase, measure_phase, run_phase};
pub(crate) use validate::{Phases, check};
