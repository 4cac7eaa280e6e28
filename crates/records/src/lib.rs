//! The records database of a centrifuge laboratory (issue 30, `docs/RECORDS.md`): every
//! study, certificate and probe phase in one SQLite file, and from them the history of each
//! unit (its certified coefficients against date, their drift and the value predicted at a
//! date), the recommended calibration interval and the centrifuge's health (C_r, the static
//! offset and Δk2 = k1·C_r·g/R² of eq. 19 against date, and whether to rebalance before the
//! next campaign).
//!
//! Read as [`Submission`] (what a study hands over, on values: its results and the bytes of
//! the files it wrote; checked before anything is written) → [`Database`] (the one module
//! that touches a file: the database it is given; WAL, a busy timeout, every write one
//! transaction, records keyed by the SHA-256 of results.json, never updated in place) →
//! [`UnitRecords`], [`CentrifugeRecords`] (what is stored, read back) → [`unit_history`],
//! [`centrifuge_health`] (on values: [`fit_drift`], a weighted straight line through
//! `identify::lstsq`, and [`variables_interval`], the variables method of NCSLI RP-1).
//!
//! # References
//! - Liu et al. (2025), eq. 19 (Δk2 from C_r).
//! - ISO/IEC 17025:2017 §7.8.8 (amendments: a new certificate that supersedes the old).
//! - H. Castrup, "Calibration Intervals from Variables Data", NCSL International Workshop and
//!   Symposium, 2005; NCSLI RP-1, *Establishment and Adjustment of Calibration Intervals*;
//!   NASA-HDBK-8739.19-5 §7.

mod date;
mod db;
mod drift;
mod error;
mod history;
mod interval;
mod schema;
mod stored;
mod submission;

pub use date::{DAYS_PER_YEAR, Date};
pub use db::{Access, BUSY_TIMEOUT, BalanceOutcome, Database, Outcome};
pub use drift::{Drift, Observation, Prediction, fit_drift};
pub use error::{RecordsError, Result};
pub use history::{
    Advice, AtSource, CentrifugeHealth, HealthOptions, HistoryOptions, IntervalRecommendation,
    NextSource, TermHistory, TermPoint, UnitHistory, centrifuge_health, unit_history,
};
pub use interval::{ASSUMPTIONS, Interval, IntervalRequest, METHOD, variables_interval};
pub use schema::{APPLICATION_ID, MIGRATIONS, SCHEMA_VERSION};
pub use stored::{
    BalanceEvent, Campaign, CentrifugeRecords, StoredCertificate, StoredTerm, UnitRecords,
};
pub use submission::{InputFile, Submission, UnitIdentity, sha256_hex};
