//! The calibration section's results: k0…k3 with their uncertainties (JCGM 100 and 101).

use serde::{Deserialize, Serialize};

use super::common::{DegreesOfFreedom, Estimate};
use super::declarations::ProbeSign;

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

/// The PIGA coefficients' names, k0 … k3.
pub const COEFFICIENT_NAMES: [&str; 4] = ["k0", "k1", "k2", "k3"];
/// The coefficients' native units, k0 … k3.
pub const COEFFICIENT_UNITS: [&str; 4] = ["rad/s", "rad/(s·g)", "rad/(s·g²)", "rad/(s·g³)"];
/// The units of k0, k2 and k3 relative to k1, in millionths of g (k1 has none): what
/// results.json's `relative.unit`, the report and the certificate write.
pub const RELATIVE_UNITS: [&str; 4] = ["µg", "", "µg/g²", "µg/g³"];

/// One line of an uncertainty budget.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BudgetLine {
    /// The input quantity.
    pub quantity: String,
    /// Type A or B.
    pub evaluation: String,
    /// Its value (for the fit's coefficients, a correlated group: absent).
    pub value: Option<f64>,
    /// The unit of its value and standard uncertainty, as a budget shows it (`m`, `m/s²`,
    /// `1 (relative)`; for the fit's group, the output's unit). Empty in a results.json
    /// written before it was recorded.
    #[serde(default)]
    pub unit: String,
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
    /// What the study says of the input: the reason for a zero, or where its uncertainty
    /// comes from (the probe gain from the recordings' stated sensitivity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl BudgetLine {
    /// The line of an input quantity `q` (in `unit`) in an output's budget, with its
    /// contribution `c` to the output and what the study says of it (`note`).
    pub(crate) fn input(
        q: &uncertainty::InputQuantity,
        unit: &str,
        c: &uncertainty::Contribution,
        note: Option<String>,
    ) -> Self {
        Self {
            quantity: q.name.clone(),
            evaluation: match q.kind {
                uncertainty::Evaluation::TypeA => "A".to_owned(),
                uncertainty::Evaluation::TypeB => "B".to_owned(),
            },
            value: Some(q.value),
            unit: unit.to_owned(),
            u: q.standard_uncertainty,
            sensitivity: c.sensitivity,
            contribution: c.uncertainty,
            percent: c.variance_percent,
            dof: DegreesOfFreedom::from_dof(q.dof),
            note,
        }
    }

    /// A fit's coefficients as one line of `output`'s budget (`group`, their contributions):
    /// their correlated contribution (the shares of the group, which may be negative one by
    /// one, sum to the group's share), with sensitivity 1 and the fit's ν, in the output's
    /// `unit`; `fit` names the fit (`the eq. 18 fit`).
    pub(crate) fn fit_group(
        output: &uncertainty::GumOutput,
        unit: &str,
        group: &[uncertainty::Contribution],
        fit: &str,
        dof: uncertainty::Dof,
    ) -> Self {
        let share: f64 = group.iter().map(|c| c.variance_percent).sum();
        let contribution = (share.max(0.0) / 100.0).sqrt() * output.standard_uncertainty;
        Self {
            quantity: ::calibration::noise_budget_line(fit, dof),
            evaluation: "A".to_owned(),
            value: None,
            unit: unit.to_owned(),
            u: contribution,
            sensitivity: 1.0,
            contribution,
            percent: share,
            dof: DegreesOfFreedom::from_dof(dof),
            note: None,
        }
    }
}

/// What the study says beside input `input` of a budget (its index in
/// `calibration::input`), from `notes` (by that index): the reason for a zero, where its
/// uncertainty comes from, that it is not stated.
pub(crate) fn budget_note(notes: &[(usize, String)], input: usize) -> Option<String> {
    notes
        .iter()
        .find(|(index, _)| *index == input)
        .map(|(_, note)| note.clone())
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

impl Coefficient {
    /// A coefficient of `value` with the GUM's uncertainty of its output `o`.
    pub(crate) const fn of(o: &uncertainty::GumOutput, value: f64) -> Self {
        Self {
            value,
            u: o.standard_uncertainty,
            u95: o.expanded_uncertainty,
            k: o.coverage_factor,
            dof: DegreesOfFreedom::from_dof(o.dof),
        }
    }
}

impl MonteCarloOutput {
    /// The Monte Carlo result of the model's output `name` with its §8 validation against
    /// the GUM (`validation`, of the same evaluation).
    pub(crate) fn of(
        mc: &uncertainty::McResult,
        validation: &uncertainty::Validation,
        name: &str,
    ) -> Self {
        let o = mc.output(name).expect("the model names its outputs");
        let v = validation.output(name).expect("validated per output");
        Self {
            mean: o.estimate,
            u: o.standard_uncertainty,
            low95: o.coverage_interval.0,
            high95: o.coverage_interval.1,
            gum_agrees: v.agrees,
            tolerance: v.tolerance,
            d_low: v.d_low,
            d_high: v.d_high,
            heavy_tailed: o.heavy_tailed,
        }
    }
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
    /// The C_r used, m·s², and its standard uncertainty from the phase's fit (Type A).
    pub c_r_m_s2: Estimate,
    /// The same C_r with its combined standard uncertainty through the inputs that carry it
    /// into Δk2 (the fit's Type A, the probe gain, the lever heights and the rate scale), so
    /// that C_r and Δk2 are stated with one consistent uncertainty.
    pub c_r_combined_m_s2: Estimate,
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
    /// The GUM covariance matrix of k0, k1, k2, k3 (every input: the fit, C_r and the Type B
    /// inputs), in their own units.
    pub covariance: super::common::OutputCovariance,
    /// The design's terms: `1, ω, ω², ω³, a², a³`.
    pub terms: Vec<String>,
    /// Variance inflation factor of each non-constant term (a diagnostic: every polynomial
    /// design in ω has large ones, so no warning is based on them).
    pub variance_inflation: Vec<f64>,
    /// How much wider u(k0…k3) are than they need be: what the warning on the rates is
    /// based on (`None` when it could not be computed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u_inflation: Option<UncertaintyInflation>,
    /// Condition number of the column-scaled design.
    pub condition_number: f64,
    /// Uncertainty budgets per coefficient (JCGM 100): k2's is `budget.k2`.
    pub budget: PigaCoefficients<Vec<BudgetLine>>,
    /// The same model by Monte Carlo (JCGM 101).
    pub monte_carlo: MonteCarlo,
    /// The probe's sign convention (which way the gap moves when the spindle moves towards
    /// the PIGA), echoed beside C_r.
    pub probe_direction: ProbeSign,
    /// The 95 % interval each coefficient is stated with (JCGM 101 §8): the GUM's when the
    /// Monte Carlo validates it clearly, else the Monte Carlo's.
    pub headline: PigaCoefficients<Headline>,
    /// Warnings in plain words (terms hard to separate, a budget without Type B inputs...).
    pub warnings: Vec<String>,
}

/// How much wider the coefficients' standard uncertainties are than they need be
/// (`calibration::coefficient_inflation`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct UncertaintyInflation {
    /// u over the u of the same number of points with the same total weight, evenly spread
    /// from `reference_from_deg_s` to `reference_to_deg_s`; warned on above `limit`.
    pub versus_spread: PigaCoefficients<f64>,
    /// The reference design's lowest rate (10 % of the top rate), °/s.
    pub reference_from_deg_s: f64,
    /// The reference design's top rate (the design's own), °/s.
    pub reference_to_deg_s: f64,
    /// The factor above which the study warns.
    pub limit: f64,
    /// u in the fit over u in the same fit without the ω and ω³ nuisance columns: their
    /// price, large on every design (a diagnostic).
    pub nuisance: PigaCoefficients<f64>,
}

/// Which method a coefficient's stated 95 % interval comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadlineMethod {
    /// JCGM 100 (GUM), validated by the Monte Carlo method (JCGM 101 §8).
    Gum,
    /// JCGM 101 (Monte Carlo): the GUM interval is not validated, or its validation is
    /// borderline.
    MonteCarlo,
}

/// A coefficient's stated value and 95 % coverage interval (JCGM 101 §8).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Headline {
    /// The estimate (the GUM's: the model at the inputs' values).
    pub value: f64,
    /// Lower end of the 95 % coverage interval.
    pub low95: f64,
    /// Upper end.
    pub high95: f64,
    /// The method the interval comes from.
    pub method: HeadlineMethod,
    /// The §8 comparison lies within half the Monte Carlo's numerical tolerance δ of its
    /// threshold (`|max(d_low, d_high) − δ| ≤ δ/2`): another run could give either verdict,
    /// so the Monte Carlo interval, valid either way, is stated.
    pub borderline: bool,
}

impl Headline {
    /// The headline of a coefficient from its GUM result and its Monte Carlo one: the GUM
    /// interval when validated clearly, else the Monte Carlo one.
    pub fn of(gum: &Coefficient, mc: &MonteCarloOutput) -> Self {
        let d = mc.d_low.max(mc.d_high);
        let borderline = (d - mc.tolerance).abs() <= 0.5 * mc.tolerance;
        if mc.gum_agrees && !borderline {
            Self {
                value: gum.value,
                low95: gum.value - gum.u95,
                high95: gum.value + gum.u95,
                method: HeadlineMethod::Gum,
                borderline,
            }
        } else {
            Self {
                value: gum.value,
                low95: mc.low95,
                high95: mc.high95,
                method: HeadlineMethod::MonteCarlo,
                borderline,
            }
        }
    }

    /// The interval's half-widths below and above the value, scaled by `scale`.
    pub fn widths(&self, scale: f64) -> (f64, f64) {
        (
            (self.value - self.low95) * scale.abs(),
            (self.high95 - self.value) * scale.abs(),
        )
    }
}

/// The nuisance coefficients of the eq. 18 design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Nuisance {
    /// Coefficient of ω (dimensionless: −Δφ_ys and the Coriolis term).
    pub omega: Estimate,
    /// Coefficient of ω³, s² (−C_φ).
    pub omega3_s2: Estimate,
}
