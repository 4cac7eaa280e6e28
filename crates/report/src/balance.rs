//! The balance advisor's report section and its polar plot (`balance_polar.svg`).

use std::fmt::Write as _;

use plotters::prelude::*;

use crate::error::{ReportError, Result};
use crate::format;
use pipeline::{
    BalanceResults, CorrectionResult, CounterweightResults, PhasorResult, PredictedResult,
    TwoPlaneResults,
};

fn opt(value: Option<f64>, fmt: impl Fn(f64) -> String) -> String {
    value.map_or_else(|| "—".to_owned(), fmt)
}

fn correction_line(out: &mut String, c: &CorrectionResult, p: &PredictedResult) {
    let _ = writeln!(
        out,
        "| {} | {:.4} ± {:.4} | {} | {:.3} ± {:.3} | {:.4e} | {:.3e} ± {:.3e} | {:.3e} ± {:.3e} | {:.4e} | {} |",
        c.method.replace('_', " "),
        c.mass_kg,
        c.mass_u_kg,
        c.radius_m,
        c.azimuth_deg,
        c.azimuth_u_deg,
        c.unbalance_g_mm,
        p.c_r_m_s2,
        p.c_r_u_m_s2,
        p.delta_k2_rad_s_g2,
        p.delta_k2_u_rad_s_g2,
        p.residual_unbalance_g_mm,
        opt(p.iso_grade_mm_s, |g| format!(
            "G {g} ({:.3} mm/s)",
            p.e_per_omega_mm_s.unwrap_or(0.0)
        )),
    );
}

/// Appends the balance section to report.md.
pub(crate) fn section(out: &mut String, b: &BalanceResults) {
    let _ = writeln!(out, "## Balance advisor\n");
    let _ = writeln!(
        out,
        "The first harmonic of each phase, read as the drift of the spindle axis in the spindle \
         frame O2 (azimuth from O2X2, the arm towards the PIGA, towards O2Y2), is fitted over its \
         rates as S + D·ω² (complex least squares): S the static part (eq. 3–4), D the dynamic \
         part (eq. 1–2). Magnitudes are at the PIGA plane (× lever ratio, eq. 22); the O2X2 \
         component of D is C_r. Figure: `balance_polar.svg`. Procedure: `docs/BALANCING.md`.\n"
    );
    format::table_head(
        out,
        "| phase | static \\|S\\| (µm) | static azimuth (deg) | dynamic \\|D\\| (µm·s²) | dynamic azimuth (deg) | C_r (m·s²) | lack of fit \\|B\\|/σ | √(χ²/dof) |",
    );
    for p in &b.phases {
        let _ = writeln!(
            out,
            "| `{}` | {:.4} ± {:.4} | {:.3} ± {:.3} | {:.5} ± {:.5} | {:.3} ± {:.3} | {:.4e} | {} | {} |",
            p.name,
            p.static_phasor.magnitude_um,
            p.static_phasor.magnitude_u_um,
            p.static_phasor.azimuth_deg,
            p.static_phasor.azimuth_u_deg,
            p.dynamic.magnitude_um_s2,
            p.dynamic.magnitude_u_um_s2,
            p.dynamic.azimuth_deg,
            p.dynamic.azimuth_u_deg,
            p.dynamic.c_r_m_s2,
            opt(p.linear_significance, |v| format!("{v:.2}")),
            opt(p.reduced_chi, |v| format!("{v:.3}")),
        );
    }
    if let Some(a) = &b.influence {
        let _ = writeln!(
            out,
            "\nInfluence coefficient (trial phase `{}`): |α| = {:.5e} µm·s² per kg·m at {:.3}° \
             (an effective radial stiffness of {:.4e} N/m).",
            b.trial.as_deref().unwrap_or("—"),
            a.magnitude_um_s2_per_kg_m,
            a.azimuth_deg,
            a.effective_stiffness_n_m
        );
    }
    if let Some(s) = &b.stiffness {
        let _ = writeln!(
            out,
            "\nStiffness model (eq. 1, k_r = {:e} N/m): imbalance m·R_cm = {:.4} ± {:.4} kg·m at {:.3}°.",
            s.radial_stiffness_n_m, s.imbalance_kg_m, s.imbalance_u_kg_m, s.imbalance_azimuth_deg
        );
    }
    let _ = writeln!(
        out,
        "\n| correction | mass (kg) | radius (m) | azimuth (deg) | unbalance (g·mm) | residual C_r (m·s²) | residual Δk2 (rad/(s·g²)) | residual unbalance (g·mm) | ISO 21940-11 |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|");
    correction_line(out, &b.correction, &b.predicted);
    if let Some(s) = &b.stiffness
        && b.correction.method != s.correction.method
    {
        correction_line(out, &s.correction, &s.predicted);
    }
    if let Some(split) = &b.correction.split {
        let parts: Vec<String> = split
            .iter()
            .map(|m| format!("{:.4} kg at {}°", m.mass_kg, m.azimuth_deg))
            .collect();
        let _ = writeln!(
            out,
            "\nOn the fixed positions: {} (the same vector sum).",
            parts.join(" and ")
        );
    }
    if let Some(c) = &b.check {
        let _ = writeln!(
            out,
            "\nCheck run `{}`: C_r = {:.4e} ± {:.4e} m·s², {:.3}σ from the prediction; C_r fell by {:.1}×.",
            c.phase, c.c_r_m_s2, c.c_r_u_m_s2, c.z, c.reduction
        );
    }
    let _ = writeln!(
        out,
        "\nThe predicted residual is zero by construction; its uncertainty comes from the \
         phasors' covariances (the initial and the trial runs). Assumption: {}.\n",
        b.assumption
    );
    if let Some(t) = &b.two_plane {
        two_plane_section(out, t);
    }
}

fn phasor_cell(p: &PhasorResult, decimals: usize, unit: &str) -> String {
    format!(
        "{:.d$} ± {:.d$} {unit} at {:.3}° ± {:.3}°",
        p.magnitude,
        p.magnitude_u,
        p.azimuth_deg,
        p.azimuth_u_deg,
        d = decimals
    )
}

/// The two-plane subsection: translation and tilt, static and couple unbalance, the
/// two-plane corrections and their check.
fn two_plane_section(out: &mut String, t: &TwoPlaneResults) {
    let _ = writeln!(
        out,
        "### Two probe planes
"
    );
    let _ = writeln!(
        out,
        "Probes at {:.3} m and {:.3} m from the PIGA plane (second probe's phase `{}`): the \
         spindle axis is read as a line, translation at the PIGA plane plus tilt × height \
         (eq. 5), with no cone assumption.\n",
        t.probe_heights_m[0], t.probe_heights_m[1], t.second_probe_phase
    );
    format::table_head(out, "| quantity | static | dynamic (∝ ω²) |");
    let _ = writeln!(
        out,
        "| translation at the PIGA plane | {} | {} |",
        phasor_cell(&t.static_translation_um, 4, "µm"),
        phasor_cell(&t.dynamic_translation_um_s2, 5, "µm·s²")
    );
    let _ = writeln!(
        out,
        "| tilt (lean of the axis) | {} | {} |",
        phasor_cell(&t.static_tilt_urad, 4, "µrad"),
        phasor_cell(&t.dynamic_tilt_urad_s2, 5, "µrad·s²")
    );
    let _ = writeln!(
        out,
        "\nC_r at the PIGA plane from the two planes: {:.4e} ± {:.4e} m·s².",
        t.c_r_m_s2, t.c_r_u_m_s2
    );
    if let (Some(st), Some(co)) = (&t.static_kg_m, &t.couple_kg_m2) {
        let _ = writeln!(
            out,
            "\nUnbalance ({}): static {}, couple about the PIGA plane {}.",
            t.unbalance_method
                .as_deref()
                .unwrap_or("—")
                .replace('_', " "),
            phasor_cell(st, 4, "kg·m"),
            phasor_cell(co, 4, "kg·m²")
        );
    }
    if !t.corrections.is_empty() {
        let _ = writeln!(
            out,
            "\n| two-plane correction | plane height (m) | mass (kg) | radius (m) | azimuth (deg) | residual C_r (m·s²) | residual Δk2 (rad/(s·g²)) |"
        );
        let _ = writeln!(out, "|---|---|---|---|---|---|---|");
        for c in &t.corrections {
            for p in &c.planes {
                let k = &p.correction;
                let _ = writeln!(
                    out,
                    "| {} | {} | {:.4} ± {:.4} | {} | {:.3} ± {:.3} | {:.3e} ± {:.3e} | {:.3e} ± {:.3e} |",
                    c.method.replace('_', " "),
                    p.height_m,
                    k.mass_kg,
                    k.mass_u_kg,
                    k.radius_m,
                    k.azimuth_deg,
                    k.azimuth_u_deg,
                    c.predicted.c_r_m_s2,
                    c.predicted.c_r_u_m_s2,
                    c.predicted.delta_k2_rad_s_g2,
                    c.predicted.delta_k2_u_rad_s_g2,
                );
            }
        }
    }
    if let Some(c) = &t.check {
        let _ = writeln!(
            out,
            "\nCheck run `{}` (two planes): C_r = {:.4e} ± {:.4e} m·s², {:.3}σ from the prediction; C_r fell by {:.1}×.",
            c.phase, c.c_r_m_s2, c.c_r_u_m_s2, c.z, c.reduction
        );
    }
    let _ = writeln!(out);
}

/// Appends the counterweight section (the paper check) to report.md.
pub(crate) fn counterweight_section(out: &mut String, c: &CounterweightResults) {
    let _ = writeln!(out, "## Counterweight from one change of radius error\n");
    let _ = writeln!(
        out,
        "Phase `{}` gives only the change of radius error between {} and {} deg/s, {} µm. \
         With the radial stiffness k_r = {:e} N/m{}, the stiffness model (eq. 1) turns it into \
         the \"empirical formula\" of a counterweight: {:.4e} g·mm of unbalance per µm, \
         {:.4e} g·mm in all ({:.4} kg at {} m, at {}°, if the imbalance lies on the arm's line). \
         Procedure: `docs/BALANCING.md`.\n",
        c.phase,
        c.from_rate_deg_s,
        c.to_rate_deg_s,
        c.change_um,
        c.radial_stiffness_n_m,
        if c.stiffness_source.is_empty() {
            String::new()
        } else {
            format!(" ({})", crate::format::md_text(&c.stiffness_source))
        },
        c.unbalance_per_um_g_mm,
        c.unbalance_x_g_mm,
        c.correction_mass_kg,
        c.correction_radius_m,
        c.correction_azimuth_deg,
    );
    let _ = writeln!(out, "What the one number determines:\n");
    for d in &c.determined {
        let _ = writeln!(out, "- {d}");
    }
    let _ = writeln!(out, "\nWhat it does not determine:\n");
    for d in &c.not_determined {
        let _ = writeln!(out, "- {d}");
    }
    let _ = writeln!(out);
}

fn plot_error(message: impl ToString) -> ReportError {
    ReportError::Plot {
        what: "balance_polar.svg",
        message: message.to_string(),
    }
}

/// The polar plot: each phase's measured drift per rate at the PIGA plane (points), its fit
/// `S + D·ω²` from ω = 0 to the top rate (line), the static phasor S (arrow from the origin)
/// and the direction of the correction (dashed, to the plot's edge).
///
/// # Errors
/// [`ReportError::Plot`] when plotters fails.
pub fn balance_polar_svg(b: &BalanceResults, title: &str) -> Result<String> {
    let colours = [RED, BLUE, GREEN, MAGENTA, CYAN];
    let mut reach: f64 = 1e-6;
    for p in &b.phases {
        for q in &p.points_um {
            reach = reach.max(q[1].hypot(q[2]));
        }
    }
    if let Some(t) = &b.two_plane {
        for q in &t.per_rate {
            reach = reach.max(q[1].hypot(q[2]));
        }
    }
    let lim = reach * 1.15;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(-lim..lim, -lim..lim)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .x_desc("drift along O2X2 at the PIGA plane (µm)")
            .y_desc("along O2Y2 (µm)")
            .draw()
            .map_err(plot_error)?;
        for (k, p) in b.phases.iter().enumerate() {
            let colour = colours[k % colours.len()];
            let top = p.points_um.iter().map(|q| q[0]).fold(0.0, f64::max);
            let (s, d) = (&p.static_phasor, &p.dynamic);
            let (sa, da) = (s.azimuth_deg.to_radians(), d.azimuth_deg.to_radians());
            let curve: Vec<(f64, f64)> = (0..=100)
                .map(|i| {
                    let w = (top * f64::from(i) / 100.0).to_radians();
                    let r = d.magnitude_um_s2 * w * w;
                    (
                        s.magnitude_um * sa.cos() + r * da.cos(),
                        s.magnitude_um * sa.sin() + r * da.sin(),
                    )
                })
                .collect();
            chart
                .draw_series(LineSeries::new(curve, colour.stroke_width(2)))
                .map_err(plot_error)?
                .label(format!("{}: S + D·ω²", p.name))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            chart
                .draw_series(
                    p.points_um
                        .iter()
                        .map(|q| Circle::new((q[1], q[2]), 4, colour.filled())),
                )
                .map_err(plot_error)?;
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![
                        (0.0, 0.0),
                        (s.magnitude_um * sa.cos(), s.magnitude_um * sa.sin()),
                    ],
                    colour.stroke_width(1),
                )))
                .map_err(plot_error)?;
        }
        if let Some(t) = &b.two_plane {
            chart
                .draw_series(
                    t.per_rate
                        .iter()
                        .map(|q| TriangleMarker::new((q[1], q[2]), 6, BLACK.filled())),
                )
                .map_err(plot_error)?
                .label(format!(
                    "{}: translation at the PIGA plane (two planes, no cone)",
                    b.initial
                ))
                .legend(|(x, y)| TriangleMarker::new((x + 10, y), 6, BLACK.filled()));
        }
        let ca = b.correction.azimuth_deg.to_radians();
        let dashes: Vec<PathElement<(f64, f64)>> = (0..20)
            .filter(|i| i % 2 == 0)
            .map(|i| {
                let (a, z) = (f64::from(i) / 20.0 * lim, f64::from(i + 1) / 20.0 * lim);
                PathElement::new(
                    vec![(a * ca.cos(), a * ca.sin()), (z * ca.cos(), z * ca.sin())],
                    BLACK.stroke_width(2),
                )
            })
            .collect();
        chart
            .draw_series(dashes)
            .map_err(plot_error)?
            .label(if b.two_plane.is_some() {
                format!(
                    "single-plane correction through the cone, for comparison only: {:.4} kg at {:.2}° (two planes: see the report)",
                    b.correction.mass_kg, b.correction.azimuth_deg
                )
            } else {
                format!(
                    "correction: {:.4} kg at {:.2}°",
                    b.correction.mass_kg, b.correction.azimuth_deg
                )
            })
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}
