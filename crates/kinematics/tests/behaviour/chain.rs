//! The chain itself: eq. 5 vs eq. 8/9, eq. 12/13 at an instant, exact means, errors.

use approx::assert_relative_eq;
use kinematics::{
    Chain, ErrorMotion, INPUT_HIGHEST_HARMONIC, KinematicsError, SleeveFrameMotion, SpindleOffsets,
    piga_mount, spindle_transform,
};

use crate::{centrifuge, errors};

fn max_abs(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// Eq. 8 with the exact primed coefficients reproduces eq. 5 for large and small tilts; the
/// primed drifts are the corrected eq. 9 exactly, and the first-order tilts and the twist
/// deviate quadratically.
#[test]
fn sleeve_frame_form_equals_spindle_frame_form() {
    for &scale in &[1e4, 1.0] {
        let off = SpindleOffsets {
            dr_x_m: 5e-6 * scale,
            dr_y_m: -3e-6 * scale,
            dphi_x_rad: 4e-6 * scale,
            dphi_y_rad: 2.5e-6 * scale,
        };
        for k in 0..24 {
            let theta = -3.0 + 0.37 * f64::from(k);
            let eq5 = spindle_transform(theta, &off);
            let exact = SleeveFrameMotion::exact(&off, theta);
            let eq8 = exact.transform();
            let diff = eq5.homogeneous().max_abs_diff(eq8.homogeneous());
            assert!(diff < 1e-15, "scale {scale}, θ = {theta}: {diff:e}");

            // corrected eq. 9: a plane rotation of (Δr_x, Δr_y)
            let (s, c) = theta.sin_cos();
            assert_eq!(exact.dr_x_m, off.dr_x_m * c - off.dr_y_m * s);
            assert_eq!(exact.dr_y_m, off.dr_x_m * s + off.dr_y_m * c);
            // the paper's misprint (sin ωt twice) is wrong whenever Δr_y ≠ 0 and cos ≠ sin
            let misprint = off.dr_x_m * s + off.dr_y_m * s;
            if (c - s).abs() > 0.1 {
                assert!((misprint - exact.dr_y_m).abs() > 1e-2 * off.dr_y_m.abs());
            }

            let fo = SleeveFrameMotion::first_order(&off, theta);
            let eps = 4e-6 * scale;
            assert!((fo.dphi_x_rad - exact.dphi_x_rad).abs() < 2.0 * eps * eps);
            assert!((fo.dphi_y_rad - exact.dphi_y_rad).abs() < 2.0 * eps * eps);
            assert!(exact.twist_rad.abs() < 2.0 * eps * eps);
        }
    }
}

/// The twist is genuinely second order: it is non-zero for large tilts and falls by 100 when
/// the tilts fall by 10.
#[test]
fn twist_is_second_order() {
    let twist = |e: f64| {
        let off = SpindleOffsets {
            dphi_x_rad: 3.0 * e,
            dphi_y_rad: 2.0 * e,
            ..SpindleOffsets::default()
        };
        SleeveFrameMotion::exact(&off, 0.8).twist_rad
    };
    let (a, b) = (twist(1e-2), twist(1e-3));
    assert!(a.abs() > 1e-6, "{a:e}");
    assert_relative_eq!(a / b, 100.0, max_relative = 1e-3);
}

/// Eq. 11 assembled either way: sleeve form × mount equals the chain's `T₃⁰`.
#[test]
fn chain_through_either_form() {
    let chain = Chain::new(&centrifuge(errors().scaled(100.0)), 3.0).unwrap();
    for k in 0..10 {
        let t = 0.13 * f64::from(k);
        let via_eq8 =
            chain.sleeve_in_ground() * chain.sleeve_frame_motion(t).transform() * piga_mount(2.5);
        let direct = chain.piga_in_ground(t);
        assert!(direct.homogeneous().max_abs_diff(via_eq8.homogeneous()) < 1e-14);
        // jets carry the same value
        let jet = chain.piga_in_ground_jet(t).value();
        assert!(direct.homogeneous().max_abs_diff(jet.homogeneous()) < 1e-15);
    }
}

/// Ideal spindle: eq. 12 by hand. D = R(cos θ, sin θ, 0), X3 = −(cos θ, sin θ, 0), so
/// a_R = (Rω²/g, 0, 0), a_G = (0, 0, 1), a_C = 2Rω/g·(ω_ie sin L, 0, ω_ie cos L sin θ) and
/// the rate is (−ω_ie cos L sin θ, −ω_ie cos L cos θ, ω + ω_ie sin L).
#[test]
fn ideal_spindle_inputs_by_hand() {
    let c = centrifuge(ErrorMotion::ZERO);
    let w = 200.1234_f64.to_radians();
    let chain = Chain::new(&c, w).unwrap();
    let (r, g) = (2.5, 9.8);
    let (oy, oz) = (
        c.site.earth_rate_vector_rad_s()[1],
        c.site.earth_rate_vector_rad_s()[2],
    );
    for k in 0..9 {
        let t = 0.21 * f64::from(k);
        let theta = w * t;
        let i = chain.inputs_at(t);
        assert!(max_abs(i.centripetal_g, [r * w * w / g, 0.0, 0.0]) < 1e-13);
        assert!(max_abs(i.gravity_g, [0.0, 0.0, 1.0]) < 1e-15);
        let cor = [
            2.0 * r * w * oz / g,
            0.0,
            2.0 * r * w * oy * theta.sin() / g,
        ];
        assert!(
            max_abs(i.coriolis_g, cor) < 1e-18,
            "{:?} vs {cor:?}",
            i.coriolis_g
        );
        // eq. 13: X3 = −(cos θ, sin θ, 0), Y3 = (sin θ, −cos θ, 0), Z3 = ẑ
        let rate = [-oy * theta.sin(), -oy * theta.cos(), w + oz];
        let dr = max_abs(i.angular_rate_rad_s, rate);
        assert!(dr < 1e-15 * w, "{dr:e} {:?} {rate:?}", i.angular_rate_rad_s);
    }
}

/// The angular rate from `Ȧ Aᵀ` equals the paper's eq. 13 form `Aᵀ(Ω_ie + ω ẑ)` with error motion.
#[test]
fn angular_rate_is_eq_13() {
    let c = centrifuge(errors().scaled(1e3));
    let w = 2.7;
    let chain = Chain::new(&c, w).unwrap();
    let o = c.site.earth_rate_vector_rad_s();
    for k in 0..9 {
        let t = 0.4 * f64::from(k);
        let a = chain.piga_in_ground(t).homogeneous().rotation();
        let v = [o[0], o[1], o[2] + w];
        let eq13: [f64; 3] = core::array::from_fn(|i| (0..3).map(|j| a[j][i] * v[j]).sum());
        assert!(max_abs(chain.inputs_at(t).angular_rate_rad_s, eq13) < 1e-15 * w);
    }
}

/// The uniform rule with the minimal 3 nodes already gives the exact mean (the inputs contain
/// only harmonics 0 and 1), and the mean matches the closed form given in the crate docs.
#[test]
fn means_are_exact() {
    let c = centrifuge(errors().scaled(300.0));
    for &deg_s in &[10.0, 60.0, 80.1234, 110.1234, 160.1234, 200.1234] {
        let w = f64::to_radians(deg_s);
        let chain = Chain::new(&c, w).unwrap();
        let minimal = chain.mean_inputs(2 * INPUT_HIGHEST_HARMONIC + 1).unwrap();
        let dense = chain.mean_inputs(257).unwrap();
        for (a, b) in [
            (minimal.centripetal_g, dense.centripetal_g),
            (minimal.gravity_g, dense.gravity_g),
            (minimal.coriolis_g, dense.coriolis_g),
        ] {
            assert!(max_abs(a, b) < 1e-14 * (1.0 + w * w), "{a:?} {b:?}");
        }
        assert!(max_abs(minimal.angular_rate_rad_s, dense.angular_rate_rad_s) < 1e-15 * w);

        // closed form of the exact mean
        let off = chain.offsets();
        let (sx, cx) = off.dphi_x_rad.sin_cos();
        let (sy, cy) = off.dphi_y_rad.sin_cos();
        let px = off.dr_x_m + 2.5 * cy;
        let py = off.dr_y_m + 2.5 * sx * sy;
        let oz = c.site.earth_rate_vertical_rad_s();
        let a_x = (w * w + 2.0 * w * oz) * (cy * px + sx * sy * py) / 9.8 + sy * cx;
        assert_relative_eq!(minimal.a_x_g(), a_x, max_relative = 1e-14);
        assert_relative_eq!(
            minimal.omega_i_rad_s(),
            (w + oz) * sy * cx,
            max_relative = 1e-13
        );
    }
}

/// The instantaneous inputs really do vary within a revolution (so averaging matters), but
/// only through the horizontal Earth rate.
#[test]
fn within_revolution_variation_is_from_the_horizontal_earth_rate() {
    let mut c = centrifuge(errors().scaled(100.0));
    let w = 1.5;
    let spread = |c: &kinematics::Centrifuge| {
        let chain = Chain::new(c, w).unwrap();
        let xs: Vec<f64> = (0..16)
            .map(|k| chain.inputs_at(f64::from(k) * 0.26).omega_i_rad_s())
            .collect();
        xs.iter().copied().fold(f64::MIN, f64::max) - xs.iter().copied().fold(f64::MAX, f64::min)
    };
    assert!(spread(&c) > 1e-5);
    c.site.latitude_deg = 90.0; // pole: no horizontal Earth rate
    assert!(spread(&c) < 1e-18, "{:e}", spread(&c));
}

#[test]
fn bad_inputs_are_typed_errors() {
    let c = centrifuge(errors());
    assert!(matches!(
        Chain::new(&c, f64::NAN),
        Err(KinematicsError::NonFinite {
            field: "rate_rad_s",
            ..
        })
    ));
    assert!(matches!(
        Chain::new(&c, f64::INFINITY),
        Err(KinematicsError::NonFinite {
            field: "rate_rad_s",
            ..
        })
    ));
    let mut bad = c;
    bad.radius_m = 0.0;
    assert_eq!(
        Chain::new(&bad, 1.0),
        Err(KinematicsError::NotPositive {
            field: "radius_m",
            value: 0.0
        })
    );
    let mut bad = c;
    bad.site.latitude_deg = 91.0;
    assert!(matches!(
        Chain::new(&bad, 1.0),
        Err(KinematicsError::OutOfRange {
            field: "latitude_deg",
            ..
        })
    ));
    let chain = Chain::new(&c, 1.0).unwrap();
    assert_eq!(
        chain.mean_inputs(2),
        Err(KinematicsError::TooFewQuadraturePoints {
            points: 2,
            highest_harmonic: 1,
            need: 3
        })
    );
    // zero rate: a well-defined, time-independent mean
    let still = Chain::new(&c, 0.0).unwrap();
    assert_eq!(still.period_s(), None);
    let m = still.mean_inputs(3).unwrap();
    assert_relative_eq!(
        m.a_x_g(),
        c.error_motion.dphi_ys_rad.sin() * c.error_motion.dphi_xs_rad.cos(),
        max_relative = 1e-12
    );
}
