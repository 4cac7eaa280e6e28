//! Orchestration: per-point geometry (eq. 21–22), the radius-error fit and Δk2 (eq. 19).
//!
//! Everything here computes on [`Inputs`]; nothing touches the file system.

use std::path::Path;

use harmonics::FirstHarmonic;
use identify::RadiusModel;
use units::{deg_s_to_rad_s, m_to_um, um_to_m};

use ::calibration::CalibrationModel;

use crate::calibration::{self, CalibrationFailure, Nominal, Setting};
use crate::config::{RadiusModelName, Weighting};
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::{Inputs, Phase, PhaseData, radius_model};
use crate::mechanism::{self, MeasuredDrift, PhaseFailure};
use crate::probe_analysis::{self, Progress};
use crate::results::{
    MechanismPhase, MechanismResults, ModelFit, PhaseResults, PigaResult, PointResult, ProbeTrace,
    StudyInputs, StudyResults, Warning,
};

/// Runs a study: both phases, each with its per-point geometry, its radius-error fit and the
/// pseudo-second-order error `Δk2` it implies, and the mechanism section when configured.
///
/// The computation reads only the inputs; published values are never consulted.
pub fn run(inputs: &Inputs) -> Result<StudyResults> {
    run_with_progress(inputs, &|_| {})
}

/// [`run`], reporting progress through `progress` (called from several threads while
/// recordings are analyzed in parallel).
pub fn run_with_progress(
    inputs: &Inputs,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<StudyResults> {
    let _study = tracing::info_span!("study", name = %inputs.name).entered();
    let total = inputs
        .phases
        .iter()
        .map(|phase| match &phase.data {
            PhaseData::Recordings(set) => set.files.len(),
            _ => 0,
        })
        .sum();
    if total > 0 {
        progress(Progress::Recordings { total });
    }
    let mut warnings = Vec::new();
    let mut phases = Vec::with_capacity(inputs.phases.len());
    // Phases holding a second probe's data are fitted like the others, through the first
    // probe's lever and direction: their C_r is not the PIGA plane's, and they say so.
    let second_probe_phases: Vec<usize> = inputs
        .balance
        .as_ref()
        .and_then(|b| b.second.as_ref())
        .map(|s| s.phase_of.values().copied().collect())
        .unwrap_or_default();
    for (p, phase) in inputs.phases.iter().enumerate() {
        let (results, more) = run_phase(inputs, phase, progress)?;
        if second_probe_phases.contains(&p) {
            warnings.push(Warning {
                code: "second_probe_phase".into(),
                message: format!(
                    "phase `{}` holds the second probe's data: its radius-error fit here reads \
                     it with the first probe's lever and direction, so its C_r and Δk2 are not \
                     the PIGA plane's; `balance.two_plane` gives C_r at the PIGA plane from both \
                     probes",
                    phase.name
                ),
                location: phase.key.clone(),
            });
        }
        phases.push(results);
        warnings.extend(more);
    }
    let mechanism = inputs
        .mechanism
        .as_ref()
        .map(|m| {
            let _span = tracing::info_span!("mechanism").entered();
            let geometry = inputs.geometry();
            let phase = |(n, &p): (usize, &usize)| {
                let results: &PhaseResults = &phases[p];
                let drift = MeasuredDrift {
                    c_r_m_s2: results.fit.c_r_m_s2,
                    c_r_sigma_m_s2: results.fit.c_r_sigma_m_s2,
                    offset_um: results.fit.offset_um,
                };
                // One noise stream per simulated phase: the seed, then seed + 1, ...
                mechanism::run_phase(geometry, m, drift, m.seed.wrapping_add(n as u64))
                    .map(|phase| MechanismPhase {
                        phase: results.name.clone(),
                        ..phase
                    })
                    .map_err(|e| locate(e, &inputs.source, &format!("mechanism.phases[{n}]")))
            };
            Ok::<_, PipelineError>(MechanismResults {
                rates_deg_s: m.rates_deg_s.clone(),
                piga: PigaResult {
                    k0_rad_s: m.piga.k0_rad_s,
                    k1_rad_s_g: m.piga.k1_rad_s_g,
                    k2_rad_s_g2: m.piga.k2_rad_s_g2,
                    k3_rad_s_g3: m.piga.k3_rad_s_g3,
                },
                latitude_deg: m.latitude_deg,
                output_noise_rad_s: m.output_noise_rad_s,
                phases: m
                    .phases
                    .iter()
                    .enumerate()
                    .map(phase)
                    .collect::<Result<Vec<_>>>()?,
            })
        })
        .transpose()?;
    let mut calibration_warnings: Vec<Warning> = Vec::new();
    let calibration = inputs
        .calibration
        .as_ref()
        .map(|c| {
            let _span = tracing::info_span!("calibration").entered();
            let phase = &phases[c.phase];
            let setting = setting(inputs, phase);
            let (points, more) = c.points(&inputs.source)?;
            calibration_warnings.extend(more);
            let evaluated = calibration::evaluate(c, &points, &setting)
                .map_err(|e| calibration_error(inputs, e))?;
            let results = calibration::results(
                c,
                &points,
                &setting,
                &phase.name,
                inputs.type_b_given,
                &evaluated,
            );
            let phase_rates: Vec<f64> = phase.points.iter().map(|p| p.rate_deg_s).collect();
            calibration_warnings.extend(calibration::data_warnings(&results, &phase_rates));
            Ok::<_, PipelineError>(results)
        })
        .transpose()?;
    let balance = inputs
        .balance
        .as_ref()
        .map(|b| {
            let _span = tracing::info_span!("balance").entered();
            let setting = crate::balancing::Setting {
                lever: inputs.lever,
                lever_ratio: inputs.lever_ratio,
                k1_rad_s_g: inputs.k1_rad_s_g,
                radius_m: inputs.radius_m,
                g_m_s2: inputs.g_m_s2,
            };
            crate::balancing::run(b, &phases, &setting).map_err(|(field, source)| {
                PipelineError::Balance {
                    path: inputs.source.clone(),
                    field,
                    source: Box::new(source),
                }
            })
        })
        .transpose()?;
    warnings.extend(calibration_warnings);
    // A correction known to no better than its own size (a near-singular influence
    // coefficient, trial runs that barely moved the spindle) is not a correction to mount.
    if let Some(b) = balance.as_ref() {
        let mut corrections: Vec<(String, &crate::results::CorrectionResult)> =
            vec![("balance.correction".to_owned(), &b.correction)];
        if let Some(t) = &b.two_plane {
            for (c, correction) in t.corrections.iter().enumerate() {
                for (k, plane) in correction.planes.iter().enumerate() {
                    corrections.push((
                        format!("balance.two_plane.corrections[{c}].planes[{k}]"),
                        &plane.correction,
                    ));
                }
            }
        }
        for (location, c) in corrections {
            if c.mass_u_kg >= c.mass_kg {
                warnings.push(Warning {
                    code: "correction_uncertain".into(),
                    message: format!(
                        "the correction's mass {:.4} kg has a standard uncertainty of {:.4} kg, \
                         as large as itself: the trial run(s) did not move the spindle \
                         clearly enough (near-parallel or small responses) — use a larger \
                         trial mass, or another trial azimuth or plane",
                        c.mass_kg, c.mass_u_kg
                    ),
                    location,
                });
            }
        }
    }
    // With two probes, the initial phase's C_r through the cone of eq. 22 beside the one
    // both probes give at the PIGA plane: the phase's number is the one a calibration or a
    // mechanism section would use.
    if let Some((b, t)) = balance
        .as_ref()
        .and_then(|b| b.two_plane.as_ref().map(|t| (b, t)))
        && let Some(phase) = phases.iter().find(|p| p.name == b.initial)
    {
        let cone = phase.fit.c_r_m_s2;
        if (cone - t.c_r_m_s2).abs() > 3.0 * t.c_r_u_m_s2 {
            warnings.push(Warning {
                code: "cone_c_r".into(),
                message: format!(
                    "phase `{}`'s C_r read by one probe through the cone of eq. 22 is {cone:.4e} \
                     m·s²; both probes give {:.4e} ± {:.1e} m·s² at the PIGA plane: the spindle \
                     does not move as a cone about the assumed pivot, and a calibration or \
                     mechanism section that uses the phase's C_r is off by the difference",
                    b.initial, t.c_r_m_s2, t.c_r_u_m_s2
                ),
                location: "balance.two_plane".into(),
            });
        }
    }
    let counterweight = inputs
        .counterweight
        .as_ref()
        .map(|c| {
            crate::balancing::counterweight(
                c,
                &phases[c.phase].name,
                inputs.k1_rad_s_g,
                inputs.radius_m,
                inputs.g_m_s2,
            )
            .map_err(|source| PipelineError::Balance {
                path: inputs.source.clone(),
                field: "counterweight".to_owned(),
                source: Box::new(source),
            })
        })
        .transpose()?;
    let results = StudyResults {
        study: inputs.name.clone(),
        inputs: StudyInputs {
            radius_m: inputs.radius_m,
            g_m_s2: inputs.g_m_s2,
            k1_rad_s_g: inputs.k1_rad_s_g,
            lever_ratio: inputs.lever_ratio,
        },
        phases,
        mechanism,
        calibration,
        warnings,
        balance,
        counterweight,
    };
    // The libraries refuse their own non-finite results; this catches what is combined here.
    edge_io::check_finite(&results).map_err(|e| PipelineError::NonFiniteResult {
        path: inputs.source.clone(),
        field: e.path,
        value: e.value,
    })?;
    Ok(results)
}

/// A mechanism failure as a study error naming the configuration and the section.
fn locate(failure: PhaseFailure, path: &Path, field: &str) -> PipelineError {
    match failure {
        PhaseFailure::Model(source) => PipelineError::AccelModel {
            path: path.to_owned(),
            field: field.to_owned(),
            source,
        },
        PhaseFailure::Identify(source) => PipelineError::Identify {
            path: path.to_owned(),
            field: field.to_owned(),
            source,
        },
    }
}

/// The calibration's measurement model with its validated input quantities and the Monte
/// Carlo options, set up as [`run`] sets them up before its GUM and Monte Carlo evaluations
/// (the compensating phase's C_r fit, the calibration's points, then the eq. 18 fit), for a
/// benchmark or an outside check of the uncertainty evaluation. `None` when the study has no
/// calibration section.
///
/// Errors: those of [`run`] for the compensating phase and the calibration.
pub fn calibration_measurement(inputs: &Inputs) -> Result<Option<CalibrationMeasurement>> {
    let Some(c) = inputs.calibration.as_ref() else {
        return Ok(None);
    };
    let (phase, _) = run_phase(inputs, &inputs.phases[c.phase], &|_| {})?;
    let setting = setting(inputs, &phase);
    let (points, _) = c.points(&inputs.source)?;
    let setup =
        calibration::setup(c, &points, &setting).map_err(|e| calibration_error(inputs, e))?;
    Ok(Some(CalibrationMeasurement {
        model: setup.model,
        inputs: setup.set,
        options: setup.options,
    }))
}

/// The calibration's uncertainty evaluation as [`calibration_measurement`] sets it up.
#[derive(Debug, Clone)]
pub struct CalibrationMeasurement {
    /// The measurement model (14 inputs, 6 outputs; see [`CalibrationModel`]).
    pub model: CalibrationModel,
    /// Its input quantities, validated, with the eq. 18 fit's coefficients as one correlated
    /// Type A group.
    pub inputs: uncertainty::Inputs,
    /// The Monte Carlo options the study asks for (its seed and trials).
    pub options: uncertainty::McOptions,
}

/// The nominal values and uncertainties of the calibration, with the compensating `phase`.
fn setting<'a>(inputs: &'a Inputs, phase: &PhaseResults) -> Setting<'a> {
    Setting {
        nominal: Nominal {
            radius_m: inputs.radius_m,
            g_m_s2: inputs.g_m_s2,
            pivot_to_probe_mm: inputs.lever.pivot_to_probe_mm,
            probe_to_piga_mm: inputs.lever.probe_to_piga_mm,
            c_r_m_s2: phase.fit.c_r_m_s2,
        },
        type_b: &inputs.type_b,
        c_r_sigma: phase.fit.c_r_sigma_m_s2.map(|s| (s, phase.fit.dof)),
    }
}

/// A calibration failure located in the study file.
fn calibration_error(inputs: &Inputs, e: CalibrationFailure) -> PipelineError {
    match e {
        CalibrationFailure::Identify(source) => PipelineError::Identify {
            path: inputs.source.clone(),
            field: "calibration".to_owned(),
            source,
        },
        CalibrationFailure::Uncertainty(source) => PipelineError::Uncertainty {
            path: inputs.source.clone(),
            field: "calibration".to_owned(),
            source: Box::new(source),
        },
    }
}

fn run_phase(
    inputs: &Inputs,
    phase: &Phase,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<(PhaseResults, Vec<Warning>)> {
    let _span = tracing::info_span!("phase", name = %phase.name).entered();
    let (points, traces, mut warnings) = phase_points(inputs, phase, progress)?;
    tracing::info!(points = points.len(), "per-point geometry done");
    if let PhaseData::RadiusChange { .. } = phase.data {
        let results = PhaseResults {
            name: phase.name.clone(),
            fit: exact_two_point(inputs, &points, &phase.key)?,
            points,
            alternative: None,
            traces,
        };
        return Ok((results, warnings));
    }
    let fit = fit_model(inputs, &points, inputs.radius_model, phase)?;
    warnings.extend(lack_of_fit(&points, &fit, &phase.key));
    let other = match inputs.radius_model {
        RadiusModelName::TwoTerm => RadiusModelName::ThreeTerm,
        RadiusModelName::ThreeTerm => RadiusModelName::TwoTerm,
    };
    // The alternative is shown only where it has a residual degree of freedom.
    let alternative = if points.len() > radius_model(other).unknowns() {
        Some(fit_model(inputs, &points, other, phase)?)
    } else {
        None
    };
    tracing::info!(
        c_r_m_s2 = fit.c_r_m_s2,
        delta_k2_rad_s_g2 = fit.delta_k2_rad_s_g2,
        "radius-error fit done"
    );
    let results = PhaseResults {
        name: phase.name.clone(),
        points,
        fit,
        alternative,
        traces,
    };
    Ok((results, warnings))
}

/// The warning `lack_of_fit` when the radius-error residuals are well above the σ of the
/// points (recordings only).
fn lack_of_fit(points: &[PointResult], fit: &ModelFit, section: &str) -> Option<Warning> {
    if fit.dof == 0 {
        return None;
    }
    let mut chi2 = 0.0;
    for (p, r) in points.iter().zip(&fit.residuals_um) {
        let s = p.radius_error_sigma_um.filter(|s| *s > 0.0)?;
        chi2 += (r / s).powi(2);
    }
    let ratio = (chi2 / fit.dof as f64).sqrt();
    (ratio > ::calibration::lack_of_fit_limit(fit.dof)).then(|| Warning {
        code: "lack_of_fit".into(),
        message: format!(
            "the radius-error residuals are {ratio:.1}× their white-noise σ (√(χ²/dof), {} \
             degrees of freedom): a + C_r·ω² does not describe the points within their \
             noise; look for drift (`drift: true`), a rate error or a pickup not synchronous \
             with the spindle (see the other warnings), or another `radius_model`. σ(C_r) \
             comes from the residuals and includes the scatter, not a bias",
            fit.dof
        ),
        location: format!("{section}.points"),
    })
}

/// `a + C_r·ω²` through two points: `C_r = Δr / (ω₂² − ω₁²)`, exact, with no standard error.
fn exact_two_point(inputs: &Inputs, points: &[PointResult], section: &str) -> Result<ModelFit> {
    let [p1, p2] = [&points[0], &points[1]];
    let (w1, w2) = (p1.rate_rad_s, p2.rate_rad_s);
    let c_r_m_s2 = um_to_m(p2.radius_error_um - p1.radius_error_um) / (w2 * w2 - w1 * w1);
    let exact_c_r = identify::CrEstimate {
        c_r_m_s2,
        c_r_sigma_m_s2: 0.0,
    };
    let k2 = identify::pseudo_second_order(inputs.k1_rad_s_g, exact_c_r, inputs.geometry())
        .map_err(|source| PipelineError::Identify {
            path: inputs.source.clone(),
            field: format!("{section}.points"),
            source,
        })?;
    Ok(ModelFit {
        model: RadiusModelName::TwoTerm,
        c_r_m_s2,
        c_r_sigma_m_s2: None,
        offset_um: p1.radius_error_um - m_to_um(c_r_m_s2 * w1 * w1),
        linear_um_s: None,
        residuals_um: vec![0.0; 2],
        residual_sd_um: None,
        weighting: Weighting::Unweighted,
        reduced_chi: None,
        dof: 0,
        condition_number: None,
        delta_k2_rad_s_g2: k2.delta_k2_rad_s_g2,
        delta_k2_sigma_rad_s_g2: None,
    })
}

/// Per-point geometry: each input form gives the radius error at the PIGA plane.
fn phase_points(
    inputs: &Inputs,
    phase: &Phase,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<(Vec<PointResult>, Vec<ProbeTrace>, Vec<Warning>)> {
    let section = phase.key.as_str();
    let path = inputs.source.as_path();
    let radius_point = |rate_deg_s: f64, radius_error_um: f64| PointResult {
        rate_deg_s,
        rate_rad_s: deg_s_to_rad_s(rate_deg_s),
        measured_rate_deg_s: None,
        angle_source: None,
        dropped_revolutions: None,
        dc1_um: None,
        ds1_um: None,
        amplitude_um: None,
        beta_deg: None,
        radius_error_um,
        dc1_sigma_um: None,
        ds1_sigma_um: None,
        radius_error_sigma_um: None,
        revolutions: None,
        residual_rms_um: None,
    };
    let harmonic_point =
        |i: usize, rate_deg_s: f64, dc1_um: f64, ds1_um: f64| -> Result<PointResult> {
            let drift = inputs
                .lever
                .project(FirstHarmonic {
                    c1: dc1_um,
                    s1: ds1_um,
                })
                .map_err(|source| PipelineError::Harmonics {
                    path: path.to_owned(),
                    field: format!("{section}.points[{i}]"),
                    source,
                })?;
            Ok(PointResult {
                dc1_um: Some(dc1_um),
                ds1_um: Some(ds1_um),
                amplitude_um: Some(drift.probe_amplitude),
                beta_deg: Some(drift.beta_rad.to_degrees()),
                ..radius_point(rate_deg_s, drift.radius_error)
            })
        };
    match &phase.data {
        PhaseData::FirstHarmonic(points) => Ok((
            points
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let point = harmonic_point(i, p.rate_deg_s, p.dc1_um, p.ds1_um)?;
                    // a stated σ of the first harmonic: the radius error's is σ·lever ratio
                    Ok(PointResult {
                        dc1_sigma_um: p.sigma_um,
                        ds1_sigma_um: p.sigma_um,
                        radius_error_sigma_um: p.sigma_um.map(|s| s * inputs.lever_ratio),
                        ..point
                    })
                })
                .collect::<Result<_>>()?,
            Vec::new(),
            Vec::new(),
        )),
        PhaseData::Recordings(set) => {
            let analyzed = probe_analysis::analyze(set, section, path, progress)?;
            let mut points = Vec::with_capacity(analyzed.len());
            let mut traces = Vec::with_capacity(analyzed.len());
            let mut warnings = Vec::new();
            for (i, (file, h)) in set.files.iter().zip(analyzed).enumerate() {
                let point = harmonic_point(i, file.rate_deg_s, h.dc1_um, h.ds1_um)?;
                warnings.extend(h.warnings);
                points.push(PointResult {
                    rate_rad_s: h.rate_rad_s,
                    measured_rate_deg_s: h.measured_rate_rad_s.map(f64::to_degrees),
                    angle_source: Some(h.angle_source),
                    dropped_revolutions: Some(h.dropped_revolutions),
                    dc1_sigma_um: h.dc1_sigma_um,
                    ds1_sigma_um: h.ds1_sigma_um,
                    radius_error_sigma_um: Some(h.dc1_noise_sigma_um * inputs.lever_ratio),
                    revolutions: Some(h.revolutions),
                    residual_rms_um: Some(h.residual_rms_um),
                    ..point
                });
                traces.push(h.trace);
            }
            Ok((points, traces, warnings))
        }
        PhaseData::RadiusError(points) => Ok((
            points
                .iter()
                .map(|p| radius_point(p.rate_deg_s, p.radius_error_um))
                .collect(),
            Vec::new(),
            Vec::new(),
        )),
        PhaseData::RadiusChange {
            from_rate_deg_s,
            to_rate_deg_s,
            change_um,
        } => Ok((
            vec![
                radius_point(*from_rate_deg_s, 0.0),
                radius_point(*to_rate_deg_s, *change_um),
            ],
            Vec::new(),
            Vec::new(),
        )),
    }
}

fn fit_model(
    inputs: &Inputs,
    points: &[PointResult],
    model: RadiusModelName,
    phase: &Phase,
) -> Result<ModelFit> {
    let section = phase.key.as_str();
    let identify_error = |source| PipelineError::Identify {
        path: inputs.source.clone(),
        field: format!("{section}.points"),
        source,
    };
    let solver_model: RadiusModel = radius_model(model);
    let rates: Vec<f64> = points.iter().map(|p| p.rate_rad_s).collect();
    let radius_errors_m: Vec<f64> = points.iter().map(|p| um_to_m(p.radius_error_um)).collect();
    let fit = match phase.weighting {
        Weighting::Unweighted => identify::fit_radius_error(&rates, &radius_errors_m, solver_model),
        Weighting::InverseVariance => {
            let mut sigma_m = Vec::with_capacity(points.len());
            for (i, p) in points.iter().enumerate() {
                match p.radius_error_sigma_um {
                    Some(s) if s > 0.0 => sigma_m.push(um_to_m(s)),
                    _ => {
                        return Err(PipelineError::Unsupported {
                            path: inputs.source.clone(),
                            field: format!("{section}.points.files[{i}]"),
                            reason: UnsupportedReason::NoStandardError,
                        });
                    }
                }
            }
            identify::fit_radius_error_weighted(&rates, &radius_errors_m, &sigma_m, solver_model)
        }
    }
    .map_err(identify_error)?;
    let ssr_um2: f64 = fit.residuals_m.iter().map(|r| m_to_um(*r).powi(2)).sum();
    let k2 = identify::pseudo_second_order(inputs.k1_rad_s_g, fit.c_r(), inputs.geometry())
        .map_err(identify_error)?;
    Ok(ModelFit {
        model,
        c_r_m_s2: fit.c_r_m_s2,
        c_r_sigma_m_s2: Some(fit.c_r_sigma_m_s2),
        offset_um: m_to_um(fit.offset_m),
        linear_um_s: fit.linear_m_s.map(m_to_um),
        residuals_um: fit.residuals_m.iter().map(|r| m_to_um(*r)).collect(),
        residual_sd_um: Some((ssr_um2 / fit.fit.dof as f64).sqrt()),
        weighting: phase.weighting,
        reduced_chi: fit.weighted.then_some(fit.fit.residual_sd),
        dof: fit.fit.dof,
        condition_number: Some(fit.fit.condition_number),
        delta_k2_rad_s_g2: k2.delta_k2_rad_s_g2,
        delta_k2_sigma_rad_s_g2: Some(k2.sigma_rad_s_g2),
    })
}
