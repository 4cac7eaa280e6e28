//! Each input distribution of JCGM 101 §6.4, seen through the identity model `Y = X`.
//!
//! The standard uncertainties are chosen just below 1 so that two significant digits give a
//! tolerance δ = 0.005, about 0.5 % of u.

use uncertainty::{Dof, InputQuantity, Inputs, McOptions, McOutput, model_fn, monte_carlo};

fn identity(q: InputQuantity) -> McOutput {
    let model = model_fn(["Y"], |x, y| {
        y[0] = x[0];
        Ok(())
    });
    let mc = monte_carlo(
        &model,
        &Inputs::new(vec![q]).unwrap(),
        &McOptions::default(),
    )
    .unwrap();
    mc.outputs[0].clone()
}

fn assert_close(what: &str, got: f64, want: f64, o: &McOutput) {
    assert!(
        (got - want).abs() <= o.tolerance,
        "{what}: {got} vs {want} (δ = {})",
        o.tolerance
    );
}

#[test]
fn scaled_and_shifted_t_for_type_a() {
    // §6.4.9: x + u·t_ν with ν = 5: standard deviation u·√(5/3), 95 % interval ±2.5706·u
    // (a normal draw would give u and ±1.96·u, off by 0.2 and 0.45).
    let o = identity(InputQuantity::type_a("X", 10.0, 0.74, Dof::Finite(5.0)));
    assert_eq!(o.tolerance, 0.005);
    assert_close(
        "u",
        o.standard_uncertainty,
        0.74 * (5.0f64 / 3.0).sqrt(),
        &o,
    );
    assert_close(
        "low",
        o.coverage_interval.0,
        10.0 - 0.74 * 2.570_581_835_636_315,
        &o,
    );
    assert_close(
        "high",
        o.coverage_interval.1,
        10.0 + 0.74 * 2.570_581_835_636_315,
        &o,
    );
}

#[test]
fn rectangular() {
    // §6.4.2: half-width a = 1.65: u = a/√3, 95 % interval ±0.95·a.
    let o = identity(InputQuantity::rectangular("X", 1.0, 1.65));
    assert_eq!(o.tolerance, 0.005);
    assert_close("mean", o.estimate, 1.0, &o);
    assert_close("u", o.standard_uncertainty, 1.65 / 3f64.sqrt(), &o);
    assert_close("low", o.coverage_interval.0, 1.0 - 0.95 * 1.65, &o);
    assert_close("high", o.coverage_interval.1, 1.0 + 0.95 * 1.65, &o);
}

#[test]
fn normal_and_constant() {
    let o = identity(InputQuantity::normal("X", -3.0, 0.96));
    assert_close("u", o.standard_uncertainty, 0.96, &o);
    assert_close(
        "low",
        o.coverage_interval.0,
        -3.0 - 0.96 * 1.959_963_984_540_054,
        &o,
    );
    assert_close(
        "high",
        o.coverage_interval.1,
        -3.0 + 0.96 * 1.959_963_984_540_054,
        &o,
    );
    let o = identity(InputQuantity::normal("X", 2.5, 0.0));
    assert_eq!(
        (o.estimate, o.standard_uncertainty, o.coverage_interval),
        (2.5, 0.0, (2.5, 2.5))
    );
}

#[test]
fn a_t_without_variance_settles_on_its_coverage_interval() {
    // ν = 2: the t has no variance, so the batches' standard deviations never settle; the
    // adaptive procedure waits on the coverage limits only and stops (it used to run to the
    // 10⁷ cap and fail). The 95 % interval is ±4.3027·u.
    let o = identity(InputQuantity::type_a("X", 10.0, 0.74, Dof::Finite(2.0)));
    assert!(o.heavy_tailed);
    let half = 4.302_652_7 * 0.74;
    let tolerance = 0.02 * half;
    assert!(
        (o.coverage_interval.0 - (10.0 - half)).abs() < tolerance,
        "{:?}",
        o.coverage_interval
    );
    assert!(
        (o.coverage_interval.1 - (10.0 + half)).abs() < tolerance,
        "{:?}",
        o.coverage_interval
    );
    // ν = 3 has a variance: the usual procedure.
    let o = identity(InputQuantity::type_a("X", 10.0, 0.74, Dof::Finite(3.0)));
    assert!(!o.heavy_tailed);
}
