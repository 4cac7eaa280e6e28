//! A PIGA table's output noise stated in the study (`output_sigma_rad_s`: `constant(σ)` or
//! `per_rate([(rate_deg_s, σ), …])`) instead of a σ column: the same fit, weighting, τ and
//! uncertainty as a σ column of those values, in the calibration section and in the
//! two-orientation section; both at once, an unlisted rate or a σ ≤ 0 refused by field.

use std::path::Path;

use pipeline::{Inputs, PipelineError, StudyConfig, StudyResults};
use serde_json::Value;
use simulate::{Orientation, Simulation};
use test_support::MemoryFiles;

use super::calibration::{Campaign, DIR, campaign, error_of, run, table_study_text};
use super::two_orientation::{self as two, Declared, probe_study, scenario};

/// Every number of `a` and `b` equal to `relative` (and every other value equal), with the
/// path of each difference.
fn differences(path: &str, a: &Value, b: &Value, relative: f64, out: &mut Vec<String>) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if (x - y).abs() > relative * x.abs().max(y.abs()) {
                out.push(format!("{path}: {x:e} vs {y:e}"));
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (x, y)) in x.iter().zip(y).enumerate() {
                differences(&format!("{path}[{i}]"), x, y, relative, out);
            }
        }
        (Value::Object(x), Value::Object(y)) if x.len() == y.len() => {
            for (k, v) in x {
                match y.get(k) {
                    Some(w) => differences(&format!("{path}.{k}"), v, w, relative, out),
                    None => out.push(format!("{path}.{k}: only in one")),
                }
            }
        }
        _ if a == b => {}
        _ => out.push(format!("{path}: {a} vs {b}")),
    }
}

/// `a` and `b` equal to 1e-12 relative, number by number.
fn assert_same(a: &impl serde::Serialize, b: &impl serde::Serialize) {
    let (a, b) = (
        serde_json::to_value(a).unwrap(),
        serde_json::to_value(b).unwrap(),
    );
    let mut out = Vec::new();
    differences("", &a, &b, 1e-12, &mut out);
    assert!(out.is_empty(), "{}", out.join("\n"));
}

/// σ of the rate `rate_deg_s`, rad/s: larger at the higher rates.
fn sigma_at(rate_deg_s: f64) -> f64 {
    1e-9 * (1.0 + rate_deg_s / 200.0)
}

/// The campaign's table with a σ column `sigma_rad_s` of `sigma(rate)` (written to round
/// trip), and every `odd` row offset by `offset_rad_s` (scatter beyond σ, for the τ).
fn with_sigma_column(
    data: &Campaign,
    sigma: impl Fn(f64) -> f64,
    offset_rad_s: f64,
) -> (Campaign, Vec<f64>) {
    let table = Path::new(DIR).join("piga.csv");
    let csv = String::from_utf8(data.0[&table].clone()).unwrap();
    let mut out = String::from("rate_deg_s,output_rad_s,sigma_rad_s\n");
    let mut rates = Vec::new();
    for (i, line) in csv.lines().skip(1).enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        let rate: f64 = f[0].parse().unwrap();
        let y: f64 = f[1].parse::<f64>().unwrap() + if i % 2 == 1 { offset_rad_s } else { 0.0 };
        out.push_str(&format!("{rate:?},{y:?},{:?}\n", sigma(rate)));
        rates.push(rate);
    }
    let mut files = data.0.clone();
    files.insert(table, out.into_bytes());
    (MemoryFiles(files), rates)
}

/// The calibration on the same table weighted by its σ column and by the same σ stated as
/// `output_sigma_rad_s`: within the points' σ, and with scatter beyond them (a τ).
#[test]
fn a_stated_sigma_fits_as_a_sigma_column_in_the_calibration() {
    let data = campaign(11);
    let column = table_study_text("fixed(2000)").replace(
        "table: (file: \"campaign/piga.csv\")",
        "table: (file: \"campaign/piga.csv\", sigma_column: \"sigma_rad_s\")",
    );
    let stated = |declared: &str| {
        table_study_text("fixed(2000)").replace(
            "table: (file: \"campaign/piga.csv\")",
            &format!("table: (file: \"campaign/piga.csv\", output_sigma_rad_s: {declared})"),
        )
    };
    for offset in [0.0, 5e-9] {
        // one σ for every row
        let (table, _) = with_sigma_column(&data, |_| 1e-9, offset);
        let by_column = run(&column, &table).unwrap();
        let by_field = run(&stated("constant(1e-9)"), &table).unwrap();
        let c = by_column.calibration.as_ref().unwrap();
        assert!(c.weighted);
        if offset > 0.0 {
            assert!(c.excess_u_rad_s.is_some(), "scatter beyond σ gives a τ");
        }
        assert_same(&by_column.calibration, &by_field.calibration);
        assert_same(&by_column.warnings, &by_field.warnings);

        // one σ per rate
        let (table, rates) = with_sigma_column(&data, sigma_at, offset);
        let mut distinct = rates.clone();
        distinct.dedup();
        let list: Vec<String> = distinct
            .iter()
            .map(|&r| format!("({r:?}, {:?})", sigma_at(r)))
            .collect();
        let by_column = run(&column, &table).unwrap();
        let by_field = run(&stated(&format!("per_rate([{}])", list.join(", "))), &table).unwrap();
        assert_same(&by_column.calibration, &by_field.calibration);
    }
}

/// Both a σ column and `output_sigma_rad_s`, a rate `per_rate` does not list, and σ ≤ 0:
/// each refused by its field.
#[test]
fn a_stated_sigma_is_refused_with_its_field() {
    let data = campaign(12);
    let (table, _) = with_sigma_column(&data, |_| 1e-9, 0.0);
    let text = |fields: &str| {
        table_study_text("fixed(2000)").replace(
            "table: (file: \"campaign/piga.csv\")",
            &format!("table: (file: \"campaign/piga.csv\", {fields})"),
        )
    };
    let e = error_of(
        &text("sigma_column: \"sigma_rad_s\", output_sigma_rad_s: constant(1e-9)"),
        &table,
    );
    let message = crate::chain(&e);
    assert!(
        message.contains("field `calibration.table.output_sigma_rad_s` states each output's standard uncertainty, and so does `calibration.table.sigma_column`: state it once"),
        "{message}"
    );
    let e = error_of(
        &text("output_sigma_rad_s: per_rate([(20.0, 1e-9), (30.0, 1e-9)])"),
        &table,
    );
    let PipelineError::Several { errors } = &e else {
        panic!("every unlisted row at once: {e}")
    };
    let first = crate::chain(&errors[0]);
    assert!(
        first.contains("`calibration.table.output_sigma_rad_s`")
            && first.contains("piga.csv:4: rate 40 deg/s has no standard uncertainty in `per_rate` (rates listed: 20, 30)"),
        "{first}"
    );
    for bad in ["constant(0.0)", "per_rate([(20.0, -1e-9)])", "per_rate([])"] {
        let e = error_of(&text(&format!("output_sigma_rad_s: {bad}")), &table);
        let message = crate::chain(&e);
        assert!(
            message.contains("calibration.table.output_sigma_rad_s"),
            "{bad}: {message}"
        );
    }
}

/// The two-orientation section on the simulation's two mounting tables, each with the σ
/// column `u_rad_s` (`stated: false`) or the same σ stated as `output_sigma_rad_s`.
fn two_orientation_study(sim: &Simulation, stated: bool) -> StudyResults {
    let (text, mut files) = probe_study(sim, Declared::Right);
    let mut sets = String::new();
    for m in &sim.mountings {
        let (name, file) = match m.orientation {
            Orientation::IaIn => ("ia_in", "piga_ia_in.csv"),
            Orientation::IaOut => ("ia_out", "piga_ia_out.csv"),
        };
        let mut csv = String::from("rate_deg_s,output_rad_s,u_rad_s\n");
        for r in &m.piga {
            csv.push_str(&format!(
                "{:?},{:?},{:?}\n",
                r.rate_deg_s,
                r.output_rad_s,
                sigma_at(r.rate_deg_s)
            ));
        }
        files.insert(Path::new(two::DIR).join(file), csv.into_bytes());
        let sigma = if stated {
            let list: Vec<String> = m
                .piga
                .iter()
                .map(|r| format!("({:?}, {:?})", r.rate_deg_s, sigma_at(r.rate_deg_s)))
                .collect();
            format!("output_sigma_rad_s: per_rate([{}])", list.join(", "))
        } else {
            "sigma_column: \"u_rad_s\"".to_owned()
        };
        sets.push_str(&format!(
            "(orientation: {name}, radius_m: {:?}, table: (file: \"{file}\", {sigma})),",
            m.radius_m
        ));
    }
    let end = text.rfind(')').unwrap();
    let text = format!(
        "{}    two_orientation: (orientations: [{sets}], compare_with: \"spindle\", trials: fixed(2000)),\n)\n",
        &text[..end]
    );
    let source = Path::new(two::DIR).join("study.ron");
    let config = StudyConfig::from_ron(&text, &source).unwrap();
    let inputs = Inputs::new(config, &source, &MemoryFiles(files)).unwrap();
    pipeline::run(&inputs).unwrap()
}

/// The two-orientation fit of two tables weighted by their σ columns and by the same σ
/// stated per rate: the same results.
#[test]
fn a_stated_sigma_fits_as_a_sigma_column_in_the_two_orientation_section() {
    let sim = simulate::simulate(&scenario(31, 0.0)).unwrap();
    let by_column = two_orientation_study(&sim, false);
    let by_field = two_orientation_study(&sim, true);
    assert!(by_column.two_orientation.is_some());
    assert_same(&by_column.two_orientation, &by_field.two_orientation);
    assert_same(&by_column.warnings, &by_field.warnings);
    // weighted: no warning that the σ were not used
    assert!(
        !by_field
            .warnings
            .iter()
            .any(|w| w.code == pipeline::WarningCode::CalibrationUnweighted),
        "{:?}",
        by_field.warnings
    );
}
