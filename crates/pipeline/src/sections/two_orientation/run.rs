//! The two-orientation section's run: the joint fit of eq. 23, its GUM and Monte Carlo
//! evaluation with the §8 comparison, the probe phase's C_r against the PIGA's C, k2 by the
//! probe method on the IA-in data set, and the results with their warnings.

use ::calibration::{
    K2_INFLATION_LIMIT, Orientation, OrientationData, ProbeCr, TwoOrientationError,
    TwoOrientationEvaluation, TwoOrientationFit, TwoOrientationWarning, evaluate_two_orientation,
    fit_two_orientation,
};
use uncertainty::{McOptions, Trials};

use super::validate::TwoOrientationInputs;
use crate::error::{PipelineError, Result};
use crate::inputs::Core;
use crate::piga_data::{self, PigaPoints};
use crate::results::{
    BudgetLine, Coefficient, Estimate, Headline, MonteCarloOutput, MountingResults,
    OutputCovariance, PhaseResults, ProbeComparison, ProbeDeclared, RateSpread,
    TwoOrientationBudgets, TwoOrientationHeadline, TwoOrientationMonteCarlo, TwoOrientationResults,
    Warning, budget_note,
};

/// Runs the section against the study's phase results (the probe phase's C_r).
pub(crate) fn run(
    core: &Core,
    s: &TwoOrientationInputs,
    phases: &[PhaseResults],
) -> Result<(TwoOrientationResults, Vec<Warning>)> {
    let _span = tracing::info_span!("two_orientation").entered();
    let fail = |e: TwoOrientationError| PipelineError::TwoOrientation {
        path: core.source.clone(),
        source: Box::new(e),
    };
    let (reduced, mut warnings) = reduce(core, s)?;
    let rates: Vec<Vec<f64>> = reduced
        .iter()
        .map(|p| {
            p.rates_deg_s
                .iter()
                .map(|&r| units::deg_s_to_rad_s(r))
                .collect()
        })
        .collect();
    let data: Vec<OrientationData<'_>> = s
        .sets
        .iter()
        .zip(&reduced)
        .zip(&rates)
        .map(|((d, p), w)| OrientationData {
            field: &d.field,
            orientation: Some(d.orientation),
            radius_m: Some(d.radius_m),
            rates_rad_s: w,
            output_rad_s: &p.outputs_rad_s,
            sigma_rad_s: p.sigma_rad_s.as_deref(),
        })
        .collect();
    let fit =
        fit_two_orientation(&data, core.g_m_s2, "two_orientation.orientations").map_err(fail)?;
    let spread = rate_spread(&data, core.g_m_s2);
    if let Some(r) = spread.filter(|r| r.k2.max(r.c) > ::calibration::INFLATION_LIMIT) {
        warnings.push(Warning::two_orientation_rates_bunched(
            r.k2,
            r.c,
            (r.reference_low_deg_s, r.reference_top_deg_s),
            ::calibration::INFLATION_LIMIT,
        ));
    }
    let phase = &phases[s.phase];
    let probe = probe_cr(core, phase);
    let options = McOptions {
        seed: s.seed,
        trials: s.trials.map_or(McOptions::default().trials, Trials::Fixed),
        ..McOptions::default()
    };
    let e = evaluate_two_orientation(&fit, &s.type_b, Some(probe), Some(&options)).map_err(fail)?;
    let mc = e
        .monte_carlo
        .as_ref()
        .expect("the Monte Carlo method was asked for");
    let validation = uncertainty::validate(&e.gum, mc, 2)
        .map_err(|u| fail(TwoOrientationError::Uncertainty(u)))?;
    let coefficient = |name: &str| {
        let o = e.gum.output(name).expect("the model names its outputs");
        Coefficient::of(o, o.estimate)
    };
    let mountings = mountings(s, &fit, &reduced, coefficient);
    let k2 = coefficient("k2");
    let c = coefficient("C");
    let monte_carlo = monte_carlo(mc, &validation, s.seed);
    let k3 = coefficient("k3");
    let headline = TwoOrientationHeadline {
        k2: Headline::of(&k2, &monte_carlo.k2),
        k3: Headline::of(&k3, &monte_carlo.k3),
        c: Headline::of(&c, &monte_carlo.c),
    };
    let (k2_probe, k2_probe_u95) = probe_k2(core, s, &reduced, probe).map_err(fail)?;
    let (d, u, z) = e
        .probe_difference
        .expect("the evaluation was given the probe");
    let comparison = ProbeComparison {
        phase: phase.name.clone(),
        chosen_by: s.chosen_by.to_owned(),
        c_r_m_s2: Estimate {
            value: probe.c_r_m_s2,
            u: probe.u_m_s2,
        },
        difference_m_s2: Coefficient {
            value: d,
            u,
            ..coefficient("C − C_r")
        },
        z,
        agrees: z.abs() <= ::calibration::Z_LIMIT,
        k2_probe,
        k2_probe_u95,
        k2_difference: k2.value - k2_probe.value,
    };
    let all: f64 = fit.residuals_rad_s.iter().flatten().map(|r| r * r).sum();
    let results = TwoOrientationResults {
        mountings,
        k2,
        k3,
        c_m_s2: c,
        delta_k2_total: coefficient("Δk2,total"),
        g_m_s2: Estimate {
            value: core.g_m_s2,
            u: s.type_b.g_u_m_s2,
        },
        dof: fit.fit.dof,
        residual_sd_rad_s: (all / fit.fit.dof.max(1) as f64).sqrt(),
        omega4_vif: fit.gamma_vif,
        k2_inflation_by_omega4: fit.k2_inflation,
        k2_c_correlation: fit.k2_gamma_correlation,
        u_inflation_by_rates: spread,
        condition_number: fit.fit.condition_number,
        budget: TwoOrientationBudgets {
            k2: budget(&e, "k2", &s.type_b_notes, &s.earth_rate.words),
            c: budget(&e, "C", &s.type_b_notes, &s.earth_rate.words),
            difference: Some(budget(&e, "C − C_r", &s.type_b_notes, &s.earth_rate.words)),
        },
        monte_carlo,
        headline,
        covariance: OutputCovariance::of(&e.gum, 6),
        probe: Some(comparison),
        earth_rate: s.earth_rate.clone(),
    };
    warnings.extend(evaluation_warnings(&e, core, s, phase));
    Ok((results, warnings))
}

/// Each data set's points: a table's rows, or each raw recording reduced (every recording's
/// problem at once, both orientations), with the reduction's warnings and one when only one
/// data set gives σ (the joint fit is weighted only when both do).
fn reduce(core: &Core, s: &TwoOrientationInputs) -> Result<(Vec<PigaPoints>, Vec<Warning>)> {
    let mut reduced = Vec::with_capacity(s.sets.len());
    let mut errors = Vec::new();
    let mut warnings = Vec::new();
    for d in &s.sets {
        match piga_data::points(&d.data, &core.source) {
            Ok((p, w)) => {
                reduced.push(p);
                warnings.extend(w);
            }
            Err(e) => errors.push(e),
        }
    }
    PipelineError::from_list(errors)?;
    if let ([a, b], [pa, pb]) = (s.sets.as_slice(), reduced.as_slice())
        && pa.sigma_rad_s.is_some() != pb.sigma_rad_s.is_some()
    {
        let (with, without) = if pa.sigma_rad_s.is_some() {
            (a, b)
        } else {
            (b, a)
        };
        warnings.push(Warning::two_orientation_unweighted(
            &with.field,
            &without.field,
        ));
    }
    Ok((reduced, warnings))
}

/// The probe phase's C_r with its standard uncertainty and degrees of freedom, and the
/// lever heights that scale it to the PIGA.
fn probe_cr(core: &Core, phase: &PhaseResults) -> ProbeCr {
    let c_r_u = phase.fit.c_r_sigma_m_s2.unwrap_or(0.0);
    ProbeCr {
        c_r_m_s2: phase.fit.c_r_m_s2,
        u_m_s2: c_r_u,
        dof: (c_r_u > 0.0 && phase.fit.dof > 0).then_some(phase.fit.dof as f64),
        pivot_to_probe_mm: core.lever.pivot_to_probe_mm,
        probe_to_piga_mm: core.lever.probe_to_piga_mm,
    }
}

/// Each mounting's results (IA in, then IA out): its data, radius, rates, k0 and k1 (by
/// `coefficient`, from the GUM), the Earth-rate term and its residual SD.
fn mountings(
    s: &TwoOrientationInputs,
    fit: &TwoOrientationFit,
    reduced: &[PigaPoints],
    coefficient: impl Fn(&str) -> Coefficient,
) -> Vec<MountingResults> {
    [Orientation::IaIn, Orientation::IaOut]
        .iter()
        .enumerate()
        .map(|(k, &o)| {
            let m = fit.mounting(o);
            let (set, points) = s
                .sets
                .iter()
                .zip(reduced)
                .find(|(d, _)| d.orientation == o)
                .expect("one data set per orientation");
            let tag = if k == 0 { "IA in" } else { "IA out" };
            let res = &fit.residuals_rad_s[k];
            MountingResults {
                orientation: match o {
                    Orientation::IaIn => "ia_in",
                    Orientation::IaOut => "ia_out",
                }
                .to_owned(),
                field: set.field.clone(),
                radius_m: m.radius_m,
                table: points.table.as_ref().map(|t| t.display().to_string()),
                recordings: points.recordings.clone(),
                points: points.rates_deg_s.len(),
                rate_low_deg_s: points
                    .rates_deg_s
                    .iter()
                    .copied()
                    .fold(f64::INFINITY, f64::min),
                rate_high_deg_s: points
                    .rates_deg_s
                    .iter()
                    .copied()
                    .fold(f64::NEG_INFINITY, f64::max),
                distinct_rates: m.distinct_rates,
                k0: coefficient(&format!("k0 ({tag})")),
                k1: coefficient(&format!("k1 ({tag})")),
                omega: Estimate {
                    value: m.b1.0,
                    u: m.b1.1,
                },
                residual_sd_rad_s: (res.iter().map(|r| r * r).sum::<f64>()
                    / res.len().max(1) as f64)
                    .sqrt(),
            }
        })
        .collect()
}

/// The Monte Carlo results of k2, k3, C, Δk2,total and C − C_r with their §8 validation.
fn monte_carlo(
    mc: &uncertainty::McResult,
    validation: &uncertainty::Validation,
    seed: u64,
) -> TwoOrientationMonteCarlo {
    let mc_output = |name: &str| MonteCarloOutput::of(mc, validation, name);
    TwoOrientationMonteCarlo {
        trials: mc.trials,
        seed,
        gum_agrees: ["k2", "k3", "C", "Δk2,total"]
            .iter()
            .all(|n| validation.output(n).is_some_and(|v| v.agrees)),
        k2: mc_output("k2"),
        k3: mc_output("k3"),
        c: mc_output("C"),
        delta_k2_total: mc_output("Δk2,total"),
        difference: Some(mc_output("C − C_r")),
    }
}

/// The evaluation's warnings in the study's words: ω⁴ not separable from k2, the probe
/// disagreeing with the PIGA's C (naming what the probe phase declares).
fn evaluation_warnings(
    e: &TwoOrientationEvaluation,
    core: &Core,
    s: &TwoOrientationInputs,
    phase: &PhaseResults,
) -> Vec<Warning> {
    e.warnings
        .iter()
        .map(|w| match *w {
            TwoOrientationWarning::GammaNotSeparable {
                vif,
                k2_inflation,
                correlation,
            } => Warning::omega4_not_separable(k2_inflation, correlation, K2_INFLATION_LIMIT, vif),
            TwoOrientationWarning::ProbeDisagrees {
                difference_m_s2,
                u_m_s2,
                z,
            } => Warning::probe_disagrees(
                &ProbeDeclared {
                    phase: phase.name.clone(),
                    angle_zero: core.angle_zero,
                    direction: crate::inputs::probe_sign(core.lever.probe_direction),
                    gap_field: s.gap_unit.0.clone(),
                    gap_unit: s.gap_unit.1.clone(),
                },
                phase.fit.c_r_m_s2,
                difference_m_s2,
                u_m_s2,
                z,
            ),
        })
        .collect()
}

/// k2 by the probe method, as the calibration section computes it: the IA-in data set's
/// eq. 18 fit (at its radius, k1 fitted, weighted with the Paule–Mandel τ when the points
/// give σ), compensated with the probe's C_r (eq. 19), and its uncertainty from
/// [`CalibrationModel`](::calibration::CalibrationModel) by the GUM with every Type B input
/// of the study (u(R) of the IA-in radius, g, the rate scale, the lever heights, the probe
/// gain) and u(C_r): the value, its standard uncertainty and U95.
fn probe_k2(
    core: &Core,
    s: &TwoOrientationInputs,
    reduced: &[PigaPoints],
    probe: ProbeCr,
) -> std::result::Result<(Estimate, f64), TwoOrientationError> {
    use ::calibration::{CalibrationModel, CrInput, K1Input, K1Mode, Nominal, output};
    let (set, points) = s
        .sets
        .iter()
        .zip(reduced)
        .find(|(d, _)| d.orientation == Orientation::IaIn)
        .expect("one data set per orientation");
    let rates: Vec<f64> = points
        .rates_deg_s
        .iter()
        .map(|&r| units::deg_s_to_rad_s(r))
        .collect();
    let geometry = identify::Geometry {
        radius_m: set.radius_m,
        g_m_s2: core.g_m_s2,
    };
    let compensation = ::calibration::compensation(probe.c_r_m_s2, probe.u_m_s2, None);
    let fitted = ::calibration::calibrate_compensated(
        &::calibration::Points {
            rates_rad_s: &rates,
            outputs_rad_s: &points.outputs_rad_s,
            sigma_rad_s: points.sigma_rad_s.as_deref(),
        },
        geometry,
        &compensation,
    )
    .map_err(|e| match e {
        ::calibration::CalibrationError::Fit(e) => TwoOrientationError::Fit(e),
        e => TwoOrientationError::Calibration(e),
    })?;
    let nominal = Nominal {
        radius_m: set.radius_m,
        g_m_s2: core.g_m_s2,
        pivot_to_probe_mm: probe.pivot_to_probe_mm,
        probe_to_piga_mm: probe.probe_to_piga_mm,
    };
    let c_r = CrInput {
        c_r_m_s2: probe.c_r_m_s2,
        sigma: probe.dof.map(|nu| (probe.u_m_s2, nu as usize)),
    };
    let (_, inputs) = ::calibration::measurement_inputs(
        &nominal,
        &s.type_b,
        c_r,
        K1Input::Fitted,
        &fitted.calibration.uncompensated.fit,
        fitted.weighting.group_dof,
    )
    .map_err(TwoOrientationError::Uncertainty)?;
    let model = CalibrationModel::new(nominal, K1Mode::Fitted);
    let gum = uncertainty::gum(&model, &inputs, &uncertainty::GumOptions::default())
        .map_err(TwoOrientationError::Uncertainty)?;
    let k2 = &gum.outputs[output::K2];
    Ok((
        Estimate {
            value: k2.estimate,
            u: k2.standard_uncertainty,
        },
        k2.expanded_uncertainty,
    ))
}

/// One output's budget: the fit's ten coefficients as one line (their correlated
/// contribution), then every other input that enters the output (g, the rate scale, each
/// mounting's radius; with the probe its lever heights, gain and C_r), each with what the
/// study says of it (`notes`, by the input of `calibration::input` it is: not stated, the
/// reason for a zero, where its u comes from).
fn budget(
    e: &TwoOrientationEvaluation,
    name: &str,
    notes: &[(usize, String)],
    earth_rate_words: &str,
) -> Vec<BudgetLine> {
    use ::calibration::{input, two_orientation_input as si};
    let (index, output) = e
        .gum
        .outputs
        .iter()
        .enumerate()
        .find(|(_, o)| o.name == name)
        .expect("the model names its outputs");
    let quantities = e.inputs.quantities();
    let terms = ::calibration::TWO_ORIENTATION_TERMS;
    let mut lines = vec![BudgetLine::fit_group(
        output,
        ::calibration::TWO_ORIENTATION_OUTPUT_UNITS[index],
        &output.contributions[..terms],
        "the two-orientation fit",
        quantities[0].dof,
    )];
    for (k, (c, q)) in output
        .contributions
        .iter()
        .zip(quantities)
        .enumerate()
        .skip(terms)
    {
        // an input the output does not depend on (C on g: a change of g rescales k1 and
        // γ = k1·C/g alike); a sensitivity of rounding size is no dependence either
        // (by its contribution too: the Earth rate's value is 0 when it is not stated)
        if (c.sensitivity * q.value).abs().max(c.uncertainty) <= 1e-9 * output.estimate.abs() {
            continue;
        }
        let study_input = match k {
            si::G => Some(input::G),
            si::RATE_SCALE => Some(input::RATE_SCALE),
            si::RADIUS_IN | si::RADIUS_OUT => Some(input::RADIUS),
            si::PIVOT_TO_PROBE => Some(input::PIVOT_TO_PROBE),
            si::PROBE_TO_PIGA => Some(input::PROBE_TO_PIGA),
            si::PROBE_GAIN => Some(input::PROBE_GAIN),
            _ => None,
        };
        let note = if k == si::EARTH_RATE {
            Some(earth_rate_words.to_owned())
        } else {
            study_input.and_then(|i| budget_note(notes, i))
        };
        lines.push(BudgetLine {
            // (+ 0.0: an input stated exactly contributes −0 % otherwise)
            percent: c.variance_percent + 0.0,
            ..BudgetLine::input(q, si::UNITS[k - si::G], c, note)
        });
    }
    lines
}

/// What the rates cost k2 and C against the evenly spread design
/// (`calibration::two_orientation_spread`), in both mountings' order IA in, IA out; `None` when
/// the reference design cannot be fitted (it then says nothing the fit has not said).
fn rate_spread(data: &[OrientationData<'_>], g_m_s2: f64) -> Option<RateSpread> {
    let design = |o: Orientation| {
        data.iter()
            .find(|d| d.orientation == Some(o))
            .and_then(|d| {
                Some(::calibration::MountingDesign {
                    orientation: o,
                    radius_m: d.radius_m?,
                    rates_rad_s: d.rates_rad_s,
                    sigma_rad_s: d.sigma_rad_s,
                })
            })
    };
    let designs = [design(Orientation::IaIn)?, design(Orientation::IaOut)?];
    let s = ::calibration::two_orientation_spread(&designs, g_m_s2).ok()?;
    Some(RateSpread {
        k2: s.k2,
        c: s.c,
        reference_low_deg_s: s.reference_rad_s.0.to_degrees(),
        reference_top_deg_s: s.reference_rad_s.1.to_degrees(),
    })
}
