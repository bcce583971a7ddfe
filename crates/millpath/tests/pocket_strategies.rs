//! The three strategies on the built-in samples, checked by the stock simulation.

use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, samples};
use millpath::toolpath::Tool;

fn coarse() -> SimOptions {
    SimOptions {
        cell: 0.1,
        step: 0.2,
        ..SimOptions::default()
    }
}

#[test]
#[allow(clippy::print_stderr)]
fn aerospace_pocket_all_strategies_verify() {
    let shape = samples::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions {
        depth: 6.0,
        step_down: 6.0,
        ..PocketOptions::default()
    };
    for kind in [
        StrategyKind::Zigzag,
        StrategyKind::Offset,
        StrategyKind::Spiral,
    ] {
        let r = pocket::generate(kind, &shape, &tool, &opts, &coarse()).unwrap();
        let v = &r.verification;
        let t = pocket::cycle_time(&r.toolpath).unwrap();
        eprintln!(
            "{:?}: len {:.1} time {:.2} moves {} {:?}",
            kind,
            r.toolpath.cut_length(),
            t,
            r.toolpath.moves.len(),
            v
        );
        assert!(v.problems().is_empty(), "{kind:?}: {:?}", v.problems());
    }
}

#[test]
#[allow(clippy::print_stderr)]
fn spiral_debug() {
    let shape = samples::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions::default();
    let (plan, stats) = pocket::spiral::plan_with_stats(&shape, &tool, &opts).unwrap();
    eprintln!("{stats:?}");
    let path = &plan.cuts[0].path;
    let mut worst = (f64::INFINITY, 0);
    for (i, s) in path.iter().enumerate() {
        let d = shape.outer.distance_to(s.b);
        if d < worst.0 {
            worst = (d, i);
        }
    }
    eprintln!("n {} worst {:?} at {:?}", path.len(), worst, path[worst.1]);
}
