//! Writing one submission's rows inside the caller's transaction: the unit, the study, its
//! files and phases, the certificate and its certified values; a rule of the records broken
//! (a conflicting certificate, a supersession of an unknown or another unit's certificate) is a
//! typed error, and the caller rolls the transaction back.

use rusqlite::{OptionalExtension as _, params};

use crate::error::RecordsError;
use crate::submission::{CertificateRow, Rows};

/// What recording a study did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// The study is now recorded.
    Recorded {
        /// The record's key (SHA-256 of results.json).
        record: String,
        /// The certificate recorded, if any.
        certificate: Option<String>,
        /// The certificate it supersedes, if any.
        supersedes: Option<String>,
        /// The unit, if a certificate was recorded.
        unit: Option<String>,
        /// The centrifuge its probe phases were recorded under, if any.
        centrifuge: Option<String>,
        /// Probe phases recorded.
        phases: usize,
    },
    /// The same results were recorded before: nothing was written.
    AlreadyRecorded {
        /// The record's key.
        record: String,
        /// When it was recorded (UTC).
        recorded_at: String,
    },
}

/// An insertion's failure: SQLite's, or a rule of the records.
pub(super) enum Insert {
    Sql(&'static str, rusqlite::Error),
    Records(RecordsError),
}

fn sql(action: &'static str) -> impl Fn(rusqlite::Error) -> Insert {
    move |e| Insert::Sql(action, e)
}

pub(super) fn centrifuge_id(tx: &rusqlite::Transaction<'_>, name: &str) -> rusqlite::Result<i64> {
    tx.execute(
        "INSERT OR IGNORE INTO centrifuges (name) VALUES (?1)",
        [name],
    )?;
    tx.query_row("SELECT id FROM centrifuges WHERE name = ?1", [name], |r| {
        r.get(0)
    })
}

/// Inserts a submission's rows, one table after another: the unit and the certificate it
/// supersedes (checked), the study, its input files and probe phases, its certificate.
pub(super) fn insert(
    tx: &rusqlite::Transaction<'_>,
    rows: &Rows,
) -> std::result::Result<Outcome, Insert> {
    let (unit_id, supersedes_id) = match &rows.certificate {
        Some(c) => {
            let (unit, supersedes) = unit_of(tx, c, rows.supersedes.as_deref())?;
            (Some(unit), supersedes)
        }
        None => (None, None),
    };
    let study = insert_study(tx, rows, unit_id)?;
    insert_files_and_phases(tx, rows, study)?;
    if let Some(c) = &rows.certificate {
        insert_certificate(tx, c, study, unit_id, supersedes_id)?;
    }
    Ok(Outcome::Recorded {
        record: rows.hash.clone(),
        certificate: rows.certificate.as_ref().map(|c| c.id.clone()),
        supersedes: rows.supersedes.clone(),
        unit: rows.certificate.as_ref().map(|c| c.unit.to_string()),
        centrifuge: rows.centrifuge.clone(),
        phases: rows.phases.len(),
    })
}

/// The certified unit's id (recorded if new) and the id of the certificate it supersedes:
/// refused when the certificate is recorded already, or the superseded one is unknown, of
/// another unit or superseded already.
fn unit_of(
    tx: &rusqlite::Transaction<'_>,
    c: &CertificateRow,
    supersedes: Option<&str>,
) -> std::result::Result<(i64, Option<i64>), Insert> {
    if let Some(record) = tx
        .query_row(
            "SELECT s.record_hash FROM certificates c JOIN studies s ON s.id = c.study_id \
             WHERE c.certificate_id = ?1",
            [&c.id],
            |r| r.get::<_, String>(0),
        )
        .optional()
        .map_err(sql("looking the certificate up"))?
    {
        return Err(Insert::Records(RecordsError::CertificateConflict {
            id: c.id.clone(),
            record,
        }));
    }
    tx.execute(
        "INSERT OR IGNORE INTO units (kind, manufacturer, model, serial) VALUES (?1, ?2, ?3, ?4)",
        params![
            c.unit.kind,
            c.unit.manufacturer,
            c.unit.model,
            c.unit.serial
        ],
    )
    .map_err(sql("recording the unit"))?;
    let id: i64 = tx
        .query_row(
            "SELECT id FROM units WHERE manufacturer = ?1 AND model = ?2 AND serial = ?3",
            params![c.unit.manufacturer, c.unit.model, c.unit.serial],
            |r| r.get(0),
        )
        .map_err(sql("recording the unit"))?;
    if let Some(old) = supersedes {
        let found: Option<(i64, i64, String, String)> = tx
            .query_row(
                "SELECT c.id, c.unit_id, u.model, u.serial FROM certificates c \
                 JOIN units u ON u.id = c.unit_id WHERE c.certificate_id = ?1",
                [old],
                |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?)),
            )
            .optional()
            .map_err(sql("looking the superseded certificate up"))?;
        let Some((old_id, old_unit, model, serial)) = found else {
            return Err(Insert::Records(RecordsError::SupersedesUnknown {
                id: old.to_owned(),
            }));
        };
        if old_unit != id {
            return Err(Insert::Records(RecordsError::SupersedesOtherUnit {
                id: old.to_owned(),
                old_unit: format!("{model}/{serial}"),
                new_unit: c.unit.to_string(),
            }));
        }
        if let Some(by) = tx
            .query_row(
                "SELECT certificate_id FROM certificates WHERE supersedes = ?1",
                [old_id],
                |r| r.get::<_, String>(0),
            )
            .optional()
            .map_err(sql("looking the superseded certificate up"))?
        {
            return Err(Insert::Records(RecordsError::AlreadySuperseded {
                id: old.to_owned(),
                by,
            }));
        }
        return Ok((id, Some(old_id)));
    }
    Ok((id, None))
}

/// Inserts the study's row (with its centrifuge, recorded if new): its id.
fn insert_study(
    tx: &rusqlite::Transaction<'_>,
    rows: &Rows,
    unit_id: Option<i64>,
) -> std::result::Result<i64, Insert> {
    let centrifuge = rows
        .centrifuge
        .as_deref()
        .map(|name| centrifuge_id(tx, name))
        .transpose()
        .map_err(sql("recording the centrifuge"))?;
    tx.execute(
        "INSERT INTO studies (record_hash, name, recorded_at, measured_from, measured_to, \
             measured_day, operator, procedure, profile, tool_version, unit_id, centrifuge_id, \
             radius_m, g_m_s2, k1_rad_s_g, compensated_with) \
         VALUES (?1, ?2, strftime('%Y-%m-%dT%H:%M:%SZ', 'now'), ?3, ?4, ?5, ?6, ?7, ?8, ?9, \
             ?10, ?11, ?12, ?13, ?14, ?15)",
        params![
            rows.hash,
            rows.name,
            rows.measured.0.to_string(),
            rows.measured.1.to_string(),
            rows.measured.0.days(),
            rows.operator,
            rows.procedure,
            rows.profile,
            rows.tool_version,
            unit_id,
            centrifuge,
            rows.radius_m,
            rows.g_m_s2,
            rows.k1_rad_s_g,
            rows.compensated_with,
        ],
    )
    .map_err(sql("recording the study"))?;
    Ok(tx.last_insert_rowid())
}

/// Inserts the study's input files and probe phases, in order.
fn insert_files_and_phases(
    tx: &rusqlite::Transaction<'_>,
    rows: &Rows,
    study: i64,
) -> std::result::Result<(), Insert> {
    let mut stmt = tx
        .prepare_cached(
            "INSERT INTO input_files (study_id, position, role, field, path, bytes, sha256) \
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)",
        )
        .map_err(sql("recording the input files"))?;
    for (i, f) in rows.inputs.iter().enumerate() {
        stmt.execute(params![
            study,
            i,
            f.role,
            f.field,
            f.path,
            i64::try_from(f.bytes).unwrap_or(i64::MAX),
            f.sha256
        ])
        .map_err(sql("recording the input files"))?;
    }
    let mut stmt = tx
        .prepare_cached(
            "INSERT INTO probe_phases (study_id, position, name, c_r_m_s2, c_r_u_m_s2, \
                 offset_um, delta_k2_rad_s_g2, delta_k2_u_rad_s_g2) \
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)",
        )
        .map_err(sql("recording the probe phases"))?;
    for (i, p) in rows.phases.iter().enumerate() {
        stmt.execute(params![
            study,
            i,
            p.name,
            p.c_r_m_s2,
            p.c_r_u_m_s2,
            p.offset_um,
            p.delta_k2_rad_s_g2,
            p.delta_k2_u_rad_s_g2
        ])
        .map_err(sql("recording the probe phases"))?;
    }

    Ok(())
}

/// Inserts the certificate with its certified values and their covariance.
fn insert_certificate(
    tx: &rusqlite::Transaction<'_>,
    c: &CertificateRow,
    study: i64,
    unit_id: Option<i64>,
    supersedes_id: Option<i64>,
) -> std::result::Result<(), Insert> {
    tx.execute(
        "INSERT INTO certificates (study_id, certificate_id, unit_id, issued, method, \
             supersedes, dcc_sha256, pdf_sha256, dcc_xml_zlib) \
         VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
        params![
            study,
            c.id,
            unit_id,
            c.issued.to_string(),
            c.method,
            supersedes_id,
            c.dcc_sha256,
            c.pdf_sha256,
            c.dcc_xml_zlib
        ],
    )
    .map_err(sql("recording the certificate"))?;
    let cert = tx.last_insert_rowid();
    let mut stmt = tx
        .prepare_cached(
            "INSERT INTO certified (certificate, position, term, mounting, unit, value, u, \
                 expanded, k, dof, low95, high95, interval_method) \
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13)",
        )
        .map_err(sql("recording the certified values"))?;
    for (i, k) in c.certified.iter().enumerate() {
        stmt.execute(params![
            cert,
            i,
            k.term,
            k.mounting,
            k.unit,
            k.value,
            k.u,
            k.expanded,
            k.k,
            k.dof,
            k.low95,
            k.high95,
            k.interval_method
        ])
        .map_err(sql("recording the certified values"))?;
    }
    let mut stmt = tx
        .prepare_cached(
            "INSERT INTO certified_covariance (certificate, row, col, value) VALUES (?1, ?2, ?3, ?4)",
        )
        .map_err(sql("recording the certified covariance"))?;
    for (i, row) in c.covariance.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            stmt.execute(params![cert, i, j, v])
                .map_err(sql("recording the certified covariance"))?;
        }
    }
    Ok(())
}
