//! `cargo xtask plan` for a plan file with `two_orientation` (issue 20): the two-orientation
//! plan's run sheet and summary, beside the probe method's u(k2) in the same budget, and its
//! check by simulated campaigns through the exact chain.

use std::fmt::Write as _;

use anyhow::Context as _;
use planning::{PlanInputs, RateGrid, SimulationCheck, TwoOrientationPlan};

/// The plan's noise-free mean outputs through the exact chain (`simulate::piga_table_mounted`,
/// zero noise; the expected C_r as the spindle's dynamic drift, the arm stretch, each
/// mounting's radius and bias shift), IA in then IA out.
fn exact_outputs(
    inputs: &PlanInputs,
    plan: &TwoOrientationPlan,
    latitude_deg: f64,
) -> anyhow::Result<[Vec<f64>; 2]> {
    let spec = inputs
        .two_orientation
        .as_ref()
        .context("the plan file has no two_orientation section")?;
    let (centrifuge, piga) = inputs.simulated(latitude_deg);
    let mut out: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for (k, m) in plan.mountings.iter().enumerate() {
        let shift = [spec.ia_in, spec.ia_out][k].bias_shift_rad_s;
        let mount = simulate::Mount {
            orientation: m.orientation,
            radius_m: m.radius_m,
            arm_stretch_m_s2: spec.arm_stretch_m_s2,
            bias_shift_rad_s: shift,
        };
        let rates: Vec<f64> = m.points.iter().map(|q| q.rate_deg_s).collect();
        let table = simulate::piga_table_mounted(
            &centrifuge,
            &piga,
            &mount,
            &rates,
            &simulate::OutputNoise {
                sigma_rad_s: 0.0,
                seed: 1,
            },
        )
        .with_context(|| format!("the noise-free PIGA table {}", m.orientation.label()))?;
        out[k] = table.iter().map(|r| r.output_rad_s).collect();
    }
    Ok(out)
}

/// The two-orientation plan simulated `campaigns` times, its noise-free outputs through the
/// exact chain, each campaign fitted by the calibration's joint fit.
pub(crate) fn simulate_check(
    inputs: &PlanInputs,
    plan: &TwoOrientationPlan,
    campaigns: usize,
    seed: u64,
    latitude_deg: f64,
) -> anyhow::Result<SimulationCheck> {
    let y = exact_outputs(inputs, plan, latitude_deg)?;
    Ok(planning::simulate_two_orientation_plan(
        plan,
        [&y[0], &y[1]],
        campaigns,
        seed,
    )?)
}

pub(crate) fn run_sheet_csv(plan: &TwoOrientationPlan) -> String {
    let mut s = String::from(
        "point,orientation,rate_deg_s,revolutions,settling_s,recording_s,duration_s,sigma_mean_rad_s,reserve\n",
    );
    let mut i = 0;
    for m in &plan.mountings {
        for q in &m.points {
            i += 1;
            let _ = writeln!(
                s,
                "{i},{},{},{},{},{},{},{:e},{}",
                m.orientation.tag(),
                q.rate_deg_s,
                q.revolutions,
                q.settling_s,
                q.recording_s,
                q.duration_s,
                q.sigma_mean_rad_s,
                q.reserve
            );
        }
    }
    s
}

pub(crate) fn run_sheet_md(plan: &TwoOrientationPlan) -> String {
    let mut s = String::from("# Run sheet: IA in, then IA out\n\n");
    let n: usize = plan.mountings.iter().map(|m| m.points.len()).sum();
    let _ = writeln!(
        s,
        "{n} points in two mountings, {:.0} s of {:.0} s budget (with {:.0} s to turn the PIGA \
         round); predicted U95(k2) = {:.3e} rad/(s·g²) from the PIGA alone (no probe).\n",
        plan.total_time_s, plan.budget_s, plan.remount_s, plan.u95_k2_rad_s_g2
    );
    s.push_str(
        "| point | mounting | radius (m) | rate (deg/s) | revolutions | settling (s) | recording (s) | duration (s) | reserve |\n",
    );
    s.push_str("|---:|---|---:|---:|---:|---:|---:|---:|---|\n");
    let mut i = 0;
    for (k, m) in plan.mountings.iter().enumerate() {
        if k == 1 {
            let _ = writeln!(
                s,
                "| | turn the PIGA round | | | | | | {:.1} | |",
                plan.remount_s
            );
        }
        for q in &m.points {
            i += 1;
            let _ = writeln!(
                s,
                "| {i} | {} | {} | {:.4} | {} | {:.1} | {:.1} | {:.1} | {} |",
                m.orientation.label(),
                m.radius_m,
                q.rate_deg_s,
                q.revolutions,
                q.settling_s,
                q.recording_s,
                q.duration_s,
                if q.reserve { "yes" } else { "" }
            );
        }
    }
    let _ = writeln!(s, "| total | | | | | | | {:.1} | |", plan.total_time_s);
    s
}

/// The plan in words, for the terminal.
pub(crate) fn summary(plan: &TwoOrientationPlan) -> String {
    let mut s = String::new();
    let n: usize = plan.mountings.iter().map(|m| m.points.len()).sum();
    let _ = writeln!(
        s,
        "two-orientation plan (IA in and IA out, one joint fit, no probe): {n} points, {:.0} s of {:.0} s including {:.0} s to turn the PIGA round",
        plan.total_time_s, plan.budget_s, plan.remount_s
    );
    let _ = match plan.rates {
        RateGrid::Round { step_deg_s } => writeln!(
            s,
            "rates on a round grid: whole multiples of {step_deg_s} deg/s (for the unrounded optimum, set rates: candidates in the plan file)"
        ),
        RateGrid::Candidates => writeln!(
            s,
            "rates from the plan file's candidates, unrounded (rates: round(step_deg_s: …) puts them on a grid an operator types)"
        ),
    };
    for m in &plan.mountings {
        let _ = writeln!(
            s,
            "{} at {} m: {} points from {} candidates (≤ {:.4} deg/s), {:.0} s recording ({:.0} % of all recording)",
            m.orientation.label(),
            m.radius_m,
            m.points.len(),
            m.candidates,
            m.max_rate_deg_s,
            m.recording_s,
            100.0
                * if m.orientation == accel_model::Orientation::IaIn {
                    plan.recording_share_ia_in
                } else {
                    1.0 - plan.recording_share_ia_in
                }
        );
        let _ = writeln!(
            s,
            "{:>12} {:>11} {:>12} {:>12}",
            "rate deg/s", "revolutions", "recording s", "duration s"
        );
        for q in &m.points {
            let _ = writeln!(
                s,
                "{:>12.4} {:>11} {:>12.1} {:>12.1}{}",
                q.rate_deg_s,
                q.revolutions,
                q.recording_s,
                q.duration_s,
                if q.reserve {
                    "   (reserve, for the lack-of-fit test)"
                } else {
                    ""
                }
            );
        }
    }
    let _ = writeln!(
        s,
        "u(k2) from the PIGA alone {:.4e} rad/(s·g²), {} residual dof, k {:.3}, U95 {:.4e} (target {:.4e}: {})",
        plan.u_k2_rad_s_g2,
        plan.fit_dof,
        plan.k,
        plan.u95_k2_rad_s_g2,
        plan.target_u95_rad_s_g2,
        if plan.target_met { "met" } else { "not met" }
    );
    let _ = writeln!(
        s,
        "total radius growth C = C_r + C_a expected {:.4e} m·s², u(C) from the PIGA alone {:.4e} m·s²",
        plan.c_expected_m_s2, plan.u_c_m_s2
    );
    if plan.u_c_m_s2 > 0.5 * plan.c_expected_m_s2.abs() {
        let _ = writeln!(
            s,
            "  C is not measured usefully by this plan (u(C) is {:.1} × |C|): its rates and times are chosen for k2, not for C",
            plan.u_c_m_s2 / plan.c_expected_m_s2.abs().max(f64::MIN_POSITIVE)
        );
    }
    let _ = writeln!(
        s,
        "  fitting C as well widens u(k2) by a factor {:.2} over C known{}",
        plan.k2_inflation,
        if plan.c_separable {
            ""
        } else {
            ": above 3, the study will warn that C and k2 are not separated (u(k2) above already counts it)"
        }
    );
    let r = &plan.rounding;
    let _ = writeln!(
        s,
        "rounding the rates to the {} deg/s grid costs {:.1} % in u(k2) ({:.4e} unrounded)",
        r.step_deg_s, r.cost_percent, r.u_k2_unrounded_rad_s_g2
    );
    let v = &plan.reserve;
    if v.extra_rates_per_orientation == 0 && v.time_fraction == 0.0 {
        let _ = writeln!(
            s,
            "no lack-of-fit reserve: {} residual dof (reserve: (extra_rates_per_orientation: 2, time_fraction: 0.1) keeps one)",
            v.residual_dof
        );
    } else {
        let _ = writeln!(
            s,
            "lack-of-fit reserve: {} more rates per orientation in the widest gaps and {:.0} % of the recording time spread over every point cost {:.1} % in u(k2) ({:.4e} without); {} residual dof, the fit is reported as lacking above a Birge ratio of {:.2}",
            v.extra_rates_per_orientation,
            100.0 * v.time_fraction,
            v.cost_percent,
            v.u_k2_without_rad_s_g2,
            v.residual_dof,
            v.lack_of_fit_limit
        );
    }
    let p = &plan.probe_method;
    let _ = writeln!(
        s,
        "probe method in the same {:.0} s (IA in only, {} points, compensated with the probe's C_r): u(k2) {:.4e}, U95 {:.4e}; {:.2} × the two-orientation u(k2)",
        p.budget_s,
        p.points.len(),
        p.compensated.u_rad_s_g2,
        p.compensated.u95_rad_s_g2,
        plan.probe_over_two_orientations
    );
    if plan.arm_stretch_m_s2 != 0.0 {
        let _ = writeln!(
            s,
            "  the probe method's k2 is also off by k1·C_a·g/R² = {:.4e} rad/(s·g²): the arm stretch C_a = {:.4e} m·s² the probe does not see",
            plan.probe_method_arm_stretch_error_rad_s_g2, plan.arm_stretch_m_s2
        );
    }
    s
}
