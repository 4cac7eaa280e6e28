//! Recording a study, and one unit's history, in a records database of 10,000 certificates
//! of 1,000 units (ten yearly certificates each, every one with its DCC), on disk
//! (`target/records-bench/records.sqlite`, WAL). Prints the database's size.
//!
//! `cargo bench -p records --bench records`; figures in docs/PERFORMANCE.md.

use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use pipeline::StudyResults;
use records::{Access, Database, Date, HistoryOptions, IntervalRequest, Submission};

const UNITS: usize = 1_000;
const PER_UNIT: usize = 10;

fn campaign() -> StudyResults {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let inputs = pipeline::load_study(&root.join("fixtures/studies/campaign.ron")).unwrap();
    pipeline::run(&inputs).unwrap()
}

/// Unit `u`'s `n`-th certificate: its own serial, id, date and a k2 drifting by 1 % a year.
fn variant(base: &StudyResults, u: usize, n: usize) -> StudyResults {
    let mut r = base.clone();
    let c = r.certificate.as_mut().unwrap();
    c.item.serial = format!("SN {u:05}");
    c.id = format!("CC-{u:05}-{n:02}");
    let date = Date::from_ymd(2016 + n as i64, 1 + (u % 12) as u32, 1 + (u % 28) as u32)
        .unwrap()
        .to_string();
    c.dates.measured = date.clone();
    c.dates.issued = date;
    for k in &mut c.certified.coefficients {
        if k.name == "k2" {
            k.value *= 1.0 + 0.01 * n as f64;
        }
    }
    r
}

struct Encoded {
    results: StudyResults,
    json: Vec<u8>,
    dcc: Vec<u8>,
}

fn encode(r: StudyResults, software: &dcc::Software) -> Encoded {
    let dcc = dcc::write_dcc(&dcc::DccInput {
        results: &r,
        software,
        files: None,
    })
    .unwrap()
    .into_bytes();
    let json = serde_json::to_vec(&r).unwrap();
    Encoded {
        results: r,
        json,
        dcc,
    }
}

fn submission(e: &Encoded) -> Submission<'_> {
    Submission {
        results: &e.results,
        results_json: &e.json,
        inputs: Vec::new(),
        tool_version: Some("bench".into()),
        dcc_xml: Some(&e.dcc),
        certificate_pdf: None,
        centrifuge: None,
        date: None,
        profile: None,
        supersedes: None,
    }
}

fn database(base: &StudyResults, software: &dcc::Software) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/records-bench");
    let path = dir.join("records.sqlite");
    if path.is_file()
        && let Ok(db) = Database::open(&path, Access::Existing)
        && db.counts().map(|c| c.1).unwrap_or(0) >= (UNITS * PER_UNIT) as i64
    {
        return path;
    }
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut db = Database::open(&path, Access::CreateIfMissing).unwrap();
    for u in 0..UNITS {
        for n in 0..PER_UNIT {
            let e = encode(variant(base, u, n), software);
            db.record(&submission(&e)).unwrap();
        }
    }
    path
}

#[allow(clippy::print_stderr)] // the database's size, beside criterion's figures
fn bench(c: &mut Criterion) {
    let base = campaign();
    let software = dcc::Software {
        name: "centrifuge-cal".into(),
        release: "bench".into(),
        commit: "unknown".into(),
    };
    let path = database(&base, &software);
    let size = |p: &Path| std::fs::metadata(p).map(|m| m.len()).unwrap_or(0);
    eprintln!(
        "records database of {} certificates: {:.1} MB (+ {:.1} MB WAL)",
        UNITS * PER_UNIT,
        size(&path) as f64 / 1e6,
        size(&path.with_extension("sqlite-wal")) as f64 / 1e6
    );
    let one = encode(variant(&base, 0, 0), &software);
    eprintln!(
        "one certificate: results.json {} bytes, DCC {} bytes",
        one.json.len(),
        one.dcc.len()
    );

    let mut db = Database::open(&path, Access::Existing).unwrap();
    let mut next = 0usize;
    c.bench_function("record one study into 10,000 certificates", |b| {
        b.iter_batched(
            || {
                next += 1;
                encode(variant(&base, UNITS + next, 0), &software)
            },
            |e| black_box(db.record(&submission(&e)).unwrap()),
            BatchSize::PerIteration,
        );
    });
    drop(db);
    c.bench_function("history of one unit among 10,000 certificates", |b| {
        b.iter(|| {
            let db = Database::open(&path, Access::Existing).unwrap();
            let h = records::unit_history(
                db.unit_records(black_box("SN 00500")).unwrap(),
                &HistoryOptions {
                    at: None,
                    interval: Some((
                        "k2".into(),
                        IntervalRequest {
                            tolerance: 1e-7,
                            reliability: 0.95,
                        },
                    )),
                },
            )
            .unwrap();
            black_box(h)
        });
    });
}

fn all_units(c: &mut Criterion) {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/records-bench/records.sqlite");
    c.bench_function("records of all 1,000 units read, no fit", |b| {
        b.iter(|| {
            let db = Database::open(&path, Access::Existing).unwrap();
            let n: usize = db
                .units()
                .unwrap()
                .iter()
                .map(|u| db.unit_records(u).unwrap().certificates.len())
                .sum();
            black_box(n)
        });
    });
    c.bench_function("history of all 1,000 units (10,000 certificates)", |b| {
        b.iter(|| {
            let db = Database::open(&path, Access::Existing).unwrap();
            let mut drifting = 0usize;
            for unit in db.units().unwrap() {
                let h = records::unit_history(
                    db.unit_records(&unit).unwrap(),
                    &HistoryOptions::default(),
                )
                .unwrap();
                drifting += h
                    .terms
                    .iter()
                    .filter(|t| t.drift.as_ref().is_some_and(|d| d.significant))
                    .count();
            }
            black_box(drifting)
        });
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench, all_units
}
criterion_main!(benches);
