//! Numbers as D-SI writes them: every value in the shortest decimal text that reads back to
//! the same `f64` (Rust's `Display`/`LowerExp`, which round-trip exactly), in the forms the
//! D-SI patterns accept (`si:decimalType`: sign, digits, point, exponent; `si:kValueType`:
//! no exponent, at least 1; `si:probabilityValueType`: within [0, 1], no exponent).

use crate::error::{DccError, Result};
use crate::text::Text;

/// A finite number in the shortest text that reads back to it: plain digits between 1e-3
/// and 1e15 in magnitude (and for zero), scientific notation otherwise.
pub(crate) fn decimal(quantity: &str, x: f64) -> Result<Text> {
    finite(quantity, x)?;
    let magnitude = x.abs();
    Ok(Text::own(
        if magnitude == 0.0 || (1e-3..1e15).contains(&magnitude) {
            format!("{x}")
        } else {
            format!("{x:e}")
        },
    ))
}

/// A standard or expanded uncertainty: finite and ≥ 0 (D-SI's uncertainty types have no
/// sign).
pub(crate) fn uncertainty(quantity: &str, u: f64) -> Result<Text> {
    finite(quantity, u)?;
    if u < 0.0 {
        return Err(DccError::OutOfDomain {
            quantity: quantity.to_owned(),
            value: format!("{u}"),
            requirement: "an uncertainty must be ≥ 0",
        });
    }
    // -0.0 would print its sign
    decimal(quantity, u.abs())
}

/// A coverage factor: finite and ≥ 1, written without an exponent.
pub(crate) fn coverage_factor(quantity: &str, k: f64) -> Result<Text> {
    finite(quantity, k)?;
    if k < 1.0 {
        return Err(DccError::OutOfDomain {
            quantity: quantity.to_owned(),
            value: format!("{k}"),
            requirement: "a coverage factor must be at least 1 (D-SI)",
        });
    }
    // Display never uses an exponent for f64: 1e20 is written with all its digits.
    Ok(Text::own(format!("{k}")))
}

fn finite(quantity: &str, x: f64) -> Result<()> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(DccError::NonFinite {
            quantity: quantity.to_owned(),
            value: format!("{x}"),
        })
    }
}

/// The coverage probability of every stated interval.
pub(crate) const COVERAGE_PROBABILITY: &str = "0.95";
/// The same as a number.
pub(crate) const COVERAGE_PROBABILITY_P: f64 = 0.95;

/// The coverage factor of the hyper-ellipsoidal coverage region of probability `p` for an
/// `n`-variate normal distribution (JCGM 102:2011 §6.5.2.2): `k_p² = χ²_n(p)`, the `p`-quantile
/// of the chi-squared distribution with `n` degrees of freedom, found by bisection on its
/// distribution function (the regularized lower incomplete gamma function `P(n/2, x/2)`).
pub(crate) fn ellipsoid_coverage_factor(n: usize, p: f64) -> f64 {
    let a = n as f64 / 2.0;
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    while lower_gamma_regularized(a, hi / 2.0) < p {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if lower_gamma_regularized(a, mid / 2.0) < p {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
    }
    (0.5 * (lo + hi)).sqrt()
}

/// `P(a, x) = γ(a, x)/Γ(a)` by its power series `e^{−x} x^a Σ x^j / Γ(a + j + 1)`, which
/// converges for every `x ≥ 0` (the terms fall once `j > x − a`); `ln Γ(a)` for the half
/// integers `a = n/2` it is called with exactly, by recursion from Γ(1) = 1 and Γ(1/2) = √π.
fn lower_gamma_regularized(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    // the series' first term x^a e^{−x} / Γ(a + 1), in logarithms
    let mut term = (a * x.ln() - x - ln_gamma_half_integer(a + 1.0)).exp();
    let mut sum = term;
    let mut j = 1.0;
    while term > sum * f64::EPSILON * 0.25 && j < 10_000.0 {
        term *= x / (a + j);
        sum += term;
        j += 1.0;
    }
    sum.min(1.0)
}

/// `ln Γ(a)` for `a` a positive multiple of 1/2.
fn ln_gamma_half_integer(a: f64) -> f64 {
    let (mut x, mut acc) = if (a - a.floor()).abs() < 0.25 {
        (1.0, 0.0)
    } else {
        (0.5, 0.5 * std::f64::consts::PI.ln())
    };
    while x + 0.5 < a {
        acc += x.ln();
        x += 1.0;
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly_in_the_d_si_forms() {
        for x in [
            0.5634,
            -1.234_567_890_123_456_7e-7,
            6.552e-6,
            1e-5,
            9.99e14,
            1e15,
            -3.0e-300,
            0.0,
            -0.0,
            123_456.789,
            f64::MAX,
            f64::MIN_POSITIVE,
        ] {
            let t = decimal("x", x).unwrap();
            let s = t.as_str();
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{s}");
            // si:decimalType's pattern, by hand: [-+]?(digits with one point)([Ee][-+]?\d+)?
            let (mantissa, exponent) = s.split_once('e').unwrap_or((s, "0"));
            let mantissa = mantissa.strip_prefix('-').unwrap_or(mantissa);
            assert!(
                mantissa.chars().all(|c| c.is_ascii_digit() || c == '.'),
                "{s}"
            );
            assert!(mantissa.matches('.').count() <= 1, "{s}");
            let exponent = exponent.strip_prefix('-').unwrap_or(exponent);
            assert!(exponent.chars().all(|c| c.is_ascii_digit()), "{s}");
        }
        assert!(decimal("k2", f64::NAN).is_err());
        assert!(uncertainty("u(k2)", -1e-9).is_err());
        assert_eq!(uncertainty("u", -0.0).unwrap().as_str(), "0");
        assert_eq!(coverage_factor("k", 2.0).unwrap().as_str(), "2");
        assert_eq!(coverage_factor("k", 2.4469).unwrap().as_str(), "2.4469");
        assert_eq!(
            coverage_factor("k", 1e20).unwrap().as_str(),
            "100000000000000000000"
        );
        assert!(coverage_factor("k", 0.9).is_err());
    }

    #[test]
    fn the_ellipsoid_coverage_factor_is_the_chi_squared_quantile() {
        // n = 1: the normal distribution's two-sided 95 % factor, as the workspace's Student
        // t gives it at infinitely many degrees of freedom
        let z = uncertainty_reference();
        assert!(
            (ellipsoid_coverage_factor(1, 0.95) - z).abs() < 1e-12,
            "{z}"
        );
        // n = 2: P(χ²₂ ≤ x) = 1 − e^{−x/2}, so k² = −2 ln(1 − p)
        let k2 = (-2.0 * (0.05_f64).ln()).sqrt();
        assert!((ellipsoid_coverage_factor(2, 0.95) - k2).abs() < 1e-12);
        // n = 4 and 6: the closed forms 1 − e^{−x/2} Σ_{j<n/2} (x/2)^j / j! at the quantile
        for n in [4_usize, 6] {
            let k = ellipsoid_coverage_factor(n, 0.95);
            let h = k * k / 2.0;
            let mut sum = 0.0;
            let mut term = 1.0;
            for j in 0..n / 2 {
                if j > 0 {
                    term *= h / j as f64;
                }
                sum += term;
            }
            let cdf = 1.0 - (-h).exp() * sum;
            assert!((cdf - 0.95).abs() < 1e-13, "n = {n}: {cdf}");
        }
    }

    /// The two-sided 95 % quantile of the normal distribution, by bisection on erf through
    /// the series of `P(1/2, x)` is what is under test; the reference is independent:
    /// Φ⁻¹(0.975) from the complementary error function's continued fraction.
    fn uncertainty_reference() -> f64 {
        // erfc(x) by Lentz's continued fraction (x > 0.5), bisection for erfc(z/√2) = 0.05
        fn erfc(x: f64) -> f64 {
            let mut f = x;
            let (mut c, mut d) = (x, 0.0);
            for n in 1..200 {
                let a = f64::from(n) / 2.0;
                d = 1.0 / (x + a * d);
                c = x + a / c;
                let delta = c * d;
                f *= delta;
                if (delta - 1.0).abs() < 1e-16 {
                    break;
                }
            }
            (-x * x).exp() / (f * std::f64::consts::PI.sqrt())
        }
        let (mut lo, mut hi) = (1.0_f64, 3.0_f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if erfc(mid / std::f64::consts::SQRT_2) > 0.05 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }
}
