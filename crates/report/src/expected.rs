//! Regression checks: published or previously verified values with a tolerance each, compared
//! with a study's results. Only this module and the report read them; the study never does.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{ReportError, Result};
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
    /// Reads an expected-values file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| ReportError::Io {
            path: path.to_owned(),
            source,
        })?;
        ron::from_str(&text).map_err(|e| ReportError::Parse {
            path: path.to_owned(),
            line: e.span.start.line,
            column: e.span.start.col,
            message: e.code.to_string(),
        })
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
                    ["name", "phase"]
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
}
