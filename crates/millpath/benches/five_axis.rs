//! Compute time of our five-axis minimum-time planner and of the paper's GA baseline on the
//! paper's case (31 intervals, paper A/B machine).

use criterion::{Criterion, criterion_group, criterion_main};
use millpath::machine::kinematics::{PaperAb, inverse_path};
use millpath::motion::five_axis::{self, BaselineOptions, KnotOptions, Limits};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let kin = PaperAb::paper();
    let lim = Limits::paper();
    let poses = five_axis::paper_path();
    let (joints, _) = inverse_path(&kin, &poses, &Default::default()).expect("paper case");
    let geo = five_axis::Geometry::new(&joints);
    let bo = BaselineOptions::default();
    let ko = KnotOptions::default();
    let fixed = five_axis::fixed_states(&geo, &kin, &lim, &bo);
    let mut g = c.benchmark_group("five_axis_paper_case");
    g.sample_size(10);
    g.bench_function("ours_knot_optimiser", |b| {
        b.iter(|| {
            five_axis::optimize(
                black_box(&geo),
                &kin,
                &lim,
                &ko,
                std::slice::from_ref(&fixed),
            )
            .expect("plan")
            .total()
        });
    });
    g.bench_function("baseline_paper_ga", |b| {
        b.iter(|| {
            five_axis::run_baseline(black_box(&fixed), &kin, &lim, &bo, &ko.min_time)
                .expect("baseline")
                .0
                .iter()
                .sum::<f64>()
        });
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
