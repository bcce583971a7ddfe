//! "No panic on any input" for the motion planner: arbitrary programs (lines, rapids, arcs
//! with extra turns, dwells, hostile feeds and coordinates, every corner mode) on presets and
//! on machines with arbitrary limits. Seeded and bounded; a panic fails with the input.
//! Every plan that succeeds is checked by the independent limit verifier (`motion::verify`,
//! 1 kHz sampling of every axis's velocity, acceleration and jerk): 0 violations, or the
//! test fails with the program and machine. `HOSTILE_SEED=N` explores other seeds.

mod hostile_common;

use hostile_common::{Harness, env_or, hostile_f64, mostly_sane, rng};
use millpath::machine::{AxisLimits, Machine};
use millpath::motion::{PlanOptions, plan_moves, plan_toolpath_opt};
use millpath::motion::{VerifyOptions, verify_plan};
use millpath::toolpath::{Corner, MoveKind, Plane};
use millpath::{Move, Point3, Tool, Toolpath};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

fn point(r: &mut ChaCha8Rng, near: Point3) -> Point3 {
    if r.random_bool(0.02) {
        return Point3::new(hostile_f64(r), hostile_f64(r), hostile_f64(r));
    }
    let step = if r.random_bool(0.1) { 1e-7 } else { 20.0 };
    Point3::new(
        near.x + r.random_range(-step..step),
        near.y + r.random_range(-step..step),
        near.z + r.random_range(-step..step) * 0.2,
    )
}

fn program(r: &mut ChaCha8Rng) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    let mut at = Point3::ORIGIN;
    for _ in 0..r.random_range(0..25) {
        let to = point(r, at);
        let feed = mostly_sane(r, 1.0, 200.0, 0.03);
        let mut m = match r.random_range(0..10) {
            0 => Move::rapid(to),
            1 => Move::dwell(at, mostly_sane(r, 0.0, 2.0, 0.1)),
            2..=4 if r.random_bool(0.97) => {
                // A consistent arc or helix in XY (the end on the start's circle): the planner
                // refuses arcs whose radii differ beyond LinuxCNC's rule, and most of the pass
                // must reach the planner proper.
                let c = point(r, at);
                let a = r.random_range(-7.0..7.0f64);
                let (dx, dy) = (at.x - c.x, at.y - c.y);
                let end = Point3::new(
                    c.x + dx * a.cos() - dy * a.sin(),
                    c.y + dx * a.sin() + dy * a.cos(),
                    to.z,
                );
                Move::arc_xy(end, Point3::new(c.x, c.y, at.z), r.random_bool(0.5), feed)
            }
            2..=4 => {
                let c = point(r, at);
                let mut m = Move::arc_xy(to, Point3::new(c.x, c.y, at.z), r.random_bool(0.5), feed);
                if let MoveKind::Arc { plane, turns, .. } = &mut m.kind {
                    *plane = match r.random_range(0..3) {
                        0 => Plane::Xy,
                        1 => Plane::Zx,
                        _ => Plane::Yz,
                    };
                    *turns = if r.random_bool(0.1) {
                        r.random_range(0..5)
                    } else {
                        0
                    };
                }
                m
            }
            _ => Move::line(to, feed),
        };
        m = m.with_corner(match r.random_range(0..5) {
            0 => Corner::ExactStop,
            1 => Corner::ExactPath,
            2 => Corner::Blend(mostly_sane(r, 0.001, 1.0, 0.1)),
            _ => Corner::Machine,
        });
        if !matches!(m.kind, MoveKind::Dwell { .. }) {
            at = m.to;
        }
        tp.push(m);
    }
    tp
}

fn machine(r: &mut ChaCha8Rng) -> Machine {
    let base = Machine::preset(Machine::PRESET_NAMES[r.random_range(0..3)]).unwrap();
    if r.random_bool(0.4) {
        return base;
    }
    let axis = |r: &mut ChaCha8Rng| AxisLimits {
        max_velocity: mostly_sane(r, 10.0, 1000.0, 0.05),
        max_acceleration: mostly_sane(r, 100.0, 20000.0, 0.05),
        max_jerk: if r.random_bool(0.2) {
            f64::INFINITY
        } else {
            mostly_sane(r, 1000.0, 1e6, 0.05)
        },
    };
    Machine {
        axes: [axis(r), axis(r), axis(r)],
        max_feed: mostly_sane(r, 10.0, 500.0, 0.05),
        rapid: [
            mostly_sane(r, 100.0, 1000.0, 0.03),
            mostly_sane(r, 100.0, 1000.0, 0.03),
            mostly_sane(r, 100.0, 1000.0, 0.03),
        ],
        path_tolerance: mostly_sane(r, 0.0, 0.1, 0.05),
        ipo_cycle: mostly_sane(r, 0.0005, 0.01, 0.05),
        curvature_accel_share: mostly_sane(r, 0.1, 0.9, 0.05),
        curvature_jerk_share: mostly_sane(r, 0.1, 0.9, 0.05),
        ..base
    }
}

/// Most machine time a plan may take and still be verified here, s (at 1 kHz: at most
/// 20,000 samples a program, which keeps the pass to seconds).
const VERIFY_MAX_TIME: f64 = 20.0;

#[test]
fn planner_survives_arbitrary_programs_and_machines() {
    let mut h = Harness::new("planner");
    let seed = env_or("HOSTILE_SEED", 0x91a2u64);
    let mut r = rng(seed);
    let (mut ok, mut verified) = (0, 0);
    for case in 0..2000 {
        let tp = program(&mut r);
        let m = machine(&mut r);
        let opts = PlanOptions::default()
            .with_keep_geometry(true)
            .with_check_profiles(r.random_bool(0.7));
        let outcome = h.run(&(seed, case, &tp, &m, &opts), || {
            let plan = if case % 2 == 0 {
                plan_toolpath_opt(&tp, &m, &opts)
            } else {
                plan_moves(tp.segments().map(|(f, mv)| Ok((f, *mv))), &m, &opts)
            };
            let Ok(plan) = plan else {
                return (false, false);
            };
            if plan.total_time() > VERIFY_MAX_TIME {
                return (true, false);
            }
            let moves: Vec<_> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
            match verify_plan(&plan, &moves, &m, &VerifyOptions::default()) {
                Ok(rep) => {
                    assert_eq!(
                        rep.violations, 0,
                        "seed {seed:#x}, case {case}: {} limit violations, first {:?}",
                        rep.violations, rep.first
                    );
                    (true, true)
                }
                Err(e) => panic!("seed {seed:#x}, case {case}: the verifier refused the plan: {e}"),
            }
        });
        if let Some((planned, checked)) = outcome {
            ok += usize::from(planned);
            verified += usize::from(checked);
        }
    }
    // The pass must reach the planner proper, not only its input checks, and verify most of
    // what it plans.
    assert!(
        ok >= 600,
        "seed {seed:#x}: only {ok} of 2000 programs planned"
    );
    assert!(
        verified >= ok / 2,
        "seed {seed:#x}: only {verified} of {ok} plans verified"
    );
    h.finish(2000);
}
