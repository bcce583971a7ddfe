//! What the spiral's morphs share: the last loop's margin, the arc tolerance, the stats, and
//! sampling along closed loops.

use super::super::segments::{Seg, segs_from_vertices};
use super::super::shape::closed_chain;
use crate::geom::Point;
use crate::toolpath::Tool;
use cavalier_contours::polyline::{PlineCreation, PlineSourceMut, Polyline};

/// Inward margin of the spiral's last loop, mm, for tools up to 12.7 mm, times the tool's
/// [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale) above (see the module docs).
pub const LAST_LOOP_MARGIN: f64 = 0.005;
/// With `--arcs`: the largest distance between the fitted arcs and the smooth curve through
/// the spiral's samples, mm, for tools up to 12.7 mm ([`arc_tolerance`] for a tool). Below
/// [`LAST_LOOP_MARGIN`], so that the last lap's arcs stay inside the boundary offset where
/// the lap runs onto it.
pub const ARC_TOLERANCE: f64 = 0.004;

/// [`LAST_LOOP_MARGIN`] for `tool`: times its [`Tool::tolerance_scale`].
pub fn last_loop_margin(tool: &Tool) -> f64 {
    LAST_LOOP_MARGIN * tool.tolerance_scale()
}

/// [`ARC_TOLERANCE`] for `tool`: times its [`Tool::tolerance_scale`] (below
/// [`last_loop_margin`] at every scale).
pub fn arc_tolerance(tool: &Tool) -> f64 {
    ARC_TOLERANCE * tool.tolerance_scale()
}

/// The construction a spiral's laps came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Construction {
    /// The contour-parallel loops joined by lane changes (`--morph offsets`).
    #[default]
    Offsets,
    /// The paper's central spiral grown into the walls along offset fronts (`--morph fronts`).
    Fronts,
    /// The paper's central spiral morphed harmonically into the walls (`--morph harmonic`).
    Harmonic,
    /// The harmonic morph stalled and the laps follow the walls' distance field instead.
    DistanceField,
}

/// What the spiral planner measured.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpiralStats {
    /// Turns of the central Archimedean spiral.
    pub central_turns: usize,
    /// Laps of the harmonic morph (the last onto the boundary offset included).
    pub morph_laps: usize,
    /// Largest measured distance between consecutive loops, mm.
    pub max_loop_distance: f64,
    /// Radius of the central spiral, mm.
    pub r0: f64,
    /// Which construction made the laps.
    pub construction: Construction,
    /// Length of the ridge cut as a slot by the fronts' first lap, mm (0: none).
    pub ridge_slot: f64,
    /// Length of the ridge segment the central spiral's capsules are drawn about, mm (0: a
    /// circular central spiral).
    pub capsule: f64,
    /// Chains of offset loops, each one continuous spiral (the offsets morph).
    pub chains: usize,
}

/// `B_ε`, the spiral's last loop: `B` moved inward by `margin` ([`last_loop_margin`]; `B`
/// itself if that offset is not one loop).
pub fn last_loop(b: &Polyline<f64>, margin: f64) -> Polyline<f64> {
    match crate::geom::region::offset_loops(b, margin).as_slice() {
        [one] => one.clone(),
        _ => b.clone(),
    }
}

/// One lap of the morph from the closed loop `lap` onto the loop walked by `along` (of length
/// `len`, starting near `lap[0]`): the point at arc-length fraction `f` of `lap` moves the
/// fraction `f` of the way to the point at the same fraction of the target, so the lap starts
/// on `lap` and ends on the target. Appended to `out`.
pub fn blend_lap(lap: &[Point], along: &LoopWalker, len: f64, out: &mut Vec<Point>) {
    for (p, f) in lap.iter().zip(fractions(lap)) {
        let q = along.at(f * len);
        out.push(*p + (q - *p) * f);
    }
}

/// Arc-length lookups along a closed loop.
#[derive(Debug)]
pub struct LoopWalker {
    segs: Vec<Seg>,
    cum: Vec<f64>,
}

impl LoopWalker {
    pub fn new(pl: &Polyline<f64>) -> Self {
        let segs = segs_from_vertices(&closed_chain(pl));
        let mut acc = 0.0;
        let cum = segs
            .iter()
            .map(|s| {
                let a = acc;
                acc += s.length();
                a
            })
            .collect();
        LoopWalker { segs, cum }
    }

    /// The point at arc length `t` from the start.
    pub fn at(&self, t: f64) -> Point {
        let i = self.cum.partition_point(|&c| c <= t).saturating_sub(1);
        match self.segs.get(i) {
            Some(s) => s.point_at(t - self.cum[i]),
            None => Point::ORIGIN,
        }
    }
}

/// Arc-length fraction of each point of a closed loop (the closing chord included).
pub fn fractions(pts: &[Point]) -> Vec<f64> {
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(pts.len());
    for (i, p) in pts.iter().enumerate() {
        if i > 0 {
            acc += pts[i - 1].distance(*p);
        }
        out.push(acc);
    }
    let total = acc
        + pts
            .last()
            .zip(pts.first())
            .map_or(0.0, |(a, b)| a.distance(*b));
    out.iter().map(|a| a / total.max(1e-12)).collect()
}

/// The closed loop through `pts` resampled at spacing at most `ds`, keeping the first point.
pub fn resample(pts: &[Point], ds: f64) -> Vec<Point> {
    let mut closed = pts.to_vec();
    if let Some(&p0) = pts.first() {
        closed.push(p0);
    }
    let total: f64 = closed.windows(2).map(|w| w[0].distance(w[1])).sum();
    let n = ((total / ds).ceil() as usize).max(8);
    let step = total / n as f64;
    let mut out = Vec::with_capacity(n);
    let mut seg = 0;
    let mut seg_start = 0.0;
    for k in 0..n {
        let target = step * k as f64;
        while seg + 1 < closed.len() - 1
            && seg_start + closed[seg].distance(closed[seg + 1]) < target
        {
            seg_start += closed[seg].distance(closed[seg + 1]);
            seg += 1;
        }
        let l = closed[seg].distance(closed[seg + 1]);
        let f = if l > 0.0 {
            ((target - seg_start) / l).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(closed[seg].lerp(closed[seg + 1], f));
    }
    out
}

/// A closed polyline through `pts` (for distance queries).
pub fn closed_pline(pts: &[Point]) -> Polyline<f64> {
    let mut pl = Polyline::with_capacity(pts.len(), true);
    for p in pts {
        pl.add(p.x, p.y, 0.0);
    }
    pl
}

/// Points along a closed loop at spacing at most `ds` (arcs sampled on the arc).
pub fn sample_every(pl: &Polyline<f64>, ds: f64) -> Vec<Point> {
    let mut out = Vec::new();
    for sg in segs_from_vertices(&closed_chain(pl)) {
        let n = ((sg.length() / ds).ceil() as usize).max(1);
        for k in 0..n {
            out.push(sg.point_at(sg.length() * k as f64 / n as f64));
        }
    }
    out
}
