//! Exact clearance between the tool centre's path and the walls.
//!
//! For every move that reaches below the stock top (`z < 0`), the distance from the tool
//! centre's XY path to the outline and the islands is minimised: `f(t) = dist(P(t), walls)`
//! along the move's arc length `t` is 1-Lipschitz, so sampling it every `h` mm bounds the true
//! minimum from below by `min − h/2`; every sample within `h/2` of the running minimum is then
//! refined by golden-section search on `[t − h, t + h]` to 1e-9 mm (distances to the walls
//! are exact: cavalier_contours' closest point on lines and arcs, through a spatial index of
//! the walls, [`super::nearest`]). A straight move, and an arc in XY, is measured whole,
//! exactly ([`super::nearest::IndexedWall::distance_to_segment`], `distance_to_arc`); the
//! sampling is left for arcs in other planes. The check is against the
//! geometry, not the raster.

use super::StockSpec;
use super::nearest::IndexedWall;
use crate::geom::{Point, Point3};
use crate::toolpath::{MoveKind, Plane, Toolpath};

/// The smallest clearance and where it happens.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    /// Smallest distance from the tool centre to a wall, mm (infinite if nothing cut).
    pub distance: f64,
    /// Where (tool centre).
    pub at: Point3,
    /// Index of the move.
    pub move_index: usize,
}

/// Sample spacing before refinement, mm, times the tool's
/// [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale) (the refinement finds the
/// minimum to 1e-9 mm whatever the spacing; the spacing only has to separate the minima).
const SAMPLE: f64 = 0.25;

/// The smallest distance between the tool centre (below `z = 0`) and the walls.
pub fn min_clearance(tp: &Toolpath, spec: StockSpec<'_>) -> Clearance {
    min_clearance_levels(tp, &[spec])
}

/// [`min_clearance`] with a pocket per level (`specs[i]` for `tp.levels[i]`, the last one
/// standing for levels beyond the list). A move of level `i` is measured against the walls of
/// its own section and of the section of the level above (the slab's top: the tool is a
/// cylinder reaching up through the slab), less the difference between its level's wall
/// stock and the last level's, so that one threshold, `r + last stock`, holds for all. A move
/// below `z = 0` outside every level is measured against every section.
pub fn min_clearance_levels(tp: &Toolpath, specs: &[StockSpec<'_>]) -> Clearance {
    let final_stock = specs.last().map_or(0.0, |s| s.wall_stock);
    let mut level_of_move = vec![None; tp.moves.len()];
    for (li, lv) in tp.levels.iter().enumerate() {
        for slot in level_of_move
            .iter_mut()
            .take(lv.end.min(tp.moves.len()))
            .skip(lv.start)
        {
            *slot = Some(li);
        }
    }
    // Every spec's loops indexed once (the distance queries dominate the verifier's time).
    let indexed: Vec<Vec<IndexedWall<'_>>> = specs
        .iter()
        .map(|spec| {
            std::iter::once(spec.outer)
                .chain(spec.islands.iter())
                .map(|o| IndexedWall::new(o.polyline()))
                .collect()
        })
        .collect();
    let walls_of = |k: usize| -> Vec<usize> {
        if specs.is_empty() {
            return Vec::new();
        }
        let last = specs.len().saturating_sub(1);
        let mut v: Vec<usize> = match level_of_move.get(k).copied().flatten() {
            Some(li) => {
                let own = li.min(last);
                let above = li.checked_sub(1).map(|a| a.min(last));
                std::iter::once(own).chain(above).collect()
            }
            None => (0..specs.len()).collect(),
        };
        v.dedup_by(|a, b| super::simulate::same_spec(specs[*a], specs[*b]));
        v
    };
    let dist_to = |walls: &[usize], p: Point| {
        walls
            .iter()
            .map(|&i| {
                indexed[i]
                    .iter()
                    .map(|w| w.distance(p))
                    .fold(f64::INFINITY, f64::min)
                    - (specs[i].wall_stock - final_stock)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let mut best = Clearance {
        distance: f64::INFINITY,
        at: tp.start,
        move_index: 0,
    };
    for (k, (from, m)) in tp.segments().enumerate() {
        if matches!(m.kind, MoveKind::Dwell { .. }) || from.z.min(m.to.z) >= 0.0 {
            continue;
        }
        let walls = walls_of(k);
        if matches!(m.kind, MoveKind::Line | MoveKind::Rapid) {
            // A straight move: measured whole, exactly (nearest::IndexedWall).
            let (a, b) = (from.xy(), m.to.xy());
            for &i in &walls {
                for w in &indexed[i] {
                    let (d, p) = w.distance_to_segment(a, b);
                    let d = d - (specs[i].wall_stock - final_stock);
                    if d < best.distance {
                        let len = a.distance(b);
                        let f = if len > 0.0 { a.distance(p) / len } else { 1.0 };
                        best = Clearance {
                            distance: d,
                            at: from.lerp(m.to, f.clamp(0.0, 1.0)),
                            move_index: k,
                        };
                    }
                }
            }
            continue;
        }
        if let (MoveKind::Arc { center, plane, .. }, Some((r, sweep))) =
            (m.kind, m.sweep_from(from))
            && plane == Plane::Xy
            && sweep != 0.0
        {
            // An arc in XY: measured whole, exactly (nearest::IndexedWall::distance_to_arc).
            let a0 = (from.y - center.y).atan2(from.x - center.x);
            for &i in &walls {
                for w in &indexed[i] {
                    let (d, rel) = w.distance_to_arc(center.xy(), r, a0, sweep);
                    let d = d - (specs[i].wall_stock - final_stock);
                    if d < best.distance {
                        let a = a0 + rel;
                        let f = (rel / sweep).clamp(0.0, 1.0);
                        best = Clearance {
                            distance: d,
                            at: Point3::new(
                                center.x + r * a.cos(),
                                center.y + r * a.sin(),
                                from.z + (m.to.z - from.z) * f,
                            ),
                            move_index: k,
                        };
                    }
                }
            }
            continue;
        }
        let dist = |p: Point| dist_to(&walls, p);
        let len = m.length_from(from).max(0.0);
        let pos = |t: f64| -> Point3 {
            let f = if len > 0.0 {
                (t / len).clamp(0.0, 1.0)
            } else {
                1.0
            };
            match (m.kind, m.sweep_from(from)) {
                (MoveKind::Arc { center, .. }, Some((r, sweep))) => {
                    let a = (from.y - center.y).atan2(from.x - center.x) + sweep * f;
                    Point3::new(
                        center.x + r * a.cos(),
                        center.y + r * a.sin(),
                        from.z + (m.to.z - from.z) * f,
                    )
                }
                _ => from.lerp(m.to, f),
            }
        };
        let n = ((len / (SAMPLE * tp.tool.tolerance_scale())).ceil() as usize).max(1);
        let h = len / n as f64;
        let vals: Vec<f64> = (0..=n).map(|i| dist(pos(h * i as f64).xy())).collect();
        let floor = vals.iter().copied().fold(f64::INFINITY, f64::min);
        if floor - 0.5 * h > best.distance {
            continue;
        }
        for (i, &v) in vals.iter().enumerate() {
            if v - 0.5 * h > best.distance.min(floor + 0.5 * h) {
                continue;
            }
            let (mut a, mut b) = ((h * i as f64 - h).max(0.0), (h * i as f64 + h).min(len));
            // Golden section, one new distance per step (to 1e-9 mm of arc length: the
            // distance is 1-Lipschitz, so within 1e-9 mm of the minimum's value).
            let g = 0.5 * (5f64.sqrt() - 1.0);
            let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
            let (mut fc, mut fd) = (dist(pos(c).xy()), dist(pos(d).xy()));
            for _ in 0..80 {
                if b - a < 1e-9 {
                    break;
                }
                if fc < fd {
                    (b, d, fd) = (d, c, fc);
                    c = b - g * (b - a);
                    fc = dist(pos(c).xy());
                } else {
                    (a, c, fc) = (c, d, fd);
                    d = a + g * (b - a);
                    fd = dist(pos(d).xy());
                }
            }
            for t in [a, 0.5 * (a + b), h * i as f64] {
                let p = pos(t);
                let dd = dist(p.xy());
                if dd < best.distance {
                    best = Clearance {
                        distance: dd,
                        at: p,
                        move_index: k,
                    };
                }
            }
        }
    }
    best
}
