//! Pockets with islands: offset and zigzag pass the stock simulation and the gouge check with
//! one to three islands (also with a finishing pass and floor/wall stock); so does the spiral
//! (its default morph), as long as `offset` or shorter by at most 15 %, while its `fronts` and
//! `harmonic` morphs refuse them with a message suggesting `offset`; islands touching the
//! outline or each other are input errors.

use millpath::Error;
use millpath::geom::{Outline, Point};
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::toolpath::{MoveKind, Tool};

fn coarse() -> SimOptions {
    SimOptions::default().with_cell(0.1).with_step(0.2)
}

fn circle(cx: f64, cy: f64, r: f64) -> Outline {
    Outline::new(
        &[(Point::new(cx - r, cy), 1.0), (Point::new(cx + r, cy), 1.0)],
        "circle",
    )
    .unwrap()
}

fn one_level() -> PocketOptions {
    PocketOptions::default().with_depth(2.0).with_step_down(2.0)
}

/// The pockets: one square island in the middle; a round and a square island, one close to
/// the wall (a gap narrower than two tool diameters); three islands.
fn pockets() -> Vec<(&'static str, PocketShape)> {
    let outer = || builtin::rounded_rectangle(0.0, 0.0, 80.0, 60.0, 5.0);
    vec![
        (
            "one island",
            PocketShape::new(
                outer(),
                vec![builtin::rounded_rectangle(30.0, 20.0, 20.0, 20.0, 3.0)],
                "t",
            )
            .unwrap(),
        ),
        (
            "two islands, one near the wall",
            PocketShape::new(
                outer(),
                vec![
                    circle(20.0, 30.0, 8.0),
                    builtin::rounded_rectangle(50.0, 8.0, 20.0, 12.0, 2.0),
                ],
                "t",
            )
            .unwrap(),
        ),
        (
            "three islands",
            PocketShape::new(
                outer(),
                vec![
                    circle(18.0, 18.0, 6.0),
                    circle(60.0, 40.0, 7.0),
                    builtin::rounded_rectangle(35.0, 35.0, 10.0, 16.0, 2.0),
                ],
                "t",
            )
            .unwrap(),
        ),
    ]
}

#[test]
fn offset_and_zigzag_verify_with_one_to_three_islands() {
    let tool = Tool::flat(8.0).unwrap();
    for (name, shape) in pockets() {
        for kind in [StrategyKind::Offset, StrategyKind::Zigzag] {
            let r = pocket::generate(kind, &shape, &tool, &one_level(), &coarse())
                .unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
            let v = &r.verification;
            assert!(
                v.problems().is_empty(),
                "{name} {kind:?}: {:?}",
                v.problems()
            );
            assert!(v.plunges == 0 && v.rapids_through_material == 0);
            // The tool went round every island: it came within r + 1 mm of each.
            for (k, isl) in shape.islands.iter().enumerate() {
                let closest = r
                    .toolpath
                    .segments()
                    .filter(|(_, m)| m.is_feed() && m.to.z < 0.0)
                    .map(|(_, m)| isl.distance_to(m.to.xy()))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    closest <= 4.0 + 1.0,
                    "{name} {kind:?}: island {k} at {closest}"
                );
            }
        }
    }
}

/// Two levels, wall and floor stock, conventional milling, ramp entries; then a finishing
/// pass: the verifier holds, and the finish takes the walls to zero stock around the islands.
#[test]
fn islands_with_stock_levels_and_finishing() {
    let tool = Tool::flat(6.0).unwrap();
    let shapes = pockets();
    let (name, shape) = &shapes[1];
    for kind in [StrategyKind::Offset, StrategyKind::Zigzag] {
        for finish in [false, true] {
            let opts = PocketOptions::default()
                .with_depth(4.0)
                .with_step_down(2.0)
                .with_wall_stock(0.5)
                .with_floor_stock(0.2)
                .with_direction(pocket::Direction::Conventional)
                .with_entry(pocket::Entry::Ramp {
                    ramp_angle: 5f64.to_radians(),
                })
                .with_finish(finish);
            let r = pocket::generate(kind, shape, &tool, &opts, &coarse())
                .unwrap_or_else(|e| panic!("{name} {kind:?}: {e}"));
            let v = &r.verification;
            assert!(
                v.problems().is_empty(),
                "{name} {kind:?} finish {finish}: {:?}",
                v.problems()
            );
            let want = if finish { 3.0 } else { 3.5 };
            assert!((v.required_clearance_mm - want).abs() < 1e-12);
            // The finish comes to the walls: its clearance is r within 1 µm.
            if finish {
                assert!(
                    (v.min_clearance_mm - 3.0).abs() < 1e-3,
                    "{}",
                    v.min_clearance_mm
                );
            }
        }
    }
}

#[test]
fn the_spiral_verifies_with_islands_and_is_about_as_long_as_offset() {
    let tool = Tool::flat(8.0).unwrap();
    for (name, shape) in pockets() {
        let r = pocket::generate(StrategyKind::Spiral, &shape, &tool, &one_level(), &coarse())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let v = &r.verification;
        assert!(v.problems().is_empty(), "{name}: {:?}", v.problems());
        assert!(
            v.uncut_area_mm2 < 0.05,
            "{name}: uncut {}",
            v.uncut_area_mm2
        );
        let o =
            pocket::generate(StrategyKind::Offset, &shape, &tool, &one_level(), &coarse()).unwrap();
        let (ls, lo) = (r.toolpath.cut_length(), o.toolpath.cut_length());
        assert!(
            ls <= 1.15 * lo,
            "{name}: spiral {ls:.1} mm, offset {lo:.1} mm"
        );
    }
}

#[test]
fn the_older_spiral_morphs_refuse_islands_and_suggest_offset() {
    let tool = Tool::flat(8.0).unwrap();
    let shapes = pockets();
    for morph in [pocket::SpiralMorph::Fronts, pocket::SpiralMorph::Harmonic] {
        let opts = one_level().with_morph(morph);
        let e = pocket::generate(StrategyKind::Spiral, &shapes[0].1, &tool, &opts, &coarse())
            .unwrap_err();
        assert!(matches!(e, Error::Input(_)), "{e}");
        assert!(e.to_string().contains("offset"), "{e}");
    }
}

#[test]
fn touching_crossing_and_nested_islands_are_input_errors() {
    let outer = || builtin::rounded_rectangle(0.0, 0.0, 80.0, 60.0, 5.0);
    for (what, islands) in [
        ("touching the wall", vec![circle(10.0, 30.0, 10.0)]),
        ("crossing the wall", vec![circle(5.0, 30.0, 10.0)]),
        (
            "touching each other",
            vec![circle(30.0, 30.0, 5.0), circle(40.0, 30.0, 5.0)],
        ),
        (
            "crossing each other",
            vec![circle(30.0, 30.0, 6.0), circle(40.0, 30.0, 6.0)],
        ),
        (
            "nested",
            vec![circle(30.0, 30.0, 10.0), circle(30.0, 30.0, 3.0)],
        ),
    ] {
        let e = PocketShape::new(outer(), islands, "t.json").unwrap_err();
        assert!(e.to_string().contains("island"), "{what}: {e}");
    }
}

/// The links of both strategies never cross an island: every feed move at depth keeps the
/// tool centre r away from each island (the gouge check measures it exactly; here the end
/// points are checked as well, independently of it).
#[test]
fn no_move_at_depth_enters_an_island() {
    let tool = Tool::flat(8.0).unwrap();
    for (name, shape) in pockets() {
        for kind in [StrategyKind::Offset, StrategyKind::Zigzag] {
            let tp = pocket::toolpath(kind, &shape, &tool, &one_level()).unwrap();
            for (from, m) in tp.segments() {
                if from.z >= 0.0 || m.to.z >= 0.0 || matches!(m.kind, MoveKind::Rapid) {
                    continue;
                }
                // The chord's midpoint only for lines (an arc's chord cuts inside the arc).
                let mid = if matches!(m.kind, MoveKind::Line) {
                    from.xy().midpoint(m.to.xy())
                } else {
                    m.to.xy()
                };
                for p in [from.xy(), mid, m.to.xy()] {
                    for isl in &shape.islands {
                        assert!(
                            !isl.contains(p) && isl.distance_to(p) >= 4.0 - 1e-6,
                            "{name} {kind:?}: move to {:?}",
                            m.to
                        );
                    }
                }
            }
        }
    }
}
