//! The white noise of the per-revolution fits and what the spread across revolutions says:
//! the pooled residual variance, the white-noise standard errors of the first harmonic and
//! of a fitted slope, the drift of the revolutions' mean gap, and the χ² limits that tell a
//! spread beyond white noise.

use std::f64::consts::PI;
use std::ops::Range;

use crate::analysis::{FitConfig, HarmonicAnalysis, RevolutionFit};
use crate::signal::{ProbeSignal, SpindleAngle};

/// Ratio of the revolution-to-revolution spread of `d_c1`/`d_s1` to its white-noise σ
/// above which [`revolution_spread`] reports it (with few revolutions, the threshold grows
/// so that white noise alone reaches it about once in 10⁵).
pub const SPREAD_WARNING_RATIO: f64 = 2.0;

/// The residual variance `s²` of the per-revolution fits pooled over their degrees of
/// freedom: each revolution's residual sum of squares over its samples less the
/// `parameters` fitted per revolution. The unbiased white-noise variance even when a
/// revolution holds few samples.
pub fn pooled_residual_variance(revolutions: &[RevolutionFit], parameters: usize) -> f64 {
    let dof: usize = revolutions
        .iter()
        .map(|r| r.samples.saturating_sub(parameters))
        .sum();
    let rss: f64 = revolutions
        .iter()
        .map(|r| r.residual_rms * r.residual_rms * r.samples as f64)
        .sum();
    rss / dof.max(1) as f64
}

/// The residual RMS of all the per-revolution fits together, gap unit.
pub fn pooled_residual_rms(revolutions: &[RevolutionFit]) -> f64 {
    let samples: usize = revolutions.iter().map(|r| r.samples).sum();
    let rss: f64 = revolutions
        .iter()
        .map(|r| r.residual_rms * r.residual_rms * r.samples as f64)
        .sum();
    (rss / samples.max(1) as f64).sqrt()
}

/// The white-noise standard errors of the first harmonic `(d_c1, d_s1)`, gap unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstHarmonicNoise {
    /// Of one revolution's coefficients, averaged over the revolutions: `√(Σᵣ 2s²fᵣ/nᵣ / K)`.
    pub revolution_sigma: [f64; 2],
    /// Of the mean over the `K` revolutions: `√(Σᵣ 2s²fᵣ/nᵣ)/K`.
    pub mean_sigma: [f64; 2],
}

/// The angle of sample `i` of a signal, rad.
fn angle_at(signal: &ProbeSignal<'_>, i: usize) -> f64 {
    match signal.angle {
        SpindleAngle::Encoder(a) => a[i],
        SpindleAngle::Rate {
            rate_rad_s,
            start_angle_rad,
        } => start_angle_rad + rate_rad_s * (signal.time_s[i] - signal.time_s[0]),
    }
}

/// The white-noise standard errors of the first harmonic of an analysis of `signal`: each
/// revolution's `d_c1` has variance `2s²/nᵣ` (`s²` the [`pooled_residual_variance`]),
/// times the drift term's variance inflation ([`drift_inflation`]) in its direction when a
/// drift is fitted (`fᵣ`, from the revolution's first angle).
pub fn first_harmonic_noise(
    analysis: &HarmonicAnalysis,
    signal: &ProbeSignal<'_>,
    config: &FitConfig,
) -> FirstHarmonicNoise {
    first_harmonic_noise_with(analysis, config, |i| angle_at(signal, i))
}

/// [`first_harmonic_noise`] with the angle of a revolution's first sample given by
/// `angle_at` (sample index → rad): for a recording streamed from its file, which keeps
/// the angle where each revolution starts.
pub fn first_harmonic_noise_with(
    analysis: &HarmonicAnalysis,
    config: &FitConfig,
    angle_at: impl Fn(usize) -> f64,
) -> FirstHarmonicNoise {
    let revs = &analysis.revolutions;
    let parameters = 2 * config.order + 1 + usize::from(config.drift);
    let pooled = pooled_residual_variance(revs, parameters);
    let k = revs.len() as f64;
    let inflation = drift_inflation(config);
    let mut sum_var = [0.0; 2];
    for r in revs {
        let (sin0, cos0) = angle_at(r.first_sample).sin_cos();
        let base = 2.0 * pooled / r.samples as f64;
        sum_var[0] += base * (1.0 + (inflation - 1.0) * sin0 * sin0);
        sum_var[1] += base * (1.0 + (inflation - 1.0) * cos0 * cos0);
    }
    FirstHarmonicNoise {
        revolution_sigma: sum_var.map(|v| (v / k).sqrt()),
        mean_sigma: sum_var.map(|v| v.sqrt() / k),
    }
}

/// The variance inflation of the first harmonic's coefficient along `sin(θ − θ₀)` (θ₀ the
/// revolution's first angle) when a drift term is fitted: within a revolution time is a
/// ramp in θ, whose part along that sine the drift term shares. With `v = π²/3 − 2Σₖ≤N 1/k²`
/// the ramp's variance beyond order N, the factor is `(2 + v)/v` (5.5 for N = 4); 1
/// without drift.
pub fn drift_inflation(config: &FitConfig) -> f64 {
    if !config.drift {
        return 1.0;
    }
    let beyond = PI.powi(2) / 3.0
        - 2.0
            * (1..=config.order)
                .map(|k| 1.0 / (k * k) as f64)
                .sum::<f64>();
    (2.0 + beyond) / beyond
}

/// A significant drift of the revolutions' mean gap ([`drift_across_revolutions`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriftAcrossRevolutions {
    /// The drift, gap unit per second.
    pub drift_per_s: f64,
    /// The bias `2b/ω` it implies in the first harmonic, in standard errors of the mean.
    pub bias_sigmas: f64,
}

/// The drift of the revolutions' mean gap `l0` against their middle times, when it is
/// significant (beyond 4 of its standard errors) and its bias on the first harmonic
/// (`2b/ω`, from a ramp `b·t` over a revolution) exceeds 3 standard errors of the mean
/// (`mean_noise_sigma`). `None` with fewer than three revolutions.
pub fn drift_across_revolutions(
    time_s: &[f64],
    revolutions: &[RevolutionFit],
    mean_noise_sigma: f64,
    rate_rad_s: f64,
) -> Option<DriftAcrossRevolutions> {
    drift_across_revolutions_with(|i| time_s[i], revolutions, mean_noise_sigma, rate_rad_s)
}

/// [`drift_across_revolutions`] with the time of a revolution's first and last samples
/// given by `time_at` (sample index → s): for a recording streamed from its file, which
/// keeps the times where each revolution starts and ends.
pub fn drift_across_revolutions_with(
    time_at: impl Fn(usize) -> f64,
    revolutions: &[RevolutionFit],
    mean_noise_sigma: f64,
    rate_rad_s: f64,
) -> Option<DriftAcrossRevolutions> {
    if revolutions.len() < 3 {
        return None;
    }
    let x: Vec<f64> = revolutions
        .iter()
        .map(|r| 0.5 * (time_at(r.first_sample) + time_at(r.first_sample + r.samples - 1)))
        .collect();
    let y: Vec<f64> = revolutions.iter().map(|r| r.coefficients.l0).collect();
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
        DriftAcrossRevolutions {
            drift_per_s: slope,
            bias_sigmas,
        },
    )
}

/// The spread of the first harmonic across revolutions over its white-noise σ,
/// `(d_c1, d_s1)`, when it is beyond white noise: `ratio²` above [`SPREAD_WARNING_RATIO`]²
/// and above `1 + 6·√(2/(K−1))` (for white noise `ratio² ~ χ²(K−1)/(K−1)`, of mean 1 and
/// standard deviation `√(2/(K−1))`). `None` with fewer than three revolutions.
pub fn revolution_spread(
    analysis: &HarmonicAnalysis,
    revolution_sigma: [f64; 2],
) -> Option<(f64, f64)> {
    let std = analysis.std.as_ref()?;
    let k = analysis.revolutions.len() as f64;
    if analysis.revolutions.len() < 3 || !revolution_sigma.iter().all(|s| *s > 0.0) {
        return None;
    }
    let ratio_c1 = std.c[0] / revolution_sigma[0];
    let ratio_s1 = std.s[0] / revolution_sigma[1];
    let limit = SPREAD_WARNING_RATIO
        .powi(2)
        .max(1.0 + 6.0 * (2.0 / (k - 1.0)).sqrt());
    (ratio_c1.max(ratio_s1).powi(2) > limit).then_some((ratio_c1, ratio_s1))
}

/// The 99 % quantile of `χ²(ν)/ν` (Wilson–Hilferty): the largest squared ratio of a sample
/// standard deviation with `ν` degrees of freedom to its true value that white noise
/// reaches once in a hundred.
pub fn chi_square_ratio_99(nu: f64) -> f64 {
    (1.0 - 2.0 / (9.0 * nu) + 2.326_348 * (2.0 / (9.0 * nu)).sqrt()).powi(3)
}

/// `[(XᵀX)⁻¹]_bb` of one revolution's design `[1, t − t̄, cos kφ, sin kφ (k ≤ N)]` at the
/// times and spindle angles of `signal`'s samples in `range`: the fitted slope's variance
/// per unit noise variance, exact for any number of samples (the harmonics beside the
/// slope inflate it, more so with few samples per revolution). Solved by Cholesky on the
/// unit-diagonal scaled normal matrix; infinite if that is not positive definite.
pub fn slope_variance_factor(signal: &ProbeSignal<'_>, range: Range<usize>, order: usize) -> f64 {
    let p = 2 * order + 2;
    let t = &signal.time_s[range.clone()];
    let t_mean = t.iter().sum::<f64>() / t.len() as f64;
    let mut a = vec![0.0; p * p];
    let mut row = vec![0.0; p];
    for i in range {
        let phi = angle_at(signal, i);
        row[0] = 1.0;
        row[1] = signal.time_s[i] - t_mean;
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
