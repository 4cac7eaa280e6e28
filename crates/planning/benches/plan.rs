//! Planning on a 100-rate grid, and the simulation check of a plan.
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
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
