//! NIST Statistical Reference Datasets (StRD) for linear regression: a parser of the file
//! format and the log relative error (LRE) used to score a solver against the certified values.
//!
//! This module is support for the accuracy check (`cargo xtask accuracy` and the crate's
//! tests), public because the `xtask` binary needs it. It only parses text handed to it; reading
//! the files is the caller's job. It is not needed for calibration.
//!
//! An StRD file is a header that names the model (`y = B0 + B1*x + B2*(x**2) + …` or
//! `y = B0 + B1*x1 + … + B6*x6`) and gives the line ranges of two blocks: the certified values
//! (one line `Bk estimate std_dev` per parameter and a `Standard Deviation` line for the residual
//! standard deviation) and the data (`y x` or `y x1 … xp` per line).
//!
//! ```
//! use identify::strd;
//! approx::assert_abs_diff_eq!(strd::lre(1.000_000_1, 1.0), 7.0, epsilon = 1e-6);
//! assert_eq!(strd::lre(2.0, 2.0), strd::MAX_LRE);
//! ```

use crate::dd::Dd;
use crate::design::{Design, power};
use crate::error::Result;
use crate::lstsq::{Fit, LstsqOptions, lstsq_design};

/// LREs are capped here: NIST certifies 15 significant digits.
pub const MAX_LRE: f64 = 15.0;

/// Log relative error `−log10(|estimate − certified| / |certified|)`, the number of correct
/// significant digits; `−log10(|estimate|)` (log absolute error) when the certified value is 0,
/// as in NIST's usage. Capped at [`MAX_LRE`]; `0` for a non-finite estimate.
#[must_use]
pub fn lre(estimate: f64, certified: f64) -> f64 {
    if !estimate.is_finite() {
        return 0.0;
    }
    let error = if certified == 0.0 {
        estimate.abs()
    } else {
        (estimate - certified).abs() / certified.abs()
    };
    if error == 0.0 {
        MAX_LRE
    } else {
        (-error.log10()).min(MAX_LRE)
    }
}

/// One term of the model: a column of the design.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Term {
    /// The constant column (B0).
    Intercept,
    /// `x_p^e`: predictor `predictor` (index into [`Dataset::predictors`]) to the power
    /// `exponent`.
    Power {
        /// Index of the predictor.
        predictor: usize,
        /// Exponent (≥ 1).
        exponent: u32,
    },
}

/// A certified parameter: estimate and its standard deviation.
#[derive(Debug, Clone, PartialEq)]
pub struct CertifiedParameter {
    /// Parameter name as in the file (`B0`, `B1`, …).
    pub name: String,
    /// Certified estimate.
    pub estimate: f64,
    /// Certified standard deviation of the estimate.
    pub std_dev: f64,
}

/// A parsed StRD linear-regression dataset.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// Dataset name (`Filip`, `Longley`, …).
    pub name: String,
    /// Predictor names from the data header (`x`, or `x1` … `x6`).
    pub predictors: Vec<String>,
    /// Model terms, one per certified parameter and in the same order.
    pub terms: Vec<Term>,
    /// Certified parameters.
    pub certified: Vec<CertifiedParameter>,
    /// Certified residual standard deviation.
    pub certified_residual_sd: f64,
    /// Responses.
    pub y: Vec<f64>,
    /// Predictor values, `x[observation][predictor]`.
    pub x: Vec<Vec<f64>>,
}

/// Accuracy of a fit against a dataset's certified values.
#[derive(Debug, Clone, PartialEq)]
pub struct Accuracy {
    /// Dataset name.
    pub name: String,
    /// Minimum LRE over the coefficients.
    pub min_lre_coef: f64,
    /// Minimum LRE over the standard errors.
    pub min_lre_se: f64,
    /// LRE of the residual standard deviation.
    pub lre_residual_sd: f64,
    /// The fit that was scored.
    pub fit: Fit,
}

/// What an StRD file lacks or holds malformed ([`StrdError`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Expected {
    /// A `Dataset Name:` line.
    DatasetName,
    /// `Certified Values (lines A to B)` in the header.
    CertifiedValuesRange,
    /// `Data (lines A to B)` in the header.
    DataRange,
    /// Line ranges that lie inside the file.
    RangesInsideFile,
    /// `Data:` followed by the column names.
    DataHeader,
    /// Column names `y x…`.
    ColumnNames,
    /// A model line `y = …` in the header.
    ModelLine,
    /// Model terms `Bk`, `Bk*x` or `Bk*(x**p)`.
    ModelTerms,
    /// A certified parameter line `Bk estimate std_dev` with two numbers.
    ParameterLine,
    /// A residual `Standard Deviation` value.
    ResidualStandardDeviation,
    /// Certified parameters `Bk estimate std_dev`.
    CertifiedParameters,
    /// A model term for every certified parameter.
    TermPerParameter,
    /// As many model terms as certified parameters.
    TermCount,
    /// One finite number per data column on a data line.
    DataRow,
}

impl core::fmt::Display for Expected {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::DatasetName => "a `Dataset Name:` line",
            Self::CertifiedValuesRange => "`Certified Values (lines A to B)` in the header",
            Self::DataRange => "`Data (lines A to B)` in the header",
            Self::RangesInsideFile => "line ranges inside the file",
            Self::DataHeader => "`Data:` followed by the column names",
            Self::ColumnNames => "column names `y x…`",
            Self::ModelLine => "a model line `y = …` in the header",
            Self::ModelTerms => "model terms `Bk`, `Bk*x` or `Bk*(x**p)`",
            Self::ParameterLine => "`Bk estimate std_dev` with two numbers",
            Self::ResidualStandardDeviation => "a residual `Standard Deviation` value",
            Self::CertifiedParameters => "certified parameters `Bk estimate std_dev`",
            Self::TermPerParameter => "a model term for every certified parameter",
            Self::TermCount => "as many model terms as certified parameters",
            Self::DataRow => "one finite number per data column",
        })
    }
}

/// An StRD file that does not have the expected layout: the parser's own error, apart from
/// the solver's [`IdentifyError`](crate::IdentifyError) (a file is not a least-squares problem).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("StRD file{}: expected {expected}", match line { Some(l) => format!(", line {l}"), None => String::new() })]
pub struct StrdError {
    /// 1-based line at fault, or `None` when something is missing from the whole file.
    pub line: Option<usize>,
    /// What was expected.
    pub expected: Expected,
}

fn format_error(line: usize, expected: Expected) -> StrdError {
    StrdError {
        line: Some(line),
        expected,
    }
}

fn missing(expected: Expected) -> StrdError {
    StrdError {
        line: None,
        expected,
    }
}

/// `(lines A to B)` in a header line → (A, B), 1-based inclusive.
fn line_range(line: &str) -> Option<(usize, usize)> {
    let start = line.find("(lines")?;
    let inner = line[start + 6..].split(')').next()?;
    let mut it = inner.split_whitespace();
    let a = it.next()?.parse().ok()?;
    (it.next()? == "to").then_some(())?;
    let b = it.next()?.parse().ok()?;
    Some((a, b))
}

/// Parses the text of an StRD linear-regression file.
///
/// # Errors
/// [`StrdError`] naming the 1-based line (when one is at fault) and what was expected there.
pub fn parse(text: &str) -> std::result::Result<Dataset, StrdError> {
    let lines: Vec<&str> = text.lines().collect();
    let name = lines
        .iter()
        .find_map(|l| l.trim().strip_prefix("Dataset Name:"))
        .and_then(|rest| rest.split_whitespace().next())
        .ok_or_else(|| missing(Expected::DatasetName))?
        .to_string();

    let mut certified_range = None;
    let mut data_range = None;
    for line in &lines {
        if let Some(range) = line_range(line) {
            if line.contains("Certified Values") {
                certified_range = Some(range);
            } else if line.contains("Data") {
                data_range = Some(range);
            }
        }
    }
    let (c0, c1) = certified_range.ok_or_else(|| missing(Expected::CertifiedValuesRange))?;
    let (d0, d1) = data_range.ok_or_else(|| missing(Expected::DataRange))?;
    if c0 == 0 || d0 < 2 || c1 < c0 || d1 < d0 || c1 > lines.len() || d1 > lines.len() {
        return Err(missing(Expected::RangesInsideFile));
    }

    // Data header, e.g. `Data:  y  x1  x2`, on the line before the data block.
    let header_index = d0 - 2;
    let header = lines[header_index]
        .trim()
        .strip_prefix("Data:")
        .ok_or_else(|| format_error(header_index + 1, Expected::DataHeader))?;
    let columns: Vec<&str> = header.split_whitespace().collect();
    if columns.first() != Some(&"y") || columns.len() < 2 {
        return Err(format_error(header_index + 1, Expected::ColumnNames));
    }
    let predictors: Vec<String> = columns[1..].iter().map(|s| (*s).to_string()).collect();

    // Model line `y = …` before the certified block.
    let (model_index, model) = lines[..c0 - 1]
        .iter()
        .enumerate()
        .find_map(|(i, l)| l.trim().strip_prefix("y =").map(|m| (i, m)))
        .ok_or_else(|| missing(Expected::ModelLine))?;
    let bad_model = || format_error(model_index + 1, Expected::ModelTerms);
    let mut named_terms: Vec<(String, Term)> = Vec::new();
    let mut ellipsis = false;
    for part in model.split('+') {
        let part = part.trim();
        if part == "e" || part.is_empty() {
            continue;
        }
        if part == "..." {
            ellipsis = true;
            continue;
        }
        let term = parse_term(part, &predictors).ok_or_else(bad_model)?;
        if std::mem::take(&mut ellipsis) {
            // `B2*(x**2) + ... + B9*(x**9)`: fill in the powers between.
            let filled = named_terms
                .last()
                .and_then(|previous| fill_ellipsis(previous, &term))
                .ok_or_else(bad_model)?;
            named_terms.extend(filled);
        }
        named_terms.push(term);
    }

    // Certified block.
    let mut certified = Vec::new();
    let mut certified_residual_sd = None;
    for (offset, line) in lines[c0 - 1..c1].iter().enumerate() {
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let is_parameter = tokens.first().is_some_and(|t| {
            t.len() > 1 && t.starts_with('B') && t[1..].chars().all(|c| c.is_ascii_digit())
        });
        if is_parameter {
            let (estimate, std_dev) = match tokens.as_slice() {
                [_, e, s] => (e.parse::<f64>().ok(), s.parse::<f64>().ok()),
                _ => (None, None),
            };
            match (estimate, std_dev) {
                (Some(estimate), Some(std_dev)) => certified.push(CertifiedParameter {
                    name: tokens[0].to_string(),
                    estimate,
                    std_dev,
                }),
                _ => {
                    return Err(format_error(c0 + offset, Expected::ParameterLine));
                }
            }
        } else if let Some(rest) = line.trim().strip_prefix("Standard Deviation")
            && let Ok(v) = rest.trim().parse::<f64>()
        {
            certified_residual_sd.get_or_insert(v);
        }
    }
    let certified_residual_sd =
        certified_residual_sd.ok_or_else(|| missing(Expected::ResidualStandardDeviation))?;
    if certified.is_empty() {
        return Err(missing(Expected::CertifiedParameters));
    }

    // Order the model terms as the certified parameters.
    let mut terms = Vec::with_capacity(certified.len());
    for p in &certified {
        let term = named_terms
            .iter()
            .find(|(n, _)| *n == p.name)
            .map(|(_, t)| *t)
            .ok_or_else(|| format_error(model_index + 1, Expected::TermPerParameter))?;
        terms.push(term);
    }
    if named_terms.len() != certified.len() {
        return Err(format_error(model_index + 1, Expected::TermCount));
    }

    // Data block.
    let mut y = Vec::with_capacity(d1 - d0 + 1);
    let mut x = Vec::with_capacity(d1 - d0 + 1);
    for (offset, line) in lines[d0 - 1..d1].iter().enumerate() {
        let values: Option<Vec<f64>> = line
            .split_whitespace()
            .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect();
        match values {
            Some(v) if v.len() == columns.len() => {
                y.push(v[0]);
                x.push(v[1..].to_vec());
            }
            _ => {
                return Err(format_error(d0 + offset, Expected::DataRow));
            }
        }
    }

    Ok(Dataset {
        name,
        predictors,
        terms,
        certified,
        certified_residual_sd,
        y,
        x,
    })
}

/// The terms elided by `...` between two powers of the same predictor whose parameter indices
/// advance with the exponent (`B2*(x**2) + ... + B5*(x**5)` → B3, B4).
fn fill_ellipsis(before: &(String, Term), after: &(String, Term)) -> Option<Vec<(String, Term)>> {
    let index = |name: &str| name[1..].parse::<u32>().ok();
    match (before.1, after.1) {
        (
            Term::Power {
                predictor: p0,
                exponent: e0,
            },
            Term::Power {
                predictor: p1,
                exponent: e1,
            },
        ) if p0 == p1 && e1 > e0 => {
            let (k0, k1) = (index(&before.0)?, index(&after.0)?);
            (k1.checked_sub(k0)? == e1 - e0).then(|| {
                (1..e1 - e0)
                    .map(|d| {
                        (
                            format!("B{}", k0 + d),
                            Term::Power {
                                predictor: p0,
                                exponent: e0 + d,
                            },
                        )
                    })
                    .collect()
            })
        }
        _ => None,
    }
}

/// `Bk`, `Bk*x1`, `Bk*(x**p)` → (name, term).
fn parse_term(part: &str, predictors: &[String]) -> Option<(String, Term)> {
    let (coef, rest) = match part.split_once('*') {
        Some((c, r)) => (c.trim(), Some(r.trim())),
        None => (part, None),
    };
    if !(coef.len() > 1 && coef.starts_with('B') && coef[1..].chars().all(|c| c.is_ascii_digit())) {
        return None;
    }
    let term = match rest {
        None => Term::Intercept,
        Some(r) => {
            let r = r.trim_start_matches('(').trim_end_matches(')');
            let (var, exponent) = match r.split_once("**") {
                Some((v, e)) => (v.trim(), e.trim().parse::<u32>().ok()?),
                None => (r.trim(), 1),
            };
            let predictor = predictors.iter().position(|p| p == var)?;
            if exponent == 0 {
                return None;
            }
            Term::Power {
                predictor,
                exponent,
            }
        }
    };
    Some((coef.to_string(), term))
}

impl Dataset {
    /// The design, one column per term, held in double-double: powers of the predictors are
    /// formed in double-double so that the fit is that of the exact design of the data.
    #[must_use]
    pub fn design(&self) -> Design {
        Design::from_dd_fn(self.y.len(), self.terms.len(), |i, j| match self.terms[j] {
            Term::Intercept => Dd::from_f64(1.0),
            Term::Power {
                predictor,
                exponent,
            } => power(self.x[i][predictor], exponent),
        })
    }

    /// Fits the dataset with [`lstsq_design`] and scores the result against the certified values.
    ///
    /// # Errors
    /// Those of [`lstsq_design`].
    pub fn check(&self, options: &LstsqOptions) -> Result<Accuracy> {
        Ok(self.score(lstsq_design(&self.design(), &self.y, options)?))
    }

    /// Scores a fit of this dataset (coefficients in the order of [`Dataset::certified`])
    /// against the certified values.
    #[must_use]
    pub fn score(&self, fit: Fit) -> Accuracy {
        let min_lre_coef = self
            .certified
            .iter()
            .zip(&fit.coefficients)
            .map(|(c, b)| lre(*b, c.estimate))
            .fold(MAX_LRE, f64::min);
        let min_lre_se = self
            .certified
            .iter()
            .zip(&fit.std_errors)
            .map(|(c, s)| lre(*s, c.std_dev))
            .fold(MAX_LRE, f64::min);
        let lre_residual_sd = lre(fit.residual_sd, self.certified_residual_sd);
        Accuracy {
            name: self.name.clone(),
            min_lre_coef,
            min_lre_se,
            lre_residual_sd,
            fit,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A miniature file in the StRD layout (y = 1 + 2x through three points, exact).
    pub(crate) fn tiny() -> String {
        let mut lines = vec![String::new(); 40];
        lines[0] = "NIST/ITL StRD".into();
        lines[1] = "Dataset Name:  Tiny (Tiny.dat)".into();
        lines[4] = "               Certified Values  (lines 10 to 16)".into();
        lines[5] = "               Data              (lines 21 to 23)".into();
        lines[7] = "               y = B0 + B1*x + e".into();
        lines[9] = "                          Standard Deviation".into();
        lines[10] = "     Parameter   Estimate   of Estimate".into();
        lines[11] = "        B0        1.00000000000000   0.0".into();
        lines[12] = "        B1        0.200000000000000E+01   0.0".into();
        lines[13] = "     Residual".into();
        lines[14] = "     Standard Deviation   0.0".into();
        lines[19] = "Data:   y   x".into();
        lines[20] = "   1   0".into();
        lines[21] = "   3   1".into();
        lines[22] = "   5   2".into();
        lines.truncate(23);
        lines.join("\n")
    }

    #[test]
    fn parses_the_layout() {
        let d = parse(&tiny()).unwrap();
        assert_eq!(d.name, "Tiny");
        assert_eq!(d.predictors, vec!["x".to_string()]);
        assert_eq!(
            d.terms,
            vec![
                Term::Intercept,
                Term::Power {
                    predictor: 0,
                    exponent: 1
                }
            ]
        );
        assert_eq!(d.certified[1].estimate, 2.0);
        assert_eq!(d.y, vec![1.0, 3.0, 5.0]);
        let a = d.check(&LstsqOptions::default()).unwrap();
        assert_eq!(a.min_lre_coef, MAX_LRE);
        assert!(a.lre_residual_sd >= 14.0);
    }

    #[test]
    fn powers_and_multiple_predictors() {
        let predictors = vec!["x1".to_string(), "x2".to_string()];
        assert_eq!(
            parse_term("B2*(x2**3)", &predictors),
            Some((
                "B2".to_string(),
                Term::Power {
                    predictor: 1,
                    exponent: 3
                }
            ))
        );
        assert_eq!(parse_term("B2*z", &predictors), None);
        assert_eq!(parse_term("C2", &predictors), None);
    }

    #[test]
    fn bad_data_line_is_located() {
        let text = tiny().replace("   3   1", "   3   one");
        assert_eq!(
            parse(&text),
            Err(StrdError {
                line: Some(22),
                expected: Expected::DataRow
            })
        );
        assert!(matches!(
            parse("nothing here"),
            Err(StrdError { line: None, .. })
        ));
        // A data block said to start on line 1 leaves no room for its `Data:` header.
        let text = tiny().replace("(lines 21 to 23)", "(lines 1 to 23)");
        assert!(matches!(parse(&text), Err(StrdError { line: None, .. })));
    }

    #[test]
    fn lre_conventions() {
        assert_eq!(lre(0.0, 0.0), MAX_LRE);
        assert!((lre(1e-9, 0.0) - 9.0).abs() < 1e-12);
        assert_eq!(lre(f64::NAN, 1.0), 0.0);
        assert!((lre(1.01, 1.0) - 2.0).abs() < 1e-9);
    }
}
