//! One adaptive pass: the tool steps along the material's edge, each step turned so that it
//! removes the target area.
//!
//! From `p` with heading `θ`, a step of length `δ` turned by `φ` towards the material side
//! ends at `q(φ) = p + δ·(cos(θ ∓ φ), sin(θ ∓ φ))` (`∓`: the material lies on the right of
//! a climb cut, on the left of a conventional one). With the disc at `p` already cleared, the
//! material the tool meets between `p` and `q` is the material within `r` of `q`
//! (`A(φ)`, counted on the field); a straight cut of radial width `a_e` removes `a_e·δ`, so
//! holding `A(φ) = a_e·δ` holds the engagement of a straight cut of width `a_e`, which is how
//! `--stepover` reads for this strategy. `A` grows as the step turns into the material, so
//! the step taken is the largest turn on a grid of [`TURNS`] whose area is at most the
//! target, refined by bisection towards the next turn up. Turns are bounded (at most
//! [`MAX_INTO`] into the material per step, [`MAX_AWAY`] away from it): the path's radius of
//! curvature stays above `δ / MAX_INTO`.
//!
//! The tool centre stays where the field's wall distance is at least `reach`. The pass ends
//! where every allowed step would cut more than [`OVERLOAD`] times the target (the
//! material closes in around the tool), where no step is allowed (a wall ahead), or after
//! [`AIR_RADII`] tool radii of steps that cut less than [`MIN_CUT`] of it (the material ran
//! out); the steps after its last cut are dropped.

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

    /// The step from `p` heading `theta`, or `None` where the pass must end.
    fn choose(&self, field: &Field, p: Point, theta: f64) -> Option<Step> {
        let turn = |k: usize| -MAX_AWAY + (MAX_INTO + MAX_AWAY) * k as f64 / TURNS as f64;
        let tries: Vec<(f64, Option<Step>)> = (0..=TURNS)
            .map(|k| (turn(k), self.at(field, p, theta, turn(k))))
            .collect();
        // The largest turn at or below the target, and the allowed turn just above it.
        let mut below: Option<(f64, Step)> = None;
        let mut above: Option<(f64, Step)> = None;
        for &(phi, st) in &tries {
            if let Some(st) = st {
                if st.area <= self.target {
                    below = Some((phi, st));
                    above = None;
                } else if above.is_none() {
                    above = Some((phi, st));
                }
            }
        }
        match (below, above) {
            (Some((mut lo, mut best)), Some((mut hi, _))) if hi > lo => {
                for _ in 0..6 {
                    let mid = 0.5 * (lo + hi);
                    match self.at(field, p, theta, mid) {
                        Some(st) if st.area <= self.target => {
                            lo = mid;
                            best = st;
                        }
                        _ => hi = mid,
                    }
                }
                Some(best)
            }
            (Some((_, best)), _) => Some(best),
            (None, _) => tries
                .iter()
                .filter_map(|t| t.1)
                .min_by(|a, b| a.area.total_cmp(&b.area))
                .filter(|st| st.area <= OVERLOAD * self.target),
        }
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
        for _ in 0..self.max_steps {
            let Some(st) = self.choose(field, p, theta) else {
                break;
            };
            if st.area < min_cut {
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

    /// The most cells the first step from `p` heading `theta` can remove.
    pub(crate) fn first_bite(&self, field: &Field, p: Point, theta: f64) -> f64 {
        (0..=TURNS)
            .filter_map(|k| {
                let phi = -MAX_AWAY + (MAX_INTO + MAX_AWAY) * k as f64 / TURNS as f64;
                self.at(field, p, theta, phi)
            })
            .map(|s| s.area)
            .fold(0.0, f64::max)
    }

    /// Where the material's edge that the tool at `p` (heading `theta`, clear of material and
    /// touching it) would follow begins: the edge walked backwards, the disc of radius
    /// `r + s/2` overlapping the material by `s/2` (the edge `r` from its centre), until the
    /// material ends beside it or a wall stops it; the point and the cutting heading there.
    /// `None` when the walk comes back round (a closed edge: start anywhere) or gets lost.
    pub(crate) fn upstream(&self, field: &Field, p: Point, theta: f64) -> Option<(Point, f64)> {
        let big = self.r + 0.5 * self.s;
        let depth = 0.5 * self.s;
        let seg = big * big * (1.0 - depth / big).acos()
            - (big - depth) * (2.0 * big * depth - depth * depth).sqrt();
        let goal = seg / (field.h * field.h);
        let (mut q, mut beta) = (p, theta + std::f64::consts::PI);
        let mut travel = 0.0;
        let turns = 16;
        let max_turn = 1.0;
        loop {
            let mut best: Option<(Point, f64, f64)> = None;
            let mut most: f64 = 0.0;
            for k in 0..=turns {
                let phi = -max_turn + 2.0 * max_turn * k as f64 / turns as f64;
                let b = beta + self.side * phi;
                let c = q + Vec2::new(b.cos(), b.sin()) * self.delta;
                if !self.walls.allows(field, c) {
                    continue;
                }
                let n = f64::from(field.count_disc(c, big));
                most = most.max(n);
                if n <= goal {
                    best = Some((c, b, n));
                }
            }
            match best {
                Some((c, b, _)) if most >= 0.3 * goal => {
                    q = c;
                    beta = b;
                    travel += self.delta;
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
        (travel > 0.0).then_some((q, beta + std::f64::consts::PI))
    }
}
