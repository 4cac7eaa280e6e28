//! Bad input is a typed error naming the field.

use balance::{
    BalanceError, Fields, ProbePhase, ProbePoint, Requirement, TrialMass, fit_phasors,
    influence_correction,
};
use harmonics::{LeverGeometry, ProbeDirection};

use crate::common::{context, plane};

const LEVER: LeverGeometry = LeverGeometry {
    pivot_to_probe_mm: 700.0,
    probe_to_piga_mm: 510.0,
    probe_direction: ProbeDirection::AgainstO1X1,
};

fn points(d_um_s2: (f64, f64), sigma: f64) -> Vec<ProbePoint> {
    [10.0_f64, 60.0, 110.0, 160.0, 200.0]
        .iter()
        .map(|deg| {
            let w = deg.to_radians();
            // drift x + iy = S + D·ω² at the probe plane; against O1X1: dc1 = −x, ds1 = y
            let (x, y) = (2.0 + d_um_s2.0 * w * w, -1.0 + d_um_s2.1 * w * w);
            ProbePoint {
                rate_rad_s: w,
                dc1_um: -x,
                ds1_um: y,
                sigma_um: Some(sigma),
            }
        })
        .collect()
}

fn phase<'a>(field: &'a str, points: &'a [ProbePoint]) -> ProbePhase<'a> {
    ProbePhase {
        field,
        points,
        lever: LEVER,
    }
}

const TRIAL: TrialMass = TrialMass {
    mass_kg: 1.0,
    radius_m: 2.0,
    azimuth_deg: 30.0,
};

#[test]
fn a_trial_phase_equal_to_the_initial_one_is_a_singular_influence_coefficient() {
    let p = points((0.9, 0.2), 1e-3);
    let f = fit_phasors(&phase("balance.initial", &p)).unwrap();
    let t = fit_phasors(&phase("balance.trial", &p)).unwrap();
    let fields = Fields {
        trial: "balance.trial",
        ..Fields::default()
    };
    let err = influence_correction(&f, &t, &TRIAL, &plane(), &context(), &fields).unwrap_err();
    assert!(
        matches!(&err, BalanceError::SingularInfluence { field, .. } if field == "balance.trial"),
        "{err}"
    );
}

#[test]
fn a_trial_mass_of_zero_names_the_field() {
    let f = fit_phasors(&phase("initial", &points((0.9, 0.2), 1e-3))).unwrap();
    let t = fit_phasors(&phase("trial", &points((1.4, 0.2), 1e-3))).unwrap();
    let fields = Fields {
        trial_mass: "balance.trial_mass",
        ..Fields::default()
    };
    let zero = TrialMass {
        mass_kg: 0.0,
        ..TRIAL
    };
    let err = influence_correction(&f, &t, &zero, &plane(), &context(), &fields).unwrap_err();
    assert_eq!(
        err,
        BalanceError::InvalidField {
            field: "balance.trial_mass.mass_kg".to_owned(),
            value: 0.0,
            requirement: Requirement::Positive,
        }
    );
}

#[test]
fn fewer_than_three_rates_names_the_phase() {
    let p = points((0.9, 0.2), 1e-3);
    let err = fit_phasors(&phase("balance.initial", &p[..2])).unwrap_err();
    assert_eq!(
        err,
        BalanceError::TooFewRates {
            field: "balance.initial.points".to_owned(),
            got: 2,
            need: 3,
        }
    );
}

#[test]
fn non_finite_and_duplicate_points_name_the_point() {
    let mut p = points((0.9, 0.2), 1e-3);
    p[3].ds1_um = f64::NAN;
    let err = fit_phasors(&phase("x", &p)).unwrap_err();
    assert!(
        matches!(&err, BalanceError::InvalidField { field, .. } if field == "x.points[3].ds1_um")
    );
    let mut p = points((0.9, 0.2), 1e-3);
    p[2].rate_rad_s = p[0].rate_rad_s;
    let err = fit_phasors(&phase("x", &p)).unwrap_err();
    assert!(
        matches!(&err, BalanceError::DuplicateRate { field, .. } if field == "x.points[2].rate_rad_s")
    );
}

#[test]
fn exact_data_gives_the_exact_phasors() {
    let p = points((0.9, 0.2), 1e-3);
    let f = fit_phasors(&phase("x", &p)).unwrap();
    let ratio = 1210.0 / 700.0;
    approx::assert_relative_eq!(f.static_probe_um.x, 2.0, max_relative = 1e-12);
    approx::assert_relative_eq!(f.static_probe_um.y, -1.0, max_relative = 1e-12);
    approx::assert_relative_eq!(f.dynamic_piga_um_s2.x, 0.9 * ratio, max_relative = 1e-12);
    approx::assert_relative_eq!(f.dynamic_piga_um_s2.y, 0.2 * ratio, max_relative = 1e-12);
    // noise-free: χ² ≈ 0, so σ stays the points' (never shrunk)
    assert!(f.reduced_chi.unwrap() < 1e-6);
    assert!(f.dynamic_probe_um_s2.covariance[0][0] > 0.0);
}
