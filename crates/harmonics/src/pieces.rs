//! The analysis of a recording around its bad samples: cut at each gap and around each
//! non-finite sample, the pieces fitted apart, their whole revolutions pooled and the others
//! counted as dropped.

use std::ops::Range;

use crate::analysis::{FitConfig, HarmonicAnalysis, RevolutionFit, analyze, statistics};
use crate::error::{HarmonicsError, Result};
use crate::signal::{ProbeSignal, SpindleAngle};

/// Which bad samples cost only the revolutions they touch (instead of refusing the
/// recording).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DropBadSamples {
    /// An interval above `max_gap_intervals` nominal intervals.
    pub gaps: bool,
    /// A NaN or infinite time, gap or angle.
    pub non_finite: bool,
}

/// A pooled analysis and the revolutions it dropped.
#[derive(Debug, Clone, PartialEq)]
pub struct PooledAnalysis {
    /// The fits of the revolutions kept and their statistics across revolutions.
    pub analysis: HarmonicAnalysis,
    /// Whole revolutions of the recording dropped because a bad sample touches them.
    pub dropped_revolutions: usize,
}

/// Fits eq. 20 per revolution ([`analyze`]) to the samples between bad ones: with nothing
/// to drop, or no bad sample, the whole recording as [`analyze`] does; else each run of
/// good samples apart, pooling their revolutions (the first `config.revolutions` when
/// set) into one mean, standard deviation and standard error. `rate_rad_s` (the measured
/// mean rate, else the declared one) counts the recording's whole turns, of which those
/// not fitted are dropped. Errors name the sample's index in the whole signal.
///
/// ```
/// use harmonics::{DropBadSamples, FitConfig, ProbeSignal, SpindleAngle, analyze_around_bad_samples};
/// let rate = 10f64.to_radians();
/// let time_s: Vec<f64> = (0..36_000 * 4).map(|i| i as f64 * 1e-3).collect();
/// let mut gap: Vec<f64> = time_s.iter().map(|t| 5.0 + (rate * t).cos()).collect();
/// gap[50_000] = f64::NAN; // in the second revolution
/// let signal = ProbeSignal { time_s: &time_s, gap: &gap,
///     angle: SpindleAngle::Rate { rate_rad_s: rate, start_angle_rad: 0.0 } };
/// let drop = DropBadSamples { gaps: false, non_finite: true };
/// let pooled = analyze_around_bad_samples(&signal, &FitConfig::default(), drop, rate)?;
/// assert_eq!(pooled.dropped_revolutions, 1); // of 4: one whole one before the NaN, two after
/// approx::assert_relative_eq!(pooled.analysis.mean.c[0], 1.0, epsilon = 1e-9);
/// # Ok::<(), harmonics::HarmonicsError>(())
/// ```
///
/// # Errors
/// Those of [`analyze`]; a non-finite sample or a gap that is not to be dropped;
/// [`HarmonicsError::NoCompleteRevolution`] when no piece holds a whole revolution,
/// [`HarmonicsError::TooFewRevolutions`] when fewer than `config.revolutions` are kept.
pub fn analyze_around_bad_samples(
    signal: &ProbeSignal<'_>,
    config: &FitConfig,
    drop: DropBadSamples,
    rate_rad_s: f64,
) -> Result<PooledAnalysis> {
    let n = signal.time_s.len();
    let pieces = good_pieces(signal, config, drop)?;
    if pieces.len() == 1 && pieces[0] == (0..n) {
        return Ok(PooledAnalysis {
            analysis: analyze(signal, config)?,
            dropped_revolutions: 0,
        });
    }
    pooled(signal, config, &pieces, rate_rad_s)
}

/// The samples of `range` as a signal (a rate angle continues from the first sample).
fn piece<'a>(signal: &ProbeSignal<'a>, range: Range<usize>) -> ProbeSignal<'a> {
    let angle = match signal.angle {
        SpindleAngle::Encoder(a) => SpindleAngle::Encoder(&a[range.clone()]),
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        } => SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad: start_angle_rad
                + rate_rad_s
                    * (signal.time_s.get(range.start).copied().unwrap_or(0.0) - signal.time_s[0]),
        },
    };
    ProbeSignal {
        time_s: &signal.time_s[range.clone()],
        gap: &signal.gap[range],
        angle,
    }
}

/// The runs of good samples: the whole recording when nothing is to be dropped, else the
/// pieces between gaps and non-finite samples.
fn good_pieces(
    signal: &ProbeSignal<'_>,
    config: &FitConfig,
    drop: DropBadSamples,
) -> Result<Vec<Range<usize>>> {
    let t = signal.time_s;
    let n = t.len();
    if !drop.gaps && !drop.non_finite {
        return Ok(std::iter::once(0..n).collect());
    }
    let angle = match signal.angle {
        SpindleAngle::Encoder(a) => Some(a),
        SpindleAngle::Rate { .. } => None,
    };
    let bad = |i: usize| {
        !(t[i].is_finite() && signal.gap[i].is_finite() && angle.is_none_or(|a| a[i].is_finite()))
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
            if !drop.non_finite {
                let column = if t[i].is_finite() { "gap" } else { "time" };
                return Err(HarmonicsError::NonFinite {
                    index: i,
                    column,
                    value: if t[i].is_finite() {
                        signal.gap[i]
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
                if !drop.gaps {
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

/// Fits each piece apart and pools their revolutions.
fn pooled(
    signal: &ProbeSignal<'_>,
    config: &FitConfig,
    pieces: &[Range<usize>],
    rate_rad_s: f64,
) -> Result<PooledAnalysis> {
    let piece_config = FitConfig {
        revolutions: None,
        ..config.clone()
    };
    let mut revolutions: Vec<RevolutionFit> = Vec::new();
    let mut template = None;
    for range in pieces {
        match analyze(&piece(signal, range.clone()), &piece_config) {
            Ok(a) => {
                revolutions.extend(a.revolutions.iter().cloned().map(|mut r| {
                    r.first_sample += range.start;
                    r
                }));
                template.get_or_insert(a);
            }
            // A piece too short for a revolution holds only dropped revolutions.
            Err(
                HarmonicsError::NoCompleteRevolution { .. } | HarmonicsError::TooFewSamples { .. },
            ) => {}
            Err(e) => return Err(e.with_sample_offset(range.start)),
        }
    }
    let total_turns = total_turns(signal.time_s, rate_rad_s);
    let Some(mut analysis) = template else {
        return Err(HarmonicsError::NoCompleteRevolution {
            samples: signal.time_s.len(),
            turns: total_turns,
        });
    };
    let available = revolutions.len();
    if let Some(k) = config.revolutions {
        if k > available {
            return Err(HarmonicsError::TooFewRevolutions {
                requested: k,
                available,
            });
        }
        revolutions.truncate(k);
    }
    // The last sample's interval belongs to the recording too.
    let whole = (total_turns + 1e-6).floor() as usize;
    let (mean, std, std_error) = statistics(&revolutions);
    analysis.revolutions = revolutions;
    analysis.mean = mean;
    analysis.std = std;
    analysis.std_error = std_error;
    analysis.revolutions_available = available;
    analysis.incomplete = None;
    Ok(PooledAnalysis {
        analysis,
        dropped_revolutions: whole.saturating_sub(available),
    })
}

/// Turns of the whole recording at `rate_rad_s`, between its first and last finite times
/// plus one sample interval.
fn total_turns(t: &[f64], rate_rad_s: f64) -> f64 {
    let first = (0..t.len()).find(|&i| t[i].is_finite()).unwrap_or(0);
    let last = (0..t.len())
        .rev()
        .find(|&i| t[i].is_finite())
        .unwrap_or(t.len().saturating_sub(1));
    let interval = (t[last] - t[first]) / (last - first).max(1) as f64;
    rate_rad_s * (t[last] - t[first] + interval) / std::f64::consts::TAU
}
