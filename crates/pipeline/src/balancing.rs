//! The balance section: the study's phases handed to the `balance` advisor, and its results
//! in results.json's terms.

use balance::{
    CalibrationContext, Correction, CorrectionPlane, Fields, Phasor, PhasorFit, Prediction,
    ProbePhase, ProbePoint, TrialMass, fit_phasors, influence_correction, stiffness_correction,
};
use harmonics::LeverGeometry;

use crate::results::{
    BalancePhase, BalanceResults, CheckResult, CorrectionResult, DynamicPhasor, Influence,
    PhaseResults, PredictedResult, SplitMass, StaticPhasor, StiffnessResult,
};

/// What one probe plane cannot separate, stated in the results.
pub(crate) const ONE_PLANE: &str = "one probe plane: the first-harmonic motion is taken as a cone about the tilt pivot (eq. 22), so translation and tilt, static and couple unbalance, are not separated; the correction is a single-plane one";

/// The validated balance section.
#[derive(Debug, Clone)]
pub(crate) struct BalanceInputs {
    /// Index of the initial phase.
    pub(crate) initial: usize,
    /// Index of the trial phase and its trial mass.
    pub(crate) trial: Option<(usize, TrialMass)>,
    pub(crate) radial_stiffness_n_m: Option<f64>,
    pub(crate) plane: CorrectionPlane,
    pub(crate) rotor_mass_kg: Option<f64>,
    /// Index of the check phase.
    pub(crate) check: Option<usize>,
}

/// The study's numbers the advisor needs.
pub(crate) struct Setting {
    pub(crate) lever: LeverGeometry,
    pub(crate) lever_ratio: f64,
    pub(crate) k1_rad_s_g: f64,
    pub(crate) radius_m: f64,
    pub(crate) g_m_s2: f64,
}

/// Runs the advisor on the phases' results. Errors carry the field they name.
pub(crate) fn run(
    b: &BalanceInputs,
    phases: &[PhaseResults],
    s: &Setting,
) -> Result<BalanceResults, (String, balance::BalanceError)> {
    let fit = |i: usize| -> Result<PhasorFit, (String, balance::BalanceError)> {
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
            lever: s.lever,
        })
        .map_err(|e| (field.clone(), e))
    };
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

    Ok(BalanceResults {
        initial: phases[b.initial].name.clone(),
        trial: b.trial.map(|(t, _)| phases[t].name.clone()),
        assumption: ONE_PLANE.to_owned(),
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
