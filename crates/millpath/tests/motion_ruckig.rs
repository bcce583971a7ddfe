//! Exactness: a rest-to-rest straight move takes the time-optimal jerk-limited time, equal to
//! rsruckig's minimum duration within 1e-9 s over thousands of seeded random moves.

use millpath::motion::{Limits1, SpanProfile, rest_to_rest_time};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rsruckig::prelude::*;

fn ruckig_time(d: f64, lim: Limits1) -> f64 {
    let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 0.001);
    let mut input = InputParameter::new(None);
    let mut traj = Trajectory::new(None);
    input.current_position[0] = 0.0;
    input.target_position[0] = d;
    input.max_velocity[0] = lim.v;
    input.max_acceleration[0] = lim.a;
    input.max_jerk[0] = lim.j;
    otg.calculate(&input, &mut traj).expect("ruckig");
    traj.get_duration()
}

fn log_uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    (rng.random_range(lo.ln()..hi.ln())).exp()
}

#[test]
fn rest_to_rest_matches_ruckig() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x0005_eed3);
    let mut worst: f64 = 0.0;
    for _ in 0..3000 {
        let lim = Limits1 {
            v: log_uniform(&mut rng, 1.0, 2000.0),
            a: log_uniform(&mut rng, 50.0, 50_000.0),
            j: log_uniform(&mut rng, 500.0, 5e6),
        };
        let d = log_uniform(&mut rng, 1e-3, 2000.0);
        let ours = rest_to_rest_time(d, lim).unwrap();
        let theirs = ruckig_time(d, lim);
        let p = SpanProfile::new(0.0, 0.0, d, lim).unwrap();
        p.check(lim).unwrap();
        worst = worst.max((ours - theirs).abs());
        assert!(
            (ours - theirs).abs() <= 1e-9,
            "d {d} {lim:?}: ours {ours} ruckig {theirs}"
        );
    }
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn trapezoidal_limit_of_ruckig_as_jerk_grows() {
    // With J = ∞ our time is a lower bound of every finite-J time and the limit of ruckig's
    // time as J grows: 0 ≤ T(J) − T(∞) ≤ A/J + 4∛(d/J).
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        let v = log_uniform(&mut rng, 1.0, 500.0);
        let a = log_uniform(&mut rng, 50.0, 5000.0);
        let d = log_uniform(&mut rng, 1e-2, 500.0);
        let inf = rest_to_rest_time(
            d,
            Limits1 {
                v,
                a,
                j: f64::INFINITY,
            },
        )
        .unwrap();
        let j = 1e9;
        let fin = ruckig_time(d, Limits1 { v, a, j });
        assert!(
            fin >= inf - 1e-12 && fin - inf <= a / j + 4.0 * (d / j).cbrt(),
            "{fin} {inf}"
        );
    }
}

fn ruckig_time_between(v0: f64, v1: f64, d: f64, lim: Limits1) -> f64 {
    let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 0.001);
    let mut input = InputParameter::new(None);
    let mut traj = Trajectory::new(None);
    input.current_position[0] = 0.0;
    input.current_velocity[0] = v0;
    input.target_position[0] = d;
    input.target_velocity[0] = v1;
    input.max_velocity[0] = lim.v;
    input.max_acceleration[0] = lim.a;
    input.max_jerk[0] = lim.j;
    otg.calculate(&input, &mut traj).expect("ruckig");
    traj.get_duration()
}

#[test]
fn spans_between_junction_speeds_match_ruckig() {
    // The look-ahead's spans: from (v0, a = 0) to (v1, a = 0) over a distance at least the
    // velocity change needs.
    let mut rng = ChaCha8Rng::seed_from_u64(0x0005_eed4);
    for _ in 0..2000 {
        let lim = Limits1 {
            v: log_uniform(&mut rng, 1.0, 2000.0),
            a: log_uniform(&mut rng, 50.0, 50_000.0),
            j: log_uniform(&mut rng, 500.0, 5e6),
        };
        let v0 = rng.random_range(0.0..lim.v);
        let v1 = rng.random_range(0.0..lim.v);
        let need = millpath::motion::change_distance(v0, v1, lim.a, lim.j);
        let d = need * (1.0 + log_uniform(&mut rng, 1e-3, 10.0)) + 1e-6;
        let ours = SpanProfile::new(v0, v1, d, lim).unwrap();
        ours.check(lim).unwrap();
        let theirs = ruckig_time_between(v0, v1, d, lim);
        assert!(
            (ours.duration - theirs).abs() <= 1e-9 * theirs.max(1.0),
            "v0 {v0} v1 {v1} d {d} {lim:?}: ours {} ruckig {theirs}",
            ours.duration
        );
    }
}
