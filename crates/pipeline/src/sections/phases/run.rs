//! A phase's run: per-point geometry (eq. 21–22), the radius-error fit (eq. 16) and Δk2
//! (eq. 19), on values only.

use harmonics::FirstHarmonic;
use identify::RadiusModel;
use units::{deg_s_to_rad_s, m_to_um, um_to_m};

use super::analysis::{self, Progress};
use super::validate::{Phase, PhaseData};
use crate::error::{PipelineError, Result, UnsupportedReason};
use crate::inputs::Core;
use crate::results::{
    FitWeighting, ModelFit, PhaseResults, PointResult, ProbeTrace, RadiusModel as ModelName,
    Warning,
};

/// What a phase measured at each rate, carried to the PIGA plane (eq. 21–22): its points,
/// the probe traces of its recordings and their warnings. It depends on the probe's lever
/// and the data only, so a several-unit study measures each phase once and fits it for each
/// unit ([`fit_phase`]).
#[derive(Debug, Clone)]
pub(crate) struct Measured {
    points: Vec<PointResult>,
    traces: Vec<ProbeTrace>,
    warnings: Vec<Warning>,
}

/// Runs one phase: its points, the study's model fitted to them and the other model beside
/// it where the points allow, with the phase's warnings.
pub(crate) fn run_phase(
    inputs: &Core,
    model: RadiusModel,
    phase: &Phase,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<(PhaseResults, Vec<Warning>)> {
    let measured = measure_phase(inputs, phase, progress)?;
    fit_phase(inputs, model, phase, &measured)
}

/// A phase's points at the PIGA plane ([`Measured`]).
pub(crate) fn measure_phase(
    inputs: &Core,
    phase: &Phase,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<Measured> {
    let _span = tracing::info_span!("phase", name = %phase.name).entered();
    let (points, traces, warnings) = phase_points(inputs, phase, progress)?;
    tracing::info!(points = points.len(), "per-point geometry done");
    Ok(Measured {
        points,
        traces,
        warnings,
    })
}

/// A measured phase fitted by the radius-error model with the Δk2 of `inputs`' k1 and
/// geometry (eq. 16, 19), with the phase's warnings.
pub(crate) fn fit_phase(
    inputs: &Core,
    model: RadiusModel,
    phase: &Phase,
    measured: &Measured,
) -> Result<(PhaseResults, Vec<Warning>)> {
    let points = measured.points.clone();
    let traces = measured.traces.clone();
    let mut warnings = measured.warnings.clone();
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
    let fit = fit_model(inputs, &points, model, phase)?;
    warnings.extend(lack_of_fit(&points, &fit, &phase.key));
    let other = match model {
        RadiusModel::TwoTerm => RadiusModel::ThreeTerm,
        RadiusModel::ThreeTerm => RadiusModel::TwoTerm,
    };
    // The alternative is shown only where it has a residual degree of freedom.
    let alternative = if points.len() > other.unknowns() {
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
    (ratio > ::calibration::lack_of_fit_limit(fit.dof))
        .then(|| Warning::lack_of_fit(ratio, fit.dof, section))
}

/// `a + C_r·ω²` through two points: `C_r = Δr / (ω₂² − ω₁²)`, exact, with no standard error.
fn exact_two_point(inputs: &Core, points: &[PointResult], section: &str) -> Result<ModelFit> {
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
        model: ModelName::TwoTerm,
        c_r_m_s2,
        c_r_sigma_m_s2: None,
        offset_um: p1.radius_error_um - m_to_um(c_r_m_s2 * w1 * w1),
        linear_um_s: None,
        residuals_um: vec![0.0; 2],
        residual_sd_um: None,
        weighting: FitWeighting::Unweighted,
        reduced_chi: None,
        dof: 0,
        condition_number: None,
        delta_k2_rad_s_g2: k2.delta_k2_rad_s_g2,
        delta_k2_sigma_rad_s_g2: None,
    })
}

/// Per-point geometry: each input form gives the radius error at the PIGA plane.
fn phase_points(
    inputs: &Core,
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
            let analyzed = analysis::analyze(set, section, path, progress)?;
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
    inputs: &Core,
    points: &[PointResult],
    model: RadiusModel,
    phase: &Phase,
) -> Result<ModelFit> {
    let section = phase.key.as_str();
    let identify_error = |source| PipelineError::Identify {
        path: inputs.source.clone(),
        field: format!("{section}.points"),
        source,
    };
    let rates: Vec<f64> = points.iter().map(|p| p.rate_rad_s).collect();
    let radius_errors_m: Vec<f64> = points.iter().map(|p| um_to_m(p.radius_error_um)).collect();
    let fit = match phase.weighting {
        FitWeighting::Unweighted => identify::fit_radius_error(&rates, &radius_errors_m, model),
        FitWeighting::InverseVariance => {
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
            identify::fit_radius_error_weighted(&rates, &radius_errors_m, &sigma_m, model)
        }
    }
    .map_err(identify_error)?;
    let ssr_um2: f64 = fit.residuals_m.iter().map(|r| m_to_um(*r).powi(2)).sum();
    let k2 = identify::pseudo_second_order(inputs.k1_rad_s_g, fit.c_r(), inputs.geometry())
        .map_err(identify_error)?;
    Ok(ModelFit {
        model: model_name(model),
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

/// The output's name of a solver's model.
const fn model_name(model: RadiusModel) -> ModelName {
    match model {
        RadiusModel::TwoTerm => ModelName::TwoTerm,
        RadiusModel::ThreeTerm => ModelName::ThreeTerm,
    }
}
