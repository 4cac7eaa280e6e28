//! Two probe planes through the simulator: static and couple unbalance recovered from a
//! spindle with masses at two heights, and the two-plane correction's closed loop.

use balance::{
    AxisMotion, CorrectionPlane, HeightPlane, ProbePhase, ProbePlane, Stiffness, TrialMass,
    TwoPlaneFields, axis_motion, fit_phasors, static_couple, two_plane_influence_correction,
    two_plane_stiffness_correction,
};
use harmonics::{LeverGeometry, ProbeDirection};
use kinematics::{ErrorMotionSpec, ImbalanceMass};
use simulate::{LoadedScenario, Scenario, SecondProbeSpec, simulate};

use crate::common::{context, recording_points, scenario, with_masses};

/// The second probe: 600 mm below the first (1110 mm below the PIGA plane).
const SECOND_BELOW_PIGA_MM: f64 = 1110.0;
/// Correction planes A (the fixture mass's, 0.15 m above the PIGA plane) and B (0.6 m below).
const HEIGHTS_M: [f64; 2] = [0.15, -0.6];
const K_R: f64 = 5.0e7;
const K_THETA: f64 = 2.4e8;

/// A mass at height −0.6 m besides the fixture's 32 kg at 2.5 m, 0°, +0.15 m: the spindle has
/// both static and couple unbalance.
const LOWER: ImbalanceMass = ImbalanceMass {
    mass_kg: 20.0,
    radius_m: 2.5,
    azimuth_deg: 120.0,
    arm_m: -0.6,
};

fn two_probe(seed: u64, masses: &[ImbalanceMass]) -> LoadedScenario {
    scenario(|s: &mut Scenario| {
        s.seed = seed;
        s.min_duration_s = 36.0;
        s.second_probe = Some(SecondProbeSpec {
            probe_to_piga_mm: SECOND_BELOW_PIGA_MM,
            probe_direction: ProbeDirection::AlongO1X1,
        });
        with_masses(s, &[LOWER]);
        with_masses(s, masses);
    })
}

/// The two probes' phasor fits split into translation and tilt.
fn motion(loaded: &LoadedScenario) -> AxisMotion {
    let sim = simulate(loaded).expect("simulates");
    let lever = loaded.scenario.probe.lever;
    let first_points = recording_points(&sim.recordings, &sim.truth.rates);
    let second_points = recording_points(&sim.second_recordings, &sim.truth.rates);
    let second_lever = LeverGeometry {
        // the cone's pivot is not used: only the probe-plane phasors are
        pivot_to_probe_mm: 2000.0,
        probe_to_piga_mm: SECOND_BELOW_PIGA_MM,
        probe_direction: ProbeDirection::AlongO1X1,
    };
    let f1 = fit_phasors(&ProbePhase {
        field: "first",
        points: &first_points,
        lever,
    })
    .expect("fits");
    let f2 = fit_phasors(&ProbePhase {
        field: "second",
        points: &second_points,
        lever: second_lever,
    })
    .expect("fits");
    axis_motion(
        &ProbePlane {
            fit: &f1,
            height_m: -lever.probe_to_piga_mm * 1e-3,
        },
        &ProbePlane {
            fit: &f2,
            height_m: -SECOND_BELOW_PIGA_MM * 1e-3,
        },
        "second_probe",
    )
    .expect("two planes")
}

/// Σ m·r·e^{iθ} and Σ m·r·l·e^{iθ} of the scenario's masses.
fn truth(loaded: &LoadedScenario) -> ([f64; 2], [f64; 2]) {
    let ErrorMotionSpec::Physical(p) = &loaded.scenario.error_motion else {
        panic!("physical");
    };
    let mut all = vec![ImbalanceMass {
        mass_kg: p.mass_kg,
        radius_m: p.mass_radius_m,
        azimuth_deg: p.imbalance_azimuth_deg,
        arm_m: p.arm_m,
    }];
    all.extend_from_slice(&p.masses);
    let (mut s, mut c) = ([0.0; 2], [0.0; 2]);
    for m in all {
        let (sn, cs) = m.azimuth_deg.to_radians().sin_cos();
        s[0] += m.mass_kg * m.radius_m * cs;
        s[1] += m.mass_kg * m.radius_m * sn;
        c[0] += m.mass_kg * m.radius_m * m.arm_m * cs;
        c[1] += m.mass_kg * m.radius_m * m.arm_m * sn;
    }
    (s, c)
}

fn planes() -> [HeightPlane; 2] {
    HEIGHTS_M.map(|height_m| HeightPlane {
        height_m,
        plane: CorrectionPlane {
            radius_m: 2.5,
            fixed_azimuths_deg: vec![],
        },
    })
}

/// Within `k` standard deviations along each axis (and a relative floor for exact data).
fn assert_close(what: &str, got: &balance::Phasor, want: [f64; 2], k: f64) {
    for (i, (g, w)) in [got.x, got.y].iter().zip(want).enumerate() {
        let sigma = got.covariance[i][i].sqrt();
        assert!(
            (g - w).abs() <= k * sigma + 1e-9 * w.abs(),
            "{what}[{i}]: {g} vs {w} (σ {sigma})"
        );
    }
}

#[test]
fn static_and_couple_unbalance_match_the_simulated_masses() {
    let loaded = two_probe(11, &[]);
    let m = motion(&loaded);
    let sc = static_couple(
        &m,
        &Stiffness {
            radial_n_m: K_R,
            angular_n_m_rad: K_THETA,
        },
        "balance",
    )
    .unwrap();
    let (s, c) = truth(&loaded);
    assert_close("static kg·m", &sc.static_kg_m, s, 3.0);
    assert_close("couple kg·m²", &sc.couple_kg_m2, c, 3.0);
    // the noise is small against both: these are real measurements, not zeros
    assert!(sc.static_kg_m.max_sigma() < 1e-3 * sc.static_kg_m.magnitude());
    assert!(sc.couple_kg_m2.max_sigma() < 1e-2 * sc.couple_kg_m2.magnitude());
    // the PIGA-plane translation is C_r of the truth, with no cone assumption
    let sim_c_r = loaded.error_motion.c_r_m_s2 * 1e6;
    let t = m.dynamic.a;
    assert!((t.x - sim_c_r).abs() < 3.0 * t.covariance[0][0].sqrt() + 1e-9);
    // a cone through one probe would misread it: the tilt is not the cone's
    let cone = m.dynamic_at_um_s2(-0.51).x * 1210.0 / 700.0;
    assert!((cone - sim_c_r).abs() > 100.0 * t.covariance[0][0].sqrt());
    // per rate, both probes give a translation and a tilt
    assert_eq!(m.per_rate.len(), loaded.scenario.rates_deg_s.len());
}

/// Before run, one trial run per plane, correction, check run: C_r at the PIGA plane.
fn influence_loop(seed: u64) -> (f64, f64, f64, f64, f64) {
    let before = two_probe(seed, &[]);
    let trial = |k: usize| TrialMass {
        mass_kg: 8.0,
        radius_m: 2.5,
        azimuth_deg: [90.0, -30.0][k],
    };
    let trial_run = |k: usize| {
        let t = trial(k);
        two_probe(
            seed + 1 + k as u64,
            &[ImbalanceMass {
                mass_kg: t.mass_kg,
                radius_m: t.radius_m,
                azimuth_deg: t.azimuth_deg,
                arm_m: HEIGHTS_M[k],
            }],
        )
    };
    let m0 = motion(&before);
    let ma = motion(&trial_run(0));
    let mb = motion(&trial_run(1));
    let (ta, tb) = (trial(0), trial(1));
    let advice = two_plane_influence_correction(
        &m0,
        [&ma, &mb],
        [&ta, &tb],
        &planes(),
        &context(),
        &TwoPlaneFields::default(),
    )
    .expect("a correction");
    let corrections: Vec<ImbalanceMass> = advice
        .planes
        .iter()
        .zip(HEIGHTS_M)
        .map(|(c, h)| ImbalanceMass {
            mass_kg: c.mass_kg,
            radius_m: c.radius_m,
            azimuth_deg: c.azimuth_deg,
            arm_m: h,
        })
        .collect();
    let check = motion(&two_probe(seed + 10, &corrections));
    let t = check.dynamic.a;
    (
        m0.dynamic.a.x * 1e-6,
        t.x * 1e-6,
        advice.predicted.c_r_m_s2,
        advice.predicted.c_r_u_m_s2,
        t.covariance[0][0].sqrt() * 1e-6,
    )
}

#[test]
fn two_plane_correction_cuts_c_r_fifty_fold_and_meets_the_prediction() {
    let (before, after, predicted, sigma_pred, sigma_meas) = influence_loop(21);
    assert!(before.abs() > 1e-6, "C_r before {before:e}");
    assert!(
        after.abs() * 50.0 < before.abs(),
        "C_r {before:e} → {after:e}"
    );
    let sigma = sigma_pred.hypot(sigma_meas);
    assert!(
        (after - predicted).abs() <= 3.0 * sigma,
        "after {after:e}, predicted {predicted:e} ± {sigma_pred:e} (check run ± {sigma_meas:e})"
    );
}

#[test]
fn two_plane_stiffness_correction_cancels_static_and_couple() {
    let before = two_probe(31, &[]);
    let m0 = motion(&before);
    let advice = two_plane_stiffness_correction(
        &m0,
        &Stiffness {
            radial_n_m: K_R,
            angular_n_m_rad: K_THETA,
        },
        "balance",
        &planes(),
        &context(),
        &TwoPlaneFields::default(),
    )
    .unwrap();
    let corrections: Vec<ImbalanceMass> = advice
        .planes
        .iter()
        .zip(HEIGHTS_M)
        .map(|(c, h)| ImbalanceMass {
            mass_kg: c.mass_kg,
            radius_m: c.radius_m,
            azimuth_deg: c.azimuth_deg,
            arm_m: h,
        })
        .collect();
    // exact in the simulator's coefficients: the corrected spindle has (almost) no dynamic
    // translation or tilt left
    let after = two_probe(32, &corrections);
    let e0 = before.error_motion;
    let e1 = after.error_motion;
    assert!(e1.c_r_m_s2.abs() * 50.0 < e0.c_r_m_s2.abs());
    assert!(e1.c_phi_s2.hypot(e1.c_phi_x_s2) * 50.0 < e0.c_phi_s2.hypot(e0.c_phi_x_s2));
    let u = advice.predicted.c_r_u_m_s2;
    assert!(e1.c_r_m_s2.abs() <= 3.0 * u, "{} vs σ {u}", e1.c_r_m_s2);
}

#[test]
fn probes_at_one_height_name_the_second_probe() {
    let loaded = two_probe(41, &[]);
    let f = crate::common::fit(&loaded, "first");
    let plane = ProbePlane {
        fit: &f,
        height_m: -0.51,
    };
    let err = axis_motion(&plane, &plane, "balance.second_probe").unwrap_err();
    assert!(
        matches!(&err, balance::BalanceError::SameHeight { field, .. } if field == "balance.second_probe.height_m"),
        "{err}"
    );
}

#[test]
fn a_trial_run_that_changes_nothing_is_a_singular_influence_naming_it() {
    let m0 = motion(&two_probe(51, &[]));
    let ma = motion(&two_probe(
        52,
        &[ImbalanceMass {
            mass_kg: 8.0,
            radius_m: 2.5,
            azimuth_deg: 90.0,
            arm_m: HEIGHTS_M[0],
        }],
    ));
    let t = TrialMass {
        mass_kg: 8.0,
        radius_m: 2.5,
        azimuth_deg: 90.0,
    };
    let fields = TwoPlaneFields {
        trials: ["balance.trial", "balance.two_plane.trial"],
        ..TwoPlaneFields::default()
    };
    let err =
        two_plane_influence_correction(&m0, [&ma, &m0], [&t, &t], &planes(), &context(), &fields)
            .unwrap_err();
    assert!(
        matches!(&err, balance::BalanceError::SingularInfluence { field, .. } if field == "balance.two_plane.trial"),
        "{err}"
    );
    // the model-free static and couple unbalance of a good loop match the masses
    let before = two_probe(61, &[]);
    let (s, c) = truth(&before);
    let mb = motion(&two_probe(
        63,
        &[ImbalanceMass {
            mass_kg: 8.0,
            radius_m: 2.5,
            azimuth_deg: -30.0,
            arm_m: HEIGHTS_M[1],
        }],
    ));
    let tb = TrialMass {
        azimuth_deg: -30.0,
        ..t
    };
    let advice = two_plane_influence_correction(
        &motion(&before),
        [&ma, &mb],
        [&t, &tb],
        &planes(),
        &context(),
        &fields,
    )
    .unwrap();
    let sc = advice.cancelled_unbalance();
    assert_close("static kg·m (influence)", &sc.static_kg_m, s, 3.0);
    assert_close("couple kg·m² (influence)", &sc.couple_kg_m2, c, 3.0);
}
