//! The spiral on offset fronts: central spiral, then one lap from each front to the next,
//! then the boundary offset once with exact arcs.
//!
//! The central spiral is the paper's Archimedean spiral about the centre or, when the fronts'
//! core is a capsule about the ridge segment `PQ` ([`super::fronts`]), a spiral of capsules:
//! lap `j` blends the capsule of radius `ρ_{j−1}` into that of radius `ρ_j` at equal
//! arc-length fractions, from the middle of the capsule's right-hand side (on the entry
//! helix's circle). The radii `ρ_j` are the circular spiral's whole turns, so the caps are
//! paced like the circle; along the sides the pitch is at most `s'`.
//!
//! Lap `k` runs from front `L_k` to front `L_{k+1}`: its point at arc-length fraction `f` of
//! `L_k` is `p + f·(q − p)`, `q` the point of `L_{k+1}` at the same arc-length fraction, the
//! fractions of `L_{k+1}` counted from its point nearest to the lap's start. At `f = 0` the lap
//! is on `L_k`, at `f = 1` on `L_{k+1}`, where the next lap starts: the laps join without a
//! corner or a retract, and, both fronts being smooth and parametrized by arc length, the lap is
//! smooth. The planning happens in the pocket's own coordinates (exact offsets do not depend on
//! a grid); only the start direction of the central spiral is taken from the pocket's principal
//! axis, so that turning the pocket turns the path.

use super::super::levels::{Cut, CutEntry, LevelPlan};
use super::super::segments::segs_from_vertices;
use super::super::shape::{closed_chain, restart_near, reversed};
use super::common::{
    Construction, LAST_LOOP_MARGIN, LoopWalker, SpiralStats, blend_lap, fractions, resample,
    sample_every,
};
use super::fronts::{FrontOptions, capsule, circle, fronts};
use crate::geom::{Point, Vec2};
use cavalier_contours::polyline::{PlineSource, Polyline};
use std::f64::consts::TAU;

/// Everything the front spiral needs, in mm.
#[derive(Debug)]
pub struct FrontSpiral<'a> {
    /// The boundary offset, counter-clockwise.
    pub b: &'a Polyline<f64>,
    /// `B` moved inward by [`super::common::LAST_LOOP_MARGIN`] (the last loop), counter-clockwise.
    pub b_eps: &'a Polyline<f64>,
    /// Centre and inscribed radius.
    pub c: Point,
    pub rho_b: f64,
    /// Radius of the central spiral's last loop and of the entry helix.
    pub r0: f64,
    pub rho_h: f64,
    /// Largest stepover `s'` and sample spacings.
    pub sp: f64,
    pub ds: f64,
    pub ds_last: f64,
    /// Tool radius (the central spiral's pitch depends on it).
    pub tool_radius: f64,
    /// Smoothing radius of the interior fronts.
    pub smooth: f64,
    /// Counter-clockwise (climb) or clockwise.
    pub ccw: bool,
    /// Start direction of the central spiral, rad.
    pub start_angle: f64,
    /// The ridge segment, when the central spiral is a capsule spiral about it
    /// ([`super::fronts::ridge_segment`]); `None`: a circular spiral about `c`.
    pub ridge: Option<(Point, Point)>,
    /// Output the sampled laps as tangent-continuous arcs ([`super::common::ARC_TOLERANCE`]).
    pub arcs: bool,
    /// Largest gap between consecutive fronts, mm ([`super::fronts::FrontOptions::max_gap`]).
    pub max_gap: f64,
    /// The tool's [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale) (the last
    /// loop's margin and the arc tolerance).
    pub scale: f64,
}

impl FrontSpiral<'_> {
    /// The level plan, or `None` when the fronts do not reach `B` (see [`super::fronts`]).
    pub fn plan(&self) -> Option<(LevelPlan, SpiralStats)> {
        let opts = FrontOptions {
            step: self.sp,
            open_radius: self.smooth,
            close_radius: self.smooth,
            sample: self.ds,
            max_gap: self.max_gap,
            slot_reach: SLOT_REACH * self.tool_radius,
            slot_area: super::fronts::SLOT_AREA * self.scale * self.scale,
        };
        let core = match self.ridge {
            Some((p, q)) => capsule(p, q, self.r0),
            None => circle(self.c, self.r0),
        };
        let f = fronts(self.b, &core, self.rho_b, &opts)?;
        let orient = |pl: &Polyline<f64>| if self.ccw { pl.clone() } else { reversed(pl) };
        let mut stats = SpiralStats {
            r0: self.r0,
            max_loop_distance: f.max_distance,
            construction: Construction::Fronts,
            ridge_slot: f.ridge_slot,
            ..SpiralStats::default()
        };
        let (c, rho_h, ds) = (self.c, self.rho_h, self.ds);
        // Central spiral from the helix out to R₀, its pitch set by the engagement (below).
        let mut pts: Vec<Point> = Vec::new();
        let (turns, radius_at) = central_spiral(
            rho_h,
            self.r0,
            self.tool_radius,
            CENTRAL_DEPTH * self.sp,
            self.sp,
        );
        stats.central_turns = turns;
        let mut lap = if let Some((p, q)) = self.ridge {
            // About the ridge segment: laps between capsules of the spiral's radii, blended
            // at equal arc-length fractions, from the middle of the capsule's right-hand side
            // (which lies on the entry helix's circle about `c`).
            stats.capsule = p.distance(q);
            let cap = |rho: f64| {
                let raw = capsule(p, q, rho);
                let start = raw.at(0).pos();
                restart_near(&orient(&raw), Point::new(start.x, start.y))
            };
            let mut lap = resample(&sample_every(&cap(rho_h), 0.25 * ds), ds);
            // The first blend lap passes the ridge on one side at about (ρ_h + ρ_1)/2 and on
            // the other at ρ_1 (the half it starts on was passed at ρ_h): when those are more
            // than 1.8 r apart the ridge between them would stand uncut, so the first capsule
            // is traced all the way round first (a slot along the ridge).
            let r1 = radius_at(TAU);
            if turns == 0 || 0.5 * (rho_h + r1) + r1 > 1.8 * self.tool_radius {
                pts.extend(lap.iter().copied());
            }
            for j in 1..=turns {
                let target = cap(radius_at(TAU * j as f64));
                blend_lap(
                    &lap,
                    &LoopWalker::new(&target),
                    target.path_length(),
                    &mut pts,
                );
                lap = resample(&sample_every(&target, 0.25 * ds), ds);
            }
            lap
        } else {
            self.circle_spiral(turns, &radius_at, &mut pts)
        };
        let count = f.loops.len();
        let mut last_loop = None;
        for (k, next) in f.loops.iter().enumerate().skip(1) {
            let start = lap.first().copied()?;
            // Where the next front starts: its point nearest to a point a little ahead of the
            // lap's start along the travel. Nearest to the start itself is ambiguous where the
            // fronts are symmetric about it (the ridge's ends), and a tie broken by the loops'
            // vertex order would make the path depend on where the outline's loop starts.
            let ahead = lap
                .get(1)
                .and_then(|p1| (*p1 - start).normalize())
                .map_or(start, |t| start + t * (0.25 * self.sp));
            if k + 1 < count {
                // A morph lap: from L_{k-1} to L_k over one revolution.
                let target = restart_near(&orient(next), ahead);
                let len = target.path_length();
                let along = LoopWalker::new(&target);
                if k == 1 && f.ridge_slot > 0.0 {
                    // The first front reaches far beyond the circle along the ridge: a blend
                    // would cut across the ridge's ends, so the lap joins the front over a
                    // short smoothstep transition and then traces it all the way round.
                    let window = (2.0 * self.sp).min(0.25 * len);
                    let mut acc = 0.0;
                    let mut prev = start;
                    let mut joined = 0.0;
                    for p in &lap {
                        acc += prev.distance(*p);
                        prev = *p;
                        if acc > window {
                            break;
                        }
                        let w = smoothstep(acc / window);
                        pts.push(*p + (along.at(acc) - *p) * w);
                        joined = acc;
                    }
                    let fine = resample(&sample_every(&target, 0.25 * ds), ds);
                    let fr = fractions(&fine);
                    for (q, x) in fine.iter().zip(&fr) {
                        if x * len > joined {
                            pts.push(*q);
                        }
                    }
                    pts.push(along.at(0.0));
                    lap = fine;
                    stats.morph_laps += 1;
                    continue;
                }
                blend_lap(&lap, &along, len, &mut pts);
                // Equal spacing along the whole loop (not per segment of the front, whose
                // vertices depend on the offsets' internals): no short chords for the
                // look-ahead to stumble on, and the same samples however the pocket is turned.
                lap = resample(&sample_every(&target, 0.25 * ds), ds);
                stats.morph_laps += 1;
                continue;
            }
            // The last lap: from L_{n-1} onto B_ε (sampled finely enough that its chords stay
            // inside B at concave arcs), then B_ε once round with exact arcs: B's neighbour
            // is then the last lap, at most one step away everywhere.
            // The last front is `B` with rounded corners (see [`fronts`]): the lap ends on
            // it (moved in by ε), and the last loop `B_ε` starts from the nearest point.
            let fine = resample(&lap, self.ds_last);
            let target = restart_near(
                &orient(&super::common::last_loop(
                    next,
                    LAST_LOOP_MARGIN * self.scale,
                )),
                ahead,
            );
            let len = target.path_length();
            let along = LoopWalker::new(&target);
            blend_lap(&fine, &along, len, &mut pts);
            let close = target.at(0).pos();
            let close = Point::new(close.x, close.y);
            pts.push(close);
            let last = restart_near(&orient(self.b_eps), close);
            let first = last.at(0).pos();
            pts.push(Point::new(first.x, first.y));
            stats.morph_laps += 1;
            let mut path =
                super::keep_inside::lap_path(&pts, self.b_eps, self.ds_last, self.arcs, self.scale);
            path.extend(segs_from_vertices(&closed_chain(&last)));
            last_loop = Some(path);
            break;
        }
        let path = last_loop?;
        let plan = LevelPlan {
            cuts: vec![Cut {
                entry: CutEntry::Helix {
                    center: c,
                    radius: rho_h,
                    flat_turn: false,
                },
                path,
            }],
        };
        Some((plan, stats))
    }

    /// The circular central spiral (appended to `pts`) and its last loop, the circle `L_0` of
    /// radius `R₀` from the start direction.
    fn circle_spiral(
        &self,
        turns: usize,
        radius_at: &dyn Fn(f64) -> f64,
        pts: &mut Vec<Point>,
    ) -> Vec<Point> {
        let (c, r0, ds, a0) = (self.c, self.r0, self.ds, self.start_angle);
        let sign = if self.ccw { 1.0 } else { -1.0 };
        if turns > 0 {
            let total = TAU * turns as f64;
            let mut th = 0.0;
            while th < total {
                let rho = radius_at(th);
                pts.push(c + Vec2::from_angle(a0 + sign * th) * rho);
                th += (ds / rho.max(1e-3)).min(0.2);
            }
        }
        let n0 = ((TAU * r0 / ds).ceil() as usize).max(16);
        (0..n0)
            .map(|i| c + Vec2::from_angle(a0 + sign * TAU * i as f64 / n0 as f64) * r0)
            .collect()
    }
}

/// The removal-rate-equivalent radial depth the central spiral is paced to, as a multiple of
/// the step `s'` (its pitch never exceeds `s'`). At 1.1 (1.08·s at the default 0.98·s step:
/// an engagement angle of 82° against the nominal 78.5° at 40% of a 12.7 mm tool) the
/// built-in pocket's capsule spiral takes one turn fewer than at 1.0 (−3.2 s of 75.5 s) and
/// its caps stay near the nominal engagement (the share above it: 13.6%; a constant pitch
/// `s'`, the paper's, puts every cap above it: 23.7%).
const CENTRAL_DEPTH: f64 = 1.1;

/// The first front's ridge slot is cut by a lap that traces the front all round: every point
/// of the slot must lie within this fraction of the tool radius of that lap or of the core's
/// last loop ([`super::fronts::FrontOptions::slot_reach`]). Below 1 for the laps' chords,
/// their smoothed join and the verifier's raster cells.
const SLOT_REACH: f64 = 0.9;

/// `3x² − 2x³` on [0, 1]: zero slope at both ends, so a transition leaves one curve and joins
/// the other tangentially.
fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// The central spiral's turns and its radius as a function of the angle turned.
///
/// On an outward circular pass of radius `ρ` whose previous pass lies `a` further in, a tool
/// of radius `r` removes `((ρ+r)² − (ρ+r−a)²)/2` mm² per radian while its centre travels
/// `ρ`: the radial depth of cut of a straight pass with the same removal rate is
/// `a_e = (2a(ρ+r) − a²)/(2ρ)`, larger than `a` (the material wraps around the tool). A
/// constant pitch (the paper's Archimedean spiral) therefore cuts above the nominal
/// engagement on every turn. Here the pitch is the `a` that gives `a_e = s'`:
/// `a(ρ) = (ρ + r) − √((ρ + r)² − 2s'ρ)` (→ `s'` for large `ρ`), i.e.
/// `dρ/dθ = a(ρ)/(2π)`. The angle this takes from `ρ_h` to `R₀` is rounded up to whole turns
/// (so the spiral ends where the circle `L_0` starts) by scaling the pitch down uniformly; the
/// radius is then tabulated by a midpoint integration and interpolated.
pub fn central_spiral(
    rho_h: f64,
    r0: f64,
    r: f64,
    sp: f64,
    cap: f64,
) -> (usize, impl Fn(f64) -> f64) {
    let pitch = |rho: f64| {
        let q = rho + r;
        (q - (q * q - 2.0 * sp * rho).max(0.0).sqrt()).clamp(0.05 * sp, cap)
    };
    let n = 256usize;
    let h = (r0 - rho_h).max(0.0) / n as f64;
    // θ(ρ) = ∫ 2π/a(ρ) dρ by the midpoint rule.
    let mut theta = vec![0.0; n + 1];
    for i in 0..n {
        let mid = rho_h + (i as f64 + 0.5) * h;
        theta[i + 1] = theta[i] + TAU * h / pitch(mid);
    }
    let total = theta[n];
    let turns = if h > 0.0 {
        (total / TAU - 1e-9).ceil().max(1.0) as usize
    } else {
        0
    };
    let scale = if total > 0.0 {
        turns as f64 * TAU / total
    } else {
        1.0
    };
    let radius_at = move |th: f64| {
        let t = th / scale;
        let i = theta.partition_point(|&x| x <= t).clamp(1, n);
        let (t0, t1) = (theta[i - 1], theta[i]);
        let f = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
        rho_h + h * ((i - 1) as f64 + f.clamp(0.0, 1.0))
    };
    (turns, radius_at)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The central spiral runs from the helix to R₀ in whole turns, outward, and its pitch
    /// keeps the removal-rate-equivalent radial depth at or below s' on every turn.
    #[test]
    fn central_spiral_pitch_keeps_the_equivalent_depth() {
        let (rho_h, r0, r, sp) = (2.5, 21.8, 6.35, 4.9);
        let (turns, at) = central_spiral(rho_h, r0, r, sp, sp);
        assert!(turns >= 4, "{turns}");
        assert!((at(0.0) - rho_h).abs() < 1e-9);
        assert!(
            (at(TAU * turns as f64) - r0).abs() < 1e-6,
            "{}",
            at(TAU * turns as f64)
        );
        let mut worst: f64 = 0.0;
        for k in 0..(turns * 64) {
            let th = TAU * k as f64 / 64.0;
            let (inner, outer) = (at(th), at(th + TAU).min(r0));
            assert!(outer >= inner - 1e-12);
            let a = outer - inner;
            // a_e = (2a(ρ+r) − a²)/(2ρ) at the outer pass.
            let ae = (2.0 * a * (outer + r) - a * a) / (2.0 * outer);
            worst = worst.max(ae);
        }
        assert!(worst <= sp * 1.01, "{worst}");
        // A constant pitch would exceed it on the first turns.
        let a = (r0 - rho_h) / turns as f64;
        let ae_const = (2.0 * a * (rho_h + a + r) - a * a) / (2.0 * (rho_h + a));
        assert!(ae_const > sp, "{ae_const}");
    }
}
