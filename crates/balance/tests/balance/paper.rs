//! The paper check: what the published pre-balance change of radius error determines.

use approx::assert_relative_eq;
use balance::radius_change_advice;

use crate::common::{context, plane};

#[test]
fn the_papers_pre_balance_change_in_the_empirical_formulas_units() {
    let from = 10.0_f64.to_radians();
    let to = 200.1234_f64.to_radians();
    // k_r of the pre-balance scenario (fixtures/scenarios/pre-balance.ron)
    let a = radius_change_advice(19.4640, from, to, 5.0e7, &plane(), &context()).unwrap();
    let dw2 = to * to - from * from;
    assert_relative_eq!(a.c_r_m_s2, 19.4640e-6 / dw2, max_relative = 1e-12);
    assert_relative_eq!(a.c_r_m_s2, 1.599e-6, max_relative = 1e-3);
    assert_relative_eq!(a.delta_k2_rad_s_g2, 1.40e-6, max_relative = 5e-3);
    // k_r/(ω₂² − ω₁²) per µm: 5e7 N/m / 12.17 (rad/s)² = 4.11 kg·m = 4.11e6 g·mm per µm
    assert_relative_eq!(a.unbalance_per_um_g_mm, 5.0e7 / dw2, max_relative = 1e-12);
    assert_relative_eq!(
        a.unbalance_x_g_mm,
        19.4640 * a.unbalance_per_um_g_mm,
        max_relative = 1e-12
    );
    // 80 kg·m: 32 kg at 2.5 m, opposite the arm if the imbalance lies on it
    assert_relative_eq!(a.correction_mass_kg, 32.0, max_relative = 2e-3);
    assert_eq!(a.correction_azimuth_deg, 180.0);
}
