//! Real drawings (`../shared/real-inputs/files/`) on which pocketing once failed, each as
//! small as the failure allows: what the sweep of every drawing × five tools × three
//! strategies (`millpath-cli/tests/cli_real_files.rs`, `full_sweep`) found.
//!
//! * The region's offsets hold the whole eroded region (`pb_latch_test.dxf`, pocket 2:
//!   cavalier_contours' shape offset returned loops of no area at two epsilons where a
//!   37 mm arm ends, near 17.4 mm from the walls). The verifier is pointwise and shares
//!   nothing with the offset: on a grid over the pocket, every point farther than
//!   `d + 1 µm` from the walls (the outline's exact distance) must lie inside the offset's
//!   loops, and every point nearer than `d − 1 µm` outside them.
//! * The pockets below are generated and held to the stock simulation's verdict
//!   (`Verification::problems`: no gouge beyond the written program's resolution, nothing
//!   uncut the tool could reach), as `millpath verify` holds the written program.

use millpath::geom::{Outline, Point};
use millpath::io::ImportSettings;
use millpath::strategy::pocket::{PocketOptions, PocketShape, StrategyKind, generate};
use millpath::toolpath::Tool;

/// Pocket `n` (1-based, largest first) of a real drawing in `../shared/real-inputs/files/`.
fn real_pocket(name: &str, n: usize) -> PocketShape {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/real-inputs/files")
        .join(name);
    let (loops, _) =
        millpath::job::load_outline(&path.display().to_string(), &ImportSettings::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let p = loops.pockets().into_iter().nth(n - 1).expect("the pocket");
    PocketShape::new(p.outer, p.islands, name).expect("a valid pocket")
}

/// Inside the offset's loops: inside an outer (counter-clockwise) loop, outside every island.
fn inside(loops: &[Outline], p: Point) -> bool {
    let (outers, islands): (Vec<&Outline>, Vec<&Outline>) =
        loops.iter().partition(|o| o.signed_area() > 0.0);
    outers.iter().any(|o| o.contains(p)) && islands.iter().all(|o| !o.contains(p))
}

/// The grid points (spacing `step`) misplaced by the offset at `d`, and how many points were
/// farther than `d + 1 µm` from the walls.
fn misplaced(shape: &PocketShape, d: f64, step: f64) -> (Vec<Point>, usize) {
    let loops = shape.offset_loops(d);
    let b = shape.outer.bounds();
    let (nx, ny) = (
        ((b.max.x - b.min.x) / step) as usize,
        ((b.max.y - b.min.y) / step) as usize,
    );
    let mut wrong = Vec::new();
    let mut deep = 0;
    for i in 0..=nx {
        for j in 0..=ny {
            let p = Point::new(b.min.x + step * i as f64, b.min.y + step * j as f64);
            if !shape.contains(p) {
                continue;
            }
            let w = shape.distance_to(p);
            if w > d + 1e-3 {
                deep += 1;
                if !inside(&loops, p) {
                    wrong.push(p);
                }
            } else if w < d - 1e-3 && inside(&loops, p) {
                wrong.push(p);
            }
        }
    }
    (wrong, deep)
}

/// Pocket 2 of `pb_latch_test.dxf` at the offset strategy's loop distances for a 6 mm tool
/// (3 + 2.4·k mm) and at the last ones before the region vanishes: every grid point is on
/// the right side of the offset, and the points beyond 17.4 mm exist (the arm's end).
#[test]
fn pb_latch_offsets_hold_the_whole_eroded_region() {
    let shape = real_pocket("pb_latch_test.dxf", 2);
    let mut checked = 0;
    for (k, d) in [3.0, 12.6, 15.0, 17.4, 19.8, 29.4, 38.5]
        .into_iter()
        .enumerate()
    {
        let (wrong, deep) = misplaced(&shape, d, 1.0);
        assert!(
            wrong.is_empty(),
            "offset {d} mm: {} grid points on the wrong side, e.g. {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(3)]
        );
        if k == 3 {
            assert!(deep > 2000, "17.4 mm: {deep} grid points beyond it");
        }
        checked += deep;
    }
    assert!(checked > 10_000, "{checked} points checked inside");
}

/// Generates every pocket of `name` with `kind` and a `diameter` mm tool, one level
/// `min(3, diameter)` deep, every other option at its default (the stock raster at
/// `diameter / 40`, at least 0.05 mm), and asserts the verifier's
/// verdict on each: no problem (gouge or uncut material), and the uncut area within the
/// tolerance.
fn assert_verified(name: &str, diameter: f64, kind: StrategyKind) {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/real-inputs/files")
        .join(name);
    let (loops, _) =
        millpath::job::load_outline(&path.display().to_string(), &ImportSettings::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let tool = Tool::flat(diameter).expect("tool");
    let depth = diameter.min(3.0);
    let opts = PocketOptions::default()
        .with_depth(depth)
        .with_step_down(depth);
    // The raster at a fortieth of the tool (twenty cells to the radius), never finer than
    // the default 0.05 mm.
    let sim = millpath::job::pocket::sim_options(Some((diameter / 40.0).max(0.05)), diameter);
    let pockets = loops.pockets();
    assert!(!pockets.is_empty());
    for (i, p) in pockets.into_iter().enumerate() {
        let shape = PocketShape::new(p.outer, p.islands, name).expect("pocket");
        let r = generate(kind, &shape, &tool, &opts, &sim)
            .unwrap_or_else(|e| panic!("{name} pocket {} {kind:?}: {e}", i + 1));
        let v = &r.verification;
        assert!(
            v.problems().is_empty(),
            "{name} pocket {} {kind:?}: {:?} (clearance {} mm, needs {})",
            i + 1,
            v.problems(),
            v.min_clearance_mm,
            v.required_clearance_mm
        );
        assert!(v.uncut_area_mm2 <= v.uncut_tolerance_mm2);
    }
}

/// `wro_Plate_2.DXF` with a 4.09 mm tool: a rectangular island's corner and a round island
/// are exactly one tool diameter apart, so their loops in the tool-centre region touch at a
/// point. The spiral moved the rectangle's loop 5 µm into the region (its last-loop margin),
/// which ran 0.0048 mm into the round island's clearance over 0.4 mm, between the samples
/// that checked it (0.5 mm apart): the program was written and `verify` refused it as a
/// gouge. The moved loop must now cross none of the region's loops.
#[test]
fn wro_plate_2_spiral_keeps_clear_where_two_islands_loops_touch() {
    assert_verified("wro_Plate_2.DXF", 4.09, StrategyKind::Spiral);
}

/// `s2g_smooth_curves.svg` with a 0.9855 mm tool: cavalier_contours' shape offset of pocket
/// 1 (ten islands) by the tool radius came back without the loop of one island, every loop
/// it did return at the right distance; the zigzag's rows ran across that island and every
/// strategy was refused as gouging (internal error, exit 1). The wall samples of
/// `offset_check` now lie outside every accepted offset.
#[test]
fn smooth_curves_offset_keeps_every_islands_loop() {
    let shape = real_pocket("s2g_smooth_curves.svg", 1);
    let loops = shape.offset_loops(0.49275);
    assert_eq!(loops.len(), 1 + shape.islands.len(), "one loop per wall");
    let (wrong, deep) = misplaced(&shape, 0.49275, 0.25);
    assert!(
        wrong.is_empty(),
        "{} grid points misplaced: {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(3)]
    );
    assert!(deep > 800, "{deep} grid points inside");
    assert_verified("s2g_smooth_curves.svg", 0.9855, StrategyKind::Zigzag);
}

/// Every move that ends within 1 µm of its level's height ends exactly at it, so that the
/// written program (3 decimals) has one depth per level: `wro_Braking_Arm.DXF` with a
/// 0.2245 mm tool one tool deep had ramps ending a few ulps above `z = -0.2245` (written
/// `Z-0.224`, the cuts `Z-0.225`), and `verify` found nine levels and 780 mm² uncut on the
/// program `pocket` wrote; `s2g_shapes.svg` at 0.8355 mm likewise. Helix and ramp entries
/// (`levels::emit_cut`, shared by every strategy), by zigzag.
#[test]
fn entries_end_at_their_levels_height() {
    for (name, diameter) in [("wro_Braking_Arm.DXF", 0.2245), ("s2g_shapes.svg", 0.8355)] {
        let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../../shared/real-inputs/files")
            .join(name);
        let (loops, _) =
            millpath::job::load_outline(&path.display().to_string(), &ImportSettings::default())
                .expect("drawing");
        let tool = Tool::flat(diameter).expect("tool");
        let mut checked = 0;
        for entry in [
            millpath::strategy::pocket::Entry::Helix {
                radius: 2.5,
                ramp_angle: 3f64.to_radians(),
            },
            millpath::strategy::pocket::Entry::Ramp {
                ramp_angle: 3f64.to_radians(),
            },
        ] {
            let opts = PocketOptions::default()
                .with_depth(diameter)
                .with_step_down(diameter)
                .with_entry(entry);
            for kind in [
                StrategyKind::Zigzag,
                StrategyKind::Offset,
                StrategyKind::Spiral,
            ] {
                for p in loops.pockets() {
                    let shape = PocketShape::new(p.outer, p.islands, name).expect("pocket");
                    let Ok(tp) = millpath::strategy::pocket::toolpath(kind, &shape, &tool, &opts)
                    else {
                        continue;
                    };
                    for lv in &tp.levels {
                        for m in &tp.moves[lv.start..lv.end] {
                            if (m.to.z - lv.z).abs() < 1e-6 {
                                assert!(
                                    m.to.z.to_bits() == lv.z.to_bits(),
                                    "{name} {kind:?} {entry:?}: {m:?} not at z = {}",
                                    lv.z
                                );
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(checked > 1000, "{name}: {checked} moves at their level");
    }
}

/// Every pocket of a drawing, in the drawing's order.
fn all_pockets(name: &str) -> Vec<(usize, PocketShape)> {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/real-inputs/files")
        .join(name);
    let (loops, _) =
        millpath::job::load_outline(&path.display().to_string(), &ImportSettings::default())
            .expect("drawing");
    loops
        .pockets()
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            (
                i + 1,
                PocketShape::new(p.outer, p.islands, name).expect("pocket"),
            )
        })
        .collect()
}

/// `pb_screw_plate.dxf` with a 0.7029 mm tool: pocket 2 (6.6 mm², five islands) is at most
/// 0.299 mm from its walls (a 0.01 mm grid of exact distances), so no centre of the tool
/// (radius 0.351) fits, and the offset strategy left it out; the verifier's reach map counted
/// it reachable from its transform's bound (within 2 cells of fitting) and refused the
/// program for 6.634 mm² uncut. Its exact search now agrees; it still finds room for the
/// 0.2223 mm tool, and the part planned with it is verified.
#[test]
fn the_verifier_agrees_a_pocket_narrower_than_the_tool_is_out_of_reach() {
    let pockets = all_pockets("pb_screw_plate.dxf");
    let p2 = &pockets[1].1;
    let spec = |wall_stock| millpath::stock::StockSpec {
        outer: &p2.outer,
        islands: &p2.islands,
        wall_stock,
    };
    let b = p2.outer.bounds();
    let mut widest: f64 = 0.0;
    let step = 0.01;
    for i in 0..=((b.max.x - b.min.x) / step) as usize {
        for j in 0..=((b.max.y - b.min.y) / step) as usize {
            let p = Point::new(b.min.x + step * i as f64, b.min.y + step * j as f64);
            if p2.contains(p) {
                widest = widest.max(p2.distance_to(p));
            }
        }
    }
    assert!((0.29..0.30).contains(&widest), "{widest}");
    assert!(!millpath::stock::reachable(spec(0.0), 0.7029 / 2.0, 0.05));
    assert!(millpath::stock::reachable(spec(0.0), 0.2223 / 2.0, 0.05));
    // Within a grid step of the widest point: still room (the search is exact).
    assert!(millpath::stock::reachable(spec(0.0), widest - step, 0.05));
}

/// `s2g_vanderbilt_logo.svg` with a 0.7482 mm tool by offset: pocket 1's region has a
/// piece 0.03 mm long cut off from the rest, with no room to ramp into and no cleared
/// material beside it. The part planner left the whole pocket out and wrote a program
/// `verify` refused (80 mm² uncut); the pocket is reachable, so the part is refused as bad
/// input naming the cut. `s2g_smooth_curves.svg` at 1.753 mm by zigzag: a row 0.04 mm long
/// beside the clean-up pass far from that pass's segment ends; now entered from the nearest
/// point of the pass, and every pocket is cut and verified.
#[test]
fn a_cut_only_a_plunge_reaches_refuses_the_part_and_one_beside_a_pass_is_entered() {
    use millpath::strategy::pocket::{PartStrategy, generate_part};
    let time = |tp: &millpath::toolpath::Toolpath| Ok(tp.cut_length());
    let pockets = all_pockets("s2g_vanderbilt_logo.svg");
    let tool = Tool::flat(0.7482).expect("tool");
    let opts = PocketOptions::default()
        .with_depth(0.7482)
        .with_step_down(0.7482);
    let sim = millpath::job::pocket::sim_options(None, 0.7482);
    match generate_part(
        &pockets,
        PartStrategy::One(StrategyKind::Offset),
        &tool,
        &opts,
        &sim,
        &time,
    ) {
        Err(millpath::Error::Input(e)) => {
            let m = e.to_string();
            assert!(m.contains("only a plunge reaches"), "{m}");
        }
        other => panic!(
            "expected a refusal: {:?}",
            other.map(|p| p.verification.total.uncut_area_mm2)
        ),
    }
    let pockets = all_pockets("s2g_smooth_curves.svg");
    let tool = Tool::flat(1.753).expect("tool");
    let opts = PocketOptions::default()
        .with_depth(1.753)
        .with_step_down(1.753);
    let sim = millpath::job::pocket::sim_options(None, 1.753);
    let part = generate_part(
        &pockets,
        PartStrategy::One(StrategyKind::Zigzag),
        &tool,
        &opts,
        &sim,
        &time,
    )
    .expect("planned");
    assert!(part.pockets.iter().all(|p| p.skipped.is_none()));
    let v = &part.verification;
    assert!(v.total.problems().is_empty(), "{:?}", v.total.problems());
    assert!(v.unreachable.is_empty());
    for pv in &v.pockets {
        assert!(
            pv.uncut_area_mm2 <= pv.uncut_tolerance_mm2,
            "{}",
            pv.uncut_area_mm2
        );
    }
}

/// `ma_Part.dxf` with a 5 mm tool by offset: an island's loop at one level touches its outer
/// loop at the island loop's first vertex, whose winding number then said "outside"; the
/// island's loop belonged to no node and was never cut (0.24 mm² left, an internal error).
/// A loop's owner is now the region holding most of its points.
#[test]
fn ma_part_offset_cuts_an_islands_loop_touching_its_outer_loop() {
    assert_verified("ma_Part.dxf", 5.0, StrategyKind::Offset);
}

/// `ez_clockwise_arcs_hatch.dxf` (metres: 56 × 70 m, 2·10⁵–6·10⁵ mm from the origin) with
/// a 4427 mm tool by spiral: the spiral's loops were sliced into arc pieces a few ulps long
/// (1e-11 mm), and a move keeps only an arc's end and centre, so such a piece read back as a
/// full circle of 2 m through the walls (an internal error, "within 0.0000 mm of a wall").
/// Flatness is now judged by the piece's own sweep and slices drop pieces below 1e-12 of the
/// loop's length.
#[test]
fn metre_scale_spiral_slices_become_no_full_circles() {
    assert_verified("ez_clockwise_arcs_hatch.dxf", 4427.0, StrategyKind::Spiral);
}
