//! Several units calibrated in one centrifuge run (issue 30 part 4, `units:` in a study
//! file): the probe phases measured once and each unit calibrated as its own single-unit
//! study; the two-unit fixture against its truth; a unit's numbers equal to those of its
//! single-unit study; the list's problems refused at once, each naming its field.

use std::path::Path;

use pipeline::{PipelineError, StudyConfig, StudyResults, parse_study};

use super::{chain, root};

fn fixture() -> (String, std::path::PathBuf) {
    let path = root().join("fixtures/studies/units.ron");
    (std::fs::read_to_string(&path).unwrap(), path)
}

fn run(text: &str, path: &Path) -> StudyResults {
    let inputs = parse_study(text, path).unwrap_or_else(|e| panic!("{}", chain(&e)));
    pipeline::run(&inputs).unwrap_or_else(|e| panic!("{}", chain(&e)))
}

fn truth() -> serde_json::Value {
    serde_json::from_str(
        &std::fs::read_to_string(root().join("fixtures/units/truth.json")).unwrap(),
    )
    .unwrap()
}

/// Every number of `a` within 1e-12 relative of the same number of `b` (and every other
/// value equal), naming the first that is not.
fn same_numbers(a: &serde_json::Value, b: &serde_json::Value, at: &str) {
    use serde_json::Value as V;
    match (a, b) {
        (V::Number(x), V::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(y.abs()),
                "{at}: {x:e} against {y:e}"
            );
        }
        (V::Array(x), V::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths");
            for (i, (x, y)) in x.iter().zip(y).enumerate() {
                same_numbers(x, y, &format!("{at}[{i}]"));
            }
        }
        (V::Object(x), V::Object(y)) => {
            let keys: Vec<_> = x.keys().collect();
            assert_eq!(keys, y.keys().collect::<Vec<_>>(), "{at}: keys");
            for (k, v) in x {
                same_numbers(v, &y[k], &format!("{at}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

/// Two units from one probe phase: each k2 (compensated with the one C_r, at its own k1)
/// within its U95 of its truth; the C_r is the same for both, and each unit's Δk2 is its k1
/// times C_r·g/R²; the top summary names each unit with its certificate.
#[test]
fn the_two_unit_fixture_covers_each_units_truth() {
    let (text, path) = fixture();
    let r = run(&text, &path);
    let truth = truth();
    assert!(r.calibration.is_none() && r.certificate.is_none());
    let units = r.units.as_ref().expect("the units' summary");
    assert_eq!(units.len(), 2);
    assert_eq!(r.unit_studies.len(), 2);
    let c_r = r.phases[0].fit.c_r_m_s2;
    let true_c_r = truth["spindle"]["c_r_m_s2"].as_f64().unwrap();
    let sigma = r.phases[0].fit.c_r_sigma_m_s2.unwrap();
    assert!(
        (c_r - true_c_r).abs() < 4.0 * sigma,
        "C_r {c_r:e} ± {sigma:e} against {true_c_r:e}"
    );
    for ((summary, unit), t) in units
        .iter()
        .zip(&r.unit_studies)
        .zip(truth["units"].as_array().unwrap())
    {
        assert_eq!(summary.label, t["label"].as_str().unwrap());
        assert_eq!(summary.folder, format!("units/{}", summary.label));
        let cal = unit.calibration.as_ref().expect("each unit's calibration");
        // the one C_r, measured once, in every unit
        assert_eq!(unit.phases[0].fit.c_r_m_s2.to_bits(), c_r.to_bits());
        assert_eq!(cal.c_r_m_s2.value.to_bits(), c_r.to_bits());
        let k1 = t["k1_rad_s_g"].as_f64().unwrap();
        assert_eq!(unit.inputs.k1_rad_s_g, k1);
        let expected_dk2 = k1 * c_r * 9.8 / (2.5 * 2.5);
        let dk2 = unit.phases[0].fit.delta_k2_rad_s_g2;
        assert!(
            (dk2 - expected_dk2).abs() <= 1e-12 * expected_dk2.abs(),
            "unit {}: Δk2 {dk2:e} against k1·C_r·g/R² {expected_dk2:e}",
            summary.label
        );
        let k2 = cal.coefficients.k2;
        let true_k2 = t["k2_rad_s_g2"].as_f64().unwrap();
        assert!(
            (k2.value - true_k2).abs() <= k2.u95,
            "unit {}: k2 = {:e} ± {:e} (U95) misses its truth {true_k2:e}",
            summary.label,
            k2.value,
            k2.u95
        );
        assert_eq!(summary.k2, Some(k2));
        let cert = unit.certificate.as_ref().expect("each unit's certificate");
        assert_eq!(summary.certificate.as_deref(), Some(cert.id.as_str()));
        assert!(unit.units.is_none() && unit.unit_studies.is_empty());
    }
    assert_ne!(units[0].certificate, units[1].certificate);
}

/// Everything a unit shares (C_r, each phase's Δk2 at its k1 and radius, g, the Type B
/// inputs, the budget, the certificate) is what the single-unit study of that unit gives:
/// every number of its results within 1e-12 relative (here: the same to the bit).
#[test]
fn a_units_numbers_are_its_single_unit_studys() {
    let (text, path) = fixture();
    let r = run(&text, &path);
    let config = StudyConfig::from_ron(&text, &path).unwrap();
    for (i, unit) in r.unit_studies.iter().enumerate() {
        let single = config.for_unit(i).unwrap();
        let inputs = pipeline::Inputs::new(single, &path, &pipeline::Files)
            .unwrap_or_else(|e| panic!("{}", chain(&e)));
        let alone = pipeline::run(&inputs).unwrap_or_else(|e| panic!("{}", chain(&e)));
        same_numbers(
            &serde_json::to_value(unit).unwrap(),
            &serde_json::to_value(&alone).unwrap(),
            &format!("units[{i}]"),
        );
    }
    // and a unit at its own radius: its Δk2 at that radius, C_r unchanged
    let moved = text.replacen("label: \"B\",", "label: \"B\", radius_m: 2.6,", 1);
    let r2 = run(&moved, &path);
    let b = &r2.unit_studies[1];
    assert_eq!(b.inputs.radius_m, 2.6);
    assert_eq!(r2.units.as_ref().unwrap()[1].radius_m, 2.6);
    let ratio =
        b.phases[0].fit.delta_k2_rad_s_g2 / r.unit_studies[1].phases[0].fit.delta_k2_rad_s_g2;
    assert!((ratio - (2.5f64 / 2.6).powi(2)).abs() < 1e-12, "{ratio}");
    assert_eq!(
        b.phases[0].fit.c_r_m_s2.to_bits(),
        r.unit_studies[1].phases[0].fit.c_r_m_s2.to_bits()
    );
}

/// The fields of every error of a refused study, in order.
fn fields(e: &PipelineError) -> Vec<String> {
    let one = |e: &PipelineError| match e {
        PipelineError::InvalidName { field, .. }
        | PipelineError::DuplicateName { field, .. }
        | PipelineError::UsedTwice { field, .. }
        | PipelineError::BesideUnits { field, .. }
        | PipelineError::EmptyList { field, .. }
        | PipelineError::Recording { field, .. }
        | PipelineError::UnknownPhase { field, .. }
        | PipelineError::InvalidField { field, .. } => field.clone(),
        other => format!("<{other}>"),
    };
    match e {
        PipelineError::Several { errors } => errors.iter().map(one).collect(),
        e => vec![one(e)],
    }
}

/// A label that is not a folder's name, two labels a case-insensitive file system would take
/// for one folder, one certificate identification twice and a top-level calibration beside
/// `units`: refused at once, each naming its field.
#[test]
fn the_units_lists_problems_are_refused_at_once_by_field() {
    let (text, path) = fixture();
    let bad = text
        .replacen("label: \"A\",", "label: \"../A\",", 1)
        .replace("CC-2026-0052", "CC-2026-0051");
    let e = parse_study(&bad, &path).unwrap_err();
    assert_eq!(
        fields(&e),
        ["units[0].label", "units[1].certificate.id"],
        "{}",
        chain(&e)
    );
    let message = chain(&e);
    assert!(message.contains("`../A` is not a valid name"), "{message}");
    assert!(
        message.contains("\"CC-2026-0051\": a certificate's identification (each certificate has its own) is already used at `units[0].certificate.id`"),
        "{message}"
    );
    let twice = text.replacen("label: \"B\",", "label: \"a\",", 1);
    let e = parse_study(&twice, &path).unwrap_err();
    assert_eq!(fields(&e), ["units[1].label"], "{}", chain(&e));
    assert!(
        chain(&e).contains("already used at `units[0].label`"),
        "{}",
        chain(&e)
    );
    // a top-level calibration (and certificate) beside the units
    let top = text.replacen(
        "    units: [",
        "    calibration: (table: (file: \"../units/piga_A.csv\"), compensate_with: \"spindle\"),\n    units: [",
        1,
    );
    let e = parse_study(&top, &path).unwrap_err();
    assert_eq!(fields(&e), ["calibration"], "{}", chain(&e));
    assert!(
        chain(&e).contains("move it into `units[…].calibration`"),
        "{}",
        chain(&e)
    );
    let empty = text[..text.find("    units: [").unwrap()].to_owned() + "    units: [],\n)\n";
    let e = parse_study(&empty, &path).unwrap_err();
    assert_eq!(fields(&e), ["units"], "{}", chain(&e));
}

/// A unit's own problem is named by the unit's field, a shared one once.
#[test]
fn a_units_own_problem_names_the_units_field() {
    let (text, path) = fixture();
    let bad = text
        .replacen("piga_B.csv", "no_such_table.csv", 1)
        .replacen(
            "k1_rad_s_g: 0.56,\n            calibration",
            "k1_rad_s_g: -0.56,\n            calibration",
            1,
        );
    let e = parse_study(&bad, &path).unwrap_err();
    let message = chain(&e);
    assert!(message.contains("units[0].k1_rad_s_g"), "{message}");
    assert!(message.contains("units[1].calibration.table"), "{message}");
    // the probe phase's problem is the study's, named once
    let phase = text.replacen("probe_020.0000deg_s.csv", "probe_missing.csv", 1);
    let e = parse_study(&phase, &path).unwrap_err();
    let message = chain(&e);
    assert_eq!(message.matches("probe_missing.csv").count(), 1, "{message}");
}
