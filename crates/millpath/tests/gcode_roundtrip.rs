//! Round trip: toolpath → G-code (every dialect, mm and inch) → reader → the same moves.

mod gcode_common;

use gcode_common::{
    corner_read_back, expand_turns, move_difference, varied_toolpath, with_start_rapid,
};
use millpath::gcode::{Dialect, ReaderOptions, Units, WriterOptions, read_str, write_to_string};
use millpath::toolpath::{Corner, MoveKind, Toolpath};

/// Writes `tp` and reads it back; returns the expected and the read toolpaths.
fn round_trip(
    tp: &Toolpath,
    d: Dialect,
    units: Units,
    decimals: Option<u32>,
) -> (Toolpath, Toolpath, String) {
    let opts = WriterOptions::default()
        .with_dialect(d)
        .with_units(units)
        .with_decimals(decimals)
        .with_line_numbers(true);
    let (text, _) = write_to_string(tp, &opts).unwrap();
    let ropts = ReaderOptions::default()
        .with_dialect(d)
        .with_start(tp.start);
    let (read, warnings) =
        read_str(&text, ropts).unwrap_or_else(|e| panic!("{d} {units}: {e}\n{text}"));
    assert!(warnings.is_empty(), "{warnings:?}");
    let tp = &with_start_rapid(tp);
    let expected = if matches!(d, Dialect::Fanuc | Dialect::Grbl) {
        expand_turns(tp)
    } else {
        tp.clone()
    };
    (expected, read, text)
}

fn assert_same(
    expected: &Toolpath,
    read: &Toolpath,
    d: Dialect,
    bound: impl Fn(&MoveKind) -> f64,
    text: &str,
) {
    assert_eq!(
        expected.moves.len(),
        read.moves.len(),
        "{d}: move count\n{text}"
    );
    for (i, (a, b)) in expected.moves.iter().zip(&read.moves).enumerate() {
        let diff = move_difference(a, b);
        assert!(
            diff <= bound(&a.kind),
            "{d} move {i}: {a:?} read as {b:?} (diff {diff:e})\n{text}"
        );
        let want = if matches!(a.kind, MoveKind::Dwell { .. }) {
            Corner::ExactStop
        } else {
            corner_read_back(d, a.corner)
        };
        match (b.corner, want) {
            // Tolerances are written rounded down to >= 6 decimals of the program unit.
            (Corner::Blend(r), Corner::Blend(w)) => {
                assert!(r <= w && w - r <= 2.6e-5, "{d} move {i}: {r} vs {w}");
            }
            (r, w) => assert_eq!(r, w, "{d} move {i} corner"),
        }
    }
}

#[test]
fn every_dialect_round_trips_within_1e9_mm_with_10_decimals() {
    let tp = varied_toolpath();
    for d in Dialect::ALL {
        for units in [Units::Mm, Units::Inch] {
            // 10 decimals of an inch are 2.5e-9 mm: inches need 11 for the 1e-9 mm check.
            let dec = if units == Units::Inch { 11 } else { 10 };
            let (expected, read, text) = round_trip(&tp, d, units, Some(dec));
            assert_same(&expected, &read, d, |_| 1e-9, &text);
        }
    }
}

#[test]
fn default_decimals_round_trip_within_the_rounding_bound() {
    let tp = varied_toolpath();
    for d in Dialect::ALL {
        for units in [Units::Mm, Units::Inch] {
            let dec = d.default_decimals(units);
            // Each coordinate, centre and per-minute feed is off by at most half a unit of the
            // last place; feeds are in units per minute, so /60 in mm/s... but the feed of a
            // 25 mm/s move in in/min is a bigger number: the bound is per printed number.
            let half = 0.5 * 10f64.powi(-(dec as i32)) * units.mm_per_unit() * (1.0 + 1e-9);
            let (expected, read, text) = round_trip(&tp, d, units, None);
            assert_same(
                &expected,
                &read,
                d,
                |k| {
                    if matches!(k, MoveKind::Dwell { .. }) {
                        0.0005
                    } else {
                        half
                    }
                },
                &text,
            );
        }
    }
}

mod random {
    use super::*;
    use gcode_common::{build_random, random_step};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, rng_seed: proptest::test_runner::RngSeed::Fixed(7), ..ProptestConfig::default() })]

        #[test]
        fn random_toolpaths_round_trip_in_every_dialect(steps in proptest::collection::vec(random_step(), 1..16)) {
            let tp = build_random(&steps);
            for d in Dialect::ALL {
                for units in [Units::Mm, Units::Inch] {
                    let dec = if units == Units::Inch { 11 } else { 10 };
                    let (expected, read, text) = round_trip(&tp, d, units, Some(dec));
                    assert_same(&expected, &read, d, |_| 1e-9, &text);
                }
            }
        }
    }
}
