//! The G-code reader: modal behaviour, each dialect's forms, errors with line numbers,
//! streaming.

use millpath::Error;
use millpath::gcode::{Dialect, FeedMode, Reader, ReaderOptions, read_str};
use millpath::geom::{Point3, Vec3};
use millpath::toolpath::{Corner, MoveKind, Plane, Toolpath};
use std::io::{BufReader, Read};

fn read(text: &str) -> Toolpath {
    read_str(text, ReaderOptions::default())
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .0
}

fn read_as(d: Dialect, text: &str) -> Toolpath {
    let o = ReaderOptions::default().with_dialect(d);
    read_str(text, o)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .0
}

fn error(text: &str) -> String {
    let o = ReaderOptions::default().with_origin("part.ngc");
    match read_str(text, o) {
        Err(e @ Error::Input(_)) => e.to_string(),
        other => panic!("expected an input error for\n{text}\ngot {other:?}"),
    }
}

fn close(a: Point3, b: Point3) -> bool {
    a.distance(b) < 1e-9
}

#[test]
fn errors_name_the_file_line_and_word() {
    let e = error("G21 G90\nG1 X1 F100\nG1 X2 U5\n");
    assert!(e.contains("part.ngc:3") && e.contains("U5"), "{e}");
    let e = error("G21\nG1 X1\n");
    assert!(
        e.contains("part.ngc:2") && e.contains("feed"),
        "missing F: {e}"
    );
    let e = error("G21\nF0\nG1 X1\n");
    assert!(e.contains("part.ngc:3") && e.contains("feed"), "F0: {e}");
    let e = error("G21\nG1 X1 F-5\n");
    assert!(
        e.contains("part.ngc:2") && e.contains("F-5"),
        "negative F: {e}"
    );
    let e = error("G21 G90\nG0 X10 Y0\nG2 X-10.5 Y0 I-10 J0 F100\n");
    assert!(
        e.contains("part.ngc:3") && e.contains("radius"),
        "radius mismatch: {e}"
    );
    let e = error("G21\n\nG1 XNaN F100\n");
    assert!(e.contains("part.ngc:3") && e.contains("XNaN"), "NaN: {e}");
    let e = error("G1 X1 F1e5\n");
    assert!(
        e.contains("part.ngc:1") && e.contains("e5"),
        "exponent: {e}"
    );
    let e = error("G21\nG1 X1e300 F100\n");
    assert!(e.contains(":2"), "{e}");
    let e = error(&format!("G21\nG1 X1{} F100\n", "0".repeat(30)));
    assert!(e.contains(":2") && e.contains("magnitude"), "{e}");
    // Parameters are read (#1 is 0 until set); a named one must be set before it is read.
    let e = error("G21\nG1 X#<nope> F100\n");
    assert!(
        e.contains("part.ngc:2") && e.contains("#<nope>") && e.contains("not defined"),
        "{e}"
    );
    let e = error("G21\nG70 Z-5 F100\n");
    assert!(
        e.contains("part.ngc:2") && e.contains("G70"),
        "unsupported G: {e}"
    );
    let e = error("M98 P100\n");
    assert!(e.contains("M98"), "{e}");
    let e = error("G21\nX10\n");
    assert!(
        e.contains("part.ngc:2") && e.contains("motion"),
        "axis words without motion: {e}"
    );
    let e = error("G1 X1 X2 F100\n");
    assert!(e.contains("one X word"), "{e}");
    let e = error("G0 X1\nG3 X3 Y0 R0.5 F100\n");
    assert!(e.contains("radius") && e.contains(":2"), "{e}");
}

#[test]
fn lenient_skips_unsupported_words_with_warnings() {
    let text = "G21 G90\nG1 X1 F100 U5\nG70 Z1\nG1 X2\n";
    let o = ReaderOptions::default().with_lenient(true);
    let (tp, warnings) = read_str(text, o).unwrap();
    // Only the word is skipped: Z1 still moves in the modal G1.
    assert_eq!(tp.moves.len(), 3);
    assert!(close(tp.moves[1].to, Point3::new(1.0, 0.0, 1.0)));
    assert!(close(tp.moves[2].to, Point3::new(2.0, 0.0, 1.0)));
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert_eq!(warnings[0].line, 2);
    assert!(warnings[0].message.contains("U5"), "{warnings:?}");
    assert!(
        warnings[1].message.contains("G70") && warnings[1].line == 3,
        "{warnings:?}"
    );
    // Lenient does not excuse a real error.
    let o = ReaderOptions::default().with_lenient(true);
    assert!(read_str("G1 X1\n", o).is_err());
}

#[test]
fn units_distance_modes_and_feeds() {
    let tp = read("G20 G91\nG1 X1 Y1 F60\nX1\nG90 G21 G0 Z5\n");
    assert!(close(tp.moves[0].to, Point3::new(25.4, 25.4, 0.0)));
    assert!(close(tp.moves[1].to, Point3::new(50.8, 25.4, 0.0)));
    assert!(close(tp.moves[2].to, Point3::new(50.8, 25.4, 5.0)));
    assert!(
        (tp.moves[0].feed - 25.4).abs() < 1e-12,
        "60 in/min = 25.4 mm/s"
    );
    assert_eq!(tp.moves[2].kind, MoveKind::Rapid);
}

#[test]
fn inverse_time_feed_becomes_mm_per_s() {
    // 30 mm in 1/F = 0.5 min = 30 s → 1 mm/s.
    let tp = read("G21 G93\nG1 X30 F2\nG1 X60 F4\n");
    assert!((tp.moves[0].feed - 1.0).abs() < 1e-12);
    assert!((tp.moves[1].feed - 2.0).abs() < 1e-12);
    let e = error("G21 G93\nG1 X30 F2\nG1 X60\n");
    assert!(e.contains(":3") && e.contains("inverse"), "{e}");
    // Back to G94: F forgotten.
    let e = error("G21 G94 F100\nG93\nG94\nG1 X1\n");
    assert!(e.contains(":4"), "{e}");
    let r = Reader::new("G93\nG1 X1 F1\n".as_bytes(), ReaderOptions::default());
    let m = r.into_iter().next().unwrap().unwrap();
    assert_eq!(m.modal.feed_mode, FeedMode::InverseTime);
    assert_eq!(m.line, 2);
}

#[test]
fn arcs_in_r_form_absolute_centres_planes_and_turns() {
    let tp = read("G21 G90 G0 X10 Y0\nG3 X0 Y10 R10 F60\nG3 X10 Y0 R-10\n");
    let (r, s) = tp.moves[1].sweep_from(tp.moves[0].to).unwrap();
    assert!((r - 10.0).abs() < 1e-9 && (s - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    let (_, s) = tp.moves[2].sweep_from(tp.moves[1].to).unwrap();
    assert!((s - 1.5 * std::f64::consts::PI).abs() < 1e-9);
    // G90.1: absolute centre; full circle with 3 turns (P3) and a helix.
    let tp = read("G21 G90 G90.1 G0 X15 Y5\nG2 X15 Y5 Z-3 I5 J5 P3 F60\n");
    let MoveKind::Arc {
        center, turns, ccw, ..
    } = tp.moves[1].kind
    else {
        panic!()
    };
    assert!(close(center, Point3::new(5.0, 5.0, 0.0)) && turns == 2 && !ccw);
    let len = tp.moves[1].length_from(tp.moves[0].to);
    assert!((len - (3.0 * std::f64::consts::TAU * 10.0).hypot(3.0)).abs() < 1e-9);
    // G18: offsets I (X) and K (Z).
    let tp = read("G21 G18 G0 X0 Z0\nG2 X10 Z0 I5 K0 F60\n");
    let MoveKind::Arc { center, plane, .. } = tp.moves[1].kind else {
        panic!()
    };
    assert!(plane == Plane::Zx && close(center, Point3::new(5.0, 0.0, 0.0)));
    // A J word in G18 is refused.
    assert!(error("G18 G0 X0\nG2 X10 I5 J1 F60\n").contains("J word"));
}

#[test]
fn work_offsets_tool_length_and_g53() {
    let mut o = ReaderOptions::default();
    o.work_offsets[1] = Vec3::new(100.0, 0.0, -50.0);
    let text = "G21 G90\nG55 G0 X1 Y2 Z3\nG43 H1 G0 Z4\nG53 G0 X0 Y0 Z0\nG54 G0 X1\n";
    let tp = read_str(text, o).unwrap().0;
    assert!(close(tp.moves[0].to, Point3::new(101.0, 2.0, -47.0)));
    assert!(close(tp.moves[1].to, Point3::new(101.0, 2.0, -46.0)));
    assert!(close(tp.moves[2].to, Point3::ORIGIN));
    assert!(close(tp.moves[3].to, Point3::new(1.0, 0.0, 0.0)));
}

#[test]
fn corner_modes_per_dialect() {
    let tp = read("G21 F60\nG61.1 G1 X1\nG61 X2\nG64 P0.02 X3\nG64 X4\n");
    let c: Vec<Corner> = tp.moves.iter().map(|m| m.corner).collect();
    assert_eq!(
        c,
        [
            Corner::ExactStop,
            Corner::ExactPath,
            Corner::Blend(0.02),
            Corner::Machine
        ]
    );
    let tp = read_as(
        Dialect::Sinumerik,
        "G71 F60\nG60 G1 X1\nG64 X2\nCYCLE832(0.05,_FINISH,1)\nX3\nG642 X4\nG9 X5\n",
    );
    let c: Vec<Corner> = tp.moves.iter().map(|m| m.corner).collect();
    assert_eq!(
        c,
        [
            Corner::ExactStop,
            Corner::ExactPath,
            Corner::Blend(0.05),
            Corner::Machine,
            Corner::ExactStop
        ]
    );
    let tp = read_as(
        Dialect::Fanuc,
        "%\nO1234 (X)\nG21 F60\nG61 G1 X1.\nG64 X2.\nG09 X3.\n%\n",
    );
    let c: Vec<Corner> = tp.moves.iter().map(|m| m.corner).collect();
    assert_eq!(c, [Corner::ExactStop, Corner::Machine, Corner::ExactStop]);
}

#[test]
fn dwell_words_per_dialect() {
    let secs = |tp: &Toolpath| match tp.moves[0].kind {
        MoveKind::Dwell { seconds } => seconds,
        k => panic!("{k:?}"),
    };
    assert!((secs(&read("G4 P1.5\n")) - 1.5).abs() < 1e-12);
    assert!((secs(&read_as(Dialect::Fanuc, "G04 X1.5\n")) - 1.5).abs() < 1e-12);
    assert!((secs(&read_as(Dialect::Fanuc, "G04 P1500\n")) - 1.5).abs() < 1e-12);
    assert!((secs(&read_as(Dialect::Grbl, "G4 P1.5\n")) - 1.5).abs() < 1e-12);
    // Sinumerik: F in a G4 block is the time, not the feed.
    let tp = read_as(Dialect::Sinumerik, "G4 F1.5\nG1 X1 F60\n");
    assert!((secs(&tp) - 1.5).abs() < 1e-12 && (tp.moves[1].feed - 1.0).abs() < 1e-12);
    assert!(error("G4\n").contains("dwell"));
}

#[test]
fn program_end_block_delete_comments_and_percent() {
    let tp = read("%\n(header) ; more\nN10 G21 G1 X1 F60 (inline)\n/G1 X5\nM30\nG1 X9\n%\n");
    assert_eq!(
        tp.moves.len(),
        2,
        "the / line runs with the switch off; nothing after M30"
    );
    let o = ReaderOptions::default().with_block_delete(true);
    let tp = read_str("G21 G1 X1 F60\n/G1 X5\nG1 X2\n", o).unwrap().0;
    assert_eq!(tp.moves.len(), 2);
    assert!(close(tp.moves[1].to, Point3::new(2.0, 0.0, 0.0)));
}

/// An endless program: the reader must yield moves without reading to the end.
struct Endless {
    pending: Vec<u8>,
    n: u64,
}

impl Read for Endless {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.pending.is_empty() {
            self.n += 1;
            self.pending = format!("G1 X{} Y{} F600\n", self.n % 100, self.n % 7).into_bytes();
        }
        let k = buf.len().min(self.pending.len());
        buf[..k].copy_from_slice(&self.pending[..k]);
        self.pending.drain(..k);
        Ok(k)
    }
}

#[test]
fn reading_streams_an_endless_program() {
    let src = BufReader::new(Endless {
        pending: Vec::new(),
        n: 0,
    });
    let reader = Reader::new(src, ReaderOptions::default());
    let moves: Vec<_> = reader.take(50_000).collect::<Result<_, _>>().unwrap();
    assert_eq!(moves.len(), 50_000);
    assert_eq!(moves[49_999].line, 50_000);
}

#[test]
fn progress_counts_bytes_lines_and_the_end() {
    let text = "G21 G90\nG1 X1 F60\nM2\nG1 X5\n";
    let mut r = Reader::new(text.as_bytes(), ReaderOptions::default());
    assert!(r.next().unwrap().is_ok());
    assert_eq!((r.lines_read(), r.bytes_read()), (2, 18));
    assert!(r.next().is_none());
    assert!(r.ended() && r.lines_read() == 3, "stops at M2");
}

#[test]
fn a_huge_line_is_refused_not_buffered() {
    let line = format!("G1 X1 F60 ({})\n", "x".repeat(200_000));
    assert!(error(&line).contains("longer than"));
}

#[test]
fn units_in_the_same_block_follow_the_dialects_order() {
    // RS274/NGC sets the feed rate before the length units (rs274 prints SET_FEED_RATE(60)
    // before USE_LENGTH_UNITS(INCHES)): 60 mm/min.
    let tp = read("G21 F600\nG20 G1 X1 F60\nG21 G1 X30\n");
    assert!((tp.moves[0].feed - 1.0).abs() < 1e-12, "60 mm/min");
    assert!(
        (tp.moves[1].feed - 1.0).abs() < 1e-12,
        "the feed keeps its physical value"
    );
    assert!(close(tp.moves[1].to, Point3::new(30.0, 0.0, 0.0)));
    // The other dialects take the units first: 60 in/min.
    let o = ReaderOptions::default().with_dialect(Dialect::Fanuc);
    let (tp, _) = read_str("G21 F600.\nG20 G1 X1. F60.\nG21 G1 X30.\n", o).unwrap();
    assert!((tp.moves[0].feed - 25.4).abs() < 1e-12, "60 in/min");
    assert!((tp.moves[1].feed - 25.4).abs() < 1e-12);
}

#[test]
fn lenient_skips_unused_words_but_keeps_the_motion() {
    let o = ReaderOptions::default().with_lenient(true);
    let (tp, warnings) = read_str("G21 G1 X1 F60 Q3\n", o).unwrap();
    assert_eq!(tp.moves.len(), 1);
    assert!(warnings[0].message.contains("Q3"), "{warnings:?}");
    assert!(error("G21 G1 X1 F60 Q3\n").contains("Q3"));
    // Arc words without axis words and without G2/G3 in the block are an error.
    assert!(error("G21 G0 X1\nG2 X2 I0.5 F60\nI0.5\n").contains(":3"));
}

mod no_panics {
    use super::*;
    use proptest::prelude::*;

    fn words() -> impl Strategy<Value = String> {
        let word = (
            prop::sample::select(vec![
                "G",
                "M",
                "X",
                "Y",
                "Z",
                "I",
                "J",
                "K",
                "R",
                "F",
                "P",
                "Q",
                "S",
                "T",
                "N",
                "A",
                "(",
                ";",
                "%",
                "/",
                "#",
                "TURN=",
                "CYCLE832(",
            ]),
            prop::sample::select(vec![
                "0",
                "1",
                "2",
                "3",
                "4",
                "17",
                "18",
                "19",
                "20",
                "21",
                "61.1",
                "64",
                "90.1",
                "91",
                "93",
                "-1.5",
                ".5",
                "1e3",
                "",
                "-",
                "99999999999999999999",
            ]),
        );
        prop::collection::vec(prop::collection::vec(word, 0..8), 1..12).prop_map(|lines| {
            lines
                .iter()
                .map(|l| {
                    l.iter()
                        .map(|(a, b)| format!("{a}{b}"))
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .collect::<Vec<_>>()
                .join("\n")
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 400, rng_seed: proptest::test_runner::RngSeed::Fixed(11), ..ProptestConfig::default() })]

        /// Word soup and random bytes: errors are fine, panics and non-finite moves are not.
        #[test]
        fn the_reader_never_panics_or_yields_non_finite_moves(text in words(), bytes in prop::collection::vec(any::<u8>(), 0..200)) {
            for d in Dialect::ALL {
                for lenient in [false, true] {
                    let o = ReaderOptions::default().with_dialect(d).with_lenient(lenient);
                    for m in Reader::new(text.as_bytes(), o.clone()).flatten() {
                        prop_assert!(m.mv.to.is_finite() && m.mv.feed.is_finite());
                        prop_assert!(!m.mv.is_feed() || m.mv.feed > 0.0);
                    }
                    let _ = Reader::new(bytes.as_slice(), o).count();
                }
            }
        }
    }
}
