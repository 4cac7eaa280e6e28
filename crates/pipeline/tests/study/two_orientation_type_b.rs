//! The two-orientation budget with the study's Type B inputs (issue 20): u(R) of each
//! mounting, g and the rate scale in k2 and C; the probe's lever heights and gain in C − C_r;
//! k2 by the probe method through the calibration section's model. Coverage over simulated
//! campaigns whose true radii, g and rates differ from the declared ones by draws from the
//! declared u.

use calibration::{OrientationData, TypeB, evaluate_two_orientation, fit_two_orientation};
use pipeline::{PipelineError, StudyResults, WarningCode};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;
use simulate::{Mount, OutputNoise, Simulation};

use super::two_orientation::{C_R, Declared, K2, scenario};

const G: f64 = 9.8;

/// The campaign's Type B inputs (`fixtures/studies/campaign.ron`'s `uncertainty`).
const CAMPAIGN_UNCERTAINTY: &str = "uncertainty: (radius_u_m: 5.0e-6, g_u_m_s2: 1.0e-5, \
     rate_u_relative: 1.0e-6, pivot_to_probe_u_mm: 0.5, probe_to_piga_u_mm: 0.5, \
     probe_gain_u_relative: 2.0e-3),";

/// The probe phase on the simulation, then `sections` (RON fields of the study), then the
/// two-orientation section on the two mounting tables; run.
fn study(sim: &Simulation, sections: &str) -> Result<StudyResults, PipelineError> {
    super::two_orientation_study::tables_study(sim, sim, Declared::Right, sections)
}

/// The budget's line for `quantity` (its first words).
fn line<'a>(lines: &'a [pipeline::BudgetLine], quantity: &str) -> Option<&'a pipeline::BudgetLine> {
    lines.iter().find(|l| l.quantity.starts_with(quantity))
}

/// The campaign's Type B inputs in the two-orientation budget, in words: u(R) of each
/// mounting, g and the rate scale in k2's; no g in C's (C does not depend on it); the probe's
/// lever heights, gain and C_r in C − C_r's. No warning about inputs left out.
#[test]
fn the_budget_carries_every_type_b_input_in_words() {
    let sim = simulate::simulate(&scenario(21, 0.3 * C_R)).unwrap();
    let r = study(&sim, CAMPAIGN_UNCERTAINTY).unwrap();
    let s = r.two_orientation.as_ref().unwrap();
    let k2 = &s.budget.k2;
    for q in [
        "g (gravity)",
        "rate scale (common to every rate)",
        "R of the IA-in mounting",
        "R of the IA-out mounting",
    ] {
        let l = line(k2, q).unwrap_or_else(|| panic!("{q} in {k2:?}"));
        assert_eq!(l.evaluation, "B");
        assert!(l.contribution > 0.0, "{l:?}");
    }
    // k2 ∝ g²: ∂k2/∂g = 2·k2/g
    let g = line(k2, "g (gravity)").unwrap();
    assert!(
        (g.sensitivity / (2.0 * s.k2.value / G) - 1.0).abs() < 1e-4,
        "{g:?}"
    );
    let r_in = line(k2, "R of the IA-in mounting").unwrap();
    assert_eq!(r_in.u, 5.0e-6);
    assert_eq!(line(k2, "R of the IA-out mounting").unwrap().u, 5.0e-6);
    assert!(
        line(&s.budget.c, "g (gravity)").is_none(),
        "{:?}",
        s.budget.c
    );
    assert!(line(&s.budget.c, "R of the IA-out mounting").is_some());
    let d = s.budget.difference.as_ref().expect("a probe phase");
    for q in [
        "pivot-to-probe height",
        "probe-to-PIGA height",
        "probe gain",
        "C_r (probe)",
    ] {
        assert!(line(d, q).is_some(), "{q} in {d:?}");
    }
    // the probe gain's 2e-3 of C_r = 1.6e-6
    let gain = line(d, "probe gain").unwrap();
    assert!(
        (gain.contribution / (2e-3 * C_R) - 1.0).abs() < 1e-3,
        "{gain:?}"
    );
    // words: no configuration keys or Rust names in the quantities
    for l in k2.iter().chain(&s.budget.c).chain(d) {
        assert!(
            !l.quantity.contains('_') || l.quantity.contains("C_r"),
            "{l:?}"
        );
        if l.quantity.starts_with("Earth rate about the spindle axis") {
            // what the section states of the site and spin, or that it states nothing
            assert!(
                l.note.as_deref().is_some_and(|n| n.contains("stated")),
                "{l:?}"
            );
        } else {
            assert!(l.note.is_none(), "every input is stated: {l:?}");
        }
    }
    assert!(
        r.warnings
            .iter()
            .all(|w| w.code == WarningCode::ProbeDisagrees),
        "{:?}",
        r.warnings
    );
    // u(k1,s) now holds u(R)/R and the rate scale: k1 ∝ 1/R, ∝ 1/σ²
    let k1 = &s.mountings[0].k1;
    let relative = (5.0e-6f64 / 2.5).hypot(2.0 * 1.0e-6);
    assert!(k1.u >= relative * k1.value, "{k1:?}");
}

/// Every line of the two-orientation budgets carries its unit as data (issue 31): each input
/// its own, the fit's line (the first) its output's.
#[test]
fn every_budget_line_carries_its_unit() {
    let sim = simulate::simulate(&scenario(21, 0.3 * C_R)).unwrap();
    let r = study(&sim, CAMPAIGN_UNCERTAINTY).unwrap();
    let s = r.two_orientation.as_ref().unwrap();
    let d = s.budget.difference.as_ref().expect("a probe phase");
    for (lines, output_unit) in [
        (&s.budget.k2, "rad/(s·g²)"),
        (&s.budget.c, "m·s²"),
        (d, "m·s²"),
    ] {
        assert!(
            lines[0].quantity.starts_with("PIGA mean outputs"),
            "{lines:?}"
        );
        assert_eq!(lines[0].unit, output_unit, "{:?}", lines[0]);
        for l in &lines[1..] {
            let q = l.quantity.as_str();
            let want = if q.starts_with("R of the IA-") {
                "m"
            } else if q.starts_with("Earth rate about the spindle axis") {
                "rad/s"
            } else {
                match q {
                    "g (gravity)" => "m/s²",
                    "rate scale (common to every rate)" | "probe gain" => "1 (relative)",
                    "pivot-to-probe height" | "probe-to-PIGA height" => "mm",
                    "C_r (probe)" => "m·s²",
                    other => panic!("an input this test does not know: {other}"),
                }
            };
            assert_eq!(l.unit, want, "{l:?}");
        }
    }
}

/// The `uncertainty` section is read as the calibration section reads it: an input it does
/// not state is refused by its field (every one at once), a negative one too; without the
/// section every input is 0 and the budget says so beside each.
#[test]
fn an_unstated_input_is_refused_and_no_section_is_said_so() {
    let sim = simulate::simulate(&scenario(21, 0.3 * C_R)).unwrap();
    let e = study(
        &sim,
        "uncertainty: (g_u_m_s2: 1.0e-5, radius_u_m: -1.0e-3),",
    )
    .unwrap_err();
    let PipelineError::Several { errors } = &e else {
        panic!("{e}")
    };
    let fields: Vec<String> = errors
        .iter()
        .map(|e| match e {
            PipelineError::InvalidField { field, .. }
            | PipelineError::MissingField { field, .. } => field.clone(),
            other => panic!("{other}"),
        })
        .collect();
    assert_eq!(
        fields,
        [
            "uncertainty.radius_u_m",
            "uncertainty.rate_u_relative",
            "uncertainty.pivot_to_probe_u_mm",
            "uncertainty.probe_to_piga_u_mm",
            "uncertainty.probe_gain_u_relative",
        ],
        "{e}"
    );
    assert!(
        matches!(&errors[0], PipelineError::InvalidField { .. }),
        "{e}"
    );
    // no uncertainty section at all
    let r = study(&sim, "").unwrap();
    let s = r.two_orientation.as_ref().unwrap();
    for line_name in ["R of the IA-in mounting", "g (gravity)"] {
        let l = line(&s.budget.k2, line_name);
        assert!(l.is_none_or(|l| l.u == 0.0), "{l:?}");
    }
    let gain = line(s.budget.difference.as_ref().unwrap(), "probe gain").unwrap();
    assert_eq!(
        gain.note.as_deref(),
        Some("not stated (the study has no `uncertainty` section): taken as 0")
    );
}

/// k2 by the probe method is the calibration section's k2 when both calibrate the IA-in
/// table at its radius with the same probe phase and Type B inputs: the same value, u and U95.
#[test]
fn the_probe_method_k2_is_the_calibration_sections() {
    let sim = simulate::simulate(&scenario(21, 0.3 * C_R)).unwrap();
    let calibration = "calibration: (table: (file: \"piga_ia_in.csv\"), \
                       compensate_with: \"spindle\", k1: fitted, seed: 1, trials: fixed(2000)),";
    let r = study(&sim, &format!("{calibration}\n    {CAMPAIGN_UNCERTAINTY}")).unwrap();
    let p = r.two_orientation.as_ref().unwrap().probe.as_ref().unwrap();
    let c = r.calibration.as_ref().unwrap().coefficients.k2;
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    assert!(rel(p.k2_probe.value, c.value) < 1e-12, "{p:?} vs {c:?}");
    assert!(rel(p.k2_probe.u, c.u) < 1e-9, "{p:?} vs {c:?}");
    assert!(rel(p.k2_probe_u95, c.u95) < 1e-9, "{p:?} vs {c:?}");
    // with the Type B inputs and the fit's 6 degrees of freedom, k is not 2
    assert!(p.k2_probe_u95 / p.k2_probe.u > 2.1, "{p:?}");
}

/// What one simulated campaign gives: per output (k2, C), the estimate, its u and whether
/// the 95 % interval holds the truth, with the Type B inputs and without them.
struct Outcome {
    k2: (f64, f64, bool, bool),
    c: (f64, f64, bool, bool),
}

/// `campaigns` campaigns through the exact chain (IA in at 2.5 m, IA out at 2.54 m, C_a =
/// 0.3·C_r, 12 rates 35–200 deg/s, `noise_rad_s` per rate), each with its true radii, site
/// gravity and rate scale drawn from the declared values and `type_b`'s u; fitted and
/// evaluated at the declared values.
fn campaigns(noise_rad_s: f64, type_b: &TypeB, campaigns: u64) -> Vec<Outcome> {
    let base = scenario(0, 0.3 * C_R);
    let s = &base.scenario;
    let piga = s.piga.coefficients;
    let truth_c = C_R + 0.3 * C_R;
    (0..campaigns)
        .into_par_iter()
        .map(|seed| {
            let mut rng = StdRng::seed_from_u64(7000 + seed);
            let mut draw = |u: f64| Normal::new(0.0, u).unwrap().sample(&mut rng);
            let mut site = s.centrifuge.site;
            site.gravity_m_s2 = G + draw(type_b.g_u_m_s2);
            let scale = 1.0 + draw(type_b.rate_u_relative);
            let centrifuge = kinematics::Centrifuge {
                radius_m: s.centrifuge.radius_m,
                site,
                error_motion: base.error_motion,
            };
            let noise = OutputNoise {
                sigma_rad_s: noise_rad_s,
                seed: 5000 + seed,
            };
            let true_rates: Vec<f64> = s.rates_deg_s.iter().map(|w| w * scale).collect();
            let tables: Vec<(calibration::Orientation, f64, Vec<f64>, Vec<f64>)> = s
                .mountings
                .iter()
                .map(|m| {
                    let mut mount: Mount = m.mount(s.arm_stretch_m_s2);
                    mount.radius_m = m.radius_m + draw(type_b.radius_u_m);
                    let rows = simulate::piga_table_mounted(
                        &centrifuge,
                        &piga,
                        &mount,
                        &true_rates,
                        &noise,
                    )
                    .unwrap();
                    // the table holds the declared rates
                    (
                        m.orientation,
                        m.radius_m,
                        s.rates_deg_s.iter().map(|w| w.to_radians()).collect(),
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
            let with = evaluate_two_orientation(&fit, type_b, None, None).unwrap();
            let without = evaluate_two_orientation(&fit, &TypeB::default(), None, None).unwrap();
            let of = |name: &str, truth: f64| {
                let o = with.gum.output(name).unwrap();
                let (lo, hi) = o.coverage_interval();
                let (lo0, hi0) = without.gum.output(name).unwrap().coverage_interval();
                (
                    o.estimate,
                    o.standard_uncertainty,
                    lo <= truth && truth <= hi,
                    lo0 <= truth && truth <= hi0,
                )
            };
            Outcome {
                k2: of("k2", K2),
                c: of("C", truth_c),
            }
        })
        .collect()
}

/// Coverage with and without the Type B inputs, and the mean u over the spread of the
/// estimates, for one output.
fn summary(outcomes: &[(f64, f64, bool, bool)]) -> (f64, f64, f64) {
    let n = outcomes.len() as f64;
    let covered = outcomes.iter().filter(|o| o.2).count() as f64 / n;
    let covered_without = outcomes.iter().filter(|o| o.3).count() as f64 / n;
    let mean = outcomes.iter().map(|o| o.0).sum::<f64>() / n;
    let spread = (outcomes.iter().map(|o| (o.0 - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let mean_u = outcomes.iter().map(|o| o.1).sum::<f64>() / n;
    (covered, covered_without, mean_u / spread)
}

#[allow(clippy::print_stderr)] // the figures, shown with --nocapture
fn check(what: &str, noise_rad_s: f64, type_b: &TypeB, under: [bool; 2]) {
    let outcomes = campaigns(noise_rad_s, type_b, 1000);
    for (name, list, under) in [
        (
            "k2",
            outcomes.iter().map(|o| o.k2).collect::<Vec<_>>(),
            under[0],
        ),
        ("C", outcomes.iter().map(|o| o.c).collect(), under[1]),
    ] {
        let (covered, without, ratio) = summary(&list);
        eprintln!(
            "{what}, {name}: coverage {covered:.3} ({without:.3} without the Type B inputs), mean u over spread {ratio:.3}"
        );
        assert!(
            (0.92..=0.98).contains(&covered),
            "{what}, {name}: coverage {covered}"
        );
        assert!(
            (ratio - 1.0).abs() < 0.1,
            "{what}, {name}: u/spread {ratio}"
        );
        if under {
            assert!(
                without < 0.90,
                "{what}, {name}: {without} without the Type B inputs"
            );
        }
    }
}

/// A PIGA with 10⁻⁹ rad/s of noise per rate, radii known to 3 mm, g to 10⁻³ m/s², the rates
/// to 10⁻⁴: u(R) and the rate scale make k2's Type B part larger than its Type A part
/// (C hardly depends on R and not on g: its interval is the fit's). Over 1000 campaigns the
/// intervals of k2 and C hold the truth in 92–98 %; k2's without the Type B inputs would
/// not (< 90 %).
#[test]
fn k2_covers_the_truth_when_the_radii_are_uncertain() {
    let type_b = TypeB {
        radius_u_m: 3e-3,
        g_u_m_s2: 1e-3,
        rate_u_relative: 1e-4,
        ..TypeB::default()
    };
    check("radii to 3 mm", 1e-9, &type_b, [true, false]);
}

/// A quiet PIGA (5·10⁻¹¹ rad/s per rate) with the rates known to 10⁻³ and the radii to 3 mm:
/// C ∝ 1/σ², so the rate scale's Type B part of u(C) is comparable with its Type A part, and
/// k2's is many times its Type A part. Both intervals hold the truth in 92–98 % of 1000
/// campaigns; without the Type B inputs both would not (< 90 %).
#[test]
fn k2_and_c_cover_the_truth_when_the_rate_scale_is_uncertain() {
    let type_b = TypeB {
        radius_u_m: 3e-3,
        g_u_m_s2: 1e-3,
        rate_u_relative: 1e-3,
        ..TypeB::default()
    };
    check("rates to 1e-3", 5e-11, &type_b, [true, true]);
}
