//! Criterion benchmarks: planning one level of the built-in aerospace pocket (150 × 100 mm,
//! 12.7 mm tool, 40% stepover) with each strategy; and the spiral on each pocket of the sample
//! part (the L takes the harmonic morph, the slowest planning path); the aerospace spiral
//! also with `--arcs` (biarcs fitted to the laps and each checked against the last loop).

use criterion::{Criterion, criterion_group, criterion_main};
use millpath::strategy::pocket::{PocketOptions, StrategyKind, plan_level, samples};
use millpath::toolpath::Tool;
use std::hint::black_box;

fn plan(c: &mut Criterion) {
    let shape = samples::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap_or_default();
    let opts = PocketOptions::default();
    let mut g = c.benchmark_group("pocket level, aerospace 150x100");
    for kind in [
        StrategyKind::Spiral,
        StrategyKind::Offset,
        StrategyKind::Zigzag,
    ] {
        g.bench_function(kind.name(), |b| {
            b.iter(|| plan_level(kind, black_box(&shape), &tool, &opts));
        });
    }
    let arcs = PocketOptions {
        arcs: true,
        ..PocketOptions::default()
    };
    g.bench_function("spiral --arcs", |b| {
        b.iter(|| plan_level(StrategyKind::Spiral, black_box(&shape), &tool, &arcs));
    });
    g.finish();
    let mut g = c.benchmark_group("spiral level, sample part");
    g.sample_size(10);
    for (name, shape) in samples::structural_part() {
        g.bench_function(name.as_str(), |b| {
            b.iter(|| plan_level(StrategyKind::Spiral, black_box(&shape), &tool, &opts));
        });
    }
    g.finish();
}

criterion_group!(benches, plan);
criterion_main!(benches);
