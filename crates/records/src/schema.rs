//! The database's schema, as numbered migrations: migration `n` takes a database of
//! `PRAGMA user_version = n − 1` to `n`, in the transaction that records the new version.
//! A database is recognised as the records' by `PRAGMA application_id`.
//!
//! Nothing is updated in place or deleted (ISO/IEC 17025 §7.8.8: a corrected certificate is a
//! new record that supersedes the old one): triggers refuse `UPDATE` and `DELETE` on every
//! table, so that even a hand-written query cannot rewrite a record.

/// `PRAGMA application_id` of a records database: the bytes "CCrd".
pub const APPLICATION_ID: i32 = 0x4343_7264;

/// The schema's migrations, in order; the schema version is their number.
pub const MIGRATIONS: &[&str] = &[V1];

/// The newest schema version this build writes.
#[allow(clippy::cast_possible_wrap, clippy::cast_possible_truncation)] // a handful of migrations
pub const SCHEMA_VERSION: i64 = MIGRATIONS.len() as i64;

/// The tables whose rows are never updated or deleted.
pub(crate) const TABLES: &[&str] = &[
    "units",
    "centrifuges",
    "studies",
    "input_files",
    "probe_phases",
    "certificates",
    "certified",
    "certified_covariance",
    "balance_events",
];

const V1: &str = r"
CREATE TABLE units (
    id INTEGER PRIMARY KEY,
    kind TEXT NOT NULL,                 -- the certificate's item description
    manufacturer TEXT NOT NULL,
    model TEXT NOT NULL,
    serial TEXT NOT NULL,
    UNIQUE (manufacturer, model, serial)
);
CREATE INDEX units_serial ON units (serial);
CREATE INDEX units_model_serial ON units (model, serial);

CREATE TABLE centrifuges (
    id INTEGER PRIMARY KEY,
    name TEXT NOT NULL UNIQUE           -- the certificate's centrifuge identity, or --centrifuge
);

CREATE TABLE studies (
    id INTEGER PRIMARY KEY,
    record_hash TEXT NOT NULL UNIQUE,   -- SHA-256 of results.json as written (it holds the inputs' SHA-256)
    name TEXT NOT NULL,
    recorded_at TEXT NOT NULL,          -- UTC, ISO 8601
    measured_from TEXT NOT NULL,        -- YYYY-MM-DD
    measured_to TEXT NOT NULL,
    measured_day INTEGER NOT NULL,      -- measured_from as days since 1970-01-01
    operator TEXT,
    procedure TEXT,
    profile TEXT,
    tool_version TEXT,
    unit_id INTEGER REFERENCES units (id),
    centrifuge_id INTEGER REFERENCES centrifuges (id),
    radius_m REAL NOT NULL,
    g_m_s2 REAL NOT NULL,
    k1_rad_s_g REAL NOT NULL,
    compensated_with TEXT               -- the probe phase the calibration compensated with
);
CREATE INDEX studies_unit ON studies (unit_id, measured_day);
CREATE INDEX studies_centrifuge ON studies (centrifuge_id, measured_day);

CREATE TABLE input_files (
    study_id INTEGER NOT NULL REFERENCES studies (id),
    position INTEGER NOT NULL,
    role TEXT NOT NULL,                 -- configuration, expected, probe_recording, piga_table, piga_recording
    field TEXT,
    path TEXT NOT NULL,
    bytes INTEGER NOT NULL,
    sha256 TEXT NOT NULL,
    PRIMARY KEY (study_id, position)
) WITHOUT ROWID;
CREATE INDEX input_files_sha256 ON input_files (sha256);

CREATE TABLE probe_phases (
    study_id INTEGER NOT NULL REFERENCES studies (id),
    position INTEGER NOT NULL,
    name TEXT NOT NULL,
    c_r_m_s2 REAL NOT NULL,
    c_r_u_m_s2 REAL,
    offset_um REAL NOT NULL,
    delta_k2_rad_s_g2 REAL NOT NULL,
    delta_k2_u_rad_s_g2 REAL,
    PRIMARY KEY (study_id, position)
) WITHOUT ROWID;

CREATE TABLE certificates (
    id INTEGER PRIMARY KEY,
    study_id INTEGER NOT NULL UNIQUE REFERENCES studies (id),
    certificate_id TEXT NOT NULL UNIQUE,
    unit_id INTEGER NOT NULL REFERENCES units (id),
    issued TEXT NOT NULL,
    method TEXT NOT NULL,               -- probe, two_orientation
    supersedes INTEGER UNIQUE REFERENCES certificates (id),
    dcc_sha256 TEXT,
    pdf_sha256 TEXT,
    dcc_xml_zlib BLOB                   -- certificate.dcc.xml, zlib-compressed (RFC 1950)
);
CREATE INDEX certificates_unit ON certificates (unit_id);

CREATE TABLE certified (
    certificate INTEGER NOT NULL REFERENCES certificates (id),
    position INTEGER NOT NULL,
    term TEXT NOT NULL,                 -- k0, k1, k2, k3
    mounting TEXT,                      -- ia_in, ia_out; NULL when shared
    unit TEXT NOT NULL,
    value REAL NOT NULL,
    u REAL NOT NULL,
    expanded REAL NOT NULL,
    k REAL,                             -- NULL for a Monte Carlo interval
    dof REAL,                           -- NULL: infinite
    low95 REAL NOT NULL,
    high95 REAL NOT NULL,
    interval_method TEXT NOT NULL,      -- gum, monte_carlo
    PRIMARY KEY (certificate, position)
) WITHOUT ROWID;

CREATE TABLE certified_covariance (
    certificate INTEGER NOT NULL REFERENCES certificates (id),
    row INTEGER NOT NULL,
    col INTEGER NOT NULL,
    value REAL NOT NULL,
    PRIMARY KEY (certificate, row, col)
) WITHOUT ROWID;

CREATE TABLE balance_events (
    id INTEGER PRIMARY KEY,
    centrifuge_id INTEGER NOT NULL REFERENCES centrifuges (id),
    date TEXT NOT NULL,
    day INTEGER NOT NULL,
    note TEXT NOT NULL,
    recorded_at TEXT NOT NULL,
    UNIQUE (centrifuge_id, date, note)
);

CREATE VIEW current_certificates AS
    SELECT c.* FROM certificates c
    WHERE NOT EXISTS (SELECT 1 FROM certificates n WHERE n.supersedes = c.id);
";

/// The triggers that refuse `UPDATE` and `DELETE` on `table`.
pub(crate) fn immutability_triggers(table: &str) -> String {
    format!(
        "CREATE TRIGGER IF NOT EXISTS {table}_never_updated BEFORE UPDATE ON {table} \
         BEGIN SELECT RAISE(ABORT, 'records are never updated in place: record a new one that supersedes it'); END;\n\
         CREATE TRIGGER IF NOT EXISTS {table}_never_deleted BEFORE DELETE ON {table} \
         BEGIN SELECT RAISE(ABORT, 'records are never deleted'); END;\n"
    )
}
