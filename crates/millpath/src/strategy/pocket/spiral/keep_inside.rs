//! The spiral's sampled laps as moves, kept inside the last loop `B_ε` ([`super::common::last_loop`]).
//!
//! A lap blends the previous loop into the next one point by point; where the next one is
//! `B` (or near it) and `B` has a concave arc (round a corner of the wall pointing into the
//! pocket), the blend of two points on either side of the dent cuts across it: the tool
//! centre inside the wall's clearance, a gouge. [`keep_inside`] moves such samples onto
//! `B_ε`; [`lap_path`] then writes the samples as moves.
//!
//! Samples inside `B_ε` are not enough: a chord between two of them can still cross a
//! concave arc of `B_ε` (its sagitta `L²/8ρ` for a chord `L` on an arc of radius `ρ`), and a
//! moved stretch is where that happens, since projecting the samples of a chord that cuts
//! deep across a dent onto the arc round it spreads them far apart. So every chord is checked
//! against `T`, `B_ε` moved outward by ¾ of [`LAST_LOOP_MARGIN`] (so ¼ of it inside `B`),
//! with a segment index; a chord that crosses it is split at its midpoint (moved onto `B_ε`
//! if it lies outside), again until none does. Where that does not settle within
//! [`SPLIT_BUDGET`] splits (a chord across a thin wall spike: each midpoint lands on the side
//! of the spike nearer it, so the splits only creep towards the tip), the chord is replaced by the
//! way along `B_ε`: from its start's nearest point round to its end's, the shorter way.
//! With `--arcs`, each biarc fitted through the samples is checked against `T` in the same
//! way, and one that crosses it is written as the chords it spans.

use super::common::{ARC_TOLERANCE, LAST_LOOP_MARGIN};
use crate::geom::Point;
use crate::geom::region::offset_loops;
use crate::strategy::pocket::segments::{Seg, fit_arcs, fit_arcs_where, segs_from_points};
use crate::strategy::pocket::shape::{pt, reversed, v2};
use cavalier_contours::polyline::{
    PlineSegIntr, PlineSource, PlineVertex, Polyline, dist_from_segment_start, pline_seg_intr,
    seg_length,
};
use cavalier_contours::static_aabb2d_index::StaticAABB2DIndex;

/// The samples `pts` as moves, kept inside `b_eps` ([`keep_inside`], resampling at
/// `max_chord / 2` beside a moved sample, and splitting chords that leave it): G1 chords, or
/// with `arcs` tangent-continuous biarcs within [`ARC_TOLERANCE`] (times `scale`, the
/// tool's [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale), as the margin
/// [`LAST_LOOP_MARGIN`] of `b_eps`). A moved stretch has a kink
/// where it meets `B_ε`, and biarcs fitted through it overshoot by more than their tolerance
/// (18 µm found by the fuzzer): a path with moved samples or split chords is written as
/// chords. Elsewhere a biarc may still bulge past the samples by up to the tolerance, so each
/// one is checked against the guard's loop `T` like a chord, and one that crosses it is
/// written as the chords through the samples it spans ([`fit_arcs_where`]): on the fuzz
/// corpus, unchecked biarcs came up to 7.7 µm inside the wall's clearance.
pub(super) fn lap_path(
    pts: &[Point],
    b_eps: &Polyline<f64>,
    max_chord: f64,
    arcs: bool,
    scale: f64,
) -> Vec<Seg> {
    let margin = LAST_LOOP_MARGIN * scale;
    let guard = ChordGuard::new(b_eps, max_chord, margin);
    let (pts, moved) = keep_inside(pts, b_eps, max_chord, margin, guard.as_ref());
    if arcs && !moved {
        let tol = ARC_TOLERANCE * scale;
        let fitted = match &guard {
            Some(g) => fit_arcs_where(&pts, tol, |s| !g.crosses_seg(s)),
            None => Some(fit_arcs(&pts, tol)),
        };
        if let Some(path) = fitted {
            return path;
        }
    }
    segs_from_points(&pts)
}

/// Moves a sample more than half the margin (`margin`, [`LAST_LOOP_MARGIN`] for the tool)
/// outside `b_eps` onto its nearest point (`true`: moved). Samples on `B_ε` (the last lap
/// ends on it) or less than half the margin outside it are still well inside `B`: left
/// alone, so that a lap merely touching `B_ε` keeps its arcs.
fn project(b_eps: &Polyline<f64>, p: Point, margin: f64) -> (Point, bool) {
    if b_eps.winding_number(v2(p)) != 0 {
        return (p, false);
    }
    match b_eps.closest_point(v2(p), 1e-12) {
        Some(c) if c.distance > 0.5 * margin => (pt(c.seg_point), true),
        _ => (p, false),
    }
}

/// `pts` with every sample more than half `margin` outside `b_eps` moved onto its nearest
/// point ([`project_samples`]), then every chord that crosses the test loop `T` split
/// ([`ChordGuard`]). A path whose samples and chords never leave `B_ε` is returned unchanged,
/// with `false` (`true`: some moved or split).
fn keep_inside(
    pts: &[Point],
    b_eps: &Polyline<f64>,
    max_chord: f64,
    margin: f64,
    guard: Option<&ChordGuard<'_>>,
) -> (Vec<Point>, bool) {
    let (out, moved) = project_samples(pts, b_eps, max_chord, margin);
    match guard {
        Some(guard) => {
            let (out, split) = guard.split_chords(&out);
            (out, moved || split)
        }
        None => (out, moved),
    }
}

/// `pts` with every sample more than half `margin` outside `b_eps` moved onto its nearest
/// point ([`project`]), and the stretches next to a moved sample resampled at
/// `max_chord / 2` (each new sample moved in the same way); `true` if any was moved.
fn project_samples(
    pts: &[Point],
    b_eps: &Polyline<f64>,
    max_chord: f64,
    margin: f64,
) -> (Vec<Point>, bool) {
    let step = resample_step(max_chord);
    let mut out = Vec::with_capacity(pts.len());
    let mut prev: Option<(Point, bool)> = None;
    let mut any = false;
    for &p in pts {
        let (q, moved) = project(b_eps, p, margin);
        any |= moved;
        if let Some((a, a_moved)) = prev
            && (moved || a_moved)
        {
            let n = ((a.distance(p) / step).ceil() as usize).clamp(1, 10_000);
            for k in 1..n {
                out.push(project(b_eps, a + (p - a) * (k as f64 / n as f64), margin).0);
            }
        }
        out.push(q);
        prev = Some((p, moved));
    }
    (out, any)
}

/// Spacing of the samples [`keep_inside`] adds (beside a moved sample, on the arcs of a walk
/// along `B_ε`), mm: half the largest chord whose sagitta on a concave arc of `B_ε` stays
/// within the margin.
fn resample_step(max_chord: f64) -> f64 {
    0.5 * max_chord.max(1e-3)
}

/// Most midpoint splits of one chord before it is walked along `B_ε` instead
/// ([`ChordGuard::walk`]): a chord across a concave arc settles in a few (each split quarters
/// the sagitta), one across a thin spike of the wall never does.
const SPLIT_BUDGET: u32 = 64;

/// The chord check of [`keep_inside`]: `T`, `B_ε` moved outward by ¾ of the margin
/// ([`LAST_LOOP_MARGIN`] for the tool), and an index of its segments. Every sample is at most
/// half the margin outside `B_ε` (so at least ¼ of it inside `T`); a chord that stays inside
/// `T` stays at least ¼ of the margin inside `B`, clear of the wall's clearance.
struct ChordGuard<'a> {
    b_eps: &'a Polyline<f64>,
    t: Polyline<f64>,
    index: StaticAABB2DIndex<f64>,
    /// Sample spacing on the arcs of a walk along `B_ε`, mm.
    step: f64,
    /// The margin of `B_ε` inside `B`, mm.
    margin: f64,
}

impl<'a> ChordGuard<'a> {
    /// `None` if `T` is not one loop (chords then go unchecked, as samples are).
    fn new(b_eps: &'a Polyline<f64>, max_chord: f64, margin: f64) -> Option<Self> {
        let t = match offset_loops(b_eps, -0.75 * margin).as_slice() {
            [one] if one.vertex_count() >= 2 => one.clone(),
            _ => return None,
        };
        let index = t.create_aabb_index();
        Some(ChordGuard {
            b_eps,
            t,
            index,
            step: resample_step(max_chord),
            margin,
        })
    }

    /// Whether the chord `a → b` meets `T`.
    fn crosses(&self, a: Point, b: Point) -> bool {
        self.crosses_seg(&Seg::line(a, b))
    }

    /// Whether the line or arc `s` meets `T`.
    fn crosses_seg(&self, s: &Seg) -> bool {
        let n = self.t.vertex_count();
        let (v1, v2) = (
            PlineVertex::new(s.a.x, s.a.y, s.bulge()),
            PlineVertex::new(s.b.x, s.b.y, 0.0),
        );
        let (lo, hi) = seg_box(s);
        self.index.query_iter(lo.x, lo.y, hi.x, hi.y).any(|i| {
            let (u1, u2) = (self.t.at(i), self.t.at((i + 1) % n));
            !matches!(
                pline_seg_intr(v1, v2, u1, u2, 1e-9),
                PlineSegIntr::NoIntersect
            )
        })
    }

    /// `pts` with every chord that crosses `T` split at its midpoint (projected onto `B_ε`,
    /// [`project`]), recursively, or where that does not settle walked along `B_ε`; `true` if
    /// any chord was.
    fn split_chords(&self, pts: &[Point]) -> (Vec<Point>, bool) {
        let mut out = Vec::with_capacity(pts.len());
        let mut any = false;
        for (i, &p) in pts.iter().enumerate() {
            if let Some(&prev) = i.checked_sub(1).and_then(|j| pts.get(j)) {
                let mark = out.len();
                let mut budget = SPLIT_BUDGET;
                let settled = self.split(prev, p, &mut budget, &mut out);
                any |= !settled || out.len() > mark;
                if !settled && let Some(way) = self.walk(prev, p) {
                    out.truncate(mark);
                    // The walk's own chords run on `B_ε`; what still crosses (a concave arc
                    // sampled too coarsely) is split once more.
                    let mut a = prev;
                    for q in way.into_iter().chain(std::iter::once(p)) {
                        let mut budget = SPLIT_BUDGET;
                        self.split(a, q, &mut budget, &mut out);
                        if q != p {
                            out.push(q);
                        }
                        a = q;
                    }
                }
            }
            out.push(p);
        }
        (out, any)
    }

    /// Pushes points strictly between `a` and `b` that keep the chord inside `T`, splitting
    /// at most `budget` times; `false` if the budget ran out (or a split made no progress)
    /// with a piece still crossing.
    fn split(&self, a: Point, b: Point, budget: &mut u32, out: &mut Vec<Point>) -> bool {
        if a.distance(b) < 1e-9 || !self.crosses(a, b) {
            return true;
        }
        if *budget == 0 {
            return false;
        }
        *budget -= 1;
        let (m, _) = project(self.b_eps, a.midpoint(b), self.margin);
        if m.distance(a) < 1e-12 || m.distance(b) < 1e-12 {
            return false;
        }
        let left = self.split(a, m, budget, out);
        out.push(m);
        left && self.split(m, b, budget, out)
    }

    /// The way from `a` to `b` along `B_ε`, without its ends: `a`'s nearest point on `B_ε`,
    /// the vertices of `B_ε` from there to `b`'s nearest point the shorter way round (arcs
    /// sampled every `step`), and that point. `None` if a nearest point cannot be found.
    fn walk(&self, a: Point, b: Point) -> Option<Vec<Point>> {
        let ca = self.b_eps.closest_point(v2(a), 1e-12)?;
        let fwd = self
            .b_eps
            .rotate_start(ca.seg_start_index, ca.seg_point, 1e-9)?;
        let back = reversed(&fwd);
        let (w1, l1) = walk_to(&fwd, b, self.step)?;
        let (w2, l2) = walk_to(&back, b, self.step)?;
        let mut way = vec![pt(ca.seg_point)];
        way.extend(if l1 <= l2 { w1 } else { w2 });
        way.dedup_by(|p, q| p.distance(*q) < 1e-9);
        Some(way)
    }
}

/// A box holding the segment `s` (lower-left and upper-right corners): the chord's box, grown
/// by the arc's sagitta `r·(1 − cos(θ/2))` when its sweep `θ` is at most π (such an arc lies
/// over its chord, within the sagitta of it), or the whole circle's box.
fn seg_box(s: &Seg) -> (Point, Point) {
    let (lo, hi) = (
        Point::new(s.a.x.min(s.b.x), s.a.y.min(s.b.y)),
        Point::new(s.a.x.max(s.b.x), s.a.y.max(s.b.y)),
    );
    match s.arc {
        None => (lo, hi),
        Some(arc) if arc.sweep <= std::f64::consts::PI => {
            let g = arc.radius * (1.0 - (0.5 * arc.sweep).cos());
            (
                Point::new(lo.x - g, lo.y - g),
                Point::new(hi.x + g, hi.y + g),
            )
        }
        Some(arc) => {
            let (c, r) = (arc.center, arc.radius);
            (Point::new(c.x - r, c.y - r), Point::new(c.x + r, c.y + r))
        }
    }
}

/// The points of the closed loop `lp` from its start to the nearest point of `b` (its vertices,
/// arcs sampled every `step`, that point last), and the length of that way.
fn walk_to(lp: &Polyline<f64>, b: Point, step: f64) -> Option<(Vec<Point>, f64)> {
    let cb = lp.closest_point(v2(b), 1e-12)?;
    let n = lp.vertex_count();
    let mut way = Vec::new();
    let mut len = 0.0;
    for k in 0..=cb.seg_start_index.min(n.saturating_sub(1)) {
        let (v1, v2) = (lp.at(k), lp.at((k + 1) % n));
        let a = pt(v1.pos());
        let last = k == cb.seg_start_index;
        let end = if last {
            dist_from_segment_start(v1, v2, cb.seg_point, 1e-9)
        } else {
            seg_length(v1, v2)
        };
        if !v1.bulge_is_zero() {
            let sg = Seg::from_bulge(a, pt(v2.pos()), v1.bulge);
            let pieces = (end / step).ceil().clamp(1.0, 1e5) as usize;
            for i in 1..pieces {
                way.push(sg.point_at(end * i as f64 / pieces as f64));
            }
        }
        way.push(pt(if last { cb.seg_point } else { v2.pos() }));
        len += end;
    }
    Some((way, len))
}

#[cfg(test)]
mod tests {
    use super::*;
    use cavalier_contours::polyline::PlineSourceMut;

    /// A 10 × 10 square, counter-clockwise, whose top edge has a dent: a concave arc of
    /// radius 1.25 from (6, 10) to (4, 10) reaching down to y = 9.5.
    fn dented() -> Polyline<f64> {
        let mut pl = Polyline::new_closed();
        for (x, y, bulge) in [
            (0.0, 0.0, 0.0),
            (10.0, 0.0, 0.0),
            (10.0, 10.0, 0.0),
            (6.0, 10.0, -0.5),
            (4.0, 10.0, 0.0),
            (0.0, 10.0, 0.0),
        ] {
            pl.add(x, y, bulge);
        }
        pl
    }

    /// How far the chords of `pts` go outside `pl`, sampled 200 times per chord (a verifier
    /// apart from the chord test: winding number and closest point).
    fn deepest_outside(pl: &Polyline<f64>, pts: &[Point]) -> f64 {
        let mut worst: f64 = 0.0;
        for w in pts.windows(2) {
            for k in 0..=200 {
                let p = w[0] + (w[1] - w[0]) * (k as f64 / 200.0);
                if pl.winding_number(v2(p)) == 0
                    && let Some(c) = pl.closest_point(v2(p), 1e-12)
                {
                    worst = worst.max(c.distance);
                }
            }
        }
        worst
    }

    #[test]
    fn a_lap_across_a_dent_follows_it_within_the_margin() {
        let b = dented();
        // Samples 0.5 mm apart on a line just outside the top edge, 0.15 mm from the dent's
        // centre: projected onto the arc, samples 0.1 mm apart on the line land 0.8 mm apart.
        let pts: Vec<Point> = (0..=12)
            .map(|i| Point::new(8.0 - 0.5 * i as f64, 10.6))
            .collect();
        let (projected, moved) = project_samples(&pts, &b, 0.2, LAST_LOOP_MARGIN);
        assert!(moved);
        let deep = deepest_outside(&b, &projected);
        assert!(
            deep > 2.0 * LAST_LOOP_MARGIN,
            "the samples alone are not enough: {deep}"
        );
        let (out, moved) = keep_inside(
            &pts,
            &b,
            0.2,
            LAST_LOOP_MARGIN,
            ChordGuard::new(&b, 0.2, LAST_LOOP_MARGIN).as_ref(),
        );
        assert!(moved);
        let deep = deepest_outside(&b, &out);
        assert!(deep <= 0.75 * LAST_LOOP_MARGIN + 1e-9, "{deep}");
    }

    #[test]
    fn chords_across_the_arc_are_split_until_their_sagitta_is_within_the_margin() {
        let b = dented();
        // Two points on the arc, 1.6 mm apart: the chord's sagitta is 0.3 mm.
        let c = Point::new(5.0, 10.75);
        let on = |deg: f64| c + crate::geom::Vec2::from_angle(deg.to_radians()) * 1.25;
        let pts = [on(-90.0 - 40.0), on(-90.0 + 40.0)];
        assert!(deepest_outside(&b, &pts) > 0.1);
        let (out, moved) = keep_inside(
            &pts,
            &b,
            10.0,
            LAST_LOOP_MARGIN,
            ChordGuard::new(&b, 10.0, LAST_LOOP_MARGIN).as_ref(),
        );
        assert!(moved && out.len() > 2, "{out:?}");
        assert!(deepest_outside(&b, &out) <= 0.75 * LAST_LOOP_MARGIN + 1e-9);
        assert_eq!(out.first(), pts.first());
        assert_eq!(out.last(), pts.last());
    }

    /// A 20 × 20 square, counter-clockwise, with a thin spike of wall from its right side to
    /// (5, 10): 0.2 mm wide at the side.
    fn spiked() -> Polyline<f64> {
        let mut pl = Polyline::new_closed();
        for (x, y) in [
            (0.0, 0.0),
            (20.0, 0.0),
            (20.0, 9.9),
            (5.0, 10.0),
            (20.0, 10.1),
            (20.0, 20.0),
            (0.0, 20.0),
        ] {
            pl.add(x, y, 0.0);
        }
        pl
    }

    #[test]
    fn a_lap_across_a_thin_spike_goes_round_its_tip() {
        let b = spiked();
        // Samples 0.5 mm apart across the spike at x = 12: the two inside it are moved onto
        // its sides, and the chord between them runs through it.
        let pts: Vec<Point> = (0..=20)
            .map(|i| Point::new(12.0, 5.0 + 0.5 * i as f64))
            .collect();
        let (projected, _) = project_samples(&pts, &b, 0.2, LAST_LOOP_MARGIN);
        assert!(deepest_outside(&b, &projected) > 0.01);
        let (out, moved) = keep_inside(
            &pts,
            &b,
            0.2,
            LAST_LOOP_MARGIN,
            ChordGuard::new(&b, 0.2, LAST_LOOP_MARGIN).as_ref(),
        );
        assert!(moved);
        let deep = deepest_outside(&b, &out);
        assert!(deep <= 0.75 * LAST_LOOP_MARGIN + 1e-9, "{deep}");
        // Round the tip (the midpoint splits only creep towards it), not round the square.
        let min_x = out.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
        assert!((4.9..=5.1).contains(&min_x), "{min_x}");
        let len: f64 = out.windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!(len < 10.0 + 2.0 * 7.1, "{len}");
    }

    #[test]
    fn a_lap_well_inside_is_unchanged() {
        let b = dented();
        let pts: Vec<Point> = (0..40)
            .map(|i| {
                let t = i as f64 / 40.0 * std::f64::consts::TAU;
                Point::new(5.0 + 3.0 * t.cos(), 5.0 + 3.0 * t.sin())
            })
            .collect();
        let (out, moved) = keep_inside(
            &pts,
            &b,
            0.2,
            LAST_LOOP_MARGIN,
            ChordGuard::new(&b, 0.2, LAST_LOOP_MARGIN).as_ref(),
        );
        assert!(!moved);
        assert_eq!(out, pts);
    }

    #[test]
    fn a_segment_box_holds_its_arc() {
        let (a, b) = (Point::new(1.0, 0.5), Point::new(-2.0, 3.0));
        for bulge in [0.0, 0.4, -0.9, 1.0, 2.5, -6.0] {
            let s = Seg::from_bulge(a, b, bulge);
            let (lo, hi) = seg_box(&s);
            for k in 0..=200 {
                let p = s.point_at(s.length() * f64::from(k) / 200.0);
                assert!(p.x >= lo.x - 1e-12 && p.y >= lo.y - 1e-12, "{bulge}: {p:?}");
                assert!(p.x <= hi.x + 1e-12 && p.y <= hi.y + 1e-12, "{bulge}: {p:?}");
            }
        }
    }

    #[test]
    fn an_arc_bulging_across_the_dent_crosses_the_guard() {
        // The dent of `dented` reaches down to y = 9.5 between x = 4 and 6; its chord from
        // (3, 9.3) to (7, 9.3) passes under it, an arc through (5, 9.9) does not.
        let b = dented();
        let g = ChordGuard::new(&b, 0.2, LAST_LOOP_MARGIN).expect("one loop");
        let (p, q) = (Point::new(3.0, 9.3), Point::new(7.0, 9.3));
        assert!(!g.crosses(p, q));
        let sagitta = 0.6;
        let bulge = 2.0 * sagitta / p.distance(q);
        // A positive bulge turns left (counter-clockwise): below the chord, clear of the dent.
        assert!(!g.crosses_seg(&Seg::from_bulge(p, q, bulge)));
        assert!(g.crosses_seg(&Seg::from_bulge(p, q, -bulge)));
    }
}
