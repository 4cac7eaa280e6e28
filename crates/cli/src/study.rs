//! `cargo xtask study`: the pre/post-balance study.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::Args;
use pipeline::{Progress, StudyResults};
use report::Expected;

use crate::console::{Console, ConsoleError};
use crate::paths::Places;

/// Arguments of `cargo xtask study`.
#[derive(Debug, Args)]
pub(crate) struct Study {
    /// Study configuration (RON). Default: the paper's study, fixtures/studies/paper-2025.ron.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Output directory. Default: target/study (of the workspace for `cargo xtask`, of the
    /// current directory for `centrifuge-cal`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Values to show beside the computed ones in the report. Default: for a study of the
    /// checkout's fixtures/studies/, the file of the same name in fixtures/expected/.
    #[arg(long)]
    expected: Option<PathBuf>,
    /// Do not compare with expected values.
    #[arg(long, conflicts_with = "expected")]
    no_compare: bool,
    /// Record the study in this records database once its outputs are written
    /// (`centrifuge-cal record`; docs/RECORDS.md). A study that fails records nothing.
    #[arg(long, value_name = "FILE")]
    records: Option<PathBuf>,
}

impl Study {
    pub(crate) fn run(&self, places: &Places) -> anyhow::Result<()> {
        let config = match &self.config {
            Some(c) => c.clone(),
            None => places.paper_study()?,
        };
        let out = self.out.clone().unwrap_or_else(|| places.output("study"));
        let study = load(&config)?;
        // A spinner from the start (fits and the Monte Carlo take their time), a bar while
        // recordings are analysed; nothing when standard error is not a terminal.
        let bar = crate::progress::spinner("running the study");
        let results = pipeline::run_with_progress(&study, &|event| match event {
            Progress::Recordings { total } => {
                crate::progress::to_bar(&bar, total as u64, "recordings analyzed");
            }
            Progress::RecordingDone { path, .. } => {
                bar.inc(1);
                bar.set_message(
                    path.file_name()
                        .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
                );
                if bar.length().is_some_and(|len| bar.position() >= len) {
                    crate::progress::to_spinner(
                        &bar,
                        "fitting, and the uncertainty (GUM and Monte Carlo)",
                    );
                }
            }
            _ => {}
        })?;
        bar.finish_and_clear();
        let expected_path = if self.no_compare {
            None
        } else {
            self.expected
                .clone()
                .or_else(|| places.expected_for(&config))
        };
        let (expected, expected_record) = expected_path
            .as_deref()
            .map(Expected::load_recorded)
            .transpose()?
            .unzip();
        let outcomes = expected.as_ref().map(|e| e.compare(&results)).transpose()?;
        let provenance = report::Provenance::of_study(&study, expected_record.as_ref())?;
        // a several-unit study: each unit's provenance is the configuration and the files its
        // numbers come from (the probe recordings and its own data)
        let unit_provenance = study
            .units()
            .map(|(_, unit)| report::Provenance::of_study(unit, None))
            .collect::<report::Result<Vec<_>>>()?;
        let files = report::write_outputs_with_units(
            &out,
            &results,
            expected.as_ref(),
            outcomes.as_deref(),
            Some(&provenance),
            &unit_provenance,
        )
        .with_context(|| format!("writing the study's outputs into {}", out.display()))?;
        let mut console = Console::stdout();
        print_summary(&mut console, &results)?;
        // The calibration's summary (issue 19): after the tables, before the regression line
        // and the list of files written.
        if let Some(summary) = report::summary_text(&results) {
            writeln!(console)?;
            write!(console, "{summary}")?;
        }
        if let Some(outcomes) = &outcomes {
            let failed = outcomes.iter().filter(|o| !o.passed).count();
            writeln!(
                console,
                "regression: {} of {} checks against {} pass",
                outcomes.len() - failed,
                outcomes.len(),
                expected_path
                    .as_deref()
                    .unwrap_or(config.as_path())
                    .display()
            )?;
        }
        writeln!(
            console,
            "wrote {}, {}, {}",
            files.results_json.display(),
            files.report_md.display(),
            files.radius_error_svg.display()
        )?;
        for svg in &files.probe_signals_svg {
            writeln!(console, "wrote {}", svg.display())?;
        }
        if let Some(svg) = &files.balance_polar_svg {
            writeln!(console, "wrote {}", svg.display())?;
        }
        if let Some(pdf) = &files.certificate_pdf {
            writeln!(console, "wrote {}", pdf.display())?;
        }
        if let Some(xml) = &files.certificate_dcc {
            writeln!(console, "wrote {}", xml.display())?;
        }
        for (label, unit) in &files.units {
            let mut names = vec![unit.results_json.display().to_string()];
            names.extend(unit.certificate_pdf.iter().map(|p| p.display().to_string()));
            names.extend(unit.certificate_dcc.iter().map(|p| p.display().to_string()));
            writeln!(
                console,
                "wrote unit {label}: {} (and its report and figures)",
                names.join(", ")
            )?;
        }
        if let Some(db_path) = &self.records {
            let recorded = records::Database::open(db_path, records::Access::CreateIfMissing)
                .map_err(anyhow::Error::new)
                .and_then(|mut db| {
                    crate::record::record_dir(&mut db, &out, &crate::record::Extra::default())
                })
                .with_context(|| {
                    format!(
                        "the study's outputs are written in {}, but recording them failed; \
                         record them with `centrifuge-cal record {} --records {}`",
                        out.display(),
                        out.display(),
                        db_path.display()
                    )
                })?;
            for (study, outcome) in &recorded {
                crate::record::print_outcome(&mut console, db_path, None, study, outcome)?;
            }
        }
        Ok(())
    }
}

/// The study of a configuration, refused while it holds a placeholder of `init`; every
/// configuration problem at once, grouped (the same fault in several files is one entry).
pub(crate) fn load(config: &Path) -> anyhow::Result<pipeline::Inputs> {
    // Read once: the digest of these bytes is the configuration's provenance.
    let bytes = edge_io::read_bytes_capped(config, pipeline::MAX_STUDY_BYTES)?;
    let digest = pipeline::FileDigest::of(&bytes);
    let text = edge_io::text_from_bytes(config, bytes)?;
    let left = crate::init::config::placeholders(&text);
    if !left.is_empty() {
        let lines: Vec<String> = left.iter().map(|l| format!("  {}", l.words())).collect();
        anyhow::bail!(
            "{}: {} value{} not filled in ({}); answer {}, then `check` lists anything \
             else:\n{}",
            config.display(),
            left.len(),
            if left.len() == 1 { " is" } else { "s are" },
            crate::init::PLACEHOLDER,
            if left.len() == 1 { "it" } else { "them" },
            lines.join("\n")
        );
    }
    let study = pipeline::parse_study(&text, config).map_err(|e| match &e {
        pipeline::PipelineError::Several { errors } => anyhow::anyhow!(
            "{}: {} problems ({} distinct):\n{}",
            config.display(),
            errors.len(),
            crate::problems::group(&crate::problems::each(&e)).len(),
            crate::problems::render(&crate::problems::each(&e)).trim_end()
        ),
        _ => anyhow::Error::new(e),
    })?;
    Ok(study.with_config_digest(digest))
}

/// Prints the summary table.
fn print_summary(out: &mut Console, results: &StudyResults) -> Result<(), ConsoleError> {
    writeln!(out, "study {}", results.study)?;
    for w in &results.warnings {
        writeln!(out, "warning[{}] {}: {}", w.code, w.location, w.message)?;
    }
    let f =
        |x: Option<f64>, prec: usize| x.map_or_else(|| "—".to_owned(), |v| format!("{v:.prec$}"));
    for phase in &results.phases {
        writeln!(out)?;
        writeln!(out, "phase {}", phase.name)?;
        writeln!(
            out,
            "{:>10} {:>9} {:>9} {:>9} {:>9} {:>12}",
            "rate deg/s", "d_c1 µm", "d_s1 µm", "ΔR1 µm", "β deg", "Δr µm"
        )?;
        for p in &phase.points {
            writeln!(
                out,
                "{:>10} {:>9} {:>9} {:>9} {:>9} {:>12.4}",
                p.rate_deg_s,
                f(p.dc1_um, 4),
                f(p.ds1_um, 4),
                f(p.amplitude_um, 4),
                f(p.beta_deg, 3),
                p.radius_error_um
            )?;
        }
    }
    writeln!(out)?;
    writeln!(
        out,
        "{:<13} {:<18} {:>12} {:>11} {:>14} {:>11}",
        "phase", "model", "C_r m·s²", "σ(C_r)", "Δk2 rad/s/g²", "σ(Δk2)"
    )?;
    let e = |x: Option<f64>| x.map_or_else(|| "—".to_owned(), |v| format!("{v:.3e}"));
    for phase in &results.phases {
        let name = &phase.name;
        for fit in std::iter::once(&phase.fit).chain(phase.alternative.as_ref()) {
            writeln!(
                out,
                "{:<13} {:<18} {:>12.4e} {:>11} {:>14.3e} {:>11}",
                name,
                fit.model.to_string(),
                fit.c_r_m_s2,
                e(fit.c_r_sigma_m_s2),
                fit.delta_k2_rad_s_g2,
                e(fit.delta_k2_sigma_rad_s_g2)
            )?;
        }
    }
    if let Some(units) = &results.units {
        writeln!(
            out,
            "(Δk2 above at the study's k1 = {} rad/(s·g) and R = {} m; each unit's, at its own \
             k1 and radius, in its summary below)",
            results.inputs.k1_rad_s_g, results.inputs.radius_m
        )?;
        for u in units {
            let k2 = u.k2.map_or_else(
                || "—".to_owned(),
                |k| format!("k2 = {:.4e} ± {:.2e} rad/(s·g²) (U95)", k.value, k.u95),
            );
            writeln!(
                out,
                "unit {}: {}, certificate {}, {k2}",
                u.label,
                edge_io::visible(u.item.as_deref().unwrap_or("no certificate item")),
                edge_io::visible(u.certificate.as_deref().unwrap_or("none"))
            )?;
        }
    }
    writeln!(out)?;
    Ok(())
}
