//! Propagation of distributions by the Monte Carlo method (JCGM 101:2008 §5–§7), adaptive
//! (§7.9), seeded and parallel.
//!
//! Read in this order: `options` (what is asked), `draw` (the trials), `order` (the
//! coverage interval of a batch), `accumulate` (the statistics over batches), `result`
//! (what is returned); this file runs the batches and finishes the results.

mod accumulate;
mod draw;
mod options;
mod order;
mod result;

use rayon::prelude::*;

use crate::error::{ModelError, Result, UncertaintyError};
use crate::input::Inputs;
use crate::model::{MeasurementModel, checked_output_names};
use crate::tolerance::numerical_tolerance;
use accumulate::{
    Accumulator, COVARIANCE_BLOCK, centered_dot, has_heavy_tails, output_tolerance, unstable,
};
use draw::{draws, run_batch};
use options::check_options;
use order::coverage_interval;

pub use options::{MAX_TRIALS, MC_BYTES_PER_TRIAL_AND_OUTPUT, McOptions, Trials, check_trials};
pub use result::{McOutput, McResult, Stability};

/// The Monte Carlo method of JCGM 101:2008 applied to `model` at `inputs`.
///
/// Each trial draws every input from its distribution (§6.4: normal §6.4.7, rectangular
/// §6.4.2, scaled-and-shifted t §6.4.9; a group of correlated inputs from the multivariate
/// normal of §6.4.8 through the Cholesky factor of its correlation matrix, or from the
/// multivariate t with the group's common ν) and evaluates the model. Trials run in batches
/// of `h = max(⌈100/(1 − p)⌉, 10⁴)` (§7.9.4 b), each batch in chunks of 1000 trials on their
/// own random streams, in parallel (rayon); the streams depend only on the seed, the batch
/// and the chunk, so the result is the same on any number of threads.
///
/// With [`Trials::Adaptive`], batches are added until, for every output, twice the standard
/// deviation of the average of the batch estimates, standard uncertainties and both
/// coverage limits is at most the numerical tolerance δ of the standard uncertainty from all
/// trials (§7.9.4 f–i, §7.9.2 with `n_dig` digits). The results then come from all trials
/// (§7.9.4 j): estimate and standard uncertainty (§7.6) and the probabilistically symmetric
/// coverage interval (§7.7).
///
/// Memory: all model values are kept for the coverage intervals, 8 bytes per output and
/// trial (80 MB per output at the cap of 10⁷ trials, [`MAX_TRIALS`]: more trials, fixed or as
/// the adaptive cap, are refused before any is drawn, [`check_trials`]).
///
/// Errors: invalid options; a correlated input that is not Normal or StudentT (or a group
/// mixing them); more failed trials than `max_failed_fraction` of all trials (or a batch with
/// fewer than two successful trials); not converged within `max_trials`, naming the first
/// output and statistic that had not stabilised; an overflowing statistic; `Stopped` when
/// the caller's flag ([`stoppable`](crate::stoppable)) is raised, checked before each batch.
pub fn monte_carlo<M: MeasurementModel + ?Sized>(
    model: &M,
    inputs: &Inputs,
    options: &McOptions,
) -> Result<McResult> {
    let p = options.coverage_probability;
    let batch_size = ((100.0 / (1.0 - p)).ceil() as u64).max(10_000);
    let names = checked_output_names(model, inputs.len())?;
    check_options(options, batch_size, names.len())?;
    let draws = draws(inputs)?;
    let heavy_tailed = has_heavy_tails(inputs);
    let (n, m) = (inputs.len(), names.len());
    let mut accumulators: Vec<Accumulator> = (0..m).map(|_| Accumulator::default()).collect();
    // A fixed run's last batch takes the remainder (fewer than 2h trials), so that no batch
    // is too small for its own statistics.
    let largest = match options.trials {
        Trials::Fixed(total) => total.min(2 * batch_size - 1),
        Trials::Adaptive { .. } => batch_size,
    };
    let mut rows = vec![0.0; largest as usize * m];
    if let Trials::Fixed(total) = options.trials {
        // Every value is kept (for the coverage intervals): room for all at once, not by
        // doubling and copying.
        for acc in &mut accumulators {
            acc.values.reserve_exact(total as usize);
        }
    }
    let (mut trials, mut failed, mut first_failure, mut batches) = (0u64, 0u64, None, 0u64);
    loop {
        if crate::stop::stop_requested() {
            return Err(UncertaintyError::Stopped { trials });
        }
        let this = match options.trials {
            Trials::Fixed(total) if total - trials < 2 * batch_size => total - trials,
            _ => batch_size,
        } as usize;
        let rows = &mut rows[..this * m];
        let (f, first) = run_batch(model, &draws, n, m, options.seed, batches, rows);
        batches += 1;
        trials += this as u64;
        failed += f;
        if first_failure.is_none() {
            first_failure = first.map(|(_, e)| e);
        }
        if let Some(first) = first_failure
            && (failed as f64 > options.max_failed_fraction * trials as f64 || this as u64 - f < 2)
        {
            return Err(UncertaintyError::TooManyFailedTrials {
                failed,
                trials,
                max_fraction: options.max_failed_fraction,
                first,
            });
        }
        let rows = &*rows;
        accumulators
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, acc)| acc.add_batch(rows, m, k, p));
        match options.trials {
            Trials::Fixed(total) => {
                if trials >= total {
                    break;
                }
            }
            Trials::Adaptive { max_trials } => {
                if batches < 2 {
                    continue;
                }
                let first_unstable = accumulators.iter().enumerate().find_map(|(k, acc)| {
                    let tolerance = output_tolerance(acc, heavy_tailed, options.n_dig);
                    let s = acc.stability()?;
                    unstable(&s, tolerance, heavy_tailed).map(|stat| (k, stat))
                });
                match first_unstable {
                    None => break,
                    Some((k, statistic)) if trials + batch_size > max_trials => {
                        return Err(UncertaintyError::NotConverged {
                            output: names[k].clone(),
                            statistic,
                            trials,
                            max_trials,
                        });
                    }
                    Some(_) => {}
                }
            }
        }
    }
    finish(
        accumulators,
        names,
        options,
        p,
        trials,
        failed,
        first_failure,
        batches,
        batch_size,
        heavy_tailed,
    )
}

#[allow(clippy::too_many_arguments)]
fn finish(
    mut accumulators: Vec<Accumulator>,
    names: Vec<String>,
    options: &McOptions,
    p: f64,
    trials: u64,
    failed: u64,
    first_failure: Option<ModelError>,
    batches: u64,
    batch_size: u64,
    heavy_tailed: bool,
) -> Result<McResult> {
    let m = names.len();
    // Covariance from the aligned columns (before the selections reorder them).
    // Sums over fixed blocks of trials, added in block order: the same on any thread count.
    let pairs: Vec<(usize, usize)> = (0..m).flat_map(|a| (0..=a).map(move |b| (a, b))).collect();
    let count = accumulators[0].values.len();
    let blocks: Vec<Vec<f64>> = (0..count.div_ceil(COVARIANCE_BLOCK))
        .into_par_iter()
        .map(|block| {
            let r = block * COVARIANCE_BLOCK..count.min((block + 1) * COVARIANCE_BLOCK);
            pairs
                .iter()
                .map(|&(a, b)| {
                    let (ea, eb) = (&accumulators[a], &accumulators[b]);
                    centered_dot(
                        &ea.values[r.clone()],
                        &eb.values[r.clone()],
                        ea.mean,
                        eb.mean,
                    )
                })
                .collect()
        })
        .collect();
    let mut covariance = vec![0.0; m * m];
    for (p, &(a, b)) in pairs.iter().enumerate() {
        let c = blocks.iter().map(|sums| sums[p]).sum::<f64>() / (count - 1) as f64;
        covariance[a * m + b] = c;
        covariance[b * m + a] = c;
    }
    let outputs: Vec<McOutput> = accumulators
        .par_iter_mut()
        .zip(names)
        .map(|(acc, name)| {
            let u = acc.standard_uncertainty();
            let stability = acc.stability();
            let interval = coverage_interval(&mut acc.values, p);
            McOutput {
                name,
                estimate: acc.mean,
                standard_uncertainty: u,
                coverage_interval: interval,
                tolerance: numerical_tolerance(u, options.n_dig),
                stability,
                heavy_tailed,
            }
        })
        .collect();
    for (k, o) in outputs.iter().enumerate() {
        let finite = o.estimate.is_finite()
            && o.standard_uncertainty.is_finite()
            && o.stability.is_none_or(|s| {
                [
                    s.estimate,
                    s.standard_uncertainty,
                    s.coverage_low,
                    s.coverage_high,
                ]
                .iter()
                .all(|v| v.is_finite())
            })
            && covariance[k * m..(k + 1) * m].iter().all(|v| v.is_finite());
        if !finite {
            return Err(UncertaintyError::NonFiniteResult {
                output: o.name.clone(),
                what: "standard uncertainty or covariance",
            });
        }
    }
    Ok(McResult {
        coverage_probability: p,
        outputs,
        covariance,
        trials,
        failed_trials: failed,
        first_failure,
        batches,
        batch_size,
    })
}
