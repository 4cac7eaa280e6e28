//! Infeasible plans are errors that name the binding constraint and by how much.

use planning::{Candidates, PlanningError, plan};

#[test]
fn a_target_below_what_the_budget_allows() {
    let mut inputs = super::paper::inputs(8);
    inputs.target.u95_k2_rad_s_g2 = 1e-9;
    let e = plan(&inputs).unwrap_err();
    let PlanningError::TargetUnreachable {
        achieved, target, ..
    } = &e
    else {
        panic!("{e:?}");
    };
    assert!(achieved > target);
    let text = e.to_string();
    assert!(text.contains("target.u95_k2_rad_s_g2"), "{text}");
    assert!(text.contains("% above the target"), "{text}");
}

#[test]
fn fewer_allowed_rates_than_unknowns() {
    let mut inputs = super::paper::inputs(8);
    inputs.schedule.allow_repeats = true;
    inputs.centrifuge.candidates = Candidates::List(vec![20.0, 50.0, 90.0, 150.0, 190.0]);
    let e = plan(&inputs).unwrap_err();
    assert!(
        matches!(
            e,
            PlanningError::TooFewCandidates {
                in_range: 5,
                need: 6,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("1 short"), "{e}");
}

#[test]
fn fewer_points_than_unknowns() {
    let inputs = super::paper::inputs(6);
    let e = plan(&inputs).unwrap_err();
    assert!(
        matches!(e, PlanningError::TooFewPoints { points: 6, need: 7 }),
        "{e:?}"
    );
}

#[test]
fn a_maximum_rate_below_the_minimum() {
    let mut inputs = super::paper::inputs(8);
    inputs.centrifuge.max_acceleration_g = Some(0.5);
    inputs.centrifuge.min_rate_deg_s = 150.0;
    let e = plan(&inputs).unwrap_err();
    let PlanningError::RateRange {
        binding,
        max_rate_deg_s,
        ..
    } = &e
    else {
        panic!("{e:?}");
    };
    assert_eq!(*binding, "centrifuge.max_acceleration_g");
    assert!(*max_rate_deg_s < 150.0);
    assert!(e.to_string().contains("by "), "{e}");
}

#[test]
fn a_budget_shorter_than_settling() {
    let mut inputs = super::paper::inputs(10);
    inputs.schedule.budget_s = 300.0;
    let e = plan(&inputs).unwrap_err();
    assert!(matches!(e, PlanningError::BudgetTooShort { .. }), "{e:?}");
}

#[test]
fn non_finite_fields_are_named() {
    let mut inputs = super::paper::inputs(8);
    inputs.piga.noise = planning::NoiseSpec::PerRevolution {
        sigma_rad_s: f64::NAN,
    };
    let e = plan(&inputs).unwrap_err();
    assert!(e.to_string().starts_with("piga.noise.sigma_rad_s"), "{e}");
}

#[test]
fn the_estimated_budget_reaches_the_target() {
    let mut inputs = super::paper::inputs(8);
    inputs.target.u95_k2_rad_s_g2 = 1.5e-7;
    let e = plan(&inputs).unwrap_err();
    let PlanningError::TargetUnreachable {
        needed_budget_s: Some(t),
        ..
    } = e
    else {
        panic!("{e:?}");
    };
    assert!(t > inputs.schedule.budget_s);
    inputs.schedule.budget_s = 1.05 * t;
    let p = plan(&inputs).unwrap();
    assert!(p.compensated.u95_rad_s_g2 <= 1.5e-7);
}

#[test]
fn given_rates_that_cannot_separate_the_terms() {
    let inputs = super::paper::inputs(8);
    for rates in [
        &[][..],
        &[10.0, 50.0, 100.0][..],
        &[10.0, f64::NAN, 30.0, 40.0, 50.0, 60.0][..],
    ] {
        let e =
            planning::evaluate_rates(&inputs, rates, planning::Allocation::Optimal).unwrap_err();
        assert!(matches!(e, PlanningError::Singular { .. }), "{e:?}");
    }
    let six = super::paper::PAPER_RATES_DEG_S;
    let optimal = planning::evaluate_rates(&inputs, &six, planning::Allocation::Optimal).unwrap();
    let equal =
        planning::evaluate_rates(&inputs, &six, planning::Allocation::EqualRevolutions).unwrap();
    assert!(optimal.u_k2_fit_rad_s_g2 < equal.u_k2_fit_rad_s_g2);
    // The planner's ten points beat the paper's six in the same hour.
    let p = plan(&super::paper::inputs(10)).unwrap();
    assert!(p.u_k2_fit_rad_s_g2 < optimal.u_k2_fit_rad_s_g2 / 2.0);
}

#[test]
fn a_budget_of_too_many_revolutions() {
    let mut inputs = super::paper::inputs(8);
    inputs.schedule.budget_s = 1e12;
    let e = plan(&inputs).unwrap_err();
    assert!(e.to_string().starts_with("schedule.budget_s"), "{e}");
}
