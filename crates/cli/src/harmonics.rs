//! `cargo xtask harmonics FILE --rate-deg-s W`: per-revolution Fourier analysis of one probe
//! recording (eq. 20–21).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::bail;
use harmonics::{Coefficients, FitConfig, ProbeDirection};
use recording::{
    AngleSource, AngleSourceKind, AngleUnit, Delimiter, ReadProgress, RecordingAnalysis,
    RecordingFormat, StreamOptions, StreamedRecording,
};
use serde_json::{Value, json};

use crate::console::Console;

/// Fit eq. 20 to every complete revolution of a probe recording and average the coefficients.
#[derive(Debug, clap::Args)]
pub(crate) struct Harmonics {
    /// The recording, its reader chosen by extension: `.tdms` (NI TDMS), `.mat` (MATLAB
    /// v5/v7), else a delimited text file with a header row (`time_s,gap_um[,angle_deg]` by
    /// default; see `--format` and docs/YOUR-DATA.md).
    file: PathBuf,
    /// Declared spindle rate, deg/s (the angle is `θ = ω·(t − t₀)` when nothing measures it).
    #[arg(long)]
    rate_deg_s: f64,
    /// Highest Fourier order fitted (1 to 8; the paper uses 4).
    #[arg(long, default_value_t = harmonics::DEFAULT_ORDER)]
    order: usize,
    /// Use only the first K complete revolutions (the paper averages 8).
    #[arg(long, value_name = "K")]
    revolutions: Option<usize>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    json: bool,
    /// Also fit a linear drift in time within each revolution.
    #[arg(long)]
    drift: bool,
    /// The probe measures along O1X1 (default: against it, as in the paper); sets the sign of β.
    #[arg(long)]
    probe_along: bool,
    /// What the encoder reads, deg, when the arm's PIGA end points at the probe (a study's
    /// `lever.angle_zero_deg`): measured angles are taken less it before the fit (default 0).
    #[arg(long, allow_negative_numbers = true)]
    angle_zero_deg: Option<f64>,
    /// The recording format, a RON file as in a study's `format: (...)`; the flags below
    /// override its fields.
    #[arg(long, value_name = "FILE.ron")]
    format: Option<PathBuf>,
    /// Field delimiter: one character, or `whitespace` for runs of blanks.
    #[arg(long)]
    delimiter: Option<String>,
    /// Decimal mark: point or comma.
    #[arg(long)]
    decimal: Option<String>,
    /// Lines before the header (instrument metadata).
    #[arg(long)]
    skip_lines: Option<usize>,
    /// Name of the time column (CSV), channel (TDMS) or variable (MAT).
    #[arg(long, visible_alias = "time-channel")]
    time_column: Option<String>,
    /// TDMS: the sample times from the gap channel's `wf_start_offset`/`wf_increment`
    /// properties instead of a time channel.
    #[arg(long)]
    waveform_time: bool,
    /// TDMS: the group holding the channels (default: the first group that has them). MAT: a
    /// struct variable whose fields are the variables (default: top-level variables).
    #[arg(long)]
    group: Option<String>,
    /// Unit of the time column: s, ms, us or ns.
    #[arg(long)]
    time_unit: Option<String>,
    /// Name of the gap column (CSV), channel (TDMS) or variable (MAT).
    #[arg(long, visible_alias = "gap-channel")]
    gap_column: Option<String>,
    /// Unit of the gap column: nm, um, mm or m.
    #[arg(long)]
    gap_unit: Option<String>,
    /// Name of the encoder column (required when given), channel (TDMS) or variable (MAT).
    #[arg(long, visible_alias = "angle-channel")]
    angle_column: Option<String>,
    /// Unit of the encoder column: deg, rad or `counts(per_rev: N)`.
    #[arg(long)]
    angle_unit: Option<String>,
    /// Name of a once-per-revolution index-pulse column (instead of an encoder).
    #[arg(long, conflicts_with = "angle_column")]
    index_pulse: Option<String>,
    /// Angle of the first sample from O1X1, deg: the angle is taken from the declared rate.
    #[arg(long, conflicts_with_all = ["angle_column", "index_pulse"])]
    start_angle_deg: Option<f64>,
    /// Largest sample interval accepted, in nominal (median) intervals.
    #[arg(long)]
    max_gap_intervals: Option<f64>,
    /// What a gap does: error or drop_revolution.
    #[arg(long)]
    on_gap: Option<String>,
    /// What a NaN or infinite sample does: error or drop_revolution.
    #[arg(long)]
    on_non_finite: Option<String>,
}

/// A RON value of a format field given on the command line, e.g. `mm` or
/// `counts(per_rev: 4096)`.
fn ron_value<T: serde::de::DeserializeOwned>(flag: &str, text: &str) -> anyhow::Result<T> {
    edge_io::from_ron(
        text,
        Path::new(&format!("--{flag} “{}”", edge_io::visible(text))),
    )
    .map_err(|e| anyhow::anyhow!(e))
}

impl Harmonics {
    /// The format: the `--format` file's, with the flags given on top.
    fn recording_format(&self) -> anyhow::Result<RecordingFormat> {
        let mut f = match &self.format {
            Some(path) => {
                let text = edge_io::read_text_capped(path, edge_io::CONFIG_MAX_BYTES)?;
                edge_io::from_ron(&text, path)?
            }
            None => RecordingFormat::default(),
        };
        if let Some(d) = &self.delimiter {
            let mut chars = d.chars();
            f.delimiter = match (d.as_str(), chars.next(), chars.next()) {
                ("whitespace", ..) => Delimiter::Whitespace,
                (_, Some(c), None) => Delimiter::Char(c),
                _ => bail!("--delimiter {d:?}: expected one character or `whitespace`"),
            };
        }
        if let Some(d) = &self.decimal {
            f.decimal = ron_value("decimal", d)?;
        }
        if let Some(n) = self.skip_lines {
            f.skip_lines = n;
        }
        if let Some(c) = &self.time_column {
            f.time.column.clone_from(c);
        }
        if let Some(u) = &self.time_unit {
            f.time.unit = ron_value("time-unit", u)?;
        }
        if let Some(c) = &self.gap_column {
            f.gap.column.clone_from(c);
        }
        if let Some(u) = &self.gap_unit {
            f.gap.unit = ron_value("gap-unit", u)?;
        }
        if self.angle_column.is_some() || self.angle_unit.is_some() {
            let (column, unit, optional) = match &f.angle {
                AngleSource::Encoder {
                    column,
                    unit,
                    optional,
                } => (column.clone(), *unit, *optional),
                _ => ("angle_deg".into(), AngleUnit::Deg, false),
            };
            f.angle = AngleSource::Encoder {
                optional: optional && self.angle_column.is_none(),
                column: self.angle_column.clone().unwrap_or(column),
                unit: match &self.angle_unit {
                    Some(u) => ron_value("angle-unit", u)?,
                    None => unit,
                },
            };
        }
        if let Some(c) = &self.index_pulse {
            f.angle = AngleSource::IndexPulse { column: c.clone() };
        }
        if let Some(a) = self.start_angle_deg {
            f.angle = AngleSource::Rate { start_angle_deg: a };
        }
        if let Some(m) = self.max_gap_intervals {
            f.max_gap_intervals = m;
        }
        if let Some(o) = &self.on_gap {
            f.on_gap = ron_value("on-gap", o)?;
        }
        if let Some(o) = &self.on_non_finite {
            f.on_non_finite = ron_value("on-non-finite", o)?;
        }
        Ok(f)
    }

    /// The recording read and analysed by the reader of its file's extension (`recording`'s
    /// [`analyze_recording_file`](recording::analyze_recording_file), as the study reads
    /// it: binary files with the format's names, units, angle source and bad-sample
    /// policies). A long text recording is streamed in bounded memory, with a bar on
    /// standard error while it is read (when that is a terminal).
    fn analyze(
        &self,
        format: &RecordingFormat,
        config: &FitConfig,
        angle_zero_rad: f64,
    ) -> anyhow::Result<StreamedRecording> {
        let format = RecordingFormat {
            group: self.group.clone().or_else(|| format.group.clone()),
            waveform_time: self.waveform_time || format.waveform_time,
            ..format.clone()
        };
        let rate_rad_s = self.rate_deg_s.to_radians();
        let options = StreamOptions {
            angle_zero_rad,
            ..StreamOptions::default()
        };
        let bar = crate::progress::file_bar();
        let mut progress = |p: ReadProgress| crate::progress::show_read(&bar, p);
        let result = recording::analyze_recording_file(
            &self.file,
            &format,
            rate_rad_s,
            config,
            options,
            &mut progress,
        );
        bar.finish_and_clear();
        result.map_err(|e| match e {
            // The setting as this command's flag.
            recording::RecordingError::SettingNotForFile {
                setting,
                applies_to,
                ..
            } => anyhow::anyhow!(
                "--{} applies to {applies_to} only",
                setting.replace('_', "-")
            ),
            e => e.into(),
        })
    }

    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let format = self.recording_format()?;
        let config = FitConfig {
            order: self.order,
            drift: self.drift,
            revolutions: self.revolutions,
            max_gap_intervals: format.max_gap_intervals,
        };
        let angle_zero_rad = match self.angle_zero_deg {
            Some(deg) if !deg.is_finite() => bail!("--angle-zero-deg {deg}: must be finite"),
            Some(deg) => deg.to_radians(),
            None => 0.0,
        };
        let recording = self.analyze(&format, &config, angle_zero_rad)?;
        let result = &recording.analysis;
        let direction = if self.probe_along {
            ProbeDirection::AlongO1X1
        } else {
            ProbeDirection::AgainstO1X1
        };
        let out = if self.json {
            let mut s = edge_io::to_json_pretty(&self.to_json(&recording, result, direction)?)?;
            s.push('\n');
            s
        } else {
            self.table(&recording, result, direction)?
        };
        Console::stdout().write_str(&out)?;
        Ok(())
    }

    fn to_json(
        &self,
        recording: &StreamedRecording,
        result: &RecordingAnalysis,
        direction: ProbeDirection,
    ) -> anyhow::Result<Value> {
        let fit = &result.analysis;
        let h = fit.first_harmonic()?;
        let coefficients = |c: &Coefficients| json!({ "l0": c.l0, "c": c.c, "s": c.s, "drift_per_s": c.drift_per_s });
        Ok(json!({
            "file": recording.path.display().to_string(),
            "samples": recording.samples,
            "gap_unit": recording.gap_unit.key(),
            "angle_source": result.angle_source.name(),
            "rate_deg_s": self.rate_deg_s,
            "measured_rate_deg_s": result.measured_rate_rad_s.map(f64::to_degrees),
            "dropped_revolutions": result.dropped_revolutions,
            "warnings": result.diagnostics.iter().map(|d| json!({
                "code": d.code(),
                "message": d.to_string(),
                "where": recording.path.display().to_string(),
            })).collect::<Vec<_>>(),
            "order": fit.order,
            "drift": fit.drift,
            "revolutions_used": fit.revolutions_used(),
            "revolutions_available": fit.revolutions_available,
            "incomplete_revolution": fit.incomplete.as_ref().map(|i| json!({
                "first_sample": i.samples.start, "samples": i.samples.len(), "turns": i.turns,
            })),
            "nominal_interval_s": fit.nominal_interval_s,
            "mean": coefficients(&fit.mean),
            "std": fit.std.as_ref().map(coefficients),
            "std_error": fit.std_error.as_ref().map(coefficients),
            "angle_zero_deg": self.angle_zero_deg.unwrap_or(0.0),
            "angle_zero_stated": self.angle_zero_deg.is_some(),
            "first_harmonic": {
                "c1": h.c1,
                "s1": h.s1,
                "amplitude": h.amplitude(),
                "beta_deg": direction.beta_rad(h).to_degrees(),
                "probe_direction": match direction {
                    ProbeDirection::AgainstO1X1 => "against_o1x1",
                    _ => "along_o1x1",
                },
            },
            "revolutions": fit.revolutions.iter().map(|r| json!({
                "first_sample": r.first_sample,
                "samples": r.samples,
                "coefficients": coefficients(&r.coefficients),
                "residual_rms": r.residual_rms,
                "condition": r.condition,
            })).collect::<Vec<_>>(),
        }))
    }

    fn table(
        &self,
        recording: &StreamedRecording,
        result: &RecordingAnalysis,
        direction: ProbeDirection,
    ) -> anyhow::Result<String> {
        let fit = &result.analysis;
        let unit = recording.gap_unit.symbol();
        let mut t = String::new();
        let source = match (result.angle_source, result.measured_rate_rad_s) {
            (AngleSourceKind::Encoder, Some(m)) => format!(
                "encoder column (measured rate {:.6} deg/s, declared {} deg/s)",
                m.to_degrees(),
                self.rate_deg_s
            ),
            (AngleSourceKind::IndexPulse, Some(m)) => format!(
                "index pulses (measured rate {:.6} deg/s, declared {} deg/s)",
                m.to_degrees(),
                self.rate_deg_s
            ),
            _ => format!("declared rate {} deg/s", self.rate_deg_s),
        };
        writeln!(
            t,
            "{}: {} samples, angle from {source}, order {}",
            recording.path.display(),
            recording.samples,
            fit.order
        )?;
        write!(
            t,
            "revolutions used: {} of {}",
            fit.revolutions_used(),
            fit.revolutions_available
        )?;
        if let Some(i) = &fit.incomplete {
            write!(
                t,
                " (dropped an incomplete trailing revolution: {:.3} turn, {} samples)",
                i.turns,
                i.samples.len()
            )?;
        }
        writeln!(t)?;
        writeln!(t)?;
        writeln!(
            t,
            "{:<6} {:>14} {:>14} {:>14}",
            "coef",
            format!("mean ({unit})"),
            format!("std ({unit})"),
            format!("std err ({unit})")
        )?;
        let cell = |c: Option<&Coefficients>, pick: &dyn Fn(&Coefficients) -> f64| {
            c.map_or_else(|| format!("{:>14}", "-"), |c| format!("{:>14.6}", pick(c)))
        };
        let row = |t: &mut String, name: String, pick: &dyn Fn(&Coefficients) -> f64| {
            writeln!(
                t,
                "{name:<6} {} {} {}",
                cell(Some(&fit.mean), pick),
                cell(fit.std.as_ref(), pick),
                cell(fit.std_error.as_ref(), pick)
            )
        };
        row(&mut t, "l0".into(), &|c| c.l0)?;
        for k in 0..fit.order {
            row(&mut t, format!("c{}", k + 1), &|c| c.c[k])?;
            row(&mut t, format!("s{}", k + 1), &|c| c.s[k])?;
        }
        if fit.drift {
            row(&mut t, "drift".into(), &|c| {
                c.drift_per_s.unwrap_or(f64::NAN)
            })?;
            writeln!(t, "(drift in {unit}/s)")?;
        }
        let h = fit.first_harmonic()?;
        writeln!(t)?;
        writeln!(
            t,
            "first harmonic: amplitude ΔR1 = {:.6} {unit}, β = {:.4} deg (probe {})",
            h.amplitude(),
            direction.beta_rad(h).to_degrees(),
            if matches!(direction, ProbeDirection::AgainstO1X1) {
                "against O1X1"
            } else {
                "along O1X1"
            }
        )?;
        if result.angle_source != AngleSourceKind::DeclaredRate {
            writeln!(
                t,
                "angle zero: {}",
                match self.angle_zero_deg {
                    Some(deg) => format!(
                        "the encoder reads {deg}° when the arm's PIGA end points at the probe \
                         (--angle-zero-deg): measured angles taken less {deg}°"
                    ),
                    None => "not given: the encoder taken to read 0° when the arm's PIGA end \
                             points at the probe (--angle-zero-deg)"
                        .to_owned(),
                }
            )?;
        }
        let rms: Vec<String> = fit
            .revolutions
            .iter()
            .map(|r| format!("{:.4}", r.residual_rms))
            .collect();
        writeln!(t, "residual RMS per revolution ({unit}): {}", rms.join(" "))?;
        if result.dropped_revolutions > 0 {
            writeln!(
                t,
                "dropped revolutions (gaps or non-finite samples): {}",
                result.dropped_revolutions
            )?;
        }
        for d in &result.diagnostics {
            writeln!(t, "warning[{}]: {d}", d.code())?;
        }
        Ok(t)
    }
}
