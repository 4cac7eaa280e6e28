//! Correlated inputs: `u_c² = cᵀVc` in the GUM framework, a multivariate normal (or t) draw
//! in the Monte Carlo method.

use approx::assert_relative_eq;
use uncertainty::{
    Dof, GumOptions, InputQuantity, Inputs, McOptions, gum, model_fn, monte_carlo, validate,
};

fn difference() -> impl uncertainty::MeasurementModel {
    model_fn(["Y"], |x, y| {
        y[0] = x[0] - x[1];
        Ok(())
    })
}

const R: [f64; 4] = [1.0, 0.9, 0.9, 1.0];

/// u(Y) ≈ 1.2 has δ = 0.05 with two digits; three digits (δ = 0.005) make the comparison
/// with the analytic values sharp.
fn three_digits() -> McOptions {
    McOptions {
        n_dig: 3,
        ..McOptions::default()
    }
}

#[test]
fn difference_of_correlated_normal_inputs() {
    // Y = X1 − X2, u1 = 1, u2 = 2, r = 0.9: u² = 1 + 4 − 2·0.9·1·2 = 1.4.
    let inputs = Inputs::with_correlation(
        vec![
            InputQuantity::normal("X1", 10.0, 1.0),
            InputQuantity::normal("X2", 4.0, 2.0),
        ],
        &R,
    )
    .unwrap();
    let g = gum(&difference(), &inputs, &GumOptions::default()).unwrap();
    let y = &g.outputs[0];
    assert_relative_eq!(y.standard_uncertainty, 1.4f64.sqrt(), max_relative = 1e-10);
    // Shares of u_c²: X1: 1·(1 − 0.9·2)/1.4 = −57.1 %, X2: 2·(2 − 0.9)/1.4 = 157.1 %.
    assert_relative_eq!(
        y.contributions[0].variance_percent,
        -100.0 * 0.8 / 1.4,
        max_relative = 1e-9
    );
    assert_relative_eq!(
        y.contributions[1].variance_percent,
        100.0 * 2.2 / 1.4,
        max_relative = 1e-9
    );
    // Ignoring the correlation would give √5 = 2.24: far from the Monte Carlo value.
    let mc = monte_carlo(&difference(), &inputs, &three_digits()).unwrap();
    let o = &mc.outputs[0];
    assert!(
        (o.standard_uncertainty - 1.4f64.sqrt()).abs() <= o.tolerance,
        "{o:?}"
    );
    assert!((o.estimate - 6.0).abs() <= o.tolerance, "{o:?}");
    assert!(validate(&g, &mc, 2).unwrap().all_agree());
}

#[test]
fn correlated_type_a_group_is_one_welch_satterthwaite_term_and_a_multivariate_t() {
    // Two coefficients of one fit: common ν = 10. As one group, ν_eff = 10 exactly.
    let inputs = Inputs::with_correlation(
        vec![
            InputQuantity::type_a("X1", 10.0, 1.0, Dof::Finite(10.0)),
            InputQuantity::type_a("X2", 4.0, 2.0, Dof::Finite(10.0)),
        ],
        &R,
    )
    .unwrap();
    let g = gum(&difference(), &inputs, &GumOptions::default()).unwrap();
    assert_relative_eq!(
        g.outputs[0].dof.finite().unwrap(),
        10.0,
        max_relative = 1e-12
    );
    // The multivariate t with ν = 10 has covariance ν/(ν − 2) times the scale matrix:
    // u(Y) = √(1.4·1.25) = 1.323, and Y = 6 + √1.4·t_10 exactly, so the 95 % interval is
    // 6 ± 2.228·√1.4.
    let mc = monte_carlo(&difference(), &inputs, &three_digits()).unwrap();
    let o = &mc.outputs[0];
    assert!(
        (o.standard_uncertainty - 1.75f64.sqrt()).abs() <= o.tolerance,
        "{o:?}"
    );
    let half = 2.228_138_851_986_274 * 1.4f64.sqrt();
    assert!(
        (o.coverage_interval.0 - (6.0 - half)).abs() <= o.tolerance,
        "{o:?}"
    );
    assert!(
        (o.coverage_interval.1 - (6.0 + half)).abs() <= o.tolerance,
        "{o:?}"
    );
}
