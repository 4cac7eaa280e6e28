//! Coverage over simulated experiments: the GUM interval `y ± U95`, with the coverage factor
//! from the Welch–Satterthwaite ν_eff, contains the true value in about 95 % of experiments
//! whose Type A inputs have few degrees of freedom.

use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use uncertainty::{Dof, GumOptions, InputQuantity, Inputs, gum, model_fn};

const EXPERIMENTS: usize = 2000;

/// Returns the fraction of experiments whose GUM interval covers the truth, with the
/// Welch–Satterthwaite k and with k = 1.96 regardless of ν.
fn coverage() -> (f64, f64) {
    // Y = X1 + 2·X2 − X3: X1 the mean of 3 readings (σ = 1, ν = 2), X2 of 4 readings
    // (σ = 0.5, ν = 3), X3 a Type B input with u = 0.3 known exactly.
    let truth = [5.0, -2.0, 1.0];
    let (sigma, n) = ([1.0, 0.5], [3usize, 4usize]);
    let model = model_fn(["Y"], |x, y| {
        y[0] = x[0] + 2.0 * x[1] - x[2];
        Ok(())
    });
    let y_true = truth[0] + 2.0 * truth[1] - truth[2];
    let mut rng = StdRng::seed_from_u64(2024);
    let (mut covered_ws, mut covered_z) = (0, 0);
    for _ in 0..EXPERIMENTS {
        let mut quantities = Vec::new();
        for i in 0..2 {
            let noise = Normal::new(truth[i], sigma[i]).unwrap();
            let readings: Vec<f64> = (0..n[i]).map(|_| noise.sample(&mut rng)).collect();
            let mean = readings.iter().sum::<f64>() / n[i] as f64;
            let s2 = readings.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n[i] - 1) as f64;
            quantities.push(InputQuantity::type_a(
                format!("X{}", i + 1),
                mean,
                (s2 / n[i] as f64).sqrt(),
                Dof::Finite((n[i] - 1) as f64),
            ));
        }
        // The Type B input's estimate is drawn from its own distribution too.
        let x3 = Normal::new(truth[2], 0.3).unwrap().sample(&mut rng);
        quantities.push(InputQuantity::normal("X3", x3, 0.3));
        let g = gum(
            &model,
            &Inputs::new(quantities).unwrap(),
            &GumOptions::default(),
        )
        .unwrap();
        let y = &g.outputs[0];
        let err = (y.estimate - y_true).abs();
        covered_ws += usize::from(err <= y.expanded_uncertainty);
        covered_z += usize::from(err <= 1.959_963_984_540_054 * y.standard_uncertainty);
    }
    (
        covered_ws as f64 / EXPERIMENTS as f64,
        covered_z as f64 / EXPERIMENTS as f64,
    )
}

#[test]
fn welch_satterthwaite_interval_covers_95_percent() {
    let (ws, z) = coverage();
    // 2000 experiments: the binomial standard deviation at 95 % is 0.49 %. Measured: 95.7 %.
    assert!((0.93..=0.97).contains(&ws), "coverage with ν_eff: {ws}");
    // Ignoring the degrees of freedom (k = 1.96) covers less (91.25 % here), below the band
    // above: a method that ignores ν fails this test.
    assert!(z < 0.93, "coverage with k = 1.96: {z}");
}
