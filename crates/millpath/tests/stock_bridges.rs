//! The bridge verdict (`stock::held_by`) on hand-made profile programs, written here move by
//! move without any strategy: a 40 × 30 mm part cut out of a 10 mm plate with a 6 mm tool,
//! with two tabs, with one of them cut off afterwards, with a stretch the program forgot to
//! cut through, and with no tabs; and a 20 × 20 mm window whose slug is held by one tab,
//! with the corners the round tool cannot reach left on the frame.

use millpath::geom::{Aabb, Outline, Point, Point3};
use millpath::stock::{
    Bridge, BridgeOptions, BridgeVerdict, CutSide, FieldOptions, HeightField, Hold, Touches,
    held_by,
};
use millpath::toolpath::{Move, Tool, Toolpath};

const R: f64 = 3.0;
const BOTTOM: f64 = -10.0;
const TAB_TOP: f64 = -7.0;
const LEVELS: [f64; 4] = [-3.0, -6.0, -9.0, -10.0];

fn part() -> Outline {
    let pts = [(0.0, 0.0), (40.0, 0.0), (40.0, 30.0), (0.0, 30.0)];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    Outline::from_points(&pts, "test part").expect("a square")
}

fn field() -> HeightField {
    let block = Aabb {
        min: Point::new(-15.0, -15.0),
        max: Point::new(55.0, 45.0),
    };
    HeightField::new(block, BOTTOM, 0.0, &FieldOptions::default()).expect("a block")
}

/// Where a pass lifts over a tab: the side (0 bottom, 1 right, 2 top, 3 left, counter-
/// clockwise from the part's first vertex), the lift's start and end along that side of the
/// path (mm from the side's start), and the z it lifts to.
#[derive(Clone, Copy)]
struct Lift {
    side: usize,
    from: f64,
    to: f64,
    z: f64,
}

/// One pass round the part at `z`, the tool centre 3 mm outside it (corners as arcs about
/// the part's corners), from `(0, −3)` back to it, lifting over `lifts`.
fn pass(tp: &mut Toolpath, z: f64, lifts: &[Lift]) {
    let corners = [(0.0, 0.0), (40.0, 0.0), (40.0, 30.0), (0.0, 30.0)];
    let dirs = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
    let normals = [(0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)];
    let feed = 10.0;
    for side in 0..4 {
        let (cx, cy) = corners[side];
        let (dx, dy) = dirs[side];
        let (ux, uy) = normals[side];
        let len = if side % 2 == 0 { 40.0 } else { 30.0 };
        let at = |s: f64, z: f64| Point3::new(cx + ux * R + dx * s, cy + uy * R + dy * s, z);
        for l in lifts.iter().filter(|l| l.side == side) {
            tp.push(Move::line(at(l.from, z), feed));
            tp.push(Move::line(at(l.from, l.z), feed));
            tp.push(Move::line(at(l.to, l.z), feed));
            tp.push(Move::line(at(l.to, z), feed));
        }
        tp.push(Move::line(at(len, z), feed));
        // Round the next corner.
        let (nx, ny) = corners[(side + 1) % 4];
        let (vx, vy) = normals[(side + 1) % 4];
        tp.push(Move::arc_xy(
            Point3::new(nx + vx * R, ny + vy * R, z),
            Point3::new(nx, ny, z),
            true,
            feed,
        ));
    }
}

/// The profile at every level, lifting over `tabs` on the levels below the tab top and over
/// `skipped` on the last level.
fn profile(tabs: &[Lift], skipped: &[Lift]) -> Toolpath {
    let tool = Tool::flat(2.0 * R).expect("a tool");
    let mut tp = Toolpath::new(tool, Point3::new(0.0, -R, 5.0));
    tp.push(Move::rapid(Point3::new(0.0, -R, 1.0)));
    for (k, &z) in LEVELS.iter().enumerate() {
        tp.push(Move::line(Point3::new(0.0, -R, z), 5.0));
        let mut lifts: Vec<Lift> = if z < TAB_TOP {
            tabs.to_vec()
        } else {
            Vec::new()
        };
        if k + 1 == LEVELS.len() {
            lifts.extend_from_slice(skipped);
        }
        lifts.sort_by(|a, b| {
            (a.side, a.from)
                .partial_cmp(&(b.side, b.from))
                .expect("finite")
        });
        pass(&mut tp, z, &lifts);
    }
    tp.push(Move::rapid(Point3::new(0.0, -R, 5.0)));
    tp
}

/// Tabs 4 mm wide at the part, centred at 20 mm along the bottom and along the top: the
/// path lifts over 4 + 2r = 10 mm.
fn two_tabs() -> [Lift; 2] {
    [
        Lift {
            side: 0,
            from: 15.0,
            to: 25.0,
            z: TAB_TOP,
        },
        Lift {
            side: 2,
            from: 15.0,
            to: 25.0,
            z: TAB_TOP,
        },
    ]
}

fn verdict(tp: &Toolpath) -> BridgeVerdict {
    let mut f = field();
    let cut = f.cut(tp);
    assert!(cut.rapids_through_material.is_empty(), "{cut}");
    held_by(&f, &part(), BOTTOM, R, &BridgeOptions::default()).expect("a verdict")
}

/// A holding bridge centred `mid` mm along the outline, `neck` mm wide at the slot's
/// middle, topped at `top`; along the outline it spans what the round tool leaves at the
/// band's first row of cells, `δ` from the walls (`ρ ≤ δ < ρ + 2c`, by the transform):
/// `neck + 2r − 2√(r² − (r − δ)²)`.
fn assert_bridge(v: &BridgeVerdict, b: &Bridge, mid: f64, neck: f64, top: f64) {
    let c = v.cell_mm;
    let rho = v.band_mm.0;
    let extent = |d: f64| neck + 2.0 * R - 2.0 * (R * R - (R - d) * (R - d)).sqrt();
    assert!(b.holds(), "{b}");
    assert!(
        (b.middle_mm() - mid).abs() < 2.0 * c,
        "{b}: middle, want {mid}"
    );
    assert!((b.neck_mm - neck).abs() < 3.0 * c, "{b}: neck, want {neck}");
    assert!(
        b.length_mm > extent(rho + 2.0 * c) - c && b.length_mm < extent(rho) + c,
        "{b}: extent, want {} to {}",
        extent(rho + 2.0 * c),
        extent(rho)
    );
    assert!(
        (b.top_min - top).abs() < 1e-3 && (b.top_max - top).abs() < 1e-3,
        "{b}"
    );
}

#[test]
fn a_part_with_two_tabs_is_held_by_exactly_them() {
    let v = verdict(&profile(&two_tabs(), &[]));
    assert_eq!(v.hold(), Hold::Held { bridges: 2 }, "{v}");
    assert_eq!(v.bridges.len(), 2, "{v}");
    assert!((v.perimeter_mm - 140.0).abs() < 1e-9);
    // Bottom: 20 mm along the outline; top: 40 + 30 + 20.
    assert_bridge(&v, &v.bridges[0], 20.0, 4.0, TAB_TOP);
    assert_bridge(&v, &v.bridges[1], 90.0, 4.0, TAB_TOP);
    assert!(
        v.bridges[0].centroid.distance(Point::new(20.0, -R)) < 0.1,
        "{v}"
    );
    assert!(
        v.bridges[1].centroid.distance(Point::new(20.0, 30.0 + R)) < 0.1,
        "{v}"
    );
    // Each tab is the 10 × 6 mm rectangle of the lift less the two half discs the tool
    // leaves at its ends, within the band (6 mm less the rims).
    let (inner, outer) = v.band_mm;
    let full = 10.0 * (outer - inner);
    let discs = std::f64::consts::PI * R * R;
    for b in &v.bridges {
        let area = b.area_mm2;
        assert!(
            area < full - 0.9 * discs && area > full - discs - 0.5,
            "{b}: area {area}"
        );
    }
}

#[test]
fn a_tab_cut_off_leaves_the_other() {
    let mut tp = profile(&two_tabs(), &[]);
    // Afterwards, through the bottom tab at full depth.
    tp.push(Move::rapid(Point3::new(10.0, -R, 5.0)));
    tp.push(Move::rapid(Point3::new(10.0, -R, 1.0)));
    tp.push(Move::line(Point3::new(10.0, -R, BOTTOM), 5.0));
    tp.push(Move::line(Point3::new(30.0, -R, BOTTOM), 5.0));
    tp.push(Move::rapid(Point3::new(30.0, -R, 5.0)));
    let v = verdict(&tp);
    assert_eq!(v.hold(), Hold::Held { bridges: 1 }, "{v}");
    assert_eq!(v.bridges.len(), 1, "{v}");
    assert_bridge(&v, &v.bridges[0], 90.0, 4.0, TAB_TOP);
}

#[test]
fn a_stretch_left_uncut_is_a_bridge_no_tab_asked_for() {
    // On the last level the program skips 10 mm of path up the left side (y from 10 to 20
    // on the path running down from y = 30: 10 to 20 mm along that side), leaving 4 mm at
    // the part, topped by the level before.
    let skipped = [Lift {
        side: 3,
        from: 10.0,
        to: 20.0,
        z: 1.0,
    }];
    let v = verdict(&profile(&two_tabs(), &skipped));
    assert_eq!(v.hold(), Hold::Held { bridges: 3 }, "{v}");
    assert_eq!(v.bridges.len(), 3, "{v}");
    assert_bridge(&v, &v.bridges[0], 20.0, 4.0, TAB_TOP);
    assert_bridge(&v, &v.bridges[1], 90.0, 4.0, TAB_TOP);
    assert_bridge(&v, &v.bridges[2], 125.0, 4.0, LEVELS[2]);
}

#[test]
fn without_tabs_the_part_falls_free() {
    let v = verdict(&profile(&[], &[]));
    assert_eq!(v.hold(), Hold::Free, "{v}");
    assert!(v.bridges.is_empty(), "{v}");
    assert_eq!(v.hold().to_string(), "falls free");
    // Not cut through: a floor 0.5 mm below the bottom finds nothing, one above it finds
    // the whole slot standing.
    let mut f = field();
    f.cut(&profile(&[], &[]));
    let high = held_by(&f, &part(), BOTTOM - 0.5, R, &BridgeOptions::default()).expect("a verdict");
    assert_eq!(high.hold(), Hold::Held { bridges: 1 }, "{high}");
    assert!((high.bridges[0].length_mm - 140.0).abs() < 1.0, "{high}");
}

/// A 20 × 20 mm window cut inside with a 6 mm tool whose path turns sharp corners 3 mm in:
/// the slug is held by the one tab; the four corners the tool cannot reach stay on the
/// frame and hold nothing.
#[test]
fn a_window_slug_is_held_by_its_tab_and_the_corners_stay_on_the_frame() {
    let pts = [(10.0, 5.0), (30.0, 5.0), (30.0, 25.0), (10.0, 25.0)];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    let window = Outline::from_points(&pts, "test window").expect("a square");
    let tool = Tool::flat(2.0 * R).expect("a tool");
    let mut tp = Toolpath::new(tool, Point3::new(20.0, 8.0, 5.0));
    tp.push(Move::rapid(Point3::new(20.0, 8.0, 1.0)));
    for &z in &LEVELS {
        // From the middle of the bottom side, round the 14 × 14 square of centres; on the
        // levels below the tab top, lift over 4 + 2r mm of the right side.
        tp.push(Move::line(Point3::new(20.0, 8.0, z), 5.0));
        tp.push(Move::line(Point3::new(27.0, 8.0, z), 10.0));
        if z < TAB_TOP {
            tp.push(Move::line(Point3::new(27.0, 10.0, z), 10.0));
            tp.push(Move::line(Point3::new(27.0, 10.0, TAB_TOP), 10.0));
            tp.push(Move::line(Point3::new(27.0, 20.0, TAB_TOP), 10.0));
            tp.push(Move::line(Point3::new(27.0, 20.0, z), 10.0));
        }
        for (x, y) in [(27.0, 22.0), (13.0, 22.0), (13.0, 8.0), (20.0, 8.0)] {
            tp.push(Move::line(Point3::new(x, y, z), 10.0));
        }
    }
    tp.push(Move::rapid(Point3::new(20.0, 8.0, 5.0)));
    let mut f = field();
    f.cut(&tp);
    let opts = BridgeOptions::default().with_side(CutSide::Inside);
    let v = held_by(&f, &window, BOTTOM, R, &opts).expect("a verdict");
    assert_eq!(v.hold(), Hold::Held { bridges: 1 }, "{v}");
    let holding: Vec<_> = v.holding().collect();
    // The right side runs from 20 to 40 mm along the outline, from y = 5; the lift from
    // y = 10 to 20 leaves a tab centred at y = 15, 30 mm along the outline.
    assert_bridge(&v, holding[0], 30.0, 4.0, TAB_TOP);
    let corners: Vec<_> = v
        .bridges
        .iter()
        .filter(|b| b.touches == Touches::Stock)
        .collect();
    assert_eq!(corners.len(), 4, "{v}");
    assert_eq!(v.bridges.len(), 5, "{v}");
    // Without its tab (cut through afterwards) the slug falls free.
    let mut cut_off = tp.clone();
    cut_off.push(Move::rapid(Point3::new(27.0, 8.0, 5.0)));
    cut_off.push(Move::line(Point3::new(27.0, 8.0, BOTTOM), 5.0));
    cut_off.push(Move::line(Point3::new(27.0, 22.0, BOTTOM), 5.0));
    let mut f = field();
    f.cut(&cut_off);
    let v = held_by(&f, &window, BOTTOM, R, &opts).expect("a verdict");
    assert_eq!(v.hold(), Hold::Free, "{v}");
}

#[test]
fn a_tool_too_small_for_its_rims_or_an_outline_off_the_stock_is_refused() {
    let f = field();
    let e = held_by(&f, &part(), BOTTOM, 0.1, &BridgeOptions::default()).unwrap_err();
    assert!(e.to_string().contains("tool radius"), "{e}");
    let far: Vec<Point> = [(500.0, 500.0), (510.0, 500.0), (510.0, 510.0)]
        .iter()
        .map(|&(x, y)| Point::new(x, y))
        .collect();
    let far = Outline::from_points(&far, "far").expect("a triangle");
    let e = held_by(&f, &far, BOTTOM, R, &BridgeOptions::default()).unwrap_err();
    assert!(e.to_string().contains("outline"), "{e}");
}

/// Ramped tabs asked for more densely than their ramps allow (24 on a 60 × 10 mm outline,
/// 5.8 mm apart, each lift 2 mm and its ramps 2 mm either side): the strategy keeps only
/// tabs whose lifts and ramps stay apart, so that the tool reaches the floor between any
/// two, and the stock cut by its program holds the part by exactly one bridge per tab
/// (before, it kept all 24, whose ramps met 0.04 mm above the floor: two tabs, one bridge).
#[test]
fn crowded_ramped_tabs_stand_apart_as_one_bridge_each() {
    use millpath::strategy::profile::{
        self, ProfileOptions, ProfileSide, ProfileTarget, TabCount, TabOptions, TabShape,
    };
    let pts = [(0.0, 0.0), (60.0, 0.0), (60.0, 10.0), (0.0, 10.0)];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    let outline = Outline::from_points(&pts, "strip").expect("a strip");
    let (bottom, height, r) = (-3.0, 1.0, 0.5);
    let tool = Tool::flat(2.0 * r).expect("a tool");
    let opts = ProfileOptions::default()
        .with_depth(3.0)
        .with_step_down(1.5)
        .with_lead_radius(1.0)
        .with_tabs(
            TabOptions::default()
                .with_count(TabCount::Count(24))
                .with_width(1.0)
                .with_height(height)
                .with_shape(TabShape::Ramped),
        );
    let target = ProfileTarget {
        outline: outline.clone(),
        side: ProfileSide::Outside,
    };
    let res = profile::generate(&[target], &tool, &opts).expect("a profile");
    let n = res.tabs.len();
    assert!((2..24).contains(&n), "{n} tabs");
    let block = Aabb {
        min: Point::new(-6.0, -6.0),
        max: Point::new(66.0, 16.0),
    };
    let fopts = FieldOptions::default().with_tool_diameter(2.0 * r);
    let mut f = HeightField::new(block, bottom, 0.0, &fopts).expect("a block");
    f.cut(&res.toolpath);
    let v = held_by(&f, &outline, bottom, r, &BridgeOptions::default()).expect("a verdict");
    assert_eq!(v.hold(), Hold::Held { bridges: n }, "{v}");
    let p = v.perimeter_mm;
    for t in &res.tabs {
        let on = v
            .holding()
            .filter(|b| (t.s - b.start_mm).rem_euclid(p) <= b.length_mm)
            .count();
        assert_eq!(on, 1, "tab at {:.3} mm: {v}", t.s);
        assert!(
            v.holding().all(|b| b.top_max <= bottom + height + 1e-3),
            "{v}"
        );
    }
}
