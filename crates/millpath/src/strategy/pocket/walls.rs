//! Inclined walls: each level gets its own boundary (the paper's §3.2).
//!
//! A pocket whose walls lean into it (a draft, or a bottom smaller than the top) cannot be
//! roughed with the top outline at every level: the tool would gouge the lower part of the
//! wall. Cut with the *bottom* outline at every level it leaves the whole wedge above the
//! inclined wall. The paper intersects the part with a plane at every axial step and plans
//! each level inside its own section; so do we. A flat end mill at level `i` (depth `t_i`
//! below the top) is a vertical cylinder reaching up through the slab `[t_{i−1}, t_i]`; where
//! the walls lean inward going down, the section at the slab's bottom, `S(t_i)`, is the
//! narrowest of the slab, so planning level `i` inside `S(t_i)` gouges no wall of the slab and
//! leaves only the staircase step above the wall, at most `(t_i − t_{i−1})·tan α` wide for a
//! wall inclined by α (the axial counterpart of the corner cusp; a finishing tool follows the
//! wall). Levels must therefore be nested, `S(t_i) ⊆ S(t_{i−1})`: a bottom wider than the top
//! would be an undercut, which no 3-axis flat end mill can cut; [`level_shapes`] refuses it.
//!
//! Sections:
//! * [`Walls::Draft`]`(α)`: every wall leans into the pocket by α from the vertical. The
//!   section at depth `t` is the set of points at distance at least `t·tan α` from the walls
//!   of the top region, i.e. the top region offset inward by `δ = t·tan α` (outline inward,
//!   islands outward: cavalier_contours' shape offset, exact arcs). This is exact for a
//!   drafted wall: a point of the wall at depth `t` lies `t·tan α` from the top edge,
//!   measured horizontally along the wall's normal, and the offset of a line or an arc is a
//!   line or a concentric arc. Convex corners stay sharp (a drafted sharp corner is a sharp
//!   corner at every depth), concave ones round to radius `δ` (the offset's arcs): the
//!   section of a drafted concave corner is that arc only if the corner was drafted as a
//!   cone, which is what a draft angle on a CAD part does.
//! * [`Walls::Bottom`]: the bottom outline (and its islands) at the pocket's depth, vertex
//!   for vertex like the top. The wall is the ruled surface between corresponding segments;
//!   the section at fraction `f = t/depth` has the vertices `(1 − f)·p_top + f·p_bottom` and,
//!   for arcs, the sweep `(1 − f)·θ_top + f·θ_bottom` (bulge `tan(θ/4)`). Where the two arcs
//!   are concentric with equal sweeps (a drafted rounded corner) this is the exact section; where
//!   they are not, the ruled surface's section is not a circular arc and the interpolated arc
//!   stands in for it. Either way the verifier checks the path against the very section it
//!   was planned in, and each level against the section of the slab's top.
//!
//! The section of the deepest roughing level (at `depth − floor stock`) is interpolated at
//! that depth; the finishing pass runs in that same section.

use super::options::PocketOptions;
use super::shape::PocketShape;
use crate::error::InputError;
use crate::geom::region::{piece_points, validate_islands};
use crate::geom::{Outline, Point};
use cavalier_contours::polyline::Polyline;

pub use super::shape::Walls;

/// Largest draft angle accepted, degrees (beyond, the pocket closes within a few mm).
pub const MAX_DRAFT_DEG: f64 = 60.0;

impl PocketShape {
    /// The same pocket with `walls`; checks that a bottom outline matches the top (same
    /// number of islands, same number of vertices loop for loop) and that a draft is in
    /// `[0, 60°]`. `origin` names where the walls came from (`--draft`, a file).
    pub fn with_walls(mut self, walls: Walls, origin: &str) -> Result<Self, InputError> {
        match &walls {
            Walls::Vertical => {}
            Walls::Draft(a) => {
                let deg = a.to_degrees();
                if !(deg.is_finite() && (0.0..=MAX_DRAFT_DEG).contains(&deg)) {
                    return Err(InputError::new("draft angle", deg)
                        .at(origin)
                        .expected("an angle in [0, 60] degrees, the walls leaning into the pocket (undercuts cannot be cut with a flat end mill)"));
                }
            }
            Walls::Bottom { outer, islands } => {
                let (outer, islands) = validate_islands(outer.clone(), islands.clone(), origin)?;
                if islands.len() != self.islands.len() {
                    return Err(InputError::new("bottom islands", islands.len())
                        .at(origin)
                        .expected(format!(
                            "as many islands as the top outline ({})",
                            self.islands.len()
                        )));
                }
                for (k, (top, bot)) in std::iter::once((&self.outer, &outer))
                    .chain(self.islands.iter().zip(islands.iter()))
                    .enumerate()
                {
                    if top.len() != bot.len() {
                        let which = if k == 0 {
                            "outline".to_owned()
                        } else {
                            format!("island {}", k - 1)
                        };
                        return Err(InputError::new("bottom vertex count", bot.len())
                            .at(format!("{origin}, {which}"))
                            .expected(format!(
                                "the same number of vertices as the top's {which} ({})",
                                top.len()
                            )));
                    }
                }
                self.walls = Walls::Bottom { outer, islands };
                return Ok(self);
            }
        }
        self.walls = walls;
        Ok(self)
    }

    /// True when the walls are vertical (every level has the top's boundary).
    pub fn is_prismatic(&self) -> bool {
        match self.walls {
            Walls::Vertical => true,
            Walls::Draft(a) => a == 0.0,
            Walls::Bottom { .. } => false,
        }
    }

    /// The planar pocket at `t` mm below the top, for a pocket `depth` mm deep: the section
    /// every strategy plans a level in (vertical walls in the result).
    pub fn section(&self, t: f64, depth: f64) -> Result<PocketShape, InputError> {
        let planar = |outer: Outline, islands: Vec<Outline>| PocketShape {
            outer,
            islands,
            walls: Walls::Vertical,
        };
        let closed = || {
            InputError::new("pocket section", format!("{t:.3} mm deep"))
                .at("--draft / --bottom-outline")
                .expected("walls that leave the pocket one region with its islands apart down to the floor (a smaller draft, or a bottom outline closer to the top)")
        };
        match &self.walls {
            Walls::Vertical => Ok(planar(self.outer.clone(), self.islands.clone())),
            Walls::Draft(a) => {
                let delta = t.max(0.0) * a.tan();
                if delta <= 0.0 {
                    return Ok(planar(self.outer.clone(), self.islands.clone()));
                }
                let off = planar(self.outer.clone(), self.islands.clone()).offset(delta);
                let [outer] = off.outers.as_slice() else {
                    return Err(closed());
                };
                let origin = format!("section {t:.3} mm deep");
                let outer = Outline::from_polyline(outer.clone(), &origin).map_err(|_| closed())?;
                let islands = off
                    .islands
                    .iter()
                    .map(|i| Outline::from_polyline(i.clone(), &origin))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|_| closed())?;
                let (outer, islands) =
                    validate_islands(outer, islands, &origin).map_err(|_| closed())?;
                Ok(planar(outer, islands))
            }
            Walls::Bottom { outer, islands } => {
                let f = if depth > 0.0 {
                    (t / depth).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let origin = format!("section {t:.3} mm deep");
                let lerp_loop = |a: &Outline, b: &Outline| {
                    let v: Vec<(Point, f64)> = a
                        .vertices()
                        .zip(b.vertices())
                        .map(|((pa, ba), (pb, bb))| {
                            let theta = (1.0 - f) * 4.0 * ba.atan() + f * 4.0 * bb.atan();
                            (pa.lerp(pb, f), (0.25 * theta).tan())
                        })
                        .collect();
                    Outline::new(&v, &origin)
                };
                let o = lerp_loop(&self.outer, outer).map_err(|_| closed())?;
                let isl = self
                    .islands
                    .iter()
                    .zip(islands.iter())
                    .map(|(a, b)| lerp_loop(a, b))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|_| closed())?;
                let (o, isl) = validate_islands(o, isl, &origin).map_err(|_| closed())?;
                Ok(planar(o, isl))
            }
        }
    }

    /// True when this (planar) region lies within `other`'s, to within 1 µm: every piece of
    /// our loops between the points where they meet `other`'s loops is inside `other`'s
    /// region or on its boundary, and every piece of `other`'s loops (its outer loop too:
    /// a slit of material reaching in from its wall) is outside ours or on our boundary
    /// (`piece_points`: one point stands for each piece, since a piece meets no loop of
    /// the other region inside). Exact up to that tolerance; the check sampled 256 points a
    /// loop before, which stepped over a 0.8 mm slit (fuzz/README.md, 2026-11-23).
    pub fn within(&self, other: &PocketShape) -> bool {
        let on_or_in =
            |shape: &PocketShape, p: Point| shape.contains(p) || shape.distance_to(p) <= 1e-6;
        let outside =
            |shape: &PocketShape, p: Point| !shape.contains(p) || shape.distance_to(p) <= 1e-6;
        let ours: Vec<&Polyline<f64>> = self.loops().map(Outline::polyline).collect();
        let theirs: Vec<&Polyline<f64>> = other.loops().map(Outline::polyline).collect();
        ours.iter()
            .flat_map(|l| piece_points(l, &theirs))
            .all(|p| on_or_in(other, p))
            && theirs
                .iter()
                .flat_map(|l| piece_points(l, &ours))
                .all(|p| outside(self, p))
    }
}

/// The section of every roughing level of `opts` (top to bottom, see
/// [`super::levels::level_depths`]); refuses sections that are not nested (an undercut).
pub fn level_shapes(
    shape: &PocketShape,
    opts: &PocketOptions,
) -> Result<Vec<PocketShape>, InputError> {
    let depths = super::levels::level_depths(opts);
    if shape.is_prismatic() {
        let planar = shape.section(0.0, opts.depth)?;
        return Ok(vec![planar; depths.len()]);
    }
    let mut out: Vec<PocketShape> = Vec::with_capacity(depths.len());
    let mut above = shape.section(0.0, opts.depth)?;
    for z in depths {
        let s = shape.section(-z, opts.depth)?;
        if !s.within(&above) {
            return Err(InputError::new("pocket section", format!("{:.3} mm deep", -z))
                .at("--bottom-outline")
                .expected("a bottom outline inside the top one: walls that lean into the pocket (an undercut cannot be cut with a flat end mill)"));
        }
        above = s.clone();
        out.push(s);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strategy::pocket::builtin::rounded_rectangle;

    #[test]
    fn draft_sections_shrink_by_depth_times_tan() {
        let top = PocketShape::simple(rounded_rectangle(0.0, 0.0, 100.0, 60.0, 10.0))
            .with_walls(Walls::Draft(5f64.to_radians()), "--draft")
            .unwrap();
        let s = top.section(20.0, 20.0).unwrap();
        let d = 20.0 * 5f64.to_radians().tan();
        let b = s.outer.bounds();
        assert!((b.min.x - d).abs() < 1e-9 && (b.max.y - (60.0 - d)).abs() < 1e-9);
        // The drafted rounded rectangle is the same rounded rectangle, shrunk by d.
        let want = rounded_rectangle(d, d, 100.0 - 2.0 * d, 60.0 - 2.0 * d, 10.0 - d);
        assert!((s.outer.signed_area() - want.signed_area()).abs() < 1e-6);
        assert!(
            top.with_walls(Walls::Draft(-0.1), "--draft").is_err(),
            "an undercut draft is refused"
        );
    }

    #[test]
    fn bottom_outline_sections_interpolate_and_undercuts_are_refused() {
        let top = PocketShape::simple(rounded_rectangle(0.0, 0.0, 100.0, 60.0, 10.0));
        let bottom = rounded_rectangle(10.0, 10.0, 80.0, 40.0, 10.0);
        let p = top
            .clone()
            .with_walls(
                Walls::Bottom {
                    outer: bottom,
                    islands: Vec::new(),
                },
                "bottom",
            )
            .unwrap();
        let half = p.section(10.0, 20.0).unwrap();
        let b = half.outer.bounds();
        assert!((b.min.x - 5.0).abs() < 1e-9 && (b.max.x - 95.0).abs() < 1e-9);
        let opts = PocketOptions::default()
            .with_depth(20.0)
            .with_step_down(5.0);
        let levels = level_shapes(&p, &opts).unwrap();
        assert_eq!(levels.len(), 4);
        assert!(levels[3].within(&levels[2]) && !levels[2].within(&levels[3]));
        // Bottom wider than the top: an undercut.
        let wide = rounded_rectangle(-10.0, -10.0, 120.0, 80.0, 10.0);
        let u = top
            .with_walls(
                Walls::Bottom {
                    outer: wide,
                    islands: Vec::new(),
                },
                "bottom",
            )
            .unwrap();
        assert!(level_shapes(&u, &opts).is_err());
    }

    /// A thin slit of material reaching into the pocket from its wall (the `pocket` fuzzer's
    /// outline, pk29): shrunk towards the centroid, the slit moves into the region above it,
    /// so the lower sections are not nested in the upper ones (an undercut). The check
    /// sampled 256 points a loop before, which stepped over the 0.8 mm slit, and the spiral
    /// planned in the bottom section cut 0.68 mm into the slit's wall.
    #[test]
    fn a_slit_that_moves_with_the_bottom_outline_is_an_undercut() {
        let top = [
            (-2.2938494268365766, -7.583206032835491),
            (13.819938916514431, -6.812874942264327),
            (16.2161533731014, 39.13737775224321),
            (-1.482161754909228, 49.30004148995412),
            (-15.656458898355005, 9.745343526113583),
            (-32.64774958642704, 37.94042171885479),
            (-45.87747179616305, 14.960294013186743),
            (-52.02980149585056, 8.894402514466268),
            (-53.57964918278162, -6.01340127859758),
            (-56.480421317380525, -37.957137949013195),
            (-32.96794177381195, -53.45783349487589),
            (13.279087045403138, -42.89703327482558),
            (13.865384908827345, -7.647058823529421),
        ]
        .map(|(x, y)| Point::new(x, y));
        let c = crate::geom::region::second_moments(&top).0;
        let bottom: Vec<Point> = top.iter().map(|&p| c.lerp(p, 0.72)).collect();
        let shape = PocketShape::simple(Outline::from_points(&top, "top").unwrap())
            .with_walls(
                Walls::Bottom {
                    outer: Outline::from_points(&bottom, "bottom").unwrap(),
                    islands: Vec::new(),
                },
                "bottom",
            )
            .unwrap();
        let opts = PocketOptions::default()
            .with_depth(6.794117647058823)
            .with_step_down(2.3652884179535856);
        let e = level_shapes(&shape, &opts).expect_err("an undercut");
        assert!(e.to_string().contains("undercut"), "{e}");
        // The sections themselves are valid pockets: only their nesting fails.
        let s = shape.section(opts.depth, opts.depth).unwrap();
        assert!(!s.within(&shape.section(0.0, opts.depth).unwrap()));
    }
}
