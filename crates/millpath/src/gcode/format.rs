//! Number formatting for G-code words, and the rounding budget of the output.
//!
//! # Formatting
//! A value is printed with a fixed number of decimals (Rust's `{:.d}` formatting rounds the
//! binary value correctly to the nearest decimal), then trailing zeros are trimmed, a trailing
//! `.` is dropped (kept for Fanuc, see below), and `-0` becomes `0`.
//!
//! Fanuc controls without "decimal point programming" read an integer word such as `X10` in the
//! least input increment (10 µm on an IS-B control), so for Fanuc every non-integer-only word
//! keeps its decimal point: `X10.`. This is what Fanuc posts have always written.
//!
//! # Rounding budget
//! Rounding a coordinate to `d` decimals moves it by at most half a unit of the last place,
//! `e₁ = ½·10^(−d)` program units, per axis. In the XY plane the two axes round independently,
//! so a point moves by at most `e = √2 · e₁` (the diagonal of the rounding square). A line
//! segment whose end points each move by at most `e` stays within `e` of the original segment
//! (every point of it is a convex combination of the end points), so a flattening with chordal
//! deviation `δ` written with `d` decimals deviates from the true curve by at most `δ + e`.
//!
//! [`required_decimals`] gives the smallest `d` whose `e` (converted to mm) is at most
//! [`ROUNDING_SHARE`] of the tolerance, leaving the rest (90 %) for the chordal deviation; the
//! caller flattens with `T − rounding_error_mm(d, units)` and the sum stays within `T`.

use super::Units;
use std::fmt::Write as _;

/// Share of a path tolerance that output rounding may use (the rest is for the geometry).
pub const ROUNDING_SHARE: f64 = 0.1;

/// Most decimals the writer accepts: beyond 12 decimals f64 itself (≈ 16 significant digits)
/// cannot hold the value of a metre-sized part exactly.
pub const MAX_DECIMALS: u32 = 12;

pub use crate::geom::MM_PER_INCH;

/// Worst-case XY displacement in mm of a point whose coordinates are rounded to `decimals` in
/// `units`: `√2 · ½ · 10^(−decimals)` program units.
pub fn rounding_error_mm(decimals: u32, units: Units) -> f64 {
    let unit = match units {
        Units::Mm => 1.0,
        Units::Inch => MM_PER_INCH,
    };
    std::f64::consts::SQRT_2 * 0.5 * 10f64.powi(-(decimals as i32)) * unit
}

/// The smallest number of decimals whose XY rounding error ([`rounding_error_mm`]) is at most
/// `ROUNDING_SHARE` × `tolerance_mm`, capped at `MAX_DECIMALS`. A non-finite or
/// non-positive tolerance gets `MAX_DECIMALS`.
pub fn required_decimals(tolerance_mm: f64, units: Units) -> u32 {
    if !(tolerance_mm.is_finite() && tolerance_mm > 0.0) {
        return MAX_DECIMALS;
    }
    let budget = ROUNDING_SHARE * tolerance_mm;
    (0..=MAX_DECIMALS)
        .find(|&d| rounding_error_mm(d, units) <= budget)
        .unwrap_or(MAX_DECIMALS)
}

/// Appends `value` with at most `decimals` decimals to `out`: trailing zeros trimmed, no `-0`;
/// with `keep_point` an integral value keeps its `.` (Fanuc).
pub fn push_number(out: &mut String, value: f64, decimals: u32, keep_point: bool) {
    let start = out.len();
    // Writing to a String cannot fail.
    let _ = write!(out, "{:.*}", decimals as usize, value);
    if decimals > 0 {
        while out.ends_with('0') {
            out.pop();
        }
        if out.ends_with('.') && !keep_point {
            out.pop();
        }
    } else if keep_point {
        out.push('.');
    }
    // "-0", "-0." and "-0.000" (already trimmed to "-0"/"-0.") are zero.
    let body = &out[start..];
    if body == "-0" || body == "-0." {
        out.remove(start);
    }
}

/// `value` formatted as by [`push_number`].
pub fn format_number(value: f64, decimals: u32, keep_point: bool) -> String {
    let mut s = String::new();
    push_number(&mut s, value, decimals, keep_point);
    s
}

/// The value a reader gets back from [`format_number`]: `value` rounded to `decimals`.
pub fn round_to(value: f64, decimals: u32) -> f64 {
    format_number(value, decimals, false)
        .parse()
        .unwrap_or(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_without_negative_zero_or_trailing_zeros() {
        assert_eq!(format_number(-0.0001, 3, false), "0");
        assert_eq!(format_number(-0.0001, 3, true), "0.");
        assert_eq!(format_number(1.5000, 4, false), "1.5");
        assert_eq!(format_number(10.0, 3, false), "10");
        assert_eq!(format_number(10.0, 3, true), "10.");
        assert_eq!(format_number(-2.35, 1, false), "-2.4");
        assert_eq!(format_number(7.0, 0, true), "7.");
        assert_eq!(format_number(123.456_789, 10, false), "123.456789");
        assert_eq!(format_number(-0.5, 0, false), "0");
    }

    #[test]
    fn required_decimals_meets_the_budget_and_is_minimal() {
        for tol in [1e-1, 1e-2, 1e-3, 1e-4, 4e-5] {
            for units in [Units::Mm, Units::Inch] {
                let d = required_decimals(tol, units);
                assert!(
                    rounding_error_mm(d, units) <= ROUNDING_SHARE * tol,
                    "{tol} {units:?}"
                );
                assert!(d == 0 || rounding_error_mm(d - 1, units) > ROUNDING_SHARE * tol);
            }
        }
        assert_eq!(required_decimals(0.01, Units::Mm), 3);
        assert_eq!(required_decimals(4e-5, Units::Mm), 6);
        assert_eq!(required_decimals(f64::NAN, Units::Mm), MAX_DECIMALS);
    }

    #[test]
    fn round_to_matches_the_printed_value() {
        assert!((round_to(1.23456, 3) - 1.235).abs() < 1e-15);
    }
}
