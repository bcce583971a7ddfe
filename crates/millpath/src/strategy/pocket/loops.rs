//! The contour-parallel offset loops of a pocket and the order in which they can be cut.
//!
//! Level `k` is the region at distance `d_k = d₀ + k·h` from the walls (`d₀ = r + stock`,
//! cavalier_contours' shape offset: outer loops counter-clockwise, island loops clockwise,
//! exact arcs), `k = 0, 1, …` until nothing is left. Every point `x` of a loop of level
//! `k + 1` is at distance exactly `h` from level `k`'s loops: the nearest wall point is
//! `d_{k+1}` away, and the point of the segment to it at distance `d_k` from the walls lies
//! on a loop of level `k`.
//!
//! **Adjacency.** Loop `X` of level `k + 1` *feeds* loop `Y` of level `k` ([`LoopNode::next`],
//! [`LoopNode::prev`]) when some point of `X` has its nearest level-`k` point on `Y`: cutting
//! outwards, `Y` is cut after `X` (the material between them is within `h` of `X`). Outer
//! loops feed the outer loop that contains them, island loops the island loop inside them;
//! where loops merge or split (a neck, an island met by the shrinking outer loop) a loop has
//! several neighbours on one side. Both directions are sampled (every `h/2` along each loop,
//! at least 32 samples), and a neighbour is taken within `h + ADJACENT_SLACK·h`.
//!
//! **Chains.** `X → Y` is a *link* when `X` feeds only `Y` and only `X` feeds `Y`: then the
//! two are one band of the pocket with nothing else attached, and a spiral may run from one
//! to the other. Maximal sequences of links are the chains ([`OffsetLoops::chains`]), listed
//! innermost loop first. A chain can be cut once every loop feeding its first loop is cut.

use super::shape::{IndexedLoop, PocketShape, pt};
use crate::error::InputError;
use crate::geom::Point;
use cavalier_contours::polyline::{PlineSource, Polyline};

/// Most loops a pocket may need (a guard against degenerate input).
const MAX_LOOPS: usize = 100_000;
/// A neighbour is taken within `h·(1 + ADJACENT_SLACK)` (offsets are exact to far below this).
const ADJACENT_SLACK: f64 = 0.05;
/// Fewest samples along a loop for the adjacency test.
const MIN_SAMPLES: usize = 32;

/// One offset loop.
#[derive(Debug, Clone)]
pub struct LoopNode {
    /// Offset level (0: the boundary offset, the last pass along the walls).
    pub level: usize,
    /// The loop: counter-clockwise for an outer loop, clockwise around an island.
    pub pline: Polyline<f64>,
    /// True for a loop around an island (clockwise).
    pub island: bool,
    /// The loops of level `level − 1` this loop feeds (cut after it).
    pub next: Vec<usize>,
    /// The loops of level `level + 1` that feed this one (cut before it).
    pub prev: Vec<usize>,
}

/// All offset loops of a pocket, level by level.
#[derive(Debug, Clone)]
pub struct OffsetLoops {
    /// The loops, level 0 first.
    pub nodes: Vec<LoopNode>,
    /// Spacing between levels, mm.
    pub step: f64,
    /// Distance of level 0 from the walls, mm.
    pub d0: f64,
}

impl OffsetLoops {
    /// The loops at `d0 + k·step` from the walls of `shape`. Errors when there are more than
    /// 100 000 (a stepover far too small for the pocket); an empty result (the tool does not
    /// fit) is for the caller to report.
    pub fn build(shape: &PocketShape, d0: f64, step: f64) -> Result<Self, InputError> {
        let mut nodes: Vec<LoopNode> = Vec::new();
        let mut level = 0;
        loop {
            let region = shape.offset(d0 + step * level as f64);
            if region.is_empty() {
                break;
            }
            let loops = region
                .outers
                .into_iter()
                .map(|p| (p, false))
                .chain(region.islands.into_iter().map(|p| (p, true)))
                .filter(|(p, _)| p.vertex_count() > 1 && p.area().abs() > 0.0);
            for (pline, island) in loops {
                nodes.push(LoopNode {
                    level,
                    pline,
                    island,
                    next: Vec::new(),
                    prev: Vec::new(),
                });
            }
            if nodes.len() > MAX_LOOPS {
                return Err(InputError::new("stepover", step)
                    .at("--stepover")
                    .expected("a stepover giving fewer than 100000 offset loops"));
            }
            level += 1;
        }
        let mut loops = OffsetLoops { nodes, step, d0 };
        loops.link();
        Ok(loops)
    }

    /// The indices of the loops of `level`.
    pub fn level(&self, level: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.nodes.len()).filter(move |&i| self.nodes[i].level == level)
    }

    /// Number of levels.
    pub fn levels(&self) -> usize {
        self.nodes.last().map_or(0, |n| n.level + 1)
    }

    /// Fills `next` and `prev` from sampled nearest neighbours, both ways.
    fn link(&mut self) {
        let h = self.step;
        let reach = h * (1.0 + ADJACENT_SLACK);
        let mut pairs: Vec<(usize, usize)> = Vec::new();
        for k in 1..self.levels() {
            let inner: Vec<usize> = self.level(k).collect();
            let outer: Vec<usize> = self.level(k - 1).collect();
            let outer_idx: Vec<IndexedLoop<'_>> = outer
                .iter()
                .map(|&i| IndexedLoop::new(&self.nodes[i].pline))
                .collect();
            let inner_idx: Vec<IndexedLoop<'_>> = inner
                .iter()
                .map(|&i| IndexedLoop::new(&self.nodes[i].pline))
                .collect();
            for &x in &inner {
                for p in samples(&self.nodes[x].pline, 0.5 * h) {
                    if let Some(b) = nearest(&outer_idx, p, reach) {
                        pairs.push((x, outer[b]));
                    }
                }
            }
            for &y in &outer {
                for p in samples(&self.nodes[y].pline, 0.5 * h) {
                    if let Some(a) = nearest(&inner_idx, p, reach) {
                        pairs.push((inner[a], y));
                    }
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        for (x, y) in pairs {
            self.nodes[x].next.push(y);
            self.nodes[y].prev.push(x);
        }
    }

    /// True when `x → y` is a link of a chain (see the module docs).
    fn is_link(&self, x: usize, y: usize) -> bool {
        self.nodes[x].next == [y] && self.nodes[y].prev == [x]
    }

    /// The chains, each innermost loop first (see the module docs), in no particular order.
    pub fn chains(&self) -> Vec<Vec<usize>> {
        let mut out = Vec::new();
        for start in 0..self.nodes.len() {
            // A chain starts where no link comes in.
            let has_link_in = self.nodes[start]
                .prev
                .iter()
                .any(|&p| self.is_link(p, start));
            if has_link_in {
                continue;
            }
            let mut chain = vec![start];
            let mut at = start;
            while let [y] = self.nodes[at].next.as_slice() {
                if !self.is_link(at, *y) {
                    break;
                }
                at = *y;
                chain.push(at);
            }
            out.push(chain);
        }
        out
    }
}

/// The index of the loop nearest to `p` if it is within `reach`.
fn nearest(loops: &[IndexedLoop<'_>], p: Point, reach: f64) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (i, l) in loops.iter().enumerate() {
        let d = l.distance(p);
        if d <= reach && best.is_none_or(|b| d < b.1) {
            best = Some((i, d));
        }
    }
    best.map(|b| b.0)
}

/// Points along a closed loop, at most `ds` apart and at least `MIN_SAMPLES` (32), plus its
/// vertices.
pub fn samples(pl: &Polyline<f64>, ds: f64) -> Vec<Point> {
    let len = pl.path_length();
    let n = ((len / ds.max(1e-9)).ceil() as usize).max(MIN_SAMPLES);
    let mut out = crate::geom::region::sample_loop(pl, n);
    out.extend((0..pl.vertex_count()).map(|i| pt(pl.at(i).pos())));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strategy::pocket::builtin;

    #[test]
    fn a_rectangle_is_one_chain_from_the_ridge_to_the_walls() {
        let shape = builtin::aerospace_pocket();
        let loops = OffsetLoops::build(&shape, 6.35, 5.08).expect("loops");
        // 150 × 100 less 2·6.35: inscribed radius 43.65, so levels 0..=8.
        assert_eq!(loops.levels(), 9);
        let chains = loops.chains();
        assert_eq!(chains.len(), 1, "{chains:?}");
        let c = &chains[0];
        assert_eq!(c.len(), 9);
        assert_eq!(loops.nodes[c[0]].level, 8);
        assert_eq!(loops.nodes[*c.last().expect("loops")].level, 0);
    }

    #[test]
    fn a_dumbbell_splits_into_three_chains() {
        // Two 60 × 60 squares joined by a 20 mm wide neck.
        let pts = [
            (0.0, 0.0),
            (60.0, 0.0),
            (60.0, 20.0),
            (100.0, 20.0),
            (100.0, 0.0),
            (160.0, 0.0),
            (160.0, 60.0),
            (100.0, 60.0),
            (100.0, 40.0),
            (60.0, 40.0),
            (60.0, 60.0),
            (0.0, 60.0),
        ];
        let v: Vec<(Point, f64)> = pts.iter().map(|&(x, y)| (Point::new(x, y), 0.0)).collect();
        let outline = crate::geom::Outline::new(&v, "dumbbell").expect("outline");
        let shape = PocketShape::simple(outline);
        let loops = OffsetLoops::build(&shape, 5.0, 4.0).expect("loops");
        let chains = loops.chains();
        // The neck (tool-centre half-width 5) closes after level 1: two square chains and
        // the chain of the merged loops.
        assert_eq!(chains.len(), 3, "{chains:?}");
        let merged: Vec<&Vec<usize>> = chains
            .iter()
            .filter(|c| loops.nodes[*c.last().expect("loop")].level == 0)
            .collect();
        assert_eq!(merged.len(), 1);
        let first = merged[0][0];
        assert_eq!(loops.nodes[first].prev.len(), 2);
    }
}
