//! Parameter structs in RON scenario files.

use kinematics::{Centrifuge, ErrorMotion, ErrorMotionSpec, PhysicalImbalance};

#[test]
fn centrifuge_round_trips_through_ron() {
    let c = crate::centrifuge(crate::errors());
    let text = ron::ser::to_string_pretty(&c, ron::ser::PrettyConfig::default()).unwrap();
    assert!(text.contains("c_r_m_s2"));
    assert!(text.contains("latitude_deg"));
    let back: Centrifuge = ron::from_str(&text).unwrap();
    assert_eq!(back, c);
}

#[test]
fn missing_coefficients_default_to_zero_and_unknown_fields_are_rejected() {
    let e: ErrorMotion = ron::from_str("(c_r_m_s2: -4.05e-8, dr_xs_m: 5.6e-6)").unwrap();
    assert_eq!(
        e,
        ErrorMotion {
            c_r_m_s2: -4.05e-8,
            dr_xs_m: 5.6e-6,
            ..ErrorMotion::ZERO
        }
    );
    assert!(ron::from_str::<ErrorMotion>("(c_r: 1.0)").is_err());
}

#[test]
fn spec_in_either_form() {
    let coeffs: ErrorMotionSpec = ron::from_str("Coefficients((c_r_m_s2: 1.6e-6))").unwrap();
    assert_eq!(coeffs.resolve().unwrap().c_r_m_s2, 1.6e-6);
    let phys: ErrorMotionSpec = ron::from_str(
        "Physical((mass_kg: 0.2, mass_radius_m: 0.5, radial_stiffness_n_m: 2e9, \
         angular_stiffness_n_m_rad: 1e9, arm_m: 0.1, imbalance_azimuth_deg: 90.0))",
    )
    .unwrap();
    let e = phys.resolve().unwrap();
    assert!(e.c_r_m_s2.abs() < 1e-25);
    assert!((e.c_r_y_m_s2 - 0.5 * 0.2 / 2e9).abs() < 1e-25);
    // leaning towards +Y2 is a negative rotation about X2
    assert!((e.c_phi_x_s2 + 0.5 * 0.2 * 0.1 / 1e9).abs() < 1e-25);
    let bad = ErrorMotionSpec::Physical(PhysicalImbalance {
        angular_stiffness_n_m_rad: -1.0,
        ..PhysicalImbalance::default()
    });
    assert!(matches!(
        bad.resolve(),
        Err(kinematics::KinematicsError::NotPositive {
            field: "angular_stiffness_n_m_rad",
            ..
        })
    ));
}
