//! The balance section: a simulated trial-weight loop through the study, and its typed errors.

use std::path::Path;

use harmonics::{FitConfig, ProbeSignal, SpindleAngle, analyze};
use kinematics::{ErrorMotionSpec, ImbalanceMass};
use pipeline::{InvalidReason, PipelineError, StudyConfig, UnsupportedReason};
use simulate::Scenario;

use crate::root;

/// `first_harmonic([...])` of a simulated run of the pre-balance fixture with extra masses.
fn phase_points(seed: u64, masses: &[ImbalanceMass]) -> String {
    let text = std::fs::read_to_string(root().join("fixtures/scenarios/pre-balance.ron")).unwrap();
    let mut s = Scenario::parse(&text, Path::new("pre-balance.ron"))
        .unwrap()
        .scenario;
    s.seed = seed;
    s.min_duration_s = 36.0;
    if let ErrorMotionSpec::Physical(p) = &mut s.error_motion {
        p.masses.extend_from_slice(masses);
    }
    let loaded = s.check(Path::new("pre-balance.ron")).unwrap();
    let sim = simulate::simulate(&loaded).unwrap();
    let mut out = String::from("first_harmonic([");
    for rec in &sim.recordings {
        let angle = rec.angle_rad().unwrap();
        let signal = ProbeSignal {
            time_s: &rec.time_s,
            gap: &rec.gap_um,
            angle: SpindleAngle::Encoder(&angle),
        };
        let h = analyze(&signal, &FitConfig::default())
            .unwrap()
            .first_harmonic()
            .unwrap();
        out.push_str(&format!(
            "(rate_deg_s: {:?}, dc1_um: {:?}, ds1_um: {:?}),",
            rec.rate_deg_s, h.c1, h.s1
        ));
    }
    out.push_str("])");
    out
}

fn study(phases: &[(&str, String)], balance: &str) -> String {
    let list: Vec<String> = phases
        .iter()
        .map(|(name, points)| format!("(name: {name:?}, points: {points})"))
        .collect();
    format!(
        "(name: \"balance\", radius_m: 2.5, g_m_s2: 9.8, k1_rad_s_g: 0.56,
          lever: (pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0),
          phases: [{}], balance: {balance})",
        list.join(",")
    )
}

fn run(text: &str) -> pipeline::Result<pipeline::StudyResults> {
    let source = Path::new("balance.ron");
    let config = StudyConfig::from_ron(text, source)?;
    let inputs = pipeline::Inputs::new(config, source, &pipeline::Files)?;
    pipeline::run(&inputs)
}

const TRIAL: ImbalanceMass = ImbalanceMass {
    mass_kg: 8.0,
    radius_m: 2.5,
    azimuth_deg: 90.0,
    arm_m: 0.15,
};

const BALANCE: &str = "(initial: \"before\", trial: \"trial\",
    trial_mass: (mass_kg: 8.0, radius_m: 2.5, azimuth_deg: 90.0),
    radial_stiffness_n_m: 5.0e7, correction_radius_m: 2.5,
    fixed_azimuths_deg: [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0],
    rotor_mass_kg: 2000.0)";

#[test]
fn the_study_advises_a_correction_that_balances_the_simulated_spindle() {
    let before = phase_points(11, &[]);
    let trial = phase_points(12, &[TRIAL]);
    let text = study(
        &[("before", before.clone()), ("trial", trial.clone())],
        BALANCE,
    );
    let r = run(&text).unwrap();
    let b = r.balance.as_ref().expect("configured");
    // 32 kg at 2.5 m towards 0°: correct with 32 kg at 180°
    assert!(
        (b.correction.mass_kg - 32.0).abs() < 0.05,
        "{:?}",
        b.correction
    );
    assert!((b.correction.azimuth_deg.abs() - 180.0).abs() < 0.1);
    let split = b.correction.split.as_ref().unwrap();
    // the split's vector sum is the correction: nearly all of it on the 180° position
    let (mut x, mut y) = (0.0, 0.0);
    for m in split {
        x += m.mass_kg * m.azimuth_deg.to_radians().cos();
        y += m.mass_kg * m.azimuth_deg.to_radians().sin();
    }
    let want = b.correction.azimuth_deg.to_radians();
    assert!((x - b.correction.mass_kg * want.cos()).abs() < 1e-9);
    assert!((y - b.correction.mass_kg * want.sin()).abs() < 1e-9);
    assert!(
        split
            .iter()
            .any(|m| m.azimuth_deg == 180.0 && m.mass_kg > 31.0)
    );
    assert!((b.dynamic.c_r_m_s2 - 1.6e-6).abs() < 1e-9);
    // the stiffness model agrees
    let st = b.stiffness.as_ref().unwrap();
    assert!((st.imbalance_kg_m - 80.0).abs() < 0.1);
    // results.json carries the keys
    let json = serde_json::to_value(&r).unwrap();
    for path in [
        "/balance/static/magnitude_um",
        "/balance/static/azimuth_deg",
        "/balance/dynamic/magnitude_um_s2",
        "/balance/dynamic/azimuth_deg",
        "/balance/correction/mass_kg",
        "/balance/correction/radius_m",
        "/balance/correction/azimuth_deg",
        "/balance/predicted/c_r_m_s2",
        "/balance/predicted/c_r_u_m_s2",
        "/balance/predicted/delta_k2_rad_s_g2",
    ] {
        assert!(json.pointer(path).is_some_and(|v| v.is_number()), "{path}");
    }

    // the check run with the advised correction
    let c = &b.correction;
    let check = phase_points(
        13,
        &[ImbalanceMass {
            mass_kg: c.mass_kg,
            radius_m: c.radius_m,
            azimuth_deg: c.azimuth_deg,
            arm_m: 0.15,
        }],
    );
    let text = study(
        &[("before", before), ("trial", trial), ("check", check)],
        &BALANCE.replace("rotor_mass_kg", "check: \"check\", rotor_mass_kg"),
    );
    let r = run(&text).unwrap();
    let k = r.balance.unwrap().check.unwrap();
    assert!(k.reduction.abs() > 50.0, "{k:?}");
    assert!(k.z.abs() < 3.0, "{k:?}");
}

#[test]
fn balance_errors_name_the_field() {
    let before = phase_points(21, &[]);
    // a trial phase identical to the initial one: singular influence coefficient
    let text = study(
        &[("before", before.clone()), ("trial", before.clone())],
        BALANCE,
    );
    let err = run(&text).unwrap_err();
    assert!(
        matches!(&err, PipelineError::Balance { field, source, .. } if field == "balance" && matches!(**source, balance::BalanceError::SingularInfluence { .. })),
        "{err:?}"
    );
    assert!(
        crate::chain(&err).contains("balance.trial"),
        "{}",
        crate::chain(&err)
    );
    // a trial mass of 0
    let zero = BALANCE.replace("mass_kg: 8.0", "mass_kg: 0.0");
    let text = study(
        &[("before", before.clone()), ("trial", before.clone())],
        &zero,
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::InvalidField { field, reason: InvalidReason::NotPositive, .. }
            if field == "balance.trial_mass.mass_kg"
    ));
    // fewer than three rates
    let two = "first_harmonic([(rate_deg_s: 10.0, dc1_um: 1.0, ds1_um: 0.0), (rate_deg_s: 20.0, dc1_um: 1.0, ds1_um: 0.0)])".to_owned();
    let text = study(&[("before", two), ("trial", before.clone())], BALANCE);
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::TooFewPoints { field, got: 2, need: 3, .. } if field == "phases[0].points"
    ));
    // a trial without its mass
    let text = study(
        &[("before", before.clone()), ("trial", before.clone())],
        "(initial: \"before\", trial: \"trial\", correction_radius_m: 2.5)",
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::Unsupported { field, reason: UnsupportedReason::TrialNeedsTrialMass, .. }
            if field == "balance.trial_mass"
    ));
    // an unknown phase
    let text = study(
        &[("before", before)],
        "(initial: \"nope\", radial_stiffness_n_m: 5e7, correction_radius_m: 2.5)",
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::UnknownPhase { field, .. } if field == "balance.initial"
    ));
}

/// The second probe of the two-plane runs, 1110 mm below the PIGA plane (600 mm below the
/// first), measuring along O1X1.
const SECOND_PROBE_MM: f64 = 1110.0;

/// A mass 0.6 m below the PIGA plane besides the fixture's 32 kg at +0.15 m: static and
/// couple unbalance.
const LOWER: ImbalanceMass = ImbalanceMass {
    mass_kg: 20.0,
    radius_m: 2.5,
    azimuth_deg: 120.0,
    arm_m: -0.6,
};

fn harmonic_points(recordings: &[simulate::SimulatedRecording]) -> String {
    let mut out = String::from("first_harmonic([");
    for rec in recordings {
        let angle = rec.angle_rad().unwrap();
        let signal = ProbeSignal {
            time_s: &rec.time_s,
            gap: &rec.gap_um,
            angle: SpindleAngle::Encoder(&angle),
        };
        let h = analyze(&signal, &FitConfig::default())
            .unwrap()
            .first_harmonic()
            .unwrap();
        out.push_str(&format!(
            "(rate_deg_s: {:?}, dc1_um: {:?}, ds1_um: {:?}),",
            rec.rate_deg_s, h.c1, h.s1
        ));
    }
    out.push_str("])");
    out
}

/// Both probes' `first_harmonic([...])` of a simulated two-probe run (the pre-balance
/// fixture with `LOWER` and `masses`), and the scenario's Σ m·r·e^{iθ}, Σ m·r·l·e^{iθ}.
fn two_probe_points(seed: u64, masses: &[ImbalanceMass]) -> (String, String, [f64; 4]) {
    let text = std::fs::read_to_string(root().join("fixtures/scenarios/pre-balance.ron")).unwrap();
    let mut s = Scenario::parse(&text, Path::new("pre-balance.ron"))
        .unwrap()
        .scenario;
    s.seed = seed;
    s.min_duration_s = 36.0;
    s.second_probe = Some(simulate::SecondProbeSpec {
        probe_to_piga_mm: SECOND_PROBE_MM,
        probe_direction: harmonics::ProbeDirection::AlongO1X1,
    });
    let mut sums = [0.0; 4];
    if let ErrorMotionSpec::Physical(p) = &mut s.error_motion {
        p.masses.push(LOWER);
        p.masses.extend_from_slice(masses);
        let first = ImbalanceMass {
            mass_kg: p.mass_kg,
            radius_m: p.mass_radius_m,
            azimuth_deg: p.imbalance_azimuth_deg,
            arm_m: p.arm_m,
        };
        for m in std::iter::once(&first).chain(&p.masses) {
            let (sn, cs) = m.azimuth_deg.to_radians().sin_cos();
            let mr = m.mass_kg * m.radius_m;
            sums[0] += mr * cs;
            sums[1] += mr * sn;
            sums[2] += mr * m.arm_m * cs;
            sums[3] += mr * m.arm_m * sn;
        }
    }
    let loaded = s.check(Path::new("pre-balance.ron")).unwrap();
    let sim = simulate::simulate(&loaded).unwrap();
    (
        harmonic_points(&sim.recordings),
        harmonic_points(&sim.second_recordings),
        sums,
    )
}

const TWO_PLANE: &str = "(initial: \"before\", trial: \"trial_a\",
    trial_mass: (mass_kg: 8.0, radius_m: 2.5, azimuth_deg: 90.0, height_m: 0.15),
    radial_stiffness_n_m: 5.0e7, angular_stiffness_n_m_rad: 2.4e8, correction_radius_m: 2.5,
    rotor_mass_kg: 2000.0,
    second_probe: (probe_to_piga_mm: 1110.0, probe_direction: along_o1_x1,
        phases: {\"before\": \"before_low\", \"trial_a\": \"trial_a_low\", \"trial_b\": \"trial_b_low\"CHECK_LOW}),
    two_plane: (heights_m: (0.15, -0.6), trial: \"trial_b\",
        trial_mass: (mass_kg: 8.0, radius_m: 2.5, azimuth_deg: -30.0))CHECK)";

#[test]
fn two_probe_planes_give_static_and_couple_and_a_two_plane_correction_that_balances() {
    let trial_a = ImbalanceMass {
        mass_kg: 8.0,
        radius_m: 2.5,
        azimuth_deg: 90.0,
        arm_m: 0.15,
    };
    let trial_b = ImbalanceMass {
        mass_kg: 8.0,
        radius_m: 2.5,
        azimuth_deg: -30.0,
        arm_m: -0.6,
    };
    let (b1, b2, sums) = two_probe_points(51, &[]);
    let (a1, a2, _) = two_probe_points(52, &[trial_a]);
    let (c1, c2, _) = two_probe_points(53, &[trial_b]);
    let mut phases = vec![
        ("before", b1),
        ("before_low", b2),
        ("trial_a", a1),
        ("trial_a_low", a2),
        ("trial_b", c1),
        ("trial_b_low", c2),
    ];
    let config = TWO_PLANE.replace("CHECK_LOW", "").replace("CHECK", "");
    let r = run(&study(&phases, &config)).unwrap();
    let b = r.balance.as_ref().unwrap();
    assert!(
        b.assumption.starts_with("two probe planes"),
        "{}",
        b.assumption
    );
    let t = b.two_plane.as_ref().expect("two planes");
    // static and couple unbalance (stiffness model) match the simulated masses to 3σ
    let st = t.static_kg_m.unwrap();
    let co = t.couple_kg_m2.unwrap();
    assert_eq!(t.unbalance_method.as_deref(), Some("stiffness_model"));
    let near = |p: &pipeline::PhasorResult, x: f64, y: f64| {
        let d = (p.x - x).hypot(p.y - y);
        d <= 3.0
            * p.magnitude_u
                .max(p.magnitude * p.azimuth_u_deg.to_radians())
            + 1e-9
    };
    assert!(near(&st, sums[0], sums[1]), "static {st:?} vs {sums:?}");
    assert!(near(&co, sums[2], sums[3]), "couple {co:?} vs {sums:?}");
    assert!(st.magnitude_u < 1e-3 * st.magnitude && co.magnitude_u < 1e-2 * co.magnitude);
    // results.json: `balance.two_plane.static`, `.couple` and the corrections
    let json = serde_json::to_value(&r).unwrap();
    for path in [
        "/balance/two_plane/static/magnitude",
        "/balance/two_plane/couple/azimuth_deg",
        "/balance/two_plane/c_r_m_s2",
        "/balance/two_plane/corrections/0/planes/1/correction/mass_kg",
        "/balance/two_plane/corrections/0/predicted/c_r_u_m_s2",
    ] {
        assert!(json.pointer(path).is_some_and(|v| v.is_number()), "{path}");
    }
    let influence = &t.corrections[0];
    assert_eq!(influence.method, "influence_coefficient");
    assert_eq!(t.corrections[1].method, "stiffness_model");

    // the check run with the two-plane (influence) correction
    let masses: Vec<ImbalanceMass> = influence
        .planes
        .iter()
        .map(|p| ImbalanceMass {
            mass_kg: p.correction.mass_kg,
            radius_m: p.correction.radius_m,
            azimuth_deg: p.correction.azimuth_deg,
            arm_m: p.height_m,
        })
        .collect();
    let (k1, k2, _) = two_probe_points(54, &masses);
    phases.push(("check", k1));
    phases.push(("check_low", k2));
    let config = TWO_PLANE
        .replace("CHECK_LOW", ", \"check\": \"check_low\"")
        .replace("CHECK", ", check: \"check\"");
    let r = run(&study(&phases, &config)).unwrap();
    let k = r.balance.unwrap().two_plane.unwrap().check.unwrap();
    assert!(k.reduction.abs() >= 50.0, "{k:?}");
    assert!(k.z.abs() <= 3.0, "{k:?}");
}

#[test]
fn one_probe_states_the_cone_assumption() {
    let before = phase_points(61, &[]);
    let trial = phase_points(62, &[TRIAL]);
    let r = run(&study(&[("before", before), ("trial", trial)], BALANCE)).unwrap();
    let b = r.balance.unwrap();
    assert!(b.two_plane.is_none());
    assert!(b.assumption.contains("cone"), "{}", b.assumption);
    assert!(b.assumption.contains("eq. 22"), "{}", b.assumption);
}

#[test]
fn two_plane_errors_name_the_field() {
    let (b1, b2, _) = two_probe_points(71, &[]);
    let phases = [("before", b1.clone()), ("before_low", b2)];
    let stiff = "(initial: \"before\", radial_stiffness_n_m: 5.0e7, correction_radius_m: 2.5,
        SECOND)";
    // the second probe at the first's height
    let text = study(
        &phases,
        &stiff.replace(
            "SECOND",
            "second_probe: (probe_to_piga_mm: 510.0, phases: {\"before\": \"before_low\"})",
        ),
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::Unsupported { field, reason: UnsupportedReason::SecondProbeAtFirstHeight, .. }
            if field == "balance.second_probe.probe_to_piga_mm"
    ));
    // no second-probe phase for the initial run
    let text = study(
        &phases,
        &stiff.replace(
            "SECOND",
            "second_probe: (probe_to_piga_mm: 1110.0, phases: {})",
        ),
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::Unsupported { field, reason: UnsupportedReason::SecondProbeNeedsPhase, .. }
            if field == "balance.second_probe.phases"
    ));
    // two planes without a second probe
    let text = study(
        &phases,
        &stiff.replace("SECOND", "two_plane: (heights_m: (0.1, -0.5))"),
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::Unsupported { field, reason: UnsupportedReason::TwoPlaneNeedsSecondProbe, .. }
            if field == "balance.two_plane"
    ));
    // two planes at one height
    let text = study(
        &phases,
        &stiff.replace(
            "SECOND",
            "angular_stiffness_n_m_rad: 2.4e8, second_probe: (probe_to_piga_mm: 1110.0, phases: {\"before\": \"before_low\"}), two_plane: (heights_m: (0.1, 0.1))",
        ),
    );
    assert!(matches!(
        run(&text).unwrap_err(),
        PipelineError::Unsupported { field, reason: UnsupportedReason::PlanesAtOneHeight, .. }
            if field == "balance.two_plane.heights_m"
    ));
}

/// The paper study's counterweight section: the one published change with the study's
/// stated stiffness; the stiffness is an input (the mass scales with it), and a phase that is
/// not a radius change is a typed error.
#[test]
fn the_counterweight_of_the_papers_pre_balance_change() {
    let path = root().join("fixtures/studies/paper-2025.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let run_text = |t: &str| {
        let config = StudyConfig::from_ron(t, &path)?;
        let inputs = pipeline::Inputs::new(config, &path, &pipeline::Files)?;
        pipeline::run(&inputs)
    };
    let r = run_text(&text).unwrap();
    let c = r.counterweight.expect("configured");
    let pre = r.phases.iter().find(|p| p.name == "pre_balance").unwrap();
    assert_eq!(c.c_r_m_s2, pre.fit.c_r_m_s2);
    assert!(
        (c.unbalance_x_g_mm - 19.4640 * c.unbalance_per_um_g_mm).abs() < 1e-6 * c.unbalance_x_g_mm
    );
    assert!((c.correction_mass_kg - c.unbalance_x_g_mm * 1e-6 / 2.5).abs() < 1e-9);
    assert_eq!(c.correction_azimuth_deg, 180.0);
    assert!(c.not_determined.iter().any(|s| s.contains("azimuth")));
    assert!(
        c.not_determined
            .iter()
            .any(|s| s.contains("static and dynamic"))
    );
    assert!(c.not_determined.iter().any(|s| s.contains("plane")));
    // twice the stiffness, twice the counterweight
    let doubled =
        run_text(&text.replace("radial_stiffness_n_m: 5.0e7", "radial_stiffness_n_m: 1.0e8"))
            .unwrap()
            .counterweight
            .unwrap();
    assert!((doubled.correction_mass_kg / c.correction_mass_kg - 2.0).abs() < 1e-12);
    // a first-harmonic phase is not one number
    let err = run_text(&text.replace(
        "phase: \"pre_balance\",\n        radial",
        "phase: \"post_balance\",\n        radial",
    ))
    .unwrap_err();
    assert!(
        matches!(
            &err,
            PipelineError::Unsupported { field, reason: UnsupportedReason::CounterweightNeedsRadiusChange, .. }
                if field == "counterweight.phase"
        ),
        "{err:?}"
    );
    let err = run_text(&text.replace("radial_stiffness_n_m: 5.0e7", "radial_stiffness_n_m: 0.0"))
        .unwrap_err();
    assert!(matches!(
        err,
        PipelineError::InvalidField { field, reason: InvalidReason::NotPositive, .. }
            if field == "counterweight.radial_stiffness_n_m"
    ));
}

/// `first_harmonic` points of `S + D·ω²` (probe plane, against O1X1) with a stated σ.
fn points_with_sigma(sigma: &str) -> String {
    let mut out = String::from("first_harmonic([");
    for (k, deg) in [10.0_f64, 60.0, 110.0, 160.0, 200.0].iter().enumerate() {
        let w = deg.to_radians();
        // a little scatter (±1e-3 µm) so that the fit has residuals
        let e = if k % 2 == 0 { 1e-3 } else { -1e-3 };
        let (x, y) = (2.0 + 0.9 * w * w + e, -1.0 + 0.2 * w * w - e);
        out.push_str(&format!(
            "(rate_deg_s: {deg:?}, dc1_um: {:?}, ds1_um: {y:?}{sigma}),",
            -x
        ));
    }
    out.push_str("])");
    out
}

/// `sigma_um` on first-harmonic points: the phasor fit weighs by it (its covariance scales
/// with σ when the scatter is within it), the points carry it, and σ ≤ 0 names the field.
#[test]
fn first_harmonic_points_carry_sigma_for_the_phasor_fit() {
    let balance = "(initial: \"before\", radial_stiffness_n_m: 5.0e7, correction_radius_m: 2.5)";
    let fit = |sigma: &str| {
        let r = run(&study(&[("before", points_with_sigma(sigma))], balance)).unwrap();
        let p = r.phases[0].points[0];
        (r.balance.unwrap().phases[0].clone(), p)
    };
    let (unweighted, p0) = fit("");
    assert_eq!(unweighted.reduced_chi, None);
    assert_eq!(p0.dc1_sigma_um, None);
    let (one, p1) = fit(", sigma_um: 0.01");
    let (two, _) = fit(", sigma_um: 0.02");
    // weighted: χ²/dof is stated and below 1 (scatter 1e-3 against σ 1e-2)
    let chi = one.reduced_chi.expect("weighted");
    assert!(chi < 0.2, "{chi}");
    assert_eq!(p1.dc1_sigma_um, Some(0.01));
    assert!((p1.radius_error_sigma_um.unwrap() - 0.01 * 1210.0 / 700.0).abs() < 1e-15);
    // the covariance follows σ (not the scatter): twice σ, twice the uncertainty
    let ratio = two.dynamic.magnitude_u_um_s2 / one.dynamic.magnitude_u_um_s2;
    assert!((ratio - 2.0).abs() < 1e-9, "{ratio}");
    assert!(one.dynamic.magnitude_u_um_s2 > 2.0 * unweighted.dynamic.magnitude_u_um_s2);
    // inverse_variance weighting of the radius-error fit accepts them
    let text = study(
        &[("before", points_with_sigma(", sigma_um: 0.01"))],
        balance,
    )
    .replace(
        "points: first_harmonic",
        "weighting: inverse_variance, points: first_harmonic",
    );
    assert!(run(&text).is_ok());
    // σ must be > 0, named by its point
    let bad = points_with_sigma(", sigma_um: 0.01").replacen("sigma_um: 0.01", "sigma_um: 0.0", 1);
    let err = run(&study(&[("before", bad)], balance)).unwrap_err();
    assert!(
        matches!(
            &err,
            PipelineError::InvalidField { field, reason: InvalidReason::NotPositive, .. }
                if field == "phases[0].points[0].sigma_um"
        ),
        "{err:?}"
    );
}

/// The two-plane fixture study with `from` replaced by `to`.
fn two_plane_fixture(from: &str, to: &str) -> String {
    let text =
        std::fs::read_to_string(crate::root().join("fixtures/studies/balance-two-plane.ron"))
            .unwrap();
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

#[test]
fn second_probe_data_is_kept_apart_from_the_first_probes() {
    // Its phases are flagged, and the cone's C_r is set beside the two-plane one.
    let results = run(&two_plane_fixture("", "")).unwrap();
    let flagged: Vec<&str> = results
        .warnings
        .iter()
        .filter(|w| w.code == "second_probe_phase")
        .map(|w| w.location.as_str())
        .collect();
    assert_eq!(flagged.len(), 4, "{flagged:?}");
    assert!(results.warnings.iter().any(|w| w.code == "cone_c_r"));
    // A second probe's phase mapped to a phase the first probe gives.
    let e = run(&two_plane_fixture(
        "\"check\": \"check_low\"",
        "\"check\": \"before\"",
    ))
    .unwrap_err();
    assert!(
        matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::SecondProbePhaseIsFirst, .. } if field.starts_with("balance.second_probe.phases")),
        "{e}"
    );
    // A trial mass out of its plane.
    let e = run(&two_plane_fixture(
        "azimuth_deg: 90.0, height_m: 0.15",
        "azimuth_deg: 90.0, height_m: 0.40",
    ))
    .unwrap_err();
    assert!(
        matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::TrialOutOfPlane, .. } if field == "balance.trial_mass.height_m"),
        "{e}"
    );
}

#[test]
fn a_second_probe_phase_cannot_compensate_a_calibration_or_be_simulated() {
    let with_mechanism = two_plane_fixture(
        "    balance: (",
        "    mechanism: (phases: [\"before_low\"], k2_rad_s_g2: 1e-6, rates_deg_s: [10.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0, 200.0]),\n    balance: (",
    );
    let e = run(&with_mechanism).unwrap_err();
    assert!(
        matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::SecondProbeData, .. } if field == "mechanism.phases[0]"),
        "{e}"
    );
    // Without a list, the mechanism takes every first-probe phase.
    let every = two_plane_fixture(
        "    balance: (",
        "    mechanism: (k2_rad_s_g2: 1e-6, rates_deg_s: [10.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0, 200.0]),\n    balance: (",
    );
    let results = run(&every).unwrap();
    let m = results.mechanism.unwrap();
    assert!(
        m.phases.iter().all(|p| !p.phase.ends_with("_low")),
        "{:?}",
        m.phases.iter().map(|p| &p.phase).collect::<Vec<_>>()
    );
}

#[test]
fn a_counterweight_needs_its_stiffness_source() {
    let text =
        std::fs::read_to_string(crate::root().join("fixtures/studies/paper-2025.ron")).unwrap();
    let blank = text.replace(
        "stiffness_source: \"assumed: the bearing of fixtures/scenarios/pre-balance.ron; the paper gives none\",",
        "stiffness_source: \" \",",
    );
    assert_ne!(blank, text);
    let source = crate::root().join("fixtures/studies/paper-2025.ron");
    let config = StudyConfig::from_ron(&blank, &source).unwrap();
    let e = pipeline::Inputs::new(config, &source, &pipeline::Files).unwrap_err();
    assert!(
        matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::StiffnessNeedsSource, .. } if field == "counterweight.stiffness_source"),
        "{e}"
    );
}

#[test]
fn more_two_plane_and_counterweight_errors_name_the_field() {
    // Two planes with neither trial runs in both planes nor both stiffnesses.
    let e = run(&two_plane_fixture(
        "        angular_stiffness_n_m_rad: 2.4e8,",
        "",
    )
    .replacen(
        "            trial: \"trial_b\",               // the run with the trial mass in plane B\n            trial_mass: (mass_kg: 8.0, radius_m: 2.5, azimuth_deg: -30.0),\n",
        "",
        1,
    ))
    .unwrap_err();
    assert!(
        matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::TwoPlaneNeedsMethod, .. } if field == "balance.two_plane"),
        "{e}"
    );
    // A plane-B trial without its mass.
    let e = run(&two_plane_fixture(
        "            trial_mass: (mass_kg: 8.0, radius_m: 2.5, azimuth_deg: -30.0),\n",
        "",
    ))
    .unwrap_err();
    assert!(
        matches!(&e, PipelineError::Unsupported { field, reason: UnsupportedReason::TrialNeedsTrialMass, .. } if field == "balance.two_plane.trial_mass"),
        "{e}"
    );
    // A plane-B trial mass of 0.
    let e = run(&two_plane_fixture(
        "trial_mass: (mass_kg: 8.0, radius_m: 2.5, azimuth_deg: -30.0)",
        "trial_mass: (mass_kg: 0.0, radius_m: 2.5, azimuth_deg: -30.0)",
    ))
    .unwrap_err();
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "balance.two_plane.trial_mass.mass_kg"),
        "{e}"
    );
    // The counterweight's radius must be > 0.
    let text = std::fs::read_to_string(root().join("fixtures/studies/paper-2025.ron")).unwrap();
    let bad = text.replacen(
        "        correction_radius_m: 2.5,\n    ),\n)",
        "        correction_radius_m: 0.0,\n    ),\n)",
        1,
    );
    assert_ne!(bad, text);
    let source = root().join("fixtures/studies/paper-2025.ron");
    let e = pipeline::Inputs::new(
        StudyConfig::from_ron(&bad, &source).unwrap(),
        &source,
        &pipeline::Files,
    )
    .unwrap_err();
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "counterweight.correction_radius_m"),
        "{e}"
    );
}
