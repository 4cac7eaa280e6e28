//! Raw PIGA output recordings: time, the PIGA's output angle (its precession angle in
//! degrees or radians, or pick-off counts) and the spindle's angle reference, one file per
//! centrifuge rate; reduced to the mean output rate over whole spindle revolutions, where
//! once-per-revolution terms cancel, with its standard error across revolutions — one row
//! of the eq. 18 calibration.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::Path;

use harmonics::FitConfig;
use serde::{Deserialize, Serialize};

use crate::analyze::{Diagnostic, analyze_recording};
use crate::error::{RecordingError, Result};
use crate::format::{
    AngleSource, AngleUnit, Column, DecimalMark, Delimiter, LengthUnit, OnBadSamples,
    RecordingFormat, TimeUnit,
};
use crate::probe::{AngleSourceKind, Recording, load_recording, parse_recording};

/// Default name of the output-angle column.
pub const PIGA_OUTPUT_ANGLE_COLUMN: &str = "output_rad";

/// Layout of a raw PIGA output recording: as a probe recording's ([`RecordingFormat`]), with
/// the PIGA's output angle in place of the gap.
///
/// ```
/// let ron_text = r#"(
///     delimiter: ';',
///     output: (column: "pickoff", unit: counts(per_rev: 4096)),
///     angle: encoder(column: "spindle_deg", unit: deg),
/// )"#;
/// let format: recording::PigaRecordingFormat = ron::from_str(ron_text).unwrap();
/// assert_eq!(format.output.column, "pickoff");
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PigaRecordingFormat {
    /// Field delimiter (default `,`).
    pub delimiter: Delimiter,
    /// Decimal mark (default point).
    pub decimal: DecimalMark,
    /// Lines before the header, blank ones included.
    pub skip_lines: usize,
    /// The time column (default `time_s`, seconds).
    pub time: Column<TimeUnit>,
    /// The PIGA's output angle (default `output_rad`, radians): degrees, radians or
    /// pick-off counts per output revolution. Whole turns are unwrapped (an angle that wraps
    /// at 360° or a counter that wraps is followed), so the output must move less than a
    /// quarter turn between two samples.
    pub output: Column<AngleUnit>,
    /// Where the spindle angle comes from (default: the encoder column `angle_deg` when the
    /// header has it, else the declared rate, with the warning `angle_from_rate`).
    pub angle: AngleSource,
    /// Largest interval between samples, in nominal (median) sample intervals, before it
    /// counts as a gap (default 3).
    pub max_gap_intervals: f64,
    /// A gap: refuse the file (default) or drop the revolutions it touches.
    pub on_gap: OnBadSamples,
    /// A NaN or infinite value: refuse the file (default) or drop the revolutions it
    /// touches.
    pub on_non_finite: OnBadSamples,
}

impl Default for PigaRecordingFormat {
    fn default() -> Self {
        let probe = RecordingFormat::default();
        Self {
            delimiter: probe.delimiter,
            decimal: probe.decimal,
            skip_lines: probe.skip_lines,
            time: probe.time,
            output: Column {
                column: PIGA_OUTPUT_ANGLE_COLUMN.into(),
                unit: AngleUnit::Rad,
            },
            angle: probe.angle,
            max_gap_intervals: probe.max_gap_intervals,
            on_gap: probe.on_gap,
            on_non_finite: probe.on_non_finite,
        }
    }
}

impl PigaRecordingFormat {
    /// The same layout as a probe recording's, the output angle in the gap's place (read
    /// it with [`crate::load_recording`], then [`PigaRecording::from_recording`]).
    ///
    /// # Errors
    /// [`RecordingError::InvalidCountsPerRev`] for `counts` with 0 counts per revolution.
    pub fn probe_format(&self) -> Result<RecordingFormat> {
        if let AngleUnit::Counts { per_rev: 0 } = self.output.unit {
            return Err(RecordingError::InvalidCountsPerRev);
        }
        Ok(RecordingFormat {
            delimiter: self.delimiter,
            decimal: self.decimal,
            skip_lines: self.skip_lines,
            time: self.time.clone(),
            gap: Column {
                column: self.output.column.clone(),
                // Unused: the values are converted with the output's angle unit.
                unit: LengthUnit::Um,
            },
            angle: self.angle.clone(),
            max_gap_intervals: self.max_gap_intervals,
            on_gap: self.on_gap,
            on_non_finite: self.on_non_finite,
        })
    }
}

/// A raw PIGA output recording in memory: time (s), the output angle (rad, whole turns
/// unwrapped) and the spindle angle.
#[derive(Debug, Clone, PartialEq)]
pub struct PigaRecording {
    /// The samples, the output angle in radians in the gap's place.
    samples: Recording,
}

impl PigaRecording {
    /// The file it was read from.
    pub fn path(&self) -> &Path {
        &self.samples.path
    }

    /// Sample times, s.
    pub fn time_s(&self) -> &[f64] {
        &self.samples.time_s
    }

    /// The output angle of each sample, rad, whole turns unwrapped.
    pub fn output_rad(&self) -> &[f64] {
        &self.samples.gap
    }

    /// Where the spindle angle comes from.
    pub fn angle_source(&self) -> AngleSourceKind {
        self.samples.angle_source
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    /// Whether there are no samples (never true for a recording read from a file).
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// The 1-based line of sample `index` in the file.
    pub fn line_of_sample(&self, index: usize) -> usize {
        self.samples.line_of_sample(index)
    }

    /// A recording read as a probe recording in [`PigaRecordingFormat::probe_format`], its
    /// output (in the gap's place) converted from `unit` to radians and unwrapped.
    ///
    /// # Errors
    /// [`RecordingError::OutputStep`] for an output that moves by more than a quarter turn
    /// between two samples.
    pub fn from_recording(mut samples: Recording, unit: AngleUnit) -> Result<Self> {
        let scale = unit.rad_per_unit();
        let mut turns = 0.0;
        let mut previous: Option<f64> = None;
        for i in 0..samples.gap.len() {
            let raw = samples.gap[i] * scale;
            if !raw.is_finite() {
                // Kept only with `on_non_finite: drop_revolution`: the analysis drops it.
                samples.gap[i] = raw;
                continue;
            }
            if let Some(before) = previous {
                let step = raw - before;
                turns -= (step / TAU).round() * TAU;
                let unwrapped = step - (step / TAU).round() * TAU;
                if unwrapped.abs() > FRAC_PI_2 {
                    return Err(RecordingError::OutputStep {
                        path: samples.path.clone(),
                        line: samples.line_of_sample(i),
                        step_rad: unwrapped,
                    });
                }
            }
            previous = Some(raw);
            samples.gap[i] = raw + turns;
        }
        Ok(Self { samples })
    }
}

/// Reads a raw PIGA output recording from a file (see [`load_recording`] for the text
/// format and its errors).
///
/// # Errors
/// Those of [`load_recording`]; [`RecordingError::InvalidCountsPerRev`] for `counts` with 0
/// counts per revolution; [`RecordingError::OutputStep`] for an output that moves by more
/// than a quarter turn between two samples.
pub fn load_piga_recording(path: &Path, format: &PigaRecordingFormat) -> Result<PigaRecording> {
    let samples = load_recording(path, &format.probe_format()?)?;
    PigaRecording::from_recording(samples, format.output.unit)
}

/// Parses a raw PIGA output recording held in memory; `path` names it in errors.
///
/// ```
/// use recording::{PigaRecordingFormat, parse_piga_recording};
/// // An output angle that wraps at 360°.
/// let text = "time_s,output_deg,angle_deg\n0,359.0,0\n0.01,1.0,3.6\n";
/// let format: PigaRecordingFormat =
///     ron::from_str(r#"(output: (column: "output_deg", unit: deg))"#).unwrap();
/// let rec = parse_piga_recording(text.as_bytes(), "piga.csv".as_ref(), &format)?;
/// approx::assert_relative_eq!(rec.output_rad()[1] - rec.output_rad()[0], 2f64.to_radians(),
///                             max_relative = 1e-12);
/// # Ok::<(), recording::RecordingError>(())
/// ```
///
/// # Errors
/// As [`load_piga_recording`].
pub fn parse_piga_recording(
    text: &[u8],
    path: &Path,
    format: &PigaRecordingFormat,
) -> Result<PigaRecording> {
    let samples = parse_recording(text, path, &format.probe_format()?)?;
    PigaRecording::from_recording(samples, format.output.unit)
}

/// The mean output rate of one raw PIGA recording.
#[derive(Debug, Clone, PartialEq)]
pub struct PigaOutputRate {
    /// The rate the study declares for this file, rad/s.
    pub declared_rate_rad_s: f64,
    /// The spindle angle's mean rate over the recording, rad/s (`None` when the angle
    /// comes from the declared rate).
    pub measured_rate_rad_s: Option<f64>,
    /// The mean output rate over whole spindle revolutions, rad/s: the mean of the
    /// per-revolution slopes of the output angle.
    pub output_rad_s: f64,
    /// Its standard uncertainty, rad/s: the white-noise standard error
    /// ([`PigaOutputRate::white_noise_u_rad_s`]), or the standard error across
    /// revolutions when the slopes scatter beyond white noise (diagnostic `output_spread`).
    pub output_u_rad_s: f64,
    /// The standard error of the mean slope across revolutions, `s/√K` (K − 1 degrees of
    /// freedom).
    pub across_revolutions_u_rad_s: f64,
    /// The standard error of the mean slope that white noise of the output angle gives,
    /// from the residuals of the per-revolution fits pooled over the recording (many
    /// degrees of freedom, hence a steady weight even from few revolutions).
    pub white_noise_u_rad_s: f64,
    /// Standard deviation of the per-revolution output rates, rad/s.
    pub revolution_sd_rad_s: f64,
    /// Whole revolutions used (K ≥ 2).
    pub revolutions: usize,
    /// Revolutions dropped for gaps or non-finite samples.
    pub dropped_revolutions: usize,
    /// Where the spindle angle came from.
    pub angle_source: AngleSourceKind,
    /// What may make the number wrong (`angle_from_rate`, `rate_differs`,
    /// `dropped_revolutions`, `output_spread`).
    pub diagnostics: Vec<Diagnostic>,
}

impl PigaOutputRate {
    /// The rate of the point: the measured one when the spindle angle is measured, else the
    /// declared one.
    pub fn rate_rad_s(&self) -> f64 {
        self.measured_rate_rad_s.unwrap_or(self.declared_rate_rad_s)
    }
}

/// Reduces a raw PIGA output recording to its mean output rate: each whole spindle
/// revolution's samples are fitted with `θ_out = l0 + b·(t − t_mid) + Σₖ₌₁ᴺ (cₖ cos kφ + sₖ sin
/// kφ)` against the spindle angle φ ([`analyze_recording`] with a drift term, on the output
/// less its end-to-end trend so that no precision is lost to the ramp), so the slope `b` is
/// the revolution's mean output rate with its once-per-revolution (and up to `order`)
/// terms removed; the mean of the slopes over the revolutions is the point's output.
///
/// Its standard uncertainty is the white-noise standard error of that mean — the pooled
/// residual variance of the per-revolution fits (over their degrees of freedom) times each
/// revolution's exact `[(XᵀX)⁻¹]` of the slope at its own samples' times and angles — which
/// stays steady with few revolutions; when the slopes scatter across revolutions beyond
/// what white noise explains (above the 99 % quantile of χ²(K−1)/(K−1): a random walk of
/// the output, a disturbance not synchronous with the spindle), the diagnostic
/// `output_spread` says so and the standard error across revolutions, if larger, is used.
///
/// # Errors
/// Those of [`analyze_recording`] (an encoder rate more than 2 % from the declared one, too
/// few samples per revolution, aliasing, …) and [`RecordingError::TooFewRevolutions`] for
/// fewer than two usable revolutions.
pub fn reduce_piga_recording(
    recording: &PigaRecording,
    declared_rate_rad_s: f64,
    order: usize,
) -> Result<PigaOutputRate> {
    let config = FitConfig {
        order,
        drift: true,
        revolutions: None,
        ..FitConfig::default()
    };
    // The end-to-end trend, removed before the fit: the per-revolution fits then see the
    // ripple and the noise, not a ramp of many radians whose square would swamp the
    // residual sum of squares the normal equations give.
    let samples = &recording.samples;
    let finite = |i: &usize| samples.gap[*i].is_finite() && samples.time_s[*i].is_finite();
    let first = (0..samples.len()).find(finite);
    let last = (0..samples.len()).rev().find(finite);
    let trend_rad_s = match (first, last) {
        (Some(a), Some(b)) if b > a => {
            (samples.gap[b] - samples.gap[a]) / (samples.time_s[b] - samples.time_s[a])
        }
        _ => 0.0,
    };
    let mut detrended = samples.clone();
    if let Some(a) = first {
        let (t0, y0) = (samples.time_s[a], samples.gap[a]);
        for (y, t) in detrended.gap.iter_mut().zip(&samples.time_s) {
            *y -= y0 + trend_rad_s * (t - t0);
        }
    }
    let analysed = analyze_recording(&detrended, declared_rate_rad_s, &config)?;
    let a = &analysed.analysis;
    let revolutions = a.revolutions_used();
    let slope = |c: &harmonics::Coefficients| c.drift_per_s;
    let (Some(mean_slope), Some(sd), Some(se)) = (
        slope(&a.mean),
        a.std.as_ref().and_then(slope),
        a.std_error.as_ref().and_then(slope),
    ) else {
        return Err(RecordingError::TooFewRevolutions {
            path: recording.path().to_owned(),
            revolutions,
        });
    };
    if revolutions < 2 {
        return Err(RecordingError::TooFewRevolutions {
            path: recording.path().to_owned(),
            revolutions,
        });
    }
    // White noise: pooled residual variance over the fits' degrees of freedom.
    let parameters = 2 * order + 2;
    let rss: f64 = a
        .revolutions
        .iter()
        .map(|r| r.residual_rms * r.residual_rms * r.samples as f64)
        .sum();
    let dof: usize = a
        .revolutions
        .iter()
        .map(|r| r.samples.saturating_sub(parameters))
        .sum();
    let s2 = rss / dof.max(1) as f64;
    let variances: Vec<f64> = a
        .revolutions
        .iter()
        .map(|r| {
            let range = r.first_sample..r.first_sample + r.samples;
            s2 * slope_variance_factor(&detrended, range, declared_rate_rad_s, order)
        })
        .collect();
    let k = revolutions as f64;
    let white = (variances.iter().sum::<f64>()).sqrt() / k;
    let mut diagnostics: Vec<Diagnostic> = analysed
        .diagnostics
        .into_iter()
        // The slope is always fitted; the harmonics' white-noise model is made for a
        // gap's first harmonic, and the slopes' own spread is checked below.
        .filter(|d| {
            !matches!(
                d,
                Diagnostic::DriftNotFitted { .. } | Diagnostic::RevolutionSpread { .. }
            )
        })
        .collect();
    let per_revolution_white = (variances.iter().sum::<f64>() / k).sqrt();
    let ratio = sd / per_revolution_white;
    // ratio² ~ χ²(K−1)/(K−1) for white noise: its 99 % quantile (Wilson–Hilferty).
    let nu = k - 1.0;
    let limit = (1.0 - 2.0 / (9.0 * nu) + 2.326_348 * (2.0 / (9.0 * nu)).sqrt()).powi(3);
    // A revolution whose design is singular has no white-noise variance: the spread across
    // revolutions is all there is.
    let mut u = if white.is_finite() { white } else { se };
    if revolutions >= 3 && per_revolution_white > 0.0 && ratio * ratio > limit {
        diagnostics.push(Diagnostic::OutputSpread { ratio, revolutions });
        u = u.max(se);
    }
    Ok(PigaOutputRate {
        declared_rate_rad_s,
        measured_rate_rad_s: analysed.measured_rate_rad_s,
        output_rad_s: trend_rad_s + mean_slope,
        output_u_rad_s: u,
        across_revolutions_u_rad_s: se,
        white_noise_u_rad_s: white,
        revolution_sd_rad_s: sd,
        revolutions,
        dropped_revolutions: analysed.dropped_revolutions,
        angle_source: analysed.angle_source,
        diagnostics,
    })
}

/// `[(XᵀX)⁻¹]_bb` of one revolution's design `[1, t − t̄, cos kφ, sin kφ (k ≤ N)]` at its
/// own samples' times and spindle angles: the slope's variance per unit noise variance,
/// exact for any number of samples (the harmonics beside the slope inflate it, more so
/// with few samples per revolution). Solved by Cholesky on the unit-diagonal scaled normal
/// matrix; infinite if that is not positive definite.
fn slope_variance_factor(
    recording: &Recording,
    range: std::ops::Range<usize>,
    declared_rate_rad_s: f64,
    order: usize,
) -> f64 {
    let p = 2 * order + 2;
    let t = &recording.time_s[range.clone()];
    let t_mean = t.iter().sum::<f64>() / t.len() as f64;
    let mut a = vec![0.0; p * p];
    let mut row = vec![0.0; p];
    for i in range {
        let phi = recording.angle_at(i, declared_rate_rad_s);
        row[0] = 1.0;
        row[1] = recording.time_s[i] - t_mean;
        for k in 1..=order {
            let (s, c) = (k as f64 * phi).sin_cos();
            row[2 * k] = c;
            row[2 * k + 1] = s;
        }
        for r in 0..p {
            for c in 0..=r {
                a[r * p + c] += row[r] * row[c];
            }
        }
    }
    // Scale to a unit diagonal, then Cholesky (lower, in place).
    let d: Vec<f64> = (0..p).map(|r| a[r * p + r].sqrt().recip()).collect();
    for r in 0..p {
        for c in 0..=r {
            a[r * p + c] *= d[r] * d[c];
        }
    }
    for j in 0..p {
        let mut diag = a[j * p + j];
        for k in 0..j {
            diag -= a[j * p + k] * a[j * p + k];
        }
        if diag.is_nan() || diag <= 1e-12 {
            return f64::INFINITY;
        }
        let l = diag.sqrt();
        a[j * p + j] = l;
        for i in j + 1..p {
            let mut v = a[i * p + j];
            for k in 0..j {
                v -= a[i * p + k] * a[j * p + k];
            }
            a[i * p + j] = v / l;
        }
    }
    // [(A')⁻¹]_bb = ‖L⁻¹ e_b‖², then undo the scaling.
    let mut y = vec![0.0; p];
    for i in 0..p {
        let mut v = if i == 1 { 1.0 } else { 0.0 };
        for k in 0..i {
            v -= a[i * p + k] * y[k];
        }
        y[i] = v / a[i * p + i];
    }
    y.iter().map(|v| v * v).sum::<f64>() * d[1] * d[1]
}
