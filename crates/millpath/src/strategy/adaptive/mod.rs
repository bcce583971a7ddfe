//! Adaptive clearing: the tool's engagement held under a bound at every step, the pocket
//! cleared from the inside out in passes that follow the material.
//!
//! The planner keeps its own picture of the stock ([`field`]: a grid of cells of side
//! `h = r/32` at a stepover of 40 % or more, one bit per cell of material; see **Thin
//! stepovers** below). It enters where the pocket is farthest from its walls, then runs
//! passes ([`pass`]): each step of length `δ = r/8` is turned so that it removes
//! `TARGET_FILL · s · δ` of material, the area a straight cut of width `s` (`--stepover`)
//! removes, so the engagement is that of the straight cut at every step, the entry aside.
//!
//! **The entry.** The cells within a block (`4h`) of the largest wall distance are the
//! pocket's ridge. Where the ridge's principal axis `AB` is longer than twice the helix
//! radius `ρ` and every point of it lies `r + stock + ρ` (plus `2h`) from the walls, the
//! entry is a racetrack: the tool ramps down round the stadium of half-width `ρ` about `AB`
//! (whole laps at the ramp angle), then runs it once flat, clearing the stadium of
//! half-width `ρ + r` (`CutEntry::Lap`); elsewhere it is a helix of radius `ρ` at the ridge
//! cell nearest the ridge's centroid, clearing a disc of radius `ρ + r`. The first pass
//! starts on that loop. From a point, constant-engagement passes grow circles, which meet
//! the nearest walls long before the farthest; from the ridge they grow the stadium's
//! offsets, which meet a long pocket's walls together, leaving only the corners.
//!
//! **Passes and links.** Each pass starts where the tool, clear of material, touches it (a
//! block of a coarse distance-to-material map at `r` plus one to three blocks from the
//! nearest material, the block nearest the tool first), walked back along the material's
//! edge to where that edge begins; where the walk ends more than [`WALK_RETRY`] radii away at
//! a place no pass starts from (a narrow corner at the far end of a long edge, a sliver along
//! a wall too thin to count), at the first points of the walk, from its end, where a first
//! step bites, else at the block itself. The tool stays down and feeds there
//! in a straight line when every position of the line (at most `min(δ, 4h)` apart) is one the
//! tool centre may stand at, no step of it removes more than the target's share of its
//! length and no position's contact arc exceeds the target's engagement (mostly it cuts
//! nothing; a sliver a pass left at a wall), checked before the pass is cut; otherwise the
//! tool retracts and feeds down over cleared material (beside the pass's start, or on an
//! earlier cut within [`DIRECT_REACH`] radii) and leads in by a line that meets the same
//! rule, or, with none, ramps along the pass. (The pocket layer's own direct entries, whose
//! lead-in only stays inside the walls, are not used: this planner sees the material.) A
//! region the passes cannot reach (beyond an island, past a neck narrower than the tool)
//! gets an entry of its own. The
//! passes keep the tool centre a small margin farther from the walls than the tool-centre
//! region (the grid's distances hold to `h`); a last pass around each loop of the exact
//! tool-centre region (`r` plus the wall stock from the walls) cuts the band left there:
//! that margin, the scallops between passes meeting a wall, and the slivers thinner than
//! half the stepover that the passes leave along the walls (`pass::NEAR_WALL_CUT`). It is
//! linked from the last pass by the same rule; where that link would take in one step what
//! the last passes left at the loop's start, by the tool backing away from the wall (half a
//! radius or a radius) and feeding straight onto it, both checked as links; else it is
//! entered from above.
//!
//! **Both ways** (`AdaptiveOptions::both_ways`). A pass runs with the material on the
//! cutting side of the chosen direction. Passes that end at a wall (in a corner the grown
//! loops leave) then need a link back to the far end of the next one. With `both_ways`, a
//! pass may run the other way, the material on the other side: it does so where its start
//! is nearer the tool by more than `r`, so such passes are cut to and fro. The engagement's
//! bound is the same either way.
//!
//! Each pass's tool positions are smoothed (they wobble by the grid's count of cells, a few
//! hundredths of the target's area: Taubin's λ|μ smoothing moves each by at most
//! [`SMOOTH_RADII`] radii, scaled as below) and written as the chords between them (`δ` long,
//! the path itself, not an approximation of it; on a tight curve of a thin cut, with their
//! midpoints, below); with `--arcs`, as tangent-continuous biarcs
//! fitted within [`ARC_FIT`], kept only where they are faster (`pocket::arcs_or_chords`). The
//! chords are the default because the biarcs' curvature steps where two arcs meet, and a
//! jerk-limited controller slows at every such step. The field is then cleared along the
//! written path, so the next passes see what the program leaves; the engagement of the written
//! path differs from the planned one by at most about `SMOOTH_RADII·r / s` of the target (2.5 %
//! at a 40 % stepover) and the verifier measures it. Near the walls a smoothed position that
//! the tool may not stand at keeps its place.
//!
//! **Thin stepovers.** A step removes `s·δ/h²` cells. The count is good to a few cells and
//! the edge the previous pass left to half a cell, so at a fixed `h` the error grows as `1/s`
//! relative to the target: at 10 % (the CLI's default) a cell of `r/32` is a sixth of the
//! width cut, and the written path's engagement wandered past 1.1 × the target on up to 5 %
//! of the path. Below a stepover of [`FULL_CELL_STEPOVER`] of the diameter, with
//! `f = s / (0.4·D)` ([`thin_factor`]), the cell is `h = f^½·r/32` (at most four times the
//! cells; at 10 %, `r/64`) and smoothing moves a position by at most `f·`[`SMOOTH_RADII`]`·r`
//! (2.5 % of `s`, as at 40 %).
//!
//! **Chords on tight curves.** A chord of length `δ` on a curve of radius `R` lies `δ²/8R`
//! inside it. Where a thin cut bends tightly (a channel a little wider than the tool, combed
//! across by short curved passes), that sagitta is a real share of the width cut, and as two
//! passes' chords fall in and out of step the width swings from chord to chord: 10–20 % over
//! the target for a tenth of a millimetre after each vertex, which the verifier's 0.5 mm
//! window sees. Where the midpoint of the four-point subdivision (`(−a + 9b + 9c − d)/16`)
//! lies more than [`SAG_SHARE`]`·s` off a chord and the tool centre may stand there, it is
//! written too, which quarters the sagitta. At 40 % that takes a radius under about `1.6` mm
//! for this tool; at 10 %, under about `6` mm.
//!
//! **What is measured, and by whom.** The planner's counts are its own; the stock simulation
//! (`crate::stock`, another grid, another sweep) measures the engagement of the written path
//! and checks that nothing is left and nothing gouged, as for every strategy.

mod entry;
pub(crate) mod field;
pub(crate) mod pass;
mod smooth;
mod start;
mod tips;

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
use field::{Coarse, Field};
use pass::Stepper;
use smooth::{refined, smoothed};

/// The widest stepover the adaptive takes, a fraction of the tool's diameter (the straight
/// cut's engagement is then 143°; wider, the bound approaches a full slot's).
pub const MAX_STEPOVER: f64 = 0.9;
/// Grid cell, in tool radii, at a stepover of [`FULL_CELL_STEPOVER`] or more (thinner
/// stepovers take finer cells, [`thin_factor`]).
pub const CELL_RADII: f64 = 1.0 / 32.0;
/// The stepover, as a fraction of the tool's diameter, from which the grid's cell and the
/// smoothing's reach stay at [`CELL_RADII`] and [`SMOOTH_RADII`].
pub const FULL_CELL_STEPOVER: f64 = 0.4;
/// Step length, in tool radii.
pub const STEP_RADII: f64 = 1.0 / 8.0;
/// The share of the stepover's area each step aims at (the rest is the margin for the
/// grid's count and the arcs' fit).
pub const TARGET_FILL: f64 = 0.975;
/// How far the arcs joining a pass's positions may stray from them, in tool radii.
pub const ARC_FIT: f64 = 0.003;
/// How far smoothing may move a pass's positions, in tool radii, at a stepover of
/// [`FULL_CELL_STEPOVER`] or more (thinner stepovers in proportion, [`thin_factor`]).
pub const SMOOTH_RADII: f64 = 0.02;
/// Where a chord's subdivision midpoint lies farther than this share of the stepover off the
/// chord, it is written (a thin cut on a tight curve: the chords' sagittas made its width
/// swing from chord to chord).
pub const SAG_SHARE: f64 = 0.01;
/// Smoothing rounds (each a shrinking and an inflating Laplacian step).
const SMOOTH_ROUNDS: usize = 24;
/// The smallest helix, in tool radii: where there is less room, the entry is a ramp.
pub const MIN_HELIX_RADII: f64 = 0.1;
/// Longest ramp line where no helix fits, in tool radii.
pub const RAMP_REACH: f64 = 4.0;
/// The margin of material-free cells around a descent, beyond the tool's radius.
pub const DESCENT_CELLS: f64 = 3.0;
/// The largest contact arc a pass's step may have, as a multiple of the target's
/// engagement (the cells' count holds the area; the arc holds the angle where a thin sliver
/// wraps round the tool, in a corner).
pub const ARC_CAP: f64 = 1.05;
/// How far from a pass's start a direct entry may come down on an earlier cut, in tool
/// radii.
pub const DIRECT_REACH: f64 = 6.0;
/// A pass whose walk back along the material's edge ended farther than this from where it
/// began (in tool radii) and cut nothing there is tried again where the walk began.
pub const WALK_RETRY: f64 = 4.0;

/// Points of a walk back whose first step bites that are tried as a pass's start before the
/// block itself ([`WALK_RETRY`]).
const WALK_BITES: usize = 3;
/// Earlier cuts' points tried as a direct entry's descent, nearest first.
const DIRECT_TRIES: usize = 16;
/// A turn of the tool-centre region's boundary sharper than this is an acute corner (an
/// interior angle under 80°), rad: the passes near it cut the last slivers (`pass`), which
/// the walls' loop would meet head-on, and `tips` feeds into it.
pub const ACUTE_TURN: f64 = 100.0 * std::f64::consts::PI / 180.0;
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
    if s > MAX_STEPOVER * tool.diameter {
        return Err(crate::error::InputError::new("stepover", format!("{s} mm"))
            .at("--stepover with --strategy adaptive")
            .expected(format!(
                "at most {MAX_STEPOVER} of the tool's diameter ({} mm): the adaptive holds the \
                 engagement of a straight cut that wide, and a full slot bounds nothing",
                MAX_STEPOVER * tool.diameter
            ))
            .into());
    }
    let b = shape.outer.bounds();
    let span = (b.max.x - b.min.x + 4.0 * r) * (b.max.y - b.min.y + 4.0 * r);
    let thin = thin_factor(s, tool.diameter);
    let h = (CELL_RADII * thin.sqrt() * r).max((span / MAX_CELLS).sqrt());
    let mut field = Field::new(shape, h, 2.0 * h);
    let region = shape.offset(r + stock);
    let mut walls = Walls::new(shape, r + stock, h, 2.0 * ARC_FIT * r);
    walls.corners = sharp_corners(&region);
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
        target_angle: (1.0 - s / r).clamp(-1.0, 1.0).acos(),
        arc_cap: ARC_CAP * (1.0 - s / r).clamp(-1.0, 1.0).acos(),
        walls: &walls,
        side,
        max_steps: 10_000_000,
    };
    if region.is_empty() {
        return Err(crate::strategy::pocket::offset::too_large(tool).into());
    }
    let mut plan = Planner {
        field: &mut field,
        stepper,
        cuts: Vec::new(),
        pos: None,
        tried: Vec::new(),
        block_allowed: Vec::new(),
        band: Vec::new(),
        in_band: Vec::new(),
        fit: ARC_FIT * r,
        smooth: SMOOTH_RADII * thin * r,
        arcs: opts.spiral.arcs,
        both_ways: opts.adaptive.both_ways,
        given_up: Vec::new(),
        coarse: None,
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
    plan.tips(&region);
    plan.walls(&region, opts.direction);
    Ok(LevelPlan { cuts: plan.cuts })
}

/// The stepover `s` over [`FULL_CELL_STEPOVER`] of the tool's diameter `d`, at most 1 (and
/// exactly 1 within a part in a thousand of it). A step's area is `s·δ`: on a grid of cell
/// `h` its count is good to a few cells, and the width of the previous pass's edge to half a
/// cell, so a thin stepover needs finer cells to hold the same share of its target; the cell
/// shrinks with the square root of this factor (the cells a step removes, `s·δ/h²`, then
/// stay in proportion to `√s`) and the smoothing's reach with the factor itself (a share of
/// `s`, as at the full cell).
pub fn thin_factor(s: f64, d: f64) -> f64 {
    let f = s / (FULL_CELL_STEPOVER * d);
    if f >= 0.999 { 1.0 } else { f.max(0.0) }
}

/// A cut the tool reaches staying down ([`CutEntry::Linked`]): the link from `at`, where the
/// tool is, to `to`, then `path`.
fn linked_cut(at: Point, to: Point, path: Vec<Seg>) -> Cut {
    let mut linked = Vec::with_capacity(path.len() + 1);
    linked.push(Seg::line(at, to));
    linked.extend(path);
    Cut {
        entry: CutEntry::Linked,
        path: linked,
    }
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
    pub(crate) need: f64,
    /// The tool-centre region's acute corners (where its boundary turns by more than
    /// [`ACUTE_TURN`]).
    corners: Vec<Point>,
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
            corners: Vec::new(),
        }
    }

    /// True when `q` lies within `d` of an acute corner of the tool-centre region.
    pub(crate) fn near_corner(&self, q: Point, d: f64) -> bool {
        self.corners.iter().any(|c| c.distance(q) < d)
    }

    /// The distance from `q` to the walls: the grid's where it is sure to be beyond
    /// `need` by a cell or more, else the loops' exact distance.
    pub(crate) fn distance(&self, field: &Field, q: Point) -> f64 {
        let w = field.wall_distance(q);
        if field.sure_distance(q) >= self.sure + field.h {
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
        if field.sure_distance(q) >= self.sure {
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
    /// Per coarse block: 0 not yet known, 1 the tool centre may stand at its centre, 2 not.
    block_allowed: Vec<u8>,
    /// The blocks a pass may start from, tried or not ([`Planner::refresh_band`]).
    band: Vec<usize>,
    /// Per coarse block: in `band`.
    in_band: Vec<bool>,
    fit: f64,
    /// How far smoothing may move a position, mm.
    smooth: f64,
    /// Write the smoothed positions as biarcs (`--arcs`) instead of chords.
    arcs: bool,
    /// Passes may run either way ([`crate::strategy::pocket::AdaptiveOptions::both_ways`]).
    both_ways: bool,
    /// Where a disc of radius `r` was marked cleared on the field but left to the walls'
    /// loops (`entry::new_ramp`): the field holds no material there, the stock may.
    given_up: Vec<Point>,
    /// The last coarse distance-to-material map `start` made, with the field's count of
    /// material cells then.
    coarse: Option<(u64, Coarse)>,
}

impl<'w> Planner<'_, 'w> {
    /// Plans the next pass; false when nothing is left to clear.
    fn next_pass(&mut self, shape: &PocketShape, clear: f64, helix: f64) -> bool {
        let Some((p, theta, block)) = self.start() else {
            return self.new_helix(shape, clear, helix);
        };
        let (st, (q, heading), at_p) = self.side_for(p, theta);
        let mut done = self.pass_from(q, heading, st);
        // The walk back along the material's edge can end where no pass starts (a narrow
        // corner far along the edge, or a sliver the walls' loop takes before the material
        // thickens): from farther than [`WALK_RETRY`] radii, the pass is then tried where
        // the walk first met a bite, else where the block touches the material, before the
        // block is given up.
        if done.is_err() && q.distance(p) > WALK_RETRY * st.r {
            done = self.pass_on_walk(p, at_p, st);
        }
        if let Err(at) = done {
            self.tried[block] = true;
            self.mark_tried(at);
        }
        true
    }

    /// The stepper a pass touching the material at `p` (heading `theta` the chosen way) runs
    /// with, and where it starts: where the material's edge beside it begins, if the walk back
    /// ([`Stepper::upstream`]) finds it. With `both_ways`, the other way round (material on
    /// the other side, heading reversed) where its start is nearer the tool by more than
    /// the tool's radius. Last, the heading at `p` the way chosen.
    fn side_for(&self, p: Point, theta: f64) -> (Stepper<'w>, (Point, f64), f64) {
        let (field, st) = (&*self.field, self.stepper);
        let ahead = (
            st,
            st.upstream(field, p, theta).unwrap_or((p, theta)),
            theta,
        );
        let Some(here) = self.pos.filter(|_| self.both_ways) else {
            return ahead;
        };
        let mut rev = st;
        rev.side = -st.side;
        let back = theta + std::f64::consts::PI;
        let need = st.first_bite_need(field, p);
        if !rev.first_bite_reaches(field, p, back, need) {
            return ahead;
        }
        let other = rev.upstream(field, p, back).unwrap_or((p, back));
        if other.0.distance(here) + st.r < ahead.1.0.distance(here) {
            (rev, other, back)
        } else {
            ahead
        }
    }

    /// A pass on the walk back from `p` (heading `theta`) to where the material's edge
    /// begins, tried from that end towards `p` at the first points whose first step bites
    /// ([`WALK_BITES`] of them), else at `p` itself.
    fn pass_on_walk(&mut self, p: Point, theta: f64, st: Stepper<'w>) -> Result<(), Point> {
        let trail = st.upstream_trail(self.field, p, theta).unwrap_or_default();
        let mut tries = 0;
        for (k, &(c, heading)) in trail.iter().rev().step_by(2).enumerate() {
            if tries == WALK_BITES || c.distance(p) <= WALK_RETRY * st.r {
                break;
            }
            let need = st.first_bite_need(self.field, c);
            if !st.first_bite_reaches(self.field, c, heading, need) {
                continue;
            }
            tries += 1;
            // The walk's end is where the caller's pass just failed, on the same field: it
            // counts as tried without running that pass again.
            if k > 0 && self.pass_from(c, heading, st).is_ok() {
                return Ok(());
            }
        }
        self.pass_from(p, theta, st)
    }

    /// A pass from `p` heading `theta` run by `st`, appended to the plan; where it cuts
    /// nothing, the point it started from.
    fn pass_from(&mut self, p: Point, theta: f64, st: Stepper<'w>) -> Result<(), Point> {
        self.field.record();
        let (pts, removed) = st.run(self.field, p, theta);
        if removed == 0 || pts.len() < 2 {
            self.field.undo();
            return Err(p);
        }
        let path = self.fitted(&pts);
        self.field.undo();
        // The link, and the lead-in from a direct entry's descent, are checked against the
        // material before the pass cuts; where no descent beside the start has a lead-in that
        // a link may take, one on an earlier cut is tried, else the pass is ramped into.
        let linked = self.pos.filter(|&at| self.link_clear(at, pts[0], false));
        let from = if linked.is_some() {
            None
        } else {
            self.descent_near(&pts)
                .filter(|&f| self.link_clear(f, pts[0], false))
                .or_else(|| self.descent_on_earlier(pts[0]))
        };
        if self.cut_along(&path) == 0 {
            return Err(p);
        }
        if let Some(at) = linked {
            self.field.clear_capsule(at, pts[0], self.stepper.r);
        }
        self.join(&pts, path, from, linked);
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
        let within = self.smooth;
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
                    let tau = SAG_SHARE * self.stepper.s;
                    let fine = refined(&smooth, tau, |q| walls.allows(field, q));
                    let chords = segs_from_points(&fine);
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

    /// Appends a pass's positions to the plan: linked from `linked` (where the tool is, when
    /// the link was found clear), else as a new cut entered directly, the tool feeding down
    /// at `from`, or, with no clear point to feed down at, ramped along the pass itself.
    fn join(&mut self, pts: &[Point], path: Vec<Seg>, from: Option<Point>, linked: Option<Point>) {
        let start = pts[0];
        match (linked, self.cuts.last_mut()) {
            (Some(at), Some(_)) if at.distance(start) > 1e-9 => {
                self.cuts.push(linked_cut(at, start, path));
            }
            (Some(_), Some(cut)) => cut.path.extend(path),
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

    /// A point of an earlier cut of the level (swept at this depth, so the tool feeds down
    /// through air there) within [`DIRECT_REACH`] tool radii of `start`, whose lead-in to it
    /// is a clear link: the nearest of the cuts' segments' nearest points, at most
    /// [`DIRECT_TRIES`] of them tried.
    fn descent_on_earlier(&mut self, start: Point) -> Option<Point> {
        let reach = DIRECT_REACH * self.stepper.r;
        let mut cands: Vec<(f64, Point)> = self
            .cuts
            .iter()
            .flat_map(|c| c.path.iter())
            .map(|sg| sg.closest_point(start))
            .map(|q| (q.distance(start), q))
            .filter(|c| c.0 <= reach)
            .collect();
        cands.sort_by(|a, b| a.0.total_cmp(&b.0));
        cands
            .into_iter()
            .take(DIRECT_TRIES)
            .map(|c| c.1)
            .find(|&q| self.link_clear(q, start, false))
    }

    /// True when the tool may feed from `a` to `b` at depth: every position along the way
    /// (at most `min(δ, h·4)` apart) is one the tool centre may stand at (`b` aside when
    /// `to_wall`: a walls' loop's start lies on the tool-centre region's edge), and no step
    /// removes more than the target's share of its length, and no position's contact arc
    /// ([`Field::contact_arc`]) is wider than the target's engagement (the link's engagement
    /// is bounded as a pass's is; mostly it removes nothing, or a sliver the passes left at
    /// a wall).
    fn link_clear(&mut self, a: Point, b: Point, to_wall: bool) -> bool {
        let st = self.stepper;
        let len = a.distance(b);
        let n = ((len / st.delta.min(4.0 * self.field.h)).ceil() as usize).max(1);
        let per_step = st.target * (len / n as f64) / st.delta;
        let Some(u) = (b - a).normalize() else {
            return true;
        };
        self.field.record();
        let mut ok = true;
        for k in 1..=n {
            let q = a.lerp(b, k as f64 / n as f64);
            let exempt = to_wall && k == n;
            if !exempt && !st.walls.allows(self.field, q) {
                ok = false;
                break;
            }
            if f64::from(self.field.clear_disc(q, st.r)) > per_step
                || self.field.contact_arc(q, u, st.r) > st.target_angle
            {
                ok = false;
                break;
            }
        }
        self.field.undo();
        ok
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

    /// Where the tool at `at` may back away to, straight from `to` (the walls' loop's start),
    /// half a radius or a radius, so that both the way back and the straight feed from there
    /// to `to` are links ([`Planner::link_clear`]); `None` where neither is.
    fn back_off(
        &mut self,
        region: &crate::strategy::pocket::shape::OffsetRegion,
        at: Point,
        to: Point,
    ) -> Option<Point> {
        let u = (at - to).normalize()?;
        let r = self.stepper.r;
        [0.5 * r, r].into_iter().map(|d| at + u * d).find(|&b| {
            !crosses(region, at, b)
                && !crosses(region, b, to)
                && self.link_clear(at, b, false)
                && self.link_clear(b, to, true)
        })
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
            let linked = self.pos.filter(|&at| {
                !crosses(region, at, first)
                    && (at.distance(first) < 1e-3 || self.link_clear(at, first, true))
            });
            // Else the tool may back away from the wall and feed straight onto the loop's
            // start, where a link there directly would take what is left in one step.
            let dogleg = match (linked, self.pos) {
                (None, Some(at)) if !self.cuts.is_empty() => {
                    self.back_off(region, at, first).map(|b| (at, b))
                }
                _ => None,
            };
            match (linked, dogleg, self.cuts.last_mut()) {
                (Some(at), _, Some(_)) if at.distance(first) > 1e-9 => {
                    self.cuts.push(linked_cut(at, first, path));
                }
                (Some(_), _, Some(cut)) => cut.path.extend(path),
                (_, Some((at, b)), _) => {
                    let mut lead = vec![Seg::line(b, first)];
                    lead.extend(path);
                    self.cuts.push(linked_cut(at, b, lead));
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

/// The vertices where a loop of `region` turns by more than [`ACUTE_TURN`].
fn sharp_corners(region: &crate::strategy::pocket::shape::OffsetRegion) -> Vec<Point> {
    let mut out = Vec::new();
    for lp in region.loops() {
        let segs = segs_from_vertices(&closed_chain(lp));
        for (k, sg) in segs.iter().enumerate() {
            let next = &segs[(k + 1) % segs.len()];
            let (Some(t0), Some(t1)) = (
                sg.tangent_at(sg.length()).normalize(),
                next.tangent_at(0.0).normalize(),
            ) else {
                continue;
            };
            if t0.cross(t1).atan2(t0.dot(t1)).abs() > ACUTE_TURN {
                out.push(sg.b);
            }
        }
    }
    out
}
