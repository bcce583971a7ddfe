//! Rounding the interior offset loops as much as the stepover bound allows.
//!
//! Contour-parallel loops keep the walls' convex corners: every inward offset of a rectangle
//! is a rectangle, and a controller must nearly stop at each of its corners. Loop `X` of level
//! `k ≥ 1` is replaced by its *opening* `X_ρ` (the region inside it eroded by `ρ`, then
//! dilated by `ρ`: two exact offsets, arcs kept): convex corners become arcs of radius `ρ`,
//! everything else stays. The walls' own loops (level 0) are never rounded.
//!
//! **Bound.** Rounding moves a convex corner of interior angle `α` inward by
//! `ρ·(1/sin(α/2) − 1)`, so the band between `X_ρ` and the (rounded) loop `Y'` cut after it
//! widens there. For every sample `y` of `Y'` whose nearest loop of `X`'s level is `X`:
//!
//! ```text
//!   dist(y, X_ρ) ≤ max(g, dist(y, X) + ε)          g = [`RoundOptions::max_gap`]
//! ```
//!
//! that is, the directed gap stays below `g` (a multiple of the step, below the tool's
//! diameter so that no ridge of material stands between two passes) except where the exact
//! offsets themselves are farther apart (acute corners: `h/sin(α/2)`), where it may not grow.
//! And the loops fed into `X` stay inside `X_ρ`, at least [`RoundOptions::min_clearance`]
//! from it; and the material `X`'s own pass covers when exact (the band from `X` to the
//! loops fed into it, sampled on `X`, halfway in and on those loops) stays within
//! [`RoundOptions::reach`] of `X_ρ`, of the rounded loops outside or of the exact loops
//! inside: rounding a loop next to where the loops inside it end (a medial axis branch's
//! tip) would otherwise move it beyond the tool's reach of that material. Each loop takes the largest `ρ ≤` [`RoundOptions::max_radius`] that keeps both
//! (bisection; the gap grows with `ρ`), level by level from the walls inward, so that inner
//! loops are measured against the rounded loops outside them. At right angles with
//! `g = 1.8·h` each loop can be rounded about `0.93·h` more than the one outside it, so the
//! radii grow inward until the loops are as round as their size allows.
//!
//! **Cusps.** Where no radius keeps the bound (an acute corner whose exact gap already
//! exceeds it: the medial axis's point where the arcs round two reflex corners of the walls
//! meet, turning the path 110–160°), the loop would keep a corner where two arcs meet at an
//! angle. Written as arcs (`--arcs`, [`RoundOptions::cusp_shift`] given), such a loop is
//! filleted instead with the largest radius `step·2^-j ≥` [`RoundOptions::cusp_radius`] whose
//! opening keeps the bound with the slack `cusp_shift` (0.1 step): the corner moves in by
//! `ρ·(1/sin(α/2) − 1)`, at most that, and the reach of the band is checked as for any
//! radius. A radius the bisection finds below `cusp_radius` counts as none there (an arc a few
//! microns round is not written faithfully). Written as chords, the loops keep their
//! corners: a fillet shorter than a chord would still be one.

use super::super::loops::{OffsetLoops, samples};
use super::super::shape::IndexedLoop;
use crate::geom::Point;
use crate::geom::region::offset_loops;
use cavalier_contours::polyline::{PlineSource, Polyline};

/// What the rounding may do.
#[derive(Debug, Clone, Copy)]
pub struct RoundOptions {
    /// Largest directed gap from a loop to the rounded loop inside it, mm (where the exact
    /// offsets are closer).
    pub max_gap: f64,
    /// Largest rounding radius, mm.
    pub max_radius: f64,
    /// Least distance between a rounded loop and the loops fed into it, mm.
    pub min_clearance: f64,
    /// Sample spacing of the checks, mm.
    pub sample: f64,
    /// How far from a pass material counts as cut, mm (a little less than the tool radius):
    /// the material the exact loop would cut must stay within this of the rounded loop or of
    /// its neighbours.
    pub reach: f64,
    /// How far a loop the bound leaves unrounded may still be filleted at its corners, mm:
    /// the gap from the loops outside may grow by this much (`None`: such a loop keeps its
    /// corners).
    pub cusp_shift: Option<f64>,
    /// Smallest such fillet's radius, mm: a smaller arc is below what a program writes
    /// faithfully (its ends and centre a few resolution steps apart).
    pub cusp_radius: f64,
}

/// Bisection steps on the radius.
const BISECTIONS: usize = 5;
/// The radius tried first for a loop: this many steps more than the largest radius of the
/// loops it feeds (at right angles a loop can be rounded about 0.93 steps more than the
/// loop outside it; more where its corners are obtuse).
const GROWTH: f64 = 3.0;
/// Slack on the exact offsets' gap, as a fraction of the step.
const GAP_SLACK: f64 = 1e-3;
/// A loop no radius keeps within the bound is filleted with the largest radius in
/// `step·2^-j`, `j < CUSP_TRIES`, at least [`RoundOptions::cusp_radius`], that moves it at
/// most [`RoundOptions::cusp_shift`].
const CUSP_TRIES: i32 = 10;

/// The rounded loops, one per loop of `loops` (same indices), and their radii.
pub fn round(loops: &OffsetLoops, opts: &RoundOptions) -> (Vec<Polyline<f64>>, Vec<f64>) {
    let mut out: Vec<Polyline<f64>> = loops.nodes.iter().map(|n| n.pline.clone()).collect();
    let mut radii = vec![0.0; loops.nodes.len()];
    for k in 1..loops.levels() {
        let level: Vec<usize> = loops.level(k).collect();
        let exact: Vec<IndexedLoop<'_>> = level
            .iter()
            .map(|&i| IndexedLoop::new(&loops.nodes[i].pline))
            .collect();
        for (a, &x) in level.iter().enumerate() {
            // The samples of the rounded loops cut after X that X must reach.
            let mut assigned: Vec<(Point, f64)> = Vec::new();
            for &y in &loops.nodes[x].next {
                for p in samples(&out[y], opts.sample) {
                    let near = exact
                        .iter()
                        .enumerate()
                        .map(|(b, l)| (b, l.distance(p)))
                        .min_by(|u, v| u.1.total_cmp(&v.1));
                    if let Some((b, d)) = near
                        && b == a
                    {
                        assigned.push((p, d));
                    }
                }
            }
            let inner: Vec<Point> = loops.nodes[x]
                .prev
                .iter()
                .flat_map(|&z| samples(&loops.nodes[z].pline, opts.sample))
                .collect();
            // The material X's pass covers when exact: the band from X to the loops inside
            // it, sampled on X, halfway in, and on the inner loops. What the rounded loops
            // outside and the exact loops inside already reach needs nothing of X.
            let island = loops.nodes[x].island;
            let fixed: Vec<Polyline<f64>> = loops.nodes[x]
                .next
                .iter()
                .map(|&y| out[y].clone())
                .chain(
                    loops.nodes[x]
                        .prev
                        .iter()
                        .map(|&z| loops.nodes[z].pline.clone()),
                )
                .collect();
            let fixed_idx: Vec<IndexedLoop<'_>> = fixed.iter().map(IndexedLoop::new).collect();
            let band: Vec<Point> = samples(&loops.nodes[x].pline, opts.sample)
                .into_iter()
                .chain(
                    loops.nodes[x]
                        .pline
                        .parallel_offset(0.5 * loops.step)
                        .iter()
                        .flat_map(|p| samples(p, opts.sample)),
                )
                .chain(inner.iter().copied())
                .filter(|&p| fixed_idx.iter().all(|l| l.distance(p) > opts.reach))
                .collect();
            let ok_within = |rho: f64, slack: f64| -> Option<Polyline<f64>> {
                let opened = open(&loops.nodes[x].pline, rho)?;
                let idx = IndexedLoop::new(&opened);
                if band.iter().any(|&p| idx.distance(p) > opts.reach) {
                    return None;
                }
                let gap_ok = assigned
                    .iter()
                    .all(|&(p, d)| idx.distance(p) <= opts.max_gap.max(d + slack));
                // The inner loops on the region's side (one point tells, as none comes
                // closer than the clearance, so none crosses).
                let side = inner.first().is_none_or(|&z| {
                    let wn = opened.winding_number(super::super::shape::v2(z));
                    if island { wn == 0 } else { wn != 0 }
                });
                let inside_ok =
                    side && inner.iter().all(|&z| idx.distance(z) >= opts.min_clearance);
                (gap_ok && inside_ok).then_some(opened)
            };
            let ok = |rho: f64| ok_within(rho, GAP_SLACK * loops.step);
            let outside = loops.nodes[x]
                .next
                .iter()
                .map(|&y| radii[y])
                .fold(0.0, f64::max);
            let hi = opts.max_radius.min(outside + GROWTH * loops.step);
            // The largest radius that passes: `hi` if it does; else bisection, between the
            // radius of the loops outside (when it passes) and `hi`, or below it.
            let best = if let Some(p) = ok(hi) {
                Some((hi, p))
            } else {
                let start = outside.min(hi);
                let (mut lo, mut top, mut best) = match (start > 0.0).then(|| ok(start)).flatten() {
                    Some(p) => (start, hi, Some((start, p))),
                    None => (0.0, start.max(1e-9).min(hi), None),
                };
                if best.is_none() && start <= 0.0 {
                    top = hi;
                }
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (lo + top);
                    match ok(mid) {
                        Some(p) => {
                            lo = mid;
                            best = Some((mid, p));
                        }
                        None => top = mid,
                    }
                }
                best
            };
            // Cusps: where no radius keeps the gap (a corner whose exact gap is already
            // wider than the bound, such as the medial axis's point where two reflex
            // corners' arcs meet), the largest small fillet that moves the loop by at most
            // the cusp shift, so that the path stays tangent-continuous there.
            // Written as arcs, a radius below the least is no radius.
            let best = best.filter(|b| opts.cusp_shift.is_none() || b.0 >= opts.cusp_radius);
            let best = best.or_else(|| {
                let shift = opts.cusp_shift?;
                (0..CUSP_TRIES)
                    .map(|j| loops.step * 0.5f64.powi(j))
                    .take_while(|&rho| rho >= opts.cusp_radius)
                    .find_map(|rho| ok_within(rho, shift).map(|p| (rho, p)))
            });
            if let Some((rho, p)) = best {
                radii[x] = rho;
                out[x] = p;
            }
        }
    }
    (out, radii)
}

/// The opening of loop `pl` by `rho` towards the region's side (the inside of a
/// counter-clockwise loop, the outside of a clockwise one): `None` unless it is one loop of
/// the same orientation.
pub fn open(pl: &Polyline<f64>, rho: f64) -> Option<Polyline<f64>> {
    if rho <= 0.0 {
        return Some(pl.clone());
    }
    let ccw = pl.area() > 0.0;
    let eroded = single(offset_loops(pl, rho), ccw)?;
    single(offset_loops(&eroded, -rho), ccw)
}

/// The one loop of `pieces` with the given orientation.
fn single(pieces: Vec<Polyline<f64>>, ccw: bool) -> Option<Polyline<f64>> {
    let mut it = pieces
        .into_iter()
        .filter(|p| p.vertex_count() > 1 && p.area().abs() > 1e-12);
    let one = it.next()?;
    if it.next().is_some() || (one.area() > 0.0) != ccw {
        return None;
    }
    Some(one)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cavalier_contours::polyline::PlineSourceMut;

    fn square(ccw: bool) -> Polyline<f64> {
        let mut pl = Polyline::new_closed();
        let mut v = vec![(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
        if !ccw {
            v.reverse();
        }
        for (x, y) in v {
            pl.add(x, y, 0.0);
        }
        pl
    }

    #[test]
    fn opening_rounds_convex_corners_on_the_regions_side() {
        // Counter-clockwise: the square's own corners become arcs of radius 2.
        let o = open(&square(true), 2.0).expect("one loop");
        assert!(o.area() > 0.0);
        let want = 100.0 - (4.0 - std::f64::consts::PI) * 4.0;
        assert!((o.area() - want).abs() < 1e-6, "{}", o.area());
        // Clockwise (a loop around an island): the region is outside, whose corners are
        // concave; nothing changes.
        let c = open(&square(false), 2.0).expect("one loop");
        assert!((c.area() + 100.0).abs() < 1e-6, "{}", c.area());
        // Too large: the square vanishes.
        assert!(open(&square(true), 6.0).is_none());
    }
}
