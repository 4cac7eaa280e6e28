//! JCGM 101 §8 tells a nonlinear model whose linearisation fails from one where it holds.

use uncertainty::{
    GumOptions, InputQuantity, Inputs, McOptions, gum, model_fn, monte_carlo, validate,
};

fn ratio(u_denominator: f64) -> uncertainty::Validation {
    // Y = X1/X2, X1 ~ N(1, 0.1²), X2 rectangular about 1 with standard uncertainty u.
    let inputs = Inputs::new(vec![
        InputQuantity::normal("X1", 1.0, 0.1),
        InputQuantity::rectangular("X2", 1.0, u_denominator * 3f64.sqrt()),
    ])
    .unwrap();
    let model = model_fn(["Y"], |x, y| {
        y[0] = x[0] / x[1];
        Ok(())
    });
    let g = gum(&model, &inputs, &GumOptions::default()).unwrap();
    let mc = monte_carlo(&model, &inputs, &McOptions::default()).unwrap();
    validate(&g, &mc, 2).unwrap()
}

#[test]
fn ratio_with_a_30_percent_denominator_is_not_validated() {
    // GUM: y = 1, u_c = √(0.1² + 0.3²) = 0.316, interval [0.38, 1.62]. The model values
    // are skewed (E[1/X2] = ln(1.52/0.48)/1.04 = 1.108): the Monte Carlo interval sits
    // higher, by far more than δ = 0.005.
    let v = ratio(0.3);
    let o = &v.outputs[0];
    assert!(!o.agrees, "{o:?}");
    assert_eq!(o.tolerance, 0.005);
    assert!(
        o.d_low > 10.0 * o.tolerance && o.d_high > 10.0 * o.tolerance,
        "{o:?}"
    );
}

#[test]
fn ratio_with_a_1_percent_denominator_is_validated() {
    // The same model nearly linear over the inputs' spread: the two intervals agree.
    let v = ratio(0.01);
    assert!(v.all_agree(), "{v:?}");
}

#[test]
fn product_of_zero_mean_inputs_is_not_validated() {
    // Y = X1·X2 with x1 = x2 = 0.1 and u = 1: the sensitivities are 0.1, so the GUM gives
    // u_c = 0.14, while the product's standard deviation is
    // √(x1²u2² + x2²u1² + u1²u2²) = √1.02 = 1.01.
    let inputs = Inputs::new(vec![
        InputQuantity::normal("X1", 0.1, 1.0),
        InputQuantity::normal("X2", 0.1, 1.0),
    ])
    .unwrap();
    let model = model_fn(["Y"], |x, y| {
        y[0] = x[0] * x[1];
        Ok(())
    });
    let g = gum(&model, &inputs, &GumOptions::default()).unwrap();
    let mc = monte_carlo(&model, &inputs, &McOptions::default()).unwrap();
    assert!((g.outputs[0].standard_uncertainty - 0.02f64.sqrt()).abs() < 1e-9);
    let u = mc.outputs[0].standard_uncertainty;
    assert!((u - 1.02f64.sqrt()).abs() <= mc.outputs[0].tolerance, "{u}");
    let v = validate(&g, &mc, 2).unwrap();
    assert!(!v.outputs[0].agrees, "{v:?}");
}
