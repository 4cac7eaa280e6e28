//! The calibration on measured data — raw PIGA output recordings or a table — coverage of
//! its uncertainty over simulated campaigns, and typed errors on bad calibration input.

use std::collections::HashMap;
use std::path::Path;

use pipeline::{Inputs, PipelineError, StudyConfig};
use rayon::prelude::*;
use simulate::Scenario;
use test_support::MemoryFiles;

use crate::root;

/// A simulated campaign's files, in memory.
pub(crate) type Campaign = MemoryFiles;

pub(crate) const DIR: &str = "/nonexistent/campaign";

/// The campaign scenario with another seed, simulated into memory under `DIR`: the probe
/// recordings, the raw PIGA output recordings, and `piga.csv` whose means carry N(0,
/// `table_noise_rad_s`²) (the scenario's own table is noise-free: its noise is in the raw
/// recordings).
fn campaign_with(seed: u64, table_noise_rad_s: f64) -> Campaign {
    campaign_of(seed, table_noise_rad_s, |_| {})
}

/// [`campaign_with`] with the scenario changed by `change` first.
fn campaign_of(seed: u64, table_noise_rad_s: f64, change: impl Fn(&mut Scenario)) -> Campaign {
    campaign_gap(seed, table_noise_rad_s, 1.0, change)
}

/// [`campaign_of`] with the probe recordings' gap column multiplied by `gap_scale` (1e-3:
/// written in mm while the study reads µm).
fn campaign_gap(
    seed: u64,
    table_noise_rad_s: f64,
    gap_scale: f64,
    change: impl Fn(&mut Scenario),
) -> Campaign {
    let text = std::fs::read_to_string(root().join("fixtures/scenarios/campaign.ron")).unwrap();
    let mut loaded = Scenario::parse(&text, Path::new("campaign.ron")).unwrap();
    loaded.scenario.seed = seed;
    loaded.scenario.piga.noise_rad_s = table_noise_rad_s;
    change(&mut loaded.scenario);
    let simulation = simulate::simulate(&loaded).unwrap();
    let mut files = HashMap::new();
    for r in &simulation.recordings {
        let mut r = r.clone();
        r.gap_um.iter_mut().for_each(|g| *g *= gap_scale);
        let mut csv = Vec::new();
        r.write_csv(&mut csv).unwrap();
        files.insert(Path::new(DIR).join(&r.file_name), csv);
    }
    for r in &simulation.piga_recordings {
        files.insert(Path::new(DIR).join(&r.file_name), r.csv_text().into_bytes());
    }
    files.insert(
        Path::new(DIR).join("piga.csv"),
        simulate::piga_csv_text(&simulation.piga).into_bytes(),
    );
    MemoryFiles(files)
}

/// The campaign with noise from run to run: 1e-9 rad/s on each rate's mean output, in the
/// table and in the raw recordings' slopes (beyond the raw recordings' own noise).
pub(crate) fn campaign(seed: u64) -> Campaign {
    campaign_with(seed, 1e-9)
}

/// The campaign study (raw PIGA recordings) pointed at `DIR`, with `trials` Monte Carlo
/// trials.
fn study_text(trials: &str) -> String {
    std::fs::read_to_string(root().join("fixtures/studies/campaign.ron"))
        .unwrap()
        .replace("../campaign/", "campaign/")
        .replace("seed: 1,", &format!("seed: 1, trials: {trials},"))
}

/// The campaign study with the PIGA table (`piga.csv`) in place of the raw recordings.
pub(crate) fn table_study_text(trials: &str) -> String {
    let text = study_text(trials);
    let start = text.find("        recordings: (").unwrap();
    let end = start + text[start..].find("\n        ),\n").unwrap() + "\n        ),\n".len();
    format!(
        "{}        table: (file: \"campaign/piga.csv\"),\n{}",
        &text[..start],
        &text[end..]
    )
}

pub(crate) fn run(text: &str, data: &Campaign) -> Result<pipeline::StudyResults, PipelineError> {
    let source = Path::new("/nonexistent/study.ron");
    let config = StudyConfig::from_ron(text, source)?;
    let inputs = Inputs::new(config, source, data)?;
    pipeline::run(&inputs)
}

const K2_TRUE: f64 = 5.0e-7;

/// Over 240 simulated campaigns the reported 95 % interval of the compensated k2 holds the
/// true k2 in 92–98 % of them, and the reported u(k2) matches the spread of k2 within 20 %:
/// from the raw output recordings (weighted by their standard errors) and from a table
/// (unweighted).
#[test]
fn the_k2_interval_covers_the_truth_over_many_campaigns() {
    // The raw recordings' noise only: the points' σ are the whole story.
    coverage(
        "raw recordings",
        &study_text("fixed(2000)"),
        0.0,
        0.92..=0.98,
    );
    // The table, unweighted, with noise from run to run.
    coverage("table", &table_study_text("fixed(2000)"), 1e-9, 0.92..=0.98);
}

/// The raw recordings with noise from run to run that their within-run σ miss: the
/// weighted fit's χ²/ν exceeds 1 and the common variation τ (Paule–Mandel) is added to
/// every σ. τ comes from the same 20 points, so the coverage is a little below nominal
/// (the bound here is 90 %); with the points' own σ and the Birge ratio alone it was 83 %
/// and u(k2) was 0.62 of the spread.
#[test]
fn run_to_run_variation_the_sigmas_miss_is_estimated() {
    coverage(
        "raw recordings with run-to-run noise",
        &study_text("fixed(2000)"),
        1e-9,
        0.90..=0.98,
    );
}

#[allow(clippy::print_stderr)] // the figures, shown with --nocapture
fn coverage(
    what: &str,
    text: &str,
    run_to_run_rad_s: f64,
    expected: std::ops::RangeInclusive<f64>,
) {
    let outcomes: Vec<(f64, f64, f64, f64)> = (0..240u64)
        .into_par_iter()
        .map(|seed| {
            let results = run(text, &campaign_with(1000 + seed, run_to_run_rad_s)).unwrap();
            let c = results.calibration.unwrap();
            let k2 = c.coefficients.k2;
            (
                k2.value,
                k2.u,
                k2.u95,
                c.uncompensated.k2.value - c.delta_k2.value,
            )
        })
        .collect();
    let n = outcomes.len() as f64;
    let covered = outcomes
        .iter()
        .filter(|(v, _, u95, _)| (v - K2_TRUE).abs() <= *u95)
        .count() as f64
        / n;
    let mean = outcomes.iter().map(|o| o.0).sum::<f64>() / n;
    let sd = (outcomes.iter().map(|o| (o.0 - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let mean_u = outcomes.iter().map(|o| o.1).sum::<f64>() / n;
    eprintln!(
        "{what}: coverage {covered:.3}, sd(k2) {sd:.3e}, mean u(k2) {mean_u:.3e}, ratio {:.3}, bias {:.2e}",
        mean_u / sd,
        mean - K2_TRUE
    );
    assert!(expected.contains(&covered), "{what}: coverage {covered}");
    assert!(
        (0.8..=1.2).contains(&(mean_u / sd)),
        "{what}: u/sd = {}",
        mean_u / sd
    );
    // Uncompensated k2 minus the predicted Δk2 is the compensated k2: the bias is Δk2.
    for (v, _, _, unc) in &outcomes {
        assert!((v - unc).abs() < 1e-12, "{v} vs {unc}");
    }
}

#[test]
fn gum_and_monte_carlo_agree_on_the_campaign_fixture() {
    let inputs = pipeline::load_study(&root().join("fixtures/studies/campaign.ron")).unwrap();
    let c = pipeline::run(&inputs).unwrap().calibration.unwrap();
    assert!(c.monte_carlo.gum_agrees, "{:?}", c.monte_carlo);
    let k2 = c.coefficients.k2;
    assert!((k2.value - K2_TRUE).abs() <= k2.u95, "{k2:?}");
    // The uncompensated k2 is biased by the predicted Δk2 (truth: 1.404928e-6).
    let bias = c.uncompensated.k2.value - K2_TRUE;
    assert!((bias - 1.404928e-6).abs() <= k2.u95, "bias {bias}");
    assert!(
        c.monte_carlo.trials >= 20_000,
        "adaptive: {}",
        c.monte_carlo.trials
    );
    // The budget's shares add up to 100 %.
    let total: f64 = c.budget.k2.iter().map(|l| l.percent).sum();
    assert!((total - 100.0).abs() < 1e-6, "{total}");
}

pub(crate) fn error_of(text: &str, data: &Campaign) -> PipelineError {
    match run(text, data) {
        Err(e) => e,
        Ok(_) => panic!("expected an error"),
    }
}

#[test]
fn bad_calibration_input_is_a_typed_error() {
    let data = campaign(5);
    let text = table_study_text("adaptive");

    let e = error_of(
        &text.replace("compensate_with: \"spindle\"", "compensate_with: \"pre\""),
        &data,
    );
    assert!(
        matches!(&e, PipelineError::UnknownPhase { field, .. } if field == "calibration.compensate_with"),
        "{e}"
    );

    let e = error_of(
        &text.replace("radius_u_m: 5.0e-6,", "radius_u_m: -5.0e-6,"),
        &data,
    );
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "uncertainty.radius_u_m"),
        "{e}"
    );

    let e = error_of(
        &text.replace("k1: fitted,", "k1: given(k1_rad_s_g: 0.0),"),
        &data,
    );
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "calibration.k1.k1_rad_s_g"),
        "{e}"
    );

    let e = error_of(
        &text.replace("trials: adaptive", "trials: fixed(10)"),
        &data,
    );
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "calibration.trials"),
        "{e}"
    );

    // Six distinct rates (the table keeps only six rows).
    let mut few = MemoryFiles(data.0.clone());
    let table = Path::new(DIR).join("piga.csv");
    let text6: String = String::from_utf8(few.0[&table].clone())
        .unwrap()
        .lines()
        .take(7)
        .map(|l| format!("{l}\n"))
        .collect();
    few.0.insert(table.clone(), text6.into_bytes());
    let e = error_of(&text, &few);
    assert!(
        matches!(
            &e,
            PipelineError::TooFewRates {
                distinct: 6,
                need: 7,
                ..
            }
        ),
        "{e}"
    );

    // A rate that is not > 0 names the table's file, line and column.
    let mut negative = MemoryFiles(data.0.clone());
    let text_neg = String::from_utf8(negative.0[&table].clone())
        .unwrap()
        .replacen("\n30,", "\n-30,", 1);
    negative.0.insert(table.clone(), text_neg.into_bytes());
    let e = error_of(&text, &negative);
    assert!(
        matches!(&e, PipelineError::TableValue { line: 3, column, value, .. } if column == "rate_deg_s" && *value == -30.0),
        "{e}"
    );

    // A non-finite output names the table's file and line.
    let mut bad = MemoryFiles(data.0.clone());
    let text_nan = String::from_utf8(bad.0[&table].clone())
        .unwrap()
        .replacen("\n30,", "\n30,NaN,", 1)
        .replace("NaN,0.", "NaN\n#0.");
    bad.0.insert(table.clone(), text_nan.into_bytes());
    let e = error_of(&text, &bad);
    let message = crate::chain(&e);
    assert!(
        matches!(&e, PipelineError::Recording { field, .. } if field == "calibration.table"),
        "{message}"
    );
    assert!(message.contains("piga.csv:3"), "{message}");
}

#[test]
fn bad_raw_recording_input_is_a_typed_error() {
    let data = campaign(5);
    let text = study_text("adaptive");

    // A file declared at a rate its encoder does not turn at (a file attached to the wrong
    // rate): the recording's error, naming the field.
    let e = error_of(
        &text.replace(
            "(rate_deg_s: 110.0, file: \"campaign/piga_110",
            "(rate_deg_s: 115.0, file: \"campaign/piga_110",
        ),
        &data,
    );
    let message = crate::chain(&e);
    assert!(
        matches!(&e, PipelineError::Recording { field, .. } if field == "calibration.recordings.files[9]"),
        "{message}"
    );
    assert!(message.contains("piga_110.0000deg_s.csv"), "{message}");

    // Both a table and recordings, or neither.
    let both = text.replace(
        "        recordings: (",
        "        table: (file: \"campaign/piga.csv\"),\n        recordings: (",
    );
    let e = error_of(&both, &data);
    assert!(
        matches!(&e, PipelineError::Unsupported { field, .. } if field == "calibration"),
        "{e}"
    );

    // Six distinct rates.
    let start = text
        .find("(rate_deg_s: 80.0, file: \"campaign/piga")
        .unwrap();
    let end = text
        .find("            ],\n        ),\n        compensate_with")
        .unwrap();
    let e = error_of(&format!("{}{}", &text[..start], &text[end..]), &data);
    assert!(
        matches!(&e, PipelineError::TooFewRates { field, distinct: 6, .. } if field == "calibration.recordings.files"),
        "{e}"
    );

    // A rate that is not > 0, by its field.
    let e = error_of(
        &text.replace(
            "(rate_deg_s: 20.0, file: \"campaign/piga",
            "(rate_deg_s: -20.0, file: \"campaign/piga",
        ),
        &data,
    );
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "calibration.recordings.files[0].rate_deg_s"),
        "{e}"
    );

    // A NaN output names the file and its line.
    let mut bad = MemoryFiles(data.0.clone());
    let file = Path::new(DIR).join("piga_050.0000deg_s.csv");
    let csv = String::from_utf8(bad.0[&file].clone()).unwrap();
    let mut lines: Vec<String> = csv.lines().map(str::to_owned).collect();
    let fields: Vec<String> = lines[4].split(',').map(str::to_owned).collect();
    lines[4] = format!("{},NaN,{}", fields[0], fields[2]);
    bad.0
        .insert(file, format!("{}\n", lines.join("\n")).into_bytes());
    let e = error_of(&text, &bad);
    let message = crate::chain(&e);
    assert!(
        matches!(&e, PipelineError::Recording { field, .. } if field == "calibration.recordings.files[3]"),
        "{message}"
    );
    assert!(message.contains("piga_050.0000deg_s.csv:5"), "{message}");

    // A harmonic order outside 1–8.
    let e = error_of(
        &text.replace(
            "        recordings: (",
            "        recordings: (\n            order: 9,",
        ),
        &data,
    );
    assert!(
        matches!(&e, PipelineError::InvalidField { field, .. } if field == "calibration.recordings.order"),
        "{e}"
    );
}

/// The campaign's table with a σ column and a label column: rows `b` carry an offset.
fn labelled(data: &Campaign, offset_rad_s: f64) -> Campaign {
    let table = Path::new(DIR).join("piga.csv");
    let csv = String::from_utf8(data.0[&table].clone()).unwrap();
    let mut out = String::from("rate_deg_s,output_rad_s,sigma_rad_s,run\n");
    for (i, line) in csv.lines().skip(1).enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        let label = if i % 2 == 0 { "a" } else { "b" };
        let y: f64 = f[1].parse::<f64>().unwrap() + if i % 2 == 0 { 0.0 } else { offset_rad_s };
        out.push_str(&format!("{},{y},1e-9,{label}\n", f[0]));
    }
    let mut files = data.0.clone();
    files.insert(table, out.into_bytes());
    MemoryFiles(files)
}

#[test]
fn a_sigma_column_weights_the_fit_and_labels_are_compared() {
    let data = campaign(7);
    let text = table_study_text("fixed(2000)").replace(
        "table: (file: \"campaign/piga.csv\")",
        "table: (file: \"campaign/piga.csv\", sigma_column: \"sigma_rad_s\", label_column: \"run\")",
    );
    let results = run(&text, &labelled(&data, 0.0)).unwrap();
    let c = results.calibration.as_ref().unwrap();
    assert!(c.weighted);
    assert!(c.birge_ratio.is_some());
    assert_eq!(c.labels.len(), 2);
    assert_eq!(c.residuals[1].label.as_deref(), Some("b"));
    assert_eq!(c.residuals[1].u_rad_s, Some(1e-9));
    assert_eq!(c.residuals[1].line, Some(3));
    assert!(
        !results.warnings.iter().any(|w| w.code == "label_offset"),
        "{:?}",
        results.warnings
    );
    // Rows `b` 5 nrad/s off: the label sits apart, and says so.
    let results = run(&text, &labelled(&data, 5e-9)).unwrap();
    let w = results
        .warnings
        .iter()
        .find(|w| w.code == "label_offset")
        .expect("label_offset");
    assert!(
        w.message.contains("`b`") || w.message.contains("`a`"),
        "{}",
        w.message
    );

    // σ ≤ 0 names the file, line and column.
    let mut zero = labelled(&data, 0.0);
    let table = Path::new(DIR).join("piga.csv");
    let csv = String::from_utf8(zero.0[&table].clone())
        .unwrap()
        .replacen(",1e-9,b", ",0,b", 1);
    zero.0.insert(table.clone(), csv.into_bytes());
    let e = error_of(&text, &zero);
    assert!(
        matches!(&e, PipelineError::TableValue { line: 3, column, .. } if column == "sigma_rad_s"),
        "{e}"
    );
    // A named label column the table lacks.
    let e = error_of(
        &text.replace("label_column: \"run\"", "label_column: \"orientation\""),
        &labelled(&data, 0.0),
    );
    let message = crate::chain(&e);
    assert!(message.contains("orientation"), "{message}");
}

#[test]
fn calibration_rates_beyond_the_phase_are_flagged() {
    let data = campaign(8);
    // The phase measured C_r at 20–200 deg/s; drop its two top rates.
    let text = table_study_text("fixed(2000)")
        .replace("                    (rate_deg_s: 195.0, file: \"campaign/probe_195.0000deg_s.csv\"),\n", "")
        .replace("                    (rate_deg_s: 200.0, file: \"campaign/probe_200.0000deg_s.csv\"),\n", "");
    let results = run(&text, &data).unwrap();
    let w = results
        .warnings
        .iter()
        .find(|w| w.code == "rate_outside_phase")
        .expect("rate_outside_phase");
    assert!(w.message.contains("195, 200"), "{}", w.message);
    let plain = run(&table_study_text("fixed(2000)"), &data).unwrap();
    assert!(
        !plain
            .warnings
            .iter()
            .any(|w| w.code == "rate_outside_phase")
    );
}

#[test]
fn noise_free_recordings_give_an_unweighted_fit_that_says_so() {
    // Neither noise nor ripple: every revolution's slope is the same, no point has a σ.
    let data = campaign_of(3, 1e-9, |s| {
        if let Some(r) = s.piga.recordings.as_mut() {
            r.angle_noise_rad = 0.0;
            r.ripple_rad = 0.0;
        }
    });
    let results = run(&study_text("fixed(2000)"), &data).unwrap();
    let c = results.calibration.as_ref().unwrap();
    assert!(!c.weighted);
    assert!(c.residuals.iter().all(|r| r.u_rad_s.is_none()));
    assert!(
        results
            .warnings
            .iter()
            .any(|w| w.code == "calibration_unweighted"),
        "{:?}",
        results.warnings
    );
}

#[test]
fn eight_rates_leave_two_degrees_of_freedom_and_say_what_that_means() {
    // A table of 8 rates: the eq. 18 fit has ν = 2, whose t has no variance. The adaptive
    // Monte Carlo used to run to its cap of 10⁷ trials and fail; it settles on the coverage
    // interval and the result says why its mean and u are not to be used.
    let data = campaign(9);
    let table = Path::new(DIR).join("piga.csv");
    let csv = String::from_utf8(data.0[&table].clone()).unwrap();
    let keep = ["20", "40", "60", "90", "120", "150", "180", "200"];
    let eight: String = csv
        .lines()
        .filter(|l| l.starts_with("rate") || keep.contains(&l.split(',').next().unwrap()))
        .map(|l| format!("{l}\n"))
        .collect();
    let mut files = data.0.clone();
    files.insert(table, eight.into_bytes());
    let results = run(&table_study_text("adaptive"), &MemoryFiles(files)).unwrap();
    let c = results.calibration.unwrap();
    assert_eq!(c.dof, 2);
    assert!(c.monte_carlo.trials < 10_000_000);
    assert!(
        c.warnings.iter().any(|w| w.contains("ν ≤ 2")),
        "{:?}",
        c.warnings
    );
    // The Monte Carlo interval is about the GUM one (k ≈ 4.3).
    let k2 = c.coefficients.k2;
    let mc = c.monte_carlo.k2;
    let width = mc.high95 - mc.low95;
    assert!(
        (width / (2.0 * k2.u95) - 1.0).abs() < 0.1,
        "{width} vs {}",
        2.0 * k2.u95
    );
}

#[test]
fn with_few_points_tau_is_still_found_when_the_points_scatter_too_much() {
    // Seven raw recordings (ν = 1) with run-to-run noise: the largest residual is not always
    // a τ large enough to bring χ²/ν below 1, so the search doubles it.
    let text = study_text("fixed(2000)");
    let start = text
        .find("(rate_deg_s: 30.0, file: \"campaign/piga")
        .unwrap();
    let end = text
        .find("(rate_deg_s: 160.0, file: \"campaign/piga")
        .unwrap();
    let seven = format!("{}{}", &text[..start], &text[end..]);
    let mut scattered = 0;
    for seed in 0..24 {
        let results = run(&seven, &campaign(2000 + seed)).unwrap();
        let c = results.calibration.unwrap();
        assert_eq!(c.points, 7);
        if c.birge_ratio.is_some_and(|b| b > 1.0) {
            scattered += 1;
            assert!(
                c.excess_u_rad_s.is_some(),
                "seed {seed}: {:?}",
                c.birge_ratio
            );
        } else {
            assert!(c.excess_u_rad_s.is_none());
        }
    }
    assert!(scattered >= 6, "{scattered}");
}

/// The campaign's table cut to the rates `keep` (°/s, as the table writes them).
fn table_of(data: &Campaign, keep: &[&str]) -> Campaign {
    let table = Path::new(DIR).join("piga.csv");
    let csv = String::from_utf8(data.0[&table].clone()).unwrap();
    let kept: String = csv
        .lines()
        .filter(|l| l.starts_with("rate") || keep.contains(&l.split(',').next().unwrap()))
        .map(|l| format!("{l}\n"))
        .collect();
    let mut files = data.0.clone();
    files.insert(table, kept.into_bytes());
    MemoryFiles(files)
}

/// The warnings of a calibration that speak of its rates' power to separate the
/// coefficients.
fn separation_warnings(c: &pipeline::CalibrationResults) -> Vec<&String> {
    c.warnings
        .iter()
        .filter(|w| w.contains("separate") || w.contains("variance inflation"))
        .collect()
}

#[test]
fn well_spread_rates_give_no_separation_warning_though_their_vifs_are_large() {
    // The campaign fixture's 20 rates (raw recordings, weighted), and a 12-rate campaign
    // from its table (unweighted): every VIF is large (a polynomial design in ω), but u(k2) is
    // within a factor 2 of an evenly spread design's, and nothing is said.
    let data = campaign(10);
    let full = run(&study_text("fixed(2000)"), &data).unwrap();
    let twelve = [
        "20", "30", "40", "60", "80", "100", "120", "140", "160", "180", "195", "200",
    ];
    let part = run(&table_study_text("fixed(2000)"), &table_of(&data, &twelve)).unwrap();
    for results in [full, part] {
        let c = results.calibration.unwrap();
        assert!(c.variance_inflation.iter().all(|&v| v > 1e3), "{c:?}");
        let i = c.u_inflation.expect("computed");
        assert!(i.versus_spread.k2 < 2.0, "{i:?}");
        assert!(i.nuisance.k2 > 10.0, "{i:?}");
        assert!(separation_warnings(&c).is_empty(), "{:?}", c.warnings);
    }
}

#[test]
fn bunched_rates_say_how_much_wider_u_k2_is() {
    // Seven rates bunched at 150–200 °/s: u(k2) is hundreds of times what the same seven
    // rates spread over 20–200 °/s would give, and the warning says so with the figure.
    let data = campaign(11);
    let bunched = ["150", "160", "170", "180", "190", "195", "200"];
    let results = run(&table_study_text("fixed(2000)"), &table_of(&data, &bunched)).unwrap();
    let c = results.calibration.as_ref().unwrap();
    let i = c.u_inflation.expect("computed");
    assert!(i.versus_spread.k2 > 100.0, "{i:?}");
    let w = separation_warnings(c);
    assert_eq!(w.len(), 1, "{:?}", c.warnings);
    let figure = format!("u(k2) is {:.0} times", i.versus_spread.k2);
    assert!(w[0].contains(&figure), "{} / {figure}", w[0]);
    assert!(
        w[0].contains("7 rates spread evenly from 20 to 200 deg/s"),
        "{}",
        w[0]
    );
    // and the terminal summary carries it
    let summary = report::summary_text(&results).expect("a calibration");
    assert!(summary.contains(&figure), "{summary}");
}

#[test]
fn a_gap_column_in_mm_declared_in_um_is_named_in_results_summary_and_report() {
    // The probe recordings' gap column holds mm; the study reads µm (its default): C_r is
    // 1000 times too small. The probe signal is implausible for `um`, and the warning naming
    // the unit reaches results.json, the terminal summary and report.md.
    let results = run(
        &table_study_text("fixed(2000)"),
        &campaign_gap(12, 1e-9, 1e-3, |_| {}),
    )
    .unwrap();
    let said = "implausible for the gap column's declared unit `um`";
    let w: Vec<_> = results
        .warnings
        .iter()
        .filter(|w| w.code == "implausible_gap_unit")
        .collect();
    assert!(!w.is_empty(), "{:?}", results.warnings);
    assert!(
        w.iter().all(|w| w.message.contains(said)),
        "{}",
        w[0].message
    );
    assert!(w[0].location.contains("probe_"), "{}", w[0].location);
    let json = report::results_json(&results).unwrap();
    assert!(json.contains("\"implausible_gap_unit\""));
    assert!(json.contains(said));
    let summary = report::summary_text(&results).expect("a calibration");
    assert!(summary.contains(said), "{summary}");
    // report.md writes a message as text, never markup: its backticks are escaped
    let said_md = said.replace('`', "\\`");
    let md = report::render(&results, None, None);
    assert!(md.contains(&said_md), "{md}");
    // declared right, nothing is said
    let right = run(&table_study_text("fixed(2000)"), &campaign(12)).unwrap();
    assert!(
        !right
            .warnings
            .iter()
            .any(|w| w.code == "implausible_gap_unit"),
        "{:?}",
        right.warnings
    );
}
