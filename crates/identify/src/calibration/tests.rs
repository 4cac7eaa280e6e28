//! The tests of the eq. 18 calibration and its compensation.

use super::*;
use crate::design::Design;
use crate::error::IdentifyError;
use crate::geometry::Geometry;
use crate::lstsq::{LstsqOptions, lstsq_design};
use crate::radius::CrEstimate;
use approx::assert_relative_eq;

const R: f64 = 2.5;
const G: f64 = 9.8;
const GEOMETRY: Geometry = Geometry {
    radius_m: R,
    g_m_s2: G,
};

fn rates(n: usize) -> Vec<f64> {
    (1..=n)
        .map(|i| (200.0 * i as f64 / n as f64).to_radians())
        .collect()
}

/// Output of eq. 17 with every term, for given coefficients.
fn outputs(rates: &[f64], k: [f64; 6], noise: f64) -> Vec<f64> {
    rates
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let a = R * w * w / G;
            k[0] + k[1] * w
                + k[2] * w * w
                + k[3] * w.powi(3)
                + k[4] * a * a
                + k[5] * a.powi(3)
                + noise * if i % 2 == 0 { 1.0 } else { -1.0 }
        })
        .collect()
}

#[test]
fn recovers_every_coefficient() {
    let w = rates(9);
    let truth = [1e-4, -2e-6, 0.56 * R / G, 3e-8, 5e-6, -2e-7];
    let cal = identify_calibration(&w, &outputs(&w, truth, 0.0), GEOMETRY).unwrap();
    assert_relative_eq!(cal.bias_rad_s, truth[0], max_relative = 1e-8);
    assert_relative_eq!(cal.omega_coeff, truth[1], max_relative = 1e-7);
    assert_relative_eq!(cal.omega2_coeff_s, truth[2], max_relative = 1e-12);
    assert_relative_eq!(cal.k1_implied_rad_s_g, 0.56, max_relative = 1e-12);
    assert_relative_eq!(cal.omega3_coeff_s2, truth[3], max_relative = 1e-6);
    assert_relative_eq!(cal.k2_apparent_rad_s_g2, truth[4], max_relative = 1e-7);
    assert_relative_eq!(cal.k3_rad_s_g3, truth[5], max_relative = 1e-6);
    assert_eq!(cal.distinct_rates, 9);
    assert_eq!(cal.fit.dof, 3);
}

#[test]
fn a_scaling_is_the_unscaled_fit_rescaled() {
    // The coefficient of a² is (g/R)² times that of ω⁴, and of a³ (g/R)³ times that of ω⁶.
    let w = rates(8);
    let y = outputs(&w, [0.0, 1e-6, 0.1428, 0.0, 4e-6, 1e-7], 1e-9);
    let cal = identify_calibration(&w, &y, GEOMETRY).unwrap();
    let raw = lstsq_design(
        &Design::powers(&w, &[0, 1, 2, 3, 4, 6]),
        &y,
        &LstsqOptions::default(),
    )
    .unwrap();
    assert_relative_eq!(
        cal.k2_apparent_rad_s_g2,
        raw.coefficients[4] * (G / R).powi(2),
        max_relative = 1e-9
    );
    assert_relative_eq!(
        cal.k3_rad_s_g3,
        raw.coefficients[5] * (G / R).powi(3),
        max_relative = 1e-9
    );
    assert_relative_eq!(
        cal.k2_apparent_sigma_rad_s_g2,
        raw.std_errors[4] * (G / R).powi(2),
        max_relative = 1e-9
    );
}

#[test]
fn compensation_removes_delta_k2_and_propagates_sigma() {
    let (k1, k2, c_r, sigma) = (0.56, 5e-6, 1.6e-6, 0.1e-6);
    let w = rates(8);
    let mut y = outputs(&w, [0.0, 0.0, k1 * R / G, 0.0, k2, 0.0], 1e-12);
    for (y, w) in y.iter_mut().zip(&w) {
        *y += k1 * c_r * w.powi(4) / G;
    }
    let dk2 = k1 * c_r * G / (R * R);
    for source in [K1Source::Fitted, K1Source::Given { k1_rad_s_g: k1 }] {
        let comp = Compensation {
            c_r: CrEstimate {
                c_r_m_s2: c_r,
                c_r_sigma_m_s2: sigma,
            },
            k1: source,
        };
        let cal = identify_compensated(&w, &y, GEOMETRY, &comp).unwrap();
        // Within a few of the fit's own standard errors (the noise is ±1e-12 rad/s).
        let fit_sigma = cal.compensated.k2_apparent_sigma_rad_s_g2;
        assert!((cal.uncompensated.k2_apparent_rad_s_g2 - (k2 + dk2)).abs() < 5.0 * fit_sigma);
        assert!((cal.k2_rad_s_g2 - k2).abs() < 5.0 * fit_sigma);
        assert_relative_eq!(cal.delta_k2.delta_k2_rad_s_g2, dk2, max_relative = 1e-6);
        assert_relative_eq!(
            cal.k2_sigma_from_c_r_rad_s_g2,
            k1 * G / (R * R) * sigma,
            max_relative = 1e-6
        );
        // The fit alone is far more precise than C_r here: σ(C_r) dominates.
        assert!(fit_sigma < 0.01 * cal.k2_sigma_from_c_r_rad_s_g2);
        assert_relative_eq!(
            cal.k2_sigma_rad_s_g2,
            cal.k2_sigma_from_c_r_rad_s_g2,
            max_relative = 1e-3
        );
        // Residuals are unchanged by the compensation.
        assert_relative_eq!(
            cal.compensated.fit.residual_sd,
            cal.uncompensated.fit.residual_sd,
            max_relative = 1e-6
        );
    }
}

/// Monte Carlo check of the reported σ of the compensated k2: the empirical spread over
/// repeated noisy experiments must match it. A sign error in the cross term
/// `2·d·cov(c2, c4)`, or a missing term, shifts the reported σ far outside the tolerance.
#[test]
fn compensated_k2_sigma_matches_monte_carlo() {
    use rand::SeedableRng;
    use rand::rngs::StdRng;
    use rand_distr::{Distribution, Normal};

    const DRAWS: usize = 2000;
    // C_r is exaggerated (a real one is ~1e-6 m·s²) so that d = −C_r·g²/R³ = −1 and the
    // k1 terms are as large as the fit's own: with these 8 rates corr(c2, c4) = +0.98, and
    // the fitted-k1 fit variance is var(c4) + var(c2) − 2·cov(c2, c4) ≈ 0.18·var(c4).
    // σ(C_r) contributes about as much as the fit. Measured: empirical sd 4.39e-8, reported
    // 4.24e-8 (fitted k1); 7.97e-8 and 8.19e-8 (given k1). With the cross term's sign
    // flipped the reported σ is 1.25e-7 (2.9×), with it dropped 9.4e-8 (2.1×).
    let c_r = R.powi(3) / (G * G);
    let (k1, k2, c_r_sigma, noise_sd) = (0.56, 5e-6, 3e-8, 1e-9);
    let w = rates(8);
    let clean: Vec<f64> = outputs(&w, [1e-4, 2e-6, k1 * R / G, 0.0, k2, 1e-7], 0.0)
        .iter()
        .zip(&w)
        .map(|(y, w)| y + k1 * c_r * w.powi(4) / G)
        .collect();
    let noise = Normal::new(0.0, noise_sd).unwrap();
    let c_r_draw = Normal::new(c_r, c_r_sigma).unwrap();
    for (seed, source) in [
        (1, K1Source::Fitted),
        (2, K1Source::Given { k1_rad_s_g: k1 }),
    ] {
        let mut rng = StdRng::seed_from_u64(seed);
        let (mut sum, mut sum_sq, mut reported_var) = (0.0, 0.0, 0.0);
        for _ in 0..DRAWS {
            let y: Vec<f64> = clean.iter().map(|y| y + noise.sample(&mut rng)).collect();
            let comp = Compensation {
                c_r: CrEstimate {
                    c_r_m_s2: c_r_draw.sample(&mut rng),
                    c_r_sigma_m_s2: c_r_sigma,
                },
                k1: source,
            };
            let cal = identify_compensated(&w, &y, GEOMETRY, &comp).unwrap();
            let dev = cal.k2_rad_s_g2 - k2;
            sum += dev;
            sum_sq += dev * dev;
            reported_var += cal.k2_sigma_rad_s_g2.powi(2);
        }
        let n = DRAWS as f64;
        let mean = sum / n;
        let empirical_sd = ((sum_sq - n * mean * mean) / (n - 1.0)).sqrt();
        // Each draw's σ scales with its own residual variance s² (2 degrees of freedom), whose
        // mean is the true noise variance: compare with the RMS of the reported σ.
        let reported_sd = (reported_var / n).sqrt();
        assert_relative_eq!(empirical_sd, reported_sd, max_relative = 0.1);
        // Unbiased: the mean is within 4 standard errors of the truth.
        assert!(
            mean.abs() < 4.0 * empirical_sd / n.sqrt(),
            "{source:?}: mean {mean:e}"
        );
    }
}

#[test]
fn a_tiny_radius_is_a_named_non_finite_result_not_a_nan_sigma() {
    // R = 1e-80 m: a = R·ω²/g ≈ 1e-80, so the a³ coefficient's variance ≈ 1e480 overflows.
    // Before: Ok with σ(k2) = NaN (`cargo xtask identify --radius-m 1e-80`).
    let w = rates(8);
    let y = outputs(&w, [1e-5, 1e-6, 0.1428, 0.0, 4e-6, 1e-7], 1e-7);
    let tiny = Geometry {
        radius_m: 1e-80,
        g_m_s2: G,
    };
    let err = identify_calibration(&w, &y, tiny).unwrap_err();
    let IdentifyError::NonFiniteResult {
        quantity, inputs, ..
    } = &err
    else {
        panic!("{err:?}");
    };
    assert!(
        quantity.contains("sigma") || quantity.contains("covariance"),
        "{quantity}"
    );
    assert!(inputs.contains(&("radius_m", 1e-80)));
    assert!(err.to_string().contains("radius_m = 1e-80"), "{err}");
    let comp = Compensation {
        c_r: CrEstimate {
            c_r_m_s2: 1e-6,
            c_r_sigma_m_s2: 1e-8,
        },
        k1: K1Source::Fitted,
    };
    assert!(matches!(
        identify_compensated(&w, &y, tiny, &comp),
        Err(IdentifyError::NonFiniteResult { .. })
    ));
    // Further out, (R/g)³ itself leaves the range: the radius is named (before: the
    // internal "factors = inf", or a rank deficiency for a column of zeros).
    for radius_m in [1e-120, 1e120] {
        let err = identify_calibration(
            &w,
            &y,
            Geometry {
                radius_m,
                g_m_s2: G,
            },
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                IdentifyError::InvalidParameter {
                    name: "radius_m",
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(!err.to_string().contains("factors"), "{err}");
    }
}

#[test]
fn typed_errors() {
    let w = rates(5);
    let y = outputs(&w, [0.0, 0.0, 0.1, 0.0, 0.0, 0.0], 0.0);
    assert_eq!(
        identify_calibration(&w, &y, GEOMETRY),
        Err(IdentifyError::TooFewDistinctRates {
            distinct: 5,
            need: 6
        })
    );
    // Ten points but only five distinct rates.
    let w2: Vec<f64> = w.iter().chain(&w).copied().collect();
    let y2: Vec<f64> = y.iter().chain(&y).copied().collect();
    assert_eq!(
        identify_calibration(&w2, &y2, GEOMETRY),
        Err(IdentifyError::TooFewDistinctRates {
            distinct: 5,
            need: 6
        })
    );
    let w = rates(6);
    let y = outputs(&w, [0.0, 0.0, 0.1, 0.0, 0.0, 0.0], 0.0);
    assert_eq!(
        identify_calibration(&w, &y, GEOMETRY),
        Err(IdentifyError::TooFewObservations {
            observations: 6,
            unknowns: 6
        })
    );
    assert!(matches!(
        identify_calibration(
            &w,
            &y,
            Geometry {
                radius_m: -R,
                ..GEOMETRY
            }
        ),
        Err(IdentifyError::InvalidParameter {
            name: "radius_m",
            ..
        })
    ));
    assert!(matches!(
        identify_calibration(&w, &y[..5], GEOMETRY),
        Err(IdentifyError::DimensionMismatch { .. })
    ));
    let mut bad = w.clone();
    bad[2] = f64::NAN;
    assert_eq!(
        identify_calibration(&bad, &y, GEOMETRY),
        Err(IdentifyError::NonFinite {
            row: 2,
            column: Some(1)
        })
    );
    let comp = Compensation {
        c_r: CrEstimate {
            c_r_m_s2: f64::NAN,
            c_r_sigma_m_s2: 0.0,
        },
        k1: K1Source::Fitted,
    };
    assert!(matches!(
        identify_compensated(&w, &y, GEOMETRY, &comp),
        Err(IdentifyError::InvalidParameter {
            name: "c_r_m_s2",
            ..
        })
    ));
}

#[test]
fn weighted_fit_with_equal_sigmas_has_the_ordinary_coefficients() {
    let w = rates(9);
    let y = outputs(&w, [1e-4, -2e-6, 0.56 * R / G, 3e-8, 5e-6, -2e-7], 1e-7);
    let plain = identify_calibration(&w, &y, GEOMETRY).unwrap();
    // σ far above the scatter: Birge ratio < 1, the covariance is (XᵀWX)⁻¹ unshrunk.
    let weighted = identify_calibration_weighted(&w, &y, &[1e-5; 9], GEOMETRY).unwrap();
    let birge = weighted.birge_ratio.unwrap();
    assert!(birge < 0.1, "{birge}");
    for k in 0..6 {
        assert_relative_eq!(
            weighted.fit.coefficients[k],
            plain.fit.coefficients[k],
            max_relative = 1e-9,
            epsilon = 1e-20
        );
        // Unweighted σ scales with the residual SD; the weighted one with the given σ.
        assert_relative_eq!(
            weighted.fit.std_errors[k] * plain.fit.residual_sd,
            plain.fit.std_errors[k] * 1e-5,
            max_relative = 1e-9
        );
    }
    for (a, b) in weighted.residuals_rad_s.iter().zip(&plain.residuals_rad_s) {
        assert_relative_eq!(*a, *b, max_relative = 1e-6, epsilon = 1e-15);
    }
    assert_eq!(plain.birge_ratio, None);
    // σ far below the scatter: the covariance grows by the Birge ratio squared, which
    // makes it the ordinary (residual-scaled) one.
    let tight = identify_calibration_weighted(&w, &y, &[1e-10; 9], GEOMETRY).unwrap();
    assert!(tight.birge_ratio.unwrap() > 1.0);
    for k in 0..6 {
        assert_relative_eq!(
            tight.fit.std_errors[k],
            plain.fit.std_errors[k],
            max_relative = 1e-9
        );
    }
}

#[test]
fn a_point_with_a_large_sigma_hardly_counts() {
    let w = rates(10);
    let mut y = outputs(&w, [1e-4, -2e-6, 0.56 * R / G, 3e-8, 5e-6, -2e-7], 1e-9);
    let mut sigma = vec![1e-9; 10];
    // A disturbed point declared as such.
    y[4] += 1e-4;
    sigma[4] = 1e-2;
    let weighted = identify_calibration_weighted(&w, &y, &sigma, GEOMETRY).unwrap();
    let plain = identify_calibration(&w, &y, GEOMETRY).unwrap();
    // The weighted fit is the fit of the other nine points.
    let (w9, y9): (Vec<f64>, Vec<f64>) = w
        .iter()
        .zip(&y)
        .enumerate()
        .filter(|(i, _)| *i != 4)
        .map(|(_, (a, b))| (*a, *b))
        .unzip();
    let without = identify_calibration(&w9, &y9, GEOMETRY).unwrap();
    let from_without =
        |c: &Calibration| (c.k2_apparent_rad_s_g2 - without.k2_apparent_rad_s_g2).abs();
    assert!(
        from_without(&weighted) < 1e-12,
        "{}",
        from_without(&weighted)
    );
    assert!(from_without(&plain) > 1e-6, "{}", from_without(&plain));
}

#[test]
fn a_sigma_that_is_not_positive_is_refused() {
    let w = rates(8);
    let y = outputs(&w, [0.0, 0.0, 0.1, 0.0, 1e-6, 0.0], 1e-9);
    for bad in [0.0, -1e-9, f64::NAN, f64::INFINITY] {
        let mut sigma = vec![1e-9; 8];
        sigma[3] = bad;
        let err = identify_calibration_weighted(&w, &y, &sigma, GEOMETRY).unwrap_err();
        assert!(
            matches!(
                err,
                IdentifyError::InvalidParameter {
                    name: "sigma_rad_s",
                    ..
                }
            ),
            "{err:?}"
        );
    }
    let err = identify_calibration_weighted(&w, &y, &[1e-9; 7], GEOMETRY).unwrap_err();
    assert!(matches!(err, IdentifyError::DimensionMismatch { .. }));
}
