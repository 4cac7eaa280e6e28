//! The running statistics of each output over the batches: mean and sum of squares (Chan et
//! al.'s update), each batch's results, their spread (JCGM 101 §7.9.4) and the numerical
//! tolerance the adaptive procedure waits on.

use crate::error::Statistic;
use crate::input::Inputs;
use crate::kind::{Distribution, Dof};
use crate::tolerance::numerical_tolerance;

use super::order::{coverage_indices, select_two, within_brackets};
use super::result::Stability;

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
pub(super) fn centered_dot(a: &[f64], b: &[f64], ma: f64, mb: f64) -> f64 {
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
pub(super) const COVARIANCE_BLOCK: usize = 4096;

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
pub(super) struct Accumulator {
    pub(super) values: Vec<f64>,
    pub(super) mean: f64,
    m2: f64,
    batch: [Vec<f64>; 4],
    scratch: Vec<f64>,
}

impl Accumulator {
    /// Adds the batch's column `k` of `rows` (skipping failed trials) and records the batch's
    /// estimate, standard uncertainty and coverage limits.
    pub(super) fn add_batch(&mut self, rows: &[f64], m: usize, k: usize, p: f64) {
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

    pub(super) fn standard_uncertainty(&self) -> f64 {
        (self.m2 / (self.values.len() - 1) as f64).sqrt()
    }

    /// Twice the standard deviation of the average of the batch results (§7.9.4 f).
    pub(super) fn stability(&self) -> Option<Stability> {
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
pub(super) fn unstable(s: &Stability, tolerance: f64, heavy_tailed: bool) -> Option<Statistic> {
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
pub(super) fn has_heavy_tails(inputs: &Inputs) -> bool {
    inputs.quantities().iter().any(|q| {
        q.distribution == Distribution::StudentT && matches!(q.dof, Dof::Finite(nu) if nu <= 2.0)
    })
}

/// The numerical tolerance of an output: δ of its standard uncertainty (§7.9.2), or with
/// heavy tails (no variance) δ of the coverage interval's half-width (the same number of
/// significant digits of the expanded uncertainty instead).
pub(super) fn output_tolerance(acc: &Accumulator, heavy_tailed: bool, n_dig: u32) -> f64 {
    if heavy_tailed && !acc.batch[2].is_empty() {
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let (low, high) = (mean(&acc.batch[2]), mean(&acc.batch[3]));
        return numerical_tolerance(0.5 * (high - low), n_dig);
    }
    numerical_tolerance(acc.standard_uncertainty(), n_dig)
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
