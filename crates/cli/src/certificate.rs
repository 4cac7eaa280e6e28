//! `centrifuge-cal certificate RESULTS_DIR [--out FILE.pdf]`: the calibration certificate of
//! a study's results folder, typeset again from its results.json (PDF/A-2b, no browser), and
//! optionally its pages as PNG images for a screen.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;

use crate::console::Console;

/// Arguments of `certificate`.
#[derive(Debug, Args)]
pub(crate) struct Certificate {
    /// The folder a study wrote (holding results.json), or its results.json.
    results: PathBuf,
    /// Where to write the PDF. Default: certificate.pdf in the results folder. A folder that
    /// does not exist yet is created; an existing folder gets certificate.pdf inside it.
    #[arg(long, value_name = "FILE.pdf")]
    out: Option<PathBuf>,
    /// Also write each page as a PNG image into this folder (certificate-page-1.png, …), as
    /// the typesetter draws it.
    #[arg(long, value_name = "DIR")]
    png: Option<PathBuf>,
    /// Resolution of the PNG pages, pixels per inch.
    #[arg(long, default_value_t = 110.0, requires = "png")]
    dpi: f32,
}

impl Certificate {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let written = report::write_certificate(&self.results, self.out.as_deref())?;
        let mut console = Console::stdout();
        writeln!(console, "wrote {}", written.display())?;
        if let Some(dir) = &self.png {
            if !(self.dpi.is_finite() && (10.0..=600.0).contains(&self.dpi)) {
                anyhow::bail!(
                    "--dpi {}: give a resolution from 10 to 600 pixels per inch",
                    self.dpi
                );
            }
            let saved = report::read_results(&self.results)?;
            let document = report::certificate_document(
                &saved.results,
                saved.provenance.as_ref(),
                &report::Software::this_build(),
            )?;
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
            for (n, png) in document.png_pages(self.dpi)?.iter().enumerate() {
                let path = dir.join(format!("certificate-page-{}.png", n + 1));
                std::fs::write(&path, png)
                    .with_context(|| format!("writing {}", path.display()))?;
                writeln!(console, "wrote {}", path.display())?;
            }
        }
        Ok(())
    }
}
