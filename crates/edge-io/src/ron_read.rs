//! The one RON reader of the workspace's configuration files.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

/// RON text that does not parse into the type asked for, located in its file: the line and
/// column (1-based) where the parser stopped and what it found there. Each crate says
/// [`code`](RonError::code) in its own words (a study's keys, a scenario's fields).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}:{line}:{column}: {code}", path.display())]
pub struct RonError {
    /// The file (or what stands for it, such as a command-line flag).
    pub path: PathBuf,
    /// The line, from 1.
    pub line: usize,
    /// The column, from 1.
    pub column: usize,
    /// What the parser found wrong.
    pub code: ron::error::Error,
}

/// Parses RON `text` read from `path` into a `T`, in the workspace's dialect
/// ([`ron_options`](crate::ron_options): optional sections without `Some(...)`); a leading
/// byte-order mark is dropped. `path` only names the source in the error. Every RON file of
/// the workspace (studies, lab profiles, scenarios, expected values, plans, recording formats)
/// is read through this function.
///
/// # Errors
/// [`RonError`] with the line and column of the fault.
///
/// ```
/// let v: (u32, f64) = edge_io::from_ron("(1, 2.5)", std::path::Path::new("x.ron")).unwrap();
/// assert_eq!(v, (1, 2.5));
/// let e = edge_io::from_ron::<(u32, f64)>("(1,\n  oops)", std::path::Path::new("x.ron")).unwrap_err();
/// assert_eq!((e.line, e.column), (2, 3));
/// assert!(e.to_string().starts_with("x.ron:2:3: "), "{e}");
/// ```
pub fn from_ron<T: DeserializeOwned>(text: &str, path: &Path) -> Result<T, RonError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    crate::ron_options().from_str(text).map_err(|e| RonError {
        path: path.to_owned(),
        line: e.span.start.line,
        column: e.span.start.col,
        code: e.code,
    })
}
