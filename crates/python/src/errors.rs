//! Rust errors as the package's Python exceptions (`centrifuge_cal.errors`), with the
//! command line's message and the file, line, field and hint the error names.

use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The exception classes, by their name in `centrifuge_cal.errors`.
#[derive(Debug, Clone, Copy)]
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
    const fn class(self) -> &'static str {
        match self {
            Self::Input => "InputError",
            Self::Recording => "RecordingError",
            Self::Config => "ConfigError",
            Self::Computation => "ComputationError",
        }
    }
}

/// The error and its causes joined by `: `, leaving out a cause whose text the message
/// before it already holds: the words `cargo xtask` prints after `error: `.
pub(crate) fn chain_message(e: &(dyn std::error::Error + 'static)) -> String {
    let mut out = String::new();
    let mut next: Option<&(dyn std::error::Error + 'static)> = Some(e);
    while let Some(cause) = next {
        let text = cause.to_string();
        if !out.contains(&text) {
            if !out.is_empty() {
                out.push_str(": ");
            }
            out.push_str(&text);
        }
        next = cause.source();
    }
    out
}

/// What an error locates, read from its `Debug` form (the error types keep these in fields
/// named `path`/`file`, `line` and `field`, at any depth of nesting): the innermost file and
/// line, the outermost field.
#[derive(Debug, Default, PartialEq)]
pub(crate) struct Located {
    pub(crate) file: Option<String>,
    pub(crate) line: Option<usize>,
    pub(crate) field: Option<String>,
    pub(crate) hint: Option<String>,
}

/// The Rust string literal starting just after an opening quote, unescaped.
fn literal(s: &str) -> Option<String> {
    let mut out = String::new();
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => return Some(out),
            '\\' => match chars.next()? {
                'n' => out.push('\n'),
                't' => out.push('\t'),
                'r' => out.push('\r'),
                '0' => out.push('\0'),
                'u' => {
                    // \u{XXXX}
                    let rest: String = chars.by_ref().take_while(|&c| c != '}').collect();
                    let code = u32::from_str_radix(rest.trim_start_matches('{'), 16).ok()?;
                    out.push(char::from_u32(code)?);
                }
                other => out.push(other),
            },
            c => out.push(c),
        }
    }
    None
}

/// The number after `line: ` or `line: Some(`.
fn number(s: &str) -> Option<usize> {
    let s = s.strip_prefix("Some(").unwrap_or(s);
    let digits: String = s.chars().take_while(char::is_ascii_digit).collect();
    digits.parse().ok()
}

impl Located {
    pub(crate) fn of(debug: &str, message: &str) -> Self {
        let mut found = Self::default();
        // (position, value) of every key, to pair the innermost file with its line.
        let mut files = Vec::new();
        for key in ["path: \"", "file: \""] {
            for (at, _) in debug.match_indices(key) {
                if let Some(v) = literal(&debug[at + key.len()..]) {
                    files.push((at, v));
                }
            }
        }
        files.sort_by_key(|(at, _)| *at);
        found.file = files.last().map(|(_, v)| v.clone());
        found.line = debug
            .match_indices("line: ")
            .filter_map(|(at, k)| number(&debug[at + k.len()..]))
            .last();
        found.field = debug
            .match_indices("field: \"")
            .find_map(|(at, k)| literal(&debug[at + k.len()..]));
        found.hint = message.find("(hint: ").map(|at| {
            let rest = &message[at + "(hint: ".len()..];
            // up to the parenthesis that closes `(hint: `
            let mut depth = 0usize;
            let mut end = rest.len();
            for (i, c) in rest.char_indices() {
                match c {
                    '(' => depth += 1,
                    ')' if depth == 0 => {
                        end = i;
                        break;
                    }
                    ')' => depth -= 1,
                    _ => {}
                }
            }
            rest[..end].to_owned()
        });
        found
    }
}

/// A Python exception of `kind` with `message` and what it locates.
pub(crate) fn raise(py: Python<'_>, kind: Kind, message: String, located: Located) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let class = py.import("centrifuge_cal.errors")?.getattr(kind.class())?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("file", located.file)?;
        kwargs.set_item("line", located.line)?;
        kwargs.set_item("field", located.field)?;
        kwargs.set_item("hint", located.hint)?;
        let value = class.call((message,), Some(&kwargs))?;
        Ok(PyErr::from_value(value))
    };
    build().unwrap_or_else(|e| e)
}

/// A Rust library error as a Python exception of `kind`.
pub(crate) fn from_error<E: std::error::Error + 'static>(
    py: Python<'_>,
    kind: Kind,
    e: &E,
) -> PyErr {
    let message = chain_message(e);
    let located = Located::of(&format!("{e:?}"), &message);
    raise(py, kind, message, located)
}

/// An [`Kind::Input`] error naming the argument `field`.
pub(crate) fn input(py: Python<'_>, field: &str, message: String) -> PyErr {
    raise(
        py,
        Kind::Input,
        message,
        Located {
            field: Some(field.to_owned()),
            ..Located::default()
        },
    )
}
