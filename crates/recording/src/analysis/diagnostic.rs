//! What may make a recording's numbers wrong, in plain words: the diagnostics of the
//! analysis of a probe or raw PIGA recording.

use std::fmt;

use crate::lab::format::LengthUnit;

/// Relative difference between declared and measured rate above which
/// [`Diagnostic::RateDiffers`] is raised (0.1 %).
pub const RATE_WARNING_TOLERANCE: f64 = 1e-3;

/// The smallest mean gap a probe recording may plausibly have, µm:
/// [`Diagnostic::ImplausibleGap`] below it.
pub const MIN_PLAUSIBLE_GAP_UM: f64 = 1.0;

/// The finest resolution of a displacement probe, µm (1 nm): a first harmonic below it
/// is below any probe's own noise.
pub const PROBE_RESOLUTION_UM: f64 = 1e-3;

/// One revolution of [`Diagnostic::ResidualOutlier`].
#[derive(Debug, Clone, PartialEq)]
pub struct OutlierRevolution {
    /// Its index among the revolutions fitted (0-based).
    pub revolution: usize,
    /// The file line of its first sample (0 for a binary file).
    pub first_line: usize,
    /// Its residual RMS, gap unit.
    pub residual_rms: f64,
    /// Its largest residual, gap unit.
    pub largest_residual: f64,
    /// Where: the file line (text) or the sample index (binary file).
    pub largest_at: SampleAt,
}

/// A sample's place in its file: the line of a text file, or the index in a binary file's
/// channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleAt {
    /// 1-based line.
    Line(usize),
    /// 0-based sample index.
    Sample(usize),
}

impl fmt::Display for SampleAt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Line(l) => write!(f, "line {l}"),
            Self::Sample(i) => write!(f, "sample {i}"),
        }
    }
}

/// The likely cause of a revolution-to-revolution spread.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SpreadCause {
    /// The angle comes from the declared rate, and a real rate that differs makes the
    /// first harmonic turn from revolution to revolution.
    RateError,
    /// The mean gap moves from revolution to revolution and no drift term is fitted.
    Drift,
    /// Neither: a pickup or vibration that is not synchronous with the spindle, or speed
    /// variation within revolutions.
    NonSynchronous,
}

impl fmt::Display for SpreadCause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::RateError => {
                "a real rate that differs from the declared one (the angle is built from the \
                 declared rate): give an encoder or index-pulse column"
            }
            Self::Drift => "drift of the gap: set `drift: true`",
            Self::NonSynchronous => {
                "a pickup or vibration not synchronous with the spindle, or speed variation \
                 within revolutions"
            }
        })
    }
}

/// Something that may make a recording's numbers wrong.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Diagnostic {
    /// No angle was measured: the angle is `ω·(t − t₀) + θ₀` from the declared rate.
    AngleFromRate {
        /// Header columns not read (one may be an encoder or index pulse).
        unread_columns: Vec<String>,
        /// The angle the first sample is taken at, from the angle zero (the arm's PIGA end
        /// pointing at the probe), deg: the format's `rate(start_angle_deg)`, 0 by default.
        start_angle_deg: f64,
    },
    /// The measured mean rate differs from the declared one by more than
    /// [`RATE_WARNING_TOLERANCE`]; the measured one is used.
    RateDiffers {
        /// Declared, rad/s.
        declared_rad_s: f64,
        /// Measured, rad/s.
        measured_rad_s: f64,
    },
    /// The first harmonic varies from revolution to revolution well beyond white noise.
    RevolutionSpread {
        /// Spread of `d_c1` over its white-noise σ.
        ratio_c1: f64,
        /// Spread of `d_s1` over its white-noise σ.
        ratio_s1: f64,
        /// Likely cause.
        cause: SpreadCause,
    },
    /// The mean gap drifts and `drift: false`: a drift within revolutions biases the first
    /// harmonic by about `2b/ω`.
    DriftNotFitted {
        /// The drift, gap unit per second.
        drift_per_s: f64,
        /// The bias it implies in the first harmonic, in standard errors of the mean.
        bias_sigmas: f64,
    },
    /// Revolutions were dropped for gaps or non-finite samples.
    DroppedRevolutions {
        /// How many.
        count: usize,
        /// How many were used.
        used: usize,
    },
    /// The probe signal is implausible for the gap column's declared unit: a mean gap
    /// below [`MIN_PLAUSIBLE_GAP_UM`] (a probe stands off further; a column in mm declared
    /// `um` reads 1000 times too small), or a first harmonic below a probe's own noise
    /// ([`PROBE_RESOLUTION_UM`], 1 nm, finer than any displacement probe resolves). C_r
    /// scales with the unit: a wrong unit gives a wrong C_r with nothing else to show it.
    ImplausibleGap {
        /// The declared unit of the gap column (µm for a column in volts, converted).
        unit: LengthUnit,
        /// The mean gap, µm.
        mean_gap_um: f64,
        /// The mean first harmonic's amplitude, µm.
        first_harmonic_um: f64,
        /// The finest first harmonic a probe resolves, µm ([`PROBE_RESOLUTION_UM`]).
        noise_um: f64,
    },
    /// Revolutions whose residual RMS is far above the median of the revolutions'
    /// (`harmonics::residual_outliers`): a glitch or a dropout inside them.
    ResidualOutlier {
        /// The outlying revolutions: index among those fitted, first line (0 for a binary
        /// file), residual RMS, largest residual and its line (or sample index for a
        /// binary file), in the gap unit.
        revolutions: Vec<OutlierRevolution>,
        /// The median residual RMS of the revolutions, gap unit.
        median_rms: f64,
        /// The gap unit.
        unit: LengthUnit,
        /// Whether they were left out of the mean (`on_outlier: drop_revolution`).
        dropped: bool,
    },
    /// The residuals alternate in sign from sample to sample
    /// (`harmonics::alternating_residuals`): every other sample zeroed or held, or two
    /// interleaved channels that disagree. The first harmonic is then wrong (halved when
    /// every other sample is zero) although every revolution looks alike.
    AlternatingResiduals {
        /// The residuals' lag-one autocorrelation.
        lag1: f64,
        /// What white noise gives after the same fit (anticorrelated itself with few
        /// samples per revolution).
        white_noise_lag1: f64,
        /// Their RMS, gap unit.
        residual_rms: f64,
        /// The gap unit.
        unit: LengthUnit,
    },
    /// A raw PIGA output recording's per-revolution output rates scatter beyond what the
    /// white noise of the output angle explains.
    OutputSpread {
        /// Their standard deviation over the white-noise one.
        ratio: f64,
        /// Revolutions.
        revolutions: usize,
    },
}

impl Diagnostic {
    /// A short stable code (`angle_from_rate`, `rate_differs`, `revolution_spread`,
    /// `drift_not_fitted`, `dropped_revolutions`, `output_spread`, `implausible_gap_unit`).
    pub const fn code(&self) -> &'static str {
        match self {
            Self::AngleFromRate { .. } => "angle_from_rate",
            Self::RateDiffers { .. } => "rate_differs",
            Self::RevolutionSpread { .. } => "revolution_spread",
            Self::DriftNotFitted { .. } => "drift_not_fitted",
            Self::DroppedRevolutions { .. } => "dropped_revolutions",
            Self::OutputSpread { .. } => "output_spread",
            Self::ImplausibleGap { .. } => "implausible_gap_unit",
            Self::ResidualOutlier { .. } => "residual_outlier",
            Self::AlternatingResiduals { .. } => "alternating_residuals",
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::AngleFromRate {
                unread_columns,
                start_angle_deg,
            } => {
                write!(
                    f,
                    "no angle was measured: the angle is built from the declared rate, the \
                     first sample taken to be {}° from the angle zero (the arm's PIGA end \
                     pointing at the probe; `rate(start_angle_deg)`, and no encoder zero \
                     applies), so a real rate that differs, or a wrong start angle, shifts β \
                     and C_r without any other sign",
                    units::Compact(*start_angle_deg)
                )?;
                if !unread_columns.is_empty() {
                    write!(
                        f,
                        "; the file also has column(s) {} — if one is an encoder or an index \
                         pulse, name it in `angle`",
                        unread_columns
                            .iter()
                            .map(|c| format!("`{c}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )?;
                }
                Ok(())
            }
            Self::RateDiffers {
                declared_rad_s,
                measured_rad_s,
            } => write!(
                f,
                "the measured rate {:.6} deg/s differs from the declared {:.6} deg/s by \
                 {:+.3} %; the measured rate is used in the radius-error fit",
                measured_rad_s.to_degrees(),
                declared_rad_s.to_degrees(),
                100.0 * (measured_rad_s / declared_rad_s - 1.0)
            ),
            Self::RevolutionSpread {
                ratio_c1,
                ratio_s1,
                cause,
            } => write!(
                f,
                "the first harmonic varies from revolution to revolution {:.1}× (d_c1) and \
                 {:.1}× (d_s1) more than white noise explains; likely cause: {cause}",
                ratio_c1, ratio_s1
            ),
            Self::DriftNotFitted {
                drift_per_s,
                bias_sigmas,
            } => write!(
                f,
                "the gap drifts by {drift_per_s:.3e} per second and `drift: false`: the \
                 first harmonic may be biased by about {bias_sigmas:.1} standard errors; set \
                 `drift: true`"
            ),
            Self::DroppedRevolutions { count, used } => write!(
                f,
                "{count} revolution(s) dropped for gaps or non-finite samples; {used} used"
            ),
            Self::ImplausibleGap {
                unit,
                mean_gap_um,
                first_harmonic_um,
                noise_um,
            } => {
                let key = unit.key();
                write!(
                    f,
                    "the probe signal is implausible for the gap column's declared unit \
                     `{key}`: "
                )?;
                let low_gap = mean_gap_um.abs() < MIN_PLAUSIBLE_GAP_UM;
                if low_gap {
                    write!(
                        f,
                        "a mean gap of {:.3e} µm, below {MIN_PLAUSIBLE_GAP_UM} µm (a probe \
                         stands off further)",
                        mean_gap_um
                    )?;
                }
                if first_harmonic_um < noise_um {
                    if low_gap {
                        f.write_str(", and ")?;
                    }
                    write!(
                        f,
                        "a first harmonic of {first_harmonic_um:.3e} µm, below a probe's own \
                         noise ({noise_um} µm, finer than any displacement probe resolves)"
                    )?;
                }
                write!(
                    f,
                    "; if the column is in another unit (mm, or volts), C_r is wrong by that \
                     factor: check `gap: (column: ..., unit: {key})` (a conditioner whose \
                     output is centred on zero also has a mean gap near 0)"
                )
            }
            Self::ResidualOutlier {
                revolutions,
                median_rms,
                unit,
                dropped,
            } => {
                let symbol = unit.symbol();
                let shown = 5;
                write!(
                    f,
                    "{} of the revolutions fit far worse than the others (residual RMS more \
                     than {} × the median {} {symbol}): ",
                    revolutions.len(),
                    harmonics::OUTLIER_RMS_RATIO,
                    units::Compact(round_to(*median_rms, 3)),
                )?;
                for (i, r) in revolutions.iter().take(shown).enumerate() {
                    if i > 0 {
                        f.write_str("; ")?;
                    }
                    write!(
                        f,
                        "revolution {} has a residual RMS of {} {symbol} ({}×), its largest \
                         residual {} {symbol} at {}",
                        r.revolution + 1,
                        units::Compact(round_to(r.residual_rms, 3)),
                        units::Compact(round_to(r.residual_rms / median_rms, 3)),
                        units::Compact(round_to(r.largest_residual, 3)),
                        r.largest_at
                    )?;
                }
                if revolutions.len() > shown {
                    write!(f, "; and {} more", revolutions.len() - shown)?;
                }
                if *dropped {
                    f.write_str(
                        ". A glitch or dropout there would move the first harmonic: left out \
                         of the mean (`on_outlier: drop_revolution`, the default; \
                         `on_outlier: keep` keeps them)",
                    )
                } else {
                    f.write_str(
                        ". A glitch or dropout there moves the first harmonic: kept in the \
                         mean as `on_outlier: keep` asks (`drop_revolution` leaves them out)",
                    )
                }
            }
            Self::AlternatingResiduals {
                lag1,
                white_noise_lag1,
                residual_rms,
                unit,
            } => write!(
                f,
                "the fit's residuals alternate in sign from one sample to the next \
                 (lag-one autocorrelation {}, where noise alone would give {}; residual RMS \
                 {} {}): every other sample zeroed or held, or two interleaved channels that \
                 disagree; the first harmonic is then wrong (halved when every other sample \
                 is zero): check the recording",
                units::Compact(round_to(*lag1, 3)),
                units::Compact(round_to(*white_noise_lag1, 2)),
                units::Compact(round_to(*residual_rms, 3)),
                unit.symbol()
            ),
            Self::OutputSpread { ratio, revolutions } => write!(
                f,
                "the output rate varies from revolution to revolution {ratio:.1}× more than \
                 the white noise of the output angle explains ({revolutions} revolutions): a \
                 random walk of the output or a disturbance not synchronous with the spindle; \
                 the point's u is the standard error across revolutions"
            ),
        }
    }
}

/// `x` to `digits` significant digits (for a message).
fn round_to(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    if scale.is_finite() && scale != 0.0 {
        (x * scale).round() / scale
    } else {
        x
    }
}
