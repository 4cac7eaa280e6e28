//! The records' errors: each names the database, the field or the unit concerned, with a hint.

/// What keeps a study from being recorded, or a history from being drawn.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RecordsError {
    /// SQLite failed (locked for longer than the busy timeout, disk full, …).
    #[error("records database {path}: {action}: {source}")]
    Sqlite {
        /// The database file (`:memory:` for one in memory).
        path: String,
        /// What was being done, in words.
        action: &'static str,
        /// SQLite's error.
        source: rusqlite::Error,
    },
    /// The file is not a records database of centrifuge-cal: another program's SQLite file,
    /// a damaged one or not SQLite at all. It is left as it was.
    #[error(
        "{path} is not a centrifuge-cal records database ({reason}); it was not modified: give --records a new file name, or the records database"
    )]
    NotRecords {
        /// The file.
        path: String,
        /// What was found, in words.
        reason: String,
    },
    /// The database was written by a newer centrifuge-cal.
    #[error(
        "records database {path} has schema version {found}; this centrifuge-cal knows versions up to {known}: use a newer centrifuge-cal (the file was not modified)"
    )]
    NewerSchema {
        /// The file.
        path: String,
        /// Its schema version.
        found: i64,
        /// The newest this build knows.
        known: i64,
    },
    /// No records database at the path given (reading never creates one).
    #[error(
        "no records database at {path}: record a study first (`centrifuge-cal record RESULTS_DIR --records {path}`)"
    )]
    Missing {
        /// The path.
        path: String,
    },
    /// A date that is not `YYYY-MM-DD` (or a span of two).
    #[error(
        "field `{field}` = {value:?}: expected a calendar date written as ISO 8601 does (2026-11-19, or 2026-11-19 to 2026-11-20 for a span)"
    )]
    Date {
        /// The field.
        field: String,
        /// Its text (at most 60 characters).
        value: String,
    },
    /// A study with neither a certificate (a unit) nor a centrifuge (its probe phases).
    #[error(
        "study {study:?} has no certificate section and no centrifuge is named: nothing to attach its records to; give --centrifuge NAME (and --date YYYY-MM-DD) to record its probe phases"
    )]
    NothingToRecord {
        /// The study's name.
        study: String,
    },
    /// A study without a certificate has no date of its own.
    #[error(
        "study {study:?} has no certificate section, so no date of measurement: give --date YYYY-MM-DD"
    )]
    NoDate {
        /// The study's name.
        study: String,
    },
    /// A certificate identification recorded before with other results.
    #[error(
        "certificate {id} is already recorded with other results (record {record}): a certificate is never changed in place; issue the corrected one under its own identification and record it with --supersedes {id}"
    )]
    CertificateConflict {
        /// The certificate's identification.
        id: String,
        /// The record holding it.
        record: String,
    },
    /// `--supersedes` names a certificate not in the records.
    #[error("--supersedes {id}: no certificate {id} is recorded")]
    SupersedesUnknown {
        /// The identification given.
        id: String,
    },
    /// `--supersedes` names a certificate already superseded.
    #[error(
        "--supersedes {id}: certificate {id} was already superseded by {by}; supersede {by} instead"
    )]
    AlreadySuperseded {
        /// The identification given.
        id: String,
        /// The certificate that superseded it.
        by: String,
    },
    /// A corrected certificate must be of the same unit as the one it supersedes.
    #[error("--supersedes {id}: certificate {id} is of unit {old_unit}, this one of {new_unit}")]
    SupersedesOtherUnit {
        /// The identification given.
        id: String,
        /// The unit of the certificate superseded.
        old_unit: String,
        /// The unit of the new one.
        new_unit: String,
    },
    /// `--supersedes` on a study without a certificate.
    #[error("--supersedes {id}: the study has no certificate to supersede it with")]
    SupersedesWithoutCertificate {
        /// The identification given.
        id: String,
    },
    /// No unit matches.
    #[error("no unit {query:?} in the records{}", known_list(.known))]
    UnknownUnit {
        /// What was asked for.
        query: String,
        /// The units recorded (at most 20).
        known: Vec<String>,
    },
    /// Several units match.
    #[error("{query:?} matches {} units: {}; give the model too (MODEL/SERIAL)", .candidates.len(), .candidates.join(", "))]
    AmbiguousUnit {
        /// What was asked for.
        query: String,
        /// The units it matches.
        candidates: Vec<String>,
    },
    /// No centrifuge of that name.
    #[error("no centrifuge {name:?} in the records{}", known_list(.known))]
    UnknownCentrifuge {
        /// What was asked for.
        name: String,
        /// The centrifuges recorded (at most 20).
        known: Vec<String>,
    },
    /// A history option out of its domain.
    #[error("{field} = {}: {requirement}", units::Compact(*.value))]
    Invalid {
        /// The option (`--reliability`).
        field: String,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: units::Requirement,
    },
    /// A term not certified for the unit.
    #[error("--term {term}: the unit's certificates certify {}", .known.join(", "))]
    UnknownTerm {
        /// The term asked for.
        term: String,
        /// The terms certified.
        known: Vec<String>,
    },
    /// The drift fit failed.
    #[error("the drift fit of {quantity}: {source}")]
    Fit {
        /// The quantity fitted.
        quantity: String,
        /// The solver's error.
        source: identify::IdentifyError,
    },
    /// A coverage factor could not be computed.
    #[error("the coverage factor of {quantity}: {source}")]
    Coverage {
        /// The quantity.
        quantity: String,
        /// The quantile's error.
        source: uncertainty::UncertaintyError,
    },
    /// A number recorded or computed is not finite.
    #[error("{what} is not a finite number")]
    NonFinite {
        /// The quantity.
        what: String,
    },
}

fn known_list(known: &[String]) -> String {
    if known.is_empty() {
        String::new()
    } else {
        format!(" (recorded: {})", known.join(", "))
    }
}

impl From<units::Unmet<&str>> for RecordsError {
    fn from(e: units::Unmet<&str>) -> Self {
        Self::Invalid {
            field: e.field.to_owned(),
            value: e.value,
            requirement: e.requirement,
        }
    }
}

/// The records' result.
pub type Result<T, E = RecordsError> = std::result::Result<T, E>;
