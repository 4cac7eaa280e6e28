//! The uncertainty of a two-orientation fit: the measurement model of its outputs, its
//! inputs, the GUM and Monte Carlo evaluation, the comparison of C with the probe's C_r and
//! the warnings.

use uncertainty::{
    Dof, GumOptions, GumResult, InputQuantity, McOptions, McResult, MeasurementModel, ModelError,
    UncertaintyError,
};

use super::error::SymmetricError;
use super::fit::SymmetricFit;
use super::terms::{GAMMA_TERM, K2_TERM, SYMMETRIC_TERM_NAMES, SYMMETRIC_TERMS, Z_LIMIT};

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
    /// The `s·ω⁴` term cannot be told apart from k2: fitting C widens u(k2) more than
    /// [`K2_INFLATION_LIMIT`](crate::K2_INFLATION_LIMIT) times.
    GammaNotSeparable {
        /// Its variance inflation factor (a diagnostic).
        vif: f64,
        /// u(k2) in the joint fit over u(k2) with C known.
        k2_inflation: f64,
        /// Correlation of the k2 and C estimates.
        correlation: f64,
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
        warnings.push(SymmetricWarning::GammaNotSeparable {
            vif: fit.gamma_vif,
            k2_inflation: fit.k2_inflation,
            correlation: fit.k2_gamma_correlation,
        });
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
