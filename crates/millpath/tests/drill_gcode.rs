//! Drilling and boring programs in every dialect: the canned cycles the writer writes
//! (G81/G82/G83/G73 on LinuxCNC and Fanuc, CYCLE81/82/83 on Sinumerik, the moves on Grbl)
//! read back by the reader to the toolpath's moves; LinuxCNC's own `rs274` reads the
//! LinuxCNC programs to the same moves as our reader; the holes verifier passes the moves
//! read back and catches a program that misses.

mod gcode_common;
mod rs274_common;

use gcode_common::move_difference;
use millpath::gcode::{
    Dialect, Reader, ReaderOptions, Units, WriterOptions, read_str, write_to_string,
};
use millpath::geom::{Hole, Point};
use millpath::stock::{HoleProblem, verify_holes};
use millpath::strategy::drill::{DrillCycle, HoleOptions, HoleResult, plan_holes};
use millpath::toolpath::{CycleRetract, Move, Tool, Toolpath};
use rs274_common::canon::{canon_moves, compare};
use rs274_common::rs274;

fn holes() -> Vec<(usize, Hole)> {
    [
        (12.0, 8.0, 6.0),
        (40.0, 10.0, 6.0),
        (25.0, 30.0, 6.0),
        (70.0, 20.0, 10.0),
        (60.0, 50.0, 20.0),
        (-15.0, 35.0, 6.005),
    ]
    .iter()
    .enumerate()
    .map(|(i, &(x, y, d))| (i + 1, Hole::new(Point::new(x, y), d)))
    .collect()
}

fn cycles() -> [DrillCycle; 4] {
    [
        DrillCycle::Drill,
        DrillCycle::Dwell { seconds: 0.5 },
        DrillCycle::Peck { step: 2.0 },
        DrillCycle::ChipBreak { step: 1.5 },
    ]
}

fn plan(cycle: DrillCycle, retract: CycleRetract) -> HoleResult {
    let opts = HoleOptions::default()
        .with_depth(8.0)
        .with_cycle(cycle)
        .with_retract(retract);
    plan_holes(&holes(), &Tool::flat(6.0).unwrap(), &opts).unwrap()
}

/// The moves the writer writes: a rapid to the start first when it wrote one (a cycle's
/// start must be known).
fn expected(tp: &Toolpath, start_rapid: bool) -> Vec<Move> {
    let mut out = Vec::new();
    if start_rapid {
        out.push(Move::rapid(tp.start));
    }
    out.extend_from_slice(&tp.moves);
    out
}

fn segments(tp: &Toolpath) -> Vec<(millpath::Point3, Move)> {
    tp.segments().map(|(f, m)| (f, *m)).collect()
}

#[test]
fn every_dialect_reads_the_cycles_back_as_the_toolpath_moves() {
    let mut checked = 0;
    for cycle in cycles() {
        for retract in [CycleRetract::Initial, CycleRetract::R] {
            let r = plan(cycle, retract);
            let tp = &r.toolpath;
            assert_eq!(tp.cycles.len(), 4, "four holes of the tool's size");
            for d in Dialect::ALL {
                for (units, decimals, bound) in [
                    (Units::Mm, Some(10), 1e-9),
                    (Units::Inch, Some(11), 1e-9),
                    (Units::Mm, None, 0.005),
                    (Units::Inch, None, 0.005),
                ] {
                    let opts = WriterOptions::default()
                        .with_dialect(d)
                        .with_units(units)
                        .with_decimals(decimals);
                    let (text, summary) = write_to_string(tp, &opts).unwrap();
                    let written_as_cycles = match (d, cycle) {
                        (Dialect::Grbl, _) => 0,
                        (Dialect::Sinumerik, DrillCycle::ChipBreak { .. }) => 0,
                        _ => 4,
                    };
                    assert_eq!(summary.cycles, written_as_cycles, "{d} {cycle:?}\n{text}");
                    let word = match (d, cycle) {
                        (Dialect::Grbl, _) | (Dialect::Sinumerik, DrillCycle::ChipBreak { .. }) => {
                            "G1"
                        }
                        (Dialect::Sinumerik, DrillCycle::Drill) => "CYCLE81(",
                        (Dialect::Sinumerik, DrillCycle::Dwell { .. }) => "CYCLE82(",
                        (Dialect::Sinumerik, _) => "CYCLE83(",
                        (_, DrillCycle::Drill) => "G81 ",
                        (_, DrillCycle::Dwell { .. }) => "G82 ",
                        (_, DrillCycle::Peck { .. }) => "G83 ",
                        (_, DrillCycle::ChipBreak { .. }) => "G73 ",
                    };
                    assert!(text.contains(word), "{d} {cycle:?}: no {word}\n{text}");
                    let ropts = ReaderOptions::default()
                        .with_dialect(d)
                        .with_start(tp.start);
                    let (read, warnings) =
                        read_str(&text, ropts).unwrap_or_else(|e| panic!("{d}: {e}\n{text}"));
                    assert!(warnings.is_empty(), "{warnings:?}");
                    assert_eq!(summary.start_rapid, written_as_cycles > 0);
                    let want = expected(tp, summary.start_rapid);
                    assert_eq!(
                        want.len(),
                        read.moves.len(),
                        "{d} {units} {cycle:?} {retract:?}: move count\n{text}"
                    );
                    for (i, (a, b)) in want.iter().zip(&read.moves).enumerate() {
                        let diff = move_difference(a, b);
                        assert!(
                            diff <= bound,
                            "{d} {units} {cycle:?} {retract:?} move {i}: {a:?} read as {b:?}\n{text}"
                        );
                    }
                    // The verifier on the moves read back: the six holes, to 0.01 mm.
                    let cut: Vec<Hole> = r.holes.iter().map(|p| p.hole).collect();
                    let v = verify_holes(&cut, &segments(&read), &tp.tool, 0.0, -8.0, 0.01);
                    assert!(v.ok(), "{d} {units} {cycle:?}: {:?}\n{text}", v.problems);
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 4 * 2 * 4 * 4);
}

#[test]
fn rs274_reads_the_linuxcnc_programs_to_our_moves() {
    for cycle in cycles() {
        for retract in [CycleRetract::Initial, CycleRetract::R] {
            for units in [Units::Mm, Units::Inch] {
                let r = plan(cycle, retract);
                let opts = WriterOptions::default().with_units(units);
                let (text, _) = write_to_string(&r.toolpath, &opts).unwrap();
                rs274(&text).unwrap_or_else(|e| panic!("{cycle:?}: {e}\n{text}"));
                // Compared without the tool change: rs274's own tool table has lengths.
                let (text, _) =
                    write_to_string(&r.toolpath, &opts.with_tool_change(false)).unwrap();
                let canon = rs274(&text).unwrap_or_else(|e| panic!("{cycle:?}: {e}\n{text}"));
                let theirs = canon_moves(&canon).unwrap();
                let ours: Vec<_> = Reader::new(text.as_bytes(), ReaderOptions::default())
                    .collect::<Result<_, _>>()
                    .unwrap();
                if let Some(diff) = compare(&ours, &theirs, millpath::Point3::ORIGIN) {
                    panic!("{cycle:?} {retract:?} {units}: {diff}\n{text}\n{canon}");
                }
            }
        }
    }
}

#[test]
fn the_verifier_catches_a_hole_drilled_off_its_centre_or_not_at_all() {
    let r = plan(DrillCycle::Drill, CycleRetract::Initial);
    let (text, _) = write_to_string(&r.toolpath, &WriterOptions::default()).unwrap();
    let (read, _) = read_str(&text, ReaderOptions::default()).unwrap();
    let mut cut: Vec<Hole> = r.holes.iter().map(|p| p.hole).collect();
    let tool = r.toolpath.tool;
    assert!(verify_holes(&cut, &segments(&read), &tool, 0.0, -8.0, 0.01).ok());
    // A hole drawn 0.02 mm from where it was drilled.
    cut[0].center.x += 0.02;
    let v = verify_holes(&cut, &segments(&read), &tool, 0.0, -8.0, 0.01);
    assert!(
        v.problems
            .iter()
            .any(|p| matches!(p, HoleProblem::OffSize { .. })),
        "{:?}",
        v.problems
    );
    // A hole the program never reaches.
    cut[0].center.x -= 0.02;
    cut.push(Hole::new(Point::new(100.0, 100.0), 6.0));
    let v = verify_holes(&cut, &segments(&read), &tool, 0.0, -8.0, 0.01);
    assert!(
        matches!(v.problems[..], [HoleProblem::NotCut { .. }]),
        "{:?}",
        v.problems
    );
    // Deeper than the holes' bottom.
    let v = verify_holes(&cut[..6], &segments(&read), &tool, 0.0, -7.0, 0.01);
    assert!(
        v.problems
            .iter()
            .any(|p| matches!(p, HoleProblem::TooDeep { .. }))
    );
}
