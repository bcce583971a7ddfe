//! The morph's loops as growing *fronts*: the central disc united with the boundary offset's
//! inward offsets, smoothed.
//!
//! # The family
//!
//! Let `B` be the boundary offset (the tool-centre region's outer loop), `D(x)` the distance
//! from `x` to `B` inside it, `ρ_B = max D` its inscribed radius, `c` the centre and `R₀` the
//! radius of the central spiral's last loop. For `τ ∈ [0, ρ_B]` let
//!
//! ```text
//! Ω_τ = disc(c, R₀) ∪ { x : D(x) ≥ ρ_B − τ }        (then smoothed, see below)
//! ```
//!
//! `Ω_0` is the disc (the set `D ≥ ρ_B` is the medial "ridge", inside the disc when `R₀` covers
//! it) and `Ω_{ρ_B}` is the whole region inside `B`. The second set is an exact inward offset
//! of `B` (cavalier_contours keeps the arcs), so the loops `∂Ω_τ` are the contour-parallel
//! offsets of the `offset` strategy wherever they have left the disc, and the disc where they
//! have not yet reached it.
//!
//! **Spacing.** `D` is 1-Lipschitz, so `{D ≥ d − Δ} ⊆ {D ≥ d} ⊕ Δ` wherever the ridge is
//! reached by ascent (true for convex pockets and for the usual non-convex ones; where it is
//! not, a new piece of the offset appears away from the front, the measured step below is
//! too long and the morph falls back to the harmonic field). A union of sets each grown by at
//! most `Δ` is grown by at most `Δ`, so before smoothing every point of `∂Ω_τ` is within `Δ`
//! of `∂Ω_{τ+Δ}`, and along the sides of the region the loops are `Δ` apart both ways.
//! Measured from the outer loop, the distance at a convex corner of `B` with interior angle
//! `α` is `Δ / sin(α/2)` (`√2·Δ` at a right angle), as for every contour-parallel strategy;
//! once both loops' corners are rounded with the same radius it is `√2·Δ` along the
//! bisector either way. This is where the engagement rises above nominal and
//! the feed modulation takes over. Unlike a morph from the circle (whose lap count is set by
//! the point of `B` farthest from the circle), the lap count here is `⌈ρ_B / Δ⌉`, the same as
//! contour-parallel offsets (on the built-in 3:2 pocket: 15.1 m against the harmonic 20.6 m).
//!
//! **Smoothing.** Each loop except `B` is opened (eroded then dilated) with radius `ρ_o` and
//! closed (dilated then eroded) with radius `ρ_c`: convex corners become arcs of radius at
//! least `ρ_o` and concave kinks (where the offsets meet the disc) arcs of radius at least
//! `ρ_c`, so the curvature radius of every interior loop is at least `min(ρ_o, ρ_c)`. The
//! opening radius is capped at `0.9·τ` so that thin new fronts near the ridge (half-width
//! about `τ`) survive it instead of appearing suddenly. The result is intersected with `B`.
//! Smoothing moves a loop inward at convex corners and outward at concave kinks by a
//! fraction of the radius; the spacing is measured after it, loop by loop (below).
//!
//! **Measured steps.** The steps in `τ` are `Δ = ρ_B / n` with `n = ⌈ρ_B / s'⌉`. After each
//! loop the directed distance from the new loop to the previous one is sampled; above
//! `√2·s'` (more than a right-angle corner explains) the step is halved, down to `s'/64`,
//! and if that does not help the family is abandoned and the harmonic morph is used.

use super::super::shape::{loop_distance, v2};
use crate::geom::Point;
use cavalier_contours::polyline::{
    BooleanOp, PlineCreation, PlineSource, PlineSourceMut, Polyline,
};

/// The largest number of loops the fronts may take.
const MAX_LOOPS: usize = 2000;

/// What the fronts need.
#[derive(Debug, Clone, Copy)]
pub struct FrontOptions {
    /// Largest step between loops along the sides, mm (`s'`).
    pub step: f64,
    /// Opening radius: the smallest convex curvature radius of interior loops, mm.
    pub open_radius: f64,
    /// Closing radius: the smallest concave curvature radius of interior loops, mm.
    pub close_radius: f64,
    /// Sample spacing for the distance checks, mm.
    pub sample: f64,
}

/// The loops of the morph, from the disc (first) to `B` (last), counter-clockwise.
#[derive(Debug, Clone)]
pub struct Fronts {
    /// Counter-clockwise loops; `loops[0]` is the circle, the last is `B`.
    pub loops: Vec<Polyline<f64>>,
    /// Largest measured distance from a loop to the one before it, mm.
    pub max_distance: f64,
}

/// A counter-clockwise circle.
pub fn circle(c: Point, r: f64) -> Polyline<f64> {
    let mut pl = Polyline::with_capacity(2, true);
    pl.add(c.x - r, c.y, 1.0);
    pl.add(c.x + r, c.y, 1.0);
    pl
}

/// The largest counter-clockwise piece of a set of loops.
fn largest(pieces: Vec<Polyline<f64>>) -> Option<Polyline<f64>> {
    pieces
        .into_iter()
        .filter(|p| p.vertex_count() > 1 && p.area() > 0.0)
        .max_by(|a, b| a.area().total_cmp(&b.area()))
}

/// Inward offset of a counter-clockwise loop by `d` (negative: outward); the largest piece.
fn offset(pl: &Polyline<f64>, d: f64) -> Option<Polyline<f64>> {
    if d == 0.0 {
        return Some(pl.clone());
    }
    largest(pl.parallel_offset(d))
}

/// The inscribed radius of `b` (the largest inward offset that is not empty), found by
/// bisection on the exact offsets to `1e-9` relative, and the centre: the centroid of the
/// ridge `D ≥ ρ_B − δ` (`δ` = 1% of `ρ_B`), moved onto the ridge when the centroid falls
/// outside it (a curved ridge). The centroid is a property of the shape, so the centre does
/// not depend on how the pocket is turned or where its loop starts.
pub fn ridge_centre(b: &Polyline<f64>) -> Option<(Point, f64)> {
    let e = b.extents()?;
    let mut lo = 0.0;
    let mut hi = 0.5 * (e.max_x - e.min_x).max(e.max_y - e.min_y);
    if !(hi > 0.0 && hi.is_finite()) {
        return None;
    }
    while hi - lo > 1e-9 * hi {
        let mid = 0.5 * (lo + hi);
        if b.parallel_offset(mid).iter().any(|p| p.area() > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let rho = lo;
    if rho <= 0.0 {
        return None;
    }
    let ridge = offset(b, 0.99 * rho)?;
    let c = centroid(&ridge);
    let c = if ridge.winding_number(v2(c)) != 0 {
        c
    } else {
        ridge
            .closest_point(v2(c), 1e-12)
            .map_or(c, |cp| Point::new(cp.seg_point.x, cp.seg_point.y))
    };
    let d = loop_distance(b, c);
    Some((c, d.min(rho)))
}

/// Area centroid of a closed loop with arcs (each arc taken as its chord plus the circular
/// segment).
fn centroid(pl: &Polyline<f64>) -> Point {
    let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
    let n = pl.vertex_count();
    for i in 0..n {
        let v0 = pl.at(i);
        let v1 = pl.at((i + 1) % n);
        let cr = v0.x * v1.y - v1.x * v0.y;
        a += 0.5 * cr;
        cx += (v0.x + v1.x) * cr / 6.0;
        cy += (v0.y + v1.y) * cr / 6.0;
        if v0.bulge != 0.0 {
            // The circular segment between the chord and the arc: area r²(θ − sin θ)/2
            // (signed with the sweep θ), centroid at 4r·sin³(θ/2)/(3(θ − sin θ)) from the
            // circle's centre towards the arc, i.e. that minus r·cos(θ/2) from the chord's
            // midpoint. A counter-clockwise arc bulges to the right of its chord.
            let th = 4.0 * v0.bulge.atan();
            let ta = th.abs();
            let chord = ((v1.x - v0.x).powi(2) + (v1.y - v0.y).powi(2)).sqrt();
            if chord > 0.0 && ta > 1e-12 {
                let r = chord / (2.0 * (0.5 * ta).sin());
                let seg_area = 0.5 * r * r * (th - th.sin());
                let g = 4.0 * r * (0.5 * ta).sin().powi(3) / (3.0 * (ta - ta.sin()))
                    - r * (0.5 * ta).cos();
                let (mx, my) = (0.5 * (v0.x + v1.x), 0.5 * (v0.y + v1.y));
                let (nx, ny) = ((v1.y - v0.y) / chord, -(v1.x - v0.x) / chord);
                let (gx, gy) = (mx + th.signum() * nx * g, my + th.signum() * ny * g);
                a += seg_area;
                cx += seg_area * gx;
                cy += seg_area * gy;
            }
        }
    }
    if a.abs() < 1e-300 {
        let v = pl.at(0);
        return Point::new(v.x, v.y);
    }
    Point::new(cx / a, cy / a)
}

/// Smoothing of one front: opening with `ro`, closing with `rc`, then clipped to `b`.
fn smooth(u: &Polyline<f64>, b: &Polyline<f64>, ro: f64, rc: f64) -> Option<Polyline<f64>> {
    let mut cur = u.clone();
    if ro > 0.0 {
        let eroded = offset(&cur, ro)?;
        cur = offset(&eroded, -ro)?;
    }
    if rc > 0.0 {
        let dilated = offset(&cur, -rc)?;
        cur = offset(&dilated, rc)?;
    }
    largest(
        cur.boolean(b, BooleanOp::And)
            .pos_plines
            .into_iter()
            .map(|p| p.pline)
            .collect(),
    )
}

/// The front at `τ` (unsmoothed union of the disc and the offset of `b` by `ρ_B − τ`).
fn front(b: &Polyline<f64>, disc: &Polyline<f64>, rho_b: f64, tau: f64) -> Option<Polyline<f64>> {
    let d = rho_b - tau;
    if d <= 0.0 {
        return Some(b.clone());
    }
    let mut acc = disc.clone();
    for piece in b.parallel_offset(d) {
        if piece.vertex_count() < 2 || piece.area() <= 0.0 {
            continue;
        }
        let res = acc.boolean(&piece, BooleanOp::Or);
        // Only the piece joined to the front is kept (a separate piece shows up as a jump in
        // the measured spacing later).
        if let Some(u) = largest(res.pos_plines.into_iter().map(|p| p.pline).collect()) {
            acc = u;
        }
    }
    Some(acc)
}

/// Sampled directed distance: the largest distance from a point of `a` to the loop `b`.
pub fn directed_distance(a: &Polyline<f64>, b: &Polyline<f64>, ds: f64) -> f64 {
    super::sample_loop(a, ds)
        .into_iter()
        .map(|p| loop_distance(b, p))
        .fold(0.0, f64::max)
}

/// The loops from the circle `(c, r0)` to `b`; `None` when the family does not reach `b`
/// with measured steps (see the module docs).
pub fn fronts(
    b: &Polyline<f64>,
    c: Point,
    rho_b: f64,
    r0: f64,
    o: &FrontOptions,
) -> Option<Fronts> {
    let disc = circle(c, r0);
    let n = ((rho_b / o.step).ceil() as usize).max(1);
    let delta = rho_b / n as f64;
    let limit = std::f64::consts::SQRT_2 * o.step;
    let mut loops = vec![disc.clone()];
    let mut max_distance: f64 = 0.0;
    let mut tau = 0.0;
    let mut step = delta;
    while tau < rho_b {
        if loops.len() > MAX_LOOPS {
            return None;
        }
        let prev = loops.last()?;
        let mut h = step;
        let (next, dist, t_next) = loop {
            let t = (tau + h).min(rho_b);
            let last = t >= rho_b - 1e-9 * rho_b;
            let cand = if last {
                b.clone()
            } else {
                let raw = front(b, &disc, rho_b, t)?;
                let ro = o.open_radius.min(0.9 * t);
                smooth(&raw, b, ro, o.close_radius)?
            };
            let dist = directed_distance(&cand, prev, o.sample);
            if dist <= limit {
                break (cand, dist, t);
            }
            if h < o.step / 64.0 {
                return None;
            }
            h *= 0.5;
        };
        max_distance = max_distance.max(dist);
        loops.push(next);
        tau = if t_next >= rho_b - 1e-9 * rho_b {
            rho_b
        } else {
            t_next
        };
        // Back to the uniform grid of steps when a halved step has caught up.
        step = delta;
    }
    Some(Fronts {
        loops,
        max_distance,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(w: f64, h: f64) -> Polyline<f64> {
        let mut pl = Polyline::with_capacity(4, true);
        for (x, y) in [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)] {
            pl.add(x, y, 0.0);
        }
        pl
    }

    #[test]
    fn ridge_centre_of_a_rectangle_is_its_middle() {
        let b = rect(137.3, 87.3);
        let (c, rho) = ridge_centre(&b).unwrap();
        assert!((rho - 43.65).abs() < 1e-6, "{rho}");
        assert!(
            (c.x - 68.65).abs() < 1e-6 && (c.y - 43.65).abs() < 1e-6,
            "{c:?}"
        );
    }

    #[test]
    fn fronts_of_a_rectangle_are_as_many_as_offsets_and_spaced() {
        let b = rect(137.3, 87.3);
        let (c, rho) = ridge_centre(&b).unwrap();
        let o = FrontOptions {
            step: 4.8,
            open_radius: 5.0,
            close_radius: 5.0,
            sample: 0.5,
        };
        let f = fronts(&b, c, rho, 25.0, &o).unwrap();
        // ⌈43.65 / 4.8⌉ = 10 steps after the circle, and at most one halved step where the
        // ridge's ends first leave the disc (the harmonic morph needs 12 laps after a
        // *larger* circle on this pocket).
        assert!((11..=12).contains(&f.loops.len()), "{}", f.loops.len());
        for w in f.loops.windows(2) {
            // Within a step along the sides, √2 steps at the rounded corners, either way.
            let d = directed_distance(&w[0], &w[1], 0.5);
            assert!(d <= std::f64::consts::SQRT_2 * 4.8 + 1e-6, "{d}");
        }
        assert!(f.max_distance <= std::f64::consts::SQRT_2 * 4.8 + 1e-9);
    }

    #[test]
    fn centroid_of_a_circle_is_its_centre() {
        let c = centroid(&circle(Point::new(3.0, -2.0), 5.0));
        assert!(
            (c.x - 3.0).abs() < 1e-9 && (c.y + 2.0).abs() < 1e-9,
            "{c:?}"
        );
    }
}
