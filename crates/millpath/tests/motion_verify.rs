//! Every plan of a corpus (random polylines, arcs, helices, square/circle, short segments,
//! rapids, dwells, every corner mode) sampled at 1 kHz by the independent verifier stays within
//! every per-axis limit, the feed and the path tolerance.

use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::motion::table2::{circle, square};
use millpath::motion::{VerifyOptions, verify_plan};
use millpath::toolpath::{Corner, Move, Tool, Toolpath};
use millpath::{Point3, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn check(tp: &Toolpath, m: &Machine, what: &str) -> f64 {
    let plan = plan_toolpath(tp, m).unwrap_or_else(|e| panic!("{what} on {}: {e}", m.name));
    let moves: Vec<_> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
    let rep = verify_plan(&plan, &moves, m, &VerifyOptions::default()).unwrap();
    assert!(rep.samples > 10, "{what}");
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
