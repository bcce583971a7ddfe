//! The stock simulation's coverage: it finds material a path left and says where, and it does
//! not invent uncut material when asked for a coarse sampling step (the tool positions stay
//! within a quarter radius of each other whatever `SimOptions::step` says).

use millpath::geom::{Outline, Point, Point3};
use millpath::stock::{self, SimOptions, StockSpec};
use millpath::toolpath::{Level, LevelKind, Move, Tool, Toolpath};

/// A 40 × 20 mm rectangle.
fn rectangle() -> Outline {
    let p = Point::new;
    Outline::from_points(
        &[p(0.0, 0.0), p(40.0, 0.0), p(40.0, 20.0), p(0.0, 20.0)],
        "rectangle",
    )
    .expect("a rectangle")
}

/// Passes at y = 5, 10, 15 with a 10 mm tool from x = 5 to `x_end` and passes along x = 5
/// and x = `x_end`, one level at z = −1.
fn passes(x_end: f64) -> Toolpath {
    let tool = Tool::flat(10.0).expect("a tool");
    let mut tp = Toolpath::new(tool, Point3::new(5.0, 5.0, 5.0));
    tp.push(Move::rapid(Point3::new(5.0, 5.0, 1.0)));
    let start = tp.moves.len();
    tp.push(Move::line(Point3::new(5.0, 5.0, -1.0), 5.0));
    // Along the start, then back.
    tp.push(Move::line(Point3::new(5.0, 15.0, -1.0), 20.0));
    tp.push(Move::line(Point3::new(5.0, 5.0, -1.0), 20.0));
    for (k, y) in [5.0, 10.0, 15.0].into_iter().enumerate() {
        let (a, b) = if k % 2 == 0 {
            (5.0, x_end)
        } else {
            (x_end, 5.0)
        };
        tp.push(Move::line(Point3::new(a, y, -1.0), 20.0));
        tp.push(Move::line(Point3::new(b, y, -1.0), 20.0));
    }
    // Along the end, where the passes turn: the scallops between them at that end.
    tp.push(Move::line(Point3::new(x_end, 5.0, -1.0), 20.0));
    let end = tp.moves.len();
    tp.push(Move::rapid(Point3::new(5.0, 15.0, 5.0)));
    tp.levels.push(Level {
        z: -1.0,
        kind: LevelKind::Roughing,
        start,
        end,
    });
    tp
}

fn verify(tp: &Toolpath, step: f64) -> stock::Verification {
    verify_on(tp, step, 0.1)
}

fn verify_on(tp: &Toolpath, step: f64, cell: f64) -> stock::Verification {
    verify_in(
        tp,
        &rectangle(),
        step,
        cell,
        SimOptions::default().max_cells,
    )
}

fn verify_in(
    tp: &Toolpath,
    outer: &Outline,
    step: f64,
    cell: f64,
    max_cells: usize,
) -> stock::Verification {
    let spec = StockSpec {
        outer,
        islands: &[],
        wall_stock: 0.0,
    };
    let sim = SimOptions::default()
        .with_cell(cell)
        .with_step(step)
        .with_max_cells(max_cells);
    stock::verify(tp, spec, 90.0, &sim)
}

#[test]
fn a_path_that_stops_halfway_leaves_material_and_the_verifier_says_where() {
    let v = verify(&passes(20.0), 0.1);
    // Beyond the tool's reach from x = 20: x from 25 to the wall, about 15 × 20 mm² less the
    // corner cusps.
    assert!(v.uncut_area_mm2 > 200.0, "{v:?}");
    let at = v.uncut_at.expect("a place");
    assert!(at.x > 25.0 && at.x < 40.0, "{at:?}");
    assert!((at.z + 1.0).abs() < 1e-9, "{at:?}");
    let p = v.problems();
    assert!(
        p.iter()
            .any(|t| matches!(t, stock::Problem::Uncut { at: Some(_), .. })
                && t.to_string().contains("most of it around")),
        "{p:?}"
    );
    // The whole length: nothing the tool could reach is left.
    let full = verify(&passes(35.0), 0.1);
    assert!(
        full.uncut_area_mm2 <= stock::UNCUT_AREA_TOLERANCE,
        "{full:?}"
    );
    assert_eq!(full.uncut_at, None);
}

/// A step of 30 mm (coarser than the tool) must not turn into slivers between samples.
#[test]
fn a_coarse_step_does_not_invent_uncut_material() {
    let fine = verify(&passes(35.0), 0.1);
    let coarse = verify(&passes(35.0), 30.0);
    assert!(
        coarse.uncut_area_mm2 <= stock::UNCUT_AREA_TOLERANCE,
        "{} mm² uncut with a 30 mm step",
        coarse.uncut_area_mm2
    );
    assert!((coarse.uncut_area_mm2 - fine.uncut_area_mm2).abs() <= 0.05);
}

/// Feeding straight down where an earlier cut ended is no plunge, even when the program's
/// rounding put that end a little off the arc the verifier swept: G-code stores an arc's
/// centre to 3 decimals, so its end point lies up to ~1 µm off the circle through its start,
/// and the last disc swept is that far from where the next entry lands. `pocket`'s zigzag on
/// `ma_Part.dxf` (tool 10 mm) enters a row directly at the end of an earlier arc
/// (167.219, 15.833), and `verify` counted it as a plunge into material: one cell on the
/// landing disc's rim. Feeding down onto fresh material is a plunge.
#[test]
fn feeding_down_where_a_cut_ended_is_no_plunge() {
    let p = Point::new;
    let pocket = Outline::from_points(
        &[p(0.0, 0.0), p(100.0, 0.0), p(100.0, 100.0), p(0.0, 100.0)],
        "square",
    )
    .expect("a square");
    let tool = Tool::flat(10.0).expect("a tool");
    let mut tp = Toolpath::new(tool, Point3::new(0.0, 0.0, 5.0));
    let start = tp.moves.len();
    let mut fresh = 0;
    for k in 0..25 {
        let c = p(
            14.0 + 17.3 * f64::from(k % 5) + 0.013 * f64::from(k),
            14.0 + 17.1 * f64::from(k / 5) + 0.007 * f64::from(k),
        );
        // A quarter arc of radius 3 whose end lies 0.7 µm outside the circle through its start.
        let a = Point3::new(c.x + 3.0, c.y, -3.0);
        let angle = 1.3 + 0.01 * f64::from(k);
        let rr = 3.0 + 0.000_7 * if k % 2 == 0 { 1.0 } else { -1.0 };
        let b = Point3::new(c.x + rr * angle.cos(), c.y + rr * angle.sin(), -3.0);
        tp.push(Move::rapid(Point3::new(a.x, a.y, 1.0)));
        tp.push(Move::line(a, 5.0));
        fresh += 1;
        tp.push(Move::arc_xy(b, Point3::new(c.x, c.y, -3.0), true, 20.0));
        tp.push(Move::rapid(Point3::new(b.x, b.y, 1.0)));
        tp.push(Move::line(b, 5.0));
        tp.push(Move::rapid(Point3::new(b.x, b.y, 1.0)));
    }
    let end = tp.moves.len();
    tp.levels.push(Level {
        z: -3.0,
        kind: LevelKind::Roughing,
        start,
        end,
    });
    let spec = StockSpec {
        outer: &pocket,
        islands: &[],
        wall_stock: 0.0,
    };
    let v = stock::verify(&tp, spec, 90.0, &SimOptions::default());
    assert_eq!(v.plunges, fresh, "{v:?}");
}

/// Cells coarser than half the tool radius (3 mm cells, a 10 mm tool: the reach limit
/// `r − 2c` is negative; only a cell budget forces them, [`stock::MAX_CELL_RADII`]) still count the material whose cell centre the tool centre may
/// visit. Before 2026-11-25 such cells were never flagged and a path that stops halfway
/// passed on a coarse raster (found by the `pocket` fuzzer).
#[test]
fn a_coarse_raster_still_finds_material_in_the_reach_region() {
    // 800 mm² in at most 88 cells: 3 mm cells.
    let coarse = |tp: &Toolpath| verify_in(tp, &rectangle(), 0.5, 0.05, 88);
    let half = coarse(&passes(20.0));
    assert!(half.cell_mm >= 3.0, "{half:?}");
    // The reach region beyond the tool at x = 20 (x from 25 to 35, y from 5 to 15), counted
    // by 9 mm² cells: most of its 100 mm².
    assert!(half.uncut_area_mm2 > 50.0, "{half:?}");
    let at = half.uncut_at.expect("a place");
    assert!(at.x > 22.0 && at.x < 40.0, "{at:?}");
    let full = coarse(&passes(35.0));
    assert!(
        full.uncut_area_mm2 <= stock::UNCUT_AREA_TOLERANCE,
        "{full:?}"
    );
}

/// A 0.1 mm tool whose passes are 0.12 mm apart leaves strips 0.02 mm wide between them:
/// the simulation's cell follows the tool down ([`stock::MAX_CELL_RADII`] of its radius,
/// whatever `--cell` asks), and the strips are measured within 10 % (on the 0.05 mm cell
/// asked for, 0.385 mm² of 0.456).
#[test]
fn a_small_tool_is_verified_on_a_cell_of_its_own_scale() {
    let p = Point::new;
    let (len, r, gap) = (4.0, 0.05, 0.12);
    let height = 2.0 * r + 6.0 * gap;
    let outer = Outline::from_points(
        &[p(0.0, 0.0), p(len, 0.0), p(len, height), p(0.0, height)],
        "strip pocket",
    )
    .expect("a rectangle");
    let tool = Tool::flat(2.0 * r).expect("a tool");
    let mut tp = Toolpath::new(tool, Point3::new(r, r, 1.0));
    let start = tp.moves.len();
    tp.push(Move::line(Point3::new(r, r, -0.1), 1.0));
    for k in 0..7 {
        let y = r + gap * k as f64;
        let (a, b) = if k % 2 == 0 {
            (r, len - r)
        } else {
            (len - r, r)
        };
        tp.push(Move::line(Point3::new(a, y, -0.1), 5.0));
        tp.push(Move::line(Point3::new(b, y, -0.1), 5.0));
    }
    let end = tp.moves.len();
    tp.push(Move::rapid(Point3::new(r, height - r, 1.0)));
    tp.levels.push(Level {
        z: -0.1,
        kind: LevelKind::Roughing,
        start,
        end,
    });
    let v = verify_in(&tp, &outer, 0.1, 0.05, SimOptions::default().max_cells);
    assert!(v.cell_mm <= r / 8.0 + 1e-12, "{v:?}");
    // Six strips (gap − 2r) wide between the links at x = r and x = len − r, which cut them
    // back by the tool radius at each end.
    let strips = 6.0 * (gap - 2.0 * r) * (len - 4.0 * r);
    assert!(
        (v.uncut_area_mm2 - strips).abs() <= 0.1 * strips,
        "uncut {} mm², the strips {strips} mm²: {v:?}",
        v.uncut_area_mm2
    );
    assert!(!v.problems().is_empty(), "{v:?}");
}
