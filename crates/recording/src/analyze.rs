//! The harmonic analysis of a loaded recording (eq. 20–21): bad samples dropped by
//! revolution when the format says so, the measured rate, and the diagnostics that say
//! when the numbers may be wrong.

use std::fmt;
use std::ops::Range;

use harmonics::{Coefficients, FitConfig, HarmonicAnalysis, HarmonicsError, RevolutionFit};

use crate::error::{Hint, RecordingError, Result};
use crate::format::OnBadSamples;
use crate::probe::{AngleSourceKind, Recording, sample_index};

/// Relative difference between declared and measured rate above which
/// [`Diagnostic::RateDiffers`] is raised (0.1 %).
pub const RATE_WARNING_TOLERANCE: f64 = 1e-3;

/// Ratio of the revolution-to-revolution spread of `d_c1`/`d_s1` to its white-noise σ
/// above which [`Diagnostic::RevolutionSpread`] is raised (with few revolutions, the
/// threshold grows so that white noise alone raises it about once in 10⁵).
pub const SPREAD_WARNING_RATIO: f64 = 2.0;

/// A recording's harmonic analysis with what it rests on.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordingAnalysis {
    /// The per-revolution fits and their statistics (gap unit of the recording).
    pub analysis: HarmonicAnalysis,
    /// Where the angle came from.
    pub angle_source: AngleSourceKind,
    /// The declared rate, rad/s.
    pub declared_rate_rad_s: f64,
    /// The measured angle's mean rate, rad/s (`None` with the angle from the declared
    /// rate).
    pub measured_rate_rad_s: Option<f64>,
    /// Revolutions dropped because gaps or non-finite samples touch them.
    pub dropped_revolutions: usize,
    /// White-noise standard error of one revolution's `(d_c1, d_s1)`, gap unit, averaged
    /// over the revolutions: `√(2s²/n)`, times the drift term's variance inflation in its
    /// direction (and, with index pulses, their timing jitter).
    pub revolution_noise_sigma: [f64; 2],
    /// White-noise standard error of the mean `(d_c1, d_s1)`, gap unit: `√(Σᵣ 2s²fᵣ/nᵣ)/K`
    /// with `fᵣ` the drift term's variance inflation.
    pub mean_noise_sigma: [f64; 2],
    /// Pooled residual RMS of the per-revolution fits, gap unit.
    pub residual_rms: f64,
    /// What may make the numbers wrong, in plain words.
    pub diagnostics: Vec<Diagnostic>,
}

impl RecordingAnalysis {
    /// The rate the radius-error fit uses: the measured one when the angle is measured,
    /// else the declared one.
    pub fn rate_rad_s(&self) -> f64 {
        self.measured_rate_rad_s.unwrap_or(self.declared_rate_rad_s)
    }
}

/// The likely cause of a revolution-to-revolution spread.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpreadCause {
    /// The angle comes from the declared rate, and a real rate that differs makes the
    /// first harmonic turn from revolution to revolution.
    RateError,
    /// The mean gap moves from revolution to revolution and no drift term is fitted.
    Drift,
    /// Neither: a pickup or vibration that is not synchronous with the spindle, or speed
    /// variation within revolutions.
    NonSynchronous,
}

impl fmt::Display for SpreadCause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::RateError => {
                "a real rate that differs from the declared one (the angle is built from the \
                 declared rate): give an encoder or index-pulse column"
            }
            Self::Drift => "drift of the gap: set `drift: true`",
            Self::NonSynchronous => {
                "a pickup or vibration not synchronous with the spindle, or speed variation \
                 within revolutions"
            }
        })
    }
}

/// Something that may make a recording's numbers wrong.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Diagnostic {
    /// No angle was measured: the angle is `ω·(t − t₀) + θ₀` from the declared rate.
    AngleFromRate {
        /// Header columns not read (one may be an encoder or index pulse).
        unread_columns: Vec<String>,
    },
    /// The measured mean rate differs from the declared one by more than
    /// [`RATE_WARNING_TOLERANCE`]; the measured one is used.
    RateDiffers {
        /// Declared, rad/s.
        declared_rad_s: f64,
        /// Measured, rad/s.
        measured_rad_s: f64,
    },
    /// The first harmonic varies from revolution to revolution well beyond white noise.
    RevolutionSpread {
        /// Spread of `d_c1` over its white-noise σ.
        ratio_c1: f64,
        /// Spread of `d_s1` over its white-noise σ.
        ratio_s1: f64,
        /// Likely cause.
        cause: SpreadCause,
    },
    /// The mean gap drifts and `drift: false`: a drift within revolutions biases the first
    /// harmonic by about `2b/ω`.
    DriftNotFitted {
        /// The drift, gap unit per second.
        drift_per_s: f64,
        /// The bias it implies in the first harmonic, in standard errors of the mean.
        bias_sigmas: f64,
    },
    /// Revolutions were dropped for gaps or non-finite samples.
    DroppedRevolutions {
        /// How many.
        count: usize,
        /// How many were used.
        used: usize,
    },
    /// A raw PIGA output recording's per-revolution output rates scatter beyond what the
    /// white noise of the output angle explains.
    OutputSpread {
        /// Their standard deviation over the white-noise one.
        ratio: f64,
        /// Revolutions.
        revolutions: usize,
    },
}

impl Diagnostic {
    /// A short stable code (`angle_from_rate`, `rate_differs`, `revolution_spread`,
    /// `drift_not_fitted`, `dropped_revolutions`, `output_spread`).
    pub const fn code(&self) -> &'static str {
        match self {
            Self::AngleFromRate { .. } => "angle_from_rate",
            Self::RateDiffers { .. } => "rate_differs",
            Self::RevolutionSpread { .. } => "revolution_spread",
            Self::DriftNotFitted { .. } => "drift_not_fitted",
            Self::DroppedRevolutions { .. } => "dropped_revolutions",
            Self::OutputSpread { .. } => "output_spread",
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::AngleFromRate { unread_columns } => {
                write!(
                    f,
                    "no angle was measured: the angle is built from the declared rate with \
                     the format's start angle, so a real rate that differs, or a wrong start \
                     angle, shifts β and C_r without any other sign"
                )?;
                if !unread_columns.is_empty() {
                    write!(
                        f,
                        "; the file also has column(s) {} — if one is an encoder or an index \
                         pulse, name it in `angle`",
                        unread_columns
                            .iter()
                            .map(|c| format!("`{c}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )?;
                }
                Ok(())
            }
            Self::RateDiffers {
                declared_rad_s,
                measured_rad_s,
            } => write!(
                f,
                "the measured rate {:.6} deg/s differs from the declared {:.6} deg/s by \
                 {:+.3} %; the measured rate is used in the radius-error fit",
                measured_rad_s.to_degrees(),
                declared_rad_s.to_degrees(),
                100.0 * (measured_rad_s / declared_rad_s - 1.0)
            ),
            Self::RevolutionSpread {
                ratio_c1,
                ratio_s1,
                cause,
            } => write!(
                f,
                "the first harmonic varies from revolution to revolution {:.1}× (d_c1) and \
                 {:.1}× (d_s1) more than white noise explains; likely cause: {cause}",
                ratio_c1, ratio_s1
            ),
            Self::DriftNotFitted {
                drift_per_s,
                bias_sigmas,
            } => write!(
                f,
                "the gap drifts by {drift_per_s:.3e} per second and `drift: false`: the \
                 first harmonic may be biased by about {bias_sigmas:.1} standard errors; set \
                 `drift: true`"
            ),
            Self::DroppedRevolutions { count, used } => write!(
                f,
                "{count} revolution(s) dropped for gaps or non-finite samples; {used} used"
            ),
            Self::OutputSpread { ratio, revolutions } => write!(
                f,
                "the output rate varies from revolution to revolution {ratio:.1}× more than \
                 the white noise of the output angle explains ({revolutions} revolutions): a \
                 random walk of the output or a disturbance not synchronous with the spindle; \
                 the point's u is the standard error across revolutions"
            ),
        }
    }
}

/// Fits eq. 20 per revolution to a loaded recording ([`harmonics::analyze`]) against the
/// measured angle when there is one, else the declared rate; an error naming a sample is
/// given the sample's line in the file ([`Recording::line_of_sample`]). The format's
/// `max_gap_intervals` replaces the one in `config`.
///
/// With a measured angle, its mean rate must be within
/// [`harmonics::ENCODER_RATE_TOLERANCE`] (2 %) of the declared one, else
/// [`HarmonicsError::RateMismatch`] (a file attached to the wrong rate point); within it,
/// the measured rate is the one to use ([`RecordingAnalysis::rate_rad_s`]).
///
/// With `on_gap` or `on_non_finite` set to `drop_revolution`, the recording is cut at
/// each gap and around each non-finite sample, the pieces are fitted apart, and the
/// revolutions they hold are pooled; the others are counted as dropped.
pub fn analyze_recording(
    recording: &Recording,
    declared_rate_rad_s: f64,
    config: &FitConfig,
) -> Result<RecordingAnalysis> {
    let config = FitConfig {
        max_gap_intervals: recording.max_gap_intervals,
        ..config.clone()
    };
    let located = |offset: usize, source: HarmonicsError| {
        let hint = hint_of(recording, &source);
        RecordingError::Samples {
            path: recording.path.clone(),
            line: sample_index(&source).map(|row| recording.line_of_sample(row + offset)),
            hint,
            source,
        }
    };
    let signal = recording.signal(declared_rate_rad_s);
    // With every sample finite, harmonics checks the rate itself (one vectorised pass);
    // with non-finite ones kept, the rate is measured around them.
    let measured_rate_rad_s = match recording.on_non_finite {
        OnBadSamples::Error => None,
        OnBadSamples::DropRevolution => recording.measured_rate_rad_s(),
    };
    if recording.angle_rad.is_some() {
        let angle_ok = measured_rate_rad_s.is_some_and(f64::is_finite);
        // A recording whose samples are all good is checked by harmonics itself.
        if angle_ok || recording.on_non_finite == OnBadSamples::Error {
            let check = match measured_rate_rad_s {
                Some(m) if angle_ok && recording.on_non_finite != OnBadSamples::Error => {
                    check_rate(m, declared_rate_rad_s)
                }
                _ => harmonics::check_encoder_rate(
                    &signal,
                    harmonics::DeclaredRate::new(declared_rate_rad_s),
                ),
            };
            check.map_err(|e| located(0, e))?;
        }
    }
    let pieces = good_pieces(recording, &config).map_err(|e| located(0, e))?;
    let (analysis, dropped) = if pieces.len() == 1 && pieces[0] == (0..recording.len()) {
        (
            harmonics::analyze(&signal, &config).map_err(|e| located(0, e))?,
            0,
        )
    } else {
        pooled(recording, declared_rate_rad_s, &config, &pieces).map_err(|(o, e)| located(o, e))?
    };
    // The rate over the whole revolutions fitted: from the first one's first sample to the
    // sample that begins the revolution after the last one.
    let measured_rate_rad_s = match (analysis.revolutions.first(), analysis.revolutions.last()) {
        (Some(first), Some(last)) => recording
            .measured_rate_between(first.first_sample, last.first_sample + last.samples)
            .or(measured_rate_rad_s),
        _ => measured_rate_rad_s.or_else(|| recording.measured_rate_rad_s()),
    };
    Ok(finish(
        recording,
        analysis,
        declared_rate_rad_s,
        measured_rate_rad_s,
        dropped,
        &config,
    ))
}

/// The mean rate within 2 % of the declared one.
fn check_rate(measured: f64, declared: f64) -> harmonics::Result<()> {
    let tolerance = harmonics::ENCODER_RATE_TOLERANCE;
    if (measured - declared).abs() <= tolerance * declared {
        Ok(())
    } else {
        Err(HarmonicsError::RateMismatch {
            declared_rad_s: declared,
            encoder_rad_s: measured,
            tolerance,
        })
    }
}

/// What a failed analysis probably means for the format.
fn hint_of(recording: &Recording, error: &HarmonicsError) -> Option<Hint> {
    match error {
        HarmonicsError::AngleNotIncreasing { .. } => Some(Hint::EncoderCounts),
        HarmonicsError::RateMismatch {
            declared_rad_s,
            encoder_rad_s,
            ..
        } => {
            let ratio = encoder_rad_s / declared_rad_s;
            if [1e3, 1e-3, 1e6, 1e-6, 1e9, 1e-9]
                .iter()
                .any(|r| (ratio / r - 1.0).abs() < 0.05)
            {
                Some(Hint::TimeUnit)
            } else if recording.angle_source == AngleSourceKind::Encoder
                && !(0.0..=100.0).contains(&ratio)
            {
                Some(Hint::EncoderCounts)
            } else {
                None
            }
        }
        HarmonicsError::SampleGap { .. } => Some(Hint::OnGap),
        HarmonicsError::NonFinite { .. } => Some(Hint::OnNonFinite),
        _ => None,
    }
}

/// The runs of good samples: the whole recording when nothing is wrong, else the pieces
/// between gaps and non-finite samples (when the format drops revolutions for them).
fn good_pieces(recording: &Recording, config: &FitConfig) -> harmonics::Result<Vec<Range<usize>>> {
    let n = recording.len();
    let t = &recording.time_s;
    let drop_gap = recording.on_gap == OnBadSamples::DropRevolution;
    let drop_nan = recording.on_non_finite == OnBadSamples::DropRevolution;
    if !drop_gap && !drop_nan {
        return Ok(std::iter::once(0..n).collect());
    }
    let bad = |i: usize| {
        !(t[i].is_finite()
            && recording.gap[i].is_finite()
            && recording
                .angle_rad
                .as_ref()
                .is_none_or(|a| a[i].is_finite()))
    };
    // The nominal interval from finite neighbours (median of a spread of them).
    let mut intervals: Vec<f64> = (1..n)
        .step_by((n / 1025).max(1))
        .map(|i| t[i] - t[i - 1])
        .filter(|d| d.is_finite())
        .collect();
    if intervals.is_empty() {
        return Ok(std::iter::once(0..n).collect());
    }
    let mid = intervals.len() / 2;
    let nominal = *intervals.select_nth_unstable_by(mid, f64::total_cmp).1;
    let limit = nominal * config.max_gap_intervals;
    let mut pieces = Vec::new();
    let mut start = None::<usize>;
    let mut prev = None::<usize>;
    for i in 0..n {
        if bad(i) {
            if !drop_nan {
                let column = if t[i].is_finite() { "gap" } else { "time" };
                return Err(HarmonicsError::NonFinite {
                    index: i,
                    column,
                    value: if t[i].is_finite() {
                        recording.gap[i]
                    } else {
                        t[i]
                    },
                });
            }
            if let Some(s) = start.take() {
                pieces.push(s..i);
            }
            continue;
        }
        if let Some(p) = prev {
            let d = t[i] - t[p];
            if d <= 0.0 {
                return Err(HarmonicsError::TimeNotIncreasing {
                    index: i,
                    previous_s: t[p],
                    time_s: t[i],
                });
            }
            if d > limit && p + 1 == i {
                if !drop_gap {
                    return Err(HarmonicsError::SampleGap {
                        index: i,
                        interval_s: d,
                        nominal_interval_s: nominal,
                        max_intervals: config.max_gap_intervals,
                    });
                }
                if let Some(s) = start.take() {
                    pieces.push(s..i);
                }
            }
        }
        start.get_or_insert(i);
        prev = Some(i);
    }
    if let Some(s) = start {
        pieces.push(s..n);
    }
    Ok(pieces)
}

/// Fits each piece apart and pools their revolutions; `Err((offset, error))` names the
/// piece's first sample.
fn pooled(
    recording: &Recording,
    declared_rate_rad_s: f64,
    config: &FitConfig,
    pieces: &[Range<usize>],
) -> std::result::Result<(HarmonicAnalysis, usize), (usize, HarmonicsError)> {
    let piece_config = FitConfig {
        revolutions: None,
        ..config.clone()
    };
    let mut revolutions: Vec<RevolutionFit> = Vec::new();
    let mut template = None;
    for piece in pieces {
        let signal = recording.signal_of(piece.clone(), declared_rate_rad_s);
        match harmonics::analyze(&signal, &piece_config) {
            Ok(a) => {
                revolutions.extend(a.revolutions.iter().cloned().map(|mut r| {
                    r.first_sample += piece.start;
                    r
                }));
                template.get_or_insert(a);
            }
            // A piece too short for a revolution holds only dropped revolutions.
            Err(
                HarmonicsError::NoCompleteRevolution { .. } | HarmonicsError::TooFewSamples { .. },
            ) => {}
            Err(e) => return Err((piece.start, e)),
        }
    }
    let total_turns = total_turns(recording, declared_rate_rad_s);
    let Some(mut analysis) = template else {
        return Err((
            0,
            HarmonicsError::NoCompleteRevolution {
                samples: recording.len(),
                turns: total_turns,
            },
        ));
    };
    let available = revolutions.len();
    if let Some(k) = config.revolutions {
        if k > available {
            return Err((
                0,
                HarmonicsError::TooFewRevolutions {
                    requested: k,
                    available,
                },
            ));
        }
        revolutions.truncate(k);
    }
    // The last sample's interval belongs to the recording too.
    let whole = (total_turns + 1e-6).floor() as usize;
    let dropped = whole.saturating_sub(available);
    let (mean, std, std_error) = statistics(&revolutions);
    analysis.revolutions = revolutions;
    analysis.mean = mean;
    analysis.std = std;
    analysis.std_error = std_error;
    analysis.revolutions_available = available;
    analysis.incomplete = None;
    Ok((analysis, dropped))
}

/// Turns of the whole recording (measured angle, or declared rate).
fn total_turns(recording: &Recording, declared_rate_rad_s: f64) -> f64 {
    let t = &recording.time_s;
    let finite: Vec<usize> = [0, t.len() - 1].into_iter().collect();
    let first = (0..t.len())
        .find(|&i| t[i].is_finite())
        .unwrap_or(finite[0]);
    let last = (0..t.len())
        .rev()
        .find(|&i| t[i].is_finite())
        .unwrap_or(finite[1]);
    let rate = recording
        .measured_rate_rad_s()
        .unwrap_or(declared_rate_rad_s);
    let interval = (t[last] - t[first]) / (last - first).max(1) as f64;
    rate * (t[last] - t[first] + interval) / std::f64::consts::TAU
}

/// Mean, sample standard deviation and standard error of the coefficients.
fn statistics(
    revs: &[RevolutionFit],
) -> (Coefficients, Option<Coefficients>, Option<Coefficients>) {
    let k = revs.len() as f64;
    let each = |f: &dyn Fn(&Coefficients) -> Vec<f64>| -> Vec<Vec<f64>> {
        revs.iter().map(|r| f(&r.coefficients)).collect()
    };
    let stat = |values: Vec<Vec<f64>>| -> (Vec<f64>, Vec<f64>) {
        let m = values.first().map_or(0, Vec::len);
        let mean: Vec<f64> = (0..m)
            .map(|j| values.iter().map(|v| v[j]).sum::<f64>() / k)
            .collect();
        let sd: Vec<f64> = (0..m)
            .map(|j| {
                (values.iter().map(|v| (v[j] - mean[j]).powi(2)).sum::<f64>() / (k - 1.0)).sqrt()
            })
            .collect();
        (mean, sd)
    };
    let (l0, l0_sd) = stat(each(&|c| vec![c.l0]));
    let (c, c_sd) = stat(each(&|c| c.c.clone()));
    let (s, s_sd) = stat(each(&|c| c.s.clone()));
    let drift = revs
        .first()
        .and_then(|r| r.coefficients.drift_per_s)
        .map(|_| stat(each(&|c| vec![c.drift_per_s.unwrap_or(0.0)])));
    let mean = Coefficients {
        l0: l0[0],
        c,
        s,
        drift_per_s: drift.as_ref().map(|d| d.0[0]),
    };
    if revs.len() < 2 {
        return (mean, None, None);
    }
    let std = Coefficients {
        l0: l0_sd[0],
        c: c_sd,
        s: s_sd,
        drift_per_s: drift.as_ref().map(|d| d.1[0]),
    };
    let se = std.scaled(1.0 / k.sqrt());
    (mean, Some(std), Some(se))
}

/// The analysis with its noise levels and diagnostics.
fn finish(
    recording: &Recording,
    analysis: HarmonicAnalysis,
    declared_rate_rad_s: f64,
    measured_rate_rad_s: Option<f64>,
    dropped_revolutions: usize,
    config: &FitConfig,
) -> RecordingAnalysis {
    let revs = &analysis.revolutions;
    // Pooled residual variance s² of the per-revolution fits, each revolution's residual
    // sum of squares over its degrees of freedom (samples minus the 2N + 1 (+ drift)
    // coefficients): the unbiased white-noise variance even when a revolution holds few
    // samples.
    let parameters = 2 * config.order + 1 + usize::from(config.drift);
    let dof: usize = revs
        .iter()
        .map(|r| r.samples.saturating_sub(parameters))
        .sum();
    let rss = revs
        .iter()
        .map(|r| r.residual_rms * r.residual_rms * r.samples as f64)
        .sum::<f64>();
    let samples: usize = revs.iter().map(|r| r.samples).sum();
    let pooled = rss / dof.max(1) as f64;
    // Each revolution's d_c1 has variance ≈ 2s²/nᵣ (times the drift term's inflation);
    // K revolutions are averaged.
    let k = revs.len() as f64;
    let inflation = drift_inflation(config);
    let mut sum_var = [0.0; 2];
    for r in revs {
        let theta0 = recording.angle_at(r.first_sample, declared_rate_rad_s);
        let (sin0, cos0) = theta0.sin_cos();
        let base = 2.0 * pooled / r.samples as f64;
        sum_var[0] += base * (1.0 + (inflation - 1.0) * sin0 * sin0);
        sum_var[1] += base * (1.0 + (inflation - 1.0) * cos0 * cos0);
    }
    let mean_noise_sigma = sum_var.map(|v| v.sqrt() / k);
    let mut revolution_noise_sigma = sum_var.map(|v| (v / k).sqrt());
    if recording.angle_source == AngleSourceKind::IndexPulse {
        // Each revolution's zero is known to a sample interval: its angle jitters by
        // ω·Δt/√12, which turns the first harmonic by as much from revolution to
        // revolution (and averages out over them).
        let rate = measured_rate_rad_s.unwrap_or(declared_rate_rad_s);
        let jitter_rad = rate * analysis.nominal_interval_s / 12f64.sqrt();
        let amplitude = analysis.mean.c[0].hypot(analysis.mean.s[0]);
        revolution_noise_sigma = revolution_noise_sigma.map(|s| s.hypot(amplitude * jitter_rad));
    }
    let mut diagnostics = Vec::new();
    if recording.angle_source == AngleSourceKind::DeclaredRate {
        diagnostics.push(Diagnostic::AngleFromRate {
            unread_columns: recording.unread_columns.clone(),
        });
    }
    if let Some(m) = measured_rate_rad_s
        && (m / declared_rate_rad_s - 1.0).abs() > RATE_WARNING_TOLERANCE
    {
        diagnostics.push(Diagnostic::RateDiffers {
            declared_rad_s: declared_rate_rad_s,
            measured_rad_s: m,
        });
    }
    let drift = (!config.drift)
        .then(|| {
            drift_across_revolutions(
                recording,
                revs,
                mean_noise_sigma[0].min(mean_noise_sigma[1]),
                measured_rate_rad_s.unwrap_or(declared_rate_rad_s),
            )
        })
        .flatten();
    if let Some(d) = &drift {
        diagnostics.push(d.clone());
    }
    if let Some(std) = &analysis.std
        && revs.len() >= 3
        && revolution_noise_sigma.iter().all(|s| *s > 0.0)
    {
        let ratio_c1 = std.c[0] / revolution_noise_sigma[0];
        let ratio_s1 = std.s[0] / revolution_noise_sigma[1];
        // ratio² ~ χ²(K−1)/(K−1) for white noise: mean 1, sd √(2/(K−1)).
        let limit = SPREAD_WARNING_RATIO
            .powi(2)
            .max(1.0 + 6.0 * (2.0 / (k - 1.0)).sqrt());
        if ratio_c1.max(ratio_s1).powi(2) > limit {
            let cause = if recording.angle_source == AngleSourceKind::DeclaredRate {
                SpreadCause::RateError
            } else if drift.is_some() {
                SpreadCause::Drift
            } else {
                SpreadCause::NonSynchronous
            };
            diagnostics.push(Diagnostic::RevolutionSpread {
                ratio_c1,
                ratio_s1,
                cause,
            });
        }
    }
    if dropped_revolutions > 0 {
        diagnostics.push(Diagnostic::DroppedRevolutions {
            count: dropped_revolutions,
            used: revs.len(),
        });
    }
    RecordingAnalysis {
        analysis,
        angle_source: recording.angle_source,
        declared_rate_rad_s,
        measured_rate_rad_s,
        dropped_revolutions,
        revolution_noise_sigma,
        mean_noise_sigma,
        residual_rms: (rss / samples.max(1) as f64).sqrt(),
        diagnostics,
    }
}

/// The variance inflation of the first harmonic's coefficient along `sin(θ − θ₀)` (θ₀ the
/// revolution's first angle) when a drift term is fitted: within a revolution time is a
/// ramp in θ, whose part along that sine the drift term shares. With `v = π²/3 − 2Σₖ≤N 1/k²`
/// the ramp's variance beyond order N, the factor is `(2 + v)/v` (5.5 for N = 4); 1
/// without drift.
fn drift_inflation(config: &FitConfig) -> f64 {
    if !config.drift {
        return 1.0;
    }
    let beyond = std::f64::consts::PI.powi(2) / 3.0
        - 2.0
            * (1..=config.order)
                .map(|k| 1.0 / (k * k) as f64)
                .sum::<f64>();
    (2.0 + beyond) / beyond
}

/// A significant drift of the revolutions' mean gap, when its bias on the first harmonic
/// (`2b/ω`, from a ramp `b·t` over a revolution) exceeds 3 standard errors of the mean.
fn drift_across_revolutions(
    recording: &Recording,
    revs: &[RevolutionFit],
    mean_noise_sigma: f64,
    rate_rad_s: f64,
) -> Option<Diagnostic> {
    if revs.len() < 3 {
        return None;
    }
    let t = &recording.time_s;
    let x: Vec<f64> = revs
        .iter()
        .map(|r| 0.5 * (t[r.first_sample] + t[r.first_sample + r.samples - 1]))
        .collect();
    let y: Vec<f64> = revs.iter().map(|r| r.coefficients.l0).collect();
    let k = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / k, y.iter().sum::<f64>() / k);
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let rss: f64 = x
        .iter()
        .zip(&y)
        .map(|(a, b)| (b - my - slope * (a - mx)).powi(2))
        .sum();
    let slope_sigma = (rss / (k - 2.0).max(1.0) / sxx).sqrt();
    let bias = 2.0 * slope.abs() / rate_rad_s;
    let bias_sigmas = bias / mean_noise_sigma;
    (slope.abs() > 4.0 * slope_sigma && bias_sigmas > 3.0 && bias > 1e-12 * my.abs()).then_some(
        Diagnostic::DriftNotFitted {
            drift_per_s: slope,
            bias_sigmas,
        },
    )
}
