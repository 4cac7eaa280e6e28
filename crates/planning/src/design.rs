//! The single-orientation search space: the candidate rates of the eq. 18 design (6×6,
//! [`Problem`]) for the exchange algorithm of [`crate::exchange`], which the two-orientation
//! search (`joint`) shares.
//!
//! A point may move to any candidate (to one already used when `schedule.allow_repeats`);
//! there is no remount; the allocation a search starts from and the one after an improving
//! exchange converge (up to [`FINAL_ITERATIONS`] multiplicative steps).

use std::ops::Range;

use crate::error::{PlanningError, Result};
use crate::exchange::{self, Allocated, Budget, FINAL_ITERATIONS, Grid, Space};
use crate::inputs::{K2, Problem, UNKNOWNS};

impl Space<UNKNOWNS> for Problem {
    const K2: usize = K2;
    const PASS_ITERATIONS: usize = FINAL_ITERATIONS;

    fn grid(&self) -> &Grid<UNKNOWNS> {
        &self.grid
    }

    fn budget(&self) -> Budget {
        let s = &self.inputs.schedule;
        Budget {
            budget_s: s.budget_s,
            settling_s: s.settling_s,
            remount_s: 0.0,
            min_revolutions: s.min_revolutions,
            allow_repeats: s.allow_repeats,
        }
    }

    fn range_of(&self, _: usize) -> Range<usize> {
        0..self.rates_rad_s.len()
    }

    /// The slowest point (the first of them) moves to the fastest candidate it may use until
    /// the start fits.
    fn repair(&self, design: &mut [usize]) {
        let n = self.rates_rad_s.len();
        let repeats = self.inputs.schedule.allow_repeats;
        while self.free_time(design) < 0.0 {
            let Some((slot, _)) = design.iter().enumerate().min_by_key(|(_, i)| **i) else {
                return;
            };
            let target = (0..n).rev().find(|k| repeats || !design.contains(k));
            match target {
                Some(k) if k > design[slot] => design[slot] = k,
                _ => return,
            }
        }
    }
}

/// The best design of `schedule.points` points over the candidates ([`exchange::search`]
/// with the file's criterion, restarts and seed).
pub(crate) fn search(p: &Problem) -> Option<Allocated> {
    let parts = [(0..p.rates_rad_s.len(), p.inputs.schedule.points)];
    exchange::search(p, &parts, p.inputs.search)
}

/// Whole revolutions of an allocated design, at least `schedule.min_revolutions` each.
pub(crate) fn whole_revolutions(p: &Problem, a: &Allocated) -> Vec<u32> {
    let min_revs = vec![p.inputs.schedule.min_revolutions; a.design.len()];
    exchange::whole_revolutions(p, a, &min_revs)
}

/// The budget check needs the search space's free time (`Space::free_time`), so it lives
/// beside the space, not with the inputs (which the exchange search reads).
impl Problem {
    /// Checks that the cheapest design fits the budget.
    pub(crate) fn check_budget(&self) -> Result<()> {
        let s = &self.inputs.schedule;
        let n = self.rates_rad_s.len();
        // The cheapest points are the fastest: the last candidates (with repeats, the last one).
        let cheapest: Vec<usize> = if s.allow_repeats {
            vec![n - 1; s.points]
        } else {
            (n - s.points..n).collect()
        };
        let free = self.free_time(&cheapest);
        if free < 0.0 {
            let settling_s = s.settling_s * s.points as f64;
            return Err(PlanningError::BudgetTooShort {
                budget_s: s.budget_s,
                needed_s: s.budget_s - free,
                settling_s,
                minimum_s: s.budget_s - free - settling_s,
                points: s.points,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exchange::{allocate_final, var_k2_scaled};
    use crate::inputs::{
        Candidates, CentrifugeSpec, CrSpec, Criterion, NoiseSpec, PigaSpec, PlanInputs, ProbeSpec,
        Schedule, Search, Target, TypeB,
    };

    fn problem(rates: Vec<f64>, budget_s: f64) -> Problem {
        Problem::new(&PlanInputs {
            centrifuge: CentrifugeSpec {
                radius_m: 2.5,
                g_m_s2: 9.8,
                min_rate_deg_s: 1.0,
                max_rate_deg_s: 250.0,
                max_acceleration_g: None,
                candidates: Candidates::List(rates),
            },
            piga: PigaSpec {
                k0_rad_s: 0.0,
                k1_rad_s_g: 0.56,
                k2_rad_s_g2: 0.0,
                k3_rad_s_g3: 0.0,
                k1_u_rad_s_g: 0.0,
                noise: NoiseSpec::PerRevolution { sigma_rad_s: 1e-8 },
            },
            probe: ProbeSpec {
                noise_um: 0.05,
                sample_rate_hz: 1000.0,
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
            },
            c_r: CrSpec {
                expected_m_s2: 0.0,
                u_m_s2: None,
            },
            type_b: TypeB::default(),
            schedule: Schedule {
                points: 7,
                budget_s,
                settling_s: 0.0,
                min_revolutions: 1,
                allow_repeats: true,
            },
            target: Target {
                u95_k2_rad_s_g2: 1.0,
                tolerance_k2_rad_s_g2: 1.0,
                bias_fraction: 0.1,
            },
            search: Search::default(),
            two_orientation: None,
        })
        .unwrap()
    }

    /// On six points (a square design), the c-optimal shares of the information are known in
    /// closed form: with rows `z_i = √e_i·x_i` and `q = Z⁻ᵀc`, `p_i ∝ |q_i|` and
    /// `min var = (Σ|q_i|)²/T`. The multiplicative algorithm must reach it.
    #[test]
    fn allocation_reaches_the_closed_form_on_six_points() {
        let rates = vec![10.0, 45.0, 80.0, 120.0, 160.0, 200.0];
        // A budget so long that the one-revolution minima do not matter.
        let p = problem(rates, 1e9);
        let design: Vec<usize> = (0..6).collect();
        let a = allocate_final(&p, &design, Criterion::K2).unwrap();
        let z = nalgebra::Matrix6::from_fn(|i, j| p.grid.info_per_s[i].sqrt() * p.grid.x[i][j]);
        let q = z
            .transpose()
            .lu()
            .solve(&nalgebra::Vector6::ith(K2, 1.0))
            .unwrap();
        let l1: f64 = q.iter().map(|v| v.abs()).sum();
        let closed_form = l1 * l1 / p.free_time(&design).max(0.0);
        let rel = (a.value - closed_form).abs() / closed_form;
        assert!(rel < 1e-6, "{} vs {closed_form}: {rel}", a.value);
        // Equal times are worse.
        let equal = vec![1e9 / 6.0; 6];
        assert!(var_k2_scaled(&p, &design, &equal).unwrap() > a.value);
    }

    #[test]
    fn whole_revolutions_fit_the_budget() {
        let rates: Vec<f64> = (1..=20).map(|i| 10.0 * f64::from(i)).collect();
        let p = problem(rates, 2000.0);
        let best = search(&p).unwrap();
        let revs = whole_revolutions(&p, &best);
        let used: f64 = best
            .design
            .iter()
            .zip(&revs)
            .map(|(&i, &n)| f64::from(n) * p.grid.tau_s[i])
            .sum();
        assert!(used <= 2000.0);
        // No point's revolution would still fit.
        let slack = 2000.0 - used;
        assert!(best.design.iter().all(|&i| p.grid.tau_s[i] > slack));
    }
}
