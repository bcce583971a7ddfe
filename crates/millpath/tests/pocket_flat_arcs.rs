//! Near-straight arcs never reach a program: the writer writes an arc whose sagitta is at most
//! its output rounding as a line, and the pocket emits such arcs as lines itself (so the path
//! verified and timed is the path written). Regression: `--arcs` on a long rounded slot fitted
//! a biarc along a straight side whose centre lay 1.4 km away; the planner refused it as an
//! input error (exit 2).

use millpath::gcode::{
    ReaderOptions, Units, WriterOptions, read_str, rounding_error_mm, write_to_string,
};
use millpath::geom::Point3;
use millpath::machine::Machine;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind};
use millpath::toolpath::{Move, MoveKind, Tool, Toolpath};

/// A 180 × 30 mm slot with corners of radius 8 (bulge tan(π/8) for a quarter circle).
fn rounded_slot() -> PocketShape {
    let b = (std::f64::consts::PI / 8.0).tan();
    let json = format!(
        r#"{{"outline": [[8,0],[172,0,{b}],[180,8],[180,22,{b}],[172,30],[8,30,{b}],[0,22],[0,8,{b}]]}}"#
    );
    let l = millpath::io::outline_json::parse(&json, "slot").unwrap();
    PocketShape::new(l.outer, l.islands, "slot").unwrap()
}

#[test]
fn the_pockets_arc_criterion_is_the_writers_default_rounding() {
    assert!((pocket::ARC_AS_LINE_SAGITTA - rounding_error_mm(3, Units::Mm)).abs() < 1e-18);
    assert_eq!(WriterOptions::default().effective_decimals(), 3);
}

#[test]
fn rounded_slot_spiral_with_arcs_verifies_times_and_writes() {
    let tool = Tool::flat(10.0).unwrap();
    let opts = PocketOptions::default()
        .with_depth(5.0)
        .with_step_down(5.0)
        .with_arcs(true);
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    let r = pocket::generate(StrategyKind::Spiral, &rounded_slot(), &tool, &opts, &sim).unwrap();
    let problems = r.verification.problems();
    assert!(problems.is_empty(), "{problems:?}");
    let mut arcs = 0;
    for (from, m) in r.toolpath.segments() {
        if let MoveKind::Arc { center, .. } = m.kind {
            arcs += 1;
            let s = m.sagitta_from(from).unwrap();
            assert!(
                s > pocket::ARC_AS_LINE_SAGITTA,
                "flat arc {m:?} (sagitta {s})"
            );
            assert!(center.x.abs().max(center.y.abs()) < 1e6, "{m:?}");
        }
    }
    assert!(arcs > 10, "{arcs} arcs");
    let hsm = Machine::preset("hsm").unwrap();
    let t = millpath::motion::plan_toolpath(&r.toolpath, &hsm)
        .unwrap()
        .total_time();
    // Written as planned: no arc left for the writer to straighten, and the program read back
    // plans to the same time within the rounding.
    let (text, summary) = write_to_string(&r.toolpath, &WriterOptions::default()).unwrap();
    assert_eq!(summary.arcs_as_lines, 0);
    let (mut back, _) = read_str(&text, ReaderOptions::default()).unwrap();
    // The program starts wherever the machine is (the reader: the origin); the plan starts
    // above its first point. Compare from the same start.
    back.start = r.toolpath.start;
    let t_back = millpath::motion::plan_toolpath(&back, &hsm)
        .unwrap()
        .total_time();
    assert!(
        (t - t_back).abs() < 0.01 * t,
        "{t} s planned, {t_back} s read back"
    );
}

/// An arc of a 72.86 mm chord about a centre 1.42 km away (sagitta 0.47 µm) is a line at 3
/// decimals (rounding 0.71 µm) and an arc at 4 (0.071 µm); an arc of sagitta 1 µm stays an arc.
#[test]
fn the_writer_writes_an_arc_flatter_than_its_rounding_as_a_line() {
    let chord = 72.86;
    let one = |radius: f64| {
        let half = 0.5 * chord;
        let h = (radius * radius - half * half).sqrt();
        let mut tp = Toolpath::new(Tool::default(), Point3::new(-half, 0.0, -5.0));
        tp.push(Move::arc_xy(
            Point3::new(half, 0.0, -5.0),
            Point3::new(0.0, h, -5.0),
            true,
            20.0,
        ));
        let s = tp.moves[0].sagitta_from(tp.start).unwrap();
        (tp, s)
    };
    let (flat, s) = one(1_423_812.1);
    assert!((s - 4.66e-4).abs() < 1e-6, "{s}");
    let bent_radius = chord * chord / (8.0 * 1e-3);
    let (bent, s_bent) = one(bent_radius);
    assert!((s_bent - 1e-3).abs() < 1e-6, "{s_bent}");
    for (tp, decimals, line) in [(&flat, 3, true), (&flat, 4, false), (&bent, 3, false)] {
        let o = WriterOptions::default().with_decimals(Some(decimals));
        let (text, summary) = write_to_string(tp, &o).unwrap();
        assert_eq!(summary.arcs_as_lines, usize::from(line), "{text}");
        let last = text.lines().rev().find(|l| l.contains('X')).unwrap();
        assert_eq!(
            last.starts_with("G1 ") || last.starts_with("X"),
            line,
            "{text}"
        );
        // Read back, the move ends where it should.
        let (back, _) = read_str(&text, ReaderOptions::default()).unwrap();
        let end = back.moves.last().unwrap().to;
        assert!(end.distance(tp.moves[0].to) < 1e-3, "{end:?}");
    }
}
