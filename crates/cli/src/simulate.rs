//! `cargo xtask simulate`: closed-loop simulation of a calibration from a scenario.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use simulate::Scenario;

use crate::console::Console;
use crate::paths::Places;

/// Arguments of `cargo xtask simulate`.
#[derive(Debug, Args)]
pub(crate) struct Simulate {
    /// Scenario (RON), e.g. fixtures/scenarios/post-balance.ron. See docs/SIMULATION.md.
    #[arg(long)]
    config: PathBuf,
    /// Output directory. Default: target/simulate (of the workspace for `cargo xtask`, of the
    /// current directory for `centrifuge-cal`).
    #[arg(long)]
    out: Option<PathBuf>,
}

impl Simulate {
    pub(crate) fn run(&self, places: &Places) -> anyhow::Result<()> {
        let out = self
            .out
            .clone()
            .unwrap_or_else(|| places.output("simulate"));
        let scenario = Scenario::load(&self.config)?;
        let spinner = crate::progress::spinner(format!("simulating {}", scenario.scenario.name));
        let sim = simulate::simulate(&scenario);
        spinner.finish_and_clear();
        let sim = sim?;
        let files = simulate::write_simulation(&out, &sim)
            .with_context(|| format!("writing the simulation into {}", out.display()))?;

        let t = &sim.truth;
        let mut console = Console::stdout();
        writeln!(
            console,
            "scenario {} (seed {})",
            t.scenario.name, t.scenario.seed
        )?;
        writeln!(
            console,
            "C_r = {:.6e} m·s², Δk2 = k1·C_r·g/R² = {:.6e} rad/(s·g²), apparent k2 = {:.6e}",
            t.c_r_m_s2, t.delta_k2_predicted_rad_s_g2, t.k2_apparent_predicted_rad_s_g2
        )?;
        writeln!(console)?;
        writeln!(
            console,
            "{:>10} {:>5} {:>9} {:>10} {:>10} {:>12} {:>18}",
            "rate deg/s", "revs", "samples", "d_c1 µm", "d_s1 µm", "Δr_x µm", "output rad/s"
        )?;
        for r in &t.rates {
            writeln!(
                console,
                "{:>10.4} {:>5} {:>9} {:>10.4} {:>10.4} {:>12.6} {:>18.12}",
                r.rate_deg_s,
                r.revolutions,
                r.samples,
                r.probe_first_harmonic.dc1_um,
                r.probe_first_harmonic.ds1_um,
                r.radius_error_um,
                r.output_rad_s
            )?;
        }
        writeln!(console)?;
        if files.piga_recordings.is_empty() {
            writeln!(
                console,
                "wrote {} recordings, {} and {}",
                files.recordings.len(),
                files.piga_csv.display(),
                files.truth_json.display()
            )?;
        } else {
            writeln!(
                console,
                "wrote {} probe recordings, {} raw PIGA output recordings, {} and {}",
                files.recordings.len(),
                files.piga_recordings.len(),
                files.piga_csv.display(),
                files.truth_json.display()
            )?;
        }
        Ok(())
    }
}
