//! Every plan of a corpus (random polylines, arcs, helices, square/circle, short segments,
//! rapids, dwells, every corner mode) sampled at 1 kHz by the independent verifier stays within
//! every per-axis limit, the feed and the path tolerance.

use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::motion::table2::{circle, square};
use millpath::motion::{VerifyOptions, ViolationKind, verify_plan};
use millpath::toolpath::{Corner, Move, Tool, Toolpath};
use millpath::{Point3, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn check(tp: &Toolpath, m: &Machine, what: &str) -> f64 {
    let plan = plan_toolpath(tp, m).unwrap_or_else(|e| panic!("{what} on {}: {e}", m.name));
    let moves: Vec<_> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
    let rep = verify_plan(&plan, &moves, m, &VerifyOptions::default()).unwrap();
    assert!(rep.samples >= 2 && rep.samples + rep.bounded > 10, "{what}");
    assert_eq!(rep.violations, 0, "{what} on {}: {:#?}", m.name, rep.first);
    // The plan is never faster than the programmed feeds allow.
    let naive: f64 = tp
        .segments()
        .filter(|(_, mv)| mv.is_feed())
        .map(|(f, mv)| mv.length_from(f) / mv.feed.min(m.max_feed))
        .sum();
    assert!(plan.total_time() >= naive * (1.0 - 1e-9), "{what}");
    plan.total_time()
}

fn random_polyline(rng: &mut ChaCha8Rng, n: usize, step: f64, corner: Corner) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    let mut p = Point3::ORIGIN;
    for _ in 0..n {
        let d = Vec3::new(
            rng.random_range(-step..step),
            rng.random_range(-step..step),
            rng.random_range(-0.1 * step..0.1 * step),
        );
        p = p + d;
        let feed = rng.random_range(10.0..150.0);
        tp.push(Move::line(p, feed).with_corner(corner));
    }
    tp
}

fn arcs_and_helices(rng: &mut ChaCha8Rng) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::new(5.0, 0.0, 0.0));
    let mut p = tp.start;
    for k in 0..6 {
        let r = rng.random_range(0.5..20.0);
        let c = Point3::new(p.x - r, p.y, 0.0);
        let dz = if k % 2 == 0 {
            -rng.random_range(0.0..3.0)
        } else {
            0.0
        };
        let ang: f64 = rng.random_range(0.3..6.0);
        let to = Point3::new(c.x + r * ang.cos(), c.y + r * ang.sin(), p.z + dz);
        tp.push(Move::arc_xy(to, c, true, rng.random_range(20.0..200.0)));
        p = to;
        let q = p + Vec3::new(
            rng.random_range(-5.0..5.0),
            rng.random_range(-5.0..5.0),
            0.0,
        );
        tp.push(Move::line(q, 80.0));
        p = q;
    }
    tp
}

#[test]
fn corpus_has_no_violations() {
    // The linuxcnc model's plans follow LinuxCNC's rules, not the verifier's; they are
    // checked against LinuxCNC itself (tests/controller_linuxcnc.rs).
    let machines: Vec<Machine> = Machine::presets()
        .into_iter()
        .filter(|m| m.controller != millpath::machine::Controller::LinuxCnc)
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    for m in &machines {
        for (k, corner) in [
            Corner::Machine,
            Corner::ExactStop,
            Corner::ExactPath,
            Corner::Blend(0.02),
        ]
        .into_iter()
        .enumerate()
        {
            let tp = random_polyline(&mut rng, 12, 10.0, corner);
            check(&tp, m, &format!("polyline {k}"));
            let tp = random_polyline(&mut rng, 60, 0.2, corner);
            check(&tp, m, &format!("short segments {k}"));
        }
        for k in 0..3 {
            check(&arcs_and_helices(&mut rng), m, &format!("arcs {k}"));
        }
        for side in [12.7, 50.8] {
            check(&square(side, 169.0), m, "square");
            check(
                &circle(side * 4.0 / std::f64::consts::TAU, 169.0),
                m,
                "circle",
            );
        }
        // Rapids, a dwell, a tangent line → arc → line slot.
        let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 10.0));
        tp.push(Move::rapid(Point3::new(30.0, 5.0, 10.0)));
        tp.push(Move::line(Point3::new(30.0, 5.0, 0.0), 20.0));
        tp.push(Move::dwell(Point3::new(30.0, 5.0, 0.0), 0.3));
        tp.push(Move::line(Point3::new(60.0, 5.0, 0.0), 100.0));
        // A zero-length move (a repeated point) inside the program.
        tp.push(Move::line(Point3::new(60.0, 5.0, 0.0), 100.0));
        tp.push(Move::arc_xy(
            Point3::new(60.0, 25.0, 0.0),
            Point3::new(60.0, 15.0, 0.0),
            true,
            100.0,
        ));
        tp.push(Move::line(Point3::new(30.0, 25.0, 0.0), 100.0));
        tp.push(Move::rapid(Point3::new(0.0, 0.0, 10.0)));
        let t = check(&tp, m, "slot with rapids and dwell");
        assert!(t > 0.3);
    }
}

#[test]
fn long_colinear_short_segments_reach_the_feed() {
    // 1000 colinear 0.05 mm segments at 100 mm/s: one span, the feed is reached.
    let m = Machine::preset("hsm").unwrap();
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    for i in 1..=1000 {
        tp.push(Move::line(
            Point3::new(0.05 * f64::from(i), 0.0, 0.0),
            100.0,
        ));
    }
    let plan = plan_toolpath(&tp, &m).unwrap();
    let peak = plan.blocks.iter().map(|b| b.peak_feed).fold(0.0, f64::max);
    assert!((peak - 100.0).abs() < 1e-9, "{peak}");
    let single = {
        let mut one = Toolpath::new(Tool::default(), Point3::ORIGIN);
        one.push(Move::line(Point3::new(50.0, 0.0, 0.0), 100.0));
        plan_toolpath(&one, &m).unwrap().total_time()
    };
    assert!((plan.total_time() - single).abs() < 1e-9);
    check(&tp, &m, "colinear");
}

#[test]
fn reversed_path_takes_the_same_time() {
    // Invariance: the limits are symmetric, so a path and its reverse take the same time.
    let m = Machine::preset("router").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let tp = random_polyline(&mut rng, 30, 5.0, Corner::Machine);
    let mut pts: Vec<Point3> = std::iter::once(tp.start)
        .chain(tp.moves.iter().map(|mv| mv.to))
        .collect();
    let feeds: Vec<f64> = tp.moves.iter().map(|mv| mv.feed).collect();
    pts.reverse();
    let mut rev = Toolpath::new(Tool::default(), pts[0]);
    for (k, p) in pts.iter().skip(1).enumerate() {
        rev.push(Move::line(*p, feeds[feeds.len() - 1 - k]));
    }
    let a = plan_toolpath(&tp, &m).unwrap().total_time();
    let b = plan_toolpath(&rev, &m).unwrap().total_time();
    assert!((a - b).abs() < 1e-9 * a, "{a} {b}");
}

/// `m` with every axis limit and the maximum feed scaled by a factor in `[lo, 1]` of its own.
fn tightened(rng: &mut ChaCha8Rng, m: &Machine, lo: f64) -> Machine {
    let mut t = m.clone();
    for ax in &mut t.axes {
        ax.max_velocity *= rng.random_range(lo..1.0);
        ax.max_acceleration *= rng.random_range(lo..1.0);
        ax.max_jerk *= rng.random_range(lo..1.0);
    }
    t.max_feed *= rng.random_range(lo..1.0);
    t
}

/// The stretches' bounds take the samples of the 1 kHz grid only where a limit may be
/// reached: plans of the corpus verified against machines with tighter limits than they
/// were planned for (so that many break them) give the very violations (each one's kind,
/// block, time, value and limit, and their count) the whole grid gives, with fewer samples.
#[test]
fn the_stretches_find_every_violation_the_grid_finds() {
    let machines: Vec<Machine> = Machine::presets()
        .into_iter()
        .filter(|m| m.controller != millpath::machine::Controller::LinuxCnc)
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(37);
    let (mut cases, mut violating, mut sparse_samples, mut grid_samples) = (0, 0, 0, 0);
    for m in &machines {
        for k in 0..12 {
            let corner = [
                Corner::Machine,
                Corner::ExactStop,
                Corner::ExactPath,
                Corner::Blend(0.02),
            ][k % 4];
            let tp = match k % 3 {
                0 => random_polyline(&mut rng, 12, 10.0, corner),
                1 => random_polyline(&mut rng, 40, 0.5, corner),
                _ => arcs_and_helices(&mut rng),
            };
            let plan = plan_toolpath(&tp, m).unwrap_or_else(|e| panic!("{k} on {}: {e}", m.name));
            let moves: Vec<_> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
            let lo = if k < 4 { 1.0 - 1e-9 } else { 0.6 };
            let tight = tightened(&mut rng, m, lo);
            let all = VerifyOptions::default().with_every_sample(true);
            let grid = verify_plan(&plan, &moves, &tight, &all).unwrap();
            let sparse = verify_plan(&plan, &moves, &tight, &VerifyOptions::default()).unwrap();
            assert_eq!(
                (sparse.violations, &sparse.first),
                (grid.violations, &grid.first),
                "{k} on {}",
                m.name
            );
            assert_eq!(grid.bounded, 0);
            assert!(sparse.samples + sparse.bounded >= grid.samples);
            cases += 1;
            violating += usize::from(grid.violations > 0);
            sparse_samples += sparse.samples;
            grid_samples += grid.samples;
        }
    }
    assert!(cases >= 36, "{cases}");
    assert!(violating >= cases / 3, "{violating} of {cases}");
    assert!(
        sparse_samples * 2 < grid_samples,
        "{sparse_samples} of {grid_samples}"
    );
}

/// A violation planted in hours of slow cruise: an arc whose axes' acceleration exceeds a
/// machine lowered below what the plan used, and a line faster than its X axis allows, between
/// lines of an hour each. Both are found, in their blocks, from a few thousand samples where
/// the grid has millions.
#[test]
fn a_violation_in_hours_of_cruise_is_caught() {
    let m = Machine::preset("hsm").unwrap();
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    // 3600 mm at 1 mm/s, there and back; a fast arc and a fast line between.
    tp.push(Move::line(Point3::new(3600.0, 0.0, 0.0), 1.0));
    tp.push(Move::arc_xy(
        Point3::new(3600.0, 20.0, 0.0),
        Point3::new(3600.0, 10.0, 0.0),
        true,
        100.0,
    ));
    tp.push(Move::line(Point3::new(3400.0, 20.0, 0.0), 100.0));
    tp.push(Move::line(Point3::new(0.0, 20.0, 0.0), 1.0));
    let plan = plan_toolpath(&tp, &m).unwrap();
    let moves: Vec<_> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
    assert!(plan.total_time() > 7000.0, "{}", plan.total_time());
    let ok = verify_plan(&plan, &moves, &m, &VerifyOptions::default()).unwrap();
    assert_eq!(ok.violations, 0, "{:#?}", ok.first);
    // The highest speed and the arc's acceleration the plan reached, from the grid's own
    // samples over the fast blocks (blocks 1 and 2), then a machine just below them.
    let mut peak_vx: f64 = 0.0;
    let mut arc_acc: f64 = 0.0;
    for s in plan.sample(1e-3).unwrap() {
        match s.block {
            1 => arc_acc = arc_acc.max(s.acc[0].abs().max(s.acc[1].abs())),
            2 => peak_vx = peak_vx.max(s.vel[0].abs()),
            _ => {}
        }
    }
    assert!(peak_vx > 10.0 && arc_acc > 100.0, "{peak_vx}, {arc_acc}");
    let mut fast_x = m.clone();
    fast_x.axes[0].max_velocity = 0.9 * peak_vx;
    let mut tight_arc = m.clone();
    tight_arc.axes[0].max_acceleration = 0.9 * arc_acc;
    tight_arc.axes[1].max_acceleration = 0.9 * arc_acc;
    let mut samples = 0;
    for (slow, kind) in [
        (&fast_x, ViolationKind::Velocity),
        (&tight_arc, ViolationKind::Acceleration),
    ] {
        let rep = verify_plan(&plan, &moves, slow, &VerifyOptions::default()).unwrap();
        assert!(rep.violations > 0, "{kind:?}: nothing found");
        assert!(
            rep.first.iter().all(|v| v.block == 1 || v.block == 2),
            "{kind:?}: {:#?}",
            rep.first
        );
        assert!(rep.first.iter().any(|v| v.kind == kind), "{:#?}", rep.first);
        assert!(
            rep.samples + rep.bounded >= (1000.0 * plan.total_time()) as usize,
            "{} + {}",
            rep.samples,
            rep.bounded
        );
        samples = samples.max(rep.samples);
    }
    // The sampler took the fast blocks' grid and the slow lines' ends.
    assert!(samples < 100_000, "{samples}");
}
