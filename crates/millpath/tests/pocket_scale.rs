//! Scale invariance: the same pocket, tool and options drawn 0.01× to 1000× as large give
//! the same path scaled (cut length within 1 % of the scale times the original's), and the
//! stock simulation verifies every one of them (no gouge, no uncut material beyond its
//! tolerance). A tolerance written as an absolute length where it should be relative to the
//! tool or the pocket shows up here: as a path that changes shape with the scale, or as a
//! refusal.
//!
//! What does not scale, on purpose: the chordal and arc-fitting tolerances (µm, for the
//! machine, not the part), the verifier's uncut-area tolerance (mm²) and the simulation's
//! raster cell (the cell is scaled with the part below, within the raster's cell budget).

use millpath::Error;
use millpath::geom::{Outline, Point, Vec2};
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, Entry, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::toolpath::Tool;

/// All three strategies.
const ALL: [StrategyKind; 3] = [
    StrategyKind::Offset,
    StrategyKind::Zigzag,
    StrategyKind::Spiral,
];

/// An L-shaped pocket (no symmetry), 50 × 40 at scale 1, with a round island; every length
/// times `k`.
fn l_pocket(k: f64) -> (Outline, Outline) {
    let p = |x: f64, y: f64| Point::new(k * x, k * y);
    let ell = builtin::rounded_polygon(
        &[
            p(0.0, 0.0),
            p(50.0, 0.0),
            p(50.0, 18.0),
            p(20.0, 18.0),
            p(20.0, 40.0),
            p(0.0, 40.0),
        ],
        4.0 * k,
        "L",
    )
    .unwrap();
    let c = p(10.0, 10.0);
    let r = 3.0 * k;
    let island = Outline::new(
        &[(c + Vec2::new(r, 0.0), 1.0), (c + Vec2::new(-r, 0.0), 1.0)],
        "island",
    )
    .unwrap();
    (ell, island)
}

/// The options of scale 1 (a 6 mm tool, 40 % stepover, one 2 mm level, a finishing pass),
/// every length times `k`.
fn options(k: f64) -> PocketOptions {
    PocketOptions::default()
        .with_depth(2.0 * k)
        .with_step_down(2.0 * k)
        .with_safe_height(1.0 * k)
        .with_clearance_height(5.0 * k)
        .with_entry(Entry::Helix {
            radius: 2.5 * k,
            ramp_angle: 3f64.to_radians(),
        })
        .with_min_radius(1.0 * k)
        .with_finish(true)
}

/// The simulation at scale `k`: a 0.15 mm cell at scale 1, scaled, never finer than 0.05 mm.
fn sim(k: f64) -> SimOptions {
    SimOptions::default()
        .with_cell((0.15 * k).max(0.05))
        .with_step((0.3 * k).max(0.1))
        .with_window(0.5 * k)
}

/// Cut length of `kind` at scale `k`, after the verifier's verdict is checked.
fn verified_length(kind: StrategyKind, k: f64) -> f64 {
    let (o, isl) = l_pocket(k);
    let shape = PocketShape::new(o, vec![isl], "scaled").unwrap();
    let tool = Tool::flat(6.0 * k).unwrap();
    match pocket::generate(kind, &shape, &tool, &options(k), &sim(k)) {
        Ok(r) => {
            let p = r.verification.problems();
            assert!(p.is_empty(), "{kind:?} at scale {k}: {p:?}");
            r.toolpath.cut_length()
        }
        Err(Error::Input(e)) => panic!("{kind:?} at scale {k} refused: {e}"),
        Err(e) => panic!("{kind:?} at scale {k}: internal error {e}"),
    }
}

#[test]
fn pockets_scale_with_the_part_and_the_tool() {
    for kind in ALL {
        let l1 = verified_length(kind, 1.0);
        for k in [0.01, 0.1, 10.0, 100.0, 1000.0] {
            let l = verified_length(kind, k);
            let ratio = l / (k * l1);
            assert!(
                (ratio - 1.0).abs() <= 0.01,
                "{kind:?} at scale {k}: cut length {l:.4} mm, {ratio:.4} × the scaled {l1:.4} mm"
            );
        }
    }
}
