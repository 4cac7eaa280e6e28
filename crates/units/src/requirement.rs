//! What a number must be: the one vocabulary of the workspace's "invalid value" errors.
//!
//! A library checks a scalar input with [`finite`], [`positive`], [`non_negative`] or
//! [`require`]; each returns the value, or an [`Unmet`] naming the field, the value and the
//! [`Requirement`] it fails. Each crate's error type converts an [`Unmet`] into its own
//! variant (`impl From<Unmet<…>> for …Error`), so `?` reads
//!
//! ```
//! use units::{Requirement, Unmet};
//!
//! #[derive(Debug, PartialEq)]
//! enum MyError {
//!     InvalidParameter { name: &'static str, value: f64, requirement: Requirement },
//! }
//! impl From<Unmet<&'static str>> for MyError {
//!     fn from(u: Unmet<&'static str>) -> Self {
//!         MyError::InvalidParameter { name: u.field, value: u.value, requirement: u.requirement }
//!     }
//! }
//! fn radius(radius_m: f64) -> Result<f64, MyError> {
//!     Ok(units::positive("radius_m", radius_m)?)
//! }
//! assert_eq!(radius(1.5), Ok(1.5));
//! let err = radius(-1.0).unwrap_err();
//! assert_eq!(
//!     err,
//!     MyError::InvalidParameter { name: "radius_m", value: -1.0, requirement: Requirement::Positive }
//! );
//! assert_eq!(Requirement::Positive.to_string(), "must be finite and > 0");
//! ```
//!
//! The words are a person's (`must be finite and ≥ 0`), never a Rust name, and the numbers
//! in them are written by [`Compact`](crate::Compact).

use crate::compact::Compact;

/// What a scalar must satisfy. Every requirement includes "finite": NaN and ±∞ never pass.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Requirement {
    /// A finite number.
    Finite,
    /// A finite number greater than 0.
    Positive,
    /// A finite number, 0 or more.
    NonNegative,
    /// A finite number, at least the bound.
    AtLeast(f64),
    /// A finite number in the closed interval `[min, max]`.
    InRange {
        /// Smallest admissible value.
        min: f64,
        /// Largest admissible value.
        max: f64,
    },
    /// A finite number in the interval `(min, max]`: above `min`, at most `max`.
    AboveAtMost {
        /// The bound the value must exceed.
        min: f64,
        /// Largest admissible value.
        max: f64,
    },
    /// A finite number in `[0, 1)`.
    UnitInterval,
    /// A number strictly between 0 and 1 (a probability that is neither impossible nor sure).
    OpenUnitInterval,
}

impl Requirement {
    /// Whether `value` satisfies the requirement.
    #[must_use]
    pub fn holds(self, value: f64) -> bool {
        value.is_finite()
            && match self {
                Self::Finite => true,
                Self::Positive => value > 0.0,
                Self::NonNegative => value >= 0.0,
                Self::AtLeast(bound) => value >= bound,
                Self::InRange { min, max } => (min..=max).contains(&value),
                Self::AboveAtMost { min, max } => value > min && value <= max,
                Self::UnitInterval => (0.0..1.0).contains(&value),
                Self::OpenUnitInterval => value > 0.0 && value < 1.0,
            }
    }
}

impl std::fmt::Display for Requirement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::Finite => f.write_str("must be finite"),
            Self::Positive => f.write_str("must be finite and > 0"),
            Self::NonNegative => f.write_str("must be finite and ≥ 0"),
            Self::AtLeast(bound) => write!(f, "must be finite and ≥ {}", Compact(bound)),
            Self::InRange { min, max } => {
                write!(f, "must lie in [{}, {}]", Compact(min), Compact(max))
            }
            Self::AboveAtMost { min, max } => {
                write!(f, "must lie in ({}, {}]", Compact(min), Compact(max))
            }
            Self::UnitInterval => f.write_str("must be finite and in [0, 1)"),
            Self::OpenUnitInterval => f.write_str("must lie strictly between 0 and 1"),
        }
    }
}

/// A field whose value does not satisfy its [`Requirement`]. `F` is how the caller names the
/// field: a `&'static str` parameter name or a `String` path (`planes[1].height_m`).
#[derive(Debug, Clone, PartialEq)]
pub struct Unmet<F> {
    /// The field, as its caller names it.
    pub field: F,
    /// The value given.
    pub value: f64,
    /// What it must satisfy.
    pub requirement: Requirement,
}

impl<F: std::fmt::Display> std::fmt::Display for Unmet<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} = {} {}",
            self.field,
            Compact(self.value),
            self.requirement
        )
    }
}

impl<F: std::fmt::Debug + std::fmt::Display> std::error::Error for Unmet<F> {}

/// `Ok(value)` when it satisfies `requirement`, else the [`Unmet`] naming `field`.
pub fn require<F>(field: F, value: f64, requirement: Requirement) -> Result<f64, Unmet<F>> {
    if requirement.holds(value) {
        Ok(value)
    } else {
        Err(Unmet {
            field,
            value,
            requirement,
        })
    }
}

/// `Ok(value)` when finite ([`Requirement::Finite`]).
pub fn finite<F>(field: F, value: f64) -> Result<f64, Unmet<F>> {
    require(field, value, Requirement::Finite)
}

/// `Ok(value)` when finite and > 0 ([`Requirement::Positive`]).
pub fn positive<F>(field: F, value: f64) -> Result<f64, Unmet<F>> {
    require(field, value, Requirement::Positive)
}

/// `Ok(value)` when finite and ≥ 0 ([`Requirement::NonNegative`]).
pub fn non_negative<F>(field: F, value: f64) -> Result<f64, Unmet<F>> {
    require(field, value, Requirement::NonNegative)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_requirement_refuses_nan_and_infinity() {
        let all = [
            Requirement::Finite,
            Requirement::Positive,
            Requirement::NonNegative,
            Requirement::AtLeast(1.0),
            Requirement::InRange {
                min: f64::NEG_INFINITY,
                max: f64::INFINITY,
            },
            Requirement::AboveAtMost {
                min: f64::NEG_INFINITY,
                max: f64::INFINITY,
            },
            Requirement::UnitInterval,
            Requirement::OpenUnitInterval,
        ];
        for r in all {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                assert!(!r.holds(bad), "{r:?} holds for {bad}");
            }
        }
    }

    #[test]
    fn bounds_are_where_the_words_say() {
        assert!(!Requirement::Positive.holds(0.0));
        assert!(Requirement::NonNegative.holds(0.0));
        assert!(!Requirement::NonNegative.holds(-1e-300));
        assert!(Requirement::AtLeast(1.0).holds(1.0));
        assert!(!Requirement::AtLeast(1.0).holds(0.999));
        let r = Requirement::InRange {
            min: -1.0,
            max: 2.0,
        };
        assert!(r.holds(-1.0) && r.holds(2.0) && !r.holds(2.000_001));
        let r = Requirement::AboveAtMost { min: 0.0, max: 0.5 };
        assert!(!r.holds(0.0) && r.holds(0.5) && !r.holds(0.500_001));
        assert_eq!(r.to_string(), "must lie in (0, 0.5]");
        assert!(Requirement::UnitInterval.holds(0.0) && !Requirement::UnitInterval.holds(1.0));
        assert!(!Requirement::OpenUnitInterval.holds(0.0));
        assert!(!Requirement::OpenUnitInterval.holds(1.0));
        assert!(Requirement::OpenUnitInterval.holds(0.5));
    }

    #[test]
    fn unmet_names_field_value_and_requirement_in_words() {
        let u = positive("radius_m", -2.0).unwrap_err();
        assert_eq!(u.to_string(), "radius_m = -2 must be finite and > 0");
        let u = require(
            String::from("planes[1].height_m"),
            1e300,
            Requirement::InRange { min: 0.0, max: 1.0 },
        )
        .unwrap_err();
        assert_eq!(
            u.to_string(),
            "planes[1].height_m = 1e300 must lie in [0, 1]"
        );
        assert_eq!(
            Requirement::AtLeast(1.0).to_string(),
            "must be finite and ≥ 1"
        );
        assert_eq!(finite("x", 3.0), Ok(3.0));
        assert_eq!(non_negative("x", 0.0), Ok(0.0));
    }
}
