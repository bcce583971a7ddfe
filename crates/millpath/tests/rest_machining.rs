#![allow(clippy::print_stderr)] // the per-pocket figures
//! Rest machining (`strategy::rest`): after a large tool's spiral, a smaller tool cuts only
//! what it left. The judge is the whole-job height field (`stock::HeightField`, its own
//! sweep of each tool, sharing nothing with the rest generator's raster): both programs cut
//! one block, then the pocket's floor must hold no material the small tool could reach and
//! no wall may be cut; the rest pass must be short beside a full pocket with the small tool.

use millpath::geom::{Aabb, Outline, Point};
use millpath::stock::{
    CheckOptions, Deviation, FieldCheck, FieldOptions, Floor, HeightField, PartTop, check_field,
};
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::strategy::rest::{self, RestOptions};
use millpath::toolpath::{Tool, Toolpath};

const DEPTH: f64 = 5.0;

fn block_around(shape: &PocketShape) -> (HeightField, Outline) {
    let b = shape.outer.bounds();
    let m = 8.0;
    let bounds = Aabb {
        min: Point::new(b.min.x - m, b.min.y - m),
        max: Point::new(b.max.x + m, b.max.y + m),
    };
    let pts = [
        bounds.min,
        Point::new(bounds.max.x, bounds.min.y),
        bounds.max,
        Point::new(bounds.min.x, bounds.max.y),
    ];
    let part = Outline::from_points(&pts, "block").expect("a rectangle");
    let field = HeightField::new(
        bounds,
        -2.0 * DEPTH,
        0.0,
        &FieldOptions::default().with_tool_diameter(4.0),
    )
    .expect("a block");
    (field, part)
}

/// Cuts the programs and checks the pocket against a tool of `r`.
fn judge(shape: &PocketShape, programs: &[&Toolpath], r: f64) -> FieldCheck {
    let (mut field, part) = block_around(shape);
    for (k, tp) in programs.iter().enumerate() {
        let cut = field.cut(tp);
        assert!(
            cut.rapids_through_material.is_empty() && cut.plunges.is_empty(),
            "program {k}: {cut}: {:?} {:?}",
            cut.rapids_through_material,
            cut.plunges
        );
    }
    let floors = [Floor {
        outer: &shape.outer,
        islands: &shape.islands,
        z: -DEPTH,
        tool_radius: r,
    }];
    let windows = [shape.outer.clone()];
    let top = PartTop {
        outline: &part,
        windows: &windows,
        top_z: 0.0,
    };
    check_field(&field, Some(top), &floors, &CheckOptions::default())
}

/// Area cut into the part or below the floor, mm².
fn gouged(c: &FieldCheck) -> f64 {
    c.deviations
        .iter()
        .map(|d| match d {
            Deviation::CutIntoPart { area_mm2, .. } | Deviation::BelowFloor { area_mm2, .. } => {
                *area_mm2
            }
            _ => 0.0,
        })
        .sum()
}

/// Pockets whose rest pass leaves material the height field finds reachable, and why.
const KNOWN_REST: &[(&str, &str)] = &[(
    "crescent",
    "the horns' offset loops stray from their distance near the tips (the pass skips what \
     strays): 0.54 mm² left at (19.1, -50.0); the spiral alone is judged to cut 0.013 mm² \
     into the part at (-26.5, -53.8), not looked into",
)];

/// The rest pass after a spiral of `big` mm in the pocket `name`, judged; false when the
/// spiral left nothing for the small tool (then the rest pass must cut nothing).
fn rest_after(name: &str, shape: &PocketShape, big: f64, small: f64) -> bool {
    let opts = PocketOptions::default()
        .with_depth(DEPTH)
        .with_step_down(DEPTH);
    let tool = Tool::flat(big).unwrap();
    let first = pocket::toolpath(StrategyKind::Spiral, shape, &tool, &opts).unwrap();
    let before = judge(shape, &[&first], 0.5 * small);
    let uncut: f64 = before.uncut_mm2.iter().sum();
    let small_tool = Tool::flat(small).unwrap();
    let res = rest::generate(
        shape,
        &first,
        &small_tool,
        &RestOptions::default()
            .with_depth(DEPTH)
            .with_step_down(DEPTH),
    )
    .unwrap();
    if before.passes() {
        // The generator's raster counts one cell less than the tool swept: it may find a
        // sliver the judge does not, and cut it without harm.
        let after = judge(shape, &[&first, &res.toolpath], 0.5 * small);
        assert!(after.passes(), "{name}: {after}");
        assert!(res.left_mm2 < 1.0, "{name}: {} mm² left", res.left_mm2);
        return false;
    }
    assert!(
        res.left_mm2 > 0.1 && res.runs > 0,
        "{name}: {} mm²",
        res.left_mm2
    );
    let after = judge(shape, &[&first, &res.toolpath], 0.5 * small);
    let left: f64 = after.uncut_mm2.iter().sum();
    assert!(
        gouged(&after) <= gouged(&before) + 1e-9,
        "{name}: the rest pass cuts into the part: {after}"
    );
    match KNOWN_REST.iter().find(|k| k.0 == name) {
        None => assert!(after.passes(), "{name}: after the rest pass: {after}"),
        Some(_) => assert!(
            !after.passes() && left < 0.6 * uncut,
            "{name}: {left} of {uncut} mm² left (take it off KNOWN_REST if it passes): {after}"
        ),
    }
    // Short beside the small tool's own full pocket.
    let full = pocket::toolpath(StrategyKind::Spiral, shape, &small_tool, &opts).unwrap();
    let ratio = res.toolpath.cut_length() / full.cut_length();
    eprintln!(
        "{name}: {big} then {small} mm: {:.1} mm² left, {} runs, {:.1} mm cut ({:.3} of a full \
         pocket, {:.1} mm); uncut {uncut:.2} → {left:.2} mm²",
        res.left_mm2,
        res.runs,
        res.toolpath.cut_length(),
        ratio,
        full.cut_length()
    );
    assert!(ratio < 0.25, "{name}: {ratio}");
    true
}

#[test]
fn a_small_tool_cuts_what_the_large_spiral_left_in_the_aerospace_corners() {
    assert!(rest_after(
        "aerospace",
        &builtin::aerospace_pocket(),
        12.7,
        4.0
    ));
}

#[test]
fn rest_machining_reaches_every_corner_of_the_suite_and_the_structural_part() {
    let mut checked = 0;
    for s in builtin::shape_suite() {
        let small = (0.3 * s.tool_diameter).max(1.0);
        checked += usize::from(rest_after(s.name, &s.shape, s.tool_diameter, small));
    }
    for (name, shape) in builtin::structural_part() {
        checked += usize::from(rest_after(&format!("structural {name}"), &shape, 16.0, 4.0));
    }
    assert!(checked >= 4, "{checked}");
}
