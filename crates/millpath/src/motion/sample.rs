//! Sampling a plan in time: position, path speed and per-axis velocity, acceleration, jerk.
//!
//! With `P(s)` the block's geometry by arc length and `s(t)` the span's profile,
//! `v = P'·ṡ`, `a = P''·ṡ² + P'·s̈`, `j = P'''·ṡ³ + 3P''·ṡ·s̈ + P'·s⃛`.

use super::plan::Plan;
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

impl Plan {
    /// The state at time `t` (clamped to the plan). Needs the plan's geometry
    /// ([`super::PlanOptions::keep_geometry`]).
    pub fn state_at(&self, t: f64) -> Result<Sample, Error> {
        let k = self
            .spans
            .partition_point(|s| s.start_time <= t)
            .saturating_sub(1);
        let mut cache = None;
        self.sample_in(k, t, &mut cache)
    }

    fn sample_in(
        &self,
        k: usize,
        t: f64,
        cache: &mut Option<(usize, SpanProfile)>,
    ) -> Result<Sample, Error> {
        if self.geometry.len() != self.blocks.len() {
            return Err(Error::internal("plan sampled without its geometry"));
        }
        let Some(span) = self.spans.get(k) else {
            return Err(Error::internal("sampling an empty plan"));
        };
        let p = match cache {
            Some((ck, p)) if *ck == k => *p,
            _ => {
                let p = if span.length > 0.0 {
                    span.profile()?
                } else {
                    SpanProfile::default()
                };
                *cache = Some((k, p));
                p
            }
        };
        let st = p.state(t - span.start_time);
        // The block containing st.s (the last one starting at or before it).
        let blocks = self.blocks.get(span.first..span.end).unwrap_or_default();
        // The last block with positive length starting at or before st.s (binary search).
        let mut n = blocks
            .partition_point(|b| b.span_offset <= st.s)
            .saturating_sub(1);
        while n > 0 && blocks.get(n).is_some_and(|b| b.length <= 0.0) {
            n -= 1;
        }
        let bi = span.first + n;
        let (geom, (from, _)) = match (self.geometry.get(bi), self.ends.get(bi)) {
            (Some(g), Some(e)) => (*g, *e),
            _ => return Err(Error::internal("block index out of range")),
        };
        let offset = self.blocks.get(bi).map_or(0.0, |b| b.span_offset);
        let s = st.s - offset;
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
            t,
            block: bi,
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
        let mut cache = None;
        for i in 0..=n {
            let t = (i as f64 * dt).min(self.total_time);
            while self
                .spans
                .get(k + 1)
                .is_some_and(|s| s.start_time <= t && s.length > 0.0 || s.start_time < t)
            {
                k += 1;
            }
            f(self.sample_in(k, t, &mut cache)?)?;
        }
        Ok(())
    }
}
