//! A whole part: a drawing of several pockets (one with an island holding a pocket of its
//! own) written as a DXF, read back, nested, cut in one program by every strategy and `auto`,
//! and the written program read back and verified as a whole by the stock simulation (no
//! gouge, no uncut material in any pocket, no rapid through material, no cut outside the
//! pockets); the rapids that go from one pocket to another all stay above the stock; the
//! pockets' order is no longer than the order they are listed in. Also: `verify`'s view of
//! the programs `pocket` writes (offset, zigzag, spiral on sample shapes) passes at the
//! written program's rounding.

use millpath::gcode::{ReaderOptions, WriterOptions, read_str, write_to_string};
use millpath::geom::{Outline, Point};
use millpath::io::dxf::{DxfOptions, parse};
use millpath::io::write_dxf as write_outlines;
use millpath::stock::{self, SimOptions, StockSpec};
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::strategy::pocket::{PartStrategy, generate_part, order_pockets, tour_length};
use millpath::toolpath::{MoveKind, Tool, Toolpath};

fn sim() -> SimOptions {
    SimOptions::default().with_cell(0.1).with_step(0.2)
}

fn opts() -> PocketOptions {
    PocketOptions::default().with_depth(4.0).with_step_down(2.0)
}

fn square(x: f64, y: f64, w: f64, h: f64) -> Outline {
    builtin::rounded_rectangle(x, y, w, h, 4.0)
}

fn circle(cx: f64, cy: f64, r: f64) -> Outline {
    Outline::new(
        &[(Point::new(cx - r, cy), 1.0), (Point::new(cx + r, cy), 1.0)],
        "circle",
    )
    .expect("circle")
}

/// The drawing: a 100 × 70 plate pocket around a round island (r 22) with a round pocket
/// (r 12) inside it; a slot of half circles; a triangle; listed in a muddled order.
fn drawing() -> String {
    let slot = Outline::new(
        &[
            (Point::new(130.0, 10.0), 0.0),
            (Point::new(190.0, 10.0), 1.0),
            (Point::new(190.0, 40.0), 0.0),
            (Point::new(130.0, 40.0), 1.0),
        ],
        "slot",
    )
    .expect("slot");
    let tri = builtin::rounded_polygon(
        &[
            Point::new(120.0, 60.0),
            Point::new(200.0, 60.0),
            Point::new(160.0, 110.0),
        ],
        6.0,
        "triangle",
    )
    .expect("triangle");
    let loops = [
        circle(50.0, 35.0, 12.0),
        tri,
        square(0.0, 0.0, 100.0, 70.0),
        slot,
        circle(50.0, 35.0, 22.0),
    ];
    write_outlines(loops.iter(), "0")
}

fn shapes() -> Vec<(usize, PocketShape)> {
    let loops = parse(drawing().as_bytes(), "part.dxf", &DxfOptions::default()).expect("reads");
    loops
        .pockets()
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            (
                i + 1,
                PocketShape::new(p.outer, p.islands, "part.dxf").expect("pocket"),
            )
        })
        .collect()
}

/// The program as written and read back (3 decimals), levels from its retracts.
fn written(tp: &Toolpath) -> Toolpath {
    let (text, _) = write_to_string(tp, &WriterOptions::default()).expect("writes");
    let (mut back, _) = read_str(&text, ReaderOptions::default()).expect("reads back");
    back.tool = tp.tool;
    stock::infer_levels(&mut back);
    back
}

fn time_hsm(tp: &Toolpath) -> millpath::Result<f64> {
    millpath::motion::cycle_time(tp, &millpath::machine::Machine::preset("hsm")?)
}

#[test]
fn the_drawing_nests_into_four_pockets() {
    let s = shapes();
    assert_eq!(
        s.len(),
        4,
        "plate (with island), inner round, slot, triangle"
    );
    let islands: usize = s.iter().map(|(_, p)| p.islands.len()).sum();
    assert_eq!(islands, 1);
    // The round pocket inside the island is a pocket of its own.
    let inner = s
        .iter()
        .find(|(_, p)| {
            let c = Point::new(50.0, 35.0);
            p.outer.contains(c) && !p.islands.iter().any(|i| i.contains(c))
        })
        .expect("a pocket at the island's centre");
    assert!((inner.1.outer.signed_area() - std::f64::consts::PI * 144.0).abs() < 1e-6);
}

#[test]
fn every_strategy_cuts_every_pocket_in_one_verified_program() {
    let s = shapes();
    let tool = Tool::flat(6.0).expect("tool");
    let o = opts();
    for strategy in [
        PartStrategy::One(StrategyKind::Offset),
        PartStrategy::One(StrategyKind::Zigzag),
        PartStrategy::One(StrategyKind::Spiral),
        PartStrategy::Auto,
    ] {
        let part = generate_part(&s, strategy, &tool, &o, &sim(), &time_hsm).expect("plans");
        assert_eq!(part.pockets.len(), 4);
        assert!(
            part.pockets.iter().all(|p| p.result.is_some()),
            "{strategy:?}"
        );
        // The written program, read back, verified as a whole against the drawing.
        let back = written(&part.toolpath);
        let specs: Vec<StockSpec<'_>> = s
            .iter()
            .map(|(_, p)| StockSpec {
                outer: &p.outer,
                islands: &p.islands,
                wall_stock: 0.0,
            })
            .collect();
        let nominal = pocket::nominal_engagement(o.stepover_mm(&tool), tool.radius()).to_degrees();
        let v = stock::verify_part(&back, &specs, nominal, &sim());
        assert!(v.problems().is_empty(), "{strategy:?}: {:?}", v.problems());
        assert_eq!(v.cuts_outside, 0);
        assert!(
            v.pockets
                .iter()
                .all(|p| p.uncut_area_mm2 < 0.05 && p.mean_engagement_deg > 0.0)
        );
        // Every pocket cut: the reachable material removed in each (the verifier's coverage).
        // Rapids that change pocket stay above the stock.
        let pocket_of = |q: Point| {
            s.iter()
                .position(|(_, p)| p.outer.contains(q) && !p.islands.iter().any(|i| i.contains(q)))
        };
        let mut changes = 0;
        for (from, m) in back.segments() {
            if matches!(m.kind, MoveKind::Rapid) && pocket_of(from.xy()) != pocket_of(m.to.xy()) {
                changes += 1;
                assert!(
                    from.z >= 0.0 && m.to.z >= 0.0,
                    "{strategy:?}: rapid {from:?} -> {:?}",
                    m.to
                );
            }
        }
        assert!(
            changes >= 3,
            "{strategy:?}: {changes} rapids between pockets"
        );
        // Each pocket has its own entry: at least one descent per pocket per level.
        let ends: Vec<(Point, Point)> = part
            .pockets
            .iter()
            .filter_map(|p| p.result.as_ref())
            .map(|r| (r.toolpath.start.xy(), r.toolpath.end().xy()))
            .collect();
        let listed: Vec<usize> = (0..ends.len()).collect();
        let chosen = order_pockets(&ends, Point::ORIGIN);
        assert!(
            tour_length(&ends, Point::ORIGIN, &chosen)
                <= tour_length(&ends, Point::ORIGIN, &listed) + 1e-9
        );
    }
}

#[test]
fn select_cuts_only_the_pockets_asked_for() {
    let s = shapes();
    let some: Vec<(usize, PocketShape)> = s.iter().filter(|(i, _)| *i != 2).cloned().collect();
    let tool = Tool::flat(6.0).expect("tool");
    let part = generate_part(
        &some,
        PartStrategy::One(StrategyKind::Offset),
        &tool,
        &opts(),
        &sim(),
        &time_hsm,
    )
    .expect("plans");
    // Verified against all four pockets: the one left out is uncut, the others are not.
    let specs: Vec<StockSpec<'_>> = s
        .iter()
        .map(|(_, p)| StockSpec {
            outer: &p.outer,
            islands: &p.islands,
            wall_stock: 0.0,
        })
        .collect();
    let v = stock::verify_part(&written(&part.toolpath), &specs, 78.5, &sim());
    let area2 = s[1].1.outer.signed_area().abs();
    assert!(v.pockets[1].uncut_area_mm2 >= area2 - 1e-9);
    for k in [0, 2, 3] {
        assert!(v.pockets[k].uncut_area_mm2 < 0.05, "pocket {}", k + 1);
    }
}

#[test]
fn programs_pocket_writes_pass_verification_at_their_rounding() {
    let tool = Tool::flat(10.0).expect("tool");
    let o = PocketOptions::default().with_depth(5.0).with_step_down(2.5);
    let suite = builtin::shape_suite();
    let mut checked = 0;
    for sp in suite.iter().take(4) {
        for kind in [
            StrategyKind::Offset,
            StrategyKind::Zigzag,
            StrategyKind::Spiral,
        ] {
            let Ok(r) = pocket::generate(kind, &sp.shape, &tool, &o, &sim()) else {
                continue;
            };
            if !r.verification.problems().is_empty() {
                continue; // the strategy's own verdict; this test is about the written program
            }
            let back = written(&r.toolpath);
            let spec = StockSpec {
                outer: &sp.shape.outer,
                islands: &sp.shape.islands,
                wall_stock: 0.0,
            };
            let v = stock::verify_part(&back, &[spec], 78.5, &sim());
            assert!(
                v.problems_within(stock::gouge_resolution(3)).is_empty(),
                "{} {}: {:?}",
                sp.name,
                kind.name(),
                v.problems()
            );
            checked += 1;
        }
    }
    assert!(checked >= 8, "{checked} programs checked");
}

#[test]
fn a_vertical_retract_from_a_cut_along_the_wall_is_no_rapid_through_material() {
    // A 20 × 20 pocket cut by hand with a 6 mm tool: one slot down the middle, then a pass
    // along the walls, then G0 straight up from the wall (tool touching it).
    let outer = Outline::from_points(
        &[
            Point::new(0.0, 0.0),
            Point::new(20.0, 0.0),
            Point::new(20.0, 20.0),
            Point::new(0.0, 20.0),
        ],
        "square",
    )
    .expect("square");
    let text = "G21 G90 G17\nG0 X10 Y10 Z5\nG1 Z-1 F300\nG1 X3 Y3\nG1 X17 Y3\nG1 X17 Y17\n\
                G1 X3 Y17\nG1 X3 Y3\nG1 X10 Y3\nG1 X10 Y17\nG1 X3 Y10\nG1 X17 Y10\nG1 X3 Y3\nG0 Z5\nM2\n";
    let (mut tp, _) = read_str(text, ReaderOptions::default()).expect("reads");
    tp.tool = Tool::flat(6.0).expect("tool");
    stock::infer_levels(&mut tp);
    let spec = StockSpec {
        outer: &outer,
        islands: &[],
        wall_stock: 0.0,
    };
    let v = stock::verify(&tp, spec, 90.0, &sim());
    assert_eq!(v.rapids_through_material, 0, "{v:?}");
    assert!((v.min_clearance_mm - 3.0).abs() < 1e-9);
    // A vertical rapid down into the material is one.
    let down = "G21 G90 G17\nG0 X10 Y10 Z5\nG0 Z-1\nG1 X3 Y3 F300\nG0 Z5\nM2\n";
    let (mut tp2, _) = read_str(down, ReaderOptions::default()).expect("reads");
    tp2.tool = tp.tool;
    stock::infer_levels(&mut tp2);
    let v2 = stock::verify(&tp2, spec, 90.0, &sim());
    assert_eq!(v2.rapids_through_material, 1, "{v2:?}");
}

fn alone(o: &Outline) -> StockSpec<'_> {
    StockSpec {
        outer: o,
        islands: &[],
        wall_stock: 0.0,
    }
}

/// A pocket no tool position fits in (a 4 mm slot for a 6 mm tool) is not reachable with
/// this tool: the verifier finds it so by offsetting the outline itself, lists it, and does
/// not count it as uncut material (`pocket` skips it with a note, and `verify` failed the
/// program for `pb_screw_plate` and `s2g_smooth_curves`); a reachable pocket left uncut still
/// fails.
#[test]
fn a_pocket_narrower_than_the_tool_is_unreachable_not_uncut() {
    let s = shapes();
    let tool = Tool::flat(6.0).expect("tool");
    let part = generate_part(
        &s,
        PartStrategy::One(StrategyKind::Offset),
        &tool,
        &opts(),
        &sim(),
        &time_hsm,
    )
    .expect("plans");
    let slot = square(300.0, 0.0, 40.0, 4.0);
    let wide = square(300.0, 50.0, 40.0, 20.0);
    let mut specs: Vec<StockSpec<'_>> = s
        .iter()
        .map(|(_, p)| StockSpec {
            outer: &p.outer,
            islands: &p.islands,
            wall_stock: 0.0,
        })
        .collect();
    specs.push(alone(&slot));
    let back = written(&part.toolpath);
    let v = stock::verify_part(&back, &specs, 78.5, &sim());
    assert_eq!(v.unreachable, vec![s.len()]);
    assert!(v.problems().is_empty(), "{:?}", v.problems());
    specs.push(alone(&wide));
    let v = stock::verify_part(&back, &specs, 78.5, &sim());
    assert_eq!(v.unreachable, vec![s.len()]);
    let p = v.problems();
    assert!(
        p.iter().any(|x| matches!(
            x,
            stock::Problem::InPocket { pocket, problems }
                if *pocket == s.len() + 2
                    && matches!(problems.first(), Some(stock::Problem::Uncut { .. }))
        )),
        "{p:?}"
    );
}
