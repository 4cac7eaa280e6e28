//! Planning on a 100-rate grid, and the simulation check of a plan; the same for a
//! two-orientation plan (issue 20).
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

#[path = "../tests/planning/paper.rs"]
mod paper;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("planning");
    group.sample_size(10);
    for points in [8, 12] {
        let inputs = paper::inputs(points);
        group.bench_function(format!("plan_100_candidates_{points}_points"), |b| {
            b.iter(|| planning::plan(black_box(&inputs)).unwrap())
        });
    }
    let inputs = paper::inputs(10);
    let plan = planning::plan(&inputs).unwrap();
    let outputs = planning::expected_outputs(&inputs, &plan);
    group.bench_function("simulate_10000_campaigns", |b| {
        b.iter(|| planning::simulate_plan(black_box(&plan), &outputs, 10_000, 1).unwrap())
    });
    let mut two = paper::inputs(10);
    two.schedule.budget_s = 7200.0;
    two.two_orientation = Some(planning::TwoOrientationPlanInputs {
        ia_in: planning::MountingPlan {
            radius_m: 2.5,
            bias_shift_rad_s: 0.0,
        },
        ia_out: planning::MountingPlan {
            radius_m: 2.54,
            bias_shift_rad_s: 4e-6,
        },
        remount_s: 900.0,
        rates: planning::RateGrid::default(),
        reserve: planning::LackOfFitReserve::default(),
        arm_stretch_m_s2: 0.0,
    });
    group.bench_function("plan_two_orientation", |b| {
        b.iter(|| planning::plan_two_orientation(black_box(&two)).unwrap())
    });
    let plan = planning::plan_two_orientation(&two).unwrap();
    let y = planning::expected_two_orientation_outputs(&two, &plan).unwrap();
    group.bench_function("simulate_two_orientations_10000_campaigns", |b| {
        b.iter(|| {
            planning::simulate_two_orientation_plan(black_box(&plan), [&y[0], &y[1]], 10_000, 1)
                .unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
