//! The mechanism section's results: a calibration simulated with each phase's C_r.

use serde::{Deserialize, Serialize};

/// The mechanism section of the results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MechanismResults {
    /// Calibration rates, deg/s.
    pub rates_deg_s: Vec<f64>,
    /// The simulated PIGA.
    pub piga: PigaResult,
    /// Latitude used, degrees.
    pub latitude_deg: f64,
    /// Noise added to each mean output, rad/s.
    pub output_noise_rad_s: f64,
    /// One simulated calibration per phase simulated.
    pub phases: Vec<MechanismPhase>,
}

/// PIGA coefficients as `results.json` writes them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PigaResult {
    /// Bias k0, rad/s.
    pub k0_rad_s: f64,
    /// Scale factor k1, rad/(s·g).
    pub k1_rad_s_g: f64,
    /// Second-order coefficient k2, rad/(s·g²).
    pub k2_rad_s_g2: f64,
    /// Third-order coefficient k3, rad/(s·g³).
    pub k3_rad_s_g3: f64,
}

/// One phase's simulated calibration. Coefficients in rad/(s·g²).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MechanismPhase {
    /// The phase whose C_r was simulated.
    pub phase: String,
    /// The measured C_r the spindle was given, m·s².
    pub c_r_m_s2: f64,
    /// Its standard deviation, m·s² (`None` when the phase has none, e.g. the exact
    /// two-point form; the compensation then takes C_r as exact).
    pub c_r_sigma_m_s2: Option<f64>,
    /// The simulated PIGA's k2.
    pub k2_true: f64,
    /// The a² coefficient of the plain eq. 18 fit: `k2 + Δk2`.
    pub k2_uncompensated: f64,
    /// Its standard error from the fit's residuals.
    pub k2_uncompensated_sigma: f64,
    /// The a² coefficient after removing `k1·C_r·ω⁴/g`.
    pub k2_compensated: f64,
    /// Its standard deviation: the fit's and σ(C_r)'s contributions (`None` when σ(C_r) is
    /// unknown).
    pub k2_compensated_sigma: Option<f64>,
    /// `Δk2 = k1·C_r·g/R²` (eq. 19).
    pub delta_k2_predicted: f64,
    /// `k2_uncompensated − k2_true`: the pseudo-second-order error the fit absorbed.
    pub delta_k2_apparent: f64,
    /// `k2_compensated − k2_true`: what compensation leaves.
    pub k2_error_compensated: f64,
    /// Condition number of the column-scaled eq. 18 design.
    pub condition_number: f64,
}
