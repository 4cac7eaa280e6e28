//! The calibration certificate as a Digital Calibration Certificate (DCC) of PTB, schema
//! v3.3.0 (`https://ptb.de/dcc`), with its quantities in D-SI v2.2.1 (`https://ptb.de/si`):
//! the machine-readable twin of the printed certificate (`docs/CERTIFICATE.md`).
//!
//! [`write_dcc`] takes a study's results (its certificate section and calibration), the
//! software and the files the study read ([`DccInput`], plain values: the report writes the
//! file) and returns the document's text. It writes, in the DCC's two rings:
//! - **administrative data**: the software with its release and commit; the core data (the
//!   laboratory's country, English, the certificate's id as unique identifier, the receipt,
//!   measurement and issue dates as ISO 8601 calendar dates, the certificate this one follows
//!   as `previousReport`); the PIGA with its manufacturer, model and serial number; the
//!   laboratory; the operator and the authorising person; the customer; the place, the
//!   accreditation, the procedure and its departures, and the traceability of each Type B
//!   input, as statements;
//! - **measurement results**: the certified method (the probe method of the paper's
//!   eq. 18–19, or the two-orientation method of eq. 23) with IEEE Std 836, JCGM 100/101/102
//!   and ILAC-G8, and the g of the model; the software, the equipment, the environmental
//!   conditions; the certified k0…k3 (k0 and k1 per mounting for two mountings) as `si:real`
//!   with their stated 95 % intervals (the GUM's `expandedMU` with k, or the Monte Carlo
//!   method's `coverageIntervalMU`) and relative to k1; the coefficients together as
//!   `si:realListXMLList` with their standard uncertainties, covariance matrix and 95 %
//!   coverage region; what is certified and why, the check by the other method, each
//!   mounting's range of validity (rates, specific force), the statements of conformity and
//!   every input file's SHA-256.
//!
//! The units: see `si` (the g-normalised coefficients in rad/s, relative values in ppm).
//!
//! The document is written by quick-xml's event writer: markup comes only from element names
//! spelled in this crate, and every text — from the configuration, the files or the results —
//! is character data the writer escapes, after `text`'s gate: identifications holding a
//! control character or a bidirectional override are refused ([`DccError::HiddenCharacter`],
//! naming the field), other text shows such characters visibly, so the document is always
//! well-formed XML 1.0 and shows what its source held.
//!
//! # References
//! PTB, *Digital Calibration Certificate*, XML schema v3.3.0; PTB, *D-SI*, v2.2.1;
//! JCGM 100:2008, JCGM 101:2008, JCGM 102:2011; ILAC-G8:09/2019; IEEE Std 836-2009;
//! Liu Y. et al. (2025), eq. 18–19, and eq. 23 of the two-orientation method (the certified
//! coefficients, as `pipeline` records them in `results.certificate.certified`).

mod admin;
mod certified;
mod date;
mod error;
mod input;
mod number;
mod results;
mod si;
mod text;
mod xml;

pub use error::{DccError, Result};
pub use input::{DccInput, InputFile, Software};

/// The DCC schema's namespace.
pub const DCC_NAMESPACE: &str = "https://ptb.de/dcc";
/// D-SI's namespace.
pub const SI_NAMESPACE: &str = "https://ptb.de/si";
/// The DCC schema version written.
pub const SCHEMA_VERSION: &str = "3.3.0";

/// The file name beside the study's other outputs.
pub const FILE_NAME: &str = "certificate.dcc.xml";

/// The DCC of `input`'s certificate, as XML text (UTF-8).
///
/// # Errors
/// [`DccError::NoCertificate`] or [`DccError::NoCalibration`] when the results have nothing
/// to certify; [`DccError::HiddenCharacter`] naming an identification that holds a control
/// character or a bidirectional override; [`DccError::Date`] or [`DccError::DateOrder`]
/// naming a date that is not an ISO 8601 calendar date (or span); [`DccError::EmptyText`],
/// [`DccError::NonFinite`], [`DccError::OutOfDomain`] or [`DccError::CovarianceShape`] for
/// results the DCC cannot hold.
pub fn write_dcc(input: &DccInput<'_>) -> Result<String> {
    let results = input.results;
    let cert = results
        .certificate
        .as_ref()
        .ok_or(DccError::NoCertificate)?;
    let certified = certified::certified(results)?;
    let mut x = xml::Xml::new()?;
    x.el_with(
        "dcc:digitalCalibrationCertificate",
        &[
            ("xmlns:dcc", DCC_NAMESPACE),
            ("xmlns:si", SI_NAMESPACE),
            ("schemaVersion", SCHEMA_VERSION),
        ],
        |x| {
            admin::administrative_data(x, cert, input.software)?;
            results::measurement_results(x, cert, &certified, input.software, input.files)
        },
    )?;
    Ok(x.finish())
}
