//! One setting of a file's format as the study file writes it, with its evidence; the
//! placeholder a user must fill in. A leaf: the file analysis and the table's settings both
//! use it.

use super::columns::Column;

/// The placeholder left where the user must write a value; `check` and `study` refuse a
/// configuration that still holds it.
pub(crate) const PLACEHOLDER: &str = "FILL_IN";

/// One setting of the format: its RON text in the study file and why.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Setting {
    /// `key: value` as the study file writes it.
    pub(crate) ron: String,
    /// The evidence, or what is missing when the value is a placeholder.
    pub(crate) evidence: String,
}

impl Setting {
    pub(crate) fn new(ron: impl Into<String>, evidence: impl Into<String>) -> Self {
        Self {
            ron: ron.into(),
            evidence: evidence.into(),
        }
    }

    /// Whether the user must fill it in.
    pub(crate) fn is_placeholder(&self) -> bool {
        self.ron.contains(PLACEHOLDER)
    }
}

/// A column named in the study file.
pub(crate) fn quoted(name: &str) -> String {
    format!("{name:?}")
}

/// A column's unit in words for the evidence.
pub(crate) fn unit_words(c: &Column) -> String {
    c.unit.as_deref().map_or_else(
        || " (no unit in the header)".to_owned(),
        |u| format!(" ({u})"),
    )
}
