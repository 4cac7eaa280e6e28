//! `cargo xtask plan`: the test plan of a calibration campaign (issue 13) — rate points,
//! revolutions, predicted U95(k2) with and without compensation, the largest acceptable |C_r|
//! and the test-uncertainty ratio — with its run sheet, and optionally its check by
//! simulation.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use planning::{Allocation, Plan, PlanInputs, SimulationCheck};

use crate::console::Console;
use crate::paths::Places;

/// Files `plan` writes into its output directory.
const PLAN_FILES: &[&str] = &["plan.json", "run_sheet.csv", "run_sheet.md"];

/// Arguments of `cargo xtask plan`.
#[derive(Debug, clap::Args)]
pub(crate) struct PlanCmd {
    /// Plan file (RON), e.g. fixtures/plans/paper-centrifuge.ron. See docs/PLANNING.md.
    #[arg(long)]
    config: PathBuf,
    /// Print plan.json to standard output instead of the summary.
    #[arg(long)]
    json: bool,
    /// Output directory. Default: target/plan (of the workspace for `cargo xtask`, of the
    /// current directory for `centrifuge-cal`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also evaluate these rates (deg/s, comma-separated; e.g. the paper's six) within the
    /// same budget, with the optimal allocation and with equal revolutions.
    #[arg(long, value_delimiter = ',')]
    compare_rates: Vec<f64>,
    /// Check the prediction by simulating the plan's campaign this many times (the
    /// noise-free outputs through the exact chain, `simulate::piga_table`).
    #[arg(long)]
    simulate: Option<usize>,
    /// Seed of the simulated campaigns.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// Latitude of the simulated centrifuge, degrees (the Coriolis term it adds is ∝ ω and the ω
/// column absorbs it).
const LATITUDE_DEG: f64 = 45.0;

impl PlanCmd {
    pub(crate) fn run(&self, places: &Places) -> anyhow::Result<()> {
        let inputs = load(&self.config)?;
        if let Some(n) = self.simulate {
            // Before the search: a count beyond the cap is refused with its cost, at once.
            let kind = if inputs.two_orientation.is_some() {
                planning::CampaignKind::TwoOrientations
            } else {
                planning::CampaignKind::OneOrientation
            };
            planning::check_campaigns(n, kind).with_context(|| format!("--simulate {n}"))?;
        }
        if inputs.two_orientation.is_some() {
            return self.run_two(&inputs, places);
        }
        let context = || format!("planning {}", self.config.display());
        let plan = planning::plan(&inputs).with_context(context)?;
        let mut comparison = Vec::new();
        if !self.compare_rates.is_empty() {
            for allocation in [Allocation::Optimal, Allocation::EqualRevolutions] {
                let e = planning::evaluate_rates(&inputs, &self.compare_rates, allocation)
                    .with_context(|| "evaluating --compare-rates".to_owned())?;
                comparison.push(serde_json::json!({
                    "allocation": match allocation {
                        Allocation::Optimal => "optimal",
                        Allocation::EqualRevolutions => "equal_revolutions",
                    },
                    "rates_deg_s": e.rates_deg_s,
                    "revolutions": e.revolutions,
                    "u_k2_fit_rad_s_g2": e.u_k2_fit_rad_s_g2,
                    "u_ratio_to_plan": e.u_k2_fit_rad_s_g2 / plan.u_k2_fit_rad_s_g2,
                }));
            }
        }
        let check = match self.simulate {
            Some(n) => {
                let spinner = crate::progress::spinner(format!("simulating the plan {n} times"));
                let check = simulate_check(&inputs, &plan, n, self.seed);
                spinner.finish_and_clear();
                Some(check?)
            }
            None => None,
        };
        let mut value = serde_json::json!({
            "config": self.config.display().to_string(),
            "plan": plan,
        });
        if !comparison.is_empty() {
            value["comparison"] = serde_json::Value::Array(comparison);
        }
        if let Some(c) = &check {
            value["simulation"] = serde_json::to_value(c)?;
        }
        let json = serde_json::to_string_pretty(&value)?;
        let out = self.out.clone().unwrap_or_else(|| places.output("plan"));
        let mut set = edge_io::OutputSet::create(&out, PLAN_FILES)?;
        set.write("plan.json", json.as_bytes())?;
        set.write("run_sheet.csv", run_sheet_csv(&plan).as_bytes())?;
        set.write("run_sheet.md", run_sheet_md(&plan).as_bytes())?;
        set.commit()
            .with_context(|| format!("writing the plan into {}", out.display()))?;
        let mut console = Console::stdout();
        if self.json {
            writeln!(console, "{json}")?;
        } else {
            let mut text = summary(&plan);
            for c in value
                .get("comparison")
                .and_then(|v| v.as_array())
                .into_iter()
                .flatten()
            {
                let _ = writeln!(
                    text,
                    "--compare-rates with {} allocation: u(k2) of the fit {:.4e} ({:.3} × the plan's)",
                    c["allocation"].as_str().unwrap_or_default(),
                    c["u_k2_fit_rad_s_g2"].as_f64().unwrap_or_default(),
                    c["u_ratio_to_plan"].as_f64().unwrap_or_default()
                );
            }
            if let Some(c) = &check {
                text.push_str(&check_text(c));
            }
            write!(console, "{text}")?;
            writeln!(
                console,
                "wrote plan.json, run_sheet.csv and run_sheet.md into {}",
                out.display()
            )?;
        }
        Ok(())
    }
}

impl PlanCmd {
    /// A plan file with `two_orientation`: the two-orientation plan beside the probe
    /// method's in the same budget (`--compare-rates` evaluates rates for the probe method).
    fn run_two(&self, inputs: &PlanInputs, places: &Places) -> anyhow::Result<()> {
        let context = || format!("planning {}", self.config.display());
        let plan = planning::plan_two_orientation(inputs).with_context(context)?;
        let mut comparison = Vec::new();
        if !self.compare_rates.is_empty() {
            let e = planning::evaluate_rates(inputs, &self.compare_rates, Allocation::Optimal)
                .with_context(|| "evaluating --compare-rates".to_owned())?;
            comparison.push(serde_json::json!({
                "method": "probe",
                "allocation": "optimal",
                "rates_deg_s": e.rates_deg_s,
                "revolutions": e.revolutions,
                "u_k2_fit_rad_s_g2": e.u_k2_fit_rad_s_g2,
                "u_ratio_to_plan": e.u_k2_fit_rad_s_g2 / plan.probe_method.u_k2_fit_rad_s_g2,
            }));
        }
        let check = match self.simulate {
            Some(n) => {
                let spinner = crate::progress::spinner(format!(
                    "simulating the two-orientation plan {n} times"
                ));
                let check = crate::plan_two_orientation::simulate_check(
                    inputs,
                    &plan,
                    n,
                    self.seed,
                    LATITUDE_DEG,
                );
                spinner.finish_and_clear();
                Some(check?)
            }
            None => None,
        };
        let mut value = serde_json::json!({
            "config": self.config.display().to_string(),
            "two_orientation": plan,
        });
        if !comparison.is_empty() {
            value["comparison"] = serde_json::Value::Array(comparison.clone());
        }
        if let Some(c) = &check {
            value["simulation"] = serde_json::to_value(c)?;
        }
        let json = serde_json::to_string_pretty(&value)?;
        let out = self.out.clone().unwrap_or_else(|| places.output("plan"));
        let mut set = edge_io::OutputSet::create(&out, PLAN_FILES)?;
        set.write("plan.json", json.as_bytes())?;
        set.write(
            "run_sheet.csv",
            crate::plan_two_orientation::run_sheet_csv(&plan).as_bytes(),
        )?;
        set.write(
            "run_sheet.md",
            crate::plan_two_orientation::run_sheet_md(&plan).as_bytes(),
        )?;
        set.commit()
            .with_context(|| format!("writing the plan into {}", out.display()))?;
        let mut console = Console::stdout();
        if self.json {
            writeln!(console, "{json}")?;
            return Ok(());
        }
        let mut text = crate::plan_two_orientation::summary(&plan);
        for c in &comparison {
            let _ = writeln!(
                text,
                "--compare-rates for the probe method with optimal allocation: u(k2) of the fit {:.4e} ({:.3} × the probe plan's)",
                c["u_k2_fit_rad_s_g2"].as_f64().unwrap_or_default(),
                c["u_ratio_to_plan"].as_f64().unwrap_or_default()
            );
        }
        if let Some(c) = &check {
            text.push_str(&format!(
                "simulation: {} two-orientation campaigns through the exact chain, each fitted as the study does: SD of k2 {:.4e} against predicted u {:.4e}: ratio {:.4} (± {:.4} from the number of campaigns)\n",
                c.campaigns,
                c.simulated_sd_rad_s_g2,
                c.predicted_u_rad_s_g2,
                c.ratio,
                c.ratio_standard_error
            ));
        }
        write!(console, "{text}")?;
        writeln!(
            console,
            "wrote plan.json, run_sheet.csv and run_sheet.md into {}",
            out.display()
        )?;
        Ok(())
    }
}

/// Reads a plan file (RON, size-capped, the workspace's dialect `edge_io::ron_options`).
fn load(path: &Path) -> anyhow::Result<PlanInputs> {
    let text = edge_io::read_text_capped(path, edge_io::CONFIG_MAX_BYTES)?;
    Ok(edge_io::from_ron(&text, path)?)
}

/// The plan simulated `campaigns` times, its noise-free outputs through the exact chain.
fn simulate_check(
    inputs: &PlanInputs,
    plan: &Plan,
    campaigns: usize,
    seed: u64,
) -> anyhow::Result<SimulationCheck> {
    let (centrifuge, piga) = inputs.simulated(LATITUDE_DEG);
    let rates: Vec<f64> = plan.points.iter().map(|q| q.rate_deg_s).collect();
    let table = simulate::piga_table(
        &centrifuge,
        &piga,
        &rates,
        &simulate::OutputNoise {
            sigma_rad_s: 0.0,
            seed,
        },
    )
    .context("the noise-free PIGA table")?;
    let outputs: Vec<f64> = table.iter().map(|r| r.output_rad_s).collect();
    Ok(planning::simulate_plan(plan, &outputs, campaigns, seed)?)
}

fn run_sheet_csv(plan: &Plan) -> String {
    let mut s = String::from(
        "point,rate_deg_s,revolutions,settling_s,recording_s,duration_s,sigma_mean_rad_s\n",
    );
    for (i, q) in plan.points.iter().enumerate() {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{:e}",
            i + 1,
            q.rate_deg_s,
            q.revolutions,
            q.settling_s,
            q.recording_s,
            q.duration_s,
            q.sigma_mean_rad_s
        );
    }
    s
}

fn run_sheet_md(plan: &Plan) -> String {
    let mut s = String::from("# Run sheet\n\n");
    let _ = writeln!(
        s,
        "{} points, {:.0} s of {:.0} s budget; predicted U95(k2) = {:.3e} rad/(s·g²) compensated, \
         {:.3e} uncompensated (plus the bias Δk2 = {:.3e}).\n",
        plan.points.len(),
        plan.total_time_s,
        plan.budget_s,
        plan.compensated.u95_rad_s_g2,
        plan.uncompensated.u95_rad_s_g2,
        plan.delta_k2_expected_rad_s_g2
    );
    s.push_str(
        "| point | rate (deg/s) | revolutions | settling (s) | recording (s) | duration (s) |\n",
    );
    s.push_str("|---:|---:|---:|---:|---:|---:|\n");
    for (i, q) in plan.points.iter().enumerate() {
        let _ = writeln!(
            s,
            "| {} | {:.4} | {} | {:.1} | {:.1} | {:.1} |",
            i + 1,
            q.rate_deg_s,
            q.revolutions,
            q.settling_s,
            q.recording_s,
            q.duration_s
        );
    }
    let _ = writeln!(s, "| total | | | | | {:.1} |", plan.total_time_s);
    s
}

fn summary(plan: &Plan) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "plan: {} points from {} candidates (≤ {:.4} deg/s), criterion: {}; {:.0} s of {:.0} s",
        plan.points.len(),
        plan.candidates,
        plan.max_rate_deg_s,
        plan.criterion,
        plan.total_time_s,
        plan.budget_s
    );
    let _ = writeln!(
        s,
        "{:>12} {:>11} {:>12} {:>12}",
        "rate deg/s", "revolutions", "recording s", "duration s"
    );
    for q in &plan.points {
        let _ = writeln!(
            s,
            "{:>12.4} {:>11} {:>12.1} {:>12.1}",
            q.rate_deg_s, q.revolutions, q.recording_s, q.duration_s
        );
    }
    let _ = writeln!(
        s,
        "u(k2) of the fit {:.4e} rad/(s·g²) ({:.4e} with equal revolutions); {} residual dof",
        plan.u_k2_fit_rad_s_g2, plan.u_k2_fit_equal_revolutions_rad_s_g2, plan.fit_dof
    );
    let _ = writeln!(
        s,
        "compensated:   u(k2) {:.4e}, ν_eff {:.1}, k {:.3}, U95 {:.4e} (target {:.4e}, Type B floor {:.4e})",
        plan.compensated.u_rad_s_g2,
        plan.compensated.dof,
        plan.compensated.k,
        plan.compensated.u95_rad_s_g2,
        plan.target_u95_rad_s_g2,
        plan.type_b_floor_u95_rad_s_g2
    );
    let _ = writeln!(
        s,
        "uncompensated: u(k2) {:.4e}, U95 {:.4e}, plus the bias Δk2 = k1·C_r·g/R² = {:.4e}",
        plan.uncompensated.u_rad_s_g2,
        plan.uncompensated.u95_rad_s_g2,
        plan.delta_k2_expected_rad_s_g2
    );
    let _ = writeln!(
        s,
        "largest |C_r| with |Δk2| ≤ {} × U95 uncompensated: {:.4e} m·s² (expected C_r {} it)",
        plan.bias_fraction,
        plan.c_r_limit_m_s2,
        if plan.c_r_within_limit {
            "within"
        } else {
            "beyond"
        }
    );
    let _ = writeln!(
        s,
        "test-uncertainty ratio (tolerance/U95): {:.2}:1 compensated, {:.2}:1 uncompensated (4:1 recommended)",
        plan.tur_compensated, plan.tur_uncompensated
    );
    s
}

fn check_text(c: &SimulationCheck) -> String {
    format!(
        "simulation: {} campaigns, SD of k2 {:.4e} against predicted u {:.4e}: ratio {:.4} (± {:.4} from the number of campaigns)\n",
        c.campaigns,
        c.simulated_sd_rad_s_g2,
        c.predicted_u_rad_s_g2,
        c.ratio,
        c.ratio_standard_error
    )
}
