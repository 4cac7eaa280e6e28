//! The harmonic analysis of a loaded probe recording (eq. 20–21): the file's choices for
//! bad samples, the measured rate, the errors located on the file's lines and the
//! diagnostics in plain words. The numbers (the fit, the pooling around bad samples, the
//! noise levels, the drift and spread tests) are `harmonics`'.

use harmonics::{
    DropBadSamples, FitConfig, HarmonicAnalysis, HarmonicsError, PooledAnalysis, ProbeSignal,
    SpindleAngle,
};

use super::diagnostic::{
    Diagnostic, MIN_PLAUSIBLE_GAP_UM, OutlierRevolution, PROBE_RESOLUTION_UM,
    RATE_WARNING_TOLERANCE, SampleAt, SpreadCause,
};
use crate::error::{Hint, RecordingError, Result};
use crate::lab::format::{LengthUnit, OnBadSamples, OnOutlier};
use crate::lab::probe::{AngleSourceKind, Recording, sample_index};

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
///
/// Revolutions whose residual RMS is more than `harmonics::OUTLIER_RMS_RATIO` times the
/// median are [`Diagnostic::ResidualOutlier`] and, with `on_outlier: drop_revolution` (the
/// default), left out of the mean; residuals that alternate in sign from sample to sample
/// are [`Diagnostic::AlternatingResiduals`].
pub fn analyze_recording(
    recording: &Recording,
    declared_rate_rad_s: f64,
    config: &FitConfig,
) -> Result<RecordingAnalysis> {
    let config = FitConfig {
        max_gap_intervals: recording.max_gap_intervals,
        ..config.clone()
    };
    let located = |source: HarmonicsError| {
        let hint = hint_of(recording, &source);
        RecordingError::Samples {
            path: recording.path.clone(),
            line: sample_index(&source).map(|row| recording.line_of_sample(row)),
            hint,
            source,
        }
    };
    let signal = recording.signal(declared_rate_rad_s);
    let measured_rate_rad_s = declared_rate_check(recording, declared_rate_rad_s)?;
    let drop = DropBadSamples {
        gaps: recording.on_gap == OnBadSamples::DropRevolution,
        non_finite: recording.on_non_finite == OnBadSamples::DropRevolution,
    };
    // Dropped revolutions are counted from the recording's turns at its measured rate.
    let turns_rate_rad_s = match drop.gaps || drop.non_finite {
        true => recording
            .measured_rate_rad_s()
            .unwrap_or(declared_rate_rad_s),
        false => declared_rate_rad_s,
    };
    let PooledAnalysis {
        analysis,
        dropped_revolutions: dropped,
    } = harmonics::analyze_around_bad_samples(&signal, &config, drop, turns_rate_rad_s)
        .map_err(located)?;
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

/// Checks a recording's measured angle against the rate it is declared at, as
/// [`analyze_recording`] does first: with an encoder or index pulse, its mean rate must be
/// within [`harmonics::ENCODER_RATE_TOLERANCE`] (2 %) of the declared one, else
/// [`HarmonicsError::RateMismatch`] located in the file (one recording listed at two rates,
/// a file attached to the wrong rate point). A recording whose angle comes from the declared
/// rate passes. What a study's `check` runs on each recording without fitting it.
///
/// # Errors
/// [`RecordingError::Samples`] holding [`HarmonicsError::RateMismatch`] or the angle's own
/// error (not increasing, not finite), with the line and hint.
pub fn check_declared_rate(recording: &Recording, declared_rate_rad_s: f64) -> Result<()> {
    declared_rate_check(recording, declared_rate_rad_s).map(|_| ())
}

/// [`check_declared_rate`], returning the rate measured around non-finite samples when the
/// recording keeps them (`None` otherwise).
fn declared_rate_check(recording: &Recording, declared_rate_rad_s: f64) -> Result<Option<f64>> {
    let located = |source: HarmonicsError| {
        let hint = hint_of(recording, &source);
        RecordingError::Samples {
            path: recording.path.clone(),
            line: sample_index(&source).map(|row| recording.line_of_sample(row)),
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
            check.map_err(located)?;
        }
    }
    Ok(measured_rate_rad_s)
}

/// The mean rate within 2 % of the declared one.
pub(crate) fn check_rate(measured: f64, declared: f64) -> harmonics::Result<()> {
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
    hint_for(recording.angle_source, error)
}

/// [`hint_of`] for a recording whose angle comes from `angle_source`.
pub(crate) fn hint_for(angle_source: AngleSourceKind, error: &HarmonicsError) -> Option<Hint> {
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
            } else if angle_source == AngleSourceKind::Encoder && !(0.0..=100.0).contains(&ratio) {
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

/// The noise of a fit's first harmonic, and what the statistics of its revolutions say
/// about it, from the samples alone (recordings read from files and arrays alike).
#[derive(Debug, Clone, PartialEq)]
pub struct RevolutionStatistics {
    /// White-noise σ of one revolution's `d_c1`, `d_s1` (with an index pulse, its angle
    /// jitter added).
    pub revolution_noise_sigma: [f64; 2],
    /// White-noise σ of the mean `d_c1`, `d_s1` over the revolutions.
    pub mean_noise_sigma: [f64; 2],
    /// [`Diagnostic::DriftNotFitted`] and [`Diagnostic::RevolutionSpread`], when they apply,
    /// in that order.
    pub diagnostics: Vec<Diagnostic>,
}

/// The noise levels of `analysis` and its drift and spread diagnostics: the gap drifting
/// across revolutions while `drift` is off, and the first harmonic varying from revolution
/// to revolution beyond its white noise (with its likely cause from the angle source).
/// `rate_rad_s` is the rate the revolutions turn at (measured, else declared).
pub fn revolution_statistics(
    signal: &ProbeSignal<'_>,
    analysis: &HarmonicAnalysis,
    config: &FitConfig,
    angle_source: AngleSourceKind,
    rate_rad_s: f64,
) -> RevolutionStatistics {
    let angle_at = |i: usize| match signal.angle {
        SpindleAngle::Encoder(a) => a[i],
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        } => start_angle_rad + rate_rad_s * (signal.time_s[i] - signal.time_s[0]),
    };
    revolution_statistics_with(
        (angle_at, |i: usize| signal.time_s[i]),
        analysis,
        config,
        angle_source,
        rate_rad_s,
    )
}

/// [`revolution_statistics`] with the angle and time of a revolution's first and last
/// samples given by `(angle_at, time_at)` (sample index → rad, s), for a recording
/// streamed from its file.
pub(crate) fn revolution_statistics_with(
    (angle_at, time_at): (impl Fn(usize) -> f64, impl Fn(usize) -> f64),
    analysis: &HarmonicAnalysis,
    config: &FitConfig,
    angle_source: AngleSourceKind,
    rate_rad_s: f64,
) -> RevolutionStatistics {
    let noise = harmonics::first_harmonic_noise_with(analysis, config, angle_at);
    let mean_noise_sigma = noise.mean_sigma;
    let mut revolution_noise_sigma = noise.revolution_sigma;
    if angle_source == AngleSourceKind::IndexPulse {
        // Each revolution's zero is known to a sample interval: its angle jitters by
        // ω·Δt/√12, which turns the first harmonic by as much from revolution to
        // revolution (and averages out over them).
        let jitter_rad = rate_rad_s * analysis.nominal_interval_s / 12f64.sqrt();
        let amplitude = analysis.mean.c[0].hypot(analysis.mean.s[0]);
        revolution_noise_sigma = revolution_noise_sigma.map(|s| s.hypot(amplitude * jitter_rad));
    }
    let mut diagnostics = Vec::new();
    let drift = (!config.drift)
        .then(|| {
            harmonics::drift_across_revolutions_with(
                time_at,
                &analysis.revolutions,
                mean_noise_sigma[0].min(mean_noise_sigma[1]),
                rate_rad_s,
            )
        })
        .flatten();
    if let Some(d) = drift {
        diagnostics.push(Diagnostic::DriftNotFitted {
            drift_per_s: d.drift_per_s,
            bias_sigmas: d.bias_sigmas,
        });
    }
    if let Some((ratio_c1, ratio_s1)) =
        harmonics::revolution_spread(analysis, revolution_noise_sigma)
    {
        let cause = if angle_source == AngleSourceKind::DeclaredRate {
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
    RevolutionStatistics {
        revolution_noise_sigma,
        mean_noise_sigma,
        diagnostics,
    }
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
    let signal = recording.signal(declared_rate_rad_s);
    let binary = !recording.is_empty() && recording.line_of_sample(0) == 0;
    let place = |sample: usize| {
        if binary {
            SampleAt::Sample(sample)
        } else {
            SampleAt::Line(recording.line_of_sample(sample))
        }
    };
    let time_s = &recording.time_s;
    let facts = Facts {
        angle_source: recording.angle_source,
        unread_columns: &recording.unread_columns,
        start_angle_rad: recording.start_angle_rad,
        gap_unit: recording.gap_unit,
        on_outlier: recording.on_outlier,
    };
    harmonics::in_memory(&signal, |source| {
        finish_with(
            &facts,
            source,
            place,
            (
                |i: usize| recording.angle_at(i, declared_rate_rad_s),
                |i: usize| time_s[i],
            ),
            analysis,
            (
                declared_rate_rad_s,
                measured_rate_rad_s,
                dropped_revolutions,
            ),
            config,
        )
    })
}

/// What the diagnostics of an analysis say about the recording it came from.
pub(crate) struct Facts<'a> {
    pub(crate) angle_source: AngleSourceKind,
    pub(crate) unread_columns: &'a [String],
    pub(crate) start_angle_rad: f64,
    pub(crate) gap_unit: LengthUnit,
    pub(crate) on_outlier: OnOutlier,
}

/// The analysis with its noise levels and diagnostics, the revolutions' samples read from
/// `source` (a recording in memory, or its file read again), a sample placed by `place`,
/// and the angle and time of a revolution's ends by `ends`.
pub(crate) fn finish_with<S: harmonics::RevolutionSource>(
    facts: &Facts<'_>,
    source: &mut S,
    place: impl Fn(usize) -> SampleAt,
    ends: (impl Fn(usize) -> f64, impl Fn(usize) -> f64),
    analysis: HarmonicAnalysis,
    (declared_rate_rad_s, measured_rate_rad_s, dropped_revolutions): (f64, Option<f64>, usize),
    config: &FitConfig,
) -> std::result::Result<RecordingAnalysis, S::Error> {
    let (analysis, outliers) =
        outlier_check_in(source, analysis, facts.on_outlier, facts.gap_unit, place)?;
    let statistics = revolution_statistics_with(
        ends,
        &analysis,
        config,
        facts.angle_source,
        measured_rate_rad_s.unwrap_or(declared_rate_rad_s),
    );
    let mut diagnostics = Vec::new();
    if facts.angle_source == AngleSourceKind::DeclaredRate {
        diagnostics.push(Diagnostic::AngleFromRate {
            unread_columns: facts.unread_columns.to_vec(),
            start_angle_deg: facts.start_angle_rad.to_degrees(),
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
    diagnostics.extend(outliers);
    diagnostics.extend(statistics.diagnostics);
    if let Some(d) = implausible_gap(facts.gap_unit, &analysis) {
        diagnostics.push(d);
    }
    if dropped_revolutions > 0 {
        diagnostics.push(Diagnostic::DroppedRevolutions {
            count: dropped_revolutions,
            used: analysis.revolutions.len(),
        });
    }
    Ok(RecordingAnalysis {
        residual_rms: harmonics::pooled_residual_rms(&analysis.revolutions),
        analysis,
        angle_source: facts.angle_source,
        declared_rate_rad_s,
        measured_rate_rad_s,
        dropped_revolutions,
        revolution_noise_sigma: statistics.revolution_noise_sigma,
        mean_noise_sigma: statistics.mean_noise_sigma,
        diagnostics,
    })
}

/// The outlier checks of [`analyze_recording`] on any fit of `signal` (a recording's, or
/// arrays handed over, as the Python package does): revolutions whose residual RMS is more
/// than `harmonics::OUTLIER_RMS_RATIO` times the median are [`Diagnostic::ResidualOutlier`]
/// and, with [`OnOutlier::DropRevolution`], left out of the returned analysis; residuals
/// that alternate in sign are [`Diagnostic::AlternatingResiduals`]. `unit` is the gap's;
/// `place` names a sample (its file line, or its index).
pub fn outlier_check(
    signal: &ProbeSignal<'_>,
    analysis: HarmonicAnalysis,
    on_outlier: OnOutlier,
    unit: LengthUnit,
    place: impl Fn(usize) -> SampleAt,
) -> (HarmonicAnalysis, Vec<Diagnostic>) {
    harmonics::in_memory(signal, |source| {
        outlier_check_in(source, analysis, on_outlier, unit, place)
    })
}

/// [`outlier_check`] with the revolutions' samples read from `source`.
pub(crate) fn outlier_check_in<S: harmonics::RevolutionSource>(
    source: &mut S,
    analysis: HarmonicAnalysis,
    on_outlier: OnOutlier,
    unit: LengthUnit,
    place: impl Fn(usize) -> SampleAt,
) -> std::result::Result<(HarmonicAnalysis, Vec<Diagnostic>), S::Error> {
    let mut diagnostics = Vec::new();
    let mut analysis = analysis;
    if let Some(found) = harmonics::residual_outliers_in(source, &analysis)? {
        let dropped = on_outlier == OnOutlier::DropRevolution;
        let revolutions = found
            .revolutions
            .iter()
            .map(|o| OutlierRevolution {
                revolution: o.revolution,
                first_line: match place(o.first_sample) {
                    SampleAt::Line(line) => line,
                    SampleAt::Sample(_) => 0,
                },
                residual_rms: o.residual_rms,
                largest_residual: o.largest_residual,
                largest_at: place(o.largest_at_sample),
            })
            .collect();
        if dropped {
            let drop: Vec<usize> = found.revolutions.iter().map(|o| o.revolution).collect();
            analysis = harmonics::without_revolutions(&analysis, &drop);
        }
        diagnostics.push(Diagnostic::ResidualOutlier {
            revolutions,
            median_rms: found.median_rms,
            unit,
            dropped,
        });
    }
    if let Some(a) = harmonics::alternating_residuals_in(source, &analysis)? {
        diagnostics.push(Diagnostic::AlternatingResiduals {
            lag1: a.lag1,
            white_noise_lag1: a.white_noise_lag1,
            residual_rms: a.residual_rms,
            unit,
        });
    }
    Ok((analysis, diagnostics))
}

/// [`Diagnostic::ImplausibleGap`] when the mean gap is below a micrometre or the first
/// harmonic below a probe's own noise (1 nm): the check of a fit of a gap declared in
/// `unit` (a recording's, or arrays handed over with their unit, as the Python package
/// does), whose coefficients are in that unit.
pub fn implausible_gap(unit: LengthUnit, analysis: &HarmonicAnalysis) -> Option<Diagnostic> {
    let um = unit.um_per_unit();
    let mean_gap_um = analysis.mean.l0 * um;
    let first_harmonic_um = analysis.mean.c[0].hypot(analysis.mean.s[0]) * um;
    let noise_um = PROBE_RESOLUTION_UM;
    let plausible = mean_gap_um.abs() >= MIN_PLAUSIBLE_GAP_UM && first_harmonic_um >= noise_um;
    (!plausible
        && [mean_gap_um, first_harmonic_um, noise_um]
            .iter()
            .all(|v| v.is_finite()))
    .then_some(Diagnostic::ImplausibleGap {
        unit,
        mean_gap_um,
        first_harmonic_um,
        noise_um,
    })
}
