//! What the Monte Carlo method returns: per output, the estimate, standard uncertainty,
//! coverage interval and the batches' spread; for all outputs, the covariance and the trial
//! counts.

use crate::error::ModelError;

/// Twice the standard deviations of the batch results (JCGM 101 §7.9.4 f, i): each is at
/// most the numerical tolerance when the adaptive procedure has converged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stability {
    /// `2·s_y` of the batch estimates.
    pub estimate: f64,
    /// `2·s_u(y)` of the batch standard uncertainties.
    pub standard_uncertainty: f64,
    /// `2·s_ylow` of the batch lower coverage limits.
    pub coverage_low: f64,
    /// `2·s_yhigh` of the batch upper coverage limits.
    pub coverage_high: f64,
}

/// The Monte Carlo evaluation of one output quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct McOutput {
    /// The output.
    pub name: String,
    /// Estimate: the mean of the model values (§7.6).
    pub estimate: f64,
    /// Standard uncertainty: their standard deviation (§7.6).
    pub standard_uncertainty: f64,
    /// The probabilistically symmetric coverage interval `[y_low, y_high]` (§7.7).
    pub coverage_interval: (f64, f64),
    /// The numerical tolerance δ of the standard uncertainty with `n_dig` digits (§7.9.2).
    pub tolerance: f64,
    /// The batch spread at the end, when there was more than one batch.
    pub stability: Option<Stability>,
    /// An input is drawn from a t with ν ≤ 2, which has no variance: the model values may
    /// have none either, so the estimate and the standard uncertainty are those of the
    /// trials drawn and do not settle as trials are added; the coverage interval does, and
    /// is the result to use. The adaptive procedure then waits on the coverage limits only,
    /// to `n_dig` significant digits of the interval's half-width.
    pub heavy_tailed: bool,
}

/// The Monte Carlo evaluation of all output quantities.
#[derive(Debug, Clone, PartialEq)]
pub struct McResult {
    /// The coverage probability of the coverage intervals.
    pub coverage_probability: f64,
    /// One per output, in model order.
    pub outputs: Vec<McOutput>,
    /// Covariance matrix of the outputs from the model values (row-major, `m × m`; JCGM 102
    /// §7.6).
    pub covariance: Vec<f64>,
    /// All trials run, failed ones included (the same for every output).
    pub trials: u64,
    /// Failed trials (the model returned an error or a non-finite output), left out of every
    /// statistic.
    pub failed_trials: u64,
    /// The first failure, in trial order.
    pub first_failure: Option<ModelError>,
    /// Batches run.
    pub batches: u64,
    /// Trials per batch: `max(⌈100/(1 − p)⌉, 10⁴)` (§7.9.4 b).
    pub batch_size: u64,
}

impl McResult {
    /// The output named `name`.
    pub fn output(&self, name: &str) -> Option<&McOutput> {
        self.outputs.iter().find(|o| o.name == name)
    }
}
