//! Sampling a plan in time: position, path speed and per-axis velocity, acceleration, jerk.
//!
//! With `P(s)` the block's geometry by arc length and `s(t)` the span's profile,
//! `v = P'·ṡ`, `a = P''·ṡ² + P'·s̈`, `j = P'''·ṡ³ + 3P''·ṡ·s̈ + P'·s⃛`.
//!
//! **Stretches.** Between the knots of a plan (span starts, the phases of each span's
//! profile, block starts, the rest after a span's profile) the block is one and `s(t)` one
//! cubic: `s⃛` constant, `s̈` linear, `ṡ` quadratic. Over such a stretch the largest `ṡ` is at
//! its ends or where `s̈ = 0`, the largest `|s̈|` at its ends ([`Stretch::peaks`]), so a
//! sampler that bounds a block's geometry can tell from three states whether any sample in
//! the stretch could exceed a limit ([`Plan::for_each_sparse_path_sample`]).

use super::plan::{BlockPlan, Plan};
use super::profile::{SpanProfile, State1};
use crate::error::Error;
use crate::geom::Point3;

/// One sample of a plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time in s.
    pub t: f64,
    /// Index of the block (move) being executed.
    pub block: usize,
    /// Distance travelled within the block, mm.
    pub s: f64,
    /// The path state (s from the span start, speed, acceleration, jerk along the path).
    pub path: State1,
    /// Position.
    pub position: Point3,
    /// Path speed (feed) in mm/s.
    pub feed: f64,
    /// Per-axis velocity.
    pub vel: [f64; 3],
    /// Per-axis acceleration.
    pub acc: [f64; 3],
    /// Per-axis jerk.
    pub jerk: [f64; 3],
}

/// Where the plan is at one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PathSample {
    /// Time in s.
    pub t: f64,
    /// Index of the block being executed.
    pub block: usize,
    /// Distance travelled within the block, mm.
    pub s: f64,
    /// The path state (s from the span start, speed, acceleration, jerk along the path).
    pub path: State1,
}

/// A stretch of a plan (module docs): one block, and one phase of its span's profile (or the
/// rest after it), over which the path state is one cubic in time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stretch {
    /// The block.
    pub block: usize,
    /// The path samples at its start (the phase's own state there, after a jump of `s̈`) and
    /// at its end, in the block.
    pub ends: [PathSample; 2],
    /// The path sample inside it where `s̈` changes sign, if it does.
    pub turn: Option<PathSample>,
}

impl Stretch {
    /// The largest `ṡ`, `|s̈|` and `|s⃛|` over the stretch: `ṡ` at its ends and turn, `|s̈|`
    /// at its ends, `s⃛` constant (the largest of the three samples').
    pub(crate) fn peaks(&self) -> (f64, f64, f64) {
        let all = self.ends.iter().chain(self.turn.as_ref());
        all.fold((0.0_f64, 0.0_f64, 0.0_f64), |(v, a, j), p| {
            (
                v.max(p.path.v.abs()),
                a.max(p.path.a.abs()),
                j.max(p.path.j.abs()),
            )
        })
    }
}

/// How near a knot (relative to its time) a dense sample is taken whatever the stretch's
/// bounds: the dense sampler finds a sample's phase by subtracting the phases' durations and
/// its block by distance, which may put a sample within rounding of a knot on its other side.
const KNOT_SLACK: f64 = 1e-9;

/// [`KNOT_SLACK`] at time `t`, s.
fn knot_slack(t: f64) -> f64 {
    KNOT_SLACK * t.abs().max(1.0)
}

/// The samples every `dt` seconds a dense sampler takes ([`Plan::for_each_path_sample`]),
/// taken or passed over in time order.
struct Grid {
    dt: f64,
    total: f64,
    /// The next sample's index, and the last one's.
    next: usize,
    last: usize,
    /// The dense sampler's span and cursor.
    span: usize,
    cursor: Cursor,
}

impl Grid {
    fn time(&self, i: usize) -> f64 {
        (i as f64 * self.dt).min(self.total)
    }

    /// True when the next sample lies before `end` (or at it, when `at_end`).
    fn before(&self, end: f64, at_end: bool) -> bool {
        self.next <= self.last && {
            let t = self.time(self.next);
            t < end || (at_end && t <= end)
        }
    }

    /// Takes the samples before `end` (at it too when `at_end`), as the dense sampler does.
    fn take<F>(&mut self, plan: &Plan, end: f64, at_end: bool, f: &mut F) -> Result<(), Error>
    where
        F: FnMut(&PathSample) -> Result<(), Error>,
    {
        while self.before(end, at_end) {
            let t = self.time(self.next);
            while plan
                .spans
                .get(self.span + 1)
                .is_some_and(|s| s.start_time <= t && s.length > 0.0 || s.start_time < t)
            {
                self.span += 1;
            }
            f(&plan.path_sample_in(self.span, t, &mut self.cursor)?)?;
            self.next += 1;
        }
        Ok(())
    }

    /// Passes over the samples before `end`; how many.
    fn pass(&mut self, end: f64) -> usize {
        let from = self.next;
        while self.before(end, false) {
            self.next += 1;
        }
        self.next - from
    }
}

/// Where a sampler is in a plan: the span whose profile it holds (with the state at each
/// phase start) and how many of that span's blocks start at or before the last distance
/// looked up. Successive lookups move the count forward or back a block at a time from where
/// the last one left it (a binary search when the span changes), so sampling in time order
/// costs O(1) per sample whatever the span's length; the count is always the one a binary
/// search over the span's block offsets gives.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Cursor {
    span: Option<usize>,
    profile: SpanProfile,
    starts: [State1; 7],
    count: usize,
}

impl Cursor {
    /// The path state of span `k` of `plan` at time `t`.
    fn state(&mut self, plan: &Plan, k: usize, t: f64) -> Result<State1, Error> {
        let Some(span) = plan.spans.get(k) else {
            return Err(Error::internal("sampling an empty plan"));
        };
        if self.span != Some(k) {
            self.profile = if span.length > 0.0 {
                span.profile()?
            } else {
                SpanProfile::default()
            };
            self.starts = self.profile.phase_starts();
            self.span = Some(k);
            self.count = usize::MAX;
        }
        Ok(self.profile.state_from(&self.starts, t - span.start_time))
    }

    /// How many of `blocks` (a span's, offsets non-decreasing) start at or before `s`.
    fn count_at(&mut self, blocks: &[BlockPlan], s: f64) -> usize {
        let mut c = self.count;
        if c > blocks.len() {
            c = blocks.partition_point(|b| b.span_offset <= s);
        } else {
            while blocks.get(c).is_some_and(|b| b.span_offset <= s) {
                c += 1;
            }
            while c > 0 && blocks.get(c - 1).is_some_and(|b| b.span_offset > s) {
                c -= 1;
            }
        }
        self.count = c;
        c
    }
}

impl Plan {
    /// The state at time `t` (clamped to the plan). Needs the plan's geometry
    /// ([`super::PlanOptions::keep_geometry`]).
    pub fn state_at(&self, t: f64) -> Result<Sample, Error> {
        self.sample_in(self.span_at(t), t, &mut Cursor::default())
    }

    /// The span whose start is the last at or before `t`.
    fn span_at(&self, t: f64) -> usize {
        self.spans
            .partition_point(|s| s.start_time <= t)
            .saturating_sub(1)
    }

    /// The path state (distance from the span start, ṡ, s̈, s⃛) at time `t`, as
    /// [`Plan::state_at`] gives it; `cursor` keeps the span's profile between calls.
    pub(crate) fn path_state_at(&self, t: f64, cursor: &mut Cursor) -> Result<State1, Error> {
        cursor.state(self, self.span_at(t), t)
    }

    fn sample_in(&self, k: usize, t: f64, cursor: &mut Cursor) -> Result<Sample, Error> {
        let p = self.path_sample_in(k, t, cursor)?;
        self.sample_of(&p)
    }

    /// Where the plan is at time `t` in span `k`: the block and the path state.
    fn path_sample_in(&self, k: usize, t: f64, cursor: &mut Cursor) -> Result<PathSample, Error> {
        if self.geometry.len() != self.blocks.len() {
            return Err(Error::internal("plan sampled without its geometry"));
        }
        let st = cursor.state(self, k, t)?;
        let Some(span) = self.spans.get(k) else {
            return Err(Error::internal("sampling an empty plan"));
        };
        // The block containing st.s: the last one with positive length starting at or
        // before it.
        let blocks = self.blocks.get(span.first..span.end).unwrap_or_default();
        let mut n = cursor.count_at(blocks, st.s).saturating_sub(1);
        while n > 0 && blocks.get(n).is_some_and(|b| b.length <= 0.0) {
            n -= 1;
        }
        let block = span.first + n;
        let offset = self.blocks.get(block).map_or(0.0, |b| b.span_offset);
        Ok(PathSample {
            t,
            block,
            s: st.s - offset,
            path: st,
        })
    }

    /// The whole sample (position, per-axis velocity, acceleration and jerk) of a path
    /// sample.
    pub(crate) fn sample_of(&self, p: &PathSample) -> Result<Sample, Error> {
        let (geom, (from, _)) = match (self.geometry.get(p.block), self.ends.get(p.block)) {
            (Some(g), Some(e)) => (g, *e),
            _ => return Err(Error::internal("block index out of range")),
        };
        let (s, st) = (p.s, p.path);
        let (position, vel, acc, jerk) = match geom {
            Some(g) => {
                let [p0, d1, d2, d3] = g.derivatives(s);
                let v = d1 * st.v;
                let a = d2 * (st.v * st.v) + d1 * st.a;
                let j = d3 * st.v.powi(3) + d2 * (3.0 * st.v * st.a) + d1 * st.j;
                (
                    Point3::ORIGIN + p0,
                    v.to_array(),
                    a.to_array(),
                    j.to_array(),
                )
            }
            None => (from, [0.0; 3], [0.0; 3], [0.0; 3]),
        };
        Ok(Sample {
            t: p.t,
            block: p.block,
            s,
            path: st,
            position,
            feed: st.v,
            vel,
            acc,
            jerk,
        })
    }

    /// Samples the plan every `dt` seconds from 0 to the total time (both included).
    pub fn sample(&self, dt: f64) -> Result<Vec<Sample>, Error> {
        let mut out = Vec::new();
        self.for_each_sample(dt, |s| {
            out.push(s);
            Ok(())
        })?;
        Ok(out)
    }

    /// Calls `f` with a sample every `dt` seconds from 0 to the total time (both included),
    /// without storing them (memory independent of the program's duration).
    pub fn for_each_sample<F>(&self, dt: f64, mut f: F) -> Result<(), Error>
    where
        F: FnMut(Sample) -> Result<(), Error>,
    {
        self.for_each_path_sample(dt, |p| f(self.sample_of(p)?))
    }

    /// [`Plan::for_each_sample`]'s samples, only where the plan is (time, block, distance
    /// into the block, path state): for samplers that evaluate the geometry themselves.
    pub(crate) fn for_each_path_sample<F>(&self, dt: f64, mut f: F) -> Result<(), Error>
    where
        F: FnMut(&PathSample) -> Result<(), Error>,
    {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(crate::InputError::new("sample interval", dt)
                .expected("a finite number of seconds > 0")
                .into());
        }
        if self.spans.is_empty() {
            return Ok(());
        }
        let n = (self.total_time / dt).ceil() as usize;
        let mut k = 0;
        let mut cursor = Cursor::default();
        for i in 0..=n {
            let t = (i as f64 * dt).min(self.total_time);
            while self
                .spans
                .get(k + 1)
                .is_some_and(|s| s.start_time <= t && s.length > 0.0 || s.start_time < t)
            {
                k += 1;
            }
            f(&self.path_sample_in(k, t, &mut cursor)?)?;
        }
        Ok(())
    }

    /// [`Plan::for_each_path_sample`]'s samples, stretch by stretch (module docs): where
    /// `quiet` finds that a stretch's ends and turn bound every sample in it, only those
    /// (the ends, the turn between them), else the dense samples that fall in it. A dense
    /// sample within [`KNOT_SLACK`] of a stretch's ends is always taken: there the dense
    /// sampler may read the phase or the block on the knot's other side. Returns how many
    /// dense samples the quiet stretches stood for.
    pub(crate) fn for_each_sparse_path_sample<Q, F>(
        &self,
        dt: f64,
        mut quiet: Q,
        mut f: F,
    ) -> Result<usize, Error>
    where
        Q: FnMut(&Stretch) -> bool,
        F: FnMut(&PathSample) -> Result<(), Error>,
    {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(crate::InputError::new("sample interval", dt)
                .expected("a finite number of seconds > 0")
                .into());
        }
        if self.spans.is_empty() {
            return Ok(0);
        }
        if self.geometry.len() != self.blocks.len() {
            return Err(Error::internal("plan sampled without its geometry"));
        }
        let mut grid = Grid {
            dt,
            total: self.total_time,
            next: 0,
            last: (self.total_time / dt).ceil() as usize,
            span: 0,
            cursor: Cursor::default(),
        };
        let mut passed = 0;
        for (k, span) in self.spans.iter().enumerate() {
            let end = self
                .spans
                .get(k + 1)
                .map_or(self.total_time, |s| s.start_time);
            let profile = if span.length > 0.0 {
                span.profile()?
            } else {
                SpanProfile::default()
            };
            let starts = profile.phase_starts();
            let blocks = self.blocks.get(span.first..span.end).unwrap_or_default();
            // The pieces: each phase, then the rest (the last phase's end state), split at
            // the blocks' starts.
            let mut phase_start = span.start_time;
            let mut at = span.start_time;
            for p in 0..8 {
                let (ph, phase_end) = match profile.phases.get(p) {
                    Some(ph) => (p, phase_start + ph.duration),
                    None => (6, end),
                };
                let phase_end = phase_end.min(end);
                while at < phase_end {
                    // The block running at `at`: the last of positive length started by it.
                    let n = blocks
                        .partition_point(|b| b.start_time <= at)
                        .saturating_sub(1);
                    let n = (0..=n)
                        .rev()
                        .find(|&i| blocks.get(i).is_some_and(|b| b.length > 0.0))
                        .unwrap_or(n);
                    let to = blocks
                        .get(n + 1..)
                        .unwrap_or_default()
                        .iter()
                        .map(|b| b.start_time)
                        .find(|&t| t > at)
                        .map_or(phase_end, |t| t.min(phase_end));
                    let block = span.first + n;
                    let offset = self.blocks.get(block).map_or(0.0, |b| b.span_offset);
                    let tau0 = phase_start;
                    let sample = |t: f64| {
                        // The rest after the profile holds its end state.
                        let tau = if p < 7 { t - tau0 } else { f64::INFINITY };
                        let st = profile.state_in(&starts, ph, tau);
                        PathSample {
                            t,
                            block,
                            s: st.s - offset,
                            path: st,
                        }
                    };
                    let ends = [sample(at), sample(to)];
                    let turn = profile.phases.get(ph).filter(|_| p < 7).and_then(|phase| {
                        let t = tau0 - phase.a0 / phase.jerk;
                        (phase.jerk != 0.0 && t > at && t < to).then(|| sample(t))
                    });
                    let stretch = Stretch { block, ends, turn };
                    let (near_at, near_to) = (knot_slack(at), knot_slack(to));
                    grid.take(self, at + near_at, true, &mut f)?;
                    if quiet(&stretch) {
                        f(&ends[0])?;
                        if let Some(turn) = &turn {
                            f(turn)?;
                        }
                        f(&ends[1])?;
                        passed += grid.pass(to - near_to);
                    } else {
                        grid.take(self, to - near_to, false, &mut f)?;
                    }
                    at = to;
                }
                phase_start = phase_end.max(phase_start);
                at = at.max(phase_end);
            }
        }
        // Whatever the stretches left (the plan's last instant).
        grid.take(self, f64::INFINITY, true, &mut f)?;
        Ok(passed)
    }
}
