//! Tabs on parts cut out beside each other: three 60 mm long strips 10 mm apart (the middle
//! one 4 mm wide), cut out of a 6 mm plate by a 3 mm end mill. Every point of the middle
//! strip lies within 13 mm of another strip, but 10 mm leave solid material between the
//! slots (each 3 mm wide, plus the frame a tab joins), so each strip must get the two tabs
//! asked for; the stock simulation (`stock::held_by`, which shares nothing with the
//! placement) must find each held by exactly two bridges, with the program's rapids clear of
//! material.

use millpath::geom::{Aabb, Outline, Point};
use millpath::stock::{BridgeOptions, FieldOptions, HeightField, Hold, held_by};
use millpath::strategy::profile::{
    self, ProfileOptions, ProfileSide, ProfileTarget, TabCount, TabOptions,
};
use millpath::toolpath::Tool;

const THICKNESS: f64 = 6.0;

fn strip(y0: f64, y1: f64) -> Outline {
    let pts = [(0.0, y0), (60.0, y0), (60.0, y1), (0.0, y1)];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    Outline::from_points(&pts, "test strip").expect("a rectangle")
}

#[test]
fn strips_beside_each_other_each_get_their_tabs_and_are_held_by_them() {
    let strips = [strip(14.0, 24.0), strip(0.0, 4.0), strip(-20.0, -10.0)];
    let targets: Vec<ProfileTarget> = strips
        .iter()
        .map(|o| ProfileTarget {
            outline: o.clone(),
            side: ProfileSide::Outside,
        })
        .collect();
    let tool = Tool::flat(3.0).expect("a tool");
    let opts = ProfileOptions::default()
        .with_top_z(0.0)
        .with_depth(THICKNESS + 0.5)
        .with_stock_thickness(Some(THICKNESS))
        .with_step_down(3.0)
        .with_lead_radius(2.0)
        .with_tabs(
            TabOptions::default()
                .with_count(TabCount::Count(2))
                .with_width(3.0)
                .with_height(2.0),
        );
    let res = profile::generate(&targets, &tool, &opts).expect("a profile");
    for ti in 0..3 {
        let n = res.tabs.iter().filter(|t| t.target == ti).count();
        assert_eq!(n, 2, "strip {ti}: {:?}", res.notes);
    }
    let block = Aabb {
        min: Point::new(-12.0, -32.0),
        max: Point::new(72.0, 36.0),
    };
    let mut field = HeightField::new(
        block,
        -THICKNESS,
        0.0,
        &FieldOptions::default().with_tool_diameter(3.0),
    )
    .expect("a block");
    let cut = field.cut(&res.toolpath);
    assert!(cut.rapids_through_material.is_empty(), "{cut}");
    for (ti, o) in strips.iter().enumerate() {
        let v = held_by(&field, o, -THICKNESS, 1.5, &BridgeOptions::default()).expect("a verdict");
        assert_eq!(v.hold(), Hold::Held { bridges: 2 }, "strip {ti}: {v}");
    }
}
