//! The crate's error type.

/// Errors of the harmonic analysis.
///
/// Errors about the samples name the sample's index (0-based, into the slices given);
/// errors about a revolution name the revolution's index (0-based, among the complete
/// revolutions of the recording).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum HarmonicsError {
    /// A geometric parameter is out of its domain (non-finite, zero or negative).
    #[error("invalid geometry: `{field}` = {value_c} (must be finite and > 0)", value_c = units::Compact(*value))]
    InvalidGeometry {
        /// Name of the offending field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A harmonic coefficient is not finite.
    #[error("non-finite harmonic coefficient `{field}` = {value_c}", value_c = units::Compact(*value))]
    NonFiniteCoefficient {
        /// Name of the offending coefficient.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A fit setting is out of its domain.
    #[error("invalid fit setting: `{field}` = {value_c} ({requirement})", value_c = units::Compact(*value))]
    InvalidSetting {
        /// Name of the offending setting.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        requirement: Requirement,
    },
    /// The Fourier order is outside `1..=MAX_ORDER`.
    #[error("Fourier order {order} is not supported (1 to {max})")]
    InvalidOrder {
        /// The order asked for.
        order: usize,
        /// The largest supported order.
        max: usize,
    },
    /// Two sample columns have different lengths.
    #[error("column `{column}` has {len} samples, but `time` has {expected}")]
    LengthMismatch {
        /// The column whose length differs.
        column: &'static str,
        /// Its length.
        len: usize,
        /// The length of the time column.
        expected: usize,
    },
    /// A sample is NaN or infinite.
    #[error("sample {index}: `{column}` is not finite ({value_c})", value_c = units::Compact(*value))]
    NonFinite {
        /// Index of the sample.
        index: usize,
        /// The column holding the value.
        column: &'static str,
        /// The value.
        value: f64,
    },
    /// The time stamps do not increase strictly.
    #[error(
        "sample {index}: time {time_s_c} s does not increase (previous sample at {previous_s_c} s)", time_s_c = units::Compact(*time_s), previous_s_c = units::Compact(*previous_s)
    )]
    TimeNotIncreasing {
        /// Index of the sample.
        index: usize,
        /// Time of the previous sample, s.
        previous_s: f64,
        /// Time of this sample, s.
        time_s: f64,
    },
    /// Two consecutive samples are further apart than the allowed number of sample intervals.
    #[error(
        "sample {index}: gap of {interval_s_c} s since the previous sample, more than {max_intervals_c} \
         nominal sample intervals of {nominal_interval_s_c} s", interval_s_c = units::Compact(*interval_s), max_intervals_c = units::Compact(*max_intervals), nominal_interval_s_c = units::Compact(*nominal_interval_s)
    )]
    SampleGap {
        /// Index of the sample after the gap.
        index: usize,
        /// Time since the previous sample, s.
        interval_s: f64,
        /// The recording's nominal (median) sample interval, s.
        nominal_interval_s: f64,
        /// The allowed gap in nominal intervals.
        max_intervals: f64,
    },
    /// Two consecutive times are so far apart that their difference overflows.
    #[error("sample {index}: interval of {interval_s_c} s since the previous sample is not finite", interval_s_c = units::Compact(*interval_s))]
    NonFiniteInterval {
        /// Index of the sample.
        index: usize,
        /// The interval, s (infinite).
        interval_s: f64,
    },
    /// The spindle turns by `π/N` or more in a sample interval, so no revolution can resolve
    /// order `N` (checked before the recording is cut into revolutions).
    #[error(
        "spindle rate {rate_rad_s_c} rad/s turns {step_rad_c} rad in a sample interval of \
         {interval_s_c} s, which aliases order {order} (must be below π/{order} = {limit_rad_c} rad)", rate_rad_s_c = units::Compact(*rate_rad_s), step_rad_c = units::Compact(*step_rad), interval_s_c = units::Compact(*interval_s), limit_rad_c = units::Compact(*limit_rad)
    )]
    RateAliases {
        /// The rate, rad/s.
        rate_rad_s: f64,
        /// The interval, s: the nominal (median) one, or the longest when the recording
        /// spans more turns than it has samples.
        interval_s: f64,
        /// The angle turned in it, rad.
        step_rad: f64,
        /// The fitted order.
        order: usize,
        /// `π/order`, rad.
        limit_rad: f64,
    },
    /// The encoder's mean rate differs from the declared rate by more than the tolerance.
    #[error(
        "declared spindle rate {declared_rad_s_c} rad/s differs from the encoder's mean rate \
         {encoder_rad_s_c} rad/s by more than {tolerance_c} (relative)", declared_rad_s_c = units::Compact(*declared_rad_s), encoder_rad_s_c = units::Compact(*encoder_rad_s), tolerance_c = units::Compact(*tolerance)
    )]
    RateMismatch {
        /// The declared rate, rad/s.
        declared_rad_s: f64,
        /// The encoder's mean rate (unwrapped angle span over time span), rad/s.
        encoder_rad_s: f64,
        /// The relative tolerance.
        tolerance: f64,
    },
    /// The encoder angle goes backwards (after unwrapping: steps are taken in (−π, π]).
    #[error(
        "sample {index}: encoder angle steps back by {step_rad_c} rad (the spindle turns one way)", step_rad_c = units::Compact(*step_rad)
    )]
    AngleNotIncreasing {
        /// Index of the sample.
        index: usize,
        /// The (negative) unwrapped step, rad.
        step_rad: f64,
    },
    /// The spindle rate is not finite and positive.
    #[error("spindle rate {rate_rad_s_c} rad/s must be finite and > 0", rate_rad_s_c = units::Compact(*rate_rad_s))]
    InvalidRate {
        /// The rate given, rad/s.
        rate_rad_s: f64,
    },
    /// The recording does not hold one complete revolution.
    #[error("less than one complete revolution: {samples} samples cover {turns_c} turns", turns_c = units::Compact(*turns))]
    NoCompleteRevolution {
        /// Number of samples in the recording.
        samples: usize,
        /// Turns covered by the samples.
        turns: f64,
    },
    /// Fewer complete revolutions than asked for.
    #[error("{requested} revolutions requested, the recording has {available} complete ones")]
    TooFewRevolutions {
        /// Revolutions asked for.
        requested: usize,
        /// Complete revolutions in the recording.
        available: usize,
    },
    /// A revolution has too few samples for the number of fitted parameters.
    #[error(
        "revolution {revolution} (from sample {first_sample}): {got} samples, the fit needs at least {need}"
    )]
    TooFewSamples {
        /// Index of the revolution.
        revolution: usize,
        /// Index of its first sample.
        first_sample: usize,
        /// Samples in the revolution.
        got: usize,
        /// Samples needed.
        need: usize,
    },
    /// The angular sampling of a revolution cannot resolve the fitted order (aliasing).
    #[error(
        "revolution {revolution}: angular gap of {max_gap_rad_c} rad after sample {after_sample} \
         aliases order {order} (must be below π/{order} = {limit_rad_c} rad)", max_gap_rad_c = units::Compact(*max_gap_rad), limit_rad_c = units::Compact(*limit_rad)
    )]
    Aliasing {
        /// Index of the revolution.
        revolution: usize,
        /// Index of the sample before the largest gap.
        after_sample: usize,
        /// The fitted order.
        order: usize,
        /// The largest angular gap between consecutive samples (wrapping round the revolution).
        max_gap_rad: f64,
        /// The largest gap that resolves the order, `π/order`.
        limit_rad: f64,
    },
    /// The normal equations of a revolution are too badly conditioned to be solved reliably.
    #[error(
        "revolution {revolution}: normal equations ill-conditioned (1-norm condition {condition_c} \
         after scaling, limit {limit_c})", condition_c = units::Compact(*condition), limit_c = units::Compact(*limit)
    )]
    IllConditioned {
        /// Index of the revolution.
        revolution: usize,
        /// Estimated 1-norm condition number of the scaled normal matrix.
        condition: f64,
        /// The largest condition accepted.
        limit: f64,
    },
    /// A result of the fit is not finite although every sample was: a gap this large cannot
    /// be squared in double precision (beyond about 1e154).
    #[error(
        "{}`{quantity}` is not finite ({}): the largest gap, {} at sample {at_sample}, is beyond \
         the range the fit can square in double precision",
        match revolution { Some(r) => format!("revolution {r}: "), None => String::new() },
        units::Compact(*value),
        units::Compact(*largest_gap)
    )]
    NonFiniteResult {
        /// The revolution whose fit it is, or `None` for a statistic across revolutions.
        revolution: Option<usize>,
        /// The quantity: `residual_rms`, or a coefficient (`l0`, `c`, `s`, `drift_per_s`) of
        /// the revolution's `coefficients` or of the `mean`, `std` or `std_error` across
        /// revolutions (`std.c`).
        quantity: &'static str,
        /// The value computed (NaN or ±∞).
        value: f64,
        /// The gap of largest magnitude among the samples that drove it out of range.
        largest_gap: f64,
        /// That gap's sample index.
        at_sample: usize,
    },
}

/// What a setting must satisfy ([`HarmonicsError::InvalidSetting`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Requirement {
    /// A finite number.
    Finite,
    /// A finite number, 1 or more.
    AtLeastOne,
    /// A finite number, 0 or more.
    NonNegative,
}

impl core::fmt::Display for Requirement {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::Finite => "must be finite",
            Self::AtLeastOne => "must be finite and at least 1",
            Self::NonNegative => "must be finite and not negative",
        })
    }
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, HarmonicsError>;

impl HarmonicsError {
    /// The error with each sample index it names moved by `offset` (for a piece of a
    /// recording analysed apart, so that the index is the whole recording's).
    #[must_use]
    pub(crate) fn with_sample_offset(mut self, offset: usize) -> Self {
        match &mut self {
            Self::NonFinite { index, .. }
            | Self::NonFiniteInterval { index, .. }
            | Self::TimeNotIncreasing { index, .. }
            | Self::SampleGap { index, .. }
            | Self::AngleNotIncreasing { index, .. } => *index += offset,
            Self::TooFewSamples { first_sample, .. } => *first_sample += offset,
            Self::Aliasing { after_sample, .. } => *after_sample += offset,
            Self::NonFiniteResult { at_sample, .. } => *at_sample += offset,
            _ => {}
        }
        self
    }
}
