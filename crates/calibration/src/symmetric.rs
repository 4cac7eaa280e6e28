//! The two-orientation (IA in / IA out) calibration of issue 20 (`docs/theory.md` section
//! 11, `docs/SYMMETRIC.md`): one joint least-squares fit of eq. 23,
//!
//! ```text
//! λ̇_s = k0,s + s·(b1,s·ω + k1,s·a_s + b3·ω³ + γ·ω⁴ + k3·a_s³) + k2·a_s² + ε,   a_s = R_s·ω²/g
//! ```
//!
//! with `s = +1` (IA in) or `−1` (IA out), `γ = k1·C/g`, and `C = C_r + C_a` the total dynamic
//! radius growth at the PIGA. It measures k2 and C from the PIGA's own output, with no probe;
//! with a probe's `C_r` as well, `C − C_r` is the growth the probe does not see (arm stretch)
//! — or a wrong probe declaration.

use identify::{Fit, IdentifyError, LstsqOptions, lstsq_with};
use uncertainty::{
    Dof, GumOptions, GumResult, InputQuantity, McOptions, McResult, MeasurementModel, ModelError,
    UncertaintyError,
};

/// Which way the PIGA's input axis points on the arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Towards the spindle axis (the paper's mounting), s = +1.
    IaIn,
    /// Away from the spindle axis, s = −1.
    IaOut,
}

impl Orientation {
    /// `s`: +1 for IA in, −1 for IA out.
    #[must_use]
    pub const fn sign(self) -> f64 {
        match self {
            Self::IaIn => 1.0,
            Self::IaOut => -1.0,
        }
    }

    /// Words for a reader: `IA in` / `IA out`.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::IaIn => "IA in",
            Self::IaOut => "IA out",
        }
    }

    const fn index(self) -> usize {
        match self {
            Self::IaIn => 0,
            Self::IaOut => 1,
        }
    }
}

/// Least number of distinct rates per orientation: the six of a single eq. 18 fit, so that
/// each mounting could also be fitted on its own (the joint fit itself needs four).
pub const MIN_RATES_PER_ORIENTATION: usize = 6;

/// Number of coefficients of eq. 23.
pub const SYMMETRIC_TERMS: usize = 10;

/// The coefficients of eq. 23 in the fit's order.
pub const SYMMETRIC_TERM_NAMES: [&str; SYMMETRIC_TERMS] = [
    "k0 (IA in)",
    "b1 (IA in)",
    "k1 (IA in)",
    "k0 (IA out)",
    "b1 (IA out)",
    "k1 (IA out)",
    "b3",
    "k2",
    "k3",
    "gamma = k1·C/g",
];

/// Index of the k2 coefficient.
pub const K2_TERM: usize = 7;
/// Index of the `s·ω⁴` coefficient γ = k1·C/g.
pub const GAMMA_TERM: usize = 9;

/// A variance inflation factor of the `s·ω⁴` term above which C cannot be told apart from the
/// other terms (issue 20).
pub const GAMMA_VIF_LIMIT: f64 = 1e4;

/// The |z| above which `C − C_r` is reported as a disagreement between the PIGA and the probe.
pub const Z_LIMIT: f64 = 3.0;

/// One orientation's data set: a PIGA table (or the points reduced from raw recordings).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientationData<'a> {
    /// Where it came from, for errors (`symmetric.orientations[1]`).
    pub field: &'a str,
    /// IA in or out (`None`: not declared).
    pub orientation: Option<Orientation>,
    /// The mounting's static radius, m (`None`: not declared).
    pub radius_m: Option<f64>,
    /// Spindle rates, rad/s.
    pub rates_rad_s: &'a [f64],
    /// Mean PIGA outputs, rad/s.
    pub output_rad_s: &'a [f64],
    /// Standard uncertainties of the outputs, rad/s (raw recordings); `None`: unweighted.
    pub sigma_rad_s: Option<&'a [f64]>,
}

/// What a two-orientation calibration refuses. Every variant names the data set's field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SymmetricError {
    /// Fewer or more than two data sets, or one orientation only.
    #[error(
        "{field}: a two-orientation calibration needs one data set with the IA in and one with the IA out; got {got}"
    )]
    OneOrientationOnly {
        /// The list's field.
        field: String,
        /// What was given, in words.
        got: String,
    },
    /// Both data sets declare the same orientation.
    #[error(
        "{field}: both data sets are `{orientation}` (`{first}` and `{field}`); one must be IA in and the other IA out"
    )]
    SameOrientation {
        /// The second data set.
        field: String,
        /// The first.
        first: String,
        /// Their orientation, in words.
        orientation: &'static str,
    },
    /// A data set does not declare its orientation.
    #[error("{field}: the orientation is missing (`ia_in` or `ia_out`)")]
    MissingOrientation {
        /// The data set.
        field: String,
    },
    /// A data set does not declare its radius.
    #[error(
        "{field}: the radius is missing (`radius_m`: the PIGA's centre of mass to the spindle axis in this mounting)"
    )]
    MissingRadius {
        /// The data set.
        field: String,
    },
    /// A number outside its domain.
    #[error("{field} = {value}: {reason}")]
    Invalid {
        /// The field.
        field: String,
        /// Its value.
        value: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// Too few distinct rates in one orientation.
    #[error(
        "{field}: {distinct} distinct rates in the {orientation} data set; the joint model needs at least {need} per orientation"
    )]
    TooFewRates {
        /// The data set.
        field: String,
        /// Its orientation, in words.
        orientation: &'static str,
        /// Distinct rates given.
        distinct: usize,
        /// Distinct rates needed.
        need: usize,
    },
    /// The least-squares fit failed.
    #[error("the two-orientation fit: {0}")]
    Fit(#[source] IdentifyError),
    /// The uncertainty evaluation failed.
    #[error("the two-orientation uncertainty: {0}")]
    Uncertainty(#[source] UncertaintyError),
}

/// One mounting's own coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountingFit {
    /// IA in or out.
    pub orientation: Orientation,
    /// Its static radius, m.
    pub radius_m: f64,
    /// Distinct rates in its data set.
    pub distinct_rates: usize,
    /// `k0,s` (bias with the gravity seen through the tilt), rad/s, and its standard error.
    pub k0_rad_s: (f64, f64),
    /// `b1,s` (the ω nuisance term: tilt, Coriolis, alignment), and its standard error.
    pub b1: (f64, f64),
    /// `k1,s`, rad/(s·g), and its standard error.
    pub k1_rad_s_g: (f64, f64),
}

/// The joint fit of eq. 23.
#[derive(Debug, Clone, PartialEq)]
pub struct SymmetricFit {
    /// IA in, then IA out.
    pub mountings: [MountingFit; 2],
    /// `k2` from the PIGA alone, rad/(s·g²), and its standard error.
    pub k2_rad_s_g2: (f64, f64),
    /// `k3`, rad/(s·g³), and its standard error.
    pub k3_rad_s_g3: (f64, f64),
    /// `b3` (ω³ nuisance term), and its standard error.
    pub b3: (f64, f64),
    /// `γ = k1·C/g` (coefficient of `s·ω⁴`), rad·s³, and its standard error.
    pub gamma: (f64, f64),
    /// `C = γ·g/k̄1`, m·s², with `k̄1` the mean of the two `k1,s`, and its standard error
    /// (first order, from the fit's covariance).
    pub c_m_s2: (f64, f64),
    /// `Δk2,total = k̄1·C·g/R_in²` at the IA-in radius, rad/(s·g²), and its standard error.
    pub delta_k2_total_rad_s_g2: (f64, f64),
    /// Variance inflation factor of the `s·ω⁴` column.
    pub gamma_vif: f64,
    /// Gravity used to form `a_s`, m/s².
    pub g_m_s2: f64,
    /// Residuals `output − fitted`, rad/s, IA in's points then IA out's, each in its data
    /// set's order.
    pub residuals_rad_s: [Vec<f64>; 2],
    /// Birge ratio `√(χ²/ν)` of a weighted fit (`None` unweighted).
    pub birge_ratio: Option<f64>,
    /// The least-squares fit (coefficients in [`SYMMETRIC_TERM_NAMES`]' order; for a weighted
    /// fit the covariance is `(XᵀWX)⁻¹` times the squared Birge ratio when above 1).
    pub fit: Fit,
}

impl SymmetricFit {
    /// Whether the `s·ω⁴` term can be told apart from the others (VIF ≤ 1e4).
    #[must_use]
    pub fn separable(&self) -> bool {
        self.gamma_vif <= GAMMA_VIF_LIMIT
    }

    /// The mounting of an orientation.
    #[must_use]
    pub const fn mounting(&self, o: Orientation) -> &MountingFit {
        &self.mountings[o.index()]
    }
}

fn distinct(rates: &[f64]) -> usize {
    let mut v: Vec<f64> = rates.to_vec();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.len()
}

/// One row of eq. 23's design for a point of orientation `o` at radius `radius_m`.
#[must_use]
pub fn symmetric_row(
    o: Orientation,
    radius_m: f64,
    g_m_s2: f64,
    rate_rad_s: f64,
) -> [f64; SYMMETRIC_TERMS] {
    let s = o.sign();
    let w = rate_rad_s;
    let a = radius_m * w * w / g_m_s2;
    let mut row = [0.0; SYMMETRIC_TERMS];
    let base = 3 * o.index();
    row[base] = 1.0;
    row[base + 1] = s * w;
    row[base + 2] = s * a;
    row[6] = s * w * w * w;
    row[K2_TERM] = a * a;
    row[8] = s * a * a * a;
    row[GAMMA_TERM] = s * w * w * w * w;
    row
}

/// Checks the data sets and returns them as (IA in, IA out) with their radii.
fn check<'a>(
    data: &[OrientationData<'a>],
    list_field: &str,
) -> Result<[(OrientationData<'a>, f64); 2], SymmetricError> {
    let describe = |d: &[OrientationData<'_>]| {
        let words: Vec<&str> = d
            .iter()
            .map(|x| x.orientation.map_or("undeclared", Orientation::label))
            .collect();
        if words.is_empty() {
            "no data set".to_owned()
        } else {
            format!("{} data set(s): {}", d.len(), words.join(", "))
        }
    };
    for d in data {
        if d.orientation.is_none() {
            return Err(SymmetricError::MissingOrientation {
                field: d.field.to_owned(),
            });
        }
    }
    if data.len() == 2 && data[0].orientation == data[1].orientation {
        let o = data[0].orientation.unwrap_or(Orientation::IaIn);
        return Err(SymmetricError::SameOrientation {
            field: data[1].field.to_owned(),
            first: data[0].field.to_owned(),
            orientation: o.label(),
        });
    }
    if data.len() != 2 {
        return Err(SymmetricError::OneOrientationOnly {
            field: list_field.to_owned(),
            got: describe(data),
        });
    }
    let mut out: [Option<(OrientationData<'a>, f64)>; 2] = [None, None];
    for d in data {
        let Some(o) = d.orientation else { continue };
        let Some(r) = d.radius_m else {
            return Err(SymmetricError::MissingRadius {
                field: d.field.to_owned(),
            });
        };
        if !(r.is_finite() && r > 0.0) {
            return Err(SymmetricError::Invalid {
                field: format!("{}.radius_m", d.field),
                value: r,
                reason: "must be finite and > 0",
            });
        }
        if d.rates_rad_s.len() != d.output_rad_s.len() {
            return Err(SymmetricError::Invalid {
                field: format!("{}.output_rad_s", d.field),
                value: d.output_rad_s.len() as f64,
                reason: "must have one output per rate",
            });
        }
        for (i, (&w, &y)) in d.rates_rad_s.iter().zip(d.output_rad_s).enumerate() {
            if !w.is_finite() {
                return Err(SymmetricError::Invalid {
                    field: format!("{}.rates[{i}]", d.field),
                    value: w,
                    reason: "a rate must be finite",
                });
            }
            if !y.is_finite() {
                return Err(SymmetricError::Invalid {
                    field: format!("{}.outputs[{i}]", d.field),
                    value: y,
                    reason: "an output must be finite",
                });
            }
        }
        if let Some(sig) = d.sigma_rad_s {
            if sig.len() != d.rates_rad_s.len() {
                return Err(SymmetricError::Invalid {
                    field: format!("{}.sigma_rad_s", d.field),
                    value: sig.len() as f64,
                    reason: "must have one σ per rate",
                });
            }
            if let Some((i, &s)) = sig
                .iter()
                .enumerate()
                .find(|(_, s)| !(s.is_finite() && **s > 0.0))
            {
                return Err(SymmetricError::Invalid {
                    field: format!("{}.sigma_rad_s[{i}]", d.field),
                    value: s,
                    reason: "a σ must be finite and > 0",
                });
            }
        }
        let n = distinct(d.rates_rad_s);
        if n < MIN_RATES_PER_ORIENTATION {
            return Err(SymmetricError::TooFewRates {
                field: d.field.to_owned(),
                orientation: o.label(),
                distinct: n,
                need: MIN_RATES_PER_ORIENTATION,
            });
        }
        out[o.index()] = Some((*d, r));
    }
    match out {
        [Some(a), Some(b)] => Ok([a, b]),
        _ => Err(SymmetricError::OneOrientationOnly {
            field: list_field.to_owned(),
            got: describe(data),
        }),
    }
}

/// Fits eq. 23 to two data sets, one per orientation, by `identify`'s QR with column scaling
/// (covariance from the residuals; weighted by `1/σᵢ` when both sets give σ, with the
/// Birge-ratio policy of `identify::identify_calibration_weighted`).
///
/// `list_field` names the list of data sets in errors (`symmetric.orientations`).
///
/// # Errors
/// [`SymmetricError::OneOrientationOnly`] unless there are exactly two sets, one per
/// orientation; [`SymmetricError::SameOrientation`]; [`SymmetricError::MissingOrientation`];
/// [`SymmetricError::MissingRadius`]; [`SymmetricError::TooFewRates`] for fewer than
/// [`MIN_RATES_PER_ORIENTATION`] distinct rates in a set; [`SymmetricError::Invalid`] for a
/// non-finite number, mismatched lengths or a non-positive g or σ;
/// [`SymmetricError::Fit`] from the solver (e.g. a rank-deficient design).
pub fn fit_symmetric(
    data: &[OrientationData<'_>],
    g_m_s2: f64,
    list_field: &str,
) -> Result<SymmetricFit, SymmetricError> {
    if !(g_m_s2.is_finite() && g_m_s2 > 0.0) {
        return Err(SymmetricError::Invalid {
            field: "g_m_s2".to_owned(),
            value: g_m_s2,
            reason: "must be finite and > 0",
        });
    }
    let sets = check(data, list_field)?;
    let weighted = sets.iter().all(|(d, _)| d.sigma_rad_s.is_some());
    let rows: usize = sets.iter().map(|(d, _)| d.rates_rad_s.len()).sum();
    let mut x = nalgebra::DMatrix::zeros(rows, SYMMETRIC_TERMS);
    let mut y = Vec::with_capacity(rows);
    let mut weights = Vec::with_capacity(rows);
    let mut r = 0;
    for (d, radius) in &sets {
        let o = d.orientation.unwrap_or(Orientation::IaIn);
        for (i, (&w, &out)) in d.rates_rad_s.iter().zip(d.output_rad_s).enumerate() {
            let row = symmetric_row(o, *radius, g_m_s2, w);
            let wt = if weighted {
                d.sigma_rad_s.map_or(1.0, |s| 1.0 / s[i])
            } else {
                1.0
            };
            for (j, v) in row.iter().enumerate() {
                x[(r, j)] = v * wt;
            }
            y.push(out * wt);
            weights.push(wt);
            r += 1;
        }
    }
    let mut fit = lstsq_with(&x, &y, &LstsqOptions::default()).map_err(SymmetricError::Fit)?;
    let birge_ratio = weighted.then(|| {
        let chi2: f64 = fit.residuals.iter().map(|e| e * e).sum();
        (chi2 / fit.dof.max(1) as f64).sqrt()
    });
    if let Some(b) = birge_ratio {
        // the σᵢ taken as known: (XᵀWX)⁻¹, enlarged by the Birge ratio when above 1
        let scale = b.max(1.0).powi(2);
        fit.covariance = &fit.unscaled_covariance * scale;
        fit.std_errors = (0..SYMMETRIC_TERMS)
            .map(|j| fit.covariance[(j, j)].sqrt())
            .collect();
    }
    let residuals_all: Vec<f64> = fit
        .residuals
        .iter()
        .zip(&weights)
        .map(|(e, w)| e / w)
        .collect();
    let n_in = sets[0].0.rates_rad_s.len();
    let residuals_rad_s = [
        residuals_all[..n_in].to_vec(),
        residuals_all[n_in..].to_vec(),
    ];

    let c = &fit.coefficients;
    let se = &fit.std_errors;
    let cov = &fit.covariance;
    let pair = |j: usize| (c[j], se[j]);
    let mountings = [0, 1].map(|k| {
        let (d, radius) = &sets[k];
        MountingFit {
            orientation: if k == 0 {
                Orientation::IaIn
            } else {
                Orientation::IaOut
            },
            radius_m: *radius,
            distinct_rates: distinct(d.rates_rad_s),
            k0_rad_s: pair(3 * k),
            b1: pair(3 * k + 1),
            k1_rad_s_g: pair(3 * k + 2),
        }
    });
    // C = γ·g/k̄1, k̄1 = (k1,+ + k1,−)/2: first-order standard error through the gradient
    let k1_mean = 0.5 * (c[2] + c[5]);
    let gamma = c[GAMMA_TERM];
    let c_value = gamma * g_m_s2 / k1_mean;
    let mut grad = [0.0; SYMMETRIC_TERMS];
    grad[GAMMA_TERM] = g_m_s2 / k1_mean;
    grad[2] = -0.5 * c_value / k1_mean;
    grad[5] = -0.5 * c_value / k1_mean;
    let mut var_c = 0.0;
    for a in 0..SYMMETRIC_TERMS {
        for b in 0..SYMMETRIC_TERMS {
            var_c += grad[a] * cov[(a, b)] * grad[b];
        }
    }
    let r_in = sets[0].1;
    let dk2_scale = g_m_s2 * g_m_s2 / (r_in * r_in);
    let gamma_vif = vif(&x, &weights, &fit, GAMMA_TERM);
    let result = SymmetricFit {
        mountings,
        k2_rad_s_g2: pair(K2_TERM),
        k3_rad_s_g3: pair(8),
        b3: pair(6),
        gamma: pair(GAMMA_TERM),
        c_m_s2: (c_value, var_c.max(0.0).sqrt()),
        delta_k2_total_rad_s_g2: (gamma * dk2_scale, se[GAMMA_TERM] * dk2_scale),
        gamma_vif,
        g_m_s2,
        residuals_rad_s,
        birge_ratio,
        fit,
    };
    Ok(result)
}

/// Variance inflation factor of column `j` (the design rows already weighted): `VIF_j =
/// [(XᵀWX)⁻¹]_jj · Σᵢ (x_ij − x̄_j)²` about the weighted mean, the form of
/// `crate::variance_inflation` (valid with intercept columns; eq. 23 has one per
/// orientation, whose sum is the constant column).
fn vif(x: &nalgebra::DMatrix<f64>, weights: &[f64], fit: &Fit, j: usize) -> f64 {
    let w2: Vec<f64> = weights.iter().map(|w| w * w).collect();
    let total: f64 = w2.iter().sum();
    let raw = |i: usize| x[(i, j)] / weights[i];
    let mean = (0..x.nrows()).map(|i| raw(i) * w2[i]).sum::<f64>() / total;
    let ss: f64 = (0..x.nrows())
        .map(|i| w2[i] * (raw(i) - mean) * (raw(i) - mean))
        .sum();
    fit.unscaled_covariance[(j, j)] * ss
}

/// The probe's C_r as an input of the two-orientation evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeCr {
    /// C_r from the probe, m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub u_m_s2: f64,
    /// Its degrees of freedom (`None`: infinite).
    pub dof: Option<f64>,
}

/// Names of the outputs of [`SymmetricModel`], in order (the last only with a probe).
pub const SYMMETRIC_OUTPUTS: [&str; 9] = [
    "k0 (IA in)",
    "k1 (IA in)",
    "k0 (IA out)",
    "k1 (IA out)",
    "k2",
    "k3",
    "C",
    "Δk2,total",
    "C − C_r",
];

/// The measurement model of the two-orientation calibration: outputs
/// [`SYMMETRIC_OUTPUTS`] from the ten coefficients of eq. 23 (one correlated Type A group),
/// g, and, with a probe, its C_r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetricModel {
    /// The IA-in radius, m, for Δk2,total.
    pub radius_in_m: f64,
    /// Whether the probe's C_r is an input (and `C − C_r` an output).
    pub with_probe: bool,
}

impl SymmetricModel {
    /// Number of outputs.
    #[must_use]
    pub const fn output_count(&self) -> usize {
        if self.with_probe { 9 } else { 8 }
    }
}

impl MeasurementModel for SymmetricModel {
    fn output_names(&self) -> Vec<String> {
        SYMMETRIC_OUTPUTS[..self.output_count()]
            .iter()
            .map(|s| (*s).to_owned())
            .collect()
    }

    fn input_count(&self) -> Option<usize> {
        Some(SYMMETRIC_TERMS + 1 + usize::from(self.with_probe))
    }

    fn evaluate(&self, x: &[f64], y: &mut [f64]) -> Result<(), ModelError> {
        let c = &x[..SYMMETRIC_TERMS];
        let g = x[SYMMETRIC_TERMS];
        let k1_mean = 0.5 * (c[2] + c[5]);
        let c_total = c[GAMMA_TERM] * g / k1_mean;
        y[0] = c[0];
        y[1] = c[2];
        y[2] = c[3];
        y[3] = c[5];
        y[4] = c[K2_TERM];
        y[5] = c[8];
        y[6] = c_total;
        y[7] = c[GAMMA_TERM] * g * g / (self.radius_in_m * self.radius_in_m);
        if self.with_probe {
            y[8] = c_total - x[SYMMETRIC_TERMS + 1];
        }
        Ok(())
    }
}

/// The inputs of [`SymmetricModel`] for a fit: the ten coefficients as one Type A group
/// correlated through the fit's covariance (degrees of freedom `n − 10`), g with its Type B
/// standard uncertainty, and the probe's C_r.
///
/// # Errors
/// Those of [`uncertainty::Inputs::with_correlation`].
pub fn symmetric_inputs(
    fit: &SymmetricFit,
    g_u_m_s2: f64,
    probe: Option<ProbeCr>,
) -> Result<uncertainty::Inputs, UncertaintyError> {
    let f = &fit.fit;
    let dof = Dof::Finite(f.dof as f64);
    let mut q: Vec<InputQuantity> = SYMMETRIC_TERM_NAMES
        .iter()
        .enumerate()
        .map(|(j, name)| {
            InputQuantity::type_a(
                format!("fit coefficient {name}"),
                f.coefficients[j],
                f.std_errors[j],
                dof,
            )
        })
        .collect();
    q.push(InputQuantity::normal("g", fit.g_m_s2, g_u_m_s2));
    if let Some(p) = probe {
        let d = p.dof.map_or(Dof::Infinite, Dof::Finite);
        q.push(InputQuantity::type_a(
            "C_r (probe)",
            p.c_r_m_s2,
            p.u_m_s2,
            d,
        ));
    }
    let m = q.len();
    let mut r = vec![0.0; m * m];
    for i in 0..m {
        r[i * m + i] = 1.0;
    }
    for a in 0..SYMMETRIC_TERMS {
        for b in 0..SYMMETRIC_TERMS {
            let d = f.std_errors[a] * f.std_errors[b];
            if a != b && d > 0.0 {
                r[a * m + b] = (f.covariance[(a, b)] / d).clamp(-1.0, 1.0);
            }
        }
    }
    uncertainty::Inputs::with_correlation(q, &r)
}

/// What the two-orientation evaluation warns about.
#[derive(Debug, Clone, PartialEq)]
pub enum SymmetricWarning {
    /// The `s·ω⁴` term cannot be told apart from the others: C and k2 are not separated.
    GammaNotSeparable {
        /// Its variance inflation factor.
        vif: f64,
    },
    /// The PIGA's C and the probe's C_r disagree (|z| > 3): radius growth the probe does not
    /// see (arm stretch), or the probe's declared sign, unit or lever is wrong.
    ProbeDisagrees {
        /// `C − C_r`, m·s².
        difference_m_s2: f64,
        /// Its standard uncertainty, m·s².
        u_m_s2: f64,
        /// `z = (C − C_r)/u`.
        z: f64,
    },
}

/// The two-orientation calibration evaluated: the GUM (with its budget) and, when asked, the
/// Monte Carlo method on [`SymmetricModel`], with `C − C_r` and its z when a probe is given.
#[derive(Debug, Clone)]
pub struct SymmetricEvaluation {
    /// The model evaluated.
    pub model: SymmetricModel,
    /// Its inputs.
    pub inputs: uncertainty::Inputs,
    /// The GUM evaluation (outputs [`SYMMETRIC_OUTPUTS`]).
    pub gum: GumResult,
    /// The Monte Carlo evaluation, when asked for.
    pub monte_carlo: Option<McResult>,
    /// With a probe: `(C − C_r, u, z)`.
    pub probe_difference: Option<(f64, f64, f64)>,
    /// Warnings, in words a reader can act on ([`SymmetricWarning`]).
    pub warnings: Vec<SymmetricWarning>,
}

/// Evaluates the uncertainty of a two-orientation fit through `uncertainty`'s GUM and
/// (with `mc`) Monte Carlo method, compares C with the probe's C_r when given, and collects
/// the warnings (a non-separable `s·ω⁴` term; |z| > 3).
///
/// # Errors
/// [`SymmetricError::Uncertainty`] from the inputs, the GUM or the Monte Carlo method.
pub fn evaluate_symmetric(
    fit: &SymmetricFit,
    g_u_m_s2: f64,
    probe: Option<ProbeCr>,
    mc: Option<&McOptions>,
) -> Result<SymmetricEvaluation, SymmetricError> {
    let model = SymmetricModel {
        radius_in_m: fit.mountings[0].radius_m,
        with_probe: probe.is_some(),
    };
    let inputs = symmetric_inputs(fit, g_u_m_s2, probe).map_err(SymmetricError::Uncertainty)?;
    let gum = uncertainty::gum(&model, &inputs, &GumOptions::default())
        .map_err(SymmetricError::Uncertainty)?;
    let monte_carlo = mc
        .map(|o| uncertainty::monte_carlo(&model, &inputs, o))
        .transpose()
        .map_err(SymmetricError::Uncertainty)?;
    let mut warnings = Vec::new();
    if !fit.separable() {
        warnings.push(SymmetricWarning::GammaNotSeparable { vif: fit.gamma_vif });
    }
    let probe_difference = probe.is_some().then(|| {
        let o = &gum.outputs[8];
        let z = if o.standard_uncertainty > 0.0 {
            o.estimate / o.standard_uncertainty
        } else {
            0.0
        };
        (o.estimate, o.standard_uncertainty, z)
    });
    if let Some((d, u, z)) = probe_difference
        && z.abs() > Z_LIMIT
    {
        warnings.push(SymmetricWarning::ProbeDisagrees {
            difference_m_s2: d,
            u_m_s2: u,
            z,
        });
    }
    Ok(SymmetricEvaluation {
        model,
        inputs,
        gum,
        monte_carlo,
        probe_difference,
        warnings,
    })
}
