//! Exact per-interval minimum time.
//!
//! # Constraint check
//! An interval is five quintics, one per joint (linear axes in mm, rotary in rad), all of
//! duration `T`. The motor limits are checked **exactly** with the quintics' analytic extrema
//! ([`super::quintic`]). The feed is the tool-tip speed in the workpiece frame,
//! `f(t) = |J_tip(q(t)) q̇(t)|`, which goes through the kinematics and is no polynomial. Two
//! checks ([`FeedCheck`]):
//! * [`FeedCheck::Certified`] (default): the rigorous upper bound of
//!   [`super::certify::feed_bound`] — a feasible verdict is a proof; an upper bound above the
//!   limit with every sample below it, within a relative `certify.feed_rel_eps` (1e-9), counts
//!   as infeasible;
//! * [`FeedCheck::Sampled`]: [`MinTimeOptions::feed_samples`] samples, then golden-section
//!   refinement of every sampled local maximum that could hold the true maximum. A lower bound
//!   of the maximum; the knot optimiser iterates with it (fast) and re-solves its final states
//!   certified.
//!
//! The *margin* of a check is `min over constraints (1 − value / limit)`: ≥ 0 means feasible.
//!
//! # Search
//! With the end states fixed, feasibility is monotone in `T` when both ends are at rest (all
//! derivatives scale as `T⁻ⁿ`) but not in general: high end velocities make a long interval
//! overshoot (`v = α'/T + β' + γ'T` at a fixed `u`, see [`super::certify`]). So the search
//! brackets the true predicate's boundary and shrinks the bracket, then proves what it found:
//! 1. a proven lower bound `T_lb = max(|Δq_i| / v_max,i, |Δtip| / F)` (the mean velocity over
//!    the interval is at most the peak, and the chord is at most the arc); between rest states
//!    also the bang-bang times `2√(|Δq_i|/A_i)` and `(32|Δq_i|/J_i)^⅓`;
//! 2. an upward scan `T_lb·ρᵏ` (ρ = [`MinTimeOptions::scan_ratio`]) to the first feasible
//!    `T` — or, warm-started at a guess ([`min_time_near`]), a scan from the guess down while
//!    feasible and up while not, the ratio squaring at every step;
//! 3. between the last infeasible and the first feasible point, the Illinois variant of
//!    regula falsi on the margin (a bisection step whenever two steps did not halve the
//!    bracket) to a relative width of [`MinTimeOptions::rel_tol`] (1e-13). The result is
//!    feasible (exact motors, certified feed);
//! 4. the proof ([`super::certify::certify_infeasible`]): witnesses whose values are explicit
//!    in `T` exclude every duration in `[T_lb, T·(1 − prove_rel)]`, so a feasible island below
//!    the scan cannot have been missed. [`Check::proven_below`] records how far the proof
//!    reached (on the paper's case, every interval to `1 − 1e-8` of its time).

use super::certify::{CertifyOptions, FeedVerdict, certify_infeasible, feed_bound};
pub use super::segment::{KnotState, Limits, Segment};
use crate::machine::kinematics::Kinematics;
use serde::{Deserialize, Serialize};

/// How [`check`] decides the feed limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FeedCheck {
    /// Samples plus golden-section refinement of the local maxima: fast, a lower bound of the
    /// true maximum (used while the knot optimiser iterates).
    Sampled,
    /// The rigorous upper bound of [`super::certify::feed_bound`]: a feasible verdict is a
    /// proof.
    Certified,
}

/// Options of the per-interval search. Built from [`Default`] with the `with_*` methods (the struct
/// is `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct MinTimeOptions {
    /// Feed samples per interval before refinement. Default 48.
    pub feed_samples: usize,
    /// Scan ratio ρ > 1. Default 1.01.
    pub scan_ratio: f64,
    /// Largest `T / T_lb` scanned before giving up. Default 1e3.
    pub scan_span: f64,
    /// Relative width of the final bracket. Default 1e-13.
    pub rel_tol: f64,
    /// How the feed limit is decided. Default [`FeedCheck::Certified`].
    pub feed: FeedCheck,
    /// Options of the feed bound and of the proof of minimality.
    pub certify: CertifyOptions,
    /// Prove that no shorter duration is feasible ([`super::certify::certify_infeasible`]) up
    /// to a relative `prove_rel` below the result; 0 skips the proof. Default 1e-8.
    pub prove_rel: f64,
}

impl Default for MinTimeOptions {
    fn default() -> Self {
        MinTimeOptions {
            feed_samples: 48,
            scan_ratio: 1.01,
            scan_span: 1e3,
            rel_tol: 1e-13,
            feed: FeedCheck::Certified,
            certify: CertifyOptions::default(),
            prove_rel: 1e-8,
        }
    }
}

option_builders! {
    MinTimeOptions;
    /// Sets [`MinTimeOptions::feed_samples`].
    with_feed_samples => feed_samples: usize;
    /// Sets [`MinTimeOptions::scan_ratio`].
    with_scan_ratio => scan_ratio: f64;
    /// Sets [`MinTimeOptions::scan_span`].
    with_scan_span => scan_span: f64;
    /// Sets [`MinTimeOptions::rel_tol`].
    with_rel_tol => rel_tol: f64;
    /// Sets [`MinTimeOptions::feed`].
    with_feed => feed: FeedCheck;
    /// Sets [`MinTimeOptions::certify`].
    with_certify => certify: CertifyOptions;
    /// Sets [`MinTimeOptions::prove_rel`].
    with_prove_rel => prove_rel: f64;
}

/// Which constraint is tightest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Binding {
    /// The feed.
    Feed,
    /// Velocity of a joint.
    Velocity(usize),
    /// Acceleration of a joint.
    Acceleration(usize),
    /// Jerk of a joint.
    Jerk(usize),
}

/// Result of a constraint check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// `min (1 − value/limit)`; ≥ 0 is feasible. With [`FeedCheck::Certified`] the feed's
    /// value is its rigorous upper bound when feasible.
    pub margin: f64,
    /// The tightest constraint.
    pub binding: Binding,
    /// Every duration in `[0, proven_below)` is proven infeasible (0 when not proven); see
    /// [`min_time`].
    pub proven_below: f64,
}

/// Exact check of the motor limits, then the feed (skipped when `early_exit` and a motor limit
/// already fails).
pub fn check(
    seg: &Segment,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
    early_exit: bool,
) -> Check {
    let mut best = Check {
        margin: f64::INFINITY,
        binding: Binding::Feed,
        proven_below: 0.0,
    };
    for (i, ax) in seg.axes.iter().enumerate() {
        let [v, a, j] = ax.max_abs_derivs();
        for (m, b) in [
            (1.0 - v / lim.vel[i], Binding::Velocity(i)),
            (1.0 - a / lim.acc[i], Binding::Acceleration(i)),
            (1.0 - j / lim.jerk[i], Binding::Jerk(i)),
        ] {
            if m < best.margin || m.is_nan() {
                best = Check {
                    margin: m,
                    binding: b,
                    proven_below: 0.0,
                };
            }
        }
    }
    if early_exit && (best.margin < 0.0 || best.margin.is_nan()) {
        return best;
    }
    let feed = match opts.feed {
        FeedCheck::Sampled => max_feed(seg, kin, opts.feed_samples, early_exit.then_some(lim.feed)),
        FeedCheck::Certified => {
            let b = feed_bound(seg, kin, lim.feed, &opts.certify, early_exit);
            match b.verdict {
                FeedVerdict::Certified => b.upper,
                FeedVerdict::Violated => b.lower,
                // Undecided counts as infeasible, by the smallest amount the bound allows.
                FeedVerdict::Undecided => b.upper.max(lim.feed * (1.0 + f64::EPSILON)),
            }
        }
    };
    let fm = 1.0 - feed / lim.feed;
    if fm < best.margin || fm.is_nan() {
        best = Check {
            margin: fm,
            binding: Binding::Feed,
            proven_below: 0.0,
        };
    }
    best
}

/// Maximum feed over the segment: samples, then golden-section refinement of local maxima.
/// With `stop_above`, returns as soon as a sample exceeds it (the value is then a lower bound).
pub fn max_feed(
    seg: &Segment,
    kin: &dyn Kinematics,
    samples: usize,
    stop_above: Option<f64>,
) -> f64 {
    let n = samples.max(4);
    let h = seg.duration / n as f64;
    let f: Vec<f64> = (0..=n).map(|i| seg.feed(kin, h * i as f64)).collect();
    let mut best = f.iter().copied().fold(0.0, f64::max);
    if stop_above.is_some_and(|s| best > s) {
        return best;
    }
    // Between samples the feed can exceed its sampled neighbours by about h²·|f''|/8; the
    // second differences estimate h²·|f''|, and only local maxima within four times that
    // estimate of the best sample can hold the true maximum, so only those are refined.
    let d2 = f
        .windows(3)
        .map(|w| (w[2] - 2.0 * w[1] + w[0]).abs())
        .fold(0.0, f64::max);
    let sampled_best = best;
    for i in 0..=n {
        let left = if i == 0 { f64::NEG_INFINITY } else { f[i - 1] };
        let right = f.get(i + 1).copied().unwrap_or(f64::NEG_INFINITY);
        if f[i] >= left && f[i] >= right && f[i] >= sampled_best - 0.5 * d2 - 1e-12 * sampled_best {
            let lo = h * (i.saturating_sub(1)) as f64;
            let hi = (h * (i + 1) as f64).min(seg.duration);
            best = best.max(golden_max(|t| seg.feed(kin, t), lo, hi));
        }
    }
    best
}

fn golden_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    const R: f64 = 0.618_033_988_749_894_9;
    let mut x1 = b - R * (b - a);
    let mut x2 = a + R * (b - a);
    let (mut f1, mut f2) = (f(x1), f(x2));
    let mut best = f1.max(f2);
    let width = b - a;
    while b - a > 1e-10 * width.max(1e-300) {
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
        best = best.max(f1).max(f2);
    }
    best
}

/// Proven lower bound of the interval time (see the module docs).
pub fn lower_bound(s0: &KnotState, s1: &KnotState, kin: &dyn Kinematics, lim: &Limits) -> f64 {
    let mut t: f64 = 1e-9;
    let at_rest = [s0, s1]
        .iter()
        .all(|s| s.v.iter().chain(&s.a).all(|x| *x == 0.0));
    for i in 0..5 {
        let dq = (s1.q[i] - s0.q[i]).abs();
        t = t.max(dq / lim.vel[i]);
        if at_rest {
            // Rest to rest: bang-bang acceleration needs 2√(Δq/A), bang-bang jerk (32Δq/J)^⅓.
            t = t.max(2.0 * (dq / lim.acc[i]).sqrt());
            t = t.max((32.0 * dq / lim.jerk[i]).cbrt());
        }
    }
    let chord = kin.forward(&s0.q).tip.distance(kin.forward(&s1.q).tip);
    t.max(chord / lim.feed)
}

/// The minimum feasible duration and its check, or `None` when no duration up to
/// `scan_span · T_lb` is feasible with these end states.
pub fn min_time(
    s0: &KnotState,
    s1: &KnotState,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
) -> Option<(f64, Check)> {
    min_time_near(s0, s1, kin, lim, opts, None)
}

/// [`min_time`] warm-started at `guess` (a duration near the expected result, such as the
/// interval's time at the previous iteration): the bracket is searched from `guess`, down
/// while feasible and up while not, the step ratio squaring at each step (from
/// [`MinTimeOptions::scan_ratio`]), instead of scanning up from `T_lb` at a constant ratio.
/// The result is feasible and the proof of minimality is the same; only a feasible island
/// below the bracket (feasibility is not monotone in `T` for moving end states) could be
/// missed, which the proof then reports as a smaller [`Check::proven_below`].
pub fn min_time_near(
    s0: &KnotState,
    s1: &KnotState,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
    guess: Option<f64>,
) -> Option<(f64, Check)> {
    let feasible = |t: f64| {
        let c = check(&Segment::new(s0, s1, t), kin, lim, opts, true);
        (c.margin >= 0.0, c)
    };
    let t_lb = lower_bound(s0, s1, kin, lim);
    let (ok, mut c0) = feasible(t_lb);
    if ok {
        // T_lb is a proven lower bound: nothing shorter is feasible.
        c0.proven_below = t_lb;
        return Some((t_lb, c0));
    }
    let span = t_lb * opts.scan_span;
    let ratio = if opts.scan_ratio.is_finite() && opts.scan_ratio > 1.0 {
        opts.scan_ratio
    } else {
        1.01
    };
    // The bracket: `lo` infeasible (margin `m_lo` < 0), `hi` feasible.
    let mut lo = t_lb;
    let mut m_lo = c0.margin;
    let (mut hi, mut hi_check);
    match guess.filter(|g| g.is_finite() && *g > t_lb && *g <= span) {
        Some(g) => {
            let (ok, c) = feasible(g);
            let mut r = ratio;
            if ok {
                hi = g;
                hi_check = c;
                loop {
                    let t = hi / r;
                    if t <= t_lb {
                        break;
                    }
                    let (ok, c) = feasible(t);
                    if !ok {
                        lo = t;
                        m_lo = c.margin;
                        break;
                    }
                    hi = t;
                    hi_check = c;
                    r *= r;
                }
            } else {
                lo = g;
                m_lo = c.margin;
                loop {
                    let t = lo * r;
                    if t > span {
                        return None;
                    }
                    let (ok, c) = feasible(t);
                    if ok {
                        hi = t;
                        hi_check = c;
                        break;
                    }
                    lo = t;
                    m_lo = c.margin;
                    r *= r;
                }
            }
        }
        None => loop {
            let t = lo * ratio;
            if t > span {
                return None;
            }
            let (ok, c) = feasible(t);
            if ok {
                hi = t;
                hi_check = c;
                break;
            }
            lo = t;
            m_lo = c.margin;
        },
    }
    let (hi, mut hi_check) = refine(&feasible, (lo, m_lo), (hi, hi_check), opts.rel_tol);
    if opts.prove_rel > 0.0 {
        let to = hi * (1.0 - opts.prove_rel);
        let (reach, _) = certify_infeasible(s0, s1, kin, lim, t_lb, to, &opts.certify);
        hi_check.proven_below = if reach >= to { to } else { reach };
    }
    Some((hi, hi_check))
}

/// Shrinks the bracket `[lo, hi]` (`lo` infeasible with margin `m_lo` < 0, `hi` feasible) to
/// a relative width `rel_tol` by the Illinois variant of regula falsi on the margin, with a
/// bisection whenever two steps did not halve the bracket; returns the feasible end.
fn refine(
    feasible: &dyn Fn(f64) -> (bool, Check),
    (mut lo, mut m_lo): (f64, f64),
    (mut hi, mut hi_check): (f64, Check),
    rel_tol: f64,
) -> (f64, Check) {
    let mut m_hi = hi_check.margin;
    let mut last = 0i8;
    let mut width_before = [f64::INFINITY; 2];
    while hi - lo > rel_tol * hi {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let secant = hi - m_hi * (hi - lo) / (m_hi - m_lo);
        let stalled = hi - lo > 0.5 * width_before[0];
        let t = if !stalled && m_lo < 0.0 && m_hi >= 0.0 && secant > lo && secant < hi {
            secant
        } else {
            mid
        };
        width_before = [width_before[1], hi - lo];
        let (ok, c) = feasible(t);
        if ok {
            hi = t;
            m_hi = c.margin;
            hi_check = c;
            if last == 1 {
                m_lo *= 0.5;
            }
            last = 1;
        } else {
            lo = t;
            m_lo = c.margin.min(-f64::MIN_POSITIVE);
            if last == -1 {
                m_hi *= 0.5;
            }
            last = -1;
        }
    }
    (hi, hi_check)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::kinematics::HeadHead;

    /// Rest to rest along X on a head-head machine (workpiece frame = machine frame, rotaries
    /// fixed): the quintic is `L·(10s³ − 15s⁴ + 6s⁵)`, peak speed `15L/(8T)`, so with the feed
    /// binding `T* = 15L/(8F)` exactly; with the jerk binding (peak `60L/T³`)
    /// `T* = (60L/J)^(1/3)`.
    #[test]
    fn rest_to_rest_minimum_time_is_exact() {
        let kin = HeadHead::typical();
        let s0 = KnotState::default();
        let mut s1 = KnotState::default();
        s1.q[0] = 10.0;
        let lim = Limits::paper();
        let (t, c) = min_time(&s0, &s1, &kin, &lim, &MinTimeOptions::default()).unwrap();
        let want = 15.0 * 10.0 / (8.0 * 30.0);
        // The feed is certified within a relative `feed_rel_eps` (1e-6): never below the true
        // minimum, at most that much above it, and everything below is proven infeasible.
        let eps = MinTimeOptions::default().certify.feed_rel_eps;
        assert!(
            t >= want && t <= want * (1.0 + 1e-7),
            "{t} vs {want} (eps {eps})"
        );
        assert_eq!(c.binding, Binding::Feed);
        assert!(c.proven_below >= want * (1.0 - 1e-7), "{c:?}");
        let sampled = MinTimeOptions {
            feed: FeedCheck::Sampled,
            ..MinTimeOptions::default()
        };
        let (t, _) = min_time(&s0, &s1, &kin, &lim, &sampled).unwrap();
        assert!((t - want).abs() < 1e-12 * want, "{t} vs {want}");
        let mut lim = Limits::paper();
        lim.feed = 1e6;
        lim.vel[0] = 1e6;
        lim.acc[0] = 1e9;
        lim.jerk[0] = 1000.0;
        let (t, c) = min_time(&s0, &s1, &kin, &lim, &MinTimeOptions::default()).unwrap();
        let want = (60.0 * 10.0 / 1000.0f64).cbrt();
        assert!((t - want).abs() < 1e-12 * want, "{t} vs {want}");
        assert_eq!(c.binding, Binding::Jerk(0));
    }
}
