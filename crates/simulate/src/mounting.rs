//! The PIGA mounted with its input axis towards the spindle (IA in) or away from it (IA out),
//! at its own radius, on an arm that stretches under centrifugal load (issue 20,
//! `docs/TWO_ORIENTATION.md`).
//!
//! The exact chain of eq. 5 and 10 with two changes to the mount `T₃²`:
//!
//! ```text
//! T₃² = Trans(R_s + C_a·ω², 0, 0)·Rot(z₂, 180°)   IA in  (s = +1, eq. 10 as is)
//! T₃² = Trans(R_s + C_a·ω², 0, 0)                  IA out (s = −1, turned 180° about z₂)
//! ```
//!
//! `C_a` is the arm stretch: the radius at the PIGA grows by `C_a·ω²` beyond the spindle's
//! own motion, which the probe on the sleeve does not see. Turning the PIGA about an axis
//! parallel to the spindle turns `X3` (the IA) and `Y3` round and keeps `Z3`: every IA
//! component of the inputs of eq. 12–13 changes sign, exactly.

use core::f64::consts::PI;

use accel_model::{
    AccelModelError, AxisInputs, OUTPUT_HIGHEST_HARMONIC, PigaCoefficients, RatePoint,
};
use kinematics::{
    Axis, Centrifuge, Chain, Ground, Homogeneous, Jet, Piga, PigaInputs, RevolutionQuadrature,
    Scalar, Sleeve, Spindle, Transform, spindle_transform,
};

/// Which way the PIGA's input axis points on the arm (one home: `accel_model`).
pub use accel_model::Orientation;

/// One mounting of the PIGA on the arm, as the exact chain needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mount {
    /// IA in or out.
    pub orientation: Orientation,
    /// Static radius of this mounting `R_s`, m (PIGA centre of mass to the mean spindle
    /// axis, at rest).
    pub radius_m: f64,
    /// Arm stretch `C_a`, m·s²: the radius at the PIGA grows by `C_a·ω²` (not seen by the
    /// probe).
    pub arm_stretch_m_s2: f64,
    /// Added to the PIGA's k0 in this mounting (remounting shifts the bias), rad/s.
    pub bias_shift_rad_s: f64,
}

impl Mount {
    /// The paper's mounting (IA in, eq. 10) at `radius_m`, no stretch, no shift.
    #[must_use]
    pub const fn ia_in(radius_m: f64) -> Self {
        Self {
            orientation: Orientation::IaIn,
            radius_m,
            arm_stretch_m_s2: 0.0,
            bias_shift_rad_s: 0.0,
        }
    }

    /// The PIGA's coefficients in this mounting (k0 shifted).
    #[must_use]
    pub fn coefficients(&self, piga: &PigaCoefficients) -> PigaCoefficients {
        PigaCoefficients {
            k0_rad_s: piga.k0_rad_s + self.bias_shift_rad_s,
            ..*piga
        }
    }

    fn check(&self) -> Result<(), AccelModelError> {
        for (field, value) in [
            ("radius_m", self.radius_m),
            ("arm_stretch_m_s2", self.arm_stretch_m_s2),
            ("bias_shift_rad_s", self.bias_shift_rad_s),
        ] {
            if !value.is_finite() {
                return Err(AccelModelError::NonFinite { field, value });
            }
        }
        Ok(())
    }

    /// `T₃²` of this mounting at rate ω, over jets (constant in time).
    fn transform(&self, rate_rad_s: f64) -> Transform<Spindle, Piga, Jet> {
        let c = Jet::constant;
        let radius = self.radius_m + self.arm_stretch_m_s2 * rate_rad_s * rate_rad_s;
        let turn = match self.orientation {
            Orientation::IaIn => PI,
            Orientation::IaOut => 0.0,
        };
        Transform::from_homogeneous(
            Homogeneous::trans(c(radius), c(0.0), c(0.0)) * Homogeneous::rot(Axis::Z, c(turn)),
        )
    }

    /// The exact inputs of eq. 12–13 at time `t_s` for this mounting on `chain`'s spindle
    /// (the chain's own radius is not used: the mounting has its own).
    #[must_use]
    pub fn inputs_at(&self, chain: &Chain, t_s: f64) -> PigaInputs {
        let w = chain.rate_rad_s();
        let theta = Jet::new(w * t_s, w, 0.0);
        let pose = Transform::<Ground, Sleeve, Jet>::identity()
            * spindle_transform(theta, chain.offsets())
            * self.transform(w);
        PigaInputs::from_pose_jet(&pose, chain.site())
    }
}

/// Mean output and exact mean inputs at one rate for a PIGA in `mount`: eq. 15 evaluated on
/// the exact inputs of this mounting and averaged over a whole revolution (the uniform rule,
/// exact for the output's harmonics, as `accel_model::rate_point`). For IA in with no
/// stretch and no shift at the centrifuge's radius it is `accel_model::rate_point`, bit for
/// bit (tested).
///
/// # Errors
/// As `kinematics::Chain::new` and [`PigaCoefficients::validate`];
/// [`AccelModelError::NonFinite`] for a non-finite mounting field;
/// [`AccelModelError::NonFiniteResult`] for a result out of range.
pub fn mounted_rate_point(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    mount: &Mount,
    rate_rad_s: f64,
) -> Result<RatePoint, AccelModelError> {
    piga.validate()?;
    mount.check()?;
    let coefficients = mount.coefficients(piga);
    coefficients.validate()?;
    let chain = Chain::new(centrifuge, rate_rad_s)?;
    let q = RevolutionQuadrature::minimal(OUTPUT_HIGHEST_HARMONIC);
    let [output_rad_s, a_x_g, omega_i_rad_s] = q.mean_array(rate_rad_s, |t| {
        let i = AxisInputs::of(&mount.inputs_at(&chain, t));
        [coefficients.output_rad_s(i), i.a_x_g, i.omega_i_rad_s]
    });
    for (quantity, value) in [
        ("output_rad_s", output_rad_s),
        ("a_x_g", a_x_g),
        ("omega_i_rad_s", omega_i_rad_s),
    ] {
        if !value.is_finite() {
            return Err(AccelModelError::NonFiniteResult {
                quantity,
                value,
                inputs: vec![
                    ("rate_rad_s", rate_rad_s),
                    ("radius_m", mount.radius_m),
                    ("arm_stretch_m_s2", mount.arm_stretch_m_s2),
                    ("gravity_m_s2", centrifuge.site.gravity_m_s2),
                    ("c_r_m_s2", centrifuge.error_motion.c_r_m_s2),
                    ("k1_rad_s_g", piga.k1_rad_s_g),
                    ("k2_rad_s_g2", piga.k2_rad_s_g2),
                ],
            });
        }
    }
    Ok(RatePoint {
        rate_rad_s,
        output_rad_s,
        a_x_g,
        omega_i_rad_s,
    })
}
