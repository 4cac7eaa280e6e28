//! Spindle error motion: static and dynamic (∝ ω²) first-harmonic drift and tilt (eq. 1–7, 16).

use crate::error::Result;
use units::{finite, positive};

/// The spindle error motion of eq. 5 and 16 as coefficients in the spindle frame `O2`.
///
/// At rate ω the drift and tilt of the spindle, expressed along `X2`, `Y2`, are
///
/// ```text
/// Δr_x = Δr_xs + C_r·ω²,      Δr_y = Δr_ys + C_ry·ω²
/// Δφ_x = Δφ_xs + C_φx·ω²,     Δφ_y = Δφ_ys + C_φ·ω²
/// ```
///
/// (the paper names only `C_r` and `C_φ`, eq. 16; the other-axis coefficients complete the
/// vector). The parts are constant in `O2`, so in the sleeve frame they are first harmonics of
/// `ωt` (eq. 9). Every field defaults to zero in a scenario file.
///
/// ```
/// use approx::assert_relative_eq;
/// use kinematics::ErrorMotion;
/// let e = ErrorMotion { dr_xs_m: 5.6e-6, c_r_m_s2: -4.05e-8, ..ErrorMotion::default() };
/// let w = 200.0_f64.to_radians();
/// assert_relative_eq!(e.offsets_at(w).dr_x_m, 5.6e-6 - 4.05e-8 * w * w, max_relative = 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct ErrorMotion {
    /// Static drift along `X2` (towards the PIGA), Δr_xs, m.
    pub dr_xs_m: f64,
    /// Static drift along `Y2`, Δr_ys, m.
    pub dr_ys_m: f64,
    /// Static tilt about `X2`, Δφ_xs, rad.
    pub dphi_xs_rad: f64,
    /// Static tilt about `Y2`, Δφ_ys, rad.
    pub dphi_ys_rad: f64,
    /// `C_r`: dynamic drift along `X2` per ω², Δr_xd = C_r ω², m·s².
    pub c_r_m_s2: f64,
    /// `C_ry`: dynamic drift along `Y2` per ω², Δr_yd = C_ry ω², m·s².
    pub c_r_y_m_s2: f64,
    /// `C_φx`: dynamic tilt about `X2` per ω², Δφ_xd = C_φx ω², s² (rad per (rad/s)²).
    pub c_phi_x_s2: f64,
    /// `C_φ`: dynamic tilt about `Y2` per ω², Δφ_yd = C_φ ω², s² (rad per (rad/s)²).
    pub c_phi_s2: f64,
}

impl ErrorMotion {
    /// No error motion at all (ideal spindle).
    pub const ZERO: Self = Self {
        dr_xs_m: 0.0,
        dr_ys_m: 0.0,
        dphi_xs_rad: 0.0,
        dphi_ys_rad: 0.0,
        c_r_m_s2: 0.0,
        c_r_y_m_s2: 0.0,
        c_phi_x_s2: 0.0,
        c_phi_s2: 0.0,
    };

    /// Checks that every coefficient is finite.
    ///
    /// # Errors
    /// [`crate::KinematicsError::NonFinite`] naming the first bad field.
    pub fn validate(&self) -> Result<()> {
        finite("dr_xs_m", self.dr_xs_m)?;
        finite("dr_ys_m", self.dr_ys_m)?;
        finite("dphi_xs_rad", self.dphi_xs_rad)?;
        finite("dphi_ys_rad", self.dphi_ys_rad)?;
        finite("c_r_m_s2", self.c_r_m_s2)?;
        finite("c_r_y_m_s2", self.c_r_y_m_s2)?;
        finite("c_phi_x_s2", self.c_phi_x_s2)?;
        finite("c_phi_s2", self.c_phi_s2)?;
        Ok(())
    }

    /// The total drift and tilt of eq. 5 at rate `rate_rad_s`.
    #[must_use]
    pub fn offsets_at(&self, rate_rad_s: f64) -> SpindleOffsets {
        let w2 = rate_rad_s * rate_rad_s;
        SpindleOffsets {
            dr_x_m: self.dr_xs_m + self.c_r_m_s2 * w2,
            dr_y_m: self.dr_ys_m + self.c_r_y_m_s2 * w2,
            dphi_x_rad: self.dphi_xs_rad + self.c_phi_x_s2 * w2,
            dphi_y_rad: self.dphi_ys_rad + self.c_phi_s2 * w2,
        }
    }

    /// Every coefficient multiplied by `factor` (for order-of-magnitude studies).
    #[must_use]
    pub fn scaled(&self, factor: f64) -> Self {
        Self {
            dr_xs_m: self.dr_xs_m * factor,
            dr_ys_m: self.dr_ys_m * factor,
            dphi_xs_rad: self.dphi_xs_rad * factor,
            dphi_ys_rad: self.dphi_ys_rad * factor,
            c_r_m_s2: self.c_r_m_s2 * factor,
            c_r_y_m_s2: self.c_r_y_m_s2 * factor,
            c_phi_x_s2: self.c_phi_x_s2 * factor,
            c_phi_s2: self.c_phi_s2 * factor,
        }
    }

    /// Builds the coefficients from a physical imbalance (eq. 1–4), composing the static and
    /// dynamic parts as vectors in `O2`.
    ///
    /// A drift of magnitude ΔR towards azimuth α (from `X2` towards `Y2`) has components
    /// `(ΔR cos α, ΔR sin α)`. A tilt of magnitude Δθ that leans the top of the spindle towards
    /// azimuth α is the small rotation about the horizontal axis `(−sin α, cos α)`, i.e.
    /// `Δφ_x = −Δθ sin α`, `Δφ_y = Δθ cos α` (with `Rot(y, b)` leaning `Z` towards `+X`).
    ///
    /// ```
    /// use approx::assert_relative_eq;
    /// use kinematics::{ErrorMotion, PhysicalImbalance};
    /// let p = PhysicalImbalance {
    ///     mass_kg: 0.2, mass_radius_m: 0.5, arm_m: 0.3, imbalance_azimuth_deg: 0.0,
    ///     radial_stiffness_n_m: 2.0e9, angular_stiffness_n_m_rad: 1.0e9,
    ///     ..PhysicalImbalance::default()
    /// };
    /// let e = ErrorMotion::from_physical(&p).unwrap();
    /// assert_relative_eq!(e.c_r_m_s2, 0.5 * 0.2 / 2.0e9, max_relative = 1e-15);        // eq. 1
    /// assert_relative_eq!(e.c_phi_s2, 0.5 * 0.2 * 0.3 / 1.0e9, max_relative = 1e-15);  // eq. 2
    /// ```
    ///
    /// # Errors
    /// [`crate::KinematicsError::NonFinite`] for a non-finite field, [`crate::KinematicsError::NotPositive`] for a
    /// stiffness that is not strictly positive.
    pub fn from_physical(p: &PhysicalImbalance) -> Result<Self> {
        p.validate()?;
        let (sa, ca) = p.imbalance_azimuth_deg.to_radians().sin_cos();
        let (sf, cf) = p.static_force_azimuth_deg.to_radians().sin_cos();
        let (sm, cm) = p.static_tilt_azimuth_deg.to_radians().sin_cos();
        // eq. 1 and 2 per unit ω²
        let drift_per_w2 = p.mass_radius_m * p.mass_kg / p.radial_stiffness_n_m;
        let tilt_per_w2 = p.mass_radius_m * p.mass_kg * p.arm_m / p.angular_stiffness_n_m_rad;
        // eq. 3 and 4
        let drift_s = p.static_force_n / p.radial_stiffness_n_m;
        let tilt_s = p.static_moment_n_m / p.angular_stiffness_n_m_rad;
        let mut e = Self {
            dr_xs_m: drift_s * cf,
            dr_ys_m: drift_s * sf,
            dphi_xs_rad: -tilt_s * sm,
            dphi_ys_rad: tilt_s * cm,
            c_r_m_s2: drift_per_w2 * ca,
            c_r_y_m_s2: drift_per_w2 * sa,
            c_phi_x_s2: -tilt_per_w2 * sa,
            c_phi_s2: tilt_per_w2 * ca,
        };
        // further masses (trial weights, corrections) add as vectors (eq. 1–2 each)
        for m in &p.masses {
            let (s, c) = m.azimuth_deg.to_radians().sin_cos();
            let drift = m.radius_m * m.mass_kg / p.radial_stiffness_n_m;
            let tilt = m.radius_m * m.mass_kg * m.arm_m / p.angular_stiffness_n_m_rad;
            e.c_r_m_s2 += drift * c;
            e.c_r_y_m_s2 += drift * s;
            e.c_phi_x_s2 -= tilt * s;
            e.c_phi_s2 += tilt * c;
        }
        e.validate()?;
        Ok(e)
    }
}

/// One imbalance mass of a [`PhysicalImbalance`]'s list (a trial weight, a correction).
///
/// In RON: `(mass_kg: 0.5, radius_m: 1.2, azimuth_deg: 90.0, arm_m: 0.0)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ImbalanceMass {
    /// Mass, kg.
    pub mass_kg: f64,
    /// Distance from the spindle axis, m.
    pub radius_m: f64,
    /// Azimuth in `O2` from `X2` towards `Y2`, degrees.
    pub azimuth_deg: f64,
    /// Lever arm relative to the rotor's centre of mass, m (as [`PhysicalImbalance::arm_m`]).
    /// The tilt it gives turns the axis about the chain's `O2` origin, in the PIGA plane, so
    /// the balance advisor reads the arm as a height above the PIGA plane
    /// (`docs/BALANCING.md`: both stiffnesses about the PIGA plane).
    #[cfg_attr(feature = "serde", serde(default))]
    pub arm_m: f64,
}

/// A physical description of the spindle's imbalance and stiffness (eq. 1–4).
///
/// Azimuths are measured in `O2` from `X2` (towards the PIGA) towards `Y2`.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct PhysicalImbalance {
    /// Equivalent imbalance mass m, kg.
    pub mass_kg: f64,
    /// Distance R_cm of the imbalance mass from the spindle axis, m.
    pub mass_radius_m: f64,
    /// Equivalent lever arm l of the imbalance relative to the rotor's centre of mass, m;
    /// positive when the imbalance plane lies above (+Z) it, so that the spindle leans towards
    /// the imbalance.
    pub arm_m: f64,
    /// Azimuth of the imbalance mass, degrees.
    pub imbalance_azimuth_deg: f64,
    /// Radial stiffness k_r of the spindle bearing, N/m.
    pub radial_stiffness_n_m: f64,
    /// Angular stiffness k_θ of the spindle bearing, N·m/rad.
    pub angular_stiffness_n_m_rad: f64,
    /// Equivalent static force F_s (eq. 3), N.
    pub static_force_n: f64,
    /// Azimuth of the static force, degrees.
    pub static_force_azimuth_deg: f64,
    /// Equivalent static moment M_s (eq. 4), N·m.
    pub static_moment_n_m: f64,
    /// Azimuth towards which the static moment leans the spindle, degrees.
    pub static_tilt_azimuth_deg: f64,
    /// Further imbalance masses (trial weights, corrections), each added as a vector to the
    /// single mass above through eq. 1–2 with the same stiffnesses. Default: none.
    pub masses: Vec<ImbalanceMass>,
}

impl Default for PhysicalImbalance {
    /// No imbalance, no static load, unit stiffnesses (so that the default is valid).
    fn default() -> Self {
        Self {
            mass_kg: 0.0,
            mass_radius_m: 0.0,
            arm_m: 0.0,
            imbalance_azimuth_deg: 0.0,
            radial_stiffness_n_m: 1.0,
            angular_stiffness_n_m_rad: 1.0,
            static_force_n: 0.0,
            static_force_azimuth_deg: 0.0,
            static_moment_n_m: 0.0,
            static_tilt_azimuth_deg: 0.0,
            masses: Vec::new(),
        }
    }
}

impl PhysicalImbalance {
    /// Checks finiteness of every field and positivity of the stiffnesses.
    ///
    /// # Errors
    /// [`crate::KinematicsError::NonFinite`] or [`crate::KinematicsError::NotPositive`] naming the field.
    pub fn validate(&self) -> Result<()> {
        finite("mass_kg", self.mass_kg)?;
        finite("mass_radius_m", self.mass_radius_m)?;
        finite("arm_m", self.arm_m)?;
        finite("imbalance_azimuth_deg", self.imbalance_azimuth_deg)?;
        positive("radial_stiffness_n_m", self.radial_stiffness_n_m)?;
        positive("angular_stiffness_n_m_rad", self.angular_stiffness_n_m_rad)?;
        finite("static_force_n", self.static_force_n)?;
        finite("static_force_azimuth_deg", self.static_force_azimuth_deg)?;
        finite("static_moment_n_m", self.static_moment_n_m)?;
        finite("static_tilt_azimuth_deg", self.static_tilt_azimuth_deg)?;
        for m in &self.masses {
            finite("masses[].mass_kg", m.mass_kg)?;
            finite("masses[].radius_m", m.radius_m)?;
            finite("masses[].azimuth_deg", m.azimuth_deg)?;
            finite("masses[].arm_m", m.arm_m)?;
        }
        Ok(())
    }
}

/// How a scenario file describes the spindle error motion: directly by coefficients, or by
/// a physical imbalance.
///
/// In RON: `Coefficients((dr_xs_m: 5.6e-6, c_r_m_s2: -4.05e-8))` or
/// `Physical((mass_kg: 0.2, mass_radius_m: 0.5, radial_stiffness_n_m: 2e9))`.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ErrorMotionSpec {
    /// Coefficients of eq. 5 / 16 in `O2`.
    Coefficients(ErrorMotion),
    /// Physical imbalance of eq. 1–4.
    Physical(PhysicalImbalance),
}

impl ErrorMotionSpec {
    /// The coefficients this specification stands for.
    ///
    /// # Errors
    /// As [`ErrorMotion::validate`] and [`ErrorMotion::from_physical`].
    pub fn resolve(&self) -> Result<ErrorMotion> {
        match self {
            Self::Coefficients(e) => {
                e.validate()?;
                Ok(*e)
            }
            Self::Physical(p) => ErrorMotion::from_physical(p),
        }
    }
}

/// Total drift and tilt of the spindle at one rate, in `O2` (the arguments of eq. 5).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SpindleOffsets {
    /// Δr_x = Δr_xd + Δr_xs, m.
    pub dr_x_m: f64,
    /// Δr_y = Δr_yd + Δr_ys, m.
    pub dr_y_m: f64,
    /// Δφ_x = Δφ_xd + Δφ_xs, rad.
    pub dphi_x_rad: f64,
    /// Δφ_y = Δφ_yd + Δφ_ys, rad.
    pub dphi_y_rad: f64,
}

impl SpindleOffsets {
    /// Total drift ΔR (eq. 6).
    #[must_use]
    pub fn drift_magnitude_m(&self) -> f64 {
        self.dr_x_m.hypot(self.dr_y_m)
    }

    /// Angle β between `X2` and the direction of the combined drift, so that
    /// `Δr_x = ΔR cos β` (eq. 7). Zero when there is no drift.
    #[must_use]
    pub fn drift_azimuth_rad(&self) -> f64 {
        self.dr_y_m.atan2(self.dr_x_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn static_and_dynamic_parts_add_as_vectors() {
        let p = PhysicalImbalance {
            mass_kg: 0.1,
            mass_radius_m: 0.4,
            arm_m: 0.2,
            imbalance_azimuth_deg: 180.0,
            radial_stiffness_n_m: 1e9,
            angular_stiffness_n_m_rad: 5e8,
            static_force_n: 3000.0,
            static_force_azimuth_deg: 20.0,
            static_moment_n_m: 100.0,
            static_tilt_azimuth_deg: 90.0,
            masses: Vec::new(),
        };
        let e = ErrorMotion::from_physical(&p).unwrap();
        let w = 3.0;
        let o = e.offsets_at(w);
        let dyn_r = 0.4 * 0.1 * w * w / 1e9; // eq. 1, pointing at 180°
        let stat_r = 3000.0 / 1e9; // eq. 3, at 20°
        let (s20, c20) = 20.0_f64.to_radians().sin_cos();
        assert_relative_eq!(o.dr_x_m, stat_r * c20 - dyn_r, max_relative = 1e-12);
        assert_relative_eq!(o.dr_y_m, stat_r * s20, max_relative = 1e-9);
        // law of cosines for the magnitude (eq. 6): angle between the two vectors is 160°
        let expect =
            (stat_r * stat_r + dyn_r * dyn_r + 2.0 * stat_r * dyn_r * 160.0_f64.to_radians().cos())
                .sqrt();
        assert_relative_eq!(o.drift_magnitude_m(), expect, max_relative = 1e-12);
        assert_relative_eq!(
            o.drift_magnitude_m() * o.drift_azimuth_rad().cos(),
            o.dr_x_m,
            max_relative = 1e-12
        );
        // static tilt leans towards +Y2: a negative rotation about X2 (eq. 4)
        assert_relative_eq!(e.dphi_xs_rad, -100.0 / 5e8, max_relative = 1e-12);
        assert!(e.dphi_ys_rad.abs() < 1e-20);
        // dynamic tilt leans towards 180°: negative about Y2 (eq. 2)
        assert_relative_eq!(e.c_phi_s2, -0.4 * 0.1 * 0.2 / 5e8, max_relative = 1e-12);
    }

    #[test]
    fn listed_masses_add_as_vectors_to_the_single_mass() {
        let single = PhysicalImbalance {
            mass_kg: 0.2,
            mass_radius_m: 0.5,
            arm_m: 0.3,
            imbalance_azimuth_deg: 40.0,
            radial_stiffness_n_m: 2.0e9,
            angular_stiffness_n_m_rad: 1.0e9,
            ..PhysicalImbalance::default()
        };
        let listed = PhysicalImbalance {
            masses: vec![
                ImbalanceMass {
                    mass_kg: 0.1,
                    radius_m: 1.0,
                    azimuth_deg: 130.0,
                    arm_m: -0.2,
                },
                ImbalanceMass {
                    mass_kg: 0.05,
                    radius_m: 2.0,
                    azimuth_deg: -90.0,
                    arm_m: 0.0,
                },
            ],
            ..single.clone()
        };
        let a = ErrorMotion::from_physical(&single).unwrap();
        let b = ErrorMotion::from_physical(&listed).unwrap();
        let (s, c) = 130f64.to_radians().sin_cos();
        let d1 = 0.1 / 2.0e9;
        let d2 = 0.1 / 2.0e9;
        assert_relative_eq!(b.c_r_m_s2, a.c_r_m_s2 + d1 * c, max_relative = 1e-12);
        assert_relative_eq!(
            b.c_r_y_m_s2,
            a.c_r_y_m_s2 + d1 * s - d2,
            max_relative = 1e-12
        );
        let t1 = 0.1 * -0.2 / 1.0e9;
        assert_relative_eq!(b.c_phi_s2, a.c_phi_s2 + t1 * c, max_relative = 1e-12);
        assert_relative_eq!(b.c_phi_x_s2, a.c_phi_x_s2 - t1 * s, max_relative = 1e-12);
        // a mass opposite the single one cancels it
        let cancelled = PhysicalImbalance {
            masses: vec![ImbalanceMass {
                mass_kg: 0.1,
                radius_m: 1.0,
                azimuth_deg: 220.0,
                arm_m: 0.3,
            }],
            ..single
        };
        let e = ErrorMotion::from_physical(&cancelled).unwrap();
        assert!(e.c_r_m_s2.abs() < 1e-25 && e.c_r_y_m_s2.abs() < 1e-25);
        assert!(e.c_phi_s2.abs() < 1e-25 && e.c_phi_x_s2.abs() < 1e-25);
    }

    #[test]
    fn bad_stiffness_is_a_typed_error() {
        let p = PhysicalImbalance {
            radial_stiffness_n_m: 0.0,
            ..PhysicalImbalance::default()
        };
        assert_eq!(
            ErrorMotion::from_physical(&p),
            Err(crate::KinematicsError::NotPositive {
                field: "radial_stiffness_n_m",
                value: 0.0
            })
        );
        let e = ErrorMotion {
            c_phi_s2: f64::NAN,
            ..ErrorMotion::ZERO
        };
        assert!(matches!(
            ErrorMotionSpec::Coefficients(e).resolve(),
            Err(crate::KinematicsError::NonFinite {
                field: "c_phi_s2",
                ..
            })
        ));
    }
}
