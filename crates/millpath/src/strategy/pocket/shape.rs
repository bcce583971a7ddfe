//! The pocket region: an outer outline and islands, and its offsets in tool-centre space.
//!
//! The tool centre must stay at least `r + wall stock` from the outline and the islands, so
//! every strategy works inside the *boundary offset*: the outer loop offset inward by
//! `d = r + stock` and the islands outward by the same `d` (cavalier_contours' shape offset,
//! exact arcs). Its loops are where the last pass runs.

use super::offset_check::{first_misplaced, probes};
use crate::error::InputError;
use crate::geom::{Outline, Point, Winding};
use cavalier_contours::core::math::Vector2;
use cavalier_contours::polyline::{
    PlineSource, PlineSourceMut, PlineVertex, Polyline, seg_closest_point, seg_midpoint,
};
use cavalier_contours::shape_algorithms::{Shape, ShapeOffsetOptions};
use cavalier_contours::static_aabb2d_index::{Control, NeighborPriorityQueue, StaticAABB2DIndex};
use std::cell::RefCell;

/// How the walls run from the top outline (z = 0) down to the floor.
#[derive(Debug, Clone, Default)]
pub enum Walls {
    /// Vertical walls: every level is cut in the top outline.
    #[default]
    Vertical,
    /// Every wall leans into the pocket by this angle from the vertical, rad, in `[0, π/2)`.
    Draft(f64),
    /// The outline and islands at the pocket's depth, vertex for vertex like the top.
    Bottom {
        /// Bottom outer outline, counter-clockwise.
        outer: Outline,
        /// Bottom islands, clockwise, in the order of the top's.
        islands: Vec<Outline>,
    },
}

/// A pocket: an outer outline (counter-clockwise) and islands (clockwise) strictly inside it,
/// as they are at the top of the stock (z = 0), and how the walls run down from there.
#[derive(Debug, Clone)]
pub struct PocketShape {
    /// The outer outline, counter-clockwise.
    pub outer: Outline,
    /// Islands, clockwise, strictly inside the outer outline and apart from each other.
    pub islands: Vec<Outline>,
    /// Vertical, drafted, or interpolated to a bottom outline (see `super::walls`).
    pub walls: Walls,
}

impl PocketShape {
    /// A pocket from an outer outline and islands, in any winding; `origin` names the source.
    /// Islands must lie strictly inside the outer outline and must not touch it or each other
    /// (`crate::geom::region::validate_islands`). The walls are vertical.
    pub fn new(outer: Outline, islands: Vec<Outline>, origin: &str) -> Result<Self, InputError> {
        let (outer, islands) = crate::geom::region::validate_islands(outer, islands, origin)?;
        Ok(PocketShape {
            outer,
            islands,
            walls: Walls::Vertical,
        })
    }

    /// A pocket without islands.
    pub fn simple(outer: Outline) -> Self {
        PocketShape {
            outer: outer.with_winding(Winding::CounterClockwise),
            islands: Vec::new(),
            walls: Walls::Vertical,
        }
    }

    /// All loops: the outer first, then the islands.
    pub fn loops(&self) -> impl Iterator<Item = &Outline> {
        std::iter::once(&self.outer).chain(self.islands.iter())
    }

    /// True when `p` is in the material region (inside the outer, outside every island).
    pub fn contains(&self, p: Point) -> bool {
        self.outer.contains(p) && self.islands.iter().all(|i| !i.contains(p))
    }

    /// Distance from `p` to the nearest loop.
    pub fn distance_to(&self, p: Point) -> f64 {
        self.loops()
            .map(|o| o.distance_to(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The region where the tool centre may go at offset `d` (> 0): counter-clockwise outer
    /// loops and clockwise island loops, possibly several regions.
    ///
    /// Always cavalier_contours' shape offset (`Shape::parallel_offset`), with or without
    /// islands. Its single-polyline offset (`Polyline::parallel_offset`) returned nothing, or
    /// a part, for whole ranges of distances on some outlines whose offsets exist: on the fuzz
    /// corpus's `85f0730c…` (a 4,646 mm² outline with three nearly collinear vertices
    /// 0.02–0.06 mm apart) every offset from 9 to 24.5 mm came back empty, so the loops of
    /// `offset` and the spiral stopped at 8.5 mm and 6,438 mm² stayed uncut (2026-11-25,
    /// `hostile_corpus::uncut_over_the_corpus`); the shape offset gives 2,378 mm² at 9 mm, as
    /// the areas around it say it should. (Falling back to the shape offset only where the
    /// single one came back empty left `23c6f060…` and `d976c0b9…` 1,656 and 1,286 mm²
    /// uncut: there it returned a part.)
    ///
    /// **Checked.** Every loop of the result must lie at `d` from the walls (within
    /// `OFFSET_TOLERANCE`, at the ends and middle of each of its segments): the shape
    /// offset, too, drops pieces on some outlines. On the fuzz corpus's `250d691f…` (a wedge
    /// spike with 3 µm edges at its root) the loop at `r` cut a convex corner of the wall
    /// 0.16 mm deep; on `57cf7b3e…` and `c2ebea30…` loops ran 0.25–0.66 mm into the walls,
    /// and the programs were refused as gouging. All three come from the offset's default
    /// fuzzy epsilons (1e-4 mm to join and validate slices) on outlines with features of a
    /// few micrometres; with epsilons 100× finer the same offset is exact on all of them.
    /// Where the first result fails, the offset is computed again with epsilons 1e-6 and
    /// 1e-8 mm, then in two steps (erosion composes: `(X ⊖ B_a) ⊖ B_b = X ⊖ B_{a+b}`) at
    /// splits 1/2, 1/3 and 2/3, then at distances a hair larger (1 µm, 10 µm: never closer to
    /// the walls); the first faithful result is taken. Faithful also means complete: a result
    /// must hold the points every offset by `d` holds and leave out the walls
    /// (`offset_check`), or a region whose loops all come back empty, or one missing an
    /// island's loop, passes. If none is faithful, the largest result whose loops
    /// lie at `d` stands (else the first), and the verification of the toolpath refuses what
    /// it would gouge or leave.
    pub(crate) fn offset(&self, d: f64) -> OffsetRegion {
        let walls: Vec<&Polyline<f64>> = self.loops().map(|o| o.polyline()).collect();
        checked_offset(&walls, d)
    }

    /// The loops of the region offset by `d` (as `offset` computes it, checked against the
    /// walls): counter-clockwise outer loops, then clockwise islands; none when nothing is
    /// left.
    pub fn offset_loops(&self, d: f64) -> Vec<Outline> {
        let r = self.offset(d);
        r.outers
            .into_iter()
            .chain(r.islands)
            .map(Outline::wrap_offset)
            .collect()
    }
}

/// The offset of the region bounded by `walls` (counter-clockwise outer loops, clockwise
/// islands) by `d` (inwards; negative: outwards), checked as [`PocketShape::offset`] says:
/// cavalier_contours' shape offset with its default epsilons and with epsilons 1e-6 mm, the
/// larger region of those that are faithful — all their loops lie at `|d|` from the walls,
/// they hold every point the offset must hold and none of the walls (`offset_check`: a
/// result that misses a loop is smaller: on `c3df108e…` the default offset at the tool radius was empty where the
/// finer one has 6.7 mm²; on `bc4af3dc…` each of the two misses a loop the other has at some
/// distance; on a real drawing's pocket both returned loops of no area for the whole region
/// at 17.4 mm); where neither is faithful, epsilons 1e-8 mm, two steps, a hair farther out.
/// Where nothing is faithful, the largest result whose loops all lie at `|d|` (it misses a
/// part, which the toolpath's verification then measures); the default result where no
/// loop set is even that.
pub fn checked_offset(walls: &[&Polyline<f64>], d: f64) -> OffsetRegion {
    let plines = || walls.iter().map(|p| (*p).clone());
    let coarse = ShapeOffsetOptions::default();
    let first = shape_offset(plines(), d, &coarse);
    if d == 0.0 || !d.is_finite() {
        return first;
    }
    let index: Vec<IndexedLoop<'_>> = walls.iter().map(|p| IndexedLoop::new(p)).collect();
    let dist = |p: Point| {
        index
            .iter()
            .map(|i| i.distance(p))
            .fold(f64::INFINITY, f64::min)
    };
    let on_level = |reg: &OffsetRegion, d: f64| {
        reg.loops()
            .all(|l| loop_checkpoints(l).all(|p| (dist(p) - d.abs()).abs() <= OFFSET_TOLERANCE))
    };
    // The points a faithful offset by `d` holds and those it does not, found once (a hair
    // farther out places them alike).
    let probes = probes(walls, d, dist);
    let complete =
        |reg: &OffsetRegion| first_misplaced(&reg.outers, &reg.islands, &probes).is_none();
    let mut partial: Option<OffsetRegion> = None;
    let mut faithful = |reg: &OffsetRegion, d: f64| {
        if !on_level(reg, d) {
            return false;
        }
        if complete(reg) {
            return true;
        }
        if partial.as_ref().is_none_or(|p| p.area() < reg.area()) {
            partial = Some(reg.clone());
        }
        false
    };
    let fine = |eps: f64| ShapeOffsetOptions {
        pos_equal_eps: 0.1 * eps,
        offset_dist_eps: eps,
        slice_join_eps: eps,
    };
    let finer = shape_offset(plines(), d, &fine(1e-6));
    let best = [first.clone(), finer]
        .into_iter()
        .filter(|r| faithful(r, d))
        .max_by(|a, b| a.area().total_cmp(&b.area()));
    if let Some(best) = best {
        return best;
    }
    let again = shape_offset(plines(), d, &fine(1e-8));
    if faithful(&again, d) {
        return again;
    }
    for split in [0.5, 1.0 / 3.0, 2.0 / 3.0] {
        let part = shape_offset(plines(), split * d, &coarse);
        let two = shape_offset(part.loops().cloned(), (1.0 - split) * d, &coarse);
        if faithful(&two, d) {
            return two;
        }
    }
    for extra in [1e-6_f64, 1e-5] {
        let more = d + extra.copysign(d);
        let far = shape_offset(plines(), more, &coarse);
        if faithful(&far, more) {
            return far;
        }
    }
    partial.unwrap_or(first)
}

/// How far from `d` a loop of [`PocketShape::offset`] may lie from the walls, mm (the shape
/// offset is exact to nanometres where it is right; its failures are tenths of a millimetre).
pub const OFFSET_TOLERANCE: f64 = 1e-4;

/// cavalier_contours' shape offset of the loops `plines` by `d` (inwards for counter-clockwise
/// loops, outwards for clockwise ones). With the finer epsilons the offset can panic inside
/// cavalier_contours ("expect non-empty polyline" when a slice it stitched is empty: found by
/// the strict `pocket` fuzz run of 2026-11-25): such a result counts as none (empty, and not
/// faithful to a region that has loops).
fn shape_offset(
    plines: impl Iterator<Item = Polyline<f64>>,
    d: f64,
    opts: &ShapeOffsetOptions<f64>,
) -> OffsetRegion {
    let plines: Vec<Polyline<f64>> = plines.collect();
    let run = std::panic::AssertUnwindSafe(|| {
        let shape = Shape::from_plines(plines.iter().cloned());
        shape.parallel_offset(d, opts)
    });
    let Ok(off) = std::panic::catch_unwind(run) else {
        return OffsetRegion::default();
    };
    OffsetRegion {
        outers: off
            .ccw_plines
            .into_iter()
            .filter_map(|p| crate::geom::region::closed_loop(p.polyline))
            .filter(|p| p.vertex_count() > 1 && p.area() > 0.0)
            .collect(),
        islands: off
            .cw_plines
            .into_iter()
            .filter_map(|p| crate::geom::region::closed_loop(p.polyline))
            .collect(),
    }
}

/// The start and middle of every segment of the closed loop `pl`.
fn loop_checkpoints(pl: &Polyline<f64>) -> impl Iterator<Item = Point> + '_ {
    let n = pl.vertex_count();
    (0..n).flat_map(move |i| {
        let (a, b) = (pl.at(i), pl.at((i + 1) % n));
        [pt(a.pos()), pt(seg_midpoint(a, b))]
    })
}

/// The loops of an offset region.
#[derive(Debug, Clone, Default)]
pub struct OffsetRegion {
    /// Counter-clockwise outer loops.
    pub outers: Vec<Polyline<f64>>,
    /// Clockwise island loops.
    pub islands: Vec<Polyline<f64>>,
}

impl OffsetRegion {
    /// True when nothing is left.
    pub fn is_empty(&self) -> bool {
        self.outers.is_empty()
    }

    /// Every loop.
    pub fn loops(&self) -> impl Iterator<Item = &Polyline<f64>> {
        self.outers.iter().chain(self.islands.iter())
    }

    /// The region's area, mm² (outer loops less islands).
    pub fn area(&self) -> f64 {
        self.outers.iter().map(|p| p.area().abs()).sum::<f64>()
            - self.islands.iter().map(|p| p.area().abs()).sum::<f64>()
    }
}

/// A point as a cavalier vector.
pub fn v2(p: Point) -> Vector2<f64> {
    Vector2::new(p.x, p.y)
}

/// A cavalier vector as a point.
pub fn pt(v: Vector2<f64>) -> Point {
    Point::new(v.x, v.y)
}

/// Distance from `p` to the loop `pl`.
pub fn loop_distance(pl: &Polyline<f64>, p: Point) -> f64 {
    pl.closest_point(v2(p), 1e-12)
        .map_or(f64::INFINITY, |c| c.distance)
}

/// A loop with a spatial index of its segments (cavalier_contours' `StaticAABB2DIndex`, exact
/// segment boxes): the same distance as [`loop_distance`], visiting only the segments whose
/// boxes are nearer than the best distance found so far (about `O(log n)` instead of `O(n)`
/// per query). For the many queries against one loop of the spiral's morph.
#[derive(Debug)]
pub struct IndexedLoop<'a> {
    pl: &'a Polyline<f64>,
    index: StaticAABB2DIndex<f64>,
    queue: RefCell<NeighborPriorityQueue<f64>>,
}

impl<'a> IndexedLoop<'a> {
    /// Indexes the segments of `pl` (closed or open).
    pub fn new(pl: &'a Polyline<f64>) -> Self {
        IndexedLoop {
            pl,
            index: pl.create_aabb_index(),
            queue: RefCell::new(NeighborPriorityQueue::new()),
        }
    }

    /// Distance from `p` to the loop (infinite for a loop without segments).
    pub fn distance(&self, p: Point) -> f64 {
        let n = self.pl.vertex_count();
        let mut best = f64::INFINITY;
        let q = v2(p);
        if n <= BRUTE_FORCE_SEGMENTS {
            // A few segments: visiting each is faster than the index's priority queue.
            for i in 0..n {
                let c = seg_closest_point(self.pl.at(i), self.pl.at((i + 1) % n), q, 1e-12);
                best = best.min((c - q).length());
            }
            return best;
        }
        let mut visit = |i: usize, box_d2: f64| -> Control<()> {
            if box_d2 > best * best {
                return Control::Break(());
            }
            let (a, b) = (self.pl.at(i), self.pl.at((i + 1) % n));
            let c = seg_closest_point(a, b, q, 1e-12);
            best = best.min((c - q).length());
            Control::Continue
        };
        if n >= 2 {
            // The queue is cleared by the query; kept to save an allocation per query.
            let mut queue = self.queue.borrow_mut();
            self.index
                .visit_neighbors_with_queue(p.x, p.y, &mut visit, &mut queue);
        }
        best
    }
}

/// Loops of at most this many segments are searched segment by segment.
const BRUTE_FORCE_SEGMENTS: usize = 48;

/// The closed loop `pl` restarted at its point nearest to `p` (split there if needed).
pub fn restart_near(pl: &Polyline<f64>, p: Point) -> Polyline<f64> {
    match pl.closest_point(v2(p), 1e-12) {
        Some(c) => pl
            .rotate_start(c.seg_start_index, c.seg_point, 1e-9)
            .unwrap_or_else(|| pl.clone()),
        None => pl.clone(),
    }
}

/// The vertices of a closed loop as an open chain that returns to its start.
pub fn closed_chain(pl: &Polyline<f64>) -> Vec<(Point, f64)> {
    let mut v: Vec<(Point, f64)> = pl
        .iter_vertexes()
        .map(|v: PlineVertex<f64>| (Point::new(v.x, v.y), v.bulge))
        .collect();
    if let Some(&(p0, _)) = v.first() {
        v.push((p0, 0.0));
    }
    v
}

/// The loop reversed (same geometry, the other direction).
pub fn reversed(pl: &Polyline<f64>) -> Polyline<f64> {
    let mut r = pl.clone();
    r.invert_direction_mut();
    r
}

/// A point of largest distance to the region's loops among a grid of about `n × n` points
/// inside `outer` and outside `islands`, and that distance: an approximation of the centre of
/// the largest inscribed circle, good to the grid spacing.
pub fn inscribed_centre(
    outer: &Polyline<f64>,
    islands: &[Polyline<f64>],
    n: usize,
) -> (Point, f64) {
    let Some(e) = outer.extents() else {
        return (Point::ORIGIN, 0.0);
    };
    let mut best = (
        Point::new(0.5 * (e.min_x + e.max_x), 0.5 * (e.min_y + e.max_y)),
        0.0,
    );
    let n = n.max(2);
    let dist = |p: Point| {
        islands
            .iter()
            .map(|i| loop_distance(i, p))
            .fold(loop_distance(outer, p), f64::min)
    };
    let inside = |p: Point| {
        outer.winding_number(v2(p)) != 0 && islands.iter().all(|i| i.winding_number(v2(p)) == 0)
    };
    let mut step = (
        (e.max_x - e.min_x) / n as f64,
        (e.max_y - e.min_y) / n as f64,
    );
    for i in 0..=n {
        for j in 0..=n {
            let p = Point::new(e.min_x + step.0 * i as f64, e.min_y + step.1 * j as f64);
            if inside(p) {
                let d = dist(p);
                if d > best.1 {
                    best = (p, d);
                }
            }
        }
    }
    // Refine by pattern search around the best grid point.
    for _ in 0..30 {
        step = (step.0 * 0.5, step.1 * 0.5);
        let c = best.0;
        for (dx, dy) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
            let p = Point::new(c.x + dx * step.0, c.y + dy * step.1);
            if inside(p) {
                let d = dist(p);
                if d > best.1 {
                    best = (p, d);
                }
            }
        }
    }
    best
}

/// True when the segment `a–b` leaves `region` (touching a loop, or running along one, is
/// inside).
///
/// The loops' crossings with the segment (points, and the ends of stretches where it runs
/// along a loop) cut it into pieces; each piece is wholly inside the region or wholly
/// outside, and its midpoint says which. Testing only for crossings away from the ends and
/// then the segment's midpoint missed a link running along one loop's edge, across a pinched
/// neck of the region and along the other loop's edge (the zigzag's link between two pieces of
/// a fuzz pocket's region, 0.017 mm into the wall stock: `fuzz/regressions/pocket-link`).
/// The loops' vertices within `NEAR_VERTEX` of the segment cut it too: the intersection's
/// fuzzy epsilon drops a crossing at a vertex the segment passes a hair from (a link 2e-7 mm
/// inside a straight wall, leaving the region at the vertex where the wall meets an island's
/// arc, 1.76 mm deep across the island's clearance: `ma_Part.dxf`, 50 mm tool).
pub fn crosses(region: &OffsetRegion, a: Point, b: Point) -> bool {
    let d = b - a;
    let len2 = d.dot(d);
    if len2 < 1e-18 {
        return false;
    }
    let mut seg = Polyline::new();
    seg.add(a.x, a.y, 0.0);
    seg.add(b.x, b.y, 0.0);
    let at = |p: Vector2<f64>| ((pt(p) - a).dot(d) / len2).clamp(0.0, 1.0);
    let mut ts = vec![0.0, 1.0];
    for l in region.loops() {
        let hits = l.find_intersects(&seg);
        ts.extend(hits.basic_intersects.iter().map(|i| at(i.point)));
        for o in &hits.overlapping_intersects {
            ts.push(at(o.point1));
            ts.push(at(o.point2));
        }
        for k in 0..l.vertex_count() {
            let v = pt(l.at(k).pos());
            let t = (v - a).dot(d) / len2;
            if (0.0..=1.0).contains(&t) && (a + d * t).distance(v) <= NEAR_VERTEX {
                ts.push(t);
            }
        }
    }
    ts.sort_by(f64::total_cmp);
    let min_piece = 1e-7 / len2.sqrt();
    ts.windows(2)
        .filter(|w| w[1] - w[0] > min_piece)
        .any(|w| !inside_or_on(region, a + d * (0.5 * (w[0] + w[1]))))
}

/// A loop vertex this near a segment splits it in [`crosses`], mm.
const NEAR_VERTEX: f64 = 1e-5;

/// `p` is inside `region` or within 1e-7 mm of one of its loops.
fn inside_or_on(region: &OffsetRegion, p: Point) -> bool {
    let inside = region.outers.iter().any(|o| o.winding_number(v2(p)) != 0)
        && region.islands.iter().all(|i| i.winding_number(v2(p)) == 0);
    inside
        || region.loops().any(|l| {
            l.closest_point(v2(p), 1e-12)
                .is_some_and(|c| c.distance < 1e-7)
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The indexed distance is the brute-force one, on a loop with arcs (a rounded rectangle's
    /// offset) and on a jagged polygon, at points inside, outside and on the loops.
    #[test]
    fn indexed_distance_matches_brute_force() {
        // The sample part's rounded rectangle (120 × 80, corner radius 8).
        let (_, outline) = super::super::builtin::structural_part().swap_remove(0);
        let region = outline.offset(3.0);
        let arcs = region.outers[0].clone();
        assert!(
            arcs.iter_vertexes().any(|v| v.bulge != 0.0),
            "test loop has arcs"
        );
        let mut jagged = Polyline::new_closed();
        for i in 0..97 {
            let a = std::f64::consts::TAU * i as f64 / 97.0;
            let r = 20.0 + 7.0 * ((i * 37 % 11) as f64);
            jagged.add(r * a.cos(), r * a.sin(), 0.0);
        }
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for pl in [&arcs, &jagged] {
            let idx = IndexedLoop::new(pl);
            let mut worst: f64 = 0.0;
            for k in 0..2000 {
                let p = if k % 10 == 0 {
                    let v = pl.at(k % pl.vertex_count());
                    Point::new(v.x, v.y)
                } else {
                    Point::new(200.0 * next() - 60.0, 180.0 * next() - 70.0)
                };
                worst = worst.max((idx.distance(p) - loop_distance(pl, p)).abs());
            }
            assert!(
                worst < 1e-9,
                "indexed and brute-force distances differ by {worst}"
            );
        }
    }
}

#[cfg(test)]
mod crosses_tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polyline<f64> {
        let mut pl = Polyline::new_closed();
        for (x, y) in [(x0, y0), (x1, y0), (x1, y1), (x0, y1)] {
            pl.add(x, y, 0.0);
        }
        pl
    }

    /// Two pieces of a region whose bottom edges lie on one line, 1 mm apart (a region
    /// pinched off at a neck along a straight wall).
    fn two_pieces() -> OffsetRegion {
        OffsetRegion {
            outers: vec![rect(0.0, 0.0, 3.0, 1.0), rect(4.0, 0.0, 5.0, 1.0)],
            islands: Vec::new(),
        }
    }

    #[test]
    fn a_link_along_both_pieces_edges_across_the_gap_leaves_the_region() {
        let r = two_pieces();
        // The midpoint (2.25, 0) lies on the first piece's edge: the old midpoint test passed
        // this link, which runs outside from x = 3 to x = 4.
        let (a, b) = (Point::new(0.0, 0.0), Point::new(4.5, 0.0));
        assert!(crosses(&r, a, b));
        assert!(crosses(&r, b, a));
    }

    /// `ma_Part.dxf` (450 × 200 mm, nine 30 mm circles) at a 50 mm tool: a link 2e-7 mm
    /// inside the region's top wall leaves it where the wall meets an island's arc, crosses
    /// the island's clearance (1.76 mm deep at x = 103) and ends in a sliver of the region
    /// between two islands. The intersection drops the crossing at that vertex.
    #[test]
    fn a_link_a_hair_inside_a_wall_past_an_islands_arc_leaves_the_region() {
        let p = |x: f64, y: f64| Point::new(x, y);
        let rect = Outline::new(
            &[
                (p(-225.0, -100.0), 0.0),
                (p(225.0, -100.0), 0.0),
                (p(225.0, 100.0), 0.0),
                (p(-225.0, 100.0), 0.0),
            ],
            "rectangle",
        )
        .expect("rectangle");
        let yc = 36.760_393_530_130_39;
        let centres = [
            (-112.5, 0.0),
            (175.0, yc),
            (139.0, yc),
            (103.0, yc),
            (83.0, 0.0),
            (119.0, 0.0),
            (155.0, 0.0),
            (-25.0, 75.0),
            (25.0, 75.0),
        ];
        let islands: Vec<Outline> = centres
            .iter()
            .map(|&(x, y)| {
                Outline::new(&[(p(x - 15.0, y), 1.0), (p(x + 15.0, y), 1.0)], "circle")
                    .expect("circle")
            })
            .collect();
        let shape = PocketShape::new(rect, islands, "ma_Part").expect("shape");
        let region = shape.offset(25.0);
        let y = 75.0 - 2e-7;
        let (a, b) = (p(65.0, y), p(127.264_050_429_328_26, y));
        // The independent measure: the link's middle is 1.76 mm inside the island's clearance.
        assert!(shape.distance_to(p(103.0, y)) < 25.0 - 1.7);
        assert!(crosses(&region, a, b));
        assert!(crosses(&region, b, a));
        // Along the wall up to the arc, it stays inside.
        assert!(!crosses(&region, a, p(91.0, y)));
    }

    #[test]
    fn links_inside_or_along_an_edge_do_not_cross() {
        let r = two_pieces();
        let p = |x, y| Point::new(x, y);
        assert!(!crosses(&r, p(0.5, 0.0), p(2.5, 0.0)), "along an edge");
        assert!(
            !crosses(&r, p(0.0, 0.0), p(3.0, 1.0)),
            "a diagonal, corner to corner"
        );
        assert!(!crosses(&r, p(0.5, 0.5), p(2.5, 0.5)), "inside");
        assert!(!crosses(&r, p(1.0, 1.0), p(1.0, 1.0)), "no length");
        assert!(
            crosses(&r, p(2.5, 0.5), p(4.5, 0.5)),
            "from one piece into the other"
        );
        assert!(crosses(&r, p(2.5, 0.5), p(3.5, 0.5)), "out of the region");
    }
}
