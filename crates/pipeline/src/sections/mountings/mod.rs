//! The IEEE 836 model from several mountings (issue 29, `docs/MODEL.md`): each mounting's
//! table fitted jointly by `calibration::fit_mountings`, with the probe's C_r compensated
//! along each mounting's axes.
//!
//! - `validate`: the section's fields (every problem at once), the probe phase, the tables,
//!   and whether the mountings separate the chosen terms (refused before anything runs);
//! - `run`: the joint fit, its results and warnings.

mod run;
mod validate;

pub(crate) use run::run;
pub(crate) use validate::{MountingsInputs, validate};
