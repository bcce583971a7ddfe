//! Affine maps of the plane and the open or closed pieces (vertices with bulges) the importers
//! build, shared by DXF blocks (INSERT) and SVG `transform`.
//!
//! An [`Affine`] `[a, b, c, d, e, f]` maps `(x, y)` to `(a·x + c·y + e, b·x + d·y + f)`, SVG's
//! `matrix(a b c d e f)`. A *similarity* (rotation, uniform scale, reflection, translation)
//! maps circular arcs to circular arcs: the vertices are mapped and a bulge `tan(θ/4)` keeps
//! its value, its sign flipped by a reflection (negative determinant). Any other map (a
//! non-uniform scale, a skew) turns arcs into elliptical ones: each arc is first flattened
//! into chords within the flattening tolerance `t` *measured after the map* (the arc's
//! radius is taken as `R·σmax`, σmax the map's larger singular value), so that the result
//! stays within `t` of the exact image.
//!
//! Chords of an arc of radius `R` with `n` pieces deviate by `R·(1 − cos(θ/2n))`; `n` is
//! the smallest count keeping this within `t`.

use crate::geom::Point;

/// Vertices with bulges; for an open piece the last vertex's bulge is unused.
pub type Piece = Vec<(Point, f64)>;

/// A 2×3 affine map, SVG's `matrix(a b c d e f)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine(pub [f64; 6]);

impl Affine {
    /// A translation.
    pub fn translate(x: f64, y: f64) -> Affine {
        Affine([1.0, 0.0, 0.0, 1.0, x, y])
    }

    /// A scaling about the origin.
    pub fn scale(sx: f64, sy: f64) -> Affine {
        Affine([sx, 0.0, 0.0, sy, 0.0, 0.0])
    }

    /// A rotation about the origin by `angle` radians, counter-clockwise for y up.
    pub fn rotate(angle: f64) -> Affine {
        let (s, c) = angle.sin_cos();
        Affine([c, s, -s, c, 0.0, 0.0])
    }

    /// `self` after `first`: `(self ∘ first)(p) = self(first(p))`.
    pub fn after(self, first: Affine) -> Affine {
        let [a, b, c, d, e, f] = self.0;
        let [a2, b2, c2, d2, e2, f2] = first.0;
        Affine([
            a * a2 + c * b2,
            b * a2 + d * b2,
            a * c2 + c * d2,
            b * c2 + d * d2,
            a * e2 + c * f2 + e,
            b * e2 + d * f2 + f,
        ])
    }

    /// The image of `p`.
    pub fn apply(&self, p: Point) -> Point {
        let [a, b, c, d, e, f] = self.0;
        Point::new(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }

    /// The determinant of the linear part (negative for a reflection).
    pub fn det(&self) -> f64 {
        let [a, b, c, d, ..] = self.0;
        a * d - b * c
    }

    /// The larger singular value of the linear part (the largest stretch).
    pub fn max_stretch(&self) -> f64 {
        let [a, b, c, d, ..] = self.0;
        let s = a * a + b * b + c * c + d * d;
        let det = self.det();
        (0.5 * (s + (s * s - 4.0 * det * det).max(0.0).sqrt())).sqrt()
    }

    /// Whether the map keeps circles circles (within 1e-9 relative).
    pub fn is_similarity(&self) -> bool {
        let [a, b, c, d, ..] = self.0;
        let n = (a.abs() + b.abs() + c.abs() + d.abs()).max(1e-300);
        let rot = (a - d).abs() + (b + c).abs();
        let refl = (a + d).abs() + (b - c).abs();
        rot.min(refl) <= 1e-9 * n
    }

    /// Whether every coefficient is finite and the map is not singular.
    pub fn is_valid(&self) -> bool {
        self.0.iter().all(|v| v.is_finite()) && self.det() != 0.0 && self.det().is_finite()
    }
}

/// The image of `piece` under `t`, arcs kept exact under a similarity, else flattened within
/// `tol` (after the map).
pub fn transform_piece(piece: Piece, t: &Affine, tol: f64) -> Piece {
    if t.is_similarity() {
        let s = t.det().signum();
        return piece
            .into_iter()
            .map(|(p, b)| (t.apply(p), s * b))
            .collect();
    }
    let stretch = t.max_stretch();
    let mut out = Piece::with_capacity(piece.len());
    for (i, &(p, b)) in piece.iter().enumerate() {
        out.push((t.apply(p), 0.0));
        if b != 0.0
            && let Some(&(q, _)) = piece.get(i + 1)
        {
            for m in arc_points(p, q, b, tol / stretch).into_iter().skip(1) {
                out.push((t.apply(m), 0.0));
            }
        }
    }
    out
}

/// The interior points of the chords flattening the arc from `p` to `q` with bulge `b`
/// within `tol` (neither end included).
pub fn arc_points(p: Point, q: Point, b: f64, tol: f64) -> Vec<Point> {
    let chord = p.distance(q);
    if chord <= 0.0 || !b.is_finite() || b == 0.0 {
        return Vec::new();
    }
    let theta = 4.0 * b.atan(); // signed sweep
    let r = chord * (1.0 + b * b) / (4.0 * b.abs());
    let half = if tol >= r {
        std::f64::consts::PI
    } else {
        (1.0 - tol / r).acos()
    };
    let n = ((theta.abs() / (2.0 * half)).ceil() as usize).clamp(1, 100_000);
    let mid = Point::new(0.5 * (p.x + q.x), 0.5 * (p.y + q.y));
    let (ux, uy) = ((q.x - p.x) / chord, (q.y - p.y) / chord);
    let h = 0.5 * chord / (0.5 * theta).tan();
    let c = Point::new(mid.x - uy * h, mid.y + ux * h);
    let (vx, vy) = (p.x - c.x, p.y - c.y);
    (1..n)
        .map(|k| {
            let (s, co) = (theta * k as f64 / n as f64).sin_cos();
            Point::new(c.x + co * vx - s * vy, c.y + s * vx + co * vy)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_applies_first_then_self() {
        let t = Affine::translate(5.0, 0.0).after(Affine::rotate(std::f64::consts::FRAC_PI_2));
        let p = t.apply(Point::new(1.0, 0.0));
        assert!(p.distance(Point::new(5.0, 1.0)) < 1e-12, "{p:?}");
        assert!(Affine::scale(2.0, -2.0).is_similarity());
        assert!(!Affine::scale(2.0, 1.0).is_similarity());
        assert!((Affine::scale(3.0, 1.0).max_stretch() - 3.0).abs() < 1e-12);
    }

    /// A half circle flattened: every chord's mid point within `tol` of the circle, the
    /// points on it, and on the side the bulge's sign says.
    #[test]
    fn arc_points_stay_within_tolerance() {
        for (b, y_sign) in [(1.0, -1.0), (-1.0, 1.0)] {
            let (p, q) = (Point::new(-5.0, 0.0), Point::new(5.0, 0.0));
            let pts = arc_points(p, q, b, 0.01);
            assert!(pts.len() > 10);
            let all: Vec<Point> = std::iter::once(p).chain(pts).chain([q]).collect();
            for w in all.windows(2) {
                let m = Point::new(0.5 * (w[0].x + w[1].x), 0.5 * (w[0].y + w[1].y));
                let r = m.distance(Point::ORIGIN);
                assert!((5.0 - r) <= 0.01 + 1e-12 && r <= 5.0 + 1e-9, "{r}");
                assert!((w[0].distance(Point::ORIGIN) - 5.0).abs() < 1e-9);
            }
            assert!(
                all[all.len() / 2].y * y_sign > 4.9,
                "{:?}",
                all[all.len() / 2]
            );
        }
    }
}
