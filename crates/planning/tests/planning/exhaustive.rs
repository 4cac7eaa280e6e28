//! The planner's design against the exhaustive optimum on a grid small enough to search.

use planning::{Candidates, Criterion, exhaustive_k2};

#[test]
fn planner_is_within_one_percent_of_the_exhaustive_optimum() {
    // 20 rates, choose 7: C(20, 7) = 77 520 designs, each with its optimal allocation.
    let mut inputs = super::paper::inputs(7);
    inputs.centrifuge.candidates = Candidates::Grid {
        from_deg_s: 10.0,
        to_deg_s: 200.0,
        count: 20,
    };
    inputs.search.criterion = Criterion::K2;
    let c = exhaustive_k2(&inputs).unwrap();
    assert_eq!(c.designs, 77_520);
    let var_ratio = (c.planner_u_k2_fit_rad_s_g2 / c.exhaustive_u_k2_fit_rad_s_g2).powi(2);
    assert!(
        var_ratio >= 1.0 - 1e-9,
        "the exhaustive search is the optimum"
    );
    assert!(
        var_ratio <= 1.01,
        "planner var(k2) {var_ratio} × the optimum"
    );
}

#[test]
fn d_optimal_plan_has_a_larger_var_k2_than_the_k2_optimal_one() {
    let inputs = super::paper::inputs(8);
    let k2 = planning::plan(&inputs).unwrap();
    let mut d_inputs = inputs.clone();
    d_inputs.search.criterion = Criterion::D;
    d_inputs.target.u95_k2_rad_s_g2 = 1.0;
    let d = planning::plan(&d_inputs).unwrap();
    assert!(d.u_k2_fit_rad_s_g2 >= k2.u_k2_fit_rad_s_g2 * (1.0 - 1e-6));
}
