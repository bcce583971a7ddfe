//! Flattening and offset of the paper's outline (scaled to the die block) beside kurbo's
//! flatten of the same cubics at the same tolerance; biarcs through a pocket spiral's samples.
//!
//! `cargo bench --bench flatten -- --warm-up-time 1 --measurement-time 3`

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use millpath::curve;
use millpath::strategy::contour::{ContourOptions, offset_pass};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let outline = curve::paper_outline().expect("paper outline");
    let path = outline.to_bez_path();
    let mut g = c.benchmark_group("flatten_paper_outline");
    for tol in [1e-2, 1e-4, 4e-5] {
        g.bench_with_input(
            BenchmarkId::new("millpath_exact_greedy", tol),
            &tol,
            |b, &t| {
                b.iter(|| curve::flatten(black_box(&outline), t).map(|f| f.segments()));
            },
        );
        g.bench_with_input(BenchmarkId::new("kurbo_flatten", tol), &tol, |b, &t| {
            b.iter(|| {
                let mut n = 0usize;
                kurbo::flatten(black_box(&path), t, |_| n += 1);
                n
            });
        });
    }
    g.finish();
    let mut g = c.benchmark_group("offset_paper_outline");
    for tol in [1e-2, 1e-3, 4e-5] {
        let rounding = if tol < 1e-4 {
            0.5e-6 * std::f64::consts::SQRT_2
        } else {
            0.5e-4 * std::f64::consts::SQRT_2
        };
        let opt = ContourOptions::default()
            .with_tolerance(tol)
            .with_rounding(rounding);
        g.bench_with_input(BenchmarkId::new("inside_5.2mm", tol), &opt, |b, o| {
            b.iter(|| offset_pass(black_box(&outline), 5.2, o).map(|p| p.segments()));
        });
    }
    g.finish();
    // Biarcs (`--arcs`) through a pocket spiral's samples: 25 laps of a wavy Archimedean
    // spiral (pitch 2.4 mm, radius rippling ±0.3 mm nine times a lap), a sample every mm.
    let mut pts = Vec::new();
    let mut th = 0.0_f64;
    while th < 25.0 * std::f64::consts::TAU {
        let r = 2.0 + 2.4 * th / std::f64::consts::TAU + 0.3 * (9.0 * th).sin();
        pts.push(millpath::Point::new(r * th.cos(), r * th.sin()));
        th += 1.0 / r;
    }
    let chain = curve::OpenChain::through(&pts);
    let n = chain.0.len() as f64;
    let mut g = c.benchmark_group("biarcs_wavy_spiral_25_laps");
    g.sample_size(10);
    g.bench_function("fit_0.004mm", |b| {
        b.iter(|| curve::fit_biarcs(black_box(&chain), 0.0, n, 0.004).len());
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
