//! Revolutions and samples that do not fit like the rest (issue 32): a revolution whose
//! residual RMS is far above the others' (one glitch sample of 937 µm among samples that
//! fit to 0.045 µm moved that rate's first harmonic with no warning), and residuals that
//! alternate in sign from sample to sample (every other sample zeroed, or two interleaved
//! channels that disagree, halve the first harmonic with residuals no larger from one
//! revolution to the next). Both are found from the fits already made; dropping revolutions
//! recomputes the statistics of the others.

use crate::analysis::{HarmonicAnalysis, RevolutionFit, statistics};
use crate::signal::{ProbeSignal, SpindleAngle};

/// A revolution whose residual RMS exceeds this many times the median of the revolutions'
/// is an outlier. White noise alone puts a revolution of `n` samples within about
/// `1 ± 3/√(2n)` of the median; a factor 5 is beyond it for any revolution the fit accepts.
pub const OUTLIER_RMS_RATIO: f64 = 5.0;

/// Fewest revolutions for the outlier test: with two, neither is "the others".
pub const MIN_REVOLUTIONS_FOR_OUTLIERS: usize = 3;

/// The residuals' lag-one autocorrelation below which they alternate in sign (white noise
/// gives about 0 ± 1/√n over `n` samples; every other sample zeroed gives about −1).
pub const ALTERNATING_LAG1_LIMIT: f64 = -0.5;

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
    let fits = &analysis.revolutions;
    if fits.len() < MIN_REVOLUTIONS_FOR_OUTLIERS {
        return None;
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
    let revolutions: Vec<ResidualOutlier> = fits
        .iter()
        .enumerate()
        .filter(|(_, f)| f.residual_rms > limit)
        .map(|(r, f)| {
            let (largest_at_sample, largest_residual) = residuals(signal, f)
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .unwrap_or((f.first_sample, f64::NAN));
            ResidualOutlier {
                revolution: r,
                first_sample: f.first_sample,
                residual_rms: f.residual_rms,
                largest_residual,
                largest_at_sample,
            }
        })
        .collect();
    (!revolutions.is_empty()).then_some(ResidualOutliers {
        revolutions,
        median_rms,
        compared: n,
    })
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
/// autocorrelation within up to eight revolutions spread over the recording is below
/// [`ALTERNATING_LAG1_LIMIT`] and they are above the rounding floor. `signal` is the one
/// `analysis` was fitted to.
pub fn alternating_residuals(
    signal: &ProbeSignal<'_>,
    analysis: &HarmonicAnalysis,
) -> Option<AlternatingResiduals> {
    let fits = &analysis.revolutions;
    let step = fits.len().div_ceil(ALTERNATION_REVOLUTIONS).max(1);
    let (mut lagged, mut squares, mut count) = (0.0_f64, 0.0_f64, 0_usize);
    let mut examined = 0;
    for fit in fits.iter().step_by(step) {
        examined += 1;
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
        return None;
    }
    let residual_rms = (squares / count as f64).sqrt();
    let lag1 = lagged / squares;
    (residual_rms > ROUNDING_FLOOR * scale(analysis) && lag1 < ALTERNATING_LAG1_LIMIT).then_some(
        AlternatingResiduals {
            lag1,
            residual_rms,
            revolutions: examined,
        },
    )
}

/// The residuals of one revolution's fit, `(sample, gap − fit)`.
fn residuals<'a>(
    signal: &'a ProbeSignal<'_>,
    fit: &'a RevolutionFit,
) -> impl Iterator<Item = (usize, f64)> + 'a {
    let range = fit.first_sample..fit.first_sample + fit.samples;
    let t = &signal.time_s[range.clone()];
    let t_mid = 0.5 * (t[0] + t[t.len() - 1]);
    let k = &fit.coefficients;
    range.map(move |i| {
        let theta = match signal.angle {
            SpindleAngle::Encoder(a) => a[i],
            SpindleAngle::Rate {
                rate_rad_s,
                start_angle_rad,
            } => start_angle_rad + rate_rad_s * (signal.time_s[i] - signal.time_s[0]),
        };
        let drift = k
            .drift_per_s
            .map_or(0.0, |b| b * (signal.time_s[i] - t_mid));
        (i, signal.gap[i] - k.evaluate(theta) - drift)
    })
}
