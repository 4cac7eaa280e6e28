//! The sections of a study. Each owns its part of the configuration's validation (the file's
//! data-transfer types → a validated type), its run on values and its mapping to results;
//! they share only the core (`crate::inputs`, and `crate::resolved`: what the study settles
//! once and hands each section's validation beside its own part) and the output format
//! (`crate::results`); none imports another, or reads another's part of the configuration.
//! The study (`study.rs`) orders them.
//!
//! - [`phases`]: the probe phases (eq. 16, 19–22);
//! - [`mechanism`]: a calibration simulated with each phase's C_r (eq. 17–19);
//! - [`calibration`]: the PIGA's calibration on measured data and its uncertainty;
//! - [`balance`]: the balance advisor and the counterweight;
//! - [`certificate`]: the calibration certificate's statements and conformity;
//! - [`two_orientation`]: the two-orientation (IA in / IA out) calibration.

pub(crate) mod balance;
pub(crate) mod calibration;
pub(crate) mod certificate;
pub(crate) mod mechanism;
pub(crate) mod mountings;
pub(crate) mod phases;
pub(crate) mod two_orientation;
