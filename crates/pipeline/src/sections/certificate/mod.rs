//! The certificate section: the statements of a calibration certificate beside the
//! calibration's results (ISO/IEC 17025:2017 §7.8.2.1 and §7.8.4.1; `docs/CERTIFICATE.md`).
//!
//! - `validate`: every required field present (all missing ones named at once), a
//!   traceability statement for each Type B input with a non-zero uncertainty, limits with
//!   their decision rule;
//! - `certified`: what is certified (`certify`: the probe method or the two-orientation
//!   method), why, with the other method as the check; a value the study's own check refutes
//!   only with the laboratory's stated reason;
//! - `run`: the statements with each input's standard uncertainty and the statements of
//!   conformity read from the certified coefficients' stated intervals (ILAC-G8:09/2019).

mod certified;
mod run;
mod validate;

pub(crate) use run::run;
pub(crate) use validate::{Certificate, validate};
