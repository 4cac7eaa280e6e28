//! The study's output directory: written all at once, with provenance in results.json.

use std::collections::BTreeMap;
use std::path::Path;

use edge_io::{EdgeIoError, fault};
use pipeline::{Inputs, StudyResults};
use report::{Provenance, ReportError};
use serde_json::Value;

use super::{Scratch, root};

fn study(name: &str) -> (Inputs, StudyResults) {
    let study = pipeline::load_study(&root().join("fixtures/studies").join(name)).unwrap();
    let results = pipeline::run(&study).unwrap();
    (study, results)
}

/// Every file of a directory with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_failed_run_leaves_the_previous_outputs_and_a_good_one_replaces_them() {
    let scratch = Scratch::new("outputs");
    let out = scratch.0.join("study");
    let (recordings, recordings_results) = study("recordings-small.ron");
    let provenance = Provenance::of_study(&recordings, None).unwrap();
    report::write_outputs(&out, &recordings_results, None, None, Some(&provenance)).unwrap();
    let before = snapshot(&out);
    assert_eq!(
        before.keys().collect::<Vec<_>>(),
        [
            // the record of what was written (issue 32), then the files
            edge_io::OUTPUT_RECORD,
            "probe_signals_pre_balance.svg",
            "radius_error.svg",
            "report.md",
            "results.json"
        ]
    );

    // Another study whose last file cannot be written: nothing changes.
    let (paper, paper_results) = study("paper-2025.ron");
    let provenance = Provenance::of_study(&paper, None).unwrap();
    {
        let _fail = fault::fail_writing("radius_error.svg");
        match report::write_outputs(&out, &paper_results, None, None, Some(&provenance)) {
            Err(ReportError::File(EdgeIoError::Write { path, .. })) => {
                assert_eq!(path, out.join("radius_error.svg"));
            }
            other => panic!("expected a write error, got {other:?}"),
        }
    }
    assert_eq!(
        snapshot(&out),
        before,
        "the previous outputs, byte for byte"
    );
    assert_eq!(names(&scratch.0), ["study"], "no staging directory is left");

    // The same study succeeding: exactly its files, the other study's probe figure gone.
    let files = report::write_outputs(&out, &paper_results, None, None, Some(&provenance)).unwrap();
    assert!(files.probe_signals_svg.is_empty());
    assert_eq!(
        names(&out),
        [
            edge_io::OUTPUT_RECORD,
            "radius_error.svg",
            "report.md",
            "results.json"
        ]
    );
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(files.results_json).unwrap()).unwrap();
    assert_eq!(json["study"], paper_results.study.as_str());
    assert_eq!(names(&scratch.0), ["study"]);
}

#[test]
fn results_json_records_what_produced_it() {
    let (recordings, results) = study("recordings-small.ron");
    let expected = root().join("fixtures/expected/recordings-small.ron");
    let (_, record) = report::Expected::load_recorded(&expected).unwrap();
    let provenance = Provenance::of_study(&recordings, Some(&record)).unwrap();
    let with: Value =
        serde_json::from_str(&report::results_json_with_provenance(&results, &provenance).unwrap())
            .unwrap();
    let p = &with["provenance"];
    assert_eq!(p["tool"], "centrifuge-cal");
    assert_eq!(p["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(
        p["config"]["path"],
        recordings.source().display().to_string()
    );
    let config_bytes = std::fs::metadata(recordings.source()).unwrap().len();
    assert_eq!(p["config"]["bytes"], config_bytes);
    assert_eq!(p["expected"]["path"], expected.display().to_string());
    let inputs = p["inputs"].as_array().unwrap();
    assert_eq!(inputs.len(), 6, "the six pre-balance recordings");
    let first =
        root().join("fixtures/studies/../recordings/pre-balance-small/probe_020.0000deg_s.csv");
    assert_eq!(inputs[0]["path"], first.display().to_string());
    assert_eq!(inputs[0]["bytes"], std::fs::metadata(first).unwrap().len());
    for record in inputs.iter().chain([&p["config"], &p["expected"]]) {
        let sha = record["sha256"].as_str().unwrap();
        assert!(
            sha.len() == 64 && sha.bytes().all(|b| b.is_ascii_hexdigit()),
            "{sha}"
        );
    }
    // Without provenance the text is the results alone, as before.
    let mut without: Value =
        serde_json::from_str(&report::results_json(&results).unwrap()).unwrap();
    assert!(without.get("provenance").is_none());
    without
        .as_object_mut()
        .unwrap()
        .insert("provenance".into(), p.clone());
    assert_eq!(without, with);
}

#[test]
fn a_directory_holding_other_files_is_not_replaced() {
    let scratch = Scratch::new("outputs-foreign");
    std::fs::write(scratch.0.join("thesis.tex"), "keep").unwrap();
    let (_, results) = study("paper-2025.ron");
    match report::write_outputs(&scratch.0, &results, None, None, None) {
        Err(ReportError::File(EdgeIoError::ForeignEntries {
            count: 1, example, ..
        })) => {
            assert_eq!(example, "thesis.tex");
        }
        other => panic!("expected ForeignEntries, got {other:?}"),
    }
    assert_eq!(names(&scratch.0), ["thesis.tex"]);
}

#[test]
fn a_study_with_a_certificate_writes_its_dcc_beside_it() {
    let scratch = Scratch::new("outputs-dcc");
    let out = scratch.0.join("study");
    let (campaign, mut results) = study("campaign.ron");
    let provenance = Provenance::of_study(&campaign, None).unwrap();
    let files = report::write_outputs(&out, &results, None, None, Some(&provenance)).unwrap();
    let path = files.certificate_dcc.expect("certificate.dcc.xml");
    assert_eq!(path, out.join("certificate.dcc.xml"));
    assert!(names(&out).contains(&"certificate.pdf".to_owned()));
    let xml = std::fs::read_to_string(&path).unwrap();
    assert!(xml.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>"));
    assert!(xml.contains("<dcc:uniqueIdentifier>CC-2026-0042</dcc:uniqueIdentifier>"));
    // the configuration and every data file, each with its SHA-256
    for record in std::iter::once(&provenance.config).chain(&provenance.inputs) {
        let line = format!("<dcc:charsXMLList>{}</dcc:charsXMLList>", record.sha256);
        assert_eq!(xml.matches(&line).count(), 1, "{}", record.path);
    }
    let before = snapshot(&out);

    // A certificate the DCC cannot state: the study writes nothing, the previous outputs stay.
    results.certificate.as_mut().unwrap().item.serial = "SN \u{202e}4321".to_owned();
    match report::write_outputs(&out, &results, None, None, Some(&provenance)) {
        Err(ReportError::Dcc(dcc::DccError::HiddenCharacter { field, .. })) => {
            assert_eq!(field, "certificate.item.serial");
        }
        other => panic!("expected the DCC's refusal, got {other:?}"),
    }
    assert_eq!(snapshot(&out), before);
}
