//! `cargo xtask accuracy`: the least-squares solver against the NIST StRD linear-regression
//! datasets, scored by the log relative error (LRE, correct significant digits).

use std::path::PathBuf;

use anyhow::Context as _;
use identify::strd::{self, Accuracy as Scored};
use identify::{Design, LstsqOptions, lstsq_design};

use crate::console::{Console, ConsoleError};
use crate::paths::Places;

/// The eleven NIST StRD linear-regression datasets, in NIST's order of difficulty.
const DATASETS: [&str; 11] = [
    "Norris", "Pontius", "NoInt1", "NoInt2", "Filip", "Longley", "Wampler1", "Wampler2",
    "Wampler3", "Wampler4", "Wampler5",
];

/// Score the least-squares solver on the NIST StRD linear-regression datasets.
#[derive(Debug, clap::Args)]
pub(crate) struct Accuracy {
    /// Print JSON: {"datasets": [{"name", "min_lre_coef", "min_lre_se", "lre_residual_sd", …}]}.
    #[arg(long)]
    json: bool,
    /// Directory holding Norris.dat … Wampler5.dat
    /// [default: ../shared/reference/nist-strd relative to the workspace root].
    #[arg(long, value_name = "PATH")]
    dir: Option<PathBuf>,
    /// Skip the double-double refinement (plain scaled column-pivoted QR), for comparison.
    #[arg(long)]
    unrefined: bool,
    /// Round the design to doubles before fitting (powers of x rounded entry by entry), for
    /// comparison.
    #[arg(long)]
    rounded_design: bool,
}

impl Accuracy {
    pub(crate) fn run(&self, places: &Places) -> anyhow::Result<()> {
        let dir = self
            .dir
            .clone()
            .or_else(|| places.nist_strd())
            .unwrap_or_else(|| "nist-strd".into());
        anyhow::ensure!(
            dir.is_dir(),
            "NIST StRD directory {} not found (use --dir)",
            dir.display()
        );
        let options = LstsqOptions {
            refine: !self.unrefined,
            ..LstsqOptions::default()
        };
        let mut results = Vec::with_capacity(DATASETS.len());
        for name in DATASETS {
            let path = dir.join(format!("{name}.dat"));
            let text = std::fs::read_to_string(&path)
                .with_context(|| format!("reading {}", path.display()))?;
            let dataset =
                strd::parse(&text).with_context(|| format!("parsing {}", path.display()))?;
            let design = if self.rounded_design {
                Design::from_matrix(&dataset.design().to_matrix())
            } else {
                dataset.design()
            };
            let fit = lstsq_design(&design, &dataset.y, &options)
                .with_context(|| format!("fitting {}", path.display()))?;
            results.push(dataset.score(fit));
        }
        let mut console = Console::stdout();
        if self.json {
            writeln!(console, "{}", edge_io::to_json_pretty(&to_json(&results))?)?;
        } else {
            print_table(&mut console, &results)?;
        }
        Ok(())
    }
}

fn to_json(results: &[Scored]) -> serde_json::Value {
    let datasets: Vec<serde_json::Value> = results
        .iter()
        .map(|a| {
            serde_json::json!({
                "name": a.name,
                "min_lre_coef": a.min_lre_coef,
                "min_lre_se": a.min_lre_se,
                "lre_residual_sd": a.lre_residual_sd,
                "condition_number": a.fit.condition_number,
                "path": a.fit.path,
                "refinement_iterations": a.fit.refinement_iterations,
                "warnings": a.fit.warnings,
            })
        })
        .collect();
    serde_json::json!({ "datasets": datasets })
}

fn print_table(console: &mut Console, results: &[Scored]) -> Result<(), ConsoleError> {
    writeln!(
        console,
        "NIST StRD linear regression: LRE = correct significant digits (capped at 15)"
    )?;
    writeln!(
        console,
        "{:<9} {:>9} {:>9} {:>9} {:>10} {:>6}  path",
        "dataset", "coef min", "s.e. min", "resid sd", "cond", "iters"
    )?;
    for a in results {
        let warn = if a.fit.warnings.is_empty() {
            String::new()
        } else {
            let words: Vec<String> = a.fit.warnings.iter().map(ToString::to_string).collect();
            format!("  warning: {}", words.join("; "))
        };
        writeln!(
            console,
            "{:<9} {:>9.1} {:>9.1} {:>9.1} {:>10.2e} {:>6}  {}{}",
            a.name,
            a.min_lre_coef,
            a.min_lre_se,
            a.lre_residual_sd,
            a.fit.condition_number,
            a.fit.refinement_iterations,
            a.fit.path,
            warn
        )?;
    }
    let worst = |f: fn(&Scored) -> f64| results.iter().map(f).fold(f64::INFINITY, f64::min);
    writeln!(
        console,
        "minimum over all datasets: coefficients {:.1}, standard errors {:.1}, residual sd {:.1}",
        worst(|a| a.min_lre_coef),
        worst(|a| a.min_lre_se),
        worst(|a| a.lre_residual_sd)
    )?;
    Ok(())
}
