//! Drilling and boring programs in every dialect: the canned cycles the writer writes
//! (G81/G82/G83/G73 on LinuxCNC and Fanuc, CYCLE81/82/83 on Sinumerik, the moves on Grbl)
//! read back by the reader to the toolpath's moves; LinuxCNC's own `rs274` reads the
//! LinuxCNC programs to the same moves as our reader, and the controller checker of
//! `dialect_check` (written from the controllers' documents) passes the others; the holes verifier passes the moves
//! read back and catches a program that misses.

mod dialect_check;
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
                    if d != Dialect::LinuxCnc && decimals.is_none() {
                        dialect_check::check(&text, d).unwrap_or_else(|e| panic!("{e}\n{text}"));
                    }
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
fn the_controller_checker_refuses_what_the_controllers_refuse() {
    dialect_check::self_test();
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

/// The feed depths, rapid levels and dwells of a program read back: `f-5`, `r2`, `d0.5`.
fn steps(text: &str, d: Dialect) -> Vec<String> {
    let (tp, _) = read_str(text, ReaderOptions::default().with_dialect(d))
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    tp.moves
        .iter()
        .map(|m| match m.kind {
            millpath::MoveKind::Line => format!("f{}", (m.to.z * 1e6).round() / 1e6),
            millpath::MoveKind::Rapid => format!("r{}", (m.to.z * 1e6).round() / 1e6),
            millpath::MoveKind::Dwell { seconds } => format!("d{seconds}"),
            millpath::MoveKind::Arc { .. } => "a".into(),
        })
        .collect()
}

#[test]
fn sinumerik_cycles_read_as_the_840d_documents_them() {
    let head = "G17 G710 G90 G94\nG0 X10 Y5 Z10\nF120\n";
    // CYCLE81 with the depth relative to RFP: R = RFP + SDIS = 2, bottom −5.
    assert_eq!(
        steps(
            &format!("{head}CYCLE81(10,0,2,,5)\nM30\n"),
            Dialect::Sinumerik
        ),
        ["r10", "r2", "f-5", "r10"]
    );
    // CYCLE82: a dwell at the bottom.
    assert_eq!(
        steps(
            &format!("{head}CYCLE82(10,0,2,-5,,0.5)\nM30\n"),
            Dialect::Sinumerik
        ),
        ["r10", "r2", "f-5", "d0.5", "r10"]
    );
    // CYCLE83 chip removal with degression 2 from a first stroke of 7 (R 2 to FDEP −5):
    // strokes 7, 5, 3, 2, 2, 2, then to DP; out to R and back down to 0.6 mm above the
    // depth reached (the 840D's own anticipation distance up to a hole 30 mm deep).
    let s = steps(
        &format!("{head}CYCLE83(10,0,2,-20,,-5,,2,0,0,1,1)\nM30\n"),
        Dialect::Sinumerik,
    );
    let feeds: Vec<&str> = s
        .iter()
        .filter(|x| x.starts_with('f'))
        .map(|x| x.as_str())
        .collect();
    assert_eq!(
        feeds,
        ["f-5", "f-10", "f-13", "f-15", "f-17", "f-19", "f-20"]
    );
    assert_eq!(&s[..7], ["r10", "r2", "f-5", "r2", "r-4.4", "f-10", "r2"]);
    // Chip breaking (VARI 0): a feed back by _VRT, no degression (every stroke the first).
    assert_eq!(
        steps(
            &format!("{head}CYCLE83(10,0,2,-6,,-2,,0,0,0,1,0,,,0.5)\nM30\n"),
            Dialect::Sinumerik
        ),
        ["r10", "r2", "f-2", "f-1.5", "f-6", "r10"]
    );
    // Refused: a degression factor, a variable, RTP below R.
    for bad in [
        "CYCLE83(10,0,2,-20,,-5,,-0.5,0,0,1,1)",
        "CYCLE81(R1,0,2,-5)",
        "CYCLE81(1,0,2,-5)",
    ] {
        let text = format!("{head}{bad}\nM30\n");
        assert!(
            read_str(
                &text,
                ReaderOptions::default().with_dialect(Dialect::Sinumerik)
            )
            .is_err(),
            "{bad}"
        );
    }
}

#[test]
fn fanuc_cycles_take_g82_p_in_milliseconds() {
    let text = "%\nO0001\nG17 G21 G90 G94\nG0 X10. Y5. Z10.\n\
                G98 G82 X10. Y5. Z-5. R2. P500 F120.\nG99 G81 X20. Z-5. R2.\nG80\nM30\n%\n";
    assert_eq!(
        steps(text, Dialect::Fanuc),
        [
            "r10", "r10", "r2", "f-5", "d0.5", "r10", "r10", "r2", "f-5", "r2"
        ]
    );
}

/// Random hole sets (holes of the tool's diameter and up to 14 mm larger, apart), tools,
/// depths, cycles and retract modes: every plan, written in a random dialect and units and
/// read back, passes the holes verifier; all `CASES` cases must be planned and checked.
#[test]
fn random_hole_sets_read_back_pass_the_verifier() {
    use proptest::prelude::*;
    use proptest::test_runner::{RngSeed, TestRunner};
    const CASES: u32 = 48;
    let seed = std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .map_or(RngSeed::Fixed(3), RngSeed::Fixed);
    let config = ProptestConfig {
        cases: CASES,
        rng_seed: seed,
        failure_persistence: None,
        ..ProptestConfig::default()
    };
    let hole = (
        -80.0f64..80.0,
        -60.0f64..60.0,
        prop_oneof![Just(0.0), 0.0f64..14.0],
    );
    let case = (
        prop::collection::vec(hole, 1..7),
        1.0f64..8.0,
        0.5f64..12.0,
        0u8..4,
        any::<bool>(),
        0usize..4,
        any::<bool>(),
    );
    let cut = std::sync::atomic::AtomicUsize::new(0);
    let mut runner = TestRunner::new(config);
    let result = runner.run(&case, |(hs, tool_d, depth, kind, g99, dialect, inch)| {
        // Holes far enough apart not to overlap; a 0 extra diameter is the tool's own.
        let mut holes: Vec<(usize, Hole)> = Vec::new();
        for (x, y, extra) in hs {
            let h = Hole::new(Point::new(x, y), tool_d + extra);
            if holes
                .iter()
                .all(|(_, o)| o.center.distance(h.center) > o.radius() + h.radius() + 1.0)
            {
                holes.push((holes.len() + 1, h));
            }
        }
        let cycle = match kind {
            0 => DrillCycle::Drill,
            1 => DrillCycle::Dwell { seconds: 0.2 },
            2 => DrillCycle::Peck {
                step: 0.3 * depth + 0.2,
            },
            _ => DrillCycle::ChipBreak {
                step: 0.25 * depth + 0.2,
            },
        };
        let opts = HoleOptions::default()
            .with_depth(depth)
            .with_cycle(cycle)
            .with_retract(if g99 {
                CycleRetract::R
            } else {
                CycleRetract::Initial
            });
        let tool = Tool::flat(tool_d).unwrap();
        let r = plan_holes(&holes, &tool, &opts).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let d = Dialect::ALL[dialect];
        let units = if inch { Units::Inch } else { Units::Mm };
        let wopts = WriterOptions::default()
            .with_dialect(d)
            .with_units(units)
            .with_decimals(Some(if inch { 5 } else { 3 }));
        let (text, _) = write_to_string(&r.toolpath, &wopts).map_err(|e| {
            let segs = segments(&r.toolpath);
            let at = format!("{e}");
            let i: usize = at
                .split("move ")
                .nth(1)
                .and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next())
                .and_then(|t| t.parse().ok())
                .unwrap_or(0);
            TestCaseError::fail(format!(
                "{d} {units}: {e}: {:?} (tool {tool_d}, holes {holes:?})",
                segs.get(i)
            ))
        })?;
        let (read, _) = read_str(&text, ReaderOptions::default().with_dialect(d))
            .map_err(|e| TestCaseError::fail(format!("{d}: {e}")))?;
        let cut_holes: Vec<Hole> = r.holes.iter().map(|p| p.hole).collect();
        let v = verify_holes(&cut_holes, &segments(&read), &tool, 0.0, -depth, 0.01);
        prop_assert!(v.ok(), "{d} {units}: {:?}", v.problems);
        prop_assert_eq!(v.holes.len(), holes.len());
        cut.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    assert_eq!(cut.into_inner(), CASES as usize);
}
