//! The exact chain against the paper's first-order eq. 14.

use approx::assert_relative_eq;
use kinematics::{Chain, ErrorMotion};

use crate::{centrifuge, errors};

/// (exact mean a_x − eq. 14 − Coriolis, exact mean ω_I − eq. 14 − Earth term) at one scale.
fn residuals(scale: f64, rate_rad_s: f64) -> (f64, f64) {
    let chain = Chain::new(&centrifuge(errors().scaled(scale)), rate_rad_s).unwrap();
    let mean = chain.mean_inputs(3).unwrap();
    let fo = chain.first_order();
    (
        mean.a_x_g() - (fo.a_x_g + fo.coriolis_a_x_g),
        mean.omega_i_rad_s() - (fo.omega_i_rad_s + fo.earth_omega_i_rad_s),
    )
}

/// Scaling every error coefficient by 1/10 scales the a_x residual by 1/100, over three
/// decades (1e2 … 1e-1 times a realistic error motion), at three rates of the paper's table: eq. 14 (+ Coriolis) is right to first order and
/// the leading neglected term (−R ω² Δφ_y²/g among others) is genuinely quadratic. The ω_I
/// residual is at most quadratic (in fact cubic: (ω + ω_ie sin L)(sin Δφ_y cos Δφ_x − Δφ_y)).
#[test]
fn residual_shrinks_quadratically() {
    for &deg_s in &[10.0, 80.1234, 200.1234] {
        let w = f64::to_radians(deg_s);
        let scales = [1e2, 1e1, 1.0, 0.1];
        let r: Vec<(f64, f64)> = scales.iter().map(|&s| residuals(s, w)).collect();
        for k in 0..scales.len() - 1 {
            let (ax0, _) = r[k];
            let (ax1, _) = r[k + 1];
            assert!(ax1.abs() > 1e-16, "residual too small to measure: {ax1:e}");
            // 100 ± 6%: at 10 °/s the cubic gravity term Δφ_y·Δφ_x²/2 is still 4% of the
            // (small, ∝ ω²) quadratic one at the largest scale; linear would give 10
            assert_relative_eq!(ax0 / ax1, 100.0, max_relative = 0.06);
        }
        let wi_top = r[0].1.abs();
        assert!(wi_top > 0.0);
        for (k, &s) in scales.iter().enumerate() {
            let bound = wi_top * (s / scales[0]).powi(2) * 1.05 + 1e-21;
            assert!(r[k].1.abs() <= bound, "scale {s}: {:e} > {bound:e}", r[k].1);
        }
        // at the realistic scale the neglected terms stay below 1e-8 g
        assert!(r[2].0.abs() < 1e-8, "{:e}", r[2].0);
    }
}

/// Without the Coriolis term, eq. 14 misses 2R·ω·ω_ie·sin L/g, a first-order quantity
/// (≈ 9e-5 g at 200 °/s, R = 2.5 m, L = 45°) that does not vanish with the error motion.
#[test]
fn coriolis_term_is_in_the_mean() {
    for &lat in &[45.0, 45.75, -30.0] {
        for &deg_s in &[10.0, 200.1234] {
            let w = f64::to_radians(deg_s);
            let mut c = centrifuge(ErrorMotion::ZERO);
            c.site.latitude_deg = lat;
            let chain = Chain::new(&c, w).unwrap();
            let mean = chain.mean_inputs(3).unwrap();
            let expected =
                2.0 * 2.5 * w * kinematics::EARTH_RATE_RAD_S * f64::to_radians(lat).sin() / 9.8;
            assert_relative_eq!(
                mean.a_x_g() - chain.first_order().a_x_g,
                expected,
                max_relative = 1e-9
            );
            assert_relative_eq!(mean.coriolis_g[0], expected, max_relative = 1e-12);
        }
    }
    // the magnitude quoted in NOTES.md
    let mut c = centrifuge(ErrorMotion::ZERO);
    c.site.latitude_deg = 45.0;
    let chain = Chain::new(&c, f64::to_radians(200.0)).unwrap();
    let m = chain.mean_inputs(3).unwrap().coriolis_g[0];
    assert!((8.5e-5..9.5e-5).contains(&m), "{m:e}");
    // with error motion the mean Coriolis term is exactly 2ω·ω_ie sin L·(cos Δφ_y p_x +
    // sin Δφ_x sin Δφ_y p_y)/g, i.e. 2(R + Δr_x)·ω·ω_ie sin L/g to first order
    let c = centrifuge(errors().scaled(1e3));
    let w = 3.0;
    let chain = Chain::new(&c, w).unwrap();
    let off = chain.offsets();
    let (sx, _) = off.dphi_x_rad.sin_cos();
    let (sy, cy) = off.dphi_y_rad.sin_cos();
    let (px, py) = (off.dr_x_m + 2.5 * cy, off.dr_y_m + 2.5 * sx * sy);
    let oz = c.site.earth_rate_vertical_rad_s();
    let m = chain.mean_inputs(3).unwrap().coriolis_g[0];
    assert_relative_eq!(
        m,
        2.0 * w * oz * (cy * px + sx * sy * py) / 9.8,
        max_relative = 1e-12
    );
    let fo = chain.first_order();
    assert_relative_eq!(m, fo.coriolis_a_x_g, max_relative = 1e-4);
    assert!((m - fo.coriolis_a_x_g).abs() > 1e-12 * m);
}

/// The dynamic radius error is what eq. 14 says: its share of a_x is C_r ω⁴/g.
#[test]
fn dynamic_radius_error_enters_as_c_r_omega4_over_g() {
    let c_r = 1.6e-6;
    let w = f64::to_radians(200.1234);
    let with = Chain::new(
        &centrifuge(ErrorMotion {
            c_r_m_s2: c_r,
            ..ErrorMotion::ZERO
        }),
        w,
    )
    .unwrap();
    let without = Chain::new(&centrifuge(ErrorMotion::ZERO), w).unwrap();
    let oz = with.site().earth_rate_vertical_rad_s();
    let d = with.mean_inputs(3).unwrap().a_x_g() - without.mean_inputs(3).unwrap().a_x_g();
    // exact: C_r ω² (ω² + 2ω ω_ie sin L)/g
    assert_relative_eq!(
        d,
        c_r * w * w * (w * w + 2.0 * w * oz) / 9.8,
        max_relative = 1e-9
    );
    assert_relative_eq!(d, c_r * w.powi(4) / 9.8, max_relative = 1e-4);
}
