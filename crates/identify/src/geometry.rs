//! The centrifuge geometry that turns rates into inputs in g.

use crate::error::Result;

/// Working radius and gravity: the two numbers that turn a spindle rate ω into the nominal
/// input `a = R·ω²/g` (eq. 17–19).
///
/// ```
/// use identify::Geometry;
/// let paper = Geometry { radius_m: 2.5, g_m_s2: 9.8 };
/// approx::assert_relative_eq!(paper.input_g(2.0), 2.5 * 4.0 / 9.8, max_relative = 1e-15);
/// assert!(Geometry { radius_m: 0.0, ..paper }.validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Geometry {
    /// Working radius R, m (finite and > 0).
    pub radius_m: f64,
    /// Gravity g, m/s² (finite and > 0).
    pub g_m_s2: f64,
}

impl Geometry {
    /// Checks that the radius and g are finite and positive.
    ///
    /// # Errors
    /// [`crate::IdentifyError::InvalidParameter`] naming `radius_m` or `g_m_s2`.
    pub fn validate(&self) -> Result<()> {
        units::positive("radius_m", self.radius_m)?;
        units::positive("g_m_s2", self.g_m_s2)?;
        Ok(())
    }

    /// The nominal input `a = R·ω²/g` at `rate_rad_s`, in g.
    #[must_use]
    pub fn input_g(&self, rate_rad_s: f64) -> f64 {
        self.radius_m * rate_rad_s * rate_rad_s / self.g_m_s2
    }
}
