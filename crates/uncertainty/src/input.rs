//! Input quantities and their validated set, with correlations.

use crate::error::{Result, UncertaintyError};
use crate::kind::{Distribution, Dof, Evaluation};

/// One input quantity `X_i` of a measurement model: its estimate, standard uncertainty,
/// degrees of freedom, evaluation type and, for the Monte Carlo method, its distribution.
#[derive(Debug, Clone, PartialEq)]
pub struct InputQuantity {
    /// Name, unique among the inputs (errors name the input by it).
    pub name: String,
    /// Estimate `x_i`.
    pub value: f64,
    /// Standard uncertainty `u(x_i) ≥ 0`.
    pub standard_uncertainty: f64,
    /// Degrees of freedom of `u(x_i)`.
    pub dof: Dof,
    /// Type A or Type B.
    pub kind: Evaluation,
    /// The distribution for the Monte Carlo method.
    pub distribution: Distribution,
}

impl InputQuantity {
    /// A Type A input: the mean `value` of `n` observations with `u = s/√n` and
    /// `dof = n − 1`. Its distribution is the scaled-and-shifted t (JCGM 101 §6.4.9), or
    /// normal for `Dof::Infinite`.
    pub fn type_a(
        name: impl Into<String>,
        value: f64,
        standard_uncertainty: f64,
        dof: Dof,
    ) -> Self {
        let distribution = match dof {
            Dof::Finite(_) => Distribution::StudentT,
            Dof::Infinite => Distribution::Normal,
        };
        InputQuantity {
            name: name.into(),
            value,
            standard_uncertainty,
            dof,
            kind: Evaluation::TypeA,
            distribution,
        }
    }

    /// A Type B input with a normal distribution and infinite degrees of freedom.
    pub fn normal(name: impl Into<String>, value: f64, standard_uncertainty: f64) -> Self {
        InputQuantity {
            name: name.into(),
            value,
            standard_uncertainty,
            dof: Dof::Infinite,
            kind: Evaluation::TypeB,
            distribution: Distribution::Normal,
        }
    }

    /// A Type B input known to lie in `[value − half_width, value + half_width]` with no
    /// other information: rectangular, `u = half_width/√3`, infinite degrees of freedom.
    pub fn rectangular(name: impl Into<String>, value: f64, half_width: f64) -> Self {
        InputQuantity {
            name: name.into(),
            value,
            standard_uncertainty: half_width / 3f64.sqrt(),
            dof: Dof::Infinite,
            kind: Evaluation::TypeB,
            distribution: Distribution::Rectangular,
        }
    }

    /// The same input with degrees of freedom `dof` (e.g. a Type B uncertainty judged reliable
    /// to some relative amount, JCGM 100 eq. G.3).
    pub fn with_dof(mut self, dof: Dof) -> Self {
        self.dof = dof;
        self
    }
}

/// A group of mutually correlated inputs (a connected component of the non-zero correlations;
/// a lone input is a group of one).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Group {
    /// Indices of the members, ascending.
    pub(crate) members: Vec<usize>,
    /// The members' common degrees of freedom.
    pub(crate) dof: Dof,
    /// Lower-triangular factor `L` (row-major, `k × k`) with `L·Lᵀ` = the members' correlation
    /// matrix (a semi-definite Cholesky factor: columns of zero pivots are zero).
    pub(crate) factor: Vec<f64>,
}

/// A validated set of input quantities, possibly correlated.
///
/// Built by [`Inputs::new`] or [`Inputs::with_correlation`], which check everything once:
/// finite values, finite non-negative uncertainties, positive degrees of freedom, distributions
/// consistent with the evaluation type, unique names, and a correlation matrix that is
/// symmetric, has a unit diagonal, entries in `[−1, 1]` and is positive semi-definite.
#[derive(Debug, Clone, PartialEq)]
pub struct Inputs {
    quantities: Vec<InputQuantity>,
    /// Row-major `n × n` correlation matrix (the identity when none was given).
    correlation: Vec<f64>,
    groups: Vec<Group>,
}

/// Pivots of the correlation matrix's Cholesky factorisation within this of zero are taken as
/// zero (a singular but positive semi-definite matrix, up to rounding); below it, an error.
const PIVOT_TOLERANCE: f64 = 1e-12;

impl Inputs {
    /// Uncorrelated inputs.
    pub fn new(quantities: Vec<InputQuantity>) -> Result<Self> {
        let n = quantities.len();
        let mut identity = vec![0.0; n * n];
        for i in 0..n {
            identity[i * n + i] = 1.0;
        }
        Self::with_correlation(quantities, &identity)
    }

    /// Inputs with the correlation matrix `correlation` (row-major, `n × n` for `n` inputs,
    /// `r(x_i, x_j) = correlation[i·n + j]`).
    ///
    /// Correlated inputs must share their degrees of freedom (they then act as one term of the
    /// Welch–Satterthwaite formula, exactly so for the coefficients of one least-squares fit,
    /// whose covariance is `s²·(AᵀA)⁻¹` with one `s²` of ν degrees of freedom).
    pub fn with_correlation(quantities: Vec<InputQuantity>, correlation: &[f64]) -> Result<Self> {
        let n = quantities.len();
        if n == 0 {
            return Err(UncertaintyError::NoInputs);
        }
        let mut seen = std::collections::HashSet::with_capacity(n);
        for (index, q) in quantities.iter().enumerate() {
            check_quantity(index, q)?;
            if !seen.insert(q.name.as_str()) {
                return Err(UncertaintyError::DuplicateName {
                    name: q.name.clone(),
                });
            }
        }
        if correlation.len() != n * n {
            return Err(UncertaintyError::CorrelationSize {
                inputs: n,
                got: correlation.len(),
                expected: n * n,
            });
        }
        let invalid = |i: usize, j: usize| UncertaintyError::InvalidCorrelation {
            first: quantities[i].name.clone(),
            second: quantities[j].name.clone(),
            value: correlation[i * n + j],
        };
        for i in 0..n {
            if correlation[i * n + i] != 1.0 {
                return Err(invalid(i, i));
            }
            for j in 0..i {
                let r = correlation[i * n + j];
                if r.is_nan() || r.abs() > 1.0 || r != correlation[j * n + i] {
                    return Err(invalid(i, j));
                }
            }
        }
        let groups = groups(&quantities, correlation)?;
        Ok(Inputs {
            quantities,
            correlation: correlation.to_vec(),
            groups,
        })
    }

    /// The input quantities, in model order.
    pub fn quantities(&self) -> &[InputQuantity] {
        &self.quantities
    }

    /// Number of inputs.
    pub fn len(&self) -> usize {
        self.quantities.len()
    }

    /// Always `false`: a validated set has at least one input.
    pub fn is_empty(&self) -> bool {
        self.quantities.is_empty()
    }

    /// The estimates `x`, in model order.
    pub fn values(&self) -> Vec<f64> {
        self.quantities.iter().map(|q| q.value).collect()
    }

    /// The correlation coefficient `r(x_i, x_j)`.
    ///
    /// # Panics
    /// If `i` or `j` is not below [`Inputs::len`].
    pub fn correlation(&self, i: usize, j: usize) -> f64 {
        let n = self.len();
        assert!(i < n && j < n, "input index out of range");
        self.correlation[i * n + j]
    }

    /// Whether any two inputs are correlated.
    pub fn is_correlated(&self) -> bool {
        self.groups.len() < self.len()
    }

    pub(crate) fn groups(&self) -> &[Group] {
        &self.groups
    }
}

fn check_quantity(index: usize, q: &InputQuantity) -> Result<()> {
    if q.name.is_empty() {
        return Err(UncertaintyError::EmptyName { index });
    }
    if !q.value.is_finite() {
        return Err(UncertaintyError::NonFiniteValue {
            input: q.name.clone(),
            value: q.value,
        });
    }
    let u = q.standard_uncertainty;
    if !(u.is_finite() && u >= 0.0) {
        return Err(UncertaintyError::InvalidStandardUncertainty {
            input: q.name.clone(),
            value: u,
        });
    }
    if let Dof::Finite(nu) = q.dof
        && !(nu.is_finite() && nu > 0.0)
    {
        return Err(UncertaintyError::InvalidDof {
            input: q.name.clone(),
            dof: nu,
        });
    }
    if q.distribution == Distribution::StudentT && q.dof == Dof::Infinite {
        return Err(UncertaintyError::StudentTNeedsFiniteDof {
            input: q.name.clone(),
        });
    }
    if q.kind == Evaluation::TypeA {
        let needed = match q.dof {
            Dof::Finite(_) => Distribution::StudentT,
            Dof::Infinite => Distribution::Normal,
        };
        if q.distribution != needed {
            return Err(UncertaintyError::TypeADistribution {
                input: q.name.clone(),
                distribution: q.distribution,
                dof: q.dof,
            });
        }
    }
    Ok(())
}

/// The connected components of the non-zero correlations, each with its common degrees of
/// freedom and the semi-definite Cholesky factor of its correlation block.
fn groups(quantities: &[InputQuantity], correlation: &[f64]) -> Result<Vec<Group>> {
    let n = quantities.len();
    let mut group_of: Vec<Option<usize>> = vec![None; n];
    let mut groups = Vec::new();
    for start in 0..n {
        if group_of[start].is_some() {
            continue;
        }
        let id = groups.len();
        let mut members = vec![start];
        group_of[start] = Some(id);
        let mut next = 0;
        while next < members.len() {
            let i = members[next];
            next += 1;
            for j in 0..n {
                if group_of[j].is_none() && correlation[i * n + j] != 0.0 {
                    group_of[j] = Some(id);
                    members.push(j);
                }
            }
        }
        members.sort_unstable();
        let first = &quantities[members[0]];
        for &m in &members[1..] {
            if quantities[m].dof != first.dof {
                return Err(UncertaintyError::CorrelatedDofMismatch {
                    first: first.name.clone(),
                    first_dof: first.dof,
                    second: quantities[m].name.clone(),
                    second_dof: quantities[m].dof,
                });
            }
        }
        let factor = semidefinite_cholesky(&members, correlation, n).map_err(|k| {
            UncertaintyError::CorrelationNotPositiveSemiDefinite {
                input: quantities[members[k]].name.clone(),
            }
        })?;
        groups.push(Group {
            members,
            dof: first.dof,
            factor,
        });
    }
    Ok(groups)
}

/// Cholesky factor `L` (row-major, `k × k`) of the correlation block of `members`, for a
/// positive semi-definite block: a pivot within [`PIVOT_TOLERANCE`] of zero gives a zero
/// column, provided the rest of that column of the Schur complement is negligible
/// (`|s_ij| ≤ √PIVOT_TOLERANCE`, as `s_ij² ≤ s_ii·s_jj` holds in a semi-definite matrix).
/// `Err(k)`: the block is not positive semi-definite, detected at member `k`.
fn semidefinite_cholesky(
    members: &[usize],
    correlation: &[f64],
    n: usize,
) -> std::result::Result<Vec<f64>, usize> {
    let k = members.len();
    let mut l = vec![0.0; k * k];
    for j in 0..k {
        let a = |r: usize, c: usize| correlation[members[r] * n + members[c]];
        let dot = |l: &[f64], r: usize, c: usize| -> f64 {
            (0..c).map(|m| l[r * k + m] * l[c * k + m]).sum()
        };
        let pivot = a(j, j) - dot(&l, j, j);
        if pivot < -PIVOT_TOLERANCE || pivot.is_nan() {
            return Err(j);
        }
        if pivot <= PIVOT_TOLERANCE {
            for i in j + 1..k {
                if (a(i, j) - dot(&l, i, j)).abs() > PIVOT_TOLERANCE.sqrt() {
                    return Err(j);
                }
            }
            continue;
        }
        let d = pivot.sqrt();
        l[j * k + j] = d;
        for i in j + 1..k {
            l[i * k + j] = (a(i, j) - dot(&l, i, j)) / d;
        }
    }
    Ok(l)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(name: &str) -> InputQuantity {
        InputQuantity::normal(name, 1.0, 0.1)
    }

    #[test]
    fn groups_are_connected_components() {
        let r = [
            1.0, 0.0, 0.5, 0.0, //
            0.0, 1.0, 0.0, 0.0, //
            0.5, 0.0, 1.0, -0.2, //
            0.0, 0.0, -0.2, 1.0,
        ];
        let inputs = Inputs::with_correlation(vec![q("a"), q("b"), q("c"), q("d")], &r).unwrap();
        let members: Vec<_> = inputs.groups().iter().map(|g| g.members.clone()).collect();
        assert_eq!(members, vec![vec![0, 2, 3], vec![1]]);
        // L·Lᵀ reproduces the block.
        let g = &inputs.groups()[0];
        for i in 0..3 {
            for j in 0..3 {
                let v: f64 = (0..3)
                    .map(|m| g.factor[i * 3 + m] * g.factor[j * 3 + m])
                    .sum();
                let want = r[g.members[i] * 4 + g.members[j]];
                assert!((v - want).abs() < 1e-15, "({i},{j}) {v} vs {want}");
            }
        }
    }

    #[test]
    fn singular_but_semidefinite_is_accepted() {
        // x2 = x1 exactly and x3 = −x1: rank one.
        let r = [1.0, 1.0, -1.0, 1.0, 1.0, -1.0, -1.0, -1.0, 1.0];
        let inputs = Inputs::with_correlation(vec![q("a"), q("b"), q("c")], &r).unwrap();
        let f = &inputs.groups()[0].factor;
        assert_eq!(f, &vec![1.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0]);
    }

    #[test]
    fn indefinite_is_refused_naming_the_input() {
        // Pairwise 0.9, 0.9, −0.9: no three variables can have these correlations.
        let r = [1.0, 0.9, 0.9, 0.9, 1.0, -0.9, 0.9, -0.9, 1.0];
        let err = Inputs::with_correlation(vec![q("a"), q("b"), q("c")], &r).unwrap_err();
        assert_eq!(
            err,
            UncertaintyError::CorrelationNotPositiveSemiDefinite { input: "c".into() }
        );
    }
}
