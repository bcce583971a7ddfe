//! Contour-parallel offsets, cut from the inside out.
//!
//! Loops at distances `d_k = r + stock + k·s` from the pocket boundary (cavalier_contours'
//! parallel offset, exact arcs), `k = 0..K` until the offset vanishes. Neighbouring loops are
//! at most `s` apart (the offset of an offset by `s` is the offset by the sum, for inward
//! offsets of a region), so the radial depth of cut is `s` on straight walls; at a convex
//! corner of half-angle β the corner points of two loops are `s / sin β` apart, which is where
//! the engagement peaks (the stock simulation measures it).
//!
//! **Spacing.** A point at distance `δ` from the walls with `d_k ≤ δ < d_{k+1}` has a point of
//! loop `k` at distance `δ − d_k` (on its shortest segment to the walls: the point there at
//! distance `d_k` from the walls lies on the level set `d_k`, the loop), so it is cut when
//! `δ − d_k < r`. Where loop `k + 1` exists beyond it that holds for any `s ≤ 2r`, but at a
//! ridge of the distance field (the medial axis, where the loops of a region end) nothing
//! beyond loop `k` covers it: with `s > r` a ridge of uncut material would stay. The loops
//! are therefore spaced `h = min(s, 0.95·r)` (the 5% keep the ridge `0.05·r` inside the
//! tool's reach, above the verifier's raster cell); only stepovers above 95% of the radius
//! get more loops than asked.
//!
//! **Sharp corners kept.** Rounding the interior loops' convex corners (a morphological
//! opening by `ρ = (0.95·r − h)/(√2 − 1)`, the most the coverage margin allows at right
//! angles) makes the cycle time longer although the path is shorter: the planner already blends
//! the corners within the path tolerance, and the rounded loops move the engagement peak
//! onto longer moves, whose feed the modulation then lowers. So the loops stay exact offsets.
//!
//! **Islands.** The offsets are of the region (the outline inward, the islands outward at
//! once: cavalier_contours' shape offset), so loops around islands merge with the outer
//! loops where they meet, and the distance argument above holds with the islands' walls
//! among the walls.
//!
//! Order: the loops form a tree (a loop of level `k + 1` is nested in one of level `k`, with
//! the island loops of its region); it is cut in post-order, the nearest subtree first, so
//! each branch is cleared from its innermost loop outward before the tool moves on (one
//! retract per branch rather than one per level and branch), every loop restarted at its
//! point nearest to where the tool is. Two loops are linked by a straight feed move when
//! the link is short (at most `2s`) and crosses no loop of the boundary offset (so it cannot
//! gouge); otherwise a new cut starts with a helix (an innermost loop with room for it) or a
//! ramp along the loop.

use super::levels::{Cut, CutEntry, LevelPlan};
use super::options::{Direction, Entry, PocketOptions};
use super::segments::segs_from_vertices;
use super::shape::{
    OffsetRegion, PocketShape, closed_chain, crosses, inscribed_centre, restart_near, reversed, v2,
};
use crate::error::InputError;
use crate::geom::Point;
use crate::toolpath::Tool;
use cavalier_contours::core::math::Vector2;
use cavalier_contours::polyline::{PlineSource, Polyline};

/// Most offset loops a pocket may need (a guard against degenerate input).
const MAX_LOOPS: usize = 100_000;

/// The offset strategy's plan for one level.
pub fn plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<LevelPlan, InputError> {
    let r = tool.radius();
    let s = opts.stepover_mm(tool);
    // Loop spacing: the stepover, at most RIDGE_SPACING·r (see the module docs).
    let h = s.min(RIDGE_SPACING * r);
    let d0 = r + opts.wall_stock;
    let boundary = shape.offset(d0);
    if boundary.is_empty() {
        return Err(too_large(tool));
    }
    let mut levels: Vec<OffsetRegion> = vec![boundary.clone()];
    let mut count = 0;
    loop {
        let next = shape.offset(d0 + h * levels.len() as f64);
        if next.is_empty() {
            break;
        }
        count += next.outers.len() + next.islands.len();
        if count > MAX_LOOPS {
            return Err(InputError::new("stepover", s)
                .at("--stepover")
                .expected("a stepover giving fewer than 100000 offset loops"));
        }
        levels.push(next);
    }
    // The nesting tree: a node is an outer loop of a level with the island loops inside it;
    // its parent is the node of the level below that contains it.
    // Ownership by the majority of a loop's points (vertices and segment midpoints): a loop
    // may touch the one that holds it (an island's loop meeting its outer loop at a vertex),
    // where one point's winding number says nothing.
    let mut nodes: Vec<Node> = Vec::new();
    for (k, level) in levels.iter().enumerate() {
        let island_owner: Vec<Option<usize>> = level
            .islands
            .iter()
            .map(|i| majority_owner(i, level.outers.iter().map(|o| (o, &[][..]))))
            .collect();
        // The nodes of the level below, with their islands.
        let below: Vec<(usize, Vec<Polyline<f64>>)> = nodes
            .iter()
            .enumerate()
            .filter(|(_, n)| n.level + 1 == k)
            .map(|(ni, n)| {
                let isl = n
                    .islands
                    .iter()
                    .map(|&ii| levels[n.level].islands[ii].clone());
                (ni, isl.collect())
            })
            .collect();
        for (oi, outer) in level.outers.iter().enumerate() {
            let islands: Vec<usize> = (0..level.islands.len())
                .filter(|&ii| island_owner[ii] == Some(oi))
                .collect();
            let parent = if k == 0 {
                None
            } else {
                majority_owner(
                    outer,
                    below.iter().map(|(ni, isl)| {
                        (&levels[nodes[*ni].level].outers[nodes[*ni].outer], &isl[..])
                    }),
                )
                .map(|j| below[j].0)
            };
            nodes.push(Node {
                level: k,
                outer: oi,
                islands,
                parent,
                children: Vec::new(),
            });
        }
    }
    for i in 0..nodes.len() {
        if let Some(p) = nodes[i].parent {
            nodes[p].children.push(i);
        }
    }
    let roots: Vec<usize> = (0..nodes.len())
        .filter(|&i| nodes[i].parent.is_none())
        .collect();
    let mut em = Emitter {
        boundary: &boundary,
        opts,
        r,
        s,
        ccw: opts.direction == Direction::Climb,
        cuts: Vec::new(),
        here: None,
    };
    let mut stack_roots = roots;
    while !stack_roots.is_empty() {
        let pick = em.nearest_node(&levels, &nodes, &stack_roots);
        let root = stack_roots.swap_remove(pick);
        visit(root, &levels, &nodes, &mut em);
    }
    Ok(LevelPlan { cuts: em.cuts })
}

/// The index of the region (an outer loop less its islands) of `regions` holding most of
/// the points of `lp` (its vertices and segment midpoints), if any holds one; ties go to the
/// first.
fn majority_owner<'a>(
    lp: &Polyline<f64>,
    regions: impl Iterator<Item = (&'a Polyline<f64>, &'a [Polyline<f64>])>,
) -> Option<usize> {
    let n = lp.vertex_count();
    let pts: Vec<Vector2<f64>> = (0..n)
        .flat_map(|i| {
            let (a, b) = (lp.at(i), lp.at((i + 1) % n));
            [a.pos(), cavalier_contours::polyline::seg_midpoint(a, b)]
        })
        .collect();
    regions
        .map(|(outer, islands)| {
            pts.iter()
                .filter(|&&p| {
                    outer.winding_number(p) != 0 && islands.iter().all(|i| i.winding_number(p) == 0)
                })
                .count()
        })
        .enumerate()
        .filter(|&(_, c)| c > 0)
        .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
        .map(|(i, _)| i)
}

/// An outer loop of one offset level and the island loops inside it.
struct Node {
    level: usize,
    outer: usize,
    islands: Vec<usize>,
    parent: Option<usize>,
    children: Vec<usize>,
}

/// Post-order, with an explicit stack (the tree may be thousands of levels deep): a node's
/// subtrees (nearest first), then its own loops (nearest first).
fn visit(root: usize, levels: &[OffsetRegion], nodes: &[Node], em: &mut Emitter<'_>) {
    let kids_of = |n: usize| nodes.get(n).map_or_else(Vec::new, |x| x.children.clone());
    let mut stack: Vec<(usize, Vec<usize>)> = vec![(root, kids_of(root))];
    while let Some((n, kids)) = stack.last_mut() {
        if kids.is_empty() {
            let n = *n;
            stack.pop();
            if let Some(node) = nodes.get(n) {
                emit_node(node, levels, em);
            }
        } else {
            let pick = em.nearest_node(levels, nodes, kids);
            let kid = kids.swap_remove(pick);
            stack.push((kid, kids_of(kid)));
        }
    }
}

/// The loops of one node, nearest first.
fn emit_node(node: &Node, levels: &[OffsetRegion], em: &mut Emitter<'_>) {
    let level = &levels[node.level];
    let islands: Vec<Polyline<f64>> = node
        .islands
        .iter()
        .map(|&i| level.islands[i].clone())
        .collect();
    let mut todo: Vec<(&Polyline<f64>, bool)> = std::iter::once((&level.outers[node.outer], false))
        .chain(node.islands.iter().map(|&i| (&level.islands[i], true)))
        .collect();
    while !todo.is_empty() {
        let loops: Vec<&Polyline<f64>> = todo.iter().map(|t| t.0).collect();
        let pick = match em.here {
            None => 0,
            Some(p) => nearest_loop(&loops, p),
        };
        let (lp, island) = todo.swap_remove(pick);
        em.emit(lp, island, node.children.is_empty(), &islands);
    }
}

/// Turns loops into cuts, linking where safe.
struct Emitter<'a> {
    boundary: &'a OffsetRegion,
    opts: &'a PocketOptions,
    r: f64,
    s: f64,
    ccw: bool,
    cuts: Vec<Cut>,
    here: Option<Point>,
}

impl Emitter<'_> {
    /// The node of `of` nearest to the tool; before the first cut, the one of largest area
    /// (a choice that does not depend on how the pocket is turned or which way its outline
    /// runs, unlike the order of the offset's loops).
    fn nearest_node(&self, levels: &[OffsetRegion], nodes: &[Node], of: &[usize]) -> usize {
        let loops: Vec<&Polyline<f64>> = of
            .iter()
            .filter_map(|&i| nodes.get(i))
            .map(|n| &levels[n.level].outers[n.outer])
            .collect();
        match self.here {
            Some(p) => nearest_loop(&loops, p),
            None => loops
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.area().abs().total_cmp(&b.1.area().abs()))
                .map_or(0, |(i, _)| i),
        }
    }

    /// Appends loop `lp` (an island loop when `island`; `innermost` when nothing is nested
    /// in it): linked to the previous cut by a straight feed move when that is short (at most
    /// `2s`) and crosses no boundary loop, else a new cut with its own entry.
    fn emit(
        &mut self,
        lp: &Polyline<f64>,
        island: bool,
        innermost: bool,
        level_islands: &[Polyline<f64>],
    ) {
        let lp = if self.ccw { lp.clone() } else { reversed(lp) };
        let start_near = self.here.unwrap_or_else(|| lp.at(0).pos().into_point());
        let lp = restart_near(&lp, start_near);
        let path = segs_from_vertices(&closed_chain(&lp));
        let Some(first) = path.first() else { return };
        let linkable = self.here.is_some_and(|h| {
            h.distance(first.a) <= 2.0 * self.s + 1e-9 && !crosses(self.boundary, h, first.a)
        });
        if let (true, Some(last), Some(h)) = (linkable, self.cuts.last_mut(), self.here) {
            last.path.push(super::segments::Seg::line(h, first.a));
            last.path.extend(path.iter().copied());
            self.here = path.last().map(|s| s.b);
            return;
        }
        let entry = if island {
            CutEntry::Ramp
        } else {
            entry_for(
                &lp,
                innermost,
                level_islands,
                self.boundary,
                self.opts,
                self.r,
            )
        };
        let path = match entry {
            CutEntry::Helix { center, .. } => {
                segs_from_vertices(&closed_chain(&restart_near(&lp, helix_exit(&lp, center))))
            }
            _ => path,
        };
        self.here = path.last().map(|s| s.b);
        self.cuts.push(Cut { entry, path });
    }
}

trait IntoPoint {
    fn into_point(self) -> Point;
}
impl IntoPoint for Vector2<f64> {
    fn into_point(self) -> Point {
        Point::new(self.x, self.y)
    }
}

fn nearest_loop(loops: &[&Polyline<f64>], p: Point) -> usize {
    let mut best = (0, f64::INFINITY);
    for (i, l) in loops.iter().enumerate() {
        let d = l
            .closest_point(v2(p), 1e-12)
            .map_or(f64::INFINITY, |c| c.distance);
        if d < best.1 {
            best = (i, d);
        }
    }
    best.0
}

/// A helix in an innermost counter-clockwise loop when there is room for it, a ramp along the
/// loop otherwise. The helix centre `c` is the loop's inscribed centre (away from the
/// islands of its level); the room is measured to the *boundary offset* (the region the tool
/// centre may visit), not to the loop: the loop is itself inside that region, `d_k − d_0`
/// from its walls. The helix radius is `min(ρ, 0.9·r, 0.99·room)` (a helix wider than the
/// tool leaves a pillar at its centre), and at least [`min_helix_radius`]; the lead from the
/// helix to the loop must cross no loop of the boundary offset. Island loops never get a
/// helix (their inside is the island): the caller does not ask for one.
pub(super) fn entry_for(
    lp: &Polyline<f64>,
    innermost: bool,
    level_islands: &[Polyline<f64>],
    boundary: &OffsetRegion,
    opts: &PocketOptions,
    r: f64,
) -> CutEntry {
    let Entry::Helix { radius, .. } = opts.entry else {
        return CutEntry::Ramp;
    };
    // The loop as a counter-clockwise outer loop (climb cuts it so; conventional reversed it).
    let outer = if lp.area() > 0.0 {
        lp.clone()
    } else {
        reversed(lp)
    };
    if !innermost || outer.area() <= 0.0 {
        return CutEntry::Ramp;
    }
    let room_at = |c: Point| {
        boundary
            .loops()
            .map(|l| super::shape::loop_distance(l, c))
            .fold(f64::INFINITY, f64::min)
    };
    let want = radius.min(0.9 * r);
    // The loop's centroid when it has the room (a property of the loop alone, so the entry
    // turns with the pocket; the grid search below depends on the axes where the inscribed
    // circle is not unique, e.g. along a slot), else the inscribed centre.
    let centroid = loop_centroid(&outer).filter(|&c| {
        outer.winding_number(v2(c)) != 0
            && level_islands.iter().all(|i| i.winding_number(v2(c)) == 0)
            && room_at(c) >= want / 0.99
    });
    let c = centroid.unwrap_or_else(|| inscribed_centre(&outer, level_islands, 24).0);
    let rho = want.min(0.99 * room_at(c));
    if rho < min_helix_radius(r) {
        return CutEntry::Ramp;
    }
    let start = helix_exit(&outer, c);
    let approach = super::levels::helix_approach(c, rho, start);
    if crosses(boundary, approach, start) {
        return CutEntry::Ramp;
    }
    CutEntry::Helix {
        center: c,
        radius: rho,
        flat_turn: false,
    }
}

/// Where a loop entered by a helix about `c` starts: its point nearest to `c` (a property of
/// the loop and the centre, so the path turns with the pocket; the helix ends on the ray from
/// `c` to it, [`super::levels::helix_approach`]).
fn helix_exit(lp: &Polyline<f64>, c: Point) -> Point {
    lp.closest_point(v2(c), 1e-12)
        .map_or(c, |cp| super::shape::pt(cp.seg_point))
}

/// The area centroid of a closed loop, from 1024 points equally spaced in arc length (the
/// shoelace centroid of that polygon, within about `(L/1024)²` of the exact one).
fn loop_centroid(pl: &Polyline<f64>) -> Option<Point> {
    let pts = crate::geom::region::sample_loop(pl, 1024);
    let n = pts.len();
    let (mut a2, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let p = pts[i];
        let q = pts[(i + 1) % n];
        let w = p.x * q.y - q.x * p.y;
        a2 += w;
        cx += (p.x + q.x) * w;
        cy += (p.y + q.y) * w;
    }
    (a2.abs() > 1e-12).then(|| Point::new(cx / (3.0 * a2), cy / (3.0 * a2)))
}

/// The smallest helix radius worth a helix, mm (below, the ramp along the loop is used), for
/// tools of radius 3 mm to 6.35 mm; a thirtieth of the tool radius `r` for smaller tools, and
/// times the [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale) for tools over
/// 12.7 mm (`r/63.5`), so that a part and its tool drawn at another scale get the same
/// entries.
pub const MIN_HELIX_RADIUS: f64 = 0.1;

/// [`MIN_HELIX_RADIUS`] for a tool of radius `r`: `min(0.1 mm·λ, r/30)`, `λ` the tool's
/// tolerance scale.
pub(super) fn min_helix_radius(r: f64) -> f64 {
    (MIN_HELIX_RADIUS * crate::toolpath::tolerance_scale(2.0 * r)).min(r / 30.0)
}

/// Largest loop spacing as a fraction of the tool radius (see the module docs).
pub const RIDGE_SPACING: f64 = 0.95;

/// The error for a tool that does not fit.
pub fn too_large(tool: &Tool) -> InputError {
    InputError::new("tool diameter", tool.diameter)
        .at("--tool-diameter")
        .expected("a tool (plus wall stock) that fits inside the pocket")
}
