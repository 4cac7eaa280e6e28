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
