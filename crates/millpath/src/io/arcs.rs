//! Circles and arcs drawn as runs of short lines, read back as arcs.
//!
//! A CAD program often writes a circle or a rounded corner as many short LINEs, or as a
//! spline the reader flattens. Cut as lines, such a curve gives the profile hundreds of short
//! moves (no G2/G3), no long element for a tab to sit on, and a hole that is not a circle.
//! Each closed outline's lines are read back as arcs where they allow, in two steps:
//!
//! 1. **A whole circle.** An outline of at least `2·`[`MIN_RUN`] lines (and no arc) that
//!    [`crate::geom::Hole::from_outline`] takes for a circle within
//!    [`crate::geom::CIRCLE_TOLERANCE`] (every point of every line within it of the circle, and
//!    the area the circle's) becomes that circle, as two half arcs: what a CIRCLE entity
//!    reads as. The drawing moves by at most that tolerance, the one a hole is drilled to.
//! 2. **Runs on one circle.** Otherwise, from the end of the longest segment round, each run
//!    of at least [`MIN_RUN`] consecutive lines that lie on one circle within the reader's
//!    tolerance `t` (its flattening tolerance, 0.001 mm by default) becomes one arc through
//!    the run's two end vertices: the circle through its first, middle and last vertices,
//!    sweeping at most half a turn, the vertices in order along it. A run is accepted when
//!    every point of each of its lines lies within `t` of that circle: for a line the
//!    farthest point from the circle is one of its ends or the foot of the perpendicular
//!    from the centre, so the test is exact. A run whose arc is straighter than `t` (its
//!    sagitta below `t`) stays lines. Runs grow greedily (doubling, then bisection on the
//!    last vertex), so each test is linear in the run and an outline of `n` lines takes
//!    `O(n log n)` tests' work.
//!
//! The arcs keep the outline's vertices where runs meet, so the outline stays closed and
//! within `t` (step 2) or the circle tolerance (step 1) of the lines drawn; an outline the
//! arcs would make invalid (crossing itself) is kept as drawn.

use crate::geom::{CIRCLE_TOLERANCE, Hole, Outline, Point};
use std::f64::consts::PI;

/// The fewest consecutive lines read back as an arc.
pub const MIN_RUN: usize = 4;

/// `outline` with its runs of lines on one circle read back as arcs (module docs), within
/// `tolerance` mm (the reader's flattening tolerance); its arcs kept; unchanged when
/// nothing fits, or when the result would not be a valid outline.
pub fn with_arcs(outline: Outline, tolerance: f64) -> Outline {
    let v: Vec<(Point, f64)> = outline.vertices().collect();
    if v.len() < MIN_RUN || tolerance.is_nan() || tolerance <= 0.0 {
        return outline;
    }
    let circle = (v.len() >= 2 * MIN_RUN && v.iter().all(|x| x.1 == 0.0))
        .then(|| Hole::from_outline(&outline, CIRCLE_TOLERANCE.max(tolerance)))
        .flatten();
    if let Some(h) = circle {
        let r = h.radius();
        let c = h.center;
        let ccw = outline.signed_area() > 0.0;
        let b = if ccw { 1.0 } else { -1.0 };
        let circle = [(Point::new(c.x + r, c.y), b), (Point::new(c.x - r, c.y), b)];
        if let Ok(o) = Outline::new(&circle, "a circle drawn as lines") {
            return o;
        }
    }
    let fitted = fit_runs(&v, tolerance);
    if fitted.len() == v.len() {
        return outline;
    }
    Outline::new(&fitted, "an outline whose lines were read as arcs").unwrap_or(outline)
}

/// The vertices `v` (a closed loop) with each run of lines on one circle within
/// `tol` replaced by one arc (module docs, step 2).
fn fit_runs(v: &[(Point, f64)], tol: f64) -> Vec<(Point, f64)> {
    let n = v.len();
    let p = |k: usize| v[k % n].0;
    // Start where the longest segment ends: a run of short lines seldom goes on past it.
    let longest = (0..n)
        .max_by(|&a, &b| p(a).distance(p(a + 1)).total_cmp(&p(b).distance(p(b + 1))))
        .unwrap_or(0);
    let first = fit_from(v, tol, (longest + 1) % n);
    // Where that lies inside a run (a closed curve of short lines alone), start again where
    // the first arc ends, so that the run across the start is one arc.
    let best = match first.first() {
        Some(&(_, b)) if b != 0.0 && first.len() > 1 => {
            let again = fit_from(v, tol, first[1].0);
            if again.len() < first.len() {
                again
            } else {
                first
            }
        }
        _ => first,
    };
    best.into_iter()
        .map(|(k, b)| (v[k].0, if b == 0.0 { v[k].1 } else { b }))
        .collect()
}

/// The runs from vertex `start` round: each element's first vertex (index into `v`) and its
/// bulge (0 for a segment kept as drawn).
fn fit_from(v: &[(Point, f64)], tol: f64, start: usize) -> Vec<(usize, f64)> {
    let n = v.len();
    let p = |k: usize| v[k % n].0;
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    while i < n {
        let pts = |j: usize| -> Vec<Point> { (i..=j).map(|k| p(start + k)).collect() };
        let line = |k: usize| v[(start + k) % n].1 == 0.0;
        let fits = |j: usize| j <= n && (i..j).all(line) && arc_of(&pts(j), tol).is_some();
        if !fits(i + MIN_RUN) {
            out.push(((start + i) % n, 0.0));
            i += 1;
            continue;
        }
        // Doubling, then bisection: the last `j` that fits.
        let (mut lo, mut hi) = (i + MIN_RUN, i + 2 * MIN_RUN);
        while hi <= n && fits(hi) {
            lo = hi;
            hi = i + 2 * (hi - i);
        }
        hi = hi.min(n + 1);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if fits(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let bulge = arc_of(&pts(lo), tol).unwrap_or(0.0);
        out.push(((start + i) % n, bulge));
        i = lo;
    }
    out
}

/// The bulge of the arc from the first to the last of `pts` through the middle one, when
/// every line between consecutive points lies within `tol` of its circle, the points run
/// in order along it, it sweeps at most half a turn and its sagitta is at least `tol`.
fn arc_of(pts: &[Point], tol: f64) -> Option<f64> {
    let (a, m, b) = (pts[0], pts[pts.len() / 2], pts[pts.len() - 1]);
    let (c, r) = circle_through(a, m, b)?;
    let angle = |q: Point| (q.y - c.y).atan2(q.x - c.x);
    // Signed sweep from `a` through `m` to `b`.
    let ccw = (m - a).cross(b - m) > 0.0;
    let sign = if ccw { 1.0 } else { -1.0 };
    let step = |from: Point, to: Point| {
        let mut d = sign * (angle(to) - angle(from));
        if d < 0.0 {
            d += 2.0 * PI;
        }
        d
    };
    let mut sweep = 0.0;
    for w in pts.windows(2) {
        let d = step(w[0], w[1]);
        // Each line advances along the circle by less than a half turn.
        if d >= PI {
            return None;
        }
        sweep += d;
        if sweep > PI + 1e-12 {
            return None;
        }
        // The line's farthest point from the circle: an end or the foot from the centre.
        let ab = w[1] - w[0];
        let t = ((c - w[0]).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        let foot = w[0].lerp(w[1], t);
        let worst = [w[0], w[1], foot]
            .iter()
            .map(|q| (q.distance(c) - r).abs())
            .fold(0.0f64, f64::max);
        if worst.is_nan() || worst > tol {
            return None;
        }
    }
    let sagitta = r * (1.0 - (0.5 * sweep).cos());
    (sagitta >= tol).then(|| sign * (0.25 * sweep).tan())
}

/// The circle through three points (centre, radius); `None` when they are (nearly)
/// collinear.
fn circle_through(a: Point, b: Point, c: Point) -> Option<(Point, f64)> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.cross(ac);
    let scale = ab.length() * ac.length() * (c - b).length();
    if d.is_nan() || d.abs() <= 1e-12 * scale.max(1e-300) {
        return None;
    }
    let (l1, l2) = (ab.length_squared(), ac.length_squared());
    let ux = (ac.y * l1 - ab.y * l2) / d;
    let uy = (ab.x * l2 - ac.x * l1) / d;
    let center = Point::new(a.x + ux, a.y + uy);
    let r = center.distance(a);
    (center.is_finite() && r.is_finite()).then_some((center, r))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest distance from dense samples of `a`'s segments to `b`, mm: the verifier
    /// (the outline's own distance function, not the fit's circle).
    fn one_way(a: &Outline, b: &Outline) -> f64 {
        let n = 40 * a.len();
        a.sample(n)
            .into_iter()
            .map(|p| b.distance_to(p))
            .fold(0.0, f64::max)
    }

    fn lines(pts: &[Point]) -> Outline {
        Outline::from_points(pts, "test").expect("outline")
    }

    /// A circle of 512 lines (as a flattened spline gives) reads as two half arcs of its
    /// circle, within the circle tolerance both ways.
    #[test]
    fn a_circle_of_lines_is_two_half_arcs() {
        let (c, r) = (Point::new(204.9, 224.7), 6.63);
        let pts: Vec<Point> = (0..512)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / 512.0 + 0.3;
                Point::new(c.x + r * a.cos(), c.y + r * a.sin())
            })
            .collect();
        let drawn = lines(&pts);
        let read = with_arcs(drawn.clone(), 0.001);
        let v: Vec<(Point, f64)> = read.vertices().collect();
        assert_eq!(v.len(), 2, "{v:?}");
        assert!(v.iter().all(|x| (x.1.abs() - 1.0).abs() < 1e-12), "{v:?}");
        let (ab, ba) = (one_way(&drawn, &read), one_way(&read, &drawn));
        assert!(
            ab <= CIRCLE_TOLERANCE && ba <= CIRCLE_TOLERANCE,
            "{ab} {ba}"
        );
        assert_eq!(read.signed_area() > 0.0, drawn.signed_area() > 0.0);
    }

    /// A rectangle whose rounded corners are drawn as short lines gets one arc per corner,
    /// every point of the drawn lines within the reader's tolerance of it and back; its
    /// straight sides stay lines.
    #[test]
    fn rounded_corners_of_lines_are_arcs_within_the_tolerance() {
        let tol = 0.001;
        let mut checked = 0;
        for rad in [5.0_f64, 0.8, 12.0] {
            // Chords whose sagitta is half the tolerance, as a reader's flattening gives.
            let chord_angle = 2.0 * (1.0 - 0.5 * tol / rad).acos();
            let per_corner = (0.5 * PI / chord_angle).ceil() as usize;
            let mut pts = Vec::new();
            let corners = [(30.0, 20.0), (-30.0, 20.0), (-30.0, -20.0), (30.0, -20.0)];
            for (q, &(x, y)) in corners.iter().enumerate() {
                let (cx, cy) = (x - rad * f64::signum(x), y - rad * f64::signum(y));
                for k in 0..=per_corner {
                    let a = 0.5 * PI * (q as f64 + k as f64 / per_corner as f64);
                    pts.push(Point::new(cx + rad * a.cos(), cy + rad * a.sin()));
                }
            }
            let drawn = lines(&pts);
            let read = with_arcs(drawn.clone(), tol);
            let v: Vec<(Point, f64)> = read.vertices().collect();
            let arcs = v.iter().filter(|x| x.1 != 0.0).count();
            // A quarter circle of chords within the tolerance is one arc (four in all).
            assert_eq!(arcs, 4, "radius {rad}: {v:?}");
            assert_eq!(v.len(), 8, "radius {rad}: {v:?}");
            let (ab, ba) = (one_way(&drawn, &read), one_way(&read, &drawn));
            assert!(
                ab <= tol + 1e-9 && ba <= tol + 1e-9,
                "radius {rad}: {ab} {ba}"
            );
            checked += 1;
        }
        assert_eq!(checked, 3);
    }

    /// Lines whose vertices leave the circle by more than the tolerance, a coarse polygon
    /// (chords farther than the tolerance from its circle), and straight runs stay as drawn.
    #[test]
    fn lines_off_any_circle_stay_lines() {
        let wavy: Vec<Point> = (0..200)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / 200.0;
                let r = 10.0 + if k % 2 == 0 { 0.01 } else { -0.01 };
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect();
        let hexagon: Vec<Point> = (0..6)
            .map(|k| {
                let a = PI / 3.0 * k as f64;
                Point::new(10.0 * a.cos(), 10.0 * a.sin())
            })
            .collect();
        let comb: Vec<Point> = (0..=20)
            .map(|k| Point::new(k as f64, 0.0))
            .chain([Point::new(20.0, 5.0), Point::new(0.0, 5.0)])
            .collect();
        for pts in [wavy, hexagon, comb] {
            let drawn = lines(&pts);
            let read = with_arcs(drawn.clone(), 0.001);
            assert!(read.vertices().all(|x| x.1 == 0.0), "{:?}", read);
            assert_eq!(read.len(), drawn.len());
        }
    }
}
