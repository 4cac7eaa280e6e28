//! A several-unit study's summary: the top folder's report section naming each unit.

use std::fmt::Write as _;

use pipeline::StudyResults;

use crate::format;

/// Appends the units section of the top folder's `report.md`: one row per unit with its
/// certificate, k1, radius, Δk2 and k2 ± U95, and where its own report is.
pub(crate) fn units_markdown(out: &mut String, results: &StudyResults) {
    let Some(units) = results.units.as_ref() else {
        return;
    };
    let _ = writeln!(out, "## Units\n");
    let _ = writeln!(
        out,
        "{} unit{} calibrated from this study's probe phases, measured once. Each unit's \
         complete results (its report, results.json and certificate) are in its own folder; \
         its Δk2 = k1·C_r·g/R² (eq. 19) is at its own k1 and radius.\n",
        units.len(),
        if units.len() == 1 { "" } else { "s" }
    );
    let _ = writeln!(
        out,
        "| unit | item | certificate | k1 rad/(s·g) | R m | compensated with | Δk2 rad/(s·g²) | k2 ± U95 rad/(s·g²) | warnings | folder |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|---|");
    for u in units {
        let text = |t: Option<&String>| t.map_or_else(|| "—".to_owned(), |t| format::md_text(t));
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            format::md_text(&u.label),
            text(u.item.as_ref()),
            text(u.certificate.as_ref()),
            format::plain(u.k1_rad_s_g),
            format::plain(u.radius_m),
            text(u.compensate_with.as_ref()),
            u.delta_k2
                .map_or_else(|| "—".to_owned(), |d| format::pair(d.value, d.u).joined()),
            u.k2.map_or_else(|| "—".to_owned(), |k| format::pair(k.value, k.u95).joined()),
            u.warnings,
            format::md_text(&u.folder)
        );
    }
    let _ = writeln!(out);
}
