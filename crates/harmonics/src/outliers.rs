//! Revolutions and samples that do not fit like the rest (issue 32): a revolution whose
//! residual RMS is far above the others' (one glitch sample of 937 µm among samples that
//! fit to 0.045 µm moved that rate's first harmonic with no warning), and residuals that
//! alternate in sign from sample to sample (every other sample zeroed, or two interleaved
//! channels that disagree, halve the first harmonic with residuals no larger from one
//! revolution to the next). Both are found from the fits already made; dropping revolutions
//! recomputes the statistics of the others.

use crate::analysis::{HarmonicAnalysis, RevolutionFit, statistics};
use std::ops::Range;

use crate::signal::{ProbeSignal, SpindleAngle};

/// A revolution whose residual RMS exceeds this many times the median of the revolutions'
/// is an outlier. White noise alone puts a revolution of `n` samples within about
/// `1 ± 3/√(2n)` of the median; a factor 5 is beyond it for any revolution the fit accepts.
pub const OUTLIER_RMS_RATIO: f64 = 5.0;

/// Fewest revolutions for the outlier test: with two, neither is "the others".
pub const MIN_REVOLUTIONS_FOR_OUTLIERS: usize = 3;

/// How far the residuals' lag-one autocorrelation must lie below what white noise gives
/// after the same fit, as a fraction of the way from there to −1 (perfect alternation), for
/// them to alternate in sign. White noise left by a fit of order `K` (and drift) on `n`
/// samples per revolution is itself anticorrelated: its residuals hold only the harmonics
/// above `K`, whose lag-one autocorrelation is about
/// `−(1 + 2 Σₖ cos(k Δθ)) / (n − 2K − 1)` (−0.64 for 18 samples per revolution at order 4,
/// about 0 for hundreds). With many samples per revolution the limit is a lag-one
/// autocorrelation of −0.5; every other sample zeroed gives about −1.
pub const ALTERNATING_EXCESS_LIMIT: f64 = 0.5;

/// Below this distance between white noise's lag-one autocorrelation after the fit and −1
/// (too few samples per revolution for the order fitted) an alternation cannot be told from
/// noise and none is reported.
const ALTERNATION_MIN_ROOM: f64 = 0.1;

/// Residuals below this fraction of the gap's scale (`|l0|` plus the first harmonic's
/// amplitude) are rounding, not signal: they make neither an outlier nor an alternation.
const ROUNDING_FLOOR: f64 = 1e-9;

/// Revolutions examined for alternating residuals (evenly spread; each whole).
const ALTERNATION_REVOLUTIONS: usize = 8;

/// A revolution whose residual RMS is far above the others'.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidualOutlier {
    /// Its index among the analysis's revolutions.
    pub revolution: usize,
    /// Its first sample (index into the signal).
    pub first_sample: usize,
    /// Its residual RMS, gap unit.
    pub residual_rms: f64,
    /// Its largest residual, gap unit (signed).
    pub largest_residual: f64,
    /// The sample of the largest residual (index into the signal).
    pub largest_at_sample: usize,
}

/// The outliers of an analysis against the median residual RMS of its revolutions.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidualOutliers {
    /// The outlying revolutions, in order.
    pub revolutions: Vec<ResidualOutlier>,
    /// The median residual RMS of all the revolutions, gap unit.
    pub median_rms: f64,
    /// How many revolutions were compared.
    pub compared: usize,
}

/// Residuals that alternate in sign from sample to sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlternatingResiduals {
    /// The residuals' lag-one autocorrelation (within revolutions).
    pub lag1: f64,
    /// What white noise would give after the same fit (the same samples per revolution,
    /// order and drift): the reference `lag1` is compared with.
    pub white_noise_lag1: f64,
    /// The residual RMS of the revolutions examined, gap unit.
    pub residual_rms: f64,
    /// How many revolutions were examined.
    pub revolutions: usize,
}

/// The gap's scale, for the rounding floor.
fn scale(analysis: &HarmonicAnalysis) -> f64 {
    analysis.mean.l0.abs() + analysis.mean.c[0].hypot(analysis.mean.s[0])
}

/// The revolutions whose residual RMS exceeds [`OUTLIER_RMS_RATIO`] times the median of all
/// (and the rounding floor), with each one's largest residual; `None` with fewer than
/// [`MIN_REVOLUTIONS_FOR_OUTLIERS`] revolutions or none outlying. `signal` is the one
/// `analysis` was fitted to.
///
/// ```
/// use harmonics::{analyze, residual_outliers, FitConfig, ProbeSignal, SpindleAngle};
/// let rate = 36f64.to_radians();
/// let time_s: Vec<f64> = (0..10_000 * 5).map(|i| i as f64 * 1e-3).collect();
/// let mut gap: Vec<f64> = time_s.iter().enumerate()
///     .map(|(i, t)| 50.0 + 3.0 * (rate * t).cos() + 0.01 * ((i * 7919 % 101) as f64 / 50.0 - 1.0))
///     .collect();
/// gap[23_456] += 900.0; // one glitch in the third revolution
/// let signal = ProbeSignal { time_s: &time_s, gap: &gap,
///     angle: SpindleAngle::Rate { rate_rad_s: rate, start_angle_rad: 0.0 } };
/// let fit = analyze(&signal, &FitConfig::default())?;
/// let found = residual_outliers(&signal, &fit).unwrap();
/// assert_eq!(found.revolutions.len(), 1);
/// assert_eq!((found.revolutions[0].revolution, found.revolutions[0].largest_at_sample), (2, 23_456));
/// # Ok::<(), harmonics::HarmonicsError>(())
/// ```
pub fn residual_outliers(
    signal: &ProbeSignal<'_>,
    analysis: &HarmonicAnalysis,
) -> Option<ResidualOutliers> {
    in_memory(signal, |source| residual_outliers_in(source, analysis))
}

/// [`residual_outliers`] with the outlying revolutions' samples read from `source` (a
/// recording streamed from its file reads them again; one in memory lends them).
///
/// # Errors
/// The source's, when it cannot give a revolution's samples.
pub fn residual_outliers_in<S: RevolutionSource>(
    source: &mut S,
    analysis: &HarmonicAnalysis,
) -> Result<Option<ResidualOutliers>, S::Error> {
    let fits = &analysis.revolutions;
    if fits.len() < MIN_REVOLUTIONS_FOR_OUTLIERS {
        return Ok(None);
    }
    let mut rms: Vec<f64> = fits.iter().map(|f| f.residual_rms).collect();
    rms.sort_by(f64::total_cmp);
    let n = rms.len();
    let median_rms = if n % 2 == 1 {
        rms[n / 2]
    } else {
        0.5 * (rms[n / 2 - 1] + rms[n / 2])
    };
    let limit = (OUTLIER_RMS_RATIO * median_rms).max(ROUNDING_FLOOR * scale(analysis));
    let mut revolutions: Vec<ResidualOutlier> = Vec::new();
    for (r, f) in fits.iter().enumerate() {
        if f.residual_rms > limit {
            let window = source.samples(f.first_sample..f.first_sample + f.samples)?;
            let (largest_at_sample, largest_residual) = residuals(&window, f)
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .unwrap_or((f.first_sample, f64::NAN));
            revolutions.push(ResidualOutlier {
                revolution: r,
                first_sample: f.first_sample,
                residual_rms: f.residual_rms,
                largest_residual,
                largest_at_sample,
            });
        }
    }
    Ok((!revolutions.is_empty()).then_some(ResidualOutliers {
        revolutions,
        median_rms,
        compared: n,
    }))
}

/// The analysis without the revolutions listed (indices into its revolutions): the mean,
/// standard deviation and standard error of the others. All of them are kept when every
/// one would go.
#[must_use]
pub fn without_revolutions(analysis: &HarmonicAnalysis, drop: &[usize]) -> HarmonicAnalysis {
    let kept: Vec<RevolutionFit> = analysis
        .revolutions
        .iter()
        .enumerate()
        .filter(|(r, _)| !drop.contains(r))
        .map(|(_, f)| f.clone())
        .collect();
    if kept.is_empty() || kept.len() == analysis.revolutions.len() {
        return analysis.clone();
    }
    let (mean, std, std_error) = statistics(&kept);
    HarmonicAnalysis {
        revolutions: kept,
        mean,
        std,
        std_error,
        ..analysis.clone()
    }
}

/// Whether the residuals alternate in sign from sample to sample: their lag-one
/// autocorrelation within up to eight revolutions spread over the recording lies further
/// below what white noise gives after the same fit than [`ALTERNATING_EXCESS_LIMIT`] of the
/// way to −1, and they are above the rounding floor. `signal` is the one `analysis` was
/// fitted to.
///
/// ```
/// use harmonics::{alternating_residuals, analyze, FitConfig, ProbeSignal, SpindleAngle};
/// let rate = 36f64.to_radians();
/// // 18 samples per revolution: white noise after an order-4 fit is itself anticorrelated.
/// let time_s: Vec<f64> = (0..18 * 6).map(|i| i as f64 * 10.0 / 18.0).collect();
/// let noise = |i: usize| 0.01 * ((i * 7919 % 101) as f64 / 50.0 - 1.0);
/// let clean: Vec<f64> = time_s.iter().enumerate()
///     .map(|(i, t)| 50.0 + 3.0 * (rate * t).cos() + noise(i)).collect();
/// let angle = SpindleAngle::Rate { rate_rad_s: rate, start_angle_rad: 0.0 };
/// let signal = ProbeSignal { time_s: &time_s, gap: &clean, angle };
/// let fit = analyze(&signal, &FitConfig::default())?;
/// assert_eq!(alternating_residuals(&signal, &fit), None);
/// // Every other sample zeroed: the first harmonic halved, and warned.
/// let zeroed: Vec<f64> = clean.iter().enumerate()
///     .map(|(i, g)| if i % 2 == 1 { 0.0 } else { *g }).collect();
/// let signal = ProbeSignal { time_s: &time_s, gap: &zeroed, angle };
/// let fit = analyze(&signal, &FitConfig::default())?;
/// let found = alternating_residuals(&signal, &fit).unwrap();
/// assert!(found.lag1 < -0.9 && found.white_noise_lag1 < -0.5, "{found:?}");
/// # Ok::<(), harmonics::HarmonicsError>(())
/// ```
pub fn alternating_residuals(
    signal: &ProbeSignal<'_>,
    analysis: &HarmonicAnalysis,
) -> Option<AlternatingResiduals> {
    in_memory(signal, |source| alternating_residuals_in(source, analysis))
}

/// [`alternating_residuals`] with the examined revolutions' samples read from `source`.
///
/// # Errors
/// The source's, when it cannot give a revolution's samples.
pub fn alternating_residuals_in<S: RevolutionSource>(
    source: &mut S,
    analysis: &HarmonicAnalysis,
) -> Result<Option<AlternatingResiduals>, S::Error> {
    let fits = &analysis.revolutions;
    let step = fits.len().div_ceil(ALTERNATION_REVOLUTIONS).max(1);
    let (mut lagged, mut squares, mut count) = (0.0_f64, 0.0_f64, 0_usize);
    // What white noise of unit variance would leave: E[Σ r_i r_{i+1}] and E[Σ r_i²].
    let (mut noise_lagged, mut noise_squares) = (0.0_f64, 0.0_f64);
    let mut examined = 0;
    for fit in fits.iter().step_by(step) {
        examined += 1;
        let window = source.samples(fit.first_sample..fit.first_sample + fit.samples)?;
        let signal = &window;
        let (l, q) = white_noise_residual_moments(signal, fit, analysis.order, analysis.drift);
        noise_lagged += l;
        noise_squares += q;
        let mut previous: Option<f64> = None;
        for (_, r) in residuals(signal, fit) {
            if let Some(p) = previous {
                lagged += p * r;
            }
            squares += r * r;
            count += 1;
            previous = Some(r);
        }
    }
    if count < 2 || !(lagged.is_finite() && squares.is_finite()) {
        return Ok(None);
    }
    let residual_rms = (squares / count as f64).sqrt();
    let lag1 = lagged / squares;
    if noise_squares <= 0.0 {
        return Ok(None);
    }
    let white_noise_lag1 = (noise_lagged / noise_squares).clamp(-1.0, 1.0);
    let room = 1.0 + white_noise_lag1;
    let excess = (white_noise_lag1 - lag1) / room;
    Ok((room >= ALTERNATION_MIN_ROOM
        && residual_rms > ROUNDING_FLOOR * scale(analysis)
        && excess > ALTERNATING_EXCESS_LIMIT)
        .then_some(AlternatingResiduals {
            lag1,
            white_noise_lag1,
            residual_rms,
            revolutions: examined,
        }))
}

/// For white noise of unit variance fitted as `fit` was (order `order`, drift or not), the
/// expected lag-one sum `E[Σ r_i r_{i+1}] = −Σ H_{i,i+1}` and sum of squares
/// `E[Σ r_i²] = n − p` of its residuals, `H` the fit's hat matrix. The Fourier part of `H`
/// is taken as on a whole revolution sampled evenly in angle,
/// `H_ij ≈ (1 + 2 Σₖ cos k(θ_j − θ_i)) / n`, with each step's own angle; the drift part
/// exactly, `d_i d_j / Σ d²` (`d` the time from the revolution's middle).
fn white_noise_residual_moments(
    signal: &SampleWindow<'_>,
    fit: &RevolutionFit,
    order: usize,
    drift: bool,
) -> (f64, f64) {
    let n = fit.samples;
    let parameters = 2 * order + 1 + usize::from(drift);
    if n <= parameters + 1 {
        return (0.0, 0.0);
    }
    // Indices into the window.
    let range = fit.first_sample - signal.first_sample..fit.first_sample - signal.first_sample + n;
    let t = &signal.time_s[range.clone()];
    let angle = |i: usize| match signal.angle {
        SpindleAngle::Encoder(a) => a[i],
        SpindleAngle::Rate { rate_rad_s, .. } => rate_rad_s * signal.time_s[i],
    };
    let n_f = n as f64;
    let mut hat_lag = 0.0;
    for i in range.start..range.end - 1 {
        let step = angle(i + 1) - angle(i);
        let fourier: f64 = (1..=order).map(|k| (k as f64 * step).cos()).sum();
        hat_lag += (1.0 + 2.0 * fourier) / n_f;
    }
    if drift {
        let t_mid = 0.5 * (t[0] + t[n - 1]);
        let d: Vec<f64> = t.iter().map(|x| x - t_mid).collect();
        let dd: f64 = d.iter().map(|x| x * x).sum();
        if dd > 0.0 {
            hat_lag += d.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / dd;
        }
    }
    (-hat_lag, n_f - parameters as f64)
}

/// The residuals of one revolution's fit, `(sample, gap − fit)`.
fn residuals<'a>(
    signal: &'a SampleWindow<'_>,
    fit: &'a RevolutionFit,
) -> impl Iterator<Item = (usize, f64)> + 'a {
    let offset = signal.first_sample;
    let range = fit.first_sample - offset..fit.first_sample - offset + fit.samples;
    let t = &signal.time_s[range.clone()];
    let t_mid = 0.5 * (t[0] + t[t.len() - 1]);
    let k = &fit.coefficients;
    range.map(move |i| {
        let theta = match signal.angle {
            SpindleAngle::Encoder(a) => a[i],
            SpindleAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            } => start_angle_rad + rate_rad_s * (signal.time_s[i] - signal.recording_start_s),
        };
        let drift = k
            .drift_per_s
            .map_or(0.0, |b| b * (signal.time_s[i] - t_mid));
        (offset + i, signal.gap[i] - k.evaluate(theta) - drift)
    })
}

/// Some consecutive samples of a recording, lent for the checks that look at a
/// revolution's residuals after the fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleWindow<'a> {
    /// Index in the recording of the window's first sample.
    pub first_sample: usize,
    /// Time of the recording's first sample, s (where a rate angle starts).
    pub recording_start_s: f64,
    /// Times of the window's samples, s.
    pub time_s: &'a [f64],
    /// Gaps of the window's samples.
    pub gap: &'a [f64],
    /// Angles of the window's samples (an encoder slice of the window), or the recording's
    /// rate and start angle.
    pub angle: SpindleAngle<'a>,
}

/// Where the checks after the fit read a revolution's samples: the recording in memory,
/// or its file read again (a streamed recording keeps only the fits).
pub trait RevolutionSource {
    /// Why samples could not be given (a file that cannot be read again).
    type Error;
    /// A window holding at least the samples `range` of the recording.
    ///
    /// # Errors
    /// When the samples cannot be read.
    fn samples(&mut self, range: Range<usize>) -> Result<SampleWindow<'_>, Self::Error>;
}

/// What `read` gives from `signal` as its own [`RevolutionSource`]: the recording held in
/// memory, which cannot fail to give its samples. The one bridge from a check that reads a
/// source (`residual_outliers_in`) to its form on a signal in memory (`residual_outliers`).
pub fn in_memory<'a, T>(
    signal: &ProbeSignal<'a>,
    read: impl FnOnce(&mut ProbeSignal<'a>) -> Result<T, std::convert::Infallible>,
) -> T {
    let mut source = *signal;
    match read(&mut source) {
        Ok(found) => found,
        Err(never) => match never {},
    }
}

impl RevolutionSource for ProbeSignal<'_> {
    type Error = std::convert::Infallible;

    fn samples(&mut self, _range: Range<usize>) -> Result<SampleWindow<'_>, Self::Error> {
        Ok(SampleWindow {
            first_sample: 0,
            recording_start_s: self.time_s.first().copied().unwrap_or(0.0),
            time_s: self.time_s,
            gap: self.gap,
            angle: self.angle,
        })
    }
}
