//! Regression checks: published or previously verified values with a tolerance each, compared
//! with a study's results. Only this module and the report read them; the study never does.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{ReportError, Result};
use crate::provenance::FileRecord;
use pipeline::StudyResults;

/// A file of expected values (`fixtures/expected/*.ron`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expected {
    /// Where the values come from.
    pub source: String,
    /// The checks.
    pub checks: Vec<Check>,
}

/// One expected value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Check {
    /// Dotted path into `results.json`, e.g. `phases[post_balance].points[0].radius_error_um`:
    /// an index in brackets is a position in a list, or the `name` (or `phase`) of an element.
    pub path: String,
    /// The expected value.
    pub value: f64,
    /// Largest accepted absolute difference.
    pub tolerance: f64,
    /// What the value is (e.g. "paper Table 1", "two-term OLS standard error").
    pub note: String,
    /// `true` when the value is printed in the paper (shown beside ours in the report).
    #[serde(default)]
    pub published: bool,
    /// `false` for a value shown in the report but not checked (default `true`).
    #[serde(default = "yes")]
    pub regress: bool,
}

const fn yes() -> bool {
    true
}

/// The outcome of one check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckOutcome {
    /// The check.
    pub check: Check,
    /// The value found in the results (`None` when the path does not exist or is null).
    pub actual: Option<f64>,
    /// Whether `|actual − value| ≤ tolerance` (always `true` for a check with `regress: false`).
    pub passed: bool,
}

impl Expected {
    /// Reads and validates an expected-values file of at most
    /// [`edge_io::CONFIG_MAX_BYTES`] (16 MiB); a leading UTF-8 byte-order mark is ignored.
    ///
    /// # Errors
    /// [`ReportError::File`] when the file cannot be read, is above the cap or is not UTF-8;
    /// otherwise as [`Expected::parse`].
    pub fn load(path: &Path) -> Result<Self> {
        let text = edge_io::read_text_capped(path, edge_io::CONFIG_MAX_BYTES)?;
        Self::parse(&text, path)
    }

    /// [`Expected::load`], with the record of the file (size and SHA-256 of the bytes read)
    /// for the provenance of `results.json` ([`crate::Provenance::of_study`]); the file is
    /// read once.
    ///
    /// # Errors
    /// As [`Expected::load`].
    pub fn load_recorded(path: &Path) -> Result<(Self, FileRecord)> {
        let bytes = edge_io::read_bytes_capped(path, edge_io::CONFIG_MAX_BYTES)?;
        let record = FileRecord::read(path, &pipeline::FileDigest::of(&bytes));
        let text = edge_io::text_from_bytes(path, bytes)?;
        Ok((Self::parse(&text, path)?, record))
    }

    /// Parses and validates RON text; `path` only names the source in errors.
    ///
    /// # Errors
    /// [`ReportError::Parse`] for malformed RON, an unknown or a missing field; otherwise as
    /// [`Expected::validate`].
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let expected: Self = edge_io::from_ron(text, path).map_err(|e| ReportError::Parse {
            line: e.line,
            column: e.column,
            message: e.code.to_string(),
            path: e.path,
        })?;
        expected.validate(path)?;
        Ok(expected)
    }

    /// Checks that a regression against these values means something: every check has a
    /// well-formed results path, a finite value and a finite, non-negative tolerance; no two
    /// checks of the same kind (published, or not) share a path; and at least one check has
    /// `regress: true`. `path` names the file in errors.
    ///
    /// # Errors
    /// [`ReportError::InvalidCheckPath`], [`ReportError::InvalidCheckNumber`] or
    /// [`ReportError::DuplicateCheckPath`] naming the check by its index;
    /// [`ReportError::NoRegressionChecks`] when nothing would be checked.
    pub fn validate(&self, path: &Path) -> Result<()> {
        for (index, check) in self.checks.iter().enumerate() {
            if let Some(reason) = path_syntax_error(&check.path) {
                return Err(ReportError::InvalidCheckPath {
                    path: path.to_owned(),
                    index,
                    check_path: check.path.clone(),
                    reason,
                });
            }
            let number = |field: &str, value: f64, reason| ReportError::InvalidCheckNumber {
                path: path.to_owned(),
                field: format!("checks[{index}].{field}"),
                value,
                reason,
            };
            if !check.value.is_finite() {
                return Err(number("value", check.value, "not a finite number"));
            }
            if !check.tolerance.is_finite() {
                return Err(number(
                    "tolerance",
                    check.tolerance,
                    "not a finite number: the check would pass whatever the results",
                ));
            }
            if check.tolerance < 0.0 {
                return Err(number(
                    "tolerance",
                    check.tolerance,
                    "negative: the check could never pass",
                ));
            }
            if let Some(first) = self.checks[..index]
                .iter()
                .position(|c| c.path == check.path && c.published == check.published)
            {
                return Err(ReportError::DuplicateCheckPath {
                    path: path.to_owned(),
                    index,
                    first,
                    check_path: check.path.clone(),
                });
            }
        }
        if !self.checks.iter().any(|c| c.regress) {
            return Err(ReportError::NoRegressionChecks {
                path: path.to_owned(),
                checks: self.checks.len(),
            });
        }
        Ok(())
    }

    /// Compares every check with the results.
    pub fn compare(&self, results: &StudyResults) -> Result<Vec<CheckOutcome>> {
        let json = serde_json::to_value(results).map_err(|e| ReportError::Serialize {
            what: "results",
            message: e.to_string(),
        })?;
        Ok(self
            .checks
            .iter()
            .map(|check| {
                let actual = lookup(&json, &check.path);
                let passed = !check.regress
                    || actual.is_some_and(|a| (a - check.value).abs() <= check.tolerance);
                CheckOutcome {
                    check: check.clone(),
                    actual,
                    passed,
                }
            })
            .collect())
    }

    /// The published value at a results path, if the file has one.
    pub fn published(&self, path: &str) -> Option<f64> {
        self.checks
            .iter()
            .find(|c| c.published && c.path == path)
            .map(|c| c.value)
    }
}

/// What is wrong with a results path, if anything: it must be dot-separated keys, each
/// followed by any number of `[index]`es (`post_balance.points[0].amplitude_um`).
fn path_syntax_error(path: &str) -> Option<&'static str> {
    if path.is_empty() {
        return Some("empty");
    }
    for part in path.split('.') {
        let (key, mut indices) = part.split_at(part.find('[').unwrap_or(part.len()));
        if key.is_empty() {
            return Some("has a segment without a key");
        }
        if key.contains(']') {
            return Some("has a malformed `[index]`");
        }
        while !indices.is_empty() {
            let Some((index, rest)) = indices.strip_prefix('[').and_then(|r| r.split_once(']'))
            else {
                return Some("has a malformed `[index]`");
            };
            // A position, or the name of a list element (letters, digits, `_`, `-`).
            if index.is_empty()
                || !index
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
            {
                return Some("has a malformed `[index]`");
            }
            indices = rest;
        }
    }
    None
}

/// Resolves a dotted path with `[i]` indices in a JSON value to a number.
fn lookup(root: &serde_json::Value, path: &str) -> Option<f64> {
    let mut node = root;
    for part in path.split('.') {
        let (key, indices) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        node = node.get(key)?;
        for index in indices.split('[').skip(1) {
            let index = index.strip_suffix(']')?;
            node = match index.parse::<usize>() {
                Ok(i) => node.get(i)?,
                Err(_) => node.as_array()?.iter().find(|item| {
                    ["name", "phase", "label"]
                        .iter()
                        .any(|k| item.get(k).and_then(|v| v.as_str()) == Some(index))
                })?,
            };
        }
    }
    node.as_f64()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookup_follows_keys_and_indices() {
        let v: serde_json::Value =
            serde_json::from_str(r#"{"a": {"b": [1.5, {"c": 2.5}], "n": null}}"#).unwrap();
        assert_eq!(lookup(&v, "a.b[0]"), Some(1.5));
        assert_eq!(lookup(&v, "a.b[1].c"), Some(2.5));
        assert_eq!(lookup(&v, "a.b[2]"), None);
        assert_eq!(lookup(&v, "a.n"), None);
        assert_eq!(lookup(&v, "a.x"), None);
    }

    #[test]
    fn lookup_finds_list_elements_by_name() {
        let v: serde_json::Value = serde_json::from_str(
            r#"{"phases": [{"name": "pre", "c": 1.0}, {"name": "post", "c": 2.0}],
                "m": {"phases": [{"phase": "post", "k": 3.0}]}}"#,
        )
        .unwrap();
        assert_eq!(lookup(&v, "phases[post].c"), Some(2.0));
        assert_eq!(lookup(&v, "phases[pre].c"), Some(1.0));
        assert_eq!(lookup(&v, "m.phases[post].k"), Some(3.0));
        assert_eq!(lookup(&v, "phases[trial].c"), None);
    }

    #[test]
    fn path_syntax() {
        assert_eq!(path_syntax_error("phases[1].points[0].amplitude_um"), None);
        assert_eq!(path_syntax_error("a.b[1][2].c"), None);
        assert_eq!(path_syntax_error(""), Some("empty"));
        assert_eq!(
            path_syntax_error("a..b"),
            Some("has a segment without a key")
        );
        assert_eq!(
            path_syntax_error("a.[0]"),
            Some("has a segment without a key")
        );
        assert_eq!(path_syntax_error("phases[post_balance].c_r_m_s2"), None);
        for bad in ["a[", "a[]", "a[x y]", "a[0]b", "a[-1.5]", "a]"] {
            assert_eq!(
                path_syntax_error(bad),
                Some("has a malformed `[index]`"),
                "{bad}"
            );
        }
    }
}
