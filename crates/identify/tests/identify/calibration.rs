//! Eq. 18 identification on synthetic eq. 17 outputs, with and without compensation (eq. 19).

use approx::assert_relative_eq;
use identify::{
    Compensation, CrEstimate, Geometry, IdentifyError, K1Source, identify_calibration,
    identify_compensated,
};

const R: f64 = 2.5;
const G: f64 = 9.8;
const GEOMETRY: Geometry = Geometry {
    radius_m: R,
    g_m_s2: G,
};
const K0: f64 = 2e-5;
const K1: f64 = 0.56;
const K2: f64 = 8e-6;
const K3: f64 = -3e-7;

/// Eq. 17 with static tilt, C_φ, the Coriolis term (45° latitude) and the imbalance term.
fn outputs(rates: &[f64], c_r: f64) -> Vec<f64> {
    let (phi_ys, c_phi, dr_xs) = (3e-5, 2e-9, 1e-6);
    let coriolis = 2.0 * R * 7.292_115e-5 * std::f64::consts::FRAC_1_SQRT_2 / G;
    rates
        .iter()
        .map(|&w| {
            let a = R * w * w / G;
            (K0 + K1 * phi_ys) - phi_ys * w - c_phi * w.powi(3)
                + K1 * (R + dr_xs) * w * w / G
                + K1 * c_phi * w * w
                + K1 * coriolis * w
                + K2 * a * a
                + K1 * c_r * w.powi(4) / G
                + K3 * a.powi(3)
        })
        .collect()
}

fn rates() -> Vec<f64> {
    [
        10.0, 30.0, 60.0, 80.1234, 110.1234, 140.0, 160.1234, 200.1234,
    ]
    .iter()
    .map(|d: &f64| d.to_radians())
    .collect()
}

#[test]
fn apparent_k2_carries_delta_k2_and_compensation_removes_it() {
    // The paper's pre- and post-balance C_r (m·s²).
    for c_r in [1.597e-6, -4.0526e-8] {
        let w = rates();
        let y = outputs(&w, c_r);
        let delta_k2 = K1 * c_r * G / (R * R);
        let cal = identify_calibration(&w, &y, GEOMETRY).unwrap();
        assert!(
            (cal.k2_apparent_rad_s_g2 - K2 - delta_k2).abs() < 0.02 * delta_k2.abs(),
            "apparent k2 {} vs {}",
            cal.k2_apparent_rad_s_g2,
            K2 + delta_k2
        );
        assert_relative_eq!(cal.k3_rad_s_g3, K3, max_relative = 1e-4);
        assert!(cal.fit.warnings.is_empty());
        for k1 in [K1Source::Fitted, K1Source::Given { k1_rad_s_g: K1 }] {
            let comp = Compensation {
                c_r: CrEstimate {
                    c_r_m_s2: c_r,
                    c_r_sigma_m_s2: 0.01 * c_r.abs(),
                },
                k1,
            };
            let cal = identify_compensated(&w, &y, GEOMETRY, &comp).unwrap();
            assert!(
                (cal.k2_rad_s_g2 - K2).abs() < 0.02 * delta_k2.abs(),
                "compensated k2 {} vs {K2}",
                cal.k2_rad_s_g2
            );
            assert_relative_eq!(cal.k1_used_rad_s_g, K1, max_relative = 1e-5);
            assert!(cal.k2_sigma_rad_s_g2 >= cal.k2_sigma_from_c_r_rad_s_g2);
        }
    }
}

#[test]
fn five_distinct_rates_are_not_enough() {
    let w: Vec<f64> = rates().into_iter().take(5).cycle().take(10).collect();
    let y = outputs(&w, 0.0);
    assert_eq!(
        identify_calibration(&w, &y, GEOMETRY),
        Err(IdentifyError::TooFewDistinctRates {
            distinct: 5,
            need: 6
        })
    );
}

#[test]
fn numerically_coincident_rates_make_a_rank_deficient_design() {
    // Six distinct values, but two rates differ by 1e-13 rad/s: numerically only five.
    let mut w: Vec<f64> = rates().into_iter().take(5).collect();
    w.push(w[4] * (1.0 + 1e-13));
    w.extend(w.clone());
    let y = outputs(&w, 0.0);
    match identify_calibration(&w, &y, GEOMETRY) {
        Err(IdentifyError::RankDeficient { rank, unknowns, .. }) => {
            assert_eq!(unknowns, 6);
            assert!(rank < 6, "rank {rank}");
        }
        other => panic!("expected RankDeficient, got {other:?}"),
    }
}
