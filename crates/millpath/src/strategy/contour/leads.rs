//! The moves of one closed pass at a Z level with its tangent lead arcs, shared by the
//! [`contour`](super) and [`profile`](crate::strategy::profile) strategies.
//!
//! A loop is either its chords (the vertices of a flattened offset) or its elements (lines
//! and arcs: biarcs fitted to an offset curve, or the exact offset of a drawn outline). The
//! tool arrives on the loop's first vertex along a quarter arc of radius `ρ_l` that is
//! tangent to the loop there and lies on the free side (the side away from the wall), goes
//! round, and leaves along the mirrored arc, so the wall never sees the tool stop or turn:
//! no dwell mark. With `ρ_l = 0` the tool plunges on the loop itself.
//!
//! Lead arc geometry: with the unit tangent `t` at the first vertex `v₀` and the free-side
//! normal `n`, the lead-in arc has centre `c = v₀ + ρ_l·n` and starts at `c − ρ_l·t` (a
//! quarter turn before `v₀`); the lead-out arc has the centre `v₀ + ρ_l·n'` from the tangent
//! `t'` at the loop's end and ends at `c' + ρ_l·t'`.

use super::offset::OffsetVertex;
use crate::curve::ArcSeg;
use crate::geom::{Point, Point3, Vec2};
use crate::toolpath::Move;

/// The lead arcs of a loop and the feed it is cut at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lead {
    /// Lead arc radius, mm (0: no lead arcs, the tool plunges on the loop).
    pub radius: f64,
    /// The free side is left of travel (else right).
    pub left: bool,
    /// Cutting feed, mm/s.
    pub feed: f64,
}

/// The Z levels of a cut of `depth` below `top_z` by `step`: one at each step-down, the last
/// at full depth.
pub fn layer_depths(top_z: f64, depth: f64, step: f64) -> Vec<f64> {
    let n = (depth / step - 1e-9).ceil().max(1.0) as usize;
    (1..=n)
        .map(|k| top_z - (k as f64 * step).min(depth))
        .collect()
}

/// The moves of one closed loop at depth `z`: the XY entry point (start of the lead-in) and
/// the feed moves (lead-in arc, the loop tagged with the curve parameter, lead-out arc).
pub fn loop_moves(
    lp: &[OffsetVertex],
    arcs: Option<&[ArcSeg]>,
    z: f64,
    lead: &Lead,
    pieces: usize,
) -> (Point, Vec<Move>) {
    let tag = |m: Move, s: f64| {
        let w = s.rem_euclid(pieces as f64);
        let i = w.floor();
        m.with_tag(i as u32, w - i)
    };
    let v0 = lp[0];
    let first_dir = match arcs.and_then(|a| a.first()) {
        Some(a) => a.at(0.001) - a.start,
        None => lp.get(1).map_or(Vec2::new(1.0, 0.0), |v1| v1.p - v0.p),
    };
    let dir = first_dir.normalize().unwrap_or(Vec2::new(1.0, 0.0));
    let left = lead.left;
    let feed = lead.feed;
    let nrm = if left { dir.perp() } else { -dir.perp() };
    let rl = lead.radius;
    let p3 = |p: Point| Point3::from_xy(p, z);
    let mut moves = Vec::new();
    let entry;
    if rl > 0.0 {
        let c = v0.p + nrm * rl;
        entry = c - dir * rl;
        moves.push(Move::arc_xy(p3(v0.p), p3(c), left, feed));
    } else {
        entry = v0.p;
    }
    let mut last_dir = None;
    match arcs {
        Some(arcs) if !arcs.is_empty() => {
            for a in arcs {
                let m = match a.center {
                    Some(c) => Move::arc_xy(p3(a.end), p3(c), a.ccw, feed),
                    None => Move::line(p3(a.end), feed),
                };
                moves.push(tag(m, a.s_end));
            }
            if let Some(a) = arcs.last() {
                last_dir = (a.end - a.at(0.999)).normalize();
            }
            let end = arcs.last().map_or(v0.p, |a| a.end);
            if end.distance(v0.p) > 0.0 {
                moves.push(tag(Move::line(p3(v0.p), feed), v0.s));
            }
        }
        _ => {
            for v in lp.iter().skip(1) {
                moves.push(tag(Move::line(p3(v.p), feed), v.s));
            }
            moves.push(tag(Move::line(p3(v0.p), feed), v0.s));
        }
    }
    if rl > 0.0 {
        let m = lp.len();
        let last = lp[m - 1];
        let dir_end = last_dir
            .or_else(|| (v0.p - last.p).normalize())
            .unwrap_or(dir);
        let nrm_end = if left {
            dir_end.perp()
        } else {
            -dir_end.perp()
        };
        let c = v0.p + nrm_end * rl;
        moves.push(Move::arc_xy(p3(c + dir_end * rl), p3(c), left, feed));
    }
    (entry, moves)
}
