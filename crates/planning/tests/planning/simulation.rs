//! The predicted u(k2) against the spread of k2 over simulated campaigns.

use planning::{expected_outputs, plan, simulate_plan};

#[test]
fn predicted_u_k2_agrees_with_2000_simulated_campaigns() {
    let inputs = super::paper::inputs(10);
    let p = plan(&inputs).unwrap();
    let outputs = expected_outputs(&inputs, &p);
    let check = simulate_plan(&p, &outputs, 2000, 7).unwrap();
    // The SD of 2000 draws has a relative standard error of 1.6 %: 10 % is six of them.
    assert!((check.ratio - 1.0).abs() < 0.10, "{check:?}");
    // The mean is the apparent k2 = k2 + Δk2.
    let delta = p.delta_k2_expected_rad_s_g2;
    assert!((check.noise_free_k2_rad_s_g2 - (5e-7 + delta)).abs() < 1e-4 * p.u_k2_fit_rad_s_g2);
    assert!(
        (check.mean_k2_rad_s_g2 - check.noise_free_k2_rad_s_g2).abs()
            < 4.0 * check.simulated_sd_rad_s_g2 / 2000f64.sqrt()
    );
}

#[test]
fn the_check_does_not_depend_on_the_number_of_threads() {
    let inputs = super::paper::inputs(8);
    let p = plan(&inputs).unwrap();
    let outputs = expected_outputs(&inputs, &p);
    let a = simulate_plan(&p, &outputs, 200, 3).unwrap();
    let pool = rayon_pool();
    let b = pool.install(|| simulate_plan(&p, &outputs, 200, 3).unwrap());
    assert_eq!(a, b);
}

fn rayon_pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
}
