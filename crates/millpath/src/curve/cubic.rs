//! One cubic Bézier piece: evaluation, derivatives, curvature and the tangent-parallel roots
//! that make chordal deviation exact.
//!
//! # Form
//! `B(t) = (1−t)³p0 + 3(1−t)²t p1 + 3(1−t)t² p2 + t³p3`, `t ∈ [0, 1]`. Written in the power
//! basis about `p0`, `B(t) = p0 + t·a1 + t²·a2 + t³·a3` with
//! `a1 = 3(p1 − p0)`, `a2 = 3(p2 − 2p1 + p0)`, `a3 = p3 − 3p2 + 3p1 − p0`, so
//! `B'(t) = a1 + 2t·a2 + 3t²·a3` and `B''(t) = 2a2 + 6t·a3`.
//!
//! # Tangent-parallel points
//! For a fixed direction `c`, `f(t) = cross(B'(t), c) = cross(a1, c) + 2t·cross(a2, c) +
//! 3t²·cross(a3, c)` is a quadratic in `t`. Its roots are the only interior points where the
//! curve runs parallel to `c`, which are the only interior critical points of the signed
//! distance `cross(B(t) − A, ĉ)` to a line of direction `c` (its derivative is
//! `cross(B'(t), ĉ)`). [`Cubic::parallel_roots`] solves it in closed form with the
//! cancellation-free `q = −(b + sign(b)·√disc)/2` form, falls back to the linear case when
//! the quadratic coefficient vanishes, and always adds the parabola's vertex (a near-double
//! root under rounding). Extra candidates are harmless: they are curve points, so a maximum
//! taken over more of them is still exact.

use crate::geom::{Point, Vec2};
use serde::{Deserialize, Serialize};

/// A cubic Bézier piece with control points `p0..p3`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cubic {
    /// Start point (on the curve).
    pub p0: Point,
    /// First inner control point.
    pub p1: Point,
    /// Second inner control point.
    pub p2: Point,
    /// End point (on the curve).
    pub p3: Point,
}

impl Cubic {
    /// A new cubic from its four control points.
    pub const fn new(p0: Point, p1: Point, p2: Point, p3: Point) -> Self {
        Cubic { p0, p1, p2, p3 }
    }

    /// The cubic with start `p0`, end `p3` and parametric end derivatives `d0 = B'(0)`,
    /// `d1 = B'(1)` (Hermite form): `p1 = p0 + d0/3`, `p2 = p3 − d1/3`.
    pub fn from_hermite(p0: Point, d0: Vec2, p3: Point, d1: Vec2) -> Self {
        Cubic::new(p0, p0 + d0 / 3.0, p3 - d1 / 3.0, p3)
    }

    fn coeffs(&self) -> (Vec2, Vec2, Vec2) {
        let a1 = (self.p1 - self.p0) * 3.0;
        let a2 = ((self.p2 - self.p1) - (self.p1 - self.p0)) * 3.0;
        let a3 = (self.p3 - self.p0) - (self.p2 - self.p1) * 3.0;
        (a1, a2, a3)
    }

    /// The point at `t`.
    pub fn eval(&self, t: f64) -> Point {
        let (a1, a2, a3) = self.coeffs();
        self.p0 + ((a3 * t + a2) * t + a1) * t
    }

    /// First derivative `B'(t)`.
    pub fn d1(&self, t: f64) -> Vec2 {
        let (a1, a2, a3) = self.coeffs();
        a1 + a2 * (2.0 * t) + a3 * (3.0 * t * t)
    }

    /// Second derivative `B''(t)`.
    pub fn d2(&self, t: f64) -> Vec2 {
        let (_, a2, a3) = self.coeffs();
        a2 * 2.0 + a3 * (6.0 * t)
    }

    /// Signed curvature `κ = cross(B', B'') / |B'|³` (positive turning left); 0 where the
    /// derivative vanishes.
    pub fn curvature(&self, t: f64) -> f64 {
        let d1 = self.d1(t);
        let l = d1.length();
        if l < 1e-300 {
            return 0.0;
        }
        d1.cross(self.d2(t)) / (l * l * l)
    }

    /// The same curve run backwards.
    pub fn reversed(&self) -> Self {
        Cubic::new(self.p3, self.p2, self.p1, self.p0)
    }

    /// The parameters in the open interval `(t0, t1)` where `B'(t)` is parallel to `dir`,
    /// appended to `out` (see the module docs).
    pub fn parallel_roots(&self, dir: Vec2, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let (a1, a2, a3) = self.coeffs();
        let a = 3.0 * a3.cross(dir);
        let b = 2.0 * a2.cross(dir);
        let c = a1.cross(dir);
        let mut push = |t: f64| {
            if t > t0 && t < t1 && t.is_finite() {
                out.push(t);
            }
        };
        let scale = a.abs().max(b.abs()).max(c.abs());
        if scale == 0.0 {
            return;
        }
        if a.abs() <= 1e-14 * scale {
            if b != 0.0 {
                push(-c / b);
            }
            return;
        }
        push(-b / (2.0 * a));
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            return;
        }
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        if q != 0.0 {
            push(q / a);
            push(c / q);
        }
    }

    /// As a `kurbo` cubic (for reference computations and verifiers).
    pub fn to_kurbo(&self) -> kurbo::CubicBez {
        kurbo::CubicBez::new(self.p0, self.p1, self.p2, self.p3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Cubic {
        Cubic::new(
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(3.0, -1.0),
            Point::new(4.0, 1.0),
        )
    }

    #[test]
    fn eval_matches_kurbo_and_derivatives_match_differences() {
        use kurbo::ParamCurve;
        let c = sample();
        let k = c.to_kurbo();
        for i in 0..=10 {
            let t = f64::from(i) / 10.0;
            assert!(c.eval(t).distance(Point::from(k.eval(t))) < 1e-12);
            let h = 1e-6;
            let fd = (c.eval(t + h) - c.eval(t - h)) / (2.0 * h);
            assert!((fd - c.d1(t)).length() < 1e-6);
            let fd2 = (c.d1(t + h) - c.d1(t - h)) / (2.0 * h);
            assert!((fd2 - c.d2(t)).length() < 1e-5);
        }
    }

    #[test]
    fn parallel_roots_are_parallel() {
        let c = sample();
        let dir = Vec2::new(1.0, 0.3);
        let mut roots = Vec::new();
        c.parallel_roots(dir, 0.0, 1.0, &mut roots);
        let real: Vec<f64> = roots
            .iter()
            .copied()
            .filter(|t| c.d1(*t).cross(dir).abs() < 1e-9)
            .collect();
        assert_eq!(real.len(), 2, "{roots:?}");
    }
}
