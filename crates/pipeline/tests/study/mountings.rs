//! The IEEE 836 model from several mountings through the study (`mountings:` in a study file,
//! issue 29, docs/MODEL.md): the five-mounting fixture against its truth, the two-orientation
//! fixture through the general model equal to its own section, a design that cannot separate
//! its terms refused before the run naming the mounting that would, and a bad section refused
//! with every problem at once.

use std::path::Path;

use pipeline::{StudyResults, WarningCode, parse_study};

use super::{chain, root};

fn fixture(name: &str) -> (String, std::path::PathBuf) {
    let path = root().join("fixtures/studies").join(name);
    (std::fs::read_to_string(&path).unwrap(), path)
}

fn run(text: &str, path: &Path) -> StudyResults {
    let inputs = parse_study(text, path).unwrap_or_else(|e| panic!("{}", chain(&e)));
    pipeline::run(&inputs).unwrap_or_else(|e| panic!("{}", chain(&e)))
}

fn truth() -> serde_json::Value {
    serde_json::from_str(
        &std::fs::read_to_string(root().join("fixtures/mountings/truth.json")).unwrap(),
    )
    .unwrap()
}

/// Every chosen term's `value ± U95` covers the simulation's truth, the arm stretch the probe
/// does not see is found, and the study states what it assumed.
#[test]
fn the_five_mounting_fixture_covers_its_truth() {
    let (text, path) = fixture("mountings.ron");
    let r = run(&text, &path);
    let m = r.mountings.as_ref().expect("the mountings section ran");
    let truth = truth();
    assert_eq!(m.mountings.len(), 5);
    assert_eq!(m.terms.len(), 8, "k0, k1 and the six chosen");
    for t in &m.terms {
        let want = truth["coefficients"][&t.name]
            .as_f64()
            .unwrap_or_else(|| panic!("truth of {}", t.name));
        assert!(
            (t.value - want).abs() <= t.u95,
            "{}: {:e} ± {:e} (U95) misses the truth {want:e}",
            t.name,
            t.value,
            t.u95
        );
        assert!(t.u > 0.0 && t.k > 1.9 && t.k < 2.3, "{t:?}");
    }
    let a = m.arm_stretch.as_ref().expect("the arm stretch is fitted");
    let c_a = truth["spindle"]["arm_stretch_m_s2"].as_f64().unwrap();
    assert!(
        (a.unseen_m_s2 - c_a).abs() <= 3.0 * a.unseen_u_m_s2,
        "arm stretch {:e} ± {:e} against {c_a:e}",
        a.unseen_m_s2,
        a.unseen_u_m_s2
    );
    let p = m.probe.as_ref().expect("compensated");
    assert_eq!(p.phase, "spindle");
    let c_ry = p.c_ry_m_s2.expect("recordings give the cross-arm drift");
    let want_c_ry = truth["spindle"]["c_r_y_m_s2"].as_f64().unwrap();
    assert!(
        (c_ry - want_c_ry).abs() < 0.05 * want_c_ry,
        "C_ry {c_ry:e} against {want_c_ry:e}"
    );
    let across = p.across_static_m.unwrap();
    let want_across = truth["spindle"]["dr_ys_m"].as_f64().unwrap();
    assert!(
        (across - want_across).abs() < 0.05 * want_across.abs(),
        "Δr_ys {across:e} against {want_across:e}"
    );
    // the Type B inputs are in the budget, each named with its share of every term's u:
    // five radii, fifteen fixture angles, g, the rate scale and the probe's scale
    let inputs: Vec<&str> = m.type_b.iter().map(|l| l.input.as_str()).collect();
    assert_eq!(inputs.len(), 5 + 15 + 3, "{inputs:?}");
    for want in [
        "radius of IA in",
        "local g",
        "rate scale",
        "probe's compensation scale",
    ] {
        assert!(
            inputs.iter().any(|i| i.starts_with(want)),
            "{want}: {inputs:?}"
        );
    }
    for line in &m.type_b {
        assert_eq!(line.contributions.len(), m.terms.len());
        assert!(
            line.u > 0.0
                && line
                    .contributions
                    .iter()
                    .all(|c| c.is_finite() && *c >= 0.0)
        );
    }
    // each term's u holds them: u² ≥ Σ contributions²
    for (j, t) in m.terms.iter().enumerate() {
        let type_b: f64 = m.type_b.iter().map(|l| l.contributions[j].powi(2)).sum();
        assert!(t.u * t.u >= type_b * (1.0 - 1e-12), "{}", t.name);
    }
    assert!(
        m.uncertainty_scope.contains("Type B"),
        "{}",
        m.uncertainty_scope
    );
    assert!(
        !r.warnings
            .iter()
            .any(|w| w.code == WarningCode::MountingsAssumed && w.location == "uncertainty"),
        "{:?}",
        r.warnings
    );
    // without an `uncertainty` section, the study says the radii, g and rate scale are taken
    // as exact and not to certify from it
    let start = text.find("    uncertainty: (").unwrap();
    let end = start + text[start..].find("    ),\n").unwrap() + "    ),\n".len();
    let without = format!("{}{}", &text[..start], &text[end..]);
    let r = run(&without, &path);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.code == WarningCode::MountingsAssumed
                && w.message.contains("no `uncertainty` section")),
        "{:?}",
        r.warnings
    );
    let only_angles = &r.mountings.as_ref().unwrap().type_b;
    assert_eq!(only_angles.len(), 15, "the fixtures' angles alone");
    // the specific-force range of the IA-in mounting: R·ω²/g at 35 and 200 deg/s
    let ia_in = &m.mountings[0];
    let force = |deg: f64| 2.5 * deg.to_radians().powi(2) / 9.8;
    assert!((ia_in.specific_force_low_g - force(35.0)).abs() < 1e-12);
    assert!((ia_in.specific_force_high_g - force(200.0)).abs() < 1e-12);
}

/// The two-orientation fixture's tables through the general model (IA in, IA out with its
/// own bias and scale factor, each its ω term, the shared ω³ and the arm stretch, no probe
/// compensation) give the two-orientation section's k2, k3 and C.
#[test]
fn the_two_orientation_fixture_through_the_general_model_is_its_own_section() {
    let (text, path) = fixture("two_orientation.ron");
    // the Earth rate's same-sign ω³ term is a stated correction of the two-orientation
    // section that the general model leaves to its shared ω³ column: compared without it
    let text: String = text
        .lines()
        .filter(|l| !(l.contains("latitude_deg:") || l.contains("spin_seen_from_above:")))
        .map(|l| format!("{l}\n"))
        .collect();
    let section = r#"
    mountings: (
        kind: piga,
        terms: ["k2", "k3"],
        arm_stretch: fit,
        compensate: false,
        list: [
            (preset: "ia_in", radius_m: 2.5, angle_u_deg: 0.0, table: (file: "../two_orientation/piga_ia_in.csv")),
            (preset: "ia_out", radius_m: 2.54, angle_u_deg: 0.0, own_scale: true, table: (file: "../two_orientation/piga_ia_out.csv")),
        ],
    ),
"#;
    let at = text.rfind(')').unwrap();
    let with = format!("{}{section}{}", &text[..at], &text[at..]);
    let r = run(&with, &path);
    let m = r.mountings.as_ref().unwrap();
    let s = r.two_orientation.as_ref().unwrap();
    let term = |name: &str| m.terms.iter().find(|t| t.name == name).unwrap();
    let close = |what: &str, a: f64, b: f64| {
        assert!(
            (a - b).abs() <= 1e-9 * b.abs(),
            "{what}: {a:e} through the general model, {b:e} by eq. 23 ({:e} relative)",
            (a / b - 1.0).abs()
        );
    };
    close("k2", term("k2").value, s.k2.value);
    close("k3", term("k3").value, s.k3.value);
    close("k1", term("k1").value, s.mountings[0].k1.value);
    close("k0", term("k0").value, s.mountings[0].k0.value);
    // C = γ·g/k1: eq. 23 divides by the two mountings' mean k1, the general model by the
    // reference mounting's (they differ by the IA-out scale factor's own 1e-8)
    let c = m.arm_stretch.as_ref().unwrap().total_m_s2;
    let k1_in = s.mountings[0].k1.value;
    let k1_mean = 0.5 * (k1_in + s.mountings[1].k1.value);
    close("C", c * k1_in / k1_mean, s.c_m_s2.value);
}

/// IA in and IA out cannot tell k_ip from the other terms (no mounting moves a_i and a_p
/// together): refused at validation, before any fit, naming the mounting that separates it.
#[test]
fn mountings_that_cannot_separate_a_term_are_refused_before_the_run_naming_the_fix() {
    let (text, path) = fixture("mountings.ron");
    let two = text
        .replace(
            r#""k2", "k3", "k_oq", "k_io", "delta_o", "delta_p""#,
            r#""k2", "k_ip""#,
        )
        .lines()
        .filter(|l| !(l.contains("ia_45") || l.contains("ia_tangential") || l.contains("ia_axial")))
        .collect::<Vec<_>>()
        .join("\n");
    let e = parse_study(&two, &path).expect_err("refused");
    let said = chain(&e);
    assert!(said.contains("cannot tell"), "{said}");
    assert!(said.contains("k_ip"), "{said}");
    assert!(said.contains("adding the mounting"), "{said}");
}

/// Every problem of a bad section at once, each by its field.
#[test]
fn a_bad_mountings_section_names_every_problem_at_once() {
    let (text, path) = fixture("mountings.ron");
    let bad = text
        .replace(r#""k_oq""#, r#""k_q""#)
        .replace(
            r#"(preset: "ia_out", radius_m: 2.54"#,
            r#"(preset: "ia_sideways", radius_m: 2.54"#,
        )
        .replace(
            r#"(preset: "ia_45", radius_m: 2.48"#,
            r#"(preset: "ia_45", radius_m: -2.48"#,
        )
        .replace(
            r#"(preset: "ia_in", radius_m: 2.5, angle_u_deg: 0.001"#,
            r#"(preset: "ia_in", radius_m: 2.5, angle_u_deg: 0.001, own_bias: true"#,
        );
    let e = parse_study(&bad, &path).expect_err("refused");
    let said = chain(&e);
    for field in [
        "mountings.terms[2]",
        "mountings.list[1].preset",
        "mountings.list[2].radius_m",
        "mountings.list[0].own_bias",
    ] {
        assert!(said.contains(field), "{field} not named in: {said}");
    }
    assert!(said.contains("k_oq"), "the known terms are listed: {said}");
    assert!(
        said.contains("ia_tangential"),
        "the presets are listed: {said}"
    );
}
