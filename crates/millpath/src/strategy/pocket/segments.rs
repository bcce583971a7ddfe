//! Planar paths of lines and exact arcs, as the strategies produce them.
//!
//! A [`Seg`] is a line or a circular arc between two points; an arc keeps its centre, radius,
//! direction and unsigned sweep so that sub-arcs (for ramps) stay exact. A bulge `b` between
//! `a` and `b` (cavalier_contours' convention) gives the sweep `θ = 4·atan(b)`; with the chord
//! `c = |b − a|`, the radius is `R = c / (2·sin(θ/2))` and the centre lies on the chord's
//! perpendicular bisector at signed distance `R·cos(θ/2)` towards the side the arc turns to.

use crate::geom::{Point, Vec2};

/// A line or an arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seg {
    /// Start point.
    pub a: Point,
    /// End point.
    pub b: Point,
    /// For an arc: its geometry.
    pub arc: Option<Arc>,
}

/// The circle part of an arc segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Centre.
    pub center: Point,
    /// Radius in mm.
    pub radius: f64,
    /// Counter-clockwise.
    pub ccw: bool,
    /// Unsigned sweep in rad, in (0, 2π].
    pub sweep: f64,
}

/// Arcs whose sagitta is at most this (mm) become lines in a pocket's toolpath (when
/// `levels` makes the moves of a plan, and when `feed` splits an arc): the G-code writer's
/// output rounding at its default 3 decimals in mm (`√2·½·10⁻³`, `gcode::rounding_error_mm`),
/// below which the writer writes an arc as a line anyway, so the path that is verified and
/// timed is the path that is written. The line departs from the arc by at most its sagitta
/// (a near-straight biarc along a slot's side, its centre 1.4 km away, was refused by the
/// planner).
pub const ARC_AS_LINE_SAGITTA: f64 = 0.5e-3 * std::f64::consts::SQRT_2;

/// Bulges below this magnitude are straight lines (sagitta below 1e-12 of the chord).
const BULGE_EPS: f64 = 1e-12;

impl Seg {
    /// A straight segment.
    pub fn line(a: Point, b: Point) -> Self {
        Seg { a, b, arc: None }
    }

    /// The segment from `a` to `b` with bulge `bulge`.
    pub fn from_bulge(a: Point, b: Point, bulge: f64) -> Self {
        let chord = b - a;
        let c = chord.length();
        if bulge.abs() < BULGE_EPS || c <= 0.0 {
            return Seg::line(a, b);
        }
        let theta = 4.0 * bulge.atan();
        let half = 0.5 * theta.abs();
        let radius = c / (2.0 * half.sin());
        let n = chord.perp() / c; // left normal
        let sign = if theta > 0.0 { 1.0 } else { -1.0 };
        let center = a.midpoint(b) + n * (sign * radius * half.cos());
        Seg {
            a,
            b,
            arc: Some(Arc {
                center,
                radius,
                ccw: theta > 0.0,
                sweep: theta.abs(),
            }),
        }
    }

    /// cavalier_contours' bulge of the segment: `tan(θ/4)` for the signed sweep `θ`
    /// (positive counter-clockwise), 0 for a line.
    pub fn bulge(&self) -> f64 {
        self.arc.map_or(0.0, |arc| {
            let t = (0.25 * arc.sweep).tan();
            if arc.ccw { t } else { -t }
        })
    }

    /// Length in mm.
    pub fn length(&self) -> f64 {
        match self.arc {
            None => self.a.distance(self.b),
            Some(arc) => arc.radius * arc.sweep,
        }
    }

    /// The point at arc length `t` from the start.
    pub fn point_at(&self, t: f64) -> Point {
        let len = self.length();
        let f = if len > 0.0 {
            (t / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        match self.arc {
            None => self.a.lerp(self.b, f),
            Some(arc) => {
                let a0 = (self.a - arc.center).angle();
                let s = if arc.ccw { 1.0 } else { -1.0 };
                arc.center + Vec2::from_angle(a0 + s * arc.sweep * f) * arc.radius
            }
        }
    }

    /// The point of the segment nearest to `p`: the foot of the perpendicular on a line, the
    /// radial projection on an arc where it falls within the sweep; else the nearer end.
    pub fn closest_point(&self, p: Point) -> Point {
        let nearer_end = || {
            if p.distance(self.a) <= p.distance(self.b) {
                self.a
            } else {
                self.b
            }
        };
        match self.arc {
            None => {
                let d = self.b - self.a;
                let l2 = d.length_squared();
                if l2 <= 0.0 {
                    return self.a;
                }
                self.a
                    .lerp(self.b, ((p - self.a).dot(d) / l2).clamp(0.0, 1.0))
            }
            Some(arc) => {
                let Some(u) = (p - arc.center).normalize() else {
                    return self.a;
                };
                let a0 = (self.a - arc.center).angle();
                let turn = if arc.ccw {
                    u.angle() - a0
                } else {
                    a0 - u.angle()
                };
                if turn.rem_euclid(std::f64::consts::TAU) <= arc.sweep {
                    arc.center + u * arc.radius
                } else {
                    nearer_end()
                }
            }
        }
    }

    /// Unit tangent at arc length `t` (zero for a degenerate segment).
    pub fn tangent_at(&self, t: f64) -> Vec2 {
        match self.arc {
            None => (self.b - self.a).normalize().unwrap_or(Vec2::new(0.0, 0.0)),
            Some(arc) => {
                let r = (self.point_at(t) - arc.center)
                    .normalize()
                    .unwrap_or(Vec2::new(1.0, 0.0));
                if arc.ccw { r.perp() } else { -r.perp() }
            }
        }
    }

    /// The first `t` mm of the segment.
    pub fn head(&self, t: f64) -> Seg {
        let b = self.point_at(t);
        let len = self.length();
        Seg {
            a: self.a,
            b,
            arc: self.arc.map(|arc| Arc {
                sweep: if len > 0.0 {
                    arc.sweep * (t / len).clamp(0.0, 1.0)
                } else {
                    0.0
                },
                ..arc
            }),
        }
    }

    /// The same segment run backwards.
    pub fn reversed(&self) -> Seg {
        Seg {
            a: self.b,
            b: self.a,
            arc: self.arc.map(|arc| Arc {
                ccw: !arc.ccw,
                ..arc
            }),
        }
    }
}

/// Segments of an open chain of `(point, bulge)` vertices (the last bulge is unused).
pub fn segs_from_vertices(v: &[(Point, f64)]) -> Vec<Seg> {
    v.windows(2)
        .filter(|w| w[0].0.distance(w[1].0) > 1e-12)
        .map(|w| Seg::from_bulge(w[0].0, w[1].0, w[0].1))
        .collect()
}

/// Straight segments through `points`, skipping repeated points.
pub fn segs_from_points(points: &[Point]) -> Vec<Seg> {
    points
        .windows(2)
        .filter(|w| w[0].distance(w[1]) > 1e-12)
        .map(|w| Seg::line(w[0], w[1]))
        .collect()
}

/// The path through `points` as tangent-continuous arcs (G2/G3): biarcs fitted within `tol`
/// to the open centripetal Catmull-Rom curve through the points ([`crate::curve::biarc`]).
/// Consecutive biarcs share their end tangents (the curve's), so the moves meet at tangent
/// angles of the fit's order (far below 1°); the curve itself is within about `h³κ'`
/// of the polyline for samples `h` apart on a smooth path (0.5 mm samples: microns).
pub fn fit_arcs(points: &[Point], tol: f64) -> Vec<Seg> {
    fit_arcs_where(points, tol, |_| true).unwrap_or_else(|| segs_from_points(points))
}

/// [`fit_arcs`], with every fitted segment that `keep` rejects replaced by the chords through
/// the samples it spans (from its start to the first sample after it, sample to sample, and
/// from the last one to its end): the path keeps its arcs wherever they pass, and is no
/// longer tangent-continuous only at the replaced stretches' ends. `None` if `keep` rejects
/// one of those chords as well.
pub fn fit_arcs_where(
    points: &[Point],
    tol: f64,
    keep: impl FnMut(&Seg) -> bool,
) -> Option<Vec<Seg>> {
    fit_arcs_span(points, tol, false, keep)
}

/// [`fit_arcs`] from the second point to the last but one: the first and the last point
/// only steer the curve's end tangents (points one sample before and after on the curves
/// the path joins make it leave and join them with their tangents, to the order of the
/// Catmull-Rom curve's, where the chords' own ends would be a half chord's turn off).
pub fn fit_arcs_inner(points: &[Point], tol: f64) -> Vec<Seg> {
    fit_arcs_span(points, tol, true, |_| true).unwrap_or_else(|| match points.len() {
        n if n > 2 => segs_from_points(&points[1..n - 1]),
        _ => Vec::new(),
    })
}

/// [`fit_arcs_where`], over the whole chain or (`inner`) without its first and last pieces.
fn fit_arcs_span(
    points: &[Point],
    tol: f64,
    inner: bool,
    mut keep: impl FnMut(&Seg) -> bool,
) -> Option<Vec<Seg>> {
    use crate::curve::biarc::fit;
    use crate::curve::catmull_rom::{OpenChain, open};
    // `open` drops the same repeated points; the curve passes through `p[k]` at parameter `k`.
    let mut p: Vec<Point> = Vec::with_capacity(points.len());
    for q in points {
        if p.last().is_none_or(|l| l.distance(*q) > 1e-9) {
            p.push(*q);
        }
    }
    let chain = OpenChain(open(&p));
    let n = chain.0.len();
    if inner && n < 3 {
        return None;
    }
    if n == 0 {
        return Some(segs_from_points(points));
    }
    let (lo, hi) = if inner {
        (1.0, (n - 1) as f64)
    } else {
        (0.0, n as f64)
    };
    let mut out = Vec::new();
    let mut s0 = lo;
    for a in fit(&chain, lo, hi, tol) {
        let s1 = a.s_end;
        let span = (s0, s1);
        s0 = s1;
        if a.start.distance(a.end) <= 1e-9 {
            continue;
        }
        // Nearly straight arcs (centres far away) become lines when their sagitta
        // `chord·|bulge|/2` is below a tenth of the tolerance: the tangent then turns
        // by about `8·sagitta/chord` at most (0.02° for a 10 mm chord).
        let bulge = (0.25 * a.sweep()).tan();
        let seg = if a.center.is_none() || 0.5 * a.start.distance(a.end) * bulge.abs() < 0.1 * tol {
            Seg::line(a.start, a.end)
        } else {
            Seg::from_bulge(a.start, a.end, bulge)
        };
        if keep(&seg) {
            out.push(seg);
            continue;
        }
        let inner = (span.0.floor() as usize + 1..)
            .take_while(|&k| (k as f64) < span.1 && k < p.len())
            .map(|k| p[k]);
        let mut from = a.start;
        for q in inner.chain(std::iter::once(a.end)) {
            if from.distance(q) > 1e-9 {
                let chord = Seg::line(from, q);
                if !keep(&chord) {
                    return None;
                }
                out.push(chord);
                from = q;
            }
        }
    }
    Some(out)
}

/// Total length of a path in mm.
pub fn path_length(path: &[Seg]) -> f64 {
    path.iter().map(Seg::length).sum()
}

/// The first `len` mm of `path` (all of it if shorter).
pub fn path_head(path: &[Seg], len: f64) -> Vec<Seg> {
    let mut out = Vec::new();
    let mut left = len;
    for s in path {
        if left <= 1e-12 {
            break;
        }
        let l = s.length();
        if l <= left {
            out.push(*s);
            left -= l;
        } else {
            out.push(s.head(left));
            break;
        }
    }
    out
}

/// `path` after its first `len` mm (none of it if shorter).
pub fn path_tail(path: &[Seg], len: f64) -> Vec<Seg> {
    let mut out = Vec::new();
    let mut left = len;
    for s in path {
        let l = s.length();
        if left >= l {
            left -= l;
            continue;
        }
        if left > 1e-12 {
            out.push(s.reversed().head(l - left).reversed());
            left = 0.0;
        } else {
            out.push(*s);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The closest point is the nearest of dense samples along lines and arcs (both
    /// directions, sweeps beyond a half turn), within the samples' spacing.
    #[test]
    fn closest_point_matches_dense_samples() {
        let segs = [
            Seg::line(Point::new(-3.0, 1.0), Point::new(4.0, -2.0)),
            Seg::from_bulge(Point::new(-5.0, 0.0), Point::new(5.0, 0.0), 1.0),
            Seg::from_bulge(Point::new(-5.0, 0.0), Point::new(5.0, 0.0), -2.5),
            Seg::from_bulge(Point::new(0.0, 3.0), Point::new(2.0, 1.0), 0.3).reversed(),
        ];
        let mut checked = 0;
        for s in &segs {
            let n = 20_000;
            let dense: Vec<Point> = (0..=n)
                .map(|k| s.point_at(s.length() * k as f64 / n as f64))
                .collect();
            for i in -8..=8 {
                for j in -8..=8 {
                    let p = Point::new(1.1 * i as f64, 0.9 * j as f64 + 0.05);
                    let c = s.closest_point(p);
                    let best = dense
                        .iter()
                        .map(|q| q.distance(p))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        (c.distance(p) - best).abs() < 2.0 * s.length() / n as f64,
                        "{s:?} {p:?}: {c:?} at {} vs {best}",
                        c.distance(p)
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 4 * 17 * 17);
    }

    #[test]
    fn bulge_one_is_a_half_circle() {
        let s = Seg::from_bulge(Point::new(-5.0, 0.0), Point::new(5.0, 0.0), 1.0);
        let arc = s.arc.unwrap();
        assert!(arc.center.distance(Point::ORIGIN) < 1e-12);
        assert!((arc.radius - 5.0).abs() < 1e-12 && arc.ccw);
        assert!((s.length() - 5.0 * PI).abs() < 1e-9);
        // Counter-clockwise from (-5, 0) passes through (0, -5).
        assert!(s.point_at(s.length() * 0.5).distance(Point::new(0.0, -5.0)) < 1e-9);
        let h = s.head(s.length() * 0.5);
        assert!((h.length() - 2.5 * PI).abs() < 1e-9);
        let r = s.reversed();
        assert!(r.point_at(r.length() * 0.5).distance(Point::new(0.0, -5.0)) < 1e-9);
    }

    /// 33 samples of a half circle of radius 10 above the x axis, from (10, 0) to (−10, 0).
    fn half_circle() -> Vec<Point> {
        (0..=32)
            .map(|k| {
                let a = PI * f64::from(k) / 32.0;
                Point::new(10.0 * a.cos(), 10.0 * a.sin())
            })
            .collect()
    }

    #[test]
    fn rejected_arcs_become_the_chords_through_their_samples() {
        let pts = half_circle();
        let all = fit_arcs(&pts, 0.004);
        assert!(all.iter().all(|s| s.arc.is_some()), "{all:?}");
        // Reject what reaches left of x = 0: those stretches become chords through samples.
        let path = fit_arcs_where(&pts, 0.004, |s| s.arc.is_none() || s.a.x.min(s.b.x) > 0.0)
            .expect("chords pass");
        let (arcs, lines): (Vec<Seg>, Vec<Seg>) = path.iter().partition(|s| s.arc.is_some());
        assert!(!arcs.is_empty() && !lines.is_empty());
        assert!(arcs.iter().all(|s| s.a.x.min(s.b.x) > 0.0));
        // Still one connected path from the first sample to the last.
        assert_eq!(path[0].a, pts[0]);
        assert!(path.last().expect("moves").b.distance(pts[32]) < 1e-9);
        assert!(path.windows(2).all(|w| w[0].b.distance(w[1].a) < 1e-12));
        // Every sample left of x = 0 is a chord's end.
        for p in pts.iter().filter(|p| p.x < -1e-9) {
            assert!(lines.iter().any(|s| s.b.distance(*p) < 1e-12), "{p:?}");
        }
        // Rejecting chords as well: no path.
        assert!(fit_arcs_where(&pts, 0.004, |_| false).is_none());
    }

    #[test]
    fn bulge_round_trips() {
        for b in [-1.5, -0.3, 0.2, 1.0] {
            let s = Seg::from_bulge(Point::new(1.0, 2.0), Point::new(4.0, -1.0), b);
            assert!((s.bulge() - b).abs() < 1e-12, "{b}: {}", s.bulge());
        }
        assert!(Seg::line(Point::ORIGIN, Point::new(1.0, 0.0)).bulge().abs() < 1e-300);
    }
}
