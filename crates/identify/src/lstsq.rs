//! General linear least squares through column-pivoted Householder QR of the column-scaled
//! design.

// Index loops mirror the matrix formulas of the algorithms.
#![allow(clippy::needless_range_loop)]

use nalgebra::DMatrix;

use crate::error::{IdentifyError, Result};

/// Which numerical method produced a [`Fit`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum SolverPath {
    /// Column scaling to unit 2-norm, then column-pivoted Householder QR (faer) in double
    /// precision; no refinement.
    ScaledColPivQr,
}

/// Options for [`lstsq_with`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct LstsqOptions {
    /// Relative rank tolerance τ: the column-scaled design is declared rank deficient when a
    /// diagonal entry of the column-pivoted R satisfies `|R_kk| ≤ τ·|R_00|`.
    /// `None` selects the default `max(m, n)·ε` (ε = `f64::EPSILON`).
    pub rank_tolerance: Option<f64>,
}

/// Result of a least-squares fit `y ≈ X·β`.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// Estimated coefficients β, in the order of the design's columns.
    pub coefficients: Vec<f64>,
    /// Covariance of β, `s²·(XᵀX)⁻¹`, computed from the QR factor as
    /// `s²·D⁻¹P·R⁻¹R⁻ᵀ·PᵀD⁻¹` (never by inverting the normal equations).
    pub covariance: DMatrix<f64>,
    /// Standard errors, the square roots of the covariance diagonal.
    pub std_errors: Vec<f64>,
    /// Residuals `y − X·β`.
    pub residuals: Vec<f64>,
    /// Residual standard deviation `s = sqrt(Σr²/dof)`.
    pub residual_sd: f64,
    /// Residual degrees of freedom, observations − unknowns.
    pub dof: usize,
    /// 2-norm condition number (ratio of extreme singular values) of the **column-scaled**
    /// design `X·D⁻¹` (each column divided by its 2-norm), which is the matrix actually
    /// factorised. Column scaling is a reparametrisation, so this is the conditioning that
    /// limits the solver, not the (often much larger) condition number of the raw design.
    pub condition_number: f64,
    /// Relative rank tolerance τ that was applied to the diagonal of R (see
    /// [`LstsqOptions::rank_tolerance`]).
    pub rank_tolerance: f64,
    /// Column norms `D` used for the scaling (1 for an all-zero column, which is then reported
    /// as rank deficient).
    pub column_scale: Vec<f64>,
    /// Which method was taken.
    pub path: SolverPath,
}

/// Least squares `min ‖y − X·β‖₂` with default [`LstsqOptions`].
///
/// The design is scaled to unit column norms, factorised by column-pivoted Householder QR, and
/// the solution and covariance are mapped back through the scaling. The covariance is
/// `s²·(XᵀX)⁻¹` with `s² = Σr²/(m − n)`.
///
/// $$ \hat\beta = D^{-1} P R^{-1} Q^\top y, \qquad
///    \operatorname{Cov}\hat\beta = s^2 D^{-1} P R^{-1} R^{-\top} P^\top D^{-1} $$
///
/// # Errors
/// [`IdentifyError::NoUnknowns`], [`IdentifyError::DimensionMismatch`] (rows ≠ `y.len()`),
/// [`IdentifyError::TooFewObservations`] (needs rows > columns),
/// [`IdentifyError::NonFinite`], [`IdentifyError::RankDeficient`].
///
/// # Example
/// ```
/// use approx::assert_relative_eq;
/// // y = 1 + 2x exactly: the fit recovers the line and the residuals vanish.
/// let x = [0.0_f64, 1.0, 2.0, 3.0];
/// let design = nalgebra::DMatrix::from_fn(4, 2, |i, j| x[i].powi(j as i32));
/// let y: Vec<f64> = x.iter().map(|x| 1.0 + 2.0 * x).collect();
/// let fit = identify::lstsq(&design, &y)?;
/// assert_relative_eq!(fit.coefficients[0], 1.0, max_relative = 1e-14);
/// assert_relative_eq!(fit.coefficients[1], 2.0, max_relative = 1e-14);
/// assert!(fit.residual_sd < 1e-14);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
pub fn lstsq(design: &DMatrix<f64>, y: &[f64]) -> Result<Fit> {
    lstsq_with(design, y, &LstsqOptions::default())
}

/// [`lstsq`] with explicit options.
///
/// # Errors
/// As [`lstsq`]; also [`IdentifyError::InvalidParameter`] for a rank tolerance that is not a
/// finite number in `[0, 1)`.
pub fn lstsq_with(design: &DMatrix<f64>, y: &[f64], options: &LstsqOptions) -> Result<Fit> {
    let (m, n) = design.shape();
    validate(design, y)?;
    let tau = match options.rank_tolerance {
        None => m.max(n) as f64 * f64::EPSILON,
        Some(t) if t.is_finite() && (0.0..1.0).contains(&t) => t,
        Some(t) => {
            return Err(IdentifyError::InvalidParameter {
                name: "rank_tolerance",
                value: t,
                requirement: "finite and in [0, 1)",
            });
        }
    };

    let qr = ScaledQr::new(design, tau)?;
    let beta = qr.solve(y);
    let residuals: Vec<f64> = (0..m)
        .map(|i| y[i] - (0..n).map(|j| design[(i, j)] * beta[j]).sum::<f64>())
        .collect();
    let dof = m - n;
    let ssr: f64 = residuals.iter().map(|r| r * r).sum();
    let s2 = ssr / dof as f64;
    let covariance = qr.unscaled_inverse_gram().scale(s2);
    let std_errors = (0..n).map(|j| covariance[(j, j)].sqrt()).collect();

    Ok(Fit {
        coefficients: beta,
        covariance,
        std_errors,
        residuals,
        residual_sd: s2.sqrt(),
        dof,
        condition_number: qr.condition_number(),
        rank_tolerance: tau,
        column_scale: qr.scale.clone(),
        path: SolverPath::ScaledColPivQr,
    })
}

/// Checks shapes and finiteness.
fn validate(design: &DMatrix<f64>, y: &[f64]) -> Result<()> {
    let (m, n) = design.shape();
    if n == 0 {
        return Err(IdentifyError::NoUnknowns);
    }
    if y.len() != m {
        return Err(IdentifyError::DimensionMismatch {
            what: "observations",
            got: y.len(),
            expected: m,
        });
    }
    if m <= n {
        return Err(IdentifyError::TooFewObservations {
            observations: m,
            unknowns: n,
        });
    }
    for i in 0..m {
        for j in 0..n {
            if !design[(i, j)].is_finite() {
                return Err(IdentifyError::NonFinite {
                    row: i,
                    column: Some(j),
                });
            }
        }
        if !y[i].is_finite() {
            return Err(IdentifyError::NonFinite {
                row: i,
                column: None,
            });
        }
    }
    Ok(())
}

/// Column-pivoted QR of the column-scaled design: `X·D⁻¹·P = Q·R`.
#[derive(Debug, Clone)]
pub(crate) struct ScaledQr {
    /// Column 2-norms D.
    pub(crate) scale: Vec<f64>,
    /// Thin Q, m × n.
    pub(crate) q: DMatrix<f64>,
    /// Upper-triangular R, n × n.
    pub(crate) r: DMatrix<f64>,
    /// `perm[k]` = original column placed at position k.
    pub(crate) perm: Vec<usize>,
}

impl ScaledQr {
    /// Scales, factorises and checks the rank at relative tolerance `tau`.
    pub(crate) fn new(design: &DMatrix<f64>, tau: f64) -> Result<Self> {
        let (m, n) = design.shape();
        let scale: Vec<f64> = (0..n)
            .map(|j| {
                let norm = column_norm(design.column(j).iter().copied());
                if norm > 0.0 { norm } else { 1.0 }
            })
            .collect();
        let scaled = faer::Mat::<f64>::from_fn(m, n, |i, j| design[(i, j)] / scale[j]);
        let qr = scaled.col_piv_qr();
        let (fwd, _) = qr.P().arrays();
        let perm = fwd.to_vec();
        let r_f = qr.thin_R();
        let q_f = qr.compute_thin_Q();
        let r = DMatrix::from_fn(n, n, |i, j| if i <= j { r_f[(i, j)] } else { 0.0 });
        let q = DMatrix::from_fn(m, n, |i, j| q_f[(i, j)]);

        let r00 = r[(0, 0)].abs();
        let rank = (0..n)
            .take_while(|&k| r[(k, k)].abs() > tau * r00 && r[(k, k)] != 0.0)
            .count();
        if rank < n {
            return Err(IdentifyError::RankDeficient {
                rank,
                unknowns: n,
                tolerance: tau,
            });
        }
        Ok(Self { scale, q, r, perm })
    }

    /// Solves `min ‖y − X β‖` in double precision.
    pub(crate) fn solve(&self, y: &[f64]) -> Vec<f64> {
        let (m, n) = self.q.shape();
        let c: Vec<f64> = (0..n)
            .map(|k| (0..m).map(|i| self.q[(i, k)] * y[i]).sum())
            .collect();
        let z = self.back_substitute(&c);
        self.unpermute_unscale(&z)
    }

    /// Maps a solution `z` of the pivoted, scaled problem to the original coefficients.
    pub(crate) fn unpermute_unscale(&self, z: &[f64]) -> Vec<f64> {
        let mut beta = vec![0.0; z.len()];
        for (k, &col) in self.perm.iter().enumerate() {
            beta[col] = z[k] / self.scale[col];
        }
        beta
    }

    /// Solves `R z = c`.
    pub(crate) fn back_substitute(&self, c: &[f64]) -> Vec<f64> {
        let n = c.len();
        let mut z = c.to_vec();
        for k in (0..n).rev() {
            let mut s = z[k];
            for j in k + 1..n {
                s -= self.r[(k, j)] * z[j];
            }
            z[k] = s / self.r[(k, k)];
        }
        z
    }

    /// `(XᵀX)⁻¹ = D⁻¹ P R⁻¹ R⁻ᵀ Pᵀ D⁻¹`, from the triangular inverse of R.
    pub(crate) fn unscaled_inverse_gram(&self) -> DMatrix<f64> {
        let n = self.r.ncols();
        // R⁻¹ column by column.
        let mut rinv = DMatrix::<f64>::zeros(n, n);
        for j in 0..n {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            let col = self.back_substitute(&e);
            for i in 0..n {
                rinv[(i, j)] = col[i];
            }
        }
        let g = &rinv * rinv.transpose();
        let mut out = DMatrix::<f64>::zeros(n, n);
        for a in 0..n {
            for b in 0..n {
                let (ca, cb) = (self.perm[a], self.perm[b]);
                out[(ca, cb)] = g[(a, b)] / (self.scale[ca] * self.scale[cb]);
            }
        }
        out
    }

    /// 2-norm condition number of the scaled design (= that of R).
    pub(crate) fn condition_number(&self) -> f64 {
        let n = self.r.ncols();
        let r = faer::Mat::<f64>::from_fn(n, n, |i, j| self.r[(i, j)]);
        match r.singular_values() {
            Ok(sv) => {
                let max = sv.iter().copied().fold(0.0_f64, f64::max);
                let min = sv.iter().copied().fold(f64::INFINITY, f64::min);
                if min > 0.0 { max / min } else { f64::INFINITY }
            }
            Err(_) => f64::INFINITY,
        }
    }
}

/// Overflow-safe 2-norm.
fn column_norm(values: impl Iterator<Item = f64> + Clone) -> f64 {
    let max = values.clone().fold(0.0_f64, |a, v| a.max(v.abs()));
    if max == 0.0 {
        return 0.0;
    }
    max * values.map(|v| (v / max) * (v / max)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn three_point_line_by_hand() {
        // (0,1), (1,2), (2,4): slope 3/2, intercept 5/6, residuals 1/6, −1/3, 1/6, s² = 1/6,
        // Var(intercept) = 5/36, Var(slope) = 1/12, Cov = −1/12.
        let design = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 1.0, 1.0, 1.0, 2.0]);
        let fit = lstsq(&design, &[1.0, 2.0, 4.0]).unwrap();
        assert_relative_eq!(fit.coefficients[0], 5.0 / 6.0, max_relative = 1e-14);
        assert_relative_eq!(fit.coefficients[1], 1.5, max_relative = 1e-14);
        let expected_r = [1.0 / 6.0, -1.0 / 3.0, 1.0 / 6.0];
        for (r, e) in fit.residuals.iter().zip(expected_r) {
            assert_relative_eq!(*r, e, max_relative = 1e-12);
        }
        assert_eq!(fit.dof, 1);
        assert_relative_eq!(
            fit.residual_sd,
            (1.0_f64 / 6.0).sqrt(),
            max_relative = 1e-14
        );
        assert_relative_eq!(fit.covariance[(0, 0)], 5.0 / 36.0, max_relative = 1e-13);
        assert_relative_eq!(fit.covariance[(1, 1)], 1.0 / 12.0, max_relative = 1e-13);
        assert_relative_eq!(fit.covariance[(0, 1)], -1.0 / 12.0, max_relative = 1e-13);
        assert_relative_eq!(fit.covariance[(1, 0)], -1.0 / 12.0, max_relative = 1e-13);
        assert_relative_eq!(
            fit.std_errors[1],
            (1.0_f64 / 12.0).sqrt(),
            max_relative = 1e-13
        );
    }

    #[test]
    fn exact_line_is_recovered() {
        let x: Vec<f64> = (0..10).map(f64::from).collect();
        let design = DMatrix::from_fn(10, 2, |i, j| if j == 0 { 1.0 } else { x[i] });
        let y: Vec<f64> = x.iter().map(|x| -3.0 + 0.25 * x).collect();
        let fit = lstsq(&design, &y).unwrap();
        assert_relative_eq!(fit.coefficients[0], -3.0, max_relative = 1e-14);
        assert_relative_eq!(fit.coefficients[1], 0.25, max_relative = 1e-14);
        assert!(fit.residual_sd < 1e-14);
        assert_eq!(fit.path, SolverPath::ScaledColPivQr);
    }

    #[test]
    fn orthonormal_design_has_unit_condition() {
        // Columns (1,1,0,0) and (0,0,1,1) are orthogonal with equal norms.
        let design = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
        let fit = lstsq(&design, &[1.0, 3.0, 5.0, 9.0]).unwrap();
        assert_relative_eq!(fit.condition_number, 1.0, max_relative = 1e-12);
        assert_relative_eq!(fit.coefficients[0], 2.0, max_relative = 1e-14);
        assert_relative_eq!(fit.coefficients[1], 7.0, max_relative = 1e-14);
        // s² = (1 + 1 + 4 + 4)/2 = 5, Var = s²/2.
        assert_relative_eq!(fit.std_errors[0], 2.5_f64.sqrt(), max_relative = 1e-13);
    }

    #[test]
    fn pivoting_and_scaling_are_undone() {
        // Columns of wildly different size, given in an order the pivoting will change.
        let x: Vec<f64> = (0..8).map(|i| f64::from(i) * 0.5).collect();
        let design = DMatrix::from_fn(8, 3, |i, j| match j {
            0 => 1e-6,
            1 => 1e6 * x[i] * x[i],
            _ => x[i],
        });
        let truth = [4e6, 3e-6, -2.0];
        let y: Vec<f64> = (0..8)
            .map(|i| (0..3).map(|j| design[(i, j)] * truth[j]).sum())
            .collect();
        let fit = lstsq(&design, &y).unwrap();
        for (c, t) in fit.coefficients.iter().zip(truth) {
            assert_relative_eq!(*c, t, max_relative = 1e-12);
        }
    }

    #[test]
    fn typed_errors() {
        let d = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 1.0]);
        assert_eq!(
            lstsq(&d, &[1.0, 2.0]),
            Err(IdentifyError::TooFewObservations {
                observations: 2,
                unknowns: 2
            })
        );
        let d = DMatrix::from_row_slice(3, 1, &[1.0, 2.0, 3.0]);
        assert!(matches!(
            lstsq(&d, &[1.0, 2.0]),
            Err(IdentifyError::DimensionMismatch {
                got: 2,
                expected: 3,
                ..
            })
        ));
        let d = DMatrix::<f64>::zeros(3, 0);
        assert_eq!(lstsq(&d, &[1.0, 2.0, 3.0]), Err(IdentifyError::NoUnknowns));
        let d = DMatrix::from_row_slice(3, 1, &[1.0, 2.0, 3.0]);
        assert!(matches!(
            lstsq_with(
                &d,
                &[1.0, 2.0, 3.0],
                &LstsqOptions {
                    rank_tolerance: Some(f64::NAN)
                }
            ),
            Err(IdentifyError::InvalidParameter {
                name: "rank_tolerance",
                ..
            })
        ));
    }
}
