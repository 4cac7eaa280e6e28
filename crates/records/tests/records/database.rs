//! Recording: once per results, all or nothing, never updated in place; files that are not
//! records are refused and left as they were.

use std::path::PathBuf;

use records::{
    Access, Database, Date, HistoryOptions, Outcome, RecordsError, SCHEMA_VERSION, sha256_hex,
    unit_history,
};

use crate::common::{campaign, json, submission, variant};

fn temp_db(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("records-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("records.sqlite")
}

#[test]
fn a_study_is_recorded_once_and_read_back_as_certified() {
    let mut db = Database::in_memory().unwrap();
    let r = campaign();
    let bytes = json(r);
    let first = db.record(&submission(r, &bytes)).unwrap();
    assert!(
        matches!(&first, Outcome::Recorded { certificate: Some(id), phases: 1, .. } if id == "CC-2026-0042"),
        "{first:?}"
    );
    assert_eq!(db.counts().unwrap(), (1, 1, 1, 1));
    let again = db.record(&submission(r, &bytes)).unwrap();
    assert!(
        matches!(&again, Outcome::AlreadyRecorded { record, .. } if *record == sha256_hex(&bytes)),
        "{again:?}"
    );
    assert_eq!(db.counts().unwrap(), (1, 1, 1, 1));

    let unit = db.unit_records("SN 1604-0117").unwrap();
    assert_eq!(unit.unit.model, "PIGA-16");
    let [c] = unit.certificates.as_slice() else {
        panic!("one certificate: {unit:?}")
    };
    let certified = &r.certificate.as_ref().unwrap().certified;
    assert_eq!(c.terms.len(), certified.coefficients.len());
    for (t, k) in c.terms.iter().zip(&certified.coefficients) {
        assert_eq!(
            (t.term.as_str(), t.value, t.u, t.expanded),
            (k.name.as_str(), k.value, k.u, k.expanded)
        );
    }
    assert_eq!(c.covariance, certified.covariance);
    assert_eq!(c.measured, Date::parse("2026-11-19").unwrap());
    // the same unit asked for by model and serial
    assert_eq!(db.unit_records("PIGA-16/SN 1604-0117").unwrap(), unit);
    assert!(matches!(
        db.unit_records("SN 0000"),
        Err(RecordsError::UnknownUnit { known, .. }) if known == ["PIGA-16/SN 1604-0117"]
    ));
}

#[test]
fn the_dcc_is_stored_with_its_digest() {
    let mut db = Database::in_memory().unwrap();
    let r = campaign();
    let bytes = json(r);
    let dcc = b"<dcc:digitalCalibrationCertificate>example &amp; more</dcc:digitalCalibrationCertificate>".repeat(50);
    let pdf = b"%PDF-1.7 example".to_vec();
    let mut s = submission(r, &bytes);
    s.dcc_xml = Some(&dcc);
    s.certificate_pdf = Some(&pdf);
    db.record(&s).unwrap();
    assert_eq!(
        db.dcc_xml("CC-2026-0042").unwrap().as_deref(),
        Some(dcc.as_slice())
    );
    let unit = db.unit_records("SN 1604-0117").unwrap();
    assert_eq!(
        unit.certificates[0].dcc_sha256.as_deref(),
        Some(sha256_hex(&dcc).as_str())
    );
    assert_eq!(
        unit.certificates[0].pdf_sha256.as_deref(),
        Some(sha256_hex(&pdf).as_str())
    );
}

#[test]
fn a_certificate_recorded_with_other_results_is_refused() {
    let mut db = Database::in_memory().unwrap();
    let a = variant("CC-1", "2026-01-10", None, None);
    let b = variant("CC-1", "2026-01-10", Some(6.0e-7), None);
    let (ja, jb) = (json(&a), json(&b));
    db.record(&submission(&a, &ja)).unwrap();
    assert!(matches!(
        db.record(&submission(&b, &jb)),
        Err(RecordsError::CertificateConflict { id, .. }) if id == "CC-1"
    ));
    assert_eq!(db.counts().unwrap(), (1, 1, 1, 1));
}

#[test]
fn a_corrected_certificate_supersedes_the_old_and_both_remain() {
    let mut db = Database::in_memory().unwrap();
    let old = variant("CC-7", "2026-03-02", Some(5.0e-7), None);
    let other = variant("CC-8", "2027-03-02", Some(5.5e-7), None);
    let fixed = variant("CC-7-R1", "2026-03-02", Some(5.2e-7), None);
    let (jo, jx, jf) = (json(&old), json(&other), json(&fixed));
    db.record(&submission(&old, &jo)).unwrap();
    db.record(&submission(&other, &jx)).unwrap();
    let mut s = submission(&fixed, &jf);
    s.supersedes = Some("CC-7".into());
    let outcome = db.record(&s).unwrap();
    assert!(matches!(&outcome, Outcome::Recorded { supersedes: Some(o), .. } if o == "CC-7"));

    let unit = db.unit_records("SN 1604-0117").unwrap();
    assert_eq!(unit.certificates.len(), 3, "both remain");
    let by_id = |id: &str| unit.certificates.iter().find(|c| c.id == id).unwrap();
    assert_eq!(by_id("CC-7").superseded_by.as_deref(), Some("CC-7-R1"));
    assert_eq!(by_id("CC-7-R1").supersedes.as_deref(), Some("CC-7"));
    let h = unit_history(unit, &HistoryOptions::default()).unwrap();
    let k2 = h.terms.iter().find(|t| t.label == "k2").unwrap();
    let ids: Vec<&str> = k2.points.iter().map(|p| p.certificate.as_str()).collect();
    assert_eq!(
        ids,
        ["CC-7-R1", "CC-8"],
        "the history uses the current certificate"
    );
    assert_eq!(k2.points[0].value, 5.2e-7);

    // a certificate is superseded once; an unknown one cannot be
    let again = variant("CC-7-R2", "2026-03-02", Some(5.3e-7), None);
    let ja = json(&again);
    let mut s = submission(&again, &ja);
    s.supersedes = Some("CC-7".into());
    assert!(matches!(
        db.record(&s),
        Err(RecordsError::AlreadySuperseded { by, .. }) if by == "CC-7-R1"
    ));
    s.supersedes = Some("CC-404".into());
    assert!(matches!(
        db.record(&s),
        Err(RecordsError::SupersedesUnknown { .. })
    ));
    assert_eq!(db.counts().unwrap().1, 3);
}

#[test]
fn records_are_never_updated_or_deleted_in_place() {
    let path = temp_db("immutable");
    let mut db = Database::open(&path, Access::CreateIfMissing).unwrap();
    let r = campaign();
    let bytes = json(r);
    db.record(&submission(r, &bytes)).unwrap();
    drop(db);
    let raw = rusqlite::Connection::open(&path).unwrap();
    for sql in [
        "UPDATE certified SET value = 0",
        "DELETE FROM certificates",
        "UPDATE studies SET name = 'x'",
        "DELETE FROM units",
    ] {
        let e = raw.execute(sql, []).unwrap_err().to_string();
        assert!(e.contains("never"), "{sql}: {e}");
    }
    drop(raw);
    let db = Database::open(&path, Access::Existing).unwrap();
    assert_eq!(db.counts().unwrap(), (1, 1, 1, 1));
    assert_eq!(db.integrity().unwrap(), None);
}

#[test]
fn files_that_are_not_records_are_refused_and_left_as_they_were() {
    // not SQLite
    let text = temp_db("text");
    std::fs::write(&text, "date,value\n2026-01-01,3\n".repeat(200)).unwrap();
    // another program's SQLite database
    let other = temp_db("other");
    {
        let c = rusqlite::Connection::open(&other).unwrap();
        c.execute_batch("CREATE TABLE customers (name TEXT); INSERT INTO customers VALUES ('a');")
            .unwrap();
    }
    // a damaged records database: its first pages overwritten
    let damaged = temp_db("damaged");
    {
        let mut db = Database::open(&damaged, Access::CreateIfMissing).unwrap();
        let r = campaign();
        let bytes = json(r);
        db.record(&submission(r, &bytes)).unwrap();
    }
    let _ = std::fs::remove_file(damaged.with_extension("sqlite-wal"));
    let _ = std::fs::remove_file(damaged.with_extension("sqlite-shm"));
    let mut bytes = std::fs::read(&damaged).unwrap();
    for b in bytes.iter_mut().take(100) {
        *b = b'#';
    }
    std::fs::write(&damaged, &bytes).unwrap();

    for path in [&text, &other, &damaged] {
        let before = std::fs::read(path).unwrap();
        for access in [Access::CreateIfMissing, Access::Existing] {
            let e = Database::open(path, access).unwrap_err();
            assert!(
                matches!(e, RecordsError::NotRecords { .. }),
                "{}: {e}",
                path.display()
            );
            assert!(e.to_string().contains("not modified"), "{e}");
        }
        assert_eq!(
            std::fs::read(path).unwrap(),
            before,
            "{} unchanged",
            path.display()
        );
        assert!(
            !path.with_extension("sqlite-wal").exists(),
            "no journal left beside it"
        );
    }
    let missing = temp_db("missing");
    assert!(matches!(
        Database::open(&missing, Access::Existing),
        Err(RecordsError::Missing { .. })
    ));
    assert!(!missing.exists(), "reading never creates a database");
}

#[test]
fn a_database_of_a_newer_schema_is_refused_and_an_older_one_migrated() {
    let path = temp_db("schema");
    drop(Database::open(&path, Access::CreateIfMissing).unwrap());
    {
        let c = rusqlite::Connection::open(&path).unwrap();
        c.execute_batch(&format!("PRAGMA user_version = {}", SCHEMA_VERSION + 1))
            .unwrap();
    }
    assert!(matches!(
        Database::open(&path, Access::Existing),
        Err(RecordsError::NewerSchema { found, .. }) if found == SCHEMA_VERSION + 1
    ));
    // an empty SQLite file (what `sqlite3 FILE ''` leaves) is initialised at the newest schema
    let empty = temp_db("empty");
    std::fs::write(&empty, b"").unwrap();
    let db = Database::open(&empty, Access::Existing).unwrap();
    assert_eq!(db.schema_version().unwrap(), SCHEMA_VERSION);
}

#[test]
fn a_study_without_a_certificate_needs_a_centrifuge_and_a_date() {
    let mut db = Database::in_memory().unwrap();
    let mut r = campaign().clone();
    r.certificate = None;
    let bytes = json(&r);
    assert!(matches!(
        db.record(&submission(&r, &bytes)),
        Err(RecordsError::NothingToRecord { .. })
    ));
    let mut s = submission(&r, &bytes);
    s.centrifuge = Some("CF-9".into());
    assert!(matches!(db.record(&s), Err(RecordsError::NoDate { .. })));
    s.date = Date::parse("2026-05-05");
    db.record(&s).unwrap();
    assert_eq!(db.counts().unwrap(), (1, 0, 0, 1));
    let cf = db.centrifuge_records("CF-9").unwrap();
    assert_eq!(cf.campaigns.len(), 1);
    assert_eq!(cf.campaigns[0].c_r_m_s2, r.phases[0].fit.c_r_m_s2);
    assert_eq!(cf.campaigns[0].phase, "spindle");
}

/// A several-unit study's units are recorded in one transaction: both, or, when the second
/// fails (its certificate identification already stands for other results), neither — the
/// database as it was, and the first unit's record absent.
#[test]
fn several_units_are_recorded_all_or_none() {
    let path = temp_db("units");
    let mut db = Database::open(&path, Access::CreateIfMissing).unwrap();
    // an earlier study holding certificate CC-U2
    let earlier = variant("CC-U2", "2025-11-19", Some(4.0e-7), None);
    let earlier_json = json(&earlier);
    db.record(&submission(&earlier, &earlier_json)).unwrap();
    let before = db.counts().unwrap();
    let first = variant("CC-U1", "2026-11-19", Some(5.0e-7), None);
    let mut second = variant("CC-U2", "2026-11-19", Some(6.0e-7), None);
    second.certificate.as_mut().unwrap().item.serial = "SN 9999-0002".into();
    let (a, b) = (json(&first), json(&second));
    let e = db
        .record_all(&[submission(&first, &a), submission(&second, &b)])
        .unwrap_err();
    assert!(
        matches!(&e, RecordsError::CertificateConflict { id, .. } if id == "CC-U2"),
        "{e}"
    );
    assert_eq!(
        db.counts().unwrap(),
        before,
        "nothing of either unit written"
    );
    let none = db.unit_records("SN 1604-0117").unwrap();
    assert!(
        none.certificates.iter().all(|c| c.id != "CC-U1"),
        "the first unit's certificate is not recorded"
    );
    // both good: both recorded in one go, and again: nothing written
    second.certificate.as_mut().unwrap().id = "CC-U3".into();
    let b = json(&second);
    let outcomes = db
        .record_all(&[submission(&first, &a), submission(&second, &b)])
        .unwrap();
    assert!(
        outcomes
            .iter()
            .all(|o| matches!(o, Outcome::Recorded { .. }))
    );
    assert_eq!(db.counts().unwrap().1, before.1 + 2);
    let again = db
        .record_all(&[submission(&first, &a), submission(&second, &b)])
        .unwrap();
    assert!(
        again
            .iter()
            .all(|o| matches!(o, Outcome::AlreadyRecorded { .. }))
    );
}
