//! The paper's optimiser, as a baseline: knot velocities and accelerations fixed in advance,
//! then a simple genetic algorithm run for **one generation** per interval.
//!
//! The paper does not state its knot states nor its GA parameters; our reading:
//! * knot states: the tool tip moves at [`BaselineOptions::knot_feed_fraction`] of the feed
//!   limit along the path tangent at every interior knot, with no tangential acceleration
//!   (`σ̇_k = β F / |J_tip q_σ|`, `σ̈_k = 0` in the notation of [`super::knots`]); rest at the
//!   ends;
//! * GA: a population of [`BaselineOptions::population`] durations drawn uniformly in
//!   `[T_lb, span·T_lb]`, fitness = duration if the constraint check passes, else infeasible;
//!   one generation of binary tournament selection, blend crossover and Gaussian mutation; the
//!   interval's time is the best feasible individual of parents and children. If none is
//!   feasible the range is doubled and the generation re-run (at most 20 times).
//!
//! The constraint check is the same exact check as ours ([`super::min_time::check`]), so the
//! comparison measures the optimiser, not the checker. Seeded ([`rand_chacha::ChaCha8Rng`]).

use super::knots::Geometry;
use super::min_time::{Check, KnotState, Limits, MinTimeOptions, Segment, check, lower_bound};
use crate::machine::kinematics::Kinematics;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Options of the baseline. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct BaselineOptions {
    /// Knot tip speed as a fraction β of the feed limit. Default 0.8.
    pub knot_feed_fraction: f64,
    /// Population size. Default 40.
    pub population: usize,
    /// Initial range `[T_lb, span·T_lb]`. Default 3.
    pub span: f64,
    /// Crossover probability. Default 0.8.
    pub crossover: f64,
    /// Mutation probability. Default 0.1.
    pub mutation: f64,
    /// RNG seed. Default 2008 (the paper's year).
    pub seed: u64,
}

impl Default for BaselineOptions {
    fn default() -> Self {
        BaselineOptions {
            knot_feed_fraction: 0.8,
            population: 40,
            span: 3.0,
            crossover: 0.8,
            mutation: 0.1,
            seed: 2008,
        }
    }
}

option_builders! {
    BaselineOptions;
    /// Sets [`BaselineOptions::knot_feed_fraction`].
    with_knot_feed_fraction => knot_feed_fraction: f64;
    /// Sets [`BaselineOptions::population`].
    with_population => population: usize;
    /// Sets [`BaselineOptions::span`].
    with_span => span: f64;
    /// Sets [`BaselineOptions::crossover`].
    with_crossover => crossover: f64;
    /// Sets [`BaselineOptions::mutation`].
    with_mutation => mutation: f64;
    /// Sets [`BaselineOptions::seed`].
    with_seed => seed: u64;
}

/// The baseline's fixed knot states.
pub fn fixed_states(
    geo: &Geometry,
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &BaselineOptions,
) -> Vec<KnotState> {
    let n = geo.q.len();
    let mut sd = vec![0.0; n];
    for (k, sdk) in sd.iter_mut().enumerate().take(n.saturating_sub(1)).skip(1) {
        let j = kin.jacobian(&geo.q[k]);
        let tip_s: f64 = (0..3)
            .map(|r| {
                let d: f64 = (0..5).map(|c| j[r][c] * geo.dq[k][c]).sum();
                d * d
            })
            .sum::<f64>()
            .sqrt();
        if tip_s > 0.0 {
            *sdk = opts.knot_feed_fraction * lim.feed / tip_s;
        }
    }
    geo.states(&sd, &[])
}

/// The baseline's interval times and checks; `None` if an interval found no feasible time.
pub fn run(
    states: &[KnotState],
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &BaselineOptions,
    mt: &MinTimeOptions,
) -> Option<(Vec<f64>, Vec<Check>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(opts.seed);
    let mut times = Vec::new();
    let mut checks = Vec::new();
    for w in states.windows(2) {
        let (s0, s1) = (&w[0], &w[1]);
        let t_lb = lower_bound(s0, s1, kin, lim);
        let mut span = opts.span;
        let mut found = None;
        for _ in 0..20 {
            found = one_generation(s0, s1, kin, lim, mt, opts, &mut rng, t_lb, t_lb * span);
            if found.is_some() {
                break;
            }
            span *= 2.0;
        }
        let (t, c) = found?;
        times.push(t);
        checks.push(c);
    }
    Some((times, checks))
}

#[allow(clippy::too_many_arguments)]
fn one_generation(
    s0: &KnotState,
    s1: &KnotState,
    kin: &dyn Kinematics,
    lim: &Limits,
    mt: &MinTimeOptions,
    opts: &BaselineOptions,
    rng: &mut ChaCha8Rng,
    lo: f64,
    hi: f64,
) -> Option<(f64, Check)> {
    let fitness = |t: f64| {
        let c = check(&Segment::new(s0, s1, t), kin, lim, mt, true);
        (c.margin >= 0.0).then_some(c)
    };
    let pop: Vec<f64> = (0..opts.population.max(2))
        .map(|_| rng.random_range(lo..hi))
        .collect();
    let fit: Vec<Option<Check>> = pop.iter().map(|&t| fitness(t)).collect();
    let score = |i: usize| {
        if fit[i].is_some() {
            pop[i]
        } else {
            f64::INFINITY
        }
    };
    let mut best: Option<(f64, Check)> = None;
    let mut consider = |t: f64, c: Option<Check>| {
        if let Some(c) = c
            && best.is_none_or(|(bt, _)| t < bt)
        {
            best = Some((t, c));
        }
    };
    for (t, c) in pop.iter().zip(&fit) {
        consider(*t, *c);
    }
    let n = pop.len();
    let tournament = |rng: &mut ChaCha8Rng| {
        let a = rng.random_range(0..n);
        let b = rng.random_range(0..n);
        if score(a) <= score(b) { pop[a] } else { pop[b] }
    };
    for _ in 0..n {
        let p1 = tournament(rng);
        let p2 = tournament(rng);
        let mut child = if rng.random::<f64>() < opts.crossover {
            let alpha: f64 = rng.random();
            alpha * p1 + (1.0 - alpha) * p2
        } else {
            p1
        };
        if rng.random::<f64>() < opts.mutation {
            // Box–Muller normal deviate, σ = 5 % of the range.
            let (u1, u2): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
            let z = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
            child += 0.05 * (hi - lo) * z;
        }
        let child = child.clamp(lo, hi);
        consider(child, fitness(child));
    }
    best
}
