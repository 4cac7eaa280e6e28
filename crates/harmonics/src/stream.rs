//! The analysis of a recording streamed in pieces (issue 32): the samples arrive in order,
//! a revolution at a time is held, and the result is [`analyze`](crate::analyze)'s to the
//! last bit (the same segmentation, checks, errors and fits; a test compares them).
//!
//! What needs the whole recording is kept as it passes, in memory that does not grow with
//! the samples: the intervals the nominal interval is the median of (their places follow
//! from the number of samples, which the caller states first), the largest interval, the
//! first offending sample of each check, the intervals that are larger than every earlier
//! one (the first of them above the gap limit is the first gap, once the nominal interval is
//! known), and per revolution its range, its closing and largest angular gaps, its fit and
//! the time and angle at its ends. Errors are decided at [`StreamingFit::finish`] in the
//! order [`analyze`](crate::analyze) checks them.

use std::f64::consts::{PI, TAU};
use std::ops::Range;

use crate::analysis::{
    FitConfig, FitFailure, HarmonicAnalysis, RevolutionFit, RevolutionSamples, fit_samples,
    largest_gap, quantity_name, statistics,
};
use crate::error::{HarmonicsError, Requirement, Result};
use crate::kernel::AngleMap;
use crate::signal::{IncompleteRevolution, TimeAxis, check_setting_gap, encoder_step, phase};

/// Where a streamed recording's spindle angle comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StreamAngle {
    /// An encoder angle with every sample, rad (as [`crate::SpindleAngle::Encoder`]).
    Encoder,
    /// A constant rate from the first sample (as [`crate::SpindleAngle::Rate`]).
    Rate {
        /// Spindle rate `ω`, rad/s.
        rate_rad_s: f64,
        /// Angle `θ₀` of the first sample from O1X1, rad.
        start_angle_rad: f64,
    },
}

/// The time and angle of one sample, kept where a revolution starts and at the last
/// sample, for the statistics that need them after the fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleMark {
    /// Index of the sample in the recording.
    pub index: usize,
    /// Its time, s.
    pub time_s: f64,
    /// Its angle: the encoder's reading, rad, or `θ₀ + ω·(t − t₀)` with a rate.
    pub angle_rad: f64,
    /// Encoder steps beyond ±π (wraps, counted +1 for a step below −π and −1 above π)
    /// between the first sample and this one.
    pub wraps_before: i64,
}

/// A streamed analysis: the analysis, and what the recording's statistics need of its
/// samples without reading them again.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamedAnalysis {
    /// The analysis, equal to [`analyze`](crate::analyze)'s.
    pub analysis: HarmonicAnalysis,
    /// The recording's time axis.
    pub time_axis: TimeAxis,
    /// The first and last samples of every revolution, and the recording's last sample, in
    /// order.
    pub marks: Vec<SampleMark>,
    /// The sum of the encoder's wrapped steps over the recording, rad (as
    /// [`check_encoder_rate`](crate::check_encoder_rate) forms it; 0 with a rate).
    pub encoder_span_rad: f64,
}

impl StreamedAnalysis {
    /// The mark of sample `index` (a revolution's first sample or the last sample).
    pub fn mark(&self, index: usize) -> Option<&SampleMark> {
        self.marks
            .binary_search_by_key(&index, |m| m.index)
            .ok()
            .map(|k| &self.marks[k])
    }
}

/// Why a streamed analysis failed: the time axis ([`crate::check_time_axis`]'s errors,
/// which a reader reports as it reads the file), or the analysis.
#[derive(Debug, Clone, PartialEq)]
pub enum StreamError {
    /// The time axis is not finite, increasing and without a gap.
    TimeAxis(HarmonicsError),
    /// The analysis refused the recording.
    Analysis(HarmonicsError),
}

/// Per-revolution record.
#[derive(Debug)]
struct Rev {
    range: Range<usize>,
    /// `2π` less the angle the revolution's samples span.
    closing: f64,
    /// Span of the samples as a fraction of a turn (for an incomplete revolution).
    turns: f64,
    /// [`crate::signal::exact_max_gap`] of the revolution.
    exact_gap: (f64, usize),
    /// The fit (`None` when not fitted: beyond `config.revolutions` or too few samples).
    fit: Option<std::result::Result<RevolutionFit, FitFailure>>,
    /// Whether a gap sample is not finite.
    non_finite_gap: bool,
    /// Largest gap sample by magnitude: index in the recording, value.
    largest: (usize, f64),
}

/// Fits eq. 20 per revolution to samples fed in order, a piece at a time.
#[derive(Debug)]
pub struct StreamingFit {
    config: FitConfig,
    angle: StreamAngle,
    n: usize,
    seen: usize,
    t0: f64,
    prev_t: f64,
    a0: f64,
    prev_a: f64,
    /// First non-finite time or time not increasing (index, error).
    time_error: Option<HarmonicsError>,
    /// First non-finite interval.
    interval_error: Option<(usize, f64)>,
    /// Intervals larger than every earlier one: (index, interval).
    record_intervals: Vec<(usize, f64)>,
    max_interval: f64,
    /// Places of the intervals the nominal interval is the median of.
    nominal_k: usize,
    next_nominal: usize,
    intervals: Vec<f64>,
    /// The place of the next of them (`usize::MAX` past the last).
    next_place: usize,
    first_non_finite_angle: Option<(usize, f64)>,
    step_back: Option<(usize, f64)>,
    max_step: f64,
    first_non_finite_gap: Option<(usize, f64)>,
    /// Encoder span in lanes, as `check_encoder_rate` sums it.
    span_lanes: [f64; 8],
    span_tail: Vec<f64>,
    wraps: i64,
    /// `wraps` at the previous sample.
    prev_wraps: i64,
    /// The next whole turn whose start is looked for (rate).
    next_turn: usize,
    /// The revolution being read: its first sample and its samples.
    open_start: usize,
    buf_t: Vec<f64>,
    buf_y: Vec<f64>,
    buf_a: Vec<f64>,
    revs: Vec<Rev>,
    marks: Vec<SampleMark>,
    /// Revolutions that passed the first start of a turn (encoder crossings).
    crossings: usize,
    /// Whether a revolution used has too few samples: the analysis will fail, so later
    /// revolutions are counted, not kept (a hostile file cannot grow memory with them).
    doomed: bool,
    /// Revolutions counted, not kept.
    extra_revs: usize,
}

impl StreamingFit {
    /// A streamed analysis of a recording of `samples` samples (counted before, so that the
    /// nominal interval's places are known).
    ///
    /// # Errors
    /// Bad settings, as [`analyze`](crate::analyze).
    pub fn new(config: &FitConfig, angle: StreamAngle, samples: usize) -> Result<Self> {
        config.validate()?;
        let m = samples.saturating_sub(1);
        Ok(Self {
            config: config.clone(),
            angle,
            n: samples,
            seen: 0,
            t0: f64::NAN,
            prev_t: f64::NAN,
            a0: f64::NAN,
            prev_a: f64::NAN,
            time_error: None,
            interval_error: None,
            record_intervals: Vec::new(),
            max_interval: 0.0,
            nominal_k: m.min(1025),
            next_nominal: 0,
            intervals: Vec::with_capacity(m.min(1025)),
            next_place: if m > 0 { 0 } else { usize::MAX },
            first_non_finite_angle: None,
            step_back: None,
            max_step: 0.0,
            first_non_finite_gap: None,
            span_lanes: [0.0; 8],
            span_tail: Vec::new(),
            wraps: 0,
            prev_wraps: 0,
            next_turn: 0,
            open_start: 0,
            buf_t: Vec::new(),
            buf_y: Vec::new(),
            buf_a: Vec::new(),
            revs: Vec::new(),
            marks: Vec::new(),
            crossings: 0,
            doomed: false,
            extra_revs: 0,
        })
    }

    /// Samples fed so far.
    pub fn samples_seen(&self) -> usize {
        self.seen
    }

    /// The place of the `j`-th interval of the nominal interval's median.
    fn nominal_place(&self, j: usize) -> usize {
        j * (self.n - 1) / self.nominal_k
    }

    /// Feeds the next samples: times, gaps and (with [`StreamAngle::Encoder`]) angles, of
    /// equal lengths. Samples beyond the number stated are ignored.
    pub fn push(&mut self, time_s: &[f64], gap: &[f64], angle: Option<&[f64]>) {
        // Compiled for the CPU's instruction set (fused multiply-add and rounding inline,
        // as in the in-memory passes; the same operations, so the same bits).
        pulp::Arch::new().dispatch(Push {
            fit: self,
            time_s,
            gap,
            angle,
        });
    }

    #[inline(always)]
    fn push_samples(&mut self, time_s: &[f64], gap: &[f64], angle: Option<&[f64]>) {
        let len = time_s
            .len()
            .min(gap.len())
            .min(self.n - self.seen.min(self.n));
        match angle {
            Some(a) if a.len() >= len => {
                for j in 0..len {
                    self.sample(time_s[j], gap[j], a[j]);
                }
            }
            _ => {
                for j in 0..len {
                    self.sample(time_s[j], gap[j], f64::NAN);
                }
            }
        }
    }

    fn mark(&self, i: usize, t: f64, a: f64) -> SampleMark {
        let angle_rad = match self.angle {
            StreamAngle::Encoder => a,
            StreamAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            } => start_angle_rad + rate_rad_s * (t - self.t0),
        };
        SampleMark {
            index: i,
            time_s: t,
            angle_rad,
            wraps_before: self.wraps,
        }
    }

    #[inline(always)]
    fn sample(&mut self, t: f64, y: f64, a: f64) {
        let i = self.seen;
        let encoder = matches!(self.angle, StreamAngle::Encoder);
        // The encoder's step from the previous sample (unused before the second sample).
        let step = encoder_step(self.prev_a, a);
        if i == 0 {
            self.t0 = t;
            self.a0 = a;
        } else {
            // The time axis, as check_time_axis's scans.
            let prev = self.prev_t;
            if self.time_error.is_none() && !t.is_finite() {
                self.time_error = Some(HarmonicsError::NonFinite {
                    index: i,
                    column: "time",
                    value: t,
                });
            } else if self.time_error.is_none() && t <= prev {
                self.time_error = Some(HarmonicsError::TimeNotIncreasing {
                    index: i,
                    previous_s: prev,
                    time_s: t,
                });
            }
            let d = t - prev;
            if self.next_place == i - 1 {
                self.intervals.push(d);
                self.next_nominal += 1;
                self.next_place = if self.next_nominal < self.nominal_k {
                    self.nominal_place(self.next_nominal)
                } else {
                    usize::MAX
                };
            }
            if d.is_finite() {
                if self.record_intervals.last().is_none_or(|r| d > r.1) {
                    self.record_intervals.push((i, d));
                }
                self.max_interval = self.max_interval.max(d);
            } else if self.interval_error.is_none() {
                self.interval_error = Some((i, d));
            }
            if encoder {
                let pairs = self.n - 1;
                let body = pairs - pairs % 8;
                if i - 1 < body {
                    self.span_lanes[(i - 1) % 8] += step;
                } else {
                    self.span_tail.push(step);
                }
                if self.step_back.is_none() && step < 0.0 {
                    self.step_back = Some((i, step));
                }
                self.max_step = if step > self.max_step {
                    step
                } else {
                    self.max_step
                };
                let dw = a - self.prev_a;
                self.prev_wraps = self.wraps;
                self.wraps += i64::from(dw < -PI) - i64::from(dw > PI);
            }
        }
        if i == 0 && !t.is_finite() {
            self.time_error = Some(HarmonicsError::NonFinite {
                index: 0,
                column: "time",
                value: t,
            });
        }
        if encoder && self.first_non_finite_angle.is_none() && !a.is_finite() {
            self.first_non_finite_angle = Some((i, a));
        }
        if self.first_non_finite_gap.is_none() && !y.is_finite() {
            self.first_non_finite_gap = Some((i, y));
        }
        // Segmentation: does sample i start a revolution?
        let starts = match self.angle {
            StreamAngle::Encoder => i > 0 && phase(self.prev_a, self.a0) + step >= TAU,
            StreamAngle::Rate { rate_rad_s, .. } => {
                let turn = rate_rad_s * (t - self.t0) / TAU;
                // The first sample at or past each whole turn starts it (as
                // `partition_point` finds it); a turn with no sample is an empty revolution,
                // skipped as `segment` skips it. A time that is not finite or goes back
                // is the time axis's error, reported at the end.
                let found = turn.is_finite() && turn >= 0.0 && turn >= self.next_turn as f64;
                if found {
                    self.next_turn = turn.floor() as usize + 1;
                }
                found && i > 0
            }
        };
        if starts {
            if encoder {
                self.crossings += 1;
            }
            if !self.doomed && self.marks.last().is_none_or(|l| l.index != i - 1) {
                // The last sample of the revolution that ends here.
                let end = SampleMark {
                    wraps_before: self.prev_wraps,
                    ..self.mark(i - 1, self.prev_t, self.prev_a)
                };
                self.marks.push(end);
            }
            self.close_revolution(false);
            self.open_start = i;
        }
        if (i == 0 || starts) && !self.doomed {
            let m = self.mark(i, t, a);
            self.marks.push(m);
        }
        self.buf_t.push(t);
        self.buf_y.push(y);
        if encoder {
            self.buf_a.push(a);
        }
        self.prev_t = t;
        self.prev_a = a;
        self.seen += 1;
        if self.seen == self.n {
            let m = self.mark(i, t, a);
            if !self.doomed && self.marks.last().is_none_or(|l| l.index != i) {
                self.marks.push(m);
            }
        }
    }

    #[inline(always)]
    /// Records the revolution held and fits it; the recording's last one, which may be
    /// incomplete, is recorded only (its samples kept), and fitted at the end if complete.
    fn close_revolution(&mut self, last: bool) {
        let range = self.open_start..self.open_start + self.buf_t.len();
        if range.is_empty() {
            return;
        }
        if self.doomed && !last {
            self.extra_revs += 1;
            self.clear();
            return;
        }
        let (t, y, a) = (&self.buf_t, &self.buf_y, &self.buf_a);
        let len = t.len();
        // crate::signal::exact_max_gap on the revolution, with the same operations.
        let (span, exact) = match self.angle {
            StreamAngle::Encoder => {
                let sum: f64 = (0..len - 1).map(|j| encoder_step(a[j], a[j + 1])).sum();
                let mut exact = (TAU - sum, range.end - 1);
                for j in 0..len - 1 {
                    let g = encoder_step(a[j], a[j + 1]);
                    if g > exact.0 {
                        exact = (g, range.start + j);
                    }
                }
                (phase(a[len - 1], self.a0) - phase(a[0], self.a0), exact)
            }
            StreamAngle::Rate { rate_rad_s, .. } => {
                let sum: f64 = (0..len - 1).map(|j| rate_rad_s * (t[j + 1] - t[j])).sum();
                let mut exact = (TAU - sum, range.end - 1);
                for j in 0..len - 1 {
                    let g = rate_rad_s * (t[j + 1] - t[j]);
                    if g > exact.0 {
                        exact = (g, range.start + j);
                    }
                }
                (rate_rad_s * (t[len - 1] - t[0]), exact)
            }
        };
        let (at, value) = largest_gap(y);
        let rev = Rev {
            range: range.clone(),
            closing: TAU - span,
            turns: span / TAU,
            exact_gap: exact,
            fit: None,
            non_finite_gap: y.iter().any(|v| !v.is_finite()),
            largest: (range.start + at, value),
        };
        self.revs.push(rev);
        if !last {
            let r = self.revs.len() - 1;
            let used = self.config.revolutions.is_none_or(|k| r < k);
            if used && len < self.config.min_samples() {
                self.doomed = true;
            }
            self.fit_last_rev();
            self.clear();
        }
    }

    fn clear(&mut self) {
        self.buf_t.clear();
        self.buf_y.clear();
        self.buf_a.clear();
    }

    /// Fits the last recorded revolution from the buffer, when it is among those used and
    /// has enough samples.
    fn fit_last_rev(&mut self) {
        let r = self.revs.len() - 1;
        let rev = &self.revs[r];
        let wanted = self.config.revolutions.is_none_or(|k| r < k);
        if !wanted || rev.range.len() < self.config.min_samples() {
            return;
        }
        let (x, map) = match self.angle {
            StreamAngle::Encoder => (
                &self.buf_a[..],
                AngleMap {
                    shift: 0.0,
                    scale: 1.0,
                    offset: 0.0,
                },
            ),
            StreamAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            } => (
                &self.buf_t[..],
                AngleMap {
                    shift: self.t0,
                    scale: rate_rad_s,
                    offset: start_angle_rad,
                },
            ),
        };
        let samples = RevolutionSamples {
            first_sample: rev.range.start,
            time_s: &self.buf_t,
            gap: &self.buf_y,
            x,
        };
        let fit = fit_samples(samples, map, &self.config, r);
        self.revs[r].fit = Some(fit);
    }

    /// The analysis, or the first error in the order [`analyze`](crate::analyze) checks.
    ///
    /// # Errors
    /// [`StreamError::TimeAxis`] for the time axis's errors, [`StreamError::Analysis`] for
    /// the others, each as [`crate::check_time_axis`] and [`analyze`](crate::analyze)
    /// give them.
    pub fn finish(mut self) -> std::result::Result<StreamedAnalysis, StreamError> {
        let gap_limit = self.config.max_gap_intervals;
        check_setting_gap(gap_limit).map_err(StreamError::Analysis)?;
        let n = self.seen;
        if n != self.n || n < 2 {
            // Fewer samples than stated: nothing is fitted from a half-read recording.
            return Err(StreamError::Analysis(
                HarmonicsError::NoCompleteRevolution {
                    samples: n,
                    turns: 0.0,
                },
            ));
        }
        let time_axis = self.check_time_axis().map_err(StreamError::TimeAxis)?;
        let order = self.config.order;
        let analysis_error = StreamError::Analysis;
        // segment(): the angle's own checks.
        let nominal_step = match self.angle {
            StreamAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            } => {
                if !(rate_rad_s.is_finite() && rate_rad_s > 0.0) {
                    return Err(analysis_error(HarmonicsError::InvalidRate { rate_rad_s }));
                }
                if !start_angle_rad.is_finite() {
                    return Err(analysis_error(HarmonicsError::InvalidSetting {
                        field: "start_angle_rad",
                        value: start_angle_rad,
                        requirement: Requirement::Finite,
                    }));
                }
                let limit_rad = PI / order as f64;
                let refuse = |interval_s: f64| HarmonicsError::RateAliases {
                    rate_rad_s,
                    interval_s,
                    step_rad: rate_rad_s * interval_s,
                    order,
                    limit_rad,
                };
                if rate_rad_s * time_axis.nominal_interval_s >= limit_rad {
                    return Err(analysis_error(refuse(time_axis.nominal_interval_s)));
                }
                let turns = rate_rad_s * (self.prev_t - self.t0) / TAU;
                if turns >= n as f64 {
                    return Err(analysis_error(refuse(time_axis.max_interval_s)));
                }
                rate_rad_s * time_axis.nominal_interval_s
            }
            StreamAngle::Encoder => {
                if let Some((index, value)) = self.first_non_finite_angle {
                    return Err(analysis_error(HarmonicsError::NonFinite {
                        index,
                        column: "angle",
                        value,
                    }));
                }
                if let Some((index, step_rad)) = self.step_back {
                    return Err(analysis_error(HarmonicsError::AngleNotIncreasing {
                        index,
                        step_rad,
                    }));
                }
                let turns_total = self.crossings as f64;
                ((TAU * turns_total + phase(self.prev_a, self.a0)) / (n - 1) as f64).max(0.0)
            }
        };
        // The last revolution: complete, or dropped as incomplete.
        self.close_revolution(true);
        let last = self.revs.len() - 1;
        let mut incomplete = None;
        let mut incomplete_non_finite = false;
        if self.revs[last].closing > gap_limit * nominal_step {
            let rev = self.revs.pop().expect("a revolution");
            incomplete_non_finite = rev.non_finite_gap;
            incomplete = Some(IncompleteRevolution {
                samples: rev.range,
                turns: rev.turns,
            });
        } else {
            // Fitted from the buffer, which close_revolution(true) kept.
            self.fit_last_rev();
        }
        if self.revs.is_empty() && self.extra_revs == 0 {
            let turns = incomplete.as_ref().map_or(0.0, |i| i.turns);
            return Err(analysis_error(HarmonicsError::NoCompleteRevolution {
                samples: n,
                turns,
            }));
        }
        let step_bound = match self.angle {
            StreamAngle::Rate { rate_rad_s, .. } => rate_rad_s * time_axis.max_interval_s,
            StreamAngle::Encoder => self.max_step,
        };
        let analysis = self.analysis(time_axis, step_bound, incomplete, incomplete_non_finite)?;
        let encoder_span_rad = match self.angle {
            StreamAngle::Encoder => self.span_lanes.iter().sum::<f64>() + tail_sum(&self.span_tail),
            StreamAngle::Rate { .. } => 0.0,
        };
        Ok(StreamedAnalysis {
            analysis,
            time_axis,
            marks: self.marks,
            encoder_span_rad,
        })
    }

    /// The mean rate of the encoder over the samples fed, rad/s: the sum of its wrapped
    /// steps over the time they span ([`check_encoder_rate`](crate::check_encoder_rate)'s
    /// measured rate, to the bit).
    pub fn encoder_rate_rad_s(&self) -> f64 {
        (self.span_lanes.iter().sum::<f64>() + tail_sum(&self.span_tail)) / (self.prev_t - self.t0)
    }

    /// [`crate::check_time_axis`]'s verdict on the samples fed (all of them stated):
    /// what a reader checks first.
    ///
    /// # Errors
    /// Those of [`crate::check_time_axis`], naming the same sample.
    pub fn check_time_axis(&mut self) -> Result<TimeAxis> {
        if self.intervals.is_empty() {
            return Err(HarmonicsError::NoCompleteRevolution {
                samples: self.seen,
                turns: 0.0,
            });
        }
        let mid = self.intervals.len() / 2;
        let nominal = *self.intervals.select_nth_unstable_by(mid, f64::total_cmp).1;
        if let Some(e) = self.time_error.clone() {
            return Err(e);
        }
        let limit = nominal * self.config.max_gap_intervals;
        let gap = self.record_intervals.iter().find(|r| r.1 > limit).copied();
        let first = match (self.interval_error, gap) {
            (Some((i, d)), Some((j, _))) if i < j => Some(Err((i, d))),
            (Some((i, d)), None) => Some(Err((i, d))),
            (_, Some(g)) => Some(Ok(g)),
            (None, None) => None,
        };
        match first {
            Some(Err((index, interval_s))) => {
                Err(HarmonicsError::NonFiniteInterval { index, interval_s })
            }
            Some(Ok((index, interval_s))) => Err(HarmonicsError::SampleGap {
                index,
                interval_s,
                nominal_interval_s: nominal,
                max_intervals: self.config.max_gap_intervals,
            }),
            None => Ok(TimeAxis {
                nominal_interval_s: nominal,
                max_interval_s: self.max_interval,
            }),
        }
    }

    /// `analyze_segmented` on the revolutions recorded.
    fn analysis(
        &mut self,
        time_axis: TimeAxis,
        step_bound: f64,
        incomplete: Option<IncompleteRevolution>,
        incomplete_non_finite: bool,
    ) -> std::result::Result<HarmonicAnalysis, StreamError> {
        let err = StreamError::Analysis;
        let available = self.revs.len() + self.extra_revs;
        let used = match self.config.revolutions {
            Some(k) if k > available => {
                return Err(err(HarmonicsError::TooFewRevolutions {
                    requested: k,
                    available,
                }));
            }
            Some(k) => k,
            None => available,
        };
        let order = self.config.order;
        let need = self.config.min_samples();
        let limit_rad = PI / order as f64;
        // With revolutions counted but not kept (`doomed`), this loop fails at the one
        // that has too few samples, at the latest.
        for (r, rev) in self.revs.iter().take(used).enumerate() {
            let got = rev.range.len();
            if got < need {
                return Err(err(HarmonicsError::TooFewSamples {
                    revolution: r,
                    first_sample: rev.range.start,
                    got,
                    need,
                }));
            }
            let (mut gap, mut at) = if rev.closing > step_bound {
                (rev.closing, rev.range.end - 1)
            } else {
                (step_bound, usize::MAX)
            };
            if gap >= limit_rad && at == usize::MAX {
                (gap, at) = rev.exact_gap;
            }
            if gap >= limit_rad {
                return Err(err(HarmonicsError::Aliasing {
                    revolution: r,
                    after_sample: at,
                    order,
                    max_gap_rad: gap,
                    limit_rad,
                }));
            }
        }
        let gap_error = |(index, value): (usize, f64)| HarmonicsError::NonFinite {
            index,
            column: "gap",
            value,
        };
        let outside = incomplete_non_finite
            || self.revs[used.min(self.revs.len())..]
                .iter()
                .any(|r| r.non_finite_gap);
        if outside && let Some(first) = self.first_non_finite_gap {
            return Err(err(gap_error(first)));
        }
        let mut fits = Vec::with_capacity(used);
        for (r, rev) in self.revs.iter_mut().take(used).enumerate() {
            match rev.fit.take() {
                Some(Ok(f)) => fits.push(f),
                Some(Err(FitFailure::NonFiniteGap)) => {
                    let first = self
                        .first_non_finite_gap
                        .unwrap_or((rev.range.start, f64::NAN));
                    return Err(err(gap_error(first)));
                }
                Some(Err(FitFailure::Other(e))) => return Err(err(e)),
                // Every revolution used with enough samples is fitted; one without is
                // refused above.
                None => {
                    return Err(err(HarmonicsError::TooFewSamples {
                        revolution: r,
                        first_sample: rev.range.start,
                        got: rev.range.len(),
                        need,
                    }));
                }
            }
        }
        let (mean, std, std_error) = statistics(&fits);
        for (quantity, statistic) in [
            ("mean", Some(&mean)),
            ("std", std.as_ref()),
            ("std_error", std_error.as_ref()),
        ] {
            if let Some((field, value)) =
                statistic.and_then(crate::analysis::Coefficients::first_non_finite)
            {
                let mut largest = self.revs[0].largest;
                for rev in &self.revs[1..used] {
                    if rev.largest.1.abs().total_cmp(&largest.1.abs()).is_ge() {
                        largest = rev.largest;
                    }
                }
                return Err(err(HarmonicsError::NonFiniteResult {
                    revolution: None,
                    quantity: quantity_name(quantity, Some(field)),
                    value,
                    largest_gap: largest.1,
                    at_sample: largest.0,
                }));
            }
        }
        Ok(HarmonicAnalysis {
            order,
            drift: self.config.drift,
            revolutions: fits,
            mean,
            std,
            std_error,
            incomplete,
            revolutions_available: available,
            nominal_interval_s: time_axis.nominal_interval_s,
        })
    }
}

/// `Iterator::sum` of the few tail steps, as `check_encoder_rate` adds them.
fn tail_sum(v: &[f64]) -> f64 {
    v.iter().copied().sum()
}

/// [`StreamingFit::push`] as a `pulp` operation.
struct Push<'a, 'f> {
    fit: &'f mut StreamingFit,
    time_s: &'a [f64],
    gap: &'a [f64],
    angle: Option<&'a [f64]>,
}

impl pulp::WithSimd for Push<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        self.fit.push_samples(self.time_s, self.gap, self.angle);
    }
}
