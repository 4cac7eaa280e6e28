//! The separability analysis names the terms a set of mountings cannot tell apart, and the
//! mounting that would.

use accel_model::{AccelKind, Mounting, MountingPreset, Term};
use calibration::{
    ArmStretch, Column, JointSpec, MountingData, MountingsError, Nuisances, fit_mountings,
    separability,
};

fn rates() -> Vec<f64> {
    (0..12)
        .map(|i| (35.0 + 15.0 * f64::from(i)).to_radians())
        .collect()
}

fn mounting<'a>(
    m: usize,
    preset: MountingPreset,
    rates: &'a [f64],
    outputs: &'a [f64],
) -> MountingData<'a> {
    MountingData {
        field: format!("mountings[{m}]"),
        mounting: Mounting::preset(preset, 2.5 + 0.02 * m as f64, 0.01),
        nuisances: if m == 0 {
            Nuisances::REFERENCE
        } else {
            Nuisances::REMOUNTED
        },
        rates_rad_s: rates,
        outputs,
        sigma: None,
    }
}

fn spec(terms: &[Term]) -> JointSpec {
    JointSpec {
        kind: AccelKind::Piga,
        terms: terms.to_vec(),
        omega3: true,
        arm_stretch: ArmStretch::Off,
        g_m_s2: 9.8,
        earth_rate_vertical_rad_s: 0.0,
        probe: None,
    }
}

/// IA in, IA out and PA radial (IA up): in the last, `a_i = 1 g` while `a_p` follows the
/// radial input, so `k_ip·a_i·a_p` and `k1·δ_o·a_p` are the same column; IA tangential (PA
/// radial, `a_i = 0`) sees δ_o alone and separates them.
#[test]
fn k_ip_and_delta_o_are_named_with_the_mounting_that_separates_them() {
    let w = rates();
    let y = vec![0.0; w.len()];
    let data = [
        mounting(0, MountingPreset::IaIn, &w, &y),
        mounting(1, MountingPreset::IaOut, &w, &y),
        mounting(2, MountingPreset::PaRadial, &w, &y),
    ];
    let terms = [
        Term::K0,
        Term::K1,
        Term::K2,
        Term::K3,
        Term::Kip,
        Term::DeltaO,
    ];
    let s = separability(&spec(&terms), &data, false).unwrap();
    assert!(!s.full_rank());
    assert_eq!(s.confounded.len(), 1, "{s}");
    let group = &s.confounded[0];
    assert_eq!(
        group.columns,
        [Column::Term(Term::Kip), Column::Term(Term::DeltaO)],
        "{s}"
    );
    assert_eq!(group.fix, Some(MountingPreset::IaTangential));
    let words = s.to_string();
    assert!(
        words.contains("cannot tell k_ip, δ_o apart")
            && words.contains("adding the mounting “IA tangential (PA radial, OA up)”"),
        "{words}"
    );
    // the fit refuses the design with the same analysis
    let Err(MountingsError::NotSeparable(refused)) = fit_mountings(&spec(&terms), &data) else {
        panic!("a rank-deficient design fitted");
    };
    assert_eq!(*refused, s);
    // with the named mounting added, every term is separated
    let fixed = [
        data[0].clone(),
        data[1].clone(),
        data[2].clone(),
        mounting(3, MountingPreset::IaTangential, &w, &y),
    ];
    let again = separability(&spec(&terms), &fixed, false).unwrap();
    assert!(again.full_rank(), "{again}");
}

/// IA in alone cannot tell the arm stretch (`ω⁴`) from k2 (`a² ∝ ω⁴`): `Auto` leaves it out
/// and says so; IA in and IA out separate it (eq. 23).
#[test]
fn the_arm_stretch_is_fitted_where_the_mountings_separate_it() {
    let w = rates();
    let y: Vec<f64> = w.iter().map(|w| 0.56 * 2.5 * w * w / 9.8).collect();
    let y_out: Vec<f64> = y.iter().map(|v| -v).collect();
    let auto = JointSpec {
        arm_stretch: ArmStretch::Auto,
        ..spec(&[Term::K0, Term::K1, Term::K2, Term::K3])
    };
    let one = [mounting(0, MountingPreset::IaIn, &w, &y)];
    let f = fit_mountings(&auto, &one).unwrap();
    assert!(f.arm_stretch.is_none() && f.arm_stretch_not_separable);
    let s = separability(&auto, &one, true).unwrap();
    assert!(
        s.confounded[0].columns.contains(&Column::ArmStretch)
            && s.confounded[0].columns.contains(&Column::Term(Term::K2)),
        "{s}"
    );
    let two = [
        mounting(0, MountingPreset::IaIn, &w, &y),
        mounting(1, MountingPreset::IaOut, &w, &y_out),
    ];
    let f = fit_mountings(&auto, &two).unwrap();
    assert!(f.arm_stretch.is_some() && !f.arm_stretch_not_separable);
}
