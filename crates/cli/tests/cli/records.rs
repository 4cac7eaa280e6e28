//! `record` and `history`: a simulated unit's drift recovered across three yearly studies, two
//! processes recording at once, a killed recording, and what a person reads (snapshots).

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use test_support::Scratch;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(args)
        .env_remove("CENTRIFUGE_CAL_RECORDS")
        .output()
        .expect("runs")
}

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Simulates the campaign fixture with k2 = `k2` (noise stream `seed`) into `dir`/sim, and
/// writes its study as certificate `id` measured on `date` into `dir`/study.ron.
fn simulated_study(dir: &Path, k2: f64, seed: u64, id: &str, date: &str) -> PathBuf {
    let scenario = std::fs::read_to_string(root().join("fixtures/scenarios/campaign.ron"))
        .unwrap()
        .replace("k2_rad_s_g2: 5.0e-7", &format!("k2_rad_s_g2: {k2:e}"))
        .replace("seed: 11,", &format!("seed: {seed},"));
    std::fs::create_dir_all(dir).unwrap();
    let scenario_path = dir.join("scenario.ron");
    std::fs::write(&scenario_path, scenario).unwrap();
    let sim = dir.join("sim");
    ok(&cli(&[
        "simulate",
        "--config",
        s(&scenario_path),
        "--out",
        s(&sim),
    ]));
    let study = std::fs::read_to_string(root().join("fixtures/studies/campaign.ron"))
        .unwrap()
        .replace("../campaign/", &format!("{}/", s(&sim)))
        .replace("CC-2026-0042", id)
        .replace("2026-11-16", date)
        .replace("2026-11-19 to 2026-11-20", date)
        .replace("2026-11-24", date);
    let path = dir.join("study.ron");
    std::fs::write(&path, study).unwrap();
    path
}

fn json(out: &Output) -> serde_json::Value {
    serde_json::from_str(&ok(out)).unwrap()
}

fn term<'a>(history: &'a serde_json::Value, label: &str) -> &'a serde_json::Value {
    history["terms"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["label"] == label)
        .unwrap()
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap()
}

/// Three studies of one simulated unit a year apart, its k2 drifting by a known rate:
/// `history` recovers the drift within its U95, and from the first two predicts the third's
/// k2 within the U95 of a calibration on that date; the records hold the SHA-256 of each
/// study's certificate.pdf and certificate.dcc.xml.
#[test]
fn history_recovers_a_known_drift_and_predicts_the_third_study() {
    let scratch = Scratch::new("records-drift");
    let drift_per_year = 1.5e-7;
    let dates = ["2026-11-19", "2027-11-19", "2028-11-18"];
    let db_two = scratch.path().join("two.sqlite");
    let db_all = scratch.path().join("all.sqlite");
    let mut certified_k2 = Vec::new();
    let mut written = Vec::new();
    for (y, date) in dates.iter().enumerate() {
        let dir = scratch.path().join(format!("y{y}"));
        let k2 = 5.0e-7 + drift_per_year * y as f64;
        let config = simulated_study(&dir, k2, 11 + y as u64, &format!("CC-Y{y}"), date);
        let out = dir.join("out");
        let mut args = vec![
            "study",
            "--config",
            s(&config),
            "--out",
            s(&out),
            "--no-compare",
        ];
        args.extend(["--records", s(&db_all)]);
        let text = ok(&cli(&args));
        assert!(
            text.contains(&format!("certificate CC-Y{y} of unit PIGA-16/SN 1604-0117")),
            "{text}"
        );
        if y < 2 {
            ok(&cli(&["record", s(&out), "--records", s(&db_two)]));
        }
        // the certificate as the study wrote it: the PDF typeset by the tool and its DCC
        let pdf = std::fs::read(out.join("certificate.pdf")).unwrap();
        assert!(pdf.starts_with(b"%PDF-"), "certificate.pdf is a PDF");
        let dcc = std::fs::read(out.join("certificate.dcc.xml")).unwrap();
        written.push((
            format!("CC-Y{y}"),
            records::sha256_hex(&pdf),
            records::sha256_hex(&dcc),
        ));
        let results: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("results.json")).unwrap()).unwrap();
        let k2 = results["certificate"]["certified"]["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"] == "k2")
            .unwrap()
            .clone();
        certified_k2.push((f(&k2["value"]), f(&k2["u"])));
    }
    let all = json(&cli(&[
        "history",
        "SN 1604-0117",
        "--json",
        "--records",
        s(&db_all),
    ]));
    // the records hold the SHA-256 of the PDF and of the DCC each study wrote
    let stored = all["certificates"].as_array().unwrap();
    assert_eq!(stored.len(), written.len());
    for (id, pdf, dcc) in &written {
        let c = stored
            .iter()
            .find(|c| c["id"] == id.as_str())
            .unwrap_or_else(|| panic!("{id} not recorded"));
        assert_eq!(c["pdf_sha256"], pdf.as_str(), "{id}");
        assert_eq!(c["dcc_sha256"], dcc.as_str(), "{id}");
    }
    let k2 = term(&all, "k2");
    assert_eq!(k2["points"].as_array().unwrap().len(), 3);
    let drift = &k2["drift"];
    let (b, expanded) = (
        f(&drift["rate_per_year"]),
        f(&drift["expanded_rate_per_year"]),
    );
    assert!(
        (b - drift_per_year).abs() <= expanded,
        "drift {b:e} ± {expanded:e} per year, true {drift_per_year:e}"
    );
    assert!(
        drift["significant"].as_bool().unwrap(),
        "a drift of 3.4 u per year is seen"
    );

    let two = json(&cli(&[
        "history",
        "SN 1604-0117",
        "--json",
        "--at",
        dates[2],
        "--records",
        s(&db_two),
    ]));
    let p = &term(&two, "k2")["prediction"];
    assert_eq!(p["date"], dates[2]);
    let (value, u_reading, k) = (f(&p["value"]), f(&p["u_reading"]), f(&p["k95"]));
    let (third, _) = certified_k2[2];
    assert!(
        (third - value).abs() <= k * u_reading,
        "third study's k2 {third:e}, predicted {value:e} ± {:e}",
        k * u_reading
    );
}

/// 100 distinct studies' outputs: the campaign's results.json as certificates CC-P{i}.
fn many_results(dir: &Path, n: usize) -> Vec<PathBuf> {
    let base = dir.join("base");
    ok(&cli(&[
        "study",
        "--config",
        s(&root().join("fixtures/studies/campaign.ron")),
        "--out",
        s(&base),
        "--no-compare",
    ]));
    let text = std::fs::read_to_string(base.join("results.json")).unwrap();
    (0..n)
        .map(|i| {
            let d = dir.join(format!("study-{i:03}"));
            std::fs::create_dir_all(&d).unwrap();
            let day = 1 + i % 28;
            let month = 1 + (i / 28) % 12;
            std::fs::write(
                d.join("results.json"),
                text.replace("CC-2026-0042", &format!("CC-P{i:03}"))
                    .replace(
                        "2026-11-19 to 2026-11-20",
                        &format!("2026-{month:02}-{day:02}"),
                    ),
            )
            .unwrap();
            d
        })
        .collect()
}

fn count(db: &Path, table: &str) -> i64 {
    let out = cli(&[
        "history",
        "--centrifuge",
        "CF-2 (asset 1021)",
        "--json",
        "--records",
        s(db),
    ]);
    let health = json(&out);
    match table {
        "campaigns" => health["campaigns"].as_array().unwrap().len() as i64,
        _ => unreachable!(),
    }
}

#[test]
fn two_processes_recording_fifty_studies_each_lose_none() {
    let scratch = Scratch::new("records-concurrent");
    let dirs = many_results(scratch.path(), 100);
    let db = scratch.path().join("lab.sqlite");
    let bin = env!("CARGO_BIN_EXE_centrifuge-cal");
    let spawn = |half: &[PathBuf]| {
        let script = half
            .iter()
            .map(|d| {
                format!(
                    "'{bin}' record '{}' --records '{}' >/dev/null || exit 1",
                    s(d),
                    s(&db)
                )
            })
            .collect::<Vec<_>>()
            .join("\n");
        Command::new("sh")
            .arg("-c")
            .arg(script)
            .env_remove("CENTRIFUGE_CAL_RECORDS")
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let a = spawn(&dirs[..50]);
    let b = spawn(&dirs[50..]);
    for child in [a, b] {
        let out = child.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    assert_eq!(count(&db, "campaigns"), 100, "100 records, none lost");
    let unit = json(&cli(&[
        "history",
        "SN 1604-0117",
        "--json",
        "--records",
        s(&db),
    ]));
    assert_eq!(unit["certificates"].as_array().unwrap().len(), 100);
    // recording one again is a no-op that says so
    let again = ok(&cli(&["record", s(&dirs[7]), "--records", s(&db)]));
    assert!(again.starts_with("already recorded"), "{again}");
    assert_eq!(count(&db, "campaigns"), 100);
}

#[test]
fn a_killed_recording_leaves_the_database_as_it_was() {
    let scratch = Scratch::new("records-killed");
    let dirs = many_results(scratch.path(), 2);
    let db = scratch.path().join("lab.sqlite");
    ok(&cli(&["record", s(&dirs[0]), "--records", s(&db)]));
    record_killed_before_commit(&dirs[1], &db, &scratch.path().join("paused"));
    // everything but the commit was written; none of it is in the database
    assert_eq!(count(&db, "campaigns"), 1);
    let unit = json(&cli(&[
        "history",
        "SN 1604-0117",
        "--json",
        "--records",
        s(&db),
    ]));
    assert_eq!(unit["certificates"].as_array().unwrap().len(), 1);
    // and the database takes the same recording afterwards
    let text = ok(&cli(&["record", s(&dirs[1]), "--records", s(&db)]));
    assert!(text.starts_with("recorded"), "{text}");
    assert_eq!(count(&db, "campaigns"), 2);
}

#[test]
fn a_file_that_is_not_a_records_database_is_refused_unchanged() {
    let scratch = Scratch::new("records-foreign");
    let dirs = many_results(scratch.path(), 1);
    let file = scratch.path().join("notes.txt");
    std::fs::write(&file, "not a database\n".repeat(100)).unwrap();
    let out = cli(&["record", s(&dirs[0]), "--records", s(&file)]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("is not a centrifuge-cal records database"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        "not a database\n".repeat(100)
    );
    let missing = scratch.path().join("none.sqlite");
    let out = cli(&["history", "SN 1", "--records", s(&missing)]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("no records database at"));
    assert!(!missing.exists());
}

/// What a person reads: a unit with a corrected certificate and an interval, and a
/// centrifuge with a balance event and the rebalance warning.
#[test]
fn history_text_snapshots() {
    let scratch = Scratch::new("records-text");
    let base = scratch.path().join("base");
    ok(&cli(&[
        "study",
        "--config",
        s(&root().join("fixtures/studies/campaign.ron")),
        "--out",
        s(&base),
        "--no-compare",
    ]));
    let text = std::fs::read_to_string(base.join("results.json")).unwrap();
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let k2 = value["certificate"]["certified"]["coefficients"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "k2")
        .unwrap();
    let k2_value = f(&k2["value"]);
    let c_r = f(&value["phases"][0]["c_r_m_s2"]);
    let dk2 = f(&value["phases"][0]["delta_k2_rad_s_g2"]);
    let db = scratch.path().join("lab.sqlite");
    // four yearly certificates, k2 rising by 1.2e-7 a year, C_r by a quarter a year
    let write = |i: usize, id: &str, date: &str, k2_new: f64, c_r_new: f64| {
        let mut v = value.clone();
        let cert = &mut v["certificate"];
        cert["id"] = id.into();
        cert["dates"]["measured"] = date.into();
        cert["dates"]["issued"] = date.into();
        for c in cert["certified"]["coefficients"].as_array_mut().unwrap() {
            if c["name"] == "k2" {
                let shift = k2_new - f(&c["value"]);
                c["value"] = k2_new.into();
                c["low95"] = (f(&c["low95"]) + shift).into();
                c["high95"] = (f(&c["high95"]) + shift).into();
            }
        }
        v["phases"][0]["c_r_m_s2"] = c_r_new.into();
        v["phases"][0]["delta_k2_rad_s_g2"] = (dk2 * c_r_new / c_r).into();
        let d = scratch.path().join(format!("s{i}"));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(
            d.join("results.json"),
            serde_json::to_vec_pretty(&v).unwrap(),
        )
        .unwrap();
        d
    };
    let wiggle = [0.0, 0.3, -0.2, 0.1];
    for (i, year) in (2023..2027).enumerate() {
        let d = write(
            i,
            &format!("CC-{year}-0042"),
            &format!("{year}-11-19"),
            k2_value + 1.2e-7 * i as f64 + wiggle[i] * 4.4e-8,
            c_r * (1.0 + 0.25 * i as f64),
        );
        ok(&cli(&["record", s(&d), "--records", s(&db)]));
    }
    // the 2024 certificate corrected
    let d = write(
        9,
        "CC-2024-0042-R1",
        "2024-11-19",
        k2_value + 1.2e-7,
        c_r * 1.25,
    );
    let recorded = ok(&cli(&[
        "record",
        s(&d),
        "--records",
        s(&db),
        "--supersedes",
        "CC-2024-0042",
    ]));
    assert!(recorded.contains("superseding CC-2024-0042"), "{recorded}");
    ok(&cli(&[
        "record",
        "--balanced",
        "balanced with a 12 g trial weight at 40°",
        "--centrifuge",
        "CF-2 (asset 1021)",
        "--date",
        "2024-06-01",
        "--records",
        s(&db),
    ]));
    let svg = scratch.path().join("history.svg");
    let unit = ok(&cli(&[
        "history",
        "SN 1604-0117",
        "--term",
        "k2",
        "--tolerance",
        "4e-7",
        "--svg",
        s(&svg),
        "--records",
        s(&db),
    ]));
    let unit = unit.replace(s(&svg), "HISTORY.svg");
    insta::assert_snapshot!("history_unit", unit);
    let health_svg = scratch.path().join("centrifuge.svg");
    let health = ok(&cli(&[
        "history",
        "--centrifuge",
        "CF-2 (asset 1021)",
        "--target-u95",
        "1e-5",
        "--svg",
        s(&health_svg),
        "--records",
        s(&db),
    ]));
    let health = health.replace(s(&health_svg), "CENTRIFUGE.svg");
    insta::assert_snapshot!("history_centrifuge", health);
    for svg in [&svg, &health_svg] {
        let text = std::fs::read_to_string(svg).unwrap();
        assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
        assert!(
            !text.contains("NaN") && !text.contains("inf"),
            "{}",
            svg.display()
        );
        if let Some(dir) = std::env::var_os("CENTRIFUGE_CAL_KEEP_SVG") {
            std::fs::copy(svg, Path::new(&dir).join(svg.file_name().unwrap())).unwrap();
        }
    }
}

/// The two-unit fixture: `study --records` writes each unit's complete folder (results,
/// certificate, DCC) and records both units in one transaction, each folder a study that
/// `certificate` and `record` take as it is; a recording of the top folder killed before its
/// commit leaves the database without either unit; the centrifuge's history counts the run
/// once.
#[test]
fn a_two_unit_study_gives_two_certificates_and_two_records_from_one_probe_phase() {
    let scratch = Scratch::new("records-units");
    let out = scratch.path().join("out");
    let db = scratch.path().join("lab.sqlite");
    let text = ok(&cli(&[
        "study",
        "--config",
        s(&root().join("fixtures/studies/units.ron")),
        "--out",
        s(&out),
        "--records",
        s(&db),
    ]));
    assert!(
        text.contains("certificate CC-2026-0051 of unit PIGA-16/SN 1604-0201"),
        "{text}"
    );
    assert!(
        text.contains("certificate CC-2026-0052 of unit PIGA-22/SN 2210-0033"),
        "{text}"
    );
    assert!(text.contains("regression: "), "{text}");
    for unit in ["A", "B"] {
        let dir = out.join("units").join(unit);
        for file in [
            "results.json",
            "report.md",
            "certificate.pdf",
            "certificate.dcc.xml",
        ] {
            assert!(dir.join(file).is_file(), "units/{unit}/{file}");
        }
        // a unit's folder is a single-unit study's: re-rendered and recorded as one
        ok(&cli(&[
            "certificate",
            s(&dir),
            "--out",
            s(&scratch.path().join(format!("{unit}.pdf"))),
        ]));
        let again = ok(&cli(&["record", s(&dir), "--records", s(&db)]));
        assert!(again.starts_with("already recorded"), "{again}");
    }
    let top: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(top["units"].as_array().unwrap().len(), 2);
    assert!(top.get("certificate").is_none());
    // the run is one campaign of the centrifuge
    assert_eq!(count(&db, "campaigns"), 1);
    // the top folder recorded again: both already there, nothing written
    let again = ok(&cli(&["record", s(&out), "--records", s(&db)]));
    assert_eq!(again.matches("already recorded").count(), 2, "{again}");

    // killed before the commit: neither unit is in the database
    let fresh = scratch.path().join("fresh.sqlite");
    record_killed_before_commit(&out, &fresh, &scratch.path().join("paused"));
    for serial in ["SN 1604-0201", "SN 2210-0033"] {
        let missing = cli(&["history", serial, "--records", s(&fresh)]);
        assert!(!missing.status.success(), "{serial} is not recorded");
    }
    let text = ok(&cli(&["record", s(&out), "--records", s(&fresh)]));
    assert_eq!(text.matches("recorded ").count(), 2, "{text}");
}

/// `record RESULTS --records DB`, killed (SIGKILL: no clean-up runs) once it has written
/// everything but its commit, which it marks by creating `marker` when the test asks it to pause.
fn record_killed_before_commit(results: &Path, db: &Path, marker: &Path) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(["record", s(results), "--records", s(db)])
        .env("CENTRIFUGE_CAL_TEST_PAUSE_BEFORE_COMMIT", marker)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while !marker.exists() {
        assert!(
            start.elapsed().as_secs() < 60,
            "the recording reached its commit"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    let _ = child.wait();
}
