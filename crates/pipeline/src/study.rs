//! Orchestration: per-point geometry (eq. 21–22), the radius-error fit and Δk2 (eq. 19).

use std::path::Path;

use harmonics::FirstHarmonic;
use identify::RadiusModel;

use crate::config::{LoadedStudy, PhaseConfig, Points, StudyConfig, Weighting};
use crate::error::{PipelineError, Result};
use crate::mechanism;
use crate::probe_analysis::{self, ProbeTrace, Progress};
use crate::results::{ModelFit, PhaseResults, PointResult, StudyInputs, StudyResults};
use units::{deg_s_to_rad_s, m_to_um, um_to_m};

/// Runs a loaded study: both phases, each with its per-point geometry, its radius-error fit
/// and the pseudo-second-order error `Δk2` it implies.
///
/// The computation reads only the configuration (and the recordings it names); published
/// values are never consulted.
pub fn run(study: &LoadedStudy) -> Result<StudyResults> {
    run_with_progress(study, &|_| {})
}

/// [`run`], reporting progress through `progress` (called from several threads while
/// recordings are analysed in parallel).
pub fn run_with_progress(
    study: &LoadedStudy,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<StudyResults> {
    let config = &study.config;
    let path = study.path.as_path();
    let lever_ratio = config
        .lever
        .lever_ratio()
        .map_err(|source| PipelineError::Harmonics {
            path: path.to_owned(),
            field: "lever".to_owned(),
            source,
        })?;
    let total = [&config.pre_balance, &config.post_balance]
        .iter()
        .map(|phase| match &phase.points {
            Points::Recordings(set) => set.files.len(),
            _ => 0,
        })
        .sum();
    if total > 0 {
        progress(Progress::Recordings { total });
    }
    let run = |phase, section| run_phase(config, phase, section, path, lever_ratio, progress);
    let pre_balance = run(&config.pre_balance, "pre_balance")?;
    let post_balance = run(&config.post_balance, "post_balance")?;
    let mechanism = config
        .mechanism
        .as_ref()
        .map(|m| mechanism::run(config, m, &pre_balance, &post_balance, path))
        .transpose()?;
    Ok(StudyResults {
        study: config.name.clone(),
        inputs: StudyInputs {
            radius_m: config.radius_m,
            g_m_s2: config.g_m_s2,
            k1_rad_s_g: config.k1_rad_s_g,
            lever_ratio,
        },
        pre_balance,
        post_balance,
        mechanism,
    })
}

fn run_phase(
    config: &StudyConfig,
    phase: &PhaseConfig,
    section: &str,
    path: &Path,
    lever_ratio: f64,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<PhaseResults> {
    let (points, traces) = phase_points(config, phase, section, path, lever_ratio, progress)?;
    if let Points::RadiusChange { .. } = phase.points {
        return Ok(PhaseResults {
            fit: exact_two_point(config, &points, section, path)?,
            points,
            alternative: None,
            traces,
        });
    }
    let fit = fit_model(
        config,
        &points,
        config.radius_model,
        phase.weighting,
        section,
        path,
    )?;
    let other = match config.radius_model {
        RadiusModel::TwoTerm => RadiusModel::ThreeTerm,
        RadiusModel::ThreeTerm => RadiusModel::TwoTerm,
    };
    // The alternative is shown only where it has a residual degree of freedom.
    let alternative = if points.len() > other.unknowns() {
        Some(fit_model(
            config,
            &points,
            other,
            phase.weighting,
            section,
            path,
        )?)
    } else {
        None
    };
    Ok(PhaseResults {
        points,
        fit,
        alternative,
        traces,
    })
}

/// `a + C_r·ω²` through two points: `C_r = Δr / (ω₂² − ω₁²)`, exact, with no standard error.
fn exact_two_point(
    config: &StudyConfig,
    points: &[PointResult],
    section: &str,
    path: &Path,
) -> Result<ModelFit> {
    let [p1, p2] = [&points[0], &points[1]];
    let (w1, w2) = (p1.rate_rad_s, p2.rate_rad_s);
    let c_r_m_s2 = um_to_m(p2.radius_error_um - p1.radius_error_um) / (w2 * w2 - w1 * w1);
    let k2 = identify::pseudo_second_order(
        config.k1_rad_s_g,
        c_r_m_s2,
        0.0,
        config.g_m_s2,
        config.radius_m,
    )
    .map_err(|source| PipelineError::Identify {
        path: path.to_owned(),
        field: format!("{section}.points"),
        source,
    })?;
    Ok(ModelFit {
        model: RadiusModel::TwoTerm,
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
    config: &StudyConfig,
    phase: &PhaseConfig,
    section: &str,
    path: &Path,
    lever_ratio: f64,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<(Vec<PointResult>, Vec<ProbeTrace>)> {
    let radius_point = |rate_deg_s: f64, radius_error_um: f64| PointResult {
        rate_deg_s,
        rate_rad_s: deg_s_to_rad_s(rate_deg_s),
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
    let harmonic_point = |i: usize, rate_deg_s: f64, dc1_um: f64, ds1_um: f64| {
        let drift = FirstHarmonic::new(dc1_um, ds1_um)
            .and_then(|h| config.lever.project(h))
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
    match &phase.points {
        Points::FirstHarmonic(points) => Ok((
            points
                .iter()
                .enumerate()
                .map(|(i, p)| harmonic_point(i, p.rate_deg_s, p.dc1_um, p.ds1_um))
                .collect::<Result<_>>()?,
            Vec::new(),
        )),
        Points::Recordings(set) => {
            let analysed = probe_analysis::analyse(set, section, path, progress)?;
            let mut points = Vec::with_capacity(analysed.len());
            let mut traces = Vec::with_capacity(analysed.len());
            for (i, (file, h)) in set.files.iter().zip(analysed).enumerate() {
                let point = harmonic_point(i, file.rate_deg_s, h.dc1_um, h.ds1_um)?;
                points.push(PointResult {
                    dc1_sigma_um: h.dc1_sigma_um,
                    ds1_sigma_um: h.ds1_sigma_um,
                    radius_error_sigma_um: Some(h.dc1_noise_sigma_um * lever_ratio),
                    revolutions: Some(h.revolutions),
                    residual_rms_um: Some(h.residual_rms_um),
                    ..point
                });
                traces.push(h.trace);
            }
            Ok((points, traces))
        }
        Points::RadiusError(points) => Ok((
            points
                .iter()
                .map(|p| radius_point(p.rate_deg_s, p.radius_error_um))
                .collect(),
            Vec::new(),
        )),
        Points::RadiusChange {
            from_rate_deg_s,
            to_rate_deg_s,
            change_um,
        } => Ok((
            vec![
                radius_point(*from_rate_deg_s, 0.0),
                radius_point(*to_rate_deg_s, *change_um),
            ],
            Vec::new(),
        )),
    }
}

fn fit_model(
    config: &StudyConfig,
    points: &[PointResult],
    model: RadiusModel,
    weighting: Weighting,
    section: &str,
    path: &Path,
) -> Result<ModelFit> {
    let identify_error = |source| PipelineError::Identify {
        path: path.to_owned(),
        field: format!("{section}.points"),
        source,
    };
    let rates: Vec<f64> = points.iter().map(|p| p.rate_rad_s).collect();
    let radius_errors_m: Vec<f64> = points.iter().map(|p| um_to_m(p.radius_error_um)).collect();
    let fit = match weighting {
        Weighting::Unweighted => identify::fit_radius_error(&rates, &radius_errors_m, model),
        Weighting::InverseVariance => {
            let mut sigma_m = Vec::with_capacity(points.len());
            for (i, p) in points.iter().enumerate() {
                match p.radius_error_sigma_um {
                    Some(s) if s > 0.0 => sigma_m.push(um_to_m(s)),
                    _ => {
                        return Err(PipelineError::Unsupported {
                            path: path.to_owned(),
                            field: format!("{section}.points.files[{i}]"),
                            reason: "inverse_variance weighting needs a standard error for \
                                     every recording, and this one's harmonic fit has no \
                                     residual (noise-free data?)",
                        });
                    }
                }
            }
            identify::fit_radius_error_weighted(&rates, &radius_errors_m, &sigma_m, model)
        }
    }
    .map_err(identify_error)?;
    let ssr_um2: f64 = fit.residuals_m.iter().map(|r| m_to_um(*r).powi(2)).sum();
    let k2 = identify::pseudo_second_order(
        config.k1_rad_s_g,
        fit.c_r_m_s2,
        fit.c_r_sigma_m_s2,
        config.g_m_s2,
        config.radius_m,
    )
    .map_err(identify_error)?;
    Ok(ModelFit {
        model,
        c_r_m_s2: fit.c_r_m_s2,
        c_r_sigma_m_s2: Some(fit.c_r_sigma_m_s2),
        offset_um: m_to_um(fit.offset_m),
        linear_um_s: fit.linear_m_s.map(m_to_um),
        residuals_um: fit.residuals_m.iter().map(|r| m_to_um(*r)).collect(),
        residual_sd_um: Some((ssr_um2 / fit.fit.dof as f64).sqrt()),
        weighting,
        reduced_chi: fit.weighted.then_some(fit.fit.residual_sd),
        dof: fit.fit.dof,
        condition_number: Some(fit.fit.condition_number),
        delta_k2_rad_s_g2: k2.delta_k2_rad_s_g2,
        delta_k2_sigma_rad_s_g2: Some(k2.sigma_rad_s_g2),
    })
}
