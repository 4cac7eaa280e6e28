//! First-harmonic geometry of the probe measurement (eq. 21–22).

use crate::error::{HarmonicsError, Result};

/// First-harmonic coefficients of the probe gap, `d1 = c1·cos ωt + s1·sin ωt` (eq. 21).
///
/// Both coefficients are in the unit of the gap they were fitted from (µm in the paper).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FirstHarmonic {
    /// Cosine coefficient `d_c1`.
    pub c1: f64,
    /// Sine coefficient `d_s1`.
    pub s1: f64,
}

impl FirstHarmonic {
    /// The first harmonic itself once both coefficients are finite.
    ///
    /// # Errors
    /// [`HarmonicsError::NonFiniteCoefficient`] naming `d_c1` or `d_s1`.
    pub fn validated(self) -> Result<Self> {
        for (field, value) in [("d_c1", self.c1), ("d_s1", self.s1)] {
            if !value.is_finite() {
                return Err(HarmonicsError::NonFiniteCoefficient { field, value });
            }
        }
        Ok(self)
    }

    /// Amplitude `ΔR1 = √(d_c1² + d_s1²)` of the first harmonic in the probe plane.
    ///
    /// ```
    /// # use harmonics::FirstHarmonic;
    /// let h = FirstHarmonic { c1: -3.0, s1: 4.0 }.validated().unwrap();
    /// approx::assert_relative_eq!(h.amplitude(), 5.0, max_relative = 1e-15);
    /// ```
    pub fn amplitude(&self) -> f64 {
        self.c1.hypot(self.s1)
    }
}

/// Direction in which the displacement probe measures, relative to the sleeve axis O1X1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum ProbeDirection {
    /// The probe measures against O1X1 (the paper's set-up, Fig. 3):
    /// `d1 = ΔR1·cos(ωt + β + 180°)`, so `d_c1 = −ΔR1 cos β`, `d_s1 = ΔR1 sin β`.
    #[default]
    AgainstO1X1,
    /// The probe measures along O1X1: `d1 = ΔR1·cos(ωt + β)`,
    /// so `d_c1 = ΔR1 cos β`, `d_s1 = −ΔR1 sin β`.
    AlongO1X1,
}

impl ProbeDirection {
    /// `+1` along O1X1, `−1` against it.
    const fn sign(self) -> f64 {
        match self {
            Self::AgainstO1X1 => -1.0,
            Self::AlongO1X1 => 1.0,
        }
    }

    /// Azimuth `β` of the composite imbalance from the first harmonic (eq. 21):
    /// against O1X1, `β = atan2(d_s1, −d_c1)`; along O1X1, `β = atan2(−d_s1, d_c1)`.
    ///
    /// ```
    /// # use harmonics::{FirstHarmonic, ProbeDirection};
    /// let h = FirstHarmonic { c1: -3.0, s1: 0.0 }.validated().unwrap();
    /// approx::assert_relative_eq!(ProbeDirection::AgainstO1X1.beta_rad(h), 0.0);
    /// ```
    pub fn beta_rad(self, h: FirstHarmonic) -> f64 {
        let sign = self.sign();
        (-sign * h.s1).atan2(sign * h.c1)
    }
}

/// Heights along the spindle axis that carry the probe's first harmonic to the PIGA plane
/// by similar triangles (eq. 22), and the probe's measuring direction.
///
/// The spindle's first-harmonic motion is taken as a cone about the tilt pivot, so a drift
/// `x` measured in the probe plane is `x·(h_probe + h_piga)/h_probe` in the PIGA plane, where
/// `h_probe` is the height from the pivot to the probe plane and `h_piga` from the probe plane
/// to the PIGA plane (700 mm and 510 mm in the paper).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct LeverGeometry {
    /// Height from the tilt pivot (spindle centre of mass plane) to the probe plane, mm.
    pub pivot_to_probe_mm: f64,
    /// Height from the probe plane to the PIGA centre-of-mass plane, mm.
    pub probe_to_piga_mm: f64,
    /// The probe's measuring direction.
    #[cfg_attr(feature = "serde", serde(default))]
    pub probe_direction: ProbeDirection,
}

/// The lever ratio of eq. 22, `(h_probe + h_piga)/h_probe`: a drift in the probe plane times
/// this is the drift in the PIGA plane (1210/700 with the paper's 700 mm and 510 mm). The one
/// home of the formula: the probe analysis ([`LeverGeometry::lever_ratio`], which validates the
/// heights first), the calibration's measurement models and the planner call it. The heights
/// are taken as they are (a zero `pivot_to_probe_mm` gives ±∞ or NaN; validate first where
/// they come from a person).
///
/// ```
/// approx::assert_relative_eq!(harmonics::lever_ratio(700.0, 510.0), 1210.0 / 700.0, max_relative = 1e-15);
/// ```
#[inline]
#[must_use]
pub fn lever_ratio(pivot_to_probe_mm: f64, probe_to_piga_mm: f64) -> f64 {
    (pivot_to_probe_mm + probe_to_piga_mm) / pivot_to_probe_mm
}

/// The first harmonic carried to the PIGA plane (eq. 22, corrected form of NOTES.md).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PigaPlaneDrift {
    /// Amplitude of the first harmonic in the probe plane, `ΔR1`, in the gap's unit.
    pub probe_amplitude: f64,
    /// Azimuth `β` of the composite imbalance from O2X2, radians in (−π, π].
    pub beta_rad: f64,
    /// Drift amplitude in the PIGA plane, `ΔR1·(h_probe + h_piga)/h_probe`.
    pub piga_amplitude: f64,
    /// Working-radius error along O2X2 in the PIGA plane,
    /// `Δr_xd + Δr_xs = ΔR1 cos β·(h_probe + h_piga)/h_probe`, in the gap's unit.
    pub radius_error: f64,
}

impl LeverGeometry {
    /// Validates the heights (finite, strictly positive; the PIGA plane may coincide with
    /// the probe plane, so `probe_to_piga_mm` may be zero).
    pub fn validate(&self) -> Result<()> {
        let checks = [
            ("pivot_to_probe_mm", self.pivot_to_probe_mm, false),
            ("probe_to_piga_mm", self.probe_to_piga_mm, true),
        ];
        for (field, value, zero_ok) in checks {
            let ok = value.is_finite() && (value > 0.0 || (zero_ok && value == 0.0));
            if !ok {
                return Err(HarmonicsError::InvalidGeometry { field, value });
            }
        }
        Ok(())
    }

    /// Lever ratio `(h_probe + h_piga)/h_probe` (1210/700 in the paper).
    ///
    /// ```
    /// # use harmonics::{LeverGeometry, ProbeDirection};
    /// let g = LeverGeometry { pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0,
    ///                         probe_direction: ProbeDirection::AgainstO1X1 };
    /// approx::assert_relative_eq!(g.lever_ratio().unwrap(), 1210.0 / 700.0, max_relative = 1e-15);
    /// ```
    pub fn lever_ratio(&self) -> Result<f64> {
        self.validate()?;
        Ok(lever_ratio(self.pivot_to_probe_mm, self.probe_to_piga_mm))
    }

    /// Azimuth `β` of the composite imbalance from the first harmonic (eq. 21):
    /// against O1X1, `β = atan2(d_s1, −d_c1)`; along O1X1, `β = atan2(−d_s1, d_c1)`.
    pub fn beta_rad(&self, h: FirstHarmonic) -> f64 {
        self.probe_direction.beta_rad(h)
    }

    /// Carries a probe first harmonic to the PIGA plane (eq. 21–22).
    ///
    /// With the paper's geometry, `radius_error = −d_c1·1210/700`:
    /// ```
    /// # use harmonics::{FirstHarmonic, LeverGeometry, ProbeDirection};
    /// let g = LeverGeometry { pivot_to_probe_mm: 700.0, probe_to_piga_mm: 510.0,
    ///                         probe_direction: ProbeDirection::AgainstO1X1 };
    /// let d = g.project(FirstHarmonic { c1: -3.5, s1: 0.0 }).unwrap();
    /// approx::assert_relative_eq!(d.radius_error, 3.5 * 1210.0 / 700.0, max_relative = 1e-15);
    /// approx::assert_relative_eq!(d.beta_rad, 0.0);
    /// ```
    pub fn project(&self, h: FirstHarmonic) -> Result<PigaPlaneDrift> {
        let ratio = self.lever_ratio()?;
        let h = h.validated()?;
        let probe_amplitude = h.amplitude();
        Ok(PigaPlaneDrift {
            probe_amplitude,
            beta_rad: self.beta_rad(h),
            piga_amplitude: probe_amplitude * ratio,
            radius_error: self.probe_direction.sign() * h.c1 * ratio,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::PI;

    fn paper() -> LeverGeometry {
        LeverGeometry {
            pivot_to_probe_mm: 700.0,
            probe_to_piga_mm: 510.0,
            probe_direction: ProbeDirection::AgainstO1X1,
        }
    }

    #[test]
    fn harmonic_rebuilt_from_amplitude_and_azimuth() {
        // d1 = ΔR1 cos(ωt + β + π) must equal c1 cos ωt + s1 sin ωt at every angle.
        let h = FirstHarmonic { c1: -1.2, s1: 0.7 }.validated().unwrap();
        let d = paper().project(h).unwrap();
        for k in 0..16 {
            let t = k as f64 * PI / 8.0;
            let direct = h.c1 * t.cos() + h.s1 * t.sin();
            let polar = d.probe_amplitude * (t + d.beta_rad + PI).cos();
            assert_relative_eq!(direct, polar, epsilon = 1e-14);
        }
    }

    #[test]
    fn along_direction_flips_the_sign_and_keeps_the_motion() {
        let h = FirstHarmonic { c1: -1.2, s1: 0.7 }.validated().unwrap();
        let against = paper().project(h).unwrap();
        let along = LeverGeometry {
            probe_direction: ProbeDirection::AlongO1X1,
            ..paper()
        };
        // The same spindle motion seen by a probe facing the other way has the negated signal.
        let flipped = along
            .project(FirstHarmonic {
                c1: -h.c1,
                s1: -h.s1,
            })
            .unwrap();
        assert_relative_eq!(flipped.radius_error, against.radius_error, epsilon = 1e-15);
        assert_relative_eq!(flipped.beta_rad, against.beta_rad, epsilon = 1e-15);
    }

    #[test]
    fn hand_computed_case() {
        // c1 = −3, s1 = 4 → ΔR1 = 5, β = atan2(4, 3), radius error = 3·1210/700.
        let d = paper()
            .project(FirstHarmonic { c1: -3.0, s1: 4.0 })
            .unwrap();
        assert_relative_eq!(d.probe_amplitude, 5.0, max_relative = 1e-15);
        assert_relative_eq!(d.beta_rad, 4.0_f64.atan2(3.0), max_relative = 1e-15);
        assert_relative_eq!(d.piga_amplitude, 5.0 * 1210.0 / 700.0, max_relative = 1e-15);
        assert_relative_eq!(d.radius_error, 3.0 * 1210.0 / 700.0, max_relative = 1e-15);
        assert_relative_eq!(
            d.radius_error,
            d.piga_amplitude * d.beta_rad.cos(),
            max_relative = 1e-14
        );
    }

    #[test]
    fn bad_geometry_is_refused_with_the_field_name() {
        let g = LeverGeometry {
            pivot_to_probe_mm: -1.0,
            ..paper()
        };
        assert_eq!(
            g.lever_ratio(),
            Err(HarmonicsError::InvalidGeometry {
                field: "pivot_to_probe_mm",
                value: -1.0
            })
        );
        let g = LeverGeometry {
            probe_to_piga_mm: f64::NAN,
            ..paper()
        };
        assert!(matches!(
            g.lever_ratio(),
            Err(HarmonicsError::InvalidGeometry {
                field: "probe_to_piga_mm",
                ..
            })
        ));
        assert!(matches!(
            FirstHarmonic {
                c1: f64::INFINITY,
                s1: 0.0
            }
            .validated(),
            Err(HarmonicsError::NonFiniteCoefficient { field: "d_c1", .. })
        ));
    }
}
