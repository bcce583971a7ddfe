//! Which moves of a program can reach an outline: boxes of moves and paths, and the runs of
//! consecutive moves near an outline (within a reach of its walls, measured exactly on lines
//! and XY arcs), so that an outline's checks sweep only the moves that can touch it.

use crate::geom::{Outline, Point3};
use crate::stock::HeightField;
use crate::stock::nearest::IndexedWall;
use crate::toolpath::{Move, MoveKind, Plane, Toolpath};

/// How far beyond the tool radius a move's box may lie from an outline's box and still be
/// measured against it, mm (the finishing offset's tolerance and stock to leave are less).
pub(crate) const NEAR: f64 = 1.0;

/// True when two boxes share a point.
pub(crate) fn overlaps(a: crate::geom::Aabb, b: crate::geom::Aabb) -> bool {
    a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y
}

/// The box (in XY) of a move from `from`: its ends, and for an arc its whole circle.
pub(crate) fn move_box(from: Point3, m: &Move) -> crate::geom::Aabb {
    let b = crate::geom::Aabb::EMPTY
        .with_point(from.xy())
        .with_point(m.to.xy());
    match m.kind {
        MoveKind::Arc { center, .. } => {
            let c = center.xy();
            let rad = c.distance(from.xy()).max(c.distance(m.to.xy()));
            b.union(crate::geom::Aabb::EMPTY.with_point(c).inflate(rad))
        }
        _ => b,
    }
}

/// The box of a whole toolpath's moves.
pub(crate) fn path_box(tp: &Toolpath) -> crate::geom::Aabb {
    tp.segments().fold(
        crate::geom::Aabb::EMPTY.with_point(tp.start.xy()),
        |b, (f, m)| b.union(move_box(f, m)),
    )
}

/// The runs of consecutive moves of `tp` whose boxes meet `near`, each a toolpath starting
/// where its first move starts.
pub(crate) fn near_runs(tp: &Toolpath, near: crate::geom::Aabb) -> Vec<Toolpath> {
    runs_within(tp, near, move_box)
}

/// The box (in XY) of every point a move from `from` passes through, in any plane: its ends,
/// and for an arc the ball about its centre through its farther end (the arc lies on it).
pub(crate) fn swept_box(from: Point3, m: &Move) -> crate::geom::Aabb {
    let b = crate::geom::Aabb::EMPTY
        .with_point(from.xy())
        .with_point(m.to.xy());
    match m.kind {
        MoveKind::Arc { center, .. } => {
            let rad = (center - from).length().max((center - m.to).length());
            b.union(
                crate::geom::Aabb::EMPTY
                    .with_point(center.xy())
                    .inflate(rad),
            )
        }
        _ => b,
    }
}

/// The runs of moves of `tp` (its tool's radius `r`) that may lower a cell of `field` within
/// `2r + 3c` of `outline` (`c` the field's cell): those whose boxes come within `r` and
/// [`NEAR`] of the field's and whose paths come within [`held_slot_reach`] of the outline.
pub(crate) fn runs_for_outline(
    tp: &Toolpath,
    outline: &Outline,
    field: &HeightField,
) -> Vec<Toolpath> {
    let r = tp.tool.radius();
    let wall = IndexedWall::new(outline.polyline());
    let reach = held_slot_reach(r, field.cell());
    let near = field.bounds().inflate(r + NEAR);
    runs_where(tp, |from, m| {
        overlaps(swept_box(from, m), near) && !farther_than(&wall, from, m, reach)
    })
}

/// How far from an outline a move's path may pass and still lower a cell its bridge verdict
/// reads, mm, for a tool of radius `r` on a field of cell `c`: `r` (and [`NEAR`] for a
/// chord's sagitta and the rounding) beyond the `2r + 3c` the verdict reads (with a cell to
/// spare).
fn held_slot_reach(r: f64, c: f64) -> f64 {
    3.0 * r + 4.0 * c + NEAR
}

/// True when every point of the move `m` from `from` (in XY) is farther than `reach` from
/// `wall`. A line: its middle's distance less half its length, else its exact distance
/// ([`IndexedWall::distance_to_segment`]). An arc in XY (a helix too): its exact distance
/// from its start circle ([`IndexedWall::distance_to_arc`]) less the difference of its end
/// radii; in another plane, its centre's distance less its radius in space.
fn farther_than(wall: &IndexedWall<'_>, from: Point3, m: &Move, reach: f64) -> bool {
    match m.kind {
        MoveKind::Arc { center, plane, .. } => {
            let rad = (center - from).length().max((center - m.to).length());
            if wall.distance(center.xy()) - rad > reach {
                return true;
            }
            match (plane, m.sweep_from(from)) {
                (Plane::Xy, Some((r0, sweep))) => {
                    let c = center.xy();
                    let a0 = (from.y - c.y).atan2(from.x - c.x);
                    let spread = (m.to.xy().distance(c) - r0).abs();
                    wall.distance_to_arc(c, r0, a0, sweep).0 - spread > reach
                }
                _ => false,
            }
        }
        _ => {
            let (a, b) = (from.xy(), m.to.xy());
            let mid = wall.distance(a.lerp(b, 0.5));
            let half = 0.5 * a.distance(b);
            mid - half > reach || (mid > reach && wall.distance_to_segment(a, b).0 > reach)
        }
    }
}

/// The runs of consecutive moves of `tp` whose boxes (`box_of`) meet `near`, each a
/// toolpath starting where its first move starts.
pub(crate) fn runs_within(
    tp: &Toolpath,
    near: crate::geom::Aabb,
    box_of: fn(Point3, &Move) -> crate::geom::Aabb,
) -> Vec<Toolpath> {
    runs_where(tp, |from, m| overlaps(box_of(from, m), near))
}

/// The runs of consecutive moves of `tp` that `keep` keeps, each a toolpath starting where
/// its first move starts.
fn runs_where(tp: &Toolpath, keep: impl Fn(Point3, &Move) -> bool) -> Vec<Toolpath> {
    let mut runs: Vec<Toolpath> = Vec::new();
    let mut open = false;
    for (from, m) in tp.segments() {
        if keep(from, m) {
            if !open {
                runs.push(Toolpath::new(tp.tool, from));
                open = true;
            }
            if let Some(run) = runs.last_mut() {
                run.moves.push(*m);
            }
        } else {
            open = false;
        }
    }
    runs
}
