//! Welch–Satterthwaite (JCGM 100 eq. G.2b) and the coverage factor.

use approx::assert_relative_eq;
use uncertainty::{
    Dof, DofRounding, GumOptions, InputQuantity, Inputs, coverage_factor, gum, model_fn,
};

fn sum3() -> impl uncertainty::MeasurementModel {
    model_fn(["Y"], |x, y| {
        y[0] = x.iter().sum();
        Ok(())
    })
}

#[test]
fn two_type_a_inputs_and_one_type_b() {
    // u1 = 0.3 (ν = 4), u2 = 0.4 (ν = 9), u3 = 0.5 (ν = ∞), Y = X1 + X2 + X3.
    // By hand: u_c² = 0.09 + 0.16 + 0.25 = 0.5; ν_eff = 0.5² / (0.3⁴/4 + 0.4⁴/9)
    //        = 0.25 / (0.002025 + 0.0028444…) = 51.34056; t_0.975(51.34) = 2.00726.
    let inputs = Inputs::new(vec![
        InputQuantity::type_a("X1", 10.0, 0.3, Dof::Finite(4.0)),
        InputQuantity::type_a("X2", 20.0, 0.4, Dof::Finite(9.0)),
        InputQuantity::normal("X3", 30.0, 0.5),
    ])
    .unwrap();
    let g = gum(&sum3(), &inputs, &GumOptions::default()).unwrap();
    let y = &g.outputs[0];
    assert_relative_eq!(y.standard_uncertainty, 0.5f64.sqrt(), max_relative = 1e-10);
    let Dof::Finite(nu) = y.dof else {
        panic!("ν_eff should be finite")
    };
    assert_relative_eq!(nu, 51.340_559_041_642_9, max_relative = 1e-9);
    assert_relative_eq!(
        y.coverage_factor,
        2.007_260_484_182_316,
        max_relative = 1e-9
    );
    assert_relative_eq!(
        y.expanded_uncertainty,
        2.007_260_484_182_316 * 0.5f64.sqrt(),
        max_relative = 1e-9
    );

    // Truncated to 51 (JCGM 100 G.4.1 note 1): t_0.975(51) = 2.00758.
    let options = GumOptions {
        dof_rounding: DofRounding::Truncate,
        ..GumOptions::default()
    };
    let t = gum(&sum3(), &inputs, &options).unwrap();
    assert_eq!(t.outputs[0].dof, y.dof, "the reported ν_eff is not rounded");
    assert_relative_eq!(
        t.outputs[0].coverage_factor,
        2.007_583_770_315_836,
        max_relative = 1e-9
    );
}

#[test]
fn infinite_terms_drop_out_and_all_infinite_gives_infinity() {
    let inputs = Inputs::new(vec![
        InputQuantity::normal("X1", 1.0, 0.3),
        InputQuantity::rectangular("X2", 1.0, 0.2),
        InputQuantity::normal("X3", 1.0, 0.1),
    ])
    .unwrap();
    let y = &gum(&sum3(), &inputs, &GumOptions::default())
        .unwrap()
        .outputs[0];
    assert_eq!(y.dof, Dof::Infinite);
    assert_relative_eq!(
        y.coverage_factor,
        1.959_963_984_540_054,
        max_relative = 1e-14
    );

    // One finite term alone: ν_eff = ν·(u_c²/u_1²)² — here 3·(0.14/0.09)² = 7.26.
    let inputs = Inputs::new(vec![
        InputQuantity::type_a("X1", 1.0, 0.3, Dof::Finite(3.0)),
        InputQuantity::normal("X2", 1.0, 0.2),
        InputQuantity::normal("X3", 1.0, 0.1),
    ])
    .unwrap();
    let y = &gum(&sum3(), &inputs, &GumOptions::default())
        .unwrap()
        .outputs[0];
    assert_relative_eq!(
        y.dof.finite().unwrap(),
        3.0 * (0.14f64 / 0.09).powi(2),
        max_relative = 1e-9
    );
}

#[test]
fn a_model_that_ignores_its_inputs_has_zero_uncertainty_and_infinite_dof() {
    let inputs = Inputs::new(vec![InputQuantity::type_a("X", 1.0, 0.3, Dof::Finite(3.0))]).unwrap();
    let model = model_fn(["Y"], |_, y| {
        y[0] = 42.0;
        Ok(())
    });
    let y = &gum(&model, &inputs, &GumOptions::default())
        .unwrap()
        .outputs[0];
    assert_eq!(y.standard_uncertainty, 0.0);
    assert_eq!(y.expanded_uncertainty, 0.0);
    assert_eq!(y.dof, Dof::Infinite);
    assert_eq!(y.contributions[0].variance_percent, 0.0);
}

#[test]
fn coverage_factors_from_the_t_table() {
    for (nu, k) in [
        (1.0, 12.706),
        (2.0, 4.303),
        (5.0, 2.571),
        (10.0, 2.228),
        (30.0, 2.042),
        (100.0, 1.984),
    ] {
        let got = coverage_factor(0.95, Dof::Finite(nu)).unwrap();
        assert!((got - k).abs() < 5e-4, "ν = {nu}: {got} vs {k}");
    }
    assert!((coverage_factor(0.95, Dof::Infinite).unwrap() - 1.96).abs() < 5e-5);
}
