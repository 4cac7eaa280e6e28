//! A phase given as raw probe recordings: the study fits each per revolution, recovers the
//! simulated truth, draws Fig. 4, and names the file and line of bad input.

use std::path::{Path, PathBuf};

use pipeline::PipelineError;
use report::Expected;

use super::root;

fn study_path() -> PathBuf {
    root().join("fixtures/studies/recordings-small.ron")
}

#[test]
fn recordings_recover_the_simulated_truth() {
    let study = pipeline::load_study(&study_path()).unwrap();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let results = pipeline::run_with_progress(&study, &|event| {
        if let pipeline::Progress::RecordingDone { .. } = event {
            done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
    })
    .unwrap();
    assert_eq!(done.into_inner(), 6, "one progress event per recording");
    let expected = Expected::load(&root().join("fixtures/expected/recordings-small.ron")).unwrap();
    let outcomes = expected.compare(&results).unwrap();
    let failed: Vec<_> = outcomes.iter().filter(|o| !o.passed).collect();
    assert!(failed.is_empty(), "{failed:#?}");
    for p in &results.phase("pre_balance").unwrap().points {
        assert!(p.revolutions.unwrap() >= 2);
        let sigma = p.radius_error_sigma_um.unwrap();
        assert!(sigma > 0.0 && sigma < 0.02, "{p:?}");
    }
    assert_eq!(results.phase("pre_balance").unwrap().traces.len(), 6);
    let dir = std::env::temp_dir().join(format!("centrifuge-cal-rec-{}", std::process::id()));
    let files = report::write_outputs(&dir, &results, None, None, None).unwrap();
    assert_eq!(
        files.probe_signals_svg.len(),
        1,
        "only the pre-balance phase has recordings"
    );
    let svg = std::fs::read_to_string(&files.probe_signals_svg[0]).unwrap();
    assert!(svg.contains("200.1234 deg/s") && svg.contains("fit (eq. 20)"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The recordings study with its recording list replaced, written into a temporary folder.
fn study_with_files(dir: &Path, files: &str) -> Result<pipeline::Inputs, PipelineError> {
    let text = std::fs::read_to_string(study_path()).unwrap();
    let start = text.find("files: [").unwrap();
    let end = start + text[start..].find("],").unwrap() + 2;
    let text = format!("{}files: [{files}],{}", &text[..start], &text[end..]);
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join("study.ron");
    std::fs::write(&path, text).unwrap();
    pipeline::load_study(&path)
}

fn good_files(dir: &Path) -> Vec<PathBuf> {
    let src = root().join("fixtures/recordings/pre-balance-small");
    std::fs::create_dir_all(dir).unwrap();
    ["020.0000", "040.0000", "080.1234", "110.1234"]
        .iter()
        .map(|r| {
            let name = format!("probe_{r}deg_s.csv");
            let to = dir.join(&name);
            std::fs::copy(src.join(&name), &to).unwrap();
            to
        })
        .collect()
}

fn list(files: &[PathBuf], rates: &[f64]) -> String {
    files
        .iter()
        .zip(rates)
        .map(|(f, r)| format!("(rate_deg_s: {r}, file: {:?}),", f.file_name().unwrap()))
        .collect()
}

const RATES: [f64; 4] = [20.0, 40.0, 80.1234, 110.1234];

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("centrifuge-cal-{name}-{}", std::process::id()))
}

#[test]
fn relative_paths_resolve_against_the_configuration() {
    let dir = temp("relative");
    let files = good_files(&dir);
    let study = study_with_files(&dir, &list(&files, &RATES)).unwrap();
    let results = pipeline::run(&study).unwrap();
    assert_eq!(results.phase("pre_balance").unwrap().points.len(), 4);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_recording_names_the_field_and_the_file() {
    let dir = temp("missing");
    let mut files = good_files(&dir);
    files[2] = dir.join("nope.csv");
    let err = study_with_files(&dir, &list(&files, &RATES)).unwrap_err();
    match &err {
        PipelineError::Recording { field, source, .. } => {
            assert_eq!(field, "phases[0].points.files[2]");
            assert!(source.to_string().contains("nope.csv"), "{source}");
        }
        other => panic!("expected Recording, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bad_sample_names_the_recording_and_its_line() {
    let dir = temp("nan");
    let files = good_files(&dir);
    let text = std::fs::read_to_string(&files[1]).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    lines[100] = "3.960000,NaN,7.920000";
    std::fs::write(&files[1], lines.join("\n")).unwrap();
    let err = study_with_files(&dir, &list(&files, &RATES)).unwrap_err();
    let message = crate::chain(&err);
    assert!(
        message.contains("probe_040.0000deg_s.csv:101"),
        "the message names the file and line: {message}"
    );
    assert!(matches!(err, PipelineError::Recording { .. }));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn recording_lists_are_validated() {
    let dir = temp("lists");
    let files = good_files(&dir);
    match study_with_files(&dir, "") {
        Err(PipelineError::EmptyList { field, .. }) => {
            assert_eq!(field, "phases[0].points.files")
        }
        other => panic!("expected EmptyList, got {other:?}"),
    }
    match study_with_files(&dir, &list(&files, &[20.0, 40.0, 20.0, 110.1234])) {
        Err(PipelineError::DuplicateRate { field, first, .. }) => {
            assert_eq!(field, "phases[0].points.files[2].rate_deg_s");
            assert_eq!(first, "phases[0].points.files[0].rate_deg_s");
        }
        other => panic!("expected DuplicateRate, got {other:?}"),
    }
    match study_with_files(&dir, &list(&files[..2], &RATES[..2])) {
        Err(PipelineError::TooFewPoints { got, need, .. }) => assert_eq!((got, need), (2, 3)),
        other => panic!("expected TooFewPoints, got {other:?}"),
    }
    let text = std::fs::read_to_string(study_path())
        .unwrap()
        .replace("fit: (order: 4, drift: false)", "fit: (order: 0)");
    match pipeline::parse_study(&text, &study_path()) {
        Err(PipelineError::Harmonics { field, .. }) => assert_eq!(field, "phases[0].points.fit"),
        other => panic!("expected Harmonics, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn inverse_variance_weighting_uses_each_recordings_standard_error() {
    let text = std::fs::read_to_string(study_path()).unwrap().replace(
        "name: \"pre_balance\",\n            points: recordings((",
        "name: \"pre_balance\",\n            weighting: inverse_variance,\n            points: recordings((",
    );
    assert!(text.contains("weighting: inverse_variance"));
    let study = pipeline::parse_study(&text, &study_path()).unwrap();
    let results = pipeline::run(&study).unwrap();
    let fit = &results.phase("pre_balance").unwrap().fit;
    assert_eq!(fit.weighting, pipeline::FitWeighting::InverseVariance);
    let chi = fit.reduced_chi.unwrap();
    assert!(chi > 0.1 && chi < 5.0, "√(χ²/dof) = {chi}");
    // The weighted C_r also recovers the scenario's 1.6e-6 (3σ of the probe noise).
    assert!((fit.c_r_m_s2 - 1.6e-6).abs() < 1.0e-9, "{}", fit.c_r_m_s2);
    assert!(
        results
            .phase("post_balance")
            .unwrap()
            .fit
            .reduced_chi
            .is_none()
    );
    // Weighting needs recordings: refused on Table 1 coefficients.
    let text = text.replace(
        "name: \"post_balance\",\n            points: first_harmonic(",
        "name: \"post_balance\",\n            weighting: inverse_variance,\n            points: first_harmonic(",
    );
    match pipeline::parse_study(&text, &study_path()) {
        Err(PipelineError::Unsupported { field, .. }) => {
            assert_eq!(field, "phases[1].weighting");
        }
        other => panic!("expected Unsupported, got {other:?}"),
    }
}
