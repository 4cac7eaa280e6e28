//! The two-orientation calibration on raw PIGA output recordings (issue 20, build item 2):
//! each orientation's recordings reduced to mean outputs over whole revolutions, as the
//! calibration section reduces its own, and fitted jointly; the committed fixture study
//! against its scenario's truth; the closed loop with and without arm stretch; every bad
//! recording of both orientations named at once.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use pipeline::{Inputs, PipelineError, StudyConfig, StudyResults, WarningCode};
use simulate::{Orientation, PigaRecordingSpec, Simulation};

use super::two_orientation::{C_R, DIR, Declared, K2, probe_study, scenario};
use crate::root;
use test_support::MemoryFiles as Files;

/// The scenario of `two_orientation::scenario` with the noise in raw output recordings (white
/// noise of 1e-8 rad per sample, a once-per-revolution ripple of 2 µrad) instead of the
/// tables.
fn recorded_scenario(seed: u64, c_a: f64) -> simulate::LoadedScenario {
    let mut loaded = scenario(seed, c_a);
    loaded.scenario.piga.noise_rad_s = 0.0;
    loaded.scenario.piga.recordings = Some(PigaRecordingSpec {
        angle_noise_rad: 1e-8,
        ripple_rad: 2e-6,
        ripple_phase_deg: 30.0,
    });
    loaded
        .scenario
        .clone()
        .check(Path::new("campaign.ron"))
        .unwrap()
}

fn tag(o: Orientation) -> &'static str {
    match o {
        Orientation::IaIn => "ia_in",
        Orientation::IaOut => "ia_out",
    }
}

/// The study text and files: the probe phase, and each mounting's raw recordings in memory
/// (`two_orientation.orientations[k].recordings`).
fn recordings_study(sim: &Simulation, declared: Declared) -> (String, HashMap<PathBuf, Vec<u8>>) {
    let (text, mut files) = probe_study(sim, declared);
    let mut sets = String::new();
    for m in &sim.mountings {
        let mut list = String::new();
        for (r, rec) in m.piga.iter().zip(&m.piga_recordings) {
            files.insert(
                Path::new(DIR).join(&rec.file_name),
                rec.csv_text().into_bytes(),
            );
            list.push_str(&format!(
                "(rate_deg_s: {:?}, file: \"{}\"),",
                r.rate_deg_s, rec.file_name
            ));
        }
        sets.push_str(&format!(
            "(orientation: {}, radius_m: {:?}, recordings: (format: (output: (column: \"output_rad\", \
             unit: rad)), files: [{list}])),",
            tag(m.orientation),
            m.radius_m
        ));
    }
    let end = text.rfind(')').unwrap();
    let text = format!(
        "{}    two_orientation: (orientations: [{sets}], compare_with: \"spindle\", trials: fixed(2000)),\n)\n",
        &text[..end]
    );
    (text, files)
}

fn run(text: &str, files: HashMap<PathBuf, Vec<u8>>) -> Result<StudyResults, PipelineError> {
    let source = Path::new(DIR).join("study.ron");
    let config = StudyConfig::from_ron(text, &source)?;
    let inputs = Inputs::new(config, &source, &Files(files))?;
    pipeline::run(&inputs)
}

fn warned(r: &StudyResults, code: WarningCode) -> bool {
    r.warnings.iter().any(|w| w.code == code)
}

/// C_a = 0.3·C_r through raw recordings: k2 and C within U95, each mounting's twelve
/// recordings reduced (whole revolutions, the encoder's rate), C − C_r with z > 3 and the
/// warning; without arm stretch, |z| < 3 and no warning.
#[test]
fn raw_recordings_in_both_orientations_close_the_loop() {
    let c_a = 0.3 * C_R;
    let sim = simulate::simulate(&recorded_scenario(31, c_a)).unwrap();
    let (text, files) = recordings_study(&sim, Declared::Right);
    let r = run(&text, files).unwrap();
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
    for (m, sim_m) in s.mountings.iter().zip(&sim.mountings) {
        assert_eq!(m.table, None);
        assert_eq!(m.recordings.len(), 12);
        assert_eq!(m.points, 12);
        for (rec, row) in m.recordings.iter().zip(&sim_m.piga) {
            assert_eq!(rec.angle_source, "encoder");
            assert!(rec.revolutions >= 4, "{rec:?}");
            // the reduction's mean output holds the noise-free mean within 5 standard errors
            assert!(
                (rec.output_rad_s - row.output_rad_s).abs() < 5.0 * rec.u_rad_s,
                "{rec:?} against {}",
                row.output_rad_s
            );
        }
    }
    let p = s.probe.as_ref().unwrap();
    assert!(p.z > 3.0, "z = {}", p.z);
    assert!(warned(&r, WarningCode::ProbeDisagrees));

    let sim0 = simulate::simulate(&recorded_scenario(31, 0.0)).unwrap();
    let (text, files) = recordings_study(&sim0, Declared::Right);
    let r0 = run(&text, files).unwrap();
    let p0 = r0.two_orientation.as_ref().unwrap().probe.as_ref().unwrap();
    assert!(p0.z.abs() < 3.0, "z = {}", p0.z);
    assert!(!warned(&r0, WarningCode::ProbeDisagrees));
}

/// Raw recordings give the same joint fit as a table of their reduced means and standard
/// errors (a σ column): one reduction, whatever the data set's form.
#[test]
fn recordings_fit_as_the_table_of_their_reductions() {
    let sim = simulate::simulate(&recorded_scenario(32, 0.3 * C_R)).unwrap();
    let (text, files) = recordings_study(&sim, Declared::Right);
    let raw = run(&text, files).unwrap();
    let raw_s = raw.two_orientation.as_ref().unwrap();

    let (text, mut files) = probe_study(&sim, Declared::Right);
    let mut sets = String::new();
    for m in &raw_s.mountings {
        let mut csv = String::from("rate_deg_s,output_rad_s,u_rad_s\n");
        for rec in &m.recordings {
            csv.push_str(&format!(
                "{:?},{:?},{:?}\n",
                rec.rate_deg_s, rec.output_rad_s, rec.u_rad_s
            ));
        }
        let file = format!("{}.csv", m.orientation);
        files.insert(Path::new(DIR).join(&file), csv.into_bytes());
        sets.push_str(&format!(
            "(orientation: {}, radius_m: {:?}, table: (file: \"{file}\", sigma_column: \"u_rad_s\")),",
            m.orientation, m.radius_m
        ));
    }
    let end = text.rfind(')').unwrap();
    let text = format!(
        "{}    two_orientation: (orientations: [{sets}], compare_with: \"spindle\", trials: fixed(2000)),\n)\n",
        &text[..end]
    );
    let table = run(&text, files).unwrap();
    let t = table.two_orientation.as_ref().unwrap();
    for (a, b, what) in [
        (raw_s.k2.value, t.k2.value, "k2"),
        (raw_s.k2.u, t.k2.u, "u(k2)"),
        (raw_s.c_m_s2.value, t.c_m_s2.value, "C"),
        (raw_s.c_m_s2.u, t.c_m_s2.u, "u(C)"),
    ] {
        assert!((a - b).abs() <= 1e-12 * a.abs(), "{what}: {a} vs {b}");
    }
    assert!(t.mountings.iter().all(|m| m.recordings.is_empty()));
    assert_eq!(
        t.mountings[0].table.as_deref(),
        Some("/nonexistent/two_orientation/ia_in.csv")
    );
}

/// The committed study `fixtures/studies/two_orientation_recordings.ron` (24 raw recordings in two
/// orientations) against its scenario's truth: k2, C and each mounting's k0 within U95; the
/// probe misses the arm stretch.
#[test]
fn the_fixture_study_on_raw_recordings_holds_the_truth() {
    let path = root().join("fixtures/studies/two_orientation_recordings.ron");
    let inputs = pipeline::load_study(&path).unwrap();
    let r = pipeline::run(&inputs).unwrap();
    let truth: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("fixtures/two_orientation_recordings/truth.json"))
            .unwrap(),
    )
    .unwrap();
    let s = r.two_orientation.as_ref().unwrap();
    let k2 = truth["mountings"][0]["coefficients"]["k2_rad_s_g2"]
        .as_f64()
        .unwrap();
    let c = truth["radius_growth"]["c_m_s2"].as_f64().unwrap();
    assert!((s.k2.value - k2).abs() < s.k2.u95, "k2 {:?}", s.k2);
    assert!(
        (s.c_m_s2.value - c).abs() < s.c_m_s2.u95,
        "C {:?}",
        s.c_m_s2
    );
    let k0_in = truth["mountings"][0]["coefficients"]["k0_rad_s"]
        .as_f64()
        .unwrap();
    let k0_out = truth["mountings"][1]["coefficients"]["k0_rad_s"]
        .as_f64()
        .unwrap();
    assert!((s.mountings[0].k0.value - k0_in).abs() < s.mountings[0].k0.u95);
    assert!((s.mountings[1].k0.value - k0_out).abs() < s.mountings[1].k0.u95);
    assert_eq!(
        s.mountings
            .iter()
            .map(|m| m.recordings.len())
            .sum::<usize>(),
        24
    );
    assert!(s.probe.as_ref().unwrap().z > 3.0);
    // every recording is among the study's input files, with its SHA-256 and role
    let recorded: Vec<_> = inputs
        .input_files()
        .into_iter()
        .filter(|f| f.field.starts_with("two_orientation.orientations["))
        .collect();
    assert_eq!(recorded.len(), 24);
    assert!(
        recorded
            .iter()
            .all(|f| f.digest.is_some() && f.role == pipeline::InputRole::PigaRecording)
    );
    assert_eq!(
        recorded[13].field,
        "two_orientation.orientations[1].recordings.files[1]"
    );
}

/// Both a table and recordings in one orientation, neither in the other; then bad
/// recordings in both orientations (a non-positive rate, an empty file, a file without the
/// output column): every problem named by its field at once.
#[test]
fn bad_recording_sets_are_named_by_field_at_once() {
    let sim = simulate::simulate(&recorded_scenario(33, 0.0)).unwrap();
    let (text, mut files) = recordings_study(&sim, Declared::Right);
    files.insert(
        Path::new(DIR).join("t.csv"),
        b"rate_deg_s,output_rad_s\n".to_vec(),
    );
    // orientation 0: a table beside its recordings; orientation 1: no data at all
    let first = text.find("recordings: (format").unwrap();
    let both = format!(
        "{}table: (file: \"t.csv\"), {}",
        &text[..first],
        &text[first..]
    );
    let second = both.rfind("recordings: (format").unwrap();
    let close = second + both[second..].find("]))").unwrap() + "]))".len();
    let neither = format!(
        "{}){}",
        &both[..second].trim_end_matches(", "),
        &both[close..]
    );
    let err = run(&neither, files.clone()).unwrap_err();
    let all = super::chain(&err);
    assert!(
        all.contains(
            "field `two_orientation.orientations[0]`: give exactly one of `table` and `recordings`"
        ),
        "{all}"
    );
    assert!(
        all.contains(
            "field `two_orientation.orientations[1]`: give exactly one of `table` and `recordings`"
        ),
        "{all}"
    );

    // a rate of 0 in IA in; an empty file and a file without the output column in IA out
    let bad_rate = text.replacen(
        "(rate_deg_s: 50.0, file: \"piga_ia_in_",
        "(rate_deg_s: 0.0, file: \"piga_ia_in_",
        1,
    );
    let emptied = Path::new(DIR).join("piga_ia_out_065.0000deg_s.csv");
    assert!(files.insert(emptied, Vec::new()).is_some());
    files.insert(
        Path::new(DIR).join("piga_ia_out_080.0000deg_s.csv"),
        b"time_s,angle_deg\n0,0\n0.1,1\n".to_vec(),
    );
    let err = run(&bad_rate, files).unwrap_err();
    let PipelineError::Several { errors } = &err else {
        panic!("{}", super::chain(&err))
    };
    let text: Vec<String> = errors.iter().map(|e| super::chain(e)).collect();
    let all = text.join("\n");
    assert_eq!(errors.len(), 3, "{all}");
    assert!(
        text[0].contains("two_orientation.orientations[0].recordings.files[1].rate_deg_s"),
        "{all}"
    );
    assert!(
        text[1].contains("two_orientation.orientations[1].recordings.files[2]")
            && text[1].contains("piga_ia_out_065"),
        "{all}"
    );
    assert!(
        text[2].contains("two_orientation.orientations[1].recordings.files[3]")
            && text[2].contains("output_rad"),
        "{all}"
    );
}
