//! Double-double arithmetic: an unevaluated sum `hi + lo` of two doubles, about 106 bits.
//!
//! Error-free transformations (Knuth's two-sum, and two-product through the fused
//! multiply-add, which Rust's `f64::mul_add` guarantees to round once) following Dekker (1971)
//! and Hida, Li & Bailey's QD library. Only the operations the solver needs are provided.

use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// A double-double number `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Dd {
    pub(crate) hi: f64,
    pub(crate) lo: f64,
}

/// `a + b = s + e` exactly.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a + b = s + e` exactly, given `|a| ≥ |b|`.
#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// `a·b = p + e` exactly (FMA).
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl Dd {
    pub(crate) const ZERO: Self = Self { hi: 0.0, lo: 0.0 };

    /// Exact conversion of a double.
    #[inline]
    pub(crate) const fn from_f64(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }

    /// Nearest double.
    #[inline]
    pub(crate) fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// Exact product of two doubles.
    #[inline]
    pub(crate) fn prod(a: f64, b: f64) -> Self {
        let (hi, lo) = two_prod(a, b);
        Self { hi, lo }
    }

    /// `self · x` for a double x.
    #[inline]
    pub(crate) fn mul_f64(self, x: f64) -> Self {
        let (p, e) = two_prod(self.hi, x);
        let e = self.lo.mul_add(x, e);
        let (hi, lo) = quick_two_sum(p, e);
        Self { hi, lo }
    }

    /// Square root (one Newton step on the double estimate).
    pub(crate) fn sqrt(self) -> Self {
        if self.hi <= 0.0 {
            return Self::ZERO;
        }
        let x = self.hi.sqrt();
        let r = self - Self::prod(x, x);
        let (hi, lo) = quick_two_sum(x, r.hi / (2.0 * x));
        Self { hi, lo }
    }

    /// Quotient by a double.
    pub(crate) fn div_f64(self, d: f64) -> Self {
        let q1 = self.hi / d;
        let r = self - Self::prod(q1, d);
        let q2 = r.hi / d;
        let r = r - Self::prod(q2, d);
        let q3 = r.hi / d;
        let (hi, lo) = quick_two_sum(q1, q2);
        Self { hi, lo } + Self::from_f64(q3)
    }
}

impl Add for Dd {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        // Accurate (IEEE-style) addition of QD.
        let (s1, s2) = two_sum(self.hi, b.hi);
        let (t1, t2) = two_sum(self.lo, b.lo);
        let s2 = s2 + t1;
        let (s1, s2) = quick_two_sum(s1, s2);
        let s2 = s2 + t2;
        let (hi, lo) = quick_two_sum(s1, s2);
        Self { hi, lo }
    }
}

impl AddAssign for Dd {
    #[inline]
    fn add_assign(&mut self, b: Self) {
        *self = *self + b;
    }
}

impl Neg for Dd {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl Mul for Dd {
    type Output = Self;
    #[inline]
    fn mul(self, b: Self) -> Self {
        let (p, e) = two_prod(self.hi, b.hi);
        let e = e + (self.hi * b.lo + self.lo * b.hi);
        let (hi, lo) = quick_two_sum(p, e);
        Self { hi, lo }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sum_keeps_what_doubles_lose() {
        // (1 + 2⁻⁶⁰) − 1 = 2⁻⁶⁰, lost entirely in double precision.
        let tiny = 2f64.powi(-60);
        let s = Dd::from_f64(1.0) + Dd::from_f64(tiny) - Dd::from_f64(1.0);
        assert_eq!(s.to_f64(), tiny);
    }

    #[test]
    fn product_is_exact() {
        let a = 1.0 + f64::EPSILON;
        let p = Dd::prod(a, a); // 1 + 2ε + ε²
        let rest = p - Dd::from_f64(1.0) - Dd::from_f64(2.0 * f64::EPSILON);
        assert_eq!(rest.to_f64(), f64::EPSILON * f64::EPSILON);
    }

    #[test]
    fn sqrt_and_division() {
        let two = Dd::from_f64(2.0);
        let r = two.sqrt();
        let back = r * r - two;
        assert!(back.to_f64().abs() < 1e-30);
        let third = Dd::from_f64(1.0).div_f64(3.0);
        let back = third.mul_f64(3.0) - Dd::from_f64(1.0);
        assert!(back.to_f64().abs() < 1e-31);
    }
}
