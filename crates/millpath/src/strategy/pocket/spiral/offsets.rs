//! The spiral on the contour-parallel loops: as long as `offset`, none of its stops.
//!
//! 1. **Loops**: the offsets of the pocket at `d₀ + k·h` ([`OffsetLoops`]: `h = min(s,
//!    0.95·r)`, the `offset` strategy's spacing, so the two cover the pocket with the same
//!    loops), and which loop is cut after which.
//! 2. **Rounding**: every interior loop opened by the largest radius the stepover bound
//!    allows ([`super::rounding`]): the corners a controller would stop at become arcs whose
//!    radii grow towards the middle.
//! 3. **Chains**: where one loop follows another with nothing else attached, they form one
//!    band of the pocket; each chain becomes one continuous spiral ([`super::lanes`]): each
//!    loop once round, then a curvature-continuous lane change onto the next loop out, the
//!    changes stacked so that the radial depth stays the step's. A convex or star-shaped
//!    pocket, an L, a T, a U are one chain (their innermost loop, a thin loop round the
//!    medial axis, is cut like `offset`'s, as a slot); a neck that pinches the loops off (a
//!    dumbbell) or islands make several, cut innermost first like `offset`'s loop tree,
//!    linked by a straight feed move where that is short and stays in the tool-centre region,
//!    else entered again.
//!
//! The first chain is entered by a helix at its innermost loop's centroid where there is
//! room (as `offset` does), else by a ramp; the entry moves then choose direct entries over
//! cleared material ([`super::super::levels::direct_entries`]).
//!
//! **Scale.** Sample spacings, chord lengths and sagittas, the last loop's margin and the arc
//! tolerance are millimetres for tools up to 12.7 mm and grow with the tool above it
//! ([`Tool::tolerance_scale`]); the rest is in steps or tool radii. A pocket and its
//! enlargement cut with the tool enlarged alike get the same spiral, scaled, from the same
//! number of samples.

use super::super::levels::{Cut, CutEntry, LevelPlan};
use super::super::loops::{OffsetLoops, samples};
use super::super::offset::{RIDGE_SPACING, entry_for, too_large};
use super::super::options::{Direction, PocketOptions};
use super::super::segments::{Seg, segs_from_points};
use super::super::shape::{
    IndexedLoop, OffsetRegion, PocketShape, crosses, loop_distance, reversed,
};
use super::common::{arc_tolerance, last_loop, last_loop_margin};
use super::lanes::{LaneOptions, Outermost, chain_path, chorded};
use super::ring::Ring;
use super::rounding::{RoundOptions, round};
use super::smooth::{SmoothOptions, smooth};
use crate::error::InputError;
use crate::geom::{Point, Vec2};
use crate::toolpath::Tool;
use cavalier_contours::polyline::{PlineSource, Polyline};

/// Largest gap between a loop and the rounded loop inside it, in steps (see
/// [`super::rounding`]): `√2` is what right-angle corners of exact offsets have.
pub const CORNER_GAP: f64 = 1.8;
/// Largest gap between a loop and the rounded loop inside it, in tool radii: below the
/// diameter by enough that the two passes' discs still meet where the loops curve (the
/// spacing bound of the pocket's material, whatever the stepover).
pub const COVERAGE_GAP: f64 = 1.5;
/// How far a corner the gap bound leaves sharp may move in when filleted, in steps
/// ([`super::rounding`]).
const CUSP_SHIFT: f64 = 0.1;
/// Smallest fillet at such a corner, mm (times the tool's scale): ten steps of a program's
/// resolution.
const CUSP_RADIUS: f64 = 0.01;
/// Largest rounding radius, in steps.
const MAX_RADIUS: f64 = 12.0;
/// Least distance between a rounded loop and the loops inside it, in steps.
const MIN_CLEARANCE: f64 = 0.25;
/// Lane change length, in steps.
const WINDOW: f64 = 6.0;
/// Largest smoothing window, in steps ([`super::smooth`]).
const SMOOTH_WINDOW: f64 = 3.0;
/// Largest displacement of the interior path by the smoothing, in steps.
const SMOOTH_SHIFT: f64 = 0.03;
/// Sample spacing of the smoothing, mm (times the tool's scale, module docs).
const SMOOTH_SPACING: f64 = 0.1;
/// Deflection (rad) of a junction the smoothing keeps as a kink (a step, an unrounded corner).
const SMOOTH_KINK: f64 = 0.1;
/// Largest distance between the smoothed interior and its chords, mm, times the tool's scale (the
/// interior laps are a step from the walls; longer chords plan faster, measured: 0.002 →
/// 0.01 mm took the aerospace level from 14.84 to 14.58 s on `hsm`).
const SMOOTH_CHORD_TOLERANCE: f64 = 0.01;
/// Sagitta of the chords that replace interior loops' arcs, mm (times the tool's scale).
const CHORD_TOLERANCE: f64 = 0.002;
/// Longest chord on interior loops' arcs, mm (times the tool's scale).
const MAX_CHORD: f64 = 1.0;
/// Longest chord along a lane change, mm (times the tool's scale).
const LANE_CHORD: f64 = 0.5;
/// The full circle about `c` from and to `a`, counter-clockwise when
/// `ccw`: two half circles.
fn circle_from(c: Point, a: Point, ccw: bool) -> Vec<Seg> {
    let b = c - (a - c);
    let bulge = if ccw { 1.0 } else { -1.0 };
    vec![Seg::from_bulge(a, b, bulge), Seg::from_bulge(b, a, bulge)]
}

/// Whether every point of `ring` lies within `radius` of `c` (64 samples and the bound on
/// the chord between them: a sample within `radius − len/128` keeps its neighbourhood in).
fn within(ring: &Ring, c: Point, radius: f64) -> bool {
    const N: usize = 64;
    let slack = ring.len() / (2 * N) as f64;
    (0..N).all(|k| ring.point(ring.len() * k as f64 / N as f64).distance(c) <= radius - slack)
}

/// Grid spacing over a wide helix's pillar and the margin its points keep inside the tool,
/// in tool radii ([`Emitter::wide_helix`]).
const PILLAR_REACH: f64 = 0.05;
/// Spacing of the samples that check a wall's loop moved in by the last loop's margin, mm
/// (times the tool's scale).
const FAITHFUL_SAMPLE: f64 = 0.5;

/// What the offsets spiral measured.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OffsetsStats {
    /// Offset loops.
    pub loops: usize,
    /// Chains (continuous spirals).
    pub chains: usize,
    /// Largest rounding radius, mm.
    pub max_radius: f64,
}

/// The spiral of the module docs for one level.
pub fn plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<(LevelPlan, OffsetsStats), InputError> {
    let r = tool.radius();
    let s = opts.stepover_mm(tool);
    let h = s.min(RIDGE_SPACING * r);
    let k = tool.tolerance_scale();
    let margin = last_loop_margin(tool);
    let d0 = r + opts.wall_stock;
    let loops = OffsetLoops::build(shape, d0, h)?;
    if loops.nodes.is_empty() {
        return Err(too_large(tool));
    }
    let boundary = shape.offset(d0);
    let gap = (CORNER_GAP * h).min(COVERAGE_GAP * r);
    let (rounded, radii) = round(
        &loops,
        &RoundOptions {
            max_gap: gap,
            max_radius: MAX_RADIUS * h,
            min_clearance: MIN_CLEARANCE * h,
            sample: (h / 3.0).clamp(0.05 * k, 1.5 * k),
            reach: RIDGE_SPACING * r,
            // Filleted cusps only where they are written as arcs (as chords, a fillet much
            // shorter than a chord is still a corner).
            cusp_shift: opts.spiral.arcs.then_some(CUSP_SHIFT * h),
            cusp_radius: CUSP_RADIUS * k,
        },
    );
    let chains = loops.chains();
    let mut chain_of = vec![0; loops.nodes.len()];
    for (c, ch) in chains.iter().enumerate() {
        for &i in ch {
            chain_of[i] = c;
        }
    }
    let ccw = opts.direction == Direction::Climb;
    let mut em = Emitter {
        loops: &loops,
        rounded: &rounded,
        boundary: &boundary,
        opts,
        r,
        s,
        ccw,
        scale: k,
        margin,
        lanes: LaneOptions {
            window: WINDOW * h,
            chord: LANE_CHORD * k,
            step: h,
            reach: RIDGE_SPACING * r,
            arcs: opts.spiral.arcs,
            arc_tolerance: arc_tolerance(tool),
            wall_chord: (LANE_CHORD * k).min(0.9 * (8.0 * d0 * margin).sqrt()),
            scale: k,
            // Exact arcs to smooth or with --arcs, else the arcs as chords.
            chords: (!opts.spiral.arcs && !opts.spiral.curvature_ramps)
                .then_some((CHORD_TOLERANCE * k, MAX_CHORD * k)),
        },
        // The interior smoothed to curvature ramps, as chords (not with --arcs).
        smooth: (!opts.spiral.arcs && opts.spiral.curvature_ramps).then_some(SmoothOptions {
            max_window: SMOOTH_WINDOW * h,
            max_shift: SMOOTH_SHIFT * h,
            spacing: SMOOTH_SPACING * k,
            chord_tolerance: SMOOTH_CHORD_TOLERANCE * k,
            kink: SMOOTH_KINK,
        }),
        cuts: Vec::new(),
        here: None,
        circle: None,
    };
    // Post-order over the chains: a chain after every chain feeding its first loop.
    let deps = |c: usize| -> Vec<usize> {
        let mut d: Vec<usize> = loops.nodes[chains[c][0]]
            .prev
            .iter()
            .map(|&p| chain_of[p])
            .collect();
        d.sort_unstable();
        d.dedup();
        d
    };
    let mut done = vec![false; chains.len()];
    let mut roots: Vec<usize> = (0..chains.len())
        .filter(|&c| {
            chains[c]
                .last()
                .is_some_and(|&l| loops.nodes[l].next.is_empty())
        })
        .collect();
    while !roots.is_empty() {
        let pick = em.nearest(&chains, &roots);
        let root = roots.swap_remove(pick);
        let mut stack: Vec<(usize, Vec<usize>)> = vec![(root, deps(root))];
        while let Some((c, kids)) = stack.last_mut() {
            kids.retain(|&k| !done[k]);
            if kids.is_empty() {
                let c = *c;
                stack.pop();
                if !done[c] {
                    done[c] = true;
                    em.emit(&chains[c]);
                }
            } else {
                let pick = em.nearest(&chains, kids);
                let kid = kids.swap_remove(pick);
                let kd = deps(kid);
                stack.push((kid, kd));
            }
        }
    }
    let stats = OffsetsStats {
        loops: loops.nodes.len(),
        chains: chains.len(),
        max_radius: radii.iter().copied().fold(0.0, f64::max),
    };
    Ok((LevelPlan { cuts: em.cuts }, stats))
}

/// Turns chains into cuts.
struct Emitter<'a> {
    loops: &'a OffsetLoops,
    rounded: &'a [Polyline<f64>],
    boundary: &'a OffsetRegion,
    opts: &'a PocketOptions,
    r: f64,
    s: f64,
    ccw: bool,
    /// The tool's [`Tool::tolerance_scale`].
    scale: f64,
    /// The last loop's margin for the tool ([`last_loop_margin`]), mm.
    margin: f64,
    lanes: LaneOptions,
    smooth: Option<SmoothOptions>,
    cuts: Vec<Cut>,
    here: Option<Point>,
    /// The last cut is a helix's flat circle alone (a leaf loop inside it): its centre and
    /// radius, until the next chain is emitted.
    circle: Option<(Point, f64)>,
}

impl Emitter<'_> {
    /// The chain of `of` whose first loop is nearest to the tool; before the first cut, the
    /// one of largest area.
    fn nearest(&self, chains: &[Vec<usize>], of: &[usize]) -> usize {
        let first = |c: usize| &self.loops.nodes[chains[c][0]].pline;
        match self.here {
            Some(p) => {
                let mut best = (0, f64::INFINITY);
                for (i, &c) in of.iter().enumerate() {
                    let d = loop_distance(first(c), p);
                    if d < best.1 {
                        best = (i, d);
                    }
                }
                best.0
            }
            None => of
                .iter()
                .enumerate()
                .max_by(|a, b| {
                    first(*a.1)
                        .area()
                        .abs()
                        .total_cmp(&first(*b.1).area().abs())
                })
                .map_or(0, |(i, _)| i),
        }
    }

    /// The ring of loop `i` in the cutting direction, and for a wall's loop how far the
    /// lane changes onto it must stay short of it (see [`Outermost`]).
    fn ring(&self, i: usize) -> (Ring, Outermost) {
        let pl = &self.rounded[i];
        let ring = if self.ccw {
            Ring::new(pl)
        } else {
            Ring::new(&reversed(pl))
        };
        if self.loops.nodes[i].level == 0 {
            // The walls' loops moved in by the margin (5 µm of extra stock): the lane
            // change's chords onto one, at most `wall_chord` long, then stay inside the wall
            // loop itself at its concave arcs too (sagitta c²/(8·d₀) below the margin).
            // Not where that drops a part of the loop (a zero-width bridge where an island
            // meets the wall at exactly the tool's diameter: the tool centre must run along
            // it to clear the gap).
            let moved = last_loop(pl, self.margin);
            let idx = IndexedLoop::new(&moved);
            let sample = FAITHFUL_SAMPLE * self.scale;
            // Inside the region: its samples, and no crossing of any of the region's loops
            // (where two loops of the region touch, an island's loop moved in runs into the
            // other's clearance over a stretch shorter than the samples' spacing).
            let faithful = samples(pl, sample)
                .into_iter()
                .all(|p| idx.distance(p) <= 2.0 * self.margin)
                && samples(&moved, sample)
                    .into_iter()
                    .all(|p| self.in_boundary(p))
                && self.boundary.loops().all(|b| {
                    let x = moved.find_intersects(b);
                    x.basic_intersects.is_empty() && x.overlapping_intersects.is_empty()
                });
            let b_eps = if self.ccw {
                Ring::new(&moved)
            } else {
                Ring::new(&reversed(&moved))
            };
            if b_eps.is_empty() || !faithful {
                // The exact loop: chords of `wall_chord` sag at most c²/(8·d₀) across its
                // concave arcs (radius d₀ at least).
                let c = self.lanes.wall_chord;
                let inset = 1.1 * c * c / (8.0 * self.loops.d0);
                (ring, Outermost::Wall { inset })
            } else {
                (b_eps, Outermost::Wall { inset: 0.0 })
            }
        } else {
            (ring, Outermost::Interior)
        }
    }

    /// True when `p` is inside the tool-centre region (the walls' loops) or on its edge.
    fn in_boundary(&self, p: Point) -> bool {
        let v = super::super::shape::v2(p);
        let on = |l: &Polyline<f64>| loop_distance(l, p) < 1e-9;
        self.boundary
            .outers
            .iter()
            .any(|o| o.winding_number(v) != 0 || on(o))
            && self
                .boundary
                .islands
                .iter()
                .all(|i| i.winding_number(v) == 0 || on(i))
    }

    /// `path` led in from the entry helix about `c` of radius `rho` along a tangent curve:
    /// the helix (counter-clockwise when climbing) is left at the point a quarter turn
    /// before the direction of the path's start from `c`, and a cubic Hermite curve with the
    /// helix's and the path's tangents (scaled by the chord) joins the two, as chords (as
    /// arcs with `--arcs`). The path then starts on the helix circle, so the entry ends there
    /// ([`super::super::levels::helix_approach`] of a point on the circle is the point).
    /// The centre of a helix of radius `rho` that runs into `path` tangentially: the circle
    /// through the path's start, tangent to it there, turning the way the path does (its
    /// centre `rho` to the path's left when climbing, to its right otherwise), where that
    /// circle lies in the region (its centre inside, at least `rho` from every loop). The
    /// helix then ends where the cut begins, going its way: no lead, no turn sharper than
    /// the helix. `None` where the circle does not fit.
    fn tangent_helix(&self, path: &[Seg], rho: f64) -> Option<Point> {
        let first = path.first()?;
        let e = first.a;
        let left = first.tangent_at(0.0).perp();
        let c = e + if self.ccw { left } else { -left } * rho;
        let room = self
            .boundary
            .loops()
            .map(|l| loop_distance(l, c))
            .fold(f64::INFINITY, f64::min);
        (room >= rho * (1.0 + 1e-9) && !crosses(self.boundary, c, e)).then_some(c)
    }

    /// The widest helix tangent to the path's start, of radius over `rho` and at most
    /// [`SpiralOptions::wide_helix`](super::super::options::SpiralOptions::wide_helix) tool
    /// radii, whose pillar (the disc of radius `ρ − r` about its centre, which a helix
    /// wider than the tool leaves standing) the path itself then takes: every point of a
    /// grid of [`PILLAR_REACH`]·r over the pillar lies within `(1 − PILLAR_REACH)·r` of the
    /// path (the distance to the path changes by at most the grid's half-diagonal between
    /// its points, so the whole disc lies within `r`). Radii are tried from the widest down
    /// by tenths of `r`.
    fn wide_helix(&self, path: &[Seg], rho: f64) -> Option<(Point, f64)> {
        let widest = self.opts.spiral.wide_helix * self.r;
        let step = 0.1 * self.r;
        let mut w = widest;
        while w > rho + 1e-9 {
            if let Some(c) = self.tangent_helix(path, w)
                && self.pillar_taken(path, c, w - self.r)
            {
                return Some((c, w));
            }
            w -= step;
        }
        None
    }

    /// Whether `path` passes over the whole disc of radius `p` about `c` (see
    /// [`Emitter::wide_helix`]).
    fn pillar_taken(&self, path: &[Seg], c: Point, p: f64) -> bool {
        if p <= 0.0 {
            return true;
        }
        let g = PILLAR_REACH * self.r;
        let reach = self.r - g;
        let n = (p / g).ceil() as i64;
        let near: Vec<&Seg> = path
            .iter()
            .filter(|s| s.closest_point(c).distance(c) <= p + self.r + g)
            .collect();
        (-n..=n).all(|i| {
            (-n..=n).all(|j| {
                let q = c + Vec2::new(i as f64 * g, j as f64 * g);
                q.distance(c) > p + g
                    || near.iter().any(|s| s.closest_point(q).distance(q) <= reach)
            })
        })
    }

    fn helix_lead(&self, c: Point, rho: f64, path: Vec<Seg>) -> Vec<Seg> {
        let Some(first) = path.first() else {
            return path;
        };
        let e = first.a;
        let te = first.tangent_at(0.0);
        let Some(u) = (e - c).normalize() else {
            return path;
        };
        let sign = if self.ccw { 1.0 } else { -1.0 };
        // Quarter a turn back: the helix's tangent there points at `e`'s direction.
        let radial = u.rotate(-sign * std::f64::consts::FRAC_PI_2);
        let h = c + radial * rho;
        let th = radial.perp() * sign;
        let k = h.distance(e);
        if k < 1e-9 {
            return path;
        }
        // The biarc with both tangents (exact arcs, tangent at both ends); the cubic
        // Hermite curve with the same ends where it degenerates.
        let lead: Vec<Seg> = match crate::curve::biarc::biarc(h, th, e, te, 0.0, 1.0) {
            Some(arcs) => arcs
                .iter()
                .filter(|a| a.start.distance(a.end) > 1e-9)
                .map(|a| Seg::from_bulge(a.start, a.end, (0.25 * a.sweep()).tan()))
                .collect(),
            None => {
                let n = ((k / (0.1 * self.scale)).ceil() as usize).max(16);
                let pts: Vec<Point> = (0..=n)
                    .map(|j| {
                        let t = j as f64 / n as f64;
                        let (t2, t3) = (t * t, t * t * t);
                        let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
                        let h10 = t3 - 2.0 * t2 + t;
                        let h01 = -2.0 * t3 + 3.0 * t2;
                        let h11 = t3 - t2;
                        (h.to_vec2() * h00 + th * (k * h10) + e.to_vec2() * h01 + te * (k * h11))
                            .to_point()
                    })
                    .collect();
                segs_from_points(&pts)
            }
        };
        let mut out = if self.opts.spiral.arcs {
            lead
        } else {
            chorded(&lead, CHORD_TOLERANCE * self.scale, MAX_CHORD * self.scale)
        };
        out.extend(path);
        out
    }

    /// Whether every point inside `ring` (loop `i`) is within the reach of the loops it feeds:
    /// each point of the loop within `reach − len/(2π) − len/(2n)` of one of them (`n`
    /// samples). A point inside a closed loop of length `len` is within `len/(2π)` of it (the
    /// disc round it up to the loop lies inside, and its perimeter is no longer than the
    /// loop), and each point of the loop within `len/(2n)` of a sample.
    fn covered_by_next(&self, i: usize, ring: Option<&Ring>) -> bool {
        let Some(ring) = ring else { return false };
        const SAMPLES: usize = 32;
        let margin =
            self.lanes.reach - ring.len() * (0.5 / std::f64::consts::PI + 0.5 / SAMPLES as f64);
        let next: Vec<Ring> = self.loops.nodes[i]
            .next
            .iter()
            .map(|&j| self.ring(j).0)
            .collect();
        if margin <= 0.0 || next.is_empty() {
            return false;
        }
        (0..SAMPLES).all(|k| {
            let p = ring.point(ring.len() * k as f64 / SAMPLES as f64);
            next.iter().any(|n| n.project(p).1 <= margin)
        })
    }

    /// Appends one chain: linked to the previous cut where the link is short and safe, else
    /// a new cut with its own entry.
    fn emit(&mut self, chain: &[usize]) {
        let Some(&first) = chain.first() else { return };
        let node = &self.loops.nodes[first];
        let (mut rings, kinds): (Vec<Ring>, Vec<Outermost>) =
            chain.iter().map(|&i| self.ring(i)).unzip();
        let outer = kinds.last().copied().unwrap_or(Outermost::Interior);
        let leaf = node.prev.is_empty();
        // A leaf loop whose whole inside the loops it feeds reach is not run round (round a
        // loop much smaller than the tool, the path is a string of sharp turns for nothing):
        // the chain starts on the next loop, or, a chain of that loop alone, is left out.
        if leaf && self.covered_by_next(first, rings.first()) {
            if rings.len() > 1 {
                rings.remove(0);
            } else if outer == Outermost::Interior {
                return;
            }
        }
        // Where the chain is entered: near the tool, or at the helix.
        let mut entry = CutEntry::Ramp;
        let mut swept_leaf = false;
        let enter = match self.here {
            Some(p) if !leaf => p,
            _ => {
                entry = if node.island {
                    CutEntry::Ramp
                } else {
                    let level_islands: Vec<Polyline<f64>> = self
                        .loops
                        .level(node.level)
                        .filter(|&j| self.loops.nodes[j].island)
                        .map(|j| self.loops.nodes[j].pline.clone())
                        .collect();
                    let lp = if self.ccw {
                        self.rounded[first].clone()
                    } else {
                        reversed(&self.rounded[first])
                    };
                    entry_for(&lp, true, &level_islands, self.boundary, self.opts, self.r)
                };
                // A leaf loop within the helix's radius of its centre lies in the disc the
                // helix's flat turn sweeps (radius `ρ + r`, `ρ ≤ 0.9·r`): the chain starts on
                // the next loop, led from the helix where it is (a loop much smaller than the
                // tool is a string of sharp turns).
                // A chain of that loop alone is the helix's flat turn itself.
                if let CutEntry::Helix { center, radius, .. } = entry
                    && within(&rings[0], center, radius)
                {
                    if rings.len() > 1 {
                        rings.remove(0);
                        entry = CutEntry::Helix {
                            center,
                            radius,
                            flat_turn: true,
                        };
                        swept_leaf = true;
                    } else if outer == Outermost::Interior {
                        let a = center + Vec2::new(radius, 0.0);
                        self.cuts.push(Cut {
                            entry,
                            path: circle_from(center, a, self.ccw),
                        });
                        self.here = Some(a);
                        self.circle = Some((center, radius));
                        return;
                    }
                }
                match entry {
                    CutEntry::Helix { center, .. } => center,
                    _ => self.here.unwrap_or_else(|| rings[0].point(0.0)),
                }
            }
        };
        let cp = chain_path(&rings, enter, outer, &self.lanes);
        let mut path: Vec<Seg> = match &self.smooth {
            Some(o) => smooth(&cp.segs, cp.interior, o),
            None => cp.segs,
        };
        if let CutEntry::Helix {
            center,
            radius,
            flat_turn,
        } = entry
        {
            let tangent = if swept_leaf {
                None
            } else {
                self.tangent_helix(&path, radius)
            };
            match tangent {
                Some(c) => {
                    let (center, radius) = self.wide_helix(&path, radius).unwrap_or((c, radius));
                    entry = CutEntry::Helix {
                        center,
                        radius,
                        flat_turn,
                    }
                }
                None => path = self.helix_lead(center, radius, path),
            }
        }
        let Some(start) = path.first().map(|g| g.a) else {
            return;
        };
        let end = path.last().map(|g| g.b);
        let linkable = !leaf
            && self.here.is_some_and(|h| {
                h.distance(start) <= 2.0 * self.s + 1e-9 && !crosses(self.boundary, h, start)
            });
        // The last cut a helix's flat circle alone: it is left where the link to this chain
        // turns least.
        let exit = self.circle.take().and_then(|(c, rho)| {
            let t = path.first()?.tangent_at(0.0);
            Some((c, self.circle_exit(c, rho, start, t)?))
        });
        if let (true, Some(last), Some(mut h)) = (linkable, self.cuts.last_mut(), self.here) {
            if let Some((c, a)) = exit {
                last.path = circle_from(c, a, self.ccw);
                h = a;
            }
            if h.distance(start) > 1e-9 {
                last.path.push(Seg::line(h, start));
            }
            last.path.extend(path);
        } else {
            self.cuts.push(Cut { entry, path });
        }
        self.here = end;
    }

    /// The point of the circle of radius `rho` about `c` (cut in the chain's sense) from which
    /// a straight link to `start`, where the path goes on along `t`, turns least in all
    /// (from the circle's tangent into the link, from the link into `t`), among 72 and with
    /// the link inside the tool-centre region.
    fn circle_exit(&self, c: Point, rho: f64, start: Point, t: Vec2) -> Option<Point> {
        let sign = if self.ccw { 1.0 } else { -1.0 };
        let turn = |u: Vec2, v: Vec2| u.cross(v).atan2(u.dot(v)).abs();
        (0..72)
            .filter_map(|k| {
                let th = k as f64 * std::f64::consts::TAU / 72.0;
                let u = Vec2::new(th.cos(), th.sin());
                let a = c + u * rho;
                let tangent = u.perp() * sign;
                let d = start - a;
                let cost = if d.length() <= 1e-9 {
                    turn(tangent, t)
                } else {
                    turn(tangent, d) + turn(d, t)
                };
                (!crosses(self.boundary, a, start)).then_some((cost, a))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .map(|(_, a)| a)
    }
}
