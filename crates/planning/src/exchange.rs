//! The design criterion, the allocation of recording time to a design's points, the
//! coordinate exchange over candidate rates and the rounding to whole revolutions, once for
//! both searches: the single orientation's eq. 18 design (6×6, `design`) and the two
//! orientations' joint eq. 23 design (10×10, `joint`).
//!
//! The information matrix of a design with recording time `t_i` at candidate `i` is
//! `M = Σ t_i·e_i·x_i x_iᵀ`, with `x_i` the candidate's design row (each column divided by
//! its largest magnitude over the candidates) and `e_i` the weight per second of recording.
//! The search solves `M v = c` by Cholesky (`c` the unit vector of k2): the criterion only
//! ranks designs, and a plan's reported numbers come from a QR of the weighted design.
//!
//! What differs between the two searches is a [`Space`]: the rows and their dimension, the
//! ranges a point may move within (all candidates, or its own mounting's), the schedule
//! (a remount or none; repeated rates allowed or not), how a start is made to fit the budget,
//! and how far an improving exchange re-allocates.

use std::ops::Range;

use nalgebra::{Cholesky, Const, SMatrix, SVector};
use rand::{SeedableRng, rngs::StdRng};
use rayon::prelude::*;

pub(crate) use crate::grid::Grid;
use crate::inputs::{Criterion, Search};

/// Multiplicative iterations per trial exchange (warm-started from the current allocation).
const SEARCH_ITERATIONS: usize = 30;
/// Largest number of multiplicative iterations of a final allocation.
pub(crate) const FINAL_ITERATIONS: usize = 5000;
/// Relative change of the criterion under which the allocation is taken as converged.
const CONVERGED: f64 = 1e-13;
/// Largest number of exchange passes over the points.
const MAX_PASSES: usize = 40;

/// The time a design may take: `budget_s` holds `remount_s` once, `settling_s` per point and
/// the recording, at least `min_revolutions` per point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Budget {
    pub(crate) budget_s: f64,
    pub(crate) settling_s: f64,
    pub(crate) remount_s: f64,
    pub(crate) min_revolutions: u32,
    /// Whether two points may share a candidate.
    pub(crate) allow_repeats: bool,
}

impl Budget {
    /// Recording time left after remounting, settling and the points' least recording times
    /// `least_s` (negative: the design does not fit).
    pub(crate) fn free_s(&self, least_s: &[f64]) -> f64 {
        self.budget_s
            - self.remount_s
            - self.settling_s * least_s.len() as f64
            - least_s.iter().sum::<f64>()
    }

    /// The whole time of points recording `recording_s`: remount, settling and recording.
    pub(crate) fn used_s(&self, recording_s: &[f64]) -> f64 {
        recording_s.iter().sum::<f64>()
            + self.settling_s * recording_s.len() as f64
            + self.remount_s
    }
}

/// A search's space: its candidates ([`Grid`], `N` coefficients), the schedule, and where a
/// point may move.
pub(crate) trait Space<const N: usize>: Sync {
    /// Index of k2 among the coefficients.
    const K2: usize;
    /// Multiplicative iterations of the allocation a search starts from and of the
    /// re-allocation after an improving exchange (warm-started).
    const PASS_ITERATIONS: usize;
    /// The candidates.
    fn grid(&self) -> &Grid<N>;
    /// The schedule's limits.
    fn budget(&self) -> Budget;
    /// The candidates a point at candidate `i` may move to.
    fn range_of(&self, i: usize) -> Range<usize>;
    /// Makes a start fit the budget, if it can.
    fn repair(&self, design: &mut [usize]);

    /// The recording time of `revolutions[k]` revolutions at each point `design[k]`.
    fn recording_s(&self, design: &[usize], revolutions: &[u32]) -> Vec<f64> {
        let tau = &self.grid().tau_s;
        design
            .iter()
            .zip(revolutions)
            .map(|(&i, &n)| f64::from(n) * tau[i])
            .collect()
    }

    /// The least recording time of each point: the schedule's minimum revolutions.
    fn least_s(&self, design: &[usize]) -> Vec<f64> {
        self.recording_s(design, &vec![self.budget().min_revolutions; design.len()])
    }

    /// Recording time a design leaves beyond its minimum revolutions (negative: it does not
    /// fit).
    fn free_time(&self, design: &[usize]) -> f64 {
        self.budget().free_s(&self.least_s(design))
    }
}

/// A design: candidate indices, the least recording time of each point, its free time
/// beyond that, and the criterion's value.
#[derive(Debug, Clone)]
pub(crate) struct Allocated {
    pub(crate) design: Vec<usize>,
    pub(crate) min_s: Vec<f64>,
    pub(crate) free_s: Vec<f64>,
    pub(crate) value: f64,
}

impl Allocated {
    /// Recording time of each point: its least time plus its free time.
    pub(crate) fn times(&self) -> Vec<f64> {
        self.min_s
            .iter()
            .zip(&self.free_s)
            .map(|(a, b)| a + b)
            .collect()
    }
}

/// `M = Σ t_i e_i x_i x_iᵀ`.
fn information<const N: usize>(
    p: &impl Space<N>,
    design: &[usize],
    time_s: &[f64],
) -> SMatrix<f64, N, N> {
    let Grid { x, info_per_s, .. } = p.grid();
    let mut m = SMatrix::<f64, N, N>::zeros();
    for (&i, &t) in design.iter().zip(time_s) {
        m.syger(t * info_per_s[i], &x[i], &x[i], 1.0);
    }
    m
}

/// The unit vector `c` of coefficient `k`.
fn unit<const N: usize>(k: usize) -> SVector<f64, N> {
    let mut c = SVector::zeros();
    c[k] = 1.0;
    c
}

/// The criterion at `M` (smaller is better): `[M⁻¹]_{k2,k2}` or `−ln det M`; `None` when
/// `M` is singular.
fn criterion_value<const N: usize>(
    criterion: Criterion,
    k2: usize,
    m: &SMatrix<f64, N, N>,
) -> Option<(f64, Cholesky<f64, Const<N>>)> {
    let chol = m.cholesky()?;
    let value = match criterion {
        Criterion::K2 => chol.solve(&unit(k2))[k2],
        Criterion::D => {
            let l = chol.l_dirty();
            -2.0 * (0..N).map(|j| l[(j, j)].ln()).sum::<f64>()
        }
    };
    (value.is_finite() && (criterion == Criterion::D || value > 0.0)).then_some((value, chol))
}

/// The criterion of a design with recording times `time_s`.
pub(crate) fn evaluate<const N: usize, S: Space<N>>(
    p: &S,
    design: &[usize],
    time_s: &[f64],
    criterion: Criterion,
) -> Option<f64> {
    criterion_value(criterion, S::K2, &information(p, design, time_s)).map(|(v, _)| v)
}

/// var(k2) (in the scaled parametrisation) of a design with recording times.
pub(crate) fn var_k2_scaled<const N: usize>(
    p: &impl Space<N>,
    design: &[usize],
    time_s: &[f64],
) -> Option<f64> {
    evaluate(p, design, time_s, Criterion::K2)
}

/// Allocates the design's free time (beyond the least times `min_s`) by the multiplicative
/// algorithm, starting from `start` (equal shares when `None`), for at most `iterations`
/// steps.
///
/// Each step sets `s_i ← F·s_i·d_i / Σ_j s_j d_j`, with `F` the free time and
/// `d_i = √e_i·|x_iᵀM⁻¹c|` for var(k2) (c-optimality) or `d_i = e_i·x_iᵀM⁻¹x_i` for the
/// determinant. At a fixed point every point with free time has the same `d_i`, which is the
/// optimality condition of either criterion with the time constraint.
pub(crate) fn allocate<const N: usize, S: Space<N>>(
    p: &S,
    design: &[usize],
    min_s: &[f64],
    start: Option<&[f64]>,
    criterion: Criterion,
    iterations: usize,
) -> Option<Allocated> {
    let free = p.budget().free_s(min_s);
    if free < 0.0 {
        return None;
    }
    let n = design.len();
    let mut s: Vec<f64> = match start {
        Some(s) if s.iter().sum::<f64>() > 0.0 => {
            let total: f64 = s.iter().sum();
            s.iter()
                .map(|v| v.max(free * 1e-9 / n as f64) * free / total)
                .collect()
        }
        _ => vec![free / n as f64; n],
    };
    let times = |s: &[f64]| -> Vec<f64> { min_s.iter().zip(s).map(|(a, b)| a + b).collect() };
    let value_at =
        |s: &[f64]| criterion_value(criterion, S::K2, &information(p, design, &times(s)));
    let (mut value, mut chol) = value_at(&s)?;
    if free > 0.0 {
        let Grid { x, info_per_s, .. } = p.grid();
        let mut d = vec![0.0; n];
        for _ in 0..iterations {
            let v = chol.solve(&unit(S::K2));
            for (k, &i) in design.iter().enumerate() {
                d[k] = match criterion {
                    Criterion::K2 => info_per_s[i].sqrt() * x[i].dot(&v).abs(),
                    Criterion::D => info_per_s[i] * x[i].dot(&chol.solve(&x[i])),
                };
            }
            let total: f64 = s.iter().zip(&d).map(|(s, d)| s * d).sum();
            if !(total > 0.0 && total.is_finite()) {
                break;
            }
            let next: Vec<f64> = s
                .iter()
                .zip(&d)
                .map(|(s, d)| free * s * d / total)
                .collect();
            let Some((v_next, c_next)) = value_at(&next) else {
                break;
            };
            if v_next > value {
                break;
            }
            let change = (value - v_next).abs() / value.abs().max(f64::MIN_POSITIVE);
            s = next;
            value = v_next;
            chol = c_next;
            if change < CONVERGED {
                break;
            }
        }
    }
    Some(Allocated {
        design: design.to_vec(),
        min_s: min_s.to_vec(),
        free_s: s,
        value,
    })
}

/// The converged allocation of a design at the schedule's minimum revolutions.
pub(crate) fn allocate_final<const N: usize>(
    p: &impl Space<N>,
    design: &[usize],
    criterion: Criterion,
) -> Option<Allocated> {
    allocate(
        p,
        design,
        &p.least_s(design),
        None,
        criterion,
        FINAL_ITERATIONS,
    )
}

/// An evenly spread start: `parts[k].1` candidates spread over the range `parts[k].0`
/// (distinct unless the budget allows repeats).
fn spread_start(parts: &[(Range<usize>, usize)], allow_repeats: bool) -> Vec<usize> {
    let mut d = Vec::new();
    for (r, m) in parts.iter().cloned() {
        let n = r.len();
        let mut part: Vec<usize> = (0..m)
            .map(|j| {
                r.start + ((j as f64) * (n - 1) as f64 / (m - 1).max(1) as f64).round() as usize
            })
            .collect();
        if !allow_repeats {
            part.dedup();
            // Rounding can merge neighbours only when n is close to m; fill from the top.
            let mut next = r.end;
            while part.len() < m && next > r.start {
                next -= 1;
                if !part.contains(&next) {
                    part.push(next);
                }
            }
            part.sort_unstable();
        }
        d.extend(part);
    }
    d
}

/// A random start: `parts[k].1` distinct candidates of the range `parts[k].0` (the range's
/// last one repeated when it holds fewer).
fn random_start(parts: &[(Range<usize>, usize)], rng: &mut StdRng) -> Vec<usize> {
    let mut d = Vec::new();
    for (r, m) in parts.iter().cloned() {
        let mut part: Vec<usize> = rand::seq::index::sample(rng, r.len(), m.min(r.len()))
            .into_iter()
            .map(|i| r.start + i)
            .collect();
        while part.len() < m {
            part.push(r.end - 1);
        }
        part.sort_unstable();
        d.extend(part);
    }
    d
}

/// Coordinate exchange from one start: each point in turn is replaced by the candidate of
/// its range that lowers the criterion most, until a pass changes nothing.
pub(crate) fn exchange<const N: usize, S: Space<N>>(
    p: &S,
    mut design: Vec<usize>,
    criterion: Criterion,
) -> Option<Allocated> {
    p.repair(&mut design);
    let repeats = p.budget().allow_repeats;
    let mut current = allocate(
        p,
        &design,
        &p.least_s(&design),
        None,
        criterion,
        S::PASS_ITERATIONS,
    )?;
    for _ in 0..MAX_PASSES {
        let mut improved = false;
        for slot in 0..current.design.len() {
            let mut best: Option<Allocated> = None;
            let mut trial = current.design.clone();
            for k in p.range_of(current.design[slot]) {
                if k == current.design[slot] || (!repeats && current.design.contains(&k)) {
                    continue;
                }
                trial[slot] = k;
                let min_s = p.least_s(&trial);
                if p.budget().free_s(&min_s) < 0.0 {
                    continue;
                }
                let Some(a) = allocate(
                    p,
                    &trial,
                    &min_s,
                    Some(&current.free_s),
                    criterion,
                    SEARCH_ITERATIONS,
                ) else {
                    continue;
                };
                let bar = best.as_ref().map_or(current.value, |b| b.value);
                if a.value < bar - 1e-12 * bar.abs() {
                    best = Some(a);
                }
            }
            if let Some(b) = best {
                current = allocate(
                    p,
                    &b.design,
                    &b.min_s,
                    Some(&b.free_s),
                    criterion,
                    S::PASS_ITERATIONS,
                )
                .unwrap_or(b);
                improved = true;
            }
        }
        if !improved {
            break;
        }
    }
    current.design.sort_unstable();
    allocate_final(p, &current.design, criterion).or(Some(current))
}

/// The label of the random starts' streams (`units::stream_seed`).
const RESTART_STREAM: u64 = 0x5EA4_C457;

/// The random stream of restart `r` under the search's `seed`: the seed and the restart
/// through `units::stream_seed`, so that no two (seed, restart) pairs share a stream (with
/// `seed + r`, seed 1's restart 1 drew seed 2's restart 0).
fn restart_rng(seed: u64, r: usize) -> StdRng {
    StdRng::seed_from_u64(units::stream_seed(seed, RESTART_STREAM, r as u64))
}

/// The best design with `parts[k].1` points in the range `parts[k].0`, over the evenly spread
/// start and `search.restarts` random starts (restart `r` drawn from its own stream,
/// [`restart_rng`], in parallel; the result does not depend on the number of threads).
pub(crate) fn search<const N: usize>(
    p: &impl Space<N>,
    parts: &[(Range<usize>, usize)],
    search: Search,
) -> Option<Allocated> {
    let starts: Vec<Vec<usize>> = std::iter::once(spread_start(parts, p.budget().allow_repeats))
        .chain((0..search.restarts).map(|r| {
            let mut rng = restart_rng(search.seed, r);
            random_start(parts, &mut rng)
        }))
        .collect();
    starts
        .into_par_iter()
        .filter_map(|s| exchange(p, s, search.criterion))
        .collect::<Vec<_>>()
        .into_iter()
        .min_by(|a, b| a.value.total_cmp(&b.value))
}

/// Whole revolutions from a continuous allocation: each point's time rounded down to whole
/// revolutions (at least `min_revs`), then one revolution at a time added where it lowers
/// var(k2) most per second, while the budget allows.
pub(crate) fn whole_revolutions<const N: usize>(
    p: &impl Space<N>,
    a: &Allocated,
    min_revs: &[u32],
) -> Vec<u32> {
    let (tau, budget) = (&p.grid().tau_s, p.budget());
    let mut revs: Vec<u32> = a
        .design
        .iter()
        .zip(a.times())
        .zip(min_revs)
        .map(|((&i, t), &m)| ((t / tau[i]).floor() as u32).max(m))
        .collect();
    let used = |revs: &[u32]| budget.used_s(&p.recording_s(&a.design, revs));
    // Rounding down can only free time; guard against a floor that overshoots anyway.
    while used(&revs) > budget.budget_s {
        let Some(k) = (0..revs.len())
            .filter(|&k| revs[k] > min_revs[k])
            .max_by(|&x, &y| tau[a.design[x]].total_cmp(&tau[a.design[y]]))
        else {
            break;
        };
        revs[k] -= 1;
    }
    loop {
        let remaining = budget.budget_s - used(&revs);
        let Some(now) = var_k2_scaled(p, &a.design, &p.recording_s(&a.design, &revs)) else {
            break;
        };
        let mut best: Option<(usize, f64)> = None;
        for k in 0..revs.len() {
            let one_s = tau[a.design[k]];
            if one_s > remaining {
                continue;
            }
            revs[k] += 1;
            if let Some(v) = var_k2_scaled(p, &a.design, &p.recording_s(&a.design, &revs)) {
                let gain = (now - v) / one_s;
                if best.is_none_or(|(_, g)| gain > g) {
                    best = Some((k, gain));
                }
            }
            revs[k] -= 1;
        }
        match best {
            Some((k, _)) => revs[k] += 1,
            None => break,
        }
    }
    revs
}

#[cfg(test)]
mod tests {
    use rand::Rng as _;

    use super::*;

    /// No restart of one seed draws the stream of a restart of a neighbouring seed: seed 1's
    /// restart 1 is not seed 2's restart 0.
    #[test]
    fn restart_streams_do_not_depend_on_the_seed_plus_the_restart() {
        let first = |seed: u64, r: usize| -> u64 { restart_rng(seed, r).random() };
        assert_ne!(first(1, 1), first(2, 0));
        let seed1: Vec<u64> = (1..200).map(|r| first(1, r)).collect();
        let seed2: Vec<u64> = (0..199).map(|r| first(2, r)).collect();
        assert!(seed1.iter().all(|x| !seed2.contains(x)));
        // and the same (seed, restart) gives the same stream
        assert_eq!(first(7, 3), first(7, 3));
    }
}
