//! Contour-parallel offsets, cut from the inside out.
//!
//! Loops at distances `d_k = r + stock + k·s` from the pocket boundary (cavalier_contours'
//! parallel offset, exact arcs), `k = 0..K` until the offset vanishes. Neighbouring loops are
//! at most `s` apart (the offset of an offset by `s` is the offset by the sum, for inward
//! offsets of a region), so the radial depth of cut is `s` on straight walls; at a convex
//! corner of half-angle β the corner points of two loops are `s / sin β` apart, which is where
//! the engagement peaks (the stock simulation measures it).
//!
//! Order: the deepest loops first, each level in nearest-neighbour order, every loop restarted
//! at its point nearest to where the tool is. Two loops are linked by a straight feed move when
//! the link is short (at most `2s`) and crosses no loop of the boundary offset (so it cannot
//! gouge); otherwise a new cut starts with a helix (an innermost loop with room for it) or a
//! ramp along the loop.

use super::chain::segs_from_vertices;
use super::levels::{Cut, CutEntry, LevelPlan};
use super::options::{Direction, Entry, PocketOptions};
use super::shape::{
    OffsetRegion, PocketShape, closed_chain, inscribed_centre, restart_near, reversed, v2,
};
use crate::error::InputError;
use crate::geom::Point;
use crate::toolpath::Tool;
use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};

/// Most offset loops a pocket may need (a guard against degenerate input).
const MAX_LOOPS: usize = 100_000;

/// The offset strategy's plan for one level.
pub fn plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<LevelPlan, InputError> {
    let r = tool.radius();
    let s = opts.stepover_mm(tool);
    let d0 = r + opts.wall_stock;
    let boundary = shape.offset(d0);
    if boundary.is_empty() {
        return Err(too_large(tool));
    }
    let mut levels: Vec<OffsetRegion> = vec![boundary.clone()];
    let mut count = 0;
    loop {
        let next = shape.offset(d0 + s * levels.len() as f64);
        if next.is_empty() {
            break;
        }
        count += next.outers.len() + next.islands.len();
        if count > MAX_LOOPS {
            return Err(InputError::new("stepover", s)
                .at("--stepover")
                .expected("a stepover giving fewer than 100000 offset loops"));
        }
        levels.push(next);
    }
    let ccw = opts.direction == Direction::Climb;
    let mut cuts: Vec<Cut> = Vec::new();
    let mut here: Option<Point> = None;
    for (k, level) in levels.iter().enumerate().rev() {
        let mut todo: Vec<&Polyline<f64>> = level.loops().collect();
        while !todo.is_empty() {
            let pick = match here {
                None => 0,
                Some(p) => nearest_loop(&todo, p),
            };
            let lp = todo.swap_remove(pick);
            let lp = if ccw { lp.clone() } else { reversed(lp) };
            let start_near = here.unwrap_or_else(|| lp.at(0).pos().into_point());
            let lp = restart_near(&lp, start_near);
            let path = segs_from_vertices(&closed_chain(&lp));
            let Some(first) = path.first() else { continue };
            let linkable = here.is_some_and(|h| {
                h.distance(first.a) <= 2.0 * s + 1e-9 && !crosses(&boundary, h, first.a)
            });
            if linkable {
                if let Some(last) = cuts.last_mut() {
                    last.path
                        .push(super::chain::Seg::line(here.unwrap_or(first.a), first.a));
                    last.path.extend(path.iter().copied());
                }
                here = path.last().map(|s| s.b);
            } else {
                let innermost = k + 1 == levels.len();
                let entry = entry_for(&lp, innermost, opts, r);
                let path = match entry {
                    CutEntry::Helix { center, radius } => segs_from_vertices(&closed_chain(
                        &restart_near(&lp, center + crate::geom::Vec2::new(radius, 0.0)),
                    )),
                    _ => path,
                };
                here = path.last().map(|s| s.b);
                cuts.push(Cut { entry, path });
            }
        }
    }
    Ok(LevelPlan { cuts })
}

trait IntoPoint {
    fn into_point(self) -> Point;
}
impl IntoPoint for cavalier_contours::core::math::Vector2<f64> {
    fn into_point(self) -> Point {
        Point::new(self.x, self.y)
    }
}

fn nearest_loop(loops: &[&Polyline<f64>], p: Point) -> usize {
    let mut best = (0, f64::INFINITY);
    for (i, l) in loops.iter().enumerate() {
        let d = l
            .closest_point(v2(p), 1e-12)
            .map_or(f64::INFINITY, |c| c.distance);
        if d < best.1 {
            best = (i, d);
        }
    }
    best.0
}

/// True when the segment `a–b` crosses a loop of `region` (touching at the ends excepted).
pub fn crosses(region: &OffsetRegion, a: Point, b: Point) -> bool {
    if a.distance(b) < 1e-9 {
        return false;
    }
    let mut seg = Polyline::new();
    seg.add(a.x, a.y, 0.0);
    seg.add(b.x, b.y, 0.0);
    region.loops().any(|l| {
        let hits = l.find_intersects(&seg);
        hits.basic_intersects.iter().any(|i| {
            let p = Point::new(i.point.x, i.point.y);
            p.distance(a) > 1e-6 && p.distance(b) > 1e-6
        })
    }) || {
        // Entirely outside (both ends on loops, the middle outside the region)? A link
        // running along a loop (overlapping it) is inside.
        let m = a.midpoint(b);
        let on_loop = region.loops().any(|l| {
            l.closest_point(v2(m), 1e-12)
                .is_some_and(|c| c.distance < 1e-7)
        });
        let inside = region.outers.iter().any(|o| o.winding_number(v2(m)) != 0)
            && region.islands.iter().all(|i| i.winding_number(v2(m)) == 0);
        !inside && !on_loop
    }
}

/// A helix at the loop's inscribed centre when it is an innermost loop with room for it, a
/// ramp along the loop otherwise.
fn entry_for(lp: &Polyline<f64>, innermost: bool, opts: &PocketOptions, r: f64) -> CutEntry {
    if let (true, Entry::Helix { radius, .. }) = (innermost, opts.entry)
        && lp.area().abs() > 0.0
    {
        let outer = if lp.area() > 0.0 {
            lp.clone()
        } else {
            reversed(lp)
        };
        let (c, room) = inscribed_centre(&outer, &[], 24);
        // A helix wider than the tool would leave a pillar at its centre.
        let radius = radius.min(0.9 * r);
        if room >= radius {
            return CutEntry::Helix { center: c, radius };
        }
    }
    CutEntry::Ramp
}

/// The error for a tool that does not fit.
pub fn too_large(tool: &Tool) -> InputError {
    InputError::new("tool diameter", tool.diameter)
        .at("--tool-diameter")
        .expected("a tool (plus wall stock) that fits inside the pocket")
}
