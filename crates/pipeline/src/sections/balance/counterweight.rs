//! The counterweight section: what one change of radius error between two rates (a
//! `radius_change` phase, the paper's one pre-balance number) determines of the correction
//! with a stated radial stiffness (eq. 1, 19).

use std::collections::HashMap;

use balance::{CalibrationContext, CorrectionPlane};

use crate::config::CounterweightConfig;
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::{Check, Core, sorted_names};
use crate::resolved::{PhaseShape, Resolved};
use crate::results::CounterweightResults;

/// The validated counterweight section.
#[derive(Debug, Clone)]
pub(crate) struct CounterweightInputs {
    /// Index of the `radius_change` phase.
    pub(crate) phase: usize,
    pub(crate) from_rate_deg_s: f64,
    pub(crate) to_rate_deg_s: f64,
    pub(crate) change_um: f64,
    pub(crate) radial_stiffness_n_m: f64,
    pub(crate) stiffness_source: String,
    pub(crate) correction_radius_m: f64,
}

/// Runs the counterweight section with the name of its phase.
pub(crate) fn run(
    inputs: &Core,
    c: &CounterweightInputs,
    phase: &str,
) -> Result<CounterweightResults> {
    determine(c, phase, inputs.k1_rad_s_g, inputs.radius_m, inputs.g_m_s2).map_err(|source| {
        PipelineError::Balance {
            path: inputs.source.clone(),
            field: "counterweight".to_owned(),
            source: Box::new(source),
        }
    })
}

/// What one change of radius error determines, and what it does not (the paper check).
fn determine(
    c: &CounterweightInputs,
    phase: &str,
    k1_rad_s_g: f64,
    radius_m: f64,
    g_m_s2: f64,
) -> std::result::Result<CounterweightResults, balance::BalanceError> {
    let to_rate_rad_s = c.to_rate_deg_s.to_radians();
    let plane = CorrectionPlane {
        radius_m: c.correction_radius_m,
        fixed_azimuths_deg: Vec::new(),
    };
    let context = CalibrationContext {
        k1_rad_s_g,
        radius_m,
        g_m_s2,
        top_rate_rad_s: to_rate_rad_s,
        rotor_mass_kg: None,
    };
    let a = balance::radius_change_advice(
        c.change_um,
        c.from_rate_deg_s.to_radians(),
        to_rate_rad_s,
        c.radial_stiffness_n_m,
        &plane,
        &context,
    )?;
    let determined = vec![
        format!(
            "C_r = Δr/(ω₂² − ω₁²) = {:.4e} m·s², the O2X2 component of the dynamic phasor D at the PIGA plane, hence |D| ≥ |C_r| (equal if the imbalance lies on the arm's line)",
            a.c_r_m_s2
        ),
        format!(
            "Δk2 = k1·C_r·g/R² = {:.4e} rad/(s·g²) (eq. 19)",
            a.delta_k2_rad_s_g2
        ),
        format!(
            "with k_r = {:e} N/m (eq. 1): {:.4e} g·mm of unbalance per µm of radius change, so m·R_cm ≥ k_r·|C_r| = {:.4e} g·mm; on the arm's line that is {:.4} kg at {} m, at {}°",
            c.radial_stiffness_n_m,
            a.unbalance_per_um_g_mm,
            a.unbalance_x_g_mm.abs(),
            a.correction_mass_kg,
            c.correction_radius_m,
            a.correction_azimuth_deg
        ),
    ];
    let not_determined = vec![
        "the azimuth of the imbalance: one number along O2X2 says nothing of the O2Y2 component, so the counterweight's azimuth (and its mass, beyond the lower bound) needs a phase of first harmonics (d_c1, d_s1) at several rates".to_owned(),
        "the split between static and dynamic parts: a difference of two rates cancels the static part and cannot test that the change is ∝ ω² (three rates or more give S + D·ω² and its lack of fit)".to_owned(),
        "the plane: one probe cannot separate translation from tilt (static from couple unbalance), so neither the height at which the counterweight goes nor a two-plane correction follows (two probe planes do)".to_owned(),
        "the stiffness itself: k_r is a study input, not a measurement; the mass scales with it".to_owned(),
    ];
    Ok(CounterweightResults {
        phase: phase.to_owned(),
        change_um: c.change_um,
        from_rate_deg_s: c.from_rate_deg_s,
        to_rate_deg_s: c.to_rate_deg_s,
        radial_stiffness_n_m: c.radial_stiffness_n_m,
        stiffness_source: c.stiffness_source.clone(),
        c_r_m_s2: a.c_r_m_s2,
        delta_k2_rad_s_g2: a.delta_k2_rad_s_g2,
        unbalance_per_um_g_mm: a.unbalance_per_um_g_mm,
        unbalance_x_g_mm: a.unbalance_x_g_mm,
        correction_mass_kg: a.correction_mass_kg,
        correction_radius_m: c.correction_radius_m,
        correction_azimuth_deg: a.correction_azimuth_deg,
        determined,
        not_determined,
    })
}

/// The counterweight section: a known `radius_change` phase, a positive stiffness and
/// radius.
pub(crate) fn validate(
    check: &Check<'_>,
    c: &CounterweightConfig,
    resolved: &Resolved<'_>,
    names: &HashMap<&str, usize>,
) -> Result<CounterweightInputs> {
    let Some(&i) = names.get(c.phase.as_str()) else {
        return Err(PipelineError::UnknownPhase {
            path: check.path.to_owned(),
            field: "counterweight.phase".to_owned(),
            name: c.phase.clone(),
            known: sorted_names(names),
        });
    };
    let PhaseShape::RadiusChange {
        from_rate_deg_s,
        to_rate_deg_s,
        change_um,
    } = resolved.phase_shape(i)
    else {
        return Err(PipelineError::Unsupported {
            path: check.path.to_owned(),
            field: "counterweight.phase".to_owned(),
            reason: UnsupportedReason::CounterweightNeedsRadiusChange,
        });
    };
    check.positive("counterweight.radial_stiffness_n_m", c.radial_stiffness_n_m)?;
    check.positive("counterweight.correction_radius_m", c.correction_radius_m)?;
    // The mass scales with k_r, which no measurement here gives: its provenance is part
    // of the result.
    if c.stiffness_source.trim().is_empty() {
        return Err(PipelineError::Unsupported {
            path: check.path.to_owned(),
            field: "counterweight.stiffness_source".to_owned(),
            reason: UnsupportedReason::StiffnessNeedsSource,
        });
    }
    Ok(CounterweightInputs {
        phase: i,
        from_rate_deg_s,
        to_rate_deg_s,
        change_um,
        radial_stiffness_n_m: c.radial_stiffness_n_m,
        stiffness_source: c.stiffness_source.clone(),
        correction_radius_m: c.correction_radius_m,
    })
}
