//! The paper's closed-form input/output equation (eq. 17).

use kinematics::Centrifuge;

use crate::error::{AccelModelError, Result};
use crate::piga::{PigaCoefficients, result_inputs};

/// The terms of eq. 17 at one rate, rad/s, each named after its origin:
///
/// ```text
/// λ̇ = (k0 + k1·Δφ_ys) − Δφ_ys·ω − C_φ·ω³
///     + [k1·(R + Δr_xs)·ω²/g + k1·C_φ·ω²]
///     + (k2·R²·ω⁴/g² + k1·C_r·ω⁴/g) + k3·R³·ω⁶/g³
/// ```
///
/// Eq. 17 follows from eq. 14 in eq. 15 with `a_x` taken at its nominal value `Rω²/g` inside
/// the `k2` and `k3` terms. It omits the Earth-rate terms of the mean inputs; they are given
/// separately in [`Eq17Terms::earth_rate_rad_s`] (see [`kinematics::FirstOrderInputs`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Eq17Terms {
    /// `k0 + k1·Δφ_ys`: bias and gravity through the static tilt.
    pub bias_rad_s: f64,
    /// `−Δφ_ys·ω`: spindle rate on the statically tilted input axis.
    pub omega_rad_s: f64,
    /// `−C_φ·ω³`: spindle rate on the dynamically tilted input axis.
    pub omega3_rad_s: f64,
    /// `k1(R + Δr_xs)ω²/g + k1·C_φ·ω²`: nominal centripetal input, static radius error and
    /// gravity through the dynamic tilt.
    pub omega2_rad_s: f64,
    /// `k2·R²ω⁴/g²`: the PIGA's own second-order term.
    pub k2_rad_s: f64,
    /// `k1·C_r·ω⁴/g`: the pseudo-second-order term of the dynamic radius error.
    pub pseudo_second_order_rad_s: f64,
    /// `k3·R³ω⁶/g³`: the PIGA's own third-order term.
    pub k3_rad_s: f64,
    /// Not in eq. 17: `k1·2(R + Δr_x)·ω·ω_ie sin L/g − Δφ_y·ω_ie sin L` (Coriolis specific
    /// force and vertical Earth rate through the tilt, to first order).
    pub earth_rate_rad_s: f64,
}

impl Eq17Terms {
    /// Eq. 17 as printed: the sum of every term except [`Self::earth_rate_rad_s`].
    #[must_use]
    pub fn total_rad_s(&self) -> f64 {
        self.bias_rad_s
            + self.omega_rad_s
            + self.omega3_rad_s
            + self.omega2_rad_s
            + self.k2_rad_s
            + self.pseudo_second_order_rad_s
            + self.k3_rad_s
    }

    /// Eq. 17 plus the Earth-rate terms the paper drops.
    #[must_use]
    pub fn total_with_earth_rate_rad_s(&self) -> f64 {
        self.total_rad_s() + self.earth_rate_rad_s
    }
}

/// Evaluates eq. 17 for `centrifuge` and `piga` at `rate_rad_s`.
///
/// Only `Δr_xs`, `Δφ_ys`, `C_r` and `C_φ` enter; the other-axis error motion is of second order
/// along the input axis.
///
/// ```
/// use approx::assert_relative_eq;
/// use accel_model::{eq17, PigaCoefficients};
/// use kinematics::{Centrifuge, ErrorMotion, Site, EARTH_RATE_RAD_S};
/// let c = Centrifuge {
///     radius_m: 2.5,
///     site: Site {
///         latitude_deg: 45.0,
///         earth_rate_rad_s: EARTH_RATE_RAD_S,
///         gravity_m_s2: 9.8,
///     }
///     .validated()?,
///     error_motion: ErrorMotion { c_r_m_s2: 1.6e-6, ..ErrorMotion::ZERO },
/// };
/// let piga = PigaCoefficients { k0_rad_s: 0.0, k1_rad_s_g: 0.56, k2_rad_s_g2: 0.0, k3_rad_s_g3: 0.0 };
/// let w = 200.0_f64.to_radians();
/// let t = eq17(&c, &piga, w)?;
/// assert_relative_eq!(t.pseudo_second_order_rad_s, 0.56 * 1.6e-6 * w.powi(4) / 9.8, max_relative = 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`kinematics::Centrifuge::validate`] and [`PigaCoefficients::validate`];
/// [`AccelModelError::NonFiniteRate`] for a non-finite rate.
pub fn eq17(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    rate_rad_s: f64,
) -> Result<Eq17Terms> {
    centrifuge.validate()?;
    piga.validate()?;
    if !rate_rad_s.is_finite() {
        return Err(AccelModelError::NonFiniteRate {
            index: 0,
            value: rate_rad_s,
        });
    }
    let e = &centrifuge.error_motion;
    let (r, g, w) = (
        centrifuge.radius_m,
        centrifuge.site.gravity_m_s2,
        rate_rad_s,
    );
    let (w2, w3) = (w * w, w * w * w);
    let w4 = w2 * w2;
    let k1 = piga.k1_rad_s_g;
    let oz = centrifuge.site.earth_rate_vertical_rad_s();
    let radius = r + e.dr_xs_m + e.c_r_m_s2 * w2;
    let tilt_y = e.dphi_ys_rad + e.c_phi_s2 * w2;
    let terms = Eq17Terms {
        bias_rad_s: piga.k0_rad_s + k1 * e.dphi_ys_rad,
        omega_rad_s: -e.dphi_ys_rad * w,
        omega3_rad_s: -e.c_phi_s2 * w3,
        omega2_rad_s: k1 * (r + e.dr_xs_m) * w2 / g + k1 * e.c_phi_s2 * w2,
        k2_rad_s: piga.k2_rad_s_g2 * r * r * w4 / (g * g),
        pseudo_second_order_rad_s: k1 * e.c_r_m_s2 * w4 / g,
        k3_rad_s: piga.k3_rad_s_g3 * (r * w2 / g).powi(3),
        earth_rate_rad_s: k1 * 2.0 * radius * w * oz / g - tilt_y * oz,
    };
    for (quantity, value) in [
        ("bias_rad_s", terms.bias_rad_s),
        ("omega_rad_s", terms.omega_rad_s),
        ("omega2_rad_s", terms.omega2_rad_s),
        ("omega3_rad_s", terms.omega3_rad_s),
        ("k2_rad_s", terms.k2_rad_s),
        ("pseudo_second_order_rad_s", terms.pseudo_second_order_rad_s),
        ("k3_rad_s", terms.k3_rad_s),
        ("earth_rate_rad_s", terms.earth_rate_rad_s),
        (
            "total_with_earth_rate_rad_s",
            terms.total_with_earth_rate_rad_s(),
        ),
    ] {
        if !value.is_finite() {
            return Err(AccelModelError::NonFiniteResult {
                quantity,
                value,
                inputs: result_inputs(centrifuge, piga, rate_rad_s),
            });
        }
    }
    Ok(terms)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use kinematics::{ErrorMotion, Site};

    /// Finite inputs whose terms overflow: a named error, not an `Ok` holding ±∞.
    #[test]
    fn overflowing_terms_are_a_named_error() {
        let c = Centrifuge {
            radius_m: 2.5,
            site: Site {
                latitude_deg: 40.0,
                earth_rate_rad_s: 7.292_115e-5,
                gravity_m_s2: 9.8,
            }
            .validated()
            .unwrap(),
            error_motion: ErrorMotion {
                c_r_m_s2: 1e308,
                ..ErrorMotion::ZERO
            },
        };
        let p = PigaCoefficients {
            k0_rad_s: 0.0,
            k1_rad_s_g: 0.56,
            k2_rad_s_g2: 0.0,
            k3_rad_s_g3: 0.0,
        };
        let e = eq17(&c, &p, 100f64.to_radians()).unwrap_err();
        assert!(
            matches!(e, AccelModelError::NonFiniteResult { .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("c_r_m_s2 = 1e308"), "{e}");
        // g = 1e-300: the specific force is ~1e300 g, and k2·a² overflows.
        let tiny_g = Centrifuge {
            site: Site {
                latitude_deg: 40.0,
                earth_rate_rad_s: 7.292_115e-5,
                gravity_m_s2: 1e-300,
            }
            .validated()
            .unwrap(),
            error_motion: ErrorMotion::ZERO,
            ..c
        };
        let with_k2 = PigaCoefficients {
            k2_rad_s_g2: 2e-6,
            ..p
        };
        let e = crate::rate_point(&tiny_g, &with_k2, 100f64.to_radians()).unwrap_err();
        assert!(
            matches!(e, AccelModelError::NonFiniteResult { .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("gravity_m_s2 = 1e-300"), "{e}");
    }

    /// Eq. 17 is eq. 15 at eq. 14's inputs with a_x nominal in the k2, k3 terms.
    #[test]
    fn eq17_is_eq15_at_eq14_inputs() {
        let e = ErrorMotion {
            dr_xs_m: 5e-6,
            dphi_ys_rad: 3e-6,
            c_r_m_s2: 1.6e-6,
            c_phi_s2: 4e-7,
            ..ErrorMotion::ZERO
        };
        let c = Centrifuge {
            radius_m: 2.5,
            site: Site {
                latitude_deg: 40.0,
                earth_rate_rad_s: 7.292_115e-5,
                gravity_m_s2: 9.8,
            }
            .validated()
            .unwrap(),
            error_motion: e,
        };
        let p = PigaCoefficients {
            k0_rad_s: 1e-5,
            k1_rad_s_g: 0.56,
            k2_rad_s_g2: 2e-6,
            k3_rad_s_g3: 1e-7,
        };
        let w = 2.9;
        let t = eq17(&c, &p, w).unwrap();
        let dr = e.dr_xs_m + e.c_r_m_s2 * w * w;
        let dphi = e.dphi_ys_rad + e.c_phi_s2 * w * w;
        let a_x = (2.5 + dr) * w * w / 9.8 + dphi; // eq. 14
        let a = 2.5 * w * w / 9.8;
        let expect =
            p.k0_rad_s + p.k1_rad_s_g * a_x + p.k2_rad_s_g2 * a * a + p.k3_rad_s_g3 * a * a * a
                - dphi * w;
        assert_relative_eq!(t.total_rad_s(), expect, max_relative = 1e-14);
        assert!(matches!(
            eq17(&c, &p, f64::NAN),
            Err(AccelModelError::NonFiniteRate { .. })
        ));
    }
}
