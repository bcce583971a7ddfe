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
        assert!(v.max_engagement_deg <= 180.0 + 1e-9);
        assert!(r.toolpath.levels.len() == 1);
        assert!(v.problems().is_empty(), "{kind:?}: {:?}", v.problems());
    }
}

/// The spiral's loops never exceed the stepover (measured by the planner) and its share of
/// path above the nominal engagement is no larger than offset's.
#[test]
fn spiral_spacing_and_engagement_share() {
    let shape = samples::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions {
        depth: 6.0,
        step_down: 6.0,
        ..PocketOptions::default()
    };
    let (_, stats) = pocket::spiral::plan_with_stats(&shape, &tool, &opts).unwrap();
    assert!(stats.max_loop_distance <= 0.4 * 12.7 + 1e-9, "{stats:?}");
    let sp = pocket::generate(StrategyKind::Spiral, &shape, &tool, &opts, &coarse()).unwrap();
    let off = pocket::generate(StrategyKind::Offset, &shape, &tool, &opts, &coarse()).unwrap();
    assert!(
        sp.verification.share_above_nominal <= off.verification.share_above_nominal,
        "spiral {} offset {}",
        sp.verification.share_above_nominal,
        off.verification.share_above_nominal
    );
}

/// Non-convex, non-star-shaped pockets: the spiral still verifies.
#[test]
fn spiral_on_l_t_crescent_and_long_slot() {
    use millpath::geom::{Outline, Point};
    let tool = Tool::flat(6.0).unwrap();
    let opts = PocketOptions {
        depth: 3.0,
        step_down: 3.0,
        ..PocketOptions::default()
    };
    let p = |x: f64, y: f64| Point::new(x, y);
    let ell = samples::rounded_polygon(
        &[
            p(0.0, 0.0),
            p(60.0, 0.0),
            p(60.0, 20.0),
            p(20.0, 20.0),
            p(20.0, 60.0),
            p(0.0, 60.0),
        ],
        4.0,
        "L",
    )
    .unwrap();
    let tee = samples::rounded_polygon(
        &[
            p(0.0, 40.0),
            p(20.0, 40.0),
            p(20.0, 0.0),
            p(40.0, 0.0),
            p(40.0, 40.0),
            p(60.0, 40.0),
            p(60.0, 60.0),
            p(0.0, 60.0),
        ],
        4.0,
        "T",
    )
    .unwrap();
    // Crescent: a big half disc with a smaller one taken out (arcs).
    let crescent = Outline::new(
        &[
            (p(-30.0, 0.0), 1.0),
            (p(30.0, 0.0), 0.0),
            (p(15.0, 0.0), -1.0),
            (p(-15.0, 0.0), 0.0),
        ],
        "crescent",
    )
    .unwrap();
    let slot = samples::rounded_rectangle(0.0, 0.0, 120.0, 20.0, 5.0);
    for (name, o) in [
        ("L", ell),
        ("T", tee),
        ("crescent", crescent),
        ("slot 6:1", slot),
    ] {
        let shape = pocket::PocketShape::simple(o);
        let r = pocket::generate(StrategyKind::Spiral, &shape, &tool, &opts, &coarse())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            r.verification.problems().is_empty(),
            "{name}: {:?}",
            r.verification.problems()
        );
    }
}

/// The several pockets of the sample part, all three strategies.
#[test]
fn structural_part_all_strategies() {
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions {
        depth: 5.0,
        step_down: 5.0,
        ..PocketOptions::default()
    };
    for (name, shape) in samples::structural_part() {
        for kind in [
            StrategyKind::Zigzag,
            StrategyKind::Offset,
            StrategyKind::Spiral,
        ] {
            let r = pocket::generate(kind, &shape, &tool, &opts, &coarse())
                .unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
            assert!(
                r.verification.problems().is_empty(),
                "{name} {kind:?}: {:?}",
                r.verification.problems()
            );
        }
    }
}
