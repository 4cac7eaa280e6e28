//! The terms of the model, the kinds of accelerometer and their units, and the output of one
//! instant.

use crate::error::{AccelModelError, Result};

/// Number of terms of the model.
pub const TERM_COUNT: usize = 13;

/// A term of the IEEE 836 model. A lab chooses which of them its test identifies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Term {
    /// Bias k0 (output units).
    K0,
    /// Scale factor k1 (output units per g).
    K1,
    /// Second-order coefficient k2, of `a_i²`.
    K2,
    /// Third-order coefficient k3, of `a_i³`.
    K3,
    /// Fourth-order coefficient k4, of `a_i⁴`.
    K4,
    /// Odd-quadratic coefficient k_oq, of `a_i·|a_i|`.
    Koq,
    /// Cross-coupling k_ip, of `a_i·a_p`.
    Kip,
    /// Cross-coupling k_io, of `a_i·a_o`.
    Kio,
    /// Cross-axis quadratic k_pp, of `a_p²`.
    Kpp,
    /// Cross-axis quadratic k_oo, of `a_o²`.
    Koo,
    /// Cross-axis cross term k_po, of `a_p·a_o`.
    Kpo,
    /// Misalignment δ_o of IA towards PA (rotation about OA), rad: `k1·δ_o·a_p`.
    DeltaO,
    /// Misalignment δ_p of IA towards −OA (rotation about PA), rad: `−k1·δ_p·a_o`.
    DeltaP,
}

impl Term {
    /// Every term, in the model's order.
    pub const ALL: [Self; TERM_COUNT] = [
        Self::K0,
        Self::K1,
        Self::K2,
        Self::K3,
        Self::K4,
        Self::Koq,
        Self::Kip,
        Self::Kio,
        Self::Kpp,
        Self::Koo,
        Self::Kpo,
        Self::DeltaO,
        Self::DeltaP,
    ];

    /// Position in [`Term::ALL`].
    #[must_use]
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The symbol a person reads: `k0`, `k_ip`, `δ_o`.
    #[must_use]
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::K0 => "k0",
            Self::K1 => "k1",
            Self::K2 => "k2",
            Self::K3 => "k3",
            Self::K4 => "k4",
            Self::Koq => "k_oq",
            Self::Kip => "k_ip",
            Self::Kio => "k_io",
            Self::Kpp => "k_pp",
            Self::Koo => "k_oo",
            Self::Kpo => "k_po",
            Self::DeltaO => "δ_o",
            Self::DeltaP => "δ_p",
        }
    }

    /// The tag of configuration files: `k0`, `k_ip`, `delta_o`.
    #[must_use]
    pub const fn tag(self) -> &'static str {
        match self {
            Self::DeltaO => "delta_o",
            Self::DeltaP => "delta_p",
            other => other.symbol(),
        }
    }

    /// What the term multiplies, in words: `a_i·a_p`.
    #[must_use]
    pub const fn regressor_words(self) -> &'static str {
        match self {
            Self::K0 => "1",
            Self::K1 => "a_i",
            Self::K2 => "a_i²",
            Self::K3 => "a_i³",
            Self::K4 => "a_i⁴",
            Self::Koq => "a_i·|a_i|",
            Self::Kip => "a_i·a_p",
            Self::Kio => "a_i·a_o",
            Self::Kpp => "a_p²",
            Self::Koo => "a_o²",
            Self::Kpo => "a_p·a_o",
            Self::DeltaO => "k1·a_p",
            Self::DeltaP => "−k1·a_o",
        }
    }

    /// The power of g the term's coefficient is per (k0: 0, k1 and the misalignments: 1 — a
    /// misalignment is in rad —, the quadratic terms 2, k3 3, k4 4).
    #[must_use]
    pub const fn g_power(self) -> i32 {
        match self {
            Self::K0 => 0,
            Self::K1 | Self::DeltaO | Self::DeltaP => 1,
            Self::K3 => 3,
            Self::K4 => 4,
            _ => 2,
        }
    }

    /// Whether the term is a misalignment (an angle, rad), fitted as `k1·δ`.
    #[must_use]
    pub const fn is_misalignment(self) -> bool {
        matches!(self, Self::DeltaO | Self::DeltaP)
    }

    /// The term's regressor at the inputs `(a_i, a_p, a_o)` in g, in the fit's
    /// parametrisation: a misalignment's column is `a_p` (or `−a_o`) and its coefficient
    /// `k1·δ`; every other term's coefficient is the term itself.
    #[must_use]
    pub fn regressor(self, a: [f64; 3]) -> f64 {
        let [i, p, o] = a;
        match self {
            Self::K0 => 1.0,
            Self::K1 => i,
            Self::K2 => i * i,
            Self::K3 => i * i * i,
            Self::K4 => i * i * i * i,
            Self::Koq => i * i.abs(),
            Self::Kip => i * p,
            Self::Kio => i * o,
            Self::Kpp => p * p,
            Self::Koo => o * o,
            Self::Kpo => p * o,
            Self::DeltaO => p,
            Self::DeltaP => -o,
        }
    }

    /// The term's tag parsed back (`k_ip`, `delta_o`), `None` for another word.
    #[must_use]
    pub fn from_tag(tag: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.tag() == tag)
    }
}

impl std::fmt::Display for Term {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.symbol())
    }
}

/// The unit a pendulous accelerometer's output is declared in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum OutputUnit {
    /// Milliampere (a force-rebalance loop's current).
    MilliAmpere,
    /// Volt (a current through a sense resistor).
    Volt,
    /// Pulses per second (a pulse-rebalanced loop's rate).
    PulsesPerSecond,
}

impl OutputUnit {
    /// The unit's symbol: `mA`, `V`, `pulse/s`.
    #[must_use]
    pub const fn symbol(self) -> &'static str {
        match self {
            Self::MilliAmpere => "mA",
            Self::Volt => "V",
            Self::PulsesPerSecond => "pulse/s",
        }
    }
}

/// The kind of accelerometer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum AccelKind {
    /// A pendulous integrating gyroscopic accelerometer: output rate in rad/s, with the
    /// gyroscopic `−ω_i` term of eq. 15 (the rate of the case about IA, known from the
    /// chain and not fitted).
    Piga,
    /// A pendulous (force-rebalance, e.g. quartz flexure) accelerometer: output in a declared
    /// unit, no `ω_i` term.
    Pendulous {
        /// The unit of the output.
        unit: OutputUnit,
    },
}

impl AccelKind {
    /// The output unit's symbol: `rad/s` for a PIGA.
    #[must_use]
    pub const fn output_unit(self) -> &'static str {
        match self {
            Self::Piga => "rad/s",
            Self::Pendulous { unit } => unit.symbol(),
        }
    }

    /// The factor of `ω_i` in the output: −1 for a PIGA, 0 for a pendulous accelerometer.
    #[must_use]
    pub const fn omega_i_factor(self) -> f64 {
        match self {
            Self::Piga => -1.0,
            Self::Pendulous { .. } => 0.0,
        }
    }

    /// Words for a reader.
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::Piga => "PIGA (output rate in rad/s, with the −ω_i term)",
            Self::Pendulous { .. } => "pendulous accelerometer (no ω_i term)",
        }
    }
}

/// The model's coefficients for one accelerometer: every term (zero for a term the lab does
/// not choose), in the kind's output units; the misalignments in rad.
///
/// ```
/// use accel_model::{AccelKind, ModelCoefficients, Term};
/// let mut c = ModelCoefficients::zero(AccelKind::Piga);
/// c.set(Term::K1, 0.56);
/// c.set(Term::DeltaO, 1e-4);
/// c.set(Term::Kip, 2e-6);
/// let out = c.output([2.0, 0.5, 1.0], 3e-6);
/// let expect = 0.56 * (2.0 + 1e-4 * 0.5) + 2e-6 * 2.0 * 0.5 - 3e-6;
/// assert!((out - expect).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelCoefficients {
    /// The kind (and so the output unit and the `ω_i` term).
    pub kind: AccelKind,
    /// The terms' values in [`Term::ALL`]'s order.
    pub values: [f64; TERM_COUNT],
}

impl ModelCoefficients {
    /// Every term zero.
    #[must_use]
    pub const fn zero(kind: AccelKind) -> Self {
        Self {
            kind,
            values: [0.0; TERM_COUNT],
        }
    }

    /// A term's value.
    #[must_use]
    pub const fn get(&self, term: Term) -> f64 {
        self.values[term.index()]
    }

    /// Sets a term's value.
    pub const fn set(&mut self, term: Term, value: f64) {
        self.values[term.index()] = value;
    }

    /// Checks that every value is finite.
    ///
    /// # Errors
    /// [`AccelModelError::NonFinite`] naming the first bad term by its tag.
    pub fn validate(&self) -> Result<()> {
        for t in Term::ALL {
            let value = self.get(t);
            if !value.is_finite() {
                return Err(AccelModelError::NonFinite {
                    field: t.tag(),
                    value,
                });
            }
        }
        Ok(())
    }

    /// The coefficient of a term in the fit's parametrisation: `k1·δ` for a misalignment, the
    /// term itself otherwise.
    #[must_use]
    pub fn fit_value(&self, term: Term) -> f64 {
        if term.is_misalignment() {
            self.get(Term::K1) * self.get(term)
        } else {
            self.get(term)
        }
    }

    /// The output of one instant without the random error, in the kind's unit: the specific
    /// force `a = [a_i, a_p, a_o]` in g along the case axes and the rate `omega_i_rad_s` of
    /// the case about IA.
    #[must_use]
    pub fn output(&self, a: [f64; 3], omega_i_rad_s: f64) -> f64 {
        let [i, p, o] = a;
        let k = |t: Term| self.get(t);
        k(Term::K0)
            + k(Term::K1) * (i + k(Term::DeltaO) * p - k(Term::DeltaP) * o)
            + i * i * (k(Term::K2) + i * (k(Term::K3) + i * k(Term::K4)))
            + k(Term::Koq) * i * i.abs()
            + k(Term::Kip) * i * p
            + k(Term::Kio) * i * o
            + k(Term::Kpp) * p * p
            + k(Term::Koo) * o * o
            + k(Term::Kpo) * p * o
            + self.kind.omega_i_factor() * omega_i_rad_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_output_is_the_sum_of_the_regressors_times_the_fit_values() {
        let mut c = ModelCoefficients::zero(AccelKind::Pendulous {
            unit: OutputUnit::MilliAmpere,
        });
        for (j, t) in Term::ALL.into_iter().enumerate() {
            c.set(
                t,
                1e-3 * (j as f64 + 1.0) * if j % 2 == 0 { 1.0 } else { -1.0 },
            );
        }
        for a in [[2.0, 0.3, -0.7], [-1.5, 1.0, 0.2], [0.0, -2.0, 3.0]] {
            let sum: f64 = Term::ALL
                .into_iter()
                .map(|t| c.fit_value(t) * t.regressor(a))
                .sum();
            assert!((c.output(a, 5.0) - sum).abs() < 1e-14, "{a:?}");
        }
        let piga = ModelCoefficients {
            kind: AccelKind::Piga,
            ..c
        };
        assert!((c.output([1.0; 3], 0.25) - piga.output([1.0; 3], 0.25) - 0.25).abs() < 1e-15);
    }

    #[test]
    fn tags_read_back_and_a_bad_value_is_named() {
        for t in Term::ALL {
            assert_eq!(Term::from_tag(t.tag()), Some(t));
        }
        assert_eq!(Term::from_tag("k9"), None);
        let mut c = ModelCoefficients::zero(AccelKind::Piga);
        c.set(Term::Kpo, f64::NAN);
        assert!(matches!(
            c.validate(),
            Err(AccelModelError::NonFinite { field: "k_po", .. })
        ));
    }
}
