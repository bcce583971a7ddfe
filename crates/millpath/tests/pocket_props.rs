//! Property and invariance tests: random pockets (convex, non-convex, with islands) and random
//! tools and stepovers; every strategy is verified by the stock simulation or refused with an
//! input error that names the value and where it came from, and most cases must be planned
//! (a run where every case is refused fails). The same pocket reversed, rotated, translated
//! and with its start vertex moved gives the same cycle time, for every strategy.
//!
//! Kept fast: pockets about 30 mm across, one level, a 0.15 mm raster cell (the verifier's
//! coverage test looks only at cells within `r − 2c` of the reachable region, and its
//! uncut-area tolerance is 0.05 mm², so a coarse cell does not make it lenient: it measures
//! the same things at a coarser grain), [`CASES`] cases per property.

use millpath::Error;
use millpath::geom::{Outline, Point, Vec2};
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::toolpath::Tool;
use proptest::prelude::*;
use proptest::test_runner::{RngSeed, TestRunner};

fn coarse() -> SimOptions {
    SimOptions::default().with_cell(0.15).with_step(0.3)
}

/// All three strategies.
const ALL: [StrategyKind; 3] = [
    StrategyKind::Offset,
    StrategyKind::Zigzag,
    StrategyKind::Spiral,
];

/// A star-shaped polygon: radii at equally spaced angles (convex when all radii are equal
/// enough, non-convex otherwise), corners rounded.
fn star(radii: &[f64], round: f64) -> Option<Outline> {
    let n = radii.len();
    let pts: Vec<Point> = radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect();
    builtin::rounded_polygon(&pts, round, "random star")
}

fn circle(c: Point, r: f64) -> Outline {
    Outline::new(
        &[
            (Point::new(c.x - r, c.y), 1.0),
            (Point::new(c.x + r, c.y), 1.0),
        ],
        "circle",
    )
    .unwrap()
}

/// Random cases per property.
const CASES: u32 = 12;
/// Of which at least this many must be planned by every strategy (the rest may be refused
/// as bad input: a tool that does not fit, a stepover beyond what a region allows).
const MIN_PLANNED: usize = 8;

/// Every strategy of `kinds` verifies on the pocket, or refuses it with an input error that
/// says what is wrong, where it came from and what would be accepted. `Ok(true)` when all
/// planned it.
fn check(
    kinds: &[StrategyKind],
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<bool, TestCaseError> {
    let mut all = true;
    for &kind in kinds {
        match pocket::generate(kind, shape, tool, opts, &coarse()) {
            Ok(r) => {
                let p = r.verification.problems();
                prop_assert!(p.is_empty(), "{kind:?}: {p:?}");
                prop_assert!(r.verification.uncut_area_mm2 <= 0.05);
                prop_assert!(r.toolpath.cut_length() > 0.0);
            }
            Err(Error::Input(e)) => {
                let text = e.to_string();
                prop_assert!(
                    text.starts_with("invalid ")
                        && text.contains("(from ")
                        && text.contains("expected"),
                    "{kind:?}: {text}"
                );
                all = false;
            }
            Err(e) => prop_assert!(false, "{kind:?}: internal error {e}"),
        }
    }
    Ok(all)
}

/// Runs `case` on [`CASES`] values of `strategy`; fails unless at least [`MIN_PLANNED`] were
/// planned by every strategy.
fn property<S: Strategy>(
    name: &str,
    strategy: S,
    case: impl Fn(S::Value) -> Result<bool, TestCaseError>,
) {
    let config = ProptestConfig {
        cases: CASES,
        rng_seed: seed(),
        failure_persistence: None,
        ..ProptestConfig::default()
    };
    let planned = std::sync::atomic::AtomicUsize::new(0);
    let mut runner = TestRunner::new(config);
    let result = runner.run(&strategy, |v| {
        if case(v)? {
            planned.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e} (seed {:?}; PROPTEST_RNG_SEED sets it)", seed());
    }
    let planned = planned.into_inner();
    assert!(
        planned >= MIN_PLANNED,
        "{name}: only {planned} of {CASES} cases planned by every strategy (seed {:?})",
        seed()
    );
}

/// The properties' random seed: fixed, so that the test command is repeatable (a randomly
/// seeded run found the spiral's uncut ridge slot below, and then failed the test command at random);
/// `PROPTEST_RNG_SEED=N` explores others:
/// `for n in $(seq 1 50); do PROPTEST_RNG_SEED=$n cargo test --release -p millpath --test pocket_props || break; done`.
fn seed() -> RngSeed {
    std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .map_or(RngSeed::Fixed(1), RngSeed::Fixed)
}

fn one_level(so: f64) -> PocketOptions {
    PocketOptions::default()
        .with_depth(1.0)
        .with_step_down(1.0)
        .with_stepover(pocket::Stepover::Fraction(so))
}

#[test]
fn convex_pockets_verify() {
    let s = (
        10.0f64..16.0,
        5usize..8,
        3.0f64..7.0,
        0.2f64..1.0,
        any::<bool>(),
    );
    property("convex", s, |(r, n, d, so, arcs)| {
        let o = star(&vec![r; n], 2.0).expect("a regular polygon");
        let tool = Tool::flat(d).unwrap();
        check(
            &ALL,
            &PocketShape::simple(o),
            &tool,
            &one_level(so).with_arcs(arcs),
        )
    });
}

#[test]
fn non_convex_pockets_verify() {
    let s = (
        prop::collection::vec(9.0f64..17.0, 6..9),
        2.5f64..5.0,
        0.2f64..1.0,
        any::<bool>(),
    );
    property("non-convex", s, |(radii, d, so, arcs)| {
        let o = star(&radii, 1.5).expect("a star");
        let tool = Tool::flat(d).unwrap();
        check(
            &ALL,
            &PocketShape::simple(o),
            &tool,
            &one_level(so).with_arcs(arcs),
        )
    });
}

#[test]
fn pockets_with_islands_verify() {
    let s = (
        prop::collection::vec(15.0f64..19.0, 6..8),
        prop::collection::vec(
            (0.0f64..std::f64::consts::TAU, 0.0f64..7.0, 1.5f64..3.5),
            1..4,
        ),
        2.5f64..4.5,
        0.25f64..0.7,
    );
    property("islands", s, |(radii, islands, d, so)| {
        let o = star(&radii, 1.5).expect("a star");
        // Random islands that overlap are moved apart along their angles (overlapping ones are
        // an input error, checked elsewhere); each keeps 1 mm from the others.
        let mut isl: Vec<(Point, f64)> = Vec::new();
        for &(a, rho, ri) in &islands {
            let c = Point::ORIGIN + Vec2::from_angle(a) * rho;
            if isl.iter().all(|(q, rq)| q.distance(c) > ri + rq + 1.0) {
                isl.push((c, ri));
            }
        }
        let shape = PocketShape::new(
            o,
            isl.iter().map(|&(c, r)| circle(c, r)).collect(),
            "random islands",
        )
        .expect("islands apart");
        let tool = Tool::flat(d).unwrap();
        check(&ALL, &shape, &tool, &one_level(so))
    });
}

/// A randomly seeded `non_convex_pockets_verify` found this star (8 radii, a 4.97 mm tool at
/// 72% stepover): the distance to the boundary offset has a second maximum in the upper-left
/// lobe nearly as high as the one the spiral's core sits on, so the first front reached into
/// the lobe at once. The fronts took it as a ridge slot (a thin neighbourhood of the medial
/// ridge, cut by the first lap tracing the front) without checking that it was thin: the lap
/// ran round the lobe 7 mm from the core and left 21 mm² uncut inside it, with chords and with
/// `--arcs`. Now a front whose new part is not within 0.9 r of its loops is no slot, and the
/// harmonic morph takes the pocket.
#[test]
fn a_second_maximum_of_the_distance_is_not_taken_for_a_ridge_slot() {
    let radii = [
        15.920744303040173,
        10.097192062822225,
        16.69617998230954,
        16.271318990413548,
        15.169366527125218,
        10.978016778729064,
        16.67245195186218,
        15.181104768615349,
    ];
    let o = star(&radii, 1.5).unwrap();
    let tool = Tool::flat(4.9680392574462475).unwrap();
    for arcs in [false, true] {
        let opts = one_level(0.7175041304758163).with_arcs(arcs);
        let r = pocket::generate(
            StrategyKind::Spiral,
            &PocketShape::simple(o.clone()),
            &tool,
            &opts,
            &coarse(),
        )
        .unwrap();
        let p = r.verification.problems();
        assert!(p.is_empty(), "arcs {arcs}: {p:?}");
        assert!(r.verification.uncut_area_mm2 < 0.05, "arcs {arcs}");
    }
}

/// The pocket moved: turned by `angle` about the origin, translated, optionally reversed,
/// its vertices started `shift` places later.
fn transformed(o: &Outline, angle: f64, dx: f64, dy: f64, reverse: bool, shift: usize) -> Outline {
    let mut v: Vec<(Point, f64)> = o
        .vertices()
        .map(|(p, b)| (p.rotate_about(Point::ORIGIN, angle) + Vec2::new(dx, dy), b))
        .collect();
    let k = shift % v.len().max(1);
    v.rotate_left(k);
    if reverse {
        // Reversed direction: vertices backwards, each bulge moves to the other end and flips.
        let n = v.len();
        let rev: Vec<(Point, f64)> = (0..n)
            .map(|i| (v[n - 1 - i].0, -v[(2 * n - 2 - i) % n].1))
            .collect();
        v = rev;
    }
    Outline::new(&v, "moved").unwrap()
}

/// Path length and cycle time on `hsm` of `kind` on the pocket `o` with an island `isl`.
fn run(kind: StrategyKind, o: Outline, isl: Outline) -> (f64, f64) {
    let tool = Tool::flat(6.0).unwrap();
    let opts = PocketOptions::default().with_depth(2.0).with_step_down(2.0);
    let shape = PocketShape::new(o, vec![isl], "moved").unwrap();
    let tp = pocket::toolpath(kind, &shape, &tool, &opts).unwrap();
    (tp.cut_length(), hsm_time(&tp))
}

/// An L-shaped pocket (no symmetry) with a round island.
fn l_pocket() -> (Outline, Outline) {
    let p = Point::new;
    let ell = builtin::rounded_polygon(
        &[
            p(0.0, 0.0),
            p(50.0, 0.0),
            p(50.0, 18.0),
            p(20.0, 18.0),
            p(20.0, 40.0),
            p(0.0, 40.0),
        ],
        4.0,
        "L",
    )
    .unwrap();
    (ell, circle(p(10.0, 10.0), 3.0))
}

/// Reversed, translated, turned by 90° and 180°, and started at another vertex: the cycle
/// time on `hsm` within 0.5% (the machine's axes are alike, so quarter turns are symmetries
/// of the machine too).
#[test]
fn invariance_under_reversal_translation_quarter_turns_and_start_vertex() {
    let (base, isl) = l_pocket();
    for kind in ALL {
        let (l0, t0) = run(kind, base.clone(), isl.clone());
        for (angle, dx, dy, rev, shift) in [
            (0.0, 0.0, 0.0, true, 0),
            (0.0, 123.0, -45.0, false, 0),
            (std::f64::consts::FRAC_PI_2, 0.0, 0.0, false, 0),
            (std::f64::consts::PI, 17.0, 3.0, true, 0),
            (0.0, 0.0, 0.0, false, 3),
            (0.0, 0.0, 0.0, false, 7),
            (std::f64::consts::FRAC_PI_2, -8.0, 2.0, true, 5),
        ] {
            let (l, t) = run(
                kind,
                transformed(&base, angle, dx, dy, rev, shift),
                transformed(&isl, angle, dx, dy, rev, shift),
            );
            assert!(
                (l - l0).abs() <= 0.005 * l0,
                "{kind:?} length {l} vs {l0} ({angle}, {rev}, {shift})"
            );
            assert!(
                (t - t0).abs() <= 0.005 * t0,
                "{kind:?} time {t} vs {t0} ({angle}, {rev}, {shift})"
            );
        }
    }
}

/// Turned by arbitrary angles: the path is the same path turned (length within 0.5%: offset
/// loops and the spiral on them are a property of the region, zigzag passes are laid in the
/// pocket's principal frame); the cycle time on `hsm` changes with the angle because its limits are per axis
/// (a move at 45° may use √2 times the axis velocity and acceleration along the path). How
/// much is measured here and bounded; see the zigzag module docs.
#[test]
#[allow(clippy::print_stderr)]
fn arbitrary_rotation_keeps_the_path_and_bounds_the_time_change() {
    let (base, isl) = l_pocket();
    for kind in ALL {
        let (l0, t0) = run(kind, base.clone(), isl.clone());
        let mut worst: f64 = 0.0;
        for angle in [0.3, 0.7, std::f64::consts::FRAC_PI_4, 2.0] {
            let (l, t) = run(
                kind,
                transformed(&base, angle, 5.0, -7.0, false, 0),
                transformed(&isl, angle, 5.0, -7.0, false, 0),
            );
            assert!(
                (l - l0).abs() <= 0.005 * l0,
                "{kind:?} length {l} vs {l0} at {angle} rad"
            );
            worst = worst.max((t - t0).abs() / t0);
            eprintln!("{kind:?} at {angle:.3} rad: time {t:.3} s vs {t0:.3} s");
        }
        eprintln!(
            "{kind:?}: largest time change under rotation {:.2}%",
            100.0 * worst
        );
        assert!(worst <= MAX_ROTATION_TIME_CHANGE, "{kind:?}: {worst}");
    }
}

/// The largest relative change of the `hsm` cycle time under an arbitrary rotation.
const MAX_ROTATION_TIME_CHANGE: f64 = 0.06;

/// Cycle time on the `hsm` preset, s.
fn hsm_time(tp: &millpath::toolpath::Toolpath) -> f64 {
    let hsm = millpath::machine::Machine::preset("hsm").unwrap();
    millpath::motion::cycle_time(tp, &hsm).unwrap()
}
