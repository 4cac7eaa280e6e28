//! The records database: one SQLite file (WAL, a busy timeout, every write one transaction),
//! recognised by its application id, migrated to the schema of this build on opening.
//!
//! This module is the crate's only edge: it opens the database file it is given and no other
//! (results, certificates and their files come as values, read by the command line).

use std::path::Path;
use std::time::Duration;

use rusqlite::{Connection, OpenFlags, OptionalExtension as _, TransactionBehavior, params};

use crate::date::Date;
use crate::error::{RecordsError, Result};
use crate::schema::{APPLICATION_ID, MIGRATIONS, SCHEMA_VERSION, TABLES, immutability_triggers};
use crate::stored::{
    BalanceEvent, Campaign, CentrifugeRecords, StoredCertificate, StoredTerm, UnitRecords,
};
use crate::submission::{Submission, UnitIdentity};

mod insert;

pub use insert::Outcome;
use insert::{Insert, centrifuge_id, insert};

/// How long a write waits for another process's write to finish before giving up.
pub const BUSY_TIMEOUT: Duration = Duration::from_secs(30);

/// An open records database.
#[derive(Debug)]
pub struct Database {
    conn: Connection,
    path: String,
}

/// What recording a balance event did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BalanceOutcome {
    /// Recorded.
    Recorded,
    /// The same event (centrifuge, date and note) was recorded before.
    AlreadyRecorded,
}

/// Whether [`Database::open`] may create the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Create the database when the file does not exist (recording).
    CreateIfMissing,
    /// The database must exist (history).
    Existing,
}

impl Database {
    /// Opens (or creates) the records database at `path`, refusing a file that is not one
    /// without modifying it, and brings its schema to this build's.
    ///
    /// # Errors
    /// [`RecordsError::Missing`] (with [`Access::Existing`]), [`RecordsError::NotRecords`],
    /// [`RecordsError::NewerSchema`], [`RecordsError::Sqlite`].
    pub fn open(path: &Path, access: Access) -> Result<Self> {
        let shown = path.display().to_string();
        let exists = path.exists();
        if !exists && access == Access::Existing {
            return Err(RecordsError::Missing { path: shown });
        }
        let flags = if access == Access::CreateIfMissing {
            OpenFlags::SQLITE_OPEN_READ_WRITE | OpenFlags::SQLITE_OPEN_CREATE
        } else {
            OpenFlags::SQLITE_OPEN_READ_WRITE
        } | OpenFlags::SQLITE_OPEN_NO_MUTEX;
        let conn =
            Connection::open_with_flags(path, flags).map_err(|source| RecordsError::Sqlite {
                path: shown.clone(),
                action: "opening",
                source,
            })?;
        Self::setup(conn, shown)
    }

    /// A database in memory (tests, benchmarks).
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`].
    pub fn in_memory() -> Result<Self> {
        let conn = Connection::open_in_memory().map_err(|source| RecordsError::Sqlite {
            path: ":memory:".into(),
            action: "opening",
            source,
        })?;
        Self::setup(conn, ":memory:".into())
    }

    fn sql(&self, action: &'static str) -> impl FnOnce(rusqlite::Error) -> RecordsError + '_ {
        move |source| RecordsError::Sqlite {
            path: self.path.clone(),
            action,
            source,
        }
    }

    fn setup(conn: Connection, path: String) -> Result<Self> {
        let db = Self { conn, path };
        db.conn
            .busy_timeout(BUSY_TIMEOUT)
            .map_err(db.sql("setting the busy timeout"))?;
        db.check_ours()?;
        // WAL: readers do not block the writer nor the writer the readers; persistent in the
        // file once set. Switching needs a moment alone with the file: retried while another
        // process holds it.
        let mut tries = 0;
        loop {
            match db
                .conn
                .query_row("PRAGMA journal_mode = WAL", [], |r| r.get::<_, String>(0))
            {
                Ok(_) => break,
                Err(e) if is_busy(&e) && tries < 300 => {
                    tries += 1;
                    std::thread::sleep(Duration::from_millis(10));
                }
                Err(e) => return Err(db.sql("switching to write-ahead logging")(e)),
            }
        }
        db.conn
            .execute_batch("PRAGMA foreign_keys = ON; PRAGMA synchronous = NORMAL;")
            .map_err(db.sql("setting the connection's options"))?;
        let mut db = db;
        db.migrate()?;
        Ok(db)
    }

    /// Refuses a file that is not a records database (read only: nothing is written).
    fn check_ours(&self) -> Result<()> {
        let not_records = |reason: String| RecordsError::NotRecords {
            path: self.path.clone(),
            reason,
        };
        // The header and the schema read in one read transaction, one snapshot: read apart,
        // a process creating the database between them showed "application id 0, 41 schema
        // objects" and the file was refused as another program's (two processes recording
        // into a new file at once).
        let snapshot = self
            .conn
            .unchecked_transaction()
            .map_err(self.sql("starting to read its header"))?;
        let app: i32 = snapshot
            .query_row("PRAGMA application_id", [], |r| r.get(0))
            .map_err(|e| match e {
                rusqlite::Error::SqliteFailure(f, _)
                    if matches!(
                        f.code,
                        rusqlite::ErrorCode::NotADatabase | rusqlite::ErrorCode::DatabaseCorrupt
                    ) =>
                {
                    not_records("not an SQLite database, or a damaged one".into())
                }
                other => self.sql("reading its header")(other),
            })?;
        let tables: i64 = snapshot
            .query_row("SELECT count(*) FROM sqlite_schema", [], |r| r.get(0))
            .map_err(|e| match e {
                rusqlite::Error::SqliteFailure(f, _)
                    if matches!(
                        f.code,
                        rusqlite::ErrorCode::NotADatabase | rusqlite::ErrorCode::DatabaseCorrupt
                    ) =>
                {
                    not_records("a damaged SQLite database".into())
                }
                other => self.sql("reading its schema")(other),
            })?;
        let version: i64 = snapshot
            .query_row("PRAGMA user_version", [], |r| r.get(0))
            .map_err(self.sql("reading its schema version"))?;
        snapshot
            .commit()
            .map_err(self.sql("ending the read of its header"))?;
        if app == APPLICATION_ID {
            if version > SCHEMA_VERSION {
                return Err(RecordsError::NewerSchema {
                    path: self.path.clone(),
                    found: version,
                    known: SCHEMA_VERSION,
                });
            }
            Ok(())
        } else if tables == 0 && app == 0 {
            Ok(()) // new or empty: ours to initialise
        } else {
            Err(not_records(format!(
                "an SQLite database of another program: application id {app:#x}, {tables} schema objects"
            )))
        }
    }

    /// Applies the migrations the file lacks, in one transaction.
    fn migrate(&mut self) -> Result<()> {
        let path = self.path.clone();
        let err = |action: &'static str| {
            let path = path.clone();
            move |source| RecordsError::Sqlite {
                path,
                action,
                source,
            }
        };
        let current: i64 = self
            .conn
            .query_row("PRAGMA user_version", [], |r| r.get(0))
            .map_err(err("reading its schema version"))?;
        if current == SCHEMA_VERSION {
            return Ok(());
        }
        let tx = self
            .conn
            .transaction_with_behavior(TransactionBehavior::Immediate)
            .map_err(err("starting the schema's migration"))?;
        // Another process may have migrated while this one waited for the lock.
        let current: i64 = tx
            .query_row("PRAGMA user_version", [], |r| r.get(0))
            .map_err(err("reading its schema version"))?;
        let start = usize::try_from(current).unwrap_or(0);
        for migration in MIGRATIONS.iter().skip(start) {
            tx.execute_batch(migration)
                .map_err(err("migrating the schema"))?;
        }
        if start < MIGRATIONS.len() {
            let triggers: String = TABLES.iter().map(|t| immutability_triggers(t)).collect();
            tx.execute_batch(&triggers)
                .map_err(err("creating the triggers that keep records unchanged"))?;
            tx.execute_batch(&format!(
                "PRAGMA application_id = {APPLICATION_ID}; PRAGMA user_version = {SCHEMA_VERSION};"
            ))
            .map_err(err("recording the schema version"))?;
        }
        tx.commit()
            .map_err(err("committing the schema's migration"))
    }

    /// The schema version of the open database.
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`].
    pub fn schema_version(&self) -> Result<i64> {
        self.conn
            .query_row("PRAGMA user_version", [], |r| r.get(0))
            .map_err(self.sql("reading its schema version"))
    }

    /// Records a study: all of it in one transaction, or nothing.
    ///
    /// # Errors
    /// What [`Submission`]'s checks find (before anything is written),
    /// [`RecordsError::CertificateConflict`], the `--supersedes` errors, [`RecordsError::Sqlite`].
    pub fn record(&mut self, submission: &Submission<'_>) -> Result<Outcome> {
        self.record_then(submission, || {})
    }

    /// [`Database::record`], calling `before_commit` when everything is written but not yet
    /// committed (the tests stop a recording there).
    ///
    /// # Errors
    /// As [`Database::record`].
    pub fn record_then(
        &mut self,
        submission: &Submission<'_>,
        before_commit: impl FnOnce(),
    ) -> Result<Outcome> {
        let mut outcomes = self.record_all_then(std::slice::from_ref(submission), before_commit)?;
        Ok(outcomes.remove(0))
    }

    /// Records several studies in one transaction: all of them, or, if any fails, none (a
    /// several-unit study's units, each its own study and certificate from one probe phase).
    /// A study recorded before is left as it is ([`Outcome::AlreadyRecorded`]); the others
    /// are recorded.
    ///
    /// # Errors
    /// As [`Database::record`], for any of them: then nothing of any is written.
    pub fn record_all(&mut self, submissions: &[Submission<'_>]) -> Result<Vec<Outcome>> {
        self.record_all_then(submissions, || {})
    }

    /// [`Database::record_all`], calling `before_commit` when everything is written but not
    /// yet committed (the tests stop a recording there).
    ///
    /// # Errors
    /// As [`Database::record_all`].
    pub fn record_all_then(
        &mut self,
        submissions: &[Submission<'_>],
        before_commit: impl FnOnce(),
    ) -> Result<Vec<Outcome>> {
        // every study checked before the database is touched
        let rows = submissions
            .iter()
            .map(Submission::rows)
            .collect::<Result<Vec<_>>>()?;
        let path = self.path.clone();
        let err = move |action: &'static str| {
            let path = path.clone();
            move |source| RecordsError::Sqlite {
                path,
                action,
                source,
            }
        };
        let tx = self
            .conn
            .transaction_with_behavior(TransactionBehavior::Immediate)
            .map_err(err("starting the record's transaction"))?;
        let mut outcomes = Vec::with_capacity(rows.len());
        for rows in &rows {
            if let Some((record, recorded_at)) = tx
                .query_row(
                    "SELECT record_hash, recorded_at FROM studies WHERE record_hash = ?1",
                    [&rows.hash],
                    |r| Ok((r.get::<_, String>(0)?, r.get::<_, String>(1)?)),
                )
                .optional()
                .map_err(err("looking the record up"))?
            {
                outcomes.push(Outcome::AlreadyRecorded {
                    record,
                    recorded_at,
                });
                continue;
            }
            // an error here drops the transaction: nothing of any study is written
            outcomes.push(insert(&tx, rows).map_err(|e| match e {
                Insert::Sql(action, source) => RecordsError::Sqlite {
                    path: self.path.clone(),
                    action,
                    source,
                },
                Insert::Records(e) => e,
            })?);
        }
        before_commit();
        tx.commit().map_err(err("committing the record"))?;
        Ok(outcomes)
    }

    /// Records a balancing of `centrifuge` on `date`.
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`].
    pub fn record_balance(
        &mut self,
        centrifuge: &str,
        date: Date,
        note: &str,
    ) -> Result<BalanceOutcome> {
        let path = self.path.clone();
        let err = move |source| RecordsError::Sqlite {
            path: path.clone(),
            action: "recording a balance event",
            source,
        };
        let tx = self
            .conn
            .transaction_with_behavior(TransactionBehavior::Immediate)
            .map_err(err.clone())?;
        let id = centrifuge_id(&tx, centrifuge).map_err(err.clone())?;
        let n = tx
            .execute(
                "INSERT OR IGNORE INTO balance_events (centrifuge_id, date, day, note, recorded_at) \
                 VALUES (?1, ?2, ?3, ?4, strftime('%Y-%m-%dT%H:%M:%SZ', 'now'))",
                params![id, date.to_string(), date.days(), note],
            )
            .map_err(err.clone())?;
        tx.commit().map_err(err)?;
        Ok(if n == 1 {
            BalanceOutcome::Recorded
        } else {
            BalanceOutcome::AlreadyRecorded
        })
    }

    /// Counts of the records: (studies, certificates, units, centrifuges).
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`].
    pub fn counts(&self) -> Result<(i64, i64, i64, i64)> {
        self.conn
            .query_row(
                "SELECT (SELECT count(*) FROM studies), (SELECT count(*) FROM certificates), \
                 (SELECT count(*) FROM units), (SELECT count(*) FROM centrifuges)",
                [],
                |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)),
            )
            .map_err(self.sql("counting the records"))
    }

    /// Runs SQLite's integrity check: `None` when the file is sound, else its first finding.
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`].
    pub fn integrity(&self) -> Result<Option<String>> {
        let text: String = self
            .conn
            .query_row("PRAGMA integrity_check", [], |r| r.get(0))
            .map_err(self.sql("checking its integrity"))?;
        Ok((text != "ok").then_some(text))
    }

    /// The DCC stored with a certificate, decompressed, if one was recorded.
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`]; [`RecordsError::NotRecords`] for a stored DCC that does not
    /// decompress.
    pub fn dcc_xml(&self, certificate_id: &str) -> Result<Option<Vec<u8>>> {
        let blob: Option<Option<Vec<u8>>> = self
            .conn
            .query_row(
                "SELECT dcc_xml_zlib FROM certificates WHERE certificate_id = ?1",
                [certificate_id],
                |r| r.get(0),
            )
            .optional()
            .map_err(self.sql("reading a certificate's DCC"))?;
        blob.flatten()
            .map(|z| {
                miniz_oxide::inflate::decompress_to_vec_zlib(&z).map_err(|e| {
                    RecordsError::NotRecords {
                        path: self.path.clone(),
                        reason: format!("the DCC of {certificate_id} does not decompress: {e}"),
                    }
                })
            })
            .transpose()
    }

    /// The unit `query` names (`SERIAL` or `MODEL/SERIAL`) and its certificates.
    ///
    /// # Errors
    /// [`RecordsError::UnknownUnit`], [`RecordsError::AmbiguousUnit`], [`RecordsError::Sqlite`].
    pub fn unit_records(&self, query: &str) -> Result<UnitRecords> {
        // By serial, and by MODEL/SERIAL split at each '/' (a serial may hold one): each an
        // indexed lookup.
        let mut stmt = self
            .conn
            .prepare_cached(
                "SELECT id, kind, manufacturer, model, serial FROM units \
                 WHERE (?1 IS NULL AND serial = ?2) OR (model = ?1 AND serial = ?2)",
            )
            .map_err(self.sql("finding the unit"))?;
        let mut candidates: Vec<(Option<&str>, &str)> = vec![(None, query)];
        candidates.extend(
            query
                .match_indices('/')
                .map(|(i, _)| (Some(&query[..i]), &query[i + 1..])),
        );
        let mut found: Vec<(i64, UnitIdentity)> = Vec::new();
        for (model, serial) in candidates {
            let rows: Vec<(i64, UnitIdentity)> = stmt
                .query_map(params![model, serial], |r| {
                    Ok((
                        r.get(0)?,
                        UnitIdentity {
                            kind: r.get(1)?,
                            manufacturer: r.get(2)?,
                            model: r.get(3)?,
                            serial: r.get(4)?,
                        },
                    ))
                })
                .and_then(Iterator::collect)
                .map_err(self.sql("finding the unit"))?;
            for row in rows {
                if !found.iter().any(|(id, _)| *id == row.0) {
                    found.push(row);
                }
            }
        }
        let (unit_id, unit) = match found.len() {
            1 => found
                .into_iter()
                .next()
                .ok_or_else(|| unreachable_unit(query))?,
            0 => {
                let known =
                    self.names("SELECT model || '/' || serial FROM units ORDER BY 1 LIMIT 20")?;
                return Err(RecordsError::UnknownUnit {
                    query: query.to_owned(),
                    known,
                });
            }
            _ => {
                return Err(RecordsError::AmbiguousUnit {
                    query: query.to_owned(),
                    candidates: found.iter().map(|(_, u)| u.to_string()).collect(),
                });
            }
        };
        let mut stmt = self
            .conn
            .prepare_cached(
                "SELECT c.id, c.certificate_id, s.measured_from, c.issued, c.method, s.record_hash, \
                        (SELECT o.certificate_id FROM certificates o WHERE o.id = c.supersedes), \
                        (SELECT n.certificate_id FROM certificates n WHERE n.supersedes = c.id), \
                        c.dcc_sha256, c.pdf_sha256 \
                 FROM certificates c JOIN studies s ON s.id = c.study_id \
                 WHERE c.unit_id = ?1 ORDER BY s.measured_day, c.id",
            )
            .map_err(self.sql("reading the unit's certificates"))?;
        let heads: Vec<(i64, StoredCertificate)> = stmt
            .query_map([unit_id], |r| {
                let measured: String = r.get(2)?;
                let issued: String = r.get(3)?;
                Ok((
                    r.get(0)?,
                    StoredCertificate {
                        id: r.get(1)?,
                        measured: Date::parse(&measured).unwrap_or(Date::from_days(0)),
                        issued: Date::parse(&issued).unwrap_or(Date::from_days(0)),
                        method: r.get(4)?,
                        record: r.get(5)?,
                        supersedes: r.get(6)?,
                        superseded_by: r.get(7)?,
                        dcc_sha256: r.get(8)?,
                        pdf_sha256: r.get(9)?,
                        terms: Vec::new(),
                        covariance: Vec::new(),
                    },
                ))
            })
            .and_then(Iterator::collect)
            .map_err(self.sql("reading the unit's certificates"))?;
        let mut terms = self
            .conn
            .prepare_cached(
                "SELECT term, mounting, unit, value, u, expanded FROM certified \
                 WHERE certificate = ?1 ORDER BY position",
            )
            .map_err(self.sql("reading the certified values"))?;
        let mut cov = self
            .conn
            .prepare_cached(
                "SELECT row, col, value FROM certified_covariance WHERE certificate = ?1",
            )
            .map_err(self.sql("reading the certified covariance"))?;
        let mut certificates = Vec::with_capacity(heads.len());
        for (id, mut c) in heads {
            c.terms = terms
                .query_map([id], |r| {
                    Ok(StoredTerm {
                        term: r.get(0)?,
                        mounting: r.get(1)?,
                        unit: r.get(2)?,
                        value: r.get(3)?,
                        u: r.get(4)?,
                        expanded: r.get(5)?,
                    })
                })
                .and_then(Iterator::collect)
                .map_err(self.sql("reading the certified values"))?;
            let n = c.terms.len();
            c.covariance = vec![vec![0.0; n]; n];
            let cells: Vec<(usize, usize, f64)> = cov
                .query_map([id], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))
                .and_then(Iterator::collect)
                .map_err(self.sql("reading the certified covariance"))?;
            for (i, j, v) in cells {
                if i < n && j < n {
                    c.covariance[i][j] = v;
                }
            }
            certificates.push(c);
        }
        Ok(UnitRecords { unit, certificates })
    }

    /// Every unit recorded, as `MODEL/SERIAL`, in order.
    ///
    /// # Errors
    /// [`RecordsError::Sqlite`].
    pub fn units(&self) -> Result<Vec<String>> {
        self.names("SELECT model || '/' || serial FROM units ORDER BY model, serial")
    }

    /// The campaigns and balance events of centrifuge `name`.
    ///
    /// # Errors
    /// [`RecordsError::UnknownCentrifuge`], [`RecordsError::Sqlite`].
    pub fn centrifuge_records(&self, name: &str) -> Result<CentrifugeRecords> {
        let id: Option<i64> = self
            .conn
            .query_row("SELECT id FROM centrifuges WHERE name = ?1", [name], |r| {
                r.get(0)
            })
            .optional()
            .map_err(self.sql("finding the centrifuge"))?;
        let Some(id) = id else {
            let known = self.names("SELECT name FROM centrifuges ORDER BY 1 LIMIT 20")?;
            return Err(RecordsError::UnknownCentrifuge {
                name: name.to_owned(),
                known,
            });
        };
        // Per study, the phase its calibration compensated with, else its last phase; a study
        // whose certificate a corrected one superseded is the same campaign: left out.
        let mut stmt = self
            .conn
            .prepare_cached(
                "SELECT s.measured_from, s.name, p.name, p.c_r_m_s2, p.c_r_u_m_s2, p.offset_um, \
                        p.delta_k2_rad_s_g2, p.delta_k2_u_rad_s_g2 \
                 FROM studies s JOIN probe_phases p ON p.study_id = s.id \
                 WHERE s.centrifuge_id = ?1 AND p.position = COALESCE( \
                     (SELECT q.position FROM probe_phases q WHERE q.study_id = s.id AND q.name = s.compensated_with), \
                     (SELECT max(q.position) FROM probe_phases q WHERE q.study_id = s.id)) \
                   AND NOT EXISTS (SELECT 1 FROM certificates c JOIN certificates n \
                       ON n.supersedes = c.id WHERE c.study_id = s.id) \
                 ORDER BY s.measured_day, s.id",
            )
            .map_err(self.sql("reading the centrifuge's campaigns"))?;
        let mut campaigns: Vec<Campaign> = stmt
            .query_map([id], |r| {
                let date: String = r.get(0)?;
                Ok(Campaign {
                    date: Date::parse(&date).unwrap_or(Date::from_days(0)),
                    study: r.get(1)?,
                    phase: r.get(2)?,
                    c_r_m_s2: r.get(3)?,
                    c_r_u_m_s2: r.get(4)?,
                    offset_um: r.get(5)?,
                    delta_k2_rad_s_g2: r.get(6)?,
                    delta_k2_u_rad_s_g2: r.get(7)?,
                })
            })
            .and_then(Iterator::collect)
            .map_err(self.sql("reading the centrifuge's campaigns"))?;
        // The units of a several-unit study are recorded as one study each, from one probe
        // phase: the same campaign, counted once (the first unit's line; its Δk2 is at that
        // unit's k1 and radius).
        campaigns.dedup_by(|later, first| {
            later.date == first.date
                && later.phase == first.phase
                && later.c_r_m_s2.to_bits() == first.c_r_m_s2.to_bits()
                && later.offset_um.to_bits() == first.offset_um.to_bits()
        });
        let mut stmt = self
            .conn
            .prepare_cached(
                "SELECT date, note FROM balance_events WHERE centrifuge_id = ?1 ORDER BY day, id",
            )
            .map_err(self.sql("reading the balance events"))?;
        let balances: Vec<BalanceEvent> = stmt
            .query_map([id], |r| {
                let date: String = r.get(0)?;
                Ok(BalanceEvent {
                    date: Date::parse(&date).unwrap_or(Date::from_days(0)),
                    note: r.get(1)?,
                })
            })
            .and_then(Iterator::collect)
            .map_err(self.sql("reading the balance events"))?;
        Ok(CentrifugeRecords {
            name: name.to_owned(),
            campaigns,
            balances,
        })
    }

    fn names(&self, sql: &str) -> Result<Vec<String>> {
        let mut stmt = self.conn.prepare(sql).map_err(self.sql("listing names"))?;
        stmt.query_map([], |r| r.get(0))
            .and_then(Iterator::collect)
            .map_err(self.sql("listing names"))
    }
}

fn unreachable_unit(query: &str) -> RecordsError {
    RecordsError::UnknownUnit {
        query: query.to_owned(),
        known: Vec::new(),
    }
}

fn is_busy(e: &rusqlite::Error) -> bool {
    matches!(e, rusqlite::Error::SqliteFailure(f, _)
        if matches!(f.code, rusqlite::ErrorCode::DatabaseBusy | rusqlite::ErrorCode::DatabaseLocked))
}
