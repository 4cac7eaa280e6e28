//! Nothing silently assumed (issue 19 item 5): every Type B input of the budget stated, a
//! zero with its reason, the probe gain stated once — by the uncertainty section, or by the
//! recordings' sensitivity when the gap is recorded in volts.

use std::path::{Path, PathBuf};

use pipeline::{Inputs, PipelineError, StudyConfig};

use crate::{chain, root};

fn campaign_text() -> String {
    std::fs::read_to_string(root().join("fixtures/studies/campaign.ron")).unwrap()
}

fn inputs(text: &str, path: &Path) -> Result<Inputs, PipelineError> {
    let config = StudyConfig::from_ron(text, path)?;
    Inputs::new(config, path, &pipeline::Files)
}

fn fields(e: &PipelineError) -> Vec<String> {
    let list = match e {
        PipelineError::Several { errors } => errors.iter().collect(),
        one => vec![one],
    };
    list.into_iter()
        .map(|e| match e {
            PipelineError::MissingField { field, .. } => field.clone(),
            PipelineError::StatedTwice { field, other, .. } => format!("{field} & {other}"),
            other => format!("other: {other}"),
        })
        .collect()
}

#[test]
fn a_type_b_input_left_out_is_an_error_naming_it() {
    let path = root().join("fixtures/studies/campaign.ron");
    let text = campaign_text()
        .replace("        rate_u_relative: 1.0e-6,\n", "")
        .replace("        probe_to_piga_u_mm: 0.5,\n", "");
    let e = inputs(&text, &path).unwrap_err();
    assert_eq!(
        fields(&e),
        [
            "uncertainty.rate_u_relative",
            "uncertainty.probe_to_piga_u_mm"
        ],
        "{e}"
    );
    assert!(
        chain(&e).contains("every Type B input of the budget is stated"),
        "{e}"
    );
}

#[test]
fn a_zero_needs_its_reason_and_the_budget_shows_it() {
    let path = root().join("fixtures/studies/campaign.ron");
    let text = campaign_text().replace("rate_u_relative: 1.0e-6,", "rate_u_relative: 0.0,");
    let e = inputs(&text, &path).unwrap_err();
    assert_eq!(
        fields(&e),
        ["uncertainty.zero_reasons.rate_u_relative"],
        "{e}"
    );
    assert!(
        chain(&e).contains("`uncertainty.rate_u_relative` is 0: say why"),
        "{e}"
    );
    // with the reason, the study runs and its budget states it beside the zero
    let text = text.replace(
        "rate_u_relative: 0.0,",
        "rate_u_relative: 0.0,\n        zero_reasons: {\"rate_u_relative\": \"encoder against the frequency standard, below 1e-9\"},",
    );
    let results = pipeline::run(&inputs(&text, &path).unwrap()).unwrap();
    let line = results
        .calibration
        .unwrap()
        .budget
        .k2
        .into_iter()
        .find(|l| l.quantity.starts_with("rate scale"))
        .unwrap();
    assert_eq!(line.u, 0.0);
    assert_eq!(
        line.note.as_deref(),
        Some("taken as 0: encoder against the frequency standard, below 1e-9")
    );
    // a reason for something that is not an input
    let text = text.replace(
        "{\"rate_u_relative\":",
        "{\"rate_u_relative\": \"x\", \"rate\":",
    );
    let e = inputs(&text, &path).unwrap_err();
    assert!(chain(&e).contains("`rate` is not one of"), "{e}");
}

/// The campaign's probe recordings rewritten in volts at 8 V/mm (gap_V = gap_µm · 0.008),
/// in a temporary folder, and the study pointing at them with the volts format.
fn volts_study(dir: &Path, also_in_uncertainty: bool) -> (String, PathBuf) {
    std::fs::create_dir_all(dir).unwrap();
    let text = campaign_text();
    for entry in std::fs::read_dir(root().join("fixtures/campaign")).unwrap() {
        let p = entry.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        let csv = std::fs::read_to_string(&p).unwrap();
        let out = if name.starts_with("probe_") {
            let mut lines = csv.lines();
            let header = lines.next().unwrap().replace("gap_um", "gap_v");
            let mut out = format!("{header}\n");
            for l in lines {
                let mut cols: Vec<String> = l.split(',').map(str::to_owned).collect();
                let gap: f64 = cols[1].parse().unwrap();
                cols[1] = format!("{:.12e}", gap * 0.008);
                out.push_str(&cols.join(","));
                out.push('\n');
            }
            out
        } else {
            csv
        };
        std::fs::write(dir.join(&name), out).unwrap();
    }
    let mut text = text
        .replace("../campaign/", "")
        .replace(
            "                fit: (order: 4),",
            "                format: (gap: (column: \"gap_v\", unit: volts(sensitivity: 8.0, \
             sensitivity_unit: v_per_mm, u_sensitivity: 0.016))),\n                fit: (order: 4),",
        );
    if !also_in_uncertainty {
        text = text.replace("        probe_gain_u_relative: 2.0e-3,\n", "");
    }
    let study = dir.join("study.ron");
    std::fs::write(&study, &text).unwrap();
    (text, study)
}

#[test]
fn a_volts_recording_states_the_probe_gain_once() {
    let dir = std::env::temp_dir().join(format!("type-b-volts-{}", std::process::id()));
    // stated twice: an error naming both places
    let (text, study) = volts_study(&dir, true);
    let e = inputs(&text, &study).unwrap_err();
    assert_eq!(
        fields(&e),
        ["uncertainty.probe_gain_u_relative & phases[0].points.format.gap.unit (u_sensitivity)"],
        "{e}"
    );
    // stated once, by the sensitivity (0.016/8 = 2e-3, as the µm study's uncertainty section)
    let (text, study) = volts_study(&dir, false);
    let volts = pipeline::run(&inputs(&text, &study).unwrap()).unwrap();
    let um = pipeline::run(
        &pipeline::load_study(&root().join("fixtures/studies/campaign.ron")).unwrap(),
    )
    .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let (cv, cu) = (&volts.phases[0].fit, &um.phases[0].fit);
    assert!(
        ((cv.c_r_m_s2 - cu.c_r_m_s2) / cu.c_r_m_s2).abs() < 1e-9,
        "C_r {} in volts, {} in µm",
        cv.c_r_m_s2,
        cu.c_r_m_s2
    );
    let (kv, ku) = (volts.calibration.unwrap(), um.calibration.unwrap());
    let gain_lines: Vec<_> = kv
        .budget
        .k2
        .iter()
        .filter(|l| l.quantity == "probe gain")
        .collect();
    assert_eq!(gain_lines.len(), 1);
    assert!(
        (gain_lines[0].u - 2e-3).abs() < 1e-15,
        "{}",
        gain_lines[0].u
    );
    assert!(
        gain_lines[0]
            .note
            .as_deref()
            .is_some_and(|n| n.contains("stated sensitivity")),
        "{:?}",
        gain_lines[0].note
    );
    assert!(
        ((kv.coefficients.k2.u - ku.coefficients.k2.u) / ku.coefficients.k2.u).abs() < 1e-6,
        "u(k2) {} in volts, {} in µm",
        kv.coefficients.k2.u,
        ku.coefficients.k2.u
    );
    // C_r and Δk2 with one consistent uncertainty: C_r's includes the probe gain
    assert!(kv.c_r_combined_m_s2.u > kv.c_r_m_s2.u);
    let relative = kv.c_r_combined_m_s2.u / kv.c_r_combined_m_s2.value.abs();
    assert!(relative >= 2e-3, "{relative}");
}

/// The probe's sign convention is echoed in words with C_r (issue 19 item 6): a study
/// declared `along_o1_x1` says the probe's reading rises when the spindle moves towards the
/// PIGA, so a wrong declaration is visible beside the C_r it changed. The self-describing
/// names (`reading_falls_towards_piga`, `reading_rises_towards_piga`) are the same
/// declarations.
#[test]
fn the_probe_sign_convention_is_echoed_in_words() {
    let path = root().join("fixtures/studies/campaign.ron");
    let against = pipeline::run(&inputs(&campaign_text(), &path).unwrap()).unwrap();
    let text = campaign_text().replace(
        "probe_direction: against_o1_x1",
        "probe_direction: along_o1_x1",
    );
    let along = pipeline::run(&inputs(&text, &path).unwrap()).unwrap();
    let (a, b) = (against.calibration.unwrap(), along.calibration.unwrap());
    assert!(
        a.probe_direction.words().contains("gap closes"),
        "{}",
        a.probe_direction.words()
    );
    assert!(
        b.probe_direction.words().contains("reading rises"),
        "{}",
        b.probe_direction.words()
    );
    // the slip changes C_r's sign; the echo is what shows which convention produced it
    assert!(a.c_r_m_s2.value * b.c_r_m_s2.value < 0.0);
    for (alias, same) in [
        ("reading_falls_towards_piga", &a),
        ("reading_rises_towards_piga", &b),
    ] {
        let text = campaign_text().replace(
            "probe_direction: against_o1_x1",
            &format!("probe_direction: {alias}"),
        );
        let r = pipeline::run(&inputs(&text, &path).unwrap()).unwrap();
        let c = r.calibration.unwrap();
        assert_eq!(c.probe_direction, same.probe_direction, "{alias}");
        assert_eq!(c.c_r_m_s2.value, same.c_r_m_s2.value, "{alias}");
    }
}

/// The unit a budget states for an input, by the input's name (the budget's words).
fn unit_of_input(quantity: &str) -> &'static str {
    match quantity {
        "R (working radius)" => "m",
        "g (gravity)" => "m/s²",
        "rate scale (common to every rate)" | "probe gain" => "1 (relative)",
        "pivot-to-probe height" | "probe-to-PIGA height" => "mm",
        "C_r of the compensating phase" => "m·s²",
        "k1 (given)" => "rad/(s·g)",
        other => panic!("an input this test does not know: {other}"),
    }
}

/// Every line of the calibration's budgets carries its unit as data (issue 31): each input
/// its own, the eq. 18 fit's line its output's; so does each traceability statement of the
/// certificate. An older results.json line without a unit still reads (its unit empty).
#[test]
fn every_budget_line_carries_its_unit() {
    let path = root().join("fixtures/studies/campaign.ron");
    let results = pipeline::run(&inputs(&campaign_text(), &path).unwrap()).unwrap();
    let c = results.calibration.as_ref().unwrap();
    let budgets = [
        (&c.budget.k0, "rad/s"),
        (&c.budget.k1, "rad/(s·g)"),
        (&c.budget.k2, "rad/(s·g²)"),
        (&c.budget.k3, "rad/(s·g³)"),
    ];
    for (lines, output_unit) in budgets {
        for l in lines {
            let want = if l.quantity.starts_with("PIGA mean outputs") {
                output_unit
            } else {
                unit_of_input(&l.quantity)
            };
            assert_eq!(l.unit, want, "{l:?}");
        }
    }
    let certificate = results
        .certificate
        .as_ref()
        .expect("the campaign certifies");
    assert!(!certificate.traceability.is_empty());
    for t in &certificate.traceability {
        assert_eq!(t.unit, unit_of_input(&t.input), "{t:?}");
    }
    let mut json = serde_json::to_value(&c.budget.k2[0]).unwrap();
    json.as_object_mut().unwrap().remove("unit").unwrap();
    let old: pipeline::BudgetLine = serde_json::from_value(json).unwrap();
    assert_eq!(old.unit, "");
    assert_eq!(old.quantity, c.budget.k2[0].quantity);
}
