//! Closed loops through the simulator: trial weight → correction → check run, and the
//! stiffness model's recovery of the simulated imbalance.

use approx::assert_relative_eq;
use balance::{Fields, TrialMass, influence_correction, stiffness_correction};
use kinematics::ImbalanceMass;

use crate::common::{context, fit, plane, scenario, with_masses};

const TRIAL: TrialMass = TrialMass {
    mass_kg: 8.0,
    radius_m: 2.5,
    azimuth_deg: 90.0,
};

/// One loop: before run, trial run, correction, check run. Returns (C_r before, C_r after,
/// predicted C_r, its σ, σ of the measured C_r after) in m·s².
fn one_loop(seed: u64, min_duration_s: f64) -> [f64; 5] {
    let before = scenario(|s| {
        s.seed = seed;
        s.min_duration_s = min_duration_s;
    });
    let trial = scenario(|s| {
        s.seed = seed + 1000;
        s.min_duration_s = min_duration_s;
        with_masses(
            s,
            &[ImbalanceMass {
                mass_kg: TRIAL.mass_kg,
                radius_m: TRIAL.radius_m,
                azimuth_deg: TRIAL.azimuth_deg,
                arm_m: 0.15,
            }],
        );
    });
    let f0 = fit(&before, "initial");
    let ft = fit(&trial, "trial");
    let advice = influence_correction(&f0, &ft, &TRIAL, &plane(), &context(), &Fields::default())
        .expect("a correction");
    let c = &advice.correction;
    let check = scenario(|s| {
        s.seed = seed + 2000;
        s.min_duration_s = min_duration_s;
        with_masses(
            s,
            &[ImbalanceMass {
                mass_kg: c.mass_kg,
                radius_m: c.radius_m,
                azimuth_deg: c.azimuth_deg,
                arm_m: 0.15,
            }],
        );
    });
    let fc = fit(&check, "check");
    let d = fc.dynamic_piga_um_s2;
    [
        f0.dynamic_piga_um_s2.x * 1e-6,
        d.x * 1e-6,
        advice.predicted.c_r_m_s2,
        advice.predicted.c_r_u_m_s2,
        d.covariance[0][0].sqrt() * 1e-6,
    ]
}

#[test]
fn trial_weight_correction_cuts_c_r_fifty_fold_and_meets_the_prediction() {
    let [before, after, predicted, sigma_pred, sigma_meas] = one_loop(1, 72.0);
    // the paper's pre-balance size
    assert_relative_eq!(before, 1.6e-6, max_relative = 1e-3);
    assert!(
        after.abs() * 50.0 < before.abs(),
        "C_r {before:e} → {after:e}"
    );
    let sigma = sigma_pred.hypot(sigma_meas);
    assert!(
        (after - predicted).abs() <= 3.0 * sigma,
        "after {after:e}, predicted {predicted:e} ± {sigma_pred:e} (check run ± {sigma_meas:e})"
    );
}

/// The claimed σ of the predicted residual (with the check run's own σ) describes the scatter
/// of the measured residual over seeds: the mean of z² is near 1.
#[test]
fn predicted_residual_sigma_is_calibrated_over_seeds() {
    let n = 24;
    let mut z2 = 0.0;
    for seed in 0..n {
        let [_, after, predicted, sigma_pred, sigma_meas] = one_loop(100 + 7 * seed, 36.0);
        let z = (after - predicted) / sigma_pred.hypot(sigma_meas);
        assert!(z.abs() < 4.5, "seed {seed}: z = {z}");
        z2 += z * z;
    }
    let mean = z2 / n as f64;
    // χ²(24)/24 lies in [0.4, 1.8] with probability above 99 %
    assert!((0.4..1.8).contains(&mean), "mean z² = {mean}");
}

#[test]
fn stiffness_model_recovers_the_simulated_imbalance() {
    let loaded = scenario(|s| {
        if let kinematics::ErrorMotionSpec::Physical(p) = &mut s.error_motion {
            p.imbalance_azimuth_deg = 35.0;
        }
    });
    let f = fit(&loaded, "initial");
    let advice = stiffness_correction(
        &f,
        5.0e7,
        "radial_stiffness_n_m",
        &plane(),
        &context(),
        &Fields::default(),
    )
    .unwrap();
    let u = advice.imbalance_kg_m;
    // 32 kg at 2.5 m towards 35°
    let (m_r, m_r_sigma) = (u.magnitude(), u.magnitude_sigma());
    assert!(
        (m_r - 80.0).abs() < 3.0 * m_r_sigma + 1e-9 * 80.0,
        "m·R = {m_r} ± {m_r_sigma} kg·m"
    );
    assert!(
        (u.azimuth_deg() - 35.0).abs() < 3.0 * u.azimuth_sigma_deg() + 1e-9,
        "azimuth {} ± {}",
        u.azimuth_deg(),
        u.azimuth_sigma_deg()
    );
    assert_relative_eq!(advice.correction.mass_kg, 32.0, max_relative = 1e-4);
    assert_relative_eq!(advice.correction.azimuth_deg, 35.0 - 180.0, epsilon = 0.01);
    // the static drift of the fixture: 300 N / 5e7 N/m = 6 µm towards −20° at the PIGA plane
    let s = f.static_piga_um;
    assert!((s.magnitude() - 6.0).abs() < 3.0 * s.magnitude_sigma() + 1e-6);
    assert!((s.azimuth_deg() + 20.0).abs() < 3.0 * s.azimuth_sigma_deg() + 1e-6);
    // the model S + D·ω² holds: no significant linear term
    let lof = f.lack_of_fit.expect("8 rates");
    assert!(lof.linear_significance < 4.0, "{lof:?}");
}
