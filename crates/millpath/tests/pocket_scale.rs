//! Scale invariance: the same pocket, tool and options drawn 0.01× to 1000× as large give
//! the same path scaled (cut length within 1 % of the scale times the original's), and the
//! stock simulation verifies every one of them (no gouge, no uncut material beyond its
//! tolerance). A tolerance written as an absolute length where it should be relative to the
//! tool or the pocket shows up here: as a path that changes shape with the scale, or as a
//! refusal.
//!
//! Same work at every scale (`the_same_work_at_every_scale`): from the reference tool
//! (12.7 mm, `toolpath::REFERENCE_DIAMETER`) up, every default resolution and tolerance of
//! pocketing and of its verification grows with the tool (`Tool::tolerance_scale`), so a
//! real drawing and the same ×10 and ×100, with the tool, depths and heights ×10 and ×100
//! and the simulation left at its defaults, give the same path scaled (Hausdorff distance of
//! the two paths, divided by the scale, within 0.01 mm, the gouge tolerance) from the same
//! work: the same raster (cells counted), the same tool positions swept, and the same moves
//! planned. Planning time follows those counts; the measured times are in BENCHMARKS.md.
//! (The feed profile's rate and shortest piece are the machine's, in millimetres at every
//! scale: the larger pocket's feed changes split its moves into more pieces; the count
//! compared is of the moves before that.)
//!
//! What does not scale, on purpose: the program's resolution (the writer's 3 decimals, the
//! gouge verdict's `GOUGE_RESOLUTION`, arcs flatter than `ARC_AS_LINE_SAGITTA` written as
//! lines), the offsets' numerical tolerances, the feed profile, and every default below the
//! reference tool
//! (in `pockets_scale_with_the_part_and_the_tool` the cell is given, scaled with the part,
//! within the raster's cell budget).

use millpath::Error;
use millpath::geom::{Outline, Point, Point3, Vec2};
use millpath::io::ImportSettings;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{
    self, Entry, PocketOptions, PocketResult, PocketShape, SpiralMorph, StrategyKind, builtin,
};
use millpath::toolpath::{MoveKind, Tool, Toolpath};
use std::collections::HashMap;

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

/// `ez_clockwise_arcs_hatch.dxf` (a hatch of clockwise arcs, 56 × 70 mm read as mm, two
/// outlines cut as their union) with every coordinate times `k`.
fn ez_pocket(k: f64) -> PocketShape {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/real-inputs/files/ez_clockwise_arcs_hatch.dxf");
    let import = ImportSettings {
        drawing_units: Some("mm".into()),
        ..ImportSettings::default()
    };
    let (loops, _) = millpath::job::load_outline(&path.display().to_string(), &import)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let scaled = |o: &Outline| {
        let v: Vec<(Point, f64)> = o
            .vertices()
            .map(|(p, b)| (Point::new(k * p.x, k * p.y), b))
            .collect();
        Outline::new(&v, "scaled").unwrap()
    };
    let islands = loops.islands.iter().map(scaled).collect();
    PocketShape::new(scaled(&loops.outer), islands, "ez_clockwise_arcs_hatch").unwrap()
}

/// Points along the moves of `tp`, at most `step` apart (arcs and helices followed), every
/// coordinate divided by `k`.
fn path_points(tp: &Toolpath, step: f64, k: f64) -> Vec<Point3> {
    let mut out = vec![tp.start];
    for (from, m) in tp.segments() {
        if matches!(m.kind, MoveKind::Dwell { .. }) {
            continue;
        }
        let len = m.length_from(from);
        let n = ((len / step).ceil() as usize).max(1);
        out.extend((1..=n).map(|j| m.point_at(from, len * j as f64 / n as f64)));
    }
    out.into_iter()
        .map(|p| Point3::new(p.x / k, p.y / k, p.z / k))
        .collect()
}

/// The largest distance from a point of `a` to the nearest point of `b` (a grid of cells of
/// side `cell` over `b`; exact for distances up to `cell`, which is all this is asked).
fn directed_hausdorff(a: &[Point3], b: &[Point3], cell: f64) -> f64 {
    let key = |p: &Point3| {
        (
            (p.x / cell).floor() as i64,
            (p.y / cell).floor() as i64,
            (p.z / cell).floor() as i64,
        )
    };
    let mut grid: HashMap<(i64, i64, i64), Vec<Point3>> = HashMap::new();
    for p in b {
        grid.entry(key(p)).or_default().push(*p);
    }
    let mut worst: f64 = 0.0;
    for p in a {
        let (i, j, l) = key(p);
        let mut near = f64::INFINITY;
        for di in -1..=1 {
            for dj in -1..=1 {
                for dl in -1..=1 {
                    for q in grid.get(&(i + di, j + dj, l + dl)).into_iter().flatten() {
                        near = near.min(p.distance(*q));
                    }
                }
            }
        }
        worst = worst.max(near.min(cell));
    }
    worst
}

/// The pocket of [`ez_pocket`] at scale `k` with `kind` (and `morph` for the spiral): a
/// 12.7 mm tool (the reference tool, from which every default scales) at 40 %, one level of
/// 5 mm, the heights, helix and smallest radius ×`k` too, the simulation at its defaults;
/// verified (no problem) or the test fails. With the number of moves planned (before the
/// feed profile splits them) longer than `k`·1e-9 mm: a move of a few ulps of the
/// coordinates (7e-12 mm where the zigzag's clean-up pass starts on the last row's end, on
/// the ×100 drawing 60 m from the origin) is their rounding, not a move.
fn plan_ez(kind: StrategyKind, morph: SpiralMorph, arcs: bool, k: f64) -> (PocketResult, usize) {
    let shape = ez_pocket(k);
    let tool = Tool::flat(12.7 * k).unwrap();
    let opts = PocketOptions::default()
        .with_depth(5.0 * k)
        .with_step_down(5.0 * k)
        .with_safe_height(1.0 * k)
        .with_clearance_height(5.0 * k)
        .with_entry(Entry::Helix {
            radius: 2.5 * k,
            ramp_angle: 3f64.to_radians(),
        })
        .with_min_radius(1.0 * k)
        .with_morph(morph)
        .with_arcs(arcs);
    let r = pocket::generate(kind, &shape, &tool, &opts, &SimOptions::default())
        .unwrap_or_else(|e| panic!("{kind:?} {morph:?} at scale {k}: {e}"));
    let p = r.verification.problems();
    assert!(p.is_empty(), "{kind:?} {morph:?} at scale {k}: {p:?}");
    let planned = pocket::toolpath(kind, &shape, &tool, &opts)
        .unwrap_or_else(|e| panic!("{kind:?} {morph:?} at scale {k}: {e}"))
        .segments()
        .filter(|(from, m)| m.length_from(*from) > k * 1e-9)
        .count();
    (r, planned)
}

#[test]
fn the_same_work_at_every_scale() {
    for (kind, morph, arcs) in [
        (StrategyKind::Offset, SpiralMorph::Offsets, false),
        (StrategyKind::Zigzag, SpiralMorph::Offsets, false),
        (StrategyKind::Spiral, SpiralMorph::Offsets, false),
        (StrategyKind::Spiral, SpiralMorph::Fronts, true),
    ] {
        let (base, n1) = plan_ez(kind, morph, arcs, 1.0);
        let (v1, tp1) = (&base.verification, &base.toolpath);
        let pts1 = path_points(tp1, 0.1, 1.0);
        for k in [10.0, 100.0] {
            let (r, n) = plan_ez(kind, morph, arcs, k);
            let (v, tp) = (&r.verification, &r.toolpath);
            let what = format!("{kind:?} ({morph:?}, arcs {arcs}) at scale {k}");
            // What the planning time follows: the raster, the positions swept, the moves.
            assert!(
                (v.cell_mm / (k * v1.cell_mm) - 1.0).abs() < 1e-9,
                "{what}: cell {} mm against {} mm at scale 1",
                v.cell_mm,
                v1.cell_mm
            );
            assert_eq!(v.raster_cells, v1.raster_cells, "{what}: raster cells");
            let positions = v.tool_positions as f64 / v1.tool_positions as f64;
            assert!(
                (positions - 1.0).abs() <= 0.002,
                "{what}: {} tool positions against {}",
                v.tool_positions,
                v1.tool_positions
            );
            assert_eq!(n, n1, "{what}: moves planned");
            // The same path, scaled.
            let ratio = tp.cut_length() / (k * tp1.cut_length());
            assert!(
                (ratio - 1.0).abs() <= 1e-4,
                "{what}: cut length {ratio} × the scaled one"
            );
            let pts = path_points(tp, 0.1 * k, k);
            let h = directed_hausdorff(&pts, &pts1, 1.0).max(directed_hausdorff(&pts1, &pts, 1.0));
            // The samples are 0.1 mm apart (at scale 1): a point lies within 0.05 mm of a
            // sample of the same path; the paths themselves within the gouge tolerance.
            assert!(
                h <= 0.05 + pocket::GOUGE_TOLERANCE,
                "{what}: the paths (divided by the scale) are {h:.4} mm apart"
            );
        }
    }
}
