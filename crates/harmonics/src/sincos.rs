//! Sine and cosine of sample angles, written so that a loop over lanes vectorises:
//! no table, no branch, no integer conversion.
//!
//! The angle is reduced to `r ∈ [−π/4, π/4]` by `θ = r + q·π/2` (Cody–Waite, π/2 split in
//! three parts so that `q·π/2` is exact for `|θ| < 2²⁵ rad`), `sin r` and `cos r` are fdlibm's
//! minimax polynomials (error below 2⁻⁵⁸ on `[−π/4, π/4]`), and the quadrant `q mod 4`
//! swaps and negates them.

use std::f64::consts::{FRAC_2_PI, FRAC_PI_2};

/// `π/2` with its 27 low mantissa bits cleared, so `q·PIO2_HI` is exact for `|q| < 2²⁷`.
const PIO2_HI: f64 = f64::from_bits(FRAC_PI_2.to_bits() & !((1_u64 << 27) - 1));
/// The rest of `FRAC_PI_2` (at most 27 significant bits, so `q·PIO2_MID` is exact too).
const PIO2_MID: f64 = FRAC_PI_2 - PIO2_HI;
/// `π/2 − FRAC_PI_2`, the rounding error of `FRAC_PI_2` (which is `cos(FRAC_PI_2)` in
/// double precision; a unit test checks that).
const PIO2_LO: f64 = 6.123_233_995_736_766e-17;

/// fdlibm's `S1…S6` (`__kernel_sin`): `sin r ≈ r + r·z·(S1 + z·(S2 + …))`, `z = r²`.
#[allow(clippy::excessive_precision)] // the published decimals
const SIN: [f64; 6] = [
    -1.666_666_666_666_663_243_48e-1,
    8.333_333_333_322_489_461_24e-3,
    -1.984_126_982_985_794_931_34e-4,
    2.755_731_370_707_006_767_89e-6,
    -2.505_076_025_340_686_341_95e-8,
    1.589_690_995_211_550_102_21e-10,
];
/// fdlibm's `C1…C6` (`__kernel_cos`): `cos r ≈ 1 − z/2 + z²·(C1 + z·(C2 + …))`.
#[allow(clippy::excessive_precision)] // the published decimals
const COS: [f64; 6] = [
    4.166_666_666_666_660_190_37e-2,
    -1.388_888_888_887_410_957_49e-3,
    2.480_158_728_947_672_941_78e-5,
    -2.755_731_435_139_066_330_35e-7,
    2.087_572_321_298_174_827_90e-9,
    -1.135_964_755_778_819_482_65e-11,
];

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

    // fdlibm's minimax polynomials for [−π/4, π/4] (k_sin.c, k_cos.c; error below 2⁻⁵⁸):
    // one term fewer each than the Taylor series to the same accuracy.
    let ps = z.mul_add(
        z.mul_add(
            z.mul_add(z.mul_add(z.mul_add(SIN[5], SIN[4]), SIN[3]), SIN[2]),
            SIN[1],
        ),
        SIN[0],
    );
    let sr = (r * z).mul_add(ps, r);
    let pc = z.mul_add(
        z.mul_add(
            z.mul_add(z.mul_add(z.mul_add(COS[5], COS[4]), COS[3]), COS[2]),
            COS[1],
        ),
        COS[0],
    );
    let cr = (z * z).mul_add(pc, (-0.5_f64).mul_add(z, 1.0));

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
    fn minimax_coefficients_are_near_taylor() {
        // The minimax polynomials differ from the series' 1/n! by at most 1 % (the last
        // terms; the first two agree to 1e-11): a wrong sign, order or digit shows.
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for (i, c) in SIN.iter().enumerate() {
            let n = 2 * i as u32 + 3;
            let taylor = if i % 2 == 0 { -1.0 } else { 1.0 } / fact(n);
            assert!((c / taylor - 1.0).abs() < 1.5e-2, "sin term {n}");
        }
        for (i, c) in COS.iter().enumerate() {
            let n = 2 * i as u32 + 4;
            let taylor = if i % 2 == 0 { 1.0 } else { -1.0 } / fact(n);
            assert!((c / taylor - 1.0).abs() < 1.5e-2, "cos term {n}");
        }
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
