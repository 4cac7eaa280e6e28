//! The IEEE 836 model from several mountings in the report and the terminal summary
//! (`docs/MODEL.md`): each chosen term with U95 (and normalised by k1), each mounting with
//! its rates and specific-force range, the nuisance terms, the arm stretch, and what the
//! expanded uncertainties hold.

use std::fmt::Write as _;

use pipeline::{MountingsResults, StudyResults, TermResult};

use crate::format;

/// `value ± U95 unit`.
fn with_u95(t: &TermResult) -> String {
    let p = format::pair(t.value, t.u95).joined();
    format!("{p} {}", t.unit)
}

/// The term normalised by k1, `value ± U95 unit` (10⁶·value/k1 in the study's unit: k0 in
/// µg, k2 in µg/g², k3 in µg/g³).
fn normalised(t: &TermResult) -> String {
    t.normalised.as_ref().map_or_else(String::new, |n| {
        format!(
            "{} {}",
            format::pair(n.value * 1e6, t.k * n.u * 1e6).joined(),
            n.relative_unit
        )
    })
}

/// The summary lines (no heading, no warnings).
fn lines(out: &mut String, s: &MountingsResults) {
    let _ = writeln!(
        out,
        "IEEE 836 model from {} mountings ({}), one joint fit, 95 % coverage:",
        s.mountings.len(),
        s.kind
    );
    let width = s
        .terms
        .iter()
        .map(|t| t.name.chars().count())
        .max()
        .unwrap_or(2);
    for t in &s.terms {
        let pad = " ".repeat(width - t.name.chars().count());
        let n = normalised(t);
        let _ = writeln!(
            out,
            "  {}{pad}  {}{}  (k = {})",
            t.name,
            with_u95(t),
            if n.is_empty() {
                String::new()
            } else {
                format!("  = {n}")
            },
            format::coverage_factor(t.k)
        );
    }
    if let Some(a) = &s.arm_stretch {
        let _ = writeln!(
            out,
            "  radius growth the probe does not see (arm stretch) {} m·s² (standard uncertainty)",
            format::pair(a.unseen_m_s2, a.unseen_u_m_s2).joined()
        );
    }
    if let Some(p) = &s.probe {
        let _ = writeln!(
            out,
            "  compensated with phase `{}`'s C_r {} m·s² (standard uncertainty)",
            p.phase,
            format::pair(p.c_r_m_s2, p.c_r_u_m_s2).joined()
        );
    }
    let _ = writeln!(out, "  {}", s.uncertainty_scope);
}

/// The summary of a study whose only calibration is the mountings section.
pub(crate) fn summary_alone(results: &StudyResults) -> Option<String> {
    let s = results.mountings.as_ref()?;
    Some(crate::standalone::summary(results, |out| lines(out, s)))
}

/// The mountings lines inside another section's summary (before its warnings).
pub(crate) fn summary_lines(out: &mut String, results: &StudyResults) {
    if let Some(s) = &results.mountings {
        lines(out, s);
    }
}

/// The report's section.
pub(crate) fn section(out: &mut String, s: &MountingsResults) {
    let _ = writeln!(out, "## The IEEE 836 model from several mountings\n");
    let _ = writeln!(
        out,
        "The {} was calibrated in {} mountings; one joint fit of every mounting's table \
         (docs/MODEL.md) identifies the chosen terms of the IEEE Std 836 model, with each \
         mounting's own nuisance terms{}. {}.\n",
        s.kind,
        s.mountings.len(),
        s.probe.as_ref().map_or_else(
            || ", the probe's C_r not compensated".to_owned(),
            |p| format!(
                " and phase `{}`'s C_r compensated along each mounting's axes",
                format::md_text(&p.phase)
            )
        ),
        s.uncertainty_scope
    );
    let _ = writeln!(
        out,
        "| mounting | radius m | rates deg/s | specific force g | points | residual RMS {} |",
        s.output_unit
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for m in &s.mountings {
        let _ = writeln!(
            out,
            "| {} | {} | {} to {} | {} to {} | {} | {:.2e} |",
            format::md_text(&m.name),
            format::plain(m.radius_m),
            format::rate(m.rate_low_deg_s),
            format::rate(m.rate_high_deg_s),
            format::significant(m.specific_force_low_g, 3),
            format::significant(m.specific_force_high_g, 3),
            m.points,
            m.residual_rms
        );
    }
    let _ = writeln!(
        out,
        "\n| term | multiplies | value ± U95 | k | relative to k1 ± U95 |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|");
    for t in &s.terms {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} |",
            t.name,
            format::md_text(&t.multiplies),
            with_u95(t),
            format::coverage_factor(t.k),
            normalised(t)
        );
    }
    if !s.nuisances.is_empty() {
        let _ = writeln!(
            out,
            "\n| nuisance term | value ± u (standard uncertainty) |"
        );
        let _ = writeln!(out, "|---|---|");
        for n in &s.nuisances {
            let _ = writeln!(
                out,
                "| {} | {} |",
                format::md_text(&n.name),
                format::pair(n.value, n.u).joined()
            );
        }
    }
    if let Some(a) = &s.arm_stretch {
        let _ = writeln!(
            out,
            "\nRadius growth the probe does not see (arm stretch): {} m·s²; total growth at the \
             accelerometer C = {} m·s² (standard uncertainties).",
            format::pair(a.unseen_m_s2, a.unseen_u_m_s2).joined(),
            format::pair(a.total_m_s2, a.total_u_m_s2).joined()
        );
    }
    let _ = writeln!(
        out,
        "\nFit: {}; {} degrees of freedom; residual SD {:.2e} {}; condition number {:.1e}. \
         Vertical Earth rate: {}. Separability: {}.\n",
        s.weighting,
        s.dof,
        s.residual_sd,
        s.output_unit,
        s.condition_number,
        s.earth_rate_words,
        format::md_text(&s.separability)
    );
}
