//! `cargo xtask harmonics FILE --rate-deg-s W`: per-revolution Fourier analysis of one probe
//! recording (eq. 20–21).

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::bail;
use harmonics::{Coefficients, FitConfig, HarmonicAnalysis, ProbeDirection};
use recording::{AngleUnit, BinaryChannels, LengthUnit, Recording, RecordingFormat};
use serde_json::{Value, json};

use crate::console::Console;

/// Fit eq. 20 to every complete revolution of a probe recording and average the coefficients.
#[derive(Debug, clap::Args)]
pub(crate) struct Harmonics {
    /// The recording, its reader chosen by extension: `.tdms` (NI TDMS), `.mat` (MATLAB v5/v7),
    /// else a CSV file with a header row (`time_s,gap_um[,angle_deg]` by default).
    file: PathBuf,
    /// Spindle rate, deg/s; gives the angle `θ = ω·(t − t₀)` when the file has no encoder column.
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
    /// Angle of the first sample from O1X1, deg (without an encoder column).
    #[arg(long, default_value_t = 0.0)]
    start_angle_deg: f64,
    /// The probe measures along O1X1 (default: against it, as in the paper); sets the sign of β.
    #[arg(long)]
    probe_along: bool,
    /// Name of the time column (CSV), channel (TDMS) or variable (MAT).
    #[arg(long, visible_alias = "time-column", default_value = "time_s")]
    time_channel: String,
    /// TDMS: the sample times from the gap channel's `wf_start_offset`/`wf_increment`
    /// properties instead of a time channel.
    #[arg(long)]
    waveform_time: bool,
    /// Name of the gap column (CSV), channel (TDMS) or variable (MAT).
    #[arg(long, visible_alias = "gap-channel", default_value = "gap_um")]
    gap_column: String,
    /// Unit of the gap column: um, mm or m.
    #[arg(long, default_value = "um")]
    gap_unit: String,
    /// Name of the encoder-angle column, channel or variable (used when present).
    #[arg(long, visible_alias = "angle-channel", default_value = "angle_deg")]
    angle_column: String,
    /// TDMS: the group holding the channels (default: the first group that has them). MAT: a
    /// struct variable whose fields are the variables (default: top-level variables).
    #[arg(long)]
    group: Option<String>,
    /// Unit of the angle column: deg or rad.
    #[arg(long, default_value = "deg")]
    angle_unit: String,
    /// Field delimiter (one ASCII character).
    #[arg(long, default_value_t = ',')]
    delimiter: char,
    /// Largest sample interval accepted, in nominal (median) intervals.
    #[arg(long, default_value_t = 3.0)]
    max_gap_intervals: f64,
}

impl Harmonics {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let format = RecordingFormat {
            time_column: self.time_channel.clone(),
            gap_column: self.gap_column.clone(),
            gap_unit: match self.gap_unit.as_str() {
                "um" => LengthUnit::Um,
                "mm" => LengthUnit::Mm,
                "m" => LengthUnit::M,
                other => bail!("--gap-unit {other:?}: expected um, mm or m"),
            },
            angle_column: self.angle_column.clone(),
            angle_unit: match self.angle_unit.as_str() {
                "deg" => AngleUnit::Deg,
                "rad" => AngleUnit::Rad,
                other => bail!("--angle-unit {other:?}: expected deg or rad"),
            },
            delimiter: self.delimiter,
            max_gap_intervals: self.max_gap_intervals,
        };
        let config = FitConfig {
            order: self.order,
            drift: self.drift,
            revolutions: self.revolutions,
            max_gap_intervals: self.max_gap_intervals,
        };
        let recording = self.load(&format)?;
        let rate_rad_s = self.rate_deg_s.to_radians();
        let fit = recording::analyze_recording(
            &recording,
            rate_rad_s,
            self.start_angle_deg.to_radians(),
            &config,
        )?;
        let direction = if self.probe_along {
            ProbeDirection::AlongO1X1
        } else {
            ProbeDirection::AgainstO1X1
        };
        // The analysis is finite (harmonics refuses otherwise); checked again here because a
        // JSON null would stand for a NaN.
        edge_io::check_finite(&fit)?;
        let out = if self.json {
            let mut s = edge_io::to_json_pretty(&self.to_json(&recording, &fit, direction)?)?;
            s.push('\n');
            s
        } else {
            self.table(&recording, &fit, direction)?
        };
        Console::stdout().write_str(&out)?;
        Ok(())
    }

    /// The recording, read by the reader of its file's extension.
    fn load(&self, format: &RecordingFormat) -> anyhow::Result<Recording> {
        let extension = self
            .file
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let binary = || BinaryChannels {
            group: self.group.clone(),
            time: (!self.waveform_time).then(|| format.time_column.clone()),
            gap: format.gap_column.clone(),
            gap_unit: format.gap_unit,
            angle: Some(format.angle_column.clone()),
            angle_unit: format.angle_unit,
            max_gap_intervals: format.max_gap_intervals,
        };
        let only_binary = |flag: &str, given: bool| {
            if given {
                bail!("{flag} applies to TDMS and MAT files only");
            }
            Ok(())
        };
        Ok(match extension.as_deref() {
            Some("tdms") => recording::load_tdms(&self.file, &binary())?,
            Some("mat") => {
                if self.waveform_time {
                    bail!("--waveform-time applies to TDMS files only");
                }
                recording::load_mat(&self.file, &binary())?
            }
            _ => {
                only_binary("--group", self.group.is_some())?;
                only_binary("--waveform-time", self.waveform_time)?;
                recording::load_recording(&self.file, format)?
            }
        })
    }

    fn angle_source(recording: &Recording) -> &'static str {
        if recording.angle_rad.is_some() {
            "encoder"
        } else {
            "rate"
        }
    }

    fn to_json(
        &self,
        recording: &Recording,
        fit: &HarmonicAnalysis,
        direction: ProbeDirection,
    ) -> anyhow::Result<Value> {
        let h = fit.first_harmonic()?;
        let coefficients = |c: &Coefficients| json!({ "l0": c.l0, "c": c.c, "s": c.s, "drift_per_s": c.drift_per_s });
        Ok(json!({
            "file": recording.path.display().to_string(),
            "samples": recording.len(),
            "gap_unit": recording.gap_unit.symbol(),
            "angle_source": Self::angle_source(recording),
            "rate_deg_s": self.rate_deg_s,
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
        recording: &Recording,
        fit: &HarmonicAnalysis,
        direction: ProbeDirection,
    ) -> anyhow::Result<String> {
        let unit = recording.gap_unit.symbol();
        let mut t = String::new();
        let source = match Self::angle_source(recording) {
            "encoder" => "encoder column".to_string(),
            _ => format!("rate {} deg/s", self.rate_deg_s),
        };
        writeln!(
            t,
            "{}: {} samples, angle from {source}, order {}",
            recording.path.display(),
            recording.len(),
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
        let rms: Vec<String> = fit
            .revolutions
            .iter()
            .map(|r| format!("{:.4}", r.residual_rms))
            .collect();
        writeln!(t, "residual RMS per revolution ({unit}): {}", rms.join(" "))?;
        Ok(t)
    }
}
