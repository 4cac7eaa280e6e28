//! The joint fit and what it gives: each chosen term with its u (and normalised by k1), the
//! arm stretch, the nuisance terms, the weighting and the residuals.

use accel_model::{AccelKind, Term};
use identify::{Fit, LstsqOptions, lstsq_design};
use nalgebra::DMatrix;

use super::check::check;
use super::column::Column;
use super::design::{JointDesign, build};
use super::error::MountingsError;
use super::separability::{full_rank, separability};
use super::spec::{ArmStretch, JointSpec, MountingData};
use crate::Weighting;
use crate::calibrate::weigh;

/// One chosen term's estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TermEstimate {
    /// The term.
    pub term: Term,
    /// Its value: output units per g^n (a misalignment in rad).
    pub value: f64,
    /// Its standard uncertainty from the fit.
    pub u: f64,
    /// Normalised by k1 (value/k1, u/k1): g for k0, g/gⁿ for the others (a misalignment
    /// and k1 itself: not normalised, `None`).
    pub normalised: Option<(f64, f64)>,
}

/// The arm stretch (radius growth the probe does not see), from the `c_i·ω⁴` column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmStretchEstimate {
    /// γ = k1·C/g, the column's coefficient, and its u.
    pub gamma: (f64, f64),
    /// The growth beyond the probe's C_r, `C − C_r = γ·g/k1`, m·s², and its u.
    pub unseen_m_s2: (f64, f64),
    /// The total growth `C = C_r + γ·g/k1` (C_r 0 without a probe), m·s², and its u (with
    /// the probe's u(C_r)).
    pub total_m_s2: (f64, f64),
}

/// A nuisance term's estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct NuisanceEstimate {
    /// The column.
    pub column: Column,
    /// Its words (an own bias is reported as its shift against k0).
    pub label: String,
    /// Its value and u.
    pub value: (f64, f64),
}

/// The joint fit over several mountings.
#[derive(Debug, Clone, PartialEq)]
pub struct MountingsFit {
    /// The kind (and so the output unit).
    pub kind: AccelKind,
    /// The chosen terms, in the model's order.
    pub terms: Vec<TermEstimate>,
    /// The terms' covariance (in `terms`' order; misalignments in rad).
    pub covariance: DMatrix<f64>,
    /// The arm stretch, when fitted.
    pub arm_stretch: Option<ArmStretchEstimate>,
    /// Whether the arm stretch was left out because the mountings do not separate it
    /// (`ArmStretch::Auto`): its radius growth then hides in the even terms.
    pub arm_stretch_not_separable: bool,
    /// The nuisance terms.
    pub nuisances: Vec<NuisanceEstimate>,
    /// The design's columns.
    pub columns: Vec<Column>,
    /// How the points were weighted (the calibration's one policy), with the coefficients'
    /// degrees of freedom.
    pub weighting: Weighting,
    /// Residuals `output − fitted` in the output unit, per mounting in its data's order.
    pub residuals: Vec<Vec<f64>>,
    /// The residuals' standard deviation `√(Σr²/ν)`, output units.
    pub residual_sd: f64,
    /// The least-squares fit (coefficients in `columns`' order).
    pub fit: Fit,
}

impl MountingsFit {
    /// A term's estimate, when chosen.
    #[must_use]
    pub fn term(&self, term: Term) -> Option<&TermEstimate> {
        self.terms.iter().find(|t| t.term == term)
    }

    /// The fit's coefficient of a column.
    #[must_use]
    pub fn coefficient(&self, column: Column) -> Option<(f64, f64)> {
        self.columns
            .iter()
            .position(|c| *c == column)
            .map(|j| (self.fit.coefficients[j], self.fit.std_errors[j]))
    }
}

/// One solve at the σ given: the fit, its residuals in output units, its Birge ratio.
struct Solved {
    fit: Fit,
    residuals: Vec<f64>,
    birge: Option<f64>,
}

fn solve(
    d: &JointDesign,
    sigma: Option<&[f64]>,
    options: &LstsqOptions,
) -> Result<Solved, MountingsError> {
    let Some(s) = sigma else {
        let fit = lstsq_design(&d.design, &d.y, options).map_err(MountingsError::Fit)?;
        let residuals = fit.residuals.clone();
        return Ok(Solved {
            fit,
            residuals,
            birge: None,
        });
    };
    let w: Vec<f64> = s.iter().map(|s| 1.0 / s).collect();
    let y: Vec<f64> = d.y.iter().zip(&w).map(|(y, w)| y * w).collect();
    let design = d
        .design
        .clone()
        .scale_rows(&w)
        .map_err(MountingsError::Fit)?;
    let mut fit = lstsq_design(&design, &y, options).map_err(MountingsError::Fit)?;
    let chi2: f64 = fit.residuals.iter().map(|e| e * e).sum();
    let birge = (chi2 / fit.dof.max(1) as f64).sqrt();
    // the σᵢ taken as known: (XᵀWX)⁻¹, enlarged by the Birge ratio when above 1 (identify's
    // policy for a weighted fit)
    fit.covariance = &fit.unscaled_covariance * birge.max(1.0).powi(2);
    fit.std_errors = (0..fit.coefficients.len())
        .map(|j| fit.covariance[(j, j)].sqrt())
        .collect();
    let residuals = fit.residuals.iter().zip(s).map(|(e, s)| e * s).collect();
    Ok(Solved {
        fit,
        residuals,
        birge: Some(birge),
    })
}

/// Fits the model jointly over the mountings: the separability checked first (a design that
/// cannot separate the chosen terms is refused with the analysis, naming the mounting that
/// would fix it), the arm stretch fitted as declared (`Auto`: when the mountings separate
/// it), the points weighted by the calibration's one policy, `identify`'s QR with column
/// scaling and covariance.
///
/// # Errors
/// [`MountingsError::NotSeparable`] with the analysis; the declaration's and data's
/// [`MountingsError`]s; [`MountingsError::Fit`] from the solver.
pub fn fit_mountings(
    spec: &JointSpec,
    data: &[MountingData<'_>],
) -> Result<MountingsFit, MountingsError> {
    fit_mountings_with(spec, data, &LstsqOptions::default())
}

/// [`fit_mountings`] for a refit whose values alone are used (the Type B budget's, an input
/// moved by ± its u): the same coefficients to the last bit, the covariance unrefined
/// ([`LstsqOptions::refine_covariance`]), in a tenth of the time.
pub(crate) fn refit_values(
    spec: &JointSpec,
    data: &[MountingData<'_>],
) -> Result<MountingsFit, MountingsError> {
    let options = LstsqOptions {
        refine_covariance: false,
        ..LstsqOptions::default()
    };
    fit_mountings_with(spec, data, &options)
}

fn fit_mountings_with(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    options: &LstsqOptions,
) -> Result<MountingsFit, MountingsError> {
    check(spec, data)?;
    let (arm, not_separable) = match spec.arm_stretch {
        ArmStretch::Off => (false, false),
        ArmStretch::Fit => (true, false),
        ArmStretch::Auto => {
            let with = full_rank(spec, data, true)?;
            (with, !with)
        }
    };
    if !full_rank(spec, data, arm)? {
        return Err(MountingsError::NotSeparable(Box::new(separability(
            spec, data, arm,
        )?)));
    }
    let design = build(spec, data, arm)?;
    // σ in the design's row order
    let sigma: Option<Vec<f64>> = data[0].sigma.map(|_| {
        design
            .rows
            .iter()
            .map(|&(m, i)| data[m].sigma.map_or(1.0, |s| s[i]))
            .collect()
    });
    let (solved, weighting) = weigh(
        sigma.as_deref(),
        |s| solve(&design, s, options),
        // the τ search reads the Birge ratio alone: its trial fits skip the covariance's
        // refinement (the same residuals to the last bit)
        |s| {
            solve(
                &design,
                s,
                &LstsqOptions {
                    refine_covariance: false,
                    ..*options
                },
            )
        },
        |s| s.birge,
        |s| s.residuals.clone(),
        |s| s.fit.dof,
    )?;
    Ok(results(
        spec,
        data,
        &design,
        solved,
        weighting,
        arm,
        not_separable,
    ))
}

fn results(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    design: &JointDesign,
    solved: Solved,
    weighting: Weighting,
    arm: bool,
    arm_stretch_not_separable: bool,
) -> MountingsFit {
    let fit = solved.fit;
    let cols = &design.columns;
    let n = cols.len();
    let beta = &fit.coefficients;
    let cov = &fit.covariance;
    let at = |c: Column| cols.iter().position(|k| *k == c);
    let k1_j = at(Column::Term(Term::K1));
    let k1 = k1_j.map_or(f64::NAN, |j| beta[j]);
    // the reported terms as functions of the coefficients: value and gradient
    let chosen = spec.chosen_terms();
    let mut values = Vec::new();
    let mut grads: Vec<Vec<f64>> = Vec::new();
    for &t in &chosen {
        let j = at(Column::Term(t)).unwrap_or(0);
        let mut g = vec![0.0; n];
        if t.is_misalignment() {
            if let Some(kj) = k1_j {
                g[j] = 1.0 / k1;
                g[kj] = -beta[j] / (k1 * k1);
            }
            values.push(beta[j] / k1);
        } else {
            g[j] = 1.0;
            values.push(beta[j]);
        }
        grads.push(g);
    }
    let propagate = |a: &[f64], b: &[f64]| -> f64 {
        let mut s = 0.0;
        for p in 0..n {
            for q in 0..n {
                s += a[p] * cov[(p, q)] * b[q];
            }
        }
        s
    };
    let m = chosen.len();
    let covariance = DMatrix::from_fn(m, m, |a, b| propagate(&grads[a], &grads[b]));
    let terms = chosen
        .iter()
        .enumerate()
        .map(|(a, &t)| {
            let u = covariance[(a, a)].max(0.0).sqrt();
            let normalised = (!(t.is_misalignment() || t == Term::K1) && k1.is_finite())
                .then(|| (values[a] / k1, u / k1.abs()));
            TermEstimate {
                term: t,
                value: values[a],
                u,
                normalised,
            }
        })
        .collect();
    let arm_stretch = arm.then(|| {
        let j = at(Column::ArmStretch).unwrap_or(0);
        let g_m_s2 = spec.g_m_s2;
        let gamma = beta[j];
        let unseen = gamma * g_m_s2 / k1;
        let mut grad = vec![0.0; n];
        grad[j] = g_m_s2 / k1;
        if let Some(kj) = k1_j {
            grad[kj] = -unseen / k1;
        }
        let u_unseen = propagate(&grad, &grad).max(0.0).sqrt();
        let (c_r, u_c_r) = spec
            .probe
            .map_or((0.0, 0.0), |p| (p.c_r_m_s2, p.c_r_u_m_s2));
        ArmStretchEstimate {
            gamma: (gamma, fit.std_errors[j]),
            unseen_m_s2: (unseen, u_unseen),
            total_m_s2: (c_r + unseen, u_unseen.hypot(u_c_r)),
        }
    });
    let k0_j = at(Column::Term(Term::K0));
    let nuisances = cols
        .iter()
        .enumerate()
        .filter(|(_, c)| !matches!(c, Column::Term(_) | Column::ArmStretch))
        .map(|(j, &c)| {
            let value = match (c, k0_j) {
                (Column::OwnBias(_), Some(k)) => {
                    let mut g = vec![0.0; n];
                    g[j] = 1.0;
                    g[k] = -1.0;
                    (beta[j] - beta[k], propagate(&g, &g).max(0.0).sqrt())
                }
                _ => (beta[j], fit.std_errors[j]),
            };
            let label = match c {
                Column::OwnBias(m) => format!(
                    "bias shift of {} against k0",
                    data.get(m).map_or("?", |d| d.mounting.label.as_str())
                ),
                _ => c.label(data),
            };
            NuisanceEstimate {
                column: c,
                label,
                value,
            }
        })
        .collect();
    let mut residuals: Vec<Vec<f64>> = data
        .iter()
        .map(|d| vec![0.0; d.rates_rad_s.len()])
        .collect();
    for (r, &(m, i)) in design.rows.iter().enumerate() {
        residuals[m][i] = solved.residuals[r];
    }
    let ss: f64 = solved.residuals.iter().map(|r| r * r).sum();
    let residual_sd = (ss / fit.dof.max(1) as f64).sqrt();
    MountingsFit {
        kind: spec.kind,
        terms,
        covariance,
        arm_stretch,
        arm_stretch_not_separable,
        nuisances,
        columns: cols.clone(),
        weighting,
        residuals,
        residual_sd,
        fit,
    }
}
