//! LinuxCNC's own interpreter, `rs274` (Debian package linuxcnc-uspace), as an independent
//! verifier: the writer's LinuxCNC output must pass it, and the reader's arc-radius rule must
//! agree with it.
//!
//! `rs274 -g FILE` prints canonical commands on stdout and, on an error, the message on
//! stderr, and exits with status 1 (0 on success; checked by feeding it bad files below).
//! When `rs274` is missing these tests FAIL (CI installs it): install `linuxcnc-uspace`.

mod gcode_common;
mod rs274_common;

use gcode_common::varied_toolpath;
use millpath::gcode::{Dialect, ReaderOptions, Units, WriterOptions, read_str, write_to_string};
use millpath::geom::Point3;
use millpath::toolpath::{Corner, Move, Tool, Toolpath};
use rs274_common::rs274;

#[test]
fn rs274_reports_errors_so_this_test_can_fail() {
    assert!(rs274("G21 G90\nG1 X10 F100\nQ5\nM2\n").is_err());
    assert!(
        rs274("G21 G90\nG1 X10\nM2\n").is_err(),
        "feed move without F"
    );
    assert!(rs274("G21 G90\nG1 X10 F100\nM2\n").is_ok());
}

#[test]
fn linuxcnc_output_passes_rs274_in_mm_and_inch() {
    for units in [Units::Mm, Units::Inch] {
        for (line_numbers, tol) in [(false, None), (true, Some(0.01))] {
            let mut opts = WriterOptions::default()
                .with_dialect(Dialect::LinuxCnc)
                .with_units(units)
                .with_line_numbers(line_numbers)
                .with_program_name(Some("rs274 check".into()));
            opts.path_tolerance = tol;
            let (text, summary) = write_to_string(&varied_toolpath(), &opts).unwrap();
            let canon = rs274(&text).unwrap_or_else(|e| panic!("rs274 refused:\n{e}\n{text}"));
            // Every motion block reached the canonical machine.
            let motions = canon
                .lines()
                .filter(|l| {
                    l.contains("STRAIGHT_") || l.contains("ARC_FEED") || l.contains("DWELL(")
                })
                .count();
            assert_eq!(motions, summary.blocks, "{canon}");
            assert!(canon.contains("PROGRAM_END"), "{canon}");
        }
    }
}

#[test]
fn many_short_arcs_and_lines_pass_rs274_at_default_decimals() {
    // A 2 mm circle of 200 arcs and lines: small radii stress the rounding of I/J.
    let mut tp = Toolpath::new(Tool::default(), Point3::new(1.0, 0.0, 0.0));
    let n = 200;
    for k in 1..=n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        let to = Point3::new(a.cos(), a.sin(), -0.001 * f64::from(k));
        let m = if k % 2 == 0 {
            Move::arc_xy(to, Point3::ORIGIN, true, 10.0)
        } else {
            Move::line(to, 10.0).with_corner(Corner::Blend(0.005))
        };
        tp.push(m);
    }
    for units in [Units::Mm, Units::Inch] {
        let opts = WriterOptions::default().with_units(units);
        let (text, _) = write_to_string(&tp, &opts).unwrap();
        rs274(&text).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn reader_and_rs274_agree_on_the_arc_radius_rule() {
    // Radii and end-radius errors around both thresholds, mm and inch.
    let cases = [
        (Units::Mm, 10.0, 0.027),
        (Units::Mm, 10.0, 0.03),
        (Units::Mm, 1000.0, 0.5),
        (Units::Mm, 1000.0, 1.5),
        (Units::Mm, 10_000.0, 2.7),
        (Units::Mm, 10_000.0, 2.95),
        (Units::Inch, 1.0, 0.0027),
        (Units::Inch, 1.0, 0.0030),
        (Units::Inch, 0.05, 0.0001),
    ];
    for (units, r, err) in cases {
        let g = if units == Units::Mm { "G21" } else { "G20" };
        let text = format!(
            "{g} G90 G17\nG0 X{r} Y0\nG2 X-{} Y0 I-{r} J0 F100\nM2\n",
            r + err
        );
        let ours = read_str(&text, ReaderOptions::default()).is_ok();
        let theirs = rs274(&text).is_ok();
        assert_eq!(
            ours, theirs,
            "r = {r} {units}, error {err}: ours {ours}, rs274 {theirs}"
        );
    }
}

#[test]
fn reader_agrees_with_rs274_on_bad_programs() {
    // (Rotary axes A/B/C are a deliberate difference: rs274 has them, the 3-axis reader
    // refuses them.)
    for text in [
        "G21 G90\nG1 X10\nM2\n",
        "G21 G90\nG0 X0 Y0\nG2 X40 Y0 R10 F100\nM2\n",
        "G21 G90\nG0 X0 Y0\nG3 X20 Y0 R10 F100\nM2\n",
        "G21 G90\nG0 X1 Y0\nG3 X1 Y0 I-1 J0 F100\nG1 X2\nM2\n",
    ] {
        let ours = read_str(text, ReaderOptions::default());
        let theirs = rs274(text);
        assert_eq!(
            ours.is_ok(),
            theirs.is_ok(),
            "{text}\nours: {ours:?}\nrs274: {theirs:?}"
        );
    }
}

/// One motion of rs274's canonical output, in program units: (kind, end, centre, rotation).
#[derive(Debug)]
enum Canon {
    Straight(bool, Point3),
    Arc(Point3, (f64, f64), i32),
    Dwell(f64),
}

fn numbers(line: &str) -> Vec<f64> {
    let inside = line
        .split_once('(')
        .and_then(|(_, r)| r.rsplit_once(')'))
        .map_or("", |(a, _)| a);
    inside
        .split(',')
        .filter_map(|t| t.trim().parse().ok())
        .collect()
}

/// Parses rs274's canonical commands (its own interpretation, independent of our reader).
fn canon_motions(canon: &str) -> Vec<Canon> {
    use millpath::toolpath::Plane;
    let mut plane = Plane::Xy;
    let mut out = Vec::new();
    for l in canon.lines() {
        let n = numbers(l);
        if l.contains("SELECT_PLANE(CANON_PLANE_XZ)") {
            plane = Plane::Zx;
        } else if l.contains("SELECT_PLANE(CANON_PLANE_YZ)") {
            plane = Plane::Yz;
        } else if l.contains("SELECT_PLANE(CANON_PLANE_XY)") {
            plane = Plane::Xy;
        } else if l.contains("STRAIGHT_TRAVERSE(") || l.contains("STRAIGHT_FEED(") {
            out.push(Canon::Straight(
                l.contains("TRAVERSE"),
                Point3::new(n[0], n[1], n[2]),
            ));
        } else if l.contains("ARC_FEED(") {
            // ARC_FEED(first_end, second_end, first_centre, second_centre, rotation, axis_end, ...)
            let end = Point3::ORIGIN + plane.join(n[0], n[1], n[5]);
            out.push(Canon::Arc(end, (n[2], n[3]), n[4] as i32));
        } else if l.contains("DWELL(") {
            out.push(Canon::Dwell(n[0]));
        }
    }
    out
}

#[test]
fn rs274_interprets_the_program_as_the_toolpath() {
    use millpath::toolpath::MoveKind;
    let tp = varied_toolpath();
    for units in [Units::Mm, Units::Inch] {
        let opts = WriterOptions::default()
            .with_units(units)
            .with_decimals(Some(6));
        let (text, _) = write_to_string(&tp, &opts).unwrap();
        let canon = rs274(&text).unwrap_or_else(|e| panic!("{e}"));
        let got = canon_motions(&canon);
        assert_eq!(got.len(), tp.moves.len(), "{canon}");
        // rs274 prints 4 decimals of the program unit.
        let k = units.mm_per_unit();
        let tol = 0.6e-4 * k;
        for (i, (m, c)) in tp.moves.iter().zip(&got).enumerate() {
            let close = |p: Point3| {
                (p.x * k - m.to.x)
                    .abs()
                    .max((p.y * k - m.to.y).abs())
                    .max((p.z * k - m.to.z).abs())
                    <= tol
            };
            match (m.kind, c) {
                (MoveKind::Rapid, Canon::Straight(true, p))
                | (MoveKind::Line, Canon::Straight(false, p)) => {
                    assert!(close(*p), "move {i}: {m:?} vs {c:?}");
                }
                (
                    MoveKind::Arc {
                        center,
                        plane,
                        ccw,
                        turns,
                    },
                    Canon::Arc(p, (cu, cv), rot),
                ) => {
                    assert!(close(*p), "move {i}: {m:?} vs {c:?}");
                    let (u, v, _) = plane.split(center - Point3::ORIGIN);
                    assert!(
                        (cu * k - u).abs() <= tol && (cv * k - v).abs() <= tol,
                        "move {i}: centre {m:?} vs {c:?}"
                    );
                    let want = (turns as i32 + 1) * if ccw { 1 } else { -1 };
                    assert_eq!(*rot, want, "move {i}: rotation");
                }
                (MoveKind::Dwell { seconds }, Canon::Dwell(s)) => {
                    assert!((seconds - s).abs() < 1e-4);
                }
                _ => panic!("move {i}: {m:?} interpreted by rs274 as {c:?}"),
            }
        }
    }
}

mod random {
    use super::*;
    use gcode_common::{build_random, random_step};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 12, rng_seed: proptest::test_runner::RngSeed::Fixed(3), ..ProptestConfig::default() })]

        /// Random toolpaths (arcs in all planes, helices, multi-turn circles) written at the
        /// default decimals pass rs274, in mm and inch.
        #[test]
        fn random_toolpaths_pass_rs274(steps in proptest::collection::vec(random_step(), 1..20)) {
            let tp = build_random(&steps);
            for units in [Units::Mm, Units::Inch] {
                let opts = WriterOptions::default().with_units(units);
                let (text, _) = write_to_string(&tp, &opts).unwrap();
                if let Err(e) = rs274(&text) {
                    prop_assert!(false, "rs274 refused: {}\n{}", e, text);
                }
            }
        }
    }
}
