//! The PIGA's calibration on measured data (eq. 17–19) and its measurement model.
//!
//! The mean PIGA outputs of the table are fitted by the eq. 18 design `[1, ω, ω², ω³, a², a³]`,
//! `a = R·ω²/g` (`identify::identify_compensated`), as measured and after removing the
//! pseudo-second-order term of a named phase's C_r.
//!
//! [`CalibrationModel`] is the same computation as a function of every input quantity —
//! R, g, a common rate scale, the lever heights, the probe gain, the phase's C_r, k1 when
//! given, and the six coefficients of the fit at the nominal R, g and rates — for the
//! uncertainty evaluation. The fit's coefficients are one Type A input group: their
//! covariance from the residuals, ν = n − 6 degrees of freedom (JCGM 100 G.4 treats the
//! group as one term; JCGM 101 draws it from a multivariate t). Scaling R, g or the rates
//! multiplies each column of the design by a number, `X' = X·D`, so the coefficients become
//! `D⁻¹·β` exactly; a test checks that the model at the nominal inputs equals
//! `identify_compensated`'s result.

use std::path::PathBuf;

use identify::CompensatedCalibration;

use ::calibration::{CalibrationModel, TERM_NAMES, TERMS, Weighting, input, output};

/// The validated calibration section.
#[derive(Debug, Clone)]
pub(crate) struct CalibrationInputs {
    pub(crate) data: PigaData,
    /// Index of the phase whose C_r compensates.
    pub(crate) phase: usize,
    pub(crate) k1: K1Choice,
    pub(crate) seed: u64,
    /// `None`: adaptive; `Some(n)`: exactly n trials.
    pub(crate) trials: Option<u64>,
}

/// The PIGA's data: a table, or raw output recordings to reduce.
#[derive(Debug, Clone)]
pub(crate) enum PigaData {
    Table(PigaTableRows),
    Recordings {
        /// Harmonics of the spindle angle removed per revolution.
        order: usize,
        files: Vec<LoadedPigaRecording>,
    },
}

/// A PIGA table's rows, checked (rates > 0, σ > 0).
#[derive(Debug, Clone)]
pub(crate) struct PigaTableRows {
    pub(crate) file: PathBuf,
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) outputs_rad_s: Vec<f64>,
    pub(crate) sigma_rad_s: Option<Vec<f64>>,
    pub(crate) labels: Option<Vec<String>>,
    /// The line of each row in the table file.
    pub(crate) lines: Vec<usize>,
}

/// A raw PIGA output recording and the rate the study declares for it.
#[derive(Debug, Clone)]
pub(crate) struct LoadedPigaRecording {
    pub(crate) rate_deg_s: f64,
    pub(crate) file: PathBuf,
    pub(crate) recording: recording::PigaRecording,
}

/// The calibration's points, whatever they came from: one per table row or recording.
#[derive(Debug, Clone)]
pub(crate) struct PigaPoints {
    /// The rate of each point, deg/s (a recording's measured rate when it has an encoder).
    pub(crate) rates_deg_s: Vec<f64>,
    pub(crate) outputs_rad_s: Vec<f64>,
    /// Each output's standard uncertainty, rad/s (a table's σ column, or a recording's
    /// standard error across revolutions); `None`: unweighted.
    pub(crate) sigma_rad_s: Option<Vec<f64>>,
    pub(crate) labels: Option<Vec<String>>,
    /// Where each point comes from.
    pub(crate) origins: Vec<Origin>,
    /// The table file, or `None` for recordings.
    pub(crate) table: Option<PathBuf>,
    /// Each recording's reduction (empty for a table).
    pub(crate) recordings: Vec<crate::results::PigaRecordingResult>,
}

/// Where a calibration point comes from.
#[derive(Debug, Clone)]
pub(crate) enum Origin {
    /// A table row's line.
    Line(usize),
    /// A recording file.
    File(PathBuf),
}

impl CalibrationInputs {
    /// The calibration's points: a table's rows as they are, or each raw recording reduced
    /// to its mean output over whole spindle revolutions (in parallel), with the
    /// recordings' diagnostics as warnings naming the field and the file.
    pub(crate) fn points(
        &self,
        source: &std::path::Path,
    ) -> Result<(PigaPoints, Vec<crate::results::Warning>), crate::error::PipelineError> {
        use rayon::prelude::*;
        let (order, files) = match &self.data {
            PigaData::Table(t) => {
                return Ok((
                    PigaPoints {
                        rates_deg_s: t.rates_deg_s.clone(),
                        outputs_rad_s: t.outputs_rad_s.clone(),
                        sigma_rad_s: t.sigma_rad_s.clone(),
                        labels: t.labels.clone(),
                        origins: t.lines.iter().map(|&l| Origin::Line(l)).collect(),
                        table: Some(t.file.clone()),
                        recordings: Vec::new(),
                    },
                    Vec::new(),
                ));
            }
            PigaData::Recordings { order, files } => (*order, files),
        };
        let reduced: Vec<_> = files
            .par_iter()
            .map(|f| {
                let _span = tracing::info_span!("reduce", file = %f.file.display()).entered();
                recording::reduce_piga_recording(
                    &f.recording,
                    units::deg_s_to_rad_s(f.rate_deg_s),
                    order,
                )
            })
            .collect();
        let mut errors = Vec::new();
        let mut warnings = Vec::new();
        let mut points = PigaPoints {
            rates_deg_s: Vec::with_capacity(files.len()),
            outputs_rad_s: Vec::with_capacity(files.len()),
            sigma_rad_s: Some(Vec::with_capacity(files.len())),
            labels: None,
            origins: Vec::with_capacity(files.len()),
            table: None,
            recordings: Vec::with_capacity(files.len()),
        };
        for (i, (f, result)) in files.iter().zip(reduced).enumerate() {
            let field = format!("calibration.recordings.files[{i}]");
            let r = match result {
                Ok(r) => r,
                Err(e) => {
                    errors.push(crate::error::PipelineError::Recording {
                        path: source.to_owned(),
                        field,
                        source: Box::new(e),
                    });
                    continue;
                }
            };
            let location = format!("{field} ({})", f.file.display());
            warnings.extend(r.diagnostics.iter().map(|d| crate::results::Warning {
                code: d.code().into(),
                message: d.to_string(),
                location: location.clone(),
            }));
            let rate_deg_s = r.rate_rad_s().to_degrees();
            points.rates_deg_s.push(rate_deg_s);
            points.outputs_rad_s.push(r.output_rad_s);
            if let Some(s) = points.sigma_rad_s.as_mut() {
                s.push(r.output_u_rad_s);
            }
            points.origins.push(Origin::File(f.file.clone()));
            points.recordings.push(crate::results::PigaRecordingResult {
                file: f.file.display().to_string(),
                declared_rate_deg_s: f.rate_deg_s,
                rate_deg_s,
                angle_source: r.angle_source.name().to_owned(),
                output_rad_s: r.output_rad_s,
                u_rad_s: r.output_u_rad_s,
                across_revolutions_u_rad_s: r.across_revolutions_u_rad_s,
                white_noise_u_rad_s: r.white_noise_u_rad_s,
                revolution_sd_rad_s: r.revolution_sd_rad_s,
                revolutions: r.revolutions,
                dropped_revolutions: r.dropped_revolutions,
            });
        }
        crate::error::PipelineError::from_list(errors)?;
        // A recording whose output has no scatter (noise-free data) cannot be weighted:
        // the fit is then unweighted.
        if points
            .sigma_rad_s
            .as_ref()
            .is_some_and(|s| s.iter().any(|v| !v.is_finite() || *v <= 0.0))
        {
            points.sigma_rad_s = None;
            warnings.push(crate::results::Warning {
                code: "calibration_unweighted".into(),
                message: "a recording's mean output has no scatter across revolutions \
                          (noise-free data?): the eq. 18 fit is unweighted"
                    .into(),
                location: "calibration.recordings".into(),
            });
        }
        Ok((points, warnings))
    }
}

/// Where k1 comes from, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum K1Choice {
    Fitted,
    Given { k1_rad_s_g: f64, u_rad_s_g: f64 },
}

/// Type B standard uncertainties, validated (all finite and ≥ 0).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct TypeB {
    pub(crate) radius_u_m: f64,
    pub(crate) g_u_m_s2: f64,
    pub(crate) g_source: String,
    pub(crate) rate_u_relative: f64,
    pub(crate) pivot_to_probe_u_mm: f64,
    pub(crate) probe_to_piga_u_mm: f64,
    pub(crate) probe_gain_u_relative: f64,
}

/// The nominal values the model is linearised around and scales from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Nominal {
    pub(crate) radius_m: f64,
    pub(crate) g_m_s2: f64,
    pub(crate) pivot_to_probe_mm: f64,
    pub(crate) probe_to_piga_mm: f64,
    pub(crate) c_r_m_s2: f64,
}

/// Everything the calibration computes, before it becomes results.
pub(crate) struct Evaluated {
    pub(crate) cal: CompensatedCalibration,
    /// The measurement model (its check against the fit is a unit test).
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) model: CalibrationModel,
    pub(crate) vif: [f64; 5],
    pub(crate) gum: uncertainty::GumResult,
    pub(crate) mc: uncertainty::McResult,
    pub(crate) validation: uncertainty::Validation,
    /// The inputs of the uncertainty evaluation.
    pub(crate) quantities: Vec<uncertainty::InputQuantity>,
    pub(crate) weighting: Weighting,
}

/// Where a calibration failed.
#[derive(Debug)]
pub(crate) enum CalibrationFailure {
    Identify(identify::IdentifyError),
    Uncertainty(uncertainty::UncertaintyError),
}

/// The nominal values and uncertainties the evaluation starts from.
pub(crate) struct Setting<'a> {
    pub(crate) nominal: Nominal,
    pub(crate) type_b: &'a TypeB,
    /// σ(C_r) and the degrees of freedom of the phase's fit (`None`: C_r exact).
    pub(crate) c_r_sigma: Option<(f64, usize)>,
}

/// The calibration's uncertainty evaluation, set up: the eq. 18 fit, the measurement model,
/// its input quantities (validated, with the fit's correlations) and the Monte Carlo options.
pub(crate) struct Setup {
    pub(crate) cal: CompensatedCalibration,
    pub(crate) model: CalibrationModel,
    pub(crate) vif: [f64; 5],
    pub(crate) quantities: Vec<uncertainty::InputQuantity>,
    pub(crate) set: uncertainty::Inputs,
    pub(crate) options: uncertainty::McOptions,
    pub(crate) weighting: Weighting,
}

/// Fits and builds the measurement model with its input quantities.
pub(crate) fn setup(
    inputs: &CalibrationInputs,
    points: &PigaPoints,
    setting: &Setting<'_>,
) -> Result<Setup, CalibrationFailure> {
    use uncertainty::McOptions;
    let n = setting.nominal;
    let rates_rad_s: Vec<f64> = points
        .rates_deg_s
        .iter()
        .map(|&r| units::deg_s_to_rad_s(r))
        .collect();
    let sigma_c_r = setting.c_r_sigma.map_or(0.0, |(s, _)| s);
    let geometry = identify::Geometry {
        radius_m: n.radius_m,
        g_m_s2: n.g_m_s2,
    };
    let k1_given = match inputs.k1 {
        K1Choice::Fitted => None,
        K1Choice::Given { k1_rad_s_g, .. } => Some(k1_rad_s_g),
    };
    let compensation = ::calibration::compensation(n.c_r_m_s2, sigma_c_r, k1_given);
    let ::calibration::Fitted {
        calibration: cal,
        weighting,
    } = ::calibration::fit(
        &rates_rad_s,
        &points.outputs_rad_s,
        points.sigma_rad_s.as_deref(),
        geometry,
        &compensation,
    )
    .map_err(CalibrationFailure::Identify)?;
    let nominal = ::calibration::Nominal {
        radius_m: n.radius_m,
        g_m_s2: n.g_m_s2,
        pivot_to_probe_mm: n.pivot_to_probe_mm,
        probe_to_piga_mm: n.probe_to_piga_mm,
    };
    let model = CalibrationModel::new(
        nominal,
        match inputs.k1 {
            K1Choice::Fitted => ::calibration::K1Mode::Fitted,
            K1Choice::Given { .. } => ::calibration::K1Mode::Given,
        },
    );
    let vif =
        ::calibration::variance_inflation(&cal, &rates_rad_s, weighting.sigma_used.as_deref());
    let tb = setting.type_b;
    let type_b = ::calibration::TypeB {
        radius_u_m: tb.radius_u_m,
        g_u_m_s2: tb.g_u_m_s2,
        rate_u_relative: tb.rate_u_relative,
        pivot_to_probe_u_mm: tb.pivot_to_probe_u_mm,
        probe_to_piga_u_mm: tb.probe_to_piga_u_mm,
        probe_gain_u_relative: tb.probe_gain_u_relative,
    };
    let k1 = match inputs.k1 {
        K1Choice::Fitted => ::calibration::K1Input::Fitted,
        K1Choice::Given {
            k1_rad_s_g,
            u_rad_s_g,
        } => ::calibration::K1Input::Given {
            k1_rad_s_g,
            u_rad_s_g,
        },
    };
    let c_r = ::calibration::CrInput {
        c_r_m_s2: n.c_r_m_s2,
        sigma: setting.c_r_sigma,
    };
    let (quantities, set) = ::calibration::measurement_inputs(
        &nominal,
        &type_b,
        c_r,
        k1,
        &cal.uncompensated.fit,
        weighting.group_dof,
    )
    .map_err(CalibrationFailure::Uncertainty)?;
    let options = McOptions {
        seed: inputs.seed,
        trials: match inputs.trials {
            None => McOptions::default().trials,
            Some(n) => uncertainty::Trials::Fixed(n),
        },
        ..McOptions::default()
    };
    Ok(Setup {
        cal,
        model,
        vif,
        quantities,
        set,
        options,
        weighting,
    })
}

/// Fits, builds the measurement model and evaluates its uncertainty (GUM and Monte Carlo).
pub(crate) fn evaluate(
    inputs: &CalibrationInputs,
    points: &PigaPoints,
    setting: &Setting<'_>,
) -> Result<Evaluated, CalibrationFailure> {
    use uncertainty::{GumOptions, gum, monte_carlo, validate};
    let Setup {
        cal,
        model,
        vif,
        quantities,
        set,
        options,
        weighting,
    } = setup(inputs, points, setting)?;
    let gum_result =
        gum(&model, &set, &GumOptions::default()).map_err(CalibrationFailure::Uncertainty)?;
    let mc = monte_carlo(&model, &set, &options).map_err(CalibrationFailure::Uncertainty)?;
    let validation = validate(&gum_result, &mc, 2).map_err(CalibrationFailure::Uncertainty)?;
    Ok(Evaluated {
        cal,
        model,
        vif,
        gum: gum_result,
        mc,
        validation,
        quantities,
        weighting,
    })
}

/// The results of an evaluated calibration.
pub(crate) fn results(
    inputs: &CalibrationInputs,
    points: &PigaPoints,
    setting: &Setting<'_>,
    phase_name: &str,
    type_b_given: bool,
    e: &Evaluated,
) -> crate::results::CalibrationResults {
    use crate::results::{
        CalibrationResults, CalibrationRow, Coefficient, Conventional, Estimate, MonteCarlo,
        MonteCarloOutput, Nuisance, PigaCoefficients,
    };
    let unc = &e.cal.uncompensated;
    let fit = &unc.fit;
    let out = |name: &str| {
        e.gum
            .output(name)
            .expect("the model names its outputs")
            .clone()
    };
    let coefficient = |name: &str, value: f64| {
        let o = out(name);
        Coefficient {
            value,
            u: o.standard_uncertainty,
            u95: o.expanded_uncertainty,
            k: o.coverage_factor,
            dof: dof_value(o.dof),
        }
    };
    let k1_value = e.cal.k1_used_rad_s_g;
    let coefficients = PigaCoefficients {
        k0: coefficient("k0", out("k0").estimate),
        k1: coefficient("k1", k1_value),
        k2: coefficient("k2", out("k2").estimate),
        k3: coefficient("k3", out("k3").estimate),
    };
    let se = &fit.std_errors;
    let uncompensated = PigaCoefficients {
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
    };
    // Ratios to k1 with the GUM covariance of the outputs (k0, k1, k2, k3 are outputs 0–3).
    let m = output::NAMES.len();
    let cov = |i: usize, j: usize| e.gum.covariance[i * m + j];
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
    let conventional = Conventional {
        g_m_s2: setting.nominal.g_m_s2,
        k0_ug: ratio(0, coefficients.k0.value),
        k2_ug_per_g2: ratio(2, coefficients.k2.value),
        k3_ug_per_g3: ratio(3, coefficients.k3.value),
    };
    let correlation = (0..TERMS)
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
        .collect();
    let residuals = (0..points.rates_deg_s.len())
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
        .collect();
    let residual_sd_rad_s = if unc.birge_ratio.is_some() {
        let ss: f64 = unc.residuals_rad_s.iter().map(|r| r * r).sum();
        (ss / fit.dof as f64).sqrt()
    } else {
        fit.residual_sd
    };
    let labels = label_summaries(points, &unc.residuals_rad_s, residual_sd_rad_s);
    let budget_of =
        |name: &str| budget(&out(name), &e.quantities, e.weighting.group_dof, inputs.k1);
    let budget = PigaCoefficients {
        k0: budget_of("k0"),
        k1: budget_of("k1"),
        k2: budget_of("k2"),
        k3: budget_of("k3"),
    };
    let mc_output = |name: &str| {
        let o = e.mc.output(name).expect("the model names its outputs");
        let v = e.validation.output(name).expect("validated per output");
        MonteCarloOutput {
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
    };
    let monte_carlo = MonteCarlo {
        trials: e.mc.trials,
        seed: inputs.seed,
        gum_agrees: ["k0", "k1", "k2", "k3"]
            .iter()
            .all(|n| e.validation.output(n).is_some_and(|v| v.agrees)),
        k0: mc_output("k0"),
        k1: mc_output("k1"),
        k2: mc_output("k2"),
        k3: mc_output("k3"),
    };
    let mut warnings = Vec::new();
    let worst =
        e.vif.iter().enumerate().fold(
            (0, 0.0_f64),
            |acc, (j, &v)| if v > acc.1 { (j + 1, v) } else { acc },
        );
    if worst.1 > ::calibration::VIF_LIMIT {
        warnings.push(format!(
            "terms hard to separate: the {} term's variance inflation factor is {:.3e} (above {:e}); \
             its coefficient is strongly correlated with the others' — more, and more widely spread, rates separate them",
            TERM_NAMES[worst.0], worst.1, ::calibration::VIF_LIMIT
        ));
    }
    if !type_b_given {
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
    if e.weighting.tau_not_found {
        warnings.push(
            "the points scatter more than their σ say (Birge ratio above 1), and no variation \
             τ common to every point brings χ²/ν to 1: the fit keeps the points' σ as weights \
             and its covariance is scaled by the Birge ratio"
                .to_owned(),
        );
    }
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
        uncompensated,
        delta_k2: Estimate {
            value: e.cal.delta_k2.delta_k2_rad_s_g2,
            u: out("delta_k2").standard_uncertainty,
        },
        c_r_m_s2: Estimate {
            value: setting.nominal.c_r_m_s2,
            u: setting.c_r_sigma.map_or(0.0, |(s, _)| s),
        },
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
        residuals,
        labels,
        correlation,
        terms: TERM_NAMES.iter().map(|t| (*t).to_owned()).collect(),
        variance_inflation: e.vif.to_vec(),
        condition_number: fit.condition_number,
        budget,
        monte_carlo,
        warnings,
    }
}

fn dof_value(dof: uncertainty::Dof) -> crate::results::DegreesOfFreedom {
    use crate::results::{DegreesOfFreedom, InfiniteDof};
    match dof {
        uncertainty::Dof::Finite(nu) => DegreesOfFreedom::Finite(nu),
        uncertainty::Dof::Infinite => DegreesOfFreedom::Infinite(InfiniteDof::Infinite),
    }
}

/// One output's budget: the named inputs that apply, and the mean outputs' noise as one line.
fn budget(
    output: &uncertainty::GumOutput,
    quantities: &[uncertainty::InputQuantity],
    group_dof: uncertainty::Dof,
    k1: K1Choice,
) -> Vec<crate::results::BudgetLine> {
    use crate::results::BudgetLine;
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
        lines.push(BudgetLine {
            quantity: q.name.clone(),
            evaluation: match q.kind {
                uncertainty::Evaluation::TypeA => "A".to_owned(),
                uncertainty::Evaluation::TypeB => "B".to_owned(),
            },
            value: Some(q.value),
            u: q.standard_uncertainty,
            sensitivity: c.sensitivity,
            contribution: c.uncertainty,
            percent: c.variance_percent,
            dof: dof_value(q.dof),
        });
    }
    // The fit's coefficients as one line: their correlated contribution (the shares of the
    // group, which may be negative one by one, sum to the group's share).
    let group = &output.contributions[input::FIRST_COEFFICIENT..];
    let share: f64 = group.iter().map(|c| c.variance_percent).sum();
    let contribution = (share.max(0.0) / 100.0).sqrt() * output.standard_uncertainty;
    lines.push(BudgetLine {
        quantity: "PIGA mean outputs: the eq. 18 fit (noise, from its residuals)".to_owned(),
        evaluation: "A".to_owned(),
        value: None,
        u: contribution,
        sensitivity: 1.0,
        contribution,
        percent: share,
        dof: dof_value(group_dof),
    });
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
) -> Vec<crate::results::LabelSummary> {
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
            crate::results::LabelSummary {
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
    c: &crate::results::CalibrationResults,
    phase_rates_deg_s: &[f64],
) -> Vec<crate::results::Warning> {
    use crate::results::Warning;
    let mut warnings = Vec::new();
    if let Some(b) = c.birge_ratio
        && c.dof > 0
        && b > ::calibration::lack_of_fit_limit(c.dof)
    {
        warnings.push(Warning {
            code: "calibration_lack_of_fit".into(),
            message: format!(
                "the eq. 18 residuals are {b:.1}× the points' standard uncertainties \
                 (√(χ²/ν), {} degrees of freedom): the points scatter more than their σ say — \
                 run-to-run variation the within-run σ do not hold, an unmodelled term, or a \
                 rate error. The coefficients' σ are enlarged by this ratio",
                c.dof
            ),
            location: "calibration".into(),
        });
    }
    for l in &c.labels {
        let z = l.mean_residual_rad_s / l.u_rad_s;
        // About 3σ for many rows, wider for few (Student t, 99.73 %).
        let limit = ::calibration::label_offset_limit(l.rows);
        // A label without scatter has no u to measure an offset against.
        if l.u_rad_s > 0.0 && z.abs() > limit {
            warnings.push(Warning {
                code: "label_offset".into(),
                message: format!(
                    "the {} rows labelled `{}` sit {:+.1} standard uncertainties from the fit \
                     on average (mean residual {:+.3e} rad/s, against the scatter within the \
                     label): that repeat or orientation differs from the others (a bias, a \
                     set-up change) and one eq. 18 model does not describe them all",
                    l.rows, l.label, z, l.mean_residual_rad_s
                ),
                location: "calibration.table".into(),
            });
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
        warnings.push(Warning {
            code: "rate_outside_phase".into(),
            message: format!(
                "{} calibration rate(s) ({}) lie outside {low}–{high} deg/s, the rates at which \
                 phase `{}` measured C_r: there the compensation extrapolates C_r·ω², which \
                 no probe measurement checks",
                outside.len(),
                outside
                    .iter()
                    .map(|r| format!("{r}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                c.compensate_with
            ),
            location: "calibration".into(),
        });
    }
    warnings
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Outputs of eq. 18 with given coefficients at `n` rates, plus a small deterministic
    /// wiggle so that the fit has residuals.
    fn table(n: usize, k: [f64; 6], nominal: &Nominal) -> (CalibrationInputs, PigaPoints) {
        let rates_deg_s: Vec<f64> = (1..=n).map(|i| 200.0 * i as f64 / n as f64).collect();
        let outputs_rad_s = rates_deg_s
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                let w = units::deg_s_to_rad_s(r);
                let a = nominal.radius_m * w * w / nominal.g_m_s2;
                let wiggle = 1e-9 * ((i * 7919) % 13) as f64 / 13.0;
                k[0] + k[1] * w
                    + k[2] * w * w
                    + k[3] * w.powi(3)
                    + k[4] * a * a
                    + k[5] * a.powi(3)
                    + wiggle
            })
            .collect();
        let rows = PigaTableRows {
            file: PathBuf::from("t.csv"),
            lines: (2..n + 2).collect(),
            rates_deg_s,
            outputs_rad_s,
            sigma_rad_s: None,
            labels: None,
        };
        let inputs = CalibrationInputs {
            data: PigaData::Table(rows),
            phase: 0,
            k1: K1Choice::Fitted,
            seed: 3,
            trials: Some(2000),
        };
        let (points, warnings) = inputs.points(Path::new("study.ron")).unwrap();
        assert!(warnings.is_empty());
        (inputs, points)
    }

    #[test]
    fn the_model_at_the_estimates_is_the_certified_fit() {
        let nominal = Nominal {
            radius_m: 2.5,
            g_m_s2: 9.8,
            pivot_to_probe_mm: 700.0,
            probe_to_piga_mm: 510.0,
            c_r_m_s2: 1.6e-6,
        };
        for k1 in [
            K1Choice::Fitted,
            K1Choice::Given {
                k1_rad_s_g: 0.5601,
                u_rad_s_g: 1e-5,
            },
        ] {
            let (inputs, points) = table(
                12,
                [1e-5, 2e-6, 0.56 * 2.5 / 9.8, -3e-9, 5e-7, 2e-8],
                &nominal,
            );
            let inputs = CalibrationInputs { k1, ..inputs };
            let tb = TypeB::default();
            let setting = Setting {
                nominal,
                type_b: &tb,
                c_r_sigma: Some((4e-10, 10)),
            };
            let e = evaluate(&inputs, &points, &setting).unwrap();
            let x: Vec<f64> = e.quantities.iter().map(|q| q.value).collect();
            let mut y = [0.0; 6];
            e.model.evaluate(&x, &mut y);
            let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
            // At the estimates the model is the uncompensated fit with Δk2 removed from the a²
            // coefficient: the same numbers.
            let unc = &e.cal.uncompensated;
            assert_eq!(y[0], unc.bias_rad_s);
            assert_eq!(y[3], unc.k3_rad_s_g3);
            assert_eq!(y[4], unc.k2_apparent_rad_s_g2);
            assert!(rel(y[1], e.cal.k1_used_rad_s_g) < 1e-14, "k1");
            assert!(rel(y[5], e.cal.delta_k2.delta_k2_rad_s_g2) < 1e-14, "Δk2");
            // identify's refit of the compensated outputs agrees far below the uncertainty.
            let se = &unc.fit.std_errors;
            assert!(
                (y[0] - e.cal.compensated.bias_rad_s).abs() < 1e-4 * se[0],
                "k0"
            );
            assert!((y[2] - e.cal.k2_rad_s_g2).abs() < 1e-4 * se[4], "k2");
            assert!(
                (y[3] - e.cal.compensated.k3_rad_s_g3).abs() < 1e-4 * se[5],
                "k3"
            );
            // Scaling every rate by s is the same as fitting the scaled rates.
            let s = 1.001;
            let mut scaled = x.clone();
            scaled[2] = s;
            e.model.evaluate(&scaled, &mut y);
            let rates: Vec<f64> = points
                .rates_deg_s
                .iter()
                .map(|r| units::deg_s_to_rad_s(r * s))
                .collect();
            let geometry = identify::Geometry {
                radius_m: 2.5,
                g_m_s2: 9.8,
            };
            let direct =
                identify::identify_calibration(&rates, &points.outputs_rad_s, geometry).unwrap();
            let se = &direct.fit.std_errors;
            assert!((y[4] - direct.k2_apparent_rad_s_g2).abs() < 1e-4 * se[4]);
            assert!((y[0] - direct.bias_rad_s).abs() < 1e-4 * se[0]);
            assert!(
                (y[4] - unc.k2_apparent_rad_s_g2).abs() > 1e-2 * se[4],
                "the scale matters"
            );
        }
    }
}
