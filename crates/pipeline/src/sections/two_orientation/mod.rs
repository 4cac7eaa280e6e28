//! The two-orientation calibration (issue 20, `docs/TWO_ORIENTATION.md`): one PIGA table per
//! orientation (IA in, IA out) fitted jointly by eq. 23 through the `calibration` crate, with
//! the GUM, the Monte Carlo method and their §8 comparison; with a probe phase, C − C_r and
//! k2 by both methods.
//!
//! - `validate`: the section's fields (every problem at once), the probe phase it compares
//!   with, and the reading of its tables;
//! - `run`: the fit, its uncertainty and the results, with the section's warnings.

mod run;
mod validate;

pub(crate) use run::run;
pub(crate) use validate::{TwoOrientationInputs, validate};
