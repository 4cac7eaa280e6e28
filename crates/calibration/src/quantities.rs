//! The measurement model's input quantities for an eq. 18 fit.

use identify::Fit;
use uncertainty::{Dof, Evaluation, InputQuantity, UncertaintyError};

use crate::model::{Nominal, input};
use crate::{TERM_NAMES, TERMS};

/// Type B standard uncertainties of the model's inputs (each finite and ≥ 0): the one
/// definition the study, the two-orientation fit and the planner share (the planner's plan
/// file reads it as the study's `uncertainty` section, docs/CONFIGURATION.md, every input
/// defaulting to 0; the Earth rate is the study's, not a plan's).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct TypeB {
    /// u(R), m.
    pub radius_u_m: f64,
    /// u(g), m/s².
    pub g_u_m_s2: f64,
    /// Relative u of the rate scale common to every rate.
    pub rate_u_relative: f64,
    /// u of the pivot-to-probe height, mm.
    pub pivot_to_probe_u_mm: f64,
    /// u of the probe-to-PIGA height, mm.
    pub probe_to_piga_u_mm: f64,
    /// Relative u of the probe gain.
    pub probe_gain_u_relative: f64,
    /// The Earth rate about the spindle axis, for the two-orientation fit (eq. 23 has no
    /// column for the term it makes with k2; the one-mounting fit's free ω³ column takes it).
    /// The default is exactly zero: no Type B input at all; a study states it or takes it as
    /// unknown ([`AxialEarthRate::not_stated`]).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub axial_earth_rate: AxialEarthRate,
}

/// Which way the spindle turns, seen from above, for the rates of the study (positive
/// numbers).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spin {
    /// Counterclockwise seen from above: the Earth's own sense in the northern hemisphere.
    CounterclockwiseFromAbove,
    /// Clockwise seen from above.
    ClockwiseFromAbove,
}

/// The Earth rate about the spindle axis, `Ω_a = ±Ω·sin L` (the sign: + when the spindle
/// turns the Earth's way about the local vertical, counterclockwise seen from above in the
/// northern hemisphere), rad/s, as an input quantity: a value and the half-width of a
/// rectangular distribution about it.
///
/// It enters the specific force along the arm as `R·(ω + Ω_a)²/g`, so `k2·a²` carries
/// `4·k2·R²·Ω_a·ω³/g²`, the same in both mountings: 0.014 u of k2 on the two-orientation
/// fixture (k2 = 5e-7 rad/(s·g²)), 0.85 u for a PIGA with k2 = 3e-5 (`earth_rate_tests`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AxialEarthRate {
    /// Ω_a, rad/s (0 when its sign is not known).
    pub value_rad_s: f64,
    /// Half-width of the rectangular distribution about it, rad/s (0: known).
    pub half_width_rad_s: f64,
}

impl AxialEarthRate {
    /// Stated by latitude and spin: `±Ω·sin L`, taken as exact (a latitude known to 0.1°
    /// moves it by 1e-3 of itself, far below anything else in the budget).
    #[must_use]
    pub fn stated(latitude_deg: f64, spin: Spin) -> Self {
        let sign = match spin {
            Spin::CounterclockwiseFromAbove => 1.0,
            Spin::ClockwiseFromAbove => -1.0,
        };
        Self {
            value_rad_s: sign * kinematics::EARTH_RATE_RAD_S * latitude_deg.to_radians().sin(),
            half_width_rad_s: 0.0,
        }
    }

    /// The latitude stated but not the spin: 0 ± `Ω·|sin L|` (rectangular).
    #[must_use]
    pub fn latitude_only(latitude_deg: f64) -> Self {
        Self {
            value_rad_s: 0.0,
            half_width_rad_s: kinematics::EARTH_RATE_RAD_S * latitude_deg.to_radians().sin().abs(),
        }
    }

    /// Neither stated: 0 ± Ω (rectangular), what any site and spin allow.
    #[must_use]
    pub const fn not_stated() -> Self {
        Self {
            value_rad_s: 0.0,
            half_width_rad_s: kinematics::EARTH_RATE_RAD_S,
        }
    }

    /// Whether it is an input at all (the default, exactly zero, is not).
    #[must_use]
    pub fn is_input(&self) -> bool {
        self.value_rad_s != 0.0 || self.half_width_rad_s != 0.0
    }
}

/// The compensating C_r as an input quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrInput {
    /// C_r, m·s².
    pub c_r_m_s2: f64,
    /// Its standard uncertainty and the degrees of freedom of the fit it comes from; `None`
    /// (or 0 degrees of freedom): C_r taken as exact.
    pub sigma: Option<(f64, usize)>,
}

/// k1 as an input quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum K1Input {
    /// Fitted (the model's k1 input is unused).
    Fitted,
    /// Given, with its standard uncertainty, rad/(s·g).
    Given {
        /// k1, rad/(s·g).
        k1_rad_s_g: f64,
        /// u(k1), rad/(s·g).
        u_rad_s_g: f64,
    },
}

/// The input quantities of [`crate::CalibrationModel`] for the eq. 18 `fit` and the
/// validated set the GUM and Monte Carlo evaluate: the named inputs at their nominal values
/// with their Type B uncertainties, C_r (Type A with its fit's degrees of freedom), k1 when
/// given, and the fit's six coefficients as one Type A group correlated through the fit's
/// covariance, with `group_dof` degrees of freedom (JCGM 100 G.4 treats the group as one
/// term; JCGM 101 draws it from a multivariate t).
///
/// # Errors
/// Those of [`uncertainty::Inputs::with_correlation`].
pub fn measurement_inputs(
    nominal: &Nominal,
    type_b: &TypeB,
    c_r: CrInput,
    k1: K1Input,
    fit: &Fit,
    group_dof: Dof,
) -> Result<(Vec<InputQuantity>, uncertainty::Inputs), UncertaintyError> {
    let n = nominal;
    let tb = type_b;
    let names = input::NAMES;
    let (k1_value, k1_u) = match k1 {
        K1Input::Given {
            k1_rad_s_g,
            u_rad_s_g,
        } => (k1_rad_s_g, u_rad_s_g),
        K1Input::Fitted => (0.0, 0.0),
    };
    let c_r_input = match c_r.sigma {
        Some((sigma, dof)) if dof > 0 => InputQuantity::type_a(
            names[input::C_R],
            c_r.c_r_m_s2,
            sigma,
            Dof::Finite(dof as f64),
        ),
        _ => InputQuantity {
            kind: Evaluation::TypeA,
            ..InputQuantity::normal(names[input::C_R], c_r.c_r_m_s2, 0.0)
        },
    };
    let mut quantities = vec![
        InputQuantity::normal(names[input::RADIUS], n.radius_m, tb.radius_u_m),
        InputQuantity::normal(names[input::G], n.g_m_s2, tb.g_u_m_s2),
        InputQuantity::normal(names[input::RATE_SCALE], 1.0, tb.rate_u_relative),
        InputQuantity::normal(
            names[input::PIVOT_TO_PROBE],
            n.pivot_to_probe_mm,
            tb.pivot_to_probe_u_mm,
        ),
        InputQuantity::normal(
            names[input::PROBE_TO_PIGA],
            n.probe_to_piga_mm,
            tb.probe_to_piga_u_mm,
        ),
        InputQuantity::normal(names[input::PROBE_GAIN], 1.0, tb.probe_gain_u_relative),
        c_r_input,
        InputQuantity::normal(names[input::K1_GIVEN], k1_value, k1_u),
    ];
    for (t, term) in TERM_NAMES.iter().enumerate() {
        quantities.push(InputQuantity::type_a(
            format!("fit coefficient of {term}"),
            fit.coefficients[t],
            fit.std_errors[t],
            group_dof,
        ));
    }
    let m = quantities.len();
    let first = input::FIRST_COEFFICIENT;
    let mut correlation = vec![0.0; m * m];
    for i in 0..m {
        correlation[i * m + i] = 1.0;
    }
    for a in 0..TERMS {
        for b in 0..TERMS {
            let d = fit.std_errors[a] * fit.std_errors[b];
            if a != b && d > 0.0 {
                correlation[(first + a) * m + first + b] = fit.covariance[(a, b)] / d;
            }
        }
    }
    let set = uncertainty::Inputs::with_correlation(quantities.clone(), &correlation)?;
    Ok((quantities, set))
}
