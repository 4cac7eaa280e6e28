//! The calibration section: the PIGA's calibration on measured data (eq. 17–19) and the
//! uncertainty of its coefficients (JCGM 100 and 101).
//!
//! - `validate`: the validated section and its validation (the compensating phase, k1, the
//!   Monte Carlo trials, the `uncertainty` section's Type B inputs), and the reading of its
//!   data;
//! - `evaluate`: the eq. 18 fit, the measurement model and its GUM and Monte Carlo
//!   evaluation, through the `calibration` crate (the mathematics, shared with the planner);
//! - `report`: the mapping to results and the calibration's warnings;
//! - `run`: the section's run, in that order.

mod evaluate;
mod report;
mod run;
mod validate;

pub use run::CalibrationMeasurement;
pub(crate) use run::{measurement, run};
pub(crate) use validate::{CalibrationInputs, load, validate};
