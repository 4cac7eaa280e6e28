//! The reduction of a raw PIGA output recording to its mean output rate over whole spindle
//! revolutions, with its standard uncertainty: one row of the eq. 18 calibration. The
//! per-revolution fit, the pooled white noise and the slope's variance are `harmonics`'.

use harmonics::FitConfig;

use super::diagnostic::Diagnostic;
use super::probe::analyze_recording;
use crate::error::{RecordingError, Result};
use crate::lab::piga_recording::PigaRecording;
use crate::lab::probe::AngleSourceKind;

/// The mean output rate of one raw PIGA recording.
#[derive(Debug, Clone, PartialEq)]
pub struct PigaOutputRate {
    /// The rate the study declares for this file, rad/s.
    pub declared_rate_rad_s: f64,
    /// The spindle angle's mean rate over the recording, rad/s (`None` when the angle
    /// comes from the declared rate).
    pub measured_rate_rad_s: Option<f64>,
    /// The mean output rate over whole spindle revolutions, rad/s: the mean of the
    /// per-revolution slopes of the output angle.
    pub output_rad_s: f64,
    /// Its standard uncertainty, rad/s: the white-noise standard error
    /// ([`PigaOutputRate::white_noise_u_rad_s`]), or the standard error across
    /// revolutions when the slopes scatter beyond white noise (diagnostic `output_spread`).
    pub output_u_rad_s: f64,
    /// The standard error of the mean slope across revolutions, `s/√K` (K − 1 degrees of
    /// freedom).
    pub across_revolutions_u_rad_s: f64,
    /// The standard error of the mean slope that white noise of the output angle gives,
    /// from the residuals of the per-revolution fits pooled over the recording (many
    /// degrees of freedom, hence a steady weight even from few revolutions).
    pub white_noise_u_rad_s: f64,
    /// Standard deviation of the per-revolution output rates, rad/s.
    pub revolution_sd_rad_s: f64,
    /// Whole revolutions used (K ≥ 2).
    pub revolutions: usize,
    /// Revolutions dropped for gaps or non-finite samples.
    pub dropped_revolutions: usize,
    /// Where the spindle angle came from.
    pub angle_source: AngleSourceKind,
    /// What may make the number wrong (`angle_from_rate`, `rate_differs`,
    /// `dropped_revolutions`, `output_spread`).
    pub diagnostics: Vec<Diagnostic>,
}

impl PigaOutputRate {
    /// The rate of the point: the measured one when the spindle angle is measured, else the
    /// declared one.
    pub fn rate_rad_s(&self) -> f64 {
        self.measured_rate_rad_s.unwrap_or(self.declared_rate_rad_s)
    }
}

/// Reduces a raw PIGA output recording to its mean output rate: each whole spindle
/// revolution's samples are fitted with `θ_out = l0 + b·(t − t_mid) + Σₖ₌₁ᴺ (cₖ cos kφ + sₖ sin
/// kφ)` against the spindle angle φ ([`analyze_recording`] with a drift term, on the output
/// less its end-to-end trend so that no precision is lost to the ramp), so the slope `b` is
/// the revolution's mean output rate with its once-per-revolution (and up to `order`)
/// terms removed; the mean of the slopes over the revolutions is the point's output.
///
/// Its standard uncertainty is the white-noise standard error of that mean — the pooled
/// residual variance of the per-revolution fits (over their degrees of freedom) times each
/// revolution's exact `[(XᵀX)⁻¹]` of the slope at its own samples' times and angles — which
/// stays steady with few revolutions; when the slopes scatter across revolutions beyond
/// what white noise explains (above the 99 % quantile of χ²(K−1)/(K−1): a random walk of
/// the output, a disturbance not synchronous with the spindle), the diagnostic
/// `output_spread` says so and the standard error across revolutions, if larger, is used.
///
/// # Errors
/// Those of [`analyze_recording`] (an encoder rate more than 2 % from the declared one, too
/// few samples per revolution, aliasing, …) and [`RecordingError::TooFewRevolutions`] for
/// fewer than two usable revolutions.
pub fn reduce_piga_recording(
    recording: &PigaRecording,
    declared_rate_rad_s: f64,
    order: usize,
) -> Result<PigaOutputRate> {
    let config = FitConfig {
        order,
        drift: true,
        revolutions: None,
        ..FitConfig::default()
    };
    // The end-to-end trend, removed before the fit: the per-revolution fits then see the
    // ripple and the noise, not a ramp of many radians whose square would swamp the
    // residual sum of squares the normal equations give.
    let samples = recording.samples();
    let finite = |i: &usize| samples.gap[*i].is_finite() && samples.time_s[*i].is_finite();
    let first = (0..samples.len()).find(finite);
    let last = (0..samples.len()).rev().find(finite);
    let trend_rad_s = match (first, last) {
        (Some(a), Some(b)) if b > a => {
            (samples.gap[b] - samples.gap[a]) / (samples.time_s[b] - samples.time_s[a])
        }
        _ => 0.0,
    };
    let mut detrended = samples.clone();
    if let Some(a) = first {
        let (t0, y0) = (samples.time_s[a], samples.gap[a]);
        for (y, t) in detrended.gap.iter_mut().zip(&samples.time_s) {
            *y -= y0 + trend_rad_s * (t - t0);
        }
    }
    let analysed = analyze_recording(&detrended, declared_rate_rad_s, &config)?;
    let a = &analysed.analysis;
    let revolutions = a.revolutions_used();
    let slope = |c: &harmonics::Coefficients| c.drift_per_s;
    let (Some(mean_slope), Some(sd), Some(se)) = (
        slope(&a.mean),
        a.std.as_ref().and_then(slope),
        a.std_error.as_ref().and_then(slope),
    ) else {
        return Err(RecordingError::TooFewRevolutions {
            path: recording.path().to_owned(),
            revolutions,
        });
    };
    if revolutions < 2 {
        return Err(RecordingError::TooFewRevolutions {
            path: recording.path().to_owned(),
            revolutions,
        });
    }
    // White noise: pooled residual variance over the fits' degrees of freedom, times each
    // revolution's exact slope variance at its own samples.
    let s2 = harmonics::pooled_residual_variance(&a.revolutions, 2 * order + 2);
    let signal = detrended.signal(declared_rate_rad_s);
    let variances: Vec<f64> = a
        .revolutions
        .iter()
        .map(|r| {
            let range = r.first_sample..r.first_sample + r.samples;
            s2 * harmonics::slope_variance_factor(&signal, range, order)
        })
        .collect();
    let k = revolutions as f64;
    let white = (variances.iter().sum::<f64>()).sqrt() / k;
    let mut diagnostics: Vec<Diagnostic> = analysed
        .diagnostics
        .into_iter()
        // The slope is always fitted; the harmonics' white-noise model is made for a
        // gap's first harmonic, and the slopes' own spread is checked below.
        .filter(|d| {
            !matches!(
                d,
                Diagnostic::DriftNotFitted { .. }
                    | Diagnostic::RevolutionSpread { .. }
                    | Diagnostic::ImplausibleGap { .. }
            )
        })
        .collect();
    let per_revolution_white = (variances.iter().sum::<f64>() / k).sqrt();
    let ratio = sd / per_revolution_white;
    // ratio² ~ χ²(K−1)/(K−1) for white noise: its 99 % quantile.
    let limit = harmonics::chi_square_ratio_99(k - 1.0);
    // A revolution whose design is singular has no white-noise variance: the spread across
    // revolutions is all there is.
    let mut u = if white.is_finite() { white } else { se };
    if revolutions >= 3 && per_revolution_white > 0.0 && ratio * ratio > limit {
        diagnostics.push(Diagnostic::OutputSpread { ratio, revolutions });
        u = u.max(se);
    }
    Ok(PigaOutputRate {
        declared_rate_rad_s,
        measured_rate_rad_s: analysed.measured_rate_rad_s,
        output_rad_s: trend_rad_s + mean_slope,
        output_u_rad_s: u,
        across_revolutions_u_rad_s: se,
        white_noise_u_rad_s: white,
        revolution_sd_rad_s: sd,
        revolutions,
        dropped_revolutions: analysed.dropped_revolutions,
        angle_source: analysed.angle_source,
        diagnostics,
    })
}
