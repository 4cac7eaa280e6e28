//! Design matrices whose entries are known beyond double precision.

use nalgebra::DMatrix;

use crate::dd::Dd;
use crate::error::{IdentifyError, Requirement, Result};

/// A least-squares design matrix X (m observations × n unknowns) whose entries are held in
/// double-double precision.
///
/// The solver ([`crate::lstsq_design`]) refines its solution with residuals `y − X·β` evaluated
/// in double-double; holding X to that precision makes the result the least-squares solution for
/// the *exact* design built from the given data, not for a copy of it rounded to doubles. This
/// matters for ill-conditioned polynomial designs: rounding each power `x^k` to a double is a
/// perturbation of relative size 1e-16 per entry, which a condition number of 5e9 (NIST's Filip,
/// column-scaled) turns into errors near 1e-7 in the coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    m: usize,
    n: usize,
    /// Column-major high parts.
    hi: Vec<f64>,
    /// Column-major low parts.
    lo: Vec<f64>,
}

impl Design {
    /// A design whose entries are exactly the given doubles.
    #[must_use]
    pub fn from_matrix(x: &DMatrix<f64>) -> Self {
        let (m, n) = x.shape();
        Self {
            m,
            n,
            hi: x.as_slice().to_vec(),
            lo: vec![0.0; m * n],
        }
    }

    /// Monomials of one variable: column j is `x^exponents[j]` (exponent 0 is the constant
    /// column), formed in double-double.
    ///
    /// ```
    /// use identify::Design;
    /// let d = Design::powers(&[1.0, 2.0, 3.0], &[0, 1, 3]);
    /// assert_eq!(d.to_matrix()[(2, 2)], 27.0);
    /// ```
    #[must_use]
    pub fn powers(x: &[f64], exponents: &[u32]) -> Self {
        Self::from_dd_fn(x.len(), exponents.len(), |i, j| power(x[i], exponents[j]))
    }

    /// Polynomials of one variable, one per entry: entry (i, j) is `Σ c·x_i^p` over the
    /// pairs `(c, p)` that `terms(i, j)` gives, each power formed and the sum taken in
    /// double-double. A design whose columns are polynomials in the rate with coefficients
    /// that differ between groups of rows (the mountings of a joint fit) is held as exactly
    /// as [`Design::powers`] holds monomials; a single pair `(c, p)` is
    /// `Design::powers(x, &[p]).scale_columns(&[c])` bit for bit.
    ///
    /// ```
    /// use identify::Design;
    /// let d = Design::polynomials(&[2.0, 3.0], 1, |i, _| {
    ///     if i == 0 { vec![(1.0, 0), (0.5, 2)] } else { vec![(-1.0, 3)] }
    /// })?;
    /// assert_eq!(d.to_matrix()[(0, 0)], 3.0);
    /// assert_eq!(d.to_matrix()[(1, 0)], -27.0);
    /// # Ok::<(), identify::IdentifyError>(())
    /// ```
    ///
    /// # Errors
    /// [`IdentifyError::InvalidParameter`] for a non-finite `x` or coefficient, or an entry
    /// that overflows (`name: "polynomial"`).
    pub fn polynomials(
        x: &[f64],
        n: usize,
        terms: impl Fn(usize, usize) -> Vec<(f64, u32)>,
    ) -> Result<Self> {
        let mut bad = None;
        let d = Self::from_dd_fn(x.len(), n, |i, j| {
            let mut sum = Dd::ZERO;
            for (c, p) in terms(i, j) {
                if !(c.is_finite() && x[i].is_finite()) {
                    bad.get_or_insert(if c.is_finite() { x[i] } else { c });
                }
                sum += power(x[i], p).mul_f64(c);
            }
            if !sum.hi.is_finite() {
                bad.get_or_insert(sum.hi);
            }
            sum
        });
        match bad {
            None => Ok(d),
            Some(value) => Err(IdentifyError::InvalidParameter {
                name: "polynomial",
                value,
                requirement: Requirement::Finite,
            }),
        }
    }

    /// Multiplies column j by `factors[j]` (in double-double), e.g. to turn a column `ω⁴` into
    /// `(R/g)²·ω⁴`.
    ///
    /// # Errors
    /// [`IdentifyError::DimensionMismatch`] when `factors.len()` is not the number of columns,
    /// [`IdentifyError::InvalidParameter`] for a non-finite factor.
    pub fn scale_columns(mut self, factors: &[f64]) -> Result<Self> {
        if factors.len() != self.n {
            return Err(IdentifyError::DimensionMismatch {
                what: "column factors",
                got: factors.len(),
                expected: self.n,
            });
        }
        for (j, &f) in factors.iter().enumerate() {
            if !f.is_finite() {
                return Err(IdentifyError::InvalidParameter {
                    name: "factors",
                    value: f,
                    requirement: Requirement::Finite,
                });
            }
            for i in 0..self.m {
                let k = j * self.m + i;
                let v = Dd {
                    hi: self.hi[k],
                    lo: self.lo[k],
                }
                .mul_f64(f);
                self.hi[k] = v.hi;
                self.lo[k] = v.lo;
            }
        }
        Ok(self)
    }

    /// Multiplies row i by `factors[i]` (in double-double), e.g. by `1/σᵢ` for a weighted
    /// fit.
    ///
    /// # Errors
    /// [`IdentifyError::DimensionMismatch`] when `factors.len()` is not the number of rows,
    /// [`IdentifyError::InvalidParameter`] for a non-finite factor.
    pub fn scale_rows(mut self, factors: &[f64]) -> Result<Self> {
        if factors.len() != self.m {
            return Err(IdentifyError::DimensionMismatch {
                what: "row factors",
                got: factors.len(),
                expected: self.m,
            });
        }
        if let Some(&f) = factors.iter().find(|f| !f.is_finite()) {
            return Err(IdentifyError::InvalidParameter {
                name: "factors",
                value: f,
                requirement: Requirement::Finite,
            });
        }
        for j in 0..self.n {
            for (i, &f) in factors.iter().enumerate() {
                let k = j * self.m + i;
                let v = Dd {
                    hi: self.hi[k],
                    lo: self.lo[k],
                }
                .mul_f64(f);
                self.hi[k] = v.hi;
                self.lo[k] = v.lo;
            }
        }
        Ok(self)
    }

    /// Number of observations (rows).
    #[must_use]
    pub const fn nrows(&self) -> usize {
        self.m
    }

    /// Number of unknowns (columns).
    #[must_use]
    pub const fn ncols(&self) -> usize {
        self.n
    }

    /// The design rounded to doubles.
    #[must_use]
    pub fn to_matrix(&self) -> DMatrix<f64> {
        DMatrix::from_fn(self.m, self.n, |i, j| self.entry(i, j).to_f64())
    }

    /// Builds a design from double-double entries.
    pub(crate) fn from_dd_fn(m: usize, n: usize, mut f: impl FnMut(usize, usize) -> Dd) -> Self {
        let mut hi = vec![0.0; m * n];
        let mut lo = vec![0.0; m * n];
        for j in 0..n {
            for i in 0..m {
                let v = f(i, j);
                hi[j * m + i] = v.hi;
                lo[j * m + i] = v.lo;
            }
        }
        Self { m, n, hi, lo }
    }

    /// Entry (i, j).
    pub(crate) fn entry(&self, i: usize, j: usize) -> Dd {
        let k = j * self.m + i;
        Dd {
            hi: self.hi[k],
            lo: self.lo[k],
        }
    }

    /// Column j's high parts.
    pub(crate) fn column_hi(&self, j: usize) -> &[f64] {
        &self.hi[j * self.m..(j + 1) * self.m]
    }
}

/// `x^e` in double-double by binary powering.
pub(crate) fn power(x: f64, e: u32) -> Dd {
    let mut result = Dd::from_f64(1.0);
    let mut base = Dd::from_f64(x);
    let mut e = e;
    while e > 0 {
        if e & 1 == 1 {
            result = result * base;
        }
        e >>= 1;
        if e > 0 {
            base = base * base;
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_carry_the_bits_a_double_drops() {
        // (1 + 2⁻³⁰)³ = 1 + 3·2⁻³⁰ + 3·2⁻⁶⁰ + 2⁻⁹⁰: a double keeps 1 + 3·2⁻³⁰ only.
        let x = 1.0 + 2f64.powi(-30);
        let p = power(x, 3);
        let rest = p - Dd::from_f64(1.0 + 3.0 * 2f64.powi(-30));
        assert!((rest.to_f64() - 3.0 * 2f64.powi(-60)).abs() < 2f64.powi(-85));
        assert_eq!(power(-2.0, 0).to_f64(), 1.0);
        assert_eq!(power(-2.0, 5).to_f64(), -32.0);
    }

    #[test]
    fn scaling_columns() {
        let d = Design::powers(&[2.0, 3.0], &[1, 2])
            .scale_columns(&[0.5, 3.0])
            .unwrap();
        assert_eq!(
            d.to_matrix(),
            DMatrix::from_row_slice(2, 2, &[1.0, 12.0, 1.5, 27.0])
        );
        assert!(matches!(
            Design::powers(&[2.0], &[1]).scale_columns(&[1.0, 2.0]),
            Err(IdentifyError::DimensionMismatch { .. })
        ));
        assert!(matches!(
            Design::powers(&[2.0], &[1]).scale_columns(&[f64::NAN]),
            Err(IdentifyError::InvalidParameter { .. })
        ));
    }
}
