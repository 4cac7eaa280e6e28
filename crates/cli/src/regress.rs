//! `cargo xtask regress`: the study against its expected values.

use std::path::PathBuf;

use anyhow::{Context as _, bail};
use clap::Args;
use report::Expected;
use units::Compact;

use crate::console::Console;
use crate::paths::Places;

/// Arguments of `cargo xtask regress`.
#[derive(Debug, Args)]
pub(crate) struct Regress {
    /// Study configuration. Default: the paper's study.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Expected values. Default: for a study of the checkout's fixtures/studies/, the file of
    /// the same name in fixtures/expected/.
    #[arg(long)]
    expected: Option<PathBuf>,
}

impl Regress {
    pub(crate) fn run(&self, places: &Places) -> anyhow::Result<()> {
        let config = match &self.config {
            Some(c) => c.clone(),
            None => places.paper_study()?,
        };
        let expected_path = match &self.expected {
            Some(p) => p.clone(),
            None => places.expected_for(&config).with_context(|| {
                format!(
                    "no expected values for {} in fixtures/expected/",
                    config.display()
                )
            })?,
        };
        let results = pipeline::run(&crate::study::load(&config)?)?;
        let outcomes = Expected::load(&expected_path)?.compare(&results)?;
        let mut console = Console::stdout();
        let mut failed = 0;
        for o in &outcomes {
            let status = match (o.check.regress, o.passed) {
                (false, _) => "shown",
                (true, true) => "ok",
                (true, false) => "FAIL",
            };
            failed += usize::from(!o.passed);
            // numbers by the one formatter of numbers in messages (units::Compact: the
            // shortest text that reads back to the same f64, plain between 1e-5 and 1e16)
            let actual = o
                .actual
                .map_or_else(|| "missing".to_owned(), |a| Compact(a).to_string());
            writeln!(
                console,
                "{status:>5}  {:<48} expected {} ± {}, got {actual}",
                o.check.path,
                Compact(o.check.value),
                Compact(o.check.tolerance)
            )?;
        }
        if failed > 0 {
            bail!(
                "{failed} of {} checks in {} failed",
                outcomes.len(),
                expected_path.display()
            );
        }
        writeln!(
            console,
            "{} checks pass ({})",
            outcomes.len(),
            expected_path.display()
        )?;
        Ok(())
    }
}
