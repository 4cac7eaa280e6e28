//! The plan: the chosen design, its whole revolutions, and its predicted uncertainty.

use nalgebra::DMatrix;

use crate::design;
use crate::error::{PlanningError, Result};
use crate::exchange::{self, Allocated, Space as _};
use calibration::{input, output};

use crate::inputs::{Criterion, K2, PlanInputs, Problem, UNKNOWNS, regressors};

/// One point of the run sheet.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PlanPoint {
    /// Rate, deg/s.
    pub rate_deg_s: f64,
    /// Whole revolutions recorded.
    pub revolutions: u32,
    /// Recording time, `revolutions·360/rate`, s.
    pub recording_s: f64,
    /// Settling time before recording, s.
    pub settling_s: f64,
    /// Settling plus recording, s.
    pub duration_s: f64,
    /// Predicted standard deviation of the point's mean PIGA output, rad/s.
    pub sigma_mean_rad_s: f64,
    /// Predicted standard deviation of the point's radius error from the probe, m.
    pub sigma_radius_m: f64,
}

/// An expanded uncertainty of k2 (GUM, Welch–Satterthwaite).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Expanded {
    /// Combined standard uncertainty u(k2), rad/(s·g²).
    pub u_rad_s_g2: f64,
    /// Effective degrees of freedom.
    pub dof: f64,
    /// Coverage factor for 95 %.
    pub k: f64,
    /// U95(k2), rad/(s·g²).
    pub u95_rad_s_g2: f64,
}

/// One input's share of the compensated u(k2).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BudgetLine {
    /// The input quantity.
    pub quantity: String,
    /// Its standard uncertainty, in its unit.
    pub u: f64,
    /// Sensitivity of k2 to it.
    pub sensitivity: f64,
    /// `|sensitivity|·u`, rad/(s·g²).
    pub contribution_rad_s_g2: f64,
    /// Share of u²(k2), percent.
    pub percent: f64,
}

/// A test plan and what it predicts.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Plan {
    /// The criterion the rates were chosen for.
    pub criterion: Criterion,
    /// Working radius, m.
    pub radius_m: f64,
    /// Gravity, m/s².
    pub g_m_s2: f64,
    /// Candidate rates within the allowed range.
    pub candidates: usize,
    /// The highest allowed rate, deg/s.
    pub max_rate_deg_s: f64,
    /// The run sheet, by rate.
    pub points: Vec<PlanPoint>,
    /// Distinct rates.
    pub distinct_rates: usize,
    /// Total centrifuge time, s.
    pub total_time_s: f64,
    /// The budget, s.
    pub budget_s: f64,
    /// Predicted u(k2) of the eq. 18 fit alone (output noise, σ known), rad/(s·g²).
    pub u_k2_fit_rad_s_g2: f64,
    /// u(k2) of the fit with the same rates and total recording time shared as equal
    /// revolutions, rad/(s·g²) (how much the allocation gains).
    pub u_k2_fit_equal_revolutions_rad_s_g2: f64,
    /// Residual degrees of freedom of the fit (points − 6).
    pub fit_dof: usize,
    /// 2-norm condition number of the column-scaled, weighted design.
    pub condition_number: f64,
    /// u(C_r) used for the compensation, m·s².
    pub u_c_r_m_s2: f64,
    /// Whether u(C_r) is predicted from the probe at the plan's points (otherwise given).
    pub c_r_predicted: bool,
    /// Compensated k2: U95 of the GUM budget.
    pub compensated: Expanded,
    /// Uncompensated k2: U95 without the C_r term; the bias Δk2 is not in it.
    pub uncompensated: Expanded,
    /// The expected uncompensated bias `Δk2 = k1·C_r·g/R²`, rad/(s·g²).
    pub delta_k2_expected_rad_s_g2: f64,
    /// The fraction of the uncompensated U95 the bias may reach.
    pub bias_fraction: f64,
    /// The largest |C_r| with `|Δk2| ≤ bias_fraction·U95(uncompensated)`, m·s².
    pub c_r_limit_m_s2: f64,
    /// Whether the expected C_r is within that limit (compensation optional).
    pub c_r_within_limit: bool,
    /// Test-uncertainty ratio of the compensated calibration: tolerance / U95.
    pub tur_compensated: f64,
    /// Test-uncertainty ratio uncompensated: tolerance / (U95 + |Δk2|).
    pub tur_uncompensated: f64,
    /// The target U95(k2), rad/(s·g²).
    pub target_u95_rad_s_g2: f64,
    /// The expanded uncertainty of the Type B inputs alone (the floor no centrifuge time
    /// lowers), rad/(s·g²).
    pub type_b_floor_u95_rad_s_g2: f64,
    /// The compensated k2's budget.
    pub budget: Vec<BudgetLine>,
}

/// The planner's names of the calibration model's inputs it uses, in the order of its budget
/// (the model's own order is [`calibration::input`]): the a² coefficient first.
const BUDGET_INPUTS: [(usize, &str); 9] = [
    (
        input::FIRST_COEFFICIENT + calibration::A2_TERM,
        "apparent k2 (a² coefficient of the eq. 18 fit)",
    ),
    (input::RADIUS, "R (working radius)"),
    (input::G, "g (gravity)"),
    (input::RATE_SCALE, "rate scale (common to every rate)"),
    (input::PIVOT_TO_PROBE, "pivot-to-probe height"),
    (input::PROBE_TO_PIGA, "probe-to-PIGA height"),
    (input::PROBE_GAIN, "probe gain"),
    (input::C_R, "C_r"),
    (input::K1_GIVEN, "k1"),
];

/// Plans the calibration: the rates, the revolutions at each, and the predicted U95(k2).
///
/// # Errors
/// A field out of range ([`PlanningError::InvalidField`], [`PlanningError::TooFewPoints`]),
/// a maximum rate below the minimum ([`PlanningError::RateRange`]), too few candidates
/// ([`PlanningError::TooFewCandidates`]), a budget shorter than settling and the minimum
/// revolutions ([`PlanningError::BudgetTooShort`]), and a target the best plan misses
/// ([`PlanningError::TargetUnreachable`]).
pub fn plan(inputs: &PlanInputs) -> Result<Plan> {
    let plan = plan_unchecked(inputs)?;
    let target = inputs.target.u95_k2_rad_s_g2;
    if plan.compensated.u95_rad_s_g2 > target {
        let k = plan.compensated.k;
        let u_c = plan.compensated.u_rad_s_g2;
        let u_floor = plan.type_b_floor_u95_rad_s_g2 / 1.959_963_984_540_054;
        let needed = target / k;
        let recording: f64 = plan.points.iter().map(|q| q.recording_s).sum();
        let settling: f64 = plan.points.iter().map(|q| q.settling_s).sum();
        let needed_budget_s = (needed > u_floor).then(|| {
            let factor = (u_c * u_c - u_floor * u_floor) / (needed * needed - u_floor * u_floor);
            settling + recording * factor
        });
        return Err(PlanningError::TargetUnreachable {
            target,
            achieved: plan.compensated.u95_rad_s_g2,
            budget_s: inputs.schedule.budget_s,
            needed_budget_s,
            type_b_floor: plan.type_b_floor_u95_rad_s_g2,
        });
    }
    Ok(plan)
}

/// The plan without the check of its target (the probe method beside a two-orientation plan).
pub(crate) fn plan_unchecked(inputs: &PlanInputs) -> Result<Plan> {
    let p = Problem::new(inputs)?;
    p.check_budget()?;
    let best = design::search(&p).ok_or_else(|| PlanningError::Singular {
        rates_deg_s: Vec::new(),
    })?;
    let revolutions = design::whole_revolutions(&p, &best);
    describe(&p, &best, &revolutions)
}

/// The weighted eq. 18 design of a plan's points (rows `x_i/σ_i`, raw regressors).
fn weighted_design(p: &Problem, design: &[usize], sigma: &[f64]) -> DMatrix<f64> {
    let c = &p.inputs.centrifuge;
    let rows: Vec<[f64; UNKNOWNS]> = design
        .iter()
        .map(|&i| regressors(p.rates_rad_s[i], c.radius_m, c.g_m_s2))
        .collect();
    DMatrix::from_fn(design.len(), UNKNOWNS, |r, j| rows[r][j] / sigma[r])
}

/// u(k2) of the fit for σ known, through identify's QR (`(XᵀWX)⁻¹`, never a normal-equation
/// inverse); also the condition number.
fn fit_u_k2(p: &Problem, design: &[usize], sigma: &[f64]) -> Result<(f64, f64)> {
    let x = weighted_design(p, design, sigma);
    let y = vec![0.0; design.len()];
    let fit = identify::lstsq(&x, &y).map_err(|e| match e {
        identify::IdentifyError::RankDeficient { .. } => PlanningError::Singular {
            rates_deg_s: design
                .iter()
                .map(|&i| p.rates_rad_s[i].to_degrees())
                .collect(),
        },
        other => PlanningError::Identify(other),
    })?;
    Ok((
        fit.unscaled_covariance[(K2, K2)].sqrt(),
        fit.condition_number,
    ))
}

/// σ of a point's mean output after `revolutions` at candidate `i`.
fn sigma_mean(p: &Problem, i: usize, revolutions: u32) -> f64 {
    let t = f64::from(revolutions) * p.grid.tau_s[i];
    (1.0 / (t * p.grid.info_per_s[i])).sqrt()
}

/// σ of a point's radius error at the PIGA plane from the probe: the first-harmonic
/// coefficient of `f_s·t` samples over whole revolutions has variance `2σ²/(f_s·t)`, carried
/// to the PIGA plane by the lever ratio.
fn sigma_radius(p: &Problem, i: usize, revolutions: u32) -> f64 {
    let pr = &p.inputs.probe;
    let t = f64::from(revolutions) * p.grid.tau_s[i];
    let lever = harmonics::lever_ratio(pr.pivot_to_probe_mm, pr.probe_to_piga_mm);
    lever * pr.noise_um * 1e-6 * (2.0 / (pr.sample_rate_hz * t)).sqrt()
}

/// u(C_r) of the weighted fit `Δr = a + C_r·ω²` over the points (`1/Σ w_i (z_i − z̄)²`,
/// `z = ω²`, `z̄` the weighted mean).
fn predicted_u_c_r(p: &Problem, design: &[usize], sigma_r: &[f64]) -> f64 {
    let w: Vec<f64> = sigma_r.iter().map(|s| 1.0 / (s * s)).collect();
    let z: Vec<f64> = design.iter().map(|&i| p.rates_rad_s[i].powi(2)).collect();
    let sw: f64 = w.iter().sum();
    let mean = w.iter().zip(&z).map(|(w, z)| w * z).sum::<f64>() / sw;
    let ss: f64 = w.iter().zip(&z).map(|(w, z)| w * (z - mean).powi(2)).sum();
    (1.0 / ss).sqrt()
}

struct Gum {
    compensated: Expanded,
    uncompensated: Expanded,
    budget: Vec<BudgetLine>,
}

/// The GUM evaluation of the compensated and uncompensated k2 through the study's calibration
/// model ([`calibration::CalibrationModel`], k1 given): `k2 = β/ρ² − k1·C_r·gain·(L/L₀)/s²·g/R²`,
/// `k2_uncompensated = β/ρ²`, with `ρ = (R·s²/g)/(R₀/g₀)` and `L = (h_p + h_a)/h_p`. The
/// fit's other coefficients enter as exact (they do not reach k2).
fn gum_k2(p: &Problem, u_fit: f64, fit_dof: usize, u_c_r: Option<(f64, usize)>) -> Result<Gum> {
    use uncertainty::{Dof, GumOptions, InputQuantity, gum};
    let inputs = &p.inputs;
    let c = &inputs.centrifuge;
    let pr = &inputs.probe;
    let tb = &inputs.type_b;
    let (r0, g0) = (c.radius_m, c.g_m_s2);
    let (hp0, ha0) = (pr.pivot_to_probe_mm, pr.probe_to_piga_mm);
    let k1 = inputs.piga.k1_rad_s_g;
    let c_r = inputs.c_r.expected_m_s2;
    let apparent = inputs.piga.k2_rad_s_g2 + identify::delta_k2_rad_s_g2(k1, c_r, r0, g0);
    let name = |i: usize| {
        BUDGET_INPUTS
            .iter()
            .find(|(j, _)| *j == i)
            .map_or_else(|| format!("fit coefficient {i}"), |(_, n)| (*n).to_owned())
    };
    let c_r_input = match u_c_r {
        Some((u, dof)) if dof > 0 && u > 0.0 => {
            InputQuantity::type_a(name(input::C_R), c_r, u, Dof::Finite(dof as f64))
        }
        Some((u, _)) => InputQuantity::normal(name(input::C_R), c_r, u),
        None => InputQuantity::normal(name(input::C_R), c_r, inputs.c_r.u_m_s2.unwrap_or(0.0)),
    };
    let a2 = input::FIRST_COEFFICIENT + calibration::A2_TERM;
    let beta = if u_fit > 0.0 {
        InputQuantity::type_a(name(a2), apparent, u_fit, Dof::Finite(fit_dof as f64))
    } else {
        InputQuantity::normal(name(a2), apparent, 0.0)
    };
    let mut quantities = vec![
        InputQuantity::normal(name(input::RADIUS), r0, tb.radius_u_m),
        InputQuantity::normal(name(input::G), g0, tb.g_u_m_s2),
        InputQuantity::normal(name(input::RATE_SCALE), 1.0, tb.rate_u_relative),
        InputQuantity::normal(name(input::PIVOT_TO_PROBE), hp0, tb.pivot_to_probe_u_mm),
        InputQuantity::normal(name(input::PROBE_TO_PIGA), ha0, tb.probe_to_piga_u_mm),
        InputQuantity::normal(name(input::PROBE_GAIN), 1.0, tb.probe_gain_u_relative),
        c_r_input,
        InputQuantity::normal(name(input::K1_GIVEN), k1, inputs.piga.k1_u_rad_s_g),
    ];
    for t in 0..calibration::TERMS {
        let i = input::FIRST_COEFFICIENT + t;
        quantities.push(if i == a2 {
            beta.clone()
        } else {
            InputQuantity::normal(name(i), 0.0, 0.0)
        });
    }
    let model = calibration::CalibrationModel::new(
        calibration::Nominal {
            radius_m: r0,
            g_m_s2: g0,
            pivot_to_probe_mm: hp0,
            probe_to_piga_mm: ha0,
        },
        calibration::K1Mode::Given,
    );
    let set = uncertainty::Inputs::new(quantities.clone()).map_err(PlanningError::Uncertainty)?;
    let result = gum(&model, &set, &GumOptions::default()).map_err(PlanningError::Uncertainty)?;
    let expanded = |o: &uncertainty::GumOutput| Expanded {
        u_rad_s_g2: o.standard_uncertainty,
        // ν is finite whenever the fit's Type A term is present (every plan); the Type B
        // floor, all of whose inputs have ν = ∞, is reported as U95 alone, so 1e6 stands in
        // for ∞ only there and is never shown.
        dof: o.dof.finite().unwrap_or(1e6),
        k: o.coverage_factor,
        u95_rad_s_g2: o.expanded_uncertainty,
    };
    let comp = &result.outputs[output::K2];
    let uncomp = &result.outputs[output::K2_UNCOMPENSATED];
    // The uncompensated k2 does not use C_r, k1 or the probe: its budget omits them.
    let budget = BUDGET_INPUTS
        .iter()
        .map(|&(i, _)| (&comp.contributions[i], &quantities[i]))
        .filter(|(c, _)| c.uncertainty > 0.0)
        .map(|(c, q)| BudgetLine {
            quantity: q.name.clone(),
            u: q.standard_uncertainty,
            sensitivity: c.sensitivity,
            contribution_rad_s_g2: c.uncertainty,
            percent: c.variance_percent,
        })
        .collect();
    Ok(Gum {
        compensated: expanded(comp),
        uncompensated: expanded(uncomp),
        budget,
    })
}

/// The plan of an allocated design with whole revolutions.
fn describe(p: &Problem, best: &Allocated, revolutions: &[u32]) -> Result<Plan> {
    let inputs = &p.inputs;
    let s = &inputs.schedule;
    // Sort the points by rate.
    let mut order: Vec<usize> = (0..best.design.len()).collect();
    order.sort_by_key(|&k| best.design[k]);
    let design: Vec<usize> = order.iter().map(|&k| best.design[k]).collect();
    let revs: Vec<u32> = order.iter().map(|&k| revolutions[k]).collect();
    let sigma: Vec<f64> = design
        .iter()
        .zip(&revs)
        .map(|(&i, &n)| sigma_mean(p, i, n))
        .collect();
    let sigma_r: Vec<f64> = design
        .iter()
        .zip(&revs)
        .map(|(&i, &n)| sigma_radius(p, i, n))
        .collect();
    let (u_fit, condition_number) = fit_u_k2(p, &design, &sigma)?;
    // The same rates with equal revolutions in the same recording time.
    let recording: f64 = design
        .iter()
        .zip(&revs)
        .map(|(&i, &n)| f64::from(n) * p.grid.tau_s[i])
        .sum();
    let per_rev: f64 = design.iter().map(|&i| p.grid.tau_s[i]).sum();
    let equal = recording / per_rev;
    let sigma_equal: Vec<f64> = design
        .iter()
        .map(|&i| (1.0 / (equal * p.grid.tau_s[i] * p.grid.info_per_s[i])).sqrt())
        .collect();
    let (u_equal, _) = fit_u_k2(p, &design, &sigma_equal)?;
    let fit_dof = design.len() - UNKNOWNS;
    let (u_c_r, c_r_predicted) = match inputs.c_r.u_m_s2 {
        Some(u) => (u, false),
        None => (predicted_u_c_r(p, &design, &sigma_r), true),
    };
    let c_r_arg = c_r_predicted.then_some((u_c_r, design.len() - 2));
    let g = gum_k2(p, u_fit, fit_dof, c_r_arg)?;
    let floor = if c_r_predicted {
        gum_k2(p, 0.0, fit_dof, Some((0.0, 0)))?
    } else {
        gum_k2(p, 0.0, fit_dof, None)?
    };
    let c = &inputs.centrifuge;
    let k1 = inputs.piga.k1_rad_s_g;
    let delta_k2 = k1 * inputs.c_r.expected_m_s2 * c.g_m_s2 / (c.radius_m * c.radius_m);
    let fraction = inputs.target.bias_fraction;
    let c_r_limit =
        fraction * g.uncompensated.u95_rad_s_g2 * c.radius_m * c.radius_m / (k1.abs() * c.g_m_s2);
    let tol = inputs.target.tolerance_k2_rad_s_g2;
    let points: Vec<PlanPoint> = design
        .iter()
        .zip(&revs)
        .zip(sigma.iter().zip(&sigma_r))
        .map(|((&i, &n), (&sm, &sr))| {
            let recording_s = f64::from(n) * p.grid.tau_s[i];
            PlanPoint {
                rate_deg_s: p.rates_rad_s[i].to_degrees(),
                revolutions: n,
                recording_s,
                settling_s: s.settling_s,
                duration_s: recording_s + s.settling_s,
                sigma_mean_rad_s: sm,
                sigma_radius_m: sr,
            }
        })
        .collect();
    let mut distinct = design.clone();
    distinct.dedup();
    let plan = Plan {
        criterion: inputs.search.criterion,
        radius_m: c.radius_m,
        g_m_s2: c.g_m_s2,
        candidates: p.rates_rad_s.len(),
        max_rate_deg_s: p.max_rate_deg_s,
        distinct_rates: distinct.len(),
        total_time_s: points.iter().map(|q| q.duration_s).sum(),
        points,
        budget_s: s.budget_s,
        u_k2_fit_rad_s_g2: u_fit,
        u_k2_fit_equal_revolutions_rad_s_g2: u_equal,
        fit_dof,
        condition_number,
        u_c_r_m_s2: u_c_r,
        c_r_predicted,
        compensated: g.compensated,
        uncompensated: g.uncompensated,
        delta_k2_expected_rad_s_g2: delta_k2,
        bias_fraction: fraction,
        c_r_limit_m_s2: c_r_limit,
        c_r_within_limit: inputs.c_r.expected_m_s2.abs() <= c_r_limit,
        tur_compensated: tol / g.compensated.u95_rad_s_g2,
        tur_uncompensated: tol / (g.uncompensated.u95_rad_s_g2 + delta_k2.abs()),
        target_u95_rad_s_g2: inputs.target.u95_k2_rad_s_g2,
        type_b_floor_u95_rad_s_g2: floor.compensated.u95_rad_s_g2,
        budget: g.budget,
    };
    check_finite(&plan)?;
    Ok(plan)
}

/// No `Ok` plan holds a NaN or an infinity.
fn check_finite(plan: &Plan) -> Result<()> {
    let expanded = |e: &Expanded| [e.u_rad_s_g2, e.dof, e.k, e.u95_rad_s_g2];
    let mut fields: Vec<(&'static str, f64)> = vec![
        ("u_k2_fit_rad_s_g2", plan.u_k2_fit_rad_s_g2),
        (
            "u_k2_fit_equal_revolutions_rad_s_g2",
            plan.u_k2_fit_equal_revolutions_rad_s_g2,
        ),
        ("condition_number", plan.condition_number),
        ("u_c_r_m_s2", plan.u_c_r_m_s2),
        (
            "delta_k2_expected_rad_s_g2",
            plan.delta_k2_expected_rad_s_g2,
        ),
        ("c_r_limit_m_s2", plan.c_r_limit_m_s2),
        ("tur_compensated", plan.tur_compensated),
        ("tur_uncompensated", plan.tur_uncompensated),
        ("type_b_floor_u95_rad_s_g2", plan.type_b_floor_u95_rad_s_g2),
        ("total_time_s", plan.total_time_s),
    ];
    fields.extend(expanded(&plan.compensated).map(|v| ("compensated", v)));
    fields.extend(expanded(&plan.uncompensated).map(|v| ("uncompensated", v)));
    for q in &plan.points {
        for v in [
            q.rate_deg_s,
            q.recording_s,
            q.duration_s,
            q.sigma_mean_rad_s,
            q.sigma_radius_m,
        ] {
            fields.push(("points", v));
        }
    }
    for b in &plan.budget {
        for v in [b.u, b.sensitivity, b.contribution_rad_s_g2, b.percent] {
            fields.push(("budget", v));
        }
    }
    match fields.iter().find(|(_, v)| !v.is_finite()) {
        Some(&(field, _)) => Err(PlanningError::NonFinite { field }),
        None => Ok(()),
    }
}

/// How recording time is shared among given rates in [`evaluate_rates`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Allocation {
    /// The allocation that minimises var(k2) (as the planner's).
    Optimal,
    /// The same number of whole revolutions at every rate.
    EqualRevolutions,
}

/// The fit part of u(k2) of given rates.
#[derive(Debug, Clone, PartialEq)]
pub struct RateEvaluation {
    /// The rates, deg/s, as given.
    pub rates_deg_s: Vec<f64>,
    /// Whole revolutions at each rate.
    pub revolutions: Vec<u32>,
    /// Predicted u(k2) of the eq. 18 fit, σ known, rad/(s·g²).
    pub u_k2_fit_rad_s_g2: f64,
}

/// The fit part of u(k2) of given rates (for instance the paper's six) within the plan's
/// budget, settling and noise: with the optimal allocation or equal revolutions. Six rates
/// are allowed here (no residual degree of freedom is needed for σ known).
///
/// # Errors
/// As [`plan`] for the plan's fields; [`PlanningError::Singular`] for rates that cannot
/// separate the six terms; [`PlanningError::BudgetTooShort`] when the rates' minimum
/// revolutions and settling do not fit.
pub fn evaluate_rates(
    inputs: &PlanInputs,
    rates_deg_s: &[f64],
    allocation: Allocation,
) -> Result<RateEvaluation> {
    let mut distinct: Vec<f64> = rates_deg_s.to_vec();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    if distinct.len() < UNKNOWNS || distinct.iter().any(|r| !(r.is_finite() && *r > 0.0)) {
        return Err(PlanningError::Singular {
            rates_deg_s: rates_deg_s.to_vec(),
        });
    }
    let mut probe = inputs.clone();
    probe.centrifuge.candidates = crate::Candidates::List(distinct.clone());
    probe.centrifuge.min_rate_deg_s = probe.centrifuge.min_rate_deg_s.min(distinct[0]);
    probe.centrifuge.max_rate_deg_s = probe
        .centrifuge
        .max_rate_deg_s
        .max(distinct[distinct.len() - 1]);
    probe.centrifuge.max_acceleration_g = None;
    probe.schedule.points = UNKNOWNS + 1;
    probe.schedule.allow_repeats = true;
    let p = Problem::new(&probe)?;
    let design: Vec<usize> = rates_deg_s
        .iter()
        .map(|r| distinct.iter().position(|d| d == r).unwrap_or(0))
        .collect();
    let singular = || PlanningError::Singular {
        rates_deg_s: rates_deg_s.to_vec(),
    };
    let s = &inputs.schedule;
    let free = p.free_time(&design);
    if free < 0.0 {
        return Err(PlanningError::BudgetTooShort {
            budget_s: s.budget_s,
            needed_s: s.budget_s - free,
            settling_s: s.settling_s * design.len() as f64,
            minimum_s: s.budget_s - free - s.settling_s * design.len() as f64,
            points: design.len(),
        });
    }
    let revolutions = match allocation {
        Allocation::Optimal => {
            let a = exchange::allocate_final(&p, &design, Criterion::K2).ok_or_else(singular)?;
            design::whole_revolutions(&p, &a)
        }
        Allocation::EqualRevolutions => {
            let per_rev: f64 = design.iter().map(|&i| p.grid.tau_s[i]).sum();
            let n = ((s.budget_s - s.settling_s * design.len() as f64) / per_rev).floor();
            vec![(n as u32).max(s.min_revolutions); design.len()]
        }
    };
    let time: Vec<f64> = design
        .iter()
        .zip(&revolutions)
        .map(|(&i, &n)| f64::from(n) * p.grid.tau_s[i])
        .collect();
    let var = exchange::var_k2_scaled(&p, &design, &time).ok_or_else(singular)?;
    Ok(RateEvaluation {
        rates_deg_s: rates_deg_s.to_vec(),
        revolutions,
        u_k2_fit_rad_s_g2: var.sqrt() / p.grid.scale[K2],
    })
}

/// The exhaustive optimum of var(k2) over every set of `points` distinct candidates (for
/// tests on small grids; `C(n, points)` designs, each with its optimal allocation). Returns
/// the rates, deg/s, and the fit part of u(k2) of the continuous allocation, with the
/// planner's own continuous optimum for the same inputs.
///
/// # Errors
/// As [`plan`].
pub fn exhaustive_k2(inputs: &PlanInputs) -> Result<ExhaustiveComparison> {
    use rayon::prelude::*;
    let p = Problem::new(inputs)?;
    p.check_budget()?;
    let n = p.rates_rad_s.len();
    let m = inputs.schedule.points;
    let mut subsets = Vec::new();
    let mut idx: Vec<usize> = (0..m).collect();
    loop {
        subsets.push(idx.clone());
        let mut i = m;
        while i > 0 && idx[i - 1] == n - m + i - 1 {
            i -= 1;
        }
        if i == 0 {
            break;
        }
        idx[i - 1] += 1;
        for j in i..m {
            idx[j] = idx[j - 1] + 1;
        }
    }
    let best = subsets
        .par_iter()
        .filter_map(|d| exchange::allocate_final(&p, d, Criterion::K2))
        .min_by(|a, b| a.value.total_cmp(&b.value))
        .ok_or_else(|| PlanningError::Singular {
            rates_deg_s: Vec::new(),
        })?;
    let mut k2_inputs = inputs.clone();
    k2_inputs.search.criterion = Criterion::K2;
    let pk = Problem::new(&k2_inputs)?;
    let planned = design::search(&pk).ok_or_else(|| PlanningError::Singular {
        rates_deg_s: Vec::new(),
    })?;
    let rates = |d: &[usize]| d.iter().map(|&i| p.rates_rad_s[i].to_degrees()).collect();
    Ok(ExhaustiveComparison {
        designs: subsets.len(),
        exhaustive_rates_deg_s: rates(&best.design),
        exhaustive_u_k2_fit_rad_s_g2: best.value.sqrt() / p.grid.scale[K2],
        planner_rates_deg_s: rates(&planned.design),
        planner_u_k2_fit_rad_s_g2: planned.value.sqrt() / p.grid.scale[K2],
    })
}

/// The planner against the exhaustive optimum ([`exhaustive_k2`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ExhaustiveComparison {
    /// Designs searched.
    pub designs: usize,
    /// The exhaustive optimum's rates, deg/s.
    pub exhaustive_rates_deg_s: Vec<f64>,
    /// Its u(k2) of the fit (continuous allocation), rad/(s·g²).
    pub exhaustive_u_k2_fit_rad_s_g2: f64,
    /// The planner's rates, deg/s.
    pub planner_rates_deg_s: Vec<f64>,
    /// Its u(k2) of the fit (continuous allocation), rad/(s·g²).
    pub planner_u_k2_fit_rad_s_g2: f64,
}
