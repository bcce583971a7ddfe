//! Adaptive clearing holds the engagement: on every pocket of the suite (islands, necks,
//! slots, the structural and the sample part's pockets) the adaptive toolpath verifies
//! (no gouge, nothing uncut: `pocket::generate` refuses otherwise), and the stock simulation,
//! run again here with its samples recorded (another grid and another sweep than the
//! planner's own), finds the engagement at most 1.1 × the stepover's on at least 99 % of the
//! cutting length and never above 1.3 × (or 1.1 × what a sharp corner of the pocket forces on
//! any program, where that is more), the entries aside (`stock::engagement_stats`).

use millpath::stock::{self, SimOptions, StockSpec, engagement_stats};
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::toolpath::Tool;

/// The suite's pockets, the structural part's and the sample part's, with their tools.
fn suite() -> Vec<(String, PocketShape, f64)> {
    let mut out: Vec<(String, PocketShape, f64)> = builtin::shape_suite()
        .into_iter()
        .map(|s| (s.name.to_owned(), s.shape, s.tool_diameter))
        .collect();
    for (name, shape) in builtin::structural_part() {
        out.push((format!("structural {name}"), shape, 10.0));
    }
    out
}

/// The largest engagement allowed: 1.3 × the target (Done-when 1 of issue 41), or 1.1 × what
/// a tool feeding straight into the pocket's sharpest corner reaches where that is more
/// (`pocket::engagement_floor`: `acos(2·sin(α/2) − 1)` at a corner of interior angle `α` of
/// the tool-centre region).
fn allowed(nominal_deg: f64, shape: &PocketShape, tool: &Tool) -> f64 {
    let floor = pocket::engagement_floor(shape, tool, 0.0).to_degrees();
    (1.3 * nominal_deg).max(1.1 * floor)
}

/// The engagement of `tp` cutting `shape`, measured by the verifier.
fn measured(
    tp: &millpath::toolpath::Toolpath,
    shape: &PocketShape,
    nominal_deg: f64,
) -> stock::EngagementStats {
    let spec = StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock: 0.0,
    };
    let sim = stock::simulate(
        tp,
        spec,
        nominal_deg,
        &SimOptions::default().with_record_samples(true),
    );
    engagement_stats(tp, &sim.samples, 1.1 * nominal_deg)
}

#[test]
#[allow(clippy::print_stderr)]
fn adaptive_holds_the_engagement_on_every_pocket_of_the_suite() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for ((name, shape, d), both_ways) in suite()
        .into_iter()
        .flat_map(|p| [(p.clone(), false), (p, true)])
    {
        let name = if both_ways {
            format!("{name} (both ways)")
        } else {
            name
        };
        let tool = Tool::flat(d).unwrap();
        let opts = PocketOptions::default()
            .with_depth(3.0)
            .with_step_down(3.0)
            .with_both_ways(both_ways);
        let r = match pocket::generate(
            StrategyKind::Adaptive,
            &shape,
            &tool,
            &opts,
            &SimOptions::default(),
        ) {
            Ok(r) => r,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let nominal = r.nominal_engagement_deg;
        let st = measured(&r.toolpath, &shape, nominal);
        checked += 1;
        eprintln!(
            "{name}: cut {:.0} mm, mean {:.1}°, p99 {:.1}°, max {:.1}° ({:.2} ×), {:.2} % above 1.1 ×",
            st.cutting_mm,
            st.mean_deg,
            st.p99_deg,
            st.max_deg,
            st.max_deg / nominal,
            100.0 * st.share_above_bound
        );
        let limit = allowed(nominal, &shape, &tool);
        if st.cutting_mm <= 0.0 || st.share_above_bound > 0.01 || st.max_deg > limit {
            failures.push(format!(
                "{name}: {:.2} % of {:.0} mm above 1.1 × {nominal:.1}°, max {:.1}° (allowed {limit:.1}°)",
                100.0 * st.share_above_bound,
                st.cutting_mm,
                st.max_deg
            ));
        }
    }
    assert!(checked >= 28, "{checked} pockets checked");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A tool that does not fit is the user's error, as for every strategy: not an empty program
/// (a 12.7 mm tool in a 10 mm square).
#[test]
fn a_tool_that_does_not_fit_is_refused() {
    let sq = millpath::geom::Outline::from_points(
        &[
            millpath::geom::Point::new(0.0, 0.0),
            millpath::geom::Point::new(10.0, 0.0),
            millpath::geom::Point::new(10.0, 10.0),
            millpath::geom::Point::new(0.0, 10.0),
        ],
        "square",
    )
    .unwrap();
    let shape = PocketShape::simple(sq);
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions::default().with_depth(3.0).with_step_down(3.0);
    let r = pocket::generate(
        StrategyKind::Adaptive,
        &shape,
        &tool,
        &opts,
        &SimOptions::default(),
    );
    match r {
        Err(millpath::Error::Input(e)) => assert!(e.to_string().contains("tool diameter"), "{e}"),
        other => panic!(
            "expected an input error, got {:?}",
            other.map(|r| r.toolpath.moves.len())
        ),
    }
}

/// Feeding straight into a corner of interior angle `α` of the tool-centre region, a tool
/// cuts at `acos(2·sin(α/2) − 1)` (`stock::corner_floor`). On pockets with sharp corners of
/// 15°, 25°, 45°, 60° and 90° the floor is that angle. At the square's and the triangle's
/// corners the walls' loop feeds in, and the largest engagement the simulation measures is
/// at least 0.9 × the floor (it is one for that motion). The acuter corners are worked into
/// by strokes across them first (`adaptive::tips`), which spread the corner's material over
/// more travel than a straight feed: within [`allowed`], and under the floor at 15° and 45°
/// (where the walls' loop met what the passes left at 137°, 1.3 × the floor, before).
#[test]
fn adaptive_reaches_what_a_sharp_corner_forces_and_no_more() {
    use millpath::geom::{Outline, Point};
    let tool = Tool::flat(10.0).unwrap();
    let deg = |a: f64| a.to_radians();
    let poly = |pts: &[(f64, f64)]| {
        let p: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
        PocketShape::simple(Outline::from_points(&p, "sharp").unwrap())
    };
    let wedge = |apex: f64, len: f64| {
        let h = 0.5 * deg(apex);
        poly(&[
            (0.0, 0.0),
            (len * h.cos(), -len * h.sin()),
            (len * h.cos(), len * h.sin()),
        ])
    };
    // The wedge turned by `deg` about its tip, its outline run the other way round.
    let turned = |apex: f64, len: f64, deg: f64| {
        let (h, (s, c)) = (0.5 * apex.to_radians(), deg.to_radians().sin_cos());
        let t = |x: f64, y: f64| (c * x - s * y, s * x + c * y);
        poly(&[
            (0.0, 0.0),
            t(len * h.cos(), len * h.sin()),
            t(len * h.cos(), -len * h.sin()),
        ])
    };
    // The pocket, its floor, and whether the largest engagement reaches 0.9 × the floor
    // (`Some(true)`), stays under it (`Some(false)`), or may do either.
    let cases = [
        (
            "square",
            poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 60.0), (0.0, 60.0)]),
            65.53,
            Some(true),
        ),
        ("triangle", wedge(60.0, 90.0), 90.0, Some(true)),
        ("45° wedge", wedge(45.0, 110.0), 103.57, Some(false)),
        ("25° spike", wedge(25.0, 150.0), 124.52, None),
        ("15° spike", wedge(15.0, 200.0), 137.64, Some(false)),
        (
            "15° spike turned 37°, its vertices reversed",
            turned(15.0, 200.0, 37.0),
            137.64,
            Some(false),
        ),
    ];
    let mut failures = Vec::new();
    for (name, shape, want, reaches) in cases {
        let floor = pocket::engagement_floor(&shape, &tool, 0.0).to_degrees();
        assert!(
            (floor - want).abs() < 0.5,
            "{name}: floor {floor:.2}° against {want}°"
        );
        let opts = PocketOptions::default().with_depth(3.0).with_step_down(3.0);
        let r = pocket::generate(
            StrategyKind::Adaptive,
            &shape,
            &tool,
            &opts,
            &SimOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        let st = measured(&r.toolpath, &shape, r.nominal_engagement_deg);
        match reaches {
            Some(true) if st.max_deg < 0.9 * floor => failures.push(format!(
                "{name}: max {:.1}° under the floor {floor:.1}°",
                st.max_deg
            )),
            Some(false) if st.max_deg >= floor => failures.push(format!(
                "{name}: max {:.1}° not under the floor {floor:.1}°",
                st.max_deg
            )),
            _ => {}
        }
        let limit = allowed(r.nominal_engagement_deg, &shape, &tool);
        if st.max_deg > limit {
            failures.push(format!("{name}: max {:.1}° above {limit:.1}°", st.max_deg));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A long pocket is entered along its ridge: the aerospace pocket's descent is a racetrack
/// whose straights run along the long axis over the ridge (the points 50 mm from both long
/// walls: `x` from −25 to 25 at `y = 0`), so that the passes grow its offsets, not circles.
/// Checked on the moves: the descending lines, their direction and extent, and every
/// descending move within the helix radius of the ridge segment.
#[test]
fn a_long_pocket_is_entered_along_its_ridge() {
    use millpath::toolpath::MoveKind;
    let shape = builtin::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions::default()
        .with_depth(5.0)
        .with_step_down(5.0)
        .with_stepover(pocket::Stepover::Fraction(0.4));
    let tp = pocket::toolpath(StrategyKind::Adaptive, &shape, &tool, &opts).unwrap();
    let mut straight = 0.0;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut descending = 0;
    for (from, m) in tp.segments() {
        if m.kind == MoveKind::Rapid || m.to.z >= from.z - 1e-9 {
            if descending > 0 {
                break;
            }
            continue;
        }
        descending += 1;
        for q in [from.xy(), m.to.xy()] {
            let along_ridge = (q.x.clamp(-25.0, 25.0) - q.x).hypot(q.y);
            assert!(along_ridge <= 6.0 + 1e-6, "{q:?} off the ridge");
            lo = lo.min(q.x);
            hi = hi.max(q.x);
        }
        if matches!(m.kind, MoveKind::Line) {
            let d = m.to.xy() - from.xy();
            assert!(d.y.abs() < 1e-6 * d.length().max(1.0), "{d:?} not along x");
            straight += d.length();
        }
    }
    assert!(descending >= 4, "{descending} descending moves");
    assert!(straight >= 90.0, "{straight} mm of straights");
    assert!(lo <= -24.0 && hi >= 24.0, "{lo} … {hi}");
}

/// The aerospace pocket 5 mm deep at 40 % with the 12.7 mm tool (Done-when 1's program).
fn aerospace_5mm() -> (PocketShape, Tool, PocketOptions) {
    let opts = PocketOptions::default()
        .with_depth(5.0)
        .with_step_down(5.0)
        .with_stepover(pocket::Stepover::Fraction(0.4));
    (builtin::aerospace_pocket(), Tool::flat(12.7).unwrap(), opts)
}

/// The adaptive program, verified (`generate` refuses a gouge or uncut material).
fn adaptive(shape: &PocketShape, tool: &Tool, opts: &PocketOptions) -> pocket::PocketResult {
    pocket::generate(
        StrategyKind::Adaptive,
        shape,
        tool,
        opts,
        &SimOptions::default(),
    )
    .unwrap()
}

/// With `both_ways` the passes that end at a wall (the aerospace pocket's corners) are cut
/// to and fro instead of each followed by a link back: the tool's feed travel at depth that
/// removes nothing (the verifier's cutting flags) is a tenth or more shorter than climb only,
/// the program verifies (`generate` refuses otherwise), and the verifier's engagement holds
/// the bound as climb's does.
#[test]
fn both_ways_travels_less_in_the_air_and_holds_the_bound() {
    use millpath::toolpath::MoveKind;
    let (shape, tool, base) = aerospace_5mm();
    let air = |opts: &PocketOptions| {
        let r = adaptive(&shape, &tool, opts);
        let nominal = r.nominal_engagement_deg;
        let st = measured(&r.toolpath, &shape, nominal);
        assert!(
            st.share_above_bound <= 0.01 && st.max_deg <= allowed(nominal, &shape, &tool),
            "{:.2} % above 1.1 ×, max {:.1}°",
            100.0 * st.share_above_bound,
            st.max_deg
        );
        assert_eq!(r.cutting_moves.len(), r.toolpath.moves.len());
        r.toolpath
            .segments()
            .zip(&r.cutting_moves)
            .filter(|((from, m), cuts)| {
                !**cuts && m.kind != MoveKind::Rapid && (m.to.z - from.z).abs() < 1e-9
            })
            .map(|((from, m), _)| from.xy().distance(m.to.xy()))
            .sum::<f64>()
    };
    let climb = air(&base);
    let both = air(&base.clone().with_both_ways(true));
    assert!(
        both < 0.9 * climb,
        "{both:.0} mm in the air against {climb:.0}"
    );
}

/// Both ways, the aerospace program as `millpath pocket` makes it (its helix of 0.45 D) leaves
/// the level once, at its end: the walls' loop is reached at depth, where the tool backs away
/// from the wall and feeds straight onto the loop's start when a link there directly would
/// take what the last passes left in one step (it retracted and plunged beside it before).
/// The program verifies (`generate`).
#[test]
fn both_ways_reaches_the_walls_loop_without_a_retract() {
    use millpath::toolpath::MoveKind;
    let (shape, tool, base) = aerospace_5mm();
    let opts = base.with_both_ways(true).with_entry(pocket::Entry::Helix {
        radius: millpath::job::pocket::DEFAULT_HELIX_RADIUS_PER_DIAMETER * tool.diameter,
        ramp_angle: 3f64.to_radians(),
    });
    let r = adaptive(&shape, &tool, &opts);
    let retracts: Vec<_> = r
        .toolpath
        .segments()
        .filter(|(from, m)| m.kind == MoveKind::Rapid && from.z < -4.9 && m.to.z > from.z)
        .map(|(from, _)| from)
        .collect();
    assert_eq!(retracts.len(), 1, "retracts from the level at {retracts:?}");
}

/// With `lift` the links through cleared material rise over the floor and settle again:
/// the XY path is the one at the level (its length the same), only moves along links rise
/// (at most by the lift, some by all of it), and the program verifies and cuts as before
/// (the verifier's engagement), in about the same time.
#[test]
fn lifted_links_keep_the_path_and_cut_as_at_the_level() {
    use millpath::toolpath::MoveKind;
    let (shape, tool, base) = aerospace_5mm();
    let lift = 0.25;
    let flat = adaptive(&shape, &tool, &base);
    let lifted = adaptive(&shape, &tool, &base.clone().with_lift(lift));
    let xy_length = |tp: &millpath::toolpath::Toolpath| {
        tp.segments()
            .filter(|(_, m)| m.kind != MoveKind::Rapid)
            .map(|(from, m)| from.xy().distance(m.to.xy()))
            .sum::<f64>()
    };
    let (la, lb) = (xy_length(&flat.toolpath), xy_length(&lifted.toolpath));
    assert!(
        (la - lb).abs() < 1e-6 * la,
        "{la} mm at the level, {lb} mm lifted"
    );
    // Moves within the lift over the floor that start or end above it: the links' rises,
    // runs and descents, besides the last steps of the ramps the programs share.
    let within = |z: f64| z >= -5.0 - 1e-9 && z <= -5.0 + lift + 1e-9;
    let raised = |tp: &millpath::toolpath::Toolpath| -> Vec<f64> {
        tp.segments()
            .filter(|(from, m)| {
                within(from.z) && within(m.to.z) && from.z.max(m.to.z) > -5.0 + 1e-9
            })
            .map(|(from, m)| from.z.max(m.to.z))
            .collect()
    };
    let whole = |v: &[f64]| {
        v.iter()
            .filter(|&&z| (z - (-5.0 + lift)).abs() < 1e-9)
            .count()
    };
    let (before, up) = (raised(&flat.toolpath), raised(&lifted.toolpath));
    let full = whole(&up) - whole(&before);
    assert!(
        up.len() >= before.len() + 6 && full >= 4,
        "{} raised moves ({} at the level), {full} at the whole lift",
        up.len(),
        before.len()
    );
    let (sa, sb) = (
        measured(&flat.toolpath, &shape, flat.nominal_engagement_deg),
        measured(&lifted.toolpath, &shape, lifted.nominal_engagement_deg),
    );
    assert!(
        (sa.max_deg - sb.max_deg).abs() < 1e-9 && (sa.mean_deg - sb.mean_deg).abs() < 0.5,
        "{sa:?} against {sb:?}"
    );
    let hsm = millpath::machine::Machine::preset("hsm").unwrap();
    let time = |tp| millpath::motion::cycle_time(tp, &hsm).unwrap();
    let (ta, tb) = (time(&flat.toolpath), time(&lifted.toolpath));
    assert!(tb < 1.02 * ta, "{tb:.2} s lifted against {ta:.2} s");
}
