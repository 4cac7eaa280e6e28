//! `centrifuge-cal history`: a unit's certified coefficients across its certificates (drift,
//! prediction, recommended interval), or a centrifuge's health (C_r, offset and Δk2 by date,
//! whether to rebalance before the next campaign); as text, JSON and an SVG chart.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;
use records::{Access, Database, Date, HealthOptions, HistoryOptions, IntervalRequest};

use crate::console::Console;
use crate::record::RecordsFile;

/// The share of the target U95 that Δk2 may reach, when `--share` is not given (the command
/// line's and the Python package's default).
pub const DEFAULT_SHARE: f64 = 0.2;

/// Arguments of `centrifuge-cal history`.
#[derive(Debug, Args)]
pub(crate) struct History {
    /// The unit: its serial number, or MODEL/SERIAL.
    #[arg(required_unless_present = "centrifuge", conflicts_with = "centrifuge")]
    unit: Option<String>,
    /// A centrifuge's health instead of a unit's history.
    #[arg(long, value_name = "NAME")]
    centrifuge: Option<String>,
    #[command(flatten)]
    records: RecordsFile,
    /// The date to predict the unit's coefficients at (YYYY-MM-DD). Default: the end of the
    /// recommended interval, else one year after the latest certificate.
    #[arg(long, conflicts_with = "centrifuge")]
    at: Option<String>,
    /// The term of the recommended interval (k0, k1, k2, k3; `k0 (ia_out)` for one mounting's).
    #[arg(long, requires = "tolerance", conflicts_with = "centrifuge")]
    term: Option<String>,
    /// The tolerance on the term's deviation from the value certified, in its unit.
    #[arg(long, requires = "term")]
    tolerance: Option<f64>,
    /// The reliability target of the interval: the probability of being within the tolerance
    /// at its end.
    #[arg(long, default_value_t = 0.95, requires = "term")]
    reliability: f64,
    /// The U95 of k2 the calibration is to meet, rad/(s·g²): Δk2 is compared with a share of it.
    #[arg(long, value_name = "RAD_S_G2", requires = "centrifuge")]
    target_u95: Option<f64>,
    /// The share of the target U95 that Δk2 may reach before a rebalance is advised
    /// (0 < share ≤ 1). Default: 0.2.
    #[arg(long, requires = "target_u95")]
    share: Option<f64>,
    /// The date of the next campaign (YYYY-MM-DD). Default: the latest campaign plus the mean
    /// spacing of the campaigns since the latest balance.
    #[arg(long, requires = "centrifuge")]
    next: Option<String>,
    /// Print JSON instead of the text.
    #[arg(long)]
    json: bool,
    /// Write the chart (SVG) to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
}

fn date(field: &str, text: Option<&str>) -> anyhow::Result<Option<Date>> {
    text.map(|t| Date::parse_field(field, t))
        .transpose()
        .map_err(anyhow::Error::new)
}

impl History {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let (path, default) = self.records.resolve()?;
        let db = Database::open(&path, Access::Existing)?;
        let mut console = Console::stdout();
        if let Some(name) = &self.centrifuge {
            let share = self.share.unwrap_or(DEFAULT_SHARE);
            let health = records::centrifuge_health(
                db.centrifuge_records(name)?,
                &HealthOptions {
                    target_u95_rad_s_g2: self.target_u95,
                    share,
                    next: date("--next", self.next.as_deref())?,
                },
            )?;
            if let Some(svg) = &self.svg {
                let text = report::health_svg(&health)?;
                std::fs::write(svg, text).with_context(|| format!("writing {}", svg.display()))?;
            }
            if self.json {
                writeln!(console, "{}", edge_io::to_json_pretty(&health)?)?;
                return Ok(());
            }
            if let Some(words) = default {
                writeln!(console, "records: {} ({words})", path.display())?;
            }
            write!(console, "{}", report::health_text(&health))?;
            if self.target_u95.is_some() && self.share.is_none() {
                writeln!(
                    console,
                    "(the share of the target U95 is the default, {:.0} %: --share to change it)",
                    DEFAULT_SHARE * 100.0
                )?;
            }
            if let Some(svg) = &self.svg {
                writeln!(console, "wrote {}", svg.display())?;
            }
            return Ok(());
        }
        let unit = self
            .unit
            .as_deref()
            .context("give a unit or --centrifuge")?;
        let interval = match (&self.term, self.tolerance) {
            (Some(term), Some(tolerance)) => Some((
                term.clone(),
                IntervalRequest {
                    tolerance,
                    reliability: self.reliability,
                },
            )),
            _ => None,
        };
        let history = records::unit_history(
            db.unit_records(unit)?,
            &HistoryOptions {
                at: date("--at", self.at.as_deref())?,
                interval,
            },
        )?;
        if let Some(svg) = &self.svg {
            let text = report::history_svg(&history)?;
            std::fs::write(svg, text).with_context(|| format!("writing {}", svg.display()))?;
        }
        if self.json {
            writeln!(console, "{}", edge_io::to_json_pretty(&history)?)?;
            return Ok(());
        }
        if let Some(words) = default {
            writeln!(console, "records: {} ({words})", path.display())?;
        }
        write!(console, "{}", report::history_text(&history))?;
        if let Some(svg) = &self.svg {
            writeln!(console, "wrote {}", svg.display())?;
        }
        Ok(())
    }
}
