//! The joint design of the two-orientation calibration (eq. 23, ten coefficients): candidate
//! (orientation, rate) pairs with the calibration crate's design row
//! ([`calibration::two_orientation_row`]), searched by the exchange algorithm of
//! [`crate::exchange`] (shared with the single orientation's eq. 18 design): the recording
//! time is allocated over both orientations at once, each point moves within its own
//! orientation, the budget holds one remount. Here too: the start from another grid's rates,
//! and the lack-of-fit reserve.

use std::ops::Range;

use crate::exchange::{self, Allocated, Budget, Grid, Space};
use crate::inputs::{Criterion, NoiseSpec, Search};
use calibration::{K2_TERM, Orientation, TWO_ORIENTATION_TERMS, two_orientation_row};

/// Multiplicative iterations of the allocation a search starts from and after an exchange
/// that improves (warm-started; the final allocation converges with
/// [`exchange::FINAL_ITERATIONS`]).
const PASS_ITERATIONS: usize = 300;

/// The candidates of both orientations and the schedule's limits.
#[derive(Debug, Clone)]
pub(crate) struct TwoOrientationProblem {
    /// Rate of each candidate, rad/s (ascending within an orientation).
    pub(crate) rates_rad_s: Vec<f64>,
    /// The same in deg/s, as given.
    pub(crate) rates_deg_s: Vec<f64>,
    /// Their design rows, seconds per revolution and weight per second.
    pub(crate) grid: Grid<TWO_ORIENTATION_TERMS>,
    /// Candidate indices of IA in and IA out.
    pub(crate) ranges: [Range<usize>; 2],
    /// The budget, with the remount; no repeated rates.
    pub(crate) budget: Budget,
    /// Random starts besides the evenly spread one, and their first seed.
    pub(crate) restarts: usize,
    pub(crate) seed: u64,
}

/// The limits a joint problem is built with.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limits {
    pub(crate) g_m_s2: f64,
    pub(crate) radius_m: [f64; 2],
    pub(crate) noise: NoiseSpec,
    pub(crate) budget: Budget,
    pub(crate) restarts: usize,
    pub(crate) seed: u64,
}

impl TwoOrientationProblem {
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
                raw.push(two_orientation_row(o, limits.radius_m[k], limits.g_m_s2, w));
            }
            ranges[k] = start..rates_rad_s.len();
        }
        let grid = Grid::new(&rates_rad_s, &raw, |tau| limits.noise.info_per_s(tau));
        Self {
            rates_rad_s,
            rates_deg_s: rates_deg,
            grid,
            ranges,
            budget: limits.budget,
            restarts: limits.restarts,
            seed: limits.seed,
        }
    }

    /// Which orientation (0 IA in, 1 IA out) candidate `i` belongs to.
    pub(crate) fn side(&self, i: usize) -> usize {
        usize::from(!self.ranges[0].contains(&i))
    }
}

impl Space<TWO_ORIENTATION_TERMS> for TwoOrientationProblem {
    const K2: usize = K2_TERM;
    const PASS_ITERATIONS: usize = PASS_ITERATIONS;

    fn grid(&self) -> &Grid<TWO_ORIENTATION_TERMS> {
        &self.grid
    }

    fn budget(&self) -> Budget {
        self.budget
    }

    fn range_of(&self, i: usize) -> Range<usize> {
        self.ranges[self.side(i)].clone()
    }

    /// The slowest point (the last of them) moves to the fastest unused candidate of its
    /// orientation until the design fits the budget.
    fn repair(&self, design: &mut [usize]) {
        while self.free_time(design) < 0.0 {
            let tau = &self.grid.tau_s;
            let Some(slot) =
                (0..design.len()).max_by(|&a, &b| tau[design[a]].total_cmp(&tau[design[b]]))
            else {
                return;
            };
            let fastest = self
                .range_of(design[slot])
                .rev()
                .find(|k| !design.contains(k));
            match fastest {
                Some(k) if tau[k] < tau[design[slot]] => design[slot] = k,
                _ => return,
            }
        }
    }
}

/// The best design with `per_side[k]` distinct rates in orientation `k`
/// ([`exchange::search`] for var(k2)).
pub(crate) fn search(p: &TwoOrientationProblem, per_side: [usize; 2]) -> Option<Allocated> {
    let parts = [
        (p.ranges[0].clone(), per_side[0]),
        (p.ranges[1].clone(), per_side[1]),
    ];
    let search = Search {
        criterion: Criterion::K2,
        restarts: p.restarts,
        seed: p.seed,
    };
    exchange::search(p, &parts, search)
}

/// The exchange from one start: the design of another grid's rates moved to this grid's
/// nearest candidates (what rounding costs is measured from there).
pub(crate) fn search_near(
    p: &TwoOrientationProblem,
    rates_deg_s: [&[f64]; 2],
) -> Option<Allocated> {
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
    exchange::exchange(p, d, Criterion::K2)
}

/// The lack-of-fit reserve: `extra` candidates per orientation, each the one farthest from
/// the orientation's rates already chosen (the widest gap first), appended to the design.
pub(crate) fn add_reserve(p: &TwoOrientationProblem, design: &[usize], extra: usize) -> Vec<usize> {
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
pub(crate) fn reserve_revolutions(
    p: &TwoOrientationProblem,
    design: &[usize],
    fraction: f64,
) -> Vec<u32> {
    let least_s = p.least_s(design);
    let recording = p.budget.free_s(&least_s) + least_s.iter().sum::<f64>();
    let each_s = fraction * recording.max(0.0) / design.len() as f64;
    let min_revolutions = p.budget.min_revolutions;
    design
        .iter()
        .map(|&i| ((each_s / p.grid.tau_s[i]).floor() as u32).max(min_revolutions))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exchange::{FINAL_ITERATIONS, allocate, var_k2_scaled, whole_revolutions};

    fn problem(budget_s: f64) -> TwoOrientationProblem {
        let rates: Vec<f64> = (2..=40).map(|k| 5.0 * f64::from(k)).collect();
        TwoOrientationProblem::new(
            &Limits {
                g_m_s2: 9.8,
                radius_m: [2.5, 2.54],
                noise: NoiseSpec::PerRevolution { sigma_rad_s: 2e-8 },
                budget: Budget {
                    budget_s,
                    settling_s: 60.0,
                    remount_s: 600.0,
                    min_revolutions: 2,
                    allow_repeats: false,
                },
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
        let a = allocate(&p, &design, &min_s, None, Criterion::K2, FINAL_ITERATIONS).unwrap();
        let z = nalgebra::SMatrix::<f64, TWO_ORIENTATION_TERMS, TWO_ORIENTATION_TERMS>::from_fn(
            |i, j| p.grid.info_per_s[design[i]].sqrt() * p.grid.x[design[i]][j],
        );
        let q = z
            .transpose()
            .lu()
            .solve(&nalgebra::SVector::<f64, TWO_ORIENTATION_TERMS>::ith(
                K2_TERM, 1.0,
            ))
            .unwrap();
        let l1: f64 = q.iter().map(|v| v.abs()).sum();
        let closed = l1 * l1 / p.budget.free_s(&min_s);
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
        let min_s = p.recording_s(&d, &revs);
        let a = allocate(&p, &d, &min_s, None, Criterion::K2, FINAL_ITERATIONS).unwrap();
        let whole = whole_revolutions(&p, &a, &revs);
        let used: f64 = p.recording_s(&d, &whole).iter().sum::<f64>() + 60.0 * 16.0 + 600.0;
        assert!(used <= 7200.0);
        assert!(whole.iter().zip(&revs).all(|(w, r)| w >= r));
        // The reserve costs something, not much.
        let t: Vec<f64> = p.recording_s(&d, &whole);
        let with = var_k2_scaled(&p, &d, &t).unwrap();
        assert!(with > best.value);
    }
}
