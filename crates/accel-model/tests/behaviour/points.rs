//! The per-rate data a simulator needs, its errors and its serialisation.

use accel_model::{AccelModelError, PigaCoefficients, RatePoint, rate_points};
use approx::assert_relative_eq;
use kinematics::Chain;
use proptest::prelude::*;

use crate::{PIGA, centrifuge, errors, paper_rates};

#[test]
fn rate_points_carry_exact_mean_inputs() {
    let c = centrifuge(errors());
    let rates = paper_rates();
    let pts = rate_points(&c, &PIGA, &rates).unwrap();
    assert_eq!(pts.len(), rates.len());
    for (p, &w) in pts.iter().zip(&rates) {
        assert_eq!(p.rate_rad_s, w);
        let m = Chain::new(&c, w).unwrap().mean_inputs(3).unwrap();
        assert_relative_eq!(p.a_x_g, m.a_x_g(), max_relative = 1e-14);
        assert_relative_eq!(p.omega_i_rad_s, m.omega_i_rad_s(), max_relative = 1e-12);
    }
    assert_relative_eq!(pts[5].rate_deg_s(), 200.1234, max_relative = 1e-14);
}

#[test]
fn bad_inputs_are_typed_errors() {
    let c = centrifuge(errors());
    assert_eq!(rate_points(&c, &PIGA, &[]), Err(AccelModelError::NoRates));
    assert!(matches!(
        rate_points(&c, &PIGA, &[1.0, f64::NAN]),
        Err(AccelModelError::NonFiniteRate { index: 1, .. })
    ));
    let bad = PigaCoefficients {
        k2_rad_s_g2: f64::INFINITY,
        ..PIGA
    };
    assert!(matches!(
        rate_points(&c, &bad, &[1.0]),
        Err(AccelModelError::NonFinite {
            field: "k2_rad_s_g2",
            ..
        })
    ));
    let mut c0 = c;
    c0.radius_m = -1.0;
    assert!(matches!(
        rate_points(&c0, &PIGA, &[1.0]),
        Err(AccelModelError::Kinematics(
            kinematics::KinematicsError::NotPositive {
                field: "radius_m",
                ..
            }
        ))
    ));
    let chain = Chain::new(&c, 1.0).unwrap();
    assert_eq!(
        accel_model::mean_output_rad_s(&chain, &PIGA, 6),
        Err(AccelModelError::Kinematics(
            kinematics::KinematicsError::TooFewQuadraturePoints {
                points: 6,
                highest_harmonic: 3,
                need: 7
            }
        ))
    );
}

#[test]
fn serialisation_round_trips() {
    let p = rate_points(&centrifuge(errors()), &PIGA, &[2.0]).unwrap()[0];
    let json = serde_json::to_string(&p).unwrap();
    for key in ["rate_rad_s", "output_rad_s", "a_x_g", "omega_i_rad_s"] {
        assert!(json.contains(key), "{json}");
    }
    let back: RatePoint = serde_json::from_str(&json).unwrap();
    assert_eq!(back, p);
    let piga: PigaCoefficients =
        ron::from_str("(k0_rad_s: 1e-5, k1_rad_s_g: 0.56, k2_rad_s_g2: 2e-6, k3_rad_s_g3: 1e-7)")
            .unwrap();
    assert_eq!(piga, PIGA);
    assert!(ron::from_str::<PigaCoefficients>("(k0_rad_s: 1e-5)").is_err());
}

proptest! {
    /// For a linear PIGA the mean output is the model at the mean inputs, whatever the error
    /// motion and rate (the mean is linear); for a non-linear one it is not in general.
    #[test]
    fn linear_piga_mean_is_model_of_mean_inputs(
        s in 0.0..1e3f64,
        w in -4.0..4.0f64,
        k0 in -1e-4..1e-4f64,
        k1 in 0.1..1.0f64,
    ) {
        let piga = PigaCoefficients { k0_rad_s: k0, k1_rad_s_g: k1, k2_rad_s_g2: 0.0, k3_rad_s_g3: 0.0 };
        let p = rate_points(&centrifuge(errors().scaled(s)), &piga, &[w]).unwrap()[0];
        let model = piga.output_rad_s(p.inputs());
        prop_assert!((p.output_rad_s - model).abs() < 1e-14 * (1.0 + model.abs()));
    }
}
