//! The certificates of both fixture studies (the simulated campaign and the two-orientation
//! study): valid against PTB's DCC schema v3.3.0 (xmllint, offline, through the catalog of
//! `../shared/reference/dcc/`), and every number, identification and digest read back equal
//! to the study's results (results.json's values: `certificate.certified`, the conformity
//! statements, g) and provenance, exactly.

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use serde_json::Value;

use crate::tree::Node;

/// The workspace root.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The schemas, beside the repository as CI checks it out (`../shared`), or where
/// `DCC_SCHEMA_DIR` says (a worktree elsewhere).
fn schema_dir() -> PathBuf {
    std::env::var_os("DCC_SCHEMA_DIR")
        .map_or_else(|| root().join("../shared/reference/dcc"), PathBuf::from)
}

/// A fixture study's certificate with what it was written from.
pub(crate) struct Written {
    /// results.json's value (without provenance).
    pub(crate) json: Value,
    /// The files the study read.
    pub(crate) files: Vec<dcc::InputFile>,
    /// The DCC's text.
    pub(crate) xml: String,
}

fn write(config: &str) -> Written {
    let path = root().join("fixtures/studies").join(config);
    let study = pipeline::load_study(&path).unwrap();
    let results = pipeline::run(&study).unwrap();
    let digest = study.config_digest().expect("the configuration's digest");
    let mut files = vec![dcc::InputFile {
        path: path.display().to_string(),
        bytes: digest.bytes,
        sha256: digest.sha256.clone(),
        role: "configuration".to_owned(),
        field: None,
    }];
    for f in study.input_files() {
        let digest = f.digest.expect("a digest as read");
        files.push(dcc::InputFile {
            path: f.path.display().to_string(),
            bytes: digest.bytes,
            sha256: digest.sha256.clone(),
            role: f.role.code().to_owned(),
            field: Some(f.field),
        });
    }
    let software = dcc::Software {
        name: "centrifuge-cal".to_owned(),
        release: "0.1.0".to_owned(),
        commit: "0123456789abcdef0123456789abcdef01234567".to_owned(),
    };
    let xml = dcc::write_dcc(&dcc::DccInput {
        results: &results,
        software: &software,
        files: Some(&files),
    })
    .unwrap();
    Written {
        json: serde_json::to_value(&results).unwrap(),
        files,
        xml,
    }
}

pub(crate) fn campaign() -> &'static Written {
    static W: OnceLock<Written> = OnceLock::new();
    W.get_or_init(|| write("campaign.ron"))
}

pub(crate) fn two_orientation() -> &'static Written {
    static W: OnceLock<Written> = OnceLock::new();
    W.get_or_init(|| write("two_orientation.ron"))
}

/// xmllint's verdict on `xml` against the DCC schema, offline; `None` when xmllint or the
/// schemas are missing (and `DCC_REQUIRE_XMLLINT` is not set, as `.ci/dcc` sets it).
fn xmllint(name: &str, xml: &str) -> Option<(bool, String)> {
    let dir = schema_dir();
    let required = std::env::var_os("DCC_REQUIRE_XMLLINT").is_some();
    let available =
        dir.join("dcc.xsd").is_file() && Command::new("xmllint").arg("--version").output().is_ok();
    if !available {
        assert!(
            !required,
            "DCC_REQUIRE_XMLLINT is set, but xmllint or {} is missing",
            dir.display()
        );
        return None;
    }
    let file = std::env::temp_dir().join(format!("dcc-{name}-{}.xml", std::process::id()));
    std::fs::write(&file, xml).unwrap();
    let out = Command::new("xmllint")
        .env("XML_CATALOG_FILES", dir.join("catalog.xml"))
        .args(["--nonet", "--noout", "--schema"])
        .arg(dir.join("dcc.xsd"))
        .arg(&file)
        .output()
        .unwrap();
    std::fs::remove_file(&file).unwrap();
    Some((
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    ))
}

pub(crate) fn assert_valid(name: &str, xml: &str) {
    if let Some((ok, report)) = xmllint(name, xml) {
        assert!(ok && report.contains("validates"), "{name}: {report}");
    }
}

#[test]
fn both_certificates_validate_against_the_dcc_schema_offline() {
    // kept under target/dcc/ for a person to read
    let dir = root().join("target/dcc");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, w) in [
        ("campaign", campaign()),
        ("two_orientation", two_orientation()),
    ] {
        std::fs::write(dir.join(format!("{name}.dcc.xml")), &w.xml).unwrap();
        assert_valid(name, &w.xml);
    }
}

#[test]
fn the_validation_can_fail() {
    // a wrong schema version and a missing unique identifier are caught
    let xml = &campaign().xml;
    let wrong_version = xml.replace("schemaVersion=\"3.3.0\"", "schemaVersion=\"3.2.0\"");
    let start = xml.find("<dcc:uniqueIdentifier>").unwrap();
    let end = xml.find("</dcc:uniqueIdentifier>").unwrap() + "</dcc:uniqueIdentifier>".len();
    let no_id = format!("{}{}", &xml[..start], &xml[end..]);
    for (name, broken) in [("wrong-version", wrong_version), ("no-id", no_id)] {
        if let Some((ok, report)) = xmllint(name, &broken) {
            assert!(!ok, "{name} validates: {report}");
        }
    }
}

/// `got` equals `want` to the bit: the text written reads back to the same double.
#[track_caller]
fn same(what: &str, got: f64, want: f64) {
    assert_eq!(got.to_bits(), want.to_bits(), "{what}: {got} ≠ {want}");
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

/// Everything the DCC states, read back and compared with the results it was written from.
fn reads_back_equal(w: &Written) {
    let doc = Node::parse(&w.xml);
    assert_eq!(doc.name, "dcc:digitalCalibrationCertificate");
    let cert = &w.json["certificate"];
    let cal = &w.json["calibration"];

    // identifications, exact text
    assert_eq!(
        doc.find("dcc:uniqueIdentifier").text,
        cert["id"].as_str().unwrap()
    );
    let item = doc.find("dcc:items/dcc:item");
    assert_eq!(
        item.find("dcc:model").text,
        cert["item"]["model"].as_str().unwrap()
    );
    assert_eq!(
        item.find("dcc:manufacturer/dcc:content").text,
        cert["item"]["manufacturer"].as_str().unwrap()
    );
    assert_eq!(
        item.find("dcc:identifications/dcc:identification/dcc:value")
            .text,
        cert["item"]["serial"].as_str().unwrap()
    );
    assert_eq!(
        doc.find("dcc:calibrationLaboratory/dcc:contact/dcc:name/dcc:content")
            .text,
        cert["laboratory"]["name"].as_str().unwrap()
    );
    assert_eq!(
        doc.find("dcc:customer/dcc:name/dcc:content").text,
        cert["customer"]["name"].as_str().unwrap()
    );
    // the dates: the span's ends and the issue date as written
    let measured = cert["dates"]["measured"].as_str().unwrap();
    assert!(measured.starts_with(&doc.find("dcc:beginPerformanceDate").text));
    assert!(measured.ends_with(&doc.find("dcc:endPerformanceDate").text));
    assert_eq!(
        doc.find("dcc:issueDate").text,
        cert["dates"]["issued"].as_str().unwrap()
    );
    assert_eq!(
        doc.find("dcc:receiptDate").text,
        cert["dates"]["received"].as_str().unwrap()
    );

    // g of the model
    let g = doc.by_id("method-calibration").find("si:real");
    same("g", g.number("si:value"), f(&cal["g_m_s2"]));

    // what is certified, and why
    let certified = &cert["certified"];
    assert_eq!(
        doc.by_id("certified-method")
            .find("dcc:declaration/dcc:content")
            .text,
        certified["reason"].as_str().unwrap()
    );

    // the certified coefficients: value and stated interval, relative to k1 too, exact
    let coefficients = certified["coefficients"].as_array().unwrap();
    let validity = certified["validity"].as_array().unwrap();
    let mut labels = Vec::new();
    for c in coefficients {
        let name = c["name"].as_str().unwrap();
        let label = match c["mounting"].as_str() {
            Some(m) if validity.len() > 1 => format!("{name}_{m}"),
            _ => name.to_owned(),
        };
        let real = doc.by_id(&format!("{label}-value")).find("si:real");
        assert_eq!(real.find("si:unit").text, r"\radian\second\tothe{-1}");
        assert_eq!(real.find("si:label").text, label);
        same(&label, real.number("si:value"), f(&c["value"]));
        let gum = c["interval_method"] == "gum";
        // the stated interval of `real` against `stated` (the coefficient or its relative value)
        let interval = |what: &str, real: &Node, stated: &Value| {
            if gum {
                let mu = real.find("si:expandedMU");
                same(
                    &format!("U of {what}"),
                    mu.number("si:valueExpandedMU"),
                    f(&stated["expanded"]),
                );
                same(
                    &format!("k of {what}"),
                    mu.number("si:coverageFactor"),
                    f(&c["k"]),
                );
                assert_eq!(mu.find("si:coverageProbability").text, "0.95");
                assert!(real.try_find("si:coverageIntervalMU").is_none());
            } else {
                let mu = real.find("si:coverageIntervalMU");
                same(
                    &format!("u of {what}"),
                    mu.number("si:valueStandardMU"),
                    f(&stated["u"]),
                );
                same(
                    &format!("low95 of {what}"),
                    mu.number("si:intervalMin"),
                    f(&stated["low95"]),
                );
                same(
                    &format!("high95 of {what}"),
                    mu.number("si:intervalMax"),
                    f(&stated["high95"]),
                );
                assert_eq!(mu.find("si:coverageProbability").text, "0.95");
                assert!(real.try_find("si:expandedMU").is_none());
            }
        };
        interval(&label, real, c);
        let relative = doc
            .descendants()
            .into_iter()
            .find(|n| n.attribute("id") == Some(&format!("{label}-relative")));
        match (&c["relative"], relative) {
            (Value::Null, None) => {}
            (r, Some(node)) if !r.is_null() => {
                let rel = node.find("si:real");
                assert_eq!(rel.find("si:unit").text, r"\ppm");
                same(
                    &format!("{label}/k1"),
                    rel.number("si:value"),
                    f(&r["value"]),
                );
                interval(&format!("{label}/k1"), rel, r);
            }
            (r, node) => panic!("{label}: relative {r} against {node:?}"),
        }
        labels.push(label);
    }

    // the coefficients together, with their covariance and its 95 % region
    let list = doc.by_id("coefficients").find("si:realListXMLList");
    assert_eq!(list.find("si:labelXMLList").text, labels.join(" "));
    let numbers = |path: &str| -> Vec<f64> {
        list.find(path)
            .text
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect()
    };
    let want = |key: &str| -> Vec<f64> { coefficients.iter().map(|c| f(&c[key])).collect() };
    assert_eq!(numbers("si:valueXMLList"), want("value"));
    assert_eq!(numbers("si:valueStandardMUXMLList"), want("u"));
    let covariance = certified["covariance"].as_array().unwrap();
    let n = coefficients.len();
    assert_eq!(covariance.len(), n);
    let columns = list.all("si:columnXMLList");
    assert_eq!(columns.len(), n);
    for (j, column) in columns.iter().enumerate() {
        let cells = column.all("si:covarianceXMLList");
        assert_eq!(cells.len(), n);
        for (i, cell) in cells.iter().enumerate() {
            same(
                &format!("covariance[{i}][{j}]"),
                cell.number("si:valueXMLList"),
                f(&covariance[i][j]),
            );
            assert_eq!(
                cell.find("si:unitXMLList").text,
                r"\radian\tothe{2}\second\tothe{-2}"
            );
        }
    }
    // k² is the 95 % quantile of χ² with n degrees of freedom: P(χ²_n ≤ k²) for even n is
    // 1 − e^{−k²/2} Σ_{j<n/2} (k²/2)^j / j!
    let k = list.number("si:coverageFactorXMLList");
    let h = k * k / 2.0;
    assert_eq!(n % 2, 0);
    let (mut sum, mut term) = (0.0, 1.0);
    for j in 0..n / 2 {
        if j > 0 {
            term *= h / j as f64;
        }
        sum += term;
    }
    assert!((1.0 - (-h).exp() * sum - 0.95).abs() < 1e-12, "k = {k}");

    // the check by the other method
    match &certified["check"] {
        Value::Null => assert!(
            doc.descendants()
                .iter()
                .all(|n| n.attribute("id") != Some("check"))
        ),
        check => {
            let node = doc.by_id("check");
            let values: Vec<f64> = node
                .all("si:value")
                .iter()
                .map(|v| v.text.parse().unwrap())
                .collect();
            assert_eq!(
                values,
                [f(&check["k2"]), f(&check["expanded"]), f(&check["z"])]
            );
            same(
                "u of the check",
                node.number("si:valueStandardMU"),
                f(&check["u"]),
            );
        }
    }

    // each mounting's range of validity
    for v in validity {
        let node = doc.by_id(&format!("validity-{}", v["mounting"].as_str().unwrap()));
        let values: Vec<f64> = node
            .all("si:value")
            .iter()
            .map(|v| v.text.parse().unwrap())
            .collect();
        let keys = [
            "radius_m",
            "rate_low_deg_s",
            "rate_high_deg_s",
            "specific_force_low_g",
            "specific_force_high_g",
        ];
        assert_eq!(values, keys.map(|k| f(&v[k])));
    }

    // the statements of conformity
    let statements = cert["conformity"]["statements"].as_array().unwrap();
    for (i, s) in statements.iter().enumerate() {
        let meta = doc.by_id(&format!("conformity-{}", i + 1));
        let verdict = match s["verdict"].as_str().unwrap() {
            "pass" => "pass",
            "conditional_pass" => "conditionalPass",
            "conditional_fail" => "conditionalFail",
            "fail" => "fail",
            other => panic!("verdict {other}"),
        };
        assert_eq!(meta.find("dcc:conformity").text, verdict);
        let values: Vec<f64> = meta
            .all("si:value")
            .iter()
            .map(|v| v.text.parse().unwrap())
            .collect();
        let mut want = vec![f(&s["value"]), f(&s["low95"]), f(&s["high95"])];
        want.extend(s.get("lower").map(f));
        want.extend(s.get("upper").map(f));
        assert_eq!(values, want, "conformity {i}");
    }

    // every file the study read, with its SHA-256
    for (i, file) in w.files.iter().enumerate() {
        let meta = doc.by_id(&format!("input-file-{}", i + 1));
        assert_eq!(meta.find("dcc:charsXMLList").text, file.sha256);
        assert!(
            meta.find("dcc:description/dcc:content")
                .text
                .starts_with(&file.path)
        );
    }
    assert!(
        doc.descendants()
            .iter()
            .all(|n| n.attribute("id") != Some(&format!("input-file-{}", w.files.len() + 1))),
        "one record per file"
    );
}

#[test]
fn the_campaign_certificate_reads_back_equal_to_its_results() {
    reads_back_equal(campaign());
}

#[test]
fn the_two_orientation_certificate_reads_back_equal_to_its_results() {
    reads_back_equal(two_orientation());
}
