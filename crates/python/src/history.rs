//! The records' history from Python (`docs/RECORDS.md`, `docs/PYTHON.md`): a unit's history
//! and a centrifuge's health computed as `centrifuge-cal history --json` computes them
//! (`records::unit_history`, `records::centrifuge_health` on the database the command line
//! would open), returned as Python objects of that JSON's shape (the package turns them into
//! typed objects with numpy arrays).

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::errors::{self, Kind, Located};
use crate::interrupt::interruptible;
use crate::to_python::{ToPythonError, to_python};

/// An error of the records, raised as the package's exception: a database or unit that
/// cannot be found or read, a bad date or option (`ConfigError`), a fit that cannot be made
/// (`ComputationError`).
fn raise(py: Python<'_>, e: &records::RecordsError) -> PyErr {
    use records::RecordsError as E;
    let kind = match e {
        E::Fit { .. } | E::Coverage { .. } | E::NonFinite { .. } => Kind::Computation,
        _ => Kind::Config,
    };
    errors::raise(py, kind, errors::chain_message(e), Located::default())
}

/// The database's path as the command line finds it (`records` given, else
/// `$CENTRIFUGE_CAL_RECORDS`, else the documented default).
fn database(py: Python<'_>, records: Option<PathBuf>) -> PyResult<PathBuf> {
    cli::records_path(records.as_deref())
        .map(|(path, _)| path)
        .map_err(|e| errors::input(py, "records", format!("{e:#}")))
}

fn native<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    to_python(py, value).map_err(|e| match e {
        ToPythonError::Python(e) => e,
        e => errors::raise(py, Kind::Computation, e.to_string(), Located::default()),
    })
}

fn date(field: &str, text: Option<String>) -> Result<Option<records::Date>, records::RecordsError> {
    text.map(|t| records::Date::parse_field(field, &t))
        .transpose()
}

/// A unit's history (`centrifuge-cal history UNIT --json`): `unit` its serial or
/// MODEL/SERIAL; `at` the date to predict at (YYYY-MM-DD); `term`, `tolerance` and
/// `reliability` the recommended interval. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (unit, records = None, at = None, term = None, tolerance = None, reliability = 0.95))]
pub(crate) fn unit_history(
    py: Python<'_>,
    unit: String,
    records: Option<PathBuf>,
    at: Option<String>,
    term: Option<String>,
    tolerance: Option<f64>,
    reliability: f64,
) -> PyResult<Bound<'_, PyAny>> {
    let path = database(py, records)?;
    let interval = match (term, tolerance) {
        (Some(term), Some(tolerance)) => Some((
            term,
            records::IntervalRequest {
                tolerance,
                reliability,
            },
        )),
        (None, None) => None,
        (Some(_), None) => {
            return Err(errors::input(
                py,
                "tolerance",
                "the recommended interval needs the term and its tolerance: give `tolerance` \
                 with `term`"
                    .to_owned(),
            ));
        }
        (None, Some(_)) => {
            return Err(errors::input(
                py,
                "term",
                "the recommended interval needs the term and its tolerance: give `term` with \
                 `tolerance`"
                    .to_owned(),
            ));
        }
    };
    let history = interruptible(py, move || {
        let db = records::Database::open(&path, records::Access::Existing)?;
        records::unit_history(
            db.unit_records(&unit)?,
            &records::HistoryOptions {
                at: date("at", at)?,
                interval,
            },
        )
    })?
    .map_err(|e| raise(py, &e))?;
    native(py, &history)
}

/// A centrifuge's health (`centrifuge-cal history --centrifuge NAME --json`): `target_u95`
/// the U95 of k2 to meet (rad/(s·g²)), `share` of it Δk2 may reach (default 0.2, as the
/// command line's), `next` the next campaign's date. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (name, records = None, target_u95 = None, share = None, next = None))]
pub(crate) fn centrifuge_health(
    py: Python<'_>,
    name: String,
    records: Option<PathBuf>,
    target_u95: Option<f64>,
    share: Option<f64>,
    next: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    let path = database(py, records)?;
    let health = interruptible(py, move || {
        let db = records::Database::open(&path, records::Access::Existing)?;
        records::centrifuge_health(
            db.centrifuge_records(&name)?,
            &records::HealthOptions {
                target_u95_rad_s_g2: target_u95,
                share: share.unwrap_or(cli::DEFAULT_SHARE),
                next: date("next", next)?,
            },
        )
    })?
    .map_err(|e| raise(py, &e))?;
    native(py, &health)
}
