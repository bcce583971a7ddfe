//! Axis-aligned bounding boxes.

use super::Point;
use serde::{Deserialize, Serialize};

/// An axis-aligned rectangle; empty when `min > max`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    /// The empty box: adding any point gives the box of that point.
    pub const EMPTY: Aabb = Aabb {
        min: Point::new(f64::INFINITY, f64::INFINITY),
        max: Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    };

    /// The smallest box holding all `points`.
    pub fn from_points(points: impl IntoIterator<Item = Point>) -> Self {
        points.into_iter().fold(Aabb::EMPTY, Aabb::with_point)
    }

    /// This box grown to hold `p`.
    #[must_use]
    pub fn with_point(self, p: Point) -> Self {
        Aabb {
            min: Point::new(self.min.x.min(p.x), self.min.y.min(p.y)),
            max: Point::new(self.max.x.max(p.x), self.max.y.max(p.y)),
        }
    }

    /// The union of two boxes.
    #[must_use]
    pub fn union(self, o: Aabb) -> Self {
        self.with_point(o.min).with_point(o.max)
    }

    /// This box grown by `d` on every side.
    #[must_use]
    pub fn inflate(self, d: f64) -> Self {
        Aabb {
            min: Point::new(self.min.x - d, self.min.y - d),
            max: Point::new(self.max.x + d, self.max.y + d),
        }
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y)
    }

    /// Width (x extent).
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }

    /// Height (y extent).
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }

    /// The centre.
    pub fn center(&self) -> Point {
        self.min.midpoint(self.max)
    }

    /// True when `p` lies inside or on the border.
    pub fn contains(&self, p: Point) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
}
