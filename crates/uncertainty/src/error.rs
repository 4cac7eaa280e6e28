//! The crate's error types: [`UncertaintyError`] for the engine, [`ModelError`] for a model.

use crate::kind::{Distribution, Dof};

/// Why a measurement model could not be evaluated at one point.
///
/// Returned by [`MeasurementModel::evaluate`](crate::MeasurementModel::evaluate). At the
/// estimate (GUM) it is an error; in a Monte Carlo trial it makes the trial a failed trial,
/// which is counted, and too many of them are an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A linear system of the model is singular at this point (e.g. a rank-deficient design).
    #[error("the model's linear system is singular at this point")]
    Singular,
    /// An input lies outside the model's domain (e.g. a negative value under a square root).
    #[error("input {index} is outside the model's domain")]
    OutOfDomain {
        /// Position of the input in the model's input vector.
        index: usize,
    },
    /// Any other failure, with a fixed description.
    #[error("the model failed: {reason}")]
    Failed {
        /// What went wrong, as a fixed phrase.
        reason: &'static str,
    },
}

/// Which Monte Carlo statistic had not stabilised (JCGM 101 §7.9.4 i).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Statistic {
    /// The estimate (the mean of the model values).
    Estimate,
    /// The standard uncertainty.
    StandardUncertainty,
    /// The lower end of the coverage interval.
    CoverageLow,
    /// The upper end of the coverage interval.
    CoverageHigh,
}

impl std::fmt::Display for Statistic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Statistic::Estimate => "estimate",
            Statistic::StandardUncertainty => "standard uncertainty",
            Statistic::CoverageLow => "lower coverage limit",
            Statistic::CoverageHigh => "upper coverage limit",
        })
    }
}

/// Everything that can go wrong in `uncertainty`.
///
/// Inputs and outputs are named as the caller named them. No function of this crate returns
/// `Ok` holding an infinite or NaN number: where one would arise, one of these is returned.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum UncertaintyError {
    /// No input quantities were given.
    #[error("no input quantities")]
    NoInputs,
    /// The model declares no output quantities.
    #[error("the model has no output quantities")]
    NoOutputs,
    /// An input quantity has an empty name.
    #[error("input quantity {index} has an empty name")]
    EmptyName {
        /// Position of the input.
        index: usize,
    },
    /// Two quantities share a name.
    #[error("the name {name:?} is used twice")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },
    /// An input's value is NaN or infinite.
    #[error("input {input}: value {value} is not finite")]
    NonFiniteValue {
        /// The input.
        input: String,
        /// Its value.
        value: f64,
    },
    /// An input's standard uncertainty is negative, NaN or infinite.
    #[error("input {input}: standard uncertainty {value} is not a finite non-negative number")]
    InvalidStandardUncertainty {
        /// The input.
        input: String,
        /// The value given.
        value: f64,
    },
    /// An input's degrees of freedom are not positive, or `Dof::Finite` holds a non-finite
    /// number (use `Dof::Infinite` for ∞).
    #[error(
        "input {input}: degrees of freedom {dof} must be a finite positive number or Dof::Infinite"
    )]
    InvalidDof {
        /// The input.
        input: String,
        /// The value given.
        dof: f64,
    },
    /// A Student t distribution needs finite degrees of freedom.
    #[error("input {input}: a Student t distribution needs finite degrees of freedom")]
    StudentTNeedsFiniteDof {
        /// The input.
        input: String,
    },
    /// A Type A input must be drawn from the scaled-and-shifted t distribution when its
    /// degrees of freedom are finite (JCGM 101 §6.4.9) and from a normal distribution when
    /// they are infinite.
    #[error(
        "input {input}: a Type A evaluation with {dof} degrees of freedom needs the {} distribution, not {distribution:?}",
        if matches!(dof, Dof::Infinite) { "Normal" } else { "StudentT" }
    )]
    TypeADistribution {
        /// The input.
        input: String,
        /// The distribution given.
        distribution: Distribution,
        /// The degrees of freedom given.
        dof: Dof,
    },
    /// The correlation matrix is not `n × n` for `n` inputs.
    #[error("correlation matrix has {got} entries; {inputs} inputs need {expected}")]
    CorrelationSize {
        /// Number of inputs.
        inputs: usize,
        /// Entries given.
        got: usize,
        /// Entries needed (`inputs²`).
        expected: usize,
    },
    /// A correlation coefficient is NaN, outside `[-1, 1]`, not symmetric, or a diagonal entry
    /// is not 1.
    #[error(
        "correlation r({first}, {second}) = {value} is invalid (must be finite, in [-1, 1], symmetric, and 1 on the diagonal)"
    )]
    InvalidCorrelation {
        /// Row input.
        first: String,
        /// Column input.
        second: String,
        /// The entry.
        value: f64,
    },
    /// The correlation matrix is not positive semi-definite: its Cholesky factorisation found
    /// a negative pivot (or a zero pivot with a non-zero remainder) at this input.
    #[error("correlation matrix is not positive semi-definite (fails at input {input})")]
    CorrelationNotPositiveSemiDefinite {
        /// The input at which the factorisation failed.
        input: String,
    },
    /// Correlated inputs must share their degrees of freedom: a correlated group then enters
    /// the Welch–Satterthwaite formula as one term, and the Monte Carlo method draws it from
    /// one multivariate t (or normal) distribution.
    #[error(
        "correlated inputs {first} ({first_dof}) and {second} ({second_dof}) have different degrees of freedom"
    )]
    CorrelatedDofMismatch {
        /// One input of the group.
        first: String,
        /// Its degrees of freedom.
        first_dof: Dof,
        /// Another input of the group.
        second: String,
        /// Its degrees of freedom.
        second_dof: Dof,
    },
    /// The Monte Carlo method draws correlated inputs from a multivariate normal (or t)
    /// distribution only.
    #[error(
        "input {input}: a correlated input must be Normal or StudentT for the Monte Carlo method, not {distribution:?}"
    )]
    CorrelatedDistribution {
        /// The input.
        input: String,
        /// Its distribution.
        distribution: Distribution,
    },
    /// The model has a different number of inputs than were given.
    #[error("the model takes {model} inputs; {given} were given")]
    InputCount {
        /// Inputs the model takes.
        model: usize,
        /// Inputs given.
        given: usize,
    },
    /// The model failed at the estimate of the inputs.
    #[error("the model failed at the estimate of the inputs")]
    ModelFailedAtEstimate {
        /// Why.
        #[source]
        source: ModelError,
    },
    /// The model returned a non-finite output at the estimate of the inputs.
    #[error("output {output} is {value} at the estimate of the inputs")]
    NonFiniteEstimate {
        /// The output.
        output: String,
        /// The value returned.
        value: f64,
    },
    /// The model failed at a point of the numerical differentiation for this input.
    #[error("the model failed while differentiating with respect to input {input}")]
    SensitivityFailed {
        /// The input.
        input: String,
        /// Why.
        #[source]
        source: ModelError,
    },
    /// The model returned a non-finite output at a point of the numerical differentiation.
    #[error("output {output} is not finite while differentiating with respect to input {input}")]
    NonFiniteSensitivity {
        /// The input.
        input: String,
        /// The output.
        output: String,
    },
    /// A result (an uncertainty, a variance or a mean) overflowed to infinity or is NaN.
    #[error("the {what} of output {output} is not finite (overflow)")]
    NonFiniteResult {
        /// The output.
        output: String,
        /// Which quantity.
        what: &'static str,
    },
    /// More Monte Carlo trials failed than allowed.
    #[error(
        "{failed} of {trials} Monte Carlo trials failed (more than the allowed fraction {max_fraction}); the first failure"
    )]
    TooManyFailedTrials {
        /// Failed trials.
        failed: u64,
        /// All trials.
        trials: u64,
        /// The allowed fraction.
        max_fraction: f64,
        /// The first failure (in trial order).
        #[source]
        first: ModelError,
    },
    /// The adaptive Monte Carlo method did not stabilise within the trial cap.
    #[error(
        "output {output}: the {statistic} had not stabilised after {trials} trials (cap {max_trials})"
    )]
    NotConverged {
        /// The first output (in model order) that had not stabilised.
        output: String,
        /// The statistic of that output that had not stabilised.
        statistic: Statistic,
        /// Trials run.
        trials: u64,
        /// The cap.
        max_trials: u64,
    },
    /// More Monte Carlo trials than [`crate::MAX_TRIALS`], refused before any is drawn.
    #[error(
        "trials = {}: at most {} Monte Carlo trials are drawn; {} would keep {} of model values \
         (8 bytes per trial and output) and take about {} s of CPU",
        units::Compact(*trials as f64),
        units::Compact(*max as f64),
        units::Compact(*trials as f64),
        bytes_text(*bytes),
        units::Compact(seconds.round())
    )]
    TooManyTrials {
        /// Asked for.
        trials: u64,
        /// The cap.
        max: u64,
        /// The memory the values would take, bytes.
        bytes: u64,
        /// The CPU time estimated, s.
        seconds: f64,
    },
    /// The evaluation was asked to stop ([`stoppable`](crate::stoppable): an interrupted
    /// caller) before it finished.
    #[error("stopped on request after {trials} trials")]
    Stopped {
        /// Trials run before it stopped.
        trials: u64,
    },
    /// An option is out of its domain.
    #[error("option {name} = {} is invalid: {requirement}", units::Compact(*value))]
    InvalidOption {
        /// The option's field name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy (the workspace's one requirement vocabulary).
        requirement: units::Requirement,
    },
    /// Student's t quantile at this probability and so few degrees of freedom is beyond the
    /// range of double precision.
    #[error(
        "the t quantile at probability {} with {dof} degrees of freedom is beyond the range of double precision",
        units::Compact(*probability)
    )]
    QuantileOverflow {
        /// The probability asked for.
        probability: f64,
        /// The degrees of freedom.
        dof: Dof,
    },
    /// A GUM result and a Monte Carlo result to be compared do not describe the same outputs.
    #[error("GUM output {index} is {gum:?} but Monte Carlo output {index} is {mc:?}")]
    OutputMismatch {
        /// Position of the output.
        index: usize,
        /// The GUM result's name (empty if missing).
        gum: String,
        /// The Monte Carlo result's name (empty if missing).
        mc: String,
    },
    /// A GUM result and a Monte Carlo result to be compared have different coverage
    /// probabilities.
    #[error("GUM coverage probability {gum} differs from the Monte Carlo one {mc}")]
    CoverageProbabilityMismatch {
        /// The GUM result's.
        gum: f64,
        /// The Monte Carlo result's.
        mc: f64,
    },
}

/// `Result` with [`UncertaintyError`].
pub type Result<T> = std::result::Result<T, UncertaintyError>;

/// A size in bytes as a person reads it: `8e9 bytes (7.5 GiB)`.
fn bytes_text(bytes: u64) -> String {
    let gib = bytes as f64 / f64::from(1_u32 << 30);
    if gib >= 1.0 {
        format!("{} bytes ({gib:.1} GiB)", units::Compact(bytes as f64))
    } else {
        format!(
            "{} bytes ({:.0} MiB)",
            units::Compact(bytes as f64),
            bytes as f64 / f64::from(1_u32 << 20)
        )
    }
}
