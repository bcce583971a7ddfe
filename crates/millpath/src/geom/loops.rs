//! Single closed loops as cavalier_contours polylines: closing the loops its offsets leave
//! open, offsetting, and sampling by arc length. Shared by [`super::Outline`] and the region
//! code; nothing here knows about outer loops and islands.

use super::Point;
use cavalier_contours::polyline::{
    PlineCreation, PlineSource, PlineSourceMut, Polyline, seg_arc_radius_and_center,
};

/// How near, mm, a vertex of an open offset loop must come to its first vertex for
/// [`closed_loop`] to close the loop there.
pub const CLOSE_EPS: f64 = 1e-6;

/// `pl` as a closed loop. cavalier_contours' offsets (of a shape or of one polyline) can
/// return a loop stitched with an overlap and left open: its vertices run once round and
/// then repeat the first ones (found on the fuzz corpus' `51e5f8bd…`: 12 vertices, the last
/// two at the first two). Every consumer takes an offset loop for closed, and an open one has
/// winding number 0 everywhere: the spiral took every lap sample for outside its last loop
/// and moved it onto that loop, 0.40 mm² left uncut round the centre. Such a loop is cut at
/// the last vertex on its first one and closed; an open loop that does not come back to its
/// start is `None` (no loop rather than a made-up closing chord).
pub fn closed_loop(pl: Polyline<f64>) -> Option<Polyline<f64>> {
    if pl.is_closed() {
        return Some(pl);
    }
    let n = pl.vertex_count();
    let v0 = pl.at(0);
    let k = (1..n).rev().find(|&i| {
        let v = pl.at(i);
        (v.x - v0.x).hypot(v.y - v0.y) <= CLOSE_EPS
    })?;
    let mut out = Polyline::with_capacity(k, true);
    for i in 0..k {
        out.add_vertex(pl.at(i));
    }
    Some(out)
}

/// cavalier_contours' parallel offset of the closed loop `pl` by `d` (positive: inward for a
/// counter-clockwise loop), every result closed (`closed_loop`).
pub fn offset_loops(pl: &Polyline<f64>, d: f64) -> Vec<Polyline<f64>> {
    pl.parallel_offset(d)
        .into_iter()
        .filter_map(closed_loop)
        .collect()
}

/// Points equally spaced in arc length along a closed polyline (`n` of them, from vertex 0).
pub fn sample_loop(pl: &Polyline<f64>, n: usize) -> Vec<Point> {
    let segs: Vec<(Point, Point, f64, f64)> = pl
        .iter_segments()
        .map(|(v1, v2)| {
            let a = Point::new(v1.x, v1.y);
            let b = Point::new(v2.x, v2.y);
            let len = if v1.bulge_is_zero() {
                a.distance(b)
            } else {
                let (r, _) = seg_arc_radius_and_center(v1, v2);
                r * (4.0 * v1.bulge.atan()).abs()
            };
            (a, b, v1.bulge, len)
        })
        .collect();
    let total: f64 = segs.iter().map(|s| s.3).sum();
    if total.is_nan() || total <= 0.0 || n == 0 {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(n);
    let (mut acc, mut i) = (0.0, 0);
    for k in 0..n {
        let t = total * k as f64 / n as f64;
        while i + 1 < segs.len() && acc + segs[i].3 < t {
            acc += segs[i].3;
            i += 1;
        }
        let Some(&(a, b, bulge, len)) = segs.get(i) else {
            break;
        };
        let f = if len > 0.0 {
            ((t - acc) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(point_on_bulge_seg(a, b, bulge, f));
    }
    out
}

/// The point at fraction `f` of the arc length of the segment `a → b` with `bulge`.
pub(crate) fn point_on_bulge_seg(a: Point, b: Point, bulge: f64, f: f64) -> Point {
    let chord = b - a;
    let c = chord.length();
    if bulge.abs() < 1e-12 || c <= 0.0 {
        return a.lerp(b, f);
    }
    // Sweep θ = 4·atan(bulge); the centre lies on the chord's bisector at R·cos(θ/2),
    // R = c / (2·sin(|θ|/2)), on the side the arc turns to.
    let theta = 4.0 * bulge.atan();
    let half = 0.5 * theta.abs();
    let radius = c / (2.0 * half.sin());
    let n = chord.perp() / c;
    let center = a.midpoint(b) + n * (theta.signum() * radius * half.cos());
    let a0 = (a - center).angle();
    center + super::Vec2::from_angle(a0 + theta * f) * radius
}
