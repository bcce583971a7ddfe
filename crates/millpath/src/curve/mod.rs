//! Free-form curves: four-point interpolating cubics, C1 blends, Catmull-Rom and periodic
//! splines, optimal flattening within a chordal tolerance, biarcs.
//!
//! Every curve kind is stored the same way: a closed [`CompositeCurve`] of cubic Bézier
//! pieces ([`Cubic`]) with a global parameter `s ∈ [0, n)`: piece `⌊s⌋`, local `u = s − ⌊s⌋`.
//! Outlines are counter-clockwise once built (reversed if the input ran clockwise), so the
//! left normal `perp(P')` points inside.
//!
//! * `four_point`: the paper's cubic through 4 points at u = 0, 1/3, 2/3, 1 (basis derived,
//!   its misprint documented);
//! * `blend`: the C1 blend between groups that do not meet and to close the outline;
//! * `catmull_rom`, `spline`: closed curves through scattered points;
//! * [`flatten`]: the fewest chords within a tolerance, with an exact deviation;
//! * `intersect`: self-intersection checks, and the cut of the tiny inverted "fish-tail"
//!   lobe interpolating cubics leave at a nearly reversing corner (the paper's own outline
//!   has one at (1, 15));
//! * `verify`: dense-sampling verifiers that share no code with [`flatten`];
//! * `biarc`: arcs within a tolerance for G2/G3 output.

pub(crate) mod biarc;
pub(crate) mod blend;
pub(crate) mod catmull_rom;
mod cubic;
pub(crate) mod flatten;
pub(crate) mod four_point;
pub(crate) mod intersect;
pub(crate) mod spline;
pub(crate) mod verify;

pub use biarc::{ArcSeg, MIN_ARC_SWEEP, fit as fit_biarcs};
pub use catmull_rom::OpenChain;
pub use cubic::Cubic;
pub use flatten::{
    FlattenOptions, Flattening, PlanarCurve, asymptotic_count, flatten, flatten_curve, flatten_opt,
    kurbo_count,
};
pub use verify::{chordal_deviation, distance_to_curve, polyline_min_distance, segment_deviations};

use crate::error::InputError;
use crate::geom::{Aabb, LENGTH_EPS, Point, Vec2};
use serde::{Deserialize, Serialize};

/// Angle (rad) between the incoming and outgoing tangent above which a piece junction is a
/// corner (the curve is only C0 there): offsets join corners by arcs or trim them, and
/// flattening keeps a vertex on every corner.
pub const CORNER_ANGLE: f64 = 1e-7;

/// Which curve passes through the input points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CurveKind {
    /// The paper's four-point cubics (groups of exactly 4 points), blended where groups do not
    /// meet and to close the outline.
    #[default]
    FourPoint,
    /// Closed centripetal Catmull-Rom curve through every point (C1).
    CatmullRom,
    /// Closed periodic cubic spline through every point (C2), chord-length parameterised.
    Spline,
}

/// An input point with where it came from (`file:line`, `point 7`), for error messages.
#[derive(Debug, Clone, PartialEq)]
pub struct LabeledPoint {
    /// The point in mm.
    pub p: Point,
    /// Where it came from.
    pub origin: String,
}

/// What a piece of a [`CompositeCurve`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PieceKind {
    /// Interpolates input points.
    Interpolating,
    /// A C1 blend inserted between groups or to close the outline.
    Blend,
}

/// A closed curve of cubic Bézier pieces, counter-clockwise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompositeCurve {
    pieces: Vec<Cubic>,
    kinds: Vec<PieceKind>,
    corners: Vec<usize>,
    #[serde(default)]
    lobes: Vec<Lobe>,
    /// True when the input ran clockwise and the pieces were reversed.
    pub reversed: bool,
}

/// A fish-tail lobe of the curve as drawn, cut off at a corner by
/// `intersect::remove_fishtails`: from the crossing (the start of piece `corner`, where the
/// trimmed curve turns) out to the drawn corner point and back. A pass on the outline
/// (`--side on`) traces it; the region the outline bounds does not include it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Lobe {
    /// The piece whose start is the crossing.
    pub corner: usize,
    /// The end of the previous piece as drawn: the crossing to the corner point.
    pub to_tip: Cubic,
    /// The start of piece `corner` as drawn: the corner point back to the crossing.
    pub from_tip: Cubic,
}

impl CompositeCurve {
    /// A closed curve from pieces whose ends meet (within [`LENGTH_EPS`]); reversed to run
    /// counter-clockwise if needed.
    pub fn new(
        pieces: Vec<Cubic>,
        kinds: Vec<PieceKind>,
        origin: &str,
    ) -> Result<Self, InputError> {
        let n = pieces.len();
        if n == 0 || kinds.len() != n {
            return Err(InputError::new("curve pieces", n)
                .at(origin)
                .expected("at least one piece"));
        }
        for i in 0..n {
            let (a, b) = (pieces[i].p3, pieces[(i + 1) % n].p0);
            if a.distance(b) > LENGTH_EPS * (1.0 + a.to_vec2().length()) {
                return Err(
                    InputError::new("curve piece end", format!("({}, {})", a.x, a.y))
                        .at(format!("{origin}, piece {i}"))
                        .expected("pieces that meet end to start"),
                );
            }
        }
        let mut c = CompositeCurve {
            pieces,
            kinds,
            corners: Vec::new(),
            lobes: Vec::new(),
            reversed: false,
        };
        let area = c.signed_area();
        if !area.is_finite() || area.abs() <= LENGTH_EPS {
            return Err(InputError::new("outline area", area)
                .at(origin)
                .expected("a closed curve enclosing a non-zero area"));
        }
        if area < 0.0 {
            c.pieces = c.pieces.iter().rev().map(Cubic::reversed).collect();
            c.kinds.reverse();
            c.reversed = true;
        }
        c.corners = (0..n)
            .filter(|&i| {
                let a = c.pieces[(i + n - 1) % n].d1(1.0);
                let b = c.pieces[i].d1(0.0);
                a.cross(b).atan2(a.dot(b)).abs() > CORNER_ANGLE
            })
            .collect();
        Ok(c)
    }

    /// The fish-tail lobes cut off at corners (`intersect::remove_fishtails`): the curve
    /// as drawn, beyond the crossing that became the corner. Empty for most curves.
    pub fn lobes(&self) -> &[Lobe] {
        &self.lobes
    }

    /// The same curve with the lobes it was cut from recorded.
    pub(crate) fn with_lobes(mut self, lobes: Vec<Lobe>) -> Self {
        self.lobes = lobes;
        self
    }

    /// The pieces, in order.
    pub fn pieces(&self) -> &[Cubic] {
        &self.pieces
    }

    /// What each piece is.
    pub fn piece_kinds(&self) -> &[PieceKind] {
        &self.kinds
    }

    /// Number of pieces (the parameter period).
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// Always false: a curve has at least one piece.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// Indices `i` of the pieces whose start is a corner (tangent break above
    /// [`CORNER_ANGLE`]).
    pub fn corners(&self) -> &[usize] {
        &self.corners
    }

    /// Piece index and local parameter of the global parameter `s` (wrapped to `[0, n)`).
    pub fn locate(&self, s: f64) -> (usize, f64) {
        let n = self.pieces.len();
        let w = s.rem_euclid(n as f64);
        let i = (w.floor() as usize).min(n - 1);
        (i, (w - i as f64).clamp(0.0, 1.0))
    }

    /// The point at global parameter `s`.
    pub fn eval(&self, s: f64) -> Point {
        let (i, u) = self.locate(s);
        self.pieces[i].eval(u)
    }

    /// `dP/ds` at `s`.
    pub fn d1(&self, s: f64) -> Vec2 {
        let (i, u) = self.locate(s);
        self.pieces[i].d1(u)
    }

    /// Signed curvature at `s` (positive turning left, i.e. convex for a CCW outline).
    pub fn curvature(&self, s: f64) -> f64 {
        let (i, u) = self.locate(s);
        self.pieces[i].curvature(u)
    }

    /// Enclosed area (positive: counter-clockwise), exact by Green's theorem (kurbo).
    pub fn signed_area(&self) -> f64 {
        use kurbo::ParamCurveArea;
        self.pieces.iter().map(|c| c.to_kurbo().signed_area()).sum()
    }

    /// Arc length in mm (kurbo, accurate to 1e-9 mm per piece).
    pub fn length(&self) -> f64 {
        use kurbo::ParamCurveArclen;
        self.pieces.iter().map(|c| c.to_kurbo().arclen(1e-9)).sum()
    }

    /// Bounding box of the curve (kurbo's exact cubic extrema).
    pub fn bounds(&self) -> Aabb {
        use kurbo::ParamCurveExtrema;
        Aabb::from_points(self.pieces.iter().flat_map(|c| {
            let r = c.to_kurbo().bounding_box();
            [Point::new(r.x0, r.y0), Point::new(r.x1, r.y1)]
        }))
    }

    /// The curve as a closed kurbo path (for kurbo's flattening and reference computations).
    pub fn to_bez_path(&self) -> kurbo::BezPath {
        let mut p = kurbo::BezPath::new();
        if let Some(first) = self.pieces.first() {
            p.move_to(first.p0);
        }
        for c in &self.pieces {
            p.curve_to(c.p1, c.p2, c.p3);
        }
        p.close_path();
        p
    }

    /// The same curve with every point mapped by `f` (scaling and translating a sample).
    #[must_use]
    pub fn map_points(&self, f: impl Fn(Point) -> Point) -> Self {
        let pieces = self
            .pieces
            .iter()
            .map(|c| Cubic::new(f(c.p0), f(c.p1), f(c.p2), f(c.p3)))
            .collect();
        let map = |c: &Cubic| Cubic::new(f(c.p0), f(c.p1), f(c.p2), f(c.p3));
        let lobes = self
            .lobes
            .iter()
            .map(|l| Lobe {
                corner: l.corner,
                to_tip: map(&l.to_tip),
                from_tip: map(&l.from_tip),
            })
            .collect();
        CompositeCurve {
            pieces,
            lobes,
            ..self.clone()
        }
    }
}

fn check_points(pts: &[LabeledPoint]) -> Result<(), InputError> {
    let max = crate::geom::MAX_COORDINATE_MM;
    for p in pts {
        // Beyond ±1e6 mm, lengths and flattening counts overflow (kurbo's flattening of a
        // curve through 1e300 asked for a capacity overflow; found by the `contour` fuzzer).
        if !(p.p.x.abs() <= max && p.p.y.abs() <= max) {
            return Err(InputError::new("point", format!("({}, {})", p.p.x, p.p.y))
                .at(p.origin.clone())
                .expected(format!("finite coordinates within ±{max} mm")));
        }
    }
    for w in pts.windows(2) {
        if w[0].p.distance(w[1].p) <= LENGTH_EPS {
            return Err(
                InputError::new("point", format!("({}, {})", w[1].p.x, w[1].p.y))
                    .at(w[1].origin.clone())
                    .expected(format!(
                        "a point distinct from the previous one ({})",
                        w[0].origin
                    )),
            );
        }
    }
    Ok(())
}

/// Builds the closed curve of `kind` through the input groups. `origin` names the input.
///
/// * Four-point: every group must have exactly 4 points; a blend is inserted between
///   consecutive groups that do not meet, and from the last group to the first when they do
///   not meet (the outline is always closed).
/// * Catmull-Rom and spline: the groups are concatenated; at least 4 points; a last point
///   repeating the first is dropped.
///
/// Errors name the offending point: NaN, a repeated consecutive point, too few points, a
/// group that is not 4 points.
pub fn build(
    groups: &[Vec<LabeledPoint>],
    kind: CurveKind,
    origin: &str,
) -> Result<CompositeCurve, InputError> {
    let all: Vec<LabeledPoint> = groups.iter().flatten().cloned().collect();
    if all.len() < 4 {
        return Err(InputError::new("number of points", all.len())
            .at(origin)
            .expected("at least 4 points"));
    }
    match kind {
        CurveKind::FourPoint => {
            let mut fp = Vec::with_capacity(groups.len());
            for (gi, g) in groups.iter().enumerate() {
                check_points(g)?;
                let pts: [Point; 4] = match g.as_slice() {
                    [a, b, c, d] => [a.p, b.p, c.p, d.p],
                    _ => {
                        let at = g
                            .first()
                            .map_or_else(|| origin.to_owned(), |p| p.origin.clone());
                        return Err(InputError::new(format!("size of point group {}", gi + 1), g.len())
                            .at(at)
                            .expected("exactly 4 points per group in four-point mode (or --curve catmull-rom|spline)"));
                    }
                };
                fp.push(four_point::cubic(&pts));
            }
            let n = fp.len();
            let mut pieces = Vec::new();
            let mut kinds = Vec::new();
            for i in 0..n {
                pieces.push(fp[i]);
                kinds.push(PieceKind::Interpolating);
                let next = fp[(i + 1) % n];
                if fp[i].p3.distance(next.p0) > LENGTH_EPS {
                    pieces.push(blend::blend(&fp[i], &next));
                    kinds.push(PieceKind::Blend);
                } else {
                    if let Some(c) = pieces.last_mut() {
                        c.p3 = next.p0;
                    }
                }
            }
            intersect::remove_fishtails(CompositeCurve::new(pieces, kinds, origin)?, origin)
        }
        CurveKind::CatmullRom | CurveKind::Spline => {
            check_points(&all)?;
            let mut pts: Vec<Point> = all.iter().map(|p| p.p).collect();
            if pts.len() > 1 && pts[0].distance(pts[pts.len() - 1]) <= LENGTH_EPS {
                pts.pop();
            }
            if pts.len() < 4 {
                return Err(InputError::new("number of distinct points", pts.len())
                    .at(origin)
                    .expected("at least 4 points"));
            }
            let pieces = if kind == CurveKind::Spline {
                spline::closed(&pts).ok_or_else(|| {
                    InputError::new("points", "degenerate")
                        .at(origin)
                        .expected("points that span a closed curve")
                })?
            } else {
                catmull_rom::closed(&pts)
            };
            let kinds = vec![PieceKind::Interpolating; pieces.len()];
            intersect::remove_fishtails(CompositeCurve::new(pieces, kinds, origin)?, origin)
        }
    }
}

/// The paper's Table 1 outline (segments 1 and 3 as input groups; segment 2 is the blend),
/// in the paper's units.
pub fn paper_groups() -> Vec<Vec<LabeledPoint>> {
    let raw = [
        [(1.0, 15.0), (3.0, 14.0), (5.0, 12.5), (7.0, 10.0)],
        [(15.0, 8.0), (11.0, 17.0), (5.0, 16.5), (1.0, 15.0)],
    ];
    raw.iter()
        .enumerate()
        .map(|(g, pts)| {
            pts.iter()
                .enumerate()
                .map(|(i, (x, y))| LabeledPoint {
                    p: Point::new(*x, *y),
                    origin: format!("paper Table 1, group {}, point {}", g + 1, i + 1),
                })
                .collect()
        })
        .collect()
}

/// Scale from the paper's units to millimetres on the die block (see [`paper_outline`]).
pub const PAPER_SCALE: f64 = 20.0;
/// Translation (mm) applied after [`PAPER_SCALE`].
pub const PAPER_SHIFT: Vec2 = Vec2::new(40.0, 45.0);

/// The paper's outline scaled onto its 400 × 450 mm die block: `p ↦ 20·p + (40, 45)` mm.
/// The paper gives its points without units and a 400 × 450 mm block; scale 20 maps the
/// curve's extent (about 14.4 × 17.0 units) to about 288 × 340 mm, and the shift leaves at
/// least 40 mm of block around it on every side (checked by a test).
pub fn paper_outline() -> Result<CompositeCurve, InputError> {
    let c = build(&paper_groups(), CurveKind::FourPoint, "paper sample")?;
    Ok(c.map_points(|p| (p.to_vec2() * PAPER_SCALE + PAPER_SHIFT).to_point()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_outline_is_three_pieces_on_the_block() {
        let c = paper_outline().unwrap();
        assert_eq!(c.len(), 3);
        assert_eq!(c.piece_kinds()[1], PieceKind::Blend);
        assert!(!c.reversed);
        let b = c.bounds();
        assert!(
            b.min.x >= 40.0 && b.min.y >= 40.0 && b.max.x <= 360.0 && b.max.y <= 410.0,
            "{b:?}"
        );
        // Segment 3 arrives at (1, 15) heading (−5, 2.5) and segment 1 leaves heading
        // (6, −2.75): the paper's outline has a (nearly reversing) corner there.
        assert_eq!(c.corners(), &[0]);
    }

    #[test]
    fn bad_groups_are_named() {
        let mut g = paper_groups();
        g[1].pop();
        let e = build(&g, CurveKind::FourPoint, "t").unwrap_err();
        assert!(e.to_string().contains("group 2"), "{e}");
        let mut g = paper_groups();
        g[0][2].p = g[0][1].p;
        let e = build(&g, CurveKind::FourPoint, "t").unwrap_err();
        assert!(e.to_string().contains("group 1, point 3"), "{e}");
        let mut g = paper_groups();
        g[0][0].p.x = f64::NAN;
        assert!(build(&g, CurveKind::Spline, "t").is_err());
        let g = vec![paper_groups()[0][..3].to_vec()];
        let e = build(&g, CurveKind::CatmullRom, "t").unwrap_err();
        assert!(e.to_string().contains("at least 4"), "{e}");
    }

    /// The paper's Table 1: the blended segment 2 between segments 1 and 3.
    #[test]
    fn table_1_blend_inner_points() {
        let g = paper_groups();
        let pts = |k: usize| -> [Point; 4] { [g[k][0].p, g[k][1].p, g[k][2].p, g[k][3].p] };
        let (s1, s3) = (pts(0), pts(1));
        assert!((four_point::end_derivative(&s1) - Vec2::new(6.0, -9.5)).length() < 1e-12);
        assert!((four_point::start_derivative(&s3) - Vec2::new(-5.0, 49.75)).length() < 1e-12);
        let (p2, p3) = blend::inner_points(
            s1[3],
            four_point::end_derivative(&s1),
            s3[0],
            four_point::start_derivative(&s3),
        );
        for (got, want) in [(p2, (10.33, 4.38)), (p3, (14.11, 0.44))] {
            assert!(
                (got.x - want.0).abs() < 0.01 && (got.y - want.1).abs() < 0.01,
                "{got:?} vs {want:?}"
            );
        }
        // The built outline holds exactly this blend as its second piece (before scaling).
        let c = build(&g, CurveKind::FourPoint, "paper").unwrap();
        let b = c.pieces()[1];
        assert!(
            b.p0.distance(Point::new(7.0, 10.0)) < 1e-12
                && b.p3.distance(Point::new(15.0, 8.0)) < 1e-12
        );
        assert!(b.eval(1.0 / 3.0).distance(p2) < 1e-9 && b.eval(2.0 / 3.0).distance(p3) < 1e-9);
    }
}
