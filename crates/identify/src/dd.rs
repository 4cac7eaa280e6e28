//! Double-double arithmetic: an unevaluated sum `hi + lo` of two doubles, about 106 bits.
//!
//! Error-free transformations (Knuth's two-sum, and Dekker's two-product with Veltkamp's split,
//! falling back to the fused multiply-add, which Rust's `f64::mul_add` guarantees to round once,
//! where the split is not exact) following Dekker (1971) and Hida, Li & Bailey's QD library.
//! Only the operations the solver needs are provided.

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

/// Veltkamp's splitter for doubles, 2²⁷ + 1: `split` cuts a double into two halves of 26 bits.
const SPLITTER: f64 = 134_217_729.0;
/// Above 2⁹⁹⁵ the splitter's product may overflow.
const SPLIT_MAX: f64 = f64::from_bits((1023 + 995) << 52);
/// Dekker's partial products are exact while a·b is between 2⁻⁹⁰⁰ and 2¹⁰⁰⁰ (no partial product
/// underflows or overflows: Boldo 2006 needs the exponents' sum above −970).
const PROD_MIN: f64 = f64::from_bits((1023 - 900) << 52);
const PROD_MAX: f64 = f64::from_bits((1023 + 1000) << 52);

/// `a = hi + lo` exactly, each with at most 26 significant bits (Veltkamp).
#[inline]
fn split(a: f64) -> (f64, f64) {
    let t = SPLITTER * a;
    let hi = t - (t - a);
    (hi, a - hi)
}

/// `a·b = p + e` exactly.
///
/// Dekker's product (four partial products, inline) where it is exact, which is every product
/// the solver forms; the fused multiply-add outside that range (zeros, subnormals, near
/// overflow, non-finite values). Both give the exact `a·b − p`, so the result is the same bit
/// for bit; Dekker's is used because without the `fma` target feature (the default x86-64
/// target) `f64::mul_add` is a call to a software fma, which took 35 % of a joint fit's time.
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let size = p.abs();
    if a.abs() < SPLIT_MAX && b.abs() < SPLIT_MAX && size > PROD_MIN && size < PROD_MAX {
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    } else {
        (p, a.mul_add(b, -p))
    }
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

    /// Dekker's product and the fused multiply-add agree bit for bit, over products of every
    /// size (the guard's edges included) and the special values.
    #[test]
    fn dekker_product_equals_the_fused_one() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut values = vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1.0,
            1.0 + f64::EPSILON,
            SPLIT_MAX,
            SPLIT_MAX * (1.0 - f64::EPSILON),
            PROD_MIN.sqrt(),
            PROD_MAX.sqrt(),
            PROD_MAX.sqrt() * (1.0 + f64::EPSILON),
        ];
        for _ in 0..20_000 {
            // random bits: every exponent and significand, signs, subnormals, non-finite
            values.push(f64::from_bits(next()));
            // random significands near one, with a modest exponent
            let near = f64::from_bits((next() >> 12) | 0x3ff0_0000_0000_0000);
            values.push(near * 2f64.powi((next() % 200) as i32 - 100));
        }
        let mut compared = 0;
        let mut dekker = 0;
        for pair in values.chunks_exact(2).chain(values.windows(2).step_by(7)) {
            let (a, b) = (pair[0], pair[1]);
            let (p, e) = two_prod(a, b);
            let fused = a.mul_add(b, -p);
            assert_eq!(
                e.to_bits(),
                fused.to_bits(),
                "{a:e}·{b:e}: Dekker {e:e}, fused {fused:e}"
            );
            compared += 1;
            let size = p.abs();
            if size > PROD_MIN && size < PROD_MAX && a.abs() < SPLIT_MAX && b.abs() < SPLIT_MAX {
                dekker += 1;
            }
        }
        assert!(compared > 25_000 && dekker > 20_000, "{compared} {dekker}");
        assert_eq!(SPLIT_MAX, 2f64.powi(995));
        assert_eq!(PROD_MIN, 2f64.powi(-900));
        assert_eq!(PROD_MAX, 2f64.powi(1000));
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
