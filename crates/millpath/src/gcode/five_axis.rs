//! Five-axis G-code for table-table machines (AC or BC trunnions).
//!
//! The planned trajectory is in joint space, so the program is written in **machine joint
//! coordinates** (no tool-centre-point control needed): every interval is split into `n`
//! `G1` blocks at equal time steps `Δt = T/n`, with `X Y Z` in mm and the rotary words
//! (`A C` or `B C`) in degrees.
//!
//! # How many blocks
//! A `G1` block moves the joints linearly between its end points; the planned quintic `q(t)`
//! departs from that chord by at most `max|q̈| Δt²/8` (the interpolation error of a C² function
//! between two nodes). `max|q̈|` is the quintic's exact extremum, so `n` is the smallest count
//! with `max|q̈_i| (T/n)²/8 ≤ tol_i` for every joint ([`FiveAxisGcodeOptions::tolerance_mm`],
//! [`FiveAxisGcodeOptions::tolerance_deg`]): the joint path of the program stays within the
//! stated tolerance of the plan.
//!
//! # Feed words: what is exact
//! * inverse time (`G93`, the usual choice for simultaneous five-axis moves): `F = 1/Δt` with
//!   `Δt` in minutes, printed to nine significant digits, so every block takes its planned
//!   `Δt` on any control (relative error ≤ 5e-10) and the program's time is the plan's.
//! * units per minute (`G94`): RS274NGC (and LinuxCNC) apply `F` to the XYZ chord of a block
//!   that moves a linear axis, and to the chord of the rotary words, in degrees, of a block that
//!   moves only rotary axes. `F = chord / Δt` under that rule, with the chord of the words as
//!   printed (rounded to 4 decimals), gives every block its planned `Δt` too — exact on such
//!   controls, but only there (a control with tool-centre-point control applies `F` to the
//!   tip's path instead). Earlier versions took the largest rotary
//!   step instead of the rotary chord for rotary-only blocks, which made those blocks faster
//!   than planned by up to √2. A block moving no axis is a `G4` dwell of `Δt`.

use crate::error::{Error, InputError};
use crate::machine::kinematics::Kinematics;
use crate::motion::five_axis::Segment;
use std::io::Write;

/// Feed mode of the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedMode {
    /// `G93` inverse time.
    InverseTime,
    /// `G94` units per minute.
    UnitsPerMinute,
}

/// Options of [`write_five_axis`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiveAxisGcodeOptions {
    /// Feed mode. Default [`FeedMode::InverseTime`].
    pub feed_mode: FeedMode,
    /// Largest deviation of a linear joint between a block's chord and the plan, mm.
    /// Default 0.001.
    pub tolerance_mm: f64,
    /// Largest deviation of a rotary joint between a block's chord and the plan, degrees.
    /// Default 0.001.
    pub tolerance_deg: f64,
    /// Cap on the blocks per interval. Default 10 000.
    pub max_blocks_per_interval: usize,
}

impl Default for FiveAxisGcodeOptions {
    fn default() -> Self {
        FiveAxisGcodeOptions {
            feed_mode: FeedMode::InverseTime,
            tolerance_mm: 0.001,
            tolerance_deg: 0.001,
            max_blocks_per_interval: 10_000,
        }
    }
}

fn io_err(e: &std::io::Error) -> Error {
    Error::internal(format!("writing G-code: {e}"))
}

/// `x` to nine significant digits, without exponent.
fn sig9(x: f64) -> String {
    let mag = if x > 0.0 { x.log10().floor() as i32 } else { 0 };
    let decimals = (8 - mag).clamp(0, 12) as usize;
    format!("{x:.decimals$}")
}

/// Blocks needed for `seg` (see the module docs).
pub fn blocks_for(seg: &Segment, opts: &FiveAxisGcodeOptions) -> usize {
    let mut n = 1usize;
    for (i, ax) in seg.axes.iter().enumerate() {
        let acc = ax.max_abs_derivs()[1];
        let tol = if i < 3 {
            opts.tolerance_mm
        } else {
            opts.tolerance_deg.to_radians()
        };
        let need = (acc * seg.duration * seg.duration / (8.0 * tol))
            .sqrt()
            .ceil();
        if need.is_finite() && need >= 1.0 {
            n = n.max(need as usize);
        }
    }
    n.min(opts.max_blocks_per_interval.max(1))
}

/// Writes the program for `segments` on a table-table machine (`ac-trt` or `bc-trt`).
pub fn write_five_axis(
    w: &mut dyn Write,
    segments: &[Segment],
    kin: &dyn Kinematics,
    opts: &FiveAxisGcodeOptions,
) -> Result<(), Error> {
    if !matches!(kin.name(), "ac-trt" | "bc-trt") {
        return Err(InputError::new("machine", kin.name())
            .at("five-axis G-code")
            .expected("a table-table machine: ac-trt or bc-trt")
            .into());
    }
    for (name, v) in [
        ("tolerance_mm", opts.tolerance_mm),
        ("tolerance_deg", opts.tolerance_deg),
    ] {
        crate::error::require_positive(name, v, "five-axis G-code options")?;
    }
    let names = kin.axis_names();
    // `q` as printed: mm and degrees, rounded to the four decimals written.
    let printed = |q: &[f64; 5]| -> [f64; 5] {
        std::array::from_fn(|i| {
            let v = if i < 3 { q[i] } else { q[i].to_degrees() };
            // `+ 0.0` turns a rounded −0 into 0 (no `Y-0.0000` words).
            (v * 1e4).round() / 1e4 + 0.0
        })
    };
    let fmt = |q: &[f64; 5]| {
        format!(
            "X{:.4} Y{:.4} Z{:.4} {}{:.4} {}{:.4}",
            q[0], q[1], q[2], names[3], q[3], names[4], q[4]
        )
    };
    let total: f64 = segments.iter().map(|s| s.duration).sum();
    let mut out = String::new();
    out.push_str(&format!(
        "(millpath five-axis, {} kinematics, {} intervals, planned time {:.6} s)\n",
        kin.name(),
        segments.len(),
        total
    ));
    out.push_str(&format!(
        "(joint chords within {} mm and {} deg of the plan)\n",
        opts.tolerance_mm, opts.tolerance_deg
    ));
    out.push_str("G21 G90 G17 G40 G49 G80\n");
    let Some(first) = segments.first() else {
        return Err(InputError::new("trajectory", "no intervals")
            .expected("at least one interval")
            .into());
    };
    let start = printed(&first.eval(0.0)[0]);
    out.push_str(&format!("G0 {}\n", fmt(&start)));
    out.push_str(match opts.feed_mode {
        FeedMode::InverseTime => "G93\n",
        FeedMode::UnitsPerMinute => "G94\n",
    });
    let mut prev = start;
    for seg in segments {
        let n = blocks_for(seg, opts);
        let dt = seg.duration / n as f64;
        let minutes = dt / 60.0;
        for k in 1..=n {
            let q = printed(&seg.eval(dt * k as f64)[0]);
            // The chords of the *printed* words: what the control will interpolate.
            let lin =
                ((q[0] - prev[0]).powi(2) + (q[1] - prev[1]).powi(2) + (q[2] - prev[2]).powi(2))
                    .sqrt();
            let rot = ((q[3] - prev[3]).powi(2) + (q[4] - prev[4]).powi(2)).sqrt();
            match opts.feed_mode {
                FeedMode::InverseTime => {
                    out.push_str(&format!("G1 {} F{}\n", fmt(&q), sig9(1.0 / minutes)));
                }
                FeedMode::UnitsPerMinute if lin > 0.0 => {
                    out.push_str(&format!("G1 {} F{}\n", fmt(&q), sig9(lin / minutes)));
                }
                FeedMode::UnitsPerMinute if rot > 0.0 => {
                    out.push_str(&format!("G1 {} F{}\n", fmt(&q), sig9(rot / minutes)));
                }
                FeedMode::UnitsPerMinute => {
                    out.push_str(&format!("G4 P{}\n", sig9(dt)));
                }
            }
            prev = q;
        }
    }
    if opts.feed_mode == FeedMode::InverseTime {
        out.push_str("G94\n");
    }
    out.push_str("M2\n");
    w.write_all(out.as_bytes()).map_err(|e| io_err(&e))
}

#[cfg(test)]
mod tests {
    use super::sig9;

    #[test]
    fn nine_significant_digits() {
        assert_eq!(sig9(1234.56789012), "1234.56789");
        assert_eq!(sig9(0.0123456789012), "0.0123456789");
        assert_eq!(sig9(123_456_789_012.0), "123456789012");
    }
}
