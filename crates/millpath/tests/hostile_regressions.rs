//! Inputs the hostile passes (`hostile_*.rs`) found panicking, kept as regression tests: each
//! must now be refused with an input error that names the offending value.

use millpath::Error;
use millpath::io::{dxf, svg};

/// A DXF polyline with a vertex at -1e308 and a bulge of -1e308: `cavalier_contours` asserted
/// ("point does not lie on the line defined by p0 to p1") while scanning for self-intersections.
/// Fixed in `Outline::from_polyline`: coordinates beyond ±1e6 mm and bulges beyond 1000 are
/// refused.
#[test]
fn dxf_vertex_at_1e308_is_refused() {
    let text = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n90\n4\n70\n1\n10\n-68.02\n20\n-53.09\n\
                10\n-1e308\n20\n-1e308\n42\n-1e308\n10\n87.14\n20\n45.12\n0\nENDSEC\n0\nEOF\n";
    let e = dxf::parse(text.as_bytes(), "r.dxf", &dxf::DxfOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("1e308") || msg.contains("100000000"), "{msg}");
    assert!(msg.contains("vertex 1"), "{msg}");
}

/// A polyline whose coordinates are ordinary but one vertex is 1e29 mm away.
#[test]
fn dxf_huge_coordinate_is_refused() {
    let text = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n90\n4\n70\n1\n\
                10\n99999999999999999999999999999\n20\n82.31\n10\n-97.62\n20\n-37.12\n\
                10\n98.28\n20\n0\n42\n-72.21\n0\nENDSEC\n0\nEOF\n";
    let e = dxf::parse(text.as_bytes(), "r.dxf", &dxf::DxfOptions::default()).unwrap_err();
    assert!(e.to_string().contains("within ±1000000 mm"), "{e}");
}

/// An SVG cubic with a control point at -1e308: kurbo's flattening computed an infinite
/// subdivision count and `Vec::with_capacity` panicked with "capacity overflow". Fixed in
/// `svg::path_loops`: curve points are checked before flattening.
#[test]
fn svg_curve_at_1e308_is_refused() {
    let doc = r#"<svg><path d="M -29.08 -10 L -17.13 -69.92 S 0 -20.54 13.56 -1e308 Z"/></svg>"#;
    let e = svg::parse(doc, "r.svg", 0.01).unwrap_err();
    assert!(e.to_string().contains("SVG curve point"), "{e}");
}

/// A flattening tolerance that is not a positive number ≥ 1e-6 mm is refused up front (a zero
/// or tiny tolerance would flatten a curve into an unbounded number of points).
#[test]
fn svg_bad_tolerance_is_refused() {
    let doc = r#"<svg><circle cx="0" cy="0" r="5"/></svg>"#;
    for tol in [f64::NAN, 0.0, -1.0, 1e-12, f64::INFINITY] {
        let e = svg::parse(doc, "r.svg", tol).unwrap_err();
        assert!(e.to_string().contains("tolerance"), "{tol}: {e}");
    }
    assert!(svg::parse(doc, "r.svg", 0.01).is_ok());
}

/// The outline bounds also hold for outlines built in code.
#[test]
fn outline_bounds_are_input_errors() {
    use millpath::Point;
    use millpath::geom::Outline;
    let far = [
        Point::new(0.0, 0.0),
        Point::new(2e6, 0.0),
        Point::new(0.0, 10.0),
    ];
    let e: Error = Outline::from_points(&far, "code").unwrap_err().into();
    assert_eq!(e.exit_code(), 2);
    let bulgy = [(Point::new(0.0, 0.0), 1e300), (Point::new(10.0, 0.0), 1.0)];
    assert!(Outline::new(&bulgy, "code").is_err());
}

/// A plausible zigzag pocket with a ramp entry that the hostile pass found exhausting memory
/// (7 GB): one of its cuts is a sliver so short that the ramp's back-and-forth pass count
/// `need / head_len` was unbounded. Fixed in `pocket::levels::emit_cut`: beyond 1000 passes the
/// cut is entered by a straight plunge.
#[test]
fn pocket_ramp_on_a_sliver_cut_is_bounded() {
    use millpath::Point;
    use millpath::geom::Outline;
    use millpath::strategy::pocket::{self, Direction, Entry, PocketOptions, PocketShape};
    use millpath::strategy::pocket::{Stepover, StrategyKind};
    let pts = [
        (0.5067506716790149, 33.923399300629576),
        (-15.495039039066494, 83.90680780322668),
        (-28.44732723208258, 57.46344395193826),
        (-20.500436449782423, 85.80478063380576),
        (-39.66484633370397, 51.29906856939858),
        (-83.74719229597198, -4.105740147203079),
        (-46.45767021370686, -0.10159339765712261),
        (-24.659186956136672, 12.064754661027553),
    ]
    .map(|(x, y)| Point::new(x, y));
    let shape = PocketShape::simple(Outline::from_points(&pts, "sliver").unwrap());
    let tool = millpath::Tool {
        diameter: 14.165822809604304,
        flutes: 1,
        flute_length: 39.9137923757302,
        number: 49,
    };
    let opts = PocketOptions::default()
        .with_stepover(Stepover::Fraction(0.7923288621551071))
        .with_depth(7.152658507092601)
        .with_step_down(3.859490583661331)
        .with_wall_stock(0.27679943486176584)
        .with_floor_stock(0.06921936228126015)
        .with_direction(Direction::Climb)
        .with_entry(Entry::Ramp {
            ramp_angle: 0.08997854129228909,
        })
        .with_safe_height(0.7406850003585472)
        .with_clearance_height(8.285104908990768)
        .with_feed(22.84844133869721)
        .with_plunge_feed(11.53364949088229)
        .with_slowdown(0.3309526681507178)
        .with_zigzag_angle(-2.7371216566852055)
        .with_transition(0.7358653342432562)
        .with_min_radius(0.8251498205924716)
        .with_morph(Default::default())
        .with_arcs(false)
        .with_curvature_ramps(true)
        .with_finish(false)
        .with_modulate_feed(false);
    let tp = pocket::toolpath(StrategyKind::Zigzag, &shape, &tool, &opts).unwrap();
    assert!(tp.moves.len() < 100_000, "{} moves", tp.moves.len());
    assert!(tp.moves.iter().all(|m| m.to.is_finite()));
}

/// The `contour` fuzzer (17 crash files): a depth of 1e300 mm with a 1 mm step-down made
/// `contour::layer_depths` allocate `1e300` layers (capacity overflow). Fixed in
/// `ContourOptions::validate`: at most `MAX_LAYERS` (10,000) layers.
#[test]
fn contour_depth_1e300_is_refused() {
    use millpath::strategy::contour;
    let (c, base) = contour::sample().unwrap();
    let opt = base.with_depth(1e300).with_step_down(1.0);
    let e: Error = contour::contour(&c, &opt).unwrap_err();
    assert_eq!(e.exit_code(), 2);
    let msg = e.to_string();
    assert!(
        msg.contains("step-down") && msg.contains("10000 layers"),
        "{msg}"
    );
}

/// The `contour` fuzzer: a curve through a point at y = 1e300 reached kurbo's flattening in
/// the contour report, which asked for a capacity overflow. Fixed in `curve::build`: points
/// beyond ±1e6 mm are refused, naming the point.
#[test]
fn curve_point_at_1e300_is_refused() {
    use millpath::curve::{self, CurveKind, LabeledPoint};
    let pts = [(0.0, 0.0), (10.0, 0.0), (10.0, 1e300), (0.0, 10.0)];
    let group: Vec<LabeledPoint> = pts
        .iter()
        .enumerate()
        .map(|(i, &(x, y))| LabeledPoint {
            p: millpath::Point::new(x, y),
            origin: format!("p.csv:{}", i + 1),
        })
        .collect();
    for kind in [
        CurveKind::FourPoint,
        CurveKind::CatmullRom,
        CurveKind::Spline,
    ] {
        let e = curve::build(std::slice::from_ref(&group), kind, "p.csv").unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("p.csv:3") && msg.contains("±1000000 mm"),
            "{kind:?}: {msg}"
        );
    }
}

/// The `planner` fuzzer (150 crash files): a move to y = 1e300 planned to an infinite cycle
/// time (and the verifier then reported an infinite position error); a feed of 1e-300 mm/s or
/// a dwell of 1e300 s does the same. Fixed in `motion::plan` (`Builder::push`): coordinates
/// within ±1e6 mm, feeds ≥ `MIN_FEED` (1e-6 mm/s), dwells ≤ `MAX_DWELL` (1e6 s).
#[test]
fn planner_refuses_moves_whose_time_overflows() {
    use millpath::machine::Machine;
    use millpath::motion::plan_toolpath;
    use millpath::{Move, Point3, Tool, Toolpath};
    let m = Machine::preset("hsm").unwrap();
    let cases = [
        (Move::line(Point3::new(0.0, 1e300, 0.0), 10.0), "end point"),
        (Move::line(Point3::new(0.0, 10.0, 0.0), 1e-300), "feed"),
        (Move::dwell(Point3::ORIGIN, 1e300), "dwell"),
    ];
    for (mv, what) in cases {
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp.push(Move::line(Point3::new(1.0, 0.0, 0.0), 10.0));
        tp.push(mv);
        let e = plan_toolpath(&tp, &m).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{what}: {e}");
        let msg = e.to_string();
        assert!(
            msg.contains(what) && msg.contains("move 2"),
            "{what}: {msg}"
        );
    }
}

/// The `contour` fuzzer (timeout, 22 s under ASan; 8.7 s in release): a contour with a lead
/// radius, safe and clearance heights of 1e300 mm; and (out of memory, 2 GB) a tool of
/// 1e300 mm, whose corner joins `contour::pass::join_corner` sampled with 3e9 points. Fixed in
/// `ContourOptions::validate`: lengths beyond ±1e6 mm are refused.
#[test]
fn contour_lengths_of_1e300_are_refused() {
    use millpath::strategy::contour;
    let (c, base) = contour::sample().unwrap();
    for (what, opt) in [
        ("lead radius", base.clone().with_lead_radius(1e300)),
        (
            "safe height",
            base.clone()
                .with_safe_height(1e300)
                .with_clearance_height(1.0),
        ),
        (
            "tool diameter",
            base.clone().with_tool(millpath::Tool {
                diameter: 1e300,
                ..base.tool
            }),
        ),
    ] {
        let e: Error = contour::contour(&c, &opt).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains(what) && msg.contains("±1000000 mm"),
            "{what}: {msg}"
        );
    }
}

/// The `contour` fuzzer (600 s run, 2026-11-22; `fuzz/corpus-min/contour/regression-timeout-
/// cusp-biarcs-*`): a four-point curve through a repeated point (a cusp) contoured on the
/// line with biarcs took over a minute (ASan: > 20 s, a timeout): near the cusp the biarcs
/// shrank without end, ~10⁶ deviation evaluations. Fixed in `curve::biarc::fit`: after
/// `MAX_DEV_EVALUATIONS` the rest of the stretch is cut in chords within the tolerance
/// (13,082 moves; 22,112 since 8a0e3b4, whose biarc ends are bisected to 1e-4 of their
/// length instead of 1e-7, so the same budget makes more, cheaper biarcs near the cusp).
#[test]
fn contour_biarcs_through_a_cusp_finish() {
    use millpath::curve::{self, CurveKind, LabeledPoint};
    use millpath::strategy::contour::{self, ContourOptions, Side};
    let pts = [
        (-8.0302257886446, -60.24298466468299),
        (-48.7718128166808, -60.24176609714611),
        (-8.0302257886446, -60.24298466468299),
        (-8.037537193865873, -60.24298466468299),
    ];
    let group: Vec<LabeledPoint> = pts
        .iter()
        .enumerate()
        .map(|(i, &(x, y))| LabeledPoint {
            p: millpath::Point::new(x, y),
            origin: format!("point {i}"),
        })
        .collect();
    // The input must still build: a regression test that returned early here would pass
    // whatever the biarcs did.
    let c = curve::build(std::slice::from_ref(&group), CurveKind::FourPoint, "fuzz")
        .expect("the cusp curve builds");
    let opt = ContourOptions::default()
        .with_tool(millpath::Tool {
            diameter: 12.988927335640138,
            flutes: 2,
            flute_length: 24.01007095445182,
            number: 1,
        })
        .with_tolerance(0.15452526985580226)
        .with_rounding(7.071067811865475e-5)
        .with_side(Side::On)
        .with_top_z(-0.1561760891126882)
        .with_depth(3.3226367589837493)
        .with_step_down(1.0117189288166628)
        .with_finish_allowance(0.0)
        .with_safe_height(1.0)
        .with_clearance_height(0.5585946440833143)
        .with_feed(26.07460135805295)
        .with_plunge_feed(1.0)
        .with_lead_radius(0.0)
        .with_rapid_speed(50.13275349050126)
        .with_arcs(true);
    let res = contour::contour(&c, &opt).expect("contour");
    // Four layers of a short closed curve: thousands of moves a layer at most, not ~10⁶.
    assert!(
        res.toolpath.moves.len() < 30_000,
        "{} moves",
        res.toolpath.moves.len()
    );
    assert!(
        res.report.max_deviation_mm <= opt.tolerance,
        "deviation {}",
        res.report.max_deviation_mm
    );
}
