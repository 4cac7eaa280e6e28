//! The calibration certificate: a PDF/A-2b document typeset in process (crates/typeset, typst
//! as a library) from one template (`certificate.typ`) and one data model
//! ([`CertificateData`], built by one builder from the study's results, its provenance and
//! the software), with PNG and SVG pages of the same document for a screen.
//!
//! Its contents follow ISO/IEC 17025:2017 §7.8.2.1 (identification of the laboratory, the
//! customer, the item, the method, the dates, the results with units, the statement that
//! they relate only to the item, the authorisation, a marked end, the certificate id and
//! "Page x of y" on every page), §7.8.4.1 (measurement uncertainty in the measurand's unit,
//! the conditions, the traceability of each input) and §7.8.6 (statements of conformity with
//! the decision rule of ILAC-G8:09/2019 and where each limit comes from).
//!
//! The data reaches the template as JSON (`/data.json`); no string of the study file is ever
//! part of the template's markup, and every string is made [`typeset::printable`] (control
//! and bidirectional characters shown as `[U+XXXX]`).

mod build;
mod certified;
mod model;

pub use model::{
    Authorisation, Budget, CalendarDate, CertificateData, Certified, Check, Conformity, DataUsed,
    Field, Files, Laboratory, Method, Run, Running, Section, Table, Text,
};

use pipeline::StudyResults;

use crate::error::{ReportError, Result};
use crate::provenance::{Provenance, Software};

/// The certificate's template (typst markup).
pub const CERTIFICATE_TEMPLATE: &str = include_str!("certificate.typ");

/// The caption the residual figure is drawn with.
const FIGURE_TITLE: &str = "PIGA output residuals (eq. 18) with their standard uncertainties";

/// The certificate's data for a study with a `certificate` section (and so a calibration),
/// its input files from `provenance` (without it, the certificate says that they were not
/// recorded).
///
/// # Errors
/// [`ReportError::NoCertificate`] when the results hold no certificate or no calibration.
pub fn certificate_data(
    results: &StudyResults,
    provenance: Option<&Provenance>,
    software: &Software,
) -> Result<CertificateData> {
    let (Some(c), Some(info)) = (results.calibration.as_ref(), results.certificate.as_ref()) else {
        return Err(ReportError::NoCertificate);
    };
    Ok(build::build(results, c, info, provenance, software))
}

/// The data as the template reads it: JSON, every string made printable.
///
/// # Errors
/// [`ReportError::Serialize`] or [`ReportError::NonFiniteOutput`] (a number of the model is
/// never a float; this does not happen).
pub fn certificate_json(data: &CertificateData) -> Result<String> {
    let mut value = serde_json::to_value(data).map_err(|e| ReportError::Serialize {
        what: "the certificate's data",
        message: e.to_string(),
    })?;
    printable(&mut value);
    serde_json::to_string_pretty(&value).map_err(|e| ReportError::Serialize {
        what: "the certificate's data",
        message: e.to_string(),
    })
}

/// Every string of `value` made [`typeset::printable`].
fn printable(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::String(s) => {
            if let std::borrow::Cow::Owned(p) = typeset::printable(s) {
                *s = p;
            }
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(printable),
        serde_json::Value::Object(o) => o.values_mut().for_each(printable),
        _ => {}
    }
}

/// The certificate laid out: its pages, ready for PDF, PNG or SVG.
///
/// # Errors
/// As [`certificate_data`]; [`ReportError::Plot`] when the residual figure cannot be drawn;
/// [`ReportError::Typeset`] when the template cannot be typeset with this data.
pub fn certificate_document(
    results: &StudyResults,
    provenance: Option<&Provenance>,
    software: &Software,
) -> Result<typeset::Document> {
    let data = certificate_data(results, provenance, software)?;
    let c = results
        .calibration
        .as_ref()
        .ok_or(ReportError::NoCertificate)?;
    let figure = crate::plot::calibration_residuals_svg(c, FIGURE_TITLE)?;
    let json = certificate_json(&data)?;
    let assets = [typeset::Asset {
        path: "/residuals.svg",
        bytes: figure.as_bytes(),
    }];
    Ok(typeset::compile(
        &typeset::Template {
            name: "certificate.typ",
            source: CERTIFICATE_TEMPLATE,
            assets: &assets,
        },
        json.as_bytes(),
    )?)
}

/// The certificate as PDF/A-2b.
///
/// # Errors
/// As [`certificate_document`]; [`ReportError::Typeset`] when it cannot be written as
/// PDF/A-2b.
pub fn certificate_pdf(
    results: &StudyResults,
    provenance: Option<&Provenance>,
    software: &Software,
) -> Result<Vec<u8>> {
    let data = certificate_data(results, provenance, software)?;
    if data.issued.is_none() {
        let issued = results
            .certificate
            .as_ref()
            .map(|c| c.dates.issued.clone())
            .unwrap_or_default();
        return Err(ReportError::IssueDate { issued });
    }
    Ok(certificate_document(results, provenance, software)?.pdf()?)
}
