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
    let outer = rectangle();
    let spec = StockSpec {
        outer: &outer,
        islands: &[],
        wall_stock: 0.0,
    };
    let sim = SimOptions {
        cell: 0.1,
        step,
        ..SimOptions::default()
    };
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
            .any(|t| t.contains("uncut material") && t.contains("most of it around")),
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
