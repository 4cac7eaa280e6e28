//! The package's exceptions and warning class, created here (`create_exception!`), and Rust
//! errors raised as them: the command line's message, and the file, line, field and hint
//! read from the error's own fields (never from its text).

use std::path::Path;

use pyo3::exceptions::{PyException, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};

pyo3::create_exception!(
    centrifuge_cal.errors,
    CentrifugeCalError,
    PyException,
    "Base class of every error this package raises. Its `message` is the command line's \
     (what `cargo xtask` prints after `error: `); `file`, `line` (1-based), `field` (a field \
     of a configuration, or an argument's name) and `hint` (what to change) are what the \
     error locates, `None` where it names none."
);
pyo3::create_exception!(
    centrifuge_cal.errors,
    RecordingError,
    CentrifugeCalError,
    "A recording that cannot be read, or whose samples cannot be analysed."
);
pyo3::create_exception!(
    centrifuge_cal.errors,
    ConfigError,
    CentrifugeCalError,
    "A study, plan or format description refused (an unknown key, a missing field, a value \
     out of range, a file named that cannot be read, a structure nested too deeply)."
);
pyo3::create_exception!(
    centrifuge_cal.errors,
    ComputationError,
    CentrifugeCalError,
    "A computation that cannot give a trustworthy number (an ill-conditioned fit, a \
     non-finite result)."
);
pyo3::create_exception!(
    centrifuge_cal.errors,
    CentrifugeCalWarning,
    PyUserWarning,
    "A number was computed, but something may make it wrong (the study's warnings: its \
     `code` is results.json's, e.g. `implausible_gap_unit`, `drift_not_fitted`)."
);

/// `InputError(CentrifugeCalError, ValueError)`: two bases, which `create_exception!` does
/// not take, so it is made by `type(...)` once.
static INPUT_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();

fn input_error_type(py: Python<'_>) -> PyResult<&Bound<'_, PyType>> {
    INPUT_ERROR
        .get_or_try_init(py, || {
            let namespace = PyDict::new(py);
            namespace.set_item("__module__", "centrifuge_cal.errors")?;
            namespace.set_item(
                "__doc__",
                "A bad argument: an array of the wrong length, shape or dtype, a NaN, time that \
                 does not increase, a value out of range (also a `ValueError`).",
            )?;
            let bases = PyTuple::new(
                py,
                [
                    py.get_type::<CentrifugeCalError>(),
                    py.get_type::<PyValueError>(),
                ],
            )?;
            py.get_type::<PyType>()
                .call1(("InputError", bases, namespace))?
                .cast_into::<PyType>()
                .map(Bound::unbind)
                .map_err(PyErr::from)
        })
        .map(|t| t.bind(py))
}

/// The `message` of an error: its first argument (a property of `CentrifugeCalError`, so
/// that an error raised with one argument has it too).
#[pyfunction]
fn error_message(error: &Bound<'_, PyAny>) -> PyResult<String> {
    let args = error.getattr("args")?;
    match args.get_item(0) {
        Ok(first) => first.str()?.extract(),
        Err(_) => Ok(String::new()),
    }
}

/// Adds the classes to the module, with their attributes' defaults (`None`) and the
/// `message` property on the base class.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let base = py.get_type::<CentrifugeCalError>();
    for name in ["file", "line", "field", "hint"] {
        base.setattr(name, py.None())?;
    }
    let getter = wrap_pyfunction!(error_message, m)?;
    let property = py
        .import("builtins")?
        .getattr("property")?
        .call1((getter,))?;
    base.setattr("message", property)?;
    m.add("CentrifugeCalError", base)?;
    m.add("InputError", input_error_type(py)?)?;
    m.add("RecordingError", py.get_type::<RecordingError>())?;
    m.add("ConfigError", py.get_type::<ConfigError>())?;
    m.add("ComputationError", py.get_type::<ComputationError>())?;
    m.add(
        "CentrifugeCalWarning",
        py.get_type::<CentrifugeCalWarning>(),
    )?;
    Ok(())
}

/// The exception classes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// A bad argument or array (also a `ValueError`).
    Input,
    /// A recording that cannot be read or analysed.
    Recording,
    /// A study or plan configuration refused.
    Config,
    /// A computation that cannot give a trustworthy number.
    Computation,
}

impl Kind {
    fn class(self, py: Python<'_>) -> PyResult<Bound<'_, PyType>> {
        Ok(match self {
            Self::Input => input_error_type(py)?.clone(),
            Self::Recording => py.get_type::<RecordingError>(),
            Self::Config => py.get_type::<ConfigError>(),
            Self::Computation => py.get_type::<ComputationError>(),
        })
    }
}

/// The error and its causes as one line ([`units::ErrorChain`], the one chain printer): the
/// words `cargo xtask` prints after `error: `.
pub(crate) fn chain_message(e: &(dyn std::error::Error + 'static)) -> String {
    units::ErrorChain(e).to_string()
}

/// What an error locates, from its fields: the innermost file and line, the outermost
/// field, the hint.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Located {
    pub(crate) file: Option<String>,
    pub(crate) line: Option<usize>,
    pub(crate) field: Option<String>,
    pub(crate) hint: Option<String>,
}

fn file(path: &Path) -> Option<String> {
    Some(path.display().to_string())
}

impl Located {
    /// Only a field (an argument's name, a configuration's key).
    pub(crate) fn field(field: impl Into<String>) -> Self {
        Self {
            field: Some(field.into()),
            ..Self::default()
        }
    }

    /// A study's error.
    pub(crate) fn pipeline(e: &pipeline::PipelineError) -> Self {
        use pipeline::PipelineError as E;
        let at = |path: &Path, field: &str| Self {
            file: file(path),
            field: Some(field.to_owned()),
            ..Self::default()
        };
        match e {
            E::Parse {
                path,
                line,
                message,
                ..
            } => Self {
                file: file(path),
                line: Some(*line),
                field: serde_field(message),
                hint: None,
            },
            E::MissingField { path, field, hint } => Self {
                hint: Some(hint.clone()),
                ..at(path, field)
            },
            E::Recording {
                path,
                field,
                source,
            } => {
                let inner = Self::recording(source);
                Self {
                    file: inner.file.or_else(|| file(path)),
                    line: inner.line,
                    field: Some(field.clone()),
                    hint: inner.hint,
                }
            }
            E::TableValue {
                field,
                file: table,
                line,
                ..
            } => Self {
                file: file(table),
                line: Some(*line),
                field: Some(field.clone()),
                hint: None,
            },
            E::TooFewRates {
                field, file: table, ..
            } => Self {
                file: file(table),
                field: Some(field.clone()),
                ..Self::default()
            },
            E::Harmonics {
                path,
                field,
                source,
            } => Self {
                hint: Self::harmonics(source).hint,
                ..at(path, field)
            },
            E::InvalidField { path, field, .. }
            | E::DuplicateRate { path, field, .. }
            | E::TooFewPoints { path, field, .. }
            | E::NonFiniteResult { path, field, .. }
            | E::Identify { path, field, .. }
            | E::Calibration { path, field, .. }
            | E::Uncertainty { path, field, .. }
            | E::Balance { path, field, .. }
            | E::EmptyList { path, field }
            | E::Kinematics { path, field, .. }
            | E::AccelModel { path, field, .. }
            | E::Unsupported { path, field, .. }
            | E::DuplicateName { path, field, .. }
            | E::InvalidName { path, field, .. }
            | E::UnknownPhase { path, field, .. }
            | E::StatedTwice { path, field, .. }
            | E::InvalidMountings { path, field, .. }
            | E::BesideUnits { path, field, .. }
            | E::UsedTwice { path, field, .. }
            | E::UnknownKey { path, field, .. } => at(path, field),
            E::File(e) => Self::edge(e),
            E::TwoOrientation { path, source } => Self {
                file: file(path),
                field: two_orientation_field(source),
                ..Self::default()
            },
            E::Several { errors } => errors.first().map(Self::pipeline).unwrap_or_default(),
            _ => Self::default(),
        }
    }

    /// A recording's or table's error.
    pub(crate) fn recording(e: &recording::RecordingError) -> Self {
        use recording::{Hint, RecordingError as E};
        let hint = |h: &Option<Hint>| h.map(|h| h.to_string());
        let at = |path: &Path, line: Option<usize>, hint: Option<String>| Self {
            file: file(path),
            line,
            field: None,
            hint,
        };
        match e {
            E::LineTooLong { path, line, .. }
            | E::NoRows { path, line }
            | E::ColumnUnit { path, line, .. }
            | E::MissingField { path, line, .. }
            | E::FieldCount { path, line, .. }
            | E::TimeNotIncreasing { path, line, .. }
            | E::OutputStep { path, line, .. } => at(path, Some(*line), None),
            E::MissingColumn {
                path,
                line,
                hint: h,
                ..
            }
            | E::Parse {
                path,
                line,
                hint: h,
                ..
            }
            | E::NonFinite {
                path,
                line,
                hint: h,
                ..
            } => at(path, Some(*line), hint(h)),
            E::SampleGap { path, line, .. } => at(path, Some(*line), Some(Hint::OnGap.to_string())),
            E::Samples {
                path,
                line,
                hint: h,
                source,
            } => Self {
                field: Self::harmonics(source).field,
                ..at(path, *line, hint(h))
            },
            E::NonFiniteSample { path, .. } => at(path, None, Some(Hint::OnNonFinite.to_string())),
            E::TimeAxis { path, source, .. } => at(
                path,
                None,
                matches!(source, harmonics::HarmonicsError::SampleGap { .. })
                    .then(|| Hint::OnGap.to_string()),
            ),
            E::Io { path, .. }
            | E::TooFewIndexPulses { path, .. }
            | E::Empty { path }
            | E::Truncated { path, .. }
            | E::BadMagic { path, .. }
            | E::MatV73 { path }
            | E::Malformed { path, .. }
            | E::Unsupported { path, .. }
            | E::MissingChannel { path, .. }
            | E::ChannelLength { path, .. }
            | E::NoTimeBase { path, .. }
            | E::SettingNotForFile { path, .. }
            | E::TooFewRevolutions { path, .. } => at(path, None, None),
            E::InvalidDelimiter { .. } => Self::field("delimiter"),
            E::DuplicateColumn { field, .. } | E::InvalidSensitivity { field, .. } => {
                Self::field(*field)
            }
            E::InvalidCountsPerRev => Self::field("angle"),
            E::InvalidStartAngle { .. } => Self::field("start_angle_deg"),
            E::InvalidGapLimit { .. } => Self::field("max_gap_intervals"),
            _ => Self::default(),
        }
    }

    /// A harmonic fit's error on arrays: the argument it is about.
    pub(crate) fn harmonics(e: &harmonics::HarmonicsError) -> Self {
        use harmonics::HarmonicsError as E;
        let field = match e {
            E::NonFinite { column, .. } | E::LengthMismatch { column, .. } => match *column {
                "angle" => "angle_rad",
                "time" => "time_s",
                c => c,
            },
            E::TimeNotIncreasing { .. } | E::SampleGap { .. } | E::NonFiniteInterval { .. } => {
                "time_s"
            }
            E::AngleNotIncreasing { .. } | E::RateMismatch { .. } => "angle_rad",
            E::InvalidOrder { .. } => "order",
            E::InvalidSetting { field, .. } => field,
            E::InvalidRate { .. } => "rate_deg_s",
            E::TooFewRevolutions { .. } => "revolutions",
            _ => return Self::default(),
        };
        Self::field(field)
    }

    /// A configuration file's error (too large, unreadable, not UTF-8).
    pub(crate) fn edge(e: &edge_io::EdgeIoError) -> Self {
        use edge_io::EdgeIoError as E;
        match e {
            E::Read { path, .. } | E::TooLarge { path, .. } => Self {
                file: file(path),
                ..Self::default()
            },
            E::InvalidUtf8 { path, line, .. } => Self {
                file: file(path),
                line: Some(*line),
                ..Self::default()
            },
            _ => Self::default(),
        }
    }

    /// A plan's error.
    pub(crate) fn planning(e: &planning::PlanningError) -> Self {
        use planning::PlanningError as E;
        match e {
            E::InvalidField { field, .. } | E::NonFinite { field, .. } => Self::field(*field),
            E::TooFewPoints { .. } => Self::field("schedule.points"),
            E::TwoOrientation(source) => Self {
                field: two_orientation_field(source),
                ..Self::default()
            },
            _ => Self::default(),
        }
    }
}

fn two_orientation_field(e: &calibration::TwoOrientationError) -> Option<String> {
    use calibration::TwoOrientationError as E;
    match e {
        E::OneOrientationOnly { field, .. }
        | E::SameOrientation { field, .. }
        | E::MissingOrientation { field }
        | E::MissingRadius { field }
        | E::Invalid { field, .. }
        | E::TooFewRates { field, .. } => Some(field.clone()),
        _ => None,
    }
}

/// The field serde names in "unknown field `x`" or "missing field `x`" (serde's errors
/// carry no structured field: their message is all there is).
pub(crate) fn serde_field(message: &str) -> Option<String> {
    [
        "unknown field `",
        "missing field `",
        "unknown variant `",
        "Unexpected field named `",
        "Unexpected missing field named `",
        "Unexpected variant named `",
    ]
    .iter()
    .find_map(|k| {
        let rest = &message[message.find(k)? + k.len()..];
        Some(rest[..rest.find('`')?].to_owned())
    })
}

/// A Python exception of `kind` with `message` and what it locates.
pub(crate) fn raise(py: Python<'_>, kind: Kind, message: String, located: Located) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let value = kind.class(py)?.call1((message,))?;
        value.setattr("file", located.file)?;
        value.setattr("line", located.line)?;
        value.setattr("field", located.field)?;
        value.setattr("hint", located.hint)?;
        Ok(PyErr::from_value(value))
    };
    build().unwrap_or_else(|e| e)
}

/// An [`Kind::Input`] error naming the argument `field`.
pub(crate) fn input(py: Python<'_>, field: &str, message: String) -> PyErr {
    raise(py, Kind::Input, message, Located::field(field))
}

/// A study's error as the class of what it is about.
pub(crate) fn pipeline(py: Python<'_>, e: &pipeline::PipelineError) -> PyErr {
    use pipeline::PipelineError as E;
    let kind = match e {
        E::Recording { .. } => Kind::Recording,
        E::Identify { .. } | E::Uncertainty { .. } | E::NonFiniteResult { .. } => Kind::Computation,
        _ => Kind::Config,
    };
    raise(py, kind, chain_message(e), Located::pipeline(e))
}

/// A recording's error.
pub(crate) fn recording(py: Python<'_>, e: &recording::RecordingError) -> PyErr {
    raise(py, Kind::Recording, chain_message(e), Located::recording(e))
}

/// A plan's error.
pub(crate) fn planning(py: Python<'_>, e: &planning::PlanningError) -> PyErr {
    raise(py, Kind::Config, chain_message(e), Located::planning(e))
}

/// A configuration file's error.
pub(crate) fn edge(py: Python<'_>, e: &edge_io::EdgeIoError) -> PyErr {
    raise(py, Kind::Config, chain_message(e), Located::edge(e))
}
