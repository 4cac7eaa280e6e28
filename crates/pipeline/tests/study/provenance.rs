//! results.json lists every input of a study as the study read it (issue 17): the
//! configuration, the probe recordings and the calibration's PIGA table or raw recordings,
//! each with its size and SHA-256 taken as it was read, and nothing read again afterwards.

use std::path::Path;
use test_support::Scratch;

use report::FileRecord;
use serde_json::Value;

use crate::root;

/// results.json (with provenance) of the study at `config`, as `cargo xtask study` writes it.
fn results_json(config: &Path) -> Value {
    let study = pipeline::load_study(config).unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = report::Provenance::of_study(&study, None).unwrap();
    let text = report::results_json_with_provenance(&results, &provenance).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// The campaign study with its calibration read from the PIGA table at `table` instead of
/// the raw recordings; data paths made absolute so that the text can live anywhere.
fn campaign_with_table(table: &Path) -> String {
    let text = std::fs::read_to_string(root().join("fixtures/studies/campaign.ron")).unwrap();
    let start = text.find("        recordings: (").unwrap();
    let close = "\n        ),\n";
    let end = start + text[start..].find(close).unwrap() + close.len();
    let fixtures = root().join("fixtures").canonicalize().unwrap();
    format!(
        "{}        table: (file: {:?}),\n{}",
        &text[..start],
        table.display().to_string(),
        &text[end..]
    )
    .replace("\"../", &format!("\"{}/", fixtures.display()))
}

fn is_sha256(value: &Value) -> bool {
    value.as_str().is_some_and(|s| {
        s.len() == 64
            && s.bytes()
                .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
    })
}

#[test]
fn the_campaign_lists_its_piga_recordings_with_their_sha256() {
    let config = root().join("fixtures/studies/campaign.ron");
    let json = results_json(&config);
    let provenance = &json["provenance"];
    let inputs = provenance["inputs"].as_array().unwrap();
    let of_role =
        |role: &str| -> Vec<&Value> { inputs.iter().filter(|i| i["role"] == role).collect() };
    let piga = of_role("piga_recording");
    let probe = of_role("probe_recording");
    assert_eq!(piga.len(), 20, "{inputs:#?}");
    assert_eq!(probe.len(), 20, "{inputs:#?}");
    assert_eq!(
        inputs.len(),
        40,
        "nothing else is a data file of the campaign"
    );
    // The probe recordings first, then the PIGA's, each in the configuration's order.
    assert_eq!(inputs[0]["field"], "phases[0].points.files[0]");
    assert_eq!(inputs[20]["field"], "calibration.recordings.files[0]");
    for (i, p) in piga.iter().enumerate() {
        assert_eq!(p["field"], format!("calibration.recordings.files[{i}]"));
        let path = p["path"].as_str().unwrap();
        assert!(
            path.contains("campaign/piga_") && path.ends_with(".csv"),
            "{path}"
        );
        assert!(is_sha256(&p["sha256"]), "{p}");
        // The digest taken as the study read the file is the file's.
        let again = FileRecord::of(Path::new(path)).unwrap();
        assert_eq!(p["sha256"], again.sha256.as_str(), "{path}");
        assert_eq!(p["bytes"], again.bytes, "{path}");
    }
    for p in &probe {
        assert!(is_sha256(&p["sha256"]), "{p}");
    }
    let again = FileRecord::of(&config).unwrap();
    assert_eq!(provenance["config"]["sha256"], again.sha256.as_str());
    assert_eq!(provenance["config"]["bytes"], again.bytes);
    assert!(provenance["config"].get("role").is_none());
}

#[test]
fn a_table_calibration_lists_its_piga_table_as_it_was_read() {
    let scratch = Scratch::new("pipeline-provenance-table");
    let table = scratch.0.join("piga.csv");
    let original = std::fs::read(root().join("fixtures/campaign/piga.csv")).unwrap();
    std::fs::write(&table, &original).unwrap();
    let config = scratch.0.join("table.ron");
    std::fs::write(&config, campaign_with_table(&table)).unwrap();
    let study = pipeline::load_study(&config).unwrap();
    let files = study.input_files();
    let last = files.last().unwrap();
    assert_eq!(last.role, pipeline::InputRole::PigaTable);
    assert_eq!(last.role.to_string(), "PIGA table");
    assert_eq!(last.field, "calibration.table");
    assert_eq!(last.path, table);
    assert_eq!(files.len(), 21, "20 probe recordings and the table");

    // The files change after the study read them: the provenance is of what was read, not
    // of what is on disk now (nothing is read again).
    std::fs::write(&table, "rate_deg_s,output_rad_s\n20,1\n").unwrap();
    std::fs::write(&config, "changed").unwrap();
    let results = pipeline::run(&study).unwrap();
    let provenance = report::Provenance::of_study(&study, None).unwrap();
    let json: Value =
        serde_json::from_str(&report::results_json_with_provenance(&results, &provenance).unwrap())
            .unwrap();
    let inputs = json["provenance"]["inputs"].as_array().unwrap();
    let record = inputs.last().unwrap();
    assert_eq!(record["role"], "piga_table");
    assert_eq!(record["field"], "calibration.table");
    assert_eq!(record["path"], table.display().to_string());
    let read = pipeline::FileDigest::of(&original);
    assert_eq!(record["sha256"], read.sha256.as_str());
    assert_eq!(record["bytes"], read.bytes);
    assert_eq!(read.bytes, original.len() as u64);
    assert_ne!(
        record["sha256"],
        FileRecord::of(&table).unwrap().sha256.as_str()
    );
    let config_record = &json["provenance"]["config"];
    assert_ne!(config_record["bytes"], "changed".len());
    assert_eq!(
        config_record["bytes"],
        campaign_with_table(&table).len() as u64
    );
}
