//! Closed periodic cubic spline through all points (C2), chord-length parameterised.
//!
//! # Construction
//! Knot spacing `h_i = |P_{i+1} − P_i|`. On `[t_i, t_{i+1}]` the spline is the cubic with
//! values `P_i, P_{i+1}` and second derivatives `M_i, M_{i+1}`; matching first derivatives at
//! every knot gives, cyclically for every `i`,
//! `h_{i−1}M_{i−1} + 2(h_{i−1} + h_i)M_i + h_iM_{i+1} = 6((P_{i+1} − P_i)/h_i − (P_i − P_{i−1})/h_{i−1})`,
//! a strictly diagonally dominant cyclic tridiagonal system, solved per coordinate by the
//! Thomas algorithm with a Sherman–Morrison correction for the two corner entries.
//! Piece end derivatives (in `t`): `S'(t_i) = (P_{i+1} − P_i)/h_i − h_i(2M_i + M_{i+1})/6` and
//! `S'(t_{i+1}) = (P_{i+1} − P_i)/h_i + h_i(M_i + 2M_{i+1})/6`; times `h_i` for `u ∈ [0, 1]`.

use super::Cubic;
use crate::geom::{Point, Vec2};

/// Solves the cyclic tridiagonal system `a_i x_{i−1} + b_i x_i + c_i x_{i+1} = d_i` (indices
/// mod n, n ≥ 3) by Sherman–Morrison. Returns `None` when a pivot vanishes.
fn solve_cyclic(a: &[f64], b: &[f64], c: &[f64], d: &[f64]) -> Option<Vec<f64>> {
    let n = d.len();
    let gamma = -b[0];
    let mut bb = b.to_vec();
    bb[0] -= gamma;
    bb[n - 1] -= a[0] * c[n - 1] / gamma;
    let x = thomas(a, &bb, c, d)?;
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = c[n - 1];
    let z = thomas(a, &bb, c, &u)?;
    let fact = (x[0] + a[0] * x[n - 1] / gamma) / (1.0 + z[0] + a[0] * z[n - 1] / gamma);
    Some(x.iter().zip(&z).map(|(x, z)| x - fact * z).collect())
}

fn thomas(a: &[f64], b: &[f64], c: &[f64], d: &[f64]) -> Option<Vec<f64>> {
    let n = d.len();
    let mut cp = vec![0.0; n];
    let mut dp = vec![0.0; n];
    let mut m = b[0];
    if m == 0.0 {
        return None;
    }
    cp[0] = c[0] / m;
    dp[0] = d[0] / m;
    for i in 1..n {
        m = b[i] - a[i] * cp[i - 1];
        if m == 0.0 {
            return None;
        }
        cp[i] = c[i] / m;
        dp[i] = (d[i] - a[i] * dp[i - 1]) / m;
    }
    let mut x = dp;
    for i in (0..n - 1).rev() {
        x[i] -= cp[i] * x[i + 1];
    }
    Some(x)
}

/// The closed periodic cubic spline through `pts` (at least 3 distinct consecutive points;
/// the caller validates), one Bézier piece per input point. `None` only if the linear solve
/// breaks down, which diagonal dominance rules out for valid input.
pub fn closed(pts: &[Point]) -> Option<Vec<Cubic>> {
    let n = pts.len();
    let at = |i: usize| pts[i % n];
    let h: Vec<f64> = (0..n).map(|i| at(i + 1).distance(at(i))).collect();
    let hm = |i: usize| h[(i + n - 1) % n];
    let a: Vec<f64> = (0..n).map(hm).collect();
    let b: Vec<f64> = (0..n).map(|i| 2.0 * (hm(i) + h[i])).collect();
    let c: Vec<f64> = h.clone();
    let rhs: Vec<Vec2> = (0..n)
        .map(|i| ((at(i + 1) - at(i)) / h[i] - (at(i) - at(i + n - 1)) / hm(i)) * 6.0)
        .collect();
    let mx = solve_cyclic(&a, &b, &c, &rhs.iter().map(|v| v.x).collect::<Vec<_>>())?;
    let my = solve_cyclic(&a, &b, &c, &rhs.iter().map(|v| v.y).collect::<Vec<_>>())?;
    let m: Vec<Vec2> = mx.iter().zip(&my).map(|(x, y)| Vec2::new(*x, *y)).collect();
    Some(
        (0..n)
            .map(|i| {
                let (m0, m1) = (m[i], m[(i + 1) % n]);
                let slope = (at(i + 1) - at(i)) / h[i];
                let d0 = slope - (m0 * 2.0 + m1) * (h[i] / 6.0);
                let d1 = slope + (m0 + m1 * 2.0) * (h[i] / 6.0);
                Cubic::from_hermite(at(i), d0 * h[i], at(i + 1), d1 * h[i])
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c2_in_the_chord_length_parameter() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 1.0),
            Point::new(13.0, 8.0),
            Point::new(5.0, 12.0),
            Point::new(-2.0, 7.0),
        ];
        let c = closed(&pts).unwrap();
        let n = pts.len();
        for i in 0..n {
            let j = (i + 1) % n;
            let (hi, hj) = (pts[j].distance(pts[i]), pts[(j + 1) % n].distance(pts[j]));
            assert!(c[i].p3.distance(c[j].p0) < 1e-12);
            // d/dt = d/du / h, d²/dt² = d²/du² / h².
            assert!((c[i].d1(1.0) / hi - c[j].d1(0.0) / hj).length() < 1e-9);
            assert!((c[i].d2(1.0) / (hi * hi) - c[j].d2(0.0) / (hj * hj)).length() < 1e-9);
        }
    }

    #[test]
    fn circle_points_give_a_near_circle() {
        let n = 16;
        let pts: Vec<Point> = (0..n)
            .map(|i| {
                Point::ORIGIN + Vec2::from_angle(f64::from(i) * std::f64::consts::TAU / 16.0) * 50.0
            })
            .collect();
        let c = closed(&pts).unwrap();
        for piece in &c {
            let r = (piece.eval(0.5) - Point::ORIGIN).length();
            assert!((r - 50.0).abs() < 0.01, "{r}");
        }
    }
}
