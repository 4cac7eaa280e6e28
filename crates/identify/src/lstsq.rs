//! General linear least squares: column-pivoted Householder QR of the column-scaled design,
//! refined with double-double residuals.

// Index loops mirror the matrix formulas of the algorithms.
#![allow(clippy::needless_range_loop)]

use nalgebra::DMatrix;

use crate::dd::Dd;
use crate::design::Design;
use crate::error::{IdentifyError, Requirement, Result};

/// Which numerical method produced a [`Fit`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum SolverPath {
    /// Column scaling by powers of two near the column 2-norms, then column-pivoted
    /// Householder QR (faer) in double precision; no refinement.
    ScaledColPivQr,
    /// As [`SolverPath::ScaledColPivQr`], then iterative refinement of the augmented system
    /// `[I X; Xᵀ 0]·[r; β] = [y; c]` with both block residuals evaluated in double-double
    /// arithmetic (Björck 1967), for the solution (c = 0) and for each column of `(XᵀX)⁻¹`
    /// (y = 0, c = −e_k). The double-precision QR factors serve every correction.
    RefinedScaledColPivQr,
}

/// A condition that limits the accuracy of a [`Fit`] without preventing it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum FitWarning {
    /// Iterative refinement stopped contracting before its corrections fell below double
    /// precision: the design is too ill-conditioned for refinement from a double-precision
    /// factorisation (roughly `condition_number·ε ≳ 0.1`), so the trailing digits of the result
    /// are not established. The result is that of the last iterate.
    RefinementNotConverged {
        /// Iterations performed (the largest over the solution and covariance columns).
        iterations: usize,
        /// Size of the last correction relative to the solution (∞-norms).
        relative_correction: f64,
    },
}

/// Options for [`lstsq_with`] and [`lstsq_design`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LstsqOptions {
    /// Relative rank tolerance τ: the column-scaled design is declared rank deficient when a
    /// diagonal entry of the column-pivoted R satisfies `|R_kk| ≤ τ·|R_00|`.
    /// `None` selects the default `max(m, n)·ε` (ε = `f64::EPSILON`).
    pub rank_tolerance: Option<f64>,
    /// Refine the solution and covariance with double-double residuals (default `true`).
    pub refine: bool,
    /// Upper bound on refinement iterations per right-hand side (default 30).
    pub max_refinement_iterations: usize,
    /// Refine the covariance too (default `true`). `false` for a refit whose values alone are
    /// used (a Type B input moved by ± its u): the solution and residuals are refined exactly
    /// as with `true`, so the coefficients are the same to the last bit, and the covariance is
    /// the double-precision QR's, without the `n` refinements of its columns that take most of
    /// the time.
    pub refine_covariance: bool,
}

impl Default for LstsqOptions {
    fn default() -> Self {
        Self {
            rank_tolerance: None,
            refine: true,
            max_refinement_iterations: 30,
            refine_covariance: true,
        }
    }
}

/// Result of a least-squares fit `y ≈ X·β`.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// Estimated coefficients β, in the order of the design's columns.
    pub coefficients: Vec<f64>,
    /// Covariance of β, `s²·(XᵀX)⁻¹`, from the QR factors (`(BᵀB)⁻¹ = R⁻¹R⁻ᵀ` for the
    /// scaled, pivoted design B, refined column by column and mapped back through the scaling
    /// and pivoting), never by inverting the normal equations.
    pub covariance: DMatrix<f64>,
    /// Standard errors, the square roots of the covariance diagonal.
    pub std_errors: Vec<f64>,
    /// `(XᵀX)⁻¹` itself, the covariance for observations of unit variance (from the same
    /// refined QR solves as `covariance`). With rows weighted by `1/σᵢ` it is the covariance
    /// for the σᵢ taken as known.
    pub unscaled_covariance: DMatrix<f64>,
    /// Residuals `y − X·β` of the least-squares solution (carried in double-double by the
    /// refinement, then rounded).
    pub residuals: Vec<f64>,
    /// Residual standard deviation `s = sqrt(Σr²/dof)`.
    pub residual_sd: f64,
    /// Residual degrees of freedom, observations − unknowns.
    pub dof: usize,
    /// 2-norm condition number (ratio of the extreme singular values, from an SVD of R) of the
    /// **column-scaled** design `B = X·D⁻¹`, each column divided by the power of two nearest its
    /// 2-norm. B is the matrix actually factorised; column scaling is a reparametrisation, so
    /// this, not the often far larger condition number of the raw X, is what limits the solver.
    pub condition_number: f64,
    /// Relative rank tolerance τ that was applied to the diagonal of R (see
    /// [`LstsqOptions::rank_tolerance`]).
    pub rank_tolerance: f64,
    /// Column scale factors D (powers of two; 1 for an all-zero column, which is then reported
    /// as rank deficient).
    pub column_scale: Vec<f64>,
    /// Which method was taken.
    pub path: SolverPath,
    /// Refinement iterations taken (the largest over the solution and the covariance columns).
    pub refinement_iterations: usize,
    /// Conditions that limit the accuracy; empty when refinement established every digit.
    pub warnings: Vec<FitWarning>,
}

/// Least squares `min ‖y − X·β‖₂` with default [`LstsqOptions`]; the entries of `design` are
/// taken as exact.
///
/// Method ([`SolverPath::RefinedScaledColPivQr`]): the design is scaled to near-unit column
/// norms by powers of two (exactly, without rounding), factorised by column-pivoted Householder
/// QR `X·D⁻¹·P = Q·R`, and the least-squares solution and `(XᵀX)⁻¹` are refined as solutions of
/// the augmented system with residuals evaluated in double-double arithmetic. The result is the
/// least-squares solution of the given data correct to about double precision whenever the
/// refinement converges (roughly `condition_number·ε < 0.1`); otherwise a
/// [`FitWarning::RefinementNotConverged`] is attached. The covariance is `s²·(XᵀX)⁻¹` with
/// `s² = Σr²/(m − n)`:
///
/// ```text
/// β̂ = D⁻¹·P·R⁻¹·Qᵀ·y,    Cov(β̂) = s²·D⁻¹·P·R⁻¹·R⁻ᵀ·Pᵀ·D⁻¹
/// ```
///
/// (before refinement). For designs whose entries are not exact doubles (powers of data) build a
/// [`Design`] and call [`lstsq_design`].
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
/// assert_relative_eq!(fit.coefficients[0], 1.0, max_relative = 1e-15);
/// assert_relative_eq!(fit.coefficients[1], 2.0, max_relative = 1e-15);
/// assert!(fit.residual_sd < 1e-15);
/// assert!(fit.warnings.is_empty());
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
    lstsq_design(&Design::from_matrix(design), y, options)
}

/// Least squares for a [`Design`] held in double-double precision (see [`lstsq`] for the
/// method).
///
/// ```
/// use approx::assert_relative_eq;
/// use identify::{lstsq_design, Design, LstsqOptions};
/// let x: Vec<f64> = (0..12).map(|i| 3.0 + 0.1 * f64::from(i)).collect();
/// let y: Vec<f64> = x.iter().map(|x| 1.0 - 2.0 * x + 0.5 * x.powi(4)).collect();
/// let fit = lstsq_design(&Design::powers(&x, &[0, 1, 4]), &y, &LstsqOptions::default())?;
/// assert_relative_eq!(fit.coefficients[2], 0.5, max_relative = 1e-14);
/// # Ok::<(), identify::IdentifyError>(())
/// ```
///
/// # Errors
/// As [`lstsq_with`].
pub fn lstsq_design(design: &Design, y: &[f64], options: &LstsqOptions) -> Result<Fit> {
    let fit = lstsq_design_unchecked(design, y, options)?;
    if let Some(what) = fit.first_non_finite() {
        return Err(IdentifyError::Overflow { what });
    }
    Ok(fit)
}

impl Fit {
    /// The first part of the fit that is not finite, if any (the coefficients and the residual
    /// SD are checked by the solver itself).
    pub(crate) fn first_non_finite(&self) -> Option<&'static str> {
        if self.std_errors.iter().any(|s| !s.is_finite()) {
            Some("a standard error")
        } else if self.covariance.iter().any(|c| !c.is_finite())
            || self.unscaled_covariance.iter().any(|c| !c.is_finite())
        {
            Some("the covariance")
        } else if self.residuals.iter().any(|r| !r.is_finite()) {
            Some("a residual")
        } else {
            None
        }
    }
}

/// [`lstsq_design`] without the finiteness check of the standard errors, covariance and
/// residuals, for callers that name the quantity that overflowed themselves.
pub(crate) fn lstsq_design_unchecked(
    design: &Design,
    y: &[f64],
    options: &LstsqOptions,
) -> Result<Fit> {
    let (m, n) = (design.nrows(), design.ncols());
    validate(design, y)?;
    let tau = match options.rank_tolerance {
        None => m.max(n) as f64 * f64::EPSILON,
        Some(t) if t.is_finite() && (0.0..1.0).contains(&t) => t,
        Some(t) => {
            return Err(IdentifyError::InvalidParameter {
                name: "rank_tolerance",
                value: t,
                requirement: Requirement::UnitInterval,
            });
        }
    };

    let qr = ScaledQr::new(design, tau)?;
    let max_iterations = if options.refine {
        options.max_refinement_iterations
    } else {
        0
    };
    let solution = qr.refine(y, &vec![0.0; n], max_iterations);
    let z: Vec<f64> = solution.z.iter().map(|v| v.to_f64()).collect();
    let coefficients = qr.unpermute_unscale(&z);
    let residuals: Vec<f64> = solution.r.iter().map(|v| v.to_f64()).collect();
    let dof = m - n;
    let ssr = solution.r.iter().fold(Dd::ZERO, |acc, r| acc + *r * *r);
    let s2 = ssr.div_f64(dof as f64);

    // (BᵀB)⁻¹ column by column: the augmented system with y = 0, c = −e_k gives z = (BᵀB)⁻¹e_k.
    let mut inverse_gram = Vec::with_capacity(n);
    let mut iterations = solution.iterations;
    let mut converged = solution.converged;
    let mut worst_correction = solution.last_correction;
    let zeros = vec![0.0; m];
    let covariance_iterations = if options.refine_covariance {
        max_iterations
    } else {
        0
    };
    for k in 0..n {
        let mut c = vec![0.0; n];
        c[k] = -1.0;
        let col = qr.refine(&zeros, &c, covariance_iterations);
        iterations = iterations.max(col.iterations);
        converged &= col.converged;
        worst_correction = worst_correction.max(col.last_correction);
        inverse_gram.push(col.z);
    }
    let mut covariance = DMatrix::<f64>::zeros(n, n);
    let mut unscaled_covariance = DMatrix::<f64>::zeros(n, n);
    let mut std_errors = vec![0.0; n];
    for a in 0..n {
        for b in 0..n {
            // Symmetrise: both refined entries are accurate, their mean is as well.
            let g = (inverse_gram[a][b] + inverse_gram[b][a]).mul_f64(0.5);
            let (ca, cb) = (qr.perm[a], qr.perm[b]);
            // The scale factors are powers of two: dividing by them is exact.
            let u = g.mul_f64(1.0 / qr.scale[ca]).mul_f64(1.0 / qr.scale[cb]);
            let v = s2 * u;
            unscaled_covariance[(ca, cb)] = u.to_f64();
            covariance[(ca, cb)] = v.to_f64();
            if a == b {
                std_errors[ca] = v.sqrt().to_f64();
            }
        }
    }

    let mut warnings = Vec::new();
    if options.refine && !converged {
        warnings.push(FitWarning::RefinementNotConverged {
            iterations,
            relative_correction: worst_correction,
        });
    }
    let residual_sd = s2.sqrt().to_f64();
    if !residual_sd.is_finite() || coefficients.iter().any(|c| !c.is_finite()) {
        return Err(IdentifyError::Overflow {
            what: "the residual sum of squares or a coefficient",
        });
    }

    Ok(Fit {
        coefficients,
        covariance,
        unscaled_covariance,
        std_errors,
        residuals,
        residual_sd,
        dof,
        condition_number: qr.condition_number(),
        rank_tolerance: tau,
        column_scale: qr.scale.clone(),
        path: if options.refine {
            SolverPath::RefinedScaledColPivQr
        } else {
            SolverPath::ScaledColPivQr
        },
        refinement_iterations: iterations,
        warnings,
    })
}

/// Checks shapes and finiteness.
fn validate(design: &Design, y: &[f64]) -> Result<()> {
    let (m, n) = (design.nrows(), design.ncols());
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
            let v = design.entry(i, j);
            if !(v.hi.is_finite() && v.lo.is_finite()) {
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

/// Column-pivoted QR of the column-scaled design: `B = X·D⁻¹·P = Q·R`, with D a diagonal of
/// powers of two (so B is formed without rounding) and P the pivoting permutation.
#[derive(Debug, Clone)]
struct ScaledQr {
    /// Column scale factors D (powers of two near the column 2-norms).
    scale: Vec<f64>,
    /// B = X·D⁻¹·P in double-double, column-major, m × n (columns in pivoted order).
    b_hi: Vec<f64>,
    b_lo: Vec<f64>,
    /// Thin Q, m × n, column-major.
    q: Vec<f64>,
    /// Upper-triangular R, n × n.
    r: DMatrix<f64>,
    /// `perm[k]` = original column placed at position k.
    perm: Vec<usize>,
    m: usize,
    n: usize,
}

/// Outcome of an iterative refinement.
#[derive(Debug, Clone)]
struct Refined {
    /// Residual vector, double-double.
    r: Vec<Dd>,
    /// Solution in pivoted, scaled coordinates, double-double.
    z: Vec<Dd>,
    iterations: usize,
    converged: bool,
    /// Last correction relative to the solution (∞-norms).
    last_correction: f64,
}

impl ScaledQr {
    /// Scales, factorises and checks the rank at relative tolerance `tau`.
    fn new(design: &Design, tau: f64) -> Result<Self> {
        let (m, n) = (design.nrows(), design.ncols());
        let scale: Vec<f64> = (0..n)
            .map(|j| {
                let norm = column_norm(design.column_hi(j));
                if norm > 0.0 { pow2_near(norm) } else { 1.0 }
            })
            .collect();
        let scaled = faer::Mat::<f64>::from_fn(m, n, |i, j| design.entry(i, j).hi / scale[j]);
        let qr = scaled.col_piv_qr();
        let (fwd, _) = qr.P().arrays();
        let perm = fwd.to_vec();
        let r_f = qr.thin_R();
        let q_f = qr.compute_thin_Q();
        let r = DMatrix::from_fn(n, n, |i, j| if i <= j { r_f[(i, j)] } else { 0.0 });
        let mut q = vec![0.0; m * n];
        let mut b_hi = vec![0.0; m * n];
        let mut b_lo = vec![0.0; m * n];
        for k in 0..n {
            let s = 1.0 / scale[perm[k]];
            for i in 0..m {
                q[k * m + i] = q_f[(i, k)];
                let e = design.entry(i, perm[k]);
                b_hi[k * m + i] = e.hi * s;
                b_lo[k * m + i] = e.lo * s;
            }
        }

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
        Ok(Self {
            scale,
            b_hi,
            b_lo,
            q,
            r,
            perm,
            m,
            n,
        })
    }

    /// Solves the augmented system `[I B; Bᵀ 0]·[r; z] = [f; g]` in double precision with the
    /// QR factors: `Rᵀu = g`, `w = Qᵀf − u`, `z = R⁻¹w`, `r = f − Q·w`.
    fn solve_augmented(&self, f: &[f64], g: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (m, n) = (self.m, self.n);
        let u = self.forward_substitute_transposed(g);
        let mut w = vec![0.0; n];
        for k in 0..n {
            let col = &self.q[k * m..(k + 1) * m];
            w[k] = col.iter().zip(f).map(|(q, f)| q * f).sum::<f64>() - u[k];
        }
        let z = self.back_substitute(&w);
        let mut r = f.to_vec();
        for k in 0..n {
            let col = &self.q[k * m..(k + 1) * m];
            for i in 0..m {
                r[i] -= col[i] * w[k];
            }
        }
        (r, z)
    }

    /// Solves the augmented system `[I B; Bᵀ 0]·[r; z] = [y; c]` (least squares
    /// `min ‖y − Bz‖` when c = 0; `z = −(BᵀB)⁻¹c` when y = 0) and, when `max_iterations > 0`,
    /// refines it with residuals of both block equations evaluated in double-double
    /// (Björck 1967), reusing the QR factors for each correction.
    fn refine(&self, y: &[f64], c: &[f64], max_iterations: usize) -> Refined {
        let (m, n) = (self.m, self.n);
        let (r0, z0) = self.solve_augmented(y, c);
        let mut r: Vec<Dd> = r0.into_iter().map(Dd::from_f64).collect();
        let mut z: Vec<Dd> = z0.into_iter().map(Dd::from_f64).collect();
        let y_norm = inf_norm(y.iter().copied());
        let mut iterations = 0;
        let mut converged = max_iterations == 0;
        let mut last_correction = f64::NAN;
        let mut previous = f64::INFINITY;
        while iterations < max_iterations {
            iterations += 1;
            // f = y − r − B z and g = c − Bᵀ r, in double-double; `terms` bounds |B|·|z|.
            let mut f: Vec<Dd> = (0..m).map(|i| Dd::from_f64(y[i]) - r[i]).collect();
            let mut terms = vec![0.0_f64; m];
            let mut g = vec![Dd::ZERO; n];
            for k in 0..n {
                let (hi, lo) = (
                    &self.b_hi[k * m..(k + 1) * m],
                    &self.b_lo[k * m..(k + 1) * m],
                );
                let zk = -z[k];
                let mut gk = Dd::from_f64(c[k]);
                for i in 0..m {
                    let bik = Dd {
                        hi: hi[i],
                        lo: lo[i],
                    };
                    f[i] += zk * bik;
                    terms[i] += (hi[i] * zk.hi).abs();
                    gk = gk - r[i] * bik;
                }
                g[k] = gk;
            }
            let f: Vec<f64> = f.iter().map(|v| v.to_f64()).collect();
            let g: Vec<f64> = g.iter().map(|v| v.to_f64()).collect();
            let (dr, dz) = self.solve_augmented(&f, &g);
            for (ri, d) in r.iter_mut().zip(&dr) {
                *ri += Dd::from_f64(*d);
            }
            for (zi, d) in z.iter_mut().zip(&dz) {
                *zi += Dd::from_f64(*d);
            }
            let target = f64::EPSILON / 16.0;
            let dz_rel = relative(
                inf_norm(dz.iter().copied()),
                inf_norm(z.iter().map(|v| v.hi)),
            );
            // A residual is known at best to the double-double evaluation noise of y − B·z.
            let r_norm = inf_norm(r.iter().map(|v| v.hi));
            let noise = 64.0
                * f64::EPSILON
                * f64::EPSILON
                * (y_norm + inf_norm(terms.into_iter()) + r_norm);
            let dr_ratio = relative(inf_norm(dr.iter().copied()), (target * r_norm).max(noise));
            // size ≤ 1: both corrections below their targets. Under geometric contraction the
            // error left after a correction is smaller than the correction.
            let size = (dz_rel / target).max(dr_ratio);
            last_correction = dz_rel;
            converged = size <= 1.0;
            if size <= 1e-2 || size > 0.5 * previous {
                // Done, or stalled (if not yet converged, the conditioning is beyond repair).
                break;
            }
            previous = size;
        }
        Refined {
            r,
            z,
            iterations,
            converged,
            last_correction,
        }
    }

    /// Maps a solution `z` of the pivoted, scaled problem to the original coefficients.
    fn unpermute_unscale(&self, z: &[f64]) -> Vec<f64> {
        let mut beta = vec![0.0; z.len()];
        for (k, &col) in self.perm.iter().enumerate() {
            beta[col] = z[k] / self.scale[col];
        }
        beta
    }

    /// Solves `R z = c`.
    fn back_substitute(&self, c: &[f64]) -> Vec<f64> {
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

    /// Solves `Rᵀ u = g`.
    fn forward_substitute_transposed(&self, g: &[f64]) -> Vec<f64> {
        let n = g.len();
        let mut u = g.to_vec();
        for k in 0..n {
            let mut s = u[k];
            for j in 0..k {
                s -= self.r[(j, k)] * u[j];
            }
            u[k] = s / self.r[(k, k)];
        }
        u
    }

    /// 2-norm condition number of the scaled design (= that of R).
    fn condition_number(&self) -> f64 {
        let n = self.n;
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

fn inf_norm(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0_f64, |a, v| a.max(v.abs()))
}

/// `num/den`, with 0/0 = 0.
fn relative(num: f64, den: f64) -> f64 {
    if num == 0.0 { 0.0 } else { num / den }
}

/// The power of two nearest (in ratio, within √2) to a positive finite `x`.
fn pow2_near(x: f64) -> f64 {
    let e = x.log2().round();
    // Clamp so that both the scale and its reciprocal stay finite and normal.
    2f64.powi(e.clamp(-1000.0, 1000.0) as i32)
}

/// Overflow-safe 2-norm.
fn column_norm(values: &[f64]) -> f64 {
    let max = inf_norm(values.iter().copied());
    if max == 0.0 {
        return 0.0;
    }
    max * values
        .iter()
        .map(|v| (v / max) * (v / max))
        .sum::<f64>()
        .sqrt()
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
        assert_eq!(fit.path, SolverPath::RefinedScaledColPivQr);
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
                    rank_tolerance: Some(f64::NAN),
                    ..LstsqOptions::default()
                }
            ),
            Err(IdentifyError::InvalidParameter {
                name: "rank_tolerance",
                ..
            })
        ));
    }

    #[test]
    fn overflowing_data_is_an_error_not_nan() {
        let d = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0]);
        let y = [1e200, -1e200, 1e200, -1e200];
        assert!(matches!(lstsq(&d, &y), Err(IdentifyError::Overflow { .. })));
    }
}
