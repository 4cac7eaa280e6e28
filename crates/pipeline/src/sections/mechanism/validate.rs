//! The mechanism section's validation.

use std::collections::HashMap;

use accel_model::PigaCoefficients;

use crate::config::MechanismConfig;
use crate::error::{InvalidReason, PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, MIN_CALIBRATION_RATES, PhaseNames};

/// The validated mechanism section.
#[derive(Debug, Clone)]
pub(crate) struct Mechanism {
    /// Indices of the phases simulated, in the order given.
    pub(crate) phases: Vec<usize>,
    pub(crate) piga: PigaCoefficients,
    pub(crate) latitude_deg: f64,
    pub(crate) earth_rate_rad_s: f64,
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) output_noise_rad_s: f64,
    pub(crate) seed: u64,
}

/// Validates the mechanism section: known phases of the first probe, each once, finite
/// coefficients, a latitude, at least [`MIN_CALIBRATION_RATES`] distinct rates.
pub(crate) fn validate(
    check: &Check<'_>,
    m: &MechanismConfig,
    k1_rad_s_g: f64,
    names: &PhaseNames<'_>,
) -> Result<Mechanism> {
    let phases = match &m.phases {
        // Every phase of the first probe.
        None => {
            let mut all: Vec<usize> = names
                .names
                .values()
                .copied()
                .filter(|p| !names.second_probe.contains(p))
                .collect();
            all.sort_unstable();
            all
        }
        Some(list) => {
            let mut phases = Vec::with_capacity(list.len());
            for (i, name) in list.iter().enumerate() {
                let field = format!("mechanism.phases[{i}]");
                let p = names.index(check, &field, name)?;
                if names.second_probe.contains(&p) {
                    return Err(PipelineError::Unsupported {
                        path: check.path.to_owned(),
                        field,
                        reason: UnsupportedReason::SecondProbeData,
                    });
                }
                if phases.contains(&p) {
                    return Err(PipelineError::DuplicateName {
                        path: check.path.to_owned(),
                        field,
                        first: format!(
                            "mechanism.phases[{}]",
                            phases.iter().position(|&q| q == p).unwrap_or(0)
                        ),
                        name: name.clone(),
                    });
                }
                phases.push(p);
            }
            phases
        }
    };
    for (field, value) in [
        ("mechanism.k0_rad_s", m.k0_rad_s),
        ("mechanism.k2_rad_s_g2", m.k2_rad_s_g2),
        ("mechanism.k3_rad_s_g3", m.k3_rad_s_g3),
    ] {
        check.finite(field.to_owned(), value)?;
    }
    if !(m.latitude_deg.is_finite() && m.latitude_deg.abs() <= 90.0) {
        return Err(check.invalid(
            "mechanism.latitude_deg".to_owned(),
            m.latitude_deg,
            InvalidReason::NotALatitude,
        ));
    }
    for (field, value) in [
        ("mechanism.earth_rate_rad_s", m.earth_rate_rad_s),
        ("mechanism.output_noise_rad_s", m.output_noise_rad_s),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(check.invalid(field.to_owned(), value, InvalidReason::Negative));
        }
    }
    for (i, &rate) in m.rates_deg_s.iter().enumerate() {
        check.rate(format!("mechanism.rates_deg_s[{i}]"), rate)?;
    }
    let mut seen: HashMap<u64, usize> = HashMap::with_capacity(m.rates_deg_s.len());
    for (i, &rate) in m.rates_deg_s.iter().enumerate() {
        if let Some(j) = seen.insert(rate.to_bits(), i) {
            return Err(PipelineError::DuplicateRate {
                path: check.path.to_owned(),
                field: format!("mechanism.rates_deg_s[{i}]"),
                first: format!("mechanism.rates_deg_s[{j}]"),
                rate_deg_s: rate,
            });
        }
    }
    if m.rates_deg_s.len() < MIN_CALIBRATION_RATES {
        return Err(PipelineError::TooFewPoints {
            path: check.path.to_owned(),
            field: "mechanism.rates_deg_s".to_owned(),
            got: m.rates_deg_s.len(),
            need: MIN_CALIBRATION_RATES,
            model: "eq. 18 calibration",
        });
    }
    Ok(Mechanism {
        phases,
        piga: PigaCoefficients {
            k0_rad_s: m.k0_rad_s,
            k1_rad_s_g,
            k2_rad_s_g2: m.k2_rad_s_g2,
            k3_rad_s_g3: m.k3_rad_s_g3,
        },
        latitude_deg: m.latitude_deg,
        earth_rate_rad_s: m.earth_rate_rad_s,
        rates_deg_s: m.rates_deg_s.clone(),
        output_noise_rad_s: m.output_noise_rad_s,
        seed: m.seed,
    })
}
