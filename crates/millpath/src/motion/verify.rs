//! An independent verifier of plans: samples a plan in time and checks the machine's limits.
//!
//! It shares no code with the planner beyond the moves' own geometry
//! ([`Move::sweep_from`], [`Move::length_from`]): from the plan it takes only the path state
//! at each sample (block, distance into the block, ṡ, s̈, s⃛) and the block start times; it
//! evaluates the geometry and its arc-length derivatives itself and checks, at `rate` Hz
//! (≥ 1 kHz) and at every junction:
//! * per-axis velocity, acceleration and jerk ≤ the axis limits (relative 1e-6);
//! * path speed ≤ the programmed feed and the machine's maximum feed (rapids: the per-axis
//!   rapid velocity);
//! * that the path state integrates consistently between samples (`Δs` against the
//!   trapezoid of `ṡ` with the `s̈` end correction, exact for piecewise-cubic `s(t)`), and that
//!   the plan reaches the end of every block;
//! * at each junction with speed `v > 0`: none after an exact stop (`Corner::ExactStop`,
//!   tangent or not); a non-tangent junction is allowed only in blend
//!   mode, where the tightest circular blend the axes allow at that speed
//!   (`R = max(v²/A, √(v³/J))`) must stay within the path tolerance
//!   (`R·(1/cos(θ/2) − 1) ≤ tol`) and fit in the blocks, or in exact-path mode
//!   (`v·|Δt_i| ≤ min(A_i·T_ipo, J_i·T_ipo²)`); at tangent junctions the acceleration step
//!   `v²·|Δ(κN)_i|` must stay within `J_i·T_ipo`, and the velocity step `v·|ΔP'_i|` (zero
//!   unless a spiral arc's `|P'| ≠ 1` meets another block) within
//!   `min(A_i·T_ipo, J_i·T_ipo²)`.
//!
//! **Stretches.** The samples are the 1 kHz grid's, except over a stretch of the plan
//! (one block, one phase of its span's profile: [`super::sample`]) whose ends and turn bound
//! it below every limit: with `m₁, m₂, m₃` the largest `|P'|, |P''|, |P'''|` per axis over the
//! block (a line's direction cosines and zeros; an arc's from its radius, turn rate and
//! radial rate) and `V, A, J` the largest `ṡ, |s̈|, |s⃛|` over the stretch, every sample in it
//! has `|vᵢ| ≤ m₁V`, `|aᵢ| ≤ m₂V² + m₁A`, `|jᵢ| ≤ m₃V³ + 3m₂VA + m₁J` and a speed within
//! `|P'|ₘₐₓ·V`. Where all of these are within the limits (and `10⁻¹²` of them) the stretch is
//! checked at its ends and turn alone, else at every grid sample in it: the velocity,
//! acceleration, jerk and feed violations found are the grid's, one for one, at a cost per
//! block where the plan keeps within its limits (a metre-scale program's hours of cruise). The
//! consistency check between two samples of one stretch more than a grid step apart is exact
//! (one cubic): within the rounding of `s`, `10⁻⁹·(1 + |s|)`, and of the times, four ulps of
//! `t` at the two speeds (which every pair is allowed: at `t` of a million seconds an ulp is
//! `10⁻¹⁰` s). [`VerifyOptions::every_sample`]
//! samples the whole grid.
//!
//! Arcs whose end radius differs from the start radius (G-code rounding, tiny arcs within
//! LinuxCNC's tolerance) are the spiral with the radius linear in the angle, parametrised by
//! `s = u·L` with `L` = [`Move::length_from`] (mean radius); the verifier differentiates it
//! exactly, radial terms included, and checks the feed against the tool's speed `|P'|·ṡ`.

use super::plan::Plan;
use super::sample::Cursor;
use crate::error::Error;
use crate::geom::{Point3, Vec3};
use crate::machine::Machine;
use crate::toolpath::{Corner, Move, MoveKind};

/// Options of [`verify_plan`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct VerifyOptions {
    /// Sampling rate in Hz (at least 1000).
    pub rate: f64,
    /// Relative tolerance on every limit.
    pub rel_tol: f64,
    /// Every sample of the grid, even over the stretches whose bounds keep within the limits
    /// (module docs).
    pub every_sample: bool,
}

impl Default for VerifyOptions {
    fn default() -> Self {
        VerifyOptions {
            rate: 1000.0,
            rel_tol: 1e-6,
            every_sample: false,
        }
    }
}

option_builders! {
    VerifyOptions;
    /// Sets [`VerifyOptions::rate`], Hz.
    with_rate => rate: f64;
    /// Sets [`VerifyOptions::rel_tol`].
    with_rel_tol => rel_tol: f64;
    /// Sets [`VerifyOptions::every_sample`].
    with_every_sample => every_sample: bool;
}

/// What was violated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ViolationKind {
    /// Axis velocity.
    Velocity,
    /// Axis acceleration.
    Acceleration,
    /// Axis jerk.
    Jerk,
    /// Programmed or maximum feed.
    Feed,
    /// Path tolerance or corner rule at a junction.
    Corner,
    /// The path state does not integrate, or a block is not completed.
    Consistency,
}

/// One violation.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Violation {
    /// What.
    pub kind: ViolationKind,
    /// Block index.
    pub block: usize,
    /// Time in s.
    pub t: f64,
    /// Value found.
    pub value: f64,
    /// Limit.
    pub limit: f64,
}

/// The verifier's findings.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct VerifyReport {
    /// Number of time samples checked.
    pub samples: usize,
    /// Samples of the grid not taken, their stretches' bounds within every limit (module
    /// docs).
    pub bounded: usize,
    /// Number of junctions checked.
    pub junctions: usize,
    /// Total number of violations.
    pub violations: usize,
    /// The first violations (at most 20).
    pub first: Vec<Violation>,
    /// Largest ratio value/limit seen per kind (velocity, acceleration, jerk, feed).
    pub worst_ratio: [f64; 4],
}

impl VerifyReport {
    fn add(&mut self, v: Violation) {
        self.violations += 1;
        if self.first.len() < 20 {
            self.first.push(v);
        }
    }
}

/// The verifier's own view of a move: position and arc-length derivatives.
struct Shape {
    from: Point3,
    m: Move,
    len: f64,
}

impl Shape {
    fn eval(&self, s: f64) -> [Vec3; 4] {
        let m = &self.m;
        match (m.kind, m.sweep_from(self.from)) {
            (MoveKind::Arc { center, plane, .. }, Some((r0, sweep))) if self.len > 0.0 => {
                let u = (s / self.len).clamp(0.0, 1.0);
                let (fu, fv, fw) = plane.split(self.from - Point3::ORIGIN);
                let (cu, cv, _) = plane.split(center - Point3::ORIGIN);
                let (tu, tv, tw) = plane.split(m.to - Point3::ORIGIN);
                let r1 = (tu - cu).hypot(tv - cv);
                let a0 = (fv - cv).atan2(fu - cu);
                // The spiral r(u) = r0 + (r1 − r0)·u, angle a0 + sweep·u, u = s/len, in
                // Cartesian form: x = cu + r·cos a, y = cv + r·sin a, differentiated three
                // times in s with dr/ds = q and da/ds = w constant.
                let r = r0 + (r1 - r0) * u;
                let q = (r1 - r0) / self.len;
                let a = a0 + sweep * u;
                let w = sweep / self.len;
                let h = (tw - fw) / self.len;
                let (c, sn) = (a.cos(), a.sin());
                let (w2, w3) = (w * w, w * w * w);
                [
                    plane.join(cu + r * c, cv + r * sn, fw + (tw - fw) * u),
                    plane.join(q * c - r * w * sn, q * sn + r * w * c, h),
                    plane.join(
                        -2.0 * q * w * sn - r * w2 * c,
                        2.0 * q * w * c - r * w2 * sn,
                        0.0,
                    ),
                    plane.join(
                        -3.0 * q * w2 * c + r * w3 * sn,
                        -3.0 * q * w2 * sn - r * w3 * c,
                        0.0,
                    ),
                ]
            }
            _ => {
                let d = m.to - self.from;
                let dir = if self.len > 0.0 {
                    d / self.len
                } else {
                    Vec3::ZERO
                };
                let p = self.from + dir * s.clamp(0.0, self.len);
                [p - Point3::ORIGIN, dir, Vec3::ZERO, Vec3::ZERO]
            }
        }
    }
}

/// The largest `|P'|`, `|P''|`, `|P'''|` per axis over a move, and the largest `|P'|`
/// ([`Shape::bounds`]).
type Bounds = ([[f64; 3]; 3], f64);

impl Shape {
    /// The largest `|P'|`, `|P''|`, `|P'''|` per axis over the move, and the largest `|P'|`
    /// (module docs): a line's direction cosines; an arc's in its plane from its largest
    /// radius `ρ`, turn rate `w` and radial rate `q` (`√(q² + ρ²w²)`, `√(4q²w² + ρ²w⁴)`,
    /// `√(9q²w⁴ + ρ²w⁶)`), along its axis the rise rate alone.
    fn bounds(&self) -> Bounds {
        let m = &self.m;
        match (m.kind, m.sweep_from(self.from)) {
            (MoveKind::Arc { center, plane, .. }, Some((r0, sweep))) if self.len > 0.0 => {
                let (tu, tv, tw) = plane.split(m.to - Point3::ORIGIN);
                let (cu, cv, _) = plane.split(center - Point3::ORIGIN);
                let (_, _, fw) = plane.split(self.from - Point3::ORIGIN);
                let r1 = (tu - cu).hypot(tv - cv);
                let rho = r0.abs().max(r1);
                let q = (r1 - r0) / self.len;
                let w = (sweep / self.len).abs();
                let h = (tw - fw) / self.len;
                let d1 = q.hypot(rho * w);
                let d2 = (2.0 * q * w).hypot(rho * w * w);
                let d3 = (3.0 * q * w * w).hypot(rho * w * w * w);
                let abs = |v: Vec3| v.to_array().map(f64::abs);
                (
                    [
                        abs(plane.join(d1, d1, h)),
                        abs(plane.join(d2, d2, 0.0)),
                        abs(plane.join(d3, d3, 0.0)),
                    ],
                    d1.hypot(h),
                )
            }
            _ => {
                let [_, d1, _, _] = self.eval(0.0);
                (
                    [d1.to_array().map(f64::abs), [0.0; 3], [0.0; 3]],
                    d1.length(),
                )
            }
        }
    }
}

/// True when the stretch's bounds (module docs) keep every sample in it within the limits:
/// `limits` the block's per-axis ones, `feed` its feed limit if any.
fn stretch_is_quiet(
    peaks: (f64, f64, f64),
    bounds: &Bounds,
    limits: &[[(f64, f64); 3]; 3],
    feed: Option<(f64, f64)>,
) -> bool {
    let (v, a, j) = peaks;
    let ([m1, m2, m3], speed) = bounds;
    let within = |value: f64, over: f64| value * (1.0 + 1e-12) <= over;
    let axes_within = (0..3).all(|i| {
        let values = [
            m1[i] * v,
            m2[i] * v * v + m1[i] * a,
            m3[i] * v * v * v + 3.0 * m2[i] * v * a + m1[i] * j,
        ];
        limits[i]
            .iter()
            .zip(values)
            .all(|(&(lim, over), value)| !lim.is_finite() || within(value, over))
    });
    axes_within && feed.is_none_or(|(_, over)| within(speed * v, over))
}

/// The block being sampled and what its checks need: the limits and their thresholds
/// (`lim·(1 + tol) + 1e-9`), the line's derivatives (the same at every sample), and the
/// largest value of each checked quantity over the block's samples so far (the ratio to a
/// limit is monotonic in the value, so the largest ratio is the largest value's).
struct Current {
    block: usize,
    shape: Shape,
    /// Per-axis (velocity, acceleration, jerk) limits (rapids: the rapid velocity too) and
    /// the values above which they are violated.
    limits: [[(f64, f64); 3]; 3],
    /// The feed limit of a feed move and its threshold.
    feed_limit: Option<(f64, f64)>,
    /// The span the block belongs to.
    span: Option<u32>,
    /// The first three derivatives of a line (constant along it).
    line: Option<[Vec3; 3]>,
    /// Largest |velocity|, |acceleration|, |jerk| per axis and speed seen in the block.
    peak: [[f64; 3]; 3],
    peak_speed: f64,
}

/// A limit and the value above which it is violated (`lim·(1 + tol) + 1e-9`).
fn limit(lim: f64, tol: f64) -> (f64, f64) {
    (lim, lim * (1.0 + tol) + 1e-9)
}

/// The per-axis limits of feed moves (`[0]`) and of rapids (`[1]`), as [`Current`] holds them.
fn axis_limits(machine: &Machine, tol: f64) -> [[[(f64, f64); 3]; 3]; 2] {
    [false, true].map(|rapid| {
        std::array::from_fn(|i| {
            let ax = machine.axes[i];
            let vlim = if rapid {
                ax.max_velocity.min(machine.rapid[i])
            } else {
                ax.max_velocity
            };
            [
                limit(vlim, tol),
                limit(ax.max_acceleration, tol),
                limit(ax.max_jerk, tol),
            ]
        })
    })
}

impl Current {
    fn new(
        block: usize,
        shape: Shape,
        plan: &Plan,
        machine: &Machine,
        tol: f64,
        axis_limits: &[[[(f64, f64); 3]; 3]; 2],
    ) -> Current {
        let rapid = matches!(shape.m.kind, MoveKind::Rapid);
        let limits = axis_limits[usize::from(rapid)];
        let feed_limit = shape
            .m
            .is_feed()
            .then(|| limit(shape.m.feed.min(machine.max_feed), tol));
        let line = match shape.m.kind {
            MoveKind::Arc { .. } => None,
            _ => {
                let [_, d1, d2, d3] = shape.eval(0.0);
                Some([d1, d2, d3])
            }
        };
        Current {
            block,
            limits,
            feed_limit,
            span: plan.blocks.get(block).map(|b| b.span),
            line,
            peak: [[0.0; 3]; 3],
            peak_speed: 0.0,
            shape,
        }
    }

    /// Folds the block's peaks into the report's largest ratios.
    fn close(&self, rep: &mut VerifyReport) {
        for (axis, peaks) in self.limits.iter().zip(&self.peak) {
            for (w, ((lim, _), peak)) in axis.iter().zip(peaks).enumerate() {
                if lim.is_finite() {
                    rep.worst_ratio[w] = rep.worst_ratio[w].max(peak / lim);
                }
            }
        }
        if let Some((flim, _)) = self.feed_limit {
            rep.worst_ratio[3] = rep.worst_ratio[3].max(self.peak_speed / flim);
        }
    }
}

/// Verifies `plan`, made from `moves` (the `(from, move)` pairs it was planned from) for
/// `machine`.
pub fn verify_plan(
    plan: &Plan,
    moves: &[(Point3, Move)],
    machine: &Machine,
    opts: &VerifyOptions,
) -> Result<VerifyReport, Error> {
    if opts.rate.is_nan() || opts.rate < 1000.0 {
        return Err(crate::InputError::new("verifier rate", opts.rate)
            .expected("at least 1000 Hz")
            .into());
    }
    if plan.reshaped {
        return Err(crate::InputError::new("controller model", "linuxcnc")
            .at(format!("machine {}", machine.name))
            .expected(
                "a generic or sinumerik machine: a linuxcnc plan follows LinuxCNC's rules \
                 (kinks, parabolic blends), not the limit verifier's, and is checked against \
                 LinuxCNC itself",
            )
            .into());
    }
    if moves.len() != plan.blocks.len() {
        return Err(Error::internal("verifier: moves and plan differ in length"));
    }
    let shape = |i: usize| {
        moves.get(i).map(|&(from, m)| Shape {
            from,
            m,
            len: m.length_from(from),
        })
    };
    let tol = opts.rel_tol;
    let mut rep = VerifyReport::default();
    let dt = 1.0 / opts.rate;
    let jmax_any = machine.axes.iter().map(|a| a.max_jerk).fold(0.0, f64::max);
    let amax_any = machine
        .axes
        .iter()
        .map(|a| a.max_acceleration)
        .fold(0.0, f64::max);
    // The block being sampled (samples come in block order) and what its checks need.
    let mut current: Option<Current> = None;
    let limits = axis_limits(machine, tol);
    let mut prev: Option<(f64, Option<u32>, f64, f64, f64)> = None;
    let mut last_sample = None;
    // Each block's bounds, for the stretches (the last block's kept).
    let mut block_bounds: Option<(usize, Bounds)> = None;
    let quiet = |st: &super::sample::Stretch| {
        if opts.every_sample {
            return false;
        }
        let Some(sh) = shape(st.block) else {
            return false;
        };
        let b = match block_bounds {
            Some((k, b)) if k == st.block => b,
            _ => {
                let b = sh.bounds();
                block_bounds = Some((st.block, b));
                b
            }
        };
        let rapid = matches!(sh.m.kind, MoveKind::Rapid);
        let feed =
            sh.m.is_feed()
                .then(|| limit(sh.m.feed.min(machine.max_feed), tol));
        stretch_is_quiet(st.peaks(), &b, &limits[usize::from(rapid)], feed)
    };
    let bounded = plan.for_each_sparse_path_sample(dt, quiet, |smp| {
        rep.samples += 1;
        last_sample = Some(*smp);
        if current.as_ref().is_none_or(|c| c.block != smp.block) {
            if let Some(c) = &current {
                c.close(&mut rep);
            }
            let Some(sh) = shape(smp.block) else {
                return Err(Error::internal("verifier: sample outside the program"));
            };
            current = Some(Current::new(smp.block, sh, plan, machine, tol, &limits));
        }
        let Some(cur) = current.as_mut() else {
            return Err(Error::internal("verifier: no block"));
        };
        let st = smp.path;
        let [d1, d2, d3] = match cur.line {
            Some(d) => d,
            None => {
                let [_, d1, d2, d3] = cur.shape.eval(smp.s);
                [d1, d2, d3]
            }
        };
        let v = d1 * st.v;
        let a = d2 * (st.v * st.v) + d1 * st.a;
        let j = d3 * st.v.powi(3) + d2 * (3.0 * st.v * st.a) + d1 * st.j;
        let (v3, a3, j3) = (v.to_array(), a.to_array(), j.to_array());
        const KINDS: [ViolationKind; 3] = [
            ViolationKind::Velocity,
            ViolationKind::Acceleration,
            ViolationKind::Jerk,
        ];
        for ((lims, peaks), vals) in cur.limits.iter().zip(&mut cur.peak).zip([
            [v3[0].abs(), a3[0].abs(), j3[0].abs()],
            [v3[1].abs(), a3[1].abs(), j3[1].abs()],
            [v3[2].abs(), a3[2].abs(), j3[2].abs()],
        ]) {
            for (w, ((&(lim, over), peak), val)) in lims.iter().zip(peaks).zip(vals).enumerate() {
                if lim.is_finite() {
                    // The running maximum (a NaN, which `f64::max` would pass over, fails
                    // the comparison alike).
                    if val > *peak {
                        *peak = val;
                    }
                    if val > over {
                        rep.add(Violation {
                            kind: KINDS[w],
                            block: smp.block,
                            t: smp.t,
                            value: val,
                            limit: lim,
                        });
                    }
                }
            }
        }
        if let Some((flim, over)) = cur.feed_limit {
            // The tool's speed |P'|·ṡ (ṡ itself on lines and circles, where |P'| = 1).
            let speed = v.length();
            if speed > cur.peak_speed {
                cur.peak_speed = speed;
            }
            if speed > over {
                rep.add(Violation {
                    kind: ViolationKind::Feed,
                    block: smp.block,
                    t: smp.t,
                    value: speed,
                    limit: flim,
                });
            }
        }
        // Integration consistency of the path state within a span.
        if let Some((t0, span0, s0, v0, a0)) = prev {
            let h = smp.t - t0;
            if span0 == cur.span && h > 0.0 {
                let ds = st.s - s0;
                let pred = 0.5 * h * (v0 + st.v) + h * h * (a0 - st.a) / 12.0;
                // Exact for a cubic; a jerk jump inside the interval adds O(Δj·h³). Two
                // samples more than a grid step apart lie on one stretch: one cubic
                // (a grid step reads a few ulps of t longer or shorter).
                let step = dt * (1.0 + 1e-9) + 8.0 * f64::EPSILON * smp.t.abs();
                let slack = if h > step {
                    0.0
                } else if jmax_any.is_finite() {
                    4.0 * jmax_any * h.powi(3)
                } else {
                    amax_any * h * h
                };
                // The rounding of the times: a few ulps of t, at the two speeds.
                let slack = slack + 4.0 * f64::EPSILON * smp.t.abs() * (v0.abs() + st.v.abs());
                if (ds - pred).abs() > slack + 1e-9 * (1.0 + st.s.abs()) {
                    rep.add(Violation {
                        kind: ViolationKind::Consistency,
                        block: smp.block,
                        t: smp.t,
                        value: ds,
                        limit: pred,
                    });
                }
            }
        }
        prev = Some((smp.t, cur.span, st.s, st.v, st.a));
        Ok(())
    })?;
    rep.bounded = bounded;
    if let Some(c) = &current {
        c.close(&mut rep);
    }
    let last_sample = last_sample.map(|p| plan.sample_of(&p)).transpose()?;
    // Every block completed, and the junctions.
    if let (Some(last), Some(sh)) = (last_sample, moves.len().checked_sub(1).and_then(shape)) {
        let end = sh.eval(sh.len)[0];
        let got = last.position - Point3::ORIGIN;
        if (end - got).length() > 1e-6 {
            rep.add(Violation {
                kind: ViolationKind::Consistency,
                block: last.block,
                t: last.t,
                value: (end - got).length(),
                limit: 1e-6,
            });
        }
    }
    // The junctions, in time order (one span profile kept between them).
    let mut last_motion: Option<Shape> = None;
    let mut cursor = Cursor::default();
    for i in 0..moves.len() {
        let Some(sh) = shape(i) else { break };
        if sh.len <= 1e-12 || matches!(sh.m.kind, MoveKind::Dwell { .. }) {
            if matches!(sh.m.kind, MoveKind::Dwell { .. }) {
                last_motion = None;
            }
            continue;
        }
        if let (Some(prev_sh), Some(b)) = (&last_motion, plan.blocks.get(i)) {
            rep.junctions += 1;
            let v = plan.path_state_at(b.start_time, &mut cursor)?.v;
            check_junction(prev_sh, &sh, v, b.start_time, i, machine, tol, &mut rep);
        }
        last_motion = Some(sh);
    }
    Ok(rep)
}

/// Tangent-difference below which a corner also gets the tangent junction's curvature-step
/// check (the planner's `limits::NEAR_TANGENT`, restated here: the verifier does not import
/// the planner's model).
const NEAR_TANGENT: f64 = 1e-3;

#[allow(clippy::too_many_arguments)]
fn check_junction(
    a: &Shape,
    b: &Shape,
    v: f64,
    t: f64,
    block: usize,
    machine: &Machine,
    tol: f64,
    rep: &mut VerifyReport,
) {
    if v <= 1e-9 {
        return;
    }
    // An exact stop comes to rest at the end of its move, tangent to the next or not.
    if a.m.corner == Corner::ExactStop {
        rep.add(Violation {
            kind: ViolationKind::Corner,
            block,
            t,
            value: v,
            limit: 0.0,
        });
        return;
    }
    let ea = a.eval(a.len);
    let eb = b.eval(0.0);
    let t1 = ea[1] / ea[1].length().max(1e-300);
    let t2 = eb[1] / eb[1].length().max(1e-300);
    let du = t2 - t1;
    // The axis velocities step by v·(P'_b − P'_a): the unit tangents' difference on lines and
    // circles, plus a change of |P'| where a spiral arc meets another block.
    let dp = eb[1] - ea[1];
    let tipo = machine.ipo_cycle;
    let mut bad = |value: f64, limit: f64| {
        if value > limit * (1.0 + tol) + 1e-12 {
            rep.add(Violation {
                kind: ViolationKind::Corner,
                block,
                t,
                value,
                limit,
            });
        }
    };
    // The path tolerance at this junction (what a smoothing controller may use).
    let blend_tol = match a.m.corner {
        Corner::Machine => machine.path_tolerance,
        Corner::Blend(x) | Corner::BlendMerge { tolerance: x, .. } => x,
        _ => 0.0,
    };
    // The acceleration step v²·|Δκᵢ| of a curvature step: within one interpolation cycle
    // (jerk ≤ Jᵢ over T_ipo), or, on a controller that smooths it within the tolerance ε
    // (sinumerik, G642), spread over a curvature ramp of length L = √(24ε/|Δκ|) (the ramp
    // shifts the path by |Δκ|·L²/24): jerk v³·|Δκᵢ|/L ≤ Jᵢ.
    let smooths = machine.controller == crate::machine::Controller::Sinumerik && blend_tol > 0.0;
    let step_limit = |d: f64, dk_norm: f64, jm: f64| -> (f64, f64) {
        if smooths && dk_norm > 0.0 {
            let len = (24.0 * blend_tol / dk_norm).sqrt();
            (v * v * v * d.abs(), jm * len)
        } else {
            (v * v * d.abs(), jm * tipo)
        }
    };
    if du.length() <= 1e-9 {
        let dk = eb[2] - ea[2];
        let dkn = dk.length();
        for (i, (d, e)) in dk.to_array().iter().zip(dp.to_array()).enumerate() {
            let ax = machine.axes[i];
            if ax.max_jerk.is_finite() {
                let (value, limit) = step_limit(*d, dkn, ax.max_jerk);
                bad(value, limit);
            }
            bad(
                v * e.abs(),
                (ax.max_acceleration * tipo).min(ax.max_jerk * tipo * tipo),
            );
        }
        return;
    }
    // A near-tangent corner (G-code rounding tilts tangent junctions by up to ~1e-3 rad)
    // keeps the curvature step of the tangent case: a blend of so small a corner does not
    // remove the arc's curvature.
    if du.length() <= NEAR_TANGENT {
        let dk = eb[2] - ea[2];
        let dkn = dk.length();
        for (i, d) in dk.to_array().iter().enumerate() {
            let jm = machine.axes[i].max_jerk;
            if jm.is_finite() {
                let (value, limit) = step_limit(*d, dkn, jm);
                bad(value, limit);
            }
        }
    }
    let tolerance = match a.m.corner {
        Corner::Machine => machine.path_tolerance,
        Corner::Blend(x) | Corner::BlendMerge { tolerance: x, .. } => x,
        Corner::ExactStop => 0.0,
        Corner::ExactPath => {
            for (i, d) in dp.to_array().iter().enumerate() {
                let ax = machine.axes[i];
                bad(
                    v * d.abs(),
                    (ax.max_acceleration * tipo).min(ax.max_jerk * tipo * tipo),
                );
            }
            return;
        }
    };
    if tolerance <= 0.0 {
        bad(v, 0.0);
        return;
    }
    let amin = machine
        .axes
        .iter()
        .map(|x| x.max_acceleration)
        .fold(f64::INFINITY, f64::min);
    let jmin = machine
        .axes
        .iter()
        .map(|x| x.max_jerk)
        .fold(f64::INFINITY, f64::min);
    let mut r = v * v / amin;
    if jmin.is_finite() {
        r = r.max((v * v * v / jmin).sqrt());
    }
    let room = 0.5 * a.len.min(b.len);
    if blend_surely_fits(t1.dot(t2), r, tolerance, room, tol) {
        return;
    }
    let half = 0.5 * t1.dot(t2).clamp(-1.0, 1.0).acos();
    bad(r * (1.0 / half.cos() - 1.0), tolerance);
    bad(r * half.tan(), room);
}

/// Whether the blend checks above (`r·(1/cos(θ/2) − 1) ≤ tolerance`, `r·tan(θ/2) ≤ room`,
/// `cos θ = dot`) surely pass, without their trigonometry: with `c = dot ≥ ½`,
/// `cos(θ/2) = √((1+c)/2)`, `sin(θ/2) = √((1−c)/2)`, `1 − cos(θ/2) = (1−c)/(2(1 + cos(θ/2)))`;
/// the checks' own `acos`, `cos`, `tan` and `1/cos − 1` are each within a few 1e-16 of
/// these, which the upper bounds here add (8e-16 absolute, 1e-12 relative). `false` means
/// "compute them".
fn blend_surely_fits(dot: f64, r: f64, tolerance: f64, room: f64, rel: f64) -> bool {
    let c = dot.clamp(-1.0, 1.0);
    if !(c >= 0.5 && r.is_finite() && r >= 0.0) {
        return false;
    }
    let ch = ((1.0 + c) / 2.0).sqrt();
    let sh = ((1.0 - c) / 2.0).sqrt();
    let one_minus_ch = (1.0 - c) / (2.0 * (1.0 + ch));
    let ch_lo = ch - 8e-16;
    let sec_minus_one = (one_minus_ch * (1.0 + 1e-12) + 8e-16) / ch_lo + 8e-16;
    let deviation = r * sec_minus_one * (1.0 + 1e-12);
    let reach = r * (sh * (1.0 + 1e-12) / ch_lo) * (1.0 + 1e-12);
    deviation <= tolerance * (1.0 + rel) && reach <= room * (1.0 + rel)
}

#[cfg(test)]
mod tests;
