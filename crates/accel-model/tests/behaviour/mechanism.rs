//! The pseudo-second-order term k1·C_r·ω⁴/g in the output, and what least squares makes of it.

use accel_model::{PigaCoefficients, eq17, rate_point, rate_points};
use approx::assert_relative_eq;
use kinematics::ErrorMotion;

use crate::{PIGA, centrifuge, errors, paper_rates};

/// Mean output with C_r minus without equals k1·C_r·ω⁴/g at every rate, for either sign of C_r,
/// up to the products with k2 (2k2·a/k1 ≈ 2e-5) and the Coriolis factor (2ω_ie sin L/ω).
#[test]
fn output_contains_the_pseudo_second_order_term() {
    for &c_r in &[1.6e-6, -4.05e-8] {
        let base = ErrorMotion {
            c_r_m_s2: 0.0,
            ..errors()
        };
        let with = centrifuge(ErrorMotion {
            c_r_m_s2: c_r,
            ..base
        });
        let without = centrifuge(base);
        for &w in &paper_rates()[1..] {
            let d = rate_point(&with, &PIGA, w).unwrap().output_rad_s
                - rate_point(&without, &PIGA, w).unwrap().output_rad_s;
            let pseudo = eq17(&with, &PIGA, w).unwrap().pseudo_second_order_rad_s;
            assert_relative_eq!(
                pseudo,
                PIGA.k1_rad_s_g * c_r * w.powi(4) / 9.8,
                max_relative = 1e-14
            );
            assert_relative_eq!(d, pseudo, max_relative = 2e-4);
        }
    }
}

/// Least squares of the mean outputs on eq. 18's columns, rescaled to powers of a = Rω²/g,
/// returns k2 + k1·C_r·g/R² for the a² coefficient (eq. 19), before and after balancing.
#[test]
fn least_squares_reads_the_pseudo_term_as_k2() {
    let mut rates = paper_rates();
    rates.extend([30.0_f64.to_radians(), 140.0_f64.to_radians()]);
    for &c_r in &[1.6e-6, -4.05e-8] {
        let c = centrifuge(ErrorMotion {
            c_r_m_s2: c_r,
            ..errors()
        });
        let pts = rate_points(&c, &PIGA, &rates).unwrap();
        let design: Vec<[f64; 6]> = pts
            .iter()
            .map(|p| {
                let w = p.rate_rad_s;
                let a = 2.5 * w * w / 9.8;
                [1.0, w, w * w, w.powi(3), a * a, a.powi(3)]
            })
            .collect();
        let y: Vec<f64> = pts.iter().map(|p| p.output_rad_s).collect();
        let x = qr_least_squares(&design, &y);
        let delta_k2 = PIGA.k1_rad_s_g * c_r * 9.8 / (2.5 * 2.5);
        let apparent = x[4] - PIGA.k2_rad_s_g2;
        assert!(
            (apparent - delta_k2).abs() < 0.02 * delta_k2.abs(),
            "C_r = {c_r:e}: apparent Δk2 {apparent:e} vs {delta_k2:e}"
        );
        assert_relative_eq!(x[5], PIGA.k3_rad_s_g3, max_relative = 1e-2);
    }
    // a linear PIGA on an ideal spindle: no apparent k2 at all
    let lin = PigaCoefficients {
        k2_rad_s_g2: 0.0,
        k3_rad_s_g3: 0.0,
        ..PIGA
    };
    let pts = rate_points(&centrifuge(ErrorMotion::ZERO), &lin, &rates).unwrap();
    let design: Vec<[f64; 6]> = pts
        .iter()
        .map(|p| {
            let w = p.rate_rad_s;
            let a = 2.5 * w * w / 9.8;
            [1.0, w, w * w, w.powi(3), a * a, a.powi(3)]
        })
        .collect();
    let y: Vec<f64> = pts.iter().map(|p| p.output_rad_s).collect();
    let x = qr_least_squares(&design, &y);
    assert!(x[4].abs() < 1e-11, "{:e}", x[4]);
}

/// Least squares by Householder QR of the column-scaled design (test helper; the project's
/// solver lives in `identify`).
fn qr_least_squares(rows: &[[f64; 6]], y: &[f64]) -> [f64; 6] {
    // column-major copy of the design, each column scaled to unit norm
    let mut cols: Vec<Vec<f64>> = (0..6)
        .map(|j| rows.iter().map(|r| r[j]).collect())
        .collect();
    let scale: Vec<f64> = cols
        .iter()
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .collect();
    for (c, s) in cols.iter_mut().zip(&scale) {
        c.iter_mut().for_each(|x| *x /= s);
    }
    let mut b = y.to_vec();
    let reflect = |v: &[f64], x: &mut [f64]| {
        let vv: f64 = v.iter().map(|e| e * e).sum();
        let f = 2.0 * v.iter().zip(x.iter()).map(|(p, q)| p * q).sum::<f64>() / vv;
        x.iter_mut().zip(v).for_each(|(e, vi)| *e -= f * vi);
    };
    for k in 0..6 {
        let head = &cols[k][k..];
        let norm = head.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut v = head.to_vec();
        v[0] += if head[0] > 0.0 { norm } else { -norm };
        for c in cols[k..].iter_mut() {
            reflect(&v, &mut c[k..]);
        }
        reflect(&v, &mut b[k..]);
    }
    let mut x = [0.0; 6];
    for k in (0..6).rev() {
        let s: f64 = (k + 1..6).map(|j| cols[j][k] * x[j]).sum();
        x[k] = (b[k] - s) / cols[k][k];
    }
    core::array::from_fn(|j| x[j] / scale[j])
}
