//! The planner in bounded memory: [`plan_stream`] reads a stream of moves and hands out the
//! timed plan a chunk at a time, keeping only a window of spans whose knot speeds are not
//! final yet. It computes the same knot speeds as [`super::plan_moves`] (the look-ahead is
//! exact, not truncated), so the same times; memory is the window, not the program.
//!
//! # When is a knot speed final?
//! [`super::plan`]'s backward pass sets `y_k = min(c_k, R_k(y_{k+1}))`, where `c_k` is the
//! knot's cap (junction cap and both spans' speed caps, 0 at dwells) and
//! `R_k(v) = reachable_velocity(v, L_k, a_k, j_k)` is non-decreasing in `v`. Unrolled over a
//! window of spans `k..n` whose end knot `y_n` is not known yet,
//!
//! `y_k = min(c_k, R_k(c_{k+1}), R_k∘R_{k+1}(c_{k+2}), …, R_k∘…∘R_{n−1}(y_n)) = min(A_k, G_k(y_n))`
//!
//! with `A_k` the minimum over the caps inside the window and `G_k` the chain of reaches from
//! the window's end (a composition of non-decreasing maps commutes with `min`). Since
//! `y_n ≥ 0` and `G_k` is non-decreasing, `G_k(0) ≥ A_k` implies `y_k = A_k` whatever the
//! unknown future: the window already holds enough length to brake from the knot's cap to a
//! stop, so nothing beyond it can lower the knot. `A_k` is computed as the backward pass
//! started from a terminal speed at least every cap in the window (`R(v) ≥ v`, so that term
//! never binds) and `G_k(0)` as the backward pass from 0 without caps. The leading knots that
//! pass the test are final; the forward pass (`y_{k+1} ← min(y_{k+1}, R_k(y_k))`) needs only
//! earlier knots, so the spans between final knots are timed exactly as the whole-program
//! planner times them (`plan::time_spans`, shared code).
//!
//! The window is counted in blocks (what memory is made of): when it holds more than
//! [`StreamOptions::window`] blocks, the final prefix is handed out. A window in which no knot
//! is final yet (a long stretch of moves too short to brake in, or one span of many blocks) is
//! doubled until one is.

use super::controller::{Prepared, Shaper};
use super::path::BlockGeometry;
use super::plan::{BlockPlan, Builder, Plan, Span, pin_dwells, time_spans};
use super::profile::reachable_velocity;
use crate::error::Error;
use crate::geom::Point3;
use crate::machine::Machine;
use crate::toolpath::Move;

/// Options of [`plan_stream`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct StreamOptions {
    /// Check every span profile against its limits before accepting it.
    pub check_profiles: bool,
    /// Blocks kept before trying to finalize a chunk (doubled while no knot is final).
    pub window: usize,
}

impl Default for StreamOptions {
    fn default() -> Self {
        StreamOptions {
            check_profiles: true,
            window: 8192,
        }
    }
}

option_builders! {
    StreamOptions;
    /// Sets [`StreamOptions::check_profiles`].
    with_check_profiles => check_profiles: bool;
    /// Sets [`StreamOptions::window`], blocks.
    with_window => window: usize;
}

/// One timed chunk of a streamed program: a self-contained [`Plan`] (geometry kept, block and
/// span indices and times relative to the chunk) and the moves it was planned from, ready for
/// [`super::verify::verify_plan`] or [`Plan::sample`].
#[derive(Debug, Clone)]
pub struct Chunk {
    /// The chunk's plan; its time 0 is `start_time` of the program.
    pub plan: Plan,
    /// The `(from, move)` pairs of the chunk's blocks.
    pub moves: Vec<(Point3, Move)>,
    /// Program time at the start of the chunk, s.
    pub start_time: f64,
    /// Index in the program of the chunk's first block.
    pub first_block: usize,
}

/// What [`plan_stream`] measured on the whole program.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StreamSummary {
    /// Cycle time, s.
    pub total_time: f64,
    /// Blocks planned (one per move, except where the controller model reshapes the path:
    /// see `super::controller`).
    pub blocks: usize,
    /// Moves read.
    pub moves: usize,
    /// Spans planned.
    pub spans: usize,
    /// Chunks handed out.
    pub chunks: usize,
    /// Sum of length / programmed feed over the feed moves, s.
    pub time_at_programmed_feed: f64,
    /// Path length, mm.
    pub length: f64,
    /// Most blocks held at once (the memory figure).
    pub max_buffered_blocks: usize,
}

struct State<F> {
    opts: StreamOptions,
    b: Builder,
    blocks: Vec<BlockPlan>,
    moves: Vec<(Point3, Move)>,
    geoms: Vec<Option<BlockGeometry>>,
    block_base: usize,
    sum: StreamSummary,
    /// The chunk handed out, its buffers kept from one chunk to the next.
    chunk: Chunk,
    on_chunk: F,
}

/// Plans a stream of `(from, move)` pairs in bounded memory, calling `on_chunk` with each
/// timed chunk in program order; the first error (of the stream, the planner or `on_chunk`)
/// is returned as is.
pub fn plan_stream<I, F>(
    moves: I,
    machine: &Machine,
    opts: &StreamOptions,
    mut on_chunk: F,
) -> Result<StreamSummary, Error>
where
    I: IntoIterator<Item = Result<(Point3, Move), Error>>,
    F: FnMut(&Chunk) -> Result<(), Error>,
{
    plan_stream_owned(moves, machine, opts, |c: &mut Chunk| on_chunk(c))
}

/// A chunk with nothing in it, for `machine` (what [`plan_stream_owned`]'s callback may
/// leave in place of the chunk it takes).
pub(crate) fn empty_chunk(machine: &Machine) -> Chunk {
    Chunk {
        plan: Plan {
            reshaped: machine.controller == crate::machine::Controller::LinuxCnc,
            machine: machine.name.clone(),
            blocks: Vec::new(),
            spans: Vec::new(),
            geometry: Vec::new(),
            ends: Vec::new(),
            total_time: 0.0,
        },
        moves: Vec::new(),
        start_time: 0.0,
        first_block: 0,
    }
}

/// [`plan_stream`] whose callback may take the chunk (swap it with another chunk of the same
/// machine, [`empty_chunk`] or one handed back): the stream refills whatever chunk is left,
/// reusing its buffers.
pub(crate) fn plan_stream_owned<I, F>(
    moves: I,
    machine: &Machine,
    opts: &StreamOptions,
    on_chunk: F,
) -> Result<StreamSummary, Error>
where
    I: IntoIterator<Item = Result<(Point3, Move), Error>>,
    F: FnMut(&mut Chunk) -> Result<(), Error>,
{
    machine.validate(&machine.name)?;
    let mut st = State {
        opts: *opts,
        b: Builder::new(),
        blocks: Vec::new(),
        moves: Vec::new(),
        geoms: Vec::new(),
        block_base: 0,
        sum: StreamSummary::default(),
        chunk: empty_chunk(machine),
        on_chunk,
    };
    let base_window = opts.window.max(2);
    let mut window = base_window;
    let mut shaper = Shaper::new(machine);
    let mut prepared = Vec::new();
    for (k, item) in moves.into_iter().enumerate() {
        let (from, m) = item?;
        st.sum.moves = k + 1;
        shaper.push(k, from, &m, &mut prepared)?;
        for p in prepared.drain(..) {
            st.take(&p)?;
            if st.blocks.len() > window && st.b.spans.len() > 1 {
                let done = st.flush(false)?;
                window = if done == 0 {
                    window.saturating_mul(2)
                } else {
                    base_window
                };
            }
        }
    }
    let settle = shaper.finish(&mut prepared)?;
    for p in prepared.drain(..) {
        st.take(&p)?;
    }
    st.b.settle_last(settle);
    st.flush(true)?;
    st.sum.blocks = st.block_base;
    st.sum.spans = st.b.span_base;
    Ok(st.sum)
}

impl<F> State<F>
where
    F: FnMut(&mut Chunk) -> Result<(), Error>,
{
    /// Adds one prepared block to the window.
    fn take(&mut self, p: &Prepared) -> Result<(), Error> {
        let i = self.block_base + self.blocks.len();
        let block = self.b.push(i, p)?;
        self.sum.length += block.length;
        if block.programmed_feed > 0.0 {
            self.sum.time_at_programmed_feed += block.length / block.programmed_feed;
        }
        self.blocks.push(block);
        self.moves.push((p.from, p.mv));
        self.geoms.push(p.geom);
        self.sum.max_buffered_blocks = self.sum.max_buffered_blocks.max(self.blocks.len());
        Ok(())
    }

    /// Times and hands out the leading spans whose knots are final (all of them at the end of
    /// the stream); returns how many spans were handed out.
    fn flush(&mut self, end: bool) -> Result<usize, Error> {
        let n = self.b.spans.len();
        let mut caps = self.b.knots.clone();
        caps.push(0.0);
        pin_dwells(&self.b.spans, &mut caps);
        // Backward pass with the window's end at rest (exact where final).
        let mut y = caps.clone();
        for k in (0..n).rev() {
            let s = &self.b.spans[k];
            let r = reachable_velocity(y[k + 1], s.length, s.limits.a, s.limits.j);
            y[k] = y[k].min(r).min(s.limits.v);
        }
        let p = if end {
            n
        } else {
            // A_k: backward from a speed above every cap; G_k: reaches from rest, no caps.
            let top = self
                .b
                .spans
                .iter()
                .map(|s| s.limits.v)
                .chain(caps.iter().copied())
                .filter(|v| v.is_finite())
                .fold(0.0, f64::max);
            let mut a = caps.clone();
            if let Some(last) = a.last_mut() {
                *last = top;
            }
            let mut g = vec![0.0; n + 1];
            for k in (0..n).rev() {
                let s = &self.b.spans[k];
                let r = reachable_velocity(a[k + 1], s.length, s.limits.a, s.limits.j);
                a[k] = a[k].min(r).min(s.limits.v);
                g[k] = reachable_velocity(g[k + 1], s.length, s.limits.a, s.limits.j);
            }
            let final_knots = (0..n).take_while(|&k| g[k] >= a[k]).count();
            final_knots.saturating_sub(1)
        };
        if p == 0 && !end {
            return Ok(0);
        }
        // Forward pass over the final prefix.
        for k in 0..p {
            let s = &self.b.spans[k];
            let r = reachable_velocity(y[k], s.length, s.limits.a, s.limits.j);
            y[k + 1] = y[k + 1].min(r).min(s.limits.v);
        }
        let end_block = if p < n {
            self.b.spans[p].first
        } else {
            self.block_base + self.blocks.len()
        };
        let nb = end_block
            .saturating_sub(self.block_base)
            .min(self.blocks.len());
        let base = self.block_base;
        let chunk = &mut self.chunk;
        let plan = &mut chunk.plan;
        plan.spans.clear();
        plan.spans.extend(self.b.spans[..p].iter().map(|s| Span {
            first: s.first.saturating_sub(base),
            end: s.end.saturating_sub(base),
            ..*s
        }));
        take_prefix(&mut self.blocks, nb, &mut plan.blocks);
        let span_base = u32::try_from(self.b.span_base).unwrap_or(u32::MAX);
        for bp in &mut plan.blocks {
            bp.span = bp.span.saturating_sub(span_base);
        }
        let dt = time_spans(
            &mut plan.spans,
            &y[..=p],
            &mut plan.blocks,
            0,
            0.0,
            self.opts.check_profiles,
        )?;
        take_prefix(&mut self.moves, nb, &mut chunk.moves);
        take_prefix(&mut self.geoms, nb, &mut plan.geometry);
        plan.ends.clear();
        plan.ends
            .extend(chunk.moves.iter().map(|(f, m)| (*f, m.to)));
        plan.total_time = dt;
        chunk.start_time = self.sum.total_time;
        chunk.first_block = base;
        if !chunk.moves.is_empty() {
            (self.on_chunk)(chunk)?;
            self.sum.chunks += 1;
        }
        self.sum.total_time += dt;
        self.block_base += nb;
        self.b.spans.drain(..p);
        self.b.knots.drain(..p.min(self.b.knots.len()));
        if let (Some(k0), Some(v)) = (self.b.knots.first_mut(), y.get(p)) {
            *k0 = *v;
        }
        self.b.span_base += p;
        Ok(p)
    }
}

/// Moves the first `n` items of `window` into `out` (whatever `out` held is dropped): the two
/// buffers are swapped and only the items after `n` (the window's unfinished tail, usually
/// short) are copied, not the chunk handed out.
fn take_prefix<T: Copy>(window: &mut Vec<T>, n: usize, out: &mut Vec<T>) {
    out.clear();
    out.extend_from_slice(window.get(n..).unwrap_or_default());
    window.truncate(n);
    std::mem::swap(window, out);
}
