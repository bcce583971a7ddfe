//! The G-code writer: dialect details, number formatting, modal output, errors.

mod gcode_common;

use gcode_common::varied_toolpath;
use millpath::Error;
use millpath::gcode::{Dialect, Units, WriterOptions, write_to_string};
use millpath::geom::Point3;
use millpath::toolpath::{Corner, Move, Tool, Toolpath};

fn opts(dialect: Dialect) -> WriterOptions {
    WriterOptions {
        dialect,
        path_tolerance: Some(0.01),
        program_name: Some("demo (part)".into()),
        ..WriterOptions::default()
    }
}

fn write(d: Dialect, units: Units) -> String {
    let o = WriterOptions { units, ..opts(d) };
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

#[test]
fn line_numbers_count_up_and_skip_percent_lines() {
    let o = WriterOptions {
        line_numbers: true,
        ..opts(Dialect::Fanuc)
    };
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
    let o = WriterOptions {
        work_offset: 60,
        ..WriterOptions::default()
    };
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
