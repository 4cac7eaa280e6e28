//! The certificate section: the statements of a calibration certificate beside the
//! calibration's results (ISO/IEC 17025:2017 §7.8.2.1 and §7.8.4.1; `docs/CERTIFICATE.md`).
//!
//! - `validate`: every required field present (all missing ones named at once), a
//!   traceability statement for each Type B input with a non-zero uncertainty, limits with
//!   their decision rule;
//! - `run`: the statements with each input's standard uncertainty and the statements of
//!   conformity read from the calibration's stated intervals (ILAC-G8:09/2019).

mod run;
mod validate;

pub(crate) use run::run;
pub(crate) use validate::{Certificate, validate};
