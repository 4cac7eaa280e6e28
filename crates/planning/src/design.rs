//! The design criterion, the allocation of recording time to a design's points, and the
//! exchange algorithm over the candidate rates.
//!
//! The information matrix of a design with recording time `t_i` at candidate `i` is
//! `M = Σ t_i·e_i·x_i x_iᵀ`, with `x_i` the eq. 18 regressors (each column divided by its
//! largest magnitude over the candidates) and `e_i` the weight per second of recording. The
//! search solves the 6×6 system `M v = c` by Cholesky: the criterion only ranks designs, and
//! the plan's reported numbers come from `identify`'s QR of the weighted design.

use nalgebra::{Matrix6, Vector6};
use rand::{SeedableRng, rngs::StdRng};
use rayon::prelude::*;

use crate::inputs::{Criterion, K2, Problem, UNKNOWNS};

/// Multiplicative iterations per trial exchange (warm-started from the current allocation).
const SEARCH_ITERATIONS: usize = 30;
/// Largest number of multiplicative iterations of a final allocation.
const FINAL_ITERATIONS: usize = 5000;
/// Relative change of the criterion under which the allocation is taken as converged.
const CONVERGED: f64 = 1e-13;
/// Largest number of exchange passes over the points.
const MAX_PASSES: usize = 40;

/// A design: candidate indices, the free recording time of each point beyond its minimum
/// revolutions, and its criterion value.
#[derive(Debug, Clone)]
pub(crate) struct Allocated {
    pub(crate) design: Vec<usize>,
    pub(crate) free_s: Vec<f64>,
    pub(crate) value: f64,
}

/// Recording time of each point: its minimum revolutions plus its free time.
fn times(p: &Problem, design: &[usize], free_s: &[f64]) -> Vec<f64> {
    let min_rev = f64::from(p.inputs.schedule.min_revolutions);
    design
        .iter()
        .zip(free_s)
        .map(|(&i, &s)| min_rev * p.tau_s[i] + s)
        .collect()
}

/// `M = Σ t_i e_i x_i x_iᵀ`.
fn information(p: &Problem, design: &[usize], time_s: &[f64]) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    for (&i, &t) in design.iter().zip(time_s) {
        let x = Vector6::from_column_slice(&p.x[i]);
        m.syger(t * p.info_per_s[i], &x, &x, 1.0);
    }
    m
}

/// The criterion at `M` (smaller is better): `[M⁻¹]_{k2,k2}` or `−ln det M`; `None` when `M`
/// is singular.
fn criterion_value(
    criterion: Criterion,
    m: &Matrix6<f64>,
) -> Option<(f64, nalgebra::Cholesky<f64, nalgebra::U6>)> {
    let chol = m.cholesky()?;
    let value = match criterion {
        Criterion::K2 => {
            let v = chol.solve(&Vector6::ith(K2, 1.0));
            v[K2]
        }
        Criterion::D => {
            let l = chol.l_dirty();
            -2.0 * (0..UNKNOWNS).map(|j| l[(j, j)].ln()).sum::<f64>()
        }
    };
    (value.is_finite() && (criterion == Criterion::D || value > 0.0)).then_some((value, chol))
}

/// The criterion of a design with recording times `time_s`.
pub(crate) fn evaluate(
    p: &Problem,
    design: &[usize],
    time_s: &[f64],
    criterion: Criterion,
) -> Option<f64> {
    criterion_value(criterion, &information(p, design, time_s)).map(|(v, _)| v)
}

/// The variance of k2 (in the scaled parametrisation) of a design with recording times.
pub(crate) fn var_k2_scaled(p: &Problem, design: &[usize], time_s: &[f64]) -> Option<f64> {
    evaluate(p, design, time_s, Criterion::K2)
}

/// Allocates the design's free time by the multiplicative algorithm, starting from `start`
/// (equal shares when `None`), for at most `iterations` steps.
///
/// Each step sets `s_i ← F·s_i·d_i / Σ_j s_j d_j`, with `F` the free time and
/// `d_i = √e_i·|x_iᵀM⁻¹c|` for var(k2) (c-optimality) or `d_i = e_i·x_iᵀM⁻¹x_i` for the
/// determinant. At a fixed point every point with free time has the same `d_i`, which is the
/// optimality condition of either criterion with the time constraint.
pub(crate) fn allocate(
    p: &Problem,
    design: &[usize],
    start: Option<&[f64]>,
    criterion: Criterion,
    iterations: usize,
) -> Option<Allocated> {
    let free = p.free_time(design);
    if free < 0.0 {
        return None;
    }
    let n = design.len();
    let mut s: Vec<f64> = match start {
        Some(s) => {
            let total: f64 = s.iter().sum();
            if total > 0.0 {
                s.iter()
                    .map(|v| v.max(free * 1e-9 / n as f64) * free / total)
                    .collect()
            } else {
                vec![free / n as f64; n]
            }
        }
        None => vec![free / n as f64; n],
    };
    let (mut value, mut chol) =
        criterion_value(criterion, &information(p, design, &times(p, design, &s)))?;
    if free == 0.0 {
        return Some(Allocated {
            design: design.to_vec(),
            free_s: s,
            value,
        });
    }
    let mut d = vec![0.0; n];
    for _ in 0..iterations {
        let v = chol.solve(&Vector6::ith(K2, 1.0));
        for (k, &i) in design.iter().enumerate() {
            let x = Vector6::from_column_slice(&p.x[i]);
            d[k] = match criterion {
                Criterion::K2 => p.info_per_s[i].sqrt() * x.dot(&v).abs(),
                Criterion::D => p.info_per_s[i] * x.dot(&chol.solve(&x)),
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
        let t_next = times(p, design, &next);
        let Some((v_next, c_next)) = criterion_value(criterion, &information(p, design, &t_next))
        else {
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
    Some(Allocated {
        design: design.to_vec(),
        free_s: s,
        value,
    })
}

/// The best allocation of a design (converged).
pub(crate) fn allocate_final(
    p: &Problem,
    design: &[usize],
    criterion: Criterion,
) -> Option<Allocated> {
    allocate(p, design, None, criterion, FINAL_ITERATIONS)
}

/// An evenly spread start: `points` indices spread over the candidates.
fn spread_start(p: &Problem) -> Vec<usize> {
    let n = p.rates_rad_s.len();
    let m = p.inputs.schedule.points;
    let mut d: Vec<usize> = (0..m)
        .map(|k| ((k as f64) * (n - 1) as f64 / (m - 1) as f64).round() as usize)
        .collect();
    if !p.inputs.schedule.allow_repeats {
        d.dedup();
        // Rounding can merge neighbours only when n is close to m; fill from the top.
        let mut next = n;
        while d.len() < m {
            next -= 1;
            if !d.contains(&next) {
                d.push(next);
            }
        }
        d.sort_unstable();
    }
    d
}

/// A random start of distinct candidates.
fn random_start(p: &Problem, rng: &mut StdRng) -> Vec<usize> {
    let n = p.rates_rad_s.len();
    let m = p.inputs.schedule.points;
    let mut d = rand::seq::index::sample(rng, n, m.min(n)).into_vec();
    while d.len() < m {
        d.push(n - 1);
    }
    d.sort_unstable();
    d
}

/// Makes a start fit the budget: the slowest point moves to the fastest unused candidate
/// until it fits.
fn repair(p: &Problem, design: &mut [usize]) {
    let n = p.rates_rad_s.len();
    let repeats = p.inputs.schedule.allow_repeats;
    while p.free_time(design) < 0.0 {
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

/// Coordinate exchange from one start.
fn exchange(p: &Problem, mut design: Vec<usize>, criterion: Criterion) -> Option<Allocated> {
    repair(p, &mut design);
    let mut current = allocate_final(p, &design, criterion)?;
    let n = p.rates_rad_s.len();
    let repeats = p.inputs.schedule.allow_repeats;
    for _ in 0..MAX_PASSES {
        let mut improved = false;
        for slot in 0..design.len() {
            let mut best: Option<Allocated> = None;
            let mut trial = current.design.clone();
            for k in 0..n {
                if k == current.design[slot] || (!repeats && current.design.contains(&k)) {
                    continue;
                }
                trial[slot] = k;
                if p.free_time(&trial) < 0.0 {
                    continue;
                }
                let Some(a) = allocate(
                    p,
                    &trial,
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
                current = allocate(p, &b.design, Some(&b.free_s), criterion, FINAL_ITERATIONS)
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

/// The best design over the evenly spread start and `restarts` random starts (in parallel;
/// the result does not depend on the number of threads).
pub(crate) fn search(p: &Problem) -> Option<Allocated> {
    let search = p.inputs.search;
    let starts: Vec<Vec<usize>> = std::iter::once(spread_start(p))
        .chain((0..search.restarts).map(|r| {
            let mut rng = StdRng::seed_from_u64(search.seed.wrapping_add(r as u64));
            random_start(p, &mut rng)
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
/// revolutions (at least the minimum), then one revolution at a time added where it lowers
/// var(k2) most per second, while the budget allows.
pub(crate) fn whole_revolutions(p: &Problem, a: &Allocated) -> Vec<u32> {
    let s = &p.inputs.schedule;
    let t = times(p, &a.design, &a.free_s);
    let mut revs: Vec<u32> = a
        .design
        .iter()
        .zip(&t)
        .map(|(&i, &t)| ((t / p.tau_s[i]).floor() as u32).max(s.min_revolutions))
        .collect();
    let time_of = |revs: &[u32]| -> Vec<f64> {
        a.design
            .iter()
            .zip(revs)
            .map(|(&i, &n)| f64::from(n) * p.tau_s[i])
            .collect()
    };
    let used = |revs: &[u32]| -> f64 {
        time_of(revs).iter().sum::<f64>() + s.settling_s * revs.len() as f64
    };
    // Rounding down can only free time; guard against a floor that overshoots anyway.
    while used(&revs) > s.budget_s {
        let Some(k) = (0..revs.len())
            .filter(|&k| revs[k] > s.min_revolutions)
            .max_by(|&x, &y| p.tau_s[a.design[x]].total_cmp(&p.tau_s[a.design[y]]))
        else {
            break;
        };
        revs[k] -= 1;
    }
    loop {
        let remaining = s.budget_s - used(&revs);
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
    use crate::inputs::{
        Candidates, CentrifugeSpec, CrSpec, NoiseSpec, PigaSpec, PlanInputs, ProbeSpec, Schedule,
        Search, Target, TypeB,
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
            two_orientations: None,
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
        let z = nalgebra::Matrix6::from_fn(|i, j| p.info_per_s[i].sqrt() * p.x[i][j]);
        let q = z.transpose().lu().solve(&Vector6::ith(K2, 1.0)).unwrap();
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
            .map(|(&i, &n)| f64::from(n) * p.tau_s[i])
            .sum();
        assert!(used <= 2000.0);
        // No point's revolution would still fit.
        let slack = 2000.0 - used;
        assert!(best.design.iter().all(|&i| p.tau_s[i] > slack));
    }
}
