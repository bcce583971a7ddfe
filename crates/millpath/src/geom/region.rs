//! Planar regions: an outer outline with islands, validated once for every importer and
//! every strategy; and the region's principal frame.
//!
//! # Validation
//!
//! [`validate_islands`] normalises windings (outer counter-clockwise, islands clockwise, the
//! convention of [`crate::geom::Outline`] users) and refuses, with an input error naming the
//! island and where it came from:
//! * an island that touches or crosses the outer outline ([`loops_touch`]: a true or
//!   overlapping intersection, or a vertex of either loop within [`TOUCH_EPS`] of the other);
//! * an island outside the outer outline;
//! * two islands that touch, cross or nest.
//!
//! `TOUCH_EPS` = 1 µm: two walls closer than that cannot be told apart by any machine, and
//! the offsets the strategies take of the region would merge them anyway; it is far above the
//! f64 rounding of coordinates up to [`crate::geom::MAX_COORDINATE_MM`].
//!
//! # Principal frame
//!
//! [`principal_angle`] gives the direction of the outline's major principal axis, so that a
//! strategy can lay its passes in the pocket's own frame (zigzag): turning the pocket turns
//! the path with it. With the boundary sampled at `n` points `p_i` equally spaced in arc
//! length and `m` their mean, the second moments are `S_xx = Σ(x_i − m_x)²`, `S_yy`, `S_xy`;
//! the covariance matrix has its major eigenvector at
//! `θ = ½·atan2(2·S_xy, S_xx − S_yy)` (from `tan 2θ = 2S_xy / (S_xx − S_yy)`, the stationary
//! point of the quadratic form along the direction `θ`). An isotropic boundary (a square, a
//! circle: `|S_xx − S_yy| + 2|S_xy|` below 1e-3 of the trace) has no principal axis; there the
//! direction of its longest straight edge is used (and 0 for a boundary of arcs only). The
//! axis is then oriented: of `u` and `−u`, the one along which the third moment
//! `Σ((p_i − m)·u)³` is positive (the side the boundary's mass leans to), or, for a shape
//! symmetric along `u`, the one that makes the third moment along the normal `u⊥` positive.
//! So a half turn of the pocket turns the frame with it, and passes laid in that frame start
//! from the same end of the pocket. (A shape symmetric both ways keeps `θ` in `(−π/2, π/2]`;
//! it looks the same either way round.) Moments from samples are exact to about 1e-6 rad, so
//! an axis within [`SNAP_RAD`] of a straight edge is snapped onto that edge: passes parallel
//! to an edge, not a micro-radian off it (which would cut a sliver along the edge).

use super::loops::point_on_bulge_seg;
pub use super::loops::{closed_loop, offset_loops, sample_loop};
use super::{Outline, Point, Winding};
use crate::error::InputError;
use cavalier_contours::core::math::Vector2;
#[cfg(test)]
use cavalier_contours::polyline::PlineSourceMut;
use cavalier_contours::polyline::{PlineSource, Polyline, seg_split_at_point};

/// Two loops closer than this (mm) count as touching.
pub const TOUCH_EPS: f64 = 1e-6;

/// True when two closed loops intersect, overlap or come within [`TOUCH_EPS`] at a vertex.
pub fn loops_touch(a: &Polyline<f64>, b: &Polyline<f64>) -> bool {
    let hits = a.find_intersects(b);
    if !hits.basic_intersects.is_empty() || !hits.overlapping_intersects.is_empty() {
        return true;
    }
    let near = |p: &Polyline<f64>, q: &Polyline<f64>| {
        p.iter_vertexes().any(|v| {
            q.closest_point(v.pos(), 1e-12)
                .is_some_and(|c| c.distance <= TOUCH_EPS)
        })
    };
    near(a, b) || near(b, a)
}

/// The first vertex of an outline (the origin for an empty one, which `Outline` never is).
fn first_vertex(o: &Outline) -> Point {
    o.vertices().next().map_or(Point::ORIGIN, |v| v.0)
}

/// Normalises windings and checks that every island lies strictly inside `outer` and apart
/// from the other islands (see the module docs). `origin` names the source (file, flag).
pub fn validate_islands(
    outer: Outline,
    islands: Vec<Outline>,
    origin: &str,
) -> Result<(Outline, Vec<Outline>), InputError> {
    let outer = outer.with_winding(Winding::CounterClockwise);
    let islands: Vec<Outline> = islands
        .into_iter()
        .map(|i| i.with_winding(Winding::Clockwise))
        .collect();
    for (k, isl) in islands.iter().enumerate() {
        let p = first_vertex(isl);
        let at = format!("{origin}, island {k} near ({:.3}, {:.3})", p.x, p.y);
        if loops_touch(outer.polyline(), isl.polyline()) {
            return Err(InputError::new("island", k)
                .at(at)
                .expected("islands that do not touch or cross the outer outline"));
        }
        if !outer.contains(p) {
            return Err(InputError::new("island", k)
                .at(at)
                .expected("islands inside the outer outline"));
        }
        for (j, other) in islands.iter().enumerate().take(k) {
            let q = first_vertex(other);
            if loops_touch(other.polyline(), isl.polyline()) || isl.contains(q) || other.contains(p)
            {
                return Err(InputError::new("island", k)
                    .at(format!("{origin}, islands {j} and {k}"))
                    .expected("islands apart from each other (not touching, crossing or nested)"));
            }
        }
    }
    Ok((outer, islands))
}

/// One point on every piece into which the loops `others` cut the closed loop `l`: its
/// boundary between consecutive points where another loop meets it (crossing, touching or
/// overlapping, as cavalier_contours' `find_intersects` reports them). A piece meets no other
/// loop inside, so it lies wholly inside or wholly outside each of them, and its point tells
/// which: a region test over these points is exact, where one over points sampled at a fixed
/// spacing steps over anything narrower than the spacing. Pieces that run along another loop
/// (an overlap) are left out, and so is a piece shorter than 1e-9 of its segment. A loop that
/// meets none of `others` gets one point.
///
/// There are as many points as meeting points (plus one per run of segments without any),
/// each found through cavalier's spatial index, so two loops that meet a few times cost
/// `O((n + m) log(n + m))`.
pub fn piece_points(l: &Polyline<f64>, others: &[&Polyline<f64>]) -> Vec<Point> {
    let n = l.vertex_count();
    if n < 2 {
        return l.iter_vertexes().map(|v| Point::new(v.x, v.y)).collect();
    }
    let seg = |i: usize| (l.at(i), l.at((i + 1) % n));
    // The fraction of segment `i`'s arc length at which `p` (a point on it) lies.
    let frac = |i: usize, p: Vector2<f64>| -> f64 {
        let (v1, v2) = seg(i);
        let f = if v1.bulge_is_zero() {
            let d = v2.pos() - v1.pos();
            let dd = d.dot(d);
            if dd > 0.0 {
                (p - v1.pos()).dot(d) / dd
            } else {
                0.0
            }
        } else {
            let first = seg_split_at_point(v1, v2, p, 1e-12).updated_start.bulge;
            first.atan() / v1.bulge.atan()
        };
        if f.is_finite() {
            f.clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    let mut cuts: Vec<Vec<f64>> = vec![Vec::new(); n];
    let mut along: Vec<Vec<(f64, f64)>> = vec![Vec::new(); n];
    for o in others {
        let hits = l.find_intersects(*o);
        for h in &hits.basic_intersects {
            cuts[h.start_index1].push(frac(h.start_index1, h.point));
        }
        for h in &hits.overlapping_intersects {
            let i = h.start_index1;
            let (a, b) = (frac(i, h.point1), frac(i, h.point2));
            cuts[i].extend([a, b]);
            along[i].push((a.min(b), a.max(b)));
        }
    }
    for c in &mut cuts {
        c.sort_by(f64::total_cmp);
    }
    let none = cuts.iter().all(Vec::is_empty);
    let mut out = Vec::new();
    for i in 0..n {
        let prev_cut = !cuts[(i + n - 1) % n].is_empty();
        // Segments inside a run without meeting points need no point of their own: the run
        // has one on the segment where it starts (after a cut, or segment 0 if none).
        if cuts[i].is_empty() && !(prev_cut || (none && i == 0)) {
            continue;
        }
        let bounds: Vec<f64> = std::iter::once(0.0)
            .chain(cuts[i].iter().copied())
            .chain([1.0])
            .collect();
        let (v1, v2) = seg(i);
        let (a, b) = (Point::new(v1.x, v1.y), Point::new(v2.x, v2.y));
        for w in bounds.windows(2) {
            let (fa, fb) = (w[0], w[1]);
            let on_other = along[i]
                .iter()
                .any(|&(s, e)| s <= fa + 1e-9 && fb <= e + 1e-9);
            if fb - fa > 1e-9 && !on_other {
                out.push(point_on_bulge_seg(a, b, v1.bulge, 0.5 * (fa + fb)));
            }
        }
    }
    out
}

/// How close (rad) the moments' axis must come to a straight edge to be snapped onto it.
pub const SNAP_RAD: f64 = 1e-3;

/// The centroid of a point set and its centred second moments `(sxx, syy, sxy)` (sums over
/// the points).
pub fn second_moments(pts: &[Point]) -> (Point, f64, f64, f64) {
    let m = pts.len().max(1) as f64;
    let (cx, cy) = pts
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.x / m, a.1 + p.y / m));
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in pts {
        let (dx, dy) = (p.x - cx, p.y - cy);
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    (Point::new(cx, cy), sxx, syy, sxy)
}

/// The outline's principal-axis direction in `(−π, π]` (see the module docs).
pub fn principal_angle(o: &Outline) -> f64 {
    let pts = sample_loop(o.polyline(), 720);
    let (centroid, sxx, syy, sxy) = second_moments(&pts);
    let (cx, cy) = (centroid.x, centroid.y);
    let m = pts.len().max(1) as f64;
    let raw = if (sxx - syy).abs() + 2.0 * sxy.abs() > 1e-3 * (sxx + syy) {
        0.5 * (2.0 * sxy).atan2(sxx - syy)
    } else {
        // Isotropic: the longest straight edge (the first of equal ones from the lowest
        // direction angle, so that the choice does not depend on the start vertex).
        let mut best: Option<(f64, f64)> = None;
        for (v1, v2) in o.polyline().iter_segments() {
            if !v1.bulge_is_zero() {
                continue;
            }
            let d = Point::new(v2.x, v2.y) - Point::new(v1.x, v1.y);
            let len = d.length();
            let ang = fold(d.angle());
            let better = match best {
                None => true,
                Some((l, a)) => len > l * (1.0 + 1e-9) || (len > l * (1.0 - 1e-9) && ang < a),
            };
            if better {
                best = Some((len, ang));
            }
        }
        best.map_or(0.0, |b| b.1)
    };
    // Snap to a straight edge within SNAP_RAD: the sampled moments are exact only to about
    // 1e-6 rad, and passes a micro-radian off an edge cut slivers along it.
    let snap = o
        .polyline()
        .iter_segments()
        .filter(|(v1, v2)| v1.bulge_is_zero() && (v2.x - v1.x).hypot(v2.y - v1.y) > 0.0)
        .map(|(v1, v2)| fold((v2.y - v1.y).atan2(v2.x - v1.x) - raw))
        .filter(|d| d.abs() <= SNAP_RAD)
        .min_by(|a, b| a.abs().total_cmp(&b.abs()));
    let theta = fold(raw + snap.unwrap_or(0.0));
    // Orient the axis: the sign that makes the third moment along it positive (then along
    // its normal), so that a half turn of the pocket turns the frame with it.
    let u = super::Vec2::from_angle(theta);
    let third = |dir: super::Vec2| {
        pts.iter()
            .map(|p| {
                let t = (p.x - cx) * dir.x + (p.y - cy) * dir.y;
                t * t * t
            })
            .sum::<f64>()
    };
    let scale = (sxx + syy).max(1e-300).powf(1.5) / m.sqrt();
    let s1 = third(u);
    let s2 = third(u.perp());
    let flip = if s1.abs() > 1e-6 * scale {
        s1 < 0.0
    } else {
        s2.abs() > 1e-6 * scale && s2 < 0.0
    };
    if flip {
        if theta > 0.0 {
            theta - std::f64::consts::PI
        } else {
            theta + std::f64::consts::PI
        }
    } else {
        theta
    }
}

/// An angle modulo π, in `(−π/2, π/2]`.
fn fold(a: f64) -> f64 {
    use std::f64::consts::PI;
    let mut t = a.rem_euclid(PI);
    if t > 0.5 * PI {
        t -= PI;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An offset loop left open with its first vertices repeated at its end (as cavalier's
    /// stitching returned `B` on the fuzz corpus' `51e5f8bd…`) is closed at its first vertex:
    /// its inside has winding number 1 (0 for the open polyline); one that does not come back
    /// to its start is no loop.
    #[test]
    fn open_stitched_loops_are_closed_at_their_start() {
        let sq = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
        let mut open = Polyline::new();
        for &(x, y) in sq.iter().chain(&sq[..2]) {
            open.add(x, y, 0.0);
        }
        let inside = Vector2::new(5.0, 5.0);
        assert_eq!(open.winding_number(inside), 0);
        let closed = closed_loop(open).expect("a loop");
        assert!(closed.is_closed());
        assert_eq!(closed.vertex_count(), 4);
        assert_eq!(closed.winding_number(inside), 1);
        assert!((closed.area() - 100.0).abs() < 1e-9);
        let mut stray = Polyline::new();
        for &(x, y) in &sq {
            stray.add(x, y, 0.0);
        }
        assert!(closed_loop(stray).is_none());
        assert!(
            offset_loops(rect(0.0, 0.0, 10.0, 10.0).polyline(), 1.0)
                .iter()
                .all(PlineSource::is_closed)
        );
    }

    fn rect(x: f64, y: f64, w: f64, h: f64) -> Outline {
        Outline::from_points(
            &[
                Point::new(x, y),
                Point::new(x + w, y),
                Point::new(x + w, y + h),
                Point::new(x, y + h),
            ],
            "rect",
        )
        .unwrap()
    }

    #[test]
    fn islands_are_checked_and_windings_normalised() {
        let (o, i) = validate_islands(
            rect(0.0, 0.0, 20.0, 20.0),
            vec![rect(5.0, 5.0, 4.0, 4.0)],
            "t",
        )
        .unwrap();
        assert_eq!(o.winding(), Winding::CounterClockwise);
        assert_eq!(i[0].winding(), Winding::Clockwise);
        for bad in [
            vec![rect(0.0, 5.0, 4.0, 4.0)],  // touches the outline
            vec![rect(-2.0, 5.0, 4.0, 4.0)], // crosses it
            vec![rect(30.0, 5.0, 4.0, 4.0)], // outside
            vec![rect(5.0, 5.0, 4.0, 4.0), rect(9.0, 5.0, 4.0, 4.0)], // islands touch
            vec![rect(5.0, 5.0, 8.0, 8.0), rect(6.0, 6.0, 2.0, 2.0)], // nested
        ] {
            let e = validate_islands(rect(0.0, 0.0, 20.0, 20.0), bad, "t").unwrap_err();
            assert!(e.to_string().contains("island"), "{e}");
        }
    }

    #[test]
    fn principal_angle_follows_rotation() {
        let r = rect(-30.0, -10.0, 60.0, 20.0);
        assert!(principal_angle(&r).abs() < 1e-9);
        let a = 0.7;
        let v: Vec<(Point, f64)> = r
            .vertices()
            .map(|(p, b)| (p.rotate_about(Point::ORIGIN, a), b))
            .collect();
        let turned = Outline::new(&v, "turned").unwrap();
        assert!((principal_angle(&turned) - a).abs() < 1e-9);
        // A rounded rectangle: exactly along its edges (a micro-radian off would cut slivers).
        let rr =
            crate::strategy::pocket::builtin::rounded_rectangle(-75.0, -50.0, 150.0, 100.0, 6.0);
        let a = principal_angle(&rr);
        assert!(
            a.abs() < 1e-12 || (a - std::f64::consts::PI).abs() < 1e-12,
            "{a}"
        );
        // A square: its edge direction.
        let sq = rect(0.0, 0.0, 10.0, 10.0);
        assert!(principal_angle(&sq).abs() < 1e-9);
    }

    #[test]
    fn piece_points_stand_for_every_piece_between_meeting_points() {
        let a = rect(0.0, 0.0, 10.0, 10.0);
        let far = rect(20.0, 0.0, 5.0, 5.0);
        // No meeting point: one point, on the loop.
        let p = piece_points(a.polyline(), &[far.polyline()]);
        assert_eq!(p.len(), 1);
        assert!(a.distance_to(p[0]) < 1e-12);
        // A 0.1 mm slit crossing the square's right edge twice: the square's loop has a
        // piece inside the slit's loop and one outside (a piece may get more than one
        // point, never none), and so has the slit's.
        let slit = rect(9.0, 4.95, 5.0, 0.1);
        let p = piece_points(a.polyline(), &[slit.polyline()]);
        assert!(p.iter().all(|&q| a.distance_to(q) < 1e-12), "{p:?}");
        assert_eq!(p.iter().filter(|&&q| slit.contains(q)).count(), 1, "{p:?}");
        assert!(p.len() >= 2 && p.len() <= 4, "{p:?}");
        let q = piece_points(slit.polyline(), &[a.polyline()]);
        assert!(q.iter().any(|&q| a.contains(q)), "{q:?}");
        assert!(q.iter().any(|&q| !a.contains(q)), "{q:?}");
        // The same loop: every piece runs along the other, none is left to test.
        assert!(piece_points(a.polyline(), &[a.polyline()]).is_empty());
        // An arc cut once by a line: its two pieces' points lie on the arc, either side.
        let disc = Outline::new(
            &[(Point::new(-5.0, 0.0), 1.0), (Point::new(5.0, 0.0), 1.0)],
            "disc",
        )
        .unwrap();
        let band = rect(-1.0, -10.0, 2.0, 20.0);
        let p = piece_points(disc.polyline(), &[band.polyline()]);
        assert!(
            p.iter().all(|q| (q.to_vec2().length() - 5.0).abs() < 1e-9),
            "{p:?}"
        );
        assert_eq!(p.iter().filter(|&&q| band.contains(q)).count(), 2, "{p:?}");
        assert!(
            p.iter().filter(|&&q| !band.contains(q)).count() >= 2,
            "{p:?}"
        );
    }
}
