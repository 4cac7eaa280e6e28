//! Property tests: rigid transforms invert exactly; jets agree with central differences.

use kinematics::{Axis, Centrifuge, Chain, ErrorMotion, Ground, Homogeneous, Piga, Transform};
use proptest::prelude::*;

use crate::site;

fn axis() -> impl Strategy<Value = Axis> {
    prop_oneof![Just(Axis::X), Just(Axis::Y), Just(Axis::Z)]
}

/// A product of 1–6 random `Rot` and `Trans` factors.
fn homogeneous() -> impl Strategy<Value = Homogeneous> {
    let factor = prop_oneof![
        (axis(), -7.0..7.0f64).prop_map(|(a, ang)| Homogeneous::rot(a, ang)),
        (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64)
            .prop_map(|(x, y, z)| Homogeneous::trans(x, y, z)),
    ];
    prop::collection::vec(factor, 1..7).prop_map(|fs| {
        fs.into_iter()
            .fold(Homogeneous::identity(), |acc, f| acc * f)
    })
}

fn error_motion() -> impl Strategy<Value = ErrorMotion> {
    prop::array::uniform8(-1e-3..1e-3f64).prop_map(|v| ErrorMotion {
        dr_xs_m: v[0],
        dr_ys_m: v[1],
        dphi_xs_rad: v[2],
        dphi_ys_rad: v[3],
        c_r_m_s2: v[4],
        c_r_y_m_s2: v[5],
        c_phi_x_s2: v[6],
        c_phi_s2: v[7],
    })
}

proptest! {
    #[test]
    fn transform_times_inverse_is_identity(h in homogeneous()) {
        let id = Homogeneous::identity();
        prop_assert!((h * h.inverse()).max_abs_diff(&id) < 1e-13);
        prop_assert!((h.inverse() * h).max_abs_diff(&id) < 1e-13);
        // typed: T₃⁰ · (T₃⁰)⁻¹ is a Transform<Ground, Ground>
        let t: Transform<Ground, Piga> = Transform::from_homogeneous(h);
        let back: Transform<Ground, Ground> = t * t.inverse();
        prop_assert!(back.homogeneous().max_abs_diff(&id) < 1e-13);
        let p = kinematics::Point::<Piga>::new([0.3, -1.2, 4.0]);
        let q = t.inverse() * (t * p);
        for k in 0..3 {
            prop_assert!((q.coords_m[k] - p.coords_m[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn chain_inverse_is_identity(e in error_motion(), w in -5.0..5.0f64, t in 0.0..20.0f64) {
        let c = Centrifuge { radius_m: 2.5, site: site(), error_motion: e };
        let chain = Chain::new(&c, w).unwrap();
        let t30 = chain.piga_in_ground(t);
        let id: Transform<Piga, Piga> = t30.inverse() * t30;
        prop_assert!(id.homogeneous().max_abs_diff(&Homogeneous::identity()) < 1e-14);
    }

    /// dD/dt, d²D/dt² and dA/dt from jets against central differences with ω·h = 1e-3
    /// (truncation error ≈ (ωh)²/6 relative, rounding ≈ 1e-16/(ωh)²).
    #[test]
    fn jets_agree_with_central_differences(
        e in error_motion(),
        w in prop_oneof![-5.0..-0.05f64, 0.05..5.0f64],
        t in 0.0..20.0f64,
    ) {
        let c = Centrifuge { radius_m: 2.5, site: site(), error_motion: e };
        let chain = Chain::new(&c, w).unwrap();
        let h = 1e-3 / w.abs();
        let d = |t: f64| chain.piga_in_ground(t).homogeneous().translation();
        let a = |t: f64| chain.piga_in_ground(t).homogeneous().rotation();
        let jet = chain.piga_in_ground_jet(t);
        let j = jet.homogeneous();
        let (dp, d0, dm) = (d(t + h), d(t), d(t - h));
        let (v1, v2) = (j.translation_d1(), j.translation_d2());
        let scale1 = 2.5 * w.abs();
        let scale2 = 2.5 * w * w;
        for k in 0..3 {
            let fd1 = (dp[k] - dm[k]) / (2.0 * h);
            let fd2 = (dp[k] - 2.0 * d0[k] + dm[k]) / (h * h);
            prop_assert!((fd1 - v1[k]).abs() < 1e-6 * scale1, "Ḋ[{k}]: {fd1} vs {}", v1[k]);
            prop_assert!((fd2 - v2[k]).abs() < 1e-6 * scale2, "D̈[{k}]: {fd2} vs {}", v2[k]);
        }
        let (ap, am) = (a(t + h), a(t - h));
        let r1 = j.rotation_d1();
        for r in 0..3 {
            for col in 0..3 {
                let fd = (ap[r][col] - am[r][col]) / (2.0 * h);
                prop_assert!((fd - r1[r][col]).abs() < 1e-6 * w.abs());
            }
        }
    }
}
