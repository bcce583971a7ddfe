//! One adaptive pass: the tool steps along the material's edge, each step turned so that it
//! removes the target area.
//!
//! From `p` with heading `θ`, a step of length `δ` turned by `φ` towards the material side
//! ends at `q(φ) = p + δ·(cos(θ ∓ φ), sin(θ ∓ φ))` (`∓`: the material lies on the right of
//! a climb cut, on the left of a conventional one). With the disc at `p` already cleared, the
//! material the tool meets between `p` and `q` is the material within `r` of `q`
//! (`A(φ)`, counted on the field); a straight cut of radial width `a_e` removes `a_e·δ`, so
//! holding `A(φ) = a_e·δ` holds the engagement of a straight cut of width `a_e`, which is how
//! `--stepover` reads for this strategy. The area holds the angle only where the material's
//! edge is smooth: where a thin sliver wraps round the tool (a corner the passes cut short) a
//! small area touches a wide arc, so a step must also keep the tool's contact arc (the arc of
//! its front half over material, `Field::contact_arc`) within `arc_cap` (`ARC_CAP` times the
//! straight cut's engagement `acos(1 − a_e/r)`). Both grow as the step turns into the
//! material, so the step taken is the turn where either crosses its bound on a grid of
//! [`TURNS`] turns,
//! found by walking the grid from the last step's turn (the path's turn changes little from
//! one step to the next: two or three counts instead of the whole grid), refined by
//! bisection towards the next turn up. Turns are bounded (at most
//! [`MAX_INTO`] into the material per step, [`MAX_AWAY`] away from it): the path's radius of
//! curvature stays above `δ / MAX_INTO`.
//!
//! The tool centre stays where the field's wall distance is at least `reach`. The pass ends
//! where every allowed step would cut more than [`OVERLOAD`] times the target (the
//! material closes in around the tool), where no step is allowed (a wall ahead), or after
//! [`AIR_RADII`] tool radii of steps that cut less than [`MIN_CUT`] of it (the material ran
//! out; within the stepover of the tool-centre region's edge, away from its acute corners,
//! a step must cut [`NEAR_WALL_CUT`] of the target to count: the thinner sliver along a wall
//! or in a square corner is the walls' loop's, while in an acute corner the loop would meet
//! it head-on); the steps after its last cut are dropped.

use super::Walls;
use super::field::Field;
use crate::geom::{Point, Vec2};

/// The turns tried at each step, as fractions of the range from `−MAX_AWAY` to `MAX_INTO`.
pub(crate) const TURNS: usize = 24;
/// Largest turn into the material per step, rad.
pub(crate) const MAX_INTO: f64 = 0.8;
/// Largest turn away from the material per step, rad.
pub(crate) const MAX_AWAY: f64 = 1.2;
/// A step that would cut more than this many times the target is not taken.
pub(crate) const OVERLOAD: f64 = 1.15;
/// A step cutting less than this share of the target cuts nothing worth a pass.
pub(crate) const MIN_CUT: f64 = 0.03;
/// Travel without a cut that ends a pass, in tool radii.
pub(crate) const AIR_RADII: f64 = 10.0;
/// Within the stepover of the tool-centre region's edge, a step cutting less than this share
/// of the target cuts nothing worth a pass: the sliver is the walls' loop's.
pub(crate) const NEAR_WALL_CUT: f64 = 0.5;

/// Halvings of a step's turn between two grid turns.
const BISECTIONS: usize = 6;

/// The stepper's settings.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stepper<'w> {
    /// Where the tool centre may go.
    pub walls: &'w Walls<'w>,
    /// Tool radius, mm.
    pub r: f64,
    /// Step length, mm.
    pub delta: f64,
    /// Target cells removed per step.
    pub target: f64,
    /// The stepover, mm.
    pub s: f64,
    /// The engagement of a straight cut of width `s`, rad.
    pub target_angle: f64,
    /// The largest contact arc a step may have ([`Field::contact_arc`]), rad.
    pub arc_cap: f64,
    /// +1: material on the right (climb), −1: on the left.
    pub side: f64,
    /// Most steps in one pass.
    pub max_steps: usize,
}

/// One step's choice.
#[derive(Debug, Clone, Copy)]
struct Step {
    q: Point,
    heading: f64,
    area: f64,
}

impl Stepper<'_> {
    fn at(&self, field: &Field, p: Point, theta: f64, phi: f64) -> Option<Step> {
        let heading = theta - self.side * phi;
        let q = p + Vec2::new(heading.cos(), heading.sin()) * self.delta;
        self.walls.allows(field, q).then(|| Step {
            q,
            heading,
            area: f64::from(field.count_disc(q, self.r)),
        })
    }

    /// The step from `p` heading `theta`, or `None` where the pass must end; with the grid
    /// index of the turn taken, the next step's `hint`.
    ///
    /// The search starts at the grid turn `hint` (the last step's: the path's turn changes
    /// little from step to step) and walks the grid towards the target: up while the area
    /// stays at or below it, down while it is above, to the first crossing, then bisects
    /// between the two turns. Only where no turn of the walk is at or below the target is the
    /// whole grid scanned, as a pass's first step is.
    fn choose(&self, field: &Field, p: Point, theta: f64, hint: usize) -> Option<(Step, usize)> {
        let turn = |k: usize| -MAX_AWAY + (MAX_INTO + MAX_AWAY) * k as f64 / TURNS as f64;
        let eval = |k: usize| self.at(field, p, theta, turn(k));
        // The arc is read only where the area passes (it costs more than the count).
        let arc = |st: &Step| {
            field.contact_arc(st.q, Vec2::new(st.heading.cos(), st.heading.sin()), self.r)
        };
        let fits = |st: &Step| st.area <= self.target && arc(st) <= self.arc_cap;
        let ok = |st: &Option<Step>| st.is_some_and(|st| fits(&st));
        let hint = hint.min(TURNS);
        // `below`: the crossing's turn at or below the target; `above`: the allowed turn
        // just past it.
        let mut below: Option<(usize, Step)> = None;
        let mut above: Option<usize> = None;
        let first = eval(hint);
        if ok(&first) {
            below = first.map(|st| (hint, st));
            for k in hint + 1..=TURNS {
                match eval(k) {
                    None => {}
                    Some(st) if fits(&st) => below = Some((k, st)),
                    Some(_) => {
                        above = Some(k);
                        break;
                    }
                }
            }
        } else {
            if first.is_some() {
                above = Some(hint);
            }
            for k in (0..hint).rev() {
                match eval(k) {
                    None => {}
                    Some(st) if fits(&st) => {
                        below = Some((k, st));
                        break;
                    }
                    Some(_) => above = Some(k),
                }
            }
        }
        let Some((kb, mut best)) = below else {
            // No turn at or below the target: the least overloaded allowed one, or none.
            return (0..=TURNS)
                .filter_map(|k| eval(k).map(|st| (st, k)))
                .filter(|(st, _)| arc(st) <= OVERLOAD * self.arc_cap)
                .min_by(|a, b| a.0.area.total_cmp(&b.0.area))
                .filter(|(st, _)| st.area <= OVERLOAD * self.target);
        };
        if let Some(ka) = above {
            let (mut lo, mut hi) = (turn(kb), turn(ka));
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                match self.at(field, p, theta, mid) {
                    Some(st) if fits(&st) => {
                        lo = mid;
                        best = st;
                    }
                    _ => hi = mid,
                }
            }
        }
        Some((best, kb))
    }

    /// Runs a pass from `p0` heading `theta0`, clearing the field behind the tool; the tool
    /// positions from `p0` to the last that cut, and the cells removed.
    pub(crate) fn run(&self, field: &mut Field, p0: Point, theta0: f64) -> (Vec<Point>, u64) {
        let mut pts = vec![p0];
        let mut removed = u64::from(field.clear_disc(p0, self.r));
        let (mut p, mut theta) = (p0, theta0);
        let mut last_cut = 0;
        let mut air = 0.0;
        let min_cut = MIN_CUT * self.target;
        let near_cut = NEAR_WALL_CUT * self.target;
        let near = self.walls.clear + self.s;
        let mut hint = TURNS / 2;
        for _ in 0..self.max_steps {
            let Some((st, k)) = self.choose(field, p, theta, hint) else {
                break;
            };
            hint = k;
            let floor = if field.wall_distance(st.q) < near
                && !self.walls.near_corner(st.q, self.r + self.s)
            {
                near_cut
            } else {
                min_cut
            };
            if st.area < floor {
                air += self.delta;
                if air > AIR_RADII * self.r {
                    break;
                }
            } else {
                air = 0.0;
                last_cut = pts.len();
            }
            removed += u64::from(field.clear_disc(st.q, self.r));
            pts.push(st.q);
            p = st.q;
            theta = st.heading;
        }
        pts.truncate(last_cut + 1);
        (pts, removed)
    }

    /// The cells a pass's first step from `p` must remove to start there: [`MIN_CUT`] of the
    /// target, or 0.3 of it within `r` of the tool-centre region's edge (a sliver there is the
    /// walls' loop's).
    pub(crate) fn first_bite_need(&self, field: &Field, p: Point) -> f64 {
        let deep = field.wall_distance(p) >= self.walls.clear + self.r;
        (if deep { MIN_CUT } else { 0.3 }) * self.target
    }

    /// True when some first step from `p` heading `theta` removes at least `need` cells
    /// (the turns tried from the one deepest into the material, which usually bites most).
    pub(crate) fn first_bite_reaches(
        &self,
        field: &Field,
        p: Point,
        theta: f64,
        need: f64,
    ) -> bool {
        (0..=TURNS).rev().any(|k| {
            let phi = -MAX_AWAY + (MAX_INTO + MAX_AWAY) * k as f64 / TURNS as f64;
            self.at(field, p, theta, phi)
                .is_some_and(|s| s.area >= need)
        })
    }

    /// Where the material's edge that the tool at `p` (heading `theta`, clear of material and
    /// touching it) would follow begins: the edge walked backwards, the disc of radius
    /// `r + s/2` overlapping the material by `s/2` (the edge `r` from its centre), until the
    /// material ends beside it or a wall stops it; the point and the cutting heading there.
    /// `None` when the walk comes back round (a closed edge: start anywhere) or gets lost.
    pub(crate) fn upstream(&self, field: &Field, p: Point, theta: f64) -> Option<(Point, f64)> {
        self.upstream_trail(field, p, theta)
            .and_then(|t| t.last().copied())
    }

    /// The walk of [`Stepper::upstream`], step by step: the points it passed, from the first
    /// step after `p` to where the edge begins, each with the cutting heading there.
    pub(crate) fn upstream_trail(
        &self,
        field: &Field,
        p: Point,
        theta: f64,
    ) -> Option<Vec<(Point, f64)>> {
        let big = self.r + 0.5 * self.s;
        let depth = 0.5 * self.s;
        let seg = big * big * (1.0 - depth / big).acos()
            - (big - depth) * (2.0 * big * depth - depth * depth).sqrt();
        let goal = seg / (field.h * field.h);
        let (mut q, mut beta) = (p, theta + std::f64::consts::PI);
        let mut travel = 0.0;
        let mut trail = Vec::new();
        let turns = 16;
        let max_turn = 1.0;
        let mut hint = turns / 2;
        loop {
            // The largest turn whose disc overlaps the material by at most the goal, found
            // from the last step's turn as [`Stepper::choose`] does; the whole fan only where
            // no turn past it overlaps more (then the material must still be beside the walk:
            // the most any turn overlaps at least 0.3 of the goal).
            let at = |k: usize| {
                let b = beta + self.side * (-max_turn + 2.0 * max_turn * k as f64 / turns as f64);
                let c = q + Vec2::new(b.cos(), b.sin()) * self.delta;
                self.walls
                    .allows(field, c)
                    .then(|| (c, b, f64::from(field.count_disc(c, big))))
            };
            let mut best: Option<(Point, f64, usize)> = None;
            let mut beyond = false;
            let first = at(hint);
            match first {
                Some((c, b, n)) if n <= goal => {
                    best = Some((c, b, hint));
                    for k in hint + 1..=turns {
                        match at(k) {
                            None => {}
                            Some((c, b, n)) if n <= goal => best = Some((c, b, k)),
                            Some(_) => {
                                beyond = true;
                                break;
                            }
                        }
                    }
                }
                _ => {
                    beyond = first.is_some();
                    for k in (0..hint).rev() {
                        match at(k) {
                            None => {}
                            Some((c, b, n)) if n <= goal => {
                                best = Some((c, b, k));
                                break;
                            }
                            Some(_) => beyond = true,
                        }
                    }
                }
            }
            let enough = beyond || (0..=turns).filter_map(at).any(|(_, _, n)| n >= 0.3 * goal);
            match best {
                Some((c, b, k)) if enough => {
                    q = c;
                    beta = b;
                    hint = k;
                    travel += self.delta;
                    trail.push((q, beta + std::f64::consts::PI));
                }
                _ => break,
            }
            if travel > 4.0 * self.delta && q.distance(p) < 2.0 * self.delta {
                return None;
            }
            if travel > 1e5 * self.r {
                return None;
            }
        }
        (travel > 0.0).then_some(trail)
    }
}
