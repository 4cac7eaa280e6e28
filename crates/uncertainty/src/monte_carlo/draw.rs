//! The trials: each input drawn from its distribution on a seeded random stream per chunk of
//! trials, the model evaluated over sub-blocks, failed trials counted (JCGM 101 §6.4).

use rand::{Rng, SeedableRng};
use rand_distr::{ChiSquared, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;
use rayon::prelude::*;

use crate::error::{ModelError, Result, UncertaintyError};
use crate::input::Inputs;
use crate::kind::{Distribution, Dof};
use crate::model::MeasurementModel;

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
pub(super) enum Draw {
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

/// How each input, or group of correlated inputs, is drawn.
pub(super) fn draws(inputs: &Inputs) -> Result<Vec<Draw>> {
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
pub(super) fn stream(seed: u64, batch: u64, chunk: u64) -> McRng {
    McRng::seed_from_u64(units::stream_seed(seed, batch, chunk))
}

/// The failures of one chunk: how many, and the first (trial index in the batch, error).
type ChunkFailures = (u64, Option<(usize, ModelError)>);

/// Runs one batch of `trials` trials into `rows` (row-major `trials × m`); a failed trial's
/// row is NaN. Chunks of [`CHUNK`] trials run in parallel, each on its own stream.
pub(super) fn run_batch<M: MeasurementModel + ?Sized>(
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_differ_by_batch_and_chunk() {
        let a: u64 = stream(1, 0, 0).random();
        let b: u64 = stream(1, 1, 0).random();
        let c: u64 = stream(1, 0, 1).random();
        let d: u64 = stream(2, 0, 0).random();
        assert!(a != b && a != c && b != c && a != d);
    }
}
