//! The rate a study declares, and the check that an encoder recording's mean rate matches
//! it.

// Lane loops index several arrays at once; that is what vectorises.
#![allow(clippy::needless_range_loop)]

use crate::error::{HarmonicsError, Requirement, Result};
use crate::signal::{ProbeSignal, SpindleAngle, encoder_step};

/// Relative tolerance of [`check_encoder_rate`] used by the `pipeline` crate: 2 %. A speed
/// ripple of a fraction of a degree leaves the mean rate well inside it; a recording made
/// at another rate point of a study (10 % apart or more) is far outside.
pub const ENCODER_RATE_TOLERANCE: f64 = 0.02;

/// A spindle rate declared by a study, and how closely an encoder recording's mean rate must
/// match it ([`check_encoder_rate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeclaredRate {
    /// The declared rate `ω`, rad/s (finite and > 0).
    pub rate_rad_s: f64,
    /// Largest accepted `|ω_enc − ω|/ω` (finite and not negative).
    pub relative_tolerance: f64,
}

impl DeclaredRate {
    /// `rate_rad_s` with the tolerance [`ENCODER_RATE_TOLERANCE`].
    #[must_use]
    pub const fn new(rate_rad_s: f64) -> Self {
        Self {
            rate_rad_s,
            relative_tolerance: ENCODER_RATE_TOLERANCE,
        }
    }
}

/// Checks that an encoder recording's mean rate `ω_enc` — its unwrapped angle span over its
/// time span — matches the declared rate `ω` within the relative tolerance:
/// `|ω_enc − ω| ≤ tolerance·ω`. A rate-mode signal passes. Meant for a signal that
/// [`analyze`](crate::analyze) accepted (steps below `π`, so the unwrapping is sound).
///
/// ```
/// # use harmonics::{check_encoder_rate, DeclaredRate, HarmonicsError, ProbeSignal, SpindleAngle};
/// let time_s = [0.0, 1.0, 2.0];
/// let angle = [0.0, 3.0, 6.0]; // 3 rad/s, wrapping past 2π
/// let signal = ProbeSignal { time_s: &time_s, gap: &[0.0; 3], angle: SpindleAngle::Encoder(&angle) };
/// assert!(check_encoder_rate(&signal, DeclaredRate::new(3.05)).is_ok());
/// let strict = DeclaredRate { rate_rad_s: 3.05, relative_tolerance: 0.01 };
/// assert!(matches!(check_encoder_rate(&signal, strict),
///                  Err(HarmonicsError::RateMismatch { .. })));
/// # Ok::<(), HarmonicsError>(())
/// ```
///
/// # Errors
/// [`HarmonicsError::InvalidSetting`] for a bad tolerance, [`HarmonicsError::InvalidRate`]
/// for a declared rate that is not finite and positive (with an encoder),
/// [`HarmonicsError::LengthMismatch`] and [`HarmonicsError::NoCompleteRevolution`] for a
/// signal that `analyze` would refuse, and [`HarmonicsError::RateMismatch`] for a rate
/// outside the tolerance.
pub fn check_encoder_rate(signal: &ProbeSignal<'_>, declared: DeclaredRate) -> Result<()> {
    let DeclaredRate {
        rate_rad_s: declared_rate_rad_s,
        relative_tolerance: tolerance,
    } = declared;
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(HarmonicsError::InvalidSetting {
            field: "relative_tolerance",
            value: tolerance,
            requirement: Requirement::NonNegative,
        });
    }
    let SpindleAngle::Encoder(a) = signal.angle else {
        return Ok(());
    };
    if !(declared_rate_rad_s.is_finite() && declared_rate_rad_s > 0.0) {
        return Err(HarmonicsError::InvalidRate {
            rate_rad_s: declared_rate_rad_s,
        });
    }
    let t = signal.time_s;
    let n = t.len();
    if a.len() != n {
        return Err(HarmonicsError::LengthMismatch {
            column: "angle",
            len: a.len(),
            expected: n,
        });
    }
    if n < 2 {
        return Err(HarmonicsError::NoCompleteRevolution {
            samples: n,
            turns: 0.0,
        });
    }
    let encoder_rad_s = unwrapped_span(a) / (t[n - 1] - t[0]);
    rate_within(encoder_rad_s, declared)
}

/// [`check_encoder_rate`]'s verdict on an encoder's mean rate already measured (the sum of
/// its wrapped steps over the time they span, as a streamed analysis forms it:
/// [`StreamingFit::encoder_rate_rad_s`](crate::StreamingFit::encoder_rate_rad_s)).
///
/// # Errors
/// As [`check_encoder_rate`]: a bad tolerance or declared rate, or a rate outside the
/// tolerance.
pub fn check_measured_rate(encoder_rad_s: f64, declared: DeclaredRate) -> Result<()> {
    let DeclaredRate {
        rate_rad_s: declared_rate_rad_s,
        relative_tolerance: tolerance,
    } = declared;
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(HarmonicsError::InvalidSetting {
            field: "relative_tolerance",
            value: tolerance,
            requirement: Requirement::NonNegative,
        });
    }
    if !(declared_rate_rad_s.is_finite() && declared_rate_rad_s > 0.0) {
        return Err(HarmonicsError::InvalidRate {
            rate_rad_s: declared_rate_rad_s,
        });
    }
    rate_within(encoder_rad_s, declared)
}

/// The measured rate within the declared one's tolerance.
fn rate_within(encoder_rad_s: f64, declared: DeclaredRate) -> Result<()> {
    let DeclaredRate {
        rate_rad_s: declared_rate_rad_s,
        relative_tolerance: tolerance,
    } = declared;
    // NaN (a signal `analyze` would refuse) fails too.
    let within = (encoder_rad_s - declared_rate_rad_s).abs() <= tolerance * declared_rate_rad_s;
    if !within {
        return Err(HarmonicsError::RateMismatch {
            declared_rad_s: declared_rate_rad_s,
            encoder_rad_s,
            tolerance,
        });
    }
    Ok(())
}

/// The sum of the wrapped steps of the encoder readings (in lanes, so that it vectorises).
fn unwrapped_span(a: &[f64]) -> f64 {
    const W: usize = 8;
    let mut acc = [0.0_f64; W];
    let pairs = a.len() - 1;
    let body = pairs - pairs % W;
    for i in (0..body).step_by(W) {
        let w: &[f64; W + 1] = a[i..i + W + 1].try_into().expect("window");
        for l in 0..W {
            acc[l] += encoder_step(w[l], w[l + 1]);
        }
    }
    let tail: f64 = (body..pairs).map(|i| encoder_step(a[i], a[i + 1])).sum();
    acc.iter().sum::<f64>() + tail
}
