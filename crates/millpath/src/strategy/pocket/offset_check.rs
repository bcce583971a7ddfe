//! Completeness of a region's offset: points every faithful offset must contain.
//!
//! [`super::shape::checked_offset`] checks that each loop cavalier_contours returns lies at
//! `d` from the walls; that cannot see a loop that is *missing*. Near a distance where an
//! arm of a region ends, the shape offset can return loops of no area for the whole region:
//! every loop returned (none) lies at `d`, and the strategies' loops would stop there, the
//! rest of the pocket uncut. These probes find such a result incomplete.
//!
//! **The probes.** Walk every wall (the region is on the left of each loop: outer loops
//! counter-clockwise, islands clockwise) at a spacing of at most `|d|/2`, and at each sample
//! `w` with inward (left) unit normal `n` take `q = w + (d + δ)·n`; at a vertex where the wall
//! turns right (a corner pointing into the region), also the fan of normals between the two
//! segments' normals, at most half a radian apart. If the distance from `q` to the walls is
//! at least `d + δ/2`, then `q` lies in the eroded region `{p : dist(p, walls) ≥ d}` at least
//! `δ/2` inside its boundary, so a faithful offset (loops within
//! [`super::shape::OFFSET_TOLERANCE`] of the level set `d`) holds it. Every part of the
//! eroded region whose boundary touches the level set away from the medial axis has such a
//! `q` near its boundary, so a missing part is found unless it is narrower than the probes'
//! spacing and depth (`δ = max(|d|/100, 1 µm)`): a part the stock simulation would measure
//! as at most a sliver. The wall samples themselves lie outside every inward offset: a
//! result missing an island's loop holds them (checked for `d` above ten times `δ`). An
//! outward offset (`d < 0`) holds the region itself: the probes are the wall samples, at
//! distance `|d|` inside it.
//!
//! **Tolerances.** `δ` keeps the probes clear of the returned loops' own tolerance
//! (1e-4 mm at most against `δ/2 ≥ 5e-4 mm` for offsets above 0.1 mm); below that the probes
//! sit `δ/2` inside, and a faithful offset still holds them. At most [`MAX_PROBES`] wall
//! samples are taken on one call (the spacing grows on long walls with small offsets).

use crate::geom::{Point, Vec2};
use cavalier_contours::core::math::Vector2;
use cavalier_contours::polyline::{PlineSource, PlineVertex, Polyline, seg_arc_radius_and_center};

/// Most wall samples one call takes (their spacing grows beyond `|d|/2` on longer walls).
pub const MAX_PROBES: usize = 20_000;

/// Largest angle between two probes of a corner's fan, rad.
const FAN_STEP: f64 = 0.5;

/// The points every faithful offset by `d` of the region bounded by `walls` must contain, and
/// those it must not (see the module docs); `dist` is the distance to the walls.
pub fn probes(walls: &[&Polyline<f64>], d: f64, dist: impl Fn(Point) -> f64) -> Probes {
    let mut out = Probes::default();
    if d == 0.0 || !d.is_finite() {
        return out;
    }
    let length: f64 = walls.iter().map(|w| w.path_length()).sum();
    let spacing = (0.5 * d.abs()).max(length / MAX_PROBES as f64);
    if spacing <= 0.0 || !spacing.is_finite() {
        return out;
    }
    let delta = (0.01 * d.abs()).max(1e-3);
    for wall in walls {
        for (w, n) in samples(wall, spacing) {
            if d < 0.0 {
                out.inside.push(w);
                continue;
            }
            if d > 10.0 * delta {
                out.outside.push(w);
            }
            let q = w + n * (d + delta);
            if dist(q) >= d + 0.5 * delta {
                out.inside.push(q);
            }
        }
    }
    out
}

/// What [`probes`] found: points an offset must hold, and points it must not.
#[derive(Debug, Clone, Default)]
pub struct Probes {
    /// Points farther than the offset distance from the walls (inward offsets), or on the
    /// walls (outward ones).
    pub inside: Vec<Point>,
    /// Points on the walls, for inward offsets by more than ten times the probes' depth.
    pub outside: Vec<Point>,
}

/// The first probe the region of counter-clockwise `outers` less clockwise `islands` has on
/// the wrong side, if any: a point of `probes.inside` it does not contain, or one of
/// `probes.outside` it does.
pub fn first_misplaced(
    outers: &[Polyline<f64>],
    islands: &[Polyline<f64>],
    probes: &Probes,
) -> Option<Point> {
    let (outers, islands) = (boxed(outers), boxed(islands));
    let inside = |loops: &[(&Polyline<f64>, [f64; 4])], p: Point| {
        loops.iter().any(|(pl, b)| {
            p.x >= b[0]
                && p.x <= b[2]
                && p.y >= b[1]
                && p.y <= b[3]
                && pl.winding_number(Vector2::new(p.x, p.y)) != 0
        })
    };
    let held = |p: Point| inside(&outers, p) && !inside(&islands, p);
    probes
        .inside
        .iter()
        .copied()
        .find(|&p| !held(p))
        .or_else(|| probes.outside.iter().copied().find(|&p| held(p)))
}

/// Each loop with its extents `[min x, min y, max x, max y]`.
fn boxed(pls: &[Polyline<f64>]) -> Vec<(&Polyline<f64>, [f64; 4])> {
    pls.iter()
        .filter_map(|p| {
            p.extents()
                .map(|e| (p, [e.min_x, e.min_y, e.max_x, e.max_y]))
        })
        .collect()
}

/// Samples of the closed loop `pl` at most `spacing` apart along each segment, each with the
/// unit normal to the left of the direction of travel; at a right turn, the fan of normals
/// between the two segments'.
fn samples(pl: &Polyline<f64>, spacing: f64) -> Vec<(Point, Vec2)> {
    let n = pl.vertex_count();
    let mut out = Vec::new();
    if n < 2 {
        return out;
    }
    for i in 0..n {
        let (v0, v1, v2) = (pl.at((i + n - 1) % n), pl.at(i), pl.at((i + 1) % n));
        if (v2.pos() - v1.pos()).length() < 1e-12 {
            continue;
        }
        // The fan at v1, from the end normal of the segment before to the start normal here.
        if (v1.pos() - v0.pos()).length() >= 1e-12 {
            let t_in = seg_point(v0, v1, 1.0).1;
            let t_out = seg_point(v1, v2, 0.0).1;
            let turn = t_in.cross(t_out).atan2(t_in.dot(t_out));
            if turn < 0.0 {
                let k = (turn.abs() / FAN_STEP).ceil() as usize;
                for j in 1..k {
                    let a = turn * j as f64 / k as f64;
                    out.push((pt(v1.pos()), t_in.rotate(a).perp()));
                }
            }
        }
        let len = cavalier_contours::polyline::seg_length(v1, v2);
        let k = ((len / spacing).ceil() as usize).max(1);
        for j in 0..k {
            let (p, t) = seg_point(v1, v2, j as f64 / k as f64);
            out.push((p, t.perp()));
        }
    }
    out
}

/// The point at fraction `f` of the segment `v1 → v2` (by arc length) and the unit tangent
/// there.
fn seg_point(v1: PlineVertex<f64>, v2: PlineVertex<f64>, f: f64) -> (Point, Vec2) {
    let (a, b) = (pt(v1.pos()), pt(v2.pos()));
    if v1.bulge.abs() < 1e-12 {
        let t = (b - a).normalize().unwrap_or(Vec2::new(1.0, 0.0));
        return (a.lerp(b, f), t);
    }
    let (radius, c) = seg_arc_radius_and_center(v1, v2);
    let sweep = 4.0 * v1.bulge.atan();
    let a0 = (a.y - c.y).atan2(a.x - c.x) + f * sweep;
    let p = Point::new(c.x + radius * a0.cos(), c.y + radius * a0.sin());
    let t = Vec2::new(-a0.sin(), a0.cos()) * sweep.signum();
    (p, t)
}

fn pt(v: Vector2<f64>) -> Point {
    Point::new(v.x, v.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cavalier_contours::polyline::PlineSourceMut;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polyline<f64> {
        let mut pl = Polyline::new_closed();
        for (x, y) in [(x0, y0), (x1, y0), (x1, y1), (x0, y1)] {
            pl.add(x, y, 0.0);
        }
        pl
    }

    fn brute_distance(walls: &[&Polyline<f64>], p: Point) -> f64 {
        walls
            .iter()
            .filter_map(|w| w.closest_point(Vector2::new(p.x, p.y), 1e-12))
            .map(|c| c.distance)
            .fold(f64::INFINITY, f64::min)
    }

    /// A 40 × 10 slot offset by 3: every probe lies inside the exact eroded rectangle
    /// (3..37 × 3..7) and at least `δ/2` inside it; an empty result misses them, the exact
    /// rectangle covers them, and a result lacking the right half misses one.
    #[test]
    fn probes_lie_inside_the_eroded_region_and_find_a_missing_part() {
        let wall = rect(0.0, 0.0, 40.0, 10.0);
        let walls = [&wall];
        let d = 3.0;
        let must = probes(&walls, d, |p| brute_distance(&walls, p));
        assert!(must.inside.len() > 20, "{} probes", must.inside.len());
        for p in &must.inside {
            let depth = brute_distance(&walls, *p) - d;
            assert!(depth >= 0.5 * 0.03 - 1e-12, "{p:?} only {depth} inside");
        }
        assert!(first_misplaced(&[], &[], &must).is_some());
        let exact = rect(3.0, 3.0, 37.0, 7.0);
        assert_eq!(first_misplaced(&[exact], &[], &must), None);
        let half = rect(3.0, 3.0, 20.0, 7.0);
        let miss = first_misplaced(&[half], &[], &must).expect("the right half is missing");
        assert!(miss.x > 20.0);
    }

    /// An island's probes: outside the island grown by `d`, inside the outer loop eroded; a
    /// result with the grown island as a hole covers them (its corners cut by chords, inside
    /// the true rounded ones), one with a larger hole across the probes does not, and one
    /// without the hole holds the island's walls.
    #[test]
    fn island_probes_lie_around_the_grown_island() {
        let outer = rect(0.0, 0.0, 60.0, 60.0);
        let mut island = rect(25.0, 25.0, 35.0, 35.0);
        island.invert_direction_mut();
        let walls = [&outer, &island];
        let d = 4.0;
        let must = probes(&walls, d, |p| brute_distance(&walls, p));
        // The right turns at the island's corners give fans: probes diagonal from a corner.
        assert!(
            must.inside
                .iter()
                .any(|p| p.x > 35.0 + 2.0 && p.y > 35.0 + 2.0 && p.x < 40.0 && p.y < 40.0),
            "a probe in the corner's fan"
        );
        let out = rect(4.0, 4.0, 56.0, 56.0);
        // The grown island with its rounded corners cut by chords (inside the true hole).
        let mut hole = Polyline::new_closed();
        for (x, y) in [
            (21.0, 35.0),
            (21.0, 25.0),
            (25.0, 21.0),
            (35.0, 21.0),
            (39.0, 25.0),
            (39.0, 35.0),
            (35.0, 39.0),
            (25.0, 39.0),
        ] {
            hole.add(x, y, 0.0);
        }
        hole.invert_direction_mut();
        assert_eq!(
            first_misplaced(std::slice::from_ref(&out), &[hole], &must),
            None
        );
        let mut big_hole = rect(15.0, 15.0, 45.0, 45.0);
        big_hole.invert_direction_mut();
        assert!(first_misplaced(std::slice::from_ref(&out), &[big_hole], &must).is_some());
        // Without the island's loop, the island's own wall lies inside the result.
        let miss = first_misplaced(&[out], &[], &must).expect("the island's loop is missing");
        assert!(brute_distance(&walls, miss) < 1e-9, "{miss:?} on a wall");
    }

    /// Arcs: a circle of radius 10 offset inward by 4; the probes lie at radius 6 − δ and the
    /// disc of radius 6 covers them; outward by 4, the probes are on the circle itself.
    #[test]
    fn arc_walls_give_probes_on_the_offset_side() {
        let mut circle = Polyline::new_closed();
        circle.add(10.0, 0.0, 1.0);
        circle.add(-10.0, 0.0, 1.0);
        let walls = [&circle];
        let must = probes(&walls, 4.0, |p| brute_distance(&walls, p));
        assert!(must.inside.len() >= 8);
        for p in &must.inside {
            let r = (p.x * p.x + p.y * p.y).sqrt();
            assert!((r - (6.0 - 0.04)).abs() < 1e-9, "probe at radius {r}");
        }
        let out = probes(&walls, -4.0, |p| brute_distance(&walls, p));
        for p in &out.inside {
            assert!(((p.x * p.x + p.y * p.y).sqrt() - 10.0).abs() < 1e-9);
        }
    }
}
