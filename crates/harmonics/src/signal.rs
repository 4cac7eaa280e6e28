//! Checking a probe recording's samples and cutting it into revolutions.

// Lane loops index several arrays at once; that is what vectorises.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::TAU;
use std::ops::Range;

use crate::error::{HarmonicsError, Requirement, Result};

/// Where each sample's spindle angle comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpindleAngle<'a> {
    /// The spindle encoder's angle of each sample, rad, zero at the O1X1 reference. It may
    /// wrap (at 2π or anywhere): consecutive steps are unwrapped into `(−π, π]` and must not
    /// be negative.
    Encoder(&'a [f64]),
    /// A constant rate: `θ = ω·(t − t₀) + θ₀`, with `t₀` the first sample's time.
    Rate {
        /// Spindle rate `ω`, rad/s.
        rate_rad_s: f64,
        /// Angle `θ₀` of the first sample from O1X1, rad.
        start_angle_rad: f64,
    },
}

/// A probe recording held in memory: one sample per index of equal-length slices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeSignal<'a> {
    /// Sample times, s, strictly increasing.
    pub time_s: &'a [f64],
    /// Probe gap of each sample, in the recording's length unit (µm in the paper).
    pub gap: &'a [f64],
    /// Source of each sample's spindle angle.
    pub angle: SpindleAngle<'a>,
}

/// The sampling of a recording's time axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeAxis {
    /// Nominal sample interval, s: the median of up to 1025 intervals spread evenly over
    /// the recording.
    pub nominal_interval_s: f64,
    /// Largest sample interval, s.
    pub max_interval_s: f64,
}

/// The trailing revolution that the recording does not complete, dropped from the fit.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct IncompleteRevolution {
    /// Its samples.
    pub samples: Range<usize>,
    /// The fraction of a turn its samples cover.
    pub turns: f64,
}

/// A recording cut into complete revolutions.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Segmentation {
    /// Sample ranges of the complete revolutions, in order. Revolution `r` covers the angles
    /// `[θ_first + 2πr, θ_first + 2π(r+1))` from the first sample's angle.
    pub(crate) revolutions: Vec<Range<usize>>,
    /// The trailing incomplete revolution, if any (dropped).
    pub(crate) incomplete: Option<IncompleteRevolution>,
    /// The recording's time axis.
    pub(crate) time_axis: TimeAxis,
    /// Largest angular gap of each revolution (wrapping round it), rad, with the index of
    /// the sample before it; the index is `usize::MAX` when only a bound is known.
    pub(crate) max_gaps: Vec<(f64, usize)>,
}

/// Checks a time axis: every value finite, strictly increasing, and no interval longer than
/// `max_gap_intervals` times the nominal (median) interval. Errors name the sample index.
///
/// ```
/// # use harmonics::{check_time_axis, HarmonicsError};
/// let t = [0.0, 0.001, 0.002, 0.010, 0.011];
/// assert!(matches!(check_time_axis(&t, 3.0),
///                  Err(HarmonicsError::SampleGap { index: 3, .. })));
/// let axis = check_time_axis(&t[..3], 3.0)?;
/// approx::assert_relative_eq!(axis.nominal_interval_s, 0.001, max_relative = 1e-12);
/// # Ok::<(), HarmonicsError>(())
/// ```
pub fn check_time_axis(time_s: &[f64], max_gap_intervals: f64) -> Result<TimeAxis> {
    check_setting_gap(max_gap_intervals)?;
    let n = time_s.len();
    if n < 2 {
        if let Some(&t) = time_s.first().filter(|t| !t.is_finite()) {
            return Err(HarmonicsError::NonFinite {
                index: 0,
                column: "time",
                value: t,
            });
        }
        return Err(HarmonicsError::NoCompleteRevolution {
            samples: n,
            turns: 0.0,
        });
    }
    let nominal = nominal_interval(time_s);
    if nominal.is_finite() && nominal > 0.0 {
        // Fast path: one vectorisable pass; the slow scan below only runs to name the culprit.
        let (ok, max_interval_s) = pulp::Arch::new().dispatch(IntervalsWithin {
            t: time_s,
            limit: nominal * max_gap_intervals,
        });
        if ok {
            return Ok(TimeAxis {
                nominal_interval_s: nominal,
                max_interval_s,
            });
        }
    }
    for i in 0..n {
        let t = time_s[i];
        if !t.is_finite() {
            return Err(HarmonicsError::NonFinite {
                index: i,
                column: "time",
                value: t,
            });
        }
        if i > 0 && t <= time_s[i - 1] {
            return Err(HarmonicsError::TimeNotIncreasing {
                index: i,
                previous_s: time_s[i - 1],
                time_s: t,
            });
        }
    }
    let mut max_interval_s = 0.0_f64;
    for i in 1..n {
        let interval_s = time_s[i] - time_s[i - 1];
        if !interval_s.is_finite() {
            return Err(HarmonicsError::NonFiniteInterval {
                index: i,
                interval_s,
            });
        }
        if interval_s > nominal * max_gap_intervals {
            return Err(HarmonicsError::SampleGap {
                index: i,
                interval_s,
                nominal_interval_s: nominal,
                max_intervals: max_gap_intervals,
            });
        }
        max_interval_s = max_interval_s.max(interval_s);
    }
    // Finite, increasing and without a gap: the slow scan has the last word.
    Ok(TimeAxis {
        nominal_interval_s: nominal,
        max_interval_s,
    })
}

/// The nominal sample interval: the median of up to 1025 intervals spread evenly over the
/// recording (robust to a few gaps, and cheap). NaN or non-positive for a bad time axis.
fn nominal_interval(t: &[f64]) -> f64 {
    let m = t.len() - 1;
    let k = m.min(1025);
    let mut v: Vec<f64> = (0..k)
        .map(|j| {
            let i = j * m / k;
            t[i + 1] - t[i]
        })
        .collect();
    let mid = k / 2;
    *v.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// Whether every interval is in `(0, limit]` (false for any NaN), and the largest interval.
struct IntervalsWithin<'a> {
    t: &'a [f64],
    limit: f64,
}

impl pulp::WithSimd for IntervalsWithin<'_> {
    type Output = (bool, f64);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> (bool, f64) {
        intervals_within(self.t, self.limit)
    }
}

#[inline(always)]
fn intervals_within(t: &[f64], limit: f64) -> (bool, f64) {
    const W: usize = 8;
    // Per lane: smallest and largest interval (NaN makes the lane fail the final test).
    let mut min = [f64::INFINITY; W];
    let mut max = [0.0_f64; W];
    let mut nan = [0.0_f64; W];
    let pairs = t.len() - 1;
    let body = pairs - pairs % W;
    for i in (0..body).step_by(W) {
        let w: &[f64; W + 1] = t[i..i + W + 1].try_into().expect("window");
        for l in 0..W {
            let d = w[l + 1] - w[l];
            min[l] = if d < min[l] { d } else { min[l] };
            max[l] = if d > max[l] { d } else { max[l] };
            nan[l] += zero_if_finite(d);
        }
    }
    let mut lo = min.iter().copied().fold(f64::INFINITY, f64::min);
    let mut hi = max.iter().copied().fold(0.0, f64::max);
    let mut bad = nan.iter().sum::<f64>();
    for i in body..pairs {
        let d = t[i + 1] - t[i];
        lo = lo.min(d);
        hi = hi.max(d);
        bad += zero_if_finite(d);
    }
    (bad == 0.0 && lo > 0.0 && hi <= limit, hi)
}

/// `v − v`: 0 for a finite value, NaN for NaN or ±∞; sums of it stay 0 exactly when every
/// term is finite (one subtraction, vectorises, no branch).
#[inline(always)]
#[allow(clippy::eq_op)]
fn zero_if_finite(v: f64) -> f64 {
    v - v
}

/// [`HarmonicsError::NonFinite`] for the gap's first non-finite sample, if any.
pub(crate) fn gap_not_finite(gap: &[f64]) -> Option<HarmonicsError> {
    first_non_finite(gap).map(|index| HarmonicsError::NonFinite {
        index,
        column: "gap",
        value: gap[index],
    })
}

/// The gap's non-finite check on the samples outside `used` (ranges in order): the
/// error names the recording's first non-finite gap sample wherever it is.
pub(crate) fn check_gap_outside(gap: &[f64], used: &[Range<usize>]) -> Result<()> {
    let mut from = 0;
    for range in used.iter().chain(std::iter::once(&(gap.len()..gap.len()))) {
        if range.start > from && first_non_finite(&gap[from..range.start]).is_some() {
            return Err(gap_not_finite(gap).expect("a non-finite sample was seen"));
        }
        from = from.max(range.end);
    }
    Ok(())
}

/// Index of the first non-finite value, if any.
fn first_non_finite(x: &[f64]) -> Option<usize> {
    pulp::Arch::new().dispatch(FirstNonFinite(x))
}

struct FirstNonFinite<'a>(&'a [f64]);

impl pulp::WithSimd for FirstNonFinite<'_> {
    type Output = Option<usize>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Option<usize> {
        first_non_finite_impl(self.0)
    }
}

#[inline(always)]
fn first_non_finite_impl(x: &[f64]) -> Option<usize> {
    // `v − v` is 0 for a finite value and NaN otherwise, so the lane sums stay 0 exactly
    // when every value is finite: one vectorised pass, then a scan only to name the culprit.
    const W: usize = 8;
    let mut acc = [0.0_f64; W];
    let chunks = x.chunks_exact(W);
    let tail: f64 = chunks.remainder().iter().map(|&v| zero_if_finite(v)).sum();
    for chunk in chunks {
        let c: &[f64; W] = chunk.try_into().expect("chunk");
        for l in 0..W {
            acc[l] += zero_if_finite(c[l]);
        }
    }
    if acc.iter().sum::<f64>() + tail == 0.0 {
        None
    } else {
        x.iter().position(|v| !v.is_finite())
    }
}

pub(crate) fn check_setting_gap(max_gap_intervals: f64) -> Result<()> {
    if !(max_gap_intervals.is_finite() && max_gap_intervals >= 1.0) {
        return Err(HarmonicsError::InvalidSetting {
            field: "max_gap_intervals",
            value: max_gap_intervals,
            requirement: Requirement::AtLeastOne,
        });
    }
    Ok(())
}

/// Checks the samples and cuts the recording into complete revolutions.
///
/// Checks, in this order, naming the sample: equal lengths, finite values, strictly
/// increasing time, no gap above `max_gap_intervals` nominal intervals, an encoder angle that
/// does not step back (or a finite positive rate that turns less than `π/order` in the
/// nominal interval, which also bounds the revolutions by the samples). The trailing revolution is complete when
/// the angle left to close it is at most `max_gap_intervals` nominal angular steps; otherwise
/// it is returned as [`Segmentation::incomplete`]. Fails with
/// [`HarmonicsError::NoCompleteRevolution`] when no revolution is complete.
pub(crate) fn segment(
    signal: &ProbeSignal<'_>,
    max_gap_intervals: f64,
    order: usize,
) -> Result<Segmentation> {
    check_setting_gap(max_gap_intervals)?;
    let n = signal.time_s.len();
    if signal.gap.len() != n {
        return Err(HarmonicsError::LengthMismatch {
            column: "gap",
            len: signal.gap.len(),
            expected: n,
        });
    }
    if let SpindleAngle::Encoder(a) = signal.angle
        && a.len() != n
    {
        return Err(HarmonicsError::LengthMismatch {
            column: "angle",
            len: a.len(),
            expected: n,
        });
    }
    let time_axis = check_time_axis(signal.time_s, max_gap_intervals)?;
    // The gap is checked where it is read: the fit's own pass over each revolution (its
    // Σ(y − y₀)² is finite only when every sample is), and [`check_gap_outside`] for the
    // samples no revolution uses. A separate pass here cost a read of the whole array.
    match signal.angle {
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        } => {
            if !(rate_rad_s.is_finite() && rate_rad_s > 0.0) {
                return Err(HarmonicsError::InvalidRate { rate_rad_s });
            }
            if !start_angle_rad.is_finite() {
                return Err(HarmonicsError::InvalidSetting {
                    field: "start_angle_rad",
                    value: start_angle_rad,
                    requirement: Requirement::Finite,
                });
            }
            check_rate_resolves(signal.time_s, rate_rad_s, time_axis, order)?;
            Ok(segment_rate(
                signal.time_s,
                rate_rad_s,
                time_axis,
                max_gap_intervals,
            ))
        }
        SpindleAngle::Encoder(a) => {
            if let Some(index) = first_non_finite(a) {
                return Err(HarmonicsError::NonFinite {
                    index,
                    column: "angle",
                    value: a[index],
                });
            }
            segment_encoder(a, time_axis, max_gap_intervals)
        }
    }
    .and_then(|s| {
        if s.revolutions.is_empty() {
            let turns = s.incomplete.as_ref().map_or(0.0, |i| i.turns);
            Err(HarmonicsError::NoCompleteRevolution { samples: n, turns })
        } else {
            Ok(s)
        }
    })
}

/// Refuses a rate that turns `π/order` or more in the nominal sample interval (no
/// revolution could resolve the order), or whose recording spans more turns than it has
/// samples (then some interval spans a whole turn); this bounds the revolutions by `n`.
fn check_rate_resolves(t: &[f64], omega: f64, axis: TimeAxis, order: usize) -> Result<()> {
    let limit_rad = std::f64::consts::PI / order as f64;
    let refuse = |interval_s: f64| HarmonicsError::RateAliases {
        rate_rad_s: omega,
        interval_s,
        step_rad: omega * interval_s,
        order,
        limit_rad,
    };
    // Both factors are finite and positive: the product is not NaN.
    if omega * axis.nominal_interval_s >= limit_rad {
        return Err(refuse(axis.nominal_interval_s));
    }
    let turns = omega * (t[t.len() - 1] - t[0]) / TAU;
    if turns >= t.len() as f64 {
        return Err(refuse(axis.max_interval_s));
    }
    Ok(())
}

fn segment_rate(
    t: &[f64],
    omega: f64,
    time_axis: TimeAxis,
    max_gap_intervals: f64,
) -> Segmentation {
    let n = t.len();
    let t0 = t[0];
    let turn = |ti: f64| omega * (ti - t0) / TAU;
    let candidates = turn(t[n - 1]).floor() as usize + 1;
    let mut starts = Vec::with_capacity(candidates + 1);
    for r in 0..candidates {
        starts.push(t.partition_point(|&ti| turn(ti) < r as f64));
    }
    starts.push(n);
    let nominal_step = omega * time_axis.nominal_interval_s;
    // Every step inside the recording is at most ω·(largest interval); a revolution's closing
    // gap is checked on its own.
    let step_bound = omega * time_axis.max_interval_s;
    let mut revolutions = Vec::with_capacity(candidates);
    let mut max_gaps = Vec::with_capacity(candidates);
    let mut incomplete = None;
    for r in 0..candidates {
        let range = starts[r]..starts[r + 1];
        if range.is_empty() {
            continue;
        }
        let span = omega * (t[range.end - 1] - t[range.start]);
        let closing = TAU - span;
        let last = r + 1 == candidates;
        if last && closing > max_gap_intervals * nominal_step {
            incomplete = Some(IncompleteRevolution {
                turns: span / TAU,
                samples: range,
            });
            continue;
        }
        let (gap, at) = if closing > step_bound {
            (closing, range.end - 1)
        } else {
            (step_bound, usize::MAX)
        };
        max_gaps.push((gap, at));
        revolutions.push(range);
    }
    Segmentation {
        revolutions,
        incomplete,
        time_axis,
        max_gaps,
    }
}

/// `1/2π`: a multiplication instead of a division in the per-sample passes.
const INV_TAU: f64 = 1.0 / TAU;

/// Wrapped step `d − 2π·round(d/2π) ∈ [−π, π]` between consecutive encoder readings.
#[inline(always)]
pub(crate) fn encoder_step(prev: f64, next: f64) -> f64 {
    let d = next - prev;
    (-(d * INV_TAU).round_ties_even()).mul_add(TAU, d)
}

/// Angle of a reading from the first one, wrapped into `[0, 2π)` (up to rounding).
#[inline(always)]
pub(crate) fn phase(a: f64, start: f64) -> f64 {
    let x = a - start;
    (-(x * INV_TAU).floor()).mul_add(TAU, x)
}

/// The vectorised encoder pass: whether no step is negative, the largest step, and the
/// samples at which the angle passes the first sample's angle again (revolution starts).
struct EncoderScan<'a>(&'a [f64]);

impl pulp::WithSimd for EncoderScan<'_> {
    type Output = (bool, f64, Vec<usize>);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Self::Output {
        const W: usize = 8;
        const CHUNK: usize = 64;
        let a = self.0;
        let start = a[0];
        // Per lane: smallest and largest step, and whether the start angle was passed
        // (1.0) in the current chunk; all branch-free so that the lanes vectorise.
        let mut min_step = [f64::INFINITY; W];
        let mut max_step = [0.0_f64; W];
        let mut starts = Vec::new();
        let pairs = a.len() - 1;
        let mut base = 0;
        while base + CHUNK <= pairs {
            let mut crossed = [0.0_f64; W];
            for g in (0..CHUNK).step_by(W) {
                let w: &[f64; W + 1] = a[base + g..base + g + W + 1].try_into().expect("window");
                for l in 0..W {
                    let step = encoder_step(w[l], w[l + 1]);
                    min_step[l] = if step < min_step[l] {
                        step
                    } else {
                        min_step[l]
                    };
                    max_step[l] = if step > max_step[l] {
                        step
                    } else {
                        max_step[l]
                    };
                    crossed[l] += if phase(w[l], start) + step >= TAU {
                        1.0
                    } else {
                        0.0
                    };
                }
            }
            if crossed.iter().sum::<f64>() > 0.0 {
                push_crossings(a, start, base..base + CHUNK, &mut starts);
            }
            base += CHUNK;
        }
        push_crossings(a, start, base..pairs, &mut starts);
        for i in base..pairs {
            let step = encoder_step(a[i], a[i + 1]);
            min_step[0] = min_step[0].min(step);
            max_step[0] = max_step[0].max(step);
        }
        let ok = min_step.iter().all(|&m| m >= 0.0);
        (ok, max_step.iter().copied().fold(0.0, f64::max), starts)
    }
}

/// Appends the samples `i + 1` (for `i` in `pairs`) at which the angle passes the first
/// sample's angle again.
#[inline(always)]
fn push_crossings(a: &[f64], start: f64, pairs: Range<usize>, starts: &mut Vec<usize>) {
    for i in pairs {
        if phase(a[i], start) + encoder_step(a[i], a[i + 1]) >= TAU {
            starts.push(i + 1);
        }
    }
}

fn segment_encoder(a: &[f64], time_axis: TimeAxis, max_gap_intervals: f64) -> Result<Segmentation> {
    let n = a.len();
    let start = a[0];
    let (ok, max_step, crossings) = pulp::Arch::new().dispatch(EncoderScan(a));
    if !ok {
        // Non-finite readings are refused before this pass, so a failure is a step back.
        let i = (1..n)
            .find(|&i| encoder_step(a[i - 1], a[i]) < 0.0)
            .expect("the scan found one");
        return Err(HarmonicsError::AngleNotIncreasing {
            index: i,
            step_rad: encoder_step(a[i - 1], a[i]),
        });
    }
    let mut bounds = Vec::with_capacity(crossings.len() + 2);
    bounds.push(0);
    bounds.extend(crossings);
    bounds.push(n);
    let turns_total = (bounds.len() - 2) as f64;
    let nominal_step = ((TAU * turns_total + phase(a[n - 1], start)) / (n - 1) as f64).max(0.0);
    let mut revolutions = Vec::with_capacity(bounds.len());
    let mut max_gaps = Vec::with_capacity(bounds.len());
    let mut incomplete = None;
    for (r, w) in bounds.windows(2).enumerate() {
        let range = w[0]..w[1];
        let span = phase(a[range.end - 1], start) - phase(a[range.start], start);
        let closing = TAU - span;
        let last = r + 2 == bounds.len();
        if last && closing > max_gap_intervals * nominal_step {
            incomplete = Some(IncompleteRevolution {
                turns: span / TAU,
                samples: range,
            });
            continue;
        }
        let (gap, at) = if closing > max_step {
            (closing, range.end - 1)
        } else {
            (max_step, usize::MAX)
        };
        max_gaps.push((gap, at));
        revolutions.push(range);
    }
    Ok(Segmentation {
        revolutions,
        incomplete,
        time_axis,
        max_gaps,
    })
}

/// The largest angular gap of a revolution, wrapping round it, with the sample before it.
pub(crate) fn exact_max_gap(signal: &ProbeSignal<'_>, range: Range<usize>) -> (f64, usize) {
    let step = |i: usize| match signal.angle {
        SpindleAngle::Rate { rate_rad_s, .. } => {
            rate_rad_s * (signal.time_s[i + 1] - signal.time_s[i])
        }
        SpindleAngle::Encoder(a) => encoder_step(a[i], a[i + 1]),
    };
    let span: f64 = (range.start..range.end - 1).map(step).sum();
    let mut best = (TAU - span, range.end - 1);
    for i in range.start..range.end - 1 {
        let g = step(i);
        if g > best.0 {
            best = (g, i);
        }
    }
    best
}
