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

#[cfg(test)]
mod tests {
    use super::*;

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
