//! What a study produces; serialised as `results.json` (schema in `docs/RESULTS.md`).

use harmonics::Coefficients;
use serde::{Deserialize, Serialize};

use recording::AngleSourceKind;

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
    /// The PIGA's calibration on measured data (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub calibration: Option<CalibrationResults>,
    /// What may make a number wrong, in plain words, in the configuration's order.
    #[serde(default)]
    pub warnings: Vec<Warning>,
    /// The balance advisor (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub balance: Option<BalanceResults>,
    /// The counterweight a published change of radius error stands for (when configured).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub counterweight: Option<CounterweightResults>,
}

/// A diagnostic: the numbers were computed, but something may make them wrong.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// A short stable code (`angle_from_rate`, `rate_differs`, `revolution_spread`,
    /// `drift_not_fitted`, `dropped_revolutions`, `lack_of_fit`).
    pub code: String,
    /// What was seen and what to do, in plain words.
    pub message: String,
    /// The configuration field, and the file when it concerns a recording.
    #[serde(rename = "where")]
    pub location: String,
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

/// Degrees of freedom of an uncertainty: a number, or `"infinite"` (Type B, or a combination
/// dominated by Type B contributions) — never a JSON `null` standing for infinity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum DegreesOfFreedom {
    /// A finite number of degrees of freedom.
    Finite(f64),
    /// Infinitely many, written as the string `"infinite"`.
    Infinite(InfiniteDof),
}

/// The marker `"infinite"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InfiniteDof {
    /// Infinitely many degrees of freedom.
    Infinite,
}

/// An estimate and its standard uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its standard uncertainty.
    pub u: f64,
}

/// A calibrated coefficient with its uncertainty per JCGM 100.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Coefficient {
    /// The value.
    pub value: f64,
    /// Combined standard uncertainty.
    pub u: f64,
    /// Expanded uncertainty at 95 % coverage, `k·u`.
    #[serde(rename = "U95")]
    pub u95: f64,
    /// Coverage factor (Student t at the effective degrees of freedom).
    pub k: f64,
    /// Effective degrees of freedom (Welch–Satterthwaite).
    pub dof: DegreesOfFreedom,
}

/// The four PIGA coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PigaCoefficients<T> {
    /// Bias k0 (with k1·Δφ_ys), rad/s.
    pub k0: T,
    /// Scale factor k1, rad/(s·g).
    pub k1: T,
    /// Second-order coefficient k2, rad/(s·g²).
    pub k2: T,
    /// Third-order coefficient k3, rad/(s·g³).
    pub k3: T,
}

/// The coefficients in the conventional units of IEEE Std 836/1293 users, relative to k1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Conventional {
    /// The g used, m/s².
    pub g_m_s2: f64,
    /// k0/k1, µg.
    pub k0_ug: Estimate,
    /// k2/k1, µg/g².
    pub k2_ug_per_g2: Estimate,
    /// k3/k1, µg/g³.
    pub k3_ug_per_g3: Estimate,
}

/// One line of an uncertainty budget.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BudgetLine {
    /// The input quantity.
    pub quantity: String,
    /// Type A or B.
    pub evaluation: String,
    /// Its value (for the fit's coefficients, a correlated group: absent).
    pub value: Option<f64>,
    /// Its standard uncertainty (for the fit's group: the group's contribution itself, with
    /// sensitivity 1, so that `contribution = |sensitivity|·u` holds on every line).
    pub u: f64,
    /// Sensitivity coefficient ∂y/∂x through the computation (1 for the fit's group, whose
    /// members are correlated and are shown as one line).
    pub sensitivity: f64,
    /// Contribution |c|·u to the output's standard uncertainty.
    pub contribution: f64,
    /// Share of the combined variance, %.
    pub percent: f64,
    /// Degrees of freedom.
    pub dof: DegreesOfFreedom,
}

/// One row of the calibration table with its fitted value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationRow {
    /// Rate, deg/s (a raw recording's measured rate when it has an encoder).
    pub rate_deg_s: f64,
    /// Mean output, rad/s.
    pub output_rad_s: f64,
    /// Output minus the fitted eq. 18 model, rad/s.
    pub residual_rad_s: f64,
    /// The output's standard uncertainty, rad/s (a table's σ column or a recording's
    /// standard error across revolutions; absent for an unweighted fit).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u_rad_s: Option<f64>,
    /// The row's label (a table's label column).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// The row's line in the table file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// The raw recording the point comes from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
}

/// The residuals of the rows sharing a label: a repeat or an orientation that sits apart
/// from the others shows here (warning `label_offset`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LabelSummary {
    /// The label.
    pub label: String,
    /// Rows with it.
    pub rows: usize,
    /// Their mean residual (weighted by 1/σ² for a weighted fit), rad/s.
    pub mean_residual_rad_s: f64,
    /// Its standard uncertainty, rad/s: the (weighted) scatter of the label's residuals
    /// about their mean over √rows (the fit's residual SD for a single row).
    pub u_rad_s: f64,
}

/// A raw PIGA output recording reduced to one calibration point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PigaRecordingResult {
    /// The file.
    pub file: String,
    /// The rate the study declares, deg/s.
    pub declared_rate_deg_s: f64,
    /// The rate used: measured by the spindle angle when it is measured, deg/s.
    pub rate_deg_s: f64,
    /// Where the spindle angle comes from (`encoder`, `index_pulse`, `declared_rate`).
    pub angle_source: String,
    /// Mean output rate over whole spindle revolutions, rad/s.
    pub output_rad_s: f64,
    /// Its standard uncertainty (the point's weight), rad/s: the white-noise standard error,
    /// or the one across revolutions when the slopes scatter beyond white noise (warning
    /// `output_spread`).
    pub u_rad_s: f64,
    /// The standard error across revolutions, `s/√K`, rad/s.
    pub across_revolutions_u_rad_s: f64,
    /// The white-noise standard error from the pooled residuals of the per-revolution fits,
    /// rad/s.
    pub white_noise_u_rad_s: f64,
    /// Standard deviation of the per-revolution output rates, rad/s.
    pub revolution_sd_rad_s: f64,
    /// Whole revolutions used.
    pub revolutions: usize,
    /// Revolutions dropped for gaps or non-finite samples.
    pub dropped_revolutions: usize,
}

/// Monte Carlo results for one output (JCGM 101).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MonteCarloOutput {
    /// Mean of the output's distribution.
    pub mean: f64,
    /// Its standard deviation: the standard uncertainty.
    pub u: f64,
    /// Lower end of the probabilistically symmetric 95 % coverage interval.
    pub low95: f64,
    /// Upper end.
    pub high95: f64,
    /// §8 validation of the GUM result against this one.
    pub gum_agrees: bool,
    /// The numerical tolerance δ of the validation.
    pub tolerance: f64,
    /// |y − U95 − y_low| of the validation.
    pub d_low: f64,
    /// |y + U95 − y_high| of the validation.
    pub d_high: f64,
    /// An input is drawn from a t with ν ≤ 2 (no variance): `mean` and `u` are those of the
    /// trials drawn and do not settle; the coverage interval is the result to use.
    pub heavy_tailed: bool,
}

/// The Monte Carlo evaluation of the calibration's measurement model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MonteCarlo {
    /// Trials drawn (adaptive, JCGM 101 §7.9).
    pub trials: u64,
    /// The seed.
    pub seed: u64,
    /// Whether every coefficient's GUM result agrees with the Monte Carlo one (§8).
    pub gum_agrees: bool,
    /// Per coefficient.
    pub k0: MonteCarloOutput,
    /// k1.
    pub k1: MonteCarloOutput,
    /// k2 (compensated).
    pub k2: MonteCarloOutput,
    /// k3.
    pub k3: MonteCarloOutput,
}

/// The calibration on measured data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationResults {
    /// The PIGA table read (absent for raw recordings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<String>,
    /// The raw PIGA output recordings, each reduced to a point (absent for a table).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub recordings: Vec<PigaRecordingResult>,
    /// Whether the eq. 18 fit is weighted by `1/σᵢ` of each point.
    pub weighted: bool,
    /// For a weighted fit, `√(χ²/ν)` of the residuals against the points' own σ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub birge_ratio: Option<f64>,
    /// When the weighted fit's Birge ratio exceeds 1: the standard deviation τ common to
    /// every point that their σ miss (run-to-run variation), rad/s, chosen so that χ²/ν = 1
    /// with `σᵢ² + τ²` (Paule–Mandel); the fit is weighted by those.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub excess_u_rad_s: Option<f64>,
    /// The phase whose C_r was removed.
    pub compensate_with: String,
    /// `fitted` or `given`.
    pub k1_source: String,
    /// The g used, m/s², and where it comes from.
    pub g_m_s2: f64,
    /// Where g comes from (the `uncertainty` section's `g_source`).
    pub g_source: String,
    /// Rows of the table.
    pub points: usize,
    /// Distinct rates.
    pub distinct_rates: usize,
    /// Residual degrees of freedom of the eq. 18 fit.
    pub dof: usize,
    /// The compensated coefficients with their uncertainties (JCGM 100).
    pub coefficients: PigaCoefficients<Coefficient>,
    /// The coefficients of the fit as measured (a² coefficient = k2 + Δk2), with the fit's
    /// standard errors.
    pub uncompensated: PigaCoefficients<Estimate>,
    /// Δk2 = k1·C_r·g/R² removed (eq. 19), with its standard uncertainty.
    pub delta_k2: Estimate,
    /// The C_r used, m·s², and its standard uncertainty.
    pub c_r_m_s2: Estimate,
    /// k0, k2, k3 relative to k1 in µg, µg/g², µg/g³.
    pub conventional: Conventional,
    /// The nuisance coefficients of ω (1) and ω³ (s²).
    pub nuisance: Nuisance,
    /// Residual standard deviation of the fit, rad/s.
    pub residual_sd_rad_s: f64,
    /// Each row with its residual.
    pub residuals: Vec<CalibrationRow>,
    /// The residuals by label (a table's label column), when there are two labels or more.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub labels: Vec<LabelSummary>,
    /// Correlation matrix of the six fitted coefficients, in the order of `terms`.
    pub correlation: Vec<Vec<f64>>,
    /// The design's terms: `1, ω, ω², ω³, a², a³`.
    pub terms: Vec<String>,
    /// Variance inflation factor of each non-constant term.
    pub variance_inflation: Vec<f64>,
    /// Condition number of the column-scaled design.
    pub condition_number: f64,
    /// Uncertainty budgets per coefficient (JCGM 100): k2's is `budget.k2`.
    pub budget: PigaCoefficients<Vec<BudgetLine>>,
    /// The same model by Monte Carlo (JCGM 101).
    pub monte_carlo: MonteCarlo,
    /// Warnings in plain words (terms hard to separate, a budget without Type B inputs...).
    pub warnings: Vec<String>,
}

/// The nuisance coefficients of the eq. 18 design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Nuisance {
    /// Coefficient of ω (dimensionless: −Δφ_ys and the Coriolis term).
    pub omega: Estimate,
    /// Coefficient of ω³, s² (−C_φ).
    pub omega3_s2: Estimate,
}

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
