//! C1 blending cubic between two curve pieces (also used to close an outline).
//!
//! # Solution (derived)
//! The blend is a four-point cubic `P1, P2, P3, P4` (see [`super::four_point`]) from the end
//! `A` of the previous piece to the start `B` of the next. Position continuity fixes
//! `P1 = A`, `P4 = B`. Tangent continuity in the parameter (the paper's eqs. 8, 9) asks
//! `P'(0) = D0` (the previous piece's end derivative) and `P'(1) = D1` (the next piece's start
//! derivative):
//!
//! ```text
//! −5.5P1 + 9P2 − 4.5P3 + P4 = D0        →  9P2 − 4.5P3 = a := D0 + 5.5A − B
//! −P1 + 4.5P2 − 9P3 + 5.5P4 = D1        →  4.5P2 − 9P3 = b := D1 + A − 5.5B
//! ```
//! Eliminating: `2a − b = 13.5P2` and `a − 2b = 13.5P3`, so
//! `P2 = (2a − b)/13.5`, `P3 = (a − 2b)/13.5` (determinant `9·(−9) − (−4.5)·4.5 = −60.75 ≠ 0`:
//! the blend always exists and is unique).
//!
//! The paper prints this as eqs. 10–11 with constants `A = 0.0842, B = 0.4386, C = 0.0249,
//! D = 0.1449, E = 0.1818, F = 1.81, G = 1` that are garbled in the available text and cannot
//! be reconciled with its own Table 1; the closed form above reproduces Table 1 (inner points
//! (10.33, 4.38) and (14.11, 0.44), see the tests), so it is what we use.

use super::{Cubic, four_point};
use crate::geom::{Point, Vec2};

/// The inner points `(P2, P3)` of the four-point blend from `a` (derivative `d0`) to `b`
/// (derivative `d1`).
pub fn inner_points(a: Point, d0: Vec2, b: Point, d1: Vec2) -> (Point, Point) {
    let va = d0 + a.to_vec2() * 5.5 - b.to_vec2();
    let vb = d1 + a.to_vec2() - b.to_vec2() * 5.5;
    (
        ((va * 2.0 - vb) / 13.5).to_point(),
        ((va - vb * 2.0) / 13.5).to_point(),
    )
}

/// The C1 blend from the end of `prev` to the start of `next`, as a Bézier piece.
pub fn blend(prev: &Cubic, next: &Cubic) -> Cubic {
    let (a, b) = (prev.p3, next.p0);
    let (p2, p3) = inner_points(a, prev.d1(1.0), b, next.d1(0.0));
    four_point::cubic(&[a, p2, p3, b])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_1_of_the_paper() {
        let seg1 = four_point::cubic(&[
            Point::new(1.0, 15.0),
            Point::new(3.0, 14.0),
            Point::new(5.0, 12.5),
            Point::new(7.0, 10.0),
        ]);
        let seg3 = four_point::cubic(&[
            Point::new(15.0, 8.0),
            Point::new(11.0, 17.0),
            Point::new(5.0, 16.5),
            Point::new(1.0, 15.0),
        ]);
        assert!((seg3.d1(0.0) - Vec2::new(-5.0, 49.75)).length() < 1e-12);
        let (p2, p3) = inner_points(seg1.p3, seg1.d1(1.0), seg3.p0, seg3.d1(0.0));
        // Table 1 prints two decimals (4.38 for 4.3889: truncated, not rounded).
        assert!(
            (p2.x - 10.33).abs() < 0.01 && (p2.y - 4.38).abs() < 0.01,
            "{p2:?}"
        );
        assert!(
            (p3.x - 14.11).abs() < 0.01 && (p3.y - 0.44).abs() < 0.01,
            "{p3:?}"
        );
        let b = blend(&seg1, &seg3);
        assert!(b.p0.distance(seg1.p3) < 1e-12 && b.p3.distance(seg3.p0) < 1e-12);
        assert!((b.d1(0.0) - seg1.d1(1.0)).length() < 1e-9);
        assert!((b.d1(1.0) - seg3.d1(0.0)).length() < 1e-9);
    }
}
