//! The PIGA input/output model (eq. 15) and its mean over whole revolutions.

use kinematics::{Centrifuge, Chain, INPUT_HIGHEST_HARMONIC, PigaInputs, RevolutionQuadrature};

use crate::error::{AccelModelError, Result};

/// Highest harmonic of the spindle angle in the instantaneous PIGA output: the output is a
/// cubic polynomial in `a_x`, whose highest harmonic is
/// [`kinematics::INPUT_HIGHEST_HARMONIC`], so 3 × 1.
pub const OUTPUT_HIGHEST_HARMONIC: usize = 3 * INPUT_HIGHEST_HARMONIC;

/// Coefficients of the PIGA model, eq. 15:
///
/// ```text
/// λ̇ = k0 + k1·a_x + k2·a_x² + k3·a_x³ − ω_I  (+ ε)
/// ```
///
/// with `a_x` in g along the input axis and `ω_I` the angular rate about it. The random error ε
/// is not part of this crate (a simulator adds it).
///
/// ```
/// use approx::assert_relative_eq;
/// use accel_model::{AxisInputs, PigaCoefficients};
/// let piga = PigaCoefficients { k0_rad_s: 1e-5, k1_rad_s_g: 0.56, k2_rad_s_g2: 2e-6, k3_rad_s_g3: 1e-7 };
/// let out = piga.output_rad_s(AxisInputs { a_x_g: 2.0, omega_i_rad_s: 3e-6 });
/// assert_relative_eq!(out, 1e-5 + 0.56 * 2.0 + 2e-6 * 4.0 + 1e-7 * 8.0 - 3e-6, max_relative = 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PigaCoefficients {
    /// Bias k0, rad/s.
    pub k0_rad_s: f64,
    /// Scale factor k1, rad/(s·g).
    pub k1_rad_s_g: f64,
    /// Second-order coefficient k2, rad/(s·g²).
    pub k2_rad_s_g2: f64,
    /// Third-order coefficient k3, rad/(s·g³).
    pub k3_rad_s_g3: f64,
}

impl PigaCoefficients {
    /// Checks that every coefficient is finite.
    ///
    /// # Errors
    /// [`AccelModelError::NonFinite`] naming the first bad coefficient.
    pub fn validate(&self) -> Result<()> {
        for (field, value) in [
            ("k0_rad_s", self.k0_rad_s),
            ("k1_rad_s_g", self.k1_rad_s_g),
            ("k2_rad_s_g2", self.k2_rad_s_g2),
            ("k3_rad_s_g3", self.k3_rad_s_g3),
        ] {
            if !value.is_finite() {
                return Err(AccelModelError::NonFinite { field, value });
            }
        }
        Ok(())
    }

    /// Eq. 15 without the random error: the output rate `λ̇`, rad/s.
    #[must_use]
    pub fn output_rad_s(&self, inputs: AxisInputs) -> f64 {
        let a = inputs.a_x_g;
        self.k0_rad_s + a * (self.k1_rad_s_g + a * (self.k2_rad_s_g2 + a * self.k3_rad_s_g3))
            - inputs.omega_i_rad_s
    }

    /// The output at time `t_s` from the chain's exact instantaneous inputs.
    #[must_use]
    pub fn instantaneous_output_rad_s(&self, chain: &Chain, t_s: f64) -> f64 {
        self.output_rad_s(AxisInputs::of(&chain.inputs_at(t_s)))
    }
}

/// The two inputs of eq. 15: the specific force along the PIGA's input axis (IA) and the
/// angular rate about it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct AxisInputs {
    /// Specific force along the input axis `a_x`, g.
    pub a_x_g: f64,
    /// Angular rate about the input axis `ω_I`, rad/s.
    pub omega_i_rad_s: f64,
}

impl AxisInputs {
    /// The input-axis components of the full inputs of eq. 12 and 13.
    #[must_use]
    pub fn of(inputs: &PigaInputs) -> Self {
        Self {
            a_x_g: inputs.a_x_g(),
            omega_i_rad_s: inputs.omega_i_rad_s(),
        }
    }
}

/// One rate point of a calibration: the PIGA output and the exact inputs, each averaged over
/// whole revolutions. This is what a simulator writes to `piga.csv` (rate, output) and
/// `truth.json` (all fields).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RatePoint {
    /// Spindle rate ω, rad/s.
    pub rate_rad_s: f64,
    /// Mean PIGA output `⟨λ̇⟩` (eq. 15 averaged over a revolution, no noise), rad/s.
    pub output_rad_s: f64,
    /// Mean specific force along the input axis `⟨a_x⟩` (eq. 12), g.
    pub a_x_g: f64,
    /// Mean angular rate about the input axis `⟨ω_I⟩` (eq. 13), rad/s.
    pub omega_i_rad_s: f64,
}

impl RatePoint {
    /// The mean inputs `⟨a_x⟩`, `⟨ω_I⟩`.
    #[must_use]
    pub fn inputs(&self) -> AxisInputs {
        AxisInputs {
            a_x_g: self.a_x_g,
            omega_i_rad_s: self.omega_i_rad_s,
        }
    }

    /// Spindle rate in degrees per second.
    #[must_use]
    pub fn rate_deg_s(&self) -> f64 {
        self.rate_rad_s.to_degrees()
    }
}

/// The mean output over one revolution of `chain`, by the uniform `points`-node rule, which is
/// exact because the instantaneous output contains harmonics up to
/// [`OUTPUT_HIGHEST_HARMONIC`] only. The mean of a product is not the product of means, so the
/// average is taken of eq. 15 evaluated at each node, not of its inputs.
///
/// # Errors
/// [`AccelModelError::Kinematics`] (`TooFewQuadraturePoints`) for `points < 2·OUTPUT_HIGHEST_HARMONIC + 1`;
/// [`AccelModelError::NonFinite`] for a bad coefficient.
pub fn mean_output_rad_s(chain: &Chain, piga: &PigaCoefficients, points: usize) -> Result<f64> {
    piga.validate()?;
    let q = RevolutionQuadrature::new(points, OUTPUT_HIGHEST_HARMONIC)?;
    Ok(revolution_means(chain, piga, &q)[0])
}

/// `[⟨λ̇⟩, ⟨a_x⟩, ⟨ω_I⟩]` over one revolution of `chain` by the rule `q`: eq. 15 is evaluated
/// at each node, then averaged.
fn revolution_means(chain: &Chain, piga: &PigaCoefficients, q: &RevolutionQuadrature) -> [f64; 3] {
    q.mean_array(chain.rate_rad_s(), |t| {
        let i = AxisInputs::of(&chain.inputs_at(t));
        [piga.output_rad_s(i), i.a_x_g, i.omega_i_rad_s]
    })
}

/// Mean output and exact mean inputs at one rate.
///
/// # Errors
/// As [`kinematics::Chain::new`] and [`PigaCoefficients::validate`].
pub fn rate_point(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    rate_rad_s: f64,
) -> Result<RatePoint> {
    piga.validate()?;
    let chain = Chain::new(centrifuge, rate_rad_s)?;
    let q = RevolutionQuadrature::minimal(OUTPUT_HIGHEST_HARMONIC);
    let [output_rad_s, a_x_g, omega_i_rad_s] = revolution_means(&chain, piga, &q);
    for (quantity, value) in [
        ("output_rad_s", output_rad_s),
        ("a_x_g", a_x_g),
        ("omega_i_rad_s", omega_i_rad_s),
    ] {
        if !value.is_finite() {
            return Err(AccelModelError::NonFiniteResult {
                quantity,
                value,
                inputs: result_inputs(centrifuge, piga, rate_rad_s),
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

/// The scalar inputs an [`AccelModelError::NonFiniteResult`] names: the rate, the radius, g, the
/// dynamic radius coefficient and the PIGA's k1 and k2.
pub(crate) fn result_inputs(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    rate_rad_s: f64,
) -> Vec<(&'static str, f64)> {
    vec![
        ("rate_rad_s", rate_rad_s),
        ("radius_m", centrifuge.radius_m),
        ("gravity_m_s2", centrifuge.site.gravity_m_s2),
        ("c_r_m_s2", centrifuge.error_motion.c_r_m_s2),
        ("k1_rad_s_g", piga.k1_rad_s_g),
        ("k2_rad_s_g2", piga.k2_rad_s_g2),
    ]
}

/// Mean PIGA output and exact mean inputs for each rate of a calibration, in order.
///
/// The centrifuge carries the radius, the site (latitude, Earth rate, g) and the spindle error
/// motion; see [`rate_point`] for one rate.
///
/// ```
/// use approx::assert_relative_eq;
/// use accel_model::{rate_points, PigaCoefficients};
/// use kinematics::{Centrifuge, ErrorMotion, Site, EARTH_RATE_RAD_S};
/// let centrifuge = Centrifuge {
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
/// let rates: Vec<f64> = [10.0_f64, 100.0, 200.0].iter().map(|d| d.to_radians()).collect();
/// let points = rate_points(&centrifuge, &piga, &rates)?;
/// assert_eq!(points.len(), 3);
/// let p = &points[2];
/// // a linear PIGA: mean output = k1·⟨a_x⟩ − ⟨ω_I⟩
/// assert_relative_eq!(p.output_rad_s, 0.56 * p.a_x_g - p.omega_i_rad_s, max_relative = 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`AccelModelError::NoRates`] for an empty list, [`AccelModelError::NonFiniteRate`] naming a bad rate, otherwise
/// as [`rate_point`].
pub fn rate_points(
    centrifuge: &Centrifuge,
    piga: &PigaCoefficients,
    rates_rad_s: &[f64],
) -> Result<Vec<RatePoint>> {
    if rates_rad_s.is_empty() {
        return Err(AccelModelError::NoRates);
    }
    if let Some((index, &value)) = rates_rad_s.iter().enumerate().find(|(_, w)| !w.is_finite()) {
        return Err(AccelModelError::NonFiniteRate { index, value });
    }
    rates_rad_s
        .iter()
        .map(|&w| rate_point(centrifuge, piga, w))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const P: PigaCoefficients = PigaCoefficients {
        k0_rad_s: 1e-5,
        k1_rad_s_g: 0.56,
        k2_rad_s_g2: 2e-6,
        k3_rad_s_g3: 1e-7,
    };

    #[test]
    fn eq15_term_by_term() {
        for &a in &[-3.0, 0.0, 0.5, 10.0] {
            let expect =
                P.k0_rad_s + P.k1_rad_s_g * a + P.k2_rad_s_g2 * a * a + P.k3_rad_s_g3 * a * a * a
                    - 4e-6;
            let inputs = AxisInputs {
                a_x_g: a,
                omega_i_rad_s: 4e-6,
            };
            assert_relative_eq!(P.output_rad_s(inputs), expect, max_relative = 1e-15);
        }
        // the −ω_I term: a rate about IA lowers the output one for one
        let at = |omega_i_rad_s| AxisInputs {
            a_x_g: 1.0,
            omega_i_rad_s,
        };
        assert_relative_eq!(
            P.output_rad_s(at(0.0)) - P.output_rad_s(at(1e-3)),
            1e-3,
            max_relative = 1e-12
        );
    }

    #[test]
    fn non_finite_coefficient_is_named() {
        let bad = PigaCoefficients {
            k1_rad_s_g: f64::NAN,
            ..P
        };
        assert!(matches!(
            bad.validate(),
            Err(AccelModelError::NonFinite {
                field: "k1_rad_s_g",
                ..
            })
        ));
        assert_eq!(P.validate(), Ok(()));
    }
}
