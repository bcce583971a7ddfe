//! Holes: circles of a drawing, and how an outline is recognised as one.
//!
//! A drawing gives a circle as a CIRCLE entity or an SVG `<circle>` (read as two exact half
//! arcs), as arcs of one centre and radius joined into a loop, or as a polygon: a spline or
//! Bézier circle flattened by the reader (within its tolerance, 0.001 mm by default) or a
//! polygon the CAD program wrote. All are taken alike, by their geometry:
//!
//! 1. **Fit.** Points equally spaced in arc length along the outline (at least 64, four per
//!    segment) give the least-squares circle `x² + y² + D·x + E·y + F = 0` (Kåsa's fit,
//!    linear in D, E, F; the points are centred on their mean first). The radius is the mean
//!    distance of the points from the fitted centre.
//! 2. **Check.** The outline is that circle when every point of it lies within `tolerance`
//!    of the circle: for a straight segment the exact nearest and farthest points from the
//!    centre (the end points, and the foot of the perpendicular), for an arc 32 points along
//!    it; and when its area is the circle's within the area of the band (`4π·r·tolerance`),
//!    so that a sliver lying along part of the circle is not taken for it (a closed outline
//!    within the band that encloses the circle's area goes once round it). The radius must
//!    exceed `2·tolerance`.
//!
//! The tolerance is the largest distance between the drawn outline and the hole's circle, mm:
//! a polygon whose chords stay within it of the circle is the circle; the hole's centre and
//! diameter are then known to within about the tolerance.

use super::{Outline, Point};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The default recognition tolerance, mm: ten times the readers' flattening tolerance, and
/// the accuracy a drilled hole is checked to.
pub const CIRCLE_TOLERANCE: f64 = 0.01;

/// A hole: a circle in the plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Hole {
    /// Its centre, mm.
    pub center: Point,
    /// Its diameter, mm.
    pub diameter: f64,
}

impl Hole {
    /// A hole at `center` of `diameter` mm.
    pub fn new(center: Point, diameter: f64) -> Self {
        Hole { center, diameter }
    }

    /// Its radius, mm.
    pub fn radius(&self) -> f64 {
        0.5 * self.diameter
    }

    /// The hole `outline` is when it is a circle within `tolerance` mm (module docs), else
    /// `None`.
    pub fn from_outline(outline: &Outline, tolerance: f64) -> Option<Hole> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return None;
        }
        let n = (4 * outline.len()).max(64);
        let pts = outline.sample(n);
        let (center, r) = fit_circle(&pts)?;
        if r <= 2.0 * tolerance {
            return None;
        }
        let area = outline.signed_area().abs();
        if (area - PI * r * r).abs() > 4.0 * PI * r * tolerance {
            return None;
        }
        if deviation(outline, center, r) > tolerance {
            return None;
        }
        Some(Hole {
            center,
            diameter: 2.0 * r,
        })
    }
}

/// Kåsa's least-squares circle through `pts`: (centre, mean radius); `None` when the points
/// are collinear or fewer than three.
fn fit_circle(pts: &[Point]) -> Option<(Point, f64)> {
    if pts.len() < 3 {
        return None;
    }
    let k = pts.len() as f64;
    let mx = pts.iter().map(|p| p.x).sum::<f64>() / k;
    let my = pts.iter().map(|p| p.y).sum::<f64>() / k;
    // Normal equations of Σ (u² + v² + D·u + E·v + F)² in centred coordinates u, v.
    let mut a = [[0.0f64; 3]; 3];
    let mut b = [0.0f64; 3];
    for p in pts {
        let (u, v) = (p.x - mx, p.y - my);
        let row = [u, v, 1.0];
        let rhs = -(u * u + v * v);
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += row[i] * row[j];
            }
            b[i] += row[i] * rhs;
        }
    }
    let [d, e, _] = solve3(a, b)?;
    let center = Point::new(mx - 0.5 * d, my - 0.5 * e);
    let r = pts.iter().map(|p| p.distance(center)).sum::<f64>() / k;
    (center.is_finite() && r.is_finite()).then_some((center, r))
}

/// Solves the 3×3 system `a·x = b` by Cramer's rule; `None` when it is singular.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(&a);
    let scale = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    if d.is_nan() || d.abs() <= 1e-12 * scale.powi(3) {
        return None;
    }
    let mut x = [0.0; 3];
    for (k, xk) in x.iter_mut().enumerate() {
        let mut m = a;
        for (row, bv) in m.iter_mut().zip(b) {
            row[k] = bv;
        }
        *xk = det(&m) / d;
    }
    Some(x)
}

/// The largest distance between `outline` and the circle (`center`, `r`), mm.
fn deviation(outline: &Outline, center: Point, r: f64) -> f64 {
    let v: Vec<(Point, f64)> = outline.vertices().collect();
    let mut worst = 0.0f64;
    for (i, &(a, bulge)) in v.iter().enumerate() {
        let b = v[(i + 1) % v.len()].0;
        if bulge.abs() < 1e-12 {
            // Farthest at an end; nearest at an end or at the foot of the perpendicular.
            let ab = b - a;
            let t = ((center - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
            let foot = a.lerp(b, t);
            for p in [a, b, foot] {
                worst = worst.max((p.distance(center) - r).abs());
            }
        } else {
            // The arc's points: its centre is off the chord's midpoint along the normal.
            let theta = 4.0 * bulge.atan();
            let chord = b - a;
            let half = 0.5 * chord.length();
            let rho = half / (0.5 * theta).sin().abs();
            let mid = a.lerp(b, 0.5);
            let off = rho * (0.5 * theta).cos() * theta.signum();
            let c = mid + chord.perp().normalize().unwrap_or_default() * off;
            let a0 = (a - c).angle();
            for k in 0..=32 {
                let ang = a0 + theta * f64::from(k) / 32.0;
                let p = c + crate::geom::Vec2::from_angle(ang) * rho;
                worst = worst.max((p.distance(center) - r).abs());
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle_of_arcs(c: Point, r: f64, pieces: usize) -> Outline {
        let b = (PI / pieces as f64 / 2.0).tan();
        let v: Vec<(Point, f64)> = (0..pieces)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / pieces as f64 + 0.3;
                (c + crate::geom::Vec2::from_angle(a) * r, b)
            })
            .collect();
        Outline::new(&v, "circle").unwrap()
    }

    fn polygon(c: Point, r: f64, n: usize, wobble: f64) -> Outline {
        let pts: Vec<Point> = (0..n)
            .map(|k| {
                let a = 2.0 * PI * (k as f64 + 0.3 * (k as f64 * 1.3).sin()) / n as f64;
                c + crate::geom::Vec2::from_angle(a) * (r + wobble * (3.0 * a).cos())
            })
            .collect();
        Outline::from_points(&pts, "polygon").unwrap()
    }

    #[test]
    fn exact_circles_are_holes_at_their_centre_and_diameter() {
        for (pieces, r) in [(2, 2.5), (3, 0.1), (4, 75.0), (7, 13.0)] {
            let c = Point::new(12.3, -45.6);
            let h = Hole::from_outline(&circle_of_arcs(c, r, pieces), CIRCLE_TOLERANCE).unwrap();
            assert!(h.center.distance(c) < 1e-9, "{h:?}");
            assert!((h.diameter - 2.0 * r).abs() < 1e-9, "{h:?}");
        }
    }

    #[test]
    fn polygons_within_the_tolerance_are_holes_and_others_are_not() {
        let c = Point::new(-3.0, 7.0);
        // 400 chords on r = 5: sagitta 5·(1 − cos(π/400)) ≈ 1.5e-4 mm.
        let h = Hole::from_outline(&polygon(c, 5.0, 400, 0.0), CIRCLE_TOLERANCE).unwrap();
        assert!(h.center.distance(c) < 1e-3 && (h.diameter - 10.0).abs() < 1e-3);
        // A lobed outline 0.05 mm off the circle is not one at 0.01 mm, is at 0.1 mm.
        let lobed = polygon(c, 5.0, 400, 0.05);
        assert!(Hole::from_outline(&lobed, CIRCLE_TOLERANCE).is_none());
        assert!(Hole::from_outline(&lobed, 0.1).is_some());
        // A square, a hexagon: not circles.
        assert!(Hole::from_outline(&polygon(c, 5.0, 4, 0.0), CIRCLE_TOLERANCE).is_none());
        assert!(Hole::from_outline(&polygon(c, 5.0, 6, 0.0), 0.1).is_none());
    }

    #[test]
    fn a_sliver_along_the_circle_is_not_a_hole() {
        // Out along a half circle of r = 10 and back 0.004 mm inside it: within the band,
        // but its area is nothing like the circle's.
        let mut pts: Vec<Point> = (0..=200)
            .map(|k| Point::ORIGIN + crate::geom::Vec2::from_angle(PI * k as f64 / 200.0) * 10.0)
            .collect();
        pts.extend(
            (0..=200).rev().map(|k| {
                Point::ORIGIN + crate::geom::Vec2::from_angle(PI * k as f64 / 200.0) * 9.996
            }),
        );
        let o = Outline::from_points(&pts, "sliver").unwrap();
        assert!(Hole::from_outline(&o, CIRCLE_TOLERANCE).is_none());
    }
}
