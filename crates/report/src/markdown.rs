//! The human-readable report, `report.md`.

use std::fmt::Write as _;

use crate::expected::{CheckOutcome, Expected};
use crate::format;
use pipeline::MechanismResults;
use pipeline::model_name;
use pipeline::{ModelFit, PhaseResults, StudyResults};

/// Formats an optional number, or an em dash.
fn opt(value: Option<f64>, fmt: impl Fn(f64) -> String) -> String {
    value.map_or_else(|| "—".to_owned(), fmt)
}

fn sci(x: f64) -> String {
    format!("{x:.4e}")
}

/// Renders the report. `expected`, when given, supplies the paper's published values shown
/// beside ours and `outcomes` the regression checks; neither changes a computed number.
pub fn render(
    results: &StudyResults,
    expected: Option<&Expected>,
    outcomes: Option<&[CheckOutcome]>,
) -> String {
    let mut out = String::new();
    let published = |path: &str| expected.and_then(|e| e.published(path));
    let i = &results.inputs;
    let _ = writeln!(out, "# Study {}\n", format::md_text(&results.study));
    crate::summary::summary_markdown(&mut out, results);
    crate::units::units_markdown(&mut out, results);
    let _ = writeln!(
        out,
        "Inputs: R = {} m, g = {} m/s², k1 = {} rad/(s·g), lever ratio (probe → PIGA plane) = {:.6}.\n",
        i.radius_m, i.g_m_s2, i.k1_rad_s_g, i.lever_ratio
    );
    let _ = writeln!(
        out,
        "Probe declarations (`lever`): direction: {}; angle zero: {}.\n",
        i.probe_direction.words(),
        i.angle_zero.words()
    );
    if let Some(e) = expected {
        let _ = writeln!(
            out,
            "Published values for comparison: {}.\n",
            format::md_text(&e.source)
        );
    }
    if !results.warnings.is_empty() && results.calibration.is_none() {
        let _ = writeln!(
            out,
            "## Warnings\n\nThe numbers below were computed, but these may make them wrong:\n"
        );
        for w in &results.warnings {
            let _ = writeln!(
                out,
                "- **{}** ({}): {}",
                w.code,
                format::md_text(&w.location),
                format::md_text(&w.message)
            );
        }
        let _ = writeln!(out);
    }

    for phase in &results.phases {
        if phase.points.iter().any(|p| p.dc1_um.is_some()) {
            let key = phase_key(&phase.name);
            let beside = if published(&format!("{key}.points[0].amplitude_um")).is_some() {
                " (published values beside: the paper's Table 1)"
            } else {
                ""
            };
            let _ = writeln!(
                out,
                "## Phase `{}`: first harmonic and radius error{beside}\n",
                phase.name
            );
            point_table(&mut out, phase, &key, &published);
        }
    }

    for phase in &results.phases {
        let key = phase_key(&phase.name);
        let _ = writeln!(out, "## Phase `{}`: radius-error fit\n", phase.name);
        fit_table(&mut out, phase, &key, &published);
        residual_table(&mut out, phase);
    }

    for phase in &results.phases {
        discrepancy(&mut out, phase, &published);
    }
    if let Some(m) = &results.mechanism {
        mechanism_table(&mut out, m);
    }
    if let Some(c) = &results.calibration {
        crate::calibration::section(&mut out, c);
    }
    if let Some(s) = &results.two_orientation {
        crate::two_orientation::section(&mut out, s);
    }
    if let Some(s) = &results.mountings {
        crate::mountings::section(&mut out, s);
    }
    if let Some(b) = &results.balance {
        crate::balance::section(&mut out, b);
    }
    if let Some(c) = &results.counterweight {
        crate::balance::counterweight_section(&mut out, c);
    }

    if let Some(outcomes) = outcomes {
        let _ = writeln!(out, "## Regression checks\n");
        format::table_head(
            &mut out,
            "| path | expected | tolerance | computed | status | what |",
        );
        for o in outcomes {
            let _ = writeln!(
                out,
                "| `{}` | {:e} | {:e} | {} | {} | {} |",
                o.check.path,
                o.check.value,
                o.check.tolerance,
                opt(o.actual, |a| format!("{a:e}")),
                match (o.check.regress, o.passed) {
                    (false, _) => "shown",
                    (true, true) => "pass",
                    (true, false) => "**FAIL**",
                },
                o.check.note
            );
        }
        let checked = outcomes.iter().filter(|o| o.check.regress);
        let (passed, total) = checked.fold((0, 0), |(p, t), o| (p + usize::from(o.passed), t + 1));
        let _ = writeln!(out, "\n{passed} of {total} checks pass.");
    }
    out
}

/// The results path of a phase, as expected-value files name it: `phases[<name>]`.
fn phase_key(name: &str) -> String {
    format!("phases[{name}]")
}

fn point_table(
    out: &mut String,
    phase: &PhaseResults,
    key: &str,
    published: &dyn Fn(&str) -> Option<f64>,
) {
    format::table_head(
        out,
        "| rate (deg/s) | d_c1 (µm) | d_s1 (µm) | ΔR1 (µm) | ΔR1 paper | diff | β (deg) | Δr_xd+Δr_xs (µm) | paper | diff |",
    );
    let recorded = phase.points.iter().any(|p| p.revolutions.is_some());
    for (n, p) in phase.points.iter().enumerate() {
        let amp_paper = published(&format!("{key}.points[{n}].amplitude_um"));
        let r_paper = published(&format!("{key}.points[{n}].radius_error_um"));
        let f4 = |x: f64| format!("{x:.4}");
        let diff = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => format!("{:+.1e}", a - b),
            _ => "—".to_owned(),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {:.4} | {} | {} |",
            p.rate_deg_s,
            opt(p.dc1_um, f4),
            opt(p.ds1_um, f4),
            opt(p.amplitude_um, f4),
            opt(amp_paper, f4),
            diff(p.amplitude_um, amp_paper),
            opt(p.beta_deg, |b| format!("{b:.3}")),
            p.radius_error_um,
            opt(r_paper, f4),
            diff(Some(p.radius_error_um), r_paper),
        );
    }
    let _ = writeln!(out);
    if recorded {
        let _ = writeln!(
            out,
            "From the recordings (standard errors across revolutions):\n\n\
             | rate (deg/s) | measured rate (deg/s) | angle from | revolutions | dropped | σ(d_c1) (µm) | σ(d_s1) (µm) | σ(Δr) (µm) | fit residual RMS (µm) |\n\
             |---|---|---|---|---|---|---|---|---|"
        );
        let e = |x: Option<f64>| opt(x, |v| format!("{v:.2e}"));
        for p in &phase.points {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                p.rate_deg_s,
                opt(p.measured_rate_deg_s, |m| format!("{m:.6}")),
                p.angle_source.map_or("—", |a| a.name()),
                p.revolutions
                    .map_or_else(|| "—".to_owned(), |r| r.to_string()),
                p.dropped_revolutions
                    .map_or_else(|| "—".to_owned(), |r| r.to_string()),
                e(p.dc1_sigma_um),
                e(p.ds1_sigma_um),
                e(p.radius_error_sigma_um),
                e(p.residual_rms_um),
            );
        }
        let _ = writeln!(out);
    }
}

fn fit_row(out: &mut String, label: &str, fit: &ModelFit, paper: [Option<f64>; 3]) {
    let _ = writeln!(
        out,
        "| {label}: {}{} | {} | {} | {} | {} | {} | {} | {} | {} |",
        model_name(fit.model),
        fit.reduced_chi.map_or_else(String::new, |chi| format!(
            ", weighted 1/σ² (√(χ²/dof) = {chi:.2})"
        )),
        sci(fit.c_r_m_s2),
        opt(fit.c_r_sigma_m_s2, sci),
        sci(fit.delta_k2_rad_s_g2),
        opt(fit.delta_k2_sigma_rad_s_g2, sci),
        opt(fit.residual_sd_um, |s| format!("{s:.2e}")),
        fit.dof,
        paper
            .iter()
            .map(|v| opt(*v, |x| format!("{x:e}")))
            .collect::<Vec<_>>()
            .join(" / "),
        opt(fit.condition_number, |c| format!("{c:.3e}")),
    );
}

fn fit_table(
    out: &mut String,
    phase: &PhaseResults,
    key: &str,
    published: &dyn Fn(&str) -> Option<f64>,
) {
    format::table_head(
        out,
        "| model | C_r (m·s²) | σ(C_r) | Δk2 (rad/(s·g²)) | σ(Δk2) | residual SD (µm) | dof | paper C_r / σ / Δk2 | cond |",
    );
    let paper = [
        published(&format!("{key}.c_r_m_s2")),
        published(&format!("{key}.c_r_sigma_m_s2")),
        published(&format!("{key}.delta_k2_rad_s_g2")),
    ];
    fit_row(out, "configured", &phase.fit, paper);
    if let Some(alt) = &phase.alternative {
        fit_row(out, "alternative", alt, [None; 3]);
    }
    let _ = writeln!(out);
    if phase.fit.dof == 0 {
        let _ = writeln!(
            out,
            "The fit has as many unknowns as points: C_r is determined exactly and has no standard error.\n"
        );
    }
}

fn residual_table(out: &mut String, phase: &PhaseResults) {
    let _ = writeln!(out, "Residuals (measured − fitted, µm):\n");
    let _ = writeln!(
        out,
        "| rate (deg/s) | radius error (µm) | {} | {} |",
        model_name(phase.fit.model),
        phase
            .alternative
            .as_ref()
            .map_or("—", |a| model_name(a.model))
    );
    let _ = writeln!(out, "|---|---|---|---|");
    for (n, p) in phase.points.iter().enumerate() {
        let alt = phase
            .alternative
            .as_ref()
            .and_then(|a| a.residuals_um.get(n).copied());
        let _ = writeln!(
            out,
            "| {} | {:.4} | {:+.2e} | {} |",
            p.rate_deg_s,
            p.radius_error_um,
            phase.fit.residuals_um[n],
            opt(alt, |r| format!("{r:+.2e}"))
        );
    }
    let _ = writeln!(out);
}

/// For a phase whose published σ(C_r) is known, the account of how it relates to ours.
fn discrepancy(out: &mut String, phase: &PhaseResults, published: &dyn Fn(&str) -> Option<f64>) {
    let key = phase_key(&phase.name);
    let Some(sigma) = published(&format!("{key}.c_r_sigma_m_s2")) else {
        return;
    };
    let _ = writeln!(
        out,
        "## On the paper's stated uncertainty of C_r (phase `{}`)\n",
        phase.name
    );
    let fit = &phase.fit;
    let _ = writeln!(
        out,
        "This study fits the model {} and reports that model's own standard error: \
         C_r = {} ± {} m·s² ({} degrees of freedom).",
        model_name(fit.model),
        sci(fit.c_r_m_s2),
        opt(fit.c_r_sigma_m_s2, sci),
        fit.dof
    );
    if let Some(alt) = &phase.alternative {
        let _ = writeln!(
            out,
            "The same points fitted with {} give C_r = {} ± {} m·s².",
            model_name(alt.model),
            sci(alt.c_r_m_s2),
            opt(alt.c_r_sigma_m_s2, sci)
        );
    }
    let _ = writeln!(
        out,
        "The paper states C_r = {} ± {sigma:e} m·s²: its value matches the two-term fit, while \
         its ±{sigma:e} matches the standard error of the ω² coefficient of the three-term fit \
         a + b·ω + c·ω², whose value is different. We report each model with its own standard \
         error rather than reproducing the paper's pairing.",
        opt(published(&format!("{key}.c_r_m_s2")), |x| format!("{x:e}"))
    );
    let _ = writeln!(out);
}

fn mechanism_table(out: &mut String, m: &MechanismResults) {
    let _ = writeln!(
        out,
        "## The mechanism: a calibration simulated with the measured C_r\n"
    );
    let _ = writeln!(
        out,
        "A PIGA with k0 = {:e} rad/s, k1 = {} rad/(s·g), k2 = {:e} rad/(s·g²), k3 = {:e} rad/(s·g³) \
         is calibrated at {} rates ({} … {} deg/s, latitude {}°, output noise {:e} rad/s) through \
         the exact kinematic chain (eq. 5–13) and the PIGA model (eq. 15), on a spindle whose \
         radius error is the fitted a + C_r·ω² of each phase. The eq. 18 design (columns 1, ω, \
         ω², ω³, a², a³ with a = Rω²/g) is fitted as measured and after removing k1·C_r·ω⁴/g.\n",
        m.piga.k0_rad_s,
        m.piga.k1_rad_s_g,
        m.piga.k2_rad_s_g2,
        m.piga.k3_rad_s_g3,
        m.rates_deg_s.len(),
        m.rates_deg_s.iter().copied().fold(f64::INFINITY, f64::min),
        m.rates_deg_s
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max),
        m.latitude_deg,
        m.output_noise_rad_s,
    );
    format::table_head(
        out,
        "| phase | C_r (m·s²) | k2 true | k2 uncompensated | k2 compensated (± σ) | Δk2 predicted (eq. 19) | uncompensated − true | compensated − true | cond |",
    );
    for p in &m.phases {
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | {} | {} ± {} | {} | {} | {:+.2e} | {:.2e} |",
            p.phase,
            sci(p.c_r_m_s2),
            sci(p.k2_true),
            sci(p.k2_uncompensated),
            sci(p.k2_compensated),
            opt(p.k2_compensated_sigma, |s| format!("{s:.2e}")),
            sci(p.delta_k2_predicted),
            sci(p.delta_k2_apparent),
            p.k2_error_compensated,
            p.condition_number,
        );
    }
    let _ = writeln!(out);
}
