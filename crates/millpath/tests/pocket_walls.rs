//! Inclined walls: each level is cut in its own section (draft angle or bottom outline), and
//! the verifier, level by level against the section, finds no gouge and no uncut material
//! beyond the cusps; cutting every level in the top outline gouges the inclined walls, which
//! the same verifier reports.

use millpath::stock::{self, SimOptions, StockSpec};
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, Walls, builtin};
use millpath::toolpath::Tool;

fn coarse() -> SimOptions {
    SimOptions::default().with_cell(0.1).with_step(0.2)
}

fn opts() -> PocketOptions {
    PocketOptions::default().with_depth(6.0).with_step_down(2.0)
}

fn drafted() -> PocketShape {
    PocketShape::new(
        builtin::rounded_rectangle(0.0, 0.0, 70.0, 50.0, 6.0),
        vec![builtin::rounded_rectangle(30.0, 20.0, 10.0, 10.0, 2.0)],
        "t",
    )
    .unwrap()
    .with_walls(Walls::Draft(10f64.to_radians()), "--draft")
    .unwrap()
}

#[test]
fn drafted_pocket_verifies_level_by_level() {
    let tool = Tool::flat(6.0).unwrap();
    let shape = drafted();
    for kind in [StrategyKind::Offset, StrategyKind::Zigzag] {
        let r = pocket::generate(kind, &shape, &tool, &opts(), &coarse()).unwrap();
        let v = &r.verification;
        assert!(v.problems().is_empty(), "{kind:?}: {:?}", v.problems());
        assert_eq!(r.toolpath.levels.len(), 3);
        // Each level reaches its own wall: the path of the top level goes farther out than
        // the bottom level's by about 4 mm · tan 10° (the top level is at 2 mm, the bottom at 6).
        let reach = |li: usize| {
            let l = &r.toolpath.levels[li];
            r.toolpath.moves[l.start..l.end]
                .iter()
                .filter(|m| m.to.z < 0.0)
                .map(|m| m.to.x)
                .fold(f64::INFINITY, f64::min)
        };
        let d = 4.0 * 10f64.to_radians().tan();
        assert!(
            (reach(2) - reach(0) - d).abs() < 0.05,
            "{kind:?}: {} {}",
            reach(0),
            reach(2)
        );
    }
}

#[test]
fn top_outline_at_every_level_gouges_a_drafted_wall() {
    let tool = Tool::flat(6.0).unwrap();
    let shape = drafted();
    let vertical = PocketShape::new(shape.outer.clone(), shape.islands.clone(), "t").unwrap();
    let tp = pocket::toolpath(StrategyKind::Offset, &vertical, &tool, &opts()).unwrap();
    let sections = pocket::level_shapes(&shape, &opts()).unwrap();
    let specs: Vec<StockSpec<'_>> = sections
        .iter()
        .map(|s| StockSpec {
            outer: &s.outer,
            islands: &s.islands,
            wall_stock: 0.0,
        })
        .collect();
    let v = stock::verify_levels(&tp, &specs, 60.0, &coarse());
    assert!(
        v.problems().iter().any(stock::Problem::is_gouge),
        "{:?}",
        v.problems()
    );
}

#[test]
fn bottom_outline_pocket_verifies_and_undercuts_are_refused() {
    let tool = Tool::flat(6.0).unwrap();
    let top = PocketShape::simple(builtin::rounded_rectangle(0.0, 0.0, 70.0, 50.0, 8.0));
    let shape = top
        .clone()
        .with_walls(
            Walls::Bottom {
                outer: builtin::rounded_rectangle(4.0, 3.0, 60.0, 44.0, 8.0),
                islands: Vec::new(),
            },
            "bottom.json",
        )
        .unwrap();
    for kind in [StrategyKind::Offset, StrategyKind::Zigzag] {
        let r = pocket::generate(kind, &shape, &tool, &opts(), &coarse()).unwrap();
        assert!(
            r.verification.problems().is_empty(),
            "{kind:?}: {:?}",
            r.verification.problems()
        );
    }
    let undercut = top
        .with_walls(
            Walls::Bottom {
                outer: builtin::rounded_rectangle(-4.0, -3.0, 78.0, 56.0, 8.0),
                islands: Vec::new(),
            },
            "bottom.json",
        )
        .unwrap();
    let e =
        pocket::generate(StrategyKind::Offset, &undercut, &tool, &opts(), &coarse()).unwrap_err();
    assert!(e.to_string().contains("bottom outline"), "{e}");
    // A bottom with another vertex count.
    let wrong = PocketShape::simple(builtin::rounded_rectangle(0.0, 0.0, 70.0, 50.0, 8.0))
        .with_walls(
            Walls::Bottom {
                outer: millpath::geom::Outline::from_points(
                    &[
                        millpath::geom::Point::new(5.0, 5.0),
                        millpath::geom::Point::new(60.0, 5.0),
                        millpath::geom::Point::new(30.0, 40.0),
                    ],
                    "tri",
                )
                .unwrap(),
                islands: Vec::new(),
            },
            "bottom.json",
        )
        .unwrap_err();
    assert!(wrong.to_string().contains("vertex count"), "{wrong}");
}
