//! Propagation of distributions by the Monte Carlo method (JCGM 101:2008 §5–§7), adaptive
//! (§7.9), seeded and parallel.

use rand::{Rng, SeedableRng};
use rand_distr::{ChiSquared, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;
use rayon::prelude::*;

use crate::error::{ModelError, Result, Statistic, UncertaintyError};
use crate::input::Inputs;
use crate::kind::{Distribution, Dof};
use crate::model::{MeasurementModel, checked_output_names};
use crate::tolerance::numerical_tolerance;
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

/// Options of [`monte_carlo`].
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
    /// Adaptive (default, capped at 10⁷ trials) or fixed.
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
                max_trials: 10_000_000,
            },
            max_failed_fraction: 1e-3,
        }
    }
}

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

/// The largest coverage probability the Monte Carlo method takes: its batches hold
/// `100/(1 − p)` trials, 10⁶ here.
const MAX_COVERAGE_PROBABILITY: f64 = 0.9999;

/// The generator of the Monte Carlo draws: xoshiro256++ (Blackman & Vigna), a fixed
/// algorithm whose output for a seed is the same on every platform and every version of
/// `rand_xoshiro`; it passes BigCrush and has a period of 2²⁵⁶ − 1. Each chunk of trials has
/// its own stream, seeded through SplitMix64 (see [`stream`]).
type McRng = Xoshiro256PlusPlus;

/// Trials per random stream. Fixed, so that the streams, and therefore the results, do not
/// depend on the number of threads.
const CHUNK: usize = 1000;
/// Trials per sub-block of a chunk: the inputs are drawn a column (one input, `SUB` trials)
/// at a time, then the model runs trial by trial over the sub-block.
const SUB: usize = 250;

/// How one input, or one group of correlated inputs, is drawn.
#[derive(Debug, Clone)]
enum Draw {
    Constant {
        index: usize,
        value: f64,
    },
    Normal {
        index: usize,
        mean: f64,
        scale: f64,
    },
    Rectangular {
        index: usize,
        mean: f64,
        half_width: f64,
    },
    /// `x = μ + u·z·√(ν/w)`, `z` standard normal, `w` χ² with ν degrees of freedom.
    StudentT {
        index: usize,
        mean: f64,
        scale: f64,
        chi: ChiSquared<f64>,
        nu: f64,
    },
    /// `x = μ + diag(u)·L·z·√(ν/w)` (multivariate normal, or t when `chi` is present;
    /// JCGM 101 §6.4.8, JCGM 102 §6.5.3).
    Group {
        members: Vec<usize>,
        means: Vec<f64>,
        scales: Vec<f64>,
        factor: Vec<f64>,
        chi: Option<(ChiSquared<f64>, f64)>,
    },
}

impl Draw {
    /// Fills this draw's column(s) of `cols` (column-major, `SUB` rows per input) for the
    /// first `len` trials of a sub-block. Each draw takes its random numbers column by column:
    /// a t input its `len` normals, then its `len` chi-squares; a group its members' normals
    /// one member at a time, then one chi-square per trial. The arithmetic then runs over
    /// whole columns.
    fn fill(&self, rng: &mut McRng, cols: &mut [f64], len: usize, scratch: &mut Scratch) {
        let col = |index: usize| index * SUB..index * SUB + len;
        match self {
            Draw::Constant { index, value } => {
                let r = col(*index);
                cols[r].fill(*value);
            }
            Draw::Normal { index, mean, scale } => {
                let r = col(*index);
                for v in &mut cols[r] {
                    let n: f64 = rng.sample(StandardNormal);
                    *v = mean + scale * n;
                }
            }
            Draw::Rectangular {
                index,
                mean,
                half_width,
            } => {
                let r = col(*index);
                for v in &mut cols[r] {
                    let u: f64 = rng.random();
                    *v = mean + half_width * (2.0 * u - 1.0);
                }
            }
            Draw::StudentT {
                index,
                mean,
                scale,
                chi,
                nu,
            } => {
                let column = &mut cols[col(*index)];
                for v in column.iter_mut() {
                    *v = rng.sample(StandardNormal);
                }
                let w = &mut scratch.w[..len];
                for w in w.iter_mut() {
                    *w = rng.sample(chi);
                }
                for (v, w) in column.iter_mut().zip(w.iter()) {
                    *v = mean + scale * *v * (nu / w).sqrt();
                }
            }
            Draw::Group {
                members,
                means,
                scales,
                factor,
                chi,
            } => {
                let k = members.len();
                let z = &mut scratch.z[..k * SUB];
                for c in 0..k {
                    for v in &mut z[c * SUB..c * SUB + len] {
                        *v = rng.sample(StandardNormal);
                    }
                }
                let w = &mut scratch.w[..len];
                match chi {
                    Some((chi, nu)) => {
                        for w in w.iter_mut() {
                            let draw: f64 = rng.sample(chi);
                            *w = (nu / draw).sqrt();
                        }
                    }
                    None => w.fill(1.0),
                }
                let lz = &mut scratch.lz[..len];
                for (r, &index) in members.iter().enumerate() {
                    // (L·z)_r over the sub-block, column by column of L.
                    lz.fill(0.0);
                    for (c, &l) in factor[r * k..r * k + r + 1].iter().enumerate() {
                        for (a, z) in lz.iter_mut().zip(&z[c * SUB..c * SUB + len]) {
                            *a += l * z;
                        }
                    }
                    let (mean, scale) = (means[r], scales[r]);
                    for ((x, a), w) in cols[col(index)].iter_mut().zip(lz.iter()).zip(w.iter()) {
                        *x = mean + scale * a * w;
                    }
                }
            }
        }
    }
}

/// Work space of [`Draw::fill`] for one sub-block.
struct Scratch {
    /// A group's normals, member-major (`SUB` per member).
    z: Vec<f64>,
    /// The chi-squares of a t input, or a group's `√(ν/w)`.
    w: Vec<f64>,
    /// `L·z` of one group member.
    lz: Vec<f64>,
}

impl Scratch {
    fn new(max_group: usize) -> Self {
        Scratch {
            z: vec![0.0; max_group * SUB],
            w: vec![0.0; SUB],
            lz: vec![0.0; SUB],
        }
    }
}

fn draws(inputs: &Inputs) -> Result<Vec<Draw>> {
    let q = inputs.quantities();
    let mut out = Vec::with_capacity(inputs.groups().len());
    for group in inputs.groups() {
        if let [index] = group.members[..] {
            let (mean, u) = (q[index].value, q[index].standard_uncertainty);
            out.push(if u == 0.0 {
                Draw::Constant { index, value: mean }
            } else {
                match (q[index].distribution, q[index].dof) {
                    (Distribution::Normal, _) => Draw::Normal {
                        index,
                        mean,
                        scale: u,
                    },
                    (Distribution::Rectangular, _) => Draw::Rectangular {
                        index,
                        mean,
                        half_width: u * 3f64.sqrt(),
                    },
                    (Distribution::StudentT, Dof::Finite(nu)) => Draw::StudentT {
                        index,
                        mean,
                        scale: u,
                        nu,
                        chi: ChiSquared::new(nu).map_err(|_| UncertaintyError::InvalidDof {
                            input: q[index].name.clone(),
                            dof: nu,
                        })?,
                    },
                    (Distribution::StudentT, Dof::Infinite) => {
                        return Err(UncertaintyError::StudentTNeedsFiniteDof {
                            input: q[index].name.clone(),
                        });
                    }
                }
            });
            continue;
        }
        let first = group.members[0];
        for &m in &group.members {
            let d = q[m].distribution;
            if d == Distribution::Rectangular || d != q[first].distribution {
                return Err(UncertaintyError::CorrelatedDistribution {
                    input: q[m].name.clone(),
                    distribution: d,
                });
            }
        }
        let chi = match (q[first].distribution, group.dof) {
            (Distribution::StudentT, Dof::Finite(nu)) => Some((
                ChiSquared::new(nu).map_err(|_| UncertaintyError::InvalidDof {
                    input: q[first].name.clone(),
                    dof: nu,
                })?,
                nu,
            )),
            _ => None,
        };
        out.push(Draw::Group {
            members: group.members.clone(),
            means: group.members.iter().map(|&i| q[i].value).collect(),
            scales: group
                .members
                .iter()
                .map(|&i| q[i].standard_uncertainty)
                .collect(),
            factor: group.factor.clone(),
            chi,
        });
    }
    Ok(out)
}

/// An independent random stream per (seed, batch, chunk): the workspace's one seeding
/// convention ([`units::stream_seed`]), which `seed_from_u64` expands into the generator's
/// 256-bit state by SplitMix64 again.
fn stream(seed: u64, batch: u64, chunk: u64) -> McRng {
    McRng::seed_from_u64(units::stream_seed(seed, batch, chunk))
}

/// The failures of one chunk: how many, and the first (trial index in the batch, error).
type ChunkFailures = (u64, Option<(usize, ModelError)>);

/// Runs one batch of `trials` trials into `rows` (row-major `trials × m`); a failed trial's
/// row is NaN. Chunks of [`CHUNK`] trials run in parallel, each on its own stream.
fn run_batch<M: MeasurementModel + ?Sized>(
    model: &M,
    draws: &[Draw],
    n: usize,
    m: usize,
    seed: u64,
    batch: u64,
    rows: &mut [f64],
) -> ChunkFailures {
    let max_group = draws
        .iter()
        .map(|d| match d {
            Draw::Group { members, .. } => members.len(),
            _ => 0,
        })
        .max()
        .unwrap_or(0);
    let per_chunk: Vec<ChunkFailures> = rows
        .par_chunks_mut(CHUNK * m)
        .enumerate()
        .map(|(chunk, rows)| {
            let mut rng = stream(seed, batch, chunk as u64);
            let mut cols = vec![0.0; n * SUB];
            let mut scratch = Scratch::new(max_group);
            let mut failed = 0;
            let mut first = None;
            for (sub, rows) in rows.chunks_mut(SUB * m).enumerate() {
                let len = rows.len() / m;
                for d in draws {
                    d.fill(&mut rng, &mut cols, len, &mut scratch);
                }
                let mut error = model.evaluate_trials(&cols, SUB, len, rows);
                if let Some((t, _)) = error
                    && let Some(y) = rows.chunks_exact_mut(m).nth(t)
                {
                    y.fill(f64::NAN);
                }
                for (t, y) in rows.chunks_exact_mut(m).enumerate() {
                    if y.iter().all(|v| v.is_finite()) {
                        continue;
                    }
                    y.fill(f64::NAN);
                    failed += 1;
                    let e = match error.take() {
                        Some((at, e)) if at == t => e,
                        other => {
                            error = other;
                            ModelError::Failed {
                                reason: "non-finite output",
                            }
                        }
                    };
                    first.get_or_insert((chunk * CHUNK + sub * SUB + t, e));
                }
            }
            (failed, first)
        })
        .collect();
    per_chunk
        .into_iter()
        .fold((0, None), |(n, first), (f, fst)| (n + f, first.or(fst)))
}

/// Index `(r, r + q)` (0-based) of the probabilistically symmetric 100p % coverage interval
/// among `count` sorted values (JCGM 101 §7.7.1 and §7.7.2, with 1-based `r`).
fn coverage_indices(count: usize, p: f64) -> (usize, usize) {
    let q = ((p * count as f64) + 0.5).floor() as usize;
    let q = q.min(count - 1);
    // r = (M − q)/2 when that is an integer, (M − q + 1)/2 otherwise: ⌈(M − q)/2⌉, at least 1.
    let r = (count - q).div_ceil(2).max(1);
    (r - 1, (r + q - 1).min(count - 1))
}

/// The coverage interval of `values` (reordered in place by selection).
fn coverage_interval(values: &mut [f64], p: f64) -> (f64, f64) {
    let (lo, hi) = coverage_indices(values.len(), p);
    order_statistics(values, lo, hi)
}

/// The order statistics of 0-based ranks `lo ≤ hi` of `values` in the order of
/// [`f64::total_cmp`], by selection (`values` is reordered).
fn select_two(values: &mut [f64], lo: usize, hi: usize) -> (f64, f64) {
    let (_, low, upper) = values.select_nth_unstable_by(lo, f64::total_cmp);
    let low = *low;
    let high = if hi == lo {
        low
    } else {
        *upper.select_nth_unstable_by(hi - lo - 1, f64::total_cmp).1
    };
    (low, high)
}

/// Fewest values for which [`order_statistics`] brackets the ranks from a sample; fewer are
/// selected directly.
const BRACKET_MIN: usize = 65_536;

/// The order statistics of 0-based ranks `lo ≤ hi` of `values` (in the order of
/// [`f64::total_cmp`]; `values` may be reordered): the same numbers as two selections, at
/// the cost of about one pass for large slices.
///
/// Floyd and Rivest's bracketing: the ranks' neighbourhoods in an evenly strided sample of
/// about `n^(2/3)` values give two brackets that hold the wanted order statistics with
/// overwhelming probability; one pass counts the values below each bracket and gathers those
/// inside, and the order statistic is selected among the gathered few. A bracket that missed
/// (its count says so, exactly) falls back to selecting over all values, so the result never
/// depends on the sample.
///
/// # References
/// R. W. Floyd, R. L. Rivest, "Expected time bounds for selection", Commun. ACM 18 (1975).
fn order_statistics(values: &mut [f64], lo: usize, hi: usize) -> (f64, f64) {
    let n = values.len();
    if n < BRACKET_MIN || hi < lo {
        return select_two(values, lo, hi);
    }
    let stride = (n as f64).cbrt().ceil() as usize;
    let mut sample: Vec<f64> = values.iter().step_by(stride).copied().collect();
    let s = sample.len();
    // Sample ranks k·s/n ± 4 standard deviations of a sample rank (and 2 for rounding).
    let bracket = |k: usize, sample: &mut [f64]| -> (f64, f64) {
        let q = k as f64 / n as f64;
        let centre = q * s as f64;
        let margin = 4.0 * (s as f64 * q * (1.0 - q)).sqrt() + 2.0;
        let a = centre - margin;
        let b = centre + margin;
        let low = if a < 0.0 {
            f64::NEG_INFINITY
        } else {
            *sample.select_nth_unstable_by(a as usize, f64::total_cmp).1
        };
        let high = if b >= (s - 1) as f64 {
            f64::INFINITY
        } else {
            *sample
                .select_nth_unstable_by(b.ceil() as usize, f64::total_cmp)
                .1
        };
        (low, high)
    };
    let (a1, b1) = bracket(lo, &mut sample);
    let (a2, b2) = bracket(hi, &mut sample);
    within_brackets(values, lo, hi, [a1, b1, a2, b2])
}

/// The order statistics of ranks `lo ≤ hi`, as [`select_two`] gives them, found among the
/// values inside the brackets `[a1, b1]` and `[a2, b2]` when they hold them (one counting
/// pass tells), by selection over all values otherwise.
fn within_brackets(values: &mut [f64], lo: usize, hi: usize, brackets: [f64; 4]) -> (f64, f64) {
    let [a1, b1, a2, b2] = brackets;
    // The passes compare with `<` and `<=`, which order the values as `total_cmp` does when
    // none is NaN (counted, and failed trials are left out before) and no bound is a zero
    // (−0 = +0 to `<`).
    if [a1, b1, a2, b2].iter().any(|&b| b == 0.0 || b.is_nan()) || b1 >= a2 {
        return select_two(values, lo, hi);
    }
    // First pass, counts only (vectorised): values below and up to each bracket's ends.
    let mut counts = [0usize; 5];
    for &v in values.iter() {
        counts[0] += usize::from(v < a1);
        counts[1] += usize::from(v <= b1);
        counts[2] += usize::from(v < a2);
        counts[3] += usize::from(v <= b2);
        counts[4] += usize::from(v.is_nan());
    }
    let [below, upto_first, below_second, upto_second, nan] = counts;
    if nan > 0 || !((below..upto_first).contains(&lo) && (below_second..upto_second).contains(&hi))
    {
        return select_two(values, lo, hi);
    }
    // Second pass: gather the few values inside the brackets.
    let mut first = Vec::with_capacity(upto_first - below);
    let mut second = Vec::with_capacity(upto_second - below_second);
    for &v in values.iter() {
        // Non-short-circuit operators: one branch, rarely taken, instead of a chain.
        let in_first = (v >= a1) & (v <= b1);
        let in_second = (v >= a2) & (v <= b2);
        if in_first | in_second {
            if in_first {
                first.push(v);
            } else {
                second.push(v);
            }
        }
    }
    let low = *first.select_nth_unstable_by(lo - below, f64::total_cmp).1;
    let high = *second
        .select_nth_unstable_by(hi - below_second, f64::total_cmp)
        .1;
    (low, high)
}

/// Partial sums kept apart by [`lane_sum`] and [`centered_dot`]: independent additions the
/// compiler can vectorise, in an order fixed by the data alone.
const LANES: usize = 8;

/// `Σ a_i`, in [`LANES`] interleaved partial sums.
fn lane_sum(a: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let chunks = a.chunks_exact(LANES);
    let rest: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for (s, v) in acc.iter_mut().zip(c) {
            *s += v;
        }
    }
    acc.iter().sum::<f64>() + rest
}

/// `Σ (a_i − ma)·(b_i − mb)` over the common length, in [`LANES`] interleaved partial sums.
fn centered_dot(a: &[f64], b: &[f64], ma: f64, mb: f64) -> f64 {
    let len = a.len().min(b.len());
    let (a, b) = (&a[..len], &b[..len]);
    let mut acc = [0.0; LANES];
    let (ca, cb) = (a.chunks_exact(LANES), b.chunks_exact(LANES));
    let rest: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| (x - ma) * (y - mb))
        .sum();
    for (x, y) in ca.zip(cb) {
        for ((s, x), y) in acc.iter_mut().zip(x).zip(y) {
            *s += (x - ma) * (y - mb);
        }
    }
    acc.iter().sum::<f64>() + rest
}

/// Trials per block of the final covariance: the outputs' values of a block stay in cache
/// while all the pairs are summed.
const COVARIANCE_BLOCK: usize = 4096;

/// Mean and standard deviation of a series of at least two batch results.
fn spread(series: &[f64]) -> Option<(f64, f64)> {
    let h = series.len();
    if h < 2 {
        return None;
    }
    let mean = series.iter().sum::<f64>() / h as f64;
    let ss: f64 = series.iter().map(|v| (v - mean) * (v - mean)).sum();
    Some((mean, (ss / (h - 1) as f64).sqrt()))
}

/// The running state of one output.
#[derive(Debug, Default)]
struct Accumulator {
    values: Vec<f64>,
    mean: f64,
    m2: f64,
    batch: [Vec<f64>; 4],
    scratch: Vec<f64>,
}

impl Accumulator {
    /// Adds the batch's column `k` of `rows` (skipping failed trials) and records the batch's
    /// estimate, standard uncertainty and coverage limits.
    fn add_batch(&mut self, rows: &[f64], m: usize, k: usize, p: f64) {
        self.scratch.clear();
        self.scratch
            .extend(rows.chunks_exact(m).map(|r| r[k]).filter(|v| !v.is_nan()));
        let c = self.scratch.len();
        let mean = lane_sum(&self.scratch) / c as f64;
        let m2 = centered_dot(&self.scratch, &self.scratch, mean, mean);
        // Chan et al.'s update of the running mean and sum of squares.
        let n0 = self.values.len() as f64;
        let total = n0 + c as f64;
        let delta = mean - self.mean;
        self.mean += delta * c as f64 / total;
        self.m2 += m2 + delta * delta * n0 * c as f64 / total;
        self.values.extend_from_slice(&self.scratch);
        // The batch's limits lie, with overwhelming probability, within five batch-to-batch
        // standard deviations of the previous batches' mean limits: those brackets spare a
        // full selection (a miss falls back to it, with the same result).
        let (lo, hi) = coverage_indices(c, p);
        let (low, high) = match (spread(&self.batch[2]), spread(&self.batch[3])) {
            (Some((m_low, s_low)), Some((m_high, s_high))) => within_brackets(
                &mut self.scratch,
                lo,
                hi,
                [
                    m_low - 5.0 * s_low,
                    m_low + 5.0 * s_low,
                    m_high - 5.0 * s_high,
                    m_high + 5.0 * s_high,
                ],
            ),
            _ => select_two(&mut self.scratch, lo, hi),
        };
        for (series, v) in
            self.batch
                .iter_mut()
                .zip([mean, (m2 / (c - 1) as f64).sqrt(), low, high])
        {
            series.push(v);
        }
    }

    fn standard_uncertainty(&self) -> f64 {
        (self.m2 / (self.values.len() - 1) as f64).sqrt()
    }

    /// Twice the standard deviation of the average of the batch results (§7.9.4 f).
    fn stability(&self) -> Option<Stability> {
        let h = self.batch[0].len();
        if h < 2 {
            return None;
        }
        let two_s = |series: &[f64]| {
            let mean = series.iter().sum::<f64>() / h as f64;
            let ss: f64 = series.iter().map(|v| (v - mean) * (v - mean)).sum();
            2.0 * (ss / (h * (h - 1)) as f64).sqrt()
        };
        Some(Stability {
            estimate: two_s(&self.batch[0]),
            standard_uncertainty: two_s(&self.batch[1]),
            coverage_low: two_s(&self.batch[2]),
            coverage_high: two_s(&self.batch[3]),
        })
    }
}

/// The first statistic of `s` above `tolerance`, if any; with `heavy_tailed`, the coverage
/// limits only (the estimate and standard deviation of draws without a variance never
/// settle).
fn unstable(s: &Stability, tolerance: f64, heavy_tailed: bool) -> Option<Statistic> {
    [
        (s.estimate, Statistic::Estimate),
        (s.standard_uncertainty, Statistic::StandardUncertainty),
        (s.coverage_low, Statistic::CoverageLow),
        (s.coverage_high, Statistic::CoverageHigh),
    ]
    .into_iter()
    .skip(if heavy_tailed { 2 } else { 0 })
    .find(|(v, _)| v.is_nan() || *v > tolerance)
    .map(|(_, s)| s)
}

/// Whether an input is drawn from a t with ν ≤ 2 (no variance).
fn has_heavy_tails(inputs: &Inputs) -> bool {
    inputs.quantities().iter().any(|q| {
        q.distribution == Distribution::StudentT && matches!(q.dof, Dof::Finite(nu) if nu <= 2.0)
    })
}

/// The numerical tolerance of an output: δ of its standard uncertainty (§7.9.2), or with
/// heavy tails (no variance) δ of the coverage interval's half-width (the same number of
/// significant digits of the expanded uncertainty instead).
fn output_tolerance(acc: &Accumulator, heavy_tailed: bool, n_dig: u32) -> f64 {
    if heavy_tailed && !acc.batch[2].is_empty() {
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let (low, high) = (mean(&acc.batch[2]), mean(&acc.batch[3]));
        return numerical_tolerance(0.5 * (high - low), n_dig);
    }
    numerical_tolerance(acc.standard_uncertainty(), n_dig)
}

fn check_options(options: &McOptions, batch_size: u64) -> Result<()> {
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
        Trials::Adaptive { max_trials } if max_trials < 2 * batch_size => invalid(
            "max_trials",
            max_trials as f64,
            // two batches of max(100/(1 - p), 10^4) trials
            Requirement::AtLeast((2 * batch_size) as f64),
        ),
        Trials::Fixed(n) if n < (100.0 / (1.0 - p)).ceil() as u64 => invalid(
            "trials",
            n as f64,
            Requirement::AtLeast((100.0 / (1.0 - p)).ceil()),
        ),
        _ => Ok(()),
    }
}

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
/// trial (80 MB per output at the default cap of 10⁷ trials).
///
/// Errors: invalid options; a correlated input that is not Normal or StudentT (or a group
/// mixing them); more failed trials than `max_failed_fraction` of all trials (or a batch with
/// fewer than two successful trials); not converged within `max_trials`, naming the first
/// output and statistic that had not stabilised; an overflowing statistic.
pub fn monte_carlo<M: MeasurementModel + ?Sized>(
    model: &M,
    inputs: &Inputs,
    options: &McOptions,
) -> Result<McResult> {
    let p = options.coverage_probability;
    let batch_size = ((100.0 / (1.0 - p)).ceil() as u64).max(10_000);
    check_options(options, batch_size)?;
    let names = checked_output_names(model, inputs.len())?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_indices_follow_jcgm_101_7_7() {
        // M = 10⁴, p = 0.95: q = 9500, r = 250: [y_(250), y_(9750)] (1-based).
        assert_eq!(coverage_indices(10_000, 0.95), (249, 9749));
        // M = 10⁴ + 1: q = int(9500.95 + ½) = 9501, (M − q)/2 = 250: [y_(250), y_(9751)].
        assert_eq!(coverage_indices(10_001, 0.95), (249, 9750));
        // M = 10⁴ + 2: q = int(9501.9 + ½) = 9502, (M − q)/2 = 250.
        assert_eq!(coverage_indices(10_002, 0.95), (249, 9751));
        // M = 10⁴ + 3: q = int(9502.85 + ½) = 9503, (M − q)/2 = 250.
        assert_eq!(coverage_indices(10_003, 0.95), (249, 9752));
        // M = 10⁴ + 10: q = 9510 (pM = 9509.5 → int(9510)), (M − q)/2 = 250.
        assert_eq!(coverage_indices(10_010, 0.95), (249, 9759));
        // M = 10⁴ + 20: q = int(9519 + ½) = 9519, (M − q)/2 = 250.5 → r = 251.
        assert_eq!(coverage_indices(10_020, 0.95), (250, 9769));
    }

    #[test]
    fn coverage_interval_selects_order_statistics() {
        let mut v: Vec<f64> = (1..=10_000).rev().map(f64::from).collect();
        assert_eq!(coverage_interval(&mut v, 0.95), (250.0, 9750.0));
    }

    #[test]
    fn bracketed_order_statistics_equal_selection() {
        // Normal draws, heavy ties (rounded), signed zeros and a sorted, a reversed and a
        // constant run: the bracketing gives exactly the selected values.
        let mut rng = stream(7, 0, 0);
        let normal: Vec<f64> = (0..50_000).map(|_| rng.sample(StandardNormal)).collect();
        let ties: Vec<f64> = normal.iter().map(|v| (v * 4.0).round() / 4.0).collect();
        let zeros: Vec<f64> = (0..10_000)
            .map(|i| if i % 2 == 0 { 0.0 } else { -0.0 })
            .collect();
        let sorted: Vec<f64> = (0..20_000).map(f64::from).collect();
        let reversed: Vec<f64> = sorted.iter().rev().copied().collect();
        let constant = vec![1.5; 8192];
        for (case, values) in [normal, ties, zeros, sorted, reversed, constant]
            .into_iter()
            .enumerate()
        {
            for p in [0.5, 0.9, 0.95, 0.99, 0.9999] {
                let (lo, hi) = coverage_indices(values.len(), p);
                let mut a = values.clone();
                let mut b = values.clone();
                let got = order_statistics(&mut a, lo, hi);
                let want = select_two(&mut b, lo, hi);
                let bits = |(x, y): (f64, f64)| (x.to_bits(), y.to_bits());
                assert_eq!(bits(got), bits(want), "case {case}, p = {p}");
                // Given brackets: ones that hold the limits, and ones that miss (fallback).
                let (w0, w1) = want;
                for brackets in [
                    [w0 - 1.0, w0 + 0.5, w1 - 0.5, w1 + 1.0],
                    [w0 + 0.25, w0 + 0.5, w1 - 0.5, w1 - 0.25],
                    [-1e300, -1e299, 1e299, 1e300],
                ] {
                    let mut c = values.clone();
                    let got = within_brackets(&mut c, lo, hi, brackets);
                    assert_eq!(bits(got), bits(want), "case {case}, p = {p}, {brackets:?}");
                }
            }
        }
    }

    #[test]
    fn lane_sums_match_plain_sums() {
        let a: Vec<f64> = (0..1003).map(|i| f64::from(i) * 0.5).collect();
        let b: Vec<f64> = (0..1003).map(|i| f64::from(i % 7)).collect();
        let plain: f64 = a.iter().sum();
        assert!((lane_sum(&a) - plain).abs() <= 1e-12 * plain);
        let (ma, mb) = (3.0, 1.0);
        let plain: f64 = a.iter().zip(&b).map(|(x, y)| (x - ma) * (y - mb)).sum();
        assert!((centered_dot(&a, &b, ma, mb) - plain).abs() <= 1e-12 * plain.abs());
        assert_eq!(lane_sum(&[]), 0.0);
    }

    #[test]
    fn streams_differ_by_batch_and_chunk() {
        let a: u64 = stream(1, 0, 0).random();
        let b: u64 = stream(1, 1, 0).random();
        let c: u64 = stream(1, 0, 1).random();
        let d: u64 = stream(2, 0, 0).random();
        assert!(a != b && a != c && b != c && a != d);
    }
}
