//! Exact mean output against the closed form eq. 17.

use accel_model::{AxisInputs, PigaCoefficients, eq17, mean_output_rad_s, rate_point};
use approx::assert_relative_eq;
use kinematics::{Chain, ErrorMotion};

use crate::{PIGA, centrifuge, errors, paper_rates};

/// Eq. 15 evaluated at the first-order mean inputs (eq. 14 + Earth-rate terms).
fn model_at_first_order_inputs(chain: &Chain, piga: &PigaCoefficients) -> f64 {
    let fo = chain.first_order();
    piga.output_rad_s(AxisInputs {
        a_x_g: fo.a_x_g + fo.coriolis_a_x_g,
        omega_i_rad_s: fo.omega_i_rad_s + fo.earth_omega_i_rad_s,
    })
}

/// A linear PIGA (k2 = k3 = 0): exact mean − (eq. 17 + Earth-rate terms) is quadratic in the
/// error motion — scaling every error coefficient by 1/10 divides it by 100.
#[test]
fn linear_piga_agrees_with_eq17_to_second_order() {
    let piga = PigaCoefficients {
        k2_rad_s_g2: 0.0,
        k3_rad_s_g3: 0.0,
        ..PIGA
    };
    for &w in &paper_rates()[1..] {
        let resid = |s: f64| {
            let c = centrifuge(errors().scaled(s));
            let exact = rate_point(&c, &piga, w).unwrap().output_rad_s;
            exact - eq17(&c, &piga, w).unwrap().total_with_earth_rate_rad_s()
        };
        let r: Vec<f64> = [1e2, 1e1, 1.0, 0.1].iter().map(|&s| resid(s)).collect();
        for k in 0..3 {
            assert!(r[k + 1].abs() > 1e-15, "{:e}", r[k + 1]);
            assert_relative_eq!(r[k] / r[k + 1], 100.0, max_relative = 0.06);
        }
        // realistic magnitudes: the remainder is far below the pseudo-second-order term
        let pseudo = eq17(&centrifuge(errors()), &piga, w)
            .unwrap()
            .pseudo_second_order_rad_s;
        assert!(r[2].abs() < 1e-3 * pseudo.abs(), "{:e} vs {pseudo:e}", r[2]);
    }
}

/// Eq. 17 as printed misses the Coriolis term `2k1·R·ω·ω_ie sin L/g`; with an ideal spindle the
/// whole difference is that term plus its products with k2 and k3 (`a_x = a + c` exactly).
#[test]
fn eq17_misses_the_coriolis_term() {
    let c = centrifuge(ErrorMotion::ZERO);
    for &w in &paper_rates() {
        let exact = rate_point(&c, &PIGA, w).unwrap().output_rad_s;
        let terms = eq17(&c, &PIGA, w).unwrap();
        let a = 2.5 * w * w / 9.8;
        let cor = 2.0 * 2.5 * w * c.site.earth_rate_vertical_rad_s() / 9.8;
        assert_relative_eq!(
            terms.earth_rate_rad_s,
            PIGA.k1_rad_s_g * cor,
            max_relative = 1e-14
        );
        let predicted = PIGA.k1_rad_s_g * cor
            + PIGA.k2_rad_s_g2 * ((a + cor).powi(2) - a * a)
            + PIGA.k3_rad_s_g3 * ((a + cor).powi(3) - a.powi(3));
        assert_relative_eq!(exact - terms.total_rad_s(), predicted, max_relative = 1e-8);
        // and it is not negligible: at 200 °/s about 5e-5 rad/s
        if w > 3.0 {
            assert!((exact - terms.total_rad_s()) > 4e-5);
        }
    }
}

/// Non-linear PIGA with error motion: eq. 17 (+ Earth terms) differs from the exact mean at
/// first order only by the products of k2, k3 with the input error that eq. 17 drops (it takes
/// a_x nominal inside k2·a_x², k3·a_x³). Eq. 15 at the first-order inputs accounts for them;
/// what remains is quadratic in the error motion.
#[test]
fn nonlinear_piga_agrees_to_the_expected_order() {
    for &w in &paper_rates()[1..] {
        let parts = |s: f64| {
            let c = centrifuge(errors().scaled(s));
            let chain = Chain::new(&c, w).unwrap();
            let exact = rate_point(&c, &PIGA, w).unwrap().output_rad_s;
            let eq17_earth = eq17(&c, &PIGA, w).unwrap().total_with_earth_rate_rad_s();
            let first = model_at_first_order_inputs(&chain, &PIGA);
            (exact - eq17_earth, exact - first, first - eq17_earth)
        };
        let r: Vec<(f64, f64, f64)> = [1e2, 1e1, 1.0].iter().map(|&s| parts(s)).collect();
        for k in 0..2 {
            assert_relative_eq!(r[k].1 / r[k + 1].1, 100.0, max_relative = 0.06);
        }
        // at the realistic scale the dropped k2/k3 cross terms dominate eq. 17's error …
        let (vs_eq17, vs_first, cross) = r[2];
        assert!(cross.abs() > 3.0 * vs_first.abs(), "{cross:e} {vs_first:e}");
        // … and are of the expected size 2k2·a·δ + 3k3·a²·δ with δ = ⟨a_x⟩ − Rω²/g
        let chain = Chain::new(&centrifuge(errors()), w).unwrap();
        let fo = chain.first_order();
        let a = 2.5 * w * w / 9.8;
        let delta = fo.a_x_g + fo.coriolis_a_x_g - a;
        let expected = 2.0 * PIGA.k2_rad_s_g2 * a * delta + 3.0 * PIGA.k3_rad_s_g3 * a * a * delta;
        assert_relative_eq!(cross, expected, max_relative = 1e-3);
        assert_relative_eq!(vs_eq17, vs_first + cross, max_relative = 1e-9);
    }
}

/// The mean is exact with the minimal 7-node rule: a dense rule agrees to rounding.
#[test]
fn minimal_rule_is_exact() {
    let c = centrifuge(errors().scaled(100.0));
    for &w in &paper_rates() {
        let chain = Chain::new(&c, w).unwrap();
        let m7 = mean_output_rad_s(&chain, &PIGA, 7).unwrap();
        let m101 = mean_output_rad_s(&chain, &PIGA, 101).unwrap();
        assert_relative_eq!(m7, m101, max_relative = 1e-14);
        // rate_point and mean_output_rad_s share one quadrature: identical with 7 nodes
        assert_eq!(rate_point(&c, &PIGA, w).unwrap().output_rad_s, m7);
        // and the mean of the instantaneous output is the same sum
        let q =
            kinematics::RevolutionQuadrature::new(7, accel_model::OUTPUT_HIGHEST_HARMONIC).unwrap();
        let by_hand = q.mean(w, |t| PIGA.instantaneous_output_rad_s(&chain, t));
        assert_eq!(by_hand, m7);
    }
}
