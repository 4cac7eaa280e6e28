//! The probe phases' results: each rate point's geometry and the radius-error fit.

use harmonics::Coefficients;
use recording::AngleSourceKind;
use serde::{Deserialize, Serialize};

/// A radius-error model, as `results.json` names it (`two_term`, `three_term`); shown to a
/// person as its formula.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RadiusModel {
    /// `Δr = a + C_r·ω²`, the paper's model.
    TwoTerm,
    /// `Δr = a + b·ω + C_r·ω²`.
    ThreeTerm,
}

impl RadiusModel {
    /// The model's formula: `a + C_r·ω²` or `a + b·ω + C_r·ω²`.
    #[must_use]
    pub const fn formula(self) -> &'static str {
        match self {
            Self::TwoTerm => "a + C_r·ω²",
            Self::ThreeTerm => "a + b·ω + C_r·ω²",
        }
    }
}

impl std::fmt::Display for RadiusModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.formula())
    }
}

/// A human name of a radius-error model (its formula, [`RadiusModel::formula`]).
#[must_use]
pub const fn model_name(model: RadiusModel) -> &'static str {
    model.formula()
}

/// How a radius-error fit weighed its points, as `results.json` names it (`unweighted`,
/// `inverse_variance`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FitWeighting {
    /// Ordinary least squares: every point counts the same.
    Unweighted,
    /// Each point weighted by `1/σ²` of its radius error.
    InverseVariance,
}

impl std::fmt::Display for FitWeighting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Unweighted => "unweighted",
            Self::InverseVariance => "weighted by 1/σ² of each point",
        })
    }
}

/// One rate point after the geometry of eq. 21–22.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    /// Rate, deg/s, as declared in the configuration.
    pub rate_deg_s: f64,
    /// The rate the radius-error fit uses, rad/s: the measured mean rate when the recording
    /// measures the angle (encoder or index pulse), else the declared one.
    pub rate_rad_s: f64,
    /// The measured mean rate, deg/s (recordings with an encoder or index pulse only).
    pub measured_rate_deg_s: Option<f64>,
    /// Where the recording's angle came from (recordings only).
    pub angle_source: Option<AngleSourceKind>,
    /// Revolutions dropped for gaps or non-finite samples (recordings only).
    pub dropped_revolutions: Option<usize>,
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
    /// Standard error of `dc1_um` across revolutions (recordings), or the point's stated
    /// `sigma_um` (first-harmonic points), µm.
    pub dc1_sigma_um: Option<f64>,
    /// Standard error of `ds1_um` across revolutions (recordings), or the point's stated
    /// `sigma_um` (first-harmonic points), µm.
    pub ds1_sigma_um: Option<f64>,
    /// Standard error of the radius error from the per-revolution fit residuals (recordings),
    /// µm: `lever ratio × √(Σᵣ 2s²/nᵣ)/K` for K revolutions of nᵣ samples and pooled
    /// residual variance s²; for first-harmonic points with `sigma_um`, `lever ratio × σ`. Unlike `dc1_sigma_um`, which rests on K − 1 degrees of freedom,
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
    pub model: RadiusModel,
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
    pub weighting: FitWeighting,
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
