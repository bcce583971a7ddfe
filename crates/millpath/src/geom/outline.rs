//! Closed outlines made of lines and exact circular arcs, over `cavalier_contours`.
//!
//! An [`Outline`] is a closed polyline whose vertices carry a *bulge*: `tan(θ/4)` for the arc
//! of sweep `θ` that leaves the vertex (positive counter-clockwise, 0 for a straight segment).
//! Arcs stay exact all the way to G2/G3 output.

use super::{Aabb, LENGTH_EPS, Point, Vec2};
use crate::error::InputError;
use cavalier_contours::polyline::{
    PlineCreation, PlineOrientation, PlineSource, PlineSourceMut, PlineVertex, Polyline,
};

/// The direction an outline runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Winding {
    /// Counter-clockwise: positive area. Pocket boundaries run this way once imported.
    CounterClockwise,
    /// Clockwise: negative area. Islands run this way once imported.
    Clockwise,
}

/// A closed, non-self-intersecting outline of lines and arcs.
#[derive(Debug, Clone)]
pub struct Outline {
    pline: Polyline<f64>,
}

/// The largest coordinate magnitude an outline accepts, mm (1 km). Far beyond any machine
/// table, and small enough that lengths, areas and offsets computed from the vertices stay
/// finite and accurate in f64 (`cavalier_contours` asserts on results that overflow).
pub const MAX_COORDINATE_MM: f64 = 1e6;

/// The largest bulge magnitude an outline accepts: `tan(θ/4) = 1000` is an arc of sweep
/// θ ≈ 359.77°; larger bulges give arcs whose radius `chord·(b + 1/b)/4` overflows long
/// before it means anything.
pub const MAX_BULGE: f64 = 1e3;

impl Outline {
    /// Builds an outline from `(point, bulge)` vertices, checking that it is a valid closed
    /// loop: at least two vertices (three if all are straight), finite coordinates and bulges,
    /// no zero-length segment, no self-intersection, non-zero area. `origin` names where the
    /// vertices came from, for error messages.
    pub fn new(vertices: &[(Point, f64)], origin: &str) -> Result<Self, InputError> {
        for (i, (p, b)) in vertices.iter().enumerate() {
            if !p.is_finite() || !b.is_finite() {
                return Err(InputError::new(
                    "outline vertex",
                    format!("({}, {}, bulge {})", p.x, p.y, b),
                )
                .at(format!("{origin}, vertex {i}"))
                .expected("finite coordinates and bulge"));
            }
        }
        let mut pline = Polyline::with_capacity(vertices.len(), true);
        for (p, b) in vertices {
            pline.add(p.x, p.y, *b);
        }
        // A closing vertex repeated at the end is common in files: drop it.
        if pline.vertex_count() > 1 {
            let first = pline.at(0);
            let last = pline.at(pline.vertex_count() - 1);
            if (first.x - last.x).hypot(first.y - last.y) <= LENGTH_EPS {
                pline.remove_last();
            }
        }
        Self::from_polyline(pline, origin)
    }

    /// Builds an outline of straight segments through `points`.
    pub fn from_points(points: &[Point], origin: &str) -> Result<Self, InputError> {
        let v: Vec<(Point, f64)> = points.iter().map(|p| (*p, 0.0)).collect();
        Self::new(&v, origin)
    }

    /// Wraps a `cavalier_contours` polyline after the same checks as [`Outline::new`].
    pub(crate) fn from_polyline(
        mut pline: Polyline<f64>,
        origin: &str,
    ) -> Result<Self, InputError> {
        pline.set_is_closed(true);
        let n = pline.vertex_count();
        for (i, v) in pline.iter_vertexes().enumerate() {
            let ok_xy = v.x.abs() <= MAX_COORDINATE_MM && v.y.abs() <= MAX_COORDINATE_MM;
            let ok_bulge = v.bulge.abs() <= MAX_BULGE; // false for NaN
            if !ok_xy || !ok_bulge {
                return Err(InputError::new(
                    "outline vertex",
                    format!("({}, {}, bulge {})", v.x, v.y, v.bulge),
                )
                .at(format!("{origin}, vertex {i}"))
                .expected(format!(
                    "finite coordinates within ±{MAX_COORDINATE_MM} mm and |bulge| ≤ {MAX_BULGE}"
                )));
            }
        }
        let all_straight = pline.iter_vertexes().all(|v| v.bulge.abs() < 1e-12);
        if n < 2 || (all_straight && n < 3) {
            return Err(InputError::new("outline vertex count", n)
                .at(origin)
                .expected("a closed outline with at least 3 vertices (2 if joined by arcs)"));
        }
        for i in 0..n {
            let a = pline.at(i);
            let b = pline.at(pline.next_wrapping_index(i));
            if (a.x - b.x).hypot(a.y - b.y) <= LENGTH_EPS {
                return Err(
                    InputError::new("outline vertex", format!("({}, {})", a.x, a.y))
                        .at(format!("{origin}, vertex {i}"))
                        .expected("distinct consecutive vertices (this one repeats the next)"),
                );
            }
        }
        if let Some((i, j, at)) = first_crossing(&pline) {
            return Err(InputError::new(
                "outline",
                format!(
                    "self-intersecting near ({:.4}, {:.4}): segments from vertex {i} and vertex {j}",
                    at.x, at.y
                ),
            )
            .at(origin)
            .expected("a simple closed outline that does not cross itself"));
        }
        if pline.area().abs() <= LENGTH_EPS {
            return Err(InputError::new("outline area", pline.area())
                .at(origin)
                .expected("an outline enclosing a non-zero area"));
        }
        Ok(Outline { pline })
    }

    /// The underlying `cavalier_contours` polyline.
    pub(crate) fn polyline(&self) -> &Polyline<f64> {
        &self.pline
    }

    /// The vertices as `(point, bulge)` pairs.
    pub fn vertices(&self) -> impl Iterator<Item = (Point, f64)> + '_ {
        self.pline
            .iter_vertexes()
            .map(|v: PlineVertex<f64>| (Point::new(v.x, v.y), v.bulge))
    }

    /// The sharpest convex corner: its interior angle (radians, in `(0, π)`) and its vertex;
    /// `None` when no vertex is a convex corner (a circle of arcs, tangent joins). The angle is
    /// between the tangents of the two segments meeting there (an arc's tangent leaves its
    /// chord by half the arc's sweep `θ = 4·atan(bulge)`).
    pub fn sharpest_corner(&self) -> Option<(f64, Point)> {
        let n = self.pline.vertex_count();
        let ccw = self.pline.area() > 0.0;
        let tangents = |i: usize| -> (Vec2, Vec2) {
            let a = self.pline.at(i);
            let b = self.pline.at(self.pline.next_wrapping_index(i));
            let chord = Vec2::new(b.x - a.x, b.y - a.y);
            let half = 2.0 * a.bulge.atan();
            (chord.rotate(-half), chord.rotate(half))
        };
        let mut best: Option<(f64, Point)> = None;
        for i in 0..n {
            let (_, incoming) = tangents(self.pline.prev_wrapping_index(i));
            let (outgoing, _) = tangents(i);
            let turn = incoming.cross(outgoing).atan2(incoming.dot(outgoing));
            let turn = if ccw { turn } else { -turn };
            if turn > 1e-9 {
                let interior = std::f64::consts::PI - turn;
                if best.is_none_or(|(a, _)| interior < a) {
                    let v = self.pline.at(i);
                    best = Some((interior, Point::new(v.x, v.y)));
                }
            }
        }
        best
    }

    /// Number of vertices (= number of segments, the outline being closed).
    pub fn len(&self) -> usize {
        self.pline.vertex_count()
    }

    /// Always false: a valid outline has vertices.
    pub fn is_empty(&self) -> bool {
        self.pline.vertex_count() == 0
    }

    /// Signed area in mm²: positive for counter-clockwise.
    pub fn signed_area(&self) -> f64 {
        self.pline.area()
    }

    /// Perimeter in mm.
    pub fn length(&self) -> f64 {
        self.pline.path_length()
    }

    /// The direction the outline runs in.
    pub fn winding(&self) -> Winding {
        match self.pline.orientation() {
            PlineOrientation::Clockwise => Winding::Clockwise,
            _ => Winding::CounterClockwise,
        }
    }

    /// This outline running in `winding` direction (reversed if needed).
    #[must_use]
    pub fn with_winding(mut self, winding: Winding) -> Self {
        if self.winding() != winding {
            self.pline.invert_direction_mut();
        }
        self
    }

    /// Bounding box of the outline, arcs included.
    pub fn bounds(&self) -> Aabb {
        match self.pline.extents() {
            Some(e) => Aabb {
                min: Point::new(e.min_x, e.min_y),
                max: Point::new(e.max_x, e.max_y),
            },
            None => Aabb::EMPTY,
        }
    }

    /// Winding number of `p` about the outline: non-zero inside.
    pub fn winding_number(&self, p: Point) -> i32 {
        self.pline
            .winding_number(cavalier_contours::core::math::Vector2::new(p.x, p.y))
    }

    /// True when `p` is strictly inside (non-zero winding number).
    pub fn contains(&self, p: Point) -> bool {
        self.winding_number(p) != 0
    }

    /// Distance from `p` to the nearest point of the outline.
    pub fn distance_to(&self, p: Point) -> f64 {
        self.pline
            .closest_point(cavalier_contours::core::math::Vector2::new(p.x, p.y), 1e-12)
            .map_or(f64::INFINITY, |c| c.distance)
    }

    /// Parallel offsets at signed distance `d` (cavalier_contours convention: positive offsets
    /// a counter-clockwise outline inward). Offsets keep exact arcs; loops that would gouge are
    /// trimmed. May return several outlines, or none when the offset vanishes.
    ///
    /// The loops are taken as cavalier_contours returns them (closed where it left them
    /// open: [`Outline::signed_area`] is zero for an open loop), without [`Outline::new`]'s
    /// checks: an offset of a simple loop is simple.
    pub fn offset(&self, d: f64) -> Vec<Outline> {
        super::loops::offset_loops(&self.pline, d)
            .into_iter()
            .map(Outline::wrap_offset)
            .collect()
    }

    /// An offset loop as an outline, unchecked (see [`Outline::offset`]).
    pub(crate) fn wrap_offset(pline: Polyline<f64>) -> Outline {
        Outline { pline }
    }

    /// `n` points equally spaced in arc length along the outline, from its first vertex.
    pub fn sample(&self, n: usize) -> Vec<Point> {
        super::loops::sample_loop(&self.pline, n)
    }
}

/// The first place where the closed `pline` crosses or overlaps itself: the start vertices of
/// the two segments and a point there; `None` for a simple loop.
///
/// cavalier_contours' scan (`visit_self_intersects`) takes two segments as parallel when the
/// cross product of their direction vectors is below its position epsilon (1e-5), a test
/// that is not scaled by the segments' lengths: two *consecutive* segments 0.06 mm long that
/// turn by 1e-4 rad (a smooth 50,000-vertex outline of radius 500 mm) have a cross product of
/// 4e-7 and are reported as overlapping. Consecutive segments can only overlap by doubling
/// back, so an overlap reported between consecutive straight segments whose directions agree
/// (positive dot product) is dropped; every other report stands.
fn first_crossing(pline: &Polyline<f64>) -> Option<(usize, usize, Point)> {
    use cavalier_contours::polyline::PlineIntersect;
    use cavalier_contours::static_aabb2d_index::Control;
    let mut found = None;
    let consecutive_same_way = |i: usize, j: usize| -> bool {
        let (i, j) = if pline.next_wrapping_index(i) == j {
            (i, j)
        } else if pline.next_wrapping_index(j) == i {
            (j, i)
        } else {
            return false;
        };
        let (a, b, c) = (
            pline.at(i),
            pline.at(pline.next_wrapping_index(i)),
            pline.at(pline.next_wrapping_index(j)),
        );
        let straight = a.bulge.abs() < 1e-12 && b.bulge.abs() < 1e-12;
        straight && (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) > 0.0
    };
    pline.visit_self_intersects(&mut |x: PlineIntersect<f64>| {
        let hit = match x {
            PlineIntersect::Basic(b) => Some((b.start_index1, b.start_index2, b.point)),
            PlineIntersect::Overlapping(o) => {
                if consecutive_same_way(o.start_index1, o.start_index2) {
                    None
                } else {
                    Some((o.start_index1, o.start_index2, o.point1))
                }
            }
        };
        match hit {
            Some((i, j, p)) => {
                found = Some((i.min(j), i.max(j), Point::new(p.x, p.y)));
                Control::Break(())
            }
            _ => Control::Continue,
        }
    });
    found
}

/// Area of the material inside `outer` and outside `islands`, mm² (islands inside `outer`,
/// not overlapping).
pub fn area_less_islands(outer: &Outline, islands: &[Outline]) -> f64 {
    outer.signed_area().abs() - islands.iter().map(|i| i.signed_area().abs()).sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Outline {
        Outline::from_points(
            &[
                Point::new(0.0, 0.0),
                Point::new(10.0, 0.0),
                Point::new(10.0, 10.0),
                Point::new(0.0, 10.0),
            ],
            "test",
        )
        .unwrap()
    }

    #[test]
    fn square_properties() {
        let s = square();
        assert!((s.signed_area() - 100.0).abs() < 1e-12);
        assert!((s.length() - 40.0).abs() < 1e-12);
        assert_eq!(s.winding(), Winding::CounterClockwise);
        assert!(s.contains(Point::new(5.0, 5.0)));
        assert!(!s.contains(Point::new(15.0, 5.0)));
        assert!((s.distance_to(Point::new(5.0, 4.0)) - 4.0).abs() < 1e-12);
        let cw = s.with_winding(Winding::Clockwise);
        assert!((cw.signed_area() + 100.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_outlines() {
        let bow = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 10.0),
            Point::new(10.0, 0.0),
            Point::new(0.0, 10.0),
        ];
        let e = Outline::from_points(&bow, "bow.json").unwrap_err();
        assert!(e.to_string().contains("self-intersecting"), "{e}");
        assert!(
            e.to_string().contains("(5.0000, 5.0000)") && e.to_string().contains("vertex 0"),
            "{e}"
        );
        let nan = [
            Point::new(0.0, 0.0),
            Point::new(f64::NAN, 1.0),
            Point::new(1.0, 0.0),
        ];
        let e = Outline::from_points(&nan, "nan.json").unwrap_err();
        assert!(e.to_string().contains("vertex 1"), "{e}");
        let two = [Point::new(0.0, 0.0), Point::new(1.0, 0.0)];
        assert!(Outline::from_points(&two, "two").is_err());
    }

    /// Consecutive segments that nearly continue each other are not an overlap (cavalier's
    /// unscaled parallel test reports them); consecutive segments that double back are.
    #[test]
    fn consecutive_segments_overlap_only_when_doubling_back() {
        // 50,000 vertices on a wavy circle of radius about 500 mm (the radius a function of
        // the angle, so simple): 0.063 mm chords, nearly straight where the waves flatten.
        let n = 50_000;
        let star: Vec<Point> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let r = 500.0 * (1.0 + 0.04 * (7.0 * a).sin() + 0.01 * (61.0 * a).cos());
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect();
        let c = Outline::from_points(&star, "dense star").expect("a simple outline");
        assert_eq!(c.len(), n);
        assert!(
            c.polyline().scan_for_self_intersect(),
            "cavalier's own scan reports this loop (else this test tests nothing)"
        );
        // A spike: out along the x axis and back over the same line.
        let spike = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(20.0, 0.0),
            Point::new(15.0, 0.0),
            Point::new(10.0, 10.0),
        ];
        let e = Outline::from_points(&spike, "spike").unwrap_err();
        assert!(e.to_string().contains("self-intersecting"), "{e}");
    }

    /// A 30-60-90 triangle, either way round and from any start: 30° at its sharpest vertex;
    /// arcs count by their tangents (a D shape's corners are right angles).
    #[test]
    fn sharpest_corner_of_a_triangle_and_a_d_shape() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(3f64.sqrt() * 10.0, 0.0),
            Point::new(0.0, 10.0),
        ];
        for pts in [tri.to_vec(), tri.iter().rev().copied().collect()] {
            for k in 0..3 {
                let mut p = pts.clone();
                p.rotate_left(k);
                let o = Outline::from_points(&p, "tri").unwrap();
                let (a, at) = o.sharpest_corner().unwrap();
                assert!((a.to_degrees() - 30.0).abs() < 1e-9, "{}", a.to_degrees());
                assert!(at.distance(tri[1]) < 1e-12, "{at:?}");
            }
        }
        // A half disc: the diameter from (-5, 0) to (5, 0), then a half circle back over the top.
        let d = Outline::new(
            &[(Point::new(-5.0, 0.0), 0.0), (Point::new(5.0, 0.0), 1.0)],
            "d",
        )
        .unwrap();
        let (a, _) = d.sharpest_corner().unwrap();
        assert!((a.to_degrees() - 90.0).abs() < 1e-9, "{}", a.to_degrees());
    }

    #[test]
    fn circle_from_two_arcs() {
        let c = Outline::new(
            &[(Point::new(-5.0, 0.0), 1.0), (Point::new(5.0, 0.0), 1.0)],
            "c",
        )
        .unwrap();
        assert!((c.signed_area() - std::f64::consts::PI * 25.0).abs() < 1e-9);
        let inner = c.offset(1.0);
        assert_eq!(inner.len(), 1);
        assert!((inner[0].signed_area() - std::f64::consts::PI * 16.0).abs() < 1e-9);
    }
}
