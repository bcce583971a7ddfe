//! Adaptive clearing: the tool's engagement held under a bound at every step, the pocket
//! cleared from the inside out in passes that follow the material.
//!
//! The planner keeps its own picture of the stock ([`field`]: a grid of cells of side
//! `h = r/32`, one bit per cell of material). It enters with a helix at the point of the
//! pocket farthest from its walls (the helix clears a disc of its radius plus `r`), then
//! runs passes ([`pass`]): each step of length `δ = r/8` is turned so that it removes
//! `TARGET_FILL · s · δ` of material, the area a straight cut of width `s` (`--stepover`)
//! removes, so the engagement is that of the straight cut at every step, the entry aside.
//! Each pass starts where the tool, clear of material, touches it (a block of a coarse
//! distance-to-material map at `r` plus one to three blocks from the nearest material,
//! the block nearest the tool first); the tool stays down and feeds there in a straight
//! line when the line's every position is clear of material
//! ([`LINK_CELLS`] cells at most in the tool's disc) and inside the walls; otherwise the
//! tool retracts and feeds down there again (a direct entry over cleared material). A region
//! the passes cannot reach (beyond an island, past a neck narrower than the tool) gets a
//! helix of its own. The passes keep the tool centre `3h` farther from the walls than the
//! tool-centre region (the grid's distances hold to `h`); a last pass around each loop of the
//! exact tool-centre region (`r` plus the wall stock from the walls) cuts the band left
//! there, whose width is that margin plus the scallops between passes meeting a wall.
//!
//! Each pass's tool positions are smoothed (they wobble by the grid's count of cells, a few
//! hundredths of the target's area: Taubin's λ|μ smoothing moves each by at most
//! [`SMOOTH_RADII`]) and written as the chords between them (`δ` long, the path itself, not
//! an approximation of it); with `--arcs`, as tangent-continuous biarcs fitted within
//! [`ARC_FIT`], kept only where they are faster (`pocket::arcs_or_chords`). The chords are
//! the default because the biarcs' curvature steps where two arcs meet, and a jerk-limited
//! controller slows at every such step. The field is then cleared along the written path, so
//! the next passes see what the program leaves; the engagement of the written path differs
//! from the planned one by at most about `SMOOTH_RADII·r / s` of the target (2.5 % at a 40 %
//! stepover) and the verifier measures it. Near the walls a smoothed position that the tool
//! may not stand at keeps its place.
//!
//! **What is measured, and by whom.** The planner's counts are its own; the stock simulation
//! (`crate::stock`, another grid, another sweep) measures the engagement of the written path
//! and checks that nothing is left and nothing gouged, as for every strategy.

pub(crate) mod field;
pub(crate) mod pass;

use crate::error::Result;
use crate::geom::{Point, Vec2};
use crate::strategy::pocket::levels::{Cut, CutEntry, LevelPlan};
use crate::strategy::pocket::options::{Direction, Entry, PocketOptions};
use crate::strategy::pocket::segments::{
    Seg, fit_arcs_where, segs_from_points, segs_from_vertices,
};
use crate::strategy::pocket::shape::{
    IndexedLoop, PocketShape, closed_chain, crosses, restart_near, reversed,
};
use crate::toolpath::Tool;
use field::Field;
use pass::Stepper;

/// Grid cell, in tool radii.
pub const CELL_RADII: f64 = 1.0 / 32.0;
/// Step length, in tool radii.
pub const STEP_RADII: f64 = 1.0 / 8.0;
/// The share of the stepover's area each step aims at (the rest is the margin for the
/// grid's count and the arcs' fit).
pub const TARGET_FILL: f64 = 0.975;
/// How far the arcs joining a pass's positions may stray from them, in tool radii.
pub const ARC_FIT: f64 = 0.003;
/// How far smoothing may move a pass's positions, in tool radii.
pub const SMOOTH_RADII: f64 = 0.02;
/// Smoothing rounds (each a shrinking and an inflating Laplacian step).
const SMOOTH_ROUNDS: usize = 24;
/// The smallest helix, in tool radii: where there is less room, the entry is a ramp.
pub const MIN_HELIX_RADII: f64 = 0.1;
/// Longest ramp line where no helix fits, in tool radii.
pub const RAMP_REACH: f64 = 4.0;
/// The margin of material-free cells around a descent, beyond the tool's radius.
pub const DESCENT_CELLS: f64 = 3.0;
/// Most material cells a link may pass within the tool's radius of.
pub const LINK_CELLS: u32 = 4;
/// Coarse blocks per side, in cells.
const BLOCK: usize = 4;
/// Most cells in the planner's grid; a larger pocket gets larger cells.
const MAX_CELLS: f64 = 3.0e7;
/// Most passes in one level.
const MAX_PASSES: usize = 100_000;

/// Plans one level of adaptive clearing in the planar `shape`; a tool (plus the wall stock)
/// that does not fit is an input error, as for every strategy.
pub fn plan(shape: &PocketShape, tool: &Tool, opts: &PocketOptions) -> Result<LevelPlan> {
    let r = tool.radius();
    let stock = opts.wall_stock.max(0.0);
    let s = opts.stepover_mm(tool).min(tool.diameter);
    let b = shape.outer.bounds();
    let span = (b.max.x - b.min.x + 4.0 * r) * (b.max.y - b.min.y + 4.0 * r);
    let h = (CELL_RADII * r).max((span / MAX_CELLS).sqrt());
    let mut field = Field::new(shape, h, 2.0 * h);
    let walls = Walls::new(shape, r + stock, h, 2.0 * ARC_FIT * r);
    let delta = STEP_RADII * r;
    let side = if opts.direction == Direction::Climb {
        1.0
    } else {
        -1.0
    };
    let stepper = Stepper {
        r,
        delta,
        target: TARGET_FILL * s * delta / (h * h),
        s,
        walls: &walls,
        side,
        max_steps: 10_000_000,
    };
    let region = shape.offset(r + stock);
    if region.is_empty() {
        return Err(crate::strategy::pocket::offset::too_large(tool).into());
    }
    let mut plan = Planner {
        field: &mut field,
        stepper,
        cuts: Vec::new(),
        pos: None,
        tried: Vec::new(),
        fit: ARC_FIT * r,
        arcs: opts.spiral.arcs,
    };
    let helix = match opts.entry {
        Entry::Helix { radius, .. } => radius,
        Entry::Ramp { .. } => 0.0,
    };
    for _ in 0..MAX_PASSES {
        if !plan.next_pass(shape, r + stock, helix) {
            break;
        }
    }
    plan.walls(&region, opts.direction);
    Ok(LevelPlan { cuts: plan.cuts })
}

/// Where the tool centre may go: at least `clear` (plus a margin) from the pocket's loops.
/// The grid's distance decides where it is sure (it is within `2.2·h` of the exact one),
/// the loops' exact distance elsewhere.
#[derive(Debug)]
pub(crate) struct Walls<'a> {
    loops: Vec<IndexedLoop<'a>>,
    /// The tool-centre region's distance from the walls, mm.
    pub clear: f64,
    /// Beyond this grid distance a point is inside for sure.
    sure: f64,
    /// The exact distance a point needs: `clear` plus the margin.
    need: f64,
}

impl<'a> Walls<'a> {
    fn new(shape: &'a PocketShape, clear: f64, h: f64, margin: f64) -> Self {
        Walls {
            loops: shape
                .loops()
                .map(|o| IndexedLoop::new(o.polyline()))
                .collect(),
            clear,
            sure: clear + margin + 2.5 * h,
            need: clear + margin,
        }
    }

    /// The distance from `q` to the walls: the grid's where it is sure to be beyond
    /// `need` by a cell or more, else the loops' exact distance.
    pub(crate) fn distance(&self, field: &Field, q: Point) -> f64 {
        let w = field.wall_distance(q);
        if w >= self.sure + field.h {
            return w;
        }
        self.loops
            .iter()
            .map(|l| l.distance(q))
            .fold(f64::INFINITY, f64::min)
    }

    /// True when the tool centre may stand at `q`.
    pub(crate) fn allows(&self, field: &Field, q: Point) -> bool {
        let w = field.wall_distance(q);
        if w >= self.sure {
            return true;
        }
        if w + 2.0 * field.h < self.need {
            return false;
        }
        self.loops.iter().all(|l| l.distance(q) >= self.need)
    }
}

/// The planner's state through a level.
struct Planner<'f, 'w> {
    field: &'f mut Field,
    stepper: Stepper<'w>,
    cuts: Vec<Cut>,
    /// Where the tool is, at the level's depth.
    pos: Option<Point>,
    /// Coarse blocks tried as a start that cut nothing.
    tried: Vec<bool>,
    fit: f64,
    /// Write the smoothed positions as biarcs (`--arcs`) instead of chords.
    arcs: bool,
}

impl Planner<'_, '_> {
    /// Plans the next pass; false when nothing is left to clear.
    fn next_pass(&mut self, shape: &PocketShape, clear: f64, helix: f64) -> bool {
        let Some((p, theta, block)) = self.start() else {
            return self.new_helix(shape, clear, helix);
        };
        if let Err(at) = self.pass_from(p, theta) {
            self.tried[block] = true;
            self.mark_tried(at);
        }
        true
    }

    /// A pass from `p` heading `theta` (from where the material's edge beside it begins, if
    /// the walk back finds it), appended to the plan; where it cuts nothing, the point it
    /// started from.
    fn pass_from(&mut self, p: Point, theta: f64) -> Result<(), Point> {
        let st = self.stepper;
        let (p, theta) = st.upstream(self.field, p, theta).unwrap_or((p, theta));
        self.field.record();
        let (pts, removed) = st.run(self.field, p, theta);
        if removed == 0 || pts.len() < 2 {
            self.field.undo();
            return Err(p);
        }
        let path = self.fitted(&pts);
        self.field.undo();
        let from = self.descent_near(&pts);
        if self.cut_along(&path) == 0 {
            return Err(p);
        }
        self.join(&pts, path, from);
        Ok(())
    }

    /// Clears the field along the written path (the band each line sweeps; along an arc, tool
    /// positions at most `h` apart), where
    /// the stepper cleared it along its own positions: the two differ by the smoothing, and
    /// the next passes, the links and the entries must see the material the program leaves.
    /// The cells cleared.
    fn cut_along(&mut self, path: &[Seg]) -> u64 {
        let (h, r) = (self.field.h, self.stepper.r);
        let mut n = 0;
        for sg in path {
            if sg.arc.is_none() {
                n += u64::from(self.field.clear_capsule(sg.a, sg.b, r));
                continue;
            }
            let steps = ((sg.length() / h).ceil() as usize).max(1);
            for k in 0..=steps {
                let q = sg.point_at(sg.length() * k as f64 / steps as f64);
                n += u64::from(self.field.clear_disc(q, r));
            }
        }
        n
    }

    /// The written path through the positions: each run of them (clear of the walls, or
    /// near them) smoothed ([`smoothed`]; near the walls a smoothed position the tool may not
    /// stand at keeps its place), then written as the chords between the smoothed positions
    /// or, with `--arcs`, as fitted arcs; either kept only where every point of it (at most
    /// `h/2` apart) is one the tool centre may stand at, else the chords through the raw
    /// positions (a fitted curve can swing out at a sharp turn, a chord between a smoothed and
    /// a kept position can cut a corner).
    fn fitted(&self, pts: &[Point]) -> Vec<Seg> {
        let (field, walls) = (&*self.field, self.stepper.walls);
        let h = field.h;
        let allowed = |sg: &Seg| {
            let n = ((sg.length() / (0.5 * h)).ceil() as usize).max(1);
            (0..=n).all(|k| walls.allows(field, sg.point_at(sg.length() * k as f64 / n as f64)))
        };
        let within = SMOOTH_RADII * self.stepper.r;
        let free = |p: Point| field.wall_distance(p) >= walls.sure + within + 2.0 * h;
        let mut out = Vec::new();
        let mut i = 0;
        while i + 1 < pts.len() {
            let kind = free(pts[i]);
            let mut j = i + 1;
            while j + 1 < pts.len() && free(pts[j]) == kind {
                j += 1;
            }
            let run = &pts[i..=j];
            let fit = if run.len() > 2 {
                let mut smooth = smoothed(run, within);
                if !kind {
                    for (q, p) in smooth.iter_mut().zip(run) {
                        if !walls.allows(field, *q) {
                            *q = *p;
                        }
                    }
                }
                if self.arcs {
                    fit_arcs_where(&smooth, self.fit, allowed)
                        .or_else(|| fit_arcs_where(run, self.fit, allowed))
                } else {
                    let chords = segs_from_points(&smooth);
                    chords.iter().all(allowed).then_some(chords)
                }
            } else {
                None
            };
            out.extend(fit.unwrap_or_else(|| segs_from_points(run)));
            i = j;
        }
        out
    }

    /// Appends a pass's positions to the plan: linked from where the tool is when the link
    /// is clear, else as a new cut entered directly, the tool feeding down at `from`, or,
    /// with no clear point to feed down at, ramped along the pass itself.
    fn join(&mut self, pts: &[Point], path: Vec<Seg>, from: Option<Point>) {
        let start = pts[0];
        let linked = self.pos.filter(|&at| self.link_clear(at, start));
        match (linked, self.cuts.last_mut()) {
            (Some(at), Some(cut)) => {
                if at.distance(start) > 1e-9 {
                    cut.path.push(Seg::line(at, start));
                }
                cut.path.extend(path);
            }
            _ => {
                self.cuts.push(Cut {
                    entry: from.map_or(CutEntry::Ramp, |from| CutEntry::Direct { from }),
                    path,
                });
            }
        }
        self.pos = pts.last().copied();
    }

    /// Where the tool feeds down for a pass that starts at `pts[0]`: the first point, at
    /// `start` or going out from it (`h` apart, at most `r/2`; back along the pass's first
    /// heading, then square to it either side), where no material lies within
    /// [`DESCENT_CELLS`] cells beyond the tool's radius on the field and the walls are as far
    /// beyond the tool-centre region: the passes come within a small margin of that region,
    /// leaving a sliver thinner than a cell that the field does not hold and the verifier
    /// does. Every point on the way must be one the tool centre may stand at. Else none: the
    /// pass is ramped along (feeding down at `start` anyway plunged beside the walls' band,
    /// `kg_teeth-20.dxf` with a 6 mm tool).
    fn descent_near(&self, pts: &[Point]) -> Option<Point> {
        let (field, st) = (&*self.field, self.stepper);
        let start = pts[0];
        let reach = st.r + DESCENT_CELLS * field.h;
        let clear = |q: Point| {
            !field.disc_holds_more_than(q, reach, 0)
                && st.walls.distance(field, q) >= st.walls.clear + DESCENT_CELLS * field.h
        };
        if clear(start) {
            return Some(start);
        }
        let u = pts.get(1).and_then(|&b| (b - start).normalize())?;
        for dir in [-u, Vec2::new(-u.y, u.x), Vec2::new(u.y, -u.x)] {
            let mut t = field.h;
            while t <= 0.5 * st.r {
                let q = start + dir * t;
                if !st.walls.allows(field, q) {
                    break;
                }
                if clear(q) {
                    return Some(q);
                }
                t += field.h;
            }
        }
        None
    }

    /// True when the tool may feed from `a` to `b` at depth: every position along the way
    /// (at most `h` apart) is inside the planner's reach and meets no material.
    fn link_clear(&self, a: Point, b: Point) -> bool {
        let n = ((a.distance(b) / self.field.h).ceil() as usize).max(1);
        (0..=n).all(|k| {
            let q = a.lerp(b, k as f64 / n as f64);
            self.stepper.walls.allows(self.field, q)
                && !self
                    .field
                    .disc_holds_more_than(q, self.stepper.r, LINK_CELLS)
        })
    }

    /// The start of the next pass: the block nearest the tool that is clear of material by
    /// one to three blocks' width beyond `r`, inside the reach, not tried before, whose
    /// first step can cut; and the heading with the material on the cutting side.
    fn start(&mut self) -> Option<(Point, f64, usize)> {
        let st = self.stepper;
        let coarse = self.field.coarse_distance(BLOCK);
        let hc = self.field.h * BLOCK as f64;
        if self.tried.len() != coarse.dist.len() {
            self.tried = vec![false; coarse.dist.len()];
        }
        let here = self.pos?;
        let mut cands: Vec<(f64, usize, usize)> = Vec::new();
        for j in 1..coarse.ny.saturating_sub(1) {
            for i in 1..coarse.nx.saturating_sub(1) {
                let k = j * coarse.nx + i;
                let d = coarse.dist[k];
                if self.tried[k] || d < st.r - hc || d > st.r + 2.0 * hc {
                    continue;
                }
                let c = self.field.coarse_centre(BLOCK, i, j);
                if !st.walls.allows(self.field, c) {
                    continue;
                }
                cands.push((c.distance(here), i, j));
            }
        }
        cands.sort_by(|a, b| a.0.total_cmp(&b.0));
        for &(_, i, j) in &cands {
            let k = j * coarse.nx + i;
            let c = self.field.coarse_centre(BLOCK, i, j);
            // Towards the material: down the distance map's slope.
            let at = |ii: usize, jj: usize| coarse.dist[jj * coarse.nx + ii];
            let g = Vec2::new(at(i + 1, j) - at(i - 1, j), at(i, j + 1) - at(i, j - 1));
            let Some(n) = (-g).normalize() else {
                self.tried[k] = true;
                continue;
            };
            // The point on the line through the block along `n` nearest the material with
            // the tool's disc clear of it (bisection between clear and not).
            let (mut lo, mut hi) = (-3.0 * hc, 3.0 * hc);
            let clear_at = |t: f64| {
                let q = c + n * t;
                st.walls.allows(self.field, q) && !self.field.disc_holds_more_than(q, st.r, 0)
            };
            if !clear_at(lo) {
                self.tried[k] = true;
                continue;
            }
            if clear_at(hi) {
                lo = hi;
            } else {
                for _ in 0..8 {
                    let mid = 0.5 * (lo + hi);
                    if clear_at(mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
            }
            let c = c + n * lo;
            // The heading with `n` on the cutting side: `n` turned a quarter the other way.
            let theta = n.y.atan2(n.x) + st.side * std::f64::consts::FRAC_PI_2;
            let deep = self.field.wall_distance(c) >= st.walls.clear + st.r;
            let need = if deep { pass::MIN_CUT } else { 0.3 } * st.target;
            if st.first_bite_reaches(self.field, c, theta, need) {
                return Some((c, theta, k));
            }
            self.tried[k] = true;
        }
        None
    }

    fn mark_tried(&mut self, p: Point) {
        let hc = self.field.h * BLOCK as f64;
        let (nx, _) = self.field.size();
        let cx = nx.div_ceil(BLOCK);
        let o = self.field.centre(0, 0);
        let i = ((p.x - o.x) / hc + 0.5).floor().max(0.0) as usize;
        let j = ((p.y - o.y) / hc + 0.5).floor().max(0.0) as usize;
        if let Some(t) = self.tried.get_mut(j * cx + i) {
            *t = true;
        }
    }

    /// A helix where material is left that no pass reaches: at the cell farthest from the
    /// walls whose tool disc is at least half material; false when there is none.
    fn new_helix(&mut self, shape: &PocketShape, clear: f64, helix: f64) -> bool {
        let st = self.stepper;
        let (nx, ny) = self.field.size();
        // At least half of the disc's cells: `n ≥ π r² / 2` for a count `n`.
        let half_disc =
            ((0.5 * (std::f64::consts::PI * (st.r / self.field.h).powi(2))).ceil() as u32).max(1);
        // Cells whose disc is at least half material, on a grid of blocks; of those within
        // a block of the largest wall distance, the one nearest their centroid (the middle of
        // a ridge of equal distances, not its end).
        let mut found: Vec<(f64, Point)> = Vec::new();
        let mut top: f64 = 0.0;
        let hc = self.field.h * BLOCK as f64;
        for j in (0..ny).step_by(BLOCK) {
            for i in (0..nx).step_by(BLOCK) {
                let w = self.field.wall_at(i, j);
                if w < st.walls.clear || w < top - hc {
                    continue;
                }
                let c = self.field.centre(i, j);
                if self.field.disc_holds_more_than(c, st.r, half_disc - 1) {
                    top = top.max(w);
                    found.push((w, c));
                }
            }
        }
        found.retain(|f| f.0 >= top - hc);
        if found.is_empty() {
            return false;
        }
        let n = found.len() as f64;
        let mid = found.iter().fold(Point::ORIGIN, |a, f| {
            Point::new(a.x + f.1.x / n, a.y + f.1.y / n)
        });
        let c = found
            .iter()
            .map(|f| f.1)
            .min_by(|a, b| a.distance(mid).total_cmp(&b.distance(mid)))
            .unwrap_or(mid);
        // The helix must fit: the exact distance to the walls decides.
        let room = shape.distance_to(c) - clear - 2.0 * self.field.h;
        let rho = helix.min(room).max(0.0);
        if rho < MIN_HELIX_RADII * st.r {
            return self.new_ramp(c);
        }
        self.field.clear_disc(c, rho + st.r);
        let p0 = c + Vec2::new(rho, 0.0);
        let theta = st.side * std::f64::consts::FRAC_PI_2;
        self.field.record();
        let (mut pts, _) = st.run(self.field, p0, theta);
        if pts.len() < 2 {
            pts = vec![p0, c + Vec2::new(rho, 1e-3)];
        }
        let path = self.fitted(&pts);
        self.field.undo();
        self.cut_along(&path);
        self.cuts.push(Cut {
            entry: CutEntry::Helix {
                center: c,
                radius: rho,
                flat_turn: true,
            },
            path,
        });
        self.pos = pts.last().copied();
        true
    }

    /// Where there is no room for a helix (a region barely wider than the tool): a ramp
    /// along the longest straight run of positions the tool centre may stand at on a line
    /// from `c` (16 headings, at most [`RAMP_REACH`] radii), cleared on the field. The
    /// material around `c` is marked cleared whatever is found, so the planner moves on (the
    /// verifier refuses a program that leaves it).
    fn new_ramp(&mut self, c: Point) -> bool {
        let (st, h) = (self.stepper, self.field.h);
        // The longest run of allowed positions (`h` apart) along each heading from `c`.
        let mut best: Option<(Point, Point, f64)> = None;
        for k in 0..16 {
            let a = std::f64::consts::TAU * f64::from(k) / 16.0;
            let u = Vec2::new(a.cos(), a.sin());
            let mut run: Option<(f64, f64)> = None;
            let mut t = 0.0;
            while t <= RAMP_REACH * st.r {
                match (st.walls.allows(self.field, c + u * t), run) {
                    (true, None) => run = Some((t, t)),
                    (true, Some((t0, _))) => run = Some((t0, t)),
                    (false, Some(_)) => break,
                    (false, None) => {}
                }
                t += h;
            }
            if let Some((t0, t1)) = run
                && best.is_none_or(|b| t1 - t0 > b.2)
            {
                best = Some((c + u * t0, c + u * t1, t1 - t0));
            }
        }
        // Marked cleared whatever is found: what a line cannot reach there is left to the
        // walls' loops (and the verifier), not tried again.
        self.field.clear_disc(c, st.r);
        let Some((from, end, len)) = best.filter(|b| b.2 >= 4.0 * h) else {
            return true;
        };
        let n = (len / st.delta).ceil() as usize;
        for k in 0..=n {
            self.field
                .clear_disc(from.lerp(end, k as f64 / n as f64), st.r);
        }
        self.cuts.push(Cut {
            entry: CutEntry::Ramp,
            path: vec![Seg::line(from, end)],
        });
        self.pos = Some(end);
        true
    }

    /// Where the tool may feed down for a walls' loop starting at `path[0].a`: the first
    /// point, going in from the loop's start square to it (either side, `h` apart, at most
    /// `2r`), whose disc plus [`DESCENT_CELLS`] cells holds no material on the field and from
    /// which every point back to the start is one the tool centre may stand at. `None`: the
    /// loop is ramped into. (The field is the planner's own; a point of an earlier pass is
    /// not enough, since a link may pass within `r` of a few cells of material.)
    fn loop_descent(&self, path: &[Seg]) -> Option<Point> {
        let (field, st) = (&*self.field, self.stepper);
        let first = path.first()?;
        let start = first.a;
        let t = first.tangent_at(0.0).normalize()?;
        let reach = st.r + DESCENT_CELLS * field.h;
        for n in [Vec2::new(-t.y, t.x), Vec2::new(t.y, -t.x)] {
            let mut d = field.h;
            while d <= 2.0 * st.r {
                let q = start + n * d;
                if !st.walls.allows(field, q) {
                    break;
                }
                if !field.disc_holds_more_than(q, reach, 0) {
                    return Some(q);
                }
                d += field.h;
            }
        }
        None
    }

    /// The last passes: each loop of the tool-centre region, climb or conventional, from its
    /// point nearest the tool.
    fn walls(&mut self, region: &crate::strategy::pocket::shape::OffsetRegion, dir: Direction) {
        let loops: Vec<_> = region.loops().cloned().collect();
        for lp in loops {
            let lp = if dir == Direction::Climb {
                lp
            } else {
                reversed(&lp)
            };
            let lp = match self.pos {
                Some(p) => restart_near(&lp, p),
                None => lp,
            };
            let path = segs_from_vertices(&closed_chain(&lp));
            let Some(first) = path.first().map(|s| s.a) else {
                continue;
            };
            let last = path.last().map_or(first, |s| s.b);
            match (self.pos, self.cuts.last_mut()) {
                (Some(at), Some(cut))
                    if !crosses(region, at, first) && at.distance(first) < 1e-3 =>
                {
                    cut.path.extend(path);
                }
                _ => {
                    let entry = match self.loop_descent(&path) {
                        Some(from) => CutEntry::Direct { from },
                        None => CutEntry::Ramp,
                    };
                    self.cuts.push(Cut { entry, path });
                }
            }
            self.pos = Some(last);
        }
    }
}

/// The positions with their wobble smoothed out: Taubin's λ|μ smoothing (a Laplacian step
/// `λ = 0.5` towards the neighbours' mean, then `μ = −0.53` away from it, which removes the
/// short wavelengths without shrinking the curve), each position kept within `within` of
/// where it was; the ends stay. The stepper's turns come from cell counts, so consecutive
/// positions zigzag by a few hundredths of a millimetre; through them, an interpolating
/// curve changes its turn at every position, and the arcs fitted to it are as short as the
/// steps.
fn smoothed(pts: &[Point], within: f64) -> Vec<Point> {
    let n = pts.len();
    if n < 3 || within <= 0.0 {
        return pts.to_vec();
    }
    let mut p = pts.to_vec();
    let mut next = p.clone();
    for _ in 0..SMOOTH_ROUNDS {
        for f in [0.5, -0.53] {
            for i in 1..n - 1 {
                let m = p[i - 1].midpoint(p[i + 1]);
                let q = p[i] + (m - p[i]) * f;
                let d = q - pts[i];
                let len = d.length();
                next[i] = if len > within {
                    pts[i] + d * (within / len)
                } else {
                    q
                };
            }
            std::mem::swap(&mut p, &mut next);
        }
    }
    p
}
