//! The joint design of the two-orientation calibration (eq. 23, ten coefficients): candidate
//! (orientation, rate) pairs with the calibration crate's design row
//! ([`calibration::symmetric_row`]), the allocation of recording time over both orientations
//! by the multiplicative algorithm, coordinate exchange within each orientation, whole
//! revolutions, and the lack-of-fit reserve.
//!
//! The single-orientation search (`design`) is the same algorithm on the 6×6 design of
//! eq. 18; it is left as it is so that its plans stay bit for bit what `docs/PLANNING.md`
//! shows. Here the information matrix is `M = Σ t_i·e_i·x_i x_iᵀ` over ten columns (each
//! divided by its largest magnitude over the candidates), ranked by a Cholesky solve of
//! `M v = c` with `c` the unit vector of k2.

use std::ops::Range;

use calibration::{K2_TERM, Orientation, SYMMETRIC_TERMS, symmetric_row};
use nalgebra::{Const, SMatrix, SVector};
use rand::{SeedableRng, rngs::StdRng};
use rayon::prelude::*;

use crate::inputs::NoiseSpec;

type Mat = SMatrix<f64, SYMMETRIC_TERMS, SYMMETRIC_TERMS>;
type Col = SVector<f64, SYMMETRIC_TERMS>;
type Chol = nalgebra::Cholesky<f64, Const<SYMMETRIC_TERMS>>;

/// Multiplicative iterations per trial exchange (warm-started).
const SEARCH_ITERATIONS: usize = 30;
/// Largest number of multiplicative iterations of a final allocation.
pub(crate) const FINAL_ITERATIONS: usize = 5000;
/// Relative change of the criterion under which an allocation is converged.
const CONVERGED: f64 = 1e-13;
/// Multiplicative iterations after an exchange that improves (warm-started; the final
/// allocation converges with [`FINAL_ITERATIONS`]).
const PASS_ITERATIONS: usize = 300;
/// Largest number of exchange passes.
const MAX_PASSES: usize = 40;

/// The candidates of both orientations and the schedule's limits.
#[derive(Debug, Clone)]
pub(crate) struct JointProblem {
    /// Rate of each candidate, rad/s (ascending within an orientation).
    pub(crate) rates_rad_s: Vec<f64>,
    /// The same in deg/s, as given.
    pub(crate) rates_deg_s: Vec<f64>,
    /// Design rows, each column divided by `scale`.
    pub(crate) x: Vec<Col>,
    /// Seconds per revolution.
    pub(crate) tau_s: Vec<f64>,
    /// Weight per second of recording, 1/(rad/s)².
    pub(crate) info_per_s: Vec<f64>,
    /// Candidate indices of IA in and IA out.
    pub(crate) ranges: [Range<usize>; 2],
    pub(crate) budget_s: f64,
    pub(crate) settling_s: f64,
    pub(crate) remount_s: f64,
    pub(crate) min_revolutions: u32,
    pub(crate) restarts: usize,
    pub(crate) seed: u64,
}

/// The limits a joint problem is built with.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limits {
    pub(crate) g_m_s2: f64,
    pub(crate) radius_m: [f64; 2],
    pub(crate) noise: NoiseSpec,
    pub(crate) budget_s: f64,
    pub(crate) settling_s: f64,
    pub(crate) remount_s: f64,
    pub(crate) min_revolutions: u32,
    pub(crate) restarts: usize,
    pub(crate) seed: u64,
}

/// Weight per second of recording at a rate with `tau_s` per revolution (as `Problem`).
pub(crate) fn info_per_s(noise: NoiseSpec, tau_s: f64) -> f64 {
    match noise {
        NoiseSpec::PerRevolution { sigma_rad_s } => 1.0 / (tau_s * sigma_rad_s * sigma_rad_s),
        NoiseSpec::Density { sigma_1s_rad_s } => 1.0 / (sigma_1s_rad_s * sigma_1s_rad_s),
    }
}

impl JointProblem {
    /// The problem of the candidate rates `rates_deg_s[k]` of orientation `k` (IA in, IA out;
    /// ascending, distinct).
    pub(crate) fn new(limits: &Limits, rates_deg_s: [&[f64]; 2]) -> Self {
        let mut rates_rad_s = Vec::new();
        let mut rates_deg = Vec::new();
        let mut raw = Vec::new();
        let mut ranges = [0..0, 0..0];
        for (k, o) in [Orientation::IaIn, Orientation::IaOut]
            .into_iter()
            .enumerate()
        {
            let start = rates_rad_s.len();
            for &r in rates_deg_s[k] {
                let w = units::deg_s_to_rad_s(r);
                rates_rad_s.push(w);
                rates_deg.push(r);
                raw.push(symmetric_row(o, limits.radius_m[k], limits.g_m_s2, w));
            }
            ranges[k] = start..rates_rad_s.len();
        }
        let mut scale = [0.0_f64; SYMMETRIC_TERMS];
        for r in &raw {
            for (s, v) in scale.iter_mut().zip(r) {
                *s = s.max(v.abs());
            }
        }
        for s in &mut scale {
            if *s == 0.0 {
                *s = 1.0;
            }
        }
        let x = raw
            .iter()
            .map(|r| Col::from_fn(|j, _| r[j] / scale[j]))
            .collect();
        let tau_s: Vec<f64> = rates_rad_s
            .iter()
            .map(|w| std::f64::consts::TAU / w)
            .collect();
        let info = tau_s.iter().map(|&t| info_per_s(limits.noise, t)).collect();
        Self {
            rates_rad_s,
            rates_deg_s: rates_deg,
            x,
            tau_s,
            info_per_s: info,
            ranges,
            budget_s: limits.budget_s,
            settling_s: limits.settling_s,
            remount_s: limits.remount_s,
            min_revolutions: limits.min_revolutions,
            restarts: limits.restarts,
            seed: limits.seed,
        }
    }

    /// Which orientation (0 IA in, 1 IA out) candidate `i` belongs to.
    pub(crate) fn side(&self, i: usize) -> usize {
        usize::from(!self.ranges[0].contains(&i))
    }

    /// The least recording time of each point: its least revolutions.
    pub(crate) fn min_times(&self, design: &[usize], min_revs: &[u32]) -> Vec<f64> {
        design
            .iter()
            .zip(min_revs)
            .map(|(&i, &n)| f64::from(n) * self.tau_s[i])
            .collect()
    }

    /// Recording time left after remounting, settling and the least times (negative: does
    /// not fit).
    pub(crate) fn free_time(&self, design: &[usize], min_s: &[f64]) -> f64 {
        self.budget_s
            - self.remount_s
            - self.settling_s * design.len() as f64
            - min_s.iter().sum::<f64>()
    }
}

/// A design with its least times, free times and var(k2) (scaled).
#[derive(Debug, Clone)]
pub(crate) struct Allocated {
    pub(crate) design: Vec<usize>,
    pub(crate) min_s: Vec<f64>,
    pub(crate) free_s: Vec<f64>,
    pub(crate) value: f64,
}

impl Allocated {
    pub(crate) fn times(&self) -> Vec<f64> {
        self.min_s
            .iter()
            .zip(&self.free_s)
            .map(|(a, b)| a + b)
            .collect()
    }
}

fn information(p: &JointProblem, design: &[usize], time_s: &[f64]) -> Mat {
    let mut m = Mat::zeros();
    for (&i, &t) in design.iter().zip(time_s) {
        let x = &p.x[i];
        m.syger(t * p.info_per_s[i], x, x, 1.0);
    }
    m
}

fn k2_value(m: &Mat) -> Option<(f64, Chol)> {
    let chol = m.cholesky()?;
    let v = chol.solve(&Col::ith(K2_TERM, 1.0));
    let value = v[K2_TERM];
    (value.is_finite() && value > 0.0).then_some((value, chol))
}

/// var(k2) in the scaled parametrisation of a design with recording times.
pub(crate) fn var_k2_scaled(p: &JointProblem, design: &[usize], time_s: &[f64]) -> Option<f64> {
    k2_value(&information(p, design, time_s)).map(|(v, _)| v)
}

/// Allocates the free time of a design by the multiplicative algorithm for var(k2)
/// (c-optimality): `s_i ← F·s_i·d_i/Σ s_j d_j`, `d_i = √e_i·|x_iᵀM⁻¹c|`.
pub(crate) fn allocate(
    p: &JointProblem,
    design: &[usize],
    min_s: &[f64],
    start: Option<&[f64]>,
    iterations: usize,
) -> Option<Allocated> {
    let free = p.free_time(design, min_s);
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
    let (mut value, mut chol) = k2_value(&information(p, design, &times(&s)))?;
    let mut d = vec![0.0; n];
    if free > 0.0 {
        for _ in 0..iterations {
            let v = chol.solve(&Col::ith(K2_TERM, 1.0));
            for (k, &i) in design.iter().enumerate() {
                d[k] = p.info_per_s[i].sqrt() * p.x[i].dot(&v).abs();
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
            let Some((v_next, c_next)) = k2_value(&information(p, design, &times(&next))) else {
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

/// `per_side[k]` candidates of orientation `k` spread evenly over its range.
fn spread_start(p: &JointProblem, per_side: [usize; 2]) -> Vec<usize> {
    let mut d = Vec::new();
    for (range, &m) in p.ranges.iter().zip(&per_side) {
        let r = range.clone();
        let n = r.len();
        let mut side: Vec<usize> = (0..m)
            .map(|j| {
                r.start + ((j as f64) * (n - 1) as f64 / (m - 1).max(1) as f64).round() as usize
            })
            .collect();
        side.dedup();
        let mut next = r.end;
        while side.len() < m && next > r.start {
            next -= 1;
            if !side.contains(&next) {
                side.push(next);
            }
        }
        side.sort_unstable();
        d.extend(side);
    }
    d
}

fn random_start(p: &JointProblem, per_side: [usize; 2], rng: &mut StdRng) -> Vec<usize> {
    let mut d = Vec::new();
    for (range, &m) in p.ranges.iter().zip(&per_side) {
        let r = range.clone();
        let mut side: Vec<usize> = rand::seq::index::sample(rng, r.len(), m)
            .into_iter()
            .map(|i| r.start + i)
            .collect();
        side.sort_unstable();
        d.extend(side);
    }
    d
}

/// Moves the slowest point to the fastest unused candidate of its orientation until the
/// design fits the budget.
fn repair(p: &JointProblem, design: &mut [usize], min_revs: u32) {
    loop {
        let min_s = p.min_times(design, &vec![min_revs; design.len()]);
        if p.free_time(design, &min_s) >= 0.0 {
            return;
        }
        let Some(slot) =
            (0..design.len()).max_by(|&a, &b| p.tau_s[design[a]].total_cmp(&p.tau_s[design[b]]))
        else {
            return;
        };
        let side = p.side(design[slot]);
        let fastest = p.ranges[side].clone().rev().find(|k| !design.contains(k));
        match fastest {
            Some(k) if p.tau_s[k] < p.tau_s[design[slot]] => design[slot] = k,
            _ => return,
        }
    }
}

/// Coordinate exchange from one start, each slot within its orientation.
fn exchange(p: &JointProblem, mut design: Vec<usize>) -> Option<Allocated> {
    repair(p, &mut design, p.min_revolutions);
    let min_of = |d: &[usize]| p.min_times(d, &vec![p.min_revolutions; d.len()]);
    let mut current = allocate(p, &design, &min_of(&design), None, PASS_ITERATIONS)?;
    for _ in 0..MAX_PASSES {
        let mut improved = false;
        for slot in 0..current.design.len() {
            let side = p.side(current.design[slot]);
            let mut best: Option<Allocated> = None;
            let mut trial = current.design.clone();
            for k in p.ranges[side].clone() {
                if current.design.contains(&k) {
                    continue;
                }
                trial[slot] = k;
                let min_s = min_of(&trial);
                if p.free_time(&trial, &min_s) < 0.0 {
                    continue;
                }
                let Some(a) = allocate(p, &trial, &min_s, Some(&current.free_s), SEARCH_ITERATIONS)
                else {
                    continue;
                };
                let bar = best.as_ref().map_or(current.value, |b| b.value);
                if a.value < bar - 1e-12 * bar.abs() {
                    best = Some(a);
                }
            }
            if let Some(b) = best {
                current =
                    allocate(p, &b.design, &b.min_s, Some(&b.free_s), PASS_ITERATIONS).unwrap_or(b);
                improved = true;
            }
        }
        if !improved {
            break;
        }
    }
    current.design.sort_unstable();
    let min_s = min_of(&current.design);
    allocate(p, &current.design, &min_s, None, FINAL_ITERATIONS).or(Some(current))
}

/// The best design with `per_side[k]` distinct rates in orientation `k`, over the evenly
/// spread start and the random starts (in parallel; independent of the number of threads).
pub(crate) fn search(p: &JointProblem, per_side: [usize; 2]) -> Option<Allocated> {
    let starts: Vec<Vec<usize>> = std::iter::once(spread_start(p, per_side))
        .chain((0..p.restarts).map(|r| {
            let mut rng = StdRng::seed_from_u64(p.seed.wrapping_add(r as u64));
            random_start(p, per_side, &mut rng)
        }))
        .collect();
    starts
        .into_par_iter()
        .filter_map(|s| exchange(p, s))
        .collect::<Vec<_>>()
        .into_iter()
        .min_by(|a, b| a.value.total_cmp(&b.value))
}

/// The exchange from one start: the design of another grid's rates moved to this grid's
/// nearest candidates (what rounding costs is measured from there).
pub(crate) fn search_near(p: &JointProblem, rates_deg_s: [&[f64]; 2]) -> Option<Allocated> {
    let mut d = Vec::new();
    for (range, rates) in p.ranges.iter().zip(rates_deg_s) {
        for &r in rates {
            let nearest = range.clone().filter(|k| !d.contains(k)).min_by(|&a, &b| {
                (p.rates_deg_s[a] - r)
                    .abs()
                    .total_cmp(&(p.rates_deg_s[b] - r).abs())
            });
            if let Some(k) = nearest {
                d.push(k);
            }
        }
    }
    d.sort_unstable();
    exchange(p, d)
}

/// The lack-of-fit reserve: `extra` candidates per orientation, each the one farthest from
/// the orientation's rates already chosen (the widest gap first), appended to the design.
pub(crate) fn add_reserve(p: &JointProblem, design: &[usize], extra: usize) -> Vec<usize> {
    let mut d = design.to_vec();
    for side in 0..2 {
        for _ in 0..extra {
            let distance = |k: usize| {
                d.iter()
                    .filter(|&&j| p.side(j) == side)
                    .map(|&j| (p.rates_rad_s[j] - p.rates_rad_s[k]).abs())
                    .fold(f64::INFINITY, f64::min)
            };
            let pick = p.ranges[side]
                .clone()
                .filter(|k| !d.contains(k))
                .max_by(|&a, &b| distance(a).total_cmp(&distance(b)).then(b.cmp(&a)));
            if let Some(k) = pick {
                d.push(k);
            }
        }
    }
    d.sort_unstable();
    d
}

/// The least revolutions of each point when `fraction` of the recording time is spread in
/// equal parts over every point (at least the schedule's minimum).
pub(crate) fn reserve_revolutions(p: &JointProblem, design: &[usize], fraction: f64) -> Vec<u32> {
    let floor_min = p.min_times(design, &vec![p.min_revolutions; design.len()]);
    let recording = p.free_time(design, &floor_min) + floor_min.iter().sum::<f64>();
    let each_s = fraction * recording.max(0.0) / design.len() as f64;
    design
        .iter()
        .map(|&i| ((each_s / p.tau_s[i]).floor() as u32).max(p.min_revolutions))
        .collect()
}

/// Whole revolutions from a continuous allocation: each time rounded down to whole
/// revolutions (at least `min_revs`), then one revolution at a time added where it lowers
/// var(k2) most per second, while the budget allows.
pub(crate) fn whole_revolutions(p: &JointProblem, a: &Allocated, min_revs: &[u32]) -> Vec<u32> {
    let t = a.times();
    let mut revs: Vec<u32> = a
        .design
        .iter()
        .zip(&t)
        .zip(min_revs)
        .map(|((&i, &t), &m)| ((t / p.tau_s[i]).floor() as u32).max(m))
        .collect();
    let time_of = |revs: &[u32]| -> Vec<f64> { p.min_times(&a.design, revs) };
    let used = |revs: &[u32]| -> f64 {
        time_of(revs).iter().sum::<f64>() + p.settling_s * revs.len() as f64 + p.remount_s
    };
    while used(&revs) > p.budget_s {
        let Some(k) = (0..revs.len())
            .filter(|&k| revs[k] > min_revs[k])
            .max_by(|&x, &y| p.tau_s[a.design[x]].total_cmp(&p.tau_s[a.design[y]]))
        else {
            break;
        };
        revs[k] -= 1;
    }
    loop {
        let remaining = p.budget_s - used(&revs);
        let Some(now) = var_k2_scaled(p, &a.design, &time_of(&revs)) else {
            break;
        };
        let mut best: Option<(usize, f64)> = None;
        for k in 0..revs.len() {
            let tau = p.tau_s[a.design[k]];
            if tau > remaining {
                continue;
            }
            revs[k] += 1;
            if let Some(v) = var_k2_scaled(p, &a.design, &time_of(&revs)) {
                let gain = (now - v) / tau;
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
    use super::*;

    fn problem(budget_s: f64) -> JointProblem {
        let rates: Vec<f64> = (2..=40).map(|k| 5.0 * f64::from(k)).collect();
        JointProblem::new(
            &Limits {
                g_m_s2: 9.8,
                radius_m: [2.5, 2.54],
                noise: NoiseSpec::PerRevolution { sigma_rad_s: 2e-8 },
                budget_s,
                settling_s: 60.0,
                remount_s: 600.0,
                min_revolutions: 2,
                restarts: 3,
                seed: 1,
            },
            [&rates, &rates],
        )
    }

    /// Closed form on a square design: with ten points (one per coefficient) and rows
    /// `z_i = √e_i·x_i`, `q = Z⁻ᵀc`, the c-optimal var is `(Σ|q_i|)²/T`.
    #[test]
    fn allocation_reaches_the_closed_form_on_ten_points() {
        let p = problem(1e9);
        let design: Vec<usize> = [0, 8, 18, 28, 38]
            .into_iter()
            .chain([39, 47, 57, 67, 77])
            .collect();
        let min_s = vec![0.0; 10];
        let a = allocate(&p, &design, &min_s, None, FINAL_ITERATIONS).unwrap();
        let z = Mat::from_fn(|i, j| p.info_per_s[design[i]].sqrt() * p.x[design[i]][j]);
        let q = z.transpose().lu().solve(&Col::ith(K2_TERM, 1.0)).unwrap();
        let l1: f64 = q.iter().map(|v| v.abs()).sum();
        let closed = l1 * l1 / p.free_time(&design, &min_s);
        assert!(
            (a.value - closed).abs() / closed < 1e-6,
            "{} vs {closed}",
            a.value
        );
    }

    #[test]
    fn whole_revolutions_fit_the_budget_and_the_reserve_spreads() {
        let p = problem(7200.0);
        let best = search(&p, [6, 6]).unwrap();
        assert_eq!(best.design.iter().filter(|&&i| p.side(i) == 0).count(), 6);
        let d = add_reserve(&p, &best.design, 2);
        assert_eq!(d.len(), 16);
        let revs = reserve_revolutions(&p, &d, 0.1);
        let min_s = p.min_times(&d, &revs);
        let a = allocate(&p, &d, &min_s, None, FINAL_ITERATIONS).unwrap();
        let whole = whole_revolutions(&p, &a, &revs);
        let used: f64 = p.min_times(&d, &whole).iter().sum::<f64>() + 60.0 * 16.0 + 600.0;
        assert!(used <= 7200.0);
        assert!(whole.iter().zip(&revs).all(|(w, r)| w >= r));
        // The reserve costs something, not much.
        let t: Vec<f64> = p.min_times(&d, &whole);
        let with = var_k2_scaled(&p, &d, &t).unwrap();
        assert!(with > best.value);
    }
}
