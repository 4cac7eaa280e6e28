//! The transform chain of eq. 5, 8–11 and its evaluation.

use core::f64::consts::PI;

use crate::error::Result;
use crate::error_motion::SpindleOffsets;
use crate::frames::{Ground, Piga, Sleeve, Spindle, Transform};
use crate::homogeneous::{Axis, Homogeneous};
use crate::inputs::PigaInputs;
use crate::jet::{Jet, Scalar};
use crate::quadrature::RevolutionQuadrature;
use crate::site::{Centrifuge, Site};
use units::finite;

/// Highest harmonic of the spindle angle `ωt` in every component of [`PigaInputs`] for the
/// chain of eq. 5 with constant error motion.
///
/// Why: `A = Rot(z, ωt)·M` and `D = Rot(z, ωt)·p` with `M`, `p` constant, so `Aᵀ D̈`, `Aᵀ ẑ`
/// and `Aᵀ(Ω_z ẑ × Ḋ)` do not depend on t, while the horizontal Earth-rate terms
/// `Aᵀ(Ω_y ŷ × Ḋ)` and `Aᵀ Ω_y ŷ` contain `Rot(z, ωt)ᵀ ŷ`, a first harmonic.
pub const INPUT_HIGHEST_HARMONIC: usize = 1;

/// Eq. 5: `T₂¹ = Rot(z₁, θ)·Trans(Δr_x, Δr_y, 0)·Rot(x₂, Δφ_x)·Rot(y₂, Δφ_y)`, the spindle in the
/// sleeve at spindle angle θ = ωt, over any [`Scalar`] (use a [`Jet`] angle to obtain time
/// derivatives).
///
/// ```
/// use approx::assert_relative_eq;
/// use kinematics::{spindle_transform, SpindleOffsets};
/// let off = SpindleOffsets { dr_x_m: 1e-5, ..SpindleOffsets::default() };
/// let t21 = spindle_transform(std::f64::consts::FRAC_PI_2, &off);
/// // the drift along X2 has turned with the spindle to +Y1
/// assert_relative_eq!(t21.homogeneous().translation()[1], 1e-5, max_relative = 1e-12);
/// ```
#[must_use]
pub fn spindle_transform<S: Scalar>(
    theta_rad: S,
    offsets: &SpindleOffsets,
) -> Transform<Sleeve, Spindle, S> {
    let c = S::constant;
    Transform::from_homogeneous(
        Homogeneous::rot(Axis::Z, theta_rad)
            * Homogeneous::trans(c(offsets.dr_x_m), c(offsets.dr_y_m), c(0.0))
            * Homogeneous::rot(Axis::X, c(offsets.dphi_x_rad))
            * Homogeneous::rot(Axis::Y, c(offsets.dphi_y_rad)),
    )
}

/// Eq. 10: `T₃² = Trans(R, 0, 0)·Rot(z₂, 180°)`, the PIGA on the spindle with its input axis
/// pointing at the spindle axis.
#[must_use]
pub fn piga_mount<S: Scalar>(radius_m: S) -> Transform<Spindle, Piga, S> {
    let z = S::constant(0.0);
    Transform::from_homogeneous(
        Homogeneous::trans(radius_m, z, z) * Homogeneous::rot(Axis::Z, S::constant(PI)),
    )
}

/// The chain of a [`Centrifuge`] turning at one constant rate.
///
/// ```
/// use approx::assert_relative_eq;
/// use kinematics::{Centrifuge, Chain, ErrorMotion, Site, EARTH_RATE_RAD_S};
/// let c = Centrifuge {
///     radius_m: 2.5,
///     site: Site {
///         latitude_deg: 45.0,
///         earth_rate_rad_s: EARTH_RATE_RAD_S,
///         gravity_m_s2: 9.8,
///     }
///     .validated().unwrap(),
///     error_motion: ErrorMotion { dr_xs_m: 5e-6, dphi_ys_rad: 2e-6, ..ErrorMotion::ZERO },
/// };
/// let w = 100.0_f64.to_radians();
/// let chain = Chain::new(&c, w).unwrap();
/// let mean = chain.mean_inputs(3).unwrap();
/// let fo = chain.first_order();
/// // eq. 14 plus the Coriolis term, to second order in the error motion
/// assert_relative_eq!(mean.a_x_g(), fo.a_x_g + fo.coriolis_a_x_g, max_relative = 1e-10);
/// assert_relative_eq!(mean.omega_i_rad_s(), fo.omega_i_rad_s, max_relative = 1e-4);
/// assert_relative_eq!(
///     mean.omega_i_rad_s(), fo.omega_i_rad_s + fo.earth_omega_i_rad_s, max_relative = 1e-10
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
    radius_m: f64,
    rate_rad_s: f64,
    offsets: SpindleOffsets,
    site: Site,
}

impl Chain {
    /// The chain at rate `rate_rad_s` (any sign; zero means standing still).
    ///
    /// # Errors
    /// As [`Centrifuge::validate`], [`crate::KinematicsError::NonFinite`] for the rate, and
    /// [`crate::KinematicsError::NonFiniteResult`] for a spindle offset that overflows at this
    /// rate.
    pub fn new(centrifuge: &Centrifuge, rate_rad_s: f64) -> Result<Self> {
        centrifuge.validate()?;
        finite("rate_rad_s", rate_rad_s)?;
        let offsets = centrifuge.error_motion.offsets_at(rate_rad_s);
        for (quantity, value) in [
            ("dr_x_m", offsets.dr_x_m),
            ("dr_y_m", offsets.dr_y_m),
            ("dphi_x_rad", offsets.dphi_x_rad),
            ("dphi_y_rad", offsets.dphi_y_rad),
        ] {
            if !value.is_finite() {
                return Err(crate::KinematicsError::NonFiniteResult {
                    quantity,
                    value,
                    rate_rad_s,
                });
            }
        }
        Ok(Self {
            radius_m: centrifuge.radius_m,
            rate_rad_s,
            offsets,
            site: centrifuge.site,
        })
    }

    /// Static working radius R, m.
    #[must_use]
    pub const fn radius_m(&self) -> f64 {
        self.radius_m
    }

    /// Spindle rate ω, rad/s.
    #[must_use]
    pub const fn rate_rad_s(&self) -> f64 {
        self.rate_rad_s
    }

    /// Total drift and tilt at this rate.
    #[must_use]
    pub const fn offsets(&self) -> &SpindleOffsets {
        &self.offsets
    }

    /// The site.
    #[must_use]
    pub const fn site(&self) -> &Site {
        &self.site
    }

    /// Period of one revolution, s (`None` at zero rate).
    #[must_use]
    pub fn period_s(&self) -> Option<f64> {
        (self.rate_rad_s != 0.0).then(|| 2.0 * PI / self.rate_rad_s.abs())
    }

    /// `T₁⁰`: the sleeve in the ground frame; the paper's frames coincide (identity).
    #[must_use]
    pub fn sleeve_in_ground(&self) -> Transform<Ground, Sleeve> {
        Transform::identity()
    }

    /// `T₂¹(t)` of eq. 5.
    #[must_use]
    pub fn spindle_in_sleeve(&self, t_s: f64) -> Transform<Sleeve, Spindle> {
        spindle_transform(self.rate_rad_s * t_s, &self.offsets)
    }

    /// `T₃²` of eq. 10.
    #[must_use]
    pub fn piga_in_spindle(&self) -> Transform<Spindle, Piga> {
        piga_mount(self.radius_m)
    }

    /// `T₃⁰(t) = T₁⁰·T₂¹(t)·T₃²` of eq. 11.
    #[must_use]
    pub fn piga_in_ground(&self, t_s: f64) -> Transform<Ground, Piga> {
        self.sleeve_in_ground() * self.spindle_in_sleeve(t_s) * self.piga_in_spindle()
    }

    /// `T₃⁰(t)` with exact first and second time derivatives in every entry.
    #[must_use]
    pub fn piga_in_ground_jet(&self, t_s: f64) -> Transform<Ground, Piga, Jet> {
        let theta = Jet::new(self.rate_rad_s * t_s, self.rate_rad_s, 0.0);
        Transform::<Ground, Sleeve, Jet>::identity()
            * spindle_transform(theta, &self.offsets)
            * piga_mount(Jet::constant(self.radius_m))
    }

    /// The same spindle pose written in the sleeve frame (eq. 8), with the primed
    /// coefficients of the corrected eq. 9.
    #[must_use]
    pub fn sleeve_frame_motion(&self, t_s: f64) -> SleeveFrameMotion {
        SleeveFrameMotion::exact(&self.offsets, self.rate_rad_s * t_s)
    }

    /// The PIGA's inputs at time `t_s` (eq. 12, 13), exact.
    #[must_use]
    pub fn inputs_at(&self, t_s: f64) -> PigaInputs {
        PigaInputs::from_pose_jet(&self.piga_in_ground_jet(t_s), &self.site)
    }

    /// The PIGA's inputs averaged over one whole revolution with the uniform `points`-node
    /// rule, exact for the content of the chain (see [`INPUT_HIGHEST_HARMONIC`]).
    ///
    /// # Errors
    /// [`crate::KinematicsError::TooFewQuadraturePoints`] when `points < 2·INPUT_HIGHEST_HARMONIC + 1`.
    pub fn mean_inputs(&self, points: usize) -> Result<PigaInputs> {
        let q = RevolutionQuadrature::new(points, INPUT_HIGHEST_HARMONIC)?;
        Ok(PigaInputs::from_array(q.mean_array(self.rate_rad_s, |t| {
            self.inputs_at(t).to_array()
        })))
    }

    /// The paper's first-order result (eq. 14), plus the Coriolis term it drops.
    #[must_use]
    pub fn first_order(&self) -> FirstOrderInputs {
        let w = self.rate_rad_s;
        let g = self.site.gravity_m_s2;
        let r = self.radius_m + self.offsets.dr_x_m;
        FirstOrderInputs {
            a_x_g: r * w * w / g + self.offsets.dphi_y_rad,
            omega_i_rad_s: self.offsets.dphi_y_rad * w,
            coriolis_a_x_g: 2.0 * r * w * self.site.earth_rate_vertical_rad_s() / g,
            earth_omega_i_rad_s: self.offsets.dphi_y_rad * self.site.earth_rate_vertical_rad_s(),
        }
    }
}

/// The first-order inputs of eq. 14.
///
/// ```text
/// a_x = (R + Δr_x)·ω²/g + Δφ_y,    ω_I = Δφ_y·ω
/// ```
///
/// and, separately, the two mean Earth-rate terms that eq. 14 omits: the Coriolis specific
/// force `2(R + Δr_x)·ω·ω_ie sin L / g` along IA (NOTES.md, item 4) and the vertical Earth
/// rate seen through the tilt, `Δφ_y·ω_ie sin L`. The exact means differ from
/// `a_x + coriolis_a_x_g` and `omega_i + earth_omega_i` by terms quadratic in the error motion.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FirstOrderInputs {
    /// Eq. 14 specific force along IA, g.
    pub a_x_g: f64,
    /// Eq. 14 angular rate about IA, rad/s.
    pub omega_i_rad_s: f64,
    /// Mean Coriolis specific force along IA, g (not in eq. 14).
    pub coriolis_a_x_g: f64,
    /// Mean vertical Earth rate about IA through the tilt, rad/s (not in eq. 14).
    pub earth_omega_i_rad_s: f64,
}

/// The spindle pose in the sleeve-frame form of eq. 8:
/// `T₂¹ = Trans(Δr'_x, Δr'_y, 0)·Rot(x₁, Δφ'_x)·Rot(y₁, Δφ'_y)·Rot(z₁, θ + γ)`.
///
/// The primed drifts are the corrected eq. 9 (a plane rotation of the spindle-frame drift):
///
/// ```text
/// Δr'_x = Δr_x·cos θ − Δr_y·sin θ,    Δr'_y = Δr_x·sin θ + Δr_y·cos θ
/// ```
///
/// and to first order the tilts transform alike. To make eq. 8 *exactly* equal to eq. 5 the
/// primed tilts are taken from the direction of the spindle axis and a twist γ about it,
/// of second order in the tilts, is carried; the paper's eq. 8 omits it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SleeveFrameMotion {
    /// Spindle angle θ = ωt, rad.
    pub spindle_angle_rad: f64,
    /// Δr'_x: drift along `X1`, m.
    pub dr_x_m: f64,
    /// Δr'_y: drift along `Y1`, m.
    pub dr_y_m: f64,
    /// Δφ'_x: tilt about `X1`, rad.
    pub dphi_x_rad: f64,
    /// Δφ'_y: tilt about `Y1`, rad.
    pub dphi_y_rad: f64,
    /// Residual twist γ about the spindle axis, rad (zero in the first-order form).
    pub twist_rad: f64,
}

impl SleeveFrameMotion {
    /// Primed coefficients for which eq. 8 reproduces eq. 5 exactly at angle `theta_rad`.
    #[must_use]
    pub fn exact(offsets: &SpindleOffsets, theta_rad: f64) -> Self {
        let (s, c) = theta_rad.sin_cos();
        let (dx, dy) = (offsets.dr_x_m, offsets.dr_y_m);
        // direction of the spindle axis Z2 in O1: Rot(z,θ)·Rot(x,a)·Rot(y,b)·ẑ
        let (sa, ca) = offsets.dphi_x_rad.sin_cos();
        let (sb, cb) = offsets.dphi_y_rad.sin_cos();
        let n0 = [sb, -sa * cb, ca * cb];
        let n = [c * n0[0] - s * n0[1], s * n0[0] + c * n0[1], n0[2]];
        // Rot(x,a')·Rot(y,b')·ẑ = (sin b', −sin a' cos b', cos a' cos b')
        let b1 = n[0].clamp(-1.0, 1.0).asin();
        let a1 = (-n[1]).atan2(n[2]);
        // remaining rotation about ẑ: (Rot(x,a')Rot(y,b'))ᵀ · Rot(z,θ)Rot(x,a)Rot(y,b)
        let tilt = Homogeneous::rot(Axis::X, a1) * Homogeneous::rot(Axis::Y, b1);
        let full = Homogeneous::rot(Axis::Z, theta_rad)
            * Homogeneous::rot(Axis::X, offsets.dphi_x_rad)
            * Homogeneous::rot(Axis::Y, offsets.dphi_y_rad);
        let rem = (tilt.inverse() * full).rotation();
        let psi = rem[1][0].atan2(rem[0][0]);
        let twist = (psi - theta_rad + PI).rem_euclid(2.0 * PI) - PI;
        Self {
            spindle_angle_rad: theta_rad,
            dr_x_m: dx * c - dy * s,
            dr_y_m: dx * s + dy * c,
            dphi_x_rad: a1,
            dphi_y_rad: b1,
            twist_rad: twist,
        }
    }

    /// The first-order form: eq. 9 (corrected) for the drifts and the same plane rotation for
    /// the tilts, no twist.
    #[must_use]
    pub fn first_order(offsets: &SpindleOffsets, theta_rad: f64) -> Self {
        let (s, c) = theta_rad.sin_cos();
        let rot = |x: f64, y: f64| (x * c - y * s, x * s + y * c);
        let (dr_x_m, dr_y_m) = rot(offsets.dr_x_m, offsets.dr_y_m);
        let (dphi_x_rad, dphi_y_rad) = rot(offsets.dphi_x_rad, offsets.dphi_y_rad);
        Self {
            spindle_angle_rad: theta_rad,
            dr_x_m,
            dr_y_m,
            dphi_x_rad,
            dphi_y_rad,
            twist_rad: 0.0,
        }
    }

    /// Eq. 8 as a transform.
    #[must_use]
    pub fn transform(&self) -> Transform<Sleeve, Spindle> {
        Transform::from_homogeneous(
            Homogeneous::trans(self.dr_x_m, self.dr_y_m, 0.0)
                * Homogeneous::rot(Axis::X, self.dphi_x_rad)
                * Homogeneous::rot(Axis::Y, self.dphi_y_rad)
                * Homogeneous::rot(Axis::Z, self.spindle_angle_rad + self.twist_rad),
        )
    }
}
