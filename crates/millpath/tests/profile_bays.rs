//! A part with a bay behind a mouth narrower than the tool: a 40 × 40 mm square whose middle
//! is a 16 × 16 mm bay, open to the outside by a slit 1 mm wide, cut out of a 6 mm plate by a
//! 3 mm end mill. The tool cannot pass the slit, so the outside offset splits into the loop
//! around the part and a loop inside the bay. The profile must cut both (the bay is outside
//! the drawn part, and the tool fits in it), place no tab in the bay (its material is cut off
//! from the stock by the slot across the mouth: a tab there holds nothing), and the stock
//! simulation (`stock::held_by`, which shares nothing with the planner) must find the part
//! held by exactly its tabs. Cut by the square's loop alone, the bay's material holds nothing
//! either: the verifier must not count it as stock.

use millpath::geom::{Aabb, Outline, Point, Point3};
use millpath::stock::{BridgeOptions, FieldOptions, HeightField, Hold, Touches, held_by};
use millpath::strategy::profile::{
    self, ProfileOptions, ProfileSide, ProfileTarget, TabCount, TabOptions,
};
use millpath::toolpath::{Move, Tool, Toolpath};

const THICKNESS: f64 = 6.0;
const D: f64 = 3.0;

/// The part: the square less the bay (12..28 on both axes) and the slit (x 19.5..20.5,
/// from the bay's bottom down to y = 0), clockwise or not as `reversed` asks, from any vertex.
fn part(reversed: bool, start: usize) -> Outline {
    let mut pts = vec![
        (0.0, 0.0),
        (19.5, 0.0),
        (19.5, 12.0),
        (12.0, 12.0),
        (12.0, 28.0),
        (28.0, 28.0),
        (28.0, 12.0),
        (20.5, 12.0),
        (20.5, 0.0),
        (40.0, 0.0),
        (40.0, 40.0),
        (0.0, 40.0),
    ];
    if reversed {
        pts.reverse();
    }
    let n = pts.len();
    pts.rotate_left(start % n);
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    Outline::from_points(&pts, "test part with a bay").expect("a simple outline")
}

fn options(tabs: TabCount) -> ProfileOptions {
    ProfileOptions::default()
        .with_top_z(0.0)
        .with_depth(THICKNESS + 0.5)
        .with_stock_thickness(Some(THICKNESS))
        .with_step_down(3.0)
        .with_lead_radius(2.0)
        .with_tabs(
            TabOptions::default()
                .with_count(tabs)
                .with_width(4.0)
                .with_height(2.0),
        )
}

fn block() -> HeightField {
    let b = Aabb {
        min: Point::new(-12.0, -12.0),
        max: Point::new(52.0, 52.0),
    };
    HeightField::new(
        b,
        -THICKNESS,
        0.0,
        &FieldOptions::default().with_tool_diameter(D),
    )
    .expect("a block")
}

fn in_bay(p: Point) -> bool {
    let bay = (12.0..=28.0).contains(&p.x) && (12.0..=28.0).contains(&p.y);
    let slit = (19.5..=20.5).contains(&p.x) && (0.0..=12.0).contains(&p.y);
    bay || slit
}

#[test]
fn a_bay_behind_a_narrow_mouth_is_cut_and_holds_no_tab() {
    let tool = Tool::flat(D).expect("a tool");
    for (reversed, start) in [(false, 0), (true, 0), (false, 5), (true, 9)] {
        let o = part(reversed, start);
        let targets = [ProfileTarget {
            outline: o.clone(),
            side: ProfileSide::Outside,
        }];
        let res =
            profile::generate(&targets, &tool, &options(TabCount::Count(4))).expect("a profile");
        let at: Vec<Point> = res.tabs.iter().map(|t| t.at).collect();
        assert_eq!(at.len(), 4, "{reversed} {start}: {:?}", res.notes);
        assert!(at.iter().all(|&p| !in_bay(p)), "a tab in the bay: {at:?}");
        let counted = profile::tab_counts(&targets, &tool, &options(TabCount::Count(4)));
        assert_eq!(counted, vec![(4, 4)]);
        let mut field = block();
        let cut = field.cut(&res.toolpath);
        assert!(cut.rapids_through_material.is_empty(), "{cut}");
        // The ring the bay's loop sweeps, 0.2 to 2.8 mm from the bay's walls, is cut to the
        // floor along each wall (up to the tool's radius from the corners it cannot reach).
        for k in 0..=40 {
            let t = 1.5 + 13.0 * f64::from(k) / 40.0;
            for off in [0.2, 1.5, 2.8] {
                for p in [
                    Point::new(12.0 + t, 28.0 - off),
                    Point::new(12.0 + off, 12.0 + t),
                    Point::new(28.0 - off, 12.0 + t),
                ] {
                    let h = field.height_at(p).expect("on the block");
                    assert!(
                        h <= -THICKNESS + 1e-6,
                        "material at {p:?} in the bay: z {h}"
                    );
                }
            }
        }
        let v =
            held_by(&field, &o, -THICKNESS, 0.5 * D, &BridgeOptions::default()).expect("a verdict");
        assert_eq!(
            v.hold(),
            Hold::Held { bridges: 4 },
            "{reversed} {start}: {v}"
        );
    }
}

/// The tool's centre round the square 1.5 mm out, through the plate, from (x0, −1.5) round
/// to (x1, −1.5): a gap from x1 to x0 leaves the material under it.
fn square_slot(x0: f64, x1: f64) -> Toolpath {
    let tool = Tool::flat(D).expect("a tool");
    let z = -THICKNESS - 0.5;
    let mut tp = Toolpath::new(tool, Point3::new(x0, -1.5, 5.0));
    tp.push(Move::line(Point3::new(x0, -1.5, z), 300.0));
    for (x, y) in [
        (41.5, -1.5),
        (41.5, 41.5),
        (-1.5, 41.5),
        (-1.5, -1.5),
        (x1, -1.5),
    ] {
        tp.push(Move::line(Point3::new(x, y, z), 1000.0));
    }
    tp.push(Move::rapid(Point3::new(x1, -1.5, 5.0)));
    tp
}

#[test]
fn a_bay_left_standing_holds_nothing() {
    // The slot around the square alone: the bay and the slit keep their material, joined to
    // the part and to nothing else.
    let mut field = block();
    field.cut(&square_slot(20.0, 20.0));
    assert!(
        field
            .height_at(Point::new(20.0, 20.0))
            .expect("on the block")
            > -1e-6
    );
    let v = held_by(
        &field,
        &part(false, 0),
        -THICKNESS,
        0.5 * D,
        &BridgeOptions::default(),
    )
    .expect("a verdict");
    assert_eq!(v.hold(), Hold::Free, "{v}");
    assert!(
        v.bridges
            .iter()
            .any(|b| in_bay(b.centroid) && b.touches == Touches::Piece && b.area_mm2 > 50.0),
        "{v}"
    );
    // The same, with the slot left uncut in front of the mouth: a strip 1 mm wide joins the
    // slit's material to the plate, and holds the part.
    let mut joined = block();
    joined.cut(&square_slot(22.0, 18.0));
    let v = held_by(
        &joined,
        &part(false, 0),
        -THICKNESS,
        0.5 * D,
        &BridgeOptions::default(),
    )
    .expect("a verdict");
    assert_eq!(v.hold(), Hold::Held { bridges: 1 }, "{v}");
}
