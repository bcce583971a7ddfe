//! Rigorous constraint certificates: an upper bound of the feed that certifies the feed limit,
//! and a proof that no shorter duration of an interval is feasible.
//!
//! # What is exact and what is certified
//! * **Motor limits** (every joint's velocity, acceleration, jerk) are checked exactly: they are
//!   polynomials of degree 4, 3, 2 in time, maximal at an end or at a root of the next
//!   derivative ([`super::quintic`]).
//! * **The feed** `f(t) = |d tip/dt|` goes through the forward kinematics and is no
//!   polynomial. [`feed_bound`] returns a *lower* bound (the largest sampled value, a value the
//!   trajectory attains) and a rigorous *upper* bound; it refines until either the upper bound
//!   is below the limit (**certified**), a sample exceeds the limit (**violated**), or the two
//!   bounds are within [`CertifyOptions::feed_rel_eps`] of the limit (**undecided**, counted as
//!   infeasible). So a feasible verdict is a proof, and an infeasible one is wrong by at most a
//!   relative `feed_rel_eps` (1e-9 by default: 30 pm/s at 30 mm/s).
//!
//! # The feed upper bound
//! Let `g = |tip'|²`, smooth. On a piece `[t0, t1]` of width `w`, `e = g − (linear interpolant of
//! g(t0), g(t1))` vanishes at both ends and `|e''| ≤ G2 := sup |g''|`, so
//! `e(t) ≤ G2 (t − t0)(t1 − t)/2 ≤ G2 w²/8` and
//!
//! ```text
//! max g ≤ max(g(t0), g(t1)) + G2 w² / 8,      G2 ≤ 2 S2² + 2 S1 S3
//! ```
//! (`g'' = 2|tip''|² + 2 tip'·tip'''`), with `S1, S2, S3` bounds of `|tip'|, |tip''|, |tip'''|`
//! on the piece. By the chain rule, `tip'' = Σ ∂_a tip q̈_a + Σ ∂_ab tip q̇_a q̇_b` and
//! `tip''' = Σ ∂_a tip q⃛_a + 3 Σ ∂_ab tip q̈_a q̇_b + Σ ∂_abc tip q̇_a q̇_b q̇_c`. The structural
//! facts of [`crate::machine::kinematics`] (derivatives with ≥ 2 linear indices vanish, with one
//! are ≤ 1, rotary-only ones are ≤ `R`) give, with `V, A, J` per-joint bounds of `|q̇|, |q̈|, |q⃛|`
//! on the piece and `VL = Σ_linear V`, `VR = Σ_rotary V` (likewise `A`, `J`):
//!
//! ```text
//! S1 = VL + R VR
//! S2 = AL + R AR + 2 VL VR + R VR²
//! S3 = JL + R JR + 3 (AL VR + VL AR + R AR VR) + 3 VL VR² + R VR³
//! ```
//! The per-joint bounds are rigorous: the jerk (a quadratic) exactly from its ends and vertex;
//! then `A ≤ max(|q̈(t0)|, |q̈(t1)|) + J w/2` and `V ≤ max(|q̇(t0)|, |q̇(t1)|) + A w/2` (a function
//! with Lipschitz constant `L` exceeds the larger end value by at most `L w/2`); the joint box
//! for `R` likewise. The gap shrinks as `w²`, so a piece is bisected until it certifies.
//!
//! # No shorter duration is feasible
//! With the end states fixed, a joint's position at the normalised time `u = t/T` is
//! `q(u; T) = α(u) + T β(u) + T² γ(u)` (the boundary-value solution is linear in the end
//! data: `α` carries the positions, `β` the velocities, `γ` the accelerations), so at a fixed
//! `u` the derivatives are explicit in `T`:
//!
//! ```text
//! v = α'/T + β' + γ' T,   a = α''/T² + β''/T + γ'',   j = α'''/T³ + β'''/T² + γ'''/T
//! ```
//! (primes in `u`). Their exact range over `[Ta, Tb]` needs the ends and the interior critical
//! points (`T² = α'/γ'`; in `s = 1/T` a parabola's vertex; a quadratic's roots). A **witness**
//! — a joint, a derivative order and a `u` where the limit is exceeded at some `T` — proves a
//! whole range of `T` infeasible when the range of its value stays beyond the limit. For a
//! feed witness, `|tip'(u, T)| ≥ |tip'(u, Tk)| − |J(q_T)(v_T − v_k)| − |(J(q_T) − J(q_k)) v_k|`,
//! bounded with the same structural constants over the joint box swept by `q(u; T)`.
//! [`certify_infeasible`] marches from a proven lower bound, each step jumping over the range
//! its best witness excludes. Feasibility is **not** monotone in `T` for moving end states
//! (a longer interval can overshoot), which is why the march, and not a monotonicity
//! argument, carries the proof.

use super::quintic::{End, Quintic, poly_eval, real_roots_in};
use super::segment::{KnotState, Limits, Segment};
use crate::machine::kinematics::{Joints, Kinematics};
use serde::{Deserialize, Serialize};

/// Options of the certificates. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct CertifyOptions {
    /// Initial feed samples per interval. Default 48.
    pub feed_samples: usize,
    /// Relative width (of the feed limit) below which an upper bound above the limit and a
    /// sample below it are left undecided. Default 1e-9.
    pub feed_rel_eps: f64,
    /// Largest bisection depth of a feed piece. Default 40.
    pub max_depth: usize,
    /// Largest number of march steps of [`certify_infeasible`]. Default 400.
    pub max_steps: usize,
}

impl Default for CertifyOptions {
    fn default() -> Self {
        CertifyOptions {
            feed_samples: 48,
            feed_rel_eps: 1e-9,
            max_depth: 40,
            max_steps: 400,
        }
    }
}

option_builders! {
    CertifyOptions;
    /// Sets [`CertifyOptions::feed_samples`].
    with_feed_samples => feed_samples: usize;
    /// Sets [`CertifyOptions::feed_rel_eps`].
    with_feed_rel_eps => feed_rel_eps: f64;
    /// Sets [`CertifyOptions::max_depth`].
    with_max_depth => max_depth: usize;
    /// Sets [`CertifyOptions::max_steps`].
    with_max_steps => max_steps: usize;
}

/// Verdict of [`feed_bound`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FeedVerdict {
    /// The upper bound is at most the limit: the feed limit holds, proven.
    Certified,
    /// A sampled feed exceeds the limit: the feed limit is violated, proven.
    Violated,
    /// The bounds straddle the limit within the tolerance.
    Undecided,
}

/// Bounds of the largest feed of an interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FeedBound {
    /// Largest feed found at a sample (attained), mm/s.
    pub lower: f64,
    /// Where, s into the interval.
    pub t_lower: f64,
    /// Rigorous upper bound, mm/s (of the pieces examined; with
    /// [`FeedVerdict::Violated`] it is not a bound of the whole interval).
    pub upper: f64,
    /// The verdict.
    pub verdict: FeedVerdict,
    /// Feed evaluations used.
    pub evaluations: usize,
}

#[derive(Debug, Clone, Copy)]
struct Node {
    t: f64,
    q: Joints,
    v: Joints,
    a: Joints,
    j: Joints,
    g: f64,
}

fn node(seg: &Segment, kin: &dyn Kinematics, t: f64) -> Node {
    let [q, v, a, j] = seg.eval(t);
    let jac = kin.jacobian(&q);
    let mut g = 0.0;
    for row in jac.iter().take(3) {
        let d: f64 = row.iter().zip(&v).map(|(x, y)| x * y).sum();
        g += d * d;
    }
    Node { t, q, v, a, j, g }
}

/// Rigorous bound of `g = |tip'|²` on the piece between two nodes (see the module docs).
fn piece_bound(seg: &Segment, kin: &dyn Kinematics, n0: &Node, n1: &Node) -> f64 {
    let w = n1.t - n0.t;
    let half = 0.5 * w;
    let mut lo = [0.0; 5];
    let mut hi = [0.0; 5];
    let (mut vl, mut vr, mut al, mut ar, mut jl, mut jr) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for i in 0..5 {
        // Jerk: a quadratic in t, exact on the piece (ends and vertex).
        let c = &seg.axes[i].c;
        let mut jb = n0.j[i].abs().max(n1.j[i].abs());
        if c[5] != 0.0 {
            let tv = -24.0 * c[4] / (120.0 * c[5]);
            if tv > n0.t && tv < n1.t {
                jb = jb.max((6.0 * c[3] + tv * (24.0 * c[4] + tv * 60.0 * c[5])).abs());
            }
        }
        let ab = n0.a[i].abs().max(n1.a[i].abs()) + jb * half;
        let vb = n0.v[i].abs().max(n1.v[i].abs()) + ab * half;
        lo[i] = n0.q[i].min(n1.q[i]) - vb * half;
        hi[i] = n0.q[i].max(n1.q[i]) + vb * half;
        if i < 3 {
            vl += vb;
            al += ab;
            jl += jb;
        } else {
            vr += vb;
            ar += ab;
            jr += jb;
        }
    }
    let r = kin.lever_bound(&lo, &hi);
    let s1 = vl + r * vr;
    let s2 = al + r * ar + 2.0 * vl * vr + r * vr * vr;
    let s3 = jl
        + r * jr
        + 3.0 * (al * vr + vl * ar + r * ar * vr)
        + 3.0 * vl * vr * vr
        + r * vr * vr * vr;
    let g2 = 2.0 * s2 * s2 + 2.0 * s1 * s3;
    // A few ulps for the rounding of g itself.
    n0.g.max(n1.g) * (1.0 + 1e-14) + g2 * w * w / 8.0
}

/// Lower and rigorous upper bound of the largest feed of `seg`, decided against `limit`
/// (see the module docs). With `stop_early`, returns at the first undecided piece.
pub fn feed_bound(
    seg: &Segment,
    kin: &dyn Kinematics,
    limit: f64,
    opts: &CertifyOptions,
    stop_early: bool,
) -> FeedBound {
    let n = opts.feed_samples.max(2);
    let nodes: Vec<Node> = (0..=n)
        .map(|i| node(seg, kin, seg.duration * i as f64 / n as f64))
        .collect();
    let mut out = FeedBound {
        lower: 0.0,
        t_lower: 0.0,
        upper: 0.0,
        verdict: FeedVerdict::Certified,
        evaluations: nodes.len(),
    };
    let see = |out: &mut FeedBound, nd: &Node| {
        let f = nd.g.sqrt();
        if f > out.lower || f.is_nan() {
            out.lower = f;
            out.t_lower = nd.t;
        }
    };
    for nd in &nodes {
        see(&mut out, nd);
    }
    if out.lower > limit || out.lower.is_nan() {
        out.verdict = FeedVerdict::Violated;
        out.upper = out.lower;
        return out;
    }
    let eps = opts.feed_rel_eps.max(0.0) * limit;
    let mut stack: Vec<(Node, Node, usize)> = nodes.windows(2).map(|w| (w[0], w[1], 0)).collect();
    while let Some((a, b, depth)) = stack.pop() {
        let ub = piece_bound(seg, kin, &a, &b).sqrt();
        if ub <= limit {
            out.upper = out.upper.max(ub);
            continue;
        }
        if ub - out.lower <= eps || depth >= opts.max_depth || !ub.is_finite() {
            out.upper = out.upper.max(ub);
            out.verdict = FeedVerdict::Undecided;
            if stop_early {
                return out;
            }
            continue;
        }
        let m = node(seg, kin, 0.5 * (a.t + b.t));
        out.evaluations += 1;
        see(&mut out, &m);
        if out.lower > limit {
            out.verdict = FeedVerdict::Violated;
            out.upper = out.upper.max(out.lower);
            return out;
        }
        stack.push((a, m, depth + 1));
        stack.push((m, b, depth + 1));
    }
    out.upper = out.upper.max(out.lower);
    out
}

/// `q(u; T) = α(u) + T β(u) + T² γ(u)` of one joint, coefficients in `u`.
#[derive(Debug, Clone, Copy)]
struct TPoly {
    p: [[f64; 6]; 3],
}

impl TPoly {
    fn new(s0: &KnotState, s1: &KnotState, i: usize) -> TPoly {
        let part = |e0: End, e1: End| Quintic::from_ends(e0, e1, 1.0).c;
        let z = End::default();
        TPoly {
            p: [
                part(End { q: s0.q[i], ..z }, End { q: s1.q[i], ..z }),
                part(End { v: s0.v[i], ..z }, End { v: s1.v[i], ..z }),
                part(End { a: s0.a[i], ..z }, End { a: s1.a[i], ..z }),
            ],
        }
    }

    /// `k`-th u-derivative of part `m` at `u`.
    fn d(&self, m: usize, k: usize, u: f64) -> f64 {
        let mut c = self.p[m].to_vec();
        for _ in 0..k {
            c = c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(n, x)| x * n as f64)
                .collect();
        }
        poly_eval(&c, u)
    }

    /// Coefficients `(x, y, z)` of the order-`k` time derivative at `u` written as
    /// `x T^{−k} + y T^{1−k} + z T^{2−k}`.
    fn coeffs(&self, k: usize, u: f64) -> [f64; 3] {
        [self.d(0, k, u), self.d(1, k, u), self.d(2, k, u)]
    }
}

/// Value of `x T^{−k} + y T^{1−k} + z T^{2−k}`.
fn val(c: [f64; 3], k: usize, t: f64) -> f64 {
    let s = 1.0 / t;
    let p = s.powi(k as i32);
    c[0] * p + c[1] * p * t + c[2] * p * t * t
}

/// Exact range over `T ∈ [ta, tb]` of `x T^{−k} + y T^{1−k} + z T^{2−k}`, `k ∈ 0..=3`.
fn range_in_t(c: [f64; 3], k: usize, ta: f64, tb: f64) -> (f64, f64) {
    let mut ts = vec![ta, tb];
    // Critical points: d/dT = 0 ⇔ −k x T^{−k−1} + (1−k) y T^{−k} + (2−k) z T^{1−k} = 0,
    // i.e. (2−k) z T² + (1−k) y T − k x = 0 (times T^{k+1}).
    let k_f = k as f64;
    let quad = [-k_f * c[0], (1.0 - k_f) * c[1], (2.0 - k_f) * c[2]];
    ts.extend(real_roots_in(&quad, ta, tb));
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for t in ts {
        let v = val(c, k, t);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    (lo, hi)
}

/// A point where a limit is exceeded at the duration where it was found: joint (or `None`
/// for the feed), derivative order (1 velocity, 2 acceleration, 3 jerk), normalised time `u`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Witness {
    joint: Option<usize>,
    order: usize,
    u: f64,
}

/// Exact argmax of `|d^k q/dt^k|` on `[0, T]` for a quintic.
fn argmax(q: &Quintic, k: usize) -> (f64, f64) {
    let c = &q.c;
    let d: Vec<f64> = match k {
        1 => vec![c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4], 5.0 * c[5]],
        2 => vec![2.0 * c[2], 6.0 * c[3], 12.0 * c[4], 20.0 * c[5]],
        _ => vec![6.0 * c[3], 24.0 * c[4], 60.0 * c[5]],
    };
    let dd: Vec<f64> = d
        .iter()
        .enumerate()
        .skip(1)
        .map(|(n, x)| x * n as f64)
        .collect();
    let mut best = (0.0f64, 0.0);
    for t in real_roots_in(&dd, 0.0, q.duration)
        .into_iter()
        .chain([0.0, q.duration])
    {
        let v = poly_eval(&d, t).abs();
        if v >= best.0 {
            best = (v, t);
        }
    }
    best
}

/// Every violated limit of the interval of duration `t`, as witnesses.
fn witnesses(
    s0: &KnotState,
    s1: &KnotState,
    t: f64,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &CertifyOptions,
) -> Vec<Witness> {
    let seg = Segment::new(s0, s1, t);
    let mut out = Vec::new();
    for (i, ax) in seg.axes.iter().enumerate() {
        for (k, l) in [(1, lim.vel[i]), (2, lim.acc[i]), (3, lim.jerk[i])] {
            let (v, at) = argmax(ax, k);
            if v > l {
                out.push(Witness {
                    joint: Some(i),
                    order: k,
                    u: at / t,
                });
            }
        }
    }
    // A finer tolerance than the feasibility check's: within `feed_rel_eps` of the limit the
    // check is undecided, and a witness is wanted there too.
    let fine = CertifyOptions {
        feed_rel_eps: opts.feed_rel_eps * 1e-3,
        ..*opts
    };
    let fb = feed_bound(&seg, kin, lim.feed, &fine, true);
    if fb.lower > lim.feed {
        // The sample that exceeds the limit, moved to the local maximum of the feed (golden
        // section on the neighbouring samples' bracket): the larger the excess, the wider the
        // range of durations the witness excludes.
        let h = t / opts.feed_samples.max(2) as f64;
        let (mut a, mut b) = ((fb.t_lower - h).max(0.0), (fb.t_lower + h).min(t));
        let f = |x: f64| seg.feed(kin, x);
        const R: f64 = 0.618_033_988_749_894_9;
        let (mut x1, mut x2) = (b - R * (b - a), a + R * (b - a));
        let (mut f1, mut f2) = (f(x1), f(x2));
        for _ in 0..60 {
            if f1 < f2 {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + R * (b - a);
                f2 = f(x2);
            } else {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - R * (b - a);
                f1 = f(x1);
            }
        }
        let best = [(fb.lower, fb.t_lower), (f1, x1), (f2, x2)]
            .into_iter()
            .fold(
                (f64::NEG_INFINITY, 0.0),
                |m, p| if p.0 > m.0 { p } else { m },
            );
        out.push(Witness {
            joint: None,
            order: 1,
            u: best.1 / t,
        });
    }
    out
}

/// Whether `w` proves every `T ∈ [ta, tb]` infeasible (a feed witness is expanded about
/// `ta`, where it was found).
fn excludes(
    w: &Witness,
    tp: &[TPoly; 5],
    kin: &dyn Kinematics,
    lim: &Limits,
    ta: f64,
    tb: f64,
) -> bool {
    match w.joint {
        Some(i) => {
            let l = match w.order {
                1 => lim.vel[i],
                2 => lim.acc[i],
                _ => lim.jerk[i],
            };
            let (lo, hi) = range_in_t(tp[i].coeffs(w.order, w.u), w.order, ta, tb);
            // A relative 1e-12 for the rounding of the evaluation.
            let l = l * (1.0 + 1e-12);
            lo > l || hi < -l
        }
        None => {
            let tk = ta;
            let mut qk = [0.0; 5];
            let mut vk = [0.0; 5];
            let mut dq = [0.0; 5];
            let mut dv = [0.0; 5];
            let mut lo = [0.0; 5];
            let mut hi = [0.0; 5];
            for i in 0..5 {
                let cq = tp[i].coeffs(0, w.u);
                let cv = tp[i].coeffs(1, w.u);
                qk[i] = val(cq, 0, tk);
                vk[i] = val(cv, 1, tk);
                let (ql, qh) = range_in_t(cq, 0, ta, tb);
                let (vl, vh) = range_in_t(cv, 1, ta, tb);
                lo[i] = ql;
                hi[i] = qh;
                dq[i] = (qh - qk[i]).abs().max((ql - qk[i]).abs());
                dv[i] = (vh - vk[i]).abs().max((vl - vk[i]).abs());
            }
            let jac = kin.jacobian(&qk);
            let mut g = 0.0;
            for row in jac.iter().take(3) {
                let d: f64 = row.iter().zip(&vk).map(|(x, y)| x * y).sum();
                g += d * d;
            }
            let r = kin.lever_bound(&lo, &hi);
            let sum = |x: &[f64; 5], from: usize, to: usize| {
                x[from..to].iter().map(|v| v.abs()).sum::<f64>()
            };
            let (dvl, dvr) = (sum(&dv, 0, 3), sum(&dv, 3, 5));
            let (dql, dqr) = (sum(&dq, 0, 3), sum(&dq, 3, 5));
            let (vkl, vkr) = (sum(&vk, 0, 3), sum(&vk, 3, 5));
            let drift = dvl + r * dvr + dql * vkr + dqr * vkl + r * dqr * vkr;
            g.sqrt() * (1.0 - 1e-14) - drift > lim.feed
        }
    }
}

/// Proof that no duration in `[from, to]` is feasible: the largest `T ≤ to` such that every
/// duration in `[from, T]` is proven infeasible (see the module docs), and the march steps.
/// Returns `from` when no witness covers anything (for instance when `from` is feasible).
pub fn certify_infeasible(
    s0: &KnotState,
    s1: &KnotState,
    kin: &dyn Kinematics,
    lim: &Limits,
    from: f64,
    to: f64,
    opts: &CertifyOptions,
) -> (f64, usize) {
    let tp: [TPoly; 5] = std::array::from_fn(|i| TPoly::new(s0, s1, i));
    let mut cur = from;
    let mut steps = 0;
    while cur < to && steps < opts.max_steps {
        steps += 1;
        let ws = witnesses(s0, s1, cur, kin, lim, opts);
        let mut reach = cur;
        for w in &ws {
            if excludes(w, &tp, kin, lim, cur, to) {
                reach = to;
                break;
            }
            // Bisect the reach of this witness (the tested range always starts at `cur`).
            let (mut ok, mut bad) = (cur, to);
            for _ in 0..40 {
                let mid = 0.5 * (ok + bad);
                if excludes(w, &tp, kin, lim, cur, mid) {
                    ok = mid;
                } else {
                    bad = mid;
                }
                if bad - ok <= 1e-6 * (bad - cur) {
                    break;
                }
            }
            reach = reach.max(ok);
        }
        if reach <= cur {
            break;
        }
        cur = reach;
    }
    (cur.min(to), steps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::kinematics::{HeadHead, PaperAb};

    fn state(q: Joints, v: Joints, a: Joints) -> KnotState {
        KnotState { q, v, a }
    }

    #[test]
    fn t_decomposition_matches_the_quintic() {
        let s0 = state(
            [1.0, 2.0, 3.0, 0.1, 0.2],
            [5.0, -3.0, 1.0, 0.1, -0.2],
            [50.0, 0.0, -20.0, 1.0, 2.0],
        );
        let s1 = state(
            [4.0, 0.0, 3.5, 0.2, 0.1],
            [2.0, 1.0, 0.0, 0.0, 0.3],
            [-10.0, 5.0, 0.0, 0.5, -1.0],
        );
        for t in [0.05, 0.3, 1.7] {
            let seg = Segment::new(&s0, &s1, t);
            for i in 0..5 {
                let tp = TPoly::new(&s0, &s1, i);
                for u in [0.0, 0.3, 0.77, 1.0] {
                    let e = seg.axes[i].eval(u * t);
                    for (k, &want) in e.iter().enumerate() {
                        let got = val(tp.coeffs(k, u), k, t);
                        assert!(
                            (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
                            "{i} {k} {u} {got} {want}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn range_in_t_contains_dense_samples_and_is_tight() {
        let c = [2.0, -3.0, 1.5];
        for k in 0..4 {
            let (lo, hi) = range_in_t(c, k, 0.4, 2.5);
            let (mut slo, mut shi) = (f64::INFINITY, f64::NEG_INFINITY);
            for i in 0..=20_000 {
                let t = 0.4 + 2.1 * f64::from(i) / 20_000.0;
                let v = val(c, k, t);
                slo = slo.min(v);
                shi = shi.max(v);
            }
            assert!(lo <= slo + 1e-12 && hi >= shi - 1e-12, "{k}");
            assert!(
                slo - lo < 1e-6 && hi - shi < 1e-6,
                "{k}: {lo} {slo} {hi} {shi}"
            );
        }
    }

    /// The rigorous upper bound is above a dense sampling of the feed, and certification
    /// agrees with it.
    #[test]
    fn feed_bound_brackets_the_dense_maximum() {
        let kin = PaperAb::paper();
        let s0 = state(
            [0.0, 0.0, 0.0, 0.1, 0.2],
            [10.0, 5.0, -3.0, 0.1, -0.05],
            [0.0; 5],
        );
        let s1 = state(
            [5.0, 2.0, -1.0, 0.2, 0.15],
            [5.0, 0.0, 1.0, 0.0, 0.05],
            [10.0, 0.0, 0.0, 0.1, 0.0],
        );
        let seg = Segment::new(&s0, &s1, 0.4);
        let mut dense = 0.0f64;
        for i in 0..=50_000 {
            dense = dense.max(seg.feed(&kin, 0.4 * f64::from(i) / 50_000.0));
        }
        let o = CertifyOptions::default();
        let b = feed_bound(&seg, &kin, dense * 1.001, &o, false);
        assert_eq!(b.verdict, FeedVerdict::Certified);
        assert!(
            b.upper >= dense && b.upper <= dense * 1.001,
            "{b:?} {dense}"
        );
        let b = feed_bound(&seg, &kin, dense * 0.999, &o, false);
        assert_eq!(b.verdict, FeedVerdict::Violated);
        let b = feed_bound(&seg, &kin, dense, &o, false);
        assert_ne!(b.verdict, FeedVerdict::Certified, "{b:?}");
    }

    /// Rest to rest on a head-head machine the minimum time is known in closed form; every
    /// shorter duration is proven infeasible up to it.
    #[test]
    fn march_reaches_the_closed_form_minimum() {
        let kin = HeadHead::typical();
        let s0 = KnotState::default();
        let mut s1 = KnotState::default();
        s1.q[0] = 10.0;
        let lim = Limits::paper();
        let want = 15.0 * 10.0 / (8.0 * 30.0);
        let (reach, steps) = certify_infeasible(
            &s0,
            &s1,
            &kin,
            &lim,
            0.01,
            want * (1.0 - 1e-6),
            &CertifyOptions::default(),
        );
        assert!(
            reach >= want * (1.0 - 1e-6),
            "{reach} vs {want}, {steps} steps"
        );
        // It must not certify beyond the true minimum.
        let (reach, _) = certify_infeasible(
            &s0,
            &s1,
            &kin,
            &lim,
            0.01,
            want * 1.01,
            &CertifyOptions::default(),
        );
        assert!(reach <= want, "{reach} > {want}");
    }
}
