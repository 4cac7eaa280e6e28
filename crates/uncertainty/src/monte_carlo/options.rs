//! The options of the Monte Carlo method and their checks: how many trials, the coverage
//! probability, the digits of the numerical tolerance, the failures allowed.

use crate::error::{Result, UncertaintyError};
use units::Requirement;

/// How many trials to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trials {
    /// The adaptive procedure of JCGM 101 §7.9.4: batches of `h` trials until twice the
    /// standard deviation of the batch results of the estimate, the standard uncertainty and
    /// both coverage limits is within the numerical tolerance (§7.9.2) of every output, or
    /// the cap `max_trials` is reached (an error).
    Adaptive {
        /// The cap on the number of trials (at least two batches).
        max_trials: u64,
    },
    /// Exactly this many trials (§7.2), at least `100/(1 − p)`, in batches of `h` trials (the
    /// last one takes the remainder, fewer than `2h`).
    Fixed(u64),
}

/// Options of [`monte_carlo`](fn@crate::monte_carlo).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct McOptions {
    /// Seed of the random streams: the same seed gives the same result bit for bit, on any
    /// number of threads.
    pub seed: u64,
    /// Coverage probability `p` of the coverage intervals (default 0.95, at most 0.9999).
    pub coverage_probability: f64,
    /// Significant decimal digits `n_dig` of the standard uncertainty for the numerical
    /// tolerance (§7.9.2; default 2).
    pub n_dig: u32,
    /// Adaptive (default, capped at 10⁷ trials) or fixed (at most [`MAX_TRIALS`]).
    pub trials: Trials,
    /// Largest fraction of trials allowed to fail (the model returns an error or a non-finite
    /// output); default 10⁻³, at most ½. Failed trials are left out of every statistic.
    pub max_failed_fraction: f64,
}

impl Default for McOptions {
    fn default() -> Self {
        McOptions {
            seed: 0x5EED_CA1B,
            coverage_probability: 0.95,
            n_dig: 2,
            trials: Trials::Adaptive {
                max_trials: MAX_TRIALS,
            },
            max_failed_fraction: 1e-3,
        }
    }
}

/// The most trials a Monte Carlo run draws, fixed or adaptive (`max_trials`): 10⁷, the
/// adaptive cap's default. Every model value is kept for the coverage intervals
/// ([`MC_BYTES_PER_TRIAL_AND_OUTPUT`]), so trials cost memory: 80 MB per output at the cap
/// (issue 32: `trials: fixed(1000000000)` aborted the study on an 8 GB allocation).
pub const MAX_TRIALS: u64 = 10_000_000;

/// Bytes a Monte Carlo run keeps per trial and output quantity (each model value, `f64`).
pub const MC_BYTES_PER_TRIAL_AND_OUTPUT: u64 = 8;

/// CPU time per trial used in the estimate a refusal states, s: the calibration model's
/// measured 10⁷ trials/s on one thread (docs/PERFORMANCE.md); other models are slower.
const SECONDS_PER_TRIAL: f64 = 1e-7;

/// Refuses a number of trials above [`MAX_TRIALS`] for a model of `outputs` output
/// quantities, before any is drawn, with the memory and time they would take: what the
/// study's check, the Python package and [`monte_carlo`](fn@crate::monte_carlo) call.
///
/// # Errors
/// [`UncertaintyError::TooManyTrials`].
pub fn check_trials(trials: u64, outputs: usize) -> Result<()> {
    if trials > MAX_TRIALS {
        return Err(UncertaintyError::TooManyTrials {
            trials,
            max: MAX_TRIALS,
            bytes: trials
                .saturating_mul(outputs.max(1) as u64)
                .saturating_mul(MC_BYTES_PER_TRIAL_AND_OUTPUT),
            seconds: trials as f64 * SECONDS_PER_TRIAL,
        });
    }
    Ok(())
}

/// The largest coverage probability the Monte Carlo method takes: its batches hold
/// `100/(1 − p)` trials, 10⁶ here.
const MAX_COVERAGE_PROBABILITY: f64 = 0.9999;

/// Refuses options the method cannot honour, naming the option and what it must be.
pub(super) fn check_options(options: &McOptions, batch_size: u64, outputs: usize) -> Result<()> {
    let invalid = |name, value, requirement| {
        Err(UncertaintyError::InvalidOption {
            name,
            value,
            requirement,
        })
    };
    let p = options.coverage_probability;
    if !(p > 0.0 && p <= MAX_COVERAGE_PROBABILITY) {
        // batches of up to 10^6 trials
        return invalid(
            "coverage_probability",
            p,
            Requirement::AboveAtMost {
                min: 0.0,
                max: MAX_COVERAGE_PROBABILITY,
            },
        );
    }
    let f = options.max_failed_fraction;
    if !(0.0..=0.5).contains(&f) {
        return invalid(
            "max_failed_fraction",
            f,
            Requirement::InRange { min: 0.0, max: 0.5 },
        );
    }
    if options.n_dig == 0 || options.n_dig > 6 {
        return invalid(
            "n_dig",
            options.n_dig as f64,
            Requirement::InRange { min: 1.0, max: 6.0 },
        );
    }
    match options.trials {
        Trials::Adaptive { max_trials } | Trials::Fixed(max_trials) if max_trials > MAX_TRIALS => {
            check_trials(max_trials, outputs)
        }
        Trials::Adaptive { max_trials } if max_trials < 2 * batch_size => invalid(
            "max_trials",
            max_trials as f64,
            // two batches of max(100/(1 - p), 10^4) trials
            Requirement::AtLeast((2 * batch_size) as f64),
        ),
        // (beyond MAX_TRIALS, refused above with the memory and time it would take)
        Trials::Fixed(n) if n < (100.0 / (1.0 - p)).ceil() as u64 => invalid(
            "trials",
            n as f64,
            Requirement::InRange {
                min: (100.0 / (1.0 - p)).ceil(),
                max: MAX_TRIALS as f64,
            },
        ),
        _ => Ok(()),
    }
}
