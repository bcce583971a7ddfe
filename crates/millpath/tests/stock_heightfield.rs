//! The height-field stock (`stock::HeightField`) against a dense sampling of the same moves
//! computed here (tool positions every 0.01 mm, arcs from their own centre and angles), the
//! removal figures against closed-form areas, and the per-operation findings (rapids through
//! material, plunges) on hand-made programs.

use millpath::geom::{Aabb, Point, Point3};
use millpath::stock::{CutOptions, Cutter, FieldOptions, HeightField};
use millpath::toolpath::{Move, MoveKind, Tool, Toolpath};
use std::f64::consts::{PI, TAU};

fn block(x0: f64, y0: f64, x1: f64, y1: f64) -> Aabb {
    Aabb {
        min: Point::new(x0, y0),
        max: Point::new(x1, y1),
    }
}

fn tool(d: f64) -> Tool {
    Tool::flat(d).expect("a positive diameter")
}

/// Positions along one move from `from`, at most `step` apart in 3-D, both ends included,
/// computed without the engine's move geometry: a line by interpolation, an XY arc from its
/// centre, its start and end angles and its direction (a full turn when they meet).
fn dense(from: Point3, m: &Move, step: f64) -> Vec<Point3> {
    match m.kind {
        MoveKind::Arc { center, ccw, .. } => {
            let r = (from.x - center.x).hypot(from.y - center.y);
            let a0 = (from.y - center.y).atan2(from.x - center.x);
            let a1 = (m.to.y - center.y).atan2(m.to.x - center.x);
            let mut sweep = if ccw { a1 - a0 } else { a0 - a1 }.rem_euclid(TAU);
            if sweep < 1e-9 {
                sweep = TAU;
            }
            let sweep = if ccw { sweep } else { -sweep };
            let len = (r * sweep).hypot(m.to.z - from.z);
            let n = ((len / step).ceil() as usize).max(1);
            (0..=n)
                .map(|k| {
                    let f = k as f64 / n as f64;
                    let a = a0 + sweep * f;
                    Point3::new(
                        center.x + r * a.cos(),
                        center.y + r * a.sin(),
                        from.z + (m.to.z - from.z) * f,
                    )
                })
                .collect()
        }
        _ => {
            let n = ((from.distance(m.to) / step).ceil() as usize).max(1);
            (0..=n)
                .map(|k| from.lerp(m.to, k as f64 / n as f64))
                .collect()
        }
    }
}

/// A small deterministic generator (the tests must not depend on a crate's stream).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// A random program of lines, ramps, plunges, arcs and helices inside a 30 × 30 mm square.
fn random_program(rng: &mut Lcg, d: f64) -> Toolpath {
    let mut tp = Toolpath::new(tool(d), Point3::new(15.0, 15.0, 2.0));
    let mut at = tp.start;
    for _ in 0..6 {
        let kind = (rng.next() * 5.0) as usize;
        let z = if rng.next() < 0.3 {
            at.z
        } else {
            rng.range(-6.0, 1.0)
        };
        let m = match kind {
            0 => Move::line(Point3::new(at.x, at.y, z), 1.0),
            1 | 2 => Move::line(
                Point3::new(rng.range(6.0, 24.0), rng.range(6.0, 24.0), z),
                1.0,
            ),
            _ => {
                // An arc or helix about a centre within 6 mm of the tool, the end on its
                // circle.
                let c = Point3::new(
                    at.x + rng.range(-6.0, 6.0),
                    at.y + rng.range(-6.0, 6.0),
                    0.0,
                );
                let r = (at.x - c.x).hypot(at.y - c.y);
                if r < 0.2 {
                    continue;
                }
                let a = rng.range(0.0, TAU);
                let to = Point3::new(c.x + r * a.cos(), c.y + r * a.sin(), z);
                Move::arc_xy(to, c, rng.next() < 0.5, 1.0)
            }
        };
        at = m.to;
        tp.push(m);
    }
    tp
}

/// Every cell of the field lies between the two dense bounds: no lower than the lowest
/// sample within `r + ε` of its centre (ε: half the sample spacing and the arc chords'
/// widening), no higher than the lowest sample within `r` (each sample is a position the
/// tool passed, so every cell within `r` of it is cut at least to its z).
#[test]
fn the_field_lies_between_dense_samplings_of_the_same_moves() {
    let mut rng = Lcg(7);
    let step = 0.01;
    let cases = 24;
    let mut checked_cells = 0usize;
    for case in 0..cases {
        let d = rng.range(1.0, 6.0);
        let tp = random_program(&mut rng, d);
        let (top, bottom) = (0.0, -8.0);
        let opts = FieldOptions::default().with_cell(0.1);
        let mut field =
            HeightField::new(block(0.0, 0.0, 30.0, 30.0), bottom, top, &opts).expect("a block");
        field.cut(&tp);
        let (nx, ny) = field.dims();
        let c = field.cell();
        let r = 0.5 * d;
        let eps = 0.5 * step + 2.0 * millpath::stock::ARC_SAGITTA + 1e-9;
        let mut lo = vec![top; nx * ny];
        let mut hi = vec![top; nx * ny];
        let mut from = tp.start;
        for m in std::iter::once(Move::line(tp.start, 1.0)).chain(tp.moves.iter().copied()) {
            for q in dense(from, &m, step) {
                let reach = r + eps;
                let i0 = (((q.x - reach) / c).floor().max(0.0)) as usize;
                let j0 = (((q.y - reach) / c).floor().max(0.0)) as usize;
                let i1 = (((q.x + reach) / c).ceil().max(0.0) as usize).min(nx - 1);
                let j1 = (((q.y + reach) / c).ceil().max(0.0) as usize).min(ny - 1);
                for j in j0..=j1 {
                    for i in i0..=i1 {
                        let p = Point::new((i as f64 + 0.5) * c, (j as f64 + 0.5) * c);
                        let dist = p.distance(q.xy());
                        let k = j * nx + i;
                        if dist <= reach {
                            lo[k] = lo[k].min(q.z);
                        }
                        if dist <= r - 1e-9 {
                            hi[k] = hi[k].min(q.z);
                        }
                    }
                }
            }
            from = m.to;
        }
        let tol = step + 2e-4;
        let mut cut = 0;
        for j in 0..ny {
            for i in 0..nx {
                let h = field.height(i, j).expect("on the field");
                let k = j * nx + i;
                assert!(
                    h >= lo[k] - tol && h <= hi[k] + tol,
                    "case {case}, cell ({i}, {j}): field {h}, dense bounds {} .. {}",
                    lo[k],
                    hi[k]
                );
                if h < top - 1e-3 {
                    cut += 1;
                }
            }
        }
        checked_cells += cut;
    }
    // The programs cut: the comparison is not between two untouched blocks.
    assert!(checked_cells > 10_000, "{checked_cells}");
}

/// Operations one after another: a 10 mm slot, the same slot with a 6 mm tool (nothing
/// left to cut), then with a 12 mm tool (a 1 mm strip each side and the rims of its ends):
/// the volumes removed are the closed-form capsule differences.
#[test]
fn each_operation_cuts_only_what_the_previous_ones_left() {
    let slot = |d: f64| {
        let mut tp = Toolpath::new(tool(d), Point3::new(10.0, 20.0, 5.0));
        tp.push(Move::rapid(Point3::new(10.0, 20.0, 1.0)));
        tp.push(Move::line(Point3::new(10.0, 20.0, -5.0), 1.0));
        tp.push(Move::line(Point3::new(50.0, 20.0, -5.0), 1.0));
        tp.push(Move::rapid(Point3::new(50.0, 20.0, 5.0)));
        tp
    };
    let opts = FieldOptions::default();
    let mut field =
        HeightField::new(block(0.0, 0.0, 60.0, 40.0), -20.0, 0.0, &opts).expect("a block");
    let before = field.volume();
    let capsule = |r: f64| 2.0 * r * 40.0 + PI * r * r;
    let c = field.cell();
    let first = field.cut_with(
        &slot(10.0),
        &CutOptions::default().with_cutter(Cutter::Drill),
    );
    let want = 5.0 * capsule(5.0);
    // A cell stands for its centre: the area is off by at most the rim's cells.
    let rim = |r: f64| (2.0 * 40.0 + TAU * r) * c * 5.0;
    assert!(
        (first.removed_volume_mm3 - want).abs() < rim(5.0),
        "{} vs {want}",
        first.removed_volume_mm3
    );
    assert!((before - field.volume() - first.removed_volume_mm3).abs() < 1e-6 * before);
    let second = field.cut(&slot(6.0));
    assert!(second.removed_volume_mm3 < 1e-6, "{second}");
    assert!(second.removed_area_mm2 < 1e-9, "{second}");
    let third = field.cut(&slot(12.0));
    let want = 5.0 * (capsule(6.0) - capsule(5.0));
    assert!(
        (third.removed_volume_mm3 - want).abs() < rim(6.0) + rim(5.0),
        "{} vs {want}",
        third.removed_volume_mm3
    );
    assert!(
        (third.removed_area_mm2 - (capsule(6.0) - capsule(5.0))).abs()
            < (rim(6.0) + rim(5.0)) / 5.0,
        "{third}"
    );
    // The slot's floor and the stock beside it.
    assert!((field.height_at(Point::new(30.0, 20.0)).unwrap_or(0.0) + 5.0).abs() < 1e-4);
    assert!((field.height_at(Point::new(30.0, 27.0)).unwrap_or(-1.0)).abs() < 1e-9);
    // The drill may go straight down; the 12 mm end mill going down into the 10 mm hole
    // meets a 1 mm ring of fresh stock under its end face: a plunge.
    assert!(first.problems().is_empty(), "{first}");
    assert_eq!(third.plunges, vec![1], "{third}");
}

/// A rapid down into the stock and a rapid across it are rapids through material; a
/// vertical retract is not. A straight feed down into fresh stock is a plunge for an end
/// mill, not for a drill; down into a hole already cut, or along a ramp, it is none.
#[test]
fn rapids_through_material_and_plunges_are_found() {
    let opts = FieldOptions::default().with_cell(0.1);
    let fresh =
        || HeightField::new(block(0.0, 0.0, 60.0, 40.0), -20.0, 0.0, &opts).expect("a block");
    let mut tp = Toolpath::new(tool(6.0), Point3::new(10.0, 10.0, 5.0));
    tp.push(Move::rapid(Point3::new(10.0, 10.0, -2.0))); // 0: into the stock
    tp.push(Move::rapid(Point3::new(10.0, 10.0, 5.0))); // 1: retract
    tp.push(Move::rapid(Point3::new(30.0, 10.0, 5.0))); // 2: above
    tp.push(Move::line(Point3::new(30.0, 10.0, -3.0), 1.0)); // 3: plunge
    tp.push(Move::rapid(Point3::new(30.0, 10.0, 5.0))); // 4: retract
    tp.push(Move::line(Point3::new(30.0, 10.0, -3.0), 1.0)); // 5: into its own hole
    tp.push(Move::rapid(Point3::new(40.0, 10.0, -3.0))); // 6: across the stock
    tp.push(Move::rapid(Point3::new(40.0, 10.0, 5.0))); // 7
    tp.push(Move::rapid(Point3::new(20.0, 30.0, 0.5))); // 8
    tp.push(Move::line(Point3::new(40.0, 30.0, -1.0), 1.0)); // 9: a ramp
    tp.push(Move::rapid(Point3::new(40.0, 30.0, 5.0))); // 10
    let mut f = fresh();
    let mill = f.cut(&tp);
    assert_eq!(mill.rapids_through_material, vec![0, 6], "{mill}");
    assert_eq!(mill.plunges, vec![3], "{mill}");
    let mut f = fresh();
    let drill = f.cut_with(&tp, &CutOptions::default().with_cutter(Cutter::Drill));
    assert_eq!(drill.rapids_through_material, vec![0, 6], "{drill}");
    assert!(drill.plunges.is_empty(), "{drill}");
    assert_eq!(mill.problems().len(), 2);
}

/// A block that is not one, or a cell that is not a length, is refused with the value.
#[test]
fn bad_blocks_are_refused_by_name() {
    let opts = FieldOptions::default();
    let e = HeightField::new(block(0.0, 0.0, -1.0, 5.0), -1.0, 0.0, &opts).unwrap_err();
    assert!(e.to_string().contains("stock block"), "{e}");
    let e = HeightField::new(block(0.0, 0.0, 1.0, 5.0), 0.0, 0.0, &opts).unwrap_err();
    assert!(e.to_string().contains("bottom and top"), "{e}");
    let bad_cell = FieldOptions::default().with_cell(f64::NAN);
    let e = HeightField::new(block(0.0, 0.0, 1.0, 5.0), -1.0, 0.0, &bad_cell).unwrap_err();
    assert!(e.to_string().contains("cell"), "{e}");
    // A large block gets a cell that keeps it within the cell budget.
    let big = HeightField::new(block(0.0, 0.0, 400.0, 300.0), -10.0, 0.0, &opts).expect("a block");
    let (nx, ny) = big.dims();
    assert!(
        nx * ny <= millpath::stock::DEFAULT_FIELD_MAX_CELLS,
        "{nx} × {ny}"
    );
    assert!(big.cell() < 0.09, "{}", big.cell());
}

/// Below the block's bottom there is nothing: a slot cut 2 mm through the bottom removes
/// the block's 10 mm and leaves its cells at the bottom, and going down into it again is no
/// plunge.
#[test]
fn a_cut_through_the_bottom_takes_only_the_block() {
    let opts = FieldOptions::default().with_cell(0.1);
    let mut field =
        HeightField::new(block(0.0, 0.0, 40.0, 40.0), -10.0, 0.0, &opts).expect("a block");
    let mut tp = Toolpath::new(tool(6.0), Point3::new(10.0, 20.0, 5.0));
    tp.push(Move::rapid(Point3::new(10.0, 20.0, 1.0))); // 0
    tp.push(Move::line(Point3::new(10.0, 20.0, -12.0), 1.0)); // 1: plunge
    tp.push(Move::line(Point3::new(30.0, 20.0, -12.0), 1.0)); // 2
    tp.push(Move::rapid(Point3::new(30.0, 20.0, 5.0))); // 3
    tp.push(Move::rapid(Point3::new(10.0, 20.0, 1.0))); // 4
    tp.push(Move::line(Point3::new(10.0, 20.0, -12.0), 1.0)); // 5: into the slot
    tp.push(Move::rapid(Point3::new(10.0, 20.0, 5.0))); // 6
    let cut = field.cut(&tp);
    assert_eq!(cut.plunges, vec![1], "{cut}");
    assert!(cut.rapids_through_material.is_empty(), "{cut}");
    let area = 2.0 * 3.0 * 20.0 + PI * 9.0;
    let rim = (2.0 * 20.0 + TAU * 3.0) * field.cell();
    assert!(
        (cut.removed_volume_mm3 - 10.0 * area).abs() < 10.0 * rim,
        "{cut}: want {}",
        10.0 * area
    );
    let (nx, ny) = field.dims();
    let lowest = (0..nx * ny)
        .filter_map(|k| field.height(k % nx, k / nx))
        .fold(f64::INFINITY, f64::min);
    assert!((lowest + 10.0).abs() < 1e-6, "{lowest}");
}

/// Arcs at one z swept whole: long arcs of radii up to 3 m crossing the block, arcs of more
/// than a half turn and full circles, each way round. Every cell within `r` of a dense
/// sampling of the arc (0.01 mm, computed here from its centre and angles) is cut to the
/// arc's z, and every cell farther than `r` and half the sampling's spacing from all its
/// samples keeps the top: the field cuts the arc's own sweep, no wider.
#[test]
fn arcs_at_one_z_cut_their_own_sweep_whatever_their_radius() {
    let mut rng = Lcg(41);
    let step = 0.01;
    let (top, bottom) = (0.0, -10.0);
    let (mut cut_cells, mut kept_cells, mut cases) = (0usize, 0usize, 0);
    for case in 0..12 {
        let d = rng.range(2.0, 8.0);
        let r = 0.5 * d;
        let z = rng.range(-6.0, -1.0);
        let ccw = rng.next() < 0.5;
        let (from, to, centre) = if case % 2 == 0 {
            // A long, gentle arc through the block's middle: its centre metres off, a chord
            // of about 30 mm.
            let big = rng.range(200.0, 3000.0);
            let dir = rng.range(0.0, TAU);
            let centre = Point3::new(20.0 - big * dir.cos(), 20.0 - big * dir.sin(), 0.0);
            let half = 15.0 / big;
            let (a0, a1) = if ccw {
                (dir - half, dir + half)
            } else {
                (dir + half, dir - half)
            };
            let at = |a: f64| Point3::new(centre.x + big * a.cos(), centre.y + big * a.sin(), z);
            (at(a0), at(a1), centre)
        } else {
            // More than a half turn, or a full circle, about the block's middle.
            let small = rng.range(3.0, 12.0);
            let a0 = rng.range(0.0, TAU);
            let turn = if case % 4 == 1 {
                TAU
            } else {
                rng.range(PI + 0.1, TAU - 0.1)
            };
            let a1 = if ccw { a0 + turn } else { a0 - turn };
            let centre = Point3::new(20.0, 20.0, 0.0);
            let at = |a: f64| Point3::new(20.0 + small * a.cos(), 20.0 + small * a.sin(), z);
            (at(a0), if turn >= TAU { at(a0) } else { at(a1) }, centre)
        };
        let mut tp = Toolpath::new(tool(d), Point3::new(from.x, from.y, top + 5.0));
        tp.push(Move::rapid(Point3::new(from.x, from.y, top + 1.0)));
        tp.push(Move::line(from, 1.0));
        tp.push(Move::arc_xy(to, centre, ccw, 1.0));
        tp.push(Move::rapid(Point3::new(to.x, to.y, top + 5.0)));
        let opts = FieldOptions::default().with_cell(0.1);
        let mut field =
            HeightField::new(block(0.0, 0.0, 40.0, 40.0), bottom, top, &opts).expect("a block");
        field.cut(&tp);
        // Each cell's least distance from the samples within `r` and a cell of it.
        let (nx, ny) = field.dims();
        let c = field.cell();
        let mut nearest = vec![f64::INFINITY; nx * ny];
        for q in dense(from, &tp.moves[2], step) {
            let reach = r + c;
            let i0 = (((q.x - reach) / c).floor().max(0.0)) as usize;
            let j0 = (((q.y - reach) / c).floor().max(0.0)) as usize;
            let i1 = (((q.x + reach) / c).ceil().max(0.0) as usize).min(nx - 1);
            let j1 = (((q.y + reach) / c).ceil().max(0.0) as usize).min(ny - 1);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let k = j * nx + i;
                    nearest[k] = nearest[k].min(field.centre(i, j).distance(q.xy()));
                }
            }
        }
        for j in 0..ny {
            for i in 0..nx {
                let p = field.centre(i, j);
                // The plunge at the start cuts its disc too; the rapids cut nothing.
                if p.distance(from.xy()) <= r + step {
                    continue;
                }
                let near = nearest[j * nx + i];
                let h = field.height(i, j).expect("on the field");
                if near <= r - 1e-9 {
                    assert!(
                        (h - z).abs() < 1e-4,
                        "case {case}, cell ({i}, {j}) {near} mm from the arc: {h}, not {z}"
                    );
                    cut_cells += 1;
                } else if near > r + 0.5 * step + 1e-9 {
                    assert!(
                        h >= top - 1e-9,
                        "case {case}, cell ({i}, {j}) {near} mm from the arc: cut to {h}"
                    );
                    kept_cells += 1;
                }
            }
        }
        cases += 1;
    }
    assert_eq!(cases, 12);
    assert!(
        cut_cells > 50_000 && kept_cells > 500_000,
        "{cut_cells}, {kept_cells}"
    );
}
