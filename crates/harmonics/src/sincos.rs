//! Sine and cosine of sample angles, written so that a loop over lanes vectorises:
//! no table, no branch, no integer conversion.
//!
//! The angle is reduced to `r ∈ [−π/4, π/4]` by `θ = r + q·π/2` (Cody–Waite, π/2 split in
//! three parts so that `q·π/2` is exact for `|θ| < 2²⁵ rad`), `sin r` and `cos r` are Taylor
//! polynomials (truncation below 5·10⁻¹⁷ on `[−π/4, π/4]`), and the quadrant `q mod 4`
//! swaps and negates them.

use std::f64::consts::{FRAC_2_PI, FRAC_PI_2};

/// `π/2` with its 27 low mantissa bits cleared, so `q·PIO2_HI` is exact for `|q| < 2²⁷`.
const PIO2_HI: f64 = f64::from_bits(FRAC_PI_2.to_bits() & !((1_u64 << 27) - 1));
/// The rest of `FRAC_PI_2` (at most 27 significant bits, so `q·PIO2_MID` is exact too).
const PIO2_MID: f64 = FRAC_PI_2 - PIO2_HI;
/// `π/2 − FRAC_PI_2`, the rounding error of `FRAC_PI_2` (which is `cos(FRAC_PI_2)` in
/// double precision; a unit test checks that).
const PIO2_LO: f64 = 6.123_233_995_736_766e-17;

/// `(−1)^((n−1)/2) / n!` for odd `n` (sine) and `(−1)^(n/2) / n!` for even `n` (cosine).
const fn taylor(n: u32) -> f64 {
    let mut f = 1.0;
    let mut i = 2;
    while i <= n {
        f *= i as f64;
        i += 1;
    }
    let negative = (n / 2) % 2 == 1;
    if negative { -1.0 / f } else { 1.0 / f }
}

/// `sin θ` and `cos θ`, to within a few units in the last place for `|θ| < 2²⁵`.
#[inline(always)]
pub(crate) fn sin_cos(theta: f64) -> (f64, f64) {
    let q = (theta * FRAC_2_PI).round_ties_even();
    // q·PIO2_HI and q·PIO2_MID are exact, so the fused steps lose nothing.
    let r = (-q).mul_add(
        PIO2_LO,
        (-q).mul_add(PIO2_MID, (-q).mul_add(PIO2_HI, theta)),
    );
    let z = r * r;

    let mut ps = taylor(15);
    ps = ps.mul_add(z, taylor(13));
    ps = ps.mul_add(z, taylor(11));
    ps = ps.mul_add(z, taylor(9));
    ps = ps.mul_add(z, taylor(7));
    ps = ps.mul_add(z, taylor(5));
    ps = ps.mul_add(z, taylor(3));
    let sr = (r * z).mul_add(ps, r);

    let mut pc = taylor(16);
    pc = pc.mul_add(z, taylor(14));
    pc = pc.mul_add(z, taylor(12));
    pc = pc.mul_add(z, taylor(10));
    pc = pc.mul_add(z, taylor(8));
    pc = pc.mul_add(z, taylor(6));
    pc = pc.mul_add(z, taylor(4));
    pc = pc.mul_add(z, taylor(2));
    let cr = z.mul_add(pc, 1.0);

    // Quadrant m = q mod 4 ∈ {0, 1, 2, 3}, exactly, in floating point.
    let m = (-4.0_f64).mul_add((q * 0.25).floor(), q);
    let odd = m == 1.0 || m == 3.0;
    let (s, c) = if odd { (cr, sr) } else { (sr, cr) };
    let s = if m >= 2.0 { -s } else { s };
    let c = if m == 1.0 || m == 2.0 { -c } else { c };
    (s, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_of_half_pi_is_exact_and_complete() {
        assert_eq!(PIO2_HI + PIO2_MID, FRAC_PI_2);
        assert_eq!(PIO2_LO, FRAC_PI_2.cos());
        assert_eq!(PIO2_HI.to_bits() & ((1 << 27) - 1), 0);
    }

    #[test]
    fn taylor_coefficients() {
        assert_eq!(taylor(2), -0.5);
        assert_eq!(taylor(3), -1.0 / 6.0);
        assert_eq!(taylor(4), 1.0 / 24.0);
        assert_eq!(taylor(5), 1.0 / 120.0);
    }

    #[test]
    fn agrees_with_libm_over_many_turns() {
        let mut worst: f64 = 0.0;
        let n = 200_000;
        for i in 0..=n {
            // −1000 … 1000 rad on an irregular grid, plus exact multiples of π/4.
            let theta = -1000.0 + 2000.0 * (i as f64 / n as f64).powf(1.1);
            for t in [
                theta,
                (i as f64 - n as f64 / 2.0) * std::f64::consts::FRAC_PI_4,
            ] {
                let (s, c) = sin_cos(t);
                let (s_ref, c_ref) = t.sin_cos();
                worst = worst.max((s - s_ref).abs()).max((c - c_ref).abs());
            }
        }
        assert!(worst < 4e-16, "worst error {worst:e}");
    }

    #[test]
    fn quadrant_boundaries() {
        for q in -8..=8 {
            let t = f64::from(q) * FRAC_PI_2;
            let (s, c) = sin_cos(t);
            assert!(
                (s - t.sin()).abs() < 1e-15 && (c - t.cos()).abs() < 1e-15,
                "q = {q}"
            );
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
    }
}
