//! The balance advisor's run on the phases' results, and its results in results.json's terms.

use balance::{
    AxisMotion, CalibrationContext, Correction, Fields, HeightPlane, Phasor, PhasorFit, Prediction,
    ProbePhase, ProbePlane, ProbePoint, Stiffness, TwoPlaneCorrection, TwoPlaneFields, axis_motion,
    fit_phasors, influence_correction, static_couple, stiffness_correction,
    two_plane_influence_correction, two_plane_stiffness_correction,
};
use harmonics::LeverGeometry;

use super::validate::{BalanceInputs, SecondProbeInputs};
use crate::error::{PipelineError, Result};
use crate::inputs::Core;
use crate::results::{
    BalancePhase, BalanceResults, CheckResult, CorrectionResult, DynamicPhasor, Influence,
    PhaseResults, PhasorResult, PlaneCorrection, PredictedResult, SplitMass, StaticPhasor,
    StiffnessResult, TwoPlaneCorrectionResult, TwoPlaneResults, Warning,
};

/// What one probe plane cannot separate, stated in the results.
const ONE_PLANE: &str = "one probe plane: the first-harmonic motion is taken as a cone about the tilt pivot (eq. 22), so translation and tilt, static and couple unbalance, are not separated; the correction is a single-plane one";

/// What two probe planes separate, stated in the results.
const TWO_PLANES: &str = "two probe planes: the first-harmonic motion is the spindle axis as a line, translation at the PIGA plane plus tilt times height (eq. 5), with no cone assumption (`two_plane`); `static`, `dynamic`, `correction` and `predicted` are the first probe's single-plane reading through the cone of eq. 22, kept for comparison";

type Failure = (String, balance::BalanceError);

/// The two-plane part of the advisor: translation and tilt, static and couple unbalance,
/// the two-plane correction and its check.
fn two_planes(
    b: &BalanceInputs,
    q: &SecondProbeInputs,
    phases: &[PhaseResults],
    s: &Setting,
    context: &CalibrationContext,
    fit_with: &dyn Fn(usize, LeverGeometry) -> std::result::Result<PhasorFit, Failure>,
) -> std::result::Result<TwoPlaneResults, Failure> {
    // The second probe's fits use only their probe-plane phasors: a lever of ratio 1.
    let second_lever = LeverGeometry {
        pivot_to_probe_mm: 1.0,
        probe_to_piga_mm: 0.0,
        probe_direction: q.probe_direction,
    };
    let heights_m = [-s.lever.probe_to_piga_mm * 1e-3, -q.probe_to_piga_mm * 1e-3];
    let field = "balance.second_probe";
    let motion = |i: usize| -> std::result::Result<AxisMotion, Failure> {
        let f1 = fit_with(i, s.lever)?;
        let j = q.phase_of[&i];
        let f2 = fit_with(j, second_lever)?;
        axis_motion(
            &ProbePlane {
                fit: &f1,
                height_m: heights_m[0],
            },
            &ProbePlane {
                fit: &f2,
                height_m: heights_m[1],
            },
            field,
        )
        .map_err(|e| (field.to_owned(), e))
    };
    let at = |f: &'static str| move |e| (f.to_owned(), e);
    let m0 = motion(b.initial)?;
    let stiffness = match (b.radial_stiffness_n_m, b.angular_stiffness_n_m_rad) {
        (Some(radial_n_m), Some(angular_n_m_rad)) => Some(Stiffness {
            radial_n_m,
            angular_n_m_rad,
        }),
        _ => None,
    };
    let fields = TwoPlaneFields {
        trials: ["balance.trial", "balance.two_plane.trial"],
        trial_masses: ["balance.trial_mass", "balance.two_plane.trial_mass"],
        planes: [
            "balance.two_plane.heights_m.0",
            "balance.two_plane.heights_m.1",
        ],
        context: "balance",
    };
    let mut corrections = Vec::new();
    let mut from_influence = None;
    if let Some(t) = &b.two_plane {
        if let (Some((ta, ma)), Some((tb, mb))) = (b.trial, t.trial) {
            let (xa, xb) = (motion(ta)?, motion(tb)?);
            let c = two_plane_influence_correction(
                &m0,
                [&xa, &xb],
                [&ma, &mb],
                &t.planes,
                context,
                &fields,
            )
            .map_err(at("balance.two_plane"))?;
            let sc = c.cancelled_unbalance();
            from_influence = Some((sc.static_kg_m, sc.couple_kg_m2));
            corrections.push(two_plane_result("influence_coefficient", &c, &t.planes));
        }
        if let Some(k) = &stiffness {
            let c = two_plane_stiffness_correction(&m0, k, "balance", &t.planes, context, &fields)
                .map_err(at("balance.two_plane"))?;
            corrections.push(two_plane_result("stiffness_model", &c, &t.planes));
        }
    }
    // static and couple unbalance: by the stiffnesses (eq. 1–2), else from the influence
    // correction (the unbalance it cancels)
    let unbalance = match &stiffness {
        Some(k) => {
            let sc = static_couple(&m0, k, "balance").map_err(at("balance"))?;
            Some(("stiffness_model", sc.static_kg_m, sc.couple_kg_m2))
        }
        None => from_influence.map(|(st, co)| ("influence_coefficient", st, co)),
    };
    let check = match (b.check, corrections.first()) {
        (Some(i), Some(first)) => {
            let mc = motion(i)?;
            let t = mc.dynamic.a;
            let c_r_m_s2 = t.x * 1e-6;
            let c_r_u_m_s2 = t.covariance[0][0].max(0.0).sqrt() * 1e-6;
            let p = &first.predicted;
            let sigma = p.c_r_u_m_s2.hypot(c_r_u_m_s2);
            let reduction = m0.dynamic.a.x / t.x;
            Some(CheckResult {
                phase: phases[i].name.clone(),
                c_r_m_s2,
                c_r_u_m_s2,
                z: if sigma > 0.0 {
                    (c_r_m_s2 - p.c_r_m_s2) / sigma
                } else {
                    0.0
                },
                reduction: if reduction.is_finite() {
                    reduction
                } else {
                    f64::MAX
                },
            })
        }
        _ => None,
    };
    let t = m0.dynamic.a;
    Ok(TwoPlaneResults {
        probe_heights_m: heights_m,
        second_probe_phase: phases[q.phase_of[&b.initial]].name.clone(),
        static_translation_um: phasor_result(&m0.static_translation_um),
        static_tilt_urad: phasor_result(&m0.static_tilt_urad),
        dynamic_translation_um_s2: phasor_result(&t),
        dynamic_tilt_urad_s2: phasor_result(&m0.dynamic.b),
        c_r_m_s2: t.x * 1e-6,
        c_r_u_m_s2: t.covariance[0][0].max(0.0).sqrt() * 1e-6,
        unbalance_method: unbalance.map(|u| u.0.to_owned()),
        static_kg_m: unbalance.map(|u| phasor_result(&u.1)),
        couple_kg_m2: unbalance.map(|u| phasor_result(&u.2)),
        per_rate: m0
            .per_rate
            .iter()
            .map(|p| {
                [
                    p.rate_rad_s.to_degrees(),
                    p.translation_um.x,
                    p.translation_um.y,
                    p.tilt_urad.x,
                    p.tilt_urad.y,
                ]
            })
            .collect(),
        corrections,
        check,
    })
}

fn two_plane_result(
    method: &str,
    c: &TwoPlaneCorrection,
    planes: &[HeightPlane; 2],
) -> TwoPlaneCorrectionResult {
    TwoPlaneCorrectionResult {
        method: method.to_owned(),
        planes: c
            .planes
            .iter()
            .zip(planes)
            .map(|(k, p)| PlaneCorrection {
                height_m: p.height_m,
                correction: correction_result(method, k),
            })
            .collect(),
        predicted: predicted_result(&c.predicted),
        residual_tilt_u_urad_s2: c.residual_tilt_urad_s2.max_sigma(),
    }
}

fn phasor_result(p: &Phasor) -> PhasorResult {
    PhasorResult {
        magnitude: p.magnitude(),
        magnitude_u: p.magnitude_sigma(),
        azimuth_deg: p.azimuth_deg(),
        azimuth_u_deg: p.azimuth_sigma_deg(),
        x: p.x,
        y: p.y,
    }
}

/// The study's numbers the advisor needs.
struct Setting {
    lever: LeverGeometry,
    lever_ratio: f64,
    k1_rad_s_g: f64,
    radius_m: f64,
    g_m_s2: f64,
}

/// Runs the advisor on the phases' results. Errors carry the field they name.
fn advise(
    b: &BalanceInputs,
    phases: &[PhaseResults],
    s: &Setting,
) -> std::result::Result<BalanceResults, (String, balance::BalanceError)> {
    let fit_with = |i: usize,
                    lever: LeverGeometry|
     -> std::result::Result<PhasorFit, (String, balance::BalanceError)> {
        let points: Vec<ProbePoint> = phases[i]
            .points
            .iter()
            .filter_map(|p| {
                Some(ProbePoint {
                    rate_rad_s: p.rate_rad_s,
                    dc1_um: p.dc1_um?,
                    ds1_um: p.ds1_um?,
                    sigma_um: p.radius_error_sigma_um.map(|r| r / s.lever_ratio),
                })
            })
            .collect();
        let field = format!("phases[{i}]");
        fit_phasors(&ProbePhase {
            field: &field,
            points: &points,
            lever,
        })
        .map_err(|e| (field.clone(), e))
    };
    let fit = |i: usize| fit_with(i, s.lever);
    let top_rate_rad_s = phases[b.initial]
        .points
        .iter()
        .map(|p| p.rate_rad_s)
        .fold(0.0, f64::max);
    let context = CalibrationContext {
        k1_rad_s_g: s.k1_rad_s_g,
        radius_m: s.radius_m,
        g_m_s2: s.g_m_s2,
        top_rate_rad_s,
        rotor_mass_kg: b.rotor_mass_kg,
    };
    let fields = Fields {
        trial: "balance.trial",
        trial_mass: "balance.trial_mass",
        plane: "balance.correction_radius_m",
        context: "balance",
    };
    let initial = fit(b.initial)?;
    let mut fitted = vec![(b.initial, initial.clone())];
    let at_balance = |e| ("balance".to_owned(), e);

    let stiffness = b
        .radial_stiffness_n_m
        .map(|k| {
            stiffness_correction(
                &initial,
                k,
                "balance.radial_stiffness_n_m",
                &b.plane,
                &context,
                &fields,
            )
            .map(|c| StiffnessResult {
                radial_stiffness_n_m: k,
                imbalance_kg_m: c.imbalance_kg_m.magnitude(),
                imbalance_u_kg_m: c.imbalance_kg_m.magnitude_sigma(),
                imbalance_azimuth_deg: c.imbalance_kg_m.azimuth_deg(),
                correction: correction_result("stiffness_model", &c.correction),
                predicted: predicted_result(&c.predicted),
            })
        })
        .transpose()
        .map_err(at_balance)?;

    let mut influence = None;
    let mut primary = None;
    if let Some((t, mass)) = &b.trial {
        let trial = fit(*t)?;
        let c = influence_correction(&initial, &trial, mass, &b.plane, &context, &fields)
            .map_err(at_balance)?;
        let a = c.influence_um_s2_per_kg_m;
        influence = Some(Influence {
            magnitude_um_s2_per_kg_m: a.magnitude(),
            azimuth_deg: a.azimuth_deg(),
            effective_stiffness_n_m: 1e6 / a.magnitude(),
        });
        primary = Some((
            correction_result("influence_coefficient", &c.correction),
            predicted_result(&c.predicted),
        ));
        fitted.push((*t, trial));
    }
    let (correction, predicted) = match (primary, &stiffness) {
        (Some(p), _) => p,
        (None, Some(st)) => (st.correction.clone(), st.predicted),
        // validation requires a trial run or a stiffness
        (None, None) => {
            return Err((
                "balance".to_owned(),
                balance::BalanceError::NonFiniteResult {
                    field: "balance".to_owned(),
                },
            ));
        }
    };

    let check = b
        .check
        .map(|i| {
            let f = fit(i)?;
            let d = f.dynamic_piga_um_s2;
            let c_r_m_s2 = d.x * 1e-6;
            let c_r_u_m_s2 = d.covariance[0][0].max(0.0).sqrt() * 1e-6;
            let sigma = predicted.c_r_u_m_s2.hypot(c_r_u_m_s2);
            let z = if sigma > 0.0 {
                (c_r_m_s2 - predicted.c_r_m_s2) / sigma
            } else {
                0.0
            };
            let out = CheckResult {
                phase: phases[i].name.clone(),
                c_r_m_s2,
                c_r_u_m_s2,
                z,
                reduction: initial.dynamic_piga_um_s2.x * 1e-6 / c_r_m_s2,
            };
            fitted.push((i, f));
            Ok::<_, (String, balance::BalanceError)>(out)
        })
        .transpose()?;
    // A reduction by an exact zero is not a number for results.json.
    let check = check.map(|c| CheckResult {
        reduction: if c.reduction.is_finite() {
            c.reduction
        } else {
            f64::MAX
        },
        ..c
    });

    let two_plane = b
        .second
        .as_ref()
        .map(|q| two_planes(b, q, phases, s, &context, &fit_with))
        .transpose()?;

    Ok(BalanceResults {
        initial: phases[b.initial].name.clone(),
        trial: b.trial.map(|(t, _)| phases[t].name.clone()),
        assumption: if two_plane.is_some() {
            TWO_PLANES
        } else {
            ONE_PLANE
        }
        .to_owned(),
        two_plane,
        static_phasor: static_phasor(&initial),
        dynamic: dynamic_phasor(&initial),
        phases: fitted
            .iter()
            .map(|(i, f)| BalancePhase {
                name: phases[*i].name.clone(),
                static_phasor: static_phasor(f),
                dynamic: dynamic_phasor(f),
                points_um: f
                    .measured_probe_um
                    .iter()
                    .map(|(w, z)| [w.to_degrees(), z.x * f.lever_ratio, z.y * f.lever_ratio])
                    .collect(),
                linear_significance: f.lack_of_fit.map(|l| l.linear_significance),
                reduced_chi: f.reduced_chi,
            })
            .collect(),
        influence,
        correction,
        predicted,
        stiffness,
        check,
    })
}

fn static_phasor(f: &PhasorFit) -> StaticPhasor {
    let p: Phasor = f.static_piga_um;
    StaticPhasor {
        magnitude_um: p.magnitude(),
        magnitude_u_um: p.magnitude_sigma(),
        azimuth_deg: p.azimuth_deg(),
        azimuth_u_deg: p.azimuth_sigma_deg(),
        probe_magnitude_um: f.static_probe_um.magnitude(),
    }
}

fn dynamic_phasor(f: &PhasorFit) -> DynamicPhasor {
    let p: Phasor = f.dynamic_piga_um_s2;
    DynamicPhasor {
        magnitude_um_s2: p.magnitude(),
        magnitude_u_um_s2: p.magnitude_sigma(),
        azimuth_deg: p.azimuth_deg(),
        azimuth_u_deg: p.azimuth_sigma_deg(),
        probe_magnitude_um_s2: f.dynamic_probe_um_s2.magnitude(),
        c_r_m_s2: p.x * 1e-6,
    }
}

fn correction_result(method: &str, c: &Correction) -> CorrectionResult {
    CorrectionResult {
        method: method.to_owned(),
        mass_kg: c.mass_kg,
        mass_u_kg: c.mass_u_kg,
        radius_m: c.radius_m,
        azimuth_deg: c.azimuth_deg,
        azimuth_u_deg: c.azimuth_u_deg,
        unbalance_g_mm: c.unbalance_kg_m.magnitude() * 1e6,
        split: c.split.map(|s| {
            s.iter()
                .map(|&(azimuth_deg, mass_kg)| SplitMass {
                    azimuth_deg,
                    mass_kg,
                })
                .collect()
        }),
    }
}

fn predicted_result(p: &Prediction) -> PredictedResult {
    PredictedResult {
        c_r_m_s2: p.c_r_m_s2,
        c_r_u_m_s2: p.c_r_u_m_s2,
        delta_k2_rad_s_g2: p.delta_k2_rad_s_g2,
        delta_k2_u_rad_s_g2: p.delta_k2_u_rad_s_g2,
        residual_unbalance_g_mm: p.residual_unbalance_g_mm,
        e_per_omega_mm_s: p.quality.map(|q| q.e_per_omega_mm_s),
        iso_grade_mm_s: p.quality.and_then(|q| q.grade_mm_s),
    }
}

/// Runs the balance section on the phases' results: the advisor, then its warnings — a
/// correction known no better than its own size, and (two probes) a cone C_r that differs
/// from the two probes' at the PIGA plane.
pub(crate) fn run(
    inputs: &Core,
    b: &BalanceInputs,
    phases: &[PhaseResults],
) -> Result<(BalanceResults, Vec<Warning>)> {
    let _span = tracing::info_span!("balance").entered();
    let setting = Setting {
        lever: inputs.lever,
        lever_ratio: inputs.lever_ratio,
        k1_rad_s_g: inputs.k1_rad_s_g,
        radius_m: inputs.radius_m,
        g_m_s2: inputs.g_m_s2,
    };
    let results =
        advise(b, phases, &setting).map_err(|(field, source)| PipelineError::Balance {
            path: inputs.source.clone(),
            field,
            source: Box::new(source),
        })?;
    let mut warnings = Vec::new();
    // A correction known to no better than its own size (a near-singular influence
    // coefficient, trial runs that barely moved the spindle) is not a correction to mount.
    let mut corrections: Vec<(String, &CorrectionResult)> =
        vec![("balance.correction".to_owned(), &results.correction)];
    if let Some(t) = &results.two_plane {
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
            warnings.push(Warning::correction_uncertain(
                c.mass_kg,
                c.mass_u_kg,
                location,
            ));
        }
    }
    // With two probes, the initial phase's C_r through the cone of eq. 22 beside the one
    // both probes give at the PIGA plane: the phase's number is the one a calibration or a
    // mechanism section would use.
    if let Some(t) = results.two_plane.as_ref()
        && let Some(phase) = phases.iter().find(|p| p.name == results.initial)
    {
        let cone = phase.fit.c_r_m_s2;
        if (cone - t.c_r_m_s2).abs() > 3.0 * t.c_r_u_m_s2 {
            warnings.push(Warning::cone_c_r(
                &results.initial,
                cone,
                t.c_r_m_s2,
                t.c_r_u_m_s2,
            ));
        }
    }
    Ok((results, warnings))
}
