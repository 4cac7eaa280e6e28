//! The joint fit over several mountings (issue 29, `docs/MODEL.md`): each chosen term of the
//! IEEE 836 model with its u and U95 (and normalised by k1), the arm stretch, each
//! mounting's nuisance terms and residuals, and what the separability analysis said.

use serde::{Deserialize, Serialize};

/// One chosen term.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TermResult {
    /// Its symbol (`k2`, `k_ip`, `δ_o`): the `name` a regression path selects it by.
    pub name: String,
    /// Its tag in the study file (`k_ip`, `delta_o`).
    pub tag: String,
    /// What it multiplies, in words (`a_i·a_p`).
    pub multiplies: String,
    /// Its unit (`rad/s/g²`; a misalignment: `rad`).
    pub unit: String,
    /// Its value.
    pub value: f64,
    /// Its standard uncertainty from the fit.
    pub u: f64,
    /// Its coverage factor for 95 % (Student t at the fit's degrees of freedom).
    pub k: f64,
    /// Its expanded uncertainty `k·u`.
    pub u95: f64,
    /// Normalised by k1 (value/k1 and its u; k0 in g, the others in g/gⁿ), with its unit
    /// (absent for k1 and the misalignments).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normalised: Option<Normalised>,
}

/// A term normalised by k1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Normalised {
    /// value/k1.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
    /// Its unit (`g`, `1/g`, `1/g²`).
    pub unit: String,
    /// The unit of 10⁶·value/k1, as a person reads it (`µg`, `µg/g²`, `µg/g³`; empty in a
    /// results.json written before it was recorded).
    #[serde(default)]
    pub relative_unit: String,
}

/// One mounting as fitted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingFitResult {
    /// Its name (the preset's words, or the lab's label).
    pub name: String,
    /// The configuration field (`mountings.list[2]`).
    pub field: String,
    /// The case axes in the arm's frame (x along the arm outwards, y across, z up): IA, PA,
    /// OA.
    pub axes: [[f64; 3]; 3],
    /// Its static radius, m.
    pub radius_m: f64,
    /// The fixture's angular standard uncertainty, degrees (0 when not stated).
    pub angle_u_deg: f64,
    /// The table read.
    pub table: String,
    /// Points fitted.
    pub points: usize,
    /// The lowest and highest rate, deg/s.
    pub rate_low_deg_s: f64,
    /// The highest rate, deg/s.
    pub rate_high_deg_s: f64,
    /// The specific force along the arm at those rates, `R·ω²/g` (g).
    pub specific_force_low_g: f64,
    /// At the highest rate (g).
    pub specific_force_high_g: f64,
    /// Residuals `output − fitted`, in the output unit, in the table's order.
    pub residuals: Vec<f64>,
    /// Their root mean square, output unit.
    pub residual_rms: f64,
}

/// A nuisance term (a mounting's own bias shift, scale factor or ω term; the shared ω³).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NuisanceResult {
    /// In words.
    pub name: String,
    /// Its value (output units per the power of ω it multiplies).
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
}

/// The radius growth the probe does not see.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArmStretchResult {
    /// `C − C_r`, m·s², and its u.
    pub unseen_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub unseen_u_m_s2: f64,
    /// The total growth `C = C_r + (C − C_r)`, m·s².
    pub total_m_s2: f64,
    /// Its standard uncertainty (with the probe's u(C_r)), m·s².
    pub total_u_m_s2: f64,
}

/// The probe's compensation applied.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingsProbe {
    /// The phase, by name.
    pub phase: String,
    /// How it was chosen (`compensate_with`, `calibration.compensate_with`, `first phase`).
    pub chosen_by: String,
    /// The static radius error at the accelerometer (the radius-error fit at ω = 0), m,
    /// added to every mounting's declared radius.
    pub static_m: f64,
    /// Its C_r at the accelerometer, m·s², and its standard uncertainty.
    pub c_r_m_s2: f64,
    /// u(C_r), m·s².
    pub c_r_u_m_s2: f64,
    /// The static drift across the arm at the accelerometer, m, from the probe's sine
    /// component (absent: the phase has none, and it is not compensated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub across_static_m: Option<f64>,
    /// Its coefficient of ω², m·s².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub c_ry_m_s2: Option<f64>,
}

/// The joint fit over several mountings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingsResults {
    /// The kind in words.
    pub kind: String,
    /// The output unit (`rad/s`, `mA`).
    pub output_unit: String,
    /// The chosen terms, in the model's order.
    pub terms: Vec<TermResult>,
    /// The mountings, in the configuration's order.
    pub mountings: Vec<MountingFitResult>,
    /// The nuisance terms.
    pub nuisances: Vec<NuisanceResult>,
    /// The arm stretch, when fitted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arm_stretch: Option<ArmStretchResult>,
    /// Whether the arm stretch was left out because these mountings cannot separate it (its
    /// growth then hides in the even terms).
    pub arm_stretch_not_separable: bool,
    /// The probe's compensation (absent: not compensated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probe: Option<MountingsProbe>,
    /// The vertical Earth rate taken, rad/s, and in words how.
    pub earth_rate_vertical_rad_s: f64,
    /// Where it comes from.
    pub earth_rate_words: String,
    /// How the points were weighted, in words.
    pub weighting: String,
    /// Residual degrees of freedom.
    pub dof: usize,
    /// The residuals' standard deviation, output unit.
    pub residual_sd: f64,
    /// The Birge ratio `√(χ²/ν)` of a weighted fit with the points' own σ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub birge_ratio: Option<f64>,
    /// The condition number of the column-scaled design.
    pub condition_number: f64,
    /// The separability analysis in words.
    pub separability: String,
    /// What the expanded uncertainties hold, in words.
    pub uncertainty_scope: String,
    /// The Type B inputs propagated to the terms (the radii, g, the rate scale, the fixtures'
    /// angles), each with its share of every term's u (empty: none stated).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub type_b: Vec<MountingsTypeBLine>,
}

/// One Type B input of the joint fit and its share of each term's standard uncertainty.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingsTypeBLine {
    /// The input in words ("radius of IA in", "g", "angle of IA out about PA").
    pub input: String,
    /// Its standard uncertainty, in `unit`.
    pub u: f64,
    /// The unit of `u` (m, m/s², relative, rad).
    pub unit: String,
    /// `|c|·u` for each term, in the order of `terms`, in each term's unit.
    pub contributions: Vec<f64>,
}
