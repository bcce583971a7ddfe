//! 2-D positions and directions.

use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// A position in the plane, in millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Point {
    /// X coordinate.
    pub x: f64,
    /// Y coordinate.
    pub y: f64,
}

/// A direction or displacement in the plane, in millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Vec2 {
    /// X component.
    pub x: f64,
    /// Y component.
    pub y: f64,
}

impl Point {
    /// The origin.
    pub const ORIGIN: Point = Point { x: 0.0, y: 0.0 };

    /// A new point.
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }

    /// The displacement from the origin to this point.
    pub fn to_vec2(self) -> Vec2 {
        Vec2::new(self.x, self.y)
    }

    /// Euclidean distance to `other`.
    pub fn distance(self, other: Point) -> f64 {
        (self - other).length()
    }

    /// Linear interpolation: `self` at `t = 0`, `other` at `t = 1`.
    pub fn lerp(self, other: Point, t: f64) -> Point {
        self + (other - self) * t
    }

    /// The distance to the segment `a`–`b` (to `a` where the two coincide).
    pub fn distance_to_segment(self, a: Point, b: Point) -> f64 {
        let d = b - a;
        let l2 = d.dot(d);
        let t = if l2 > 0.0 {
            ((self - a).dot(d) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.distance(a + d * t)
    }

    /// The midpoint of `self` and `other`.
    pub fn midpoint(self, other: Point) -> Point {
        self.lerp(other, 0.5)
    }

    /// True when both coordinates are finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }

    /// This point rotated by `angle` radians about `center`.
    pub fn rotate_about(self, center: Point, angle: f64) -> Point {
        center + (self - center).rotate(angle)
    }
}

impl Vec2 {
    /// The zero vector.
    pub const ZERO: Vec2 = Vec2 { x: 0.0, y: 0.0 };

    /// A new vector.
    pub const fn new(x: f64, y: f64) -> Self {
        Vec2 { x, y }
    }

    /// The unit vector at `angle` radians from the +X axis.
    pub fn from_angle(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Vec2::new(c, s)
    }

    /// Dot product.
    pub fn dot(self, o: Vec2) -> f64 {
        self.x * o.x + self.y * o.y
    }

    /// The z component of the 3-D cross product: positive when `o` is counter-clockwise from
    /// `self`.
    pub fn cross(self, o: Vec2) -> f64 {
        self.x * o.y - self.y * o.x
    }

    /// Euclidean length: `√(x² + y²)`, through `f64::hypot` only where the squares would
    /// overflow or lose precision to underflow (beyond about 1e±145; `hypot` avoids both at
    /// about three times the cost, which profiles of the pocket fuzz target put at a fifth of
    /// its time).
    pub fn length(self) -> f64 {
        let s = self.x * self.x + self.y * self.y;
        if (1e-290..=1e290).contains(&s) {
            s.sqrt()
        } else {
            self.x.hypot(self.y)
        }
    }

    /// Squared length.
    pub fn length_squared(self) -> f64 {
        self.dot(self)
    }

    /// The unit vector in this direction, or `None` for a vector shorter than `1e-300`.
    pub fn normalize(self) -> Option<Vec2> {
        let l = self.length();
        (l > 1e-300 && l.is_finite()).then(|| self / l)
    }

    /// This vector turned 90° counter-clockwise.
    pub fn perp(self) -> Vec2 {
        Vec2::new(-self.y, self.x)
    }

    /// Angle from the +X axis in radians, in (-π, π].
    pub fn angle(self) -> f64 {
        self.y.atan2(self.x)
    }

    /// This vector rotated counter-clockwise by `angle` radians.
    pub fn rotate(self, angle: f64) -> Vec2 {
        let (s, c) = angle.sin_cos();
        Vec2::new(c * self.x - s * self.y, s * self.x + c * self.y)
    }

    /// The point at this displacement from the origin.
    pub fn to_point(self) -> Point {
        Point::new(self.x, self.y)
    }

    /// True when both components are finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl Sub for Point {
    type Output = Vec2;
    fn sub(self, o: Point) -> Vec2 {
        Vec2::new(self.x - o.x, self.y - o.y)
    }
}

impl Add<Vec2> for Point {
    type Output = Point;
    fn add(self, v: Vec2) -> Point {
        Point::new(self.x + v.x, self.y + v.y)
    }
}

impl AddAssign<Vec2> for Point {
    fn add_assign(&mut self, v: Vec2) {
        *self = *self + v;
    }
}

impl Sub<Vec2> for Point {
    type Output = Point;
    fn sub(self, v: Vec2) -> Point {
        Point::new(self.x - v.x, self.y - v.y)
    }
}

impl SubAssign<Vec2> for Point {
    fn sub_assign(&mut self, v: Vec2) {
        *self = *self - v;
    }
}

impl Add for Vec2 {
    type Output = Vec2;
    fn add(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x + o.x, self.y + o.y)
    }
}

impl AddAssign for Vec2 {
    fn add_assign(&mut self, o: Vec2) {
        *self = *self + o;
    }
}

impl Sub for Vec2 {
    type Output = Vec2;
    fn sub(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x - o.x, self.y - o.y)
    }
}

impl SubAssign for Vec2 {
    fn sub_assign(&mut self, o: Vec2) {
        *self = *self - o;
    }
}

impl Mul<f64> for Vec2 {
    type Output = Vec2;
    fn mul(self, s: f64) -> Vec2 {
        Vec2::new(self.x * s, self.y * s)
    }
}

impl Mul<Vec2> for f64 {
    type Output = Vec2;
    fn mul(self, v: Vec2) -> Vec2 {
        v * self
    }
}

impl Div<f64> for Vec2 {
    type Output = Vec2;
    fn div(self, s: f64) -> Vec2 {
        Vec2::new(self.x / s, self.y / s)
    }
}

impl Neg for Vec2 {
    type Output = Vec2;
    fn neg(self) -> Vec2 {
        Vec2::new(-self.x, -self.y)
    }
}

impl From<Point> for kurbo::Point {
    fn from(p: Point) -> Self {
        kurbo::Point::new(p.x, p.y)
    }
}

impl From<kurbo::Point> for Point {
    fn from(p: kurbo::Point) -> Self {
        Point::new(p.x, p.y)
    }
}

impl From<Vec2> for kurbo::Vec2 {
    fn from(v: Vec2) -> Self {
        kurbo::Vec2::new(v.x, v.y)
    }
}

impl From<kurbo::Vec2> for Vec2 {
    fn from(v: kurbo::Vec2) -> Self {
        Vec2::new(v.x, v.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_segment_is_the_least_over_dense_samples() {
        let (a, b) = (Point::new(1.0, -2.0), Point::new(7.0, 3.0));
        for q in [
            Point::new(0.0, 0.0),
            Point::new(4.0, 0.5),
            Point::new(9.0, 5.0),
            Point::new(-3.0, -4.0),
            Point::new(3.0, 6.0),
        ] {
            let dense = (0..=100_000)
                .map(|k| q.distance(a.lerp(b, f64::from(k) / 100_000.0)))
                .fold(f64::INFINITY, f64::min);
            let d = q.distance_to_segment(a, b);
            assert!(
                d <= dense + 1e-12 && dense - d < 1e-4,
                "{q:?}: {d} against {dense}"
            );
        }
        assert!(
            (Point::new(3.0, 4.0).distance_to_segment(a, a) - a.distance(Point::new(3.0, 4.0)))
                .abs()
                < 1e-12
        );
    }

    #[test]
    fn point_vector_algebra() {
        let a = Point::new(1.0, 2.0);
        let b = Point::new(4.0, 6.0);
        let d = b - a;
        assert_eq!(d, Vec2::new(3.0, 4.0));
        assert!((d.length() - 5.0).abs() < 1e-15);
        assert_eq!(a + d, b);
        assert!((Vec2::new(1.0, 0.0).cross(Vec2::new(0.0, 1.0)) - 1.0).abs() < 1e-15);
        assert_eq!(Vec2::new(1.0, 0.0).perp(), Vec2::new(0.0, 1.0));
        assert!(Vec2::ZERO.normalize().is_none());
        let r = Point::new(2.0, 0.0).rotate_about(Point::ORIGIN, std::f64::consts::FRAC_PI_2);
        assert!(r.distance(Point::new(0.0, 2.0)) < 1e-15);
    }
}
