//! The mechanism section: a PIGA calibration simulated through the exact kinematic chain with
//! the C_r each named phase measured, identified with and without compensation (eq. 17–19).
//! Validated here; [`run`] simulates it.

mod run;
mod validate;

pub(crate) use run::run;
pub(crate) use validate::{Mechanism, validate};
