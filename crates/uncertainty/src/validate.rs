//! Validation of the GUM uncertainty framework by the Monte Carlo method (JCGM 101 §8).

use crate::error::{Result, UncertaintyError};
use crate::gum::GumResult;
use crate::monte_carlo::McResult;
use crate::tolerance::numerical_tolerance;

/// The comparison of one output's coverage intervals (JCGM 101 §8.2).
#[derive(Debug, Clone, PartialEq)]
pub struct OutputValidation {
    /// The output.
    pub name: String,
    /// Numerical tolerance δ of the GUM standard uncertainty `u_c(y)` with `n_dig` digits.
    pub tolerance: f64,
    /// `d_low = |y − U_p − y_low|`: GUM lower limit against the Monte Carlo one.
    pub d_low: f64,
    /// `d_high = |y + U_p − y_high|`: GUM upper limit against the Monte Carlo one.
    pub d_high: f64,
    /// `d_low ≤ δ` and `d_high ≤ δ`: the GUM uncertainty framework is validated for this
    /// output.
    pub agrees: bool,
}

/// The validation of every output.
#[derive(Debug, Clone, PartialEq)]
pub struct Validation {
    /// The number of significant digits of the tolerance.
    pub n_dig: u32,
    /// One per output, in model order.
    pub outputs: Vec<OutputValidation>,
}

impl Validation {
    /// Whether every output agrees.
    pub fn all_agree(&self) -> bool {
        self.outputs.iter().all(|o| o.agrees)
    }

    /// The output named `name`.
    pub fn output(&self, name: &str) -> Option<&OutputValidation> {
        self.outputs.iter().find(|o| o.name == name)
    }
}

/// Validates the GUM result by the Monte Carlo result (JCGM 101 §8.2): for each output, the
/// numerical tolerance δ of `u_c(y)` with `n_dig` significant digits (§7.9.2), and the
/// distances of the GUM coverage interval `y ± U_p` from the Monte Carlo one,
/// `d_low = |y − U_p − y_low|`, `d_high = |y + U_p − y_high|`. The GUM result is validated
/// when both are at most δ. The Monte Carlo result should itself have been obtained with a
/// tolerance at least as fine (JCGM 101 §8.3: the same `n_dig`, adaptively).
///
/// Errors: the results name different outputs, or have different coverage probabilities.
pub fn validate(gum: &GumResult, mc: &McResult, n_dig: u32) -> Result<Validation> {
    if gum.coverage_probability != mc.coverage_probability {
        return Err(UncertaintyError::CoverageProbabilityMismatch {
            gum: gum.coverage_probability,
            mc: mc.coverage_probability,
        });
    }
    let count = gum.outputs.len().max(mc.outputs.len());
    for index in 0..count {
        let g = gum.outputs.get(index).map(|o| o.name.as_str());
        let m = mc.outputs.get(index).map(|o| o.name.as_str());
        if g != m {
            return Err(UncertaintyError::OutputMismatch {
                index,
                gum: g.unwrap_or_default().to_string(),
                mc: m.unwrap_or_default().to_string(),
            });
        }
    }
    let outputs = gum
        .outputs
        .iter()
        .zip(&mc.outputs)
        .map(|(g, m)| {
            let tolerance = numerical_tolerance(g.standard_uncertainty, n_dig);
            let (low, high) = g.coverage_interval();
            let d_low = (low - m.coverage_interval.0).abs();
            let d_high = (high - m.coverage_interval.1).abs();
            OutputValidation {
                name: g.name.clone(),
                tolerance,
                d_low,
                d_high,
                agrees: d_low <= tolerance && d_high <= tolerance,
            }
        })
        .collect();
    Ok(Validation { n_dig, outputs })
}
