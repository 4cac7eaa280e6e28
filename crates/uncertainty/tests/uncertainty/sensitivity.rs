//! Sensitivity coefficients computed through the model match the analytic derivatives.

use approx::assert_relative_eq;
use uncertainty::{Dof, GumOptions, InputQuantity, Inputs, gum, model_fn};

/// `Y1 = X1·exp(X2)/X3`, `Y2 = sin(X1·X3) + X2³·X4`, `Y3 = √X4 · ln X1`.
fn derivatives(x: &[f64]) -> [[f64; 4]; 3] {
    let (x1, x2, x3, x4) = (x[0], x[1], x[2], x[3]);
    let e = x2.exp();
    let c = (x1 * x3).cos();
    [
        [e / x3, x1 * e / x3, -x1 * e / (x3 * x3), 0.0],
        [x3 * c, 3.0 * x2 * x2 * x4, x1 * c, x2.powi(3)],
        [x4.sqrt() / x1, 0.0, 0.0, x1.ln() / (2.0 * x4.sqrt())],
    ]
}

fn check(values: [f64; 4], uncertainties: [f64; 4]) -> f64 {
    let inputs = Inputs::new(
        (0..4)
            .map(|i| {
                InputQuantity::type_a(
                    format!("X{}", i + 1),
                    values[i],
                    uncertainties[i],
                    Dof::Finite(7.0),
                )
            })
            .collect(),
    )
    .unwrap();
    let model = model_fn(["Y1", "Y2", "Y3"], |x, y| {
        y[0] = x[0] * x[1].exp() / x[2];
        y[1] = (x[0] * x[2]).sin() + x[1].powi(3) * x[3];
        y[2] = x[3].sqrt() * x[0].ln();
        Ok(())
    });
    let g = gum(&model, &inputs, &GumOptions::default()).unwrap();
    let exact = derivatives(&values);
    let mut worst: f64 = 0.0;
    for (out, row) in g.outputs.iter().zip(exact) {
        for (c, d) in out.contributions.iter().zip(row) {
            if d == 0.0 {
                // A derivative that vanishes identically: central differences cancel exactly.
                assert_eq!(c.sensitivity, 0.0, "{} / {}", out.name, c.input);
            } else {
                assert_relative_eq!(c.sensitivity, d, max_relative = 1e-8);
                worst = worst.max(((c.sensitivity - d) / d).abs());
            }
        }
    }
    worst
}

#[test]
fn analytic_derivatives_with_percent_level_uncertainties() {
    // u/x of 0.5 % to 5 %: the step is u/100 (rounded to a power of two).
    let worst = check([1.3, 0.4, 2.1, 3.0], [0.01, 0.02, 0.05, 0.015]);
    // Measured: 3e-12.
    assert!(worst < 1e-10, "worst relative error {worst:e}");
}

#[test]
fn analytic_derivatives_with_tiny_uncertainties() {
    // u/x of 1e-9: the step floor 1e-5·|x| keeps rounding out of the difference.
    let worst = check([1.3, 0.4, 2.1, 3.0], [1.3e-9, 4e-10, 2.1e-9, 3e-9]);
    // Measured: 1.2e-11.
    assert!(worst < 1e-10, "worst relative error {worst:e}");
}

#[test]
fn analytic_derivatives_with_large_uncertainties() {
    // u/x up to 20 %: the step u/100 is still small enough for the h⁴ truncation.
    let worst = check([1.3, 0.4, 2.1, 3.0], [0.2, 0.08, 0.3, 0.6]);
    // Measured: 5.9e-11.
    assert!(worst < 1e-10, "worst relative error {worst:e}");
}
