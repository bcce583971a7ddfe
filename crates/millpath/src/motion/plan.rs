//! The look-ahead planner: blocks → spans → knot speeds → S-curve profiles → a timed plan.
//!
//! # Spans and knots
//! Consecutive blocks whose junction does not bind (the junction cap is at least both blocks'
//! speed caps) and whose speed caps are equal form one **span**: the S-curve runs through
//! their junctions without constraint. The span's path acceleration and jerk limits are the
//! smallest of its blocks' (conservative where the direction changes within the span; blocks
//! whose limits differ by more than a factor 2 are separated by a knot instead). A
//! **knot** separates spans; its speed cap is the junction cap (and both spans' caps); the
//! program's start and end, dwells and exact stops are knots at speed 0.
//!
//! # Look-ahead
//! The profiles have zero acceleration at knots, so a span of length `L` can take the
//! velocity from `v` to at most `reach(v, L)`, the inverse of the S-curve distance
//! ([`super::profile::reachable_velocity`], closed form). A backward pass
//! `v_k ← min(v_k, reach(v_{k+1}, L_k))` and a forward pass
//! `v_{k+1} ← min(v_{k+1}, reach(v_k, L_k))` over the whole program make every span
//! feasible; each span then gets the time-optimal profile between its knot speeds
//! ([`super::profile::SpanProfile`]), which is checked against its limits before it is
//! accepted.
//!
//! # What this is and is not optimal for
//! Given the knots, every span is exactly time-optimal. Forcing zero acceleration at a knot
//! is what a time-optimal profile does where the speed touches a cap (at a velocity minimum or
//! plateau); it is conservative where a knot's speed is not reached, e.g. a short span that
//! accelerates through a junction into a span with a higher cap. Memory is a few words per
//! block and per span; time is linear in the number of blocks.

use super::controller::{Prepared, Shaper};
use super::path::BlockGeometry;
use super::profile::{Limits1, SpanProfile, reachable_velocity};
use crate::error::Error;
use crate::geom::Point3;
use crate::machine::Machine;
use crate::toolpath::{Move, MoveKind, Toolpath};

/// Options of [`plan_moves`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PlanOptions {
    /// Keep each block's geometry in the plan (needed by [`Plan::sample`]; costs ~100 bytes per
    /// block).
    pub keep_geometry: bool,
    /// Check every span profile against its limits before accepting it.
    pub check_profiles: bool,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            keep_geometry: true,
            check_profiles: true,
        }
    }
}

impl PlanOptions {
    /// Sets [`PlanOptions::keep_geometry`].
    #[must_use]
    pub fn with_keep_geometry(mut self, keep_geometry: bool) -> Self {
        self.keep_geometry = keep_geometry;
        self
    }

    /// Sets [`PlanOptions::check_profiles`].
    #[must_use]
    pub fn with_check_profiles(mut self, check_profiles: bool) -> Self {
        self.check_profiles = check_profiles;
        self
    }
}

/// One planned block (one move of the input).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockPlan {
    /// The kind of move.
    pub kind: MoveKind,
    /// Path length in mm.
    pub length: f64,
    /// Time at the start of the block in s.
    pub start_time: f64,
    /// Duration in s.
    pub time: f64,
    /// Highest path speed reached in the block, mm/s.
    pub peak_feed: f64,
    /// Programmed feed in mm/s (0 for rapids and dwells).
    pub programmed_feed: f64,
    /// The span the block belongs to.
    pub span: u32,
    /// Distance from the start of the span to the start of the block.
    pub span_offset: f64,
    /// The input move this block times: its own index, except where the controller model
    /// reshapes the path (the `linuxcnc` model's blend arcs, trimmed and merged moves; see
    /// `super::controller`).
    pub origin: usize,
}

/// One span: blocks sharing one S-curve profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// First block.
    pub first: usize,
    /// One past the last block.
    pub end: usize,
    /// Time at the start of the span.
    pub start_time: f64,
    /// Length in mm.
    pub length: f64,
    /// Knot speed at the start.
    pub v0: f64,
    /// Knot speed at the end.
    pub v1: f64,
    /// Path limits of the span.
    pub limits: Limits1,
    /// Dwell time (a dwell span has no length).
    pub dwell: f64,
    /// Time spent at rest after the span when it ends in a stop (the controller's
    /// exact-stop settling, [`crate::machine::Machine::exact_stop_time`]), counted in its
    /// last block.
    pub settle: f64,
}

impl Span {
    /// The span's profile (recomputed: plans store only the knot speeds).
    pub fn profile(&self) -> Result<SpanProfile, Error> {
        SpanProfile::new(self.v0, self.v1, self.length, self.limits)
    }
}

/// A timed plan of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Name of the machine it was planned for.
    pub machine: String,
    /// The blocks: one per input move, except where the controller model reshapes the path
    /// (`reshaped`; each block's [`BlockPlan::origin`] names its move).
    pub blocks: Vec<BlockPlan>,
    /// The spans.
    pub spans: Vec<Span>,
    /// Geometry of each block (if kept), `None` for dwells and zero-length moves.
    pub geometry: Vec<Option<BlockGeometry>>,
    /// Start and end point of each block (if geometry is kept).
    pub ends: Vec<(Point3, Point3)>,
    /// Total time in s.
    pub total_time: f64,
    /// The controller model reshaped the path (the `linuxcnc` model's blend arcs, trimmed
    /// and merged moves): blocks are not the input moves, and the limit verifier, which
    /// checks the moves, does not apply.
    pub reshaped: bool,
}

impl Plan {
    /// The cycle time in s.
    pub fn total_time(&self) -> f64 {
        self.total_time
    }

    /// The highest feed reached on each of the first `moves` input moves (0 where a move
    /// has no block of its own: a dwell, a zero-length move, a move merged into a later one).
    pub fn peak_feed_by_move(&self, moves: usize) -> Vec<f64> {
        let mut out = vec![0.0; moves];
        for b in &self.blocks {
            if let Some(v) = out.get_mut(b.origin) {
                *v = f64::max(*v, b.peak_feed);
            }
        }
        out
    }
}

/// The incremental half of the planner: blocks are pushed one at a time and grouped into
/// spans; [`time_spans`] then times spans whose knot speeds are known. [`plan_moves`] pushes
/// a whole program, [`super::stream`] a window at a time.
pub(crate) struct Builder {
    /// Open spans (block indices global).
    pub(crate) spans: Vec<Span>,
    /// Knot speed caps: `knots[k]` is the cap at the start of `spans[k]`.
    pub(crate) knots: Vec<f64>,
    /// Global index of `spans[0]` (spans already timed and dropped by a streaming caller).
    pub(crate) span_base: usize,
    last: Option<Limits1>,
}

impl Builder {
    pub(crate) fn new() -> Self {
        Builder {
            spans: Vec::new(),
            knots: Vec::new(),
            span_base: 0,
            last: None,
        }
    }

    fn open(&mut self, first: usize, knot: f64, lim: Limits1) {
        self.knots.push(knot);
        self.spans.push(Span {
            first,
            end: first,
            start_time: 0.0,
            length: 0.0,
            v0: 0.0,
            v1: 0.0,
            limits: lim,
            dwell: 0.0,
            settle: 0.0,
        });
    }

    /// The last span, if it ends at rest, waits `t` s more there.
    pub(crate) fn settle_last(&mut self, t: f64) {
        if let Some(s) = self.spans.last_mut() {
            s.settle += t;
        }
    }

    /// Adds block `i` (one prepared by the controller model) to the spans; returns its
    /// untimed block.
    pub(crate) fn push(&mut self, i: usize, p: &Prepared) -> Result<BlockPlan, Error> {
        let zero = Limits1 {
            v: 0.0,
            a: 1.0,
            j: 1.0,
        };
        let m = &p.mv;
        let length = p.geom.as_ref().map_or(0.0, BlockGeometry::length);
        if p.settle_before > 0.0 {
            self.settle_last(p.settle_before);
        }
        let mut span_offset = 0.0;
        match (&p.geom, m.kind) {
            (_, MoveKind::Dwell { seconds }) => {
                self.open(i, 0.0, zero);
                if let Some(s) = self.spans.last_mut() {
                    s.dwell = seconds;
                }
                self.last = None;
            }
            (Some(_), _) => {
                let lim = p.limits;
                if !(lim.v > 0.0 && lim.a > 0.0 && lim.j > 0.0) {
                    return Err(Error::internal(format!("block {i}: limits {lim:?}")));
                }
                let join = match &self.last {
                    Some(pl) => {
                        let cap = p.cap_in;
                        let vmin = pl.v.min(lim.v);
                        let same = (pl.v - lim.v).abs() <= 1e-12 * lim.v;
                        // Blocks with very different path acceleration or jerk limits (a line
                        // into an arc) get a knot (a = 0) rather than sharing the smaller
                        // limit over a whole span; with `exact_limits` (a controller that
                        // runs each block at its own acceleration) any difference does.
                        let f = if p.exact_limits { 1.0 + 1e-12 } else { 2.0 };
                        let near = |x: f64, y: f64| x <= f * y && y <= f * x;
                        let alike = near(pl.a, lim.a)
                            && ((pl.j.is_infinite() && lim.j.is_infinite()) || near(pl.j, lim.j));
                        if same && alike && cap >= vmin {
                            None
                        } else {
                            Some(cap.min(vmin))
                        }
                    }
                    None => Some(0.0),
                };
                match join {
                    Some(knot) => self.open(i, knot, lim),
                    None => {
                        if let Some(s) = self.spans.last_mut() {
                            s.limits.a = s.limits.a.min(lim.a);
                            s.limits.j = s.limits.j.min(lim.j);
                        }
                    }
                }
                if let Some(s) = self.spans.last_mut() {
                    span_offset = s.length;
                    s.length += length;
                }
                self.last = Some(lim);
            }
            (None, _) => {
                if let Some(s) = self.spans.last() {
                    span_offset = s.length;
                }
            }
        }
        if let Some(s) = self.spans.last_mut() {
            s.end = i + 1;
        }
        let span = (self.span_base + self.spans.len()).saturating_sub(1);
        Ok(BlockPlan {
            kind: m.kind,
            length,
            start_time: 0.0,
            time: 0.0,
            peak_feed: 0.0,
            programmed_feed: if m.is_feed() { m.feed } else { 0.0 },
            span: u32::try_from(span).unwrap_or(u32::MAX),
            span_offset,
            origin: p.origin,
        })
    }
}

/// Pins the knots on both sides of a dwell span (a span without length) to 0; `knots` has one
/// more entry than `spans`.
pub(crate) fn pin_dwells(spans: &[Span], knots: &mut [f64]) {
    for (k, s) in spans.iter().enumerate() {
        if s.length <= 0.0 {
            for i in [k, k + 1] {
                if let Some(v) = knots.get_mut(i) {
                    *v = 0.0;
                }
            }
        }
    }
}

/// Times `spans` (knot speeds final: `knots[k]` and `knots[k + 1]` bound `spans[k]`) from
/// time `t0`, and their blocks (`blocks[0]` is global block `block_base`); returns the end
/// time.
pub(crate) fn time_spans(
    spans: &mut [Span],
    knots: &[f64],
    blocks: &mut [BlockPlan],
    block_base: usize,
    t0: f64,
    check: bool,
) -> Result<f64, Error> {
    let mut t = t0;
    for (k, s) in spans.iter_mut().enumerate() {
        s.v0 = knots.get(k).copied().unwrap_or(0.0);
        s.v1 = knots.get(k + 1).copied().unwrap_or(0.0);
        s.start_time = t;
        let first = s.first.saturating_sub(block_base);
        let end = s.end.saturating_sub(block_base);
        if s.length <= 0.0 {
            if let Some(bp) = blocks.get_mut(first) {
                bp.start_time = t;
                bp.time = s.dwell;
            }
            t += s.dwell;
            continue;
        }
        let p = SpanProfile::new(s.v0, s.v1, s.length, s.limits)?;
        if check {
            p.check(s.limits)?;
        }
        let mut tb = 0.0;
        let settle = if s.v1 <= 0.0 { s.settle } else { 0.0 };
        let n_blocks = end.saturating_sub(first);
        for (k, bp) in blocks
            .get_mut(first..end)
            .unwrap_or_default()
            .iter_mut()
            .enumerate()
        {
            let te = if bp.span_offset + bp.length >= s.length {
                p.duration
            } else {
                p.time_at(bp.span_offset + bp.length)
            };
            bp.start_time = t + tb;
            bp.time = (te - tb).max(0.0) + if k + 1 == n_blocks { settle } else { 0.0 };
            let tpk = p.t_peak.clamp(tb, te);
            bp.peak_feed = if bp.length > 0.0 { p.state(tpk).v } else { 0.0 };
            tb = te;
        }
        t += p.duration + settle;
    }
    Ok(t)
}

/// Plans a toolpath with the default options.
pub fn plan_toolpath(tp: &Toolpath, machine: &Machine) -> Result<Plan, Error> {
    plan_toolpath_opt(tp, machine, &PlanOptions::default())
}

/// Plans a toolpath.
pub fn plan_toolpath_opt(
    tp: &Toolpath,
    machine: &Machine,
    opts: &PlanOptions,
) -> Result<Plan, Error> {
    plan_moves(tp.segments().map(|(f, m)| Ok((f, *m))), machine, opts)
}

/// Plans any stream of `(from, move)` pairs (a G-code reader's output, for instance); the
/// first error of the stream is returned as is.
pub fn plan_moves<I>(moves: I, machine: &Machine, opts: &PlanOptions) -> Result<Plan, Error>
where
    I: IntoIterator<Item = Result<(Point3, Move), Error>>,
{
    machine.validate(&machine.name)?;
    let mut blocks = Vec::new();
    let mut geometry = Vec::new();
    let mut ends = Vec::new();
    let mut b = Builder::new();
    let mut shaper = Shaper::new(machine);
    let mut prepared = Vec::new();
    let mut take = |prepared: &mut Vec<Prepared>, b: &mut Builder| -> Result<(), Error> {
        for p in prepared.drain(..) {
            blocks.push(b.push(blocks.len(), &p)?);
            if opts.keep_geometry {
                geometry.push(p.geom);
                ends.push((p.from, p.mv.to));
            }
        }
        Ok(())
    };
    for (i, item) in moves.into_iter().enumerate() {
        let (from, m) = item?;
        shaper.push(i, from, &m, &mut prepared)?;
        take(&mut prepared, &mut b)?;
    }
    let settle = shaper.finish(&mut prepared)?;
    take(&mut prepared, &mut b)?;
    b.settle_last(settle);
    b.knots.push(0.0);
    let Builder {
        mut spans,
        mut knots,
        ..
    } = b;
    pin_dwells(&spans, &mut knots);
    // Look-ahead: backward then forward.
    for k in (0..spans.len()).rev() {
        let s = &spans[k];
        let r = reachable_velocity(knots[k + 1], s.length, s.limits.a, s.limits.j);
        knots[k] = knots[k].min(r).min(s.limits.v);
    }
    for k in 0..spans.len() {
        let s = &spans[k];
        let r = reachable_velocity(knots[k], s.length, s.limits.a, s.limits.j);
        knots[k + 1] = knots[k + 1].min(r).min(s.limits.v);
    }
    let t = time_spans(&mut spans, &knots, &mut blocks, 0, 0.0, opts.check_profiles)?;
    Ok(Plan {
        reshaped: machine.controller == crate::machine::Controller::LinuxCnc,
        machine: machine.name.clone(),
        blocks,
        spans,
        geometry,
        ends,
        total_time: t,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::verify::{VerifyOptions, verify_plan};
    use crate::toolpath::{Corner, Plane};
    use proptest::prelude::*;

    fn plan_and_verify(moves: &[(Point3, Move)], machine: &Machine) -> Result<usize, Error> {
        let plan = plan_moves(
            moves.iter().map(|x| Ok(*x)),
            machine,
            &PlanOptions::default(),
        )?;
        let rep = verify_plan(&plan, moves, machine, &VerifyOptions::default())?;
        Ok(rep.violations)
    }

    /// Root cause of the fuzzer's 32 mm position jump: an arc whose start point is its centre
    /// (radius 0) was skipped as a zero-length move although its end is elsewhere.
    #[test]
    fn arc_starting_at_its_centre_is_refused() {
        let m = Machine::preset("hsm").unwrap();
        let c = Point3::new(1.0, 2.0, 0.0);
        let arc = Move::arc_xy(Point3::new(20.0, -3.0, -4.0), c, true, 50.0);
        let moves = [(c, arc)];
        match plan_and_verify(&moves, &m) {
            Err(Error::Input(e)) => {
                let msg = e.to_string();
                assert!(
                    msg.contains("arc start radius") && msg.contains("move 1"),
                    "{msg}"
                );
            }
            other => panic!("expected an input error, got {other:?}"),
        }
        // A full circle of radius 0 that goes nowhere is a zero-length move, not an error.
        let still = [(c, Move::arc_xy(c, c, true, 50.0))];
        assert_eq!(plan_and_verify(&still, &m).unwrap(), 0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Root cause of the fuzzer's acceleration, jerk, feed and corner violations on arcs:
        /// spiral arcs (end radius off the start circle within the G-code tolerance, tiny arcs
        /// whose radius changes many times over) were timed as circles, and the planner and
        /// the verifier parametrised them by different lengths. Lines joined by spiral arcs of
        /// every size, in every plane and corner mode, on every preset, plan with 0
        /// violations.
        #[test]
        fn spiral_arcs_plan_within_the_limits(
            preset in 0usize..3,
            arcs in proptest::collection::vec(
                (-8.0f64..0.0, 0.2f64..5.0, -3.0f64..3.0, -3.0f64..3.0, 0usize..3, any::<bool>(),
                 0usize..4, 1.0f64..300.0, -1.0f64..1.0),
                1..5),
        ) {
            let m = Machine::preset(Machine::PRESET_NAMES[preset]).unwrap();
            let mut at = Point3::ORIGIN;
            let mut moves = Vec::new();
            for (lr, ratio, a0, a1, plane, ccw, corner, feed, dz) in arcs {
                let plane = [Plane::Xy, Plane::Zx, Plane::Yz][plane];
                let r0 = 10f64.powf(lr).max(1e-6) * 10.0;
                // Keep the end radius within the planner's acceptance (LinuxCNC's rule).
                let tau = crate::toolpath::arc_rule::CENTER_ARC_RADIUS_TOLERANCE_MM;
                let lim = (0.9 * tau).max(0.9e-3 * r0);
                let r1 = r0 + (r0 * ratio - r0).clamp(-lim, lim);
                let c = at - plane.join(r0 * a0.cos(), r0 * a0.sin(), 0.0);
                let to = c + plane.join(r1 * a1.cos(), r1 * a1.sin(), dz * r0);
                let corner = [Corner::Machine, Corner::ExactPath, Corner::ExactStop, Corner::Blend(0.01)][corner];
                let mut mv = Move::arc_xy(to, c, ccw, feed).with_corner(corner);
                if let MoveKind::Arc { plane: p, .. } = &mut mv.kind {
                    *p = plane;
                }
                moves.push((at, mv));
                at = to;
                let next = at + crate::geom::Vec3::new(3.0 * a1.sin(), 2.0, dz);
                moves.push((at, Move::line(next, feed).with_corner(corner)));
                at = next;
            }
            match plan_and_verify(&moves, &m) {
                Ok(n) => prop_assert_eq!(n, 0),
                Err(Error::Input(_)) => {}
                Err(e) => prop_assert!(false, "internal error {e}"),
            }
        }
    }
}
