//! What a study produces; serialised as `results.json` (schema in `docs/RESULTS.md`).

use harmonics::Coefficients;
use serde::{Deserialize, Serialize};

use crate::config::{RadiusModelName, Weighting};

/// All results of a study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyResults {
    /// Name of the study (from the configuration).
    pub study: String,
    /// The scalar inputs the results depend on, echoed for traceability.
    pub inputs: StudyInputs,
    /// Results of each phase, in the study's order.
    pub phases: Vec<PhaseResults>,
    /// The simulated calibration with and without compensation (when configured).
    pub mechanism: Option<MechanismResults>,
}

/// Scalar inputs of the study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StudyInputs {
    /// Working radius `R`, m.
    pub radius_m: f64,
    /// Gravity, m/s².
    pub g_m_s2: f64,
    /// PIGA scale factor, rad/(s·g).
    pub k1_rad_s_g: f64,
    /// Lever ratio from the probe plane to the PIGA plane.
    pub lever_ratio: f64,
}

/// One rate point after the geometry of eq. 21–22.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    /// Rate, deg/s.
    pub rate_deg_s: f64,
    /// Rate, rad/s.
    pub rate_rad_s: f64,
    /// First-harmonic cosine coefficient, µm (absent when the input was a radius error).
    pub dc1_um: Option<f64>,
    /// First-harmonic sine coefficient, µm.
    pub ds1_um: Option<f64>,
    /// First-harmonic amplitude `ΔR1` in the probe plane, µm.
    pub amplitude_um: Option<f64>,
    /// Azimuth `β` of the composite imbalance, degrees.
    pub beta_deg: Option<f64>,
    /// Radius error `Δr_xd + Δr_xs` at the PIGA plane, µm.
    pub radius_error_um: f64,
    /// Standard error of `dc1_um` across revolutions (recordings only), µm.
    pub dc1_sigma_um: Option<f64>,
    /// Standard error of `ds1_um` across revolutions (recordings only), µm.
    pub ds1_sigma_um: Option<f64>,
    /// Standard error of the radius error from the per-revolution fit residuals (recordings
    /// only), µm: `lever ratio × √(Σᵣ 2s²/nᵣ)/K` for K revolutions of nᵣ samples and pooled
    /// residual variance s². Unlike `dc1_sigma_um`, which rests on K − 1 degrees of freedom,
    /// it rests on thousands, so it can weigh the points of a fit.
    pub radius_error_sigma_um: Option<f64>,
    /// Complete revolutions averaged (recordings only).
    pub revolutions: Option<usize>,
    /// Root-mean-square residual of the per-revolution fits (recordings only), µm.
    pub residual_rms_um: Option<f64>,
}

/// A fit of the radius error against rate, and the pseudo-second-order term it implies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelFit {
    /// The model fitted.
    pub model: RadiusModelName,
    /// The coefficient `C_r` of ω², m·s².
    pub c_r_m_s2: f64,
    /// Standard error of `C_r` from the fit's residuals, m·s² (`None` with no degree of freedom).
    pub c_r_sigma_m_s2: Option<f64>,
    /// Constant term `a`, µm.
    pub offset_um: f64,
    /// Linear term `b` of the three-term model, µm·s (`None` for the two-term model).
    pub linear_um_s: Option<f64>,
    /// Residuals (measured − fitted) at each point, µm.
    pub residuals_um: Vec<f64>,
    /// Residual standard deviation `√(Σr²/dof)` of the residuals in µm (`None` with no degree
    /// of freedom).
    pub residual_sd_um: Option<f64>,
    /// How the points were weighted.
    pub weighting: Weighting,
    /// For a weighted fit, `√(χ²/dof)` of the residuals divided by their σ: about 1 when the
    /// per-point σ describe the scatter (`None` for an unweighted fit).
    pub reduced_chi: Option<f64>,
    /// Degrees of freedom of the fit.
    pub dof: usize,
    /// Condition number of the design the solver factorised (`None` for the exact
    /// two-point form, which uses no solver).
    pub condition_number: Option<f64>,
    /// `Δk2 = k1·C_r·g/R²` (eq. 19), rad/(s·g²).
    pub delta_k2_rad_s_g2: f64,
    /// Standard deviation of `Δk2` propagated from that of `C_r`, rad/(s·g²).
    pub delta_k2_sigma_rad_s_g2: Option<f64>,
}

/// Results of one phase.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhaseResults {
    /// The phase's name (from the configuration).
    pub name: String,
    /// Per-rate geometry.
    pub points: Vec<PointResult>,
    /// The fit of the configured model.
    #[serde(flatten)]
    pub fit: ModelFit,
    /// The other radius-error model fitted to the same points, for comparison
    /// (absent when the points cannot support it).
    pub alternative: Option<ModelFit>,
    /// One revolution of each recording with its fit, for the Fig. 4 drawing (not serialised).
    #[serde(skip)]
    pub traces: Vec<ProbeTrace>,
}

/// One revolution of a recording and the fitted eq. 20 curve: the paper's Fig. 4.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ProbeTrace {
    /// Rate, deg/s.
    pub rate_deg_s: f64,
    /// Spindle angle of each shown sample, deg in [0, 360).
    pub angle_deg: Vec<f64>,
    /// Gap of each shown sample, µm.
    pub gap_um: Vec<f64>,
    /// Mean fitted coefficients over the revolutions used, µm.
    pub fit_um: Option<Coefficients>,
}

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

impl StudyResults {
    /// The results of the phase of this name.
    pub fn phase(&self, name: &str) -> Option<&PhaseResults> {
        self.phases.iter().find(|p| p.name == name)
    }
}
