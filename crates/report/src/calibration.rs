//! The report's calibration section: what a lab attaches to a calibration record.

use std::fmt::Write as _;

use pipeline::{BudgetLine, CalibrationResults, Coefficient};

use crate::format;

use crate::format::{dof, rate};

fn row(out: &mut String, name: &str, unit: &str, c: &Coefficient) {
    let _ = writeln!(
        out,
        "| {name} | {:.6e} | {:.2e} | {:.3} | {} | {:.2e} | [{:.6e}, {:.6e}] | {unit} |",
        c.value,
        c.u,
        c.k,
        dof(c.dof),
        c.u95,
        c.value - c.u95,
        c.value + c.u95,
    );
}

/// A GUM budget table of the report, one row per input quantity: its name (with the study's
/// note on it, if any), the cells every budget shows (type, value, standard uncertainty,
/// sensitivity, contribution), then the cells of `last` (headings and contents,
/// `|`-separated). The calibration section and the two-orientation section (`two_orientation`) both
/// write their budgets with it.
pub(crate) fn budget_table(
    out: &mut String,
    lines: &[BudgetLine],
    [quantity_head, sensitivity_head]: [&str; 2],
    (last_head, last): (&str, impl Fn(&BudgetLine) -> String),
) {
    let head = format!(
        "| {quantity_head} | type | value | standard uncertainty | {sensitivity_head} | contribution | {last_head} |"
    );
    format::table_head(out, &head);
    for l in lines {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.3e} | {:.3e} | {:.3e} | {} |",
            match &l.note {
                Some(note) => format!("{} ({note})", l.quantity),
                None => l.quantity.clone(),
            },
            l.evaluation,
            l.value
                .map_or_else(|| "—".to_owned(), |v| format!("{v:.6e}")),
            l.u,
            l.sensitivity,
            l.contribution,
            last(l),
        );
    }
    let _ = writeln!(out);
}

/// Appends the calibration section.
pub(crate) fn section(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(
        out,
        "## PIGA calibration (eq. 18), compensated with phase `{}`\n",
        c.compensate_with
    );
    summary(out, c);
    coefficients(out, c);
    let _ = writeln!(out, "### Uncertainty budget of k2 (JCGM 100)\n");
    budget_table(
        out,
        &c.budget.k2,
        ["input quantity", "sensitivity ∂k2/∂x"],
        ("% of u² | dof", |l| {
            format!("{:.2} | {}", l.percent, dof(l.dof))
        }),
    );
    monte_carlo(out, c);
    recordings(out, c);
    residuals(out, c);
    design_and_warnings(out, c);
}

/// The data, the fit and the compensation in one paragraph.
fn summary(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(
        out,
        "{}: {} points at {} distinct rates, {} residual degrees of freedom, residual SD {:.3e} rad/s{}. \
         k1 {}; g = {} m/s²{}. C_r = {:.4e} ± {:.2e} m·s² (phase `{}`), Δk2 = k1·C_r·g/R² = {:.4e} ± {:.2e} rad/(s·g²) removed.\n",
        match &c.table {
            Some(t) => format!("Table {}", format::md_text(t)),
            None => format!(
                "{} raw output recordings, each reduced to its mean output over whole spindle revolutions",
                c.recordings.len()
            ),
        },
        c.points,
        c.distinct_rates,
        c.dof,
        c.residual_sd_rad_s,
        match (c.birge_ratio, c.excess_u_rad_s) {
            (Some(b), Some(tau)) => format!(
                "; weighted by 1/σ of each point, whose residuals scatter {b:.3}× their σ (Birge ratio √(χ²/ν)): \
                 a variation common to every point of τ = {tau:.3e} rad/s is added to each σ (Paule–Mandel, χ²/ν = 1 then)"
            ),
            (Some(b), None) =>
                format!("; weighted by 1/σ of each point, Birge ratio √(χ²/ν) = {b:.3}"),
            _ => "; unweighted".to_owned(),
        },
        if c.k1_source == "fitted" {
            "fitted (c₂·g/R)"
        } else {
            "given"
        },
        c.g_m_s2,
        if c.g_source.is_empty() {
            String::new()
        } else {
            format!(" ({})", format::md_text(&c.g_source))
        },
        c.c_r_m_s2.value,
        c.c_r_m_s2.u,
        c.compensate_with,
        c.delta_k2.value,
        c.delta_k2.u,
    );
}

/// The coefficients with their GUM intervals, in the conventional units, and k2 as measured.
fn coefficients(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(out, "### Coefficients (GUM, 95 % coverage)\n");
    format::table_head(
        out,
        "| coefficient | value | u | k | ν_eff | U95 | interval | unit |",
    );
    row(out, "k0", "rad/s", &c.coefficients.k0);
    row(out, "k1", "rad/(s·g)", &c.coefficients.k1);
    row(out, "k2", "rad/(s·g²)", &c.coefficients.k2);
    row(out, "k3", "rad/(s·g³)", &c.coefficients.k3);
    let conv = &c.conventional;
    let _ = writeln!(
        out,
        "\nIn the conventional units (relative to k1, g = {} m/s²): k0/k1 = {:.3} ± {:.3} µg, \
         k2/k1 = {:.4} ± {:.4} µg/g², k3/k1 = {:.4} ± {:.4} µg/g³.\n",
        conv.g_m_s2,
        conv.k0_ug.value,
        conv.k0_ug.u,
        conv.k2_ug_per_g2.value,
        conv.k2_ug_per_g2.u,
        conv.k3_ug_per_g3.value,
        conv.k3_ug_per_g3.u,
    );
    let _ = writeln!(
        out,
        "Uncompensated (as measured): k2 + Δk2 = {:.6e} ± {:.2e} rad/(s·g²) (fit only).\n",
        c.uncompensated.k2.value, c.uncompensated.k2.u
    );
}

/// The GUM against Monte Carlo, coefficient by coefficient.
fn monte_carlo(out: &mut String, c: &CalibrationResults) {
    let mc = &c.monte_carlo;
    let _ = writeln!(
        out,
        "### GUM and Monte Carlo (JCGM 101), {} trials, seed {}\n",
        mc.trials, mc.seed
    );
    format::table_head(
        out,
        "| coefficient | MC mean | MC u | MC 95 % interval | GUM interval | δ | agree |",
    );
    for (name, m, g) in [
        ("k0", &mc.k0, &c.coefficients.k0),
        ("k1", &mc.k1, &c.coefficients.k1),
        ("k2", &mc.k2, &c.coefficients.k2),
        ("k3", &mc.k3, &c.coefficients.k3),
    ] {
        let _ = writeln!(
            out,
            "| {name} | {:.6e} | {:.2e} | [{:.6e}, {:.6e}] | [{:.6e}, {:.6e}] | {:.1e} | {} |",
            m.mean,
            m.u,
            m.low95,
            m.high95,
            g.value - g.u95,
            g.value + g.u95,
            m.tolerance,
            if m.gum_agrees { "yes" } else { "**no**" },
        );
    }
    let _ = writeln!(out);
}

/// The raw output recordings and what each was reduced to, when there are any.
fn recordings(out: &mut String, c: &CalibrationResults) {
    if !c.recordings.is_empty() {
        let _ = writeln!(out, "### Raw output recordings\n");
        format::table_head(
            out,
            "| file | declared rate (deg/s) | rate used (deg/s) | angle | revolutions (dropped) | mean output (rad/s) | u (rad/s) | white-noise SE | SE across revolutions |",
        );
        for r in &c.recordings {
            let _ = writeln!(
                out,
                "| {} | {} | {:.6} | {} | {} ({}) | {:.9e} | {:.2e} | {:.2e} | {:.2e} |",
                format::md_text(&r.file),
                r.declared_rate_deg_s,
                r.rate_deg_s,
                r.angle_source,
                r.revolutions,
                r.dropped_revolutions,
                r.output_rad_s,
                r.u_rad_s,
                r.white_noise_u_rad_s,
                r.across_revolutions_u_rad_s,
            );
        }
        let _ = writeln!(out);
    }
}

/// The residuals by row and by label.
fn residuals(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(out, "### Residuals\n");
    format::table_head(
        out,
        "| rate (deg/s) | output (rad/s) | u (rad/s) | residual (rad/s) | residual/u | label | from |",
    );
    for r in &c.residuals {
        let _ = writeln!(
            out,
            "| {} | {:.9e} | {} | {:+.2e} | {} | {} | {} |",
            rate(r.rate_deg_s),
            r.output_rad_s,
            r.u_rad_s
                .map_or_else(|| "—".to_owned(), |u| format!("{u:.2e}")),
            r.residual_rad_s,
            r.u_rad_s.map_or_else(
                || "—".to_owned(),
                |u| format!("{:+.2}", r.residual_rad_s / u)
            ),
            r.label
                .as_deref()
                .map_or_else(|| "—".to_owned(), format::md_text),
            match (&r.line, &r.file) {
                (Some(l), _) => format!("line {l}"),
                (None, Some(f)) => format::md_text(f),
                (None, None) => "—".to_owned(),
            },
        );
    }
    let _ = writeln!(out);
    if !c.labels.is_empty() {
        let _ = writeln!(out, "Residuals by label (mean ± its standard error):\n");
        format::table_head(
            out,
            "| label | rows | mean residual (rad/s) | u (rad/s) | mean/u |",
        );
        for l in &c.labels {
            let _ = writeln!(
                out,
                "| {} | {} | {:+.3e} | {:.2e} | {:+.2} |",
                format::md_text(&l.label),
                l.rows,
                l.mean_residual_rad_s,
                l.u_rad_s,
                l.mean_residual_rad_s / l.u_rad_s
            );
        }
        let _ = writeln!(out);
    }
}

/// The design's condition and inflation, then the section's warnings.
fn design_and_warnings(out: &mut String, c: &CalibrationResults) {
    let _ = writeln!(
        out,
        "Design: condition number {:.3e}; variance inflation of ω, ω², ω³, a², a³: {} \
         (large on every polynomial design in ω; a diagnostic only).",
        c.condition_number,
        c.variance_inflation
            .iter()
            .map(|v| format!("{v:.3e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    if let Some(i) = &c.u_inflation {
        let _ = writeln!(
            out,
            "u(k2) is {} times that of the same number of rates spread evenly over {}–{} deg/s \
             (warned above {}); the ω and ω³ nuisance terms widen u(k2) {} times, the price of \
             an unbiased fit on any design.",
            times(i.versus_spread.k2),
            times(i.reference_from_deg_s),
            times(i.reference_to_deg_s),
            i.limit,
            times(i.nuisance.k2),
        );
    }
    let _ = writeln!(out);
    for w in &c.warnings {
        let _ = writeln!(out, "> **Warning:** {w}\n");
    }
}

/// A factor or rate as a person writes it: 2.7, 36, 7139.
fn times(f: f64) -> String {
    if f < 10.0 {
        format!("{f:.1}")
    } else {
        format!("{f:.0}")
    }
}
