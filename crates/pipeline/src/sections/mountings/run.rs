//! The mountings section's run: the probe's C_r compensated along each mounting's axes, the
//! joint fit (`calibration::fit_mountings`), and its results and warnings.

use ::calibration::{ProbeCompensation, fit_mountings};
use accel_model::{AccelKind, Term};
use uncertainty::{Dof, coverage_factor};

use super::validate::MountingsInputs;
use crate::error::{PipelineError, Result};
use crate::inputs::Core;
use crate::results::{
    ArmStretchResult, MountingFitResult, MountingsProbe, MountingsResults, Normalised,
    NuisanceResult, PhaseResults, TermResult, Warning,
};

/// The unit of a term's coefficient: the output unit per g^n (a misalignment in rad).
fn term_unit(kind: AccelKind, t: Term) -> String {
    if t.is_misalignment() {
        return "rad".to_owned();
    }
    let out = kind.output_unit();
    let per_g = match t.g_power() {
        0 => return out.to_owned(),
        1 => "g".to_owned(),
        p => format!("g{}", superscript(p)),
    };
    // rad/s per g as the rest of the toolkit writes it: rad/(s·g²)
    match out.strip_suffix("/s") {
        Some(head) if matches!(kind, AccelKind::Piga) => format!("{head}/(s·{per_g})"),
        _ => format!("{out}/{per_g}"),
    }
}

fn superscript(p: i32) -> &'static str {
    match p {
        2 => "²",
        3 => "³",
        _ => "⁴",
    }
}

/// The unit of a term normalised by k1 (k0: g; k2: 1/g; k3: 1/g²).
fn normalised_unit(t: Term) -> String {
    match t.g_power() {
        0 => "g".to_owned(),
        2 => "1/g".to_owned(),
        p => format!("1/g{}", superscript(p - 1)),
    }
}

/// The unit of a term normalised by k1 in millionths, as a person reads it: 10⁶·value/k1
/// (k0: µg; k2: µg/g²; k3: µg/g³).
fn relative_unit(t: Term) -> String {
    match t.g_power() {
        0 => "µg".to_owned(),
        p => format!("µg/g{}", superscript(p)),
    }
}

/// Runs the joint fit over the mountings.
pub(crate) fn run(
    core: &Core,
    s: &MountingsInputs,
    phases: &[PhaseResults],
) -> Result<(MountingsResults, Vec<Warning>)> {
    let _span = tracing::info_span!("mountings").entered();
    let fail = |e: ::calibration::MountingsError| PipelineError::Mountings {
        path: core.source.clone(),
        source: Box::new(e),
    };
    let probe = s
        .phase
        .map(|(p, chosen_by)| {
            let fit = &phases[p].fit;
            let across = across_arm(core, &phases[p])?;
            Ok::<_, PipelineError>((
                across,
                MountingsProbe {
                    phase: phases[p].name.clone(),
                    chosen_by: chosen_by.to_owned(),
                    static_m: fit.offset_um * 1e-6,
                    c_r_m_s2: fit.c_r_m_s2,
                    c_r_u_m_s2: fit.c_r_sigma_m_s2.unwrap_or(0.0),
                    across_static_m: across.map(|a| a.static_m),
                    c_ry_m_s2: across.map(|a| a.c_ry_m_s2),
                },
                // along the arm: the radius-error fit, static offset and C_r (left out, the
                // static offset moves the mountings' inputs by s/R at each radius and with
                // each axis's sign, which no shared k1 absorbs: 4 u of k2 on the fixture);
                // across the arm: the drift from the probe's sine component, static and ∝ ω²
                // (a tangential axis reads Δr_y/R of the radial input)
                ProbeCompensation {
                    static_m: fit.offset_um * 1e-6,
                    c_r_m_s2: fit.c_r_m_s2,
                    static_across_m: across.map_or(0.0, |a| a.static_m),
                    c_ry_m_s2: across.map_or(0.0, |a| a.c_ry_m_s2),
                    c_r_u_m_s2: fit.c_r_sigma_m_s2.unwrap_or(0.0),
                },
            ))
        })
        .transpose()?;
    let rates = s.rates_rad_s();
    let data = s.data(&rates);
    let spec = s.spec(core.g_m_s2, probe.as_ref().map(|(_, _, c)| *c));
    let fit = fit_mountings(&spec, &data).map_err(fail)?;
    // the probe's inputs in each term's u (Type B of the probe phase)
    let base: Vec<f64> = fit.terms.iter().map(|t| t.value).collect();
    let from_probe = match &probe {
        Some((across, _, c)) => {
            probe_variances(s, core.g_m_s2, &data, *c, *across, &base).map_err(fail)?
        }
        None => vec![0.0; base.len()],
    };
    // ν of each term: the fit's, with the probe phase's fit (n − 2) for its share
    // (Welch–Satterthwaite, JCGM 100 G.4)
    let probe_dof = s
        .phase
        .map_or(f64::INFINITY, |(p, _)| phases[p].fit.dof as f64);
    let fit_dof = fit.weighting.group_dof;
    // the radii, g, the rate scale and the fixtures' angles (Type B, ν = ∞)
    let type_b = ::calibration::type_b_contributions(&spec, &data, &s.type_b.unwrap_or_default())
        .map_err(fail)?;
    let from_type_b: Vec<f64> = (0..fit.terms.len())
        .map(|j| type_b.iter().map(|c| c.contributions[j].powi(2)).sum())
        .collect();
    let mut terms = Vec::with_capacity(fit.terms.len());
    let mut k_lowest = f64::INFINITY;
    for ((t, &probe_var), &type_b_var) in fit.terms.iter().zip(&from_probe).zip(&from_type_b) {
        let u = (t.u * t.u + probe_var + type_b_var).sqrt();
        let fit_share = match fit_dof {
            Dof::Finite(nu) => t.u.powi(4) / nu,
            Dof::Infinite => 0.0,
        };
        let probe_share = if probe_dof.is_finite() && probe_dof > 0.0 {
            probe_var * probe_var / probe_dof
        } else {
            0.0
        };
        let nu = if fit_share + probe_share > 0.0 {
            Dof::Finite(u.powi(4) / (fit_share + probe_share))
        } else {
            Dof::Infinite
        };
        let k95 = coverage_factor(0.95, nu).map_err(|e| PipelineError::Uncertainty {
            path: core.source.clone(),
            field: "mountings".to_owned(),
            source: Box::new(e),
        })?;
        k_lowest = k_lowest.min(k95);
        terms.push(TermResult {
            name: t.term.symbol().to_owned(),
            tag: t.term.tag().to_owned(),
            multiplies: t.term.regressor_words().to_owned(),
            unit: term_unit(s.kind, t.term),
            value: t.value,
            u,
            k: k95,
            u95: k95 * u,
            normalised: t.normalised.map(|(value, u_n)| Normalised {
                value,
                // the probe's share scales with the term as the fit's does
                u: if t.u > 0.0 { u_n * u / t.u } else { u_n },
                unit: normalised_unit(t.term),
                relative_unit: relative_unit(t.term),
            }),
        });
    }
    let mountings = s
        .sets
        .iter()
        .zip(&fit.residuals)
        .map(|(m, residuals)| {
            let rates = &m.table.rates_deg_s;
            let low = rates.iter().copied().fold(f64::INFINITY, f64::min);
            let high = rates.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let force = |deg_s: f64| {
                let w = units::deg_s_to_rad_s(deg_s);
                m.mounting.radius_m * w * w / core.g_m_s2
            };
            let rms = (residuals.iter().map(|r| r * r).sum::<f64>()
                / residuals.len().max(1) as f64)
                .sqrt();
            MountingFitResult {
                name: m.mounting.label.clone(),
                field: m.field.clone(),
                axes: [m.mounting.axes.ia, m.mounting.axes.pa, m.mounting.axes.oa],
                radius_m: m.mounting.radius_m,
                angle_u_deg: m.mounting.angle_u_deg,
                table: m.table.file.display().to_string(),
                points: rates.len(),
                rate_low_deg_s: low,
                rate_high_deg_s: high,
                specific_force_low_g: force(low),
                specific_force_high_g: force(high),
                residuals: residuals.clone(),
                residual_rms: rms,
            }
        })
        .collect();
    let nuisances = fit
        .nuisances
        .iter()
        .map(|n| NuisanceResult {
            name: n.label.clone(),
            value: n.value.0,
            u: n.value.1,
        })
        .collect();
    let arm_stretch = fit.arm_stretch.map(|a| ArmStretchResult {
        unseen_m_s2: a.unseen_m_s2.0,
        unseen_u_m_s2: a.unseen_m_s2.1,
        total_m_s2: a.total_m_s2.0,
        total_u_m_s2: a.total_m_s2.1,
    });
    let warnings = warnings(s, &fit, probe.is_some());
    let weighting = match fit.weighting.birge_ratio {
        Some(_) => "weighted by the tables' σ (the calibration's policy: a common term added \
                    when the residuals exceed them)"
            .to_owned(),
        None => "unweighted (no σ in the tables): u from the residuals".to_owned(),
    };
    let earth_rate_words = if s.earth_rate_stated {
        format!(
            "stated (latitude and spin): {:.1} µrad/s",
            s.earth_rate_vertical_rad_s * 1e6
        )
    } else {
        "not stated: taken as 0".to_owned()
    };
    let results = MountingsResults {
        kind: s.kind.words().to_owned(),
        output_unit: s.kind.output_unit().to_owned(),
        terms,
        mountings,
        nuisances,
        arm_stretch,
        arm_stretch_not_separable: fit.arm_stretch_not_separable,
        probe: probe.map(|(_, p, _)| p),
        earth_rate_vertical_rad_s: s.earth_rate_vertical_rad_s,
        earth_rate_words,
        weighting,
        dof: fit.weighting.noise_dof,
        residual_sd: fit.residual_sd,
        birge_ratio: fit.weighting.birge_ratio,
        condition_number: fit.fit.condition_number,
        separability: s.separability.to_string(),
        uncertainty_scope: scope(s, fit_dof, probe_dof, k_lowest),
        type_b: type_b.iter().map(|c| type_b_line(s, c)).collect(),
    };
    Ok((results, warnings))
}

/// What the expanded uncertainties hold, in words.
fn scope(s: &MountingsInputs, fit_dof: Dof, probe_dof: f64, k_lowest: f64) -> String {
    let probe = if probe_dof.is_finite() {
        format!(", the probe phase's C_r and drift across the arm ({probe_dof} degrees of freedom)")
    } else {
        String::new()
    };
    let angles = s.sets.iter().any(|m| m.mounting.angle_u_deg > 0.0);
    let type_b = match (s.type_b, angles) {
        (Some(_), true) => "; Type B (infinite degrees of freedom): each mounting's radius, g, \
                            the rate scale and the probe's gain and lever (the `uncertainty` \
                            section, the radii independent) and each fixture's angles about IA, PA and OA (`angle_u_deg`), \
                            propagated through refits of the joint fit"
            .to_owned(),
        (Some(_), false) => "; Type B (infinite degrees of freedom): each mounting's radius, g, \
                             the rate scale and the probe's gain and lever (the `uncertainty` \
                             section, the radii independent), propagated through refits of the joint fit; no \
                             fixture angle uncertainty stated"
            .to_owned(),
        (None, true) => "; Type B: each fixture's angles about IA, PA and OA (`angle_u_deg`); \
                         the radii, g and the rate scale are not in it (no `uncertainty` \
                         section)"
            .to_owned(),
        (None, false) => "; no Type B input is in it (no `uncertainty` section, no fixture \
                          angle uncertainty)"
            .to_owned(),
    };
    format!(
        "U95 = k·u, u from the joint fit's covariance ({fit_dof} degrees of freedom){probe}{type_b}; \
         k the Student t at each term's effective degrees of freedom (Welch–Satterthwaite; from \
         {k_lowest:.2})"
    )
}

/// A Type B input's line, in words.
fn type_b_line(
    s: &MountingsInputs,
    c: &::calibration::TypeBContribution,
) -> crate::results::MountingsTypeBLine {
    use ::calibration::TypeBInput;
    let label = |i: usize| s.sets.get(i).map_or("", |m| m.mounting.label.as_str());
    let (input, unit) = match c.input {
        TypeBInput::Radius(i) => (format!("radius of {}", label(i)), "m"),
        TypeBInput::Gravity => ("local g".to_owned(), "m/s²"),
        TypeBInput::RateScale => ("rate scale".to_owned(), "relative"),
        TypeBInput::ProbeScale => (
            "probe's compensation scale (gain and lever heights)".to_owned(),
            "relative",
        ),
        TypeBInput::Angle(i, axis) => (
            format!("fixture angle of {} about {}", label(i), axis.words()),
            "rad",
        ),
    };
    crate::results::MountingsTypeBLine {
        input,
        u: c.u,
        unit: unit.to_owned(),
        contributions: c.contributions.clone(),
    }
}

/// The drift across the arm at the accelerometer from the phase's first-harmonic sine
/// components (`Δr_y = a_y + C_ry·ω²`, m and m·s², through the lever as the radius error
/// is): `None` when the phase's points have no sine component (radius errors given).
fn across_arm(core: &Core, phase: &PhaseResults) -> Result<Option<Across>> {
    let Some(across_m): Option<Vec<f64>> = phase
        .points
        .iter()
        .map(|p| {
            p.ds1_um
                .map(|s1| ACROSS_SIGN * direction_sign(core) * s1 * core.lever_ratio * 1e-6)
        })
        .collect()
    else {
        return Ok(None);
    };
    let rates: Vec<f64> = phase.points.iter().map(|p| p.rate_rad_s).collect();
    let fit = identify::fit_radius_error(&rates, &across_m, identify::RadiusModel::TwoTerm)
        .map_err(|source| PipelineError::Identify {
            path: core.source.clone(),
            field: format!("phases[{}] (the drift across the arm)", phase.name),
            source,
        })?;
    let cov = &fit.fit.covariance;
    let last = cov.ncols() - 1;
    Ok(Some(Across {
        static_m: fit.offset_m,
        c_ry_m_s2: fit.c_r_m_s2,
        covariance: [
            [cov[(0, 0)], cov[(0, last)]],
            [cov[(last, 0)], cov[(last, last)]],
        ],
    }))
}

/// The drift across the arm fitted to the probe's sine components, with its covariance.
#[derive(Debug, Clone, Copy)]
struct Across {
    static_m: f64,
    c_ry_m_s2: f64,
    /// Covariance of (static_m, c_ry_m_s2).
    covariance: [[f64; 2]; 2],
}

/// Each chosen term's variance from the probe's inputs (C_r; the drift across the arm, static
/// and ∝ ω², correlated), by the GUM's law of propagation with sensitivities from refits at
/// each input moved by its standard uncertainty (the fit is linear in them to far better
/// than that step).
fn probe_variances(
    s: &MountingsInputs,
    g_m_s2: f64,
    data: &[::calibration::MountingData<'_>],
    probe: ProbeCompensation,
    across: Option<Across>,
    base: &[f64],
) -> std::result::Result<Vec<f64>, ::calibration::MountingsError> {
    let terms =
        |p: ProbeCompensation| -> std::result::Result<Vec<f64>, ::calibration::MountingsError> {
            let fit = fit_mountings(&s.spec(g_m_s2, Some(p)), data)?;
            Ok(fit.terms.iter().map(|t| t.value).collect())
        };
    // sensitivities per unit of each input, and the inputs' covariance
    let mut sens: Vec<Vec<f64>> = Vec::new();
    let mut cov: Vec<Vec<f64>> = Vec::new();
    let per_unit = |moved: ProbeCompensation,
                    h: f64|
     -> std::result::Result<Vec<f64>, ::calibration::MountingsError> {
        let v = terms(moved)?;
        Ok(v.iter().zip(base).map(|(a, b)| (a - b) / h).collect())
    };
    let u_c_r = probe.c_r_u_m_s2;
    if u_c_r > 0.0 {
        sens.push(per_unit(
            ProbeCompensation {
                c_r_m_s2: probe.c_r_m_s2 + u_c_r,
                ..probe
            },
            u_c_r,
        )?);
        cov.push(vec![u_c_r * u_c_r]);
    }
    let mut across_at = None;
    if let Some(a) = across {
        let (u_a, u_c) = (a.covariance[0][0].sqrt(), a.covariance[1][1].sqrt());
        if u_a > 0.0 && u_c > 0.0 {
            across_at = Some(sens.len());
            sens.push(per_unit(
                ProbeCompensation {
                    static_across_m: probe.static_across_m + u_a,
                    ..probe
                },
                u_a,
            )?);
            sens.push(per_unit(
                ProbeCompensation {
                    c_ry_m_s2: probe.c_ry_m_s2 + u_c,
                    ..probe
                },
                u_c,
            )?);
        }
    }
    let n = base.len();
    let mut var = vec![0.0; n];
    for k in 0..n {
        let mut v = 0.0;
        if u_c_r > 0.0 {
            v += sens[0][k] * sens[0][k] * cov[0][0];
        }
        if let (Some(j), Some(a)) = (across_at, across) {
            for p in 0..2 {
                for q in 0..2 {
                    v += sens[j + p][k] * sens[j + q][k] * a.covariance[p][q];
                }
            }
        }
        var[k] = v;
    }
    Ok(var)
}

/// `+1` for a probe measuring along O1X1, `−1` against it (as the radius error's).
const fn direction_sign(core: &Core) -> f64 {
    match core.lever.probe_direction {
        harmonics::ProbeDirection::AlongO1X1 => 1.0,
        harmonics::ProbeDirection::AgainstO1X1 => -1.0,
    }
}

/// The sign that turns the probe's sine component (in its measuring direction, through the
/// lever) into the drift across the arm along +Y2 of the mounting frames: a spindle drifting
/// towards +Y2 makes the probe's gap fall a quarter turn after it falls for a drift along
/// +X2 (the five-mounting fixture's test recovers the simulated Δr_ys and C_ry with this sign,
/// and the opposite one gives them negated).
const ACROSS_SIGN: f64 = -1.0;

/// What may make the joint fit's numbers wrong, in words.
fn warnings(s: &MountingsInputs, fit: &::calibration::MountingsFit, probe: bool) -> Vec<Warning> {
    let mut w = Vec::new();
    for p in s.separability.warnings() {
        w.push(Warning::mountings_poorly_separated(
            p.to_string(),
            "mountings.list",
        ));
    }
    if fit.arm_stretch_not_separable {
        w.push(Warning::mountings_poorly_separated(
            "these mountings cannot separate the radius growth the probe does not see (arm \
             stretch) from the chosen terms: it was not fitted, and any such growth is read as \
             part of the even terms (k2, k_oq); add a mounting with the input axis the other \
             way along the arm (IA out) to measure it"
                .to_owned(),
            "mountings.arm_stretch",
        ));
    }
    if !probe {
        w.push(Warning::mountings_assumed(
            "the probe's C_r is not compensated (`compensate: false`): the spindle's radius \
             growth C_r·ω² is read as part of k2 (Δk2 = k1·C_r·g/R²)"
                .to_owned(),
            "mountings.compensate",
        ));
    }
    let vertical = s.sets.iter().any(|m| m.mounting.axes.ia[2].abs() > 1e-12);
    if matches!(s.kind, AccelKind::Piga) && vertical && !s.earth_rate_stated {
        w.push(Warning::mountings_assumed(
            "a mounting's input axis has a vertical component, so the PIGA reads the vertical \
             Earth rate (up to 72.9 µrad/s); the site's latitude and the spin are not stated \
             (`latitude_deg`, `spin_seen_from_above`), so it was taken as 0 and shifts that \
             mounting's bias"
                .to_owned(),
            "mountings.latitude_deg",
        ));
    }
    let unstated: Vec<&str> = s
        .sets
        .iter()
        .filter(|m| !m.angle_u_stated)
        .map(|m| m.field.as_str())
        .collect();
    if !unstated.is_empty() {
        w.push(Warning::mountings_assumed(
            format!(
                "the fixture's angular uncertainty is not stated for {} (`angle_u_deg`): taken \
                 as 0; an index error leaks the radial input into the cross terms (IEEE Std \
                 836 §6.2)",
                unstated.join(", ")
            ),
            "mountings.list",
        ));
    }
    if s.type_b.is_none() {
        w.push(Warning::mountings_assumed(
            "no `uncertainty` section: the radii, g and the rate scale are taken as exact, and \
             the expanded uncertainties of the terms hold the joint fit, the probe phase and the \
             fixtures' angles only; state `uncertainty` (docs/CONFIGURATION.md) before \
             certifying these terms"
                .to_owned(),
            "uncertainty",
        ));
    }
    w
}
