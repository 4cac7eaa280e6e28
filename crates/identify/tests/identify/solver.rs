//! Behaviour of the general solver: typed errors, ill-conditioning reports, invariants.

use approx::assert_relative_eq;
use identify::{
    Design, FitWarning, IdentifyError, LstsqOptions, SolverPath, lstsq, lstsq_design, lstsq_with,
};
use nalgebra::DMatrix;
use proptest::prelude::*;

fn line_design(m: usize) -> DMatrix<f64> {
    DMatrix::from_fn(m, 2, |i, j| if j == 0 { 1.0 } else { i as f64 })
}

#[test]
fn rank_deficient_design_is_a_typed_error() {
    // Third column = 2·first − 0.5·second: rank 2 of 3.
    let d = DMatrix::from_fn(6, 3, |i, j| match j {
        0 => 1.0,
        1 => i as f64,
        _ => 2.0 - 0.5 * i as f64,
    });
    let y = [1.0, 2.0, 2.5, 4.0, 5.5, 6.0];
    match lstsq(&d, &y) {
        Err(IdentifyError::RankDeficient {
            rank,
            unknowns,
            tolerance,
        }) => {
            assert_eq!((rank, unknowns), (2, 3));
            assert_relative_eq!(tolerance, 6.0 * f64::EPSILON, max_relative = 1e-15);
        }
        other => panic!("expected RankDeficient, got {other:?}"),
    }
    // An all-zero column is rank deficient too.
    let d = DMatrix::from_fn(5, 2, |i, j| if j == 0 { i as f64 } else { 0.0 });
    assert!(matches!(
        lstsq(&d, &[1.0, 2.0, 3.0, 4.0, 5.0]),
        Err(IdentifyError::RankDeficient {
            rank: 1,
            unknowns: 2,
            ..
        })
    ));
}

#[test]
fn non_finite_input_is_a_typed_error() {
    let mut d = line_design(5);
    let y = [1.0, 2.0, 3.0, 4.0, 5.0];
    d[(3, 1)] = f64::NAN;
    assert_eq!(
        lstsq(&d, &y),
        Err(IdentifyError::NonFinite {
            row: 3,
            column: Some(1)
        })
    );
    let d = line_design(5);
    let y = [1.0, 2.0, f64::INFINITY, 4.0, 5.0];
    assert_eq!(
        lstsq(&d, &y),
        Err(IdentifyError::NonFinite {
            row: 2,
            column: None
        })
    );
    // A power that overflows is reported at its entry.
    let design = Design::powers(&[1.0, 2.0, 1e200, 3.0], &[0, 2]);
    assert_eq!(
        lstsq_design(&design, &[1.0, 2.0, 3.0, 4.0], &LstsqOptions::default()),
        Err(IdentifyError::NonFinite {
            row: 2,
            column: Some(1)
        })
    );
}

#[test]
fn too_few_observations_is_a_typed_error() {
    let d = line_design(2);
    assert_eq!(
        lstsq(&d, &[1.0, 2.0]),
        Err(IdentifyError::TooFewObservations {
            observations: 2,
            unknowns: 2
        })
    );
}

/// Two columns that differ by one unit in the last place in some rows: condition number near
/// 1/ε. The default rank tolerance rejects it; with the tolerance switched off the fit goes
/// through, and the refinement reports that it could not establish the digits.
#[test]
fn hopeless_conditioning_is_reported_not_hidden() {
    let m = 12;
    let d = DMatrix::from_fn(m, 2, |i, j| {
        let x = 1.0 + i as f64 / 10.0;
        if j == 0 {
            x
        } else {
            x * (1.0 + f64::EPSILON * ((i % 3) as f64 - 1.0))
        }
    });
    let y: Vec<f64> = (0..m).map(|i| (i as f64).sin()).collect();
    assert!(matches!(
        lstsq(&d, &y),
        Err(IdentifyError::RankDeficient {
            rank: 1,
            unknowns: 2,
            ..
        })
    ));
    let options = LstsqOptions {
        rank_tolerance: Some(0.0),
        ..LstsqOptions::default()
    };
    let fit = lstsq_with(&d, &y, &options).unwrap();
    assert!(
        fit.condition_number > 1e14,
        "condition {}",
        fit.condition_number
    );
    assert!(
        fit.warnings
            .iter()
            .any(|w| matches!(w, FitWarning::RefinementNotConverged { .. })),
        "warnings {:?}",
        fit.warnings
    );
}

#[test]
fn refinement_can_be_switched_off() {
    let options = LstsqOptions {
        refine: false,
        ..LstsqOptions::default()
    };
    let fit = lstsq_with(&line_design(5), &[1.0, 3.0, 5.0, 7.0, 9.5], &options).unwrap();
    assert_eq!(fit.path, SolverPath::ScaledColPivQr);
    assert_eq!(fit.refinement_iterations, 0);
    let fit = lstsq(&line_design(5), &[1.0, 3.0, 5.0, 7.0, 9.5]).unwrap();
    assert_eq!(fit.path, SolverPath::RefinedScaledColPivQr);
    assert!(fit.refinement_iterations >= 1);
}

proptest! {
    /// A noise-free polynomial of degree ≤ 5 on an offset interval is recovered; with noise,
    /// the residuals are orthogonal to every column (the normal equations hold).
    #[test]
    fn polynomial_coefficients_are_recovered(
        coefficients in prop::collection::vec(-10.0..10.0_f64, 1..=6),
        offset in -50.0..50.0_f64,
        width in 0.5..20.0_f64,
        noise in prop::collection::vec(-1.0..1.0_f64, 30),
    ) {
        let n = coefficients.len();
        let x: Vec<f64> = (0..30).map(|i| offset + width * f64::from(i) / 29.0).collect();
        let exponents: Vec<u32> = (0..n as u32).collect();
        let design = Design::powers(&x, &exponents);
        let xm = design.to_matrix();
        let exact: Vec<f64> = (0..30)
            .map(|i| (0..n).map(|j| coefficients[j] * xm[(i, j)]).sum())
            .collect();
        let fit = lstsq_design(&design, &exact, &LstsqOptions::default()).unwrap();
        // y was rounded to doubles, a relative perturbation ε: in the column-scaled coordinates
        // z_j = β_j·‖x_j‖ the error is bounded by a modest multiple of κ·ε·‖z‖.
        let norms: Vec<f64> = (0..n).map(|j| xm.column(j).norm()).collect();
        let z_norm = (0..n).map(|j| (coefficients[j] * norms[j]).abs()).fold(0.0_f64, f64::max);
        let y_norm = exact.iter().map(|v| v * v).sum::<f64>().sqrt();
        let bound = 64.0 * fit.condition_number * f64::EPSILON * z_norm.max(y_norm);
        for j in 0..n {
            let err = (fit.coefficients[j] - coefficients[j]).abs() * norms[j];
            prop_assert!(err <= bound, "column {j}: {} vs {}, cond {:e}",
                fit.coefficients[j], coefficients[j], fit.condition_number);
        }
        let noisy: Vec<f64> = exact.iter().zip(&noise).map(|(e, n)| e + n).collect();
        let fit = lstsq_design(&design, &noisy, &LstsqOptions::default()).unwrap();
        for j in 0..n {
            let dot: f64 = (0..30).map(|i| xm[(i, j)] * fit.residuals[i]).sum();
            let norm: f64 = (0..30).map(|i| xm[(i, j)].abs() * fit.residuals[i].abs()).sum();
            prop_assert!(dot.abs() <= 1e-12 * norm.max(f64::MIN_POSITIVE));
        }
    }
}

#[test]
fn an_unrefined_covariance_leaves_the_values_bit_for_bit_and_the_covariance_close() {
    // a cubic in x ∈ [1, 3] with wide column scales (as the centrifuge's powers of ω are):
    // condition about 1e4 after scaling
    let m = 40;
    let x: Vec<f64> = (0..m)
        .map(|i| 1.0 + 2.0 * i as f64 / (m - 1) as f64)
        .collect();
    let d = DMatrix::from_fn(m, 4, |i, j| x[i].powi(j as i32) * 10f64.powi(3 * j as i32));
    let y: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(i, x)| {
            0.3 + 1.7 * x - 0.2 * x * x + 0.01 * x.powi(3) + 1e-3 * ((i * 7 % 11) as f64 - 5.0)
        })
        .collect();
    let full = lstsq_with(&d, &y, &LstsqOptions::default()).unwrap();
    let values = lstsq_with(
        &d,
        &y,
        &LstsqOptions {
            refine_covariance: false,
            ..LstsqOptions::default()
        },
    )
    .unwrap();
    assert_eq!(values.coefficients, full.coefficients);
    assert_eq!(values.residuals, full.residuals);
    assert_eq!(values.path, SolverPath::RefinedScaledColPivQr);
    assert!(values.warnings.is_empty(), "{:?}", values.warnings);
    for (a, b) in values.covariance.iter().zip(full.covariance.iter()) {
        assert_relative_eq!(*a, *b, max_relative = 1e-9, epsilon = 1e-300);
    }
}
