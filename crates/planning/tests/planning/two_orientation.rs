//! The two-orientation plan (issue 20): its prediction of u(k2) against 1000 simulated
//! campaigns through the exact chain, each fitted by the calibration's joint fit; the round
//! grid, the reserve and their costs; the probe method beside it.

use planning::{
    LackOfFitReserve, MountingPlan, PlanInputs, RateGrid, TwoOrientationPlan,
    TwoOrientationPlanInputs, expected_two_orientation_outputs, plan_two_orientation,
    simulate_two_orientation_plan,
};

/// The paper's centrifuge and PIGA, two hours, IA in at 2.5 m and IA out at 2.54 m with a
/// bias shift, 15 min to turn the PIGA round, an arm stretch of 0.3·C_r.
pub(crate) fn inputs() -> PlanInputs {
    let mut i = super::paper::inputs(10);
    i.schedule.budget_s = 7200.0;
    i.two_orientation = Some(TwoOrientationPlanInputs {
        ia_in: MountingPlan {
            radius_m: 2.5,
            bias_shift_rad_s: 0.0,
        },
        ia_out: MountingPlan {
            radius_m: 2.54,
            bias_shift_rad_s: 4e-6,
        },
        remount_s: 900.0,
        rates: RateGrid::default(),
        reserve: LackOfFitReserve::default(),
        arm_stretch_m_s2: 0.3 * -4.05e-8,
    });
    i
}

/// The plan of [`inputs`], computed once for the tests that share it.
pub(crate) fn plan() -> &'static TwoOrientationPlan {
    static PLAN: std::sync::OnceLock<TwoOrientationPlan> = std::sync::OnceLock::new();
    PLAN.get_or_init(|| plan_two_orientation(&inputs()).unwrap())
}

/// The plan file's centrifuge (the expected C_r as the spindle's dynamic drift, latitude
/// 45°) and PIGA for the exact chain.
pub(crate) fn centrifuge_and_piga(
    inputs: &PlanInputs,
) -> (kinematics::Centrifuge, accel_model::PigaCoefficients) {
    inputs.simulated(45.0)
}

/// The plan's noise-free mean outputs through the exact chain (`simulate::piga_table_mounted`,
/// zero noise), IA in then IA out.
pub(crate) fn exact_outputs(inputs: &PlanInputs, plan: &TwoOrientationPlan) -> [Vec<f64>; 2] {
    let spec = inputs.two_orientation.as_ref().unwrap();
    let (centrifuge, piga) = centrifuge_and_piga(inputs);
    [0, 1].map(|k| {
        let m = &plan.mountings[k];
        let spec_m = [spec.ia_in, spec.ia_out][k];
        let mount = simulate::Mount {
            orientation: m.orientation,
            radius_m: m.radius_m,
            arm_stretch_m_s2: spec.arm_stretch_m_s2,
            bias_shift_rad_s: spec_m.bias_shift_rad_s,
        };
        let rates: Vec<f64> = m.points.iter().map(|q| q.rate_deg_s).collect();
        simulate::piga_table_mounted(
            &centrifuge,
            &piga,
            &mount,
            &rates,
            &simulate::OutputNoise {
                sigma_rad_s: 0.0,
                seed: 1,
            },
        )
        .unwrap()
        .iter()
        .map(|r| r.output_rad_s)
        .collect()
    })
}

#[test]
fn predicted_u_k2_agrees_with_1000_campaigns_through_the_exact_chain() {
    let inputs = inputs();
    let plan = plan();
    let y = exact_outputs(&inputs, plan);
    let check = simulate_two_orientation_plan(plan, [&y[0], &y[1]], 1000, 11).unwrap();
    // The SD of 1000 draws has a relative standard error of 2.2 %: 10 % is 4.5 of them.
    assert!((check.ratio - 1.0).abs() < 0.10, "{check:?}");
    // The joint fit's k2 has no Δk2: the exact chain's noise-free k2 is the PIGA's own k2
    // (the first-order model leaves out far less than u), and the mean holds it.
    let k2 = inputs.piga.k2_rad_s_g2;
    assert!(
        (check.noise_free_k2_rad_s_g2 - k2).abs() < 0.05 * plan.u_k2_rad_s_g2,
        "{check:?}"
    );
    assert!(
        (check.mean_k2_rad_s_g2 - k2).abs() < 4.0 * check.simulated_sd_rad_s_g2 / 1000f64.sqrt(),
        "{check:?}"
    );
}

#[test]
fn the_first_order_outputs_give_the_exact_chains_k2() {
    let inputs = inputs();
    let plan = plan();
    let first = expected_two_orientation_outputs(&inputs, plan).unwrap();
    let exact = exact_outputs(&inputs, plan);
    // The outputs differ by the ω terms (the Earth rate's Coriolis term), which the exact
    // chain has and eq. 23's b1 columns absorb: the fitted k2 agree to a small part of u.
    let k2 = |y: &[Vec<f64>; 2]| {
        simulate_two_orientation_plan(plan, [&y[0], &y[1]], 10, 1)
            .unwrap()
            .noise_free_k2_rad_s_g2
    };
    let (a, b) = (k2(&first), k2(&exact));
    assert!((a - 5e-7).abs() < 1e-6 * plan.u_k2_rad_s_g2, "{a}");
    assert!((a - b).abs() < 0.05 * plan.u_k2_rad_s_g2, "{a} {b}");
}

#[test]
fn the_plan_uses_round_rates_keeps_a_reserve_and_states_their_costs() {
    let inputs = inputs();
    let plan = plan();
    assert!(plan.total_time_s <= 7200.0);
    for m in &plan.mountings {
        // Six rates for the fit and two for the reserve, all distinct, on the 5 deg/s grid.
        assert_eq!(m.points.len(), 8);
        assert_eq!(m.points.iter().filter(|q| q.reserve).count(), 2);
        for q in &m.points {
            assert!(
                (q.rate_deg_s / 5.0 - (q.rate_deg_s / 5.0).round()).abs() < 1e-9,
                "{q:?}"
            );
        }
    }
    assert_eq!(plan.fit_dof, 6);
    // k2 and C are separated on this design: the study's warning will not fire.
    assert!(
        plan.c_separable && plan.k2_inflation < 1.5,
        "{}",
        plan.k2_inflation
    );
    // Rounding costs little; the reserve costs something, stated.
    assert!(plan.rounding.cost_percent > -1.0 && plan.rounding.cost_percent < 10.0);
    assert!(plan.reserve.cost_percent > 0.0 && plan.reserve.cost_percent < 40.0);
    // Both mountings get a real share of the time.
    assert!(plan.recording_share_ia_in > 0.2 && plan.recording_share_ia_in < 0.8);
    // The probe method is planned on the same budget and file.
    assert_eq!(plan.probe_method.budget_s, 7200.0);
    assert!(plan.probe_over_two_orientations > 0.0);

    // Exact rates: the plan file's candidates; rounding then reports what it would cost.
    let mut exact = inputs.clone();
    exact.two_orientation.as_mut().unwrap().rates = RateGrid::Candidates;
    let e = plan_two_orientation(&exact).unwrap();
    assert!(e.u_k2_rad_s_g2 <= plan.u_k2_rad_s_g2 * 1.0001);
    assert!((e.rounding.cost_percent - plan.rounding.cost_percent).abs() < 1e-9);

    // Reserve off: six rates per orientation, the u the reserve is measured against.
    let mut off = inputs.clone();
    off.two_orientation.as_mut().unwrap().reserve = LackOfFitReserve::OFF;
    let o = plan_two_orientation(&off).unwrap();
    assert!(o.mountings.iter().all(|m| m.points.len() == 6));
    assert_eq!(o.reserve.cost_percent, 0.0);
    assert!((o.u_k2_rad_s_g2 - plan.reserve.u_k2_without_rad_s_g2).abs() < 1e-12 * o.u_k2_rad_s_g2);
}

#[test]
fn a_plan_file_without_two_orientations_is_refused() {
    let inputs = super::paper::inputs(10);
    let e = plan_two_orientation(&inputs).unwrap_err();
    assert!(e.to_string().contains("two_orientation"), "{e}");
}

#[test]
fn bad_two_orientation_fields_are_named() {
    use planning::PlanningError;
    let field_of = |edit: &dyn Fn(&mut TwoOrientationPlanInputs)| {
        let mut i = inputs();
        edit(i.two_orientation.as_mut().unwrap());
        match plan_two_orientation(&i) {
            Err(PlanningError::InvalidField { field, .. }) => field,
            other => panic!("{other:?}"),
        }
    };
    assert_eq!(
        field_of(&|t| t.ia_out.radius_m = 0.0),
        "two_orientation.ia_out.radius_m"
    );
    assert_eq!(
        field_of(&|t| t.rates = RateGrid::Round { step_deg_s: -5.0 }),
        "two_orientation.rates.step_deg_s"
    );
    assert_eq!(
        field_of(&|t| t.reserve.time_fraction = 1.0),
        "two_orientation.reserve.time_fraction"
    );
    assert_eq!(
        field_of(&|t| t.remount_s = f64::NAN),
        "two_orientation.remount_s"
    );
    // A grid too coarse for six rates and the reserve in a mounting.
    let mut coarse = inputs();
    coarse.two_orientation.as_mut().unwrap().rates = RateGrid::Round { step_deg_s: 40.0 };
    assert!(matches!(
        plan_two_orientation(&coarse),
        Err(PlanningError::TooFewCandidates {
            in_range: 5,
            need: 8,
            ..
        })
    ));
    // A remount that leaves no time for the points.
    let mut long = inputs();
    long.two_orientation.as_mut().unwrap().remount_s = 7000.0;
    let e = plan_two_orientation(&long).unwrap_err();
    assert!(
        matches!(e, PlanningError::TwoOrientationBudgetTooShort { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("two_orientation.remount_s"), "{e}");
}
