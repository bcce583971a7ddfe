//! The final comparison of a whole job's height field with the drawing
//! (`stock::check_field`), on hand-made programs: a 40 × 30 mm pocket 5 mm deep in a
//! 60 × 50 mm part, cleared by a zigzag and a finishing pass round its walls (as drawn: the
//! corners a round tool cannot reach are not uncut), by a zigzag whose rows lie too far apart
//! (uncut strips), with a plunge too deep (below the floor) and with a move over the
//! pocket's wall into the part (cut into the part).

use millpath::geom::{Aabb, Outline, Point, Point3};
use millpath::stock::{
    CheckOptions, Deviation, FieldOptions, Floor, HeightField, PartTop, check_field,
};
use millpath::toolpath::{Move, Tool, Toolpath};

const R: f64 = 3.0;
const FLOOR: f64 = -5.0;

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Outline {
    let pts = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    Outline::from_points(&pts, "test rectangle").expect("a rectangle")
}

/// Rows `stepover` apart from y = 13 up to 37 (the tool centre 3 mm inside the pocket),
/// joined along x = 13 and x = 47; with `finish`, a pass round the centres' rectangle.
fn pocket(stepover: f64, finish: bool) -> Toolpath {
    let mut tp = Toolpath::new(
        Tool::flat(2.0 * R).expect("a tool"),
        Point3::new(13.0, 13.0, 5.0),
    );
    tp.push(Move::rapid(Point3::new(13.0, 13.0, 1.0)));
    tp.push(Move::line(Point3::new(13.0, 13.0, FLOOR), 2.0));
    let mut y = 13.0;
    let mut right = true;
    loop {
        let x = if right { 47.0 } else { 13.0 };
        tp.push(Move::line(Point3::new(x, y, FLOOR), 10.0));
        if y >= 37.0 - 1e-9 {
            break;
        }
        y = (y + stepover).min(37.0);
        tp.push(Move::line(Point3::new(x, y, FLOOR), 10.0));
        right = !right;
    }
    if finish {
        let at = tp.end();
        for (x, yy) in [
            (13.0, 37.0),
            (13.0, 13.0),
            (47.0, 13.0),
            (47.0, 37.0),
            (13.0, 37.0),
        ] {
            tp.push(Move::line(Point3::new(x, yy, FLOOR), 10.0));
        }
        tp.push(Move::line(at, 10.0));
    }
    tp.push(Move::rapid(Point3::new(tp.end().x, tp.end().y, 5.0)));
    tp
}

fn check(tp: &Toolpath) -> millpath::stock::FieldCheck {
    let block = Aabb {
        min: Point::new(-5.0, -5.0),
        max: Point::new(65.0, 55.0),
    };
    let mut field = HeightField::new(block, -20.0, 0.0, &FieldOptions::default()).expect("a block");
    field.cut(tp);
    let outline = rect(0.0, 0.0, 60.0, 50.0);
    let hole = rect(10.0, 10.0, 50.0, 40.0);
    let floors = [Floor {
        outer: &hole,
        islands: &[],
        z: FLOOR,
        tool_radius: R,
    }];
    let part = PartTop {
        outline: &outline,
        windows: &[],
        top_z: 0.0,
    };
    check_field(&field, Some(part), &floors, &CheckOptions::default())
}

#[test]
fn a_pocket_cleared_and_finished_is_as_drawn() {
    let v = check(&pocket(4.0, true));
    assert!(v.passes(), "{v}");
    assert!(v.uncut_mm2[0] < 0.05, "{:?}", v.uncut_mm2);
    assert_eq!(v.to_string(), "as drawn");
}

#[test]
fn rows_too_far_apart_leave_uncut_strips() {
    // Rows 8 mm apart with a 6 mm tool: 2 mm strips between them, 34 mm long (the joins
    // along x = 13 and 47 cut their ends), three of them.
    let v = check(&pocket(8.0, true));
    let uncut: Vec<_> = v
        .deviations
        .iter()
        .filter_map(|d| match d {
            Deviation::Uncut {
                floor: 0,
                area_mm2,
                height_mm,
                ..
            } => Some((*area_mm2, *height_mm)),
            _ => None,
        })
        .collect();
    assert_eq!(uncut.len(), 1, "{v}");
    let (area, height) = uncut[0];
    // The strips between the discs' reach: every row gap 8 − 6 = 2 mm wide, less the
    // 0.1 mm (2c) a cell must lie within the tool's reach, over 28 mm between the joins'
    // swept edges.
    assert!(area > 3.0 * 1.5 * 28.0 && area < 3.0 * 2.2 * 34.0, "{v}");
    assert!((height - 5.0).abs() < 1e-3, "{v}");
    assert_eq!(v.deviations.len(), 1, "{v}");
}

#[test]
fn too_deep_is_below_the_floor_and_over_the_wall_is_into_the_part() {
    let mut tp = pocket(4.0, true);
    tp.push(Move::rapid(Point3::new(30.0, 25.0, 1.0)));
    tp.push(Move::line(Point3::new(30.0, 25.0, FLOOR - 1.0), 2.0));
    tp.push(Move::rapid(Point3::new(30.0, 25.0, 1.0)));
    let v = check(&tp);
    assert_eq!(v.deviations.len(), 1, "{v}");
    match &v.deviations[0] {
        Deviation::BelowFloor {
            floor: 0,
            area_mm2,
            depth_mm,
            at,
        } => {
            let disc = std::f64::consts::PI * R * R;
            assert!((area_mm2 - disc).abs() < 0.05 * disc, "{v}");
            assert!((depth_mm - 1.0).abs() < 1e-3, "{v}");
            assert!(at.xy().distance(Point::new(30.0, 25.0)) < R, "{v}");
        }
        d => panic!("{d}"),
    }
    let mut tp = pocket(4.0, true);
    tp.push(Move::line(Point3::new(30.0, 25.0, -2.0), 2.0));
    tp.push(Move::line(Point3::new(30.0, 45.0, -2.0), 2.0));
    tp.push(Move::rapid(Point3::new(30.0, 45.0, 1.0)));
    let v = check(&tp);
    assert_eq!(v.deviations.len(), 1, "{v}");
    match &v.deviations[0] {
        Deviation::CutIntoPart {
            area_mm2, depth_mm, ..
        } => {
            // The slot from y = 40 to 45 and the half disc beyond, 6 mm wide.
            let want = 5.0 * 2.0 * R + 0.5 * std::f64::consts::PI * R * R;
            assert!((area_mm2 - want).abs() < 0.05 * want, "{v}: want {want}");
            assert!((depth_mm - 2.0).abs() < 1e-3, "{v}");
        }
        d => panic!("{d}"),
    }
}
