//! The two-orientation study on raw recordings, whole (issue 20: "a two-orientation study
//! with raw recordings at 2 × 12 rates and its Monte Carlo: under 2 s").
//!
//! `cargo bench -p pipeline --bench two_orientation_study`. The study is
//! `fixtures/studies/two_orientation_recordings.ron` (or the file in `TWO_ORIENTATION_STUDY`): 12 probe
//! recordings fitted per revolution for C_r, 24 raw PIGA output recordings (12 rates with the
//! IA in, 12 with it out) each reduced to its mean output rate over whole spindle revolutions,
//! the joint eq. 23 fit weighted by their standard errors, the GUM and the adaptive Monte
//! Carlo method, and the probe comparison. Three benchmarks:
//!
//! - `in_memory`: the study text and its 36 CSV files held in memory (read once, outside the
//!   timing); each iteration parses the configuration, builds `pipeline::Inputs` (which
//!   parses and checks every CSV from its bytes) and runs `pipeline::run`;
//! - `run_only`: `pipeline::run` on inputs built once (the computation alone);
//! - `from_disk`: `pipeline::load_study` (reading and hashing the files from the page cache)
//!   and `pipeline::run`.
//!
//! No report is written. Before timing, one run prints the Monte Carlo trial count the
//! adaptive run reached (`two_orientation.monte_carlo.trials`); with `TWO_ORIENTATION_STUDY_JSON=path`
//! that run's `results.json` (without provenance) is written to `path`, for
//! `bench/two_orientation_numpy.py`, which does the same job in NumPy.

use std::collections::HashMap;
use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{Criterion, criterion_group, criterion_main};
use pipeline::{Inputs, StudyConfig};
use test_support::MemoryFiles;

/// The workspace's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The study file: `TWO_ORIENTATION_STUDY` or the fixture.
fn study_path() -> PathBuf {
    std::env::var_os("TWO_ORIENTATION_STUDY").map_or_else(
        || root().join("fixtures/studies/two_orientation_recordings.ron"),
        PathBuf::from,
    )
}

/// The data paths the study text names (`file: "…"`), relative to its folder.
fn named_files(text: &str) -> Vec<&str> {
    const KEY: &str = "file: \"";
    let mut files = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(KEY) {
        let after = &rest[at + KEY.len()..];
        let end = after.find('"').expect("a closing quote");
        files.push(&after[..end]);
        rest = &after[end..];
    }
    files
}

/// The study's text and every file it names, read once, keyed by the path the study asks
/// for (its folder joined with the name, as `pipeline` resolves it).
fn read_study(path: &Path) -> (String, MemoryFiles) {
    let text = std::fs::read_to_string(path).expect("the study file");
    let base = path.parent().expect("a study file has a folder");
    let files: HashMap<PathBuf, Vec<u8>> = named_files(&text)
        .into_iter()
        .map(|name| {
            let p = base.join(name);
            let bytes = std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (p, bytes)
        })
        .collect();
    (text, MemoryFiles(files))
}

/// The whole study from memory: configuration, inputs (every CSV parsed), run.
fn study_in_memory(text: &str, source: &Path, files: &MemoryFiles) -> pipeline::StudyResults {
    let config = StudyConfig::from_ron(text, source).expect("a valid study");
    let inputs = Inputs::new(config, source, files).expect("valid inputs");
    pipeline::run(&inputs).expect("the study runs")
}

/// One run before timing: the trial count, and the results for the NumPy script.
#[allow(
    clippy::print_stdout,
    reason = "a benchmark reports what it measured on standard output, as criterion does"
)]
fn report_once(results: &pipeline::StudyResults, files: usize) {
    let two_orientation = results
        .two_orientation
        .as_ref()
        .expect("the study has a two-orientation section");
    println!(
        "two_orientation_study: {files} files held in memory; adaptive Monte Carlo reached {} trials \
         (seed {})",
        two_orientation.monte_carlo.trials, two_orientation.monte_carlo.seed
    );
    if let Some(path) = std::env::var_os("TWO_ORIENTATION_STUDY_JSON") {
        let json = report::results_json(results).expect("results as JSON");
        std::fs::write(&path, json).expect("write TWO_ORIENTATION_STUDY_JSON");
        println!(
            "two_orientation_study: results written to {}",
            Path::new(&path).display()
        );
    }
}

fn bench(c: &mut Criterion) {
    let source = study_path();
    let (text, files) = read_study(&source);
    let results = study_in_memory(&text, &source, &files);
    report_once(&results, files.0.len());
    let inputs = Inputs::new(
        StudyConfig::from_ron(&text, &source).expect("a valid study"),
        &source,
        &files,
    )
    .expect("valid inputs");

    let mut group = c.benchmark_group("two_orientation_study");
    group.sample_size(20);
    group.bench_function("in_memory", |b| {
        b.iter(|| study_in_memory(black_box(&text), &source, &files));
    });
    group.bench_function("run_only", |b| {
        b.iter(|| pipeline::run(black_box(&inputs)).expect("the study runs"));
    });
    group.bench_function("from_disk", |b| {
        b.iter(|| {
            let inputs = pipeline::load_study(black_box(&source)).expect("the study loads");
            pipeline::run(&inputs).expect("the study runs")
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
