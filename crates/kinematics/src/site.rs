//! The laboratory: latitude, Earth rate, gravity; and the centrifuge description.

use crate::error::Result;
use crate::error_motion::ErrorMotion;
use units::{finite, positive};

/// Earth's sidereal rotation rate (WGS 84 / IERS value), rad/s. A convenience default for
/// [`Site::earth_rate_rad_s`]; the chain itself always takes the rate as an input.
pub const EARTH_RATE_RAD_S: f64 = 7.292_115e-5;

/// Where the centrifuge stands.
///
/// The ground frame `O0` is east-north-up, so the Earth rate in it is
/// `Ω_ie = [0, ω_ie cos L, ω_ie sin L]` (eq. 12) and the specific force that holds the
/// PIGA up against gravity is `+1 g` along `Z0`. Accelerations in g are divided by
/// `gravity_m_s2`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Site {
    /// Geodetic latitude L, degrees (−90…90).
    pub latitude_deg: f64,
    /// Earth rotation rate ω_ie, rad/s (see [`EARTH_RATE_RAD_S`]).
    pub earth_rate_rad_s: f64,
    /// Local gravity g, m/s² (the unit "g" of every acceleration in this crate).
    pub gravity_m_s2: f64,
}

impl Site {
    /// The site itself once [`Site::validate`] has accepted it, so that a site can be built
    /// and checked in one expression.
    ///
    /// ```
    /// use kinematics::{KinematicsError, Site, EARTH_RATE_RAD_S};
    /// let site = Site { latitude_deg: 45.0, earth_rate_rad_s: EARTH_RATE_RAD_S, gravity_m_s2: 9.8 };
    /// assert_eq!(site.validated(), Ok(site));
    /// let south_of_the_pole = Site { latitude_deg: -91.0, ..site };
    /// assert!(matches!(south_of_the_pole.validated(), Err(KinematicsError::OutOfRange { .. })));
    /// ```
    ///
    /// # Errors
    /// As [`Site::validate`].
    pub fn validated(self) -> Result<Self> {
        self.validate()?;
        Ok(self)
    }

    /// Checks the fields.
    ///
    /// # Errors
    /// [`crate::KinematicsError::OutOfRange`] for a latitude outside ±90°,
    /// [`crate::KinematicsError::NotPositive`] for gravity, [`crate::KinematicsError::NonFinite`]
    /// for a non-finite Earth rate.
    pub fn validate(&self) -> Result<()> {
        units::require(
            "latitude_deg",
            self.latitude_deg,
            units::Requirement::InRange {
                min: -90.0,
                max: 90.0,
            },
        )?;
        finite("earth_rate_rad_s", self.earth_rate_rad_s)?;
        positive("gravity_m_s2", self.gravity_m_s2)?;
        Ok(())
    }

    /// Latitude in radians.
    #[must_use]
    pub fn latitude_rad(&self) -> f64 {
        self.latitude_deg.to_radians()
    }

    /// `Ω_ie = [0, ω_ie cos L, ω_ie sin L]` in `O0`, rad/s.
    #[must_use]
    pub fn earth_rate_vector_rad_s(&self) -> [f64; 3] {
        let (s, c) = self.latitude_rad().sin_cos();
        [0.0, self.earth_rate_rad_s * c, self.earth_rate_rad_s * s]
    }

    /// Vertical component of the Earth rate, `ω_ie sin L`, rad/s.
    #[must_use]
    pub fn earth_rate_vertical_rad_s(&self) -> f64 {
        self.earth_rate_rad_s * self.latitude_rad().sin()
    }
}

/// A centrifuge at a site: static working radius, spindle error motion.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Centrifuge {
    /// Static working radius R (PIGA centre of mass to the mean spindle axis), m.
    pub radius_m: f64,
    /// Site of the centrifuge.
    pub site: Site,
    /// Spindle error motion coefficients.
    #[cfg_attr(feature = "serde", serde(default))]
    pub error_motion: ErrorMotion,
}

impl Centrifuge {
    /// Checks every field.
    ///
    /// # Errors
    /// [`crate::KinematicsError::NotPositive`] for the radius, otherwise as [`Site::validate`] and
    /// [`ErrorMotion::validate`].
    pub fn validate(&self) -> Result<()> {
        positive("radius_m", self.radius_m)?;
        self.site.validate()?;
        self.error_motion.validate()
    }
}
