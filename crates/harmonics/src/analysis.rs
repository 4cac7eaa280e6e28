//! Per-revolution Fourier fit of a probe recording and its statistics across revolutions
//! (eq. 20–21).

use std::f64::consts::PI;
use std::ops::Range;

use rayon::prelude::*;

use crate::error::{HarmonicsError, Requirement, Result};
use crate::geometry::FirstHarmonic;
use crate::kernel::{AngleMap, Centring, MAX_ORDER, accumulate};
use crate::signal::{
    IncompleteRevolution, ProbeSignal, Segmentation, SpindleAngle, check_gap_outside,
    exact_max_gap, gap_not_finite, segment,
};
use crate::solve::{parameter_count, solve};

/// The paper's Fourier order (eq. 20 is fitted up to `i = 4`).
pub const DEFAULT_ORDER: usize = 4;

/// Settings of the harmonic fit.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct FitConfig {
    /// Highest Fourier order `N` fitted (1 to [`MAX_ORDER`]; the paper uses 4).
    pub order: usize,
    /// Also fit a linear drift in time within each revolution.
    pub drift: bool,
    /// Use only the first this many complete revolutions (all when `None`).
    pub revolutions: Option<usize>,
    /// Largest interval between samples, in nominal (median) sample intervals, before the
    /// recording is refused as having a gap.
    pub max_gap_intervals: f64,
}

impl Default for FitConfig {
    fn default() -> Self {
        Self {
            order: DEFAULT_ORDER,
            drift: false,
            revolutions: None,
            max_gap_intervals: 3.0,
        }
    }
}

impl FitConfig {
    /// Checks the settings.
    pub fn validate(&self) -> Result<()> {
        if !(1..=MAX_ORDER).contains(&self.order) {
            return Err(HarmonicsError::InvalidOrder {
                order: self.order,
                max: MAX_ORDER,
            });
        }
        if self.revolutions == Some(0) {
            return Err(HarmonicsError::InvalidSetting {
                field: "revolutions",
                value: 0.0,
                requirement: Requirement::AtLeastOne,
            });
        }
        crate::signal::check_setting_gap(self.max_gap_intervals)
    }

    /// Fewest samples a revolution needs: more than the `2N + 1` (or `2N + 2` with drift)
    /// parameters, and at least `2N + 2` so that order `N` is resolved.
    pub const fn min_samples(&self) -> usize {
        let p = parameter_count(self.order, self.drift);
        let resolve = 2 * self.order + 2;
        if p + 1 > resolve { p + 1 } else { resolve }
    }
}

/// Fourier coefficients of the gap (eq. 20),
/// `Δd(θ) = l0 + Σₖ (c[k−1] cos kθ + s[k−1] sin kθ)` (+ drift), in the gap's unit.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Coefficients {
    /// Constant term `l0` (with drift: its value at the revolution's middle time).
    pub l0: f64,
    /// Cosine coefficients `d_ck`; index 0 is order 1.
    pub c: Vec<f64>,
    /// Sine coefficients `d_sk`; index 0 is order 1.
    pub s: Vec<f64>,
    /// Linear drift, gap unit per second (when fitted).
    pub drift_per_s: Option<f64>,
}

impl Coefficients {
    /// The Fourier order.
    pub fn order(&self) -> usize {
        self.c.len()
    }

    /// The periodic part `l0 + Σ (c cos kθ + s sin kθ)` at angle `θ` (drift left out).
    ///
    /// ```
    /// # use harmonics::Coefficients;
    /// let k = Coefficients { l0: 1.0, c: vec![2.0, 0.5], s: vec![-1.0, 0.0], drift_per_s: None };
    /// approx::assert_relative_eq!(k.evaluate(0.0), 3.5, max_relative = 1e-15);
    /// approx::assert_relative_eq!(k.evaluate(std::f64::consts::FRAC_PI_2), -0.5, epsilon = 1e-15);
    /// ```
    pub fn evaluate(&self, theta_rad: f64) -> f64 {
        let mut v = self.l0;
        for (k, (c, s)) in self.c.iter().zip(&self.s).enumerate() {
            let (sin, cos) = ((k + 1) as f64 * theta_rad).sin_cos();
            v += c * cos + s * sin;
        }
        v
    }

    /// The first harmonic `(d_c1, d_s1)` (eq. 21).
    pub fn first_harmonic(&self) -> Result<FirstHarmonic> {
        FirstHarmonic {
            c1: self.c[0],
            s1: self.s[0],
        }
        .validated()
    }

    /// Every coefficient multiplied by `k`, e.g. to change the gap's unit.
    ///
    /// ```
    /// # use harmonics::Coefficients;
    /// let mm = Coefficients { l0: 0.05, c: vec![-0.003], s: vec![0.001], drift_per_s: None };
    /// let um = mm.scaled(1e3);
    /// approx::assert_relative_eq!(um.c[0], -3.0, max_relative = 1e-15);
    /// ```
    #[must_use]
    pub fn scaled(&self, k: f64) -> Self {
        self.map(|v| v * k)
    }

    /// The first coefficient that is not finite, by field name, with its value.
    pub(crate) fn first_non_finite(&self) -> Option<(&'static str, f64)> {
        let fields = std::iter::once(("l0", self.l0))
            .chain(self.c.iter().map(|&v| ("c", v)))
            .chain(self.s.iter().map(|&v| ("s", v)))
            .chain(self.drift_per_s.map(|v| ("drift_per_s", v)));
        fields.into_iter().find(|(_, v)| !v.is_finite())
    }

    fn map(&self, f: impl Fn(f64) -> f64) -> Self {
        Self {
            l0: f(self.l0),
            c: self.c.iter().map(|&v| f(v)).collect(),
            s: self.s.iter().map(|&v| f(v)).collect(),
            drift_per_s: self.drift_per_s.map(&f),
        }
    }

    fn zip(&self, other: &Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Self {
            l0: f(self.l0, other.l0),
            c: self
                .c
                .iter()
                .zip(&other.c)
                .map(|(&a, &b)| f(a, b))
                .collect(),
            s: self
                .s
                .iter()
                .zip(&other.s)
                .map(|(&a, &b)| f(a, b))
                .collect(),
            drift_per_s: self
                .drift_per_s
                .zip(other.drift_per_s)
                .map(|(a, b)| f(a, b)),
        }
    }
}

/// The fit of one revolution.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RevolutionFit {
    /// Index of its first sample.
    pub first_sample: usize,
    /// Number of samples.
    pub samples: usize,
    /// The fitted coefficients.
    pub coefficients: Coefficients,
    /// Root mean square of the residuals, gap unit (floor about `√ε` times the signal's
    /// RMS about its first sample, as the residual sum comes from the normal equations).
    pub residual_rms: f64,
    /// 1-norm condition number of the scaled normal matrix.
    pub condition: f64,
}

/// The harmonic analysis of a recording: per-revolution fits and their statistics.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HarmonicAnalysis {
    /// Fourier order `N`.
    pub order: usize,
    /// Whether a drift term was fitted.
    pub drift: bool,
    /// The fit of each revolution used.
    pub revolutions: Vec<RevolutionFit>,
    /// Mean of each coefficient across revolutions.
    pub mean: Coefficients,
    /// Sample standard deviation across revolutions (`None` with a single revolution).
    pub std: Option<Coefficients>,
    /// Standard error of the mean, `std/√revolutions` (`None` with a single revolution).
    pub std_error: Option<Coefficients>,
    /// The trailing incomplete revolution, dropped.
    pub incomplete: Option<IncompleteRevolution>,
    /// Complete revolutions in the recording (at least the number used).
    pub revolutions_available: usize,
    /// Nominal (median) sample interval, s.
    pub nominal_interval_s: f64,
}

impl HarmonicAnalysis {
    /// Number of revolutions averaged.
    pub fn revolutions_used(&self) -> usize {
        self.revolutions.len()
    }

    /// The mean first harmonic (eq. 21).
    pub fn first_harmonic(&self) -> Result<FirstHarmonic> {
        self.mean.first_harmonic()
    }
}

/// Fits eq. 20 to every complete revolution of a recording and averages the coefficients.
///
/// One streaming pass per revolution accumulates the normal equations (no design matrix);
/// see the crate documentation for the method and its checks.
///
/// ```
/// use harmonics::{analyze, FitConfig, ProbeSignal, SpindleAngle};
/// let rate_rad_s = 10f64.to_radians();
/// let time_s: Vec<f64> = (0..36_000 * 2).map(|i| i as f64 * 1e-3).collect();
/// let gap: Vec<f64> = time_s.iter()
///     .map(|t| 50.0 - 3.2 * (rate_rad_s * t).cos() - 1.1 * (rate_rad_s * t).sin()
///              + 0.2 * (4.0 * rate_rad_s * t).cos())
///     .collect();
/// let signal = ProbeSignal { time_s: &time_s, gap: &gap,
///     angle: SpindleAngle::Rate { rate_rad_s, start_angle_rad: 0.0 } };
/// let fit = analyze(&signal, &FitConfig::default())?;
/// assert_eq!(fit.revolutions_used(), 2);
/// approx::assert_relative_eq!(fit.mean.c[0], -3.2, epsilon = 1e-9);
/// approx::assert_relative_eq!(fit.mean.s[0], -1.1, epsilon = 1e-9);
/// approx::assert_relative_eq!(fit.mean.c[3], 0.2, epsilon = 1e-9);
/// approx::assert_relative_eq!(fit.first_harmonic()?.amplitude(), 3.2f64.hypot(1.1), epsilon = 1e-9);
/// # Ok::<(), harmonics::HarmonicsError>(())
/// ```
pub fn analyze(signal: &ProbeSignal<'_>, config: &FitConfig) -> Result<HarmonicAnalysis> {
    config.validate()?;
    let seg = segment(signal, config.max_gap_intervals, config.order)?;
    analyze_segmented(signal, config, &seg)
}

/// Fewest samples in the revolutions used for which they are fitted in parallel.
const PARALLEL_SAMPLES: usize = 1 << 16;

/// Whether any value of `x` is not finite.
fn first_non_finite_in(x: &[f64]) -> bool {
    x.iter().any(|v| !v.is_finite())
}

/// Fits one revolution (its sampling already checked).
fn fit_revolution(
    signal: &ProbeSignal<'_>,
    x: &[f64],
    map: AngleMap,
    config: &FitConfig,
    r: usize,
    range: Range<usize>,
) -> Result<RevolutionFit> {
    let samples = RevolutionSamples {
        first_sample: range.start,
        time_s: &signal.time_s[range.clone()],
        gap: &signal.gap[range.clone()],
        x: &x[range],
    };
    fit_samples(samples, map, config, r).map_err(|e| match e {
        FitFailure::NonFiniteGap => {
            // A non-finite sample (or one beyond ~1e154, which the solution names below):
            // the recording's first non-finite sample is the error, as before the fit.
            gap_not_finite(signal.gap).expect("a non-finite sample was seen")
        }
        FitFailure::Other(e) => e,
    })
}

/// The samples of one revolution: its first sample's index in the recording, its times,
/// gaps and angle sources (`x`: the encoder angle, or the time with a rate).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RevolutionSamples<'a> {
    pub(crate) first_sample: usize,
    pub(crate) time_s: &'a [f64],
    pub(crate) gap: &'a [f64],
    pub(crate) x: &'a [f64],
}

/// Why [`fit_samples`] failed: a non-finite gap sample (which the caller names as the
/// recording's first), or another error.
#[derive(Debug)]
pub(crate) enum FitFailure {
    NonFiniteGap,
    Other(HarmonicsError),
}

/// Fits one revolution held in slices (its sampling already checked): the same operations
/// whether the recording is in memory or streamed a revolution at a time.
pub(crate) fn fit_samples(
    rev: RevolutionSamples<'_>,
    map: AngleMap,
    config: &FitConfig,
    r: usize,
) -> std::result::Result<RevolutionFit, FitFailure> {
    let order = config.order;
    let t = rev.time_s;
    let (t_first, t_last) = (t[0], t[t.len() - 1]);
    let centre = Centring {
        y_ref: rev.gap[0],
        t_mid: 0.5 * (t_first + t_last),
        t_inv_half: 2.0 / (t_last - t_first),
    };
    let sums = accumulate(order, config.drift, rev.x, rev.gap, t, map, centre);
    if !sums.yy.is_finite() && first_non_finite_in(rev.gap) {
        return Err(FitFailure::NonFiniteGap);
    }
    let sol = solve(&sums, order, config.drift, r).map_err(FitFailure::Other)?;
    let coefficients = Coefficients {
        l0: sol.x[0] + centre.y_ref,
        c: sol.x[1..=order].to_vec(),
        s: sol.x[order + 1..=2 * order].to_vec(),
        drift_per_s: config
            .drift
            .then(|| sol.x[2 * order + 1] * centre.t_inv_half),
    };
    let residual_rms = (sol.rss / t.len() as f64).sqrt();
    let non_finite = match coefficients.first_non_finite() {
        Some((field, value)) => Some(("coefficients", Some(field), value)),
        None if !residual_rms.is_finite() => Some(("residual_rms", None, residual_rms)),
        None => None,
    };
    if let Some((quantity, coefficient, value)) = non_finite {
        let (at, largest_gap) = largest_gap(rev.gap);
        return Err(FitFailure::Other(HarmonicsError::NonFiniteResult {
            revolution: Some(r),
            quantity: quantity_name(quantity, coefficient),
            value,
            largest_gap,
            at_sample: rev.first_sample + at,
        }));
    }
    Ok(RevolutionFit {
        first_sample: rev.first_sample,
        samples: t.len(),
        coefficients,
        residual_rms,
        condition: sol.condition,
    })
}

/// The largest gap sample by magnitude (the last of equal ones) and its index in `gap`;
/// `(0, NaN)` for no samples.
pub(crate) fn largest_gap(gap: &[f64]) -> (usize, f64) {
    gap.iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap_or((0, f64::NAN))
}

/// `std.c` for the statistic `std` and the coefficient `c` (static names for the error).
pub(crate) fn quantity_name(
    quantity: &'static str,
    coefficient: Option<&'static str>,
) -> &'static str {
    match (quantity, coefficient) {
        ("coefficients", Some("l0")) => "coefficients.l0",
        ("coefficients", Some("c")) => "coefficients.c",
        ("coefficients", Some("s")) => "coefficients.s",
        ("coefficients", Some(_)) => "coefficients.drift_per_s",
        ("mean", Some("l0")) => "mean.l0",
        ("mean", Some("c")) => "mean.c",
        ("mean", Some("s")) => "mean.s",
        ("mean", Some(_)) => "mean.drift_per_s",
        ("std", Some("l0")) => "std.l0",
        ("std", Some("c")) => "std.c",
        ("std", Some("s")) => "std.s",
        ("std", Some(_)) => "std.drift_per_s",
        ("std_error", Some("l0")) => "std_error.l0",
        ("std_error", Some("c")) => "std_error.c",
        ("std_error", Some("s")) => "std_error.s",
        ("std_error", Some(_)) => "std_error.drift_per_s",
        (other, _) => other,
    }
}

/// [`HarmonicsError::NonFiniteResult`], naming the largest gap among `samples`.
fn non_finite_result(
    signal: &ProbeSignal<'_>,
    revolution: Option<usize>,
    quantity: &'static str,
    coefficient: Option<&'static str>,
    value: f64,
    samples: Range<usize>,
) -> HarmonicsError {
    let start = samples.start;
    let (at, largest_gap) = largest_gap(&signal.gap[samples]);
    HarmonicsError::NonFiniteResult {
        revolution,
        quantity: quantity_name(quantity, coefficient),
        value,
        largest_gap,
        at_sample: start + at,
    }
}

/// Mean, sample standard deviation and standard error of the mean of the revolutions'
/// coefficients (no spread with fewer than two revolutions). At least one revolution.
pub(crate) fn statistics(
    fits: &[RevolutionFit],
) -> (Coefficients, Option<Coefficients>, Option<Coefficients>) {
    let k = fits.len() as f64;
    let first = &fits[0].coefficients;
    let sum = fits[1..].iter().fold(first.clone(), |acc, f| {
        acc.zip(&f.coefficients, |a, b| a + b)
    });
    let mean = sum.map(|v| v / k);
    if fits.len() < 2 {
        return (mean, None, None);
    }
    let zero = mean.map(|_| 0.0);
    let ss = fits.iter().fold(zero, |acc, f| {
        let d = f.coefficients.zip(&mean, |a, m| a - m);
        acc.zip(&d, |a, d| a + d * d)
    });
    let std = ss.map(|v| (v / (k - 1.0)).sqrt());
    let se = std.map(|v| v / k.sqrt());
    (mean, Some(std), Some(se))
}

/// [`analyze`] on a recording already cut by [`segment`] (with the same signal).
pub(crate) fn analyze_segmented(
    signal: &ProbeSignal<'_>,
    config: &FitConfig,
    seg: &Segmentation,
) -> Result<HarmonicAnalysis> {
    config.validate()?;
    let available = seg.revolutions.len();
    let used = match config.revolutions {
        Some(k) if k > available => {
            return Err(HarmonicsError::TooFewRevolutions {
                requested: k,
                available,
            });
        }
        Some(k) => k,
        None => available,
    };
    let order = config.order;
    let need = config.min_samples();
    let limit_rad = PI / order as f64;
    let (x, map): (&[f64], AngleMap) = match signal.angle {
        SpindleAngle::Encoder(a) => (
            a,
            AngleMap {
                shift: 0.0,
                scale: 1.0,
                offset: 0.0,
            },
        ),
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        } => (
            signal.time_s,
            AngleMap {
                shift: signal.time_s[0],
                scale: rate_rad_s,
                offset: start_angle_rad,
            },
        ),
    };

    // Sampling checks first, in order, so that the first offending revolution is named.
    let revolutions = &seg.revolutions[..used];
    for (r, range) in revolutions.iter().enumerate() {
        let got = range.len();
        if got < need {
            return Err(HarmonicsError::TooFewSamples {
                revolution: r,
                first_sample: range.start,
                got,
                need,
            });
        }
        let (mut gap, mut at) = seg.max_gaps[r];
        if gap >= limit_rad && at == usize::MAX {
            // Only a bound was known: find the revolution's own largest gap.
            (gap, at) = exact_max_gap(signal, range.clone());
        }
        if gap >= limit_rad {
            return Err(HarmonicsError::Aliasing {
                revolution: r,
                after_sample: at,
                order,
                max_gap_rad: gap,
                limit_rad,
            });
        }
    }
    // A non-finite gap sample outside the revolutions fitted (inside them the fit's own
    // pass finds it).
    check_gap_outside(signal.gap, revolutions)?;
    // The revolutions are independent: fit them on all cores when there is enough work
    // (`RAYON_NUM_THREADS=1` keeps it to one), and report the first failure in order.
    let fit = |(r, range): (usize, &Range<usize>)| {
        fit_revolution(signal, x, map, config, r, range.clone())
    };
    let total: usize = revolutions.iter().map(|r| r.len()).sum();
    let parallel =
        revolutions.len() > 1 && total >= PARALLEL_SAMPLES && rayon::current_num_threads() > 1;
    let fits: Vec<RevolutionFit> = if parallel {
        revolutions
            .par_iter()
            .enumerate()
            .map(fit)
            .collect::<Vec<_>>()
            .into_iter()
            .collect::<Result<_>>()?
    } else {
        revolutions
            .iter()
            .enumerate()
            .map(fit)
            .collect::<Result<_>>()?
    };

    let (mean, std, std_error) = statistics(&fits);
    let span = revolutions.first().map_or(0, |r| r.start)..revolutions.last().map_or(0, |r| r.end);
    for (quantity, statistic) in [
        ("mean", Some(&mean)),
        ("std", std.as_ref()),
        ("std_error", std_error.as_ref()),
    ] {
        if let Some((field, value)) = statistic.and_then(Coefficients::first_non_finite) {
            return Err(non_finite_result(
                signal,
                None,
                quantity,
                Some(field),
                value,
                span,
            ));
        }
    }
    Ok(HarmonicAnalysis {
        order,
        drift: config.drift,
        revolutions: fits,
        mean,
        std,
        std_error,
        incomplete: seg.incomplete.clone(),
        revolutions_available: available,
        nominal_interval_s: seg.time_axis.nominal_interval_s,
    })
}
