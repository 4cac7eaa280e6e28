//! The numerical tolerance of a standard uncertainty (JCGM 101 §7.9.2).

/// The numerical tolerance `δ` of a standard uncertainty `u` stated to `n_dig` significant
/// decimal digits (JCGM 101 §7.9.2): write `u = c × 10^l` with `c` an `n_dig`-digit integer;
/// then `δ = ½ × 10^l`.
///
/// For example `u = 0.0231` with two digits is `23 × 10⁻³`, so `δ = 0.0005`; with one digit
/// it is `2 × 10⁻²`, so `δ = 0.005`. `u = 0` gives `δ = 0`. `n_dig` must be at least 1 (0 is
/// treated as 1).
///
/// ```
/// use uncertainty::numerical_tolerance;
/// assert_eq!(numerical_tolerance(0.0231, 2), 0.0005);
/// assert_eq!(numerical_tolerance(0.0231, 1), 0.005);
/// assert_eq!(numerical_tolerance(9.96, 2), 0.5); // 9.96 rounds to 10 × 10⁰
/// ```
pub fn numerical_tolerance(u: f64, n_dig: u32) -> f64 {
    if !(u.is_finite() && u > 0.0) {
        return 0.0;
    }
    let n_dig = n_dig.max(1) as i32;
    let mut l = u.log10().floor() as i32 - (n_dig - 1);
    // Rounding u to n_dig digits can carry into one more digit (9.96 → 10.0).
    if (u / pow10(l)).round() >= pow10(n_dig) {
        l += 1;
    }
    0.5 * pow10(l)
}

/// `10^l`, correctly rounded for negative `l` too (`1 / 10^|l|`, one rounding).
fn pow10(l: i32) -> f64 {
    if l >= 0 {
        10f64.powi(l)
    } else {
        1.0 / 10f64.powi(-l)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jcgm_101_examples() {
        // §7.9.2: u(y) = 1 with n_dig = 2 is 10 × 10⁻¹, δ = 0.05; §9.2.2.5-style values.
        assert_eq!(numerical_tolerance(1.0, 2), 0.05);
        assert_eq!(numerical_tolerance(0.0231, 2), 0.0005);
        assert_eq!(numerical_tolerance(2.31e5, 2), 5e3);
        assert_eq!(numerical_tolerance(0.35, 1), 0.05);
        assert_eq!(numerical_tolerance(0.0, 2), 0.0);
    }
}
