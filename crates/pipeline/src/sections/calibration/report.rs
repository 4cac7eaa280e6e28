//! The calibration's results: the coefficients with their budgets and Monte Carlo check, the
//! residuals by row and by label, and the warnings about the data.

use ::calibration::{CalibrationWarning, TERM_NAMES, TERMS, input, output};

use super::evaluate::{Evaluated, Setting};
use super::validate::{CalibrationInputs, K1Choice};
use crate::piga_data::{Origin, PigaPoints};
use crate::results::{
    BudgetLine, CalibrationResults, CalibrationRow, Coefficient, Conventional, Estimate, Headline,
    LabelSummary, MonteCarlo, MonteCarloOutput, Nuisance, OutputCovariance, PigaCoefficients,
    UncertaintyInflation, Warning, budget_note,
};

/// The results of an evaluated calibration.
pub(crate) fn results(
    inputs: &CalibrationInputs,
    points: &PigaPoints,
    setting: &Setting<'_>,
    phase_name: &str,
    e: &Evaluated,
) -> CalibrationResults {
    let unc = &e.cal.uncompensated;
    let fit = &unc.fit;
    let out = |name: &str| {
        e.gum
            .output(name)
            .expect("the model names its outputs")
            .clone()
    };
    let k1_value = e.cal.k1_used_rad_s_g;
    let coefficients = PigaCoefficients {
        k0: Coefficient::of(&out("k0"), out("k0").estimate),
        k1: Coefficient::of(&out("k1"), k1_value),
        k2: Coefficient::of(&out("k2"), out("k2").estimate),
        k3: Coefficient::of(&out("k3"), out("k3").estimate),
    };
    let se = &fit.std_errors;
    let conventional = conventional(e, setting, &coefficients);
    let residual_sd_rad_s = e.residual_sd_rad_s;
    let labels = label_summaries(points, &unc.residuals_rad_s, residual_sd_rad_s);
    let budget_of = |index: usize| {
        budget(
            &out(output::NAMES[index]),
            output::UNITS[index],
            &e.quantities,
            e.weighting.group_dof,
            inputs.k1,
            &inputs.type_b.notes,
        )
    };
    let budget = PigaCoefficients {
        k0: budget_of(output::K0),
        k1: budget_of(output::K1),
        k2: budget_of(output::K2),
        k3: budget_of(output::K3),
    };
    let monte_carlo = monte_carlo(e, inputs.seed);
    let warnings = warnings(inputs, setting, phase_name, e, &monte_carlo);
    let headline = PigaCoefficients {
        k0: Headline::of(&coefficients.k0, &monte_carlo.k0),
        k1: Headline::of(&coefficients.k1, &monte_carlo.k1),
        k2: Headline::of(&coefficients.k2, &monte_carlo.k2),
        k3: Headline::of(&coefficients.k3, &monte_carlo.k3),
    };
    CalibrationResults {
        table: points.table.as_ref().map(|t| t.display().to_string()),
        recordings: points.recordings.clone(),
        weighted: points.sigma_rad_s.is_some(),
        birge_ratio: e.weighting.birge_ratio,
        excess_u_rad_s: e.weighting.excess_u_rad_s,
        compensate_with: phase_name.to_owned(),
        k1_source: match inputs.k1 {
            K1Choice::Fitted => "fitted".to_owned(),
            K1Choice::Given { .. } => "given".to_owned(),
        },
        g_m_s2: setting.nominal.g_m_s2,
        g_source: setting.type_b.g_source.clone(),
        points: points.rates_deg_s.len(),
        distinct_rates: unc.distinct_rates,
        dof: fit.dof,
        coefficients,
        uncompensated: uncompensated(e),
        delta_k2: Estimate {
            value: e.cal.delta_k2.delta_k2_rad_s_g2,
            u: out("delta_k2").standard_uncertainty,
        },
        c_r_m_s2: Estimate {
            value: setting.nominal.c_r_m_s2,
            u: setting.c_r_sigma.map_or(0.0, |(s, _)| s),
        },
        c_r_combined_m_s2: c_r_combined(setting),
        conventional,
        nuisance: Nuisance {
            omega: Estimate {
                value: unc.omega_coeff,
                u: se[1],
            },
            omega3_s2: Estimate {
                value: unc.omega3_coeff_s2,
                u: se[3],
            },
        },
        // The fit's own residual SD is in units of the points' σ when it is weighted.
        residual_sd_rad_s,
        residuals: residual_rows(points, e),
        labels,
        correlation: correlation(fit),
        covariance: OutputCovariance::of(&e.gum, 4),
        terms: TERM_NAMES.iter().map(|t| (*t).to_owned()).collect(),
        variance_inflation: e.vif.to_vec(),
        u_inflation: e.inflation.as_ref().map(u_inflation),
        condition_number: fit.condition_number,
        budget,
        monte_carlo,
        probe_direction: crate::inputs::probe_sign(setting.probe_direction),
        headline,
        warnings,
    }
}

/// The uncompensated fit's coefficients: k0, k1 implied by the fit, the apparent k2 and k3
/// with their standard errors.
fn uncompensated(e: &Evaluated) -> PigaCoefficients<Estimate> {
    let unc = &e.cal.uncompensated;
    let se = &unc.fit.std_errors;
    PigaCoefficients {
        k0: Estimate {
            value: unc.bias_rad_s,
            u: se[0],
        },
        k1: Estimate {
            value: unc.k1_implied_rad_s_g,
            u: unc.k1_implied_sigma_rad_s_g,
        },
        k2: Estimate {
            value: unc.k2_apparent_rad_s_g2,
            u: se[4],
        },
        k3: Estimate {
            value: unc.k3_rad_s_g3,
            u: se[5],
        },
    }
}

/// The coefficients in the conventional units, as ratios to k1 (µg, µg/g², µg/g³) with the
/// GUM covariance of the outputs (k0, k1, k2, k3 are outputs 0–3).
fn conventional(
    e: &Evaluated,
    setting: &Setting<'_>,
    coefficients: &PigaCoefficients<Coefficient>,
) -> Conventional {
    let m = output::NAMES.len();
    let cov = |i: usize, j: usize| e.gum.covariance[i * m + j];
    let k1_value = e.cal.k1_used_rad_s_g;
    let ratio = |i: usize, value: f64| {
        let k1 = k1_value;
        let r = value / k1;
        let var =
            cov(i, i) / (k1 * k1) + (r / k1).powi(2) * cov(1, 1) - 2.0 * r / (k1 * k1) * cov(i, 1);
        Estimate {
            value: r * 1e6,
            u: var.max(0.0).sqrt() * 1e6,
        }
    };
    Conventional {
        g_m_s2: setting.nominal.g_m_s2,
        k0_ug: ratio(0, coefficients.k0.value),
        k2_ug_per_g2: ratio(2, coefficients.k2.value),
        k3_ug_per_g3: ratio(3, coefficients.k3.value),
    }
}

/// The correlation matrix of the fit's six coefficients.
fn correlation(fit: &identify::Fit) -> Vec<Vec<f64>> {
    (0..TERMS)
        .map(|i| {
            (0..TERMS)
                .map(|j| {
                    let d = (fit.covariance[(i, i)] * fit.covariance[(j, j)]).sqrt();
                    if d > 0.0 {
                        fit.covariance[(i, j)] / d
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect()
}

/// Each point with its residual, the σ the fit used, its label and where it came from.
fn residual_rows(points: &PigaPoints, e: &Evaluated) -> Vec<CalibrationRow> {
    let unc = &e.cal.uncompensated;
    (0..points.rates_deg_s.len())
        .map(|i| CalibrationRow {
            rate_deg_s: points.rates_deg_s[i],
            output_rad_s: points.outputs_rad_s[i],
            residual_rad_s: unc.residuals_rad_s[i],
            // The σ the fit used: the point's own, with τ when one was added.
            u_rad_s: e.weighting.sigma_used.as_ref().map(|s| s[i]),
            label: points.labels.as_ref().map(|l| l[i].clone()),
            line: match &points.origins[i] {
                Origin::Line(l) => Some(*l),
                Origin::File(_) => None,
            },
            file: match &points.origins[i] {
                Origin::Line(_) => None,
                Origin::File(f) => Some(f.display().to_string()),
            },
        })
        .collect()
}

/// The Monte Carlo results of k0…k3 with their §8 validation.
fn monte_carlo(e: &Evaluated, seed: u64) -> MonteCarlo {
    let mc_output = |name: &str| MonteCarloOutput::of(&e.mc, &e.validation, name);
    MonteCarlo {
        trials: e.mc.trials,
        seed,
        gum_agrees: ["k0", "k1", "k2", "k3"]
            .iter()
            .all(|n| e.validation.output(n).is_some_and(|v| v.agrees)),
        k0: mc_output("k0"),
        k1: mc_output("k1"),
        k2: mc_output("k2"),
        k3: mc_output("k3"),
    }
}

/// The calibration's warnings in words: its own about its fit (`CalibrationWarning`; its
/// lack of fit is a coded warning of the study, `data_warnings`), Type B inputs taken as
/// exact, an exact C_r, a heavy-tailed Type A input, the GUM disagreeing with Monte Carlo.
fn warnings(
    inputs: &CalibrationInputs,
    setting: &Setting<'_>,
    phase_name: &str,
    e: &Evaluated,
    monte_carlo: &MonteCarlo,
) -> Vec<String> {
    let mut warnings = Vec::new();
    let fit_words = |kind: fn(&CalibrationWarning) -> bool| {
        e.fit_warnings
            .iter()
            .filter(move |w| kind(w))
            .map(ToString::to_string)
    };
    warnings.extend(fit_words(|w| {
        matches!(w, CalibrationWarning::RatesBunched { .. })
    }));
    if !inputs.type_b_given {
        warnings.push(
            "the study has no `uncertainty` section: R, g, the rate scale, the lever heights and the probe \
             gain are taken as exact, so the budget holds only the Type A inputs"
                .to_owned(),
        );
    }
    if setting.c_r_sigma.is_none_or(|(_, dof)| dof == 0) {
        warnings.push(format!(
            "the C_r of phase `{phase_name}` has no standard uncertainty (an exact fit); it is taken as exact"
        ));
    }
    warnings.extend(fit_words(|w| matches!(w, CalibrationWarning::TauNotFound)));
    if e.mc.outputs.iter().any(|o| o.heavy_tailed) {
        warnings.push(format!(
            "a Type A input has ν ≤ 2 degrees of freedom (the eq. 18 fit: {}, points − 6; \
             C_r of phase `{phase_name}`: {}): its t distribution has no variance, so the \
             Monte Carlo mean and standard uncertainty do not settle and only its 95 % \
             interval is meaningful; the GUM U95 takes k from Student's t. More rates, or \
             repeats, give a smaller and steadier U95",
            e.weighting.noise_dof,
            setting
                .c_r_sigma
                .map_or_else(|| "exact".to_owned(), |(_, dof)| dof.to_string())
        ));
    }
    if !monte_carlo.gum_agrees {
        warnings.push(
            "the GUM result does not agree with the Monte Carlo one (JCGM 101 §8): the Monte Carlo \
             interval is the one to use"
                .to_owned(),
        );
    }
    warnings
}

/// C_r with its combined standard uncertainty through the inputs of the measurement model
/// that scale it (`C_r·gain·(lever/lever₀)/s²`): the fit's Type A u, the probe gain, the two
/// lever heights and the rate scale, to first order (JCGM 100 eq. 10 on relative terms).
fn c_r_combined(setting: &Setting<'_>) -> Estimate {
    let n = &setting.nominal;
    let tb = &setting.type_b.values;
    let c_r = n.c_r_m_s2;
    let type_a = setting.c_r_sigma.map_or(0.0, |(s, _)| s);
    let (h_p, h_a) = (n.pivot_to_probe_mm, n.probe_to_piga_mm);
    // ln(lever) = ln(h_p + h_a) − ln(h_p)
    let d_lever_d_hp = 1.0 / (h_p + h_a) - 1.0 / h_p;
    let d_lever_d_ha = 1.0 / (h_p + h_a);
    let relative2 = tb.probe_gain_u_relative.powi(2)
        + (2.0 * tb.rate_u_relative).powi(2)
        + (d_lever_d_hp * tb.pivot_to_probe_u_mm).powi(2)
        + (d_lever_d_ha * tb.probe_to_piga_u_mm).powi(2);
    Estimate {
        value: c_r,
        u: (type_a.powi(2) + c_r.powi(2) * relative2).sqrt(),
    }
}

/// One output's budget: the named inputs that apply, and the mean outputs' noise as one line.
fn budget(
    output: &uncertainty::GumOutput,
    unit: &str,
    quantities: &[uncertainty::InputQuantity],
    group_dof: uncertainty::Dof,
    k1: K1Choice,
    notes: &[(usize, String)],
) -> Vec<BudgetLine> {
    let mut lines = Vec::new();
    for (i, (c, q)) in output
        .contributions
        .iter()
        .zip(quantities)
        .enumerate()
        .take(input::FIRST_COEFFICIENT)
    {
        if i == input::K1_GIVEN && k1 == K1Choice::Fitted {
            continue;
        }
        lines.push(BudgetLine::input(
            q,
            input::UNITS[i],
            c,
            budget_note(notes, i),
        ));
    }
    // The fit's coefficients as one line.
    lines.push(BudgetLine::fit_group(
        output,
        unit,
        &output.contributions[input::FIRST_COEFFICIENT..],
        "the eq. 18 fit",
        group_dof,
    ));
    lines
}

/// The residuals by label, in order of first appearance, when the points carry two labels or
/// more: each label's mean residual (weighted by 1/σ² for a weighted fit) and its Type A
/// standard uncertainty from the scatter of that label's residuals about it, so that an
/// offset of one label is measured against the scatter within labels, whatever the σ given
/// or estimated (a label with one row gets the fit's scatter instead).
fn label_summaries(
    points: &PigaPoints,
    residuals_rad_s: &[f64],
    fit_residual_sd_rad_s: f64,
) -> Vec<LabelSummary> {
    let Some(labels) = &points.labels else {
        return Vec::new();
    };
    let mut order: Vec<&str> = Vec::new();
    for l in labels {
        if !order.contains(&l.as_str()) {
            order.push(l);
        }
    }
    if order.len() < 2 {
        return Vec::new();
    }
    order
        .into_iter()
        .map(|label| {
            let rows: Vec<usize> = (0..labels.len()).filter(|&i| labels[i] == label).collect();
            let w: Vec<f64> = rows
                .iter()
                .map(|&i| points.sigma_rad_s.as_ref().map_or(1.0, |s| s[i].powi(-2)))
                .collect();
            let total: f64 = w.iter().sum();
            let mean = rows
                .iter()
                .zip(&w)
                .map(|(&i, w)| w * residuals_rad_s[i])
                .sum::<f64>()
                / total;
            let n = rows.len() as f64;
            let u = if rows.len() >= 2 {
                // Weighted scatter about the mean: s² = Σw(r − m)²/Σw · n/(n − 1), over n.
                let ss = rows
                    .iter()
                    .zip(&w)
                    .map(|(&i, w)| w * (residuals_rad_s[i] - mean).powi(2))
                    .sum::<f64>()
                    / total;
                (ss * n / (n - 1.0) / n).sqrt()
            } else {
                fit_residual_sd_rad_s
            };
            LabelSummary {
                label: label.to_owned(),
                rows: rows.len(),
                mean_residual_rad_s: mean,
                u_rad_s: u,
            }
        })
        .collect()
}

/// The calibration's warnings about its data: a weighted fit whose residuals exceed the
/// points' σ (`calibration_lack_of_fit`), a label whose rows sit apart (`label_offset`),
/// and rates outside the range over which the compensating phase measured C_r
/// (`rate_outside_phase`).
pub(crate) fn data_warnings(
    c: &CalibrationResults,
    fit_warnings: &[CalibrationWarning],
    phase_rates_deg_s: &[f64],
) -> Vec<Warning> {
    let mut warnings: Vec<Warning> = fit_warnings
        .iter()
        .filter(|w| matches!(w, CalibrationWarning::LackOfFit { .. }))
        .map(Warning::calibration_lack_of_fit)
        .collect();
    for l in &c.labels {
        let z = l.mean_residual_rad_s / l.u_rad_s;
        // About 3σ for many rows, wider for few (Student t, 99.73 %).
        let limit = ::calibration::label_offset_limit(l.rows);
        // A label without scatter has no u to measure an offset against.
        if l.u_rad_s > 0.0 && z.abs() > limit {
            warnings.push(Warning::label_offset(
                l.rows,
                &l.label,
                z,
                l.mean_residual_rad_s,
            ));
        }
    }
    let (low, high) = phase_rates_deg_s
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &r| {
            (a.min(r), b.max(r))
        });
    // 0.1 % of slack: a measured rate next to a declared one is the same rate.
    let outside: Vec<f64> = c
        .residuals
        .iter()
        .map(|r| r.rate_deg_s)
        .filter(|&r| r < low * 0.999 || r > high * 1.001)
        .collect();
    if low.is_finite() && !outside.is_empty() {
        warnings.push(Warning::rate_outside_phase(
            &outside,
            low,
            high,
            &c.compensate_with,
        ));
    }
    warnings
}

/// The results' account of how much wider u(k0…k3) are than they need be.
fn u_inflation(i: &::calibration::CoefficientInflation) -> UncertaintyInflation {
    let coefficients = |a: [f64; 4]| PigaCoefficients {
        k0: a[0],
        k1: a[1],
        k2: a[2],
        k3: a[3],
    };
    UncertaintyInflation {
        versus_spread: coefficients(i.versus_spread),
        reference_from_deg_s: i.reference_rad_s.0.to_degrees(),
        reference_to_deg_s: i.reference_rad_s.1.to_degrees(),
        limit: ::calibration::INFLATION_LIMIT,
        nuisance: coefficients(i.nuisance),
    }
}
