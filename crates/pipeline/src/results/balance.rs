//! The balance and counterweight sections' results (`docs/BALANCING.md`).

use serde::{Deserialize, Serialize};

/// The balance advisor's results (`balance` in results.json; `docs/BALANCING.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BalanceResults {
    /// The phase run as found.
    pub initial: String,
    /// The phase run with the trial mass, if any.
    pub trial: Option<String>,
    /// What one probe plane cannot separate (the cone assumption of eq. 22).
    pub assumption: String,
    /// The initial phase's static phasor at the PIGA plane.
    #[serde(rename = "static")]
    pub static_phasor: StaticPhasor,
    /// The initial phase's dynamic phasor at the PIGA plane.
    pub dynamic: DynamicPhasor,
    /// Every phase the advisor fitted (initial, trial, check), for the polar plot.
    pub phases: Vec<BalancePhase>,
    /// Influence coefficient at the PIGA plane, when there is a trial run.
    pub influence: Option<Influence>,
    /// The recommended correction (influence coefficient when there is a trial run, else the
    /// stiffness model).
    pub correction: CorrectionResult,
    /// What the recommended correction leaves.
    pub predicted: PredictedResult,
    /// The stiffness-model reading (eq. 1), when the radial stiffness is given.
    pub stiffness: Option<StiffnessResult>,
    /// The check run against the prediction, when configured.
    pub check: Option<CheckResult>,
    /// Two probe planes: translation and tilt, static and couple unbalance, the two-plane
    /// correction (absent with one probe).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub two_plane: Option<TwoPlaneResults>,
}

/// A phasor in `O2` with standard uncertainties; its unit is named by the key holding it
/// (`static_translation_um`, `couple_kg_m2`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PhasorResult {
    /// Magnitude, in the key's unit.
    pub magnitude: f64,
    /// Its standard uncertainty.
    pub magnitude_u: f64,
    /// Azimuth from O2X2 towards O2Y2, deg.
    pub azimuth_deg: f64,
    /// Its standard uncertainty, deg.
    pub azimuth_u_deg: f64,
    /// Component along O2X2.
    pub x: f64,
    /// Component along O2Y2.
    pub y: f64,
}

/// Two probe planes (`balance.two_plane`): the axis as a line, no cone assumption.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwoPlaneResults {
    /// Heights of the first and the second probe plane above the PIGA plane, m.
    pub probe_heights_m: [f64; 2],
    /// The second probe's phase of the initial run.
    pub second_probe_phase: String,
    /// Static translation of the axis at the PIGA plane, µm.
    pub static_translation_um: PhasorResult,
    /// Static lean of the axis, µrad.
    pub static_tilt_urad: PhasorResult,
    /// Dynamic (∝ ω²) translation at the PIGA plane, µm·s²; its `x` is C_r.
    pub dynamic_translation_um_s2: PhasorResult,
    /// Dynamic lean, µrad·s².
    pub dynamic_tilt_urad_s2: PhasorResult,
    /// C_r at the PIGA plane from the two planes, m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub c_r_u_m_s2: f64,
    /// How static and couple unbalance were obtained: `stiffness_model` (both stiffnesses
    /// given) or `influence_coefficient` (from the two-plane correction); absent: neither.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unbalance_method: Option<String>,
    /// Static unbalance `Σ m·r·e^{iθ}`, kg·m.
    #[serde(rename = "static", default, skip_serializing_if = "Option::is_none")]
    pub static_kg_m: Option<PhasorResult>,
    /// Couple unbalance about the PIGA plane `Σ m·r·l·e^{iθ}`, kg·m².
    #[serde(rename = "couple", default, skip_serializing_if = "Option::is_none")]
    pub couple_kg_m2: Option<PhasorResult>,
    /// Per rate: `[rate_deg_s, translation x µm, y µm, tilt x µrad, y µrad]`.
    pub per_rate: Vec<[f64; 5]>,
    /// The two-plane corrections (influence coefficient first, then stiffness model).
    pub corrections: Vec<TwoPlaneCorrectionResult>,
    /// The check run's C_r from the two planes against the first correction's prediction.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<CheckResult>,
}

/// A two-plane correction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwoPlaneCorrectionResult {
    /// `influence_coefficient` or `stiffness_model`.
    pub method: String,
    /// Planes A and B.
    pub planes: Vec<PlaneCorrection>,
    /// What it leaves at the PIGA plane.
    pub predicted: PredictedResult,
    /// Standard uncertainty of the residual dynamic lean (largest axis), µrad·s².
    pub residual_tilt_u_urad_s2: f64,
}

/// The correction in one plane.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlaneCorrection {
    /// Height of the plane above the PIGA plane, m.
    pub height_m: f64,
    /// The mass, radius and azimuth in it.
    pub correction: CorrectionResult,
}

/// A static phasor, µm, with standard uncertainties.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StaticPhasor {
    /// Magnitude at the PIGA plane, µm.
    pub magnitude_um: f64,
    /// Its standard uncertainty, µm.
    pub magnitude_u_um: f64,
    /// Azimuth from O2X2 towards O2Y2, deg.
    pub azimuth_deg: f64,
    /// Its standard uncertainty, deg.
    pub azimuth_u_deg: f64,
    /// Magnitude at the probe plane, µm.
    pub probe_magnitude_um: f64,
}

/// A dynamic phasor (∝ ω²), µm·s², with standard uncertainties.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DynamicPhasor {
    /// Magnitude at the PIGA plane, µm·s².
    pub magnitude_um_s2: f64,
    /// Its standard uncertainty, µm·s².
    pub magnitude_u_um_s2: f64,
    /// Azimuth from O2X2 towards O2Y2, deg.
    pub azimuth_deg: f64,
    /// Its standard uncertainty, deg.
    pub azimuth_u_deg: f64,
    /// Magnitude at the probe plane, µm·s².
    pub probe_magnitude_um_s2: f64,
    /// Its O2X2 component at the PIGA plane, `C_r`, m·s².
    pub c_r_m_s2: f64,
}

/// One phase as the advisor sees it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BalancePhase {
    /// The phase's name.
    pub name: String,
    /// Static phasor.
    #[serde(rename = "static")]
    pub static_phasor: StaticPhasor,
    /// Dynamic phasor.
    pub dynamic: DynamicPhasor,
    /// Measured drift at the PIGA plane per rate: `[rate_deg_s, x_um, y_um]`.
    pub points_um: Vec<[f64; 3]>,
    /// `|B|/σ(B)` of the three-term check `S + B·ω + D·ω²` (4 rates or more), or null.
    pub linear_significance: Option<f64>,
    /// `√(χ²/dof)` of the fit for points with σ, or null.
    pub reduced_chi: Option<f64>,
}

/// The influence coefficient `α = (D_t − D_0)/(m_t r_t e^{iθ_t})` at the PIGA plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Influence {
    /// `|α|`, µm·s² per kg·m.
    pub magnitude_um_s2_per_kg_m: f64,
    /// `arg α`, deg (0 for a stiffness-like response).
    pub azimuth_deg: f64,
    /// `1/|α|`, the bearing's effective radial stiffness it implies, N/m.
    pub effective_stiffness_n_m: f64,
}

/// A correction mass.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CorrectionResult {
    /// `influence_coefficient` or `stiffness_model`.
    pub method: String,
    /// Mass, kg.
    pub mass_kg: f64,
    /// Its standard uncertainty, kg.
    pub mass_u_kg: f64,
    /// Radius, m.
    pub radius_m: f64,
    /// Azimuth from O2X2 towards O2Y2, deg.
    pub azimuth_deg: f64,
    /// Its standard uncertainty, deg.
    pub azimuth_u_deg: f64,
    /// Unbalance `m·r`, g·mm.
    pub unbalance_g_mm: f64,
    /// Split on the two fixed positions bracketing the azimuth, or null.
    pub split: Option<Vec<SplitMass>>,
}

/// One mass of a split correction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SplitMass {
    /// The position's azimuth, deg.
    pub azimuth_deg: f64,
    /// Mass, kg.
    pub mass_kg: f64,
}

/// The predicted residual.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PredictedResult {
    /// Residual C_r, m·s² (nominally 0).
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub c_r_u_m_s2: f64,
    /// Residual Δk2 = k1·C_r·g/R² (eq. 19), rad/(s·g²).
    pub delta_k2_rad_s_g2: f64,
    /// Its standard uncertainty, rad/(s·g²).
    pub delta_k2_u_rad_s_g2: f64,
    /// RMS residual unbalance, g·mm.
    pub residual_unbalance_g_mm: f64,
    /// ISO 21940-11 `e_per·Ω` at the top rate, mm/s (with a rotor mass), or null.
    pub e_per_omega_mm_s: Option<f64>,
    /// The finest ISO 21940-11 grade met, mm/s, or null.
    pub iso_grade_mm_s: Option<f64>,
}

/// The stiffness-model reading (eq. 1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StiffnessResult {
    /// `k_r`, N/m.
    pub radial_stiffness_n_m: f64,
    /// `m·R_cm = k_r·|D|`, kg·m.
    pub imbalance_kg_m: f64,
    /// Its standard uncertainty, kg·m.
    pub imbalance_u_kg_m: f64,
    /// Its azimuth, deg.
    pub imbalance_azimuth_deg: f64,
    /// The correction `−k_r·D`.
    pub correction: CorrectionResult,
    /// What it leaves.
    pub predicted: PredictedResult,
}

/// A check run against the prediction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckResult {
    /// The check phase's name.
    pub phase: String,
    /// Its measured C_r (O2X2 component of its dynamic phasor at the PIGA plane), m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub c_r_u_m_s2: f64,
    /// `(measured − predicted)/√(u_pred² + u_meas²)`.
    pub z: f64,
    /// `C_r(initial)/C_r(check)`: the reduction achieved.
    pub reduction: f64,
}

/// What one change of radius error between two rates determines of the correction
/// (`counterweight` in results.json; the paper check of `docs/BALANCING.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CounterweightResults {
    /// The `radius_change` phase.
    pub phase: String,
    /// The change of radius error, µm.
    pub change_um: f64,
    /// The lower rate, deg/s.
    pub from_rate_deg_s: f64,
    /// The higher rate, deg/s.
    pub to_rate_deg_s: f64,
    /// The stated radial stiffness `k_r`, N/m (a study input).
    pub radial_stiffness_n_m: f64,
    /// Where it comes from.
    pub stiffness_source: String,
    /// `C_r = Δr/(ω₂² − ω₁²)`: the O2X2 component of the dynamic phasor, m·s².
    pub c_r_m_s2: f64,
    /// `Δk2 = k1·C_r·g/R²` (eq. 19), rad/(s·g²).
    pub delta_k2_rad_s_g2: f64,
    /// The empirical formula's coefficient, `k_r/(ω₂² − ω₁²)`: unbalance along O2X2 per µm
    /// of radius change, g·mm per µm.
    pub unbalance_per_um_g_mm: f64,
    /// The unbalance along O2X2 the change stands for, `k_r·C_r` (eq. 1), g·mm: the
    /// imbalance's magnitude if it lies on the arm's line, a lower bound otherwise.
    pub unbalance_x_g_mm: f64,
    /// The counterweight under that assumption, kg at `correction_radius_m`.
    pub correction_mass_kg: f64,
    /// The counterweight's radius, m.
    pub correction_radius_m: f64,
    /// Its azimuth under that assumption, deg (180 for a radius that grows with rate).
    pub correction_azimuth_deg: f64,
    /// What the one number determines.
    pub determined: Vec<String>,
    /// What it does not.
    pub not_determined: Vec<String>,
}
