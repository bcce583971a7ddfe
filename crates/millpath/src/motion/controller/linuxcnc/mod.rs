//! The `linuxcnc` controller model: LinuxCNC 2.9's trajectory planner (`src/emc/tp/`,
//! `src/emc/task/emccanon.cc`, commit f1270d6ed7), read from its source and reproduced rule
//! by rule. Its cycle times are checked against LinuxCNC itself
//! (`../shared/tools/linuxcnc-time`, `tests/controller_linuxcnc.rs`; figures in
//! BENCHMARKS.md).
//!
//! # What LinuxCNC does with a program
//! 1. **Canon** (`canon.rs`): each line gets `v = min(F, axis speeds projected)` and the axis
//!    accelerations projected (`a = |d| / maxᵢ(|dᵢ|/aᵢ)`); each arc the speed cap
//!    `√(0.866·a·r)` (`a` the smaller acceleration of its plane's axes, `r` the effective
//!    radius of a spiral or helix) and the plane's acceleration. In `G64` with a merge
//!    tolerance (`Q`, defaulting to `P`) runs of nearly collinear G1 points become one line.
//! 2. **Queue** (`queue.rs`, `tpAddLine`/`tpAddCircle`): every segment is capped at
//!    `v ≤ L/T` (`T` the servo period), and at `L/(1.02·T)` once the look-ahead has seen it
//!    (`TP_MIN_SEGMENT_CYCLES`), so that it lasts at least one cycle — blend arcs and the
//!    stubs of lines between blends included. At each junction, in this order:
//!    * rapid ↔ feed, `G61.1` and reversals within 2°: **stop**;
//!    * the **tangent test**: the acceleration a one-cycle direction change at the slower
//!      segment's feed would take, `(v/T + a₂)·|u₂ − u₁|`, over each axis's acceleration (twice
//!      that next to an arc); below `ARC_BLEND_KINK_RATIO` (0.1) the junction is taken as
//!      tangent at full speed, both segments losing that share of their acceleration;
//!      otherwise its **kink speed** is `v·0.1/ratio`;
//!    * in `G64`: a **blend arc** (`blend.rs`), unless it cannot be made (it would leave the
//!      tolerance or its segments, not coplanar with an arc, a helix); then the best of the
//!      blend arc's speed, the kink speed and half the **parabolic blend** speed
//!      (`tpChooseBestBlend`). A parabolic blend overlaps the two segments, each at half its
//!      acceleration; its speed is bounded by `2√(a·P/cos θ)` and by what each segment
//!      reaches over half its length (`tpComputeBlendVelocity`);
//!    * in `G61`: stop, unless the tangent test passes.
//! 3. **Look-ahead** (`tpRunOptimization`): a backward pass from the newest segment, which
//!    may lose up to half its length to its own blend (so the speed before it is at most
//!    `√(a·L)`), reaching at most `ARC_BLEND_OPTIMIZATION_DEPTH` = 50 segments back. A
//!    segment's final speed is therefore what the next 50 segments allow: a dense chord path
//!    goes only as fast as it could stop within them.
//! 4. **Run time** (`tpRunCycle`): a trapezoid on each segment towards its final speed at its
//!    tangential acceleration — the axis acceleration on lines, half of it on arcs and blend
//!    arcs (`BLEND_ACC_RATIO_TANGENTIAL`; more on large arcs below their speed cap), half
//!    again on both sides of a parabolic blend and on a segment that ends the program or a
//!    run before a dwell (its mode is still `G64`, with nothing to blend into).
//!
//! # How the model gives it to the planner
//! The queue is run as LinuxCNC runs it, a segment at a time, and a segment leaves it once no
//! later segment can change it (53 behind the newest). Each becomes a planner block with its
//! own geometry (lines trimmed by blends, circles shortened, blend arcs as
//! [`BlockGeometry::Arc3`]), the limits `v = min(F, maxvel)`, `a` =
//! its tangential acceleration, jerk unlimited, and the junction cap LinuxCNC would end it at:
//! its look-ahead final speed at tangent junctions, 0 at stops, and for a parabolic blend the
//! speed at which the overlap starts (the overlap moves at about that speed: one segment
//! slows from it to rest while the other speeds up to it), the overlapping stretches of the
//! two segments given as pieces no faster than that (`overlap.rs`). The planner's trapezoids
//! between those speeds are what `tpRunCycle` runs, cycle by cycle.
//!
//! # Rotary axes (trivkins: A, B, C each its own joint)
//! A move that turns A, B or C ([`crate::toolpath::Move::rotary`]) is a segment in the joint
//! space X Y Z A B C, as LinuxCNC 2.9's `PmLine9` with `trivkins`: its length is the X Y Z
//! distance, or the rotary chord (rad) when only rotary axes move; its speed and acceleration
//! are bounded by every moving axis's limits (`canon.rs`; the machine's
//! [`crate::machine::Machine::rotary`]); the feed is along that length (the reader gives a
//! rotary-only move its feed in rad/s). Next to a segment that turns a rotary axis there is no
//! tangency and no blend arc (`tcRotaryMotionCheck` in `tpSetupTangent` and
//! `tpCheckBlendArcType`): in G64 the corner is a parabolic blend, in G61 a stop. The
//! `[TRAJ]` speed limit does not apply to rotary-only segments (`tcPureRotaryCheck`). A
//! rotary-only block is a [`BlockGeometry::Line`] that stays in place (`dir` zero) whose
//! length is the rotary chord, in degrees as LinuxCNC measures it (its feed in deg/s).
//!
//! # What is not modelled
//! * The queue is assumed to run ahead of the motion (LinuxCNC's task feeds it one segment a
//!   servo cycle; a program of segments shorter than one cycle at speed can starve it).
//! * Parabolic blends are timed as an overlap at one speed, not cycle by cycle; short
//!   segments' "ramp" acceleration (segments shorter than 10 ms) as a trapezoid.
//! * Rotary axes with other kinematics than trivkins (LinuxCNC's `xyzac-trt` and the like,
//!   switched by `M428`): the tool tip's path is not the joints' path there.
//! * Spindle, coolant and tool commands, which make LinuxCNC's task wait for motion to stop,
//!   are not in the move stream; dwells are (they stop the queue).
//! * The program starts at rest where the reader starts (LinuxCNC's tool is where the last
//!   program left it).

mod blend;
mod canon;
mod circle;
mod overlap;
mod queue;

use super::Prepared;
use crate::error::Error;
use crate::geom::Point3;
use crate::machine::Machine;
use crate::motion::path::BlockGeometry;
use crate::motion::profile::Limits1;
use crate::toolpath::{Move, MoveKind, Rotary};
use canon::{Chain, Mode};
use queue::{OPTIMIZATION_DEPTH, Term, Tp};

/// Segments held behind the newest before one leaves the queue: the look-ahead reaches
/// `OPTIMIZATION_DEPTH + 1` back, a blend changes the last two.
const HOLD: usize = OPTIMIZATION_DEPTH + 3;

/// LinuxCNC's canon and segment queue, fed one move at a time.
pub(crate) struct Queue<'m> {
    machine: &'m Machine,
    tp: Tp,
    chain: Chain,
    /// Feed and mode of the held run.
    chain_feed: f64,
    chain_mode: Option<Mode>,
    /// Junction cap of the next block to leave.
    pending_cap: f64,
    /// Its overlap with the block before (a parabolic blend): length and speed.
    pending_head: (f64, f64),
    /// Dwells waiting for the next motion.
    dwells: Vec<Prepared>,
    /// Where the rotary axes stand after the last move (they start at 0).
    rot: Rotary,
}

impl<'m> Queue<'m> {
    pub(crate) fn new(machine: &'m Machine) -> Self {
        Queue {
            machine,
            tp: Tp::new(machine),
            chain: Chain::default(),
            chain_feed: 0.0,
            chain_mode: None,
            pending_cap: 0.0,
            pending_head: (0.0, 0.0),
            dwells: Vec::new(),
            rot: Rotary::default(),
        }
    }

    /// Takes move `i` (geometry `g`, checked); appends the blocks that are final to `out`.
    pub(crate) fn push(
        &mut self,
        i: usize,
        from: Point3,
        m: &Move,
        g: Option<BlockGeometry>,
        out: &mut Vec<Prepared>,
    ) -> Result<(), Error> {
        let mode = Mode::of(m.corner, self.machine);
        let r0 = self.rot;
        let r1 = m.rotary.unwrap_or(r0);
        self.rot = r1;
        let turns = queue::turns(r0, r1);
        match m.kind {
            MoveKind::Dwell { .. } => {
                self.flush_chain();
                self.drain(out);
                // Held until a motion follows: LinuxCNC's motion time ends at rest after the
                // last motion (a trailing M5 or G4 is not timed).
                self.dwells.push(Prepared {
                    from,
                    mv: *m,
                    geom: None,
                    limits: Limits1 {
                        v: 0.0,
                        a: 1.0,
                        j: 1.0,
                    },
                    cap_in: 0.0,
                    origin: i,
                    exact_limits: true,
                    settle_before: 0.0,
                });
                return Ok(());
            }
            MoveKind::Rapid => {
                self.flush_chain();
                if g.is_some() || turns {
                    self.add_line((from, r0), (m.to, r1), 0.0, true, i, m, mode);
                }
            }
            MoveKind::Line => {
                if g.is_some() || turns {
                    self.see((from, r0), (m.to, r1), i, m, mode);
                }
            }
            MoveKind::Arc { .. } => {
                let merged = match canon::chord_deviation(from, m) {
                    Some((dev, mid)) if mode.term == Term::Parabolic && dev < mode.merge => {
                        let half = |a: f64, b: f64| (a + b) / 2.0;
                        let r_mid =
                            Rotary::new(half(r0.a, r1.a), half(r0.b, r1.b), half(r0.c, r1.c));
                        self.see((from, r0), (mid, r_mid), i, m, mode);
                        self.see((mid, r_mid), (m.to, r1), i, m, mode);
                        true
                    }
                    _ => false,
                };
                if !merged {
                    self.flush_chain();
                    if let Some(g) = g
                        && let Some(mut tc) =
                            canon::arc(&g, (from, r0), (m.to, r1), m.feed, self.machine)
                    {
                        tc.term = mode.term;
                        tc.tolerance = mode.tolerance;
                        tc.origin = i;
                        tc.mv = *m;
                        self.tp.add(tc);
                    }
                }
            }
        }
        if !(self.tp.queue.is_empty() && self.chain.points.is_empty()) {
            // (after a zero-length move they stay held)
            out.append(&mut self.dwells);
        }
        self.emit(out, HOLD);
        Ok(())
    }

    /// The end of the program: everything held leaves, the last segment ending at rest.
    pub(crate) fn finish(&mut self, out: &mut Vec<Prepared>) -> Result<(), Error> {
        self.flush_chain();
        self.drain(out);
        Ok(())
    }

    /// `see_segment`: a G1 point into the naive-CAM run; a point that turns the rotary axes
    /// is sent at once, alone.
    fn see(
        &mut self,
        from: (Point3, Rotary),
        to: (Point3, Rotary),
        i: usize,
        m: &Move,
        mode: Mode,
    ) {
        // A new feed (LinuxCNC compares it exactly) or path mode sends the run first.
        let same = self.chain_mode == Some(mode) && self.chain_feed.to_bits() == m.feed.to_bits();
        let joins = same && mode.term == Term::Parabolic && self.chain.linkable(to, mode.merge);
        if !joins {
            self.flush_chain();
        }
        if self.chain.points.is_empty() {
            self.chain.start = from;
        }
        self.chain.points.push((to, i, *m));
        self.chain_feed = m.feed;
        self.chain_mode = Some(mode);
        if to.1 != self.chain.start.1 {
            self.flush_chain();
        }
    }

    /// `flush_segments`: the held run as one line.
    fn flush_chain(&mut self) {
        let Some(&(to, i, m)) = self.chain.points.last() else {
            return;
        };
        let from = self.chain.start;
        self.chain.points.clear();
        if let Some(mode) = self.chain_mode {
            self.add_line(from, to, m.feed, false, i, &m, mode);
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn add_line(
        &mut self,
        from: (Point3, Rotary),
        to: (Point3, Rotary),
        feed: f64,
        rapid: bool,
        i: usize,
        m: &Move,
        mode: Mode,
    ) {
        if let Some(mut tc) = canon::line(from, to, feed, rapid, self.machine) {
            tc.term = mode.term;
            tc.tolerance = mode.tolerance;
            tc.origin = i;
            tc.mv = *m;
            self.tp.add(tc);
        }
    }

    /// Everything held leaves (the queue runs empty: program end, dwell).
    fn drain(&mut self, out: &mut Vec<Prepared>) {
        self.emit(out, 0);
        self.pending_cap = 0.0;
        self.pending_head = (0.0, 0.0);
    }

    /// Segments more than `hold` behind the newest leave the queue as planner blocks.
    fn emit(&mut self, out: &mut Vec<Prepared>, hold: usize) {
        while self.tp.queue.len() > hold {
            let Some(tc) = self.tp.queue.pop_front() else {
                break;
            };
            let next = self.tp.queue.front();
            let cap_out = self.tp.junction(&tc, next);
            // A parabolic blend overlaps the two segments (module `overlap`).
            let (tail, head_next) = match next {
                Some(n) if tc.term == Term::Parabolic && cap_out > 0.0 => (
                    (cap_out * cap_out / (2.0 * tc.tangential_accel()), cap_out),
                    (cap_out * cap_out / (2.0 * n.tangential_accel()), cap_out),
                ),
                _ => ((0.0, 0.0), (0.0, 0.0)),
            };
            // A rotary-only segment is in degrees (module `canon`), its feed too.
            let feed = if tc.pure_rotary() {
                tc.mv.feed.to_degrees()
            } else {
                tc.mv.feed
            };
            let block = Prepared {
                from: tc.start(),
                mv: Move {
                    to: tc.end(),
                    feed,
                    ..tc.mv
                },
                geom: tc.geom(),
                limits: self.tp.limits(&tc),
                cap_in: self.pending_cap,
                origin: tc.origin,
                exact_limits: true,
                settle_before: 0.0,
            };
            overlap::cut(
                &overlap::Leaving {
                    block,
                    head: self.pending_head,
                    tail,
                },
                out,
            );
            self.pending_cap = cap_out;
            self.pending_head = head_next;
        }
    }
}
