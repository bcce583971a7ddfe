//! Knot velocities and accelerations: derived from the interval times, not fixed in advance.
//!
//! # Knot states from interval times
//! The knots `q_k` (joint space, `k = 0..n`) are fixed; their velocities and accelerations
//! are the three-point finite differences on the time grid of the current interval durations
//! `T_{k−1}, T_k` ([`Geometry::states_for_times`]), exact for a quadratic through the knot and
//! its two neighbours:
//!
//! ```text
//! q̇_k = (d₀ T_k/T_{k−1} + d₁ T_{k−1}/T_k) / (T_{k−1} + T_k),
//! q̈_k = 2 (d₁/T_k − d₀/T_{k−1}) / (T_{k−1} + T_k),     d₀ = q_k − q_{k−1}, d₁ = q_{k+1} − q_k
//! ```
//! (the ends at rest). With equal durations the velocity is the mean of the two chords' —
//! what a constant-speed pass through evenly spaced poses needs, so the quintic between two
//! such knots has almost no jerk. (A state scaled down from it, `γ q̇` with `γ < 1`, leaves
//! every interval a small velocity mismatch `ε Δq`, whose jerk `60 ε Δq / T³` grows fast as
//! the intervals shorten: on a 200-pose sweep it bound the rotary jerk at 1.5 × length/feed.)
//! The trajectory is C² at every knot by construction.
//!
//! # Iteration
//! 1. Starting durations: each interval's moving lower bound `max(chord/F, maxᵢ|Δqᵢ|/vᵢ)`
//!    times `1 +` [`KnotOptions::start_slack`] (0.3 %), or with
//!    [`KnotOptions::ramp_start`] the durations of the jerk-limited ramps at the ends
//!    ([`super::refine_ends`]), whichever is longer.
//! 2. The states from the durations; each interval's exact minimum time for them
//!    ([`super::min_time_near`], warm-started at its current duration).
//! 3. An interval with no feasible time slows its two knots: the durations beside each are
//!    lengthened by [`KnotOptions::slow`] and the states re-derived, the intervals beside a
//!    changed knot re-solved; after [`KnotOptions::max_repairs`] rounds a knot still beside
//!    an infeasible interval is put at rest (rest to rest is always feasible).
//! 4. The minimum times become the next durations; the best total is kept; stop when an
//!    iteration gains less than [`KnotOptions::rel_gain`] (1e-4) or after
//!    [`KnotOptions::iterations`]. Each iteration costs one solve per interval, so a plan is
//!    linear in the number of poses; on the paper's case and on the sweep the best total
//!    comes at the second iteration.
//!
//! While iterating, the feed is the fast sampled check (a lower bound of the maximum) and
//! every limit is tightened by a relative 1e-6. The chosen states are then re-solved against
//! the true limits, warm-started at the iterate (the boundary lies within about 1e-6 below
//! it): the boundary with the sampled check to [`MinTimeOptions::rel_tol`], then one
//! certified check ([`super::feed_bound`]) at a relative `4 · feed_rel_eps` (4e-9) above it —
//! the certified check is undecided within `feed_rel_eps` of the limit — or, should that
//! fail, the certified search itself. Every interval of the result is thus certified, at most
//! 4e-9 (relative) above its certified minimum; that total is the last entry of
//! [`Schedule::history`].
//! The proof that no interval can be shortened ([`prove_minimal`]) is not part of planning:
//! [`super::plan`] runs it on the result, as it runs the verifier.
//!
//! Any extra candidate knot states with one state per knot (the baseline's fixed states) are
//! evaluated too, and kept if faster.
//!
//! # What remains between this and the length/feed bound
//! The interior intervals run within 0.1 % of `chord / F`. The gap is at the ends, where a
//! single quintic per interval must take the tool from rest to the feed: its speed is a
//! quartic whose mean is at most 0.6 of its final value. Poses added along the ramps
//! ([`super::FiveAxisOptions::end_knots`]) shorten that; the figures are in BENCHMARKS.md.

use super::min_time::{
    Check, FeedCheck, KnotState, Limits, MinTimeOptions, Segment, min_time, min_time_near,
};
use crate::error::Error;
use crate::machine::kinematics::{Joints, Kinematics};
use serde::{Deserialize, Serialize};

/// Geometric derivatives of the knot sequence with respect to the knot index.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// Knots.
    pub q: Vec<Joints>,
    /// `∂q/∂σ` at each knot.
    pub dq: Vec<Joints>,
    /// `∂²q/∂σ²` at each knot.
    pub ddq: Vec<Joints>,
}

impl Geometry {
    /// Central differences (zero at the ends).
    pub fn new(q: &[Joints]) -> Geometry {
        let n = q.len();
        let mut dq = vec![[0.0; 5]; n];
        let mut ddq = vec![[0.0; 5]; n];
        for k in 1..n.saturating_sub(1) {
            for i in 0..5 {
                dq[k][i] = 0.5 * (q[k + 1][i] - q[k - 1][i]);
                ddq[k][i] = q[k + 1][i] - 2.0 * q[k][i] + q[k - 1][i];
            }
        }
        Geometry {
            q: q.to_vec(),
            dq,
            ddq,
        }
    }

    /// Knot states for interval durations `times` and speed factors `gamma` (0 at rest, 1 at
    /// the natural rate): the three-point finite differences on the non-uniform time grid,
    /// exact for a quadratic through the knot and its neighbours,
    /// `q̇_k = γ_k (d₀ T₁/T₀ + d₁ T₀/T₁)/(T₀ + T₁)` and `q̈_k = γ_k² · 2(d₁/T₁ − d₀/T₀)/(T₀ + T₁)`
    /// with `d₀ = q_k − q_{k−1}`, `d₁ = q_{k+1} − q_k` and `T₀, T₁` the durations before and
    /// after the knot. The ends are at rest. A state is along the path's tangent only in the
    /// limit of small intervals; the quintics pass through every knot regardless.
    pub fn states_for_times(&self, times: &[f64], gamma: &[f64]) -> Vec<KnotState> {
        let n = self.q.len();
        (0..n)
            .map(|k| {
                let mut s = KnotState {
                    q: self.q[k],
                    ..KnotState::default()
                };
                let g = gamma.get(k).copied().unwrap_or(0.0);
                if k == 0 || k + 1 >= n || g == 0.0 {
                    return s;
                }
                let (t0, t1) = (times[k - 1], times[k]);
                let sum = t0 + t1;
                for i in 0..5 {
                    let d0 = self.q[k][i] - self.q[k - 1][i];
                    let d1 = self.q[k + 1][i] - self.q[k][i];
                    s.v[i] = g * (d0 * t1 / t0 + d1 * t0 / t1) / sum;
                    s.a[i] = g * g * 2.0 * (d1 / t1 - d0 / t0) / sum;
                }
                s
            })
            .collect()
    }

    /// Knot states for rates `σ̇`, `σ̈`.
    pub fn states(&self, sd: &[f64], sdd: &[f64]) -> Vec<KnotState> {
        (0..self.q.len())
            .map(|k| {
                let s = sd.get(k).copied().unwrap_or(0.0);
                let a = sdd.get(k).copied().unwrap_or(0.0);
                KnotState {
                    q: self.q[k],
                    v: std::array::from_fn(|i| self.dq[k][i] * s),
                    a: std::array::from_fn(|i| self.ddq[k][i] * s * s + self.dq[k][i] * a),
                }
            })
            .collect()
    }
}

/// Knot states, interval times and the checks that admitted them.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    /// Knot states.
    pub states: Vec<KnotState>,
    /// Interval durations, s.
    pub times: Vec<f64>,
    /// Check of each interval at its duration.
    pub checks: Vec<Check>,
    /// Total time after each outer iteration (the first entry is the best starting candidate).
    pub history: Vec<f64>,
}

impl Schedule {
    /// Sum of the interval times.
    pub fn total(&self) -> f64 {
        self.times.iter().sum()
    }
}

/// Options of [`optimize`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct KnotOptions {
    /// Largest number of outer iterations. Default 12.
    pub iterations: usize,
    /// Stop after `patience` iterations in a row that gain less than `rel_gain` (relative).
    /// Default 1.
    pub patience: usize,
    /// See `patience`. Default 1e-4 (0.5 ms on the paper's case).
    pub rel_gain: f64,
    /// Factor applied to the durations beside a knot of an infeasible interval, from which
    /// the knot's state is taken. Default 1.25.
    pub slow: f64,
    /// Repair rounds before the knots of a still infeasible interval are put at rest.
    /// Default 30.
    pub max_repairs: usize,
    /// Relative bracket width used while iterating (the final schedule is re-solved with
    /// `min_time.rel_tol`). Default 1e-7.
    pub iteration_rel_tol: f64,
    /// The starting durations' margin over each interval's moving lower bound (relative).
    /// Default 0.003.
    pub start_slack: f64,
    /// Start the ends' intervals at the durations of the jerk-limited ramps
    /// ([`super::refine_ends`]); meant for a path with poses added along them
    /// ([`super::FiveAxisOptions::end_knots`]). Default false.
    pub ramp_start: bool,
    /// Per-interval search.
    pub min_time: MinTimeOptions,
}

impl Default for KnotOptions {
    fn default() -> Self {
        KnotOptions {
            iterations: 12,
            patience: 1,
            rel_gain: 1e-4,
            slow: 1.25,
            max_repairs: 30,
            iteration_rel_tol: 1e-7,
            start_slack: 0.003,
            ramp_start: false,
            min_time: MinTimeOptions::default(),
        }
    }
}

option_builders! {
    KnotOptions;
    /// Sets [`KnotOptions::iterations`].
    with_iterations => iterations: usize;
    /// Sets [`KnotOptions::patience`], iterations.
    with_patience => patience: usize;
    /// Sets [`KnotOptions::rel_gain`].
    with_rel_gain => rel_gain: f64;
    /// Sets [`KnotOptions::slow`].
    with_slow => slow: f64;
    /// Sets [`KnotOptions::max_repairs`].
    with_max_repairs => max_repairs: usize;
    /// Sets [`KnotOptions::iteration_rel_tol`].
    with_iteration_rel_tol => iteration_rel_tol: f64;
    /// Sets [`KnotOptions::start_slack`].
    with_start_slack => start_slack: f64;
    /// Sets [`KnotOptions::ramp_start`].
    with_ramp_start => ramp_start: bool;
    /// Sets [`KnotOptions::min_time`].
    with_min_time => min_time: MinTimeOptions;
}

/// Solves every interval for fixed states; `None` if one has no feasible time.
pub fn solve_fixed(
    states: &[KnotState],
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
) -> Option<Schedule> {
    let mut times = Vec::new();
    let mut checks = Vec::new();
    for w in states.windows(2) {
        let (t, c) = min_time(&w[0], &w[1], kin, lim, opts)?;
        times.push(t);
        checks.push(c);
    }
    Some(Schedule {
        states: states.to_vec(),
        times,
        checks,
        history: vec![],
    })
}

/// Solves every interval for `states`, warm-started at `guess`; an interval with no feasible
/// time is `None`.
fn solve_all(
    states: &[KnotState],
    guess: &[f64],
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
) -> Vec<Option<(f64, Check)>> {
    states
        .windows(2)
        .zip(guess)
        .map(|(w, &g)| min_time_near(&w[0], &w[1], kin, lim, opts, Some(g)))
        .collect()
}

/// The certified minimum time of one interval near `guess` (no proof): the boundary found
/// with the sampled feed check to the full tolerance, then certified at a relative
/// `4 · feed_rel_eps` above it in one certified check (the certified check is undecided
/// within `feed_rel_eps` of the limit); should that fail, the certified search itself.
fn certified_near(
    s0: &KnotState,
    s1: &KnotState,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
    guess: f64,
) -> Option<(f64, Check)> {
    let certified = MinTimeOptions {
        scan_ratio: 1.0 + 1e-5,
        prove_rel: 0.0,
        feed: FeedCheck::Certified,
        ..*opts
    };
    let sampled = MinTimeOptions {
        feed: FeedCheck::Sampled,
        ..certified
    };
    if let Some((t, _)) = min_time_near(s0, s1, kin, lim, &sampled, Some(guess)) {
        let tc = t * (1.0 + 4.0 * opts.certify.feed_rel_eps.max(opts.rel_tol));
        let c = super::min_time::check(&Segment::new(s0, s1, tc), kin, lim, &certified, false);
        if c.margin >= 0.0 {
            return Some((tc, c));
        }
    }
    min_time_near(s0, s1, kin, lim, &certified, Some(guess))
}

/// Optimises the knot states and interval times (see the module docs).
pub fn optimize(
    geo: &Geometry,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &KnotOptions,
    candidates: &[Vec<KnotState>],
) -> Result<Schedule, Error> {
    let n = geo.q.len();
    if n < 2 {
        return Err(Error::internal(
            "five-axis optimiser needs at least two knots",
        ));
    }
    // While iterating: sampled feed, no proof (a lower bound of the maximum feed, so the
    // iterates can only be optimistic); the chosen states are re-solved with the full options
    // at the end.
    let coarse = MinTimeOptions {
        rel_tol: opts.iteration_rel_tol.max(opts.min_time.rel_tol),
        feed: FeedCheck::Sampled,
        prove_rel: 0.0,
        ..opts.min_time
    };
    // The iterates keep a relative 1e-6 from every limit, so that the certified re-solve finds
    // each interval's boundary just below its iterate's time.
    let tight = 1.0 - 1e-6;
    let lim_c = Limits {
        feed: lim.feed * tight,
        vel: lim.vel.map(|x| x * tight),
        acc: lim.acc.map(|x| x * tight),
        jerk: lim.jerk.map(|x| x * tight),
    };
    let mut times =
        super::ends::starting_times(&geo.q, kin, lim, opts.start_slack, opts.ramp_start);
    let mut gamma = vec![1.0; n];
    gamma[0] = 0.0;
    gamma[n - 1] = 0.0;
    let mut best: Option<Schedule> = None;
    let mut history = Vec::new();
    let mut stall = 0;
    for _ in 0..opts.iterations.max(1) {
        let mut states = geo.states_for_times(&times, &gamma);
        let mut sol = solve_all(&states, &times, kin, &lim_c, &coarse);
        // Repair: an interval without a feasible time slows its knots, by lengthening the
        // durations their states are taken from (`slow`), and the intervals beside a changed
        // knot are re-solved. After `max_repairs` rounds such knots are put at rest (γ = 0),
        // one more each round at least, until every interval is feasible (rest to rest
        // always is).
        for round in 0..opts.max_repairs + n {
            let bad: Vec<usize> = (0..n - 1).filter(|&i| sol[i].is_none()).collect();
            if bad.is_empty() {
                break;
            }
            let mut knot = vec![false; n];
            for i in bad {
                knot[i] = true;
                knot[i + 1] = true;
            }
            let mut dirty = vec![false; n - 1];
            for k in (1..n - 1).filter(|&k| knot[k]) {
                if round >= opts.max_repairs {
                    gamma[k] = 0.0;
                } else {
                    times[k - 1] *= opts.slow;
                    times[k] *= opts.slow;
                }
                dirty[k - 1] = true;
                dirty[k] = true;
                if k >= 2 {
                    dirty[k - 2] = true;
                }
                if k + 1 < n - 1 {
                    dirty[k + 1] = true;
                }
            }
            states = geo.states_for_times(&times, &gamma);
            for i in (0..n - 1).filter(|&i| dirty[i]) {
                sol[i] = min_time_near(
                    &states[i],
                    &states[i + 1],
                    kin,
                    &lim_c,
                    &coarse,
                    Some(times[i]),
                );
            }
        }
        if sol.iter().any(Option::is_none) {
            break;
        }
        let new_times: Vec<f64> = sol.iter().flatten().map(|s| s.0).collect();
        let checks: Vec<Check> = sol.iter().flatten().map(|s| s.1).collect();
        let total: f64 = new_times.iter().sum();
        history.push(total);
        let prev = best.as_ref().map_or(f64::INFINITY, Schedule::total);
        if total < prev * (1.0 - opts.rel_gain) {
            stall = 0;
        } else {
            stall += 1;
        }
        if total < prev {
            best = Some(Schedule {
                states,
                times: new_times.clone(),
                checks,
                history: vec![],
            });
        }
        if stall >= opts.patience {
            break;
        }
        times = new_times;
    }
    let rest = geo.states(&[], &[]);
    let mut best = match best {
        Some(b) => b,
        None => solve_fixed(&rest, kin, &lim_c, &coarse).ok_or_else(|| {
            Error::internal("a rest-to-rest interval found no feasible time within the scan span")
        })?,
    };
    for c in candidates.iter().filter(|c| c.len() == n) {
        if let Some(s) = solve_fixed(c, kin, &lim_c, &coarse)
            && s.total() < best.total()
        {
            best = s;
        }
    }
    // Final pass: every interval of the chosen states with the full options (certified feed,
    // full tolerance, proof of minimality), warm-started at the iterate's time. The iterates
    // used the sampled feed, a lower bound of the maximum, so a time may grow here by the
    // certification tolerance. Should the chosen states fail, rest at every knot is always
    // feasible.
    let sol: Vec<_> = best
        .states
        .windows(2)
        .zip(&best.times)
        .map(|(w, &g)| certified_near(&w[0], &w[1], kin, lim, &opts.min_time, g))
        .collect();
    let mut exact = if sol.iter().all(Option::is_some) {
        Schedule {
            states: best.states.clone(),
            times: sol.iter().flatten().map(|s| s.0).collect(),
            checks: sol.iter().flatten().map(|s| s.1).collect(),
            history: vec![],
        }
    } else {
        solve_fixed(
            &rest,
            kin,
            lim,
            &MinTimeOptions {
                prove_rel: 0.0,
                ..opts.min_time
            },
        )
        .ok_or_else(|| Error::internal("no certified schedule for the chosen knot states"))?
    };
    history.push(exact.total());
    exact.history = history;
    Ok(exact)
}

/// The proof of minimality of every interval of `schedule` ([`super::certify_infeasible`]):
/// sets each check's [`Check::proven_below`] to how far below the interval's time every
/// duration was proven infeasible (at most `1 − opts.prove_rel` of it; nothing when
/// `prove_rel` is 0). [`optimize`] plans without it; [`super::plan`] runs it on the plan.
pub fn prove_minimal(
    schedule: &mut Schedule,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MinTimeOptions,
) {
    if opts.prove_rel <= 0.0 {
        return;
    }
    for (i, w) in schedule.states.windows(2).enumerate() {
        let (Some(&t), Some(c)) = (schedule.times.get(i), schedule.checks.get_mut(i)) else {
            break;
        };
        let t_lb = super::min_time::lower_bound(&w[0], &w[1], kin, lim);
        if t <= t_lb {
            c.proven_below = t_lb;
            continue;
        }
        let to = t * (1.0 - opts.prove_rel);
        let (reach, _) =
            super::certify::certify_infeasible(&w[0], &w[1], kin, lim, t_lb, to, &opts.certify);
        c.proven_below = if reach >= to { to } else { reach };
    }
}
