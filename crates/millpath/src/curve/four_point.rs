//! The four-point interpolating cubic: the cubic through `P1..P4` at `u = 0, 1/3, 2/3, 1`.
//!
//! # Basis (Lagrange, derived)
//! `Gk(u) = Π_{j≠k} (u − u_j) / Π_{j≠k} (u_k − u_j)` with nodes `0, 1/3, 2/3, 1`:
//!
//! | | denominator | expanded | derivative |
//! |---|---|---|---|
//! | G1 | (−1/3)(−2/3)(−1) = −2/9 | −4.5u³ + 9u² − 5.5u + 1 | −13.5u² + 18u − 5.5 |
//! | G2 | (1/3)(−1/3)(−2/3) = 2/27 | 13.5u³ − 22.5u² + 9u | 40.5u² − 45u + 9 |
//! | G3 | (2/3)(1/3)(−1/3) = −2/27 | −13.5u³ + 18u² − 4.5u | −40.5u² + 36u − 4.5 |
//! | G4 | (1)(2/3)(1/3) = 2/9 | 4.5u³ − 4.5u² + u | 13.5u² − 9u + 1 |
//!
//! For example `G2 = 13.5·u(u − 2/3)(u − 1) = 13.5(u³ − 5u²/3 + 2u/3)`, whose derivative has
//! the leading coefficient `3 × 13.5 = 40.5`.
//!
//! **Misprint in the paper** (Mohamed, eq. 5, and again in the coefficient `Q` of eq. 18): it
//! prints `G2'(u) = 41.5u² − 45u + 9` and `G3'(u) = −41.5u² + 36u − 4.5`. The derivation gives
//! **40.5**; with 41.5 the four derivatives do not sum to zero (`ΣGk = 1` ⇒ `ΣGk' = 0`) and
//! `G2'` would not be the derivative of any basis that interpolates at the nodes. The tests
//! check the derivatives above against finite differences and the partition of unity.
//!
//! # End derivatives and the Bézier form
//! `P'(0) = −5.5P1 + 9P2 − 4.5P3 + P4` and `P'(1) = −P1 + 4.5P2 − 9P3 + 5.5P4` (evaluate the
//! derivative column at 0 and 1). A cubic with end points `P1, P4` and end derivatives
//! `P'(0), P'(1)` has Bézier control points `P1, P1 + P'(0)/3, P4 − P'(1)/3, P4`, which is how
//! every piece is stored ([`Cubic`]).

use super::Cubic;
use crate::geom::{Point, Vec2};

#[cfg(test)]
/// The four basis functions `[G1, G2, G3, G4]` at `u`.
pub fn basis(u: f64) -> [f64; 4] {
    [
        ((-4.5 * u + 9.0) * u - 5.5) * u + 1.0,
        ((13.5 * u - 22.5) * u + 9.0) * u,
        ((-13.5 * u + 18.0) * u - 4.5) * u,
        ((4.5 * u - 4.5) * u + 1.0) * u,
    ]
}

/// The derivatives `[G1', G2', G3', G4']` at `u` (40.5, not the paper's 41.5).
pub fn basis_d1(u: f64) -> [f64; 4] {
    [
        (-13.5 * u + 18.0) * u - 5.5,
        (40.5 * u - 45.0) * u + 9.0,
        (-40.5 * u + 36.0) * u - 4.5,
        (13.5 * u - 9.0) * u + 1.0,
    ]
}

fn combine(w: [f64; 4], p: &[Point; 4]) -> Vec2 {
    p.iter()
        .zip(w)
        .fold(Vec2::ZERO, |acc, (p, w)| acc + p.to_vec2() * w)
}

/// `P'(0) = −5.5P1 + 9P2 − 4.5P3 + P4`.
pub fn start_derivative(p: &[Point; 4]) -> Vec2 {
    combine(basis_d1(0.0), p)
}

/// `P'(1) = −P1 + 4.5P2 − 9P3 + 5.5P4`.
pub fn end_derivative(p: &[Point; 4]) -> Vec2 {
    combine(basis_d1(1.0), p)
}

#[cfg(test)]
/// The point of the four-point cubic at `u` straight from the Lagrange basis (eq. 2).
pub fn eval(p: &[Point; 4], u: f64) -> Point {
    combine(basis(u), p).to_point()
}

/// The four-point cubic through `p` as a Bézier piece.
pub fn cubic(p: &[Point; 4]) -> Cubic {
    Cubic::from_hermite(p[0], start_derivative(p), p[3], end_derivative(p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_interpolates_and_sums_to_one() {
        for (k, u) in [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0].iter().enumerate() {
            let g = basis(*u);
            for (j, gj) in g.iter().enumerate() {
                let want = if j == k { 1.0 } else { 0.0 };
                assert!((gj - want).abs() < 1e-12, "G{}({u}) = {gj}", j + 1);
            }
        }
        for i in 0..=20 {
            let u = f64::from(i) / 20.0;
            assert!((basis(u).iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(basis_d1(u).iter().sum::<f64>().abs() < 1e-12);
        }
    }

    #[test]
    fn basis_derivatives_match_finite_differences() {
        let h = 1e-6;
        for i in 0..=20 {
            let u = f64::from(i) / 20.0;
            let (a, b) = (basis(u + h), basis(u - h));
            let d = basis_d1(u);
            for k in 0..4 {
                let fd = (a[k] - b[k]) / (2.0 * h);
                assert!(
                    (fd - d[k]).abs() < 1e-6,
                    "G{}'({u}): {fd} vs {}",
                    k + 1,
                    d[k]
                );
            }
        }
        // The paper's 41.5 fails the same check.
        let misprint = |u: f64| (41.5 * u - 45.0) * u + 9.0;
        let fd = (basis(0.5 + h)[1] - basis(0.5 - h)[1]) / (2.0 * h);
        assert!((fd - misprint(0.5)).abs() > 0.2);
    }

    #[test]
    fn bezier_form_passes_through_the_four_points() {
        let p = [
            Point::new(1.0, 15.0),
            Point::new(3.0, 14.0),
            Point::new(5.0, 12.5),
            Point::new(7.0, 10.0),
        ];
        let c = cubic(&p);
        for (k, u) in [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0].iter().enumerate() {
            assert!(c.eval(*u).distance(p[k]) < 1e-12);
            assert!(c.eval(*u * 0.9 + 0.05).distance(eval(&p, *u * 0.9 + 0.05)) < 1e-12);
        }
        let d1 = end_derivative(&p);
        assert!((d1 - Vec2::new(6.0, -9.5)).length() < 1e-12);
    }
}
