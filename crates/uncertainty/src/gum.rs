//! The GUM uncertainty framework: the law of propagation of uncertainty (JCGM 100 §5), the
//! Welch–Satterthwaite formula (G.4) and the expanded uncertainty (§6, G.3).

use crate::error::{ModelError, Result, UncertaintyError};
use crate::input::Inputs;
use crate::kind::Dof;
use crate::model::{MeasurementModel, checked_output_names};
use crate::student::coverage_factor;

/// How the effective degrees of freedom enter the coverage factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DofRounding {
    /// The t quantile at the non-integer ν_eff itself (JCGM 100 G.4.1 note 1: "by
    /// interpolation").
    #[default]
    Exact,
    /// ν_eff truncated to the next lower integer (JCGM 100 G.4.1 note 1), and kept as it is
    /// when below 1.
    Truncate,
}

/// Options of [`gum`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GumOptions {
    /// Coverage probability `p` of the expanded uncertainty (default 0.95).
    pub coverage_probability: f64,
    /// How ν_eff enters the coverage factor (default [`DofRounding::Exact`]).
    pub dof_rounding: DofRounding,
}

impl Default for GumOptions {
    fn default() -> Self {
        GumOptions {
            coverage_probability: 0.95,
            dof_rounding: DofRounding::Exact,
        }
    }
}

/// One input's part in one output's uncertainty.
#[derive(Debug, Clone, PartialEq)]
pub struct Contribution {
    /// The input.
    pub input: String,
    /// Sensitivity coefficient `c_i = ∂f/∂x_i` at the estimate (JCGM 100 eq. 11a).
    pub sensitivity: f64,
    /// Uncertainty component `u_i(y) = |c_i|·u(x_i)` (JCGM 100 eq. 11b).
    pub uncertainty: f64,
    /// Share of `u_c²(y)`, in percent: `100·c_i u_i Σ_j r_ij c_j u_j / u_c²`. Without
    /// correlation this is `100·u_i(y)²/u_c²`; with correlation the shares still sum to 100
    /// but one can be negative. Zero when `u_c = 0`.
    pub variance_percent: f64,
}

/// The GUM evaluation of one output quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct GumOutput {
    /// The output.
    pub name: String,
    /// Estimate `y = f(x)`.
    pub estimate: f64,
    /// Combined standard uncertainty `u_c(y)` (JCGM 100 eq. 10, or eq. 13 with correlation).
    pub standard_uncertainty: f64,
    /// Effective degrees of freedom ν_eff (JCGM 100 eq. G.2b).
    pub dof: Dof,
    /// Coverage factor `k = t_{(1+p)/2}(ν_eff)`.
    pub coverage_factor: f64,
    /// Expanded uncertainty `U = k·u_c(y)`.
    pub expanded_uncertainty: f64,
    /// Each input's contribution, in input order.
    pub contributions: Vec<Contribution>,
}

impl GumOutput {
    /// The coverage interval `[y − U, y + U]`.
    pub fn coverage_interval(&self) -> (f64, f64) {
        (
            self.estimate - self.expanded_uncertainty,
            self.estimate + self.expanded_uncertainty,
        )
    }
}

/// The GUM evaluation of all output quantities.
#[derive(Debug, Clone, PartialEq)]
pub struct GumResult {
    /// The coverage probability of the expanded uncertainties.
    pub coverage_probability: f64,
    /// One per output, in model order.
    pub outputs: Vec<GumOutput>,
    /// Covariance matrix of the outputs `U_y = C·U_x·Cᵀ` (row-major, `m × m`; JCGM 102
    /// §6.2.1.3), with `C` the sensitivity matrix and `U_x` the inputs' covariance.
    pub covariance: Vec<f64>,
}

impl GumResult {
    /// The output named `name`.
    pub fn output(&self, name: &str) -> Option<&GumOutput> {
        self.outputs.iter().find(|o| o.name == name)
    }
}

/// Relative step of the numerical derivative where the input's uncertainty is small
/// compared with its value: the step is at least this fraction of `|x_i|`.
const MIN_RELATIVE_STEP: f64 = 1e-5;
/// The step is about this fraction of `u(x_i)` otherwise.
const STEP_PER_UNCERTAINTY: f64 = 1e-2;

/// The GUM evaluation of `model` at `inputs` (JCGM 100:2008).
///
/// * Estimate: `y = f(x)` (§4.1.4).
/// * Sensitivity coefficients `c_i = ∂f/∂x_i` by Richardson-extrapolated central differences
///   through the model: with `D(h) = (f(x + h e_i) − f(x − h e_i))/(2h)`,
///   `c_i = (4·D(h/2) − D(h))/3`, whose truncation error is `h⁴·f⁽⁵⁾/480`. The step `h` is the
///   power of two nearest `max(u(x_i)/100, 10⁻⁵·|x_i|)` (10⁻⁵ when both are zero), so that
///   `x ± h` are exact; the rounding error is then about `ε·|f|/h`, i.e. ≲ 1e-10 relative for
///   a model whose output scales with its inputs. A smooth model's coefficients match the
///   analytic derivatives to about 1e-10 relative (tests/uncertainty/sensitivity.rs). Four
///   model evaluations per input.
/// * Combined standard uncertainty `u_c² = Σ_ij c_i c_j u_i u_j r_ij` (eq. 13; eq. 10 without
///   correlation).
/// * Effective degrees of freedom by Welch–Satterthwaite (eq. G.2b),
///   `ν_eff = u_c⁴ / Σ_g u_g⁴/ν_g`, where `g` runs over the groups of correlated inputs
///   (a lone input is a group) and `u_g² = Σ_{i,j∈g} c_i c_j u_i u_j r_ij`; terms with ν = ∞
///   drop out, and ν_eff = ∞ ([`Dof::Infinite`]) when all do.
/// * Coverage factor `k = t_{(1+p)/2}(ν_eff)` (G.3.4, 1.95996 for ν = ∞) and
///   `U = k·u_c` (§6.2.1).
///
/// Errors: the model fails or returns a non-finite output at the estimate or at a
/// differentiation point; an invalid coverage probability; an overflowing result.
pub fn gum<M: MeasurementModel + ?Sized>(
    model: &M,
    inputs: &Inputs,
    options: &GumOptions,
) -> Result<GumResult> {
    let p = options.coverage_probability;
    if !(p > 0.0 && p < 1.0) {
        return Err(UncertaintyError::InvalidOption {
            name: "coverage_probability",
            value: p,
            requirement: units::Requirement::OpenUnitInterval,
        });
    }
    let names = checked_output_names(model, inputs.len())?;
    let quantities = inputs.quantities();
    let (n, m) = (quantities.len(), names.len());
    let x = inputs.values();
    let y = estimate(model, &x, &names)?;
    let sens = sensitivities(model, inputs, &names)?;
    let u: Vec<f64> = quantities.iter().map(|q| q.standard_uncertainty).collect();

    // Weighted components w_i = c_i·u_i for each output (row-major m × n).
    let w: Vec<f64> = (0..m)
        .flat_map(|k| (0..n).map(move |i| (k, i)))
        .map(|(k, i)| sens[k * n + i] * u[i])
        .collect();

    let mut covariance = vec![0.0; m * m];
    for a in 0..m {
        for b in 0..=a {
            let mut s = 0.0;
            for group in inputs.groups() {
                for &i in &group.members {
                    for &j in &group.members {
                        s += w[a * n + i] * w[b * n + j] * inputs.correlation(i, j);
                    }
                }
            }
            covariance[a * m + b] = s;
            covariance[b * m + a] = s;
        }
    }

    let mut outputs = Vec::with_capacity(m);
    for (k, name) in names.iter().enumerate() {
        let wk = &w[k * n..(k + 1) * n];
        let variance = covariance[k * m + k].max(0.0);
        let uc = variance.sqrt();
        if !uc.is_finite() {
            return Err(UncertaintyError::NonFiniteResult {
                output: name.clone(),
                what: "combined standard uncertainty",
            });
        }
        let contributions = (0..n)
            .map(|i| {
                let cross: f64 = (0..n).map(|j| inputs.correlation(i, j) * wk[j]).sum();
                Contribution {
                    input: quantities[i].name.clone(),
                    sensitivity: sens[k * n + i],
                    uncertainty: wk[i].abs(),
                    variance_percent: if variance > 0.0 {
                        100.0 * wk[i] * cross / variance
                    } else {
                        0.0
                    },
                }
            })
            .collect();
        let dof = welch_satterthwaite(inputs, wk, variance);
        let k_dof = match (dof, options.dof_rounding) {
            (Dof::Finite(nu), DofRounding::Truncate) if nu >= 1.0 => Dof::Finite(nu.floor()),
            (d, _) => d,
        };
        let coverage_factor = coverage_factor(p, k_dof)?;
        let expanded = coverage_factor * uc;
        if !expanded.is_finite() {
            return Err(UncertaintyError::NonFiniteResult {
                output: name.clone(),
                what: "expanded uncertainty",
            });
        }
        outputs.push(GumOutput {
            name: name.clone(),
            estimate: y[k],
            standard_uncertainty: uc,
            dof,
            coverage_factor,
            expanded_uncertainty: expanded,
            contributions,
        });
    }
    if let Some(k) = covariance.iter().position(|v| !v.is_finite()) {
        return Err(UncertaintyError::NonFiniteResult {
            output: names[k / m].clone(),
            what: "covariance",
        });
    }
    Ok(GumResult {
        coverage_probability: p,
        outputs,
        covariance,
    })
}

/// `y = f(x)`, checked finite.
pub(crate) fn estimate<M: MeasurementModel + ?Sized>(
    model: &M,
    x: &[f64],
    names: &[String],
) -> Result<Vec<f64>> {
    let mut y = vec![0.0; names.len()];
    model
        .evaluate(x, &mut y)
        .map_err(|source| UncertaintyError::ModelFailedAtEstimate { source })?;
    if let Some(k) = y.iter().position(|v| !v.is_finite()) {
        return Err(UncertaintyError::NonFiniteEstimate {
            output: names[k].clone(),
            value: y[k],
        });
    }
    Ok(y)
}

/// The differentiation step for an input: the power of two nearest
/// `max(u/100, 1e-5·|x|)`, or 1e-5 when both are zero.
fn step(value: f64, uncertainty: f64) -> f64 {
    let target = (STEP_PER_UNCERTAINTY * uncertainty).max(MIN_RELATIVE_STEP * value.abs());
    let target = if target > 0.0 {
        target
    } else {
        MIN_RELATIVE_STEP
    };
    2f64.powi(target.log2().round() as i32)
}

/// Sensitivity matrix `C` (row-major, outputs × inputs) by Richardson-extrapolated central
/// differences.
fn sensitivities<M: MeasurementModel + ?Sized>(
    model: &M,
    inputs: &Inputs,
    names: &[String],
) -> Result<Vec<f64>> {
    let quantities = inputs.quantities();
    let (n, m) = (quantities.len(), names.len());
    let mut x = inputs.values();
    let mut sens = vec![0.0; m * n];
    let mut ys = [vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]];
    for (i, q) in quantities.iter().enumerate() {
        let h = step(q.value, q.standard_uncertainty);
        let xi = q.value;
        for (y, offset) in ys.iter_mut().zip([h, -h, 0.5 * h, -0.5 * h]) {
            x[i] = xi + offset;
            let failed = |source: ModelError| UncertaintyError::SensitivityFailed {
                input: q.name.clone(),
                source,
            };
            let result = model.evaluate(&x, y);
            x[i] = xi;
            result.map_err(failed)?;
            if let Some(k) = y.iter().position(|v| !v.is_finite()) {
                return Err(UncertaintyError::NonFiniteSensitivity {
                    input: q.name.clone(),
                    output: names[k].clone(),
                });
            }
        }
        // The steps actually taken (exact unless x ± h crosses a binade).
        let (hp, hm) = ((xi + h) - xi, xi - (xi - h));
        let (hp2, hm2) = ((xi + 0.5 * h) - xi, xi - (xi - 0.5 * h));
        for k in 0..m {
            let d1 = (ys[0][k] - ys[1][k]) / (hp + hm);
            let d2 = (ys[2][k] - ys[3][k]) / (hp2 + hm2);
            let c = d2 + (d2 - d1) / 3.0;
            if !c.is_finite() {
                return Err(UncertaintyError::NonFiniteSensitivity {
                    input: q.name.clone(),
                    output: names[k].clone(),
                });
            }
            sens[k * n + i] = c;
        }
    }
    Ok(sens)
}

/// Welch–Satterthwaite (JCGM 100 eq. G.2b) over the groups of correlated inputs, for one
/// output with weighted components `w_i = c_i·u_i` and combined variance `variance`.
/// Written with the shares `u_g²/u_c²` so that it neither overflows nor underflows.
fn welch_satterthwaite(inputs: &Inputs, w: &[f64], variance: f64) -> Dof {
    if variance <= 0.0 {
        return Dof::Infinite;
    }
    let mut denominator = 0.0;
    for group in inputs.groups() {
        let Dof::Finite(nu) = group.dof else { continue };
        let mut ug2 = 0.0;
        for &i in &group.members {
            for &j in &group.members {
                ug2 += w[i] * w[j] * inputs.correlation(i, j);
            }
        }
        let share = ug2.max(0.0) / variance;
        denominator += share * share / nu;
    }
    if denominator > 0.0 {
        let nu = 1.0 / denominator;
        if nu.is_finite() {
            Dof::Finite(nu)
        } else {
            Dof::Infinite
        }
    } else {
        Dof::Infinite
    }
}
