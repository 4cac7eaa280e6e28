//! The one builder of the certificate's data ([`CertificateData`]) from a study's results,
//! its provenance and the software: ISO/IEC 17025:2017 §7.8.2.1 (the laboratory, the
//! customer, the item, the method, the dates, the results with their units, the statement
//! that they relate only to the item, the authorisation, a marked end) and §7.8.4.1 and
//! §7.8.6 (the uncertainty in the measurand's unit, the conditions, the traceability of each
//! input, the statements of conformity with their decision rule and the source of each
//! limit).

mod check;
mod data;
mod identification;
mod tables;
mod text;

use pipeline::{CalibrationResults, CertificateResults, StudyResults};

use super::certified::{self, Method};
use super::model::{Authorisation, CertificateData, Field, Laboratory, Running};
use crate::provenance::{Provenance, Software};
use check::check;
use data::{data_used, gum_against_mc, gum_against_mc_two_orientation};
use identification::{certified_section, files, identification, method};
use tables::{
    budget, compensation, conformity, probe_sign_words, results_notes, results_table, traceability,
};
use text::{calendar_date, rich, running, t, table};

/// The certificate's data.
pub(crate) fn build(
    results: &StudyResults,
    c: &CalibrationResults,
    info: &CertificateResults,
    provenance: Option<&Provenance>,
    software: &Software,
) -> CertificateData {
    let cert = certified::certified(results, c, &info.certified);
    let item = &info.item;
    CertificateData {
        id: running(&info.id),
        issued: calendar_date(&info.dates.issued),
        running: Running {
            left: running(&info.laboratory.name),
            right: running(&format!("Certificate {}", info.id)),
            foot: running(&format!(
                "{} {}, serial number {}",
                item.manufacturer, item.model, item.serial
            )),
        },
        // the head of page 1 (a grid, which cannot break across pages): at most 90
        // characters each, the identification table states them in full
        laboratory: Laboratory {
            name: running(&info.laboratory.name),
            address: running(&info.laboratory.address),
            accreditation: info.laboratory.accreditation.as_deref().map(running),
        },
        identification: identification(info, &results.study),
        serial: item.serial.clone(),
        certified: certified_section(&cert),
        results: results_table(&cert),
        results_notes: results_notes(&cert, c),
        compensation: (cert.method == Method::Probe)
            .then(|| compensation(c, &results.inputs.angle_zero)),
        sign_convention: (cert.method == Method::Probe).then(|| {
            t(format!(
                "Probe sign convention: {}.",
                probe_sign_words(c.probe_direction)
            ))
        }),
        check: results.two_orientation.as_ref().map(|s| check(s, &cert, c)),
        conformity: conformity(info),
        scope: "The results relate only to the item calibrated, as received, under the \
                conditions stated. This certificate shall not be reproduced except in full \
                without the written approval of the laboratory."
            .to_owned(),
        // beside the signature (a block kept on one page): at most 90 characters each, the
        // identification table states them in full
        authorisation: Authorisation {
            name: running(&info.authorisation.name),
            role: running(&info.authorisation.role),
            date: info.dates.issued.clone(),
        },
        method: method(results, info, &cert),
        conditions: info
            .conditions
            .iter()
            .map(|x| Field {
                label: x.quantity.clone(),
                value: x.value.clone(),
            })
            .collect(),
        equipment: table(
            &["role", "instrument", "identity", "calibration due"],
            &[false; 4],
            &[3, 5, 3, 2],
            info.equipment
                .iter()
                .map(|e| {
                    vec![
                        t(&e.role),
                        t(&e.description),
                        t(&e.identity),
                        t(&e.calibration_due),
                    ]
                })
                .collect(),
        ),
        traceability: traceability(info),
        budget: match (cert.method, &results.two_orientation) {
            (Method::TwoOrientation, Some(s)) => budget(
                &s.budget.k2,
                &s.k2,
                "Uncertainty budget of the certified k2, two-orientation method (JCGM 100)",
            ),
            _ => budget(
                &c.budget.k2,
                &c.coefficients.k2,
                "Uncertainty budget of the certified k2, probe method (JCGM 100)",
            ),
        },
        figure_caption: rich(if cert.method == Method::Probe {
            "Residuals of the PIGA's mean output about the fitted model (eq. 18), with the \
             standard uncertainty of each point as its error bar."
        } else {
            "Residuals of the PIGA's mean output in the IA-in mounting about the probe \
             method's fit (eq. 18, the check), with the standard uncertainty of each point as \
             its error bar."
        }),
        gum_against_mc: match (cert.method, &results.two_orientation) {
            (Method::TwoOrientation, Some(s)) => gum_against_mc_two_orientation(s),
            _ => gum_against_mc(c),
        },
        data_used: data_used(results, c),
        files: files(provenance, software),
        end: format!("End of certificate {}", info.id),
    }
}
