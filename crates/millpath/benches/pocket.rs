//! Criterion benchmarks: planning one level of the built-in aerospace pocket (150 × 100 mm,
//! 12.7 mm tool, 40% stepover) with each strategy (adaptive in a group of its own, fewer
//! samples, climb and both ways), the spiral with its default morph
//! (`offsets`) and with the paper's (`fronts`) side by side; the spiral on a 200-vertex
//! non-convex pocket (a wavy five-lobed star, 10 mm tool) with both morphs and `offset`; the
//! spiral on each pocket of the sample part; the aerospace spiral also with `--arcs`;
//! and the sections of a pocket with inclined walls (`walls::level_shapes`: a draft, or a
//! bottom outline with the exact nesting check `PocketShape::within` between levels) on the
//! aerospace pocket and on a 512-vertex wavy outline; and the stock simulation that verifies
//! a program (`stock::simulate`) on the aerospace pocket's adaptive at full depth (25 mm in
//! one level, 10 %: 18 km of path).

use criterion::{Criterion, criterion_group, criterion_main};
use millpath::geom::{Outline, Point};
use millpath::stock::{SimOptions, StockSpec, simulate};
use millpath::strategy::pocket::{
    PocketOptions, PocketShape, SpiralMorph, StrategyKind, Walls, builtin, level_shapes, plan_level,
};
use millpath::strategy::pocket::{Stepover, nominal_engagement, toolpath};
use millpath::toolpath::Tool;
use std::hint::black_box;

fn plan(c: &mut Criterion) {
    let shape = builtin::aerospace_pocket();
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
    let fronts = PocketOptions::default().with_morph(SpiralMorph::Fronts);
    g.bench_function("spiral --morph fronts", |b| {
        b.iter(|| plan_level(StrategyKind::Spiral, black_box(&shape), &tool, &fronts));
    });
    let arcs = PocketOptions::default().with_arcs(true);
    g.bench_function("spiral --arcs", |b| {
        b.iter(|| plan_level(StrategyKind::Spiral, black_box(&shape), &tool, &arcs));
    });
    g.finish();
    let mut g = c.benchmark_group("adaptive level, aerospace 150x100");
    g.sample_size(10);
    g.bench_function("adaptive", |b| {
        b.iter(|| plan_level(StrategyKind::Adaptive, black_box(&shape), &tool, &opts));
    });
    let both = opts.clone().with_both_ways(true);
    g.bench_function("adaptive --both-ways", |b| {
        b.iter(|| plan_level(StrategyKind::Adaptive, black_box(&shape), &tool, &both));
    });
    let thin = opts.clone().with_stepover(Stepover::Fraction(0.1));
    g.bench_function("adaptive --stepover 0.1", |b| {
        b.iter(|| plan_level(StrategyKind::Adaptive, black_box(&shape), &tool, &thin));
    });
    g.finish();
    let lobed = PocketShape::simple(lobed_star(200, 60.0));
    let small = Tool::flat(10.0).unwrap_or_default();
    let mut g = c.benchmark_group("pocket level, 200-vertex non-convex");
    g.sample_size(20);
    g.bench_function("spiral", |b| {
        b.iter(|| plan_level(StrategyKind::Spiral, black_box(&lobed), &small, &opts));
    });
    g.bench_function("spiral --morph fronts", |b| {
        b.iter(|| plan_level(StrategyKind::Spiral, black_box(&lobed), &small, &fronts));
    });
    g.bench_function("offset", |b| {
        b.iter(|| plan_level(StrategyKind::Offset, black_box(&lobed), &small, &opts));
    });
    g.finish();
    let mut g = c.benchmark_group("spiral level, sample part");
    g.sample_size(10);
    for (name, shape) in builtin::structural_part() {
        g.bench_function(name.as_str(), |b| {
            b.iter(|| plan_level(StrategyKind::Spiral, black_box(&shape), &tool, &opts));
        });
    }
    g.finish();
}

/// A non-convex outline of `n` vertices: radius `r·(1 + 0.3·sin 5θ)`, five lobes.
fn lobed_star(n: usize, r: f64) -> Outline {
    let v: Vec<(Point, f64)> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let rr = r * (1.0 + 0.3 * (5.0 * a).sin());
            (Point::new(rr * a.cos(), rr * a.sin()), 0.0)
        })
        .collect();
    Outline::new(&v, "bench lobed outline").expect("a lobed outline is valid")
}

/// A wavy closed outline of `n` vertices about `(cx, cy)`: radius `r` ± 8 %, 7 waves.
fn wavy(n: usize, r: f64) -> Outline {
    let v: Vec<(Point, f64)> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let rr = r * (1.0 + 0.08 * (7.0 * a).sin());
            (Point::new(rr * a.cos(), rr * a.sin()), 0.0)
        })
        .collect();
    Outline::new(&v, "bench wavy outline").expect("a wavy outline is valid")
}

fn walls(c: &mut Criterion) {
    // Four roughing levels, 25 mm deep by 6.35 mm (the aerospace pocket's CLI example).
    let opts = PocketOptions::default()
        .with_depth(25.0)
        .with_step_down(6.35);
    let cases = [
        (
            "aerospace 150x100",
            builtin::rounded_rectangle(-75.0, -50.0, 150.0, 100.0, 6.0),
            builtin::rounded_rectangle(-70.0, -45.0, 140.0, 90.0, 6.0),
        ),
        ("wavy 512 vertices", wavy(512, 60.0), wavy(512, 54.0)),
    ];
    let mut g = c.benchmark_group("pocket walls");
    for (name, top, bottom) in cases {
        let bottom_walls = Walls::Bottom {
            outer: bottom,
            islands: Vec::new(),
        };
        let Ok(drafted) = PocketShape::simple(top.clone()).with_walls(Walls::Draft(0.1), name)
        else {
            panic!("{name}: a 0.1 rad draft is accepted");
        };
        let Ok(shrunk) = PocketShape::simple(top).with_walls(bottom_walls, name) else {
            panic!("{name}: the bottom outline matches the top");
        };
        assert_eq!(level_shapes(&shrunk, &opts).map(|l| l.len()).ok(), Some(4));
        g.bench_function(format!("{name}: 4 level sections, draft"), |b| {
            b.iter(|| level_shapes(black_box(&drafted), &opts));
        });
        g.bench_function(format!("{name}: 4 level sections, bottom outline"), |b| {
            b.iter(|| level_shapes(black_box(&shrunk), &opts));
        });
        let (Ok(upper), Ok(lower)) = (shrunk.section(6.35, 25.0), shrunk.section(12.7, 25.0))
        else {
            panic!("{name}: sections");
        };
        assert!(lower.within(&upper) && !upper.within(&lower));
        g.bench_function(format!("{name}: within (nested)"), |b| {
            b.iter(|| black_box(&lower).within(&upper));
        });
    }
    g.finish();
}

fn verify(c: &mut Criterion) {
    let shape = builtin::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap_or_default();
    let opts = PocketOptions::default()
        .with_depth(25.0)
        .with_step_down(25.0)
        .with_stepover(Stepover::Fraction(0.1));
    let Ok(tp) = toolpath(StrategyKind::Adaptive, &shape, &tool, &opts) else {
        return;
    };
    let spec = StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock: 0.0,
    };
    let nominal = nominal_engagement(1.27, 6.35).to_degrees();
    let mut g = c.benchmark_group("stock simulation");
    g.sample_size(10);
    g.bench_function("aerospace adaptive, 25 mm at 10 %", |b| {
        b.iter(|| simulate(black_box(&tp), spec, nominal, &SimOptions::default()));
    });
    g.finish();
}

criterion_group!(benches, plan, walls, verify);
criterion_main!(benches);
