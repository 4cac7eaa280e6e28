//! Harmonic analysis of a centrifuge spindle's displacement-probe signal.
//!
//! A probe fixed to the spindle sleeve sees the gap
//!
//! ```text
//! Δd(θ) = l0 + Σᵢ₌₁ᴺ (d_ci·cos iθ + d_si·sin iθ)
//! ```
//!
//! with `θ = ωt` the spindle angle from the O1X1 reference (eq. 20). The first harmonic is the
//! spindle's once-per-revolution motion, `d1 = ΔR1·cos(ωt + β + 180°)` (eq. 21); carried to
//! the PIGA plane by the lever ratio of the heights it gives the working-radius error
//! `Δr_xd + Δr_xs = ΔR1 cos β·1210/700` (eq. 22, in the corrected form of the notes).
//!
//! [`analyze`] fits eq. 20 by least squares to every complete revolution of a recording
//! ([`ProbeSignal`]: time, gap and, when the spindle encoder was recorded, its angle; else
//! `θ = ω·(t − t₀) + θ₀` from the rate) and averages the coefficients across revolutions
//! (mean, standard deviation, standard error), as the paper does with 8 revolutions per rate.
//!
//! # Method
//! - **Segmentation**: revolution `r` holds the samples whose unwrapped angle is in
//!   `[θ_first + 2πr, θ_first + 2π(r+1))`; a trailing revolution that leaves more than
//!   `max_gap_intervals` nominal angular steps unclosed (`ω` times the median sample interval;
//!   with an encoder, the mean step) is dropped and reported.
//! - **One streaming pass per revolution**: the normal matrix of the Fourier basis needs only
//!   `Σ cos mθ, Σ sin mθ` for `m ≤ 2N` (product-to-sum identities) plus the data products; at
//!   each sample `cos θ, sin θ` come from a vectorised polynomial and the higher orders from
//!   the recurrence `cos kθ = 2 cos θ cos (k−1)θ − cos (k−2)θ` over the order, so the angle of
//!   every sample may come from the data (a non-uniform encoder).
//! - **Solve**: the `(2N+1)`- or `(2N+2)`-square system is scaled to unit diagonal and
//!   factored by Cholesky; its condition number is computed and a revolution above
//!   [`CONDITION_LIMIT`] is refused. This is sound because the basis is nearly orthogonal over a
//!   resolved revolution; tests compare with QR on the explicit design matrix.
//! - **Parallel revolutions**: revolutions are independent, so a long recording's are fitted
//!   on all cores (rayon; `RAYON_NUM_THREADS=1` keeps one); results do not depend on it.
//! - **Refusals** (typed [`HarmonicsError`]s naming the sample or revolution): non-finite
//!   values or intervals, time not increasing, a gap of more than `max_gap_intervals` nominal
//!   (median) intervals, an encoder stepping back, less than one complete revolution, a
//!   revolution with fewer than [`FitConfig::min_samples`] samples, and aliasing: a rate that
//!   turns `π/N` or more in the nominal interval, or an angular gap of `π/N` or more inside a
//!   revolution (including the gap that closes it).
//! - **Outliers** ([`residual_outliers`], [`alternating_residuals`]): a revolution whose
//!   residual RMS is more than [`OUTLIER_RMS_RATIO`] times the median of the revolutions',
//!   with its largest residual, and residuals that alternate in sign from sample to sample
//!   (every other sample zeroed); [`without_revolutions`] recomputes the statistics without
//!   the outlying ones. The callers (the recording crate) warn and apply the file's policy.
//! - **Streaming** ([`StreamingFit`]): the same analysis fed samples a piece at a time, for
//!   recordings of any size: it holds the revolution being read and what the checks need
//!   (the intervals of the nominal interval's median, the first offender of each check, each
//!   revolution's fit), and gives [`analyze`]'s result and errors to the bit. The checks that
//!   look at residuals after the fit take a [`RevolutionSource`] ([`residual_outliers_in`],
//!   [`alternating_residuals_in`]).
//! - **Declared rate** ([`check_encoder_rate`]): with an encoder, its mean rate can be
//!   compared with the rate a study declares ([`DeclaredRate`], by default within
//!   [`ENCODER_RATE_TOLERANCE`]).
//!
//! This crate works on numbers and slices only; reading and writing files is the edge crates'
//! job.
//!
//! # Features
//! - `serde`: `Serialize`/`Deserialize` on the settings and results ([`FitConfig`],
//!   [`LeverGeometry`], [`HarmonicAnalysis`], …).
//! - `synthetic`: `SyntheticRecording`, deterministic recordings of eq. 20 with known
//!   coefficients, drift, a non-uniform spindle and seeded Gaussian noise, for tests,
//!   benchmarks and fixtures.
//!
//! ```
//! use harmonics::{FirstHarmonic, LeverGeometry, ProbeDirection};
//! let geometry = LeverGeometry { pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0,
//!                                probe_direction: ProbeDirection::AgainstO1X1 };
//! let drift = geometry.project(FirstHarmonic { c1: -3.2385, s1: -1.1406 })?;
//! approx::assert_relative_eq!(drift.radius_error, 3.2385 * 1210.0 / 700.0, max_relative = 1e-12);
//! # Ok::<(), harmonics::HarmonicsError>(())
//! ```
//!
//! # References
//! Liu Y., Zhang C., He D., Yu Z., Ren S., "The mechanism of PIGA's pseudo-second-order term
//! generated by spindle dynamic imbalance of centrifuge", *Navigation Positioning and Timing*,
//! 2025(1), eq. 20–22.

mod analysis;
mod error;
mod geometry;
mod kernel;
mod noise;
mod outliers;
mod pieces;
mod rate;
mod signal;
mod sincos;
mod solve;
mod stream;
#[cfg(feature = "synthetic")]
mod synth;

pub use analysis::{
    Coefficients, DEFAULT_ORDER, FitConfig, HarmonicAnalysis, RevolutionFit, analyze,
};
pub use error::{HarmonicsError, Requirement, Result};
pub use geometry::{FirstHarmonic, LeverGeometry, PigaPlaneDrift, ProbeDirection, lever_ratio};
pub use kernel::MAX_ORDER;
pub use noise::{
    DriftAcrossRevolutions, FirstHarmonicNoise, SPREAD_WARNING_RATIO, chi_square_ratio_99,
    drift_across_revolutions, drift_across_revolutions_with, drift_inflation, first_harmonic_noise,
    first_harmonic_noise_with, pooled_residual_rms, pooled_residual_variance, revolution_spread,
    slope_variance_factor,
};
pub use outliers::{
    ALTERNATING_EXCESS_LIMIT, AlternatingResiduals, MIN_REVOLUTIONS_FOR_OUTLIERS,
    OUTLIER_RMS_RATIO, ResidualOutlier, ResidualOutliers, RevolutionSource, SampleWindow,
    alternating_residuals, alternating_residuals_in, in_memory, residual_outliers,
    residual_outliers_in, without_revolutions,
};
pub use pieces::{DropBadSamples, PooledAnalysis, analyze_around_bad_samples};
pub use rate::{DeclaredRate, ENCODER_RATE_TOLERANCE, check_encoder_rate, check_measured_rate};
pub use signal::{IncompleteRevolution, ProbeSignal, SpindleAngle, TimeAxis, check_time_axis};
pub use solve::CONDITION_LIMIT;
pub use stream::{SampleMark, StreamAngle, StreamError, StreamedAnalysis, StreamingFit};
#[cfg(feature = "synthetic")]
pub use synth::{SyntheticRecording, SyntheticSamples};
