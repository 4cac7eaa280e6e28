//! The two-orientation plan (issue 20): rates and recording time in both mountings for the
//! smallest u(k2) of the probe-free method, on a round rate grid with a lack-of-fit reserve,
//! beside the probe method's u(k2) in the same budget.

use calibration::{
    GAMMA_TERM, K2_TERM, MIN_RATES_PER_ORIENTATION, Orientation, OrientationData,
    TWO_ORIENTATION_TERMS, TwoOrientationFit, fit_two_orientation, two_orientation_row,
};

use crate::error::{PlanningError, Result};
use crate::exchange::{self, Allocated, Budget, FINAL_ITERATIONS, Space as _};
use crate::inputs::{Criterion, PlanInputs, Problem};
use crate::plan::{Plan, plan_unchecked};
use crate::two_orientation_inputs::{
    LackOfFitReserve, RateGrid, TwoOrientationPlanInputs, round_grid,
};
use crate::two_orientation_space::{self, Limits, TwoOrientationProblem};

/// One point of a mounting's run sheet.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OrientationPoint {
    /// Rate, deg/s.
    pub rate_deg_s: f64,
    /// Whole revolutions recorded.
    pub revolutions: u32,
    /// Recording time, s.
    pub recording_s: f64,
    /// Settling time before recording, s.
    pub settling_s: f64,
    /// Settling plus recording, s.
    pub duration_s: f64,
    /// Predicted standard deviation of the point's mean PIGA output, rad/s.
    pub sigma_mean_rad_s: f64,
    /// Whether the point was added by the lack-of-fit reserve.
    pub reserve: bool,
}

/// One mounting's part of the plan.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MountingSchedule {
    /// IA in or IA out.
    pub orientation: Orientation,
    /// Static radius, m.
    pub radius_m: f64,
    /// The highest rate allowed in this mounting (rate and acceleration limits), deg/s.
    pub max_rate_deg_s: f64,
    /// Candidate rates in this mounting.
    pub candidates: usize,
    /// The run sheet, by rate.
    pub points: Vec<OrientationPoint>,
    /// Recording time, s.
    pub recording_s: f64,
    /// Settling plus recording, s.
    pub duration_s: f64,
}

/// What rounding the rates costs.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RoundingCost {
    /// The round grid's step, deg/s.
    pub step_deg_s: f64,
    /// u(k2) of the plan on the round grid, rad/(s·g²).
    pub u_k2_round_rad_s_g2: f64,
    /// u(k2) of the plan on the plan file's candidates (unrounded), rad/(s·g²).
    pub u_k2_unrounded_rad_s_g2: f64,
    /// The unrounded plan's rates, IA in then IA out, deg/s.
    pub unrounded_rates_deg_s: [Vec<f64>; 2],
    /// `u_round/u_unrounded − 1`, percent.
    pub cost_percent: f64,
}

/// What the lack-of-fit reserve costs.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ReserveCost {
    /// The reserve asked for.
    pub extra_rates_per_orientation: usize,
    /// Its share of the recording time spread over every point.
    pub time_fraction: f64,
    /// u(k2) of the same grid without the reserve (six rates per orientation), rad/(s·g²).
    pub u_k2_without_rad_s_g2: f64,
    /// `u_with/u_without − 1`, percent.
    pub cost_percent: f64,
    /// Residual degrees of freedom of the joint fit with the reserve (points − 10).
    pub residual_dof: usize,
    /// The Birge ratio `√(χ²/ν)` above which the fit is reported as lacking
    /// ([`calibration::lack_of_fit_limit`]).
    pub lack_of_fit_limit: f64,
}

/// A two-orientation plan and what it predicts.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TwoOrientationPlan {
    /// Gravity, m/s².
    pub g_m_s2: f64,
    /// The rates chosen from.
    pub rates: RateGrid,
    /// IA in, then IA out.
    pub mountings: [MountingSchedule; 2],
    /// Time to turn the PIGA round, s.
    pub remount_s: f64,
    /// Total centrifuge time: both mountings and the remount, s.
    pub total_time_s: f64,
    /// The budget, s.
    pub budget_s: f64,
    /// Share of the recording time spent IA in.
    pub recording_share_ia_in: f64,
    /// Predicted u(k2) of the joint fit of eq. 23 (output noise, σ known; weighted by
    /// `1/σ_i²`), rad/(s·g²): k2 with no probe.
    pub u_k2_rad_s_g2: f64,
    /// Residual degrees of freedom (points − 10).
    pub fit_dof: usize,
    /// Coverage factor `t_{0.975}(ν)`.
    pub k: f64,
    /// U95(k2) = k·u, rad/(s·g²).
    pub u95_k2_rad_s_g2: f64,
    /// The total radius growth C = C_r + C_a expected, m·s².
    pub c_expected_m_s2: f64,
    /// Predicted u(C) from the PIGA alone, m·s².
    pub u_c_m_s2: f64,
    /// Variance inflation factor of the `s·ω⁴` column (a diagnostic; about 1e6–1e7 on
    /// ordinary designs).
    pub omega4_vif: f64,
    /// What fitting C costs k2: u(k2) of the joint fit over u(k2) with C known,
    /// `1/√(1 − ρ²)` (`calibration::TwoOrientationFit::k2_inflation`; the study warns that C and
    /// k2 are not separated above [`calibration::K2_INFLATION_LIMIT`]).
    pub k2_inflation: f64,
    /// Whether the study will give that warning for this design.
    pub c_separable: bool,
    /// 2-norm condition number of the column-scaled, weighted design.
    pub condition_number: f64,
    /// What the round grid costs against the unrounded optimum.
    pub rounding: RoundingCost,
    /// What the lack-of-fit reserve costs.
    pub reserve: ReserveCost,
    /// The probe method for the same budget: the single-orientation plan of the same plan
    /// file (IA in, compensated with the probe's C_r).
    pub probe_method: Plan,
    /// `u(k2)` of the probe method (compensated, with its Type B inputs) over this plan's.
    pub probe_over_two_orientations: f64,
    /// The arm stretch expected, m·s².
    pub arm_stretch_m_s2: f64,
    /// The probe method's k2 error from the arm stretch it cannot see,
    /// `k1·C_a·g/R²`, rad/(s·g²).
    pub probe_method_arm_stretch_error_rad_s_g2: f64,
    /// The target U95(k2), rad/(s·g²).
    pub target_u95_rad_s_g2: f64,
    /// Whether this plan's U95(k2) meets it.
    pub target_met: bool,
}

/// A joint design with whole revolutions and its predicted figures.
struct Outcome {
    mountings: [Vec<OrientationPoint>; 2],
    fit: TwoOrientationFit,
}

impl Outcome {
    fn u_k2(&self) -> f64 {
        self.fit.fit.unscaled_covariance[(K2_TERM, K2_TERM)].sqrt()
    }
    fn rates(&self) -> [Vec<f64>; 2] {
        self.mountings
            .each_ref()
            .map(|m| m.iter().map(|q| q.rate_deg_s).collect())
    }
}

/// The coefficients of eq. 23 a plan expects: biases with their shifts, `k1`, `k2`, `k3`,
/// `γ = k1·C/g` with `C = C_r + C_a`; the nuisance ω terms 0.
fn expected_coefficients(
    inputs: &PlanInputs,
    spec: &TwoOrientationPlanInputs,
) -> [f64; TWO_ORIENTATION_TERMS] {
    let p = &inputs.piga;
    let g = inputs.centrifuge.g_m_s2;
    let c = inputs.c_r.expected_m_s2 + spec.arm_stretch_m_s2;
    let mut b = [0.0; TWO_ORIENTATION_TERMS];
    b[0] = p.k0_rad_s + spec.ia_in.bias_shift_rad_s;
    b[2] = p.k1_rad_s_g;
    b[3] = p.k0_rad_s + spec.ia_out.bias_shift_rad_s;
    b[5] = p.k1_rad_s_g;
    b[K2_TERM] = p.k2_rad_s_g2;
    b[8] = p.k3_rad_s_g3;
    b[GAMMA_TERM] = p.k1_rad_s_g * c / g;
    b
}

/// The noise-free mean outputs of a plan's points by eq. 23 (first order; the exact chain is
/// `simulate::piga_table_mounted`), IA in then IA out.
///
/// # Errors
/// [`PlanningError::MissingTwoOrientations`] when the inputs have no two-orientation part.
pub fn expected_two_orientation_outputs(
    inputs: &PlanInputs,
    plan: &TwoOrientationPlan,
) -> Result<[Vec<f64>; 2]> {
    let spec = spec(inputs)?;
    let b = expected_coefficients(inputs, spec);
    Ok(outputs_of(&plan.mountings, plan.g_m_s2, &b))
}

/// The mean outputs of eq. 23 with coefficients `b` at the mountings' points (each row from
/// `calibration::two_orientation_row`).
fn outputs_of(
    mountings: &[MountingSchedule; 2],
    g_m_s2: f64,
    b: &[f64; TWO_ORIENTATION_TERMS],
) -> [Vec<f64>; 2] {
    mountings.each_ref().map(|m| {
        m.points
            .iter()
            .map(|q| {
                let row = two_orientation_row(
                    m.orientation,
                    m.radius_m,
                    g_m_s2,
                    units::deg_s_to_rad_s(q.rate_deg_s),
                );
                row.iter().zip(b).map(|(x, c)| x * c).sum()
            })
            .collect()
    })
}

fn spec(inputs: &PlanInputs) -> Result<&TwoOrientationPlanInputs> {
    inputs
        .two_orientation
        .as_ref()
        .ok_or(PlanningError::MissingTwoOrientations)
}

/// Fits eq. 23 to the points' outputs with their σ (the calibration's own fit).
pub(crate) fn fit_points(
    mountings: &[MountingSchedule; 2],
    g_m_s2: f64,
    outputs: [&[f64]; 2],
) -> Result<TwoOrientationFit> {
    let rates: [Vec<f64>; 2] = mountings.each_ref().map(|m| {
        m.points
            .iter()
            .map(|q| units::deg_s_to_rad_s(q.rate_deg_s))
            .collect()
    });
    let sigma: [Vec<f64>; 2] = mountings
        .each_ref()
        .map(|m| m.points.iter().map(|q| q.sigma_mean_rad_s).collect());
    let data = [0, 1].map(|k| OrientationData {
        field: ["two_orientation.ia_in", "two_orientation.ia_out"][k],
        orientation: Some(mountings[k].orientation),
        radius_m: Some(mountings[k].radius_m),
        rates_rad_s: &rates[k],
        output_rad_s: outputs[k],
        sigma_rad_s: Some(&sigma[k]),
    });
    fit_two_orientation(&data, g_m_s2, "two_orientation").map_err(PlanningError::TwoOrientation)
}

/// Plans the two-orientation calibration of `inputs.two_orientation`: per mounting the rates
/// (on the round grid unless `rates: candidates`) and whole revolutions, the time split
/// between the mountings, the lack-of-fit reserve, and the predicted u(k2) of the joint fit
/// of eq. 23 — beside the probe method's ([`plan`](crate::plan) of the same file, without
/// its target check) in the same budget, and the costs of rounding and of the reserve.
///
/// The budget holds the remount, a settling time per point and the recording.
///
/// # Errors
/// [`PlanningError::MissingTwoOrientations`]; the errors of [`plan`](crate::plan) for the
/// common fields; [`PlanningError::InvalidField`] for a two-orientation field;
/// [`PlanningError::RateRange`] and [`PlanningError::TooFewCandidates`] for a mounting;
/// [`PlanningError::TwoOrientationBudgetTooShort`]; [`PlanningError::TwoOrientation`] from the
/// fit.
pub fn plan_two_orientation(inputs: &PlanInputs) -> Result<TwoOrientationPlan> {
    let spec = spec(inputs)?;
    spec.validate()?;
    let base = Problem::new(inputs)?;
    let c = &inputs.centrifuge;
    let radii = [spec.ia_in.radius_m, spec.ia_out.radius_m];
    let max_rate = radii.map(|r| {
        c.max_acceleration_g.map_or(c.max_rate_deg_s, |a| {
            c.max_rate_deg_s.min((a * c.g_m_s2 / r).sqrt().to_degrees())
        })
    });
    let need = MIN_RATES_PER_ORIENTATION + spec.reserve.extra_rates_per_orientation;
    let step = match spec.rates {
        RateGrid::Round { step_deg_s } => step_deg_s,
        RateGrid::Candidates => crate::two_orientation_inputs::DEFAULT_STEP_DEG_S,
    };
    let mut round: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    let mut listed: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for k in 0..2 {
        if max_rate[k] < c.min_rate_deg_s {
            return Err(PlanningError::RateRange {
                min_rate_deg_s: c.min_rate_deg_s,
                max_rate_deg_s: max_rate[k],
                binding: "centrifuge.max_acceleration_g",
            });
        }
        let slack = 1e-9 * max_rate[k];
        round[k] = round_grid(step, c.min_rate_deg_s, max_rate[k]);
        listed[k] = base
            .rates_rad_s
            .iter()
            .map(|w| w.to_degrees())
            .filter(|&r| r <= max_rate[k] + slack)
            .collect();
        for (rates, reason) in [
            (&round[k], "the round grid's rates in this mounting"),
            (&listed[k], "the plan file's candidates in this mounting"),
        ] {
            if rates.len() < need {
                return Err(PlanningError::TooFewCandidates {
                    in_range: rates.len(),
                    need,
                    min_rate_deg_s: c.min_rate_deg_s,
                    max_rate_deg_s: max_rate[k],
                    reason,
                });
            }
        }
    }
    let s = &inputs.schedule;
    let limits = Limits {
        g_m_s2: c.g_m_s2,
        radius_m: radii,
        noise: inputs.piga.noise,
        budget: Budget {
            budget_s: s.budget_s,
            settling_s: s.settling_s,
            remount_s: spec.remount_s,
            min_revolutions: s.min_revolutions,
            allow_repeats: false,
        },
        restarts: inputs.search.restarts,
        seed: inputs.search.seed,
    };
    let expected = expected_coefficients(inputs, spec);
    let (chosen, other) = match spec.rates {
        RateGrid::Round { .. } => (&round, &listed),
        RateGrid::Candidates => (&listed, &round),
    };
    let p_chosen = TwoOrientationProblem::new(&limits, [&chosen[0], &chosen[1]]);
    let p_other = TwoOrientationProblem::new(&limits, [&other[0], &other[1]]);
    let reserve = spec.reserve;
    let extra = reserve.extra_rates_per_orientation;
    let best_chosen = search(&p_chosen, extra)?;
    // The other grid: one exchange from the chosen design's rates moved to its nearest
    // candidates (a local optimum next to the chosen one: what rounding costs, or saves).
    let chosen_rates = [0, 1].map(|k| {
        best_chosen
            .design
            .iter()
            .filter(|&&i| p_chosen.side(i) == k)
            .map(|&i| p_chosen.rates_deg_s[i])
            .collect::<Vec<f64>>()
    });
    let best_other =
        match two_orientation_space::search_near(&p_other, [&chosen_rates[0], &chosen_rates[1]]) {
            Some(b) => b,
            None => search(&p_other, extra)?,
        };
    let solve = |p: &TwoOrientationProblem, best: &Allocated, r: LackOfFitReserve| {
        outcome(p, best, r, &radii, c.g_m_s2, &expected)
    };
    let main = solve(&p_chosen, &best_chosen, reserve)?;
    let alternative = solve(&p_other, &best_other, reserve)?;
    let without = if reserve.is_off() {
        None
    } else {
        Some(solve(&p_chosen, &best_chosen, LackOfFitReserve::OFF)?)
    };
    let probe_method = plan_unchecked(inputs)?;
    describe(
        inputs,
        spec,
        DescribeArgs {
            main,
            alternative,
            without,
            probe_method,
            max_rate,
            candidates: [chosen[0].len(), chosen[1].len()],
            step,
        },
    )
}

/// The c-optimal design with six rates per orientation, after checking that the cheapest
/// design with the reserve's rates fits the budget.
fn search(p: &TwoOrientationProblem, extra: usize) -> Result<Allocated> {
    // The cheapest design: the fastest rates of each mounting at their least revolutions.
    let cheapest: Vec<usize> = p
        .ranges
        .iter()
        .flat_map(|r| r.clone().rev().take(MIN_RATES_PER_ORIENTATION + extra))
        .collect();
    let free = p.free_time(&cheapest);
    if free < 0.0 {
        let b = p.budget;
        let settling_s = b.settling_s * cheapest.len() as f64;
        return Err(PlanningError::TwoOrientationBudgetTooShort {
            budget_s: b.budget_s,
            needed_s: b.budget_s - free,
            remount_s: b.remount_s,
            settling_s,
            minimum_s: b.budget_s - free - settling_s - b.remount_s,
            points: cheapest.len(),
        });
    }
    two_orientation_space::search(p, [MIN_RATES_PER_ORIENTATION; 2]).ok_or(
        PlanningError::Singular {
            rates_deg_s: Vec::new(),
        },
    )
}

/// The reserve and whole revolutions of a searched design, and its predicted figures.
fn outcome(
    p: &TwoOrientationProblem,
    best: &Allocated,
    reserve: LackOfFitReserve,
    radii: &[f64; 2],
    g_m_s2: f64,
    expected: &[f64; TWO_ORIENTATION_TERMS],
) -> Result<Outcome> {
    let singular = || PlanningError::Singular {
        rates_deg_s: Vec::new(),
    };
    let (design, min_revs) = if reserve.is_off() {
        let n = best.design.len();
        (best.design.clone(), vec![p.budget.min_revolutions; n])
    } else {
        let d = two_orientation_space::add_reserve(
            p,
            &best.design,
            reserve.extra_rates_per_orientation,
        );
        let revs = two_orientation_space::reserve_revolutions(p, &d, reserve.time_fraction);
        (d, revs)
    };
    let min_s = p.recording_s(&design, &min_revs);
    let a = exchange::allocate(p, &design, &min_s, None, Criterion::K2, FINAL_ITERATIONS)
        .ok_or_else(singular)?;
    let revs = exchange::whole_revolutions(p, &a, &min_revs);
    let mut mountings: [Vec<OrientationPoint>; 2] = [Vec::new(), Vec::new()];
    for (&i, &n) in design.iter().zip(&revs) {
        let recording_s = f64::from(n) * p.grid.tau_s[i];
        mountings[p.side(i)].push(OrientationPoint {
            rate_deg_s: p.rates_deg_s[i],
            revolutions: n,
            recording_s,
            settling_s: p.budget.settling_s,
            duration_s: recording_s + p.budget.settling_s,
            sigma_mean_rad_s: (1.0 / (recording_s * p.grid.info_per_s[i])).sqrt(),
            reserve: !best.design.contains(&i),
        });
    }
    for m in &mut mountings {
        m.sort_by(|a, b| a.rate_deg_s.total_cmp(&b.rate_deg_s));
    }
    let schedules = [0, 1].map(|k| MountingSchedule {
        orientation: [Orientation::IaIn, Orientation::IaOut][k],
        radius_m: radii[k],
        max_rate_deg_s: 0.0,
        candidates: p.ranges[k].len(),
        points: mountings[k].clone(),
        recording_s: 0.0,
        duration_s: 0.0,
    });
    let outputs = outputs_of(&schedules, g_m_s2, expected);
    let fit = fit_points(&schedules, g_m_s2, [&outputs[0], &outputs[1]])?;
    Ok(Outcome { mountings, fit })
}

struct DescribeArgs {
    main: Outcome,
    alternative: Outcome,
    without: Option<Outcome>,
    probe_method: Plan,
    max_rate: [f64; 2],
    candidates: [usize; 2],
    step: f64,
}

fn describe(
    inputs: &PlanInputs,
    spec: &TwoOrientationPlanInputs,
    a: DescribeArgs,
) -> Result<TwoOrientationPlan> {
    let u = a.main.u_k2();
    let radii = [spec.ia_in.radius_m, spec.ia_out.radius_m];
    let mountings = [0, 1].map(|k| {
        let points = a.main.mountings[k].clone();
        MountingSchedule {
            orientation: [Orientation::IaIn, Orientation::IaOut][k],
            radius_m: radii[k],
            max_rate_deg_s: a.max_rate[k],
            candidates: a.candidates[k],
            recording_s: points.iter().map(|q| q.recording_s).sum(),
            duration_s: points.iter().map(|q| q.duration_s).sum(),
            points,
        }
    });
    let n: usize = mountings.iter().map(|m| m.points.len()).sum();
    let dof = n - TWO_ORIENTATION_TERMS;
    let k = uncertainty::coverage_factor(0.95, uncertainty::Dof::Finite(dof as f64))
        .map_err(PlanningError::Uncertainty)?;
    let (u_round, u_unrounded, unrounded) = match spec.rates {
        RateGrid::Round { .. } => (u, a.alternative.u_k2(), a.alternative.rates()),
        RateGrid::Candidates => (a.alternative.u_k2(), u, a.main.rates()),
    };
    let u_without = a.without.as_ref().map_or(u, Outcome::u_k2);
    let recording: f64 = mountings.iter().map(|m| m.recording_s).sum();
    let total = mountings.iter().map(|m| m.duration_s).sum::<f64>() + spec.remount_s;
    let g = inputs.centrifuge.g_m_s2;
    let k1 = inputs.piga.k1_rad_s_g;
    let r = inputs.centrifuge.radius_m;
    let u_probe = a.probe_method.compensated.u_rad_s_g2;
    let u95 = k * u;
    let plan = TwoOrientationPlan {
        g_m_s2: g,
        rates: spec.rates,
        remount_s: spec.remount_s,
        total_time_s: total,
        budget_s: inputs.schedule.budget_s,
        recording_share_ia_in: mountings[0].recording_s / recording,
        u_k2_rad_s_g2: u,
        fit_dof: dof,
        k,
        u95_k2_rad_s_g2: u95,
        c_expected_m_s2: inputs.c_r.expected_m_s2 + spec.arm_stretch_m_s2,
        u_c_m_s2: a.main.fit.c_m_s2.1,
        omega4_vif: a.main.fit.gamma_vif,
        k2_inflation: a.main.fit.k2_inflation,
        c_separable: a.main.fit.separable(),
        condition_number: a.main.fit.fit.condition_number,
        rounding: RoundingCost {
            step_deg_s: a.step,
            u_k2_round_rad_s_g2: u_round,
            u_k2_unrounded_rad_s_g2: u_unrounded,
            unrounded_rates_deg_s: unrounded,
            cost_percent: 100.0 * (u_round / u_unrounded - 1.0),
        },
        reserve: ReserveCost {
            extra_rates_per_orientation: spec.reserve.extra_rates_per_orientation,
            time_fraction: spec.reserve.time_fraction,
            u_k2_without_rad_s_g2: u_without,
            cost_percent: 100.0 * (u / u_without - 1.0),
            residual_dof: dof,
            lack_of_fit_limit: calibration::lack_of_fit_limit(dof),
        },
        probe_over_two_orientations: u_probe / u,
        probe_method: a.probe_method,
        arm_stretch_m_s2: spec.arm_stretch_m_s2,
        probe_method_arm_stretch_error_rad_s_g2: identify::delta_k2_rad_s_g2(
            k1,
            spec.arm_stretch_m_s2,
            r,
            g,
        ),
        target_u95_rad_s_g2: inputs.target.u95_k2_rad_s_g2,
        target_met: u95 <= inputs.target.u95_k2_rad_s_g2,
        mountings,
    };
    check_finite(&plan)?;
    Ok(plan)
}

/// No `Ok` plan holds a NaN or an infinity.
fn check_finite(p: &TwoOrientationPlan) -> Result<()> {
    let mut fields: Vec<(&'static str, f64)> = vec![
        ("u_k2_rad_s_g2", p.u_k2_rad_s_g2),
        ("u95_k2_rad_s_g2", p.u95_k2_rad_s_g2),
        ("k", p.k),
        ("u_c_m_s2", p.u_c_m_s2),
        ("omega4_vif", p.omega4_vif),
        ("k2_inflation", p.k2_inflation),
        ("condition_number", p.condition_number),
        ("recording_share_ia_in", p.recording_share_ia_in),
        ("rounding", p.rounding.cost_percent),
        ("reserve", p.reserve.cost_percent),
        ("probe_over_two_orientations", p.probe_over_two_orientations),
        (
            "probe_method_arm_stretch_error_rad_s_g2",
            p.probe_method_arm_stretch_error_rad_s_g2,
        ),
        ("total_time_s", p.total_time_s),
    ];
    for m in &p.mountings {
        for q in &m.points {
            fields.push(("points", q.sigma_mean_rad_s));
            fields.push(("points", q.duration_s));
        }
    }
    match fields.iter().find(|(_, v)| !v.is_finite()) {
        Some(&(field, _)) => Err(PlanningError::NonFinite { field }),
        None => Ok(()),
    }
}
