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
//! Ω_τ = K ∪ { x : D(x) ≥ ρ_B − τ }        (then smoothed, see below)
//! ```
//!
//! where the core `K` is the disc of radius `R₀` about `c` or, when the medial "ridge"
//! `D ≥ ρ_B` is a straight segment `PQ` ([`ridge_segment`]), the capsule of radius `R₀` about
//! it ([`capsule`]): the points within `R₀` of `PQ`. On a 3:2 rectangle the disc's later
//! fronts keep running round the disc across the short sides, where the offsets are still
//! inside it (laps that cut next to nothing); the capsule's sides are offsets of `B`'s long
//! sides, and the laps after it are as many as the offsets need. `Ω_0 = K` (the ridge is
//! inside the core when `R₀` covers it) and `Ω_{ρ_B}` is the whole region inside `B`. The second set is an exact inward offset
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
//! **The last front** is `B` opened with the interior fronts' radius (rounded convex
//! corners), unless that moves a point of `B` by more than half the spacing bound; `B`
//! itself is the spiral's last loop. Without it the step from the last rounded front onto
//! `B`'s sharp right-angle corners is `√2·Δ + (√2 − 1)·ρ_o`, above the bound: a halved
//! step, that is one whole extra lap.
//!
//! **Skipped fronts.** A front within half a step of the previous loop everywhere (the
//! first fronts, still inside the core) is skipped: its lap would cut next to nothing.
//!
//! **Measured steps.** The steps in `τ` are `Δ = ρ_B / n` with `n = ⌈ρ_B / s'⌉`. After each
//! loop the directed distance from the new loop to the previous one is sampled; above
//! the gap bound ([`FrontOptions::max_gap`], at least `√2·s'`, what a right-angle corner
//! explains; the spiral uses `1.8·s'`, what a 67° corner explains, capped at `1.8·r`) the
//! step is halved, down to `s'/64`, and if that does not help the family is abandoned and
//! the harmonic morph is used. The one exception is the first front beyond the core along the
//! ridge, cut as a slot by a lap that traces it all round; it is taken only where it is one
//! (every point of its new part within `0.9·r` of its loop or of the core's, `is_slot`): a
//! second maximum of `D` nearly as high as the first makes the first front reach into a whole
//! lobe at once, which such a lap would leave uncut inside.

use super::super::shape::{checked_offset, loop_distance, v2};
use crate::geom::Point;
use cavalier_contours::polyline::{
    BooleanOp, PlineCreation, PlineSource, PlineSourceMut, PlineVertex, Polyline,
};

/// The widest hair, mm, that the smoothing removes from a front before offsetting it
/// ([`drop_spikes`]): the joining tolerance of cavalier_contours' booleans (`1e-4` mm), of
/// which the unions the fronts are made of leave such hairs.
const HAIR_WIDTH: f64 = 1e-4;
/// The largest number of loops the fronts may take.
const MAX_LOOPS: usize = 2000;
/// A front that lies within this fraction of a step of the previous loop everywhere is
/// skipped (it would make a lap that cuts next to nothing: the first fronts inside the core).
const SKIP_FRACTION: f64 = 0.5;

/// The area, mm², of the first front's new part that may lie beyond the slot's reach
/// ([`is_slot`]): slivers of the offsets' rounding, far below the verifier's uncut-area
/// tolerance; for tools up to 12.7 mm ([`FrontOptions::slot_area`] for a tool).
pub const SLOT_AREA: f64 = 1e-3;

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
    /// Largest measured distance from a loop to the one before it, mm (at least `√2·step`,
    /// the gap at right-angle corners; larger lets sharper corners through without
    /// halved steps: see `CORNER_GAP` in the spiral module).
    pub max_gap: f64,
    /// How far from the loops that bound it a point of the first front's ridge slot may lie,
    /// mm: a little less than the tool radius (the first lap traces the front all round).
    pub slot_reach: f64,
    /// The area of the first front beyond the slot's reach that still counts as a slot, mm²:
    /// [`SLOT_AREA`] times the square of the tool's
    /// [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale).
    pub slot_area: f64,
}

/// The loops of the morph, from the disc (first) to `B` (last), counter-clockwise.
#[derive(Debug, Clone)]
pub struct Fronts {
    /// Counter-clockwise loops; `loops[0]` is the circle, the last is `B`.
    pub loops: Vec<Polyline<f64>>,
    /// Largest measured distance from a loop to the one before it, mm (the first front's
    /// ridge slot apart).
    pub max_distance: f64,
    /// How far the first front reaches beyond the circle along the ridge when that is more
    /// than a step (cut as a slot by the first lap), mm; 0 otherwise.
    pub ridge_slot: f64,
}

/// A counter-clockwise circle.
pub fn circle(c: Point, r: f64) -> Polyline<f64> {
    let mut pl = Polyline::with_capacity(2, true);
    pl.add(c.x - r, c.y, 1.0);
    pl.add(c.x + r, c.y, 1.0);
    pl
}

/// A counter-clockwise capsule (stadium): the points within `r` of the segment `p`–`q`,
/// starting at the middle of its right-hand side (seen from `p` towards `q`). A circle when
/// `p = q`.
pub fn capsule(p: Point, q: Point, r: f64) -> Polyline<f64> {
    let Some(u) = (q - p).normalize() else {
        return circle(p, r);
    };
    let n = u.perp() * r;
    let m = p.lerp(q, 0.5);
    let mut pl = Polyline::with_capacity(5, true);
    for (v, bulge) in [
        (m - n, 0.0),
        (q - n, 1.0),
        (q + n, 0.0),
        (p + n, 1.0),
        (p - n, 0.0),
    ] {
        pl.add(v.x, v.y, bulge);
    }
    pl
}

/// The ridge of `b` as a straight segment through `c`, when it is one: the set
/// `D ≥ 0.99·ρ_B` (`ρ_B = rho`) is a thin sliver around the medial axis's flat top; its
/// extent along its own principal axis, less the sliver's half-width `0.01·ρ_B` at each end,
/// is the segment. `None` when that is shorter than `min_len` (the ridge is a point: a
/// square, a circle) or when some point of it is closer than `r0` to `b` (a curved ridge,
/// whose chord would leave the region: the capsule of radius `r0` must lie inside `b`).
/// The direction is signed to agree with `hint` (the pocket's principal direction), so the
/// path turns with the pocket.
pub fn ridge_segment(
    b: &Polyline<f64>,
    c: Point,
    rho: f64,
    r0: f64,
    min_len: f64,
    hint: crate::geom::Vec2,
) -> Option<(Point, Point)> {
    let sliver = offset(b, 0.99 * rho)?;
    let pts = super::common::sample_every(&sliver, (0.01 * rho).max(1e-3));
    let (_, sxx, syy, sxy) = crate::geom::region::second_moments(&pts);
    let mut u = crate::geom::Vec2::from_angle(0.5 * (2.0 * sxy).atan2(sxx - syy));
    if u.dot(hint) < 0.0 {
        u = -u;
    }
    let (lo, hi) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
        let t = (*p - c).dot(u);
        (a.0.min(t), a.1.max(t))
    });
    let (lo, hi) = (lo + 0.01 * rho, hi - 0.01 * rho);
    if !(hi - lo >= min_len && lo < 0.0 && hi > 0.0) {
        return None;
    }
    let (p, q) = (c + u * lo, c + u * hi);
    let inside = (0..=32).all(|i| {
        let x = p.lerp(q, f64::from(i) / 32.0);
        b.winding_number(v2(x)) != 0 && loop_distance(b, x) >= r0 * (1.0 + 1e-9)
    });
    inside.then_some((p, q))
}

/// The largest counter-clockwise piece of a set of loops.
fn largest(pieces: Vec<Polyline<f64>>) -> Option<Polyline<f64>> {
    pieces
        .into_iter()
        .filter(|p| p.vertex_count() > 1 && p.area() > 0.0)
        .max_by(|a, b| a.area().total_cmp(&b.area()))
}

/// The counter-clockwise pieces of the offset of a counter-clockwise loop by `d` (inward;
/// negative: outward), checked against the loop ([`checked_offset`]): the single-polyline
/// offset returned nothing at 8.7–14.7 mm on the corpus's `0e2b2de6…`, where the region's
/// offset has 96–619 mm², so the ridge's bisection found a radius far too small and the
/// fronts left 1.1 mm² uncut.
///
/// An inward offset by `d` is empty when no disc of radius `d` fits, certainly when
/// `π·d² > A`: then nothing is offset (cavalier_contours' shape offset took minutes and
/// gigabytes on a 301-vertex sliver of 5·10⁻⁹ mm² offset by 0.4 mm).
fn pieces(pl: &Polyline<f64>, d: f64) -> Vec<Polyline<f64>> {
    if d > 0.0 && std::f64::consts::PI * d * d > pl.area().abs() {
        return Vec::new();
    }
    checked_offset(&[pl], d).outers
}

/// Inward offset of a counter-clockwise loop by `d` (negative: outward); the largest piece.
fn offset(pl: &Polyline<f64>, d: f64) -> Option<Polyline<f64>> {
    if d == 0.0 {
        return Some(pl.clone());
    }
    largest(pieces(pl, d))
}

/// [`offset`] for the smoothing's small radii: cavalier_contours' offset of the single loop
/// (closed where it left it open), taken when its area is what an offset by `d` can have;
/// none otherwise (the fronts then fail, and the next morph is taken). The loop's repeated
/// vertices and spikes are removed first ([`drop_spikes`], [`HAIR_WIDTH`]). Offsetting a
/// loop of area `A` and length `L` inward by `d > 0` leaves at most `A` and at least `A − L·d`
/// (every removed point is within `d` of the loop); outward by `|d|` it adds at least nothing
/// and at most `L·|d| + π·d²`. An offset that dropped a piece falls below the lower bound
/// unless the piece is smaller than the slack `1e-9·A`; the laps made from the result are
/// kept inside the walls and verified like any other.
///
/// There is no checked (shape) offset to fall back on: on the loops where the single-loop
/// offset fails, hairy unions of fronts, cavalier_contours' shape offset can take minutes and
/// gigabytes (one 24-vertex loop: 7.9 GB).
fn smoothing_offset(pl: &Polyline<f64>, d: f64) -> Option<Polyline<f64>> {
    let cleaned = drop_spikes(pl.remove_redundant(1e-7).as_ref().unwrap_or(pl), HAIR_WIDTH);
    let pl = &cleaned;
    let (a, l) = (pl.area().abs(), pl.path_length());
    let slack = 1e-9 * a.max(1.0);
    let plausible = |p: &Polyline<f64>| {
        let pa = p.area().abs();
        if d > 0.0 {
            pa <= a + slack && pa >= a - l * d - slack
        } else {
            pa >= a - slack && pa <= a + l * -d + std::f64::consts::PI * d * d + slack
        }
    };
    largest(crate::geom::region::offset_loops(pl, d)).filter(plausible)
}

/// `pl` without its spikes and repeated vertices, until none is left: a vertex within `eps`
/// of the one before it (the segment between them within `eps` of a line), and a vertex
/// where the loop turns back on itself (the two segments meeting there run in opposite
/// directions) and the triangle it makes with its neighbours is thinner than `eps`, both
/// segments within `eps` of lines. Each removal changes the region by a triangle of area
/// less than `eps` times the longer segment. The boolean unions the fronts are made of leave
/// hairs up to a tenth of a micrometre wide that run back and forth along a line, and
/// cavalier_contours' offsets fail on them (the single-loop one returns open pieces, the
/// shape offset grows the loop by hundreds of vertices a call or runs out of memory); a spike
/// removed can leave its two neighbours on one point, and the next spike behind that point
/// is found only once the point is one vertex.
fn drop_spikes(pl: &Polyline<f64>, eps: f64) -> Polyline<f64> {
    let mut v: Vec<PlineVertex<f64>> = pl.iter_vertexes().collect();
    let near_line = |a: &PlineVertex<f64>, b: &PlineVertex<f64>| {
        // The sagitta of an arc of bulge `β` over a chord `c` is `c·|β|/2` for small `β`.
        let c = ((b.x - a.x).powi(2) + (b.y - a.y).powi(2)).sqrt();
        0.5 * c * a.bulge.abs() <= eps
    };
    let mut changed = true;
    while changed && v.len() > 3 {
        changed = false;
        let mut i = 0;
        while i < v.len() && v.len() > 3 {
            let n = v.len();
            let (p, q, r) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
            let (ux, uy) = (q.x - p.x, q.y - p.y);
            let (wx, wy) = (r.x - q.x, r.y - q.y);
            let longer = (ux * ux + uy * uy).max(wx * wx + wy * wy).sqrt();
            let thin = (ux * wy - uy * wx).abs() <= eps * longer;
            let prev = (i + n - 1) % n;
            if ux.hypot(uy) <= eps && near_line(&p, &q) {
                // `q` on `p`: the segment `p → q` goes, `p` takes `q`'s segment to `r`.
                v[prev].bulge = q.bulge;
                v.remove(i);
                changed = true;
            } else if ux * wx + uy * wy < 0.0 && thin && near_line(&p, &q) && near_line(&q, &r) {
                v[prev].bulge = 0.0;
                v.remove(i);
                changed = true;
            } else {
                i += 1;
            }
        }
    }
    let mut out = Polyline::new_closed();
    for x in v {
        out.add_vertex(x);
    }
    out
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
        // Adjacent floats: no progress left (from `lo = 0` the interval shrinks through the
        // subnormals, where `1e-9 * hi` is 0, and `mid` rounds to `lo`; without this the loop
        // never ended on a loop no positive offset leaves anything of, found by the fuzzer).
        if mid <= lo || mid >= hi {
            break;
        }
        if pieces(b, mid).iter().any(|p| p.area() > 0.0) {
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
        let eroded = smoothing_offset(&cur, ro)?;
        cur = smoothing_offset(&eroded, -ro)?;
    }
    if rc > 0.0 {
        let dilated = smoothing_offset(&cur, -rc)?;
        cur = smoothing_offset(&dilated, rc)?;
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
    for piece in pieces(b, d) {
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

/// True when the part of `front` outside `core` is a slot that a lap tracing `front` clears:
/// every point of it is within `reach` of `front`'s loop or of `core`'s, that is `front`
/// eroded by `reach` lies within `core` dilated by `reach` (to `area`, mm²,
/// [`FrontOptions::slot_area`]). The first front
/// may reach beyond the core along the ridge, a thin neighbourhood of it; where the offsets'
/// new part is wider (a second maximum of the distance to `B` nearly as high as the first,
/// away from the ridge: found by `pocket_props`, 21 mm² left uncut), it is not a slot and the
/// harmonic morph takes the pocket.
fn is_slot(front: &Polyline<f64>, core: &Polyline<f64>, reach: f64, area: f64) -> bool {
    if reach.is_nan() || reach <= 0.0 {
        return false;
    }
    let Some(grown) = offset(core, -reach) else {
        return false;
    };
    pieces(front, reach).iter().all(|inner| {
        let outside: f64 = inner
            .boolean(&grown, BooleanOp::Not)
            .pos_plines
            .iter()
            .map(|p| p.pline.area().abs())
            .sum();
        outside <= area
    })
}

/// Sampled directed distance: the largest distance from a point of `a` to the loop `b`.
pub fn directed_distance(a: &Polyline<f64>, b: &Polyline<f64>, ds: f64) -> f64 {
    super::common::sample_every(a, ds)
        .into_iter()
        .map(|p| loop_distance(b, p))
        .fold(0.0, f64::max)
}

/// The loops from the circle `(c, r0)` to `b`; `None` when the family does not reach `b`
/// with measured steps (see the module docs).
pub fn fronts(
    b: &Polyline<f64>,
    core: &Polyline<f64>,
    rho_b: f64,
    o: &FrontOptions,
) -> Option<Fronts> {
    let disc = core.clone();
    let n = ((rho_b / o.step).ceil() as usize).max(1);
    let delta = rho_b / n as f64;
    let limit = (std::f64::consts::SQRT_2 * o.step).max(o.max_gap);
    // The last front: `B` with its corners rounded like the interior fronts' (`B` itself
    // when that moves any point of `B` by more than half the spacing bound, e.g. where
    // opening would drop a narrow part). A step from a rounded front onto `B`'s sharp
    // corners would be `√2·Δ + (√2 − 1)·ρ_o` long at each right-angle corner, over the bound:
    // a halved step, a whole extra lap. The spiral's last loop, `B` itself, then clears the
    // corners (`(√2 − 1)·ρ_o` deep).
    let b_round = smooth(b, b, o.open_radius, o.close_radius)
        .filter(|r| directed_distance(b, r, o.sample) <= 0.5 * limit)
        .unwrap_or_else(|| b.clone());
    let mut loops = vec![disc.clone()];
    let mut max_distance: f64 = 0.0;
    let mut ridge: f64 = 0.0;
    let mut tau = 0.0;
    let mut step = delta;
    while tau < rho_b {
        if loops.len() > MAX_LOOPS {
            return None;
        }
        let prev = loops.last()?;
        let first = loops.len() == 1;
        let mut h = step;
        let mut full_step = None;
        let (next, dist, t_next) = loop {
            let t = (tau + h).min(rho_b);
            let last = t >= rho_b - 1e-9 * rho_b;
            let cand = if last {
                b_round.clone()
            } else {
                let raw = front(b, &disc, rho_b, t)?;
                let ro = o.open_radius.min(0.9 * t);
                smooth(&raw, b, ro, o.close_radius)?
            };
            let dist = directed_distance(&cand, prev, o.sample);
            if dist <= limit {
                break (cand, dist, t);
            }
            if first && full_step.is_none() {
                full_step = Some((cand, dist, t));
            }
            if h < o.step / 64.0 {
                // The first front may reach beyond the circle along the ridge (a pocket longer
                // than the circle): its new part is then the ridge's thin neighbourhood, half
                // as wide as a step, which the first lap cuts as a slot (the engagement stays
                // within the slotting bound, as zigzag's first pass). Anything else that will
                // not come within the bound is left to the harmonic morph.
                match full_step.take() {
                    Some(f) if first && is_slot(&f.0, prev, o.slot_reach, o.slot_area) => {
                        ridge = f.1;
                        break f;
                    }
                    _ => return None,
                }
            }
            h *= 0.5;
        };
        let reached = t_next >= rho_b - 1e-9 * rho_b;
        if dist < SKIP_FRACTION * o.step && !reached {
            // The front has hardly left the core (or the previous loop): a lap onto it would
            // cut next to nothing. Go on to the next front, measured from the same loop.
            tau = t_next;
            step = delta;
            continue;
        }
        if !(first && ridge > 0.0) {
            max_distance = max_distance.max(dist);
        }
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
        ridge_slot: ridge,
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

    /// A tool-centre region 2 µm across (found by the fuzzer on 2026-11-23): no inward offset
    /// leaves anything of it, so the bisection's interval shrank from `lo = 0` through the
    /// subnormals until `mid` rounded to 0 and the loop never ended (20 s timeouts). It ends,
    /// with no centre or one no deeper than the triangle's inscribed circle.
    #[test]
    fn ridge_centre_of_a_micrometre_sliver_ends() {
        let mut b = Polyline::with_capacity(3, true);
        for (x, y) in [
            (36.39953067577565, 7.562344663834283),
            (36.39749893860321, 7.5623215979103735),
            (36.39473449630062, 7.56039908449441),
        ] {
            b.add(x, y, 0.0);
        }
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(ridge_centre(&b));
        });
        let got = rx
            .recv_timeout(std::time::Duration::from_secs(20))
            .expect("ridge_centre returns");
        // The triangle's inscribed radius, 2·area / perimeter (0.37 µm): the offsets checked
        // against the loop find about that; the default epsilons found nothing.
        let mut b: Polyline<f64> = Polyline::with_capacity(3, true);
        b.add(36.39953067577565, 7.562344663834283, 0.0);
        b.add(36.39749893860321, 7.5623215979103735, 0.0);
        b.add(36.39473449630062, 7.56039908449441, 0.0);
        let inscribed = 2.0 * b.area().abs() / b.path_length();
        assert!(
            got.is_none_or(|(_, rho)| rho <= inscribed + 1e-7),
            "{got:?}, inscribed radius {inscribed:e}"
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
            max_gap: 0.0,
            slot_reach: 1.0,
            slot_area: SLOT_AREA,
        };
        let f = fronts(&b, &circle(c, 25.0), rho, &o).unwrap();
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
    fn ridge_of_a_rectangle_is_its_medial_segment_and_a_square_has_none() {
        let b = rect(137.3, 87.3);
        let (c, rho) = ridge_centre(&b).unwrap();
        let hint = crate::geom::Vec2::new(-1.0, 0.1);
        let (p, q) = ridge_segment(&b, c, rho, 0.5 * rho, 1.0, hint).unwrap();
        // Signed to agree with the hint: from x = 93.65 to x = 43.65 on y = 43.65.
        for (got, want) in [(p, Point::new(93.65, 43.65)), (q, Point::new(43.65, 43.65))] {
            assert!(got.distance(want) < 1e-6, "{got:?} {want:?}");
        }
        let sq = rect(80.0, 80.0);
        let (c, rho) = ridge_centre(&sq).unwrap();
        assert!(ridge_segment(&sq, c, rho, 0.5 * rho, 1.0, hint).is_none());
    }

    #[test]
    fn capsule_is_the_segments_neighbourhood() {
        let (p, q, r) = (Point::new(1.0, 2.0), Point::new(31.0, 2.0), 4.0);
        let cap = capsule(p, q, r);
        let want = 2.0 * r * 30.0 + std::f64::consts::PI * r * r;
        assert!((cap.area() - want).abs() < 1e-9, "{}", cap.area());
        // Starts in the middle of the right-hand side.
        let v = cap.at(0);
        assert!((v.x - 16.0).abs() < 1e-12 && (v.y + 2.0).abs() < 1e-12);
        // Degenerate segment: the circle.
        let c = capsule(p, p, r);
        assert!((c.area() - std::f64::consts::PI * r * r).abs() < 1e-9);
    }

    /// With the capsule core the laps after the core are as many as the offsets need between
    /// the capsule and `B` (plus one for the corners), spaced within the bound; with the disc
    /// of the same radius they are more.
    #[test]
    fn capsule_core_needs_fewer_fronts_than_the_disc() {
        let b = rect(137.3, 87.3);
        let (c, rho) = ridge_centre(&b).unwrap();
        let o = FrontOptions {
            step: 4.98,
            open_radius: 7.1,
            close_radius: 7.1,
            sample: 0.5,
            max_gap: 0.0,
            slot_reach: 1.0,
            slot_area: SLOT_AREA,
        };
        let r0 = 0.5 * rho;
        let (p, q) = ridge_segment(&b, c, rho, r0, 1.0, crate::geom::Vec2::new(1.0, 0.0)).unwrap();
        let cap = fronts(&b, &capsule(p, q, r0), rho, &o).unwrap();
        let disc = fronts(&b, &circle(c, r0), rho, &o).unwrap();
        // ⌈(43.65 − 21.8)/4.98⌉ = 5 along the sides, 6 at the corners (√2 steps).
        assert!(cap.loops.len() - 1 <= 6, "{}", cap.loops.len());
        assert!(
            disc.loops.len() > cap.loops.len(),
            "{} {}",
            disc.loops.len(),
            cap.loops.len()
        );
        for w in cap.loops.windows(2) {
            let d = directed_distance(&w[1], &w[0], 0.5);
            assert!(d <= std::f64::consts::SQRT_2 * 4.98 + 1e-6, "{d}");
        }
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
