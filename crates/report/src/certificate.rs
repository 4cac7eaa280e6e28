//! The calibration certificate: one self-contained HTML file (inline CSS and SVG, nothing
//! fetched), laid out for A4 printing with the certificate id and "page x of y" on every
//! page (CSS paged media margin boxes, which Chromium's print-to-PDF honours).
//!
//! Its contents follow ISO/IEC 17025:2017 §7.8.2.1 (identification of the laboratory, the
//! customer, the item, the method, the dates, the results with units, the statement that
//! they relate only to the item, the authorisation, a clear end) and §7.8.4.1 (measurement
//! uncertainty in the measurand's unit, the conditions, the traceability of each input,
//! statements of conformity with the decision rule of ILAC-G8:09/2019).

use std::fmt::Write as _;

use pipeline::{CertifiedMethod, StudyResults};

use crate::certificate_tables::{
    budget, certified_table, compensation_block, conformity, data_used, files, gum_against_mc,
    input_unit, results_table,
};
use crate::certificate_two_orientation;
use crate::error::{ReportError, Result};
use crate::format;
use crate::format::esc;
use crate::headline::headlines;
use crate::html::{STYLE, inline_svg, page_style, row, symbols};
use crate::provenance::{Provenance, Software};

/// Renders the calibration certificate of a study with a `certificate` section (and so a
/// calibration): the HTML text, self-contained (inline CSS and SVG; nothing is fetched),
/// for A4 printing. `provenance` lists the input files with their SHA-256 (without it, the
/// certificate says that they were not recorded).
///
/// # Errors
/// [`ReportError::NoCertificate`] when the results hold no certificate or no calibration;
/// [`ReportError::Plot`] when the residual figure cannot be drawn.
pub fn certificate_html(
    results: &StudyResults,
    provenance: Option<&Provenance>,
    software: &Software,
) -> Result<String> {
    let (Some(c), Some(info)) = (results.calibration.as_ref(), results.certificate.as_ref()) else {
        return Err(ReportError::NoCertificate);
    };
    let heads = headlines(c);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>Calibration certificate {}</title>\n<style>\n{}{STYLE}</style>\n</head>\n<body>",
        esc(&info.id),
        page_style(info)
    );
    // Identification
    let _ = writeln!(
        out,
        "<div class=\"masthead\"><div><h1>Calibration certificate</h1><div class=\"id\">{}</div></div>\
         <div class=\"lab\"><strong>{}</strong><br>{}{}</div></div>",
        esc(&info.id),
        esc(&info.laboratory.name),
        esc(&info.laboratory.address),
        info.laboratory
            .accreditation
            .as_ref()
            .map_or_else(String::new, |a| format!("<br>{}", esc(a)))
    );
    let _ = writeln!(out, "<table class=\"ident\"><tbody>");
    let item = &info.item;
    row(
        &mut out,
        "Item",
        &format!(
            "{}, {} {}, serial number <strong>{}</strong>",
            esc(&item.description),
            esc(&item.manufacturer),
            esc(&item.model),
            esc(&item.serial)
        ),
    );
    row(&mut out, "Condition on receipt", &esc(&item.condition));
    row(
        &mut out,
        "Customer",
        &format!(
            "{}, {}",
            esc(&info.customer.name),
            esc(&info.customer.address)
        ),
    );
    row(&mut out, "Place of calibration", &esc(&info.location));
    row(
        &mut out,
        "Dates",
        &format!(
            "received {}; measured {}; issued {}",
            esc(&info.dates.received),
            esc(&info.dates.measured),
            esc(&info.dates.issued)
        ),
    );
    row(&mut out, "Procedure", &esc(&info.procedure));
    row(&mut out, "Performed by", &esc(&info.operator));
    let _ = writeln!(out, "</tbody></table>");

    // Results
    let _ = writeln!(out, "<h2>Results</h2>");
    let _ = writeln!(
        out,
        "<p>The PIGA's coefficients of eq. 18, k2 compensated for the spindle's pseudo-second-order \
         term Δk2. Model of the mean output rate: ω<sub>out</sub> = k0 + k1·a + k2·a² + k3·a³ \
         with a the specific force along the input axis in g.</p>"
    );
    let probe_certified = info.certified.method == CertifiedMethod::Probe;
    if !probe_certified {
        certified_table(&mut out, &info.certified);
        let _ = writeln!(
            out,
            "<p>The probe method's coefficients (one mounting, input axis towards the spindle \
             axis), stated as a check; their k2 and k3 are not certified:</p>"
        );
    }
    results_table(&mut out, c, &heads);
    compensation_block(&mut out, c, &results.inputs.angle_zero, &heads[2]);
    if let Some(s) = &results.two_orientation {
        certificate_two_orientation::certificate_block(
            &mut out,
            s,
            &heads[2],
            c.coefficients.k1.value,
            probe_certified,
        );
    }
    // the statements of conformity, the statement of scope and the authorisation on one page
    let _ = writeln!(out, "<div class=\"closing\">");
    conformity(&mut out, info);
    let _ = writeln!(
        out,
        "<p>The results relate only to the item calibrated, as received, under the conditions \
         stated. This certificate shall not be reproduced except in full without the written \
         approval of the laboratory.</p>"
    );
    let _ = writeln!(
        out,
        "<div class=\"signature\"><div>Authorised by {}, {}<br>Date {}</div><div>Signature</div></div>\n</div>",
        esc(&info.authorisation.name),
        esc(&info.authorisation.role),
        esc(&info.dates.issued)
    );

    // Details
    let _ = writeln!(out, "<section class=\"details\">");
    let _ = writeln!(out, "<h2>Method</h2>");
    let _ = writeln!(
        out,
        "<p>The PIGA is mounted on the centrifuge arm at the working radius R = {} m and \
         calibrated at the rates listed below; at each rate its mean output rate over whole spindle \
         revolutions is measured. The centrifuge's dynamic imbalance makes the working radius grow \
         as C<sub>r</sub>·ω², which adds k1·C<sub>r</sub>·ω⁴/g to the output (eq. 17): indistinguishable \
         by least squares from k2·a², it would appear as a pseudo-second-order term \
         Δk2 = k1·C<sub>r</sub>·g/R² (eq. 19). C<sub>r</sub> is measured by a displacement probe \
         on the spindle (first harmonic of the gap per revolution, eq. 20–22) and the term removed. \
         The coefficients are the least-squares solution of eq. 18 (columns 1, ω, ω², ω³, a², a³), \
         through QR with column scaling; the terms in ω and ω³ are nuisance terms of the set-up. \
         Uncertainties are evaluated by the GUM (JCGM 100) through the whole measurement model and \
         checked by the Monte Carlo method (JCGM 101).</p>",
        format::plain(results.inputs.radius_m)
    );
    if results.two_orientation.is_some() {
        let _ = writeln!(
            out,
            "<p>The check by the two-orientation method fits the mean outputs of both mountings \
             (IA in and IA out) jointly (eq. 23): a bias k0, a scale factor k1 and an ω term per \
             mounting; k2, k3, an ω³ term and the radius growth's term γ = k1·C/g shared, γ with \
             the sign of the mounting. C − C<sub>r</sub> is compared with its standard uncertainty: \
             |z| = |C − C<sub>r</sub>|/u(C − C<sub>r</sub>) above 3 is a disagreement. Its \
             uncertainties are evaluated by the GUM and checked by the Monte Carlo method.</p>"
        );
    }
    if let Some(d) = &info.deviations {
        let _ = writeln!(out, "<p>Departures from the procedure: {}.</p>", esc(d));
    }
    let _ = writeln!(out, "<h2>Conditions and equipment</h2>");
    if !info.conditions.is_empty() {
        let _ = writeln!(out, "<table class=\"ident\"><tbody>");
        for cnd in &info.conditions {
            row(&mut out, &cnd.quantity, &esc(&cnd.value));
        }
        let _ = writeln!(out, "</tbody></table>");
    }
    let _ = writeln!(
        out,
        "<table><thead><tr><th>role</th><th>instrument</th><th>identity</th><th>calibration due</th></tr></thead><tbody>"
    );
    for e in &info.equipment {
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&e.role),
            esc(&e.description),
            esc(&e.identity),
            esc(&e.calibration_due)
        );
    }
    let _ = writeln!(out, "</tbody></table>");
    let _ = writeln!(out, "<h3>Traceability of the Type B inputs</h3>");
    let _ = writeln!(
        out,
        "<table><thead><tr><th>input quantity</th><th class=\"num\">standard uncertainty</th>\
         <th class=\"unit\">unit</th><th>traceability</th></tr></thead><tbody>"
    );
    for t in &info.traceability {
        let u =
            t.u.map_or_else(|| "—".to_owned(), |u| format::significant(u, 2));
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td class=\"num\">{u}</td><td class=\"unit\">{}</td><td>{}</td></tr>",
            symbols(&t.input),
            input_unit(&t.input).unwrap_or("—"),
            esc(&t.statement)
        );
    }
    let _ = writeln!(out, "</tbody></table>");

    let _ = writeln!(out, "<h2>Evaluation</h2>");
    budget(&mut out, c);
    let svg = crate::plot::calibration_residuals_svg(
        c,
        "PIGA output residuals (eq. 18) with their standard uncertainties",
    )?;
    let _ = writeln!(
        out,
        "<div class=\"figure-box\"><h3>Residuals</h3>{}</div>",
        inline_svg(&svg)
    );
    gum_against_mc(&mut out, c);
    data_used(&mut out, results, c);
    files(&mut out, provenance, software);
    let _ = writeln!(
        out,
        "<p class=\"end\">End of certificate {}</p>\n</section>\n</body>\n</html>",
        esc(&info.id)
    );
    Ok(out)
}
