//! A study runs on recordings held in memory: nothing is read from disk.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use pipeline::{DataSource, Inputs, StudyConfig};
use recording::{Recording, RecordingError, RecordingFormat, Table, TableFormat};
use simulate::Scenario;

use crate::root;

/// The pre-balance-small scenario simulated in memory, each recording parsed from its CSV
/// text in memory, keyed by a path that does not exist on disk.
fn recordings_in_memory() -> HashMap<PathBuf, Recording> {
    let text =
        std::fs::read_to_string(root().join("fixtures/scenarios/pre-balance-small.ron")).unwrap();
    let scenario = Scenario::parse(&text, Path::new("pre-balance-small.ron")).unwrap();
    let simulation = simulate::simulate(&scenario).unwrap();
    simulation
        .recordings
        .iter()
        .map(|r| {
            let mut csv = Vec::new();
            r.write_csv(&mut csv).unwrap();
            let path = Path::new("/nonexistent/in-memory").join(&r.file_name);
            let recording =
                recording::parse_recording(&csv, &path, &RecordingFormat::default()).unwrap();
            (path, recording)
        })
        .collect()
}

/// Recordings held in memory, counting the reads; no tables.
struct Memory {
    recordings: HashMap<PathBuf, Recording>,
    reads: std::sync::atomic::AtomicUsize,
}

impl DataSource for Memory {
    fn recording(&self, path: &Path, _: &RecordingFormat) -> Result<Recording, RecordingError> {
        self.reads
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(self.recordings[path].clone())
    }

    fn table(&self, path: &Path, _: &TableFormat) -> Result<Table, RecordingError> {
        unreachable!("the study names no table, yet {path:?} was asked for")
    }
}

#[test]
fn a_study_runs_on_recordings_in_memory() {
    let memory = recordings_in_memory();
    let text = std::fs::read_to_string(root().join("fixtures/studies/recordings-small.ron"))
        .unwrap()
        .replace("../recordings/pre-balance-small/", "in-memory/");
    let source = Path::new("/nonexistent/study.ron");
    let config = StudyConfig::from_ron(&text, source).unwrap();
    let source_data = Memory {
        recordings: memory,
        reads: std::sync::atomic::AtomicUsize::new(0),
    };
    let inputs = Inputs::new(config, source, &source_data).unwrap();
    assert_eq!(source_data.reads.into_inner(), 6);
    // A source that keeps no digest: the study says so (`None`) rather than inventing one.
    assert!(inputs.config_digest().is_none());
    let files = inputs.input_files();
    assert_eq!(files.len(), 6);
    assert!(files.iter().all(|f| f.digest.is_none()));
    let in_memory = pipeline::run(&inputs).unwrap();

    // The same study from the committed files, which the simulator wrote from the same
    // scenario: the same numbers.
    let from_disk = pipeline::run(
        &pipeline::load_study(&root().join("fixtures/studies/recordings-small.ron")).unwrap(),
    )
    .unwrap();
    assert_eq!(
        in_memory.phase("pre_balance").unwrap().points,
        from_disk.phase("pre_balance").unwrap().points
    );
    assert_eq!(
        in_memory.phase("pre_balance").unwrap().fit,
        from_disk.phase("pre_balance").unwrap().fit
    );
    assert_eq!(
        in_memory.phase("post_balance").unwrap(),
        from_disk.phase("post_balance").unwrap()
    );
}
