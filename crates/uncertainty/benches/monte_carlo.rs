//! Monte Carlo throughput on a model the size of the PIGA calibration's.
//!
//! `cargo bench -p uncertainty --bench monte_carlo`. Twenty inputs (eight readings, Type A
//! with ν = 9, drawn from t; eight rectangular reading biases; a normal scale factor and
//! offset, a rectangular drift and a normal quadratic gain) give eight corrected points,
//! fitted with six polynomial coefficients through a fixed 8 × 6 design by its precomputed
//! pseudo-inverse, `y = P·obs`. 10⁶ trials per iteration, on one thread and on all threads.
//! `bench/uncertainty_numpy.py` runs the same Monte Carlo in NumPy.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use uncertainty::{
    Dof, InputQuantity, Inputs, McOptions, MeasurementModel, ModelError, Trials, monte_carlo,
};

const POINTS: usize = 8;
const COEFFICIENTS: usize = 6;
const TRIALS: u64 = 1_000_000;

/// The normalised abscissa of point `j`, in [−1, 1].
fn tau(j: usize) -> f64 {
    (j as f64 - 3.5) / 3.5
}

/// `P = R⁻¹Qᵀ` from the modified Gram–Schmidt QR of the design `A_jk = τ_j^k`.
fn pseudo_inverse() -> [[f64; POINTS]; COEFFICIENTS] {
    let mut q = [[0.0; POINTS]; COEFFICIENTS]; // columns of A, then of Q
    for (k, col) in q.iter_mut().enumerate() {
        for (j, v) in col.iter_mut().enumerate() {
            *v = tau(j).powi(k as i32);
        }
    }
    let mut r = [[0.0; COEFFICIENTS]; COEFFICIENTS];
    for k in 0..COEFFICIENTS {
        for i in 0..k {
            let d: f64 = (0..POINTS).map(|j| q[i][j] * q[k][j]).sum();
            r[i][k] = d;
            let qi = q[i];
            for (v, w) in q[k].iter_mut().zip(qi) {
                *v -= d * w;
            }
        }
        let norm = q[k].iter().map(|v| v * v).sum::<f64>().sqrt();
        r[k][k] = norm;
        q[k].iter_mut().for_each(|v| *v /= norm);
    }
    // Back-substitution R·P = Qᵀ, column by column of Qᵀ.
    let mut p = [[0.0; POINTS]; COEFFICIENTS];
    for j in 0..POINTS {
        for k in (0..COEFFICIENTS).rev() {
            let s: f64 = (k + 1..COEFFICIENTS).map(|i| r[k][i] * p[i][j]).sum();
            p[k][j] = (q[k][j] - s) / r[k][k];
        }
    }
    p
}

/// `obs_j = s·(z_j − b_j) + c + d·j/7 + g·z_j²`, `y = P·obs`.
struct Calibration {
    p: [[f64; POINTS]; COEFFICIENTS],
}

impl MeasurementModel for Calibration {
    fn output_names(&self) -> Vec<String> {
        (0..COEFFICIENTS).map(|k| format!("k{k}")).collect()
    }

    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), ModelError> {
        let (z, rest) = x.split_at(POINTS);
        let (b, common) = rest.split_at(POINTS);
        let (s, c, d, g) = (common[0], common[1], common[2], common[3]);
        let mut obs = [0.0; POINTS];
        for j in 0..POINTS {
            obs[j] = s * (z[j] - b[j]) + c + d * (j as f64 / 7.0) + g * z[j] * z[j];
        }
        for (yk, row) in y.iter_mut().zip(&self.p) {
            *yk = row.iter().zip(&obs).map(|(p, o)| p * o).sum();
        }
        Ok(())
    }

    fn input_count(&self) -> Option<usize> {
        Some(2 * POINTS + 4)
    }
}

fn inputs() -> Inputs {
    let mut q = Vec::new();
    for j in 0..POINTS {
        let t = tau(j);
        let z = 1.0 + 0.5 * t + 0.1 * t * t - 0.02 * t.powi(3);
        q.push(InputQuantity::type_a(
            format!("z{j}"),
            z,
            1e-3,
            Dof::Finite(9.0),
        ));
    }
    for j in 0..POINTS {
        q.push(InputQuantity::rectangular(format!("b{j}"), 0.0, 2e-4));
    }
    q.push(InputQuantity::normal("s", 1.0, 1e-4));
    q.push(InputQuantity::normal("c", 0.0, 1e-4));
    q.push(InputQuantity::rectangular("d", 0.0, 1e-4));
    q.push(InputQuantity::normal("g", 0.0, 1e-3));
    Inputs::new(q).expect("valid inputs")
}

fn bench(c: &mut Criterion) {
    let model = Calibration {
        p: pseudo_inverse(),
    };
    let inputs = inputs();
    let options = McOptions {
        seed: 1,
        trials: Trials::Fixed(TRIALS),
        ..McOptions::default()
    };
    let mut group = c.benchmark_group("monte_carlo_20_inputs_6_outputs");
    group.throughput(Throughput::Elements(TRIALS));
    group.sample_size(10);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for threads in [1, cores] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        group.bench_function(format!("{threads}_threads"), |b| {
            b.iter(|| {
                pool.install(|| monte_carlo(black_box(&model), &inputs, &options))
                    .expect("monte carlo")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
