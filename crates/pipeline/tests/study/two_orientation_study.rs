//! The two-orientation calibration through the study (`two_orientation:` in a study file, issue 20):
//! the simulated campaign's tables and probe recordings in memory, the study's results and
//! warnings; and a bad section refused with every problem named at once.

use std::path::{Path, PathBuf};

use pipeline::{Inputs, PipelineError, StudyConfig, StudyResults, WarningCode};
use simulate::{Orientation, Simulation};

use super::two_orientation::{C_R, DIR, Declared, ENCODER_ZERO_DEG, K2, probe_study, scenario};
use test_support::MemoryFiles as Files;

/// The two-orientation section on the simulation's two mounting tables, compared with the probe
/// phase (declared as `declared`); a small fixed Monte Carlo count.
fn study(sim: &Simulation, declared: Declared) -> StudyResults {
    study_with_tables(sim, sim, declared)
}

/// The two-orientation section on the mounting tables of `tables`, compared with the probe phase
/// of `probe`.
fn study_with_tables(probe: &Simulation, tables: &Simulation, declared: Declared) -> StudyResults {
    tables_study(probe, tables, declared, "").unwrap()
}

/// The probe phase of `probe` (declared as `declared`), then `sections` (RON fields of the
/// study), then the two-orientation section on the two mounting tables of `tables` with a small
/// fixed Monte Carlo count; run.
pub(crate) fn tables_study(
    probe: &Simulation,
    tables: &Simulation,
    declared: Declared,
    sections: &str,
) -> Result<StudyResults, PipelineError> {
    keyed_study(probe, tables, declared, sections, "two_orientation")
}

/// [`tables_study`] with the two-orientation section written under the key `key`.
fn keyed_study(
    probe: &Simulation,
    tables: &Simulation,
    declared: Declared,
    sections: &str,
    key: &str,
) -> Result<StudyResults, PipelineError> {
    let (text, mut files) = probe_study(probe, declared);
    let mut sets = String::new();
    for m in &tables.mountings {
        let (name, file) = match m.orientation {
            Orientation::IaIn => ("ia_in", "piga_ia_in.csv"),
            Orientation::IaOut => ("ia_out", "piga_ia_out.csv"),
        };
        let mut csv = String::from("rate_deg_s,output_rad_s\n");
        for r in &m.piga {
            csv.push_str(&format!("{:?},{:?}\n", r.rate_deg_s, r.output_rad_s));
        }
        files.insert(Path::new(DIR).join(file), csv.into_bytes());
        sets.push_str(&format!(
            "(orientation: {name}, radius_m: {:?}, table: (file: \"{file}\")),",
            m.radius_m
        ));
    }
    // the campaign study's text up to its calibration section: `sections` adds the rest
    let end = text.rfind(')').unwrap();
    let text = format!(
        "{}    {sections}\n    {key}: (orientations: [{sets}], compare_with: \"spindle\", trials: fixed(2000)),\n)\n",
        &text[..end]
    );
    let source = Path::new(DIR).join("study.ron");
    let config = StudyConfig::from_ron(&text, &source)?;
    let inputs = Inputs::new(config, &source, &Files(files))?;
    pipeline::run(&inputs)
}

fn warned(r: &StudyResults, code: WarningCode) -> bool {
    r.warnings.iter().any(|w| w.code == code)
}

/// The section's former name, `symmetric`, is read as `two_orientation` with the same results
/// and a `deprecated_key` warning naming the new key; both names at once are refused.
#[test]
fn the_former_section_name_is_read_with_a_warning() {
    let sim = simulate::simulate(&scenario(29, 0.3 * C_R)).unwrap();
    let new = keyed_study(&sim, &sim, Declared::Right, "", "two_orientation").unwrap();
    let old = keyed_study(&sim, &sim, Declared::Right, "", "symmetric").unwrap();
    assert_eq!(new.two_orientation, old.two_orientation);
    assert!(!warned(&new, WarningCode::DeprecatedKey));
    let w = old
        .warnings
        .iter()
        .find(|w| w.code == WarningCode::DeprecatedKey)
        .expect("a deprecated_key warning");
    assert!(w.message.contains("`two_orientation`"), "{}", w.message);
    assert_eq!(w.location, "symmetric");

    let both = "symmetric: (orientations: []),";
    let err = keyed_study(&sim, &sim, Declared::Right, both, "two_orientation").unwrap_err();
    let message = super::chain(&err);
    assert!(
        message.contains("field `two_orientation` states the two-orientation calibration, and so does `symmetric`"),
        "{message}"
    );
}

/// C_a = 0.3·C_r, R_out = R_in + 40 mm, a bias shift: the study recovers k2 and C within
/// U95, reports C − C_r with z > 3 and the warning naming both candidates; k2 both ways.
/// With C_a = 0, |z| < 3 and no warning.
#[test]
fn the_study_sees_the_arm_stretch_the_probe_misses() {
    let c_a = 0.3 * C_R;
    let r = study(
        &simulate::simulate(&scenario(21, c_a)).unwrap(),
        Declared::Right,
    );
    let s = r
        .two_orientation
        .as_ref()
        .expect("a two-orientation section");
    assert!((s.k2.value - K2).abs() < s.k2.u95, "k2 {:?}", s.k2);
    assert!(
        (s.c_m_s2.value - (C_R + c_a)).abs() < s.c_m_s2.u95,
        "C {:?}",
        s.c_m_s2
    );
    assert_eq!(s.mountings[0].orientation, "ia_in");
    assert_eq!(s.mountings[1].orientation, "ia_out");
    assert_eq!(s.monte_carlo.trials, 2000);
    let p = s.probe.as_ref().expect("a probe comparison");
    assert_eq!(p.phase, "spindle");
    assert!(p.z > 3.0, "z = {}", p.z);
    assert!(!p.agrees);
    assert!((p.difference_m_s2.value - c_a).abs() < p.difference_m_s2.u95);
    // k2 both ways: the probe method keeps k1·C_a·g/R² (4.2e-7) of arm stretch
    assert!(p.k2_probe.value > s.k2.value + s.k2.u95, "{p:?}");
    assert!((p.k2_difference - (s.k2.value - p.k2_probe.value)).abs() < 1e-15);
    assert!(warned(&r, WarningCode::ProbeDisagrees));
    let w = r
        .warnings
        .iter()
        .find(|w| w.code == WarningCode::ProbeDisagrees)
        .unwrap();
    assert!(w.message.contains("does not see") && w.message.contains("probe_direction"));
    // the ordinary 35–200 deg/s design: the ω⁴ term's VIF is above 1e4 (a diagnostic), but
    // fitting C widens u(k2) little, and nothing is said
    assert!(s.omega4_vif > 1e4);
    assert!(
        s.k2_inflation_by_omega4 < 2.0,
        "{}",
        s.k2_inflation_by_omega4
    );
    assert!(!warned(&r, WarningCode::Omega4NotSeparable));
    // nor do its rates cost k2 or C much against the evenly spread design
    let spread = s.u_inflation_by_rates.expect("the rates' price");
    assert!(spread.k2 < 2.0 && spread.c < 2.0, "{spread:?}");
    assert!(!warned(&r, WarningCode::TwoOrientationRatesBunched));

    let r0 = study(
        &simulate::simulate(&scenario(21, 0.0)).unwrap(),
        Declared::Right,
    );
    let p0 = r0.two_orientation.as_ref().unwrap().probe.as_ref().unwrap();
    assert!(p0.z.abs() < 3.0, "z = {}", p0.z);
    assert!(p0.agrees);
    assert!(!warned(&r0, WarningCode::ProbeDisagrees));
}

/// The probe declared along O1X1 instead of against it, and a mm gap column read as µm, in a
/// study with both orientations: each gives the warning.
#[test]
fn a_wrong_probe_declaration_warns_through_the_study() {
    let sim = simulate::simulate(&scenario(22, 0.0)).unwrap();
    for declared in [Declared::WrongSign, Declared::MillimetresReadAsMicrometres] {
        let r = study(&sim, declared);
        let p = r.two_orientation.as_ref().unwrap().probe.as_ref().unwrap();
        assert!(p.z.abs() > 3.0, "z = {}", p.z);
        assert!(warned(&r, WarningCode::ProbeDisagrees));
    }
}

/// Probe recordings whose encoder's zero lies 30° from the arm (it reads 330° when the arm's
/// PIGA end points at the probe; a rotated copy of the campaign's, without arm stretch):
/// declared (`lever.angle_zero_deg: 330.0`), C_r equals the zero-offset study's to 1e-9
/// relative and the
/// two methods agree; undeclared, C_r shrinks with no other sign in the probe phase, and the
/// two-orientation section's disagreement names the angle zero first, with its field.
#[test]
fn an_encoder_zero_off_the_arm_is_exact_declared_and_named_undeclared() {
    let sim = simulate::simulate(&scenario(22, 0.0)).unwrap();
    let right = study(&sim, Declared::Right);
    let declared = study(&sim, Declared::EncoderZeroOff30Stated);
    let c_r = right.phases[0].fit.c_r_m_s2;
    let c_r_declared = declared.phases[0].fit.c_r_m_s2;
    assert!(
        ((c_r_declared - c_r) / c_r).abs() < 1e-9,
        "declared {c_r_declared:e} against {c_r:e}"
    );
    assert!(declared.inputs.angle_zero.stated);
    assert_eq!(declared.inputs.angle_zero.angle_zero_deg, ENCODER_ZERO_DEG);
    assert!(!warned(&declared, WarningCode::ProbeDisagrees));
    assert!(right.inputs.angle_zero.stated && right.inputs.angle_zero.angle_zero_deg == 0.0);

    let undeclared = study(&sim, Declared::EncoderZeroOff30);
    assert!(!undeclared.inputs.angle_zero.stated);
    let c_r_undeclared = undeclared.phases[0].fit.c_r_m_s2;
    assert!(
        ((c_r_undeclared - c_r) / c_r).abs() > 0.05,
        "undeclared {c_r_undeclared:e} against {c_r:e}"
    );
    // nothing in the probe phase itself shows it
    assert!(
        !undeclared
            .warnings
            .iter()
            .any(|w| w.location.starts_with("phases")),
        "{:?}",
        undeclared.warnings
    );
    let p = undeclared
        .two_orientation
        .as_ref()
        .unwrap()
        .probe
        .as_ref()
        .unwrap();
    assert!(p.z.abs() > 3.0, "z = {}", p.z);
    let w = undeclared
        .warnings
        .iter()
        .find(|w| w.code == WarningCode::ProbeDisagrees)
        .expect("the disagreement warning");
    let m = &w.message;
    let at = |needle: &str| {
        m.find(needle)
            .unwrap_or_else(|| panic!("{needle:?} in {m}"))
    };
    // the three declarations first, by the fields a person edits, then arm stretch
    assert!(
        at("`lever.angle_zero_deg` (not stated, so 0° is taken)") < at("`lever.probe_direction`")
    );
    assert!(at("`lever.probe_direction`") < at("`phases[0].points.format.gap.unit` (um)"));
    assert!(at("`phases[0].points.format.gap.unit`") < at("arm stretching"));
    insta::assert_snapshot!("probe_disagrees_undeclared_angle_zero", m);
}

/// A section with a missing radius, the same orientation twice and tables with too few
/// rates: every problem named at once by its field.
#[test]
fn a_bad_section_names_every_problem_at_once() {
    let sim = simulate::simulate(&scenario(23, 0.0)).unwrap();
    let (text, mut files) = probe_study(&sim, Declared::Right);
    let few = b"rate_deg_s,output_rad_s\n50,0.1\n100,0.4\n150,0.9\n".to_vec();
    files.insert(PathBuf::from(DIR).join("a.csv"), few.clone());
    files.insert(PathBuf::from(DIR).join("b.csv"), few);
    let end = text.rfind(')').unwrap();
    let text = format!(
        "{}    two_orientation: (orientations: [(orientation: ia_in, table: (file: \"a.csv\")), \
         (orientation: ia_in, radius_m: 2.54, table: (file: \"b.csv\"))]),\n)\n",
        &text[..end]
    );
    let source = Path::new(DIR).join("study.ron");
    let config = StudyConfig::from_ron(&text, &source).unwrap();
    let err = Inputs::new(config, &source, &Files(files)).unwrap_err();
    let PipelineError::Several { errors } = &err else {
        panic!("{err}")
    };
    let text: Vec<String> = errors.iter().map(|e| super::chain(e)).collect();
    let all = text.join("\n");
    assert_eq!(errors.len(), 4, "{all}");
    assert!(
        text[0].contains("two_orientation.orientations[0].radius_m: the radius is missing"),
        "{all}"
    );
    assert!(
        text[1].contains("two_orientation.orientations[1].orientation: both data sets are `IA in`"),
        "{all}"
    );
    assert!(
        text[2].contains("two_orientation.orientations[0].table")
            && text[2].contains("3 distinct rates"),
        "{all}"
    );
    assert!(
        text[3].contains("two_orientation.orientations[1].table") && text[3].contains("at least 6"),
        "{all}"
    );

    // one data set only
    let sim = simulate::simulate(&scenario(23, 0.0)).unwrap();
    let (text, mut files) = probe_study(&sim, Declared::Right);
    let mut csv = String::from("rate_deg_s,output_rad_s\n");
    for r in &sim.mountings[0].piga {
        csv.push_str(&format!("{:?},{:?}\n", r.rate_deg_s, r.output_rad_s));
    }
    files.insert(PathBuf::from(DIR).join("a.csv"), csv.into_bytes());
    let end = text.rfind(')').unwrap();
    let text = format!(
        "{}    two_orientation: (orientations: [(orientation: ia_in, radius_m: 2.5, table: (file: \"a.csv\"))]),\n)\n",
        &text[..end]
    );
    let config = StudyConfig::from_ron(&text, &source).unwrap();
    let err = Inputs::new(config, &source, &Files(files)).unwrap_err();
    let message = super::chain(&err);
    assert!(
        message.contains("two_orientation.orientations: a two-orientation calibration needs one data set with the IA in and one with the IA out"),
        "{message}"
    );
}

/// Both orientations measured at seven rates bunched at 150–180 deg/s, at the same radius:
/// k2 and C are both poorly known but not correlated, so the correlation warning is silent;
/// the rates' price against the evenly spread design (u(k2) about 95 times, u(C) 7000) gives the
/// warning, with the figure, and the stated U carries it.
#[test]
fn bunched_rates_in_both_orientations_warn() {
    let probe = simulate::simulate(&scenario(24, 0.0)).unwrap();
    let mut bunched = scenario(24, 0.0);
    bunched.scenario.rates_deg_s = (0..7).map(|i| 150.0 + 5.0 * f64::from(i)).collect();
    bunched.scenario.mountings[1].radius_m = bunched.scenario.mountings[0].radius_m;
    let bunched = bunched
        .scenario
        .clone()
        .check(Path::new("campaign.ron"))
        .unwrap();
    let tables = simulate::simulate(&bunched).unwrap();
    let r = study_with_tables(&probe, &tables, Declared::Right);
    let s = r.two_orientation.as_ref().unwrap();
    let spread = s.u_inflation_by_rates.expect("the rates' price");
    assert!(spread.k2 > 30.0 && spread.c > 1000.0, "{spread:?}");
    assert!(
        (spread.reference_top_deg_s - 180.0).abs() < 1e-9,
        "{spread:?}"
    );
    assert!(
        !warned(&r, WarningCode::Omega4NotSeparable),
        "{:?}",
        r.warnings
    );
    let w = r
        .warnings
        .iter()
        .find(|w| w.code == WarningCode::TwoOrientationRatesBunched)
        .expect("the bunched rates are warned");
    assert!(w.message.contains("from 18 to 180 deg/s"), "{}", w.message);
    // the stated U says how poorly k2 is known: far wider than the spread design's
    let ordinary = study(&probe, Declared::Right);
    assert!(
        s.k2.u95 > 50.0 * ordinary.two_orientation.as_ref().unwrap().k2.u95,
        "{:?}",
        s.k2
    );
}
