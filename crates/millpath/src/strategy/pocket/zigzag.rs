//! Zigzag: parallel passes at an angle, clipped to the boundary offset, then a clean-up pass
//! along the boundary offset (the paper's "conventional" path).
//!
//! **Frame.** The pass angle is measured from the pocket's principal axis
//! ([`crate::geom::region::principal_angle`]: the long direction of the outline), not from
//! the machine's x axis. The path is then a property of the pocket: the same pocket turned by
//! any angle gets the same passes, turned. (Measured from x, a pocket turned by 30° would get
//! passes across its long direction, a different path of a different length.) The cycle time
//! is not exactly rotation-invariant even so: the machine's limits are per axis, so a pass
//! along x and the same pass at 45° accelerate differently; the pocket tests measure by how
//! much: on the L-shaped pocket of `tests/pocket_props.rs` (50 × 40 mm, one island, 6 mm
//! tool) turning the pocket by 45° makes the `hsm` cycle time 2.0% shorter for zigzag and
//! 4.0% for offset (a diagonal move may use √2 times the axis acceleration along the path),
//! while reversing, translating and quarter turns change it by less than 0.5%. We keep the
//! planner's per-axis time (it is the truth for such a machine) and make the path, not the
//! time, rotation-invariant; the tests bound the time change under arbitrary rotation at 6%.
//! With the default angle 0 the passes run along the long direction, the usual choice
//! (fewer turnarounds).
//!
//! **Islands.** The islands' offset loops are among the loops the rows are clipped by (the
//! even-odd rule makes a row skip each island), a link never crosses a loop of the boundary
//! offset (so it goes round an island, never across it), and the clean-up pass runs along
//! every loop of the boundary offset: the wall and each island.
//!
//! In a frame rotated by −angle the passes are horizontal lines `s` apart, the first and the
//! last `g = (span − m·s)/2 ≤ 1.5·r` from the region's lowest and highest points
//! ([`row_heights`], `m` as small as that allows): no row runs along the boundary offset or
//! nearer it than it need (every point between an extreme and its row lies within `g/2 <
//! r` of the clean-up pass along the extreme or of the row, along the row's normal), so a
//! rectangle `span` high gets `⌈(span − 3·r)/s⌉ + 1` rows, two fewer than rows a stepover
//! apart from extreme to extreme (`⌈span/s⌉ − 1`) on the aerospace pocket and the
//! rectangles of `tests/pocket_zigzag.rs`; the clean-up pass then cuts up to `g` deep along
//! the extremes, which the feed modulation charges. With a stepover above `1.5·r` the rows
//! divide the span evenly, `h ≤ s` apart, none on the extremes.
//!
//! **The first row's ramp.** The first cut starts on the lowest row. When that row can come
//! within `g₁ = 1.9·r − s` of the lowest point without costing a row (`m` unchanged), it
//! does, and the ramp runs along it as it is cut ([`CutEntry::RampAlong`]): an odd number
//! of passes over its head, the last ending at the level, and the row goes on from there.
//! The ramp leaves material above its slope, within the row's swath `[y₁ − r, y₁ + r]`;
//! the clean-up pass along the extreme `y₀` and the second row at `y₁ + s` sweep `[y₀ − r,
//! y₀ + r]` and `[y₁ + s − r, y₁ + s + r]`, which meet when `g₁ + s < 2r`: 1.9 r leaves a
//! tenth of the radius to the simulation's cells. That saves the ramp's length (`Δz / tan
//! α`, 114.5 mm for 6 mm at 3°) against a ramp back along the row and the row cut again,
//! which stays where the tighter row would cost one (a rectangle 50 mm high), with
//! [`ZigzagOptions::ramp_recut`](super::ZigzagOptions::ramp_recut), and where the stock
//! simulation finds material left ([`super::generate`] plans again so).
//!
//! Each line is clipped to the region (even-odd rule on the crossings with the loops, arcs solved exactly: `x = c_x ± √(R² − (y − c_y)²)`, kept when the angle
//! lies within the arc's sweep). Rows whose height falls within 1e-7 mm of a vertex or an arc
//! extreme are nudged by 2e-7 mm, so every crossing is transversal.
//!
//! Intervals are chained greedily: from the end of the current interval, the nearest
//! unvisited interval on a neighbouring row (nearer by more than [`LINK_TIE`] stepovers: a
//! tie goes to the next row, then the first interval along it, so that rounding never
//! decides, and a pocket and its enlargement chain alike) whose end can be reached by a
//! link of at most `3s`: a straight one that stays inside the region, or else one along the loop both ends
//! lie on (every interval ends on a loop of the boundary offset): round an island, the link
//! follows the island's offset instead of breaking the chain. (Without it, every row beside
//! an island was a cut of its own: on the L pocket of the property tests, 41 rapids and
//! 14.8 s; with it, 14 rapids and 11.4 s.) When there is none a new cut starts: with a ramp
//! along its first pass for the first cut of a level (the first pass runs along the
//! boundary, where a helix has no room), over cleared material for the later ones
//! ([`super::levels::direct_entries`]).
//! **Turns.** Two rows joined by a straight link (row, link, row back, `2ρ ≤ s` apart) turn
//! on a half circle of radius `ρ` instead (two quarter arcs, tangent to both rows): the rows
//! end `ρ` short of the nearer of their ends, where the circle's apex touches it, and a
//! controller holds `√(a·ρ)` through the turn instead of stopping at two corners. Only where
//! the row ends lie within `ρ` of each other along the rows, both rows stay longer than `2ρ`
//! and the whole circle lies inside the region (its centre at least `ρ` from every loop, up
//! to `10⁻⁷·ρ` of rounding); else the link stays. What
//! a turn leaves at the row ends lies within `2ρ ≤ s < r` of the boundary offset.
//! After the passes, the boundary offset loops are cut once: the last pass ends on a loop,
//! which is restarted there and appended without a retract.
//!
//! **Short rows.** Both ends of every interval lie on loops of the boundary offset, which
//! the clean-up pass runs along, so the tool discs at both ends are swept anyway. What a row
//! of length `L` adds to them is the lens between its sweep (a stadium) and the two discs,
//! at most `√(r² + L²/4) − r ≤ L²/(8r)` thick. A row with `L²/(8r) ≤` [`ROW_LEFT_CUSP`]
//! (0.1 µm; `L ≤ 10 µm` for a 0.25 mm tool) is dropped: cutting it alone is a sliver a few
//! µm long with nothing cleared to enter from (a row grazing a gear's spoke,
//! `pb_4_spoke_gear.dxf` with a 0.25 mm tool: a 1.1 µm cut that could only be plunged).

use super::levels::{Cut, CutEntry, LevelPlan};
use super::offset::too_large;
use super::options::{Direction, PocketOptions};
use super::segments::{Seg, segs_from_vertices};
use super::shape::crosses;
use super::shape::{PocketShape, closed_chain, restart_near, reversed};
use crate::error::InputError;
use crate::geom::{Point, Vec2};
use crate::toolpath::Tool;
use cavalier_contours::polyline::Polyline;
use std::f64::consts::TAU;

/// The most material a row left to the clean-up pass may leave, mm: the lens between the
/// tool's sweep along a row of length `L` and its discs at the row's ends, `L²/(8r)` thick
/// (see the module docs), for tools up to 12.7 mm (times the tool's
/// [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale) above). Well below the
/// verifier's resolution (the program's rounding, and the simulation's cell).
pub const ROW_LEFT_CUSP: f64 = 1e-4;

/// Largest gap between the boundary offset's extreme and the row nearest it, in tool radii
/// (the clean-up pass along the boundary cuts that band; see [`row_heights`]). Below 2 (a
/// band `2r` wide is the most two passes along its sides can cover); 1.5 is the spiral's
/// coverage gap, and what the stock simulation verifies on the pockets of the tests.
const EDGE_GAP: f64 = 1.5;

/// Two candidate links of the chaining whose lengths differ by less than this many
/// stepovers are a tie, broken by the order the candidates are looked at (the next row
/// before the previous one, then along the row): a tie decided by the rounding of the
/// coordinates would chain a pocket and its enlargement differently.
const LINK_TIE: f64 = 1e-6;

/// A point this near a loop of the boundary offset lies on it, mm, for tools up to 12.7 mm
/// (times the tool's [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale) above): the
/// row ends the chaining links along a loop, which the offsets place on it to within their
/// rounding (about `10⁻⁹` of the coordinates).
const ON_LOOP: f64 = 1e-6;

/// How far apart, in tool radii, the walls' loop and the second row may be when the first
/// row's ramp runs along it as it is cut (`CutEntry::RampAlong`): the material the ramp
/// leaves above its slope lies in the first row's swath, which lies in the union of the
/// walls' loop's and the second row's when these are less than `2r` apart; 1.9 leaves a
/// tenth of the radius for the stock simulation's cells and the rows' rounding. The first
/// row then comes `1.9·r − s` from the lowest point of the region, when that costs no row.
const RAMP_ROW_REACH: f64 = 1.9;

/// The chaining's tolerances for one plan, scaled with the stepover and the tool (see
/// [`LINK_TIE`] and [`ON_LOOP`]).
#[derive(Debug, Clone, Copy)]
struct Chaining {
    /// Links shorter than the best by less than this are no better, mm.
    tie: f64,
    /// A point this near a loop lies on it, mm.
    on_loop: f64,
}

impl Chaining {
    fn new(s: f64, tool: &Tool) -> Self {
        Chaining {
            tie: LINK_TIE * s,
            on_loop: ON_LOOP * tool.tolerance_scale(),
        }
    }
}

/// The interior rows' heights above the region's lowest point, for a region `span` mm high,
/// stepover `s` and largest edge gap `g_max` (mm): rows `s` apart, the first and the last
/// `g = (span − m·s)/2 ≤ g_max` from the region's extremes (`m` gaps between them, as few as
/// that allows). The clean-up pass along the boundary offset cuts the band between an extreme
/// and its row (every point of it within `g/2 < r` of the one or the other, along the row's
/// normal), so the rows need not come closer to it than that: fewer rows than rows `s`
/// apart from extreme to extreme, and a deeper cut along the boundary there. With
/// `g_max ≤ s` (a stepover near the diameter) the rows divide the span evenly, `h ≤ s`
/// apart, none on the extremes; a span no wider than `s` has no row (the clean-up pass alone
/// covers it), one no wider than `2·g_max` one, in its middle.
///
/// With `g_first` (the first row's largest gap, below `g_max`), the first row comes no
/// farther than that from the lowest point when that costs no row: the heights and `true`;
/// else the rows as above and `false`.
fn row_heights(span: f64, s: f64, g_max: f64, g_first: Option<f64>) -> (Vec<f64>, bool) {
    // The 1e-9 keeps an exact multiple (a 40 mm span at 4 mm) from gaining a row by rounding.
    if span <= s * (1.0 + 1e-9) {
        return (Vec::new(), false);
    }
    if g_max <= s {
        let n = (span / s - 1e-9).ceil().max(1.0) as usize;
        let h = span / n as f64;
        return ((1..n).map(|j| h * j as f64).collect(), false);
    }
    if span <= 2.0 * g_max {
        return (vec![0.5 * span], false);
    }
    let m = ((span - 2.0 * g_max) / s - 1e-9).ceil().max(1.0) as usize;
    let rest = span - m as f64 * s;
    let g = match g_first {
        Some(gf) if gf > 0.0 && ((span - gf - g_max) / s - 1e-9).ceil() <= m as f64 => {
            (gf.min(0.5 * rest), true)
        }
        _ => (0.5 * rest, false),
    };
    ((0..=m).map(|k| g.0 + s * k as f64).collect(), g.1)
}

/// The zigzag strategy's plan for one level.
pub fn plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<LevelPlan, InputError> {
    let s = opts.stepover_mm(tool);
    let d0 = tool.radius() + opts.wall_stock;
    let region = shape.offset(d0);
    if region.is_empty() {
        return Err(too_large(tool));
    }
    // Passes at `zigzag_angle` from the pocket's principal axis, so that turning the pocket
    // turns the path with it (see the module docs).
    let angle = crate::geom::region::principal_angle(&shape.outer) + opts.zigzag.angle;
    let rot = Vec2::from_angle(-angle);
    let back = Vec2::from_angle(angle);
    let to_world = |p: Point| rotate(p, back);
    let local: Vec<Vec<Seg>> = region
        .loops()
        .map(|l| {
            segs_from_vertices(&closed_chain(l))
                .into_iter()
                .map(|sg| rotate_seg(&sg, rot))
                .collect()
        })
        .collect();
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for sg in local.iter().flatten() {
        for p in extremes(sg) {
            y0 = y0.min(p.y);
            y1 = y1.max(p.y);
        }
    }
    // The first row's ramp runs along it as it is cut when the walls' loop and the second
    // row cover its swath (see the module docs).
    let g_first = (!opts.zigzag.ramp_recut).then(|| RAMP_ROW_REACH * tool.radius() - s);
    let (heights, ramp_along) = row_heights(y1 - y0, s, EDGE_GAP * tool.radius(), g_first);
    // Rows shorter than this are left to the clean-up pass (see the module docs).
    let min_row = (8.0 * tool.radius() * ROW_LEFT_CUSP * tool.tolerance_scale())
        .sqrt()
        .max(1e-9);
    let n = heights.len() + 1;
    let mut rows: Vec<Vec<(f64, f64)>> = Vec::with_capacity(n + 1);
    let mut ys = Vec::with_capacity(n + 1);
    for j in 0..=n {
        // The first and last rows run along the boundary offset, which the clean-up pass
        // runs along anyway: empty, they keep the rows' neighbours.
        if j == 0 || j == n {
            rows.push(Vec::new());
            ys.push(if j == 0 { y0 } else { y1 });
            continue;
        }
        let y = nudge(&local, (y0 + heights[j - 1]).clamp(y0 + 2e-7, y1 - 2e-7));
        let mut xs: Vec<f64> = local
            .iter()
            .flatten()
            .flat_map(|sg| crossings(sg, y))
            .collect();
        xs.sort_by(f64::total_cmp);
        rows.push(
            xs.chunks_exact(2)
                .map(|c| (c[0], c[1]))
                .filter(|c| c.1 - c.0 > min_row)
                .collect(),
        );
        ys.push(y);
    }
    // Greedy chaining.
    let tol = Chaining::new(s, tool);
    let mut used: Vec<Vec<bool>> = rows.iter().map(|r| vec![false; r.len()]).collect();
    let mut cuts: Vec<Cut> = Vec::new();
    let mut forward = opts.direction == Direction::Climb;
    while let Some((mut j, mut i)) = first_unused(&used) {
        let mut path: Vec<Seg> = Vec::new();
        let mut here: Option<Point> = None;
        let mut link: Option<Vec<Seg>> = None;
        loop {
            let (a, b) = rows[j][i];
            let (xa, xb) = if forward { (a, b) } else { (b, a) };
            let pa = to_world(Point::new(xa, ys[j]));
            let pb = to_world(Point::new(xb, ys[j]));
            if let Some(hh) = here {
                match link.take() {
                    Some(segs) => path.extend(segs),
                    None => path.push(Seg::line(hh, pa)),
                }
            }
            path.push(Seg::line(pa, pb));
            used[j][i] = true;
            here = Some(pb);
            forward = !forward;
            // Next: an unused interval on row j ± 1 reachable from pb.
            // A straight link that crosses no loop, or else a link along the loop both ends
            // lie on (round an island, or along a concave wall), at most 3s long.
            let mut next: Option<(usize, usize, f64, Option<Vec<Seg>>)> = None;
            for jj in [j + 1, j.wrapping_sub(1)] {
                let Some(row) = rows.get(jj) else { continue };
                for (ii, &(a, b)) in row.iter().enumerate() {
                    if used[jj][ii] {
                        continue;
                    }
                    let x = if forward { a } else { b };
                    let q = to_world(Point::new(x, ys[jj]));
                    let d = q.distance(pb);
                    if d > 3.0 * s || next.as_ref().is_some_and(|n| d >= n.2 - tol.tie) {
                        continue;
                    }
                    if !crosses(&region, pb, q) {
                        next = Some((jj, ii, d, None));
                    } else if let Some(segs) = boundary_link(&region, pb, q, 3.0 * s, tol) {
                        let len = super::segments::path_length(&segs);
                        if next.as_ref().is_none_or(|n| len < n.2 - tol.tie) {
                            next = Some((jj, ii, len, Some(segs)));
                        }
                    }
                }
            }
            match next {
                Some((jj, ii, _, segs)) => {
                    j = jj;
                    i = ii;
                    link = segs;
                }
                None => break,
            }
        }
        cuts.push(Cut {
            entry: CutEntry::Ramp,
            path: if opts.zigzag.straight_turns {
                path
            } else {
                round_turns(&path, s, back, &region)
            },
        });
    }
    // The first cut starting on the lowest row, along it: the ramp runs along that row.
    if ramp_along
        && let Some(first) = cuts.first_mut()
        && let Some(row) = first.path.first()
        && row.arc.is_none()
    {
        let on_first_row = (rotate(row.a, rot).y - ys[1]).abs() <= 1e-6 * s
            && (rotate(row.b, rot).y - ys[1]).abs() <= 1e-6 * s;
        if on_first_row && row.length() >= tool.diameter {
            first.entry = CutEntry::RampAlong {
                max_len: row.length(),
            };
        }
    }
    // Clean-up along the boundary offset.
    let ccw = opts.direction == Direction::Climb;
    let mut loops: Vec<&Polyline<f64>> = region.loops().collect();
    while !loops.is_empty() {
        let here = cuts.last().and_then(|c| c.path.last()).map(|sg| sg.b);
        let (pick, dist) = loops
            .iter()
            .enumerate()
            .map(|(i, l)| (i, here.map_or(0.0, |p| super::shape::loop_distance(l, p))))
            .fold(
                (0, f64::INFINITY),
                |acc, x| if x.1 < acc.1 { x } else { acc },
            );
        let lp = loops.swap_remove(pick);
        let lp = if ccw { lp.clone() } else { reversed(lp) };
        let lp = match here {
            Some(p) => restart_near(&lp, p),
            None => lp,
        };
        let path = segs_from_vertices(&closed_chain(&lp));
        match (cuts.last_mut(), here) {
            (Some(last), Some(p)) if dist <= tol.on_loop => {
                if let Some(f) = path.first() {
                    if p.distance(f.a) > 1e-12 {
                        last.path.push(Seg::line(p, f.a));
                    }
                }
                last.path.extend(path);
            }
            _ => cuts.push(Cut {
                entry: CutEntry::Ramp,
                path,
            }),
        }
    }
    Ok(LevelPlan { cuts })
}

/// `path` with each turn between two rows (moves along `along`) joined by a straight link
/// (row, link, row the other way, the rows `2ρ ≤ s` apart) made a half circle of radius `ρ`: the rows end `ρ` short of
/// the nearer of their two ends, where the half circle's apex touches it; a controller keeps
/// `√(a·ρ)` through it instead of stopping at two corners. Where the row ends are more than
/// `ρ` apart along the rows, a row is too short, or the circle would leave `region` (its
/// centre nearer than `ρ` to a loop), the link stays. What the turns leave at the row
/// ends lies within `2ρ ≤ s` of the boundary offset, which the clean-up pass runs along.
fn round_turns(path: &[Seg], s: f64, along: Vec2, region: &super::shape::OffsetRegion) -> Vec<Seg> {
    // A row runs along the rows' direction (a link along a loop may too, but never at a
    // row's height: rows are nudged off the loops' vertices); both moves of a turn must.
    let row = |g: &Seg| {
        g.arc.is_none()
            && (g.b - g.a)
                .normalize()
                .is_some_and(|d| d.cross(along).abs() < 1e-9)
    };
    let mut out: Vec<Seg> = Vec::with_capacity(path.len() + path.len() / 2);
    // The move at `i`, shortened when it is a row a turn has just joined.
    let mut cur: Option<Seg> = None;
    let mut i = 0;
    while i < path.len() {
        let a = cur.take().unwrap_or(path[i]);
        let turn = match (path.get(i + 1), path.get(i + 2)) {
            (Some(k), Some(b)) if row(&a) && k.arc.is_none() && row(b) => {
                half_turn(&a, k, b, s, region)
            }
            _ => None,
        };
        match turn {
            Some([a2, q1, q2, b2]) => {
                out.extend([a2, q1, q2]);
                cur = Some(b2);
                i += 2;
            }
            None => {
                out.push(a);
                i += 1;
            }
        }
    }
    out
}

/// Rows `a` and `b` joined by the link `k` as a half circle (see [`round_turns`]): the
/// shortened `a`, two quarter arcs and the shortened `b`.
fn half_turn(
    a: &Seg,
    k: &Seg,
    b: &Seg,
    s: f64,
    region: &super::shape::OffsetRegion,
) -> Option<[Seg; 4]> {
    let u = (a.b - a.a).normalize()?;
    let ub = (b.b - b.a).normalize()?;
    if u.dot(ub) > -1.0 + 1e-9 || k.a.distance(a.b) > 1e-9 || k.b.distance(b.a) > 1e-9 {
        return None;
    }
    let gap = b.a - a.b;
    let across = gap.cross(u);
    let rho = 0.5 * across.abs();
    if rho < 1e-6 * s || 2.0 * rho > s * (1.0 + 1e-9) {
        return None;
    }
    // Along the rows, from `a`'s end: `b` starts at `delta`; the apex at the nearer end.
    let delta = gap.dot(u);
    if delta.abs() > rho {
        return None;
    }
    let back = delta.min(0.0) - rho;
    let (la, lb) = (a.length() + back, b.length() - (delta - back));
    if la <= 2.0 * rho || lb <= 2.0 * rho {
        return None;
    }
    // `w` points from `a` towards `b`; the turn is to the left when `w` is `u` turned left.
    let w = if across < 0.0 { u.perp() } else { -u.perp() };
    let p1 = a.b + u * back;
    let c = p1 + w * rho;
    let p2 = p1 + w * (2.0 * rho);
    // The whole circle inside the region: its centre at least `ρ` from every loop (less the
    // rounding of the distances), and on the region's side of them (between the rows).
    let slack = 1e-7 * rho + 1e-9 * (c.x.abs() + c.y.abs());
    let room = region
        .loops()
        .map(|l| super::shape::loop_distance(l, c))
        .fold(f64::INFINITY, f64::min);
    if room < rho - slack || crosses(region, p1, p2) {
        return None;
    }
    let left = w.dot(u.perp()) > 0.0;
    let bulge = if left { 1.0 } else { -1.0 } * (std::f64::consts::PI / 8.0).tan();
    let apex = c + u * rho;
    Some([
        Seg::line(a.a, p1),
        Seg::from_bulge(p1, apex, bulge),
        Seg::from_bulge(apex, p2, bulge),
        Seg::line(p2, b.b),
    ])
}

/// The shorter way from `p` to `q` along the loop of `region` both lie on (within
/// `tol.on_loop`), if it is at most `max_len` long (two ways within `tol.tie` of each other:
/// the loop's own direction): a link that cannot gouge (it runs on the boundary offset) and
/// cuts only the cusps the passes left against that loop.
fn boundary_link(
    region: &super::shape::OffsetRegion,
    p: Point,
    q: Point,
    max_len: f64,
    tol: Chaining,
) -> Option<Vec<Seg>> {
    let on = tol.on_loop;
    let lp = region.loops().find(|l| {
        super::shape::loop_distance(l, p) < on && super::shape::loop_distance(l, q) < on
    })?;
    let mut best: Option<Vec<Seg>> = None;
    for dir in [lp.clone(), reversed(lp)] {
        let path = segs_from_vertices(&closed_chain(&restart_near(&dir, p)));
        let mut out = Vec::new();
        let mut total = 0.0;
        for sg in &path {
            if let Some(t) = position_on(sg, q, on) {
                if t > 1e-3 * on {
                    out.push(sg.head(t));
                }
                total += t;
                if total <= max_len
                    && best
                        .as_ref()
                        .is_none_or(|b| total < super::segments::path_length(b) - tol.tie)
                {
                    best = Some(out);
                }
                break;
            }
            total += sg.length();
            if total > max_len {
                break;
            }
            out.push(*sg);
        }
    }
    best
}

/// Arc length from the start of `sg` to `q`, when `q` lies on it (within `on` mm).
fn position_on(sg: &Seg, q: Point, on: f64) -> Option<f64> {
    match sg.arc {
        None => {
            let d = sg.b - sg.a;
            let len = d.length();
            if len <= 0.0 {
                return None;
            }
            let t = (q - sg.a).dot(d) / len;
            let off = (q - sg.a).cross(d).abs() / len;
            (off < on && t >= -1e-3 * on && t <= len + 1e-3 * on).then_some(t.clamp(0.0, len))
        }
        Some(arc) => {
            if (q.distance(arc.center) - arc.radius).abs() > on {
                return None;
            }
            let a0 = (sg.a - arc.center).angle();
            let aq = (q - arc.center).angle();
            let rel = if arc.ccw { aq - a0 } else { a0 - aq };
            let rel = rel.rem_euclid(TAU);
            let rel = if rel > TAU - 1e-9 { 0.0 } else { rel };
            (rel <= arc.sweep + 1e-9).then_some(rel.min(arc.sweep) * arc.radius)
        }
    }
}

fn first_unused(used: &[Vec<bool>]) -> Option<(usize, usize)> {
    used.iter()
        .enumerate()
        .find_map(|(j, r)| r.iter().position(|u| !u).map(|i| (j, i)))
}

fn rotate(p: Point, by: Vec2) -> Point {
    Point::new(by.x * p.x - by.y * p.y, by.y * p.x + by.x * p.y)
}

fn rotate_seg(sg: &Seg, by: Vec2) -> Seg {
    Seg {
        a: rotate(sg.a, by),
        b: rotate(sg.b, by),
        arc: sg.arc.map(|arc| super::segments::Arc {
            center: rotate(arc.center, by),
            ..arc
        }),
    }
}

/// The end points and, for arcs, the top and bottom of the circle when on the arc.
fn extremes(sg: &Seg) -> Vec<Point> {
    let mut v = vec![sg.a, sg.b];
    if let Some(arc) = sg.arc {
        for dir in [Vec2::new(0.0, 1.0), Vec2::new(0.0, -1.0)] {
            if on_arc(sg, dir.angle()) {
                v.push(arc.center + dir * arc.radius);
            }
        }
    }
    v
}

/// True when the angle `t` (about the arc's centre) lies within the arc's sweep.
fn on_arc(sg: &Seg, t: f64) -> bool {
    let Some(arc) = sg.arc else { return false };
    let a0 = (sg.a - arc.center).angle();
    let rel = if arc.ccw { t - a0 } else { a0 - t };
    rel.rem_euclid(TAU) <= arc.sweep
}

/// Moves `y` off vertices and arc extremes so that every crossing is transversal.
fn nudge(loops: &[Vec<Seg>], mut y: f64) -> f64 {
    for _ in 0..8 {
        let close = loops
            .iter()
            .flatten()
            .flat_map(extremes)
            .any(|p| (p.y - y).abs() < 1e-7);
        if !close {
            break;
        }
        y += 2e-7;
    }
    y
}

/// x of the crossings of the horizontal line at `y` with `sg`, half-open at the end point.
fn crossings(sg: &Seg, y: f64) -> Vec<f64> {
    match sg.arc {
        None => {
            let (a, b) = (sg.a, sg.b);
            if (a.y <= y && y < b.y) || (b.y <= y && y < a.y) {
                let t = (y - a.y) / (b.y - a.y);
                vec![a.x + t * (b.x - a.x)]
            } else {
                Vec::new()
            }
        }
        Some(arc) => {
            let dy = y - arc.center.y;
            let q = arc.radius * arc.radius - dy * dy;
            if q <= 0.0 {
                return Vec::new();
            }
            let dx = q.sqrt();
            [arc.center.x - dx, arc.center.x + dx]
                .into_iter()
                .filter(|&x| {
                    let p = Point::new(x, y);
                    p.distance(sg.b) > 1e-12 && on_arc(sg, (p - arc.center).angle())
                })
                .collect()
        }
    }
}
