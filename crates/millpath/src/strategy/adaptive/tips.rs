//! Feeding into the tool-centre region's acute corners before the walls' loop.
//!
//! The passes stop short of a corner of interior angle `α` well under a right angle (a
//! spike, a narrow V): the region there is narrower than a pass's first bite. The walls'
//! loop, running in along one wall, then meets what they left head-on. The material that
//! only positions within `x` of the corner `T` reach is `2r·x·(1 − sin(α/2))` to first order
//! (`crate::stock::corner_floor`): a tool feeding straight in removes that per unit of
//! travel once the rest is gone, the engagement `φ_T = acos(2·sin(α/2) − 1)`.
//!
//! **When.** Before the walls' loop, at each such corner (turning by more than
//! [`ACUTE_TURN`]), nearest the tool first; none where the field's cells are coarser than
//! [`MAX_CELL_RADII`] radii.
//!
//! **How.** The tool goes to the point `Q` of the bisector nearest `T` that it reaches (a
//! clear link from where it is, or a point whose disc holds no material to feed down at) and
//! works into the corner by *strokes*: straight lines, each as deep (along the bisector) as
//! keeps every step of it within the target's share of material (bisection on the depth), to
//! the corner's other edge, along the edge it stands on, or to the bisector, whichever goes
//! deepest, so that the strokes zigzag into the V. Where none goes [`MIN_ADVANCE`] cells
//! deeper, they start from a point of the bisector up to `r` behind the deepest point
//! reached (the tool backs off through cleared material and comes in at a shallower angle,
//! removing less per unit of travel). When a straight feed to `T` holds the target, or no
//! stroke goes deeper, the tool feeds to `T` if no step of that feed removes more than the
//! radial depth of `FLOOR_SLACK · φ_T` less [`GRID_CELLS`] cells (or the target's, where
//! more; the target's alone at a cusp, where `FLOOR_SLACK · φ_T` is a slot). Strokes spread the corner's material over more travel than one feed, so the
//! engagement they reach is mostly well under `φ_T`.
//!
//! **Checks.** Every step is read on the planner's field (at most `2h` long, allowed
//! [`NOISE_CELLS`] beyond its share), every position lies in the tool-centre region, and none
//! comes near where the field holds no material that the stock may (the discs an entry that
//! found no room marks cleared, for the walls' loops). A corner the tool does not reach is
//! left to the walls' loop.

use super::{ACUTE_TURN, CutEntry, DESCENT_CELLS, Planner};
use crate::geom::{Point, Vec2};
use crate::strategy::pocket::levels::Cut;
use crate::strategy::pocket::segments::{Seg, segs_from_vertices};
use crate::strategy::pocket::shape::{OffsetRegion, closed_chain};

/// The last feed's engagement may be this multiple of the corner's own (module docs).
pub const FLOOR_SLACK: f64 = 1.05;
/// The farthest (tool radii) from the corner that the feed starts.
const REACH_RADII: f64 = 8.0;
/// The field's count of a step's material can fall short of the verifier's by about a
/// cell's width at either side of the tool's band (a slot's radial depth read as `2r − 2h`):
/// the last feed's rate is held this many cells under the corner's own.
const GRID_CELLS: f64 = 2.0;
/// How far (mm) a position on the region's edge (a stroke's end, the corner) may lie
/// outside it by rounding.
const ON_EDGE: f64 = 1e-6;
/// Cells a step may remove beyond its share: a step shorter than a cell moves the disc's
/// edge across a few cells' centres whatever it cuts.
const NOISE_CELLS: f64 = 2.0;
/// The coarsest grid (cells per tool radius) the strokes are planned on: a pocket large
/// against the tool gets cells larger than `r/32` (`MAX_CELLS`), on which a stroke's count
/// of material is too coarse to hold the target, and its corners are left to the walls' loop.
const MAX_CELL_RADII: f64 = 1.0 / 16.0;
/// Most strokes into one corner.
const MAX_STROKES: usize = 128;
/// The least advance (cells) a stroke makes into the corner.
const MIN_ADVANCE: f64 = 0.125;
/// Bisections for a stroke's depth.
const BISECTIONS: usize = 10;

impl Planner<'_, '_> {
    /// Feeds into each acute corner of `region` (module docs), nearest the tool first.
    pub(super) fn tips(&mut self, region: &OffsetRegion) {
        if self.field.h > MAX_CELL_RADII * self.stepper.r {
            return;
        }
        let mut corners = acute_corners(region);
        while !corners.is_empty() {
            let here = self.pos.unwrap_or(corners[0].t);
            let k = (0..corners.len())
                .min_by(|&a, &b| {
                    corners[a]
                        .t
                        .distance(here)
                        .total_cmp(&corners[b].t.distance(here))
                })
                .unwrap_or(0);
            let corner = corners.swap_remove(k);
            self.feed_into(&corner);
        }
    }

    /// Into the corner `t` (interior angle `alpha`; `u` the bisector pointing into it,
    /// `e` the directions of its two edges away from it) from the nearest point of the
    /// bisector the tool reaches, by strokes across the corner, each as deep as the target
    /// allows, until a straight feed to `t` holds the corner's own rate (module docs); the
    /// tool then stands at `t`. Nothing is cut where the tool reaches no point of the
    /// bisector within [`REACH_RADII`].
    fn feed_into(&mut self, corner: &Corner) {
        let Corner { t, u, e, alpha, .. } = *corner;
        let st = self.stepper;
        let h = self.field.h;
        let floor = (2.0 * (0.5 * alpha).sin() - 1.0).clamp(-1.0, 1.0).acos();
        let cap = FLOOR_SLACK * floor;
        let target = st.target * h * h / st.delta;
        // At a cusp (where an island's offset meets a wall's, or a loop turns back) the cap
        // is a slot: the last feed, too, holds the target.
        let corner_rate = if cap < std::f64::consts::PI {
            target.max(st.r * (1.0 - cap.cos()) - GRID_CELLS * h)
        } else {
            target
        };
        let Some((q, linked)) = self.reach_bisector(t, u) else {
            return;
        };
        let mut path = vec![];
        let link = linked.filter(|at| at.distance(q) > 1e-9);
        if let Some(at) = link {
            path.push(Seg::line(at, q));
            self.field.clear_capsule(at, q, st.r);
        }
        // Where along the bisector a stroke ends on edge `i`.
        let half = 0.5 * alpha;
        let on_edge = |i: usize, s: f64| t + e[i] * (s / half.cos());
        let mut cur = q;
        let mut depth = (t - q).dot(u);
        let mut side = 0;
        for _ in 0..MAX_STROKES {
            if self.feed_holds(cur, t, target) {
                break;
            }
            // The deepest stroke within the target (bisection on its depth's advance): to
            // the other edge, along this one, or to the bisector, whichever goes deepest;
            // from where the tool stands or, where none goes deep enough, from a point of
            // the bisector behind it (a stroke in at a shallower angle removes less per
            // unit of its length).
            let mut best: Option<(f64, usize, Point)> = None;
            for back in [0.0, 0.25, 0.5, 1.0] {
                let from = if back == 0.0 {
                    cur
                } else {
                    t - u * (depth + back * st.r)
                };
                if back > 0.0 && !self.feed_holds(cur, from, target) {
                    continue;
                }
                for way in [side, 1 - side, 2] {
                    let end = |s: f64| if way < 2 { on_edge(way, s) } else { t - u * s };
                    let (mut lo, mut hi) = (0.0, depth);
                    for _ in 0..BISECTIONS {
                        let mid = 0.5 * (lo + hi);
                        if self.feed_holds(from, end(depth - mid), target) {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    if best.is_none_or(|b| lo > b.0) {
                        best = Some((lo, way, from));
                    }
                }
                if best.is_some_and(|b| b.0 >= MIN_ADVANCE * h) {
                    break;
                }
            }
            let Some((adv, way, from)) = best.filter(|b| b.0 >= MIN_ADVANCE * h) else {
                break;
            };
            if from.distance(cur) > 1e-9 {
                path.push(Seg::line(cur, from));
                self.field.clear_capsule(cur, from, st.r);
                cur = from;
            }
            let to = if way < 2 {
                on_edge(way, depth - adv)
            } else {
                t - u * (depth - adv)
            };
            path.push(Seg::line(cur, to));
            self.field.clear_capsule(cur, to, st.r);
            cur = to;
            depth -= adv;
            if way < 2 {
                side = 1 - way;
            }
        }
        if self.feed_holds(cur, t, corner_rate) {
            path.push(Seg::line(cur, t));
            self.field.clear_capsule(cur, t, st.r);
            cur = t;
        }
        if path.is_empty() {
            return;
        }
        match (linked, self.cuts.last_mut()) {
            (Some(_), Some(_)) if link.is_some() => self.cuts.push(Cut {
                entry: CutEntry::Linked,
                path,
            }),
            (Some(_), Some(cut)) => cut.path.extend(path),
            _ => self.cuts.push(Cut {
                entry: CutEntry::Direct { from: q },
                path,
            }),
        }
        self.pos = Some(cur);
    }

    /// The point of the bisector nearest `t` (at most [`REACH_RADII`] away, `δ` apart) that
    /// the tool centre may stand at and that the tool reaches: by a clear link from where it
    /// is (returned with the point), or by feeding down there, its disc holding no material.
    fn reach_bisector(&mut self, t: Point, u: Vec2) -> Option<(Point, Option<Point>)> {
        let st = self.stepper;
        let h = self.field.h;
        let mut d = st.delta;
        while d <= REACH_RADII * st.r {
            let q = t - u * d;
            d += st.delta;
            if !st.walls.allows(self.field, q) {
                continue;
            }
            let linked = self
                .pos
                .filter(|&at| at.distance(q) < 1e-9 || self.link_clear(at, q, false));
            if linked.is_some() {
                return Some((q, linked));
            }
            let reach = st.r + DESCENT_CELLS * h;
            if !self.field.disc_holds_more_than(q, reach, 0)
                && st.walls.distance(self.field, q) >= st.walls.clear + DESCENT_CELLS * h
            {
                return Some((q, None));
            }
        }
        None
    }

    /// True when every position from `q` to `t` lies in the tool-centre region (to
    /// [`ON_EDGE`]) and its disc clear of the discs the field marked cleared but left to the
    /// walls' loops, and every step (at most `2h` long) removes at most `rate`
    /// mm² per mm of travel.
    fn feed_holds(&mut self, q: Point, t: Point, rate: f64) -> bool {
        let st = self.stepper;
        let h = self.field.h;
        let len = q.distance(t);
        let n = ((len / (2.0 * h)).ceil() as usize).max(1);
        let cap = rate * (len / n as f64) / (h * h) + NOISE_CELLS;
        self.field.record();
        let mut ok = true;
        for k in 1..=n {
            let p = q.lerp(t, k as f64 / n as f64);
            let inside = st.walls.distance(self.field, p) >= st.walls.clear - ON_EDGE
                && self.given_up.iter().all(|g| g.distance(p) >= 2.0 * st.r);
            if !inside || f64::from(self.field.clear_disc(p, st.r)) > cap {
                ok = false;
                break;
            }
        }
        self.field.undo();
        ok
    }
}

/// A corner of the tool-centre region to work into.
struct Corner {
    /// The corner.
    t: Point,
    /// The unit bisector, pointing into the corner.
    u: Vec2,
    /// Its edges' directions away from it.
    e: [Vec2; 2],
    /// Its interior angle, rad.
    alpha: f64,
}

/// The convex corners of `region` that turn by more than [`ACUTE_TURN`].
fn acute_corners(region: &OffsetRegion) -> Vec<Corner> {
    let mut out = Vec::new();
    for lp in region.loops() {
        let segs = segs_from_vertices(&closed_chain(lp));
        let n = segs.len();
        for (k, sg) in segs.iter().enumerate() {
            let next = &segs[(k + 1) % n];
            let (Some(t0), Some(t1)) = (
                sg.tangent_at(sg.length()).normalize(),
                next.tangent_at(0.0).normalize(),
            ) else {
                continue;
            };
            let turn = t0.cross(t1).atan2(t0.dot(t1));
            if turn <= ACUTE_TURN {
                continue;
            }
            let Some(u) = (t0 - t1).normalize() else {
                continue;
            };
            out.push(Corner {
                t: sg.b,
                u,
                e: [-t0, t1],
                alpha: std::f64::consts::PI - turn,
            });
        }
    }
    out
}
