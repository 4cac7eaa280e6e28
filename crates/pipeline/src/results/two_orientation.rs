//! The two-orientation (IA in / IA out) calibration's results (issue 20, `docs/TWO_ORIENTATION.md`):
//! each mounting's k0 and k1, the shared k2 and k3, and the total radius growth C with
//! Δk2,total from the PIGA alone, with their uncertainties (JCGM 100 and 101); with a probe
//! phase, C − C_r with its z and k2 by the probe method beside the two-orientation one.

use serde::{Deserialize, Serialize};

use super::calibration::{
    BudgetLine, Coefficient, Headline, MonteCarloOutput, PigaRecordingResult,
};
use super::common::Estimate;

/// One mounting of the PIGA and its own coefficients.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MountingResults {
    /// `ia_in` or `ia_out`.
    pub orientation: String,
    /// The configuration field of its data set (`two_orientation.orientations[0]`).
    pub field: String,
    /// Its static radius, m.
    pub radius_m: f64,
    /// The PIGA table read (absent for raw recordings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<String>,
    /// Each raw PIGA output recording reduced to its point (empty for a table).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub recordings: Vec<PigaRecordingResult>,
    /// Points fitted: the table's rows, or the recordings.
    pub points: usize,
    /// The lowest rate fitted, deg/s.
    pub rate_low_deg_s: f64,
    /// The highest rate fitted, deg/s.
    pub rate_high_deg_s: f64,
    /// Distinct rates.
    pub distinct_rates: usize,
    /// Bias k0 of this mounting (with the gravity seen through its tilt), rad/s.
    pub k0: Coefficient,
    /// Scale factor k1 of this mounting, rad/(s·g).
    pub k1: Coefficient,
    /// The ω nuisance coefficient of this mounting (tilt, Coriolis, alignment), with the fit's
    /// standard error.
    pub omega: Estimate,
    /// Residual standard deviation of this mounting's points, rad/s.
    pub residual_sd_rad_s: f64,
}

/// The Monte Carlo evaluation of the two-orientation model (JCGM 101), for the outputs a
/// certificate states.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwoOrientationMonteCarlo {
    /// Trials drawn.
    pub trials: u64,
    /// The seed.
    pub seed: u64,
    /// Whether the GUM result of k2, k3, C and Δk2,total agrees with the Monte Carlo one (§8).
    pub gum_agrees: bool,
    /// k2.
    pub k2: MonteCarloOutput,
    /// k3.
    pub k3: MonteCarloOutput,
    /// C.
    pub c: MonteCarloOutput,
    /// Δk2,total.
    pub delta_k2_total: MonteCarloOutput,
    /// C − C_r (with a probe phase).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub difference: Option<MonteCarloOutput>,
}

/// Uncertainty budgets (JCGM 100) of the main outputs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwoOrientationBudgets {
    /// k2's.
    pub k2: Vec<BudgetLine>,
    /// C's.
    pub c: Vec<BudgetLine>,
    /// C − C_r's, with a probe phase (where the probe's lever heights, gain and C_r enter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub difference: Option<Vec<BudgetLine>>,
}

/// The stated 95 % intervals (JCGM 101 §8: the GUM's when the Monte Carlo validates it
/// clearly, else the Monte Carlo's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TwoOrientationHeadline {
    /// k2.
    pub k2: Headline,
    /// k3.
    pub k3: Headline,
    /// C.
    pub c: Headline,
}

/// The PIGA's C against a probe phase's C_r, and k2 both ways.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProbeComparison {
    /// The probe phase.
    pub phase: String,
    /// How it was chosen: `compare_with`, `calibration.compensate_with` or `first phase`.
    pub chosen_by: String,
    /// The phase's C_r at the PIGA plane, m·s², with its standard uncertainty.
    pub c_r_m_s2: Estimate,
    /// C − C_r, m·s²: the radius growth the probe does not see (arm stretch), or a wrong
    /// probe declaration.
    pub difference_m_s2: Coefficient,
    /// z = (C − C_r)/u.
    pub z: f64,
    /// Whether |z| ≤ 3.
    pub agrees: bool,
    /// k2 by the probe method: the IA-in data set's eq. 18 fit compensated with the phase's
    /// C_r (k1 fitted), rad/(s·g²), with its standard uncertainty (the fit, C_r and the
    /// study's Type B inputs, as in the calibration section).
    pub k2_probe: Estimate,
    /// Its expanded uncertainty for 95 % coverage, by the GUM as the calibration section
    /// evaluates it (every Type B input of the study, at the IA-in radius).
    #[serde(rename = "k2_probe_U95")]
    pub k2_probe_u95: f64,
    /// k2 (two-orientation) − k2 (probe), rad/(s·g²).
    pub k2_difference: f64,
}

/// The two-orientation calibration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwoOrientationResults {
    /// IA in, then IA out.
    pub mountings: Vec<MountingResults>,
    /// k2 from the PIGA alone, rad/(s·g²).
    pub k2: Coefficient,
    /// k3, rad/(s·g³).
    pub k3: Coefficient,
    /// Total dynamic radius growth at the PIGA, C = C_r + C_a, m·s².
    pub c_m_s2: Coefficient,
    /// Δk2,total = k̄1·C·g/R_in², rad/(s·g²).
    pub delta_k2_total: Coefficient,
    /// The g used, m/s², and its standard uncertainty (the `uncertainty` section's).
    pub g_m_s2: Estimate,
    /// Residual degrees of freedom of the joint fit.
    pub dof: usize,
    /// Residual standard deviation of the joint fit, rad/s.
    pub residual_sd_rad_s: f64,
    /// Variance inflation factor of the s·ω⁴ column (a diagnostic: about 1e6 on every
    /// ordinary design).
    pub omega4_vif: f64,
    /// u(k2) in the joint fit over u(k2) with C known (the s·ω⁴ column dropped),
    /// `1/√(1 − ρ²)`: what fitting C costs k2; warned on above 3.
    #[serde(default)]
    pub k2_inflation_by_omega4: f64,
    /// Correlation ρ of the k2 and C estimates in the joint fit.
    #[serde(default)]
    pub k2_c_correlation: f64,
    /// u(k2) and u(C) over those of the same number of points per mounting spread evenly
    /// from 10 % of the top rate to the top rate: what the rates cost; warned on above 3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u_inflation_by_rates: Option<RateSpread>,
    /// Condition number of the column-scaled design.
    pub condition_number: f64,
    /// Uncertainty budgets (JCGM 100).
    pub budget: TwoOrientationBudgets,
    /// The same model by Monte Carlo (JCGM 101).
    pub monte_carlo: TwoOrientationMonteCarlo,
    /// The 95 % interval each is stated with (JCGM 101 §8).
    pub headline: TwoOrientationHeadline,
    /// The GUM covariance matrix of k0 and k1 of each mounting, k2 and k3 (every input), in
    /// their own units.
    pub covariance: super::common::OutputCovariance,
    /// The comparison with the probe phase.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probe: Option<ProbeComparison>,
    /// The Earth rate about the spindle axis the fit was corrected for (its term with k2,
    /// which eq. 23 has no column for), as stated or taken.
    #[serde(default)]
    pub earth_rate: AxialEarthRateResult,
}

/// The Earth rate about the spindle axis as the two-orientation evaluation took it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct AxialEarthRateResult {
    /// The latitude stated, degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub latitude_deg: Option<f64>,
    /// The spin stated, in words.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin: Option<String>,
    /// The value taken, rad/s (signed: + the Earth's sense about the local vertical).
    pub value_rad_s: f64,
    /// The half-width of the rectangular distribution about it, rad/s (0: stated).
    pub half_width_rad_s: f64,
    /// What the study states, in words (also the budget line's note).
    pub words: String,
}

/// What the rates of a two-orientation design cost k2 and C (`calibration::two_orientation_spread`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RateSpread {
    /// u(k2) over the spread reference design's.
    pub k2: f64,
    /// u(C) over the spread reference design's.
    pub c: f64,
    /// The reference design's lowest rate, deg/s.
    pub reference_low_deg_s: f64,
    /// The reference design's top rate (the top rate of both mountings), deg/s.
    pub reference_top_deg_s: f64,
}
