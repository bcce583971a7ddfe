//! Closed centripetal Catmull-Rom curve through all points.
//!
//! # Construction
//! Knot spacing `Δt_i = |P_{i+1} − P_i|^α` with `α = 1/2` (centripetal: no cusps or
//! self-intersections within a piece, Yuksel et al. 2011). The tangent at `P_i` with respect
//! to the knot parameter is the Barry–Goldman form
//! `m_i = (P_i − P_{i−1})/Δt_{i−1} − (P_{i+1} − P_{i−1})/(Δt_{i−1} + Δt_i) + (P_{i+1} − P_i)/Δt_i`,
//! the derivative at `t_i` of the quadratic through `P_{i−1}, P_i, P_{i+1}` at knots
//! `t_{i−1}, t_i, t_{i+1}`. The piece from `P_i` to `P_{i+1}`, reparameterised to `u ∈ [0, 1]`,
//! is the Hermite cubic with end derivatives `Δt_i·m_i` and `Δt_i·m_{i+1}` (chain rule). Both
//! pieces meeting at `P_i` use the same `m_i`, so the curve is C1 in the knot parameter (and
//! G1 in the piece-uniform parameter millpath stores).

use super::Cubic;
use super::flatten::PlanarCurve;
use crate::geom::{Point, Vec2};

/// The closed centripetal Catmull-Rom curve through `pts` (at least 3 distinct consecutive
/// points; the caller validates), as one Bézier piece per input point.
pub fn closed(pts: &[Point]) -> Vec<Cubic> {
    let n = pts.len();
    let at = |i: usize| pts[i % n];
    let dt: Vec<f64> = (0..n)
        .map(|i| at(i + 1).distance(at(i)).sqrt().max(1e-300))
        .collect();
    let tangent = |i: usize| -> Vec2 {
        let (prev, cur, next) = (at(i + n - 1), at(i), at(i + 1));
        let (d0, d1) = (dt[(i + n - 1) % n], dt[i % n]);
        (cur - prev) / d0 - (next - prev) / (d0 + d1) + (next - cur) / d1
    };
    let m: Vec<Vec2> = (0..n).map(tangent).collect();
    (0..n)
        .map(|i| Cubic::from_hermite(at(i), m[i] * dt[i], at(i + 1), m[(i + 1) % n] * dt[i]))
        .collect()
}

/// The open centripetal Catmull-Rom curve through `pts` (consecutive points closer than
/// 1e-9 mm dropped), one piece per gap; the end tangents are one-sided (the chord to the
/// neighbour). Fewer than 2 distinct points: no pieces.
pub fn open(pts: &[Point]) -> Vec<Cubic> {
    let mut p: Vec<Point> = Vec::with_capacity(pts.len());
    for q in pts {
        if p.last().is_none_or(|l| l.distance(*q) > 1e-9) {
            p.push(*q);
        }
    }
    let n = p.len();
    if n < 2 {
        return Vec::new();
    }
    let dt: Vec<f64> = p.windows(2).map(|w| w[1].distance(w[0]).sqrt()).collect();
    let tangent = |i: usize| -> Vec2 {
        if i == 0 {
            (p[1] - p[0]) / dt[0]
        } else if i == n - 1 {
            (p[n - 1] - p[n - 2]) / dt[n - 2]
        } else {
            let (d0, d1) = (dt[i - 1], dt[i]);
            (p[i] - p[i - 1]) / d0 - (p[i + 1] - p[i - 1]) / (d0 + d1) + (p[i + 1] - p[i]) / d1
        }
    };
    let m: Vec<Vec2> = (0..n).map(tangent).collect();
    (0..n - 1)
        .map(|i| Cubic::from_hermite(p[i], m[i] * dt[i], p[i + 1], m[i + 1] * dt[i]))
        .collect()
}

/// An open chain of cubic pieces as a [`PlanarCurve`] (no corners: the caller fits it
/// over `[0, piece_count]`).
#[derive(Debug, Clone)]
pub struct OpenChain(pub Vec<Cubic>);

impl OpenChain {
    /// The open Catmull–Rom chain through `pts` (see `open`).
    pub fn through(pts: &[Point]) -> Self {
        OpenChain(open(pts))
    }
}

impl PlanarCurve for OpenChain {
    fn piece_count(&self) -> usize {
        self.0.len()
    }
    fn point_at(&self, i: usize, u: f64) -> Point {
        self.0.get(i).map_or(Point::ORIGIN, |c| c.eval(u))
    }
    fn critical(&self, i: usize, dir: Vec2, u0: f64, u1: f64, out: &mut Vec<f64>) {
        if let Some(c) = self.0.get(i) {
            c.parallel_roots(dir, u0, u1, out);
        }
    }
    fn breaks(&self) -> Vec<usize> {
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_chain_passes_through_points_tangent_continuously() {
        let pts: Vec<Point> = (0..20)
            .map(|i| {
                let a = 0.3 * f64::from(i);
                Point::new(10.0 * a.cos(), 10.0 * a.sin() + 0.1 * f64::from(i))
            })
            .collect();
        let c = open(&pts);
        assert_eq!(c.len(), 19);
        for i in 0..19 {
            assert!(c[i].p0.distance(pts[i]) < 1e-12 && c[i].p3.distance(pts[i + 1]) < 1e-12);
        }
        for w in c.windows(2) {
            let (a, b) = (w[0].d1(1.0), w[1].d1(0.0));
            assert!(a.cross(b).abs() < 1e-9 * a.length() * b.length() && a.dot(b) > 0.0);
        }
        assert!(open(&pts[..1]).is_empty());
    }

    #[test]
    fn passes_through_points_with_continuous_tangent_direction() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 1.0),
            Point::new(11.0, 8.0),
            Point::new(2.0, 9.0),
        ];
        let c = closed(&pts);
        assert_eq!(c.len(), 4);
        for i in 0..4 {
            assert!(c[i].p0.distance(pts[i]) < 1e-12);
            let (a, b) = (c[i].d1(1.0), c[(i + 1) % 4].d1(0.0));
            assert!(a.cross(b).abs() < 1e-9 * a.length() * b.length() && a.dot(b) > 0.0);
        }
    }
}
