//! Sampling a plan in time: position, path speed and per-axis velocity, acceleration, jerk.
//!
//! With `P(s)` the block's geometry by arc length and `s(t)` the span's profile,
//! `v = P'·ṡ`, `a = P''·ṡ² + P'·s̈`, `j = P'''·ṡ³ + 3P''·ṡ·s̈ + P'·s⃛`.

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
}
