//! One chain of loops as one continuous spiral: each loop once round, then a smooth lane
//! change onto the next loop out.
//!
//! The loops `R₀` (innermost) … `R_m` of a chain are nested and about `h` apart. The path runs
//! round `R₀` once, then, from position `P_i` of loop `R_i`, changes lane onto `R_{i+1}` over a
//! window of `D_i` mm: with `a(u) = R_i(P_i + u)` and `b(u)` the point of `R_{i+1}` nearest to
//! it,
//!
//! ```text
//!   x(u) = a(u) + σ(u/D)·(b(u) − a(u)),   σ(t) = 10t³ − 15t⁴ + 6t⁵,   0 ≤ u ≤ D
//! ```
//!
//! `σ` has zero first and second derivatives at both ends, so the path leaves `R_i` and joins
//! `R_{i+1}` with the loops' own tangent and curvature (curvature-continuous where the loops
//! are). On parallel straight stretches `h` apart its curvature peaks at `5.77·h/D²`. Then
//! the path follows `R_{i+1}` round to `P_{i+1}`, the point of `R_{i+1}` nearest to `P_i`: the
//! windows are stacked across the loops, so every lane change runs next to the previous one
//! `h` inside it, and the radial depth of cut stays that of the loops (a window not stacked
//! would leave a stretch of the next loop cutting `2h`). The outermost loop is run once
//! round from where the last lane change lands on it and closed, so it is cut whole (it is
//! the wall's loop, or the loop the next chain starts from). Length: each loop once, plus
//! the last window: as long as the contour-parallel loops without their links.
//!
//! **Arcs.** With `--arcs` a lane change is fitted with biarcs through its points and a point
//! a chord before and after it along the loops' tangents, and its first and last arcs are
//! replaced by the biarcs with the loops' own tangents at the ends: arcs meet arcs within
//! 1e-4 rad where the lane leaves and joins the loops.
//!
//! **Where.** The windows should lie where every loop is straight: the start `P₀` is chosen
//! among positions of `R₀` every `WINDOW_STEP` mm (times the tool's scale) to minimise the
//! total turning of all the loops over their windows, plus a small charge for the distance
//! run round `R₀` past the point where the chain is entered (the first loop is run whole
//! from there).

use super::super::segments::{Seg, fit_arcs_inner, segs_from_points};
use super::ring::Ring;
use crate::geom::{Point, Vec2};

/// What a chain's path needs.
#[derive(Debug, Clone, Copy)]
pub struct LaneOptions {
    /// Length of a lane change, mm (shorter on loops less than four times as long).
    pub window: f64,
    /// Largest chord along a lane change, mm.
    pub chord: f64,
    /// The loops' spacing, mm.
    pub step: f64,
    /// How far from a pass material counts as cut, mm (a little less than the tool radius):
    /// a lane change only where its two loops are no farther apart than this.
    pub reach: f64,
    /// Lane changes as tangent-continuous arcs (biarcs within `arc_tolerance` of the smooth
    /// curve through the chords' points), except one that lands on a wall's loop (whose
    /// arcs could overshoot it into the wall).
    pub arcs: bool,
    /// See `arcs`, mm.
    pub arc_tolerance: f64,
    /// Largest chord of a lane change that lands on a wall's loop, mm.
    pub wall_chord: f64,
    /// Interior loops' arcs as chords: their largest sagitta and length, mm (`None`: exact
    /// arcs).
    pub chords: Option<(f64, f64)>,
    /// The tool's [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale): the window
    /// starts are tried `WINDOW_STEP` times it apart, and the entry charge is per that many
    /// mm.
    pub scale: f64,
}

/// Candidate window starts along the first loop, mm apart (times [`LaneOptions::scale`]).
const WINDOW_STEP: f64 = 1.0;
/// What a straight step instead of a lane change costs in the choice of the windows, rad of
/// turning: a step is a corner the controller must slow for.
const STEP_COST: f64 = 3.0;
/// Most halvings of a lane change's sampling interval.
const MAX_REFINE: usize = 10;
/// Window starts tried in full, best first estimate first.
const CANDIDATES: usize = 12;
/// Turning (rad) that one mm (times [`LaneOptions::scale`]) of extra path past the entry
/// point is worth in the choice of the windows.
const ENTRY_CHARGE: f64 = 0.002;

/// How far along the wall's loop an inset lane change joins it, in insets (the join turns
/// by `atan(1/JOIN_SLANT)`, 2.9°).
const JOIN_SLANT: f64 = 20.0;

/// A lane change's sample: `u` along the window, the position of the nearest point on the
/// next loop, and the distance to it.
type Sample = (f64, f64, f64);

/// One lane change: the chords' points from `from` at `p` onto `to`, and the position on
/// `to` where it lands; `None` when the nearest points of `to` do not follow smoothly (they
/// jump to another part of the loop, or the loops are not about one step apart there).
///
/// The window is sampled densely enough on both loops: where the nearest point of `to`
/// advances by more than a chord between two samples (a short loop's tight turn against a
/// longer loop's wide one), the interval is halved, so that every point of the stretch of
/// `to` the change passes by is near a sample of it, at most `(1 − σ)·gap` from the lane.
/// The target points are taken `inset` mm short of `to` (towards `from`): chords onto a wall's
/// exact loop must not sag across its concave arcs.
fn lane(
    from: &Ring,
    to: &Ring,
    (p, d, q): (f64, f64, f64),
    (chord, inset, step, reach): (f64, f64, f64, f64),
) -> Option<(Vec<Point>, f64)> {
    let k = ((d / chord).ceil() as usize).max(4);
    let du = d / k as f64;
    // Samples (u, position on `to`, distance), refined where `to` runs ahead.
    let mut samples: Vec<Sample> = Vec::with_capacity(2 * k + 2);
    let mut sb = q;
    for j in 0..=k {
        let u = du * j as f64;
        let a = from.point(p + u);
        let (s, dist) = to.project_near(a, sb, 2.0 * du, 4.0 * du + 2.0 * step);
        samples.push((u, s, dist));
        sb = s;
    }
    let mut refined = Vec::with_capacity(samples.len());
    let mut stack: Vec<(Sample, Sample, usize)> =
        samples.windows(2).rev().map(|w| (w[0], w[1], 0)).collect();
    refined.push(samples[0]);
    while let Some((l, r, depth)) = stack.pop() {
        if r.1 - l.1 <= chord || depth >= MAX_REFINE {
            refined.push(r);
            continue;
        }
        let u = 0.5 * (l.0 + r.0);
        let a = from.point(p + u);
        let (s, dist) = to.project_near(a, l.1, 0.0, r.1 - l.1);
        let m = (u, s, dist);
        stack.push((m, r, depth + 1));
        stack.push((l, m, depth + 1));
    }
    let g0 = refined[0].2;
    let mut pts = Vec::with_capacity(refined.len());
    for w in refined.windows(2) {
        // Still a jump: the nearest points left the stretch (another part of `to`).
        if w[1].1 - w[0].1 > 2.0 * chord + step || w[1].1 < w[0].1 - 1e-9 {
            return None;
        }
    }
    for &(u, s, dist) in &refined {
        // The loops no farther apart than the tool reaches: the lane then cuts everything
        // between them along the stretch of `to` it passes by (each point of that stretch is
        // at most `(1 − σ)·dist` from the lane, and the lane's start was run round before).
        if !(dist <= reach && dist >= 0.5 * g0 - chord) {
            return None;
        }
        let a = from.point(p + u);
        let b = to.point(s);
        let b = b + (a - b) * (inset / dist.max(inset)).min(1.0);
        pts.push(a + (b - a) * smoothstep(u / d));
    }
    let last = refined.last().map_or(q, |r| r.1);
    let land = to.wrap(last);
    // The skipped stretch of the next loop is the window itself, not more.
    let span = last - q;
    if span > 2.0 * d * (to.len() / from.len()).max(1.0) + chord {
        return None;
    }
    Some((pts, land))
}

/// How the path gets from one loop to the next: a lane change (its points and where it lands)
/// or, where none follows the loops, a straight step at the window's start.
type Change = Option<(Vec<Point>, f64)>;
/// The changes of a chain, each with its window's start on its loop.
type Changes = Vec<(f64, Change)>;

/// What the outermost loop of a chain is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Outermost {
    /// A loop inside the pocket (the next chain starts from it).
    Interior,
    /// A wall's loop: lane changes onto it stay chords, end `inset` mm short of it (0 when
    /// the loop is already inside the wall's clearance by more than the chords' sagitta), and
    /// step onto it.
    Wall {
        /// mm.
        inset: f64,
    },
}

/// The spiral through `rings` (innermost first, all in the cutting direction), entered at the
/// point of the first ring nearest to `enter`. Returns the path (its first point is that
/// entry point).
pub fn chain_path(rings: &[Ring], enter: Point, outer: Outermost, opts: &LaneOptions) -> ChainPath {
    let mut until = None;
    let segs = chain_segs(rings, enter, outer, opts, &mut until);
    let interior = until.unwrap_or(segs.len());
    ChainPath { segs, interior }
}

/// A chain's path.
#[derive(Debug, Clone)]
pub struct ChainPath {
    /// The moves, in order.
    pub segs: Vec<Seg>,
    /// `segs[..interior]` runs inside the pocket; from there on the last change onto a wall's
    /// loop and the loop itself (which must stay as they are).
    pub interior: usize,
}

/// [`chain_path`]'s moves; `until` is set where the change onto a wall's loop starts.
fn chain_segs(
    rings: &[Ring],
    enter: Point,
    outer: Outermost,
    opts: &LaneOptions,
    until: &mut Option<usize>,
) -> Vec<Seg> {
    let (last_is_wall, wall_inset) = match outer {
        Outermost::Interior => (false, 0.0),
        Outermost::Wall { inset } => (true, inset),
    };
    let Some(first) = rings.first() else {
        return Vec::new();
    };
    let onto_wall = |i: usize| last_is_wall && i + 2 == rings.len();
    // The loops' stretches, as exact segments or as chords (never a wall's loop).
    let stretch = |i: usize, s: f64, len: f64| -> Vec<Seg> {
        let segs = rings[i].slice(s, len);
        match opts.chords {
            Some((tol, max)) if !(last_is_wall && i + 1 == rings.len()) => chorded(&segs, tol, max),
            _ => segs,
        }
    };
    let (s_in, _) = first.project(enter);
    if rings.len() == 1 && last_is_wall {
        *until = Some(0);
    }
    let mut path = stretch(0, s_in, first.len());
    if rings.len() == 1 {
        return path;
    }
    let windows = |i: usize| opts.window.min(0.25 * rings[i].len());
    // A first estimate for a start `p0` on the first ring: the loops' turning over the
    // stacked windows (the landing stretch taken in proportion to the loops' lengths).
    let estimate = |p0: f64| -> f64 {
        let mut p = p0;
        let mut cost = 0.0;
        for i in 0..rings.len() - 1 {
            let d = windows(i);
            let (q, _) = rings[i + 1].project(rings[i].point(p));
            let span = d * rings[i + 1].len() / rings[i].len();
            cost += rings[i].turning(p, d) + rings[i + 1].turning(q, span);
            p = q;
        }
        cost
    };
    // The stacked changes for `p0` (each with its start on its loop), and their cost: the
    // loops' turning over the windows, a step's worth for a step.
    let stack = |p0: f64| -> (Changes, f64) {
        let mut changes: Changes = Vec::with_capacity(rings.len() - 1);
        // Where the next change starts on ring i: the first loop's window; then, after a lane
        // change, the point stacked over the previous window's start; after a step, where
        // the step landed (the loop is run whole from there first).
        let mut p = p0;
        // Where the path entered ring i (after a lane change, a step needs the loop whole
        // from there).
        let mut entry = p0;
        let mut cost = 0.0;
        for i in 0..rings.len() - 1 {
            let d = windows(i);
            let (chord, inset) = if onto_wall(i) {
                (opts.wall_chord, wall_inset)
            } else {
                (opts.chord, 0.0)
            };
            let (q, _) = rings[i + 1].project(rings[i].point(p));
            let change = lane(
                &rings[i],
                &rings[i + 1],
                (p, d, q),
                (chord, inset, opts.step, opts.reach),
            );
            match change {
                Some((pts, land)) => {
                    cost += rings[i].turning(p, d)
                        + rings[i + 1].turning(q, rings[i + 1].wrap(land - q));
                    changes.push((p, Some((pts, land))));
                    entry = land;
                    p = q;
                }
                None => {
                    // A straight step, from where the path entered this loop once round: a
                    // stretch a lane change onto this loop passed by is then cut, as no lane
                    // change out of it runs over it.
                    cost += STEP_COST;
                    changes.push((entry, None));
                    let (s, _) = rings[i + 1].project(rings[i].point(entry));
                    entry = s;
                    p = s;
                }
            }
        }
        (changes, cost)
    };
    let charge = ENTRY_CHARGE / opts.scale;
    let n = ((first.len() / (WINDOW_STEP * opts.scale)).ceil() as usize).max(8);
    let step = first.len() / n as f64;
    let mut order: Vec<(f64, f64)> = (0..n)
        .map(|j| {
            let past = step * j as f64;
            (estimate(first.wrap(s_in + past)) + charge * past, past)
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // The best estimates in full, until one needs no step.
    let mut best: Option<(Changes, f64, f64)> = None;
    for &(_, past) in order.iter().take(CANDIDATES) {
        let (changes, turn) = stack(first.wrap(s_in + past));
        let cost = turn + charge * past;
        let clean = changes.iter().all(|c| c.1.is_some());
        if best.as_ref().is_none_or(|b| cost < b.1 - 1e-12) {
            best = Some((changes, cost, past));
        }
        if clean {
            break;
        }
    }
    let Some((changes, _, past)) = best else {
        *until = last_is_wall.then_some(path.len());
        return path;
    };
    // The rest of the first loop up to the first window.
    path.extend(stretch(0, s_in, past));
    for (i, (p, change)) in changes.iter().enumerate() {
        let (from, to) = (&rings[i], &rings[i + 1]);
        if onto_wall(i) {
            *until = Some(path.len());
        }
        // Where the path is on `to` after the change, and how much of `to` is still to run
        // before the next change (or, on the outermost loop, to close it).
        let land = match change {
            Some((pts, land)) => {
                if opts.arcs && !onto_wall(i) && pts.len() > 1 {
                    // A point a chord before and after, along the loops' tangents: the arcs
                    // leave and join the loops with their tangents.
                    let t0 = path.last().map(|g| g.tangent_at(g.length()));
                    let t1 = to
                        .slice(*land, 1e-6 * to.len())
                        .first()
                        .map(|g| g.tangent_at(0.0));
                    let n = pts.len();
                    let before = pts.get(1).map_or(opts.chord, |q| q.distance(pts[0]));
                    let after = pts
                        .get(n.saturating_sub(2))
                        .map_or(opts.chord, |q| q.distance(pts[n - 1]));
                    let mut ext = Vec::with_capacity(n + 2);
                    let (first, last) = (pts[0], pts[n - 1]);
                    let dir = |t: Option<Vec2>, a: Point, b: Point| {
                        t.or_else(|| (b - a).normalize())
                            .unwrap_or(Vec2::new(1.0, 0.0))
                    };
                    let least = 1e-3 * opts.chord;
                    ext.push(first - dir(t0, first, pts[1]) * before.max(least));
                    ext.extend_from_slice(pts);
                    ext.push(last + dir(t1, pts[n - 2], last) * after.max(least));
                    let mut arcs = fit_arcs_inner(&ext, opts.arc_tolerance);
                    tangent_ends(&mut arcs, t0, t1);
                    path.extend(arcs);
                } else {
                    path.extend(segs_from_points(pts));
                }
                // An inset lane ends just short of the loop: join it at a slant, `JOIN_SLANT`
                // times the inset further on, not straight across (two right-angle turns a
                // few µm apart, where the controller would stop twice).
                let (end, on) = (pts.last().copied(), to.point(*land));
                match end.filter(|e| e.distance(on) > 1e-12) {
                    Some(e) => {
                        let ahead = to.wrap(*land + JOIN_SLANT * e.distance(on));
                        path.push(Seg::line(e, to.point(ahead)));
                        ahead
                    }
                    None => *land,
                }
            }
            None => {
                let a = from.point(*p);
                let (q, _) = to.project(a);
                let b = to.point(q);
                if a.distance(b) > 1e-12 {
                    path.push(Seg::line(a, b));
                }
                q
            }
        };
        match changes.get(i + 1) {
            // Round to the next change's start; once round when it starts where the path
            // came onto the loop (after a step, or before one).
            Some((next_p, _)) => {
                let run = to.wrap(next_p - land);
                let full = run < 1e-9 || to.len() - run < 1e-9;
                path.extend(stretch(i + 1, land, if full { to.len() } else { run }));
            }
            None => path.extend(stretch(i + 1, land, to.len())),
        }
    }
    path
}

/// `arcs` made to leave with tangent `t0` and arrive with `t1` (where given): the first and
/// the last move (the only one, with both) replaced by the biarc between their ends with
/// those tangents and the moves' own at their other ends. The fitted arcs' end tangents are
/// the Catmull-Rom curve's, a degree or a few off the loops' where the lane turns fast; the
/// biarc of a short move with tangents a few degrees apart stays within microns of it.
fn tangent_ends(arcs: &mut Vec<Seg>, t0: Option<Vec2>, t1: Option<Vec2>) {
    use crate::curve::biarc::biarc;
    let off = |t: Option<Vec2>, u: Vec2| {
        t.is_some_and(|t| t.cross(u).atan2(t.dot(u)).abs() > TANGENT_SLACK)
    };
    let swap = |g: &Seg, ta: Vec2, tb: Vec2| -> Option<Vec<Seg>> {
        let pair = biarc(g.a, ta, g.b, tb, 0.0, 1.0)?;
        Some(
            pair.iter()
                .filter(|a| a.start.distance(a.end) > 1e-9)
                .map(|a| Seg::from_bulge(a.start, a.end, (0.25 * a.sweep()).tan()))
                .collect(),
        )
    };
    let n = arcs.len();
    if n == 0 {
        return;
    }
    let (first, last) = (arcs[0], arcs[n - 1]);
    if n == 1 {
        let (ta, tb) = (first.tangent_at(0.0), first.tangent_at(first.length()));
        if (off(t0, ta) || off(t1, tb))
            && let Some(r) = swap(&first, t0.unwrap_or(ta), t1.unwrap_or(tb))
        {
            *arcs = r;
        }
        return;
    }
    if let Some(t) = t1.filter(|&t| off(Some(t), last.tangent_at(last.length())))
        && let Some(r) = swap(&last, last.tangent_at(0.0), t)
    {
        arcs.pop();
        arcs.extend(r);
    }
    if let Some(t) = t0.filter(|&t| off(Some(t), first.tangent_at(0.0)))
        && let Some(r) = swap(&first, t, first.tangent_at(first.length()))
    {
        arcs.splice(0..1, r);
    }
}

/// Largest angle (rad) between a lane's fitted end tangent and the loop's left as it is.
const TANGENT_SLACK: f64 = 1e-4;

/// `segs` with every arc replaced by chords whose sagitta is at most `tol` and no longer
/// than `max_chord` (for controllers that plan chords faster than arcs).
pub fn chorded(segs: &[Seg], tol: f64, max_chord: f64) -> Vec<Seg> {
    let mut out = Vec::with_capacity(segs.len());
    for g in segs {
        match g.arc {
            None => out.push(*g),
            Some(arc) => {
                // Sagitta of a chord of length c on radius R: c²/(8R).
                let c = (8.0 * arc.radius * tol).sqrt().min(max_chord);
                let len = g.length();
                let n = ((len / c.max(1e-9)).ceil() as usize).max(1);
                let mut a = g.a;
                for k in 1..=n {
                    let b = if k == n {
                        g.b
                    } else {
                        g.point_at(len * k as f64 / n as f64)
                    };
                    out.push(Seg::line(a, b));
                    a = b;
                }
            }
        }
    }
    out
}

/// `10t³ − 15t⁴ + 6t⁵`: 0 → 1 with zero first and second derivatives at both ends.
fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * t * (10.0 + t * (-15.0 + 6.0 * t))
}
