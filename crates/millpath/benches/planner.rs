//! Planned moves per second for short-segment G1 programs (the estimator's hot path), on
//! each controller model: `hsm` (sinumerik), `linuxcnc-sim` (generic), `linuxcnc-time`
//! (linuxcnc).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use millpath::machine::Machine;
use millpath::motion::{PlanOptions, plan_moves};
use millpath::toolpath::Move;
use millpath::{Point3, Vec3};
use std::hint::black_box;

/// A short-segment program: `n` G1 moves of ~0.1 mm along a wavy curve (every junction a
/// small corner, as CAM output of a free-form finishing pass).
fn program(n: usize) -> Vec<(Point3, Move)> {
    let mut out = Vec::with_capacity(n);
    let mut p = Point3::ORIGIN;
    for i in 0..n {
        let a = i as f64 * 0.01;
        let q = p + Vec3::new(0.1 * a.cos(), 0.1 * a.sin(), 0.0);
        out.push((p, Move::line(q, 100.0)));
        p = q;
    }
    out
}

fn bench(c: &mut Criterion) {
    let n = 100_000;
    let moves = program(n);
    let mut g = c.benchmark_group("planner");
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(10);
    for name in ["hsm", "linuxcnc-sim", "linuxcnc-time"] {
        let m = Machine::preset(name).expect("preset");
        let opts = PlanOptions::default().with_keep_geometry(false);
        g.bench_function(format!("short_g1_{name}"), |b| {
            b.iter(|| {
                let plan = plan_moves(moves.iter().map(|x| Ok(*x)), &m, &opts).expect("plan");
                black_box(plan.total_time())
            });
        });
    }
    // Worst case: a staircase of 0.1 mm G1 moves with a 90° corner at every junction (every
    // block its own span, a profile and a check per block).
    let mut stairs = Vec::with_capacity(n);
    let mut p = Point3::ORIGIN;
    for i in 0..n {
        let d = if i % 2 == 0 {
            Vec3::new(0.1, 0.0, 0.0)
        } else {
            Vec3::new(0.0, 0.1, 0.0)
        };
        stairs.push((p, Move::line(p + d, 100.0)));
        p = p + d;
    }
    let m = Machine::preset("hsm").expect("preset");
    let opts = PlanOptions::default().with_keep_geometry(false);
    g.bench_function("staircase_corners_hsm", |b| {
        b.iter(|| {
            let plan = plan_moves(stairs.iter().map(|x| Ok(*x)), &m, &opts).expect("plan");
            black_box(plan.total_time())
        });
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
