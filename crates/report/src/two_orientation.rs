//! The two-orientation (IA in / IA out) calibration in the report and the terminal summary
//! (`docs/TWO_ORIENTATION.md`): k2 and the total radius growth C from the PIGA alone, each
//! mounting's k0 and k1, the comparison with the probe's C_r and k2 both ways.

use std::fmt::Write as _;

use pipeline::{
    BudgetLine, Coefficient, Headline, HeadlineMethod, StudyResults, TwoOrientationResults,
};

use crate::format;

/// `value ± U` (or an asymmetric Monte Carlo interval) with the unit.
fn stated(h: &Headline, unit: &str) -> String {
    let (below, above) = h.widths(1.0);
    format!(
        "{} {unit}",
        format::interval(h.value, below, above).joined()
    )
}

fn method(h: &Headline) -> &'static str {
    match h.method {
        HeadlineMethod::Gum => "the GUM, validated by Monte Carlo",
        HeadlineMethod::MonteCarlo => "the Monte Carlo method",
    }
}

fn with_u95(c: &Coefficient, unit: &str) -> String {
    format!("{} {unit}", format::pair(c.value, c.u95).joined())
}

/// The comparison's verdict in words.
fn verdict(z: f64) -> &'static str {
    if z.abs() > 3.0 {
        "they disagree: see the warning"
    } else {
        "they agree within 3 standard uncertainties"
    }
}

/// The summary lines of the two-orientation calibration (no heading, no warnings).
fn lines(out: &mut String, s: &TwoOrientationResults) {
    let _ = writeln!(
        out,
        "Two-orientation calibration (IA in and IA out, one joint fit), 95 % coverage:"
    );
    let _ = writeln!(
        out,
        "  k2 from the PIGA alone   {}  (interval from {})",
        stated(&s.headline.k2, "rad/(s·g²)"),
        method(&s.headline.k2)
    );
    if let Some(p) = &s.probe {
        let _ = writeln!(
            out,
            "  k2 by the probe method   {}  (IA-in data compensated with phase `{}`, U from the GUM with k = {})",
            format::pair(p.k2_probe.value, p.k2_probe_u95).joined() + " rad/(s·g²)",
            p.phase,
            probe_k(p)
        );
    }
    let _ = writeln!(
        out,
        "  total radius growth C    {}  (interval from {})",
        stated(&s.headline.c, "m·s²"),
        method(&s.headline.c)
    );
    let _ = writeln!(
        out,
        "  Δk2,total = k1·C·g/R²    {}  (at the IA-in radius {} m)",
        with_u95(&s.delta_k2_total, "rad/(s·g²)"),
        format::plain(s.mountings[0].radius_m)
    );
    if let Some(p) = &s.probe {
        let _ = writeln!(
            out,
            "  probe's C_r              {} m·s² (standard uncertainty; phase `{}`)",
            format::pair(p.c_r_m_s2.value, p.c_r_m_s2.u).joined(),
            p.phase
        );
        let _ = writeln!(
            out,
            "  C − C_r                  {}, z = {:+.1}: {}",
            with_u95(&p.difference_m_s2, "m·s²"),
            p.z,
            verdict(p.z)
        );
    }
}

/// The summary of a study whose only calibration is the two-orientation one: its lines and
/// every warning of the study. `None` without a two-orientation section.
pub(crate) fn summary_alone(results: &StudyResults) -> Option<String> {
    let s = results.two_orientation.as_ref()?;
    Some(crate::standalone::summary(results, |out| {
        lines(out, s);
        crate::mountings::summary_lines(out, results);
        if s.probe.is_some() {
            let i = &results.inputs;
            let _ = writeln!(
                out,
                "  probe: {}; angle zero: {}",
                i.probe_direction.words(),
                i.angle_zero.words()
            );
        }
    }))
}

/// The two-orientation lines inside a calibration's summary (before its warnings).
pub(crate) fn summary_lines(out: &mut String, results: &StudyResults) {
    if let Some(s) = &results.two_orientation {
        lines(out, s);
    }
}

fn coefficient_row(out: &mut String, name: &str, unit: &str, c: &Coefficient) {
    let _ = writeln!(
        out,
        "| {name} | {} | {} | {} | {unit} |",
        format::pair(c.value, c.u95).joined(),
        format::coverage_factor(c.k),
        format::dof(c.dof),
    );
}

fn budget_table(out: &mut String, output: &str, lines: &[BudgetLine]) {
    let quantity_head = format!("input quantity ({output})");
    let last = ("% of u²", |l: &BudgetLine| format::percent(l.percent));
    let heads = [quantity_head.as_str(), "sensitivity"];
    crate::calibration::budget_table(out, lines, heads, last);
}

/// Appends the report's two-orientation section.
pub(crate) fn section(out: &mut String, s: &TwoOrientationResults) {
    let _ = writeln!(out, "## Two-orientation calibration (IA in and IA out)\n");
    let _ = writeln!(
        out,
        "The PIGA was calibrated with its input axis towards the spindle axis (IA in) and away \
         from it (IA out). Turning the input axis round changes the sign of every term linear in \
         the input, including the radius growth's ω⁴ term, while k2·a² keeps its sign: one joint \
         fit (docs/TWO_ORIENTATION.md) gives k2 and the total dynamic radius growth C at the PIGA \
         (spindle and arm) from the PIGA's own output, with no probe. Expanded uncertainties \
         U95 for 95 % coverage.\n"
    );
    format::table_head(
        out,
        "| mounting | radius m | data | points | distinct rates | residual SD rad/s |",
    );
    for m in &s.mountings {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {:.2e} |",
            if m.orientation == "ia_in" {
                "IA in"
            } else {
                "IA out"
            },
            format::plain(m.radius_m),
            mounting_data(m),
            m.points,
            m.distinct_rates,
            m.residual_sd_rad_s
        );
    }
    let _ = writeln!(out);
    format::table_head(out, "| quantity | value ± U95 | k | ν_eff | unit |");
    for m in &s.mountings {
        let tag = if m.orientation == "ia_in" {
            "IA in"
        } else {
            "IA out"
        };
        coefficient_row(out, &format!("k0 ({tag})"), "rad/s", &m.k0);
        coefficient_row(out, &format!("k1 ({tag})"), "rad/(s·g)", &m.k1);
    }
    coefficient_row(out, "k2", "rad/(s·g²)", &s.k2);
    coefficient_row(out, "k3", "rad/(s·g³)", &s.k3);
    coefficient_row(out, "C (total radius growth)", "m·s²", &s.c_m_s2);
    coefficient_row(
        out,
        "Δk2,total = k1·C·g/R² (IA-in radius)",
        "rad/(s·g²)",
        &s.delta_k2_total,
    );
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "Stated 95 % intervals: k2 {} (from {}); C {} (from {}).\n",
        stated(&s.headline.k2, "rad/(s·g²)"),
        method(&s.headline.k2),
        stated(&s.headline.c, "m·s²"),
        method(&s.headline.c),
    );
    let _ = writeln!(
        out,
        "Joint fit: {} residual degrees of freedom, residual SD {:.2e} rad/s, condition number \
         {:.3e}, variance inflation factor of the ω⁴ term {:.3e} (a diagnostic); fitting C \
         makes u(k2) {:.2} times what it would be with C known (k2 and C correlated at {:+.3}; \
         warned above 3). g = {} m/s² with u(g) = {:.1e} m/s².\n",
        s.dof,
        s.residual_sd_rad_s,
        s.condition_number,
        s.omega4_vif,
        s.k2_inflation_by_omega4,
        s.k2_c_correlation,
        format::plain(s.g_m_s2.value),
        s.g_m_s2.u
    );
    if let Some(r) = &s.u_inflation_by_rates {
        let _ = writeln!(
            out,
            "The rates: u(k2) is {:.2} times and u(C) {:.2} times what the same number of rates \
             per orientation, spread evenly from {} to {} deg/s in both, would give (warned above \
             3).\n",
            r.k2,
            r.c,
            format::plain(rounded(r.reference_low_deg_s)),
            format::plain(rounded(r.reference_top_deg_s)),
        );
    }
    if let Some(p) = &s.probe {
        let _ = writeln!(out, "### Against the probe\n");
        let how = match p.chosen_by.as_str() {
            "compare_with" => "named by `two_orientation.compare_with`".to_owned(),
            "calibration.compensate_with" => {
                "the calibration section's compensating phase (no `compare_with` given)".to_owned()
            }
            _ => "the study's first phase (no `compare_with` given)".to_owned(),
        };
        let _ = writeln!(
            out,
            "The probe's C_r of phase `{}` ({how}) is {} m·s² (standard uncertainty). The \
             difference C − C_r = {}, z = {:+.1}: {}. A difference is first a wrong declaration \
             of the probe — its angle zero (`lever.angle_zero_deg`), its direction \
             (`lever.probe_direction`) or its gap unit (the phase's `format.gap.unit`) — and, \
             those right, radius growth the probe does not see (arm stretch) or wrong lever \
             heights.\n",
            p.phase,
            format::pair(p.c_r_m_s2.value, p.c_r_m_s2.u).joined(),
            with_u95(&p.difference_m_s2, "m·s²"),
            p.z,
            verdict(p.z)
        );
        format::table_head(out, "| k2 by | value ± U95 | unit |");
        let _ = writeln!(
            out,
            "| the two orientations (no probe) | {} | rad/(s·g²) |",
            format::pair(s.k2.value, s.k2.u95).joined()
        );
        let _ = writeln!(
            out,
            "| the probe method (IA-in data compensated with the probe's C_r; GUM with the calibration's Type B inputs, k = {}) | {} | rad/(s·g²) |",
            probe_k(p),
            format::pair(p.k2_probe.value, p.k2_probe_u95).joined()
        );
        let _ = writeln!(
            out,
            "\nThe two differ by {:.3e} rad/(s·g²).\n",
            p.k2_difference
        );
    }
    let _ = writeln!(out, "### Uncertainty budgets (GUM)\n");
    budget_table(out, "k2", &s.budget.k2);
    budget_table(out, "C", &s.budget.c);
    if let Some(lines) = &s.budget.difference {
        budget_table(out, "C − C_r", lines);
    }
    let mc = &s.monte_carlo;
    let outputs = [
        ("k2", mc.k2.gum_agrees),
        ("k3", mc.k3.gum_agrees),
        ("C", mc.c.gum_agrees),
        ("Δk2,total", mc.delta_k2_total.gum_agrees),
    ];
    let names = |agree: bool| {
        outputs
            .iter()
            .filter(|(_, a)| *a == agree)
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let verdict = match (names(true), names(false)) {
        (yes, no) if no.is_empty() => format!("The GUM result agrees with it for {yes}"),
        (yes, no) if yes.is_empty() => {
            format!(
                "The GUM result does not agree with it for {no}: the Monte Carlo intervals are stated"
            )
        }
        (yes, no) => format!(
            "The GUM result agrees with it for {yes}, not for {no}, whose Monte Carlo interval is stated"
        ),
    };
    let _ = writeln!(
        out,
        "Monte Carlo (JCGM 101): {} trials, seed {}. {verdict} (JCGM 101 §8).\n",
        mc.trials, mc.seed,
    );
}

/// A mounting's data in words: its table, or its raw recordings reduced to points.
fn mounting_data(m: &pipeline::MountingResults) -> String {
    match &m.table {
        Some(t) => format!("table {}", crate::format::md_text(t)),
        None => format!(
            "{} raw output recordings, each reduced to its mean over whole revolutions",
            m.recordings.len()
        ),
    }
}

/// The coverage factor of the probe method's k2, U95/u.
fn probe_k(p: &pipeline::ProbeComparison) -> String {
    if p.k2_probe.u > 0.0 {
        format::coverage_factor(p.k2_probe_u95 / p.k2_probe.u)
    } else {
        "—".to_owned()
    }
}

/// A rate to a micro-degree per second, as a person reads it (`20`, not the
/// `20.000000000000004` of 10 % of 200 deg/s through radians).
fn rounded(deg_s: f64) -> f64 {
    (deg_s * 1e6).round() / 1e6
}
