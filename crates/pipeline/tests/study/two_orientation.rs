//! The two-orientation calibration (issue 20) closed through the exact chain: the two-orientation
//! fit recovers k2 and C = C_r + C_a; the probe's C_r (from the study's probe phase, with
//! its declarations) misses the arm stretch with |z| > 3, agrees with |z| < 3 without one,
//! and a wrong probe declaration (sign, µm for a mm column) gives the warning; coverage of
//! the two-orientation k2 over simulated campaigns.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use calibration::{
    OrientationData, ProbeCr, TwoOrientationError, TwoOrientationEvaluation, TwoOrientationFit,
    TwoOrientationWarning, evaluate_two_orientation, fit_two_orientation,
};
use pipeline::{Inputs, StudyConfig};
use rayon::prelude::*;
use simulate::{Mount, MountingSpec, Orientation, OutputNoise, Scenario, Simulation};

use crate::root;

pub(crate) const C_R: f64 = 1.6e-6;
pub(crate) const K2: f64 = 5.0e-7;
const G: f64 = 9.8;
const R_IN: f64 = 2.5;
const R_OUT: f64 = 2.54;
const TABLE_NOISE_RAD_S: f64 = 1e-9;

fn rates_deg_s() -> Vec<f64> {
    (0..12).map(|i| 35.0 + 15.0 * f64::from(i)).collect()
}

/// The campaign scenario with both mountings (R_out = R_in + 40 mm, a bias shift of
/// 4e-6 rad/s), an arm stretch `c_a`, table noise 1e-7 rad/s and 12 rates.
pub(crate) fn scenario(seed: u64, c_a: f64) -> simulate::LoadedScenario {
    let text = std::fs::read_to_string(root().join("fixtures/scenarios/campaign.ron")).unwrap();
    let mut loaded = Scenario::parse(&text, Path::new("campaign.ron")).unwrap();
    let s = &mut loaded.scenario;
    s.seed = seed;
    s.piga.noise_rad_s = TABLE_NOISE_RAD_S;
    s.piga.recordings = None;
    s.rates_deg_s = rates_deg_s();
    s.arm_stretch_m_s2 = c_a;
    s.mountings = vec![
        MountingSpec {
            orientation: Orientation::IaIn,
            radius_m: R_IN,
            bias_shift_rad_s: 0.0,
        },
        MountingSpec {
            orientation: Orientation::IaOut,
            radius_m: R_OUT,
            bias_shift_rad_s: 4e-6,
        },
    ];
    s.clone().check(Path::new("campaign.ron")).unwrap()
}

/// The joint fit of a simulation's two mounting tables.
fn fit_tables(sim: &Simulation) -> TwoOrientationFit {
    let tables: Vec<(calibration::Orientation, f64, Vec<f64>, Vec<f64>)> = sim
        .mountings
        .iter()
        .map(|m| {
            (
                m.orientation,
                m.radius_m,
                m.piga.iter().map(|r| r.rate_deg_s.to_radians()).collect(),
                m.piga.iter().map(|r| r.output_rad_s).collect(),
            )
        })
        .collect();
    let fields = [
        "two_orientation.orientations[0]",
        "two_orientation.orientations[1]",
    ];
    let data: Vec<OrientationData<'_>> = tables
        .iter()
        .zip(fields)
        .map(|((o, r, w, y), field)| OrientationData {
            field,
            orientation: Some(*o),
            radius_m: Some(*r),
            rates_rad_s: w,
            output_rad_s: y,
            sigma_rad_s: None,
        })
        .collect();
    fit_two_orientation(&data, G, "two_orientation.orientations").unwrap()
}

/// Probe recordings in memory for the study's probe phase.
use test_support::MemoryFiles as Files;

pub(crate) const DIR: &str = "/nonexistent/two_orientation";

/// How the lab declares its probe in the study.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Declared {
    /// As it is.
    Right,
    /// Measuring along O1X1 while it measures against.
    WrongSign,
    /// The gap column holds mm, the study reads µm (the default unit).
    MillimetresReadAsMicrometres,
    /// The encoder reads 330° when the arm's PIGA end points at the probe (its zero 30°
    /// past the arm's reference), and the study does not say so.
    EncoderZeroOff30,
    /// The same encoder, declared: `lever.angle_zero_deg: 330.0`.
    EncoderZeroOff30Stated,
}

/// The encoder's reading at the angle zero in [`Declared::EncoderZeroOff30`], deg: its zero
/// 30° from the arm's reference, on the side where the campaign's imbalance (about 14° from
/// the arm) makes the error large (C_r × 0.74; 30° the other way gives × 0.99).
pub(crate) const ENCODER_ZERO_DEG: f64 = 330.0;

/// The campaign study's probe phase on the simulation's probe recordings, as the lab
/// declares the probe: the study text (no calibration section) and its files in memory.
pub(crate) fn probe_study(
    sim: &Simulation,
    declared: Declared,
) -> (String, HashMap<PathBuf, Vec<u8>>) {
    let mut files = HashMap::new();
    for r in &sim.recordings {
        let mut r = r.clone();
        if declared == Declared::MillimetresReadAsMicrometres {
            r.gap_um.iter_mut().for_each(|g| *g *= 1e-3);
        }
        if matches!(
            declared,
            Declared::EncoderZeroOff30 | Declared::EncoderZeroOff30Stated
        ) {
            // the same samples, read by an encoder whose zero lies 30° past the arm's
            // reference: it reads 330° more (30° less), wrapping at 360°
            let angles = r
                .angle_deg
                .as_mut()
                .expect("the campaign records the encoder");
            angles
                .iter_mut()
                .for_each(|a| *a = (*a + ENCODER_ZERO_DEG).rem_euclid(360.0));
        }
        let mut csv = Vec::new();
        r.write_csv(&mut csv).unwrap();
        files.insert(Path::new(DIR).join(&r.file_name), csv);
    }
    let text = std::fs::read_to_string(root().join("fixtures/studies/campaign.ron")).unwrap();
    let cut = text.find("    calibration: (").unwrap();
    let mut text = format!("{})\n", &text[..cut]).replace("../campaign/", "");
    // the rates of this campaign
    let start = text.find("files: [").unwrap() + "files: [".len();
    let end = start + text[start..].find(']').unwrap();
    let files_list: String = rates_deg_s()
        .iter()
        .map(|&w| {
            format!(
                "(rate_deg_s: {w:.1}, file: \"{}\"),",
                simulate::recording_file_name(w)
            )
        })
        .collect();
    text.replace_range(start..end, &files_list);
    if declared == Declared::WrongSign {
        text = text.replace(
            "probe_direction: against_o1_x1",
            "probe_direction: along_o1_x1",
        );
    }
    // the campaign study states its encoder's angle zero (0°)
    match declared {
        Declared::EncoderZeroOff30Stated => {
            text = text.replace(
                "angle_zero_deg: 0.0",
                &format!("angle_zero_deg: {ENCODER_ZERO_DEG:?}"),
            );
        }
        Declared::EncoderZeroOff30 => text = text.replace(", angle_zero_deg: 0.0", ""),
        _ => {}
    }
    (text, files)
}

/// C_r from the study's probe phase, as the lab declares the probe: the campaign study's
/// probe phase on the simulation's probe recordings.
fn probe_c_r(sim: &Simulation, declared: Declared) -> ProbeCr {
    let (text, files) = probe_study(sim, declared);
    let source = Path::new(DIR).join("study.ron");
    let config = StudyConfig::from_ron(&text, &source).unwrap();
    let inputs = Inputs::new(config, &source, &Files(files)).unwrap();
    let results = pipeline::run(&inputs).unwrap();
    let fit = &results.phases[0].fit;
    ProbeCr {
        c_r_m_s2: fit.c_r_m_s2,
        u_m_s2: fit.c_r_sigma_m_s2.unwrap(),
        dof: Some(fit.dof as f64),
        // the campaign study's lever
        pivot_to_probe_mm: 700.0,
        probe_to_piga_mm: 510.0,
    }
}

fn evaluate(fit: &TwoOrientationFit, probe: ProbeCr) -> TwoOrientationEvaluation {
    let type_b = calibration::TypeB {
        g_u_m_s2: 1e-5,
        ..calibration::TypeB::default()
    };
    evaluate_two_orientation(fit, &type_b, Some(probe), None).unwrap()
}

fn disagrees(e: &TwoOrientationEvaluation) -> bool {
    e.warnings
        .iter()
        .any(|w| matches!(w, TwoOrientationWarning::ProbeDisagrees { .. }))
}

/// C_a = 0.3·C_r, R_out = R_in + 40 mm, a bias shift: the two-orientation fit recovers k2 and C
/// within U95, the probe's C_r misses C_a with |z| > 3; with C_a = 0, |z| < 3.
#[test]
fn the_two_orientation_fit_sees_the_arm_stretch_the_probe_misses() {
    let c_a = 0.3 * C_R;
    let sim = simulate::simulate(&scenario(21, c_a)).unwrap();
    let fit = fit_tables(&sim);
    let probe = probe_c_r(&sim, Declared::Right);
    let e = evaluate(&fit, probe);
    let out = |name: &str| e.gum.output(name).unwrap().clone();
    let k2 = out("k2");
    let c = out("C");
    assert!(
        (k2.estimate - K2).abs() < k2.expanded_uncertainty,
        "k2 {} ± {} vs {K2}",
        k2.estimate,
        k2.expanded_uncertainty
    );
    assert!(
        (c.estimate - (C_R + c_a)).abs() < c.expanded_uncertainty,
        "C {} ± {} vs {}",
        c.estimate,
        c.expanded_uncertainty,
        C_R + c_a
    );
    // the probe measures the spindle only
    assert!((probe.c_r_m_s2 - C_R).abs() < 3.0 * probe.u_m_s2 + 1e-9);
    let (diff, u, z) = e.probe_difference.unwrap();
    assert!(z > 3.0, "z = {z}, C − C_r = {diff} ± {u}");
    assert!(
        (diff - c_a).abs() < 3.0 * u,
        "C − C_r = {diff} ± {u}, C_a = {c_a}"
    );
    assert!(disagrees(&e));
    // the same campaign without arm stretch agrees with the probe
    let sim0 = simulate::simulate(&scenario(21, 0.0)).unwrap();
    let e0 = evaluate(&fit_tables(&sim0), probe_c_r(&sim0, Declared::Right));
    let (_, _, z0) = e0.probe_difference.unwrap();
    assert!(z0.abs() < 3.0, "z = {z0}");
    assert!(!disagrees(&e0));
    // Over 35–200 deg/s the s·ω⁴ column's VIF is about 1e6 (above issue 20's 1e4), yet C is
    // known to a few per cent and fitting it hardly widens u(k2): nothing is said.
    assert!(fit.gamma_vif > 1e4, "VIF {}", fit.gamma_vif);
    assert!(fit.k2_inflation < 2.0, "{}", fit.k2_inflation);
    assert!(fit.separable());
    assert!(
        !e.warnings
            .iter()
            .any(|w| matches!(w, TwoOrientationWarning::GammaNotSeparable { .. }))
    );
}

/// The worked campaign of docs/TWO_ORIENTATION.md: the fixture's tables and probe recordings
/// (`fixtures/two_orientation/`) give k2 and C within U95 of the truth, and C − C_r with |z| > 3.
#[test]
fn the_worked_campaign_of_the_guide() {
    let dir = root().join("fixtures/two_orientation");
    let read = |name: &str| -> (Vec<f64>, Vec<f64>) {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        text.lines()
            .skip(1)
            .map(|l| {
                let (w, y) = l.split_once(',').unwrap();
                (
                    w.parse::<f64>().unwrap().to_radians(),
                    y.parse::<f64>().unwrap(),
                )
            })
            .unzip()
    };
    let (w_in, y_in) = read("piga_ia_in.csv");
    let (w_out, y_out) = read("piga_ia_out.csv");
    let data = [
        OrientationData {
            field: "orientations[0]",
            orientation: Some(calibration::Orientation::IaIn),
            radius_m: Some(R_IN),
            rates_rad_s: &w_in,
            output_rad_s: &y_in,
            sigma_rad_s: None,
        },
        OrientationData {
            field: "orientations[1]",
            orientation: Some(calibration::Orientation::IaOut),
            radius_m: Some(R_OUT),
            rates_rad_s: &w_out,
            output_rad_s: &y_out,
            sigma_rad_s: None,
        },
    ];
    let fit = fit_two_orientation(&data, G, "orientations").unwrap();
    let text =
        std::fs::read_to_string(root().join("fixtures/scenarios/two_orientation.ron")).unwrap();
    let loaded = Scenario::parse(&text, Path::new("two_orientation.ron")).unwrap();
    let sim = simulate::simulate(&loaded).unwrap();
    let probe = probe_c_r(&sim, Declared::Right);
    let e = evaluate(&fit, probe);
    let k2 = e.gum.output("k2").unwrap();
    let c = e.gum.output("C").unwrap();
    let (d, u, z) = e.probe_difference.unwrap();
    let summary = format!(
        "k2 {:e} U {:e}; C {:e} U {:e}; C_r {:e} u {:e}; C-C_r {d:e} u {u:e} z {z}; VIF {:e}; k1in {:?} k1out {:?} k0in {:?} k0out {:?} dk2 {:e}",
        k2.estimate,
        k2.expanded_uncertainty,
        c.estimate,
        c.expanded_uncertainty,
        probe.c_r_m_s2,
        probe.u_m_s2,
        fit.gamma_vif,
        fit.mountings[0].k1_rad_s_g,
        fit.mountings[1].k1_rad_s_g,
        fit.mountings[0].k0_rad_s,
        fit.mountings[1].k0_rad_s,
        e.gum.output("Δk2,total").unwrap().estimate,
    );
    assert!(
        (k2.estimate - K2).abs() < k2.expanded_uncertainty,
        "{summary}"
    );
    assert!(
        (c.estimate - 2.08e-6).abs() < c.expanded_uncertainty,
        "{summary}"
    );
    assert!(z > 3.0, "{summary}");
}

/// A probe declared with the wrong sign convention, or read in µm from a mm column: the
/// PIGA's two orientations contradict it, and the study says so.
#[test]
fn a_wrong_probe_declaration_gives_the_warning() {
    let sim = simulate::simulate(&scenario(22, 0.0)).unwrap();
    let fit = fit_tables(&sim);
    for declared in [Declared::WrongSign, Declared::MillimetresReadAsMicrometres] {
        let probe = probe_c_r(&sim, declared);
        let e = evaluate(&fit, probe);
        let (diff, u, z) = e.probe_difference.unwrap();
        assert!(z.abs() > 3.0, "C − C_r = {diff} ± {u}, z = {z}");
        assert!(disagrees(&e));
    }
}

/// Over 1000 simulated campaigns (tables through the exact chain, fresh noise each) the
/// two-orientation k2's 95 % interval holds the true k2 in 92–98 % of them, and the mean reported
/// u(k2) matches the spread of k2 within 10 %.
#[test]
fn the_two_orientation_k2_interval_covers_the_truth() {
    let base = scenario(0, 0.3 * C_R);
    let s = &base.scenario;
    let centrifuge = kinematics::Centrifuge {
        radius_m: s.centrifuge.radius_m,
        site: s.centrifuge.site,
        error_motion: base.error_motion,
    };
    let piga = s.piga.coefficients;
    let campaigns = 1000;
    let results: Vec<(f64, f64, bool)> = (0..campaigns)
        .into_par_iter()
        .map(|seed| {
            let noise = OutputNoise {
                sigma_rad_s: TABLE_NOISE_RAD_S,
                seed: 1000 + seed,
            };
            let tables: Vec<(calibration::Orientation, f64, Vec<f64>, Vec<f64>)> = s
                .mountings
                .iter()
                .map(|m| {
                    let mount: Mount = m.mount(s.arm_stretch_m_s2);
                    let rows = simulate::piga_table_mounted(
                        &centrifuge,
                        &piga,
                        &mount,
                        &s.rates_deg_s,
                        &noise,
                    )
                    .unwrap();
                    (
                        m.orientation,
                        m.radius_m,
                        rows.iter().map(|r| r.rate_deg_s.to_radians()).collect(),
                        rows.iter().map(|r| r.output_rad_s).collect(),
                    )
                })
                .collect();
            let data: Vec<OrientationData<'_>> = tables
                .iter()
                .map(|(o, r, w, y)| OrientationData {
                    field: "t",
                    orientation: Some(*o),
                    radius_m: Some(*r),
                    rates_rad_s: w,
                    output_rad_s: y,
                    sigma_rad_s: None,
                })
                .collect();
            let fit = fit_two_orientation(&data, G, "t").unwrap();
            let e =
                evaluate_two_orientation(&fit, &calibration::TypeB::default(), None, None).unwrap();
            let k2 = e.gum.output("k2").unwrap();
            let (lo, hi) = k2.coverage_interval();
            (k2.estimate, k2.standard_uncertainty, lo <= K2 && K2 <= hi)
        })
        .collect();
    let n = results.len() as f64;
    let covered = results.iter().filter(|r| r.2).count() as f64 / n;
    let mean = results.iter().map(|r| r.0).sum::<f64>() / n;
    let spread = (results.iter().map(|r| (r.0 - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let mean_u = results.iter().map(|r| r.1).sum::<f64>() / n;
    assert!((0.92..=0.98).contains(&covered), "coverage {covered}");
    assert!(
        (mean_u / spread - 1.0).abs() < 0.10,
        "mean u {mean_u:e} over spread {spread:e}"
    );
}

/// One orientation only, both the same, too few rates, a missing radius: typed errors
/// naming the field.
#[test]
fn bad_orientation_sets_are_refused_by_field() {
    let w: Vec<f64> = rates_deg_s().iter().map(|d| d.to_radians()).collect();
    let y = vec![0.0; w.len()];
    let set = |field, o, r| OrientationData {
        field,
        orientation: o,
        radius_m: r,
        rates_rad_s: &w,
        output_rad_s: &y,
        sigma_rad_s: None,
    };
    let ia_in = Some(calibration::Orientation::IaIn);
    let ia_out = Some(calibration::Orientation::IaOut);
    let one = [set("o[0]", ia_in, Some(2.5))];
    assert!(matches!(
        fit_two_orientation(&one, G, "o"),
        Err(TwoOrientationError::OneOrientationOnly { field, .. }) if field == "o"
    ));
    let same = [
        set("o[0]", ia_in, Some(2.5)),
        set("o[1]", ia_in, Some(2.54)),
    ];
    assert!(matches!(
        fit_two_orientation(&same, G, "o"),
        Err(TwoOrientationError::SameOrientation { field, first, .. }) if field == "o[1]" && first == "o[0]"
    ));
    let no_radius = [set("o[0]", ia_in, Some(2.5)), set("o[1]", ia_out, None)];
    assert!(matches!(
        fit_two_orientation(&no_radius, G, "o"),
        Err(TwoOrientationError::MissingRadius { field }) if field == "o[1]"
    ));
    let few = OrientationData {
        rates_rad_s: &w[..5],
        output_rad_s: &y[..5],
        ..set("o[1]", ia_out, Some(2.54))
    };
    let too_few = [set("o[0]", ia_in, Some(2.5)), few];
    assert!(matches!(
        fit_two_orientation(&too_few, G, "o"),
        Err(TwoOrientationError::TooFewRates { field, distinct: 5, need: 6, .. }) if field == "o[1]"
    ));
}

/// IA in over 35–200 °/s, IA out at 35–60 °/s only: IA out's ω⁴ coefficient is barely
/// known, so k2 and C both rest on IA in's and cannot be told apart (ρ ≈ −0.98, u(k2) five
/// times what it is with C known). The fit says so. (Equal radii and bunched rates do not:
/// there k2 and C come from the sum and difference of the mountings' ω⁴ coefficients,
/// uncorrelated, however large the VIF.)
#[test]
fn an_inseparable_omega4_term_is_reported() {
    let w: Vec<f64> = (0..12)
        .map(|i| (35.0 + 15.0 * f64::from(i)).to_radians())
        .collect();
    let wo: Vec<f64> = (0..6)
        .map(|i| (35.0 + 5.0 * f64::from(i)).to_radians())
        .collect();
    let y: Vec<f64> = w
        .iter()
        .map(|w| 0.56 * 2.5 * w * w / G + 1e-9 * w)
        .collect();
    let yo: Vec<f64> = wo.iter().map(|w| -0.56 * 2.54 * w * w / G).collect();
    let data = [
        OrientationData {
            field: "o[0]",
            orientation: Some(calibration::Orientation::IaIn),
            radius_m: Some(2.5),
            rates_rad_s: &w,
            output_rad_s: &y,
            sigma_rad_s: None,
        },
        OrientationData {
            field: "o[1]",
            orientation: Some(calibration::Orientation::IaOut),
            radius_m: Some(2.54),
            rates_rad_s: &wo,
            output_rad_s: &yo,
            sigma_rad_s: None,
        },
    ];
    let fit = fit_two_orientation(&data, G, "o").unwrap();
    assert!(!fit.separable(), "{}", fit.k2_inflation);
    assert!(fit.k2_inflation > 5.0, "{}", fit.k2_inflation);
    let e = evaluate_two_orientation(&fit, &calibration::TypeB::default(), None, None).unwrap();
    let w = e
        .warnings
        .iter()
        .find_map(|w| match *w {
            TwoOrientationWarning::GammaNotSeparable { k2_inflation, .. } => Some(k2_inflation),
            TwoOrientationWarning::ProbeDisagrees { .. } => None,
        })
        .expect("the warning");
    assert_eq!(w, fit.k2_inflation);
    // the study's words give the figure
    let words = pipeline::Warning::omega4_not_separable(
        fit.k2_inflation,
        fit.k2_gamma_correlation,
        calibration::K2_INFLATION_LIMIT,
        fit.gamma_vif,
    );
    let figure = format!("u(k2) {:.1} times", fit.k2_inflation);
    assert!(words.message.contains(&figure), "{}", words.message);
}

/// The Earth rate about the spindle axis (issue 31): a latitude beyond ±90° is refused by its
/// field; stated with the spin, it is the budget's value with u 0; the latitude alone, an
/// uncertainty of ±Ω·|sin L|; neither, ±Ω.
#[test]
fn the_earth_rate_is_stated_in_part_or_not_at_all_and_the_budget_says_which() {
    let path = root().join("fixtures/studies/two_orientation.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("latitude_deg: 39.9,")
            && text.contains("spin_seen_from_above: counterclockwise,")
    );
    let with = |latitude: &str, spin: &str| {
        let t = text
            .replace("latitude_deg: 39.9,", latitude)
            .replace("spin_seen_from_above: counterclockwise,", spin);
        StudyConfig::from_ron(&t, &path).and_then(|c| Inputs::new(c, &path, &pipeline::Files))
    };
    let refused = with("latitude_deg: 95.0,", "").unwrap_err().to_string();
    assert!(
        refused.contains("two_orientation.latitude_deg"),
        "{refused}"
    );
    assert!(refused.contains("±90"), "{refused}");
    let earth = |latitude: &str, spin: &str| {
        pipeline::run(&with(latitude, spin).unwrap())
            .unwrap()
            .two_orientation
            .unwrap()
            .earth_rate
    };
    let stated = earth("latitude_deg: 39.9,", "spin_seen_from_above: clockwise,");
    let omega_v = 7.292_115e-5 * 39.9_f64.to_radians().sin();
    assert!((stated.value_rad_s + omega_v).abs() < 1e-15, "{stated:?}");
    assert_eq!(stated.half_width_rad_s, 0.0);
    assert!(
        stated
            .words
            .starts_with("stated: latitude 39.9°, spin clockwise"),
        "{stated:?}"
    );
    let latitude_only = earth("latitude_deg: 39.9,", "");
    assert_eq!(latitude_only.value_rad_s, 0.0);
    assert!((latitude_only.half_width_rad_s - omega_v).abs() < 1e-15);
    assert!(
        latitude_only.words.contains("spin is not stated"),
        "{latitude_only:?}"
    );
    let neither = earth("", "");
    assert_eq!(neither.half_width_rad_s, 7.292_115e-5);
    assert!(neither.words.contains("72.9 µrad/s"), "{neither:?}");
}
