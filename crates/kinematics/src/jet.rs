//! Second-order forward-mode jets in time.

use core::fmt::Debug;
use core::ops::{Add, Mul, Neg, Sub};

/// A number that the transform chain can be evaluated over: plain `f64`, or a [`Jet`] that
/// carries its first two time derivatives along.
///
/// Only the operations the chain needs are required: ring arithmetic, lifting of constants
/// and the sine and cosine of an angle.
pub trait Scalar:
    Copy
    + Debug
    + PartialEq
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
{
    /// A constant (all time derivatives zero).
    fn constant(value: f64) -> Self;
    /// Sine of an angle in radians.
    fn sine(self) -> Self;
    /// Cosine of an angle in radians.
    fn cosine(self) -> Self;
    /// The plain value (derivatives dropped).
    fn value(self) -> f64;
}

impl Scalar for f64 {
    fn constant(value: f64) -> Self {
        value
    }
    fn sine(self) -> Self {
        self.sin()
    }
    fn cosine(self) -> Self {
        self.cos()
    }
    fn value(self) -> f64 {
        self
    }
}

/// A truncated Taylor jet `(x, ẋ, ẍ)` of a function of time at one instant.
///
/// Arithmetic follows the product and chain rules exactly, so a quantity computed from jets
/// carries its exact first and second time derivatives (up to floating-point rounding):
///
/// ```text
/// (uv)˙ = u̇·v + u·v̇,            (uv)¨ = ü·v + 2·u̇·v̇ + u·v̈
/// (sin u)˙ = cos u·u̇,          (sin u)¨ = cos u·ü − sin u·u̇²
/// ```
///
/// This is how `d²D/dt²` and `dD/dt` of eq. 12 are obtained: no finite differences and no
/// small-angle expansion.
///
/// ```
/// use approx::assert_relative_eq;
/// use kinematics::{Jet, Scalar};
/// // θ(t) = ω t at t = 0.3 s, ω = 2 rad/s; x = R cos θ.
/// let theta = Jet::new(0.6, 2.0, 0.0);
/// let x = Jet::constant(2.5) * theta.cosine();
/// assert_relative_eq!(x.d1, -2.5 * 2.0 * 0.6_f64.sin(), max_relative = 1e-15);
/// assert_relative_eq!(x.d2, -2.5 * 4.0 * 0.6_f64.cos(), max_relative = 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    /// The value `x(t)`.
    pub value: f64,
    /// The first derivative `dx/dt`.
    pub d1: f64,
    /// The second derivative `d²x/dt²`.
    pub d2: f64,
}

impl Jet {
    /// A jet from its value and derivatives.
    #[must_use]
    pub const fn new(value: f64, d1: f64, d2: f64) -> Self {
        Self { value, d1, d2 }
    }

    /// The jet of the independent variable `t` itself: `(t, 1, 0)`.
    #[must_use]
    pub const fn variable(t: f64) -> Self {
        Self::new(t, 1.0, 0.0)
    }

    /// Multiplies every component by a plain number.
    #[must_use]
    pub fn scale(self, k: f64) -> Self {
        Self::new(self.value * k, self.d1 * k, self.d2 * k)
    }
}

impl Scalar for Jet {
    fn constant(value: f64) -> Self {
        Self::new(value, 0.0, 0.0)
    }
    fn sine(self) -> Self {
        let (s, c) = self.value.sin_cos();
        Self::new(s, c * self.d1, c * self.d2 - s * self.d1 * self.d1)
    }
    fn cosine(self) -> Self {
        let (s, c) = self.value.sin_cos();
        Self::new(c, -s * self.d1, -s * self.d2 - c * self.d1 * self.d1)
    }
    fn value(self) -> f64 {
        self.value
    }
}

impl Add for Jet {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self::new(self.value + rhs.value, self.d1 + rhs.d1, self.d2 + rhs.d2)
    }
}

impl Sub for Jet {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Self::new(self.value - rhs.value, self.d1 - rhs.d1, self.d2 - rhs.d2)
    }
}

impl Neg for Jet {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.value, -self.d1, -self.d2)
    }
}

impl Mul for Jet {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        Self::new(
            self.value * rhs.value,
            self.d1 * rhs.value + self.value * rhs.d1,
            self.d2 * rhs.value + 2.0 * self.d1 * rhs.d1 + self.value * rhs.d2,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// f(t) = sin(3t)·cos(t²) by jets against the hand-derived derivatives.
    #[test]
    fn product_and_chain_rule() {
        let t = 0.7_f64;
        let tj = Jet::variable(t);
        let f = (tj.scale(3.0)).sine() * (tj * tj).cosine();
        let (a, da, dda) = (
            (3.0 * t).sin(),
            3.0 * (3.0 * t).cos(),
            -9.0 * (3.0 * t).sin(),
        );
        let (b, db, ddb) = (
            (t * t).cos(),
            -2.0 * t * (t * t).sin(),
            -2.0 * (t * t).sin() - 4.0 * t * t * (t * t).cos(),
        );
        assert_relative_eq!(f.value, a * b, max_relative = 1e-15);
        assert_relative_eq!(f.d1, da * b + a * db, max_relative = 1e-14);
        assert_relative_eq!(
            f.d2,
            dda * b + 2.0 * da * db + a * ddb,
            max_relative = 1e-14
        );
    }

    #[test]
    fn sine_squared_plus_cosine_squared_is_constant() {
        let u = Jet::new(1.3, -0.4, 2.2);
        let one = u.sine() * u.sine() + u.cosine() * u.cosine();
        assert_relative_eq!(one.value, 1.0, max_relative = 1e-15);
        assert!(one.d1.abs() < 1e-15);
        assert!(one.d2.abs() < 1e-14);
    }
}
