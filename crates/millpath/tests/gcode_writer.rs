//! The G-code writer: dialect details, number formatting, modal output, errors.

mod gcode_common;

use gcode_common::varied_toolpath;
use millpath::Error;
use millpath::gcode::{Dialect, Units, WriterOptions, write_to_string};
use millpath::geom::Point3;
use millpath::toolpath::{Corner, Move, Tool, Toolpath};

fn opts(dialect: Dialect) -> WriterOptions {
    // The tolerance alone (`with_path_tolerance` would also fix the decimals, before the
    // units are chosen).
    let mut o = WriterOptions::default()
        .with_dialect(dialect)
        .with_program_name(Some("demo (part)".into()));
    o.path_tolerance = Some(0.01);
    o
}

fn write(d: Dialect, units: Units) -> String {
    let o = opts(d).with_units(units);
    write_to_string(&varied_toolpath(), &o).unwrap().0
}

#[test]
fn every_dialect_has_its_framing_comments_and_end() {
    let l = write(Dialect::LinuxCnc, Units::Mm);
    assert!(l.starts_with("(demo  part )\n"), "{l}");
    assert!(l.contains("G64 P0.01\n") && l.contains("T1 M6\n") && l.ends_with("M2\n"));
    assert!(l.contains("G4 P0.75\n") && l.contains(" P2") && l.contains("G61.1\n"));

    let f = write(Dialect::Fanuc, Units::Mm);
    let lines: Vec<&str> = f.lines().collect();
    assert_eq!(lines.first(), Some(&"%"));
    assert_eq!(lines.get(1), Some(&"O0001 (DEMO  PART )"));
    assert_eq!(lines.last(), Some(&"%"));
    assert!(f.contains("G05.1 Q1\n") && f.contains("G04 X0.75\n") && f.contains("M30\n%\n"));
    assert!(f.contains("G0 G43 H1 X10. Y0. Z50.\n"), "{f}");
    assert!(!f.contains(" P2"), "fanuc has no turn count: {f}");

    let s = write(Dialect::Sinumerik, Units::Mm);
    assert!(s.starts_with("; demo (part)\n"), "{s}");
    assert!(s.contains("G17 G710 G90") && s.contains("CYCLE832(0.01,_FINISH,1)\n"));
    assert!(s.contains("G4 F0.75\n") && s.contains("TURN=1") && s.contains("G60\n"));
    assert!(s.ends_with("M30\n"));

    let g = write(Dialect::Grbl, Units::Mm);
    assert!(
        !g.contains("M6") && g.contains("; tool change: load T1"),
        "{g}"
    );
    assert!(!g.contains("G64") && !g.contains("G61") && g.contains("G4 P0.75\n"));
    assert!(g.ends_with("M2\n"));
}

#[test]
fn numbers_are_trimmed_and_never_negative_zero_or_nan() {
    for d in Dialect::ALL {
        for units in [Units::Mm, Units::Inch] {
            let t = write(d, units);
            let code = t.lines().filter(|l| !l.contains('(') && !l.contains(';'));
            for word in code.flat_map(str::split_whitespace) {
                let body = word.get(1..).unwrap_or("");
                assert!(
                    !body.starts_with("-0") || body.starts_with("-0.") && body != "-0.",
                    "{d} {word}"
                );
                assert!(!word.contains("NaN") && !word.contains("inf"), "{d} {word}");
                if body.contains('.')
                    && body
                        .chars()
                        .all(|c| c.is_ascii_digit() || c == '.' || c == '-')
                {
                    assert!(!body.ends_with('0'), "trailing zero in {word} ({d})");
                }
            }
        }
    }
}

#[test]
fn inches_convert_coordinates_and_feeds() {
    let t = write(Dialect::LinuxCnc, Units::Inch);
    assert!(t.contains("G20"), "{t}");
    // 5 mm/s = 300 mm/min = 11.811 in/min; Z -1 mm = -0.0394 in.
    assert!(t.contains("G1 Z-0.0394 F11.811\n"), "{t}");
}

#[test]
fn corner_modes_are_written_only_on_change() {
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    for k in 0..6 {
        let c = if k < 3 {
            Corner::ExactStop
        } else {
            Corner::Blend(0.05)
        };
        tp.push(Move::line(Point3::new(f64::from(k), 0.0, 0.0), 10.0).with_corner(c));
    }
    let o = WriterOptions::default();
    let (t, s) = write_to_string(&tp, &o).unwrap();
    assert_eq!(t.matches("G61.1").count(), 1, "{t}");
    assert_eq!(t.matches("G64 P0.05").count(), 1, "{t}");
    assert_eq!(t.matches("F600").count(), 1, "feed is modal: {t}");
    assert_eq!(s.blocks, 6);
}

/// A tolerance that rounds to 0 is exact stop in every dialect, never `G64 P0` (which
/// LinuxCNC reads as blending without a limit), and reads back as a stop.
#[test]
fn a_zero_path_tolerance_is_exact_stop_not_g64_p0() {
    use millpath::gcode::{ReaderOptions, read_str};
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    tp.push(Move::line(Point3::new(1.0, 0.0, 0.0), 10.0));
    tp.push(Move::line(Point3::new(2.0, 0.0, 0.0), 10.0).with_corner(Corner::Blend(1e-9)));
    tp.push(Move::line(Point3::new(3.0, 0.0, 0.0), 10.0).with_corner(Corner::Blend(0.02)));
    tp.push(Move::line(Point3::new(4.0, 0.0, 0.0), 10.0));
    for (d, stop) in [
        (Dialect::LinuxCnc, "G61.1"),
        (Dialect::Sinumerik, "G60"),
        (Dialect::Fanuc, "G61"),
    ] {
        for t in [0.0, 1e-9] {
            // The tolerance alone: `with_path_tolerance` would add decimals enough to hold 1e-9.
            let mut o = WriterOptions::default().with_dialect(d);
            o.path_tolerance = Some(t);
            let (text, _) = write_to_string(&tp, &o).unwrap();
            assert!(!text.contains("G64 P0\n"), "{d}: {text}");
            assert!(
                !text.contains("G05.1"),
                "{d}: no AI contour control at 0: {text}"
            );
            let header: Vec<&str> = text.lines().take_while(|l| !l.contains("G0")).collect();
            assert!(header.contains(&stop), "{d}: {stop} in the header: {text}");
            let (read, _) = read_str(&text, ReaderOptions::default().with_dialect(d)).unwrap();
            let corners: Vec<Corner> = read.moves.iter().map(|m| m.corner).collect();
            // Moves 0, 1 and 3 stop; move 2 blends (LinuxCNC, Sinumerik) or runs in G64.
            for k in [0, 1, 3] {
                assert_eq!(corners[k], Corner::ExactStop, "{d} move {k}: {text}");
            }
            assert_ne!(corners[2], Corner::ExactStop, "{d}: {text}");
        }
    }
    let bad = WriterOptions::default().with_path_tolerance(-0.01);
    assert!(write_to_string(&tp, &bad).is_err());
}

#[test]
fn line_numbers_count_up_and_skip_percent_lines() {
    let o = opts(Dialect::Fanuc).with_line_numbers(true);
    let (t, s) = write_to_string(&varied_toolpath(), &o).unwrap();
    let numbered: Vec<u64> = t
        .lines()
        .filter_map(|l| l.strip_prefix('N'))
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(numbered.len() + 3, s.lines, "all but %, O and %");
    assert!(numbered.windows(2).all(|w| w[1] == w[0] + 10));
}

#[test]
fn non_finite_coordinates_are_refused_with_the_move_index() {
    for bad in [f64::NAN, f64::INFINITY] {
        let mut tp = varied_toolpath();
        tp.moves[4].to.y = bad;
        let e = write_to_string(&tp, &WriterOptions::default()).unwrap_err();
        assert!(matches!(e, Error::Input(_)));
        assert!(e.to_string().contains("move 4"), "{e}");
    }
    let mut tp = varied_toolpath();
    tp.moves[2].feed = 0.0;
    let e = write_to_string(&tp, &WriterOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("feed") && e.contains("move 2"), "{e}");
    let o = WriterOptions::default().with_work_offset(60);
    assert!(write_to_string(&varied_toolpath(), &o).is_err());
}

#[test]
fn a_failing_output_is_an_error_not_a_panic() {
    struct Full;
    impl std::io::Write for Full {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::Error::other("disk full"))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let e =
        millpath::gcode::write_program(&varied_toolpath(), &WriterOptions::default(), &mut Full)
            .unwrap_err();
    assert!(e.to_string().contains("disk full"), "{e}");
}

#[test]
fn arcs_too_small_for_the_decimals_become_lines_and_still_read_back() {
    use millpath::gcode::{ReaderOptions, read_str};
    let start = Point3::new(5.0, 0.0, 0.0);
    let mut tp = Toolpath::new(Tool::default(), start);
    // Radius below LinuxCNC's zero-radius limit.
    tp.push(Move::arc_xy(
        Point3::new(5.0, 0.0008, 0.0),
        Point3::new(5.0, 0.0004, 0.0),
        true,
        5.0,
    ));
    // A 0.0001 rad sweep of radius 1 whose end rounds onto its start at 3 decimals: as an
    // arc it would read back as a full circle.
    let (a, c) = (0.0001f64, Point3::new(4.0, 0.0008, 0.0));
    tp.push(Move::arc_xy(
        Point3::new(4.0 + a.cos(), 0.0008 + a.sin(), 0.0),
        c,
        true,
        5.0,
    ));
    let (text, s) = write_to_string(&tp, &WriterOptions::default()).unwrap();
    assert_eq!(s.arcs_as_lines, 2, "{text}");
    let ropts = ReaderOptions::default().with_start(start);
    let (read, _) = read_str(&text, ropts).unwrap();
    let len: f64 = read.segments().map(|(f, m)| m.length_from(f)).sum();
    assert!(len < 0.01, "no full circle sneaked in: {len} mm\n{text}");
}

#[test]
fn near_full_circles_stay_near_full_after_rounding() {
    use millpath::gcode::{ReaderOptions, read_str};
    // Sweeps a hair short of a full turn, both directions, at many start angles: whatever
    // the rounding does to the end, the program read back still goes (almost) all the way round.
    for k in 0..40 {
        for ccw in [true, false] {
            let a0 = f64::from(k) * 0.157;
            let r = 10.0;
            let start = Point3::new(r * a0.cos(), r * a0.sin(), 0.0);
            let short = 3e-5;
            let a1 = if ccw { a0 - short } else { a0 + short };
            let end = Point3::new(r * a1.cos(), r * a1.sin(), 0.0);
            let mut tp = Toolpath::new(Tool::default(), start);
            tp.push(Move::arc_xy(end, Point3::ORIGIN, ccw, 5.0));
            let want = tp.cut_length();
            let (text, _) = write_to_string(&tp, &WriterOptions::default()).unwrap();
            let ropts = ReaderOptions::default().with_start(start);
            let (read, _) = read_str(&text, ropts).unwrap();
            let got = read.cut_length();
            assert!(
                (got - want).abs() < 0.01,
                "k {k} ccw {ccw}: {got} vs {want}\n{text}"
            );
        }
    }
}

#[test]
fn absurd_coordinates_are_refused() {
    let mut tp = varied_toolpath();
    tp.moves[3].to.x = 1e300;
    let e = write_to_string(&tp, &WriterOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("move 3"), "{e}");
}

#[test]
fn with_tolerance_raises_the_decimals_only_when_needed() {
    use millpath::gcode::{required_decimals, rounding_error_mm};
    let o = WriterOptions::default().with_tolerance(0.1);
    assert_eq!(
        o.effective_decimals(),
        3,
        "the default already holds 0.1 mm"
    );
    for tol in [1e-2, 1e-3, 1e-4, 4e-5] {
        for units in [Units::Mm, Units::Inch] {
            let o = WriterOptions::default()
                .with_units(units)
                .with_tolerance(tol);
            let d = o.effective_decimals();
            assert!(d >= required_decimals(tol, units));
            assert!(
                rounding_error_mm(d, units) <= 0.1 * tol,
                "{tol} {units}: {d}"
            );
        }
    }
}

#[test]
fn comments_off_means_no_comments_in_any_dialect() {
    for d in Dialect::ALL {
        let o = opts(d).with_comments(false);
        let (t, _) = write_to_string(&varied_toolpath(), &o).unwrap();
        let code = t.replace("CYCLE832(", "");
        assert!(!code.contains('(') && !code.contains(';'), "{d}:\n{t}");
    }
}
