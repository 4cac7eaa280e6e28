//! The correction mass: by influence coefficient (trial weight) or by the stiffness model
//! (eq. 1), and the residual it leaves (eq. 19).

use crate::error::{BalanceError, Result, finite_result};
use crate::phasor::{Complex, Phasor, PhasorFit};

/// Micrometres per metre.
const UM_PER_M: f64 = 1e6;
/// g·mm per kg·m.
const G_MM_PER_KG_M: f64 = 1e6;

/// A mass bolted to the rotor: how much, how far from the axis and at which azimuth in `O2`
/// (from `O2X2`, the arm towards the PIGA, towards `O2Y2`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrialMass {
    /// Mass, kg (> 0).
    pub mass_kg: f64,
    /// Distance of its centre of mass from the spindle axis, m (> 0).
    pub radius_m: f64,
    /// Azimuth, degrees.
    pub azimuth_deg: f64,
}

/// Where the correction goes.
#[derive(Debug, Clone, PartialEq)]
pub struct CorrectionPlane {
    /// Radius at which the correction mass is mounted, m (> 0).
    pub radius_m: f64,
    /// Azimuths of fixed mounting positions, degrees; empty: any azimuth. With positions the
    /// correction is also split onto the two that bracket it.
    pub fixed_azimuths_deg: Vec<f64>,
}

/// What the advisor needs of the calibration to state the k2 error a residual leaves (eq. 19)
/// and the balance quality grade.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationContext {
    /// PIGA scale factor k1, rad/(s·g) (> 0).
    pub k1_rad_s_g: f64,
    /// Working radius R, m (> 0).
    pub radius_m: f64,
    /// g, m/s² (> 0).
    pub g_m_s2: f64,
    /// The calibration's top rate, rad/s (> 0): the ISO 21940-11 grade is stated there.
    pub top_rate_rad_s: f64,
    /// Mass of the rotor, kg (> 0), for the specific unbalance `e_per = U/M`; `None`: no grade.
    pub rotor_mass_kg: Option<f64>,
}

/// The correction: one mass at the correction radius, and optionally its split onto the two
/// neighbouring fixed positions.
#[derive(Debug, Clone, PartialEq)]
pub struct Correction {
    /// The unbalance `U` to add, kg·m, as a phasor in `O2` (with its covariance).
    pub unbalance_kg_m: Phasor,
    /// `|U|/r`, kg.
    pub mass_kg: f64,
    /// Standard uncertainty of the mass, kg.
    pub mass_u_kg: f64,
    /// The correction radius, m.
    pub radius_m: f64,
    /// Azimuth of the correction, degrees in (−180, 180].
    pub azimuth_deg: f64,
    /// Standard uncertainty of the azimuth, degrees.
    pub azimuth_u_deg: f64,
    /// The same unbalance on the two fixed positions bracketing the azimuth:
    /// `(azimuth_deg, mass_kg)` each, both masses ≥ 0.
    pub split: Option<[(f64, f64); 2]>,
}

/// The residual the correction leaves, predicted.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    /// Residual dynamic phasor at the PIGA plane, µm·s² (nominally zero; its covariance is
    /// the uncertainty of the correction).
    pub dynamic_piga_um_s2: Phasor,
    /// Residual `C_r = Re D`, m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty, m·s².
    pub c_r_u_m_s2: f64,
    /// `Δk2 = k1·C_r·g/R²` (eq. 19), rad/(s·g²).
    pub delta_k2_rad_s_g2: f64,
    /// Its standard uncertainty, rad/(s·g²).
    pub delta_k2_u_rad_s_g2: f64,
    /// Expected residual unbalance, `√(|U_res|² + tr Σ_U)`, g·mm: its RMS magnitude.
    pub residual_unbalance_g_mm: f64,
    /// ISO 21940-11 at the top rate, when the rotor mass is given.
    pub quality: Option<BalanceQuality>,
}

/// ISO 21940-11 balance quality: `e_per·Ω`, and the finest standard grade it meets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BalanceQuality {
    /// Specific unbalance `e_per = U/M`, µm (g·mm/kg).
    pub e_per_um: f64,
    /// `e_per·Ω` at the top rate, mm/s.
    pub e_per_omega_mm_s: f64,
    /// The finest grade `G` (0.16, 0.4, 1, 2.5, 6.3, 16, 40, …) with `e_per·Ω ≤ G`, mm/s;
    /// `None` above G 4000.
    pub grade_mm_s: Option<f64>,
}

/// The standard grades of ISO 21940-11 (mm/s), finest first.
pub const ISO_GRADES_MM_S: [f64; 12] = [
    0.16, 0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0, 4000.0,
];

/// The correction by influence coefficient, with its prediction.
#[derive(Debug, Clone, PartialEq)]
pub struct InfluenceCorrection {
    /// `α = (D_trial − D_initial)/(m_t·r_t·e^{iθ_t})` at the PIGA plane, µm·s² per kg·m.
    pub influence_um_s2_per_kg_m: Phasor,
    /// The correction (with the trial mass removed).
    pub correction: Correction,
    /// What it leaves.
    pub predicted: Prediction,
}

/// The correction by the stiffness model of eq. 1, with its prediction.
#[derive(Debug, Clone, PartialEq)]
pub struct StiffnessCorrection {
    /// The imbalance the dynamic phasor stands for, `m·R_cm·e^{iα} = k_r·D` (eq. 1), kg·m.
    pub imbalance_kg_m: Phasor,
    /// The correction, `−k_r·D`.
    pub correction: Correction,
    /// What it leaves.
    pub predicted: Prediction,
}

pub(crate) fn validate_plane(plane: &CorrectionPlane, field: &str) -> Result<()> {
    units::positive(format!("{field}.radius_m"), plane.radius_m)?;
    for (i, &a) in plane.fixed_azimuths_deg.iter().enumerate() {
        units::finite(format!("{field}.fixed_azimuths_deg[{i}]"), a)?;
    }
    Ok(())
}

pub(crate) fn validate_context(c: &CalibrationContext, field: &str) -> Result<()> {
    units::positive(format!("{field}.k1_rad_s_g"), c.k1_rad_s_g)?;
    units::positive(format!("{field}.radius_m"), c.radius_m)?;
    units::positive(format!("{field}.g_m_s2"), c.g_m_s2)?;
    units::positive(format!("{field}.top_rate_rad_s"), c.top_rate_rad_s)?;
    if let Some(m) = c.rotor_mass_kg {
        units::positive(format!("{field}.rotor_mass_kg"), m)?;
    }
    Ok(())
}

/// Paths of the advisor's inputs in the caller's configuration, for errors.
#[derive(Debug, Clone, Copy)]
pub struct Fields<'a> {
    /// The trial phase (named by a singular influence coefficient).
    pub trial: &'a str,
    /// The trial mass.
    pub trial_mass: &'a str,
    /// The correction plane.
    pub plane: &'a str,
    /// The calibration context.
    pub context: &'a str,
}

impl Default for Fields<'_> {
    fn default() -> Self {
        Self {
            trial: "trial",
            trial_mass: "trial_mass",
            plane: "correction",
            context: "calibration",
        }
    }
}

/// The influence-coefficient correction (the shop method, model-free).
///
/// `α = (D_t − D_0)/(m_t·r_t·e^{iθ_t})` from the dynamic phasors at the PIGA plane without
/// and with the trial mass; the correction, to be mounted after the trial mass is removed,
/// is `U = −D_0/α`, a mass `|U|/r_c` at azimuth `arg U`. The prediction propagates both
/// phasors' covariances to the residual `D_0 + α·U` (with `U` as mounted, exact):
/// `δD_res = (1 − c)·δD_0 + c·δD_t` with `c = U·/(m_t r_t e^{iθ_t})`.
///
/// # Errors
/// [`BalanceError::InvalidField`] for a trial mass, radius or azimuth out of domain (a mass
/// of 0 names `<trial_mass>.mass_kg`), a bad correction plane or context;
/// [`BalanceError::SingularInfluence`] naming the trial phase when its dynamic phasor does
/// not differ from the initial one by more than 3σ; [`BalanceError::CannotSplit`];
/// [`BalanceError::NonFiniteResult`].
pub fn influence_correction(
    initial: &PhasorFit,
    trial: &PhasorFit,
    trial_mass: &TrialMass,
    plane: &CorrectionPlane,
    context: &CalibrationContext,
    fields: &Fields<'_>,
) -> Result<InfluenceCorrection> {
    let tm = fields.trial_mass;
    units::positive(format!("{tm}.mass_kg"), trial_mass.mass_kg)?;
    units::positive(format!("{tm}.radius_m"), trial_mass.radius_m)?;
    units::finite(format!("{tm}.azimuth_deg"), trial_mass.azimuth_deg)?;
    validate_plane(plane, fields.plane)?;
    validate_context(context, fields.context)?;

    let d0 = initial.dynamic_piga_um_s2;
    let dt = trial.dynamic_piga_um_s2;
    let change = dt.value().sub(d0.value());
    let change_phasor = Phasor {
        x: change.re,
        y: change.im,
        covariance: d0.plus_independent(&dt).covariance,
    };
    let three_sigma = 3.0 * change_phasor.max_sigma();
    let significant = change.abs() > three_sigma && change.abs() > 0.0;
    if !significant {
        return Err(BalanceError::SingularInfluence {
            field: fields.trial.to_owned(),
            change_um_s2: change.abs(),
            three_sigma_um_s2: three_sigma,
        });
    }
    let t = Complex::from_polar(
        trial_mass.mass_kg * trial_mass.radius_m,
        trial_mass.azimuth_deg.to_radians(),
    );
    let alpha = change.div(t);
    let inv_t = Complex::new(1.0, 0.0).div(t);
    let influence = change_phasor.times(inv_t);
    let u = d0.value().neg().div(alpha);
    // δU = −δD_0/α + D_0·δα/α² with δα = (δD_t − δD_0)/T:
    // δU = −(1 − c)/α·δD_0 − c/α·δD_t, with c = U/T.
    let c = u.mul(inv_t);
    let one_minus_c = Complex::new(1.0, 0.0).sub(c);
    let inv_alpha = Complex::new(1.0, 0.0).div(alpha);
    let u_cov = d0
        .times(one_minus_c.mul(inv_alpha))
        .plus_independent(&dt.times(c.mul(inv_alpha)))
        .covariance;
    let unbalance = Phasor {
        x: u.re,
        y: u.im,
        covariance: u_cov,
    };
    let correction = correction_from(unbalance, plane, fields.plane)?;
    // residual D_0 + α·U as mounted (U exact): (1 − c)·D_0 + c·D_t in value and variance
    // its value is zero by construction (what is left is rounding): keep the covariance
    let residual = Phasor {
        x: 0.0,
        y: 0.0,
        ..d0.times(one_minus_c).plus_independent(&dt.times(c))
    };
    let predicted = predict(residual, alpha, context)?;
    let out = InfluenceCorrection {
        influence_um_s2_per_kg_m: influence,
        correction,
        predicted,
    };
    finite_result(
        "influence correction",
        if out.influence_um_s2_per_kg_m.is_finite() {
            0.0
        } else {
            f64::NAN
        },
    )?;
    Ok(out)
}

/// The stiffness-model correction (eq. 1): the dynamic drift at the PIGA plane is
/// `m·R_cm·ω²/k_r` towards the imbalance, so the imbalance is `m·R_cm·e^{iα} = k_r·D`
/// (D in m·s²) and the correction `−k_r·D`.
///
/// The tilt of eq. 2 (`m·R_cm·l/k_θ`) is not seen by one probe under the cone assumption of
/// eq. 22, so the angular stiffness cannot be used here; two probe planes separate it
/// ([`crate::axis_motion`], [`crate::static_couple`], [`crate::two_plane_stiffness_correction`]).
///
/// # Errors
/// [`BalanceError::InvalidField`] for a radial stiffness that is not > 0 (named
/// `<field>`), a bad plane or context; [`BalanceError::CannotSplit`];
/// [`BalanceError::NonFiniteResult`].
pub fn stiffness_correction(
    initial: &PhasorFit,
    radial_stiffness_n_m: f64,
    stiffness_field: &str,
    plane: &CorrectionPlane,
    context: &CalibrationContext,
    fields: &Fields<'_>,
) -> Result<StiffnessCorrection> {
    units::positive(stiffness_field, radial_stiffness_n_m)?;
    validate_plane(plane, fields.plane)?;
    validate_context(context, fields.context)?;
    let d0 = initial.dynamic_piga_um_s2;
    let k = radial_stiffness_n_m / UM_PER_M; // kg·m per µm·s²
    let imbalance = d0.scaled(k);
    let unbalance = imbalance.scaled(-1.0);
    let correction = correction_from(unbalance, plane, fields.plane)?;
    // α = 1/k exactly: the residual is D_0 − D̂_0, zero with the covariance of D_0
    let residual = Phasor {
        x: 0.0,
        y: 0.0,
        covariance: d0.covariance,
    };
    let predicted = predict(residual, Complex::new(1.0 / k, 0.0), context)?;
    if !imbalance.is_finite() {
        return Err(BalanceError::NonFiniteResult {
            field: stiffness_field.to_owned(),
        });
    }
    Ok(StiffnessCorrection {
        imbalance_kg_m: imbalance,
        correction,
        predicted,
    })
}

pub(crate) fn correction_from(
    u: Phasor,
    plane: &CorrectionPlane,
    field: &str,
) -> Result<Correction> {
    if !u.is_finite() {
        return Err(BalanceError::NonFiniteResult {
            field: field.to_owned(),
        });
    }
    let r = plane.radius_m;
    let azimuth_deg = u.azimuth_deg();
    let split = if plane.fixed_azimuths_deg.is_empty() {
        None
    } else {
        Some(split(
            u.magnitude() / r,
            azimuth_deg,
            &plane.fixed_azimuths_deg,
            field,
        )?)
    };
    Ok(Correction {
        unbalance_kg_m: u,
        mass_kg: finite_result(field, u.magnitude() / r)?,
        mass_u_kg: finite_result(field, u.magnitude_sigma() / r)?,
        radius_m: r,
        azimuth_deg,
        azimuth_u_deg: u.azimuth_sigma_deg(),
        split,
    })
}

/// Splits a mass at `azimuth_deg` onto the two fixed positions that bracket it most tightly
/// (the vector sum is the same): `m₁ = m·sin(θ₂ − θ)/sin(θ₂ − θ₁)`,
/// `m₂ = m·sin(θ − θ₁)/sin(θ₂ − θ₁)`.
fn split(
    mass_kg: f64,
    azimuth_deg: f64,
    positions: &[f64],
    field: &str,
) -> Result<[(f64, f64); 2]> {
    let ccw = |from: f64, to: f64| (to - from).rem_euclid(360.0);
    // the nearest position at or clockwise of θ, and the nearest counter-clockwise of θ
    let below = positions
        .iter()
        .copied()
        .min_by(|&a, &b| ccw(a, azimuth_deg).total_cmp(&ccw(b, azimuth_deg)));
    let above = positions
        .iter()
        .copied()
        .min_by(|&a, &b| ccw(azimuth_deg, a).total_cmp(&ccw(azimuth_deg, b)));
    let (Some(p1), Some(p2)) = (below, above) else {
        return Err(BalanceError::CannotSplit {
            field: field.to_owned(),
            azimuth_deg,
        });
    };
    let d1 = ccw(p1, azimuth_deg);
    if d1 == 0.0 {
        return Ok([(p1, mass_kg), (p2, 0.0)]);
    }
    let gap = ccw(p1, p2);
    if gap >= 180.0 || gap == 0.0 {
        return Err(BalanceError::CannotSplit {
            field: format!("{field}.fixed_azimuths_deg"),
            azimuth_deg,
        });
    }
    let s = gap.to_radians().sin();
    let m1 = mass_kg * (gap - d1).to_radians().sin() / s;
    let m2 = mass_kg * d1.to_radians().sin() / s;
    Ok([(p1, m1.max(0.0)), (p2, m2.max(0.0))])
}

/// The prediction from a residual dynamic phasor at the PIGA plane and the influence
/// coefficient that turns unbalance into it.
fn predict(residual: Phasor, alpha: Complex, c: &CalibrationContext) -> Result<Prediction> {
    let u_res = residual.times(Complex::new(1.0, 0.0).div(alpha));
    predict_unbalance(residual, u_res, c)
}

/// The prediction from a residual dynamic phasor at the PIGA plane (µm·s²) and the residual
/// static unbalance it stands for (kg·m).
pub(crate) fn predict_unbalance(
    residual: Phasor,
    u_res: Phasor,
    c: &CalibrationContext,
) -> Result<Prediction> {
    let c_r_m_s2 = residual.x / UM_PER_M;
    let c_r_u_m_s2 = residual.covariance[0][0].max(0.0).sqrt() / UM_PER_M;
    let factor = c.k1_rad_s_g * c.g_m_s2 / (c.radius_m * c.radius_m);
    let trace = u_res.covariance[0][0] + u_res.covariance[1][1];
    let residual_unbalance_g_mm =
        (u_res.magnitude().powi(2) + trace.max(0.0)).sqrt() * G_MM_PER_KG_M;
    let quality = c.rotor_mass_kg.map(|m| {
        let e_per_um = residual_unbalance_g_mm / m; // g·mm/kg = µm
        let e_per_omega_mm_s = e_per_um * 1e-3 * c.top_rate_rad_s;
        let grade_mm_s = ISO_GRADES_MM_S
            .iter()
            .copied()
            .find(|&g| e_per_omega_mm_s <= g);
        BalanceQuality {
            e_per_um,
            e_per_omega_mm_s,
            grade_mm_s,
        }
    });
    let p = Prediction {
        dynamic_piga_um_s2: residual,
        c_r_m_s2,
        c_r_u_m_s2,
        delta_k2_rad_s_g2: factor * c_r_m_s2,
        delta_k2_u_rad_s_g2: factor * c_r_u_m_s2,
        residual_unbalance_g_mm,
        quality,
    };
    let grade_ok = p
        .quality
        .is_none_or(|q| q.e_per_um.is_finite() && q.e_per_omega_mm_s.is_finite());
    let ok = residual.is_finite()
        && p.c_r_u_m_s2.is_finite()
        && p.delta_k2_rad_s_g2.is_finite()
        && p.delta_k2_u_rad_s_g2.is_finite()
        && p.residual_unbalance_g_mm.is_finite()
        && grade_ok;
    finite_result("prediction", if ok { 0.0 } else { f64::NAN })?;
    Ok(p)
}

/// What one published number, a change of radius error between two rates, determines
/// (the paper's pre-balance 19.4640 µm between 10 and 200.1234 deg/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadiusChangeAdvice {
    /// `C_r = Δr/(ω₂² − ω₁²)`, m·s² (the `O2X2` component of the dynamic phasor only).
    pub c_r_m_s2: f64,
    /// `Δk2 = k1·C_r·g/R²` (eq. 19), rad/(s·g²).
    pub delta_k2_rad_s_g2: f64,
    /// The empirical formula's coefficient: unbalance along `O2X2` per µm of radius change,
    /// `k_r/(ω₂² − ω₁²)`, g·mm per µm.
    pub unbalance_per_um_g_mm: f64,
    /// The unbalance along `O2X2` the change stands for, `k_r·C_r`, g·mm (a lower bound of the
    /// imbalance's magnitude: the `O2Y2` component is not measured).
    pub unbalance_x_g_mm: f64,
    /// The correction if the whole imbalance lies on the arm's line (azimuth 0° or 180°):
    /// mass at the correction radius, kg.
    pub correction_mass_kg: f64,
    /// Its azimuth under that assumption, degrees (180 for a positive change).
    pub correction_azimuth_deg: f64,
}

/// The paper check: the correction one change of radius error determines, with the stiffness
/// model (eq. 1) and eq. 19.
///
/// # Errors
/// [`BalanceError::InvalidField`] naming `change_um`, `from_rate_rad_s`, `to_rate_rad_s`
/// (the two must differ), `radial_stiffness_n_m`, the plane or the context.
pub fn radius_change_advice(
    change_um: f64,
    from_rate_rad_s: f64,
    to_rate_rad_s: f64,
    radial_stiffness_n_m: f64,
    plane: &CorrectionPlane,
    context: &CalibrationContext,
) -> Result<RadiusChangeAdvice> {
    units::finite("change_um", change_um)?;
    units::non_negative("from_rate_rad_s", from_rate_rad_s)?;
    units::positive("to_rate_rad_s", to_rate_rad_s)?;
    units::positive("radial_stiffness_n_m", radial_stiffness_n_m)?;
    validate_plane(plane, "correction")?;
    validate_context(context, "calibration")?;
    let dw2 = to_rate_rad_s * to_rate_rad_s - from_rate_rad_s * from_rate_rad_s;
    if dw2 == 0.0 {
        return Err(BalanceError::InvalidField {
            field: "to_rate_rad_s".to_owned(),
            value: to_rate_rad_s,
            requirement: units::Requirement::Positive,
        });
    }
    let c_r_m_s2 = change_um / UM_PER_M / dw2;
    // Per µm of the change, whichever way the two rates are given (|Δω²|).
    let unbalance_per_um_g_mm = radial_stiffness_n_m / dw2.abs() / UM_PER_M * G_MM_PER_KG_M;
    let unbalance_x_g_mm = radial_stiffness_n_m * c_r_m_s2 * G_MM_PER_KG_M;
    let advice = RadiusChangeAdvice {
        c_r_m_s2,
        delta_k2_rad_s_g2: context.k1_rad_s_g * c_r_m_s2 * context.g_m_s2
            / (context.radius_m * context.radius_m),
        unbalance_per_um_g_mm,
        unbalance_x_g_mm,
        correction_mass_kg: unbalance_x_g_mm.abs() / G_MM_PER_KG_M / plane.radius_m,
        // Opposite the imbalance's O2X2 component: the sign of C_r, not of the change (a
        // change given from the higher rate to the lower has the other sign).
        correction_azimuth_deg: if c_r_m_s2 >= 0.0 { 180.0 } else { 0.0 },
    };
    let ok = [
        advice.c_r_m_s2,
        advice.delta_k2_rad_s_g2,
        advice.unbalance_per_um_g_mm,
        advice.unbalance_x_g_mm,
        advice.correction_mass_kg,
    ]
    .iter()
    .all(|v| v.is_finite());
    finite_result("radius change advice", if ok { 0.0 } else { f64::NAN })?;
    Ok(advice)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn a_change_given_from_the_higher_rate_is_the_same_advice() {
        let context = CalibrationContext {
            k1_rad_s_g: 0.56,
            g_m_s2: 9.8,
            radius_m: 2.5,
            top_rate_rad_s: 200f64.to_radians(),
            rotor_mass_kg: None,
        };
        let plane = CorrectionPlane {
            radius_m: 2.5,
            fixed_azimuths_deg: Vec::new(),
        };
        let (w1, w2) = (10f64.to_radians(), 200f64.to_radians());
        let up = radius_change_advice(20.0, w1, w2, 5e7, &plane, &context).unwrap();
        let down = radius_change_advice(-20.0, w2, w1, 5e7, &plane, &context).unwrap();
        assert_relative_eq!(up.c_r_m_s2, down.c_r_m_s2, max_relative = 1e-15);
        assert_eq!(up.correction_azimuth_deg, 180.0);
        assert_eq!(down.correction_azimuth_deg, 180.0);
        assert!(down.unbalance_per_um_g_mm > 0.0);
        assert_relative_eq!(
            up.unbalance_per_um_g_mm,
            down.unbalance_per_um_g_mm,
            max_relative = 1e-15
        );
        assert_relative_eq!(
            up.correction_mass_kg,
            down.correction_mass_kg,
            max_relative = 1e-15
        );
    }

    #[test]
    fn split_keeps_the_vector_sum() {
        let positions = [0.0, 60.0, 120.0, 180.0, 240.0, 300.0];
        for theta in [-170.0, -5.0, 0.0, 37.0, 59.9, 200.0] {
            let [(a1, m1), (a2, m2)] = split(2.0, theta, &positions, "p").unwrap();
            assert!(m1 >= 0.0 && m2 >= 0.0);
            let sum = Complex::from_polar(m1, f64::to_radians(a1))
                .sub(Complex::from_polar(-m2, f64::to_radians(a2)));
            let want = Complex::from_polar(2.0, f64::to_radians(theta));
            assert_relative_eq!(sum.re, want.re, epsilon = 1e-12);
            assert_relative_eq!(sum.im, want.im, epsilon = 1e-12);
        }
    }

    #[test]
    fn split_refuses_a_gap_of_half_a_turn() {
        assert!(matches!(
            split(1.0, 90.0, &[0.0, 180.0], "plane"),
            Err(BalanceError::CannotSplit { .. })
        ));
        assert!(matches!(
            split(1.0, 90.0, &[0.0], "plane"),
            Err(BalanceError::CannotSplit { .. })
        ));
    }

    #[test]
    fn grade_is_the_finest_standard_grade_met() {
        let c = CalibrationContext {
            k1_rad_s_g: 0.56,
            radius_m: 2.5,
            g_m_s2: 9.8,
            top_rate_rad_s: 100.0,
            rotor_mass_kg: Some(1000.0),
        };
        // U = 1e4 g·mm on 1000 kg: e_per = 10 µm; ·100 rad/s = 1 mm/s → G 1
        // α = 1e-6 µm·s² per kg·m, U = 1e-2 kg·m: D = 1e-8 µm·s²
        let residual = Phasor::exact(1e-8, 0.0);
        let p = predict(residual, Complex::new(1e-6, 0.0), &c).unwrap();
        assert_relative_eq!(p.residual_unbalance_g_mm, 1e4, max_relative = 1e-12);
        let q = p.quality.unwrap();
        assert_relative_eq!(q.e_per_um, 10.0, max_relative = 1e-12);
        assert_relative_eq!(q.e_per_omega_mm_s, 1.0, max_relative = 1e-12);
        assert_eq!(q.grade_mm_s, Some(1.0));
        // Δk2 = k1·C_r·g/R² (eq. 19), C_r = 1e-14 m·s²
        assert_relative_eq!(
            p.delta_k2_rad_s_g2,
            0.56 * 1e-14 * 9.8 / 6.25,
            max_relative = 1e-12
        );
        // far beyond G 4000: no grade, still a result
        let p = predict(Phasor::exact(1.0, 0.0), Complex::new(1e-6, 0.0), &c).unwrap();
        assert_eq!(p.quality.unwrap().grade_mm_s, None);
    }
}
