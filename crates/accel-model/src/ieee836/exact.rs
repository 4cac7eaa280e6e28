//! A mounting on the exact chain of `kinematics` (eq. 5–13): the specific force along IA,
//! PA and OA and the rate about IA at any instant, and the model's output averaged over
//! whole revolutions — what a simulator writes and a fit's truth is.
//!
//! The mount of eq. 10 becomes `T₃² = Trans(R + C_a·ω², 0, 0)·[IA PA OA]`: the case axes of
//! the mounting as the rotation block, its own static radius, and the arm's stretch `C_a`
//! that grows the radius at the accelerometer beyond the spindle's own motion (which the
//! probe on the sleeve does not see). For IA in with no stretch it is eq. 10.

use kinematics::{
    Centrifuge, Chain, Ground, Homogeneous, Jet, Piga, PigaInputs, RevolutionQuadrature, Scalar,
    Sleeve, Spindle, Transform, spindle_transform,
};

use super::mounting::CaseAxes;
use super::terms::ModelCoefficients;
use crate::error::{AccelModelError, Result};

/// Nodes per revolution of the mean output: exact for every polynomial term (the inputs hold
/// the first harmonic only, a quartic the fourth, which 9 nodes integrate exactly); the
/// odd-quadratic `a_i·|a_i|` is not a polynomial when `a_i` changes sign within a revolution
/// (IA across the arm), and 64 nodes take its mean to far below any noise there.
pub const NODES_PER_REVOLUTION: usize = 64;

/// The spindle and arm a mounting sits on: the centrifuge (site, error motion; its radius is
/// not used, each mounting has its own) and the arm stretch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountedSpindle {
    /// The centrifuge: the site (g, latitude, Earth rate) and the spindle's error motion.
    pub centrifuge: Centrifuge,
    /// Arm stretch `C_a`, m·s²: the radius at the accelerometer grows by `C_a·ω²`.
    pub arm_stretch_m_s2: f64,
}

/// The inputs along the case axes at one instant (or averaged).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CaseInputs {
    /// Specific force along IA, PA, OA, g.
    pub a_g: [f64; 3],
    /// Rate of the case about IA relative to inertial space, rad/s.
    pub omega_i_rad_s: f64,
}

impl CaseInputs {
    /// The case-axis components of the inputs of eq. 12–13 (`O3`'s axes are IA, PA, OA).
    #[must_use]
    pub fn of(inputs: &PigaInputs) -> Self {
        Self {
            a_g: inputs.specific_force_g(),
            omega_i_rad_s: inputs.angular_rate_rad_s[0],
        }
    }
}

/// One rate of one mounting: the output and the inputs, each averaged over a whole
/// revolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountedPoint {
    /// Spindle rate ω, rad/s.
    pub rate_rad_s: f64,
    /// Mean output (no noise), in the kind's unit.
    pub output: f64,
    /// Mean inputs.
    pub inputs: CaseInputs,
}

fn mount_transform(axes: &CaseAxes, radius_m: f64) -> Transform<Spindle, Piga, Jet> {
    let c = Jet::constant;
    let r = axes.rotation().map(|row| row.map(c));
    Transform::from_homogeneous(Homogeneous::from_parts(r, [c(radius_m), c(0.0), c(0.0)]))
}

fn inputs_at(chain: &Chain, mount: &Transform<Spindle, Piga, Jet>, t_s: f64) -> CaseInputs {
    let w = chain.rate_rad_s();
    let theta = Jet::new(w * t_s, w, 0.0);
    let pose = Transform::<Ground, Sleeve, Jet>::identity()
        * spindle_transform(theta, chain.offsets())
        * *mount;
    CaseInputs::of(&PigaInputs::from_pose_jet(&pose, chain.site()))
}

/// The model's mean output over a whole revolution of a mounting (true axes `axes`, static
/// radius `radius_m`, the bias shifted by `bias_shift` on this mounting) at `rate_rad_s`, and
/// the mean inputs.
///
/// ```
/// use accel_model::{AccelKind, ModelCoefficients, MountedSpindle, MountingPreset, Term, mounted_point};
/// use kinematics::{Centrifuge, ErrorMotion, Site, EARTH_RATE_RAD_S};
/// let site = Site { latitude_deg: 40.0, earth_rate_rad_s: EARTH_RATE_RAD_S, gravity_m_s2: 9.8 };
/// let spindle = MountedSpindle {
///     centrifuge: Centrifuge { radius_m: 2.5, site, error_motion: ErrorMotion::ZERO },
///     arm_stretch_m_s2: 0.0,
/// };
/// let mut c = ModelCoefficients::zero(AccelKind::Piga);
/// c.set(Term::K1, 0.56);
/// let w = 2.0;
/// let axial = mounted_point(&spindle, &c, &MountingPreset::IaAxial.axes(), 2.5, 0.0, w)?;
/// // IA along the spindle axis: 1 g along IA, and the PIGA's −ω_i reads the spindle's rate
/// let earth = EARTH_RATE_RAD_S * 40.0_f64.to_radians().sin();
/// assert!((axial.output - (0.56 - (w + earth))).abs() < 1e-12);
/// # Ok::<(), accel_model::AccelModelError>(())
/// ```
///
/// # Errors
/// As `kinematics::Chain::new`; [`AccelModelError::NonFinite`] for a coefficient, the
/// radius, the stretch or the bias shift; [`AccelModelError::NotACaseFrame`];
/// [`AccelModelError::NonFiniteResult`] for a result out of range.
pub fn mounted_point(
    spindle: &MountedSpindle,
    coefficients: &ModelCoefficients,
    axes: &CaseAxes,
    radius_m: f64,
    bias_shift: f64,
    rate_rad_s: f64,
) -> Result<MountedPoint> {
    coefficients.validate()?;
    axes.validate()?;
    for (field, value) in [
        ("radius_m", radius_m),
        ("arm_stretch_m_s2", spindle.arm_stretch_m_s2),
        ("bias_shift", bias_shift),
    ] {
        if !value.is_finite() {
            return Err(AccelModelError::NonFinite { field, value });
        }
    }
    let chain = Chain::new(&spindle.centrifuge, rate_rad_s)?;
    let mount = mount_transform(
        axes,
        radius_m + spindle.arm_stretch_m_s2 * rate_rad_s * rate_rad_s,
    );
    let q = RevolutionQuadrature::new(NODES_PER_REVOLUTION, 4)?;
    let [output, a_i, a_p, a_o, omega_i] = q.mean_array(rate_rad_s, |t| {
        let i = inputs_at(&chain, &mount, t);
        let [a, p, o] = i.a_g;
        [
            coefficients.output(i.a_g, i.omega_i_rad_s),
            a,
            p,
            o,
            i.omega_i_rad_s,
        ]
    });
    let output = output + bias_shift;
    for (quantity, value) in [
        ("output", output),
        ("a_i_g", a_i),
        ("a_p_g", a_p),
        ("a_o_g", a_o),
        ("omega_i_rad_s", omega_i),
    ] {
        if !value.is_finite() {
            return Err(AccelModelError::NonFiniteResult {
                quantity,
                value,
                inputs: vec![
                    ("rate_rad_s", rate_rad_s),
                    ("radius_m", radius_m),
                    ("gravity_m_s2", spindle.centrifuge.site.gravity_m_s2),
                ],
            });
        }
    }
    Ok(MountedPoint {
        rate_rad_s,
        output,
        inputs: CaseInputs {
            a_g: [a_i, a_p, a_o],
            omega_i_rad_s: omega_i,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ieee836::{AccelKind, MountingPreset, Term};
    use crate::{PigaCoefficients, rate_point};
    use kinematics::{EARTH_RATE_RAD_S, ErrorMotion, Site};

    /// Eq. 15 is the model's special case: a PIGA with k0…k3 mounted IA in gives
    /// `accel_model::rate_point`'s mean output on a spindle with error motion.
    #[test]
    fn eq15_is_the_piga_mounted_ia_in() {
        let centrifuge = Centrifuge {
            radius_m: 2.5,
            site: Site {
                latitude_deg: 39.9,
                earth_rate_rad_s: EARTH_RATE_RAD_S,
                gravity_m_s2: 9.8,
            },
            error_motion: ErrorMotion {
                dr_xs_m: 5.6e-6,
                dphi_ys_rad: 3e-6,
                c_r_m_s2: 1.6e-6,
                c_phi_s2: 2e-8,
                ..ErrorMotion::ZERO
            },
        };
        let piga = PigaCoefficients {
            k0_rad_s: 1e-5,
            k1_rad_s_g: 0.56,
            k2_rad_s_g2: 5e-7,
            k3_rad_s_g3: 2e-8,
        };
        let mut c = ModelCoefficients::zero(AccelKind::Piga);
        c.set(Term::K0, piga.k0_rad_s);
        c.set(Term::K1, piga.k1_rad_s_g);
        c.set(Term::K2, piga.k2_rad_s_g2);
        c.set(Term::K3, piga.k3_rad_s_g3);
        let spindle = MountedSpindle {
            centrifuge,
            arm_stretch_m_s2: 0.0,
        };
        for deg in [20.0_f64, 90.0, 200.0] {
            let w = deg.to_radians();
            let general =
                mounted_point(&spindle, &c, &MountingPreset::IaIn.axes(), 2.5, 0.0, w).unwrap();
            let eq15 = rate_point(&centrifuge, &piga, w).unwrap();
            assert!(
                (general.output - eq15.output_rad_s).abs() <= 1e-15 * eq15.output_rad_s.abs(),
                "{deg}: {} against {}",
                general.output,
                eq15.output_rad_s
            );
            assert!((general.inputs.a_g[0] - eq15.a_x_g).abs() <= 1e-15 * eq15.a_x_g);
        }
    }
}
