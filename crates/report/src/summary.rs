//! The summary of a calibration: what the terminal prints after `study` and what `report.md`
//! opens with — the coefficients with their 95 % intervals in both units, the coverage
//! method, C_r and Δk2 with one consistent uncertainty, and every warning.

use std::fmt::Write as _;

use pipeline::{CalibrationResults, StudyResults};

use crate::format;
use crate::headline::{Headline, MICRO_UNITS, NAMES, UNITS, headlines};

/// One coefficient's line of the summary.
struct Line {
    name: &'static str,
    native: String,
    micro: Option<String>,
    k: String,
    dof: String,
    method: &'static str,
}

/// `value ± U` or `value +a/-b` (an asymmetric Monte Carlo interval) with the unit.
fn interval(h: &Headline, scale: f64, unit: &str) -> String {
    let (below, above) = h.widths(scale);
    let text = format::interval(h.value() * scale, below, above).joined();
    if unit.is_empty() {
        text
    } else {
        format!("{text} {unit}")
    }
}

fn lines(c: &CalibrationResults) -> Vec<Line> {
    let heads = headlines(c);
    let micro = 1e6 / c.coefficients.k1.value;
    heads
        .iter()
        .enumerate()
        .map(|(n, h)| {
            let (k, dof) = if h.is_gum() {
                (format::coverage_factor(h.gum.k), format::dof(h.gum.dof))
            } else {
                ("—".to_owned(), "—".to_owned())
            };
            Line {
                name: NAMES[n],
                native: interval(h, 1.0, UNITS[n]),
                micro: (n != 1).then(|| interval(h, micro, MICRO_UNITS[n])),
                k,
                dof,
                method: h.method_short(),
            }
        })
        .collect()
}

/// C_r and Δk2 with their standard uncertainties (each is a quantity of its own: neither
/// borrows k2's coverage factor).
fn compensation(c: &CalibrationResults) -> (String, String) {
    let micro = 1e6 / c.coefficients.k1.value;
    (
        format!(
            "C_r = {} m·s² (value ± standard uncertainty u; phase `{}`); sign convention: {}",
            format::pair(c.c_r_combined_m_s2.value, c.c_r_combined_m_s2.u).joined(),
            edge_io::visible(&c.compensate_with),
            c.probe_direction.words()
        ),
        format!(
            "Δk2 = k1·C_r·g/R² = {} rad/(s·g²) = {} µg/g² (value ± standard uncertainty u), removed from k2",
            format::pair(c.delta_k2.value, c.delta_k2.u).joined(),
            format::pair(c.delta_k2.value * micro, c.delta_k2.u * micro.abs()).joined(),
        ),
    )
}

/// What the certificate certifies, in two lines: the method with k2 and its stated interval
/// relative to k1, and why.
fn certified_lines(results: &StudyResults) -> Option<(String, String)> {
    let cert = results.certificate.as_ref()?;
    let c = &cert.certified;
    let k2 = c.coefficients.iter().find(|k| k.name == "k2")?;
    let r = k2.relative.as_ref()?;
    let text = format::interval(r.value, r.value - r.low95, r.high95 - r.value).joined();
    Some((
        format!(
            "certificate {} certifies {}: k2/k1 = {text} µg/g² (95 % interval)",
            edge_io::visible(&cert.id),
            c.method.words()
        ),
        format!("why: {}", edge_io::visible(&c.reason)),
    ))
}

/// Every warning of a study: the study's (with where they arise) and the calibration's.
fn warnings(results: &StudyResults) -> Vec<String> {
    results
        .warnings
        .iter()
        .map(|w| format!("[{}] {}: {}", w.code, w.location, w.message))
        .chain(
            results
                .calibration
                .iter()
                .flat_map(|c| c.warnings.iter().cloned()),
        )
        .collect()
}

/// The summary the command line prints after a study with a calibration: the coefficients
/// with value ± U95 in rad/s units and in µg, µg/g², µg/g³, k, ν_eff and the method of the
/// interval; C_r and Δk2; every warning. `None` for a study without a calibration.
pub fn summary_text(results: &StudyResults) -> Option<String> {
    if let Some(units) = results.units.as_ref() {
        // a several-unit study: each unit's summary, headed by its label and folder
        let mut out = String::new();
        for (u, unit) in units.iter().zip(&results.unit_studies) {
            let _ = writeln!(out, "unit {} ({}):", u.label, u.folder);
            for line in summary_text(unit).unwrap_or_default().lines() {
                let _ = writeln!(out, "  {line}");
            }
        }
        return Some(out);
    }
    let Some(c) = results.calibration.as_ref() else {
        return crate::two_orientation::summary_alone(results)
            .or_else(|| crate::mountings::summary_alone(results));
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "PIGA calibration of study `{}` (eq. 18, k2 compensated for Δk2), 95 % coverage:",
        results.study
    );
    let rows = lines(c);
    let w_native = rows
        .iter()
        .map(|l| l.native.chars().count())
        .max()
        .unwrap_or(0);
    let w_micro = rows
        .iter()
        .map(|l| l.micro.as_deref().map_or(0, |m| m.chars().count()))
        .max()
        .unwrap_or(0);
    let pad = |s: &str, w: usize| format!("{s}{}", " ".repeat(w.saturating_sub(s.chars().count())));
    let _ = writeln!(
        out,
        "  {}  {}  {}  {}  ν_eff   interval from",
        pad("", 2),
        pad("value ± U95", w_native),
        pad("relative to k1 ± U95", w_micro),
        pad("k", 4),
    );
    for l in &rows {
        let _ = writeln!(
            out,
            "  {}  {}  {}  {}  {}  {}",
            l.name,
            pad(&l.native, w_native),
            pad(l.micro.as_deref().unwrap_or(""), w_micro),
            pad(&l.k, 4),
            pad(&l.dof, 6),
            l.method
        );
    }
    let (cr, dk2) = compensation(c);
    let _ = writeln!(out, "  {cr}");
    let _ = writeln!(out, "  angle zero: {}", results.inputs.angle_zero.words());
    let _ = writeln!(out, "  {dk2}");
    crate::two_orientation::summary_lines(&mut out, results);
    crate::mountings::summary_lines(&mut out, results);
    if let Some((what, why)) = certified_lines(results) {
        let _ = writeln!(out, "{what}\n  {why}");
    }
    let all = warnings(results);
    if all.is_empty() {
        let _ = writeln!(out, "no warnings");
    } else {
        for w in all {
            let _ = writeln!(out, "warning: {w}");
        }
    }
    Some(out)
}

/// Appends the summary `report.md` opens with (a study with a calibration only).
pub(crate) fn summary_markdown(out: &mut String, results: &StudyResults) {
    let Some(c) = results.calibration.as_ref() else {
        return;
    };
    let _ = writeln!(out, "## Summary\n");
    let _ = writeln!(
        out,
        "The PIGA's coefficients (eq. 18), k2 compensated for the pseudo-second-order term Δk2; \
         expanded uncertainties U95 for 95 % coverage.\n"
    );
    format::table_head(
        out,
        "| coefficient | value ± U95 | relative to k1 ± U95 | k | ν_eff | interval from |",
    );
    for l in lines(c) {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} |",
            l.name,
            l.native,
            l.micro.as_deref().unwrap_or("—"),
            l.k,
            l.dof,
            l.method
        );
    }
    let (cr, dk2) = compensation(c);
    let _ = writeln!(out, "\n{cr}.\n\n{dk2}.\n");
    if let Some((what, why)) = certified_lines(results) {
        let _ = writeln!(
            out,
            "The {}. {}\n",
            format::md_text(&what),
            format::md_text(&why)
        );
    }
    let all = warnings(results);
    if all.is_empty() {
        let _ = writeln!(out, "No warnings.\n");
    } else {
        let _ = writeln!(out, "Warnings:\n");
        for w in all {
            let _ = writeln!(out, "- {}", format::md_text(&w));
        }
        let _ = writeln!(out);
    }
}
