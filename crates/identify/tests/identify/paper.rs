//! The paper's post-balance radius-error fit (Table 1) and eq. 19, as checked in NOTES.md.

use approx::assert_relative_eq;
use identify::{Geometry, RadiusModel, fit_radius_error, pseudo_second_order};

const RATE_DEG_S: [f64; 6] = [10.0, 60.0, 80.1234, 110.1234, 160.1234, 200.1234];
const RADIUS_ERROR_UM: [f64; 6] = [5.5980, 5.5453, 5.5102, 5.4251, 5.2531, 5.1079];

fn inputs() -> (Vec<f64>, Vec<f64>) {
    (
        RATE_DEG_S.iter().map(|d| d.to_radians()).collect(),
        RADIUS_ERROR_UM.iter().map(|u| u * 1e-6).collect(),
    )
}

#[test]
fn two_term_fit_matches_notes() {
    let (w, e) = inputs();
    let fit = fit_radius_error(&w, &e, RadiusModel::TwoTerm).unwrap();
    assert_relative_eq!(fit.c_r_m_s2, -4.0526e-8, max_relative = 1e-4);
    assert_relative_eq!(fit.c_r_sigma_m_s2, 0.139e-8, max_relative = 5e-3);
    assert_eq!(fit.fit.dof, 4);
}

#[test]
fn three_term_fit_matches_notes() {
    let (w, e) = inputs();
    let fit = fit_radius_error(&w, &e, RadiusModel::ThreeTerm).unwrap();
    assert_relative_eq!(fit.c_r_m_s2, -3.28e-8, max_relative = 5e-3);
    assert_relative_eq!(fit.c_r_sigma_m_s2, 0.393e-8, max_relative = 5e-3);
    assert_eq!(fit.fit.dof, 3);
}

#[test]
fn pseudo_second_order_matches_notes() {
    let (w, e) = inputs();
    let fit = fit_radius_error(&w, &e, RadiusModel::TwoTerm).unwrap();
    let geometry = Geometry {
        radius_m: 2.5,
        g_m_s2: 9.8,
    };
    let p = pseudo_second_order(0.56, fit.c_r(), geometry).unwrap();
    assert_relative_eq!(p.delta_k2_rad_s_g2, -3.56e-8, max_relative = 2e-3);
    assert_relative_eq!(
        p.sigma_rad_s_g2,
        0.56 * 9.8 / 6.25 * fit.c_r_sigma_m_s2,
        max_relative = 1e-14
    );
}
