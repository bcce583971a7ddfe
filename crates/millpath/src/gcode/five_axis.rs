//! Five-axis G-code for table-table machines (AC or BC trunnions), in every dialect whose
//! controller has rotary axes: LinuxCNC, Fanuc and Sinumerik (Grbl 1.1 drives X, Y and Z
//! only, so a five-axis program for it is refused as bad input).
//!
//! The planned trajectory is in joint space, so the program is written in **machine joint
//! coordinates** (no tool-centre-point control needed): every interval is split into `n`
//! `G1` blocks at equal time steps `Δt = T/n`, with `X Y Z` in program units and the rotary
//! words (`A C` or `B C`) in degrees.
//!
//! # The machine each dialect's program assumes
//! * A table-table machine: the outer table tilts about X (`A`, `xyzac-trt`) or Y (`B`,
//!   `xyzbc-trt`) and carries a rotary table `C` about Z; the kinematics of
//!   [`crate::machine::kinematics::TableTable`] (LinuxCNC's `kins_trt_params`) with the tool
//!   length of the plan.
//! * `Z` is the spindle's gauge point: the plan already includes the tool length, so no tool
//!   length compensation is switched on (no `G43`/`G43 H`; LinuxCNC runs trivial kinematics
//!   in joint mode, Fanuc without tool-centre-point control `G43.4`/`G43.5`, Sinumerik without
//!   `TRAORI`: the controller interpolates the joints linearly, as the block count assumes).
//! * Rotary axes that take absolute positions in degrees, sign and turns included: on Fanuc
//!   the rotary axes' roll-over is off (parameter 1008#0 `ROA` = 0), on Sinumerik they are
//!   not modulo axes (`MD30310 ROT_IS_MODULO` = 0), so `A-30. C400.` means what it says (a
//!   modulo axis would need `C=DC(…)`/`ACP`/`ACN` and could turn the other way).
//! * Inverse time `G93` on all three (Fanuc's optional "inverse time feed", Sinumerik's
//!   `G93` "inverse-time feedrate 1/min", LinuxCNC's `G93`): `F` is 1/minutes and does not
//!   depend on the units; `G94` is restored before the end.
//!
//! What changes between the dialects is what every program of the writer gets (framing,
//! comments, units words `G20/G21` or `G700/G710`, Fanuc's decimal point, tool change,
//! spindle and coolant, the end; see [the module docs](super)): the five-axis writer writes
//! its header and footer through the same emitter as [`super::write_program`].
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
//! * units per minute (`G94`): RS274NGC (LinuxCNC; Sinumerik likewise with its default
//!   `FGROUP`, the geometry axes) apply `F` to the XYZ chord of a block
//!   that moves a linear axis, and to the chord of the rotary words, in degrees, of a block that
//!   moves only rotary axes. `F = chord / Δt` under that rule, with the chord of the words as
//!   printed (rounded to 4 decimals), gives every block its planned `Δt` too — exact on such
//!   controls, but only there (a control with tool-centre-point control applies `F` to the
//!   tip's path instead). Earlier versions took the largest rotary
//!   step instead of the rotary chord for rotary-only blocks, which made those blocks faster
//!   than planned by up to √2. A block moving no axis is a `G4` dwell of `Δt`.
//!   Fanuc applies `F` to the chord of *all* the words, degrees counted as length units
//!   (`√(ΔX² + ΔY² + ΔZ² + ΔA² + ΔC²)`, its feedrate rule for simultaneous linear and rotary
//!   axes), so its `G94` programs get `F` from that chord.

use super::dialect::Dialect;
use super::format::{MAX_DECIMALS, round_to};
use super::writer::{Emitter, WriterOptions};
use crate::error::{Error, InputError};
use crate::machine::kinematics::Kinematics;
use crate::motion::five_axis::Segment;
use std::io::Write;

mod read;
pub use read::{JointBlock, read_five_axis};

/// Feed mode of the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedMode {
    /// `G93` inverse time.
    InverseTime,
    /// `G94` units per minute.
    UnitsPerMinute,
}

/// Options of [`write_five_axis`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
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
    /// The program's dialect, units, decimals (`None`: [`five_axis_decimals`]), tool number,
    /// spindle, coolant, numbering and name, as for every program. Its path tolerance is not
    /// used: the joints follow the chords, whose deviation from the plan is bounded above.
    /// Default: LinuxCNC, mm, no spindle, no coolant, no tool change.
    pub program: WriterOptions,
}

impl Default for FiveAxisGcodeOptions {
    fn default() -> Self {
        FiveAxisGcodeOptions {
            feed_mode: FeedMode::InverseTime,
            tolerance_mm: 0.001,
            tolerance_deg: 0.001,
            max_blocks_per_interval: 10_000,
            program: WriterOptions::default()
                .with_spindle_rpm(0.0)
                .with_coolant(super::Coolant::Off)
                .with_tool_change(false),
        }
    }
}

option_builders! {
    FiveAxisGcodeOptions;
    /// Sets [`FiveAxisGcodeOptions::feed_mode`].
    with_feed_mode => feed_mode: FeedMode;
    /// Sets [`FiveAxisGcodeOptions::tolerance_mm`], mm.
    with_tolerance_mm => tolerance_mm: f64;
    /// Sets [`FiveAxisGcodeOptions::tolerance_deg`], degrees.
    with_tolerance_deg => tolerance_deg: f64;
    /// Sets [`FiveAxisGcodeOptions::max_blocks_per_interval`], blocks.
    with_max_blocks_per_interval => max_blocks_per_interval: usize;
    /// Sets [`FiveAxisGcodeOptions::program`].
    with_program => program: WriterOptions;
}

/// Decimals of a five-axis program's words: `decimals` when given, else one more than the
/// dialect's default (4 in mm, 5 in inches; degrees get the same), so that rounding
/// (½·10⁻⁴ mm) stays well inside the default 0.001 chord tolerance.
pub fn five_axis_decimals(o: &WriterOptions) -> u32 {
    o.decimals
        .unwrap_or_else(|| o.dialect.default_decimals(o.units) + 1)
}

/// `x` to nine significant digits, without exponent; with `keep_point` an integral result
/// keeps its `.` (Fanuc).
fn sig9(x: f64, keep_point: bool) -> String {
    let mag = if x > 0.0 { x.log10().floor() as i32 } else { 0 };
    let decimals = (8 - mag).clamp(0, 12) as usize;
    let mut s = format!("{x:.decimals$}");
    if keep_point && !s.contains('.') {
        s.push('.');
    }
    s
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

/// Checks what `write_five_axis` refuses before it writes: the machine, the dialect and the
/// options (callers whose options come from the user check them here first).
pub fn check_five_axis(kin: &dyn Kinematics, opts: &FiveAxisGcodeOptions) -> Result<(), Error> {
    if !matches!(kin.name(), "ac-trt" | "bc-trt") {
        return Err(InputError::new("machine", kin.name())
            .at("five-axis G-code")
            .expected("a table-table machine: ac-trt or bc-trt")
            .into());
    }
    if opts.program.dialect == Dialect::Grbl {
        return Err(InputError::new("dialect", "grbl")
            .at("five-axis G-code")
            .expected(
                "linuxcnc, fanuc or sinumerik: grbl 1.1 drives X, Y and Z only, it has no \
                 rotary axis for the A/B/C words of a five-axis program",
            )
            .into());
    }
    for (name, v) in [
        ("tolerance_mm", opts.tolerance_mm),
        ("tolerance_deg", opts.tolerance_deg),
    ] {
        crate::error::require_positive(name, v, "five-axis G-code options")?;
    }
    let d = five_axis_decimals(&opts.program);
    if d > MAX_DECIMALS {
        return Err(InputError::new("decimals", d)
            .at("five-axis G-code options")
            .expected(format!("0 to {MAX_DECIMALS}"))
            .into());
    }
    opts.program.validate()?;
    Ok(())
}

/// Writes the program for `segments` on a table-table machine (`ac-trt` or `bc-trt`) in the
/// dialect of `opts.program`.
pub fn write_five_axis(
    w: &mut dyn Write,
    segments: &[Segment],
    kin: &dyn Kinematics,
    opts: &FiveAxisGcodeOptions,
) -> Result<(), Error> {
    check_five_axis(kin, opts)?;
    let Some(first) = segments.first() else {
        return Err(InputError::new("trajectory", "no intervals")
            .expected("at least one interval")
            .into());
    };
    let dec = five_axis_decimals(&opts.program);
    let mut program = opts.program.clone().with_decimals(Some(dec));
    program.path_tolerance = None;
    let dialect = program.dialect;
    let keep_point = dialect.keeps_decimal_point();
    let unit = program.units.mm_per_unit();
    let names = kin.axis_names();
    // `q` as printed: program units and degrees, rounded to the decimals written.
    let printed = |q: &[f64; 5]| -> [f64; 5] {
        std::array::from_fn(|i| {
            let v = if i < 3 {
                q[i] / unit
            } else {
                q[i].to_degrees()
            };
            round_to(v, dec)
        })
    };
    let total: f64 = segments.iter().map(|s| s.duration).sum();
    let mut e = Emitter::new(&program, w);
    e.header(None)?;
    e.comment(&format!(
        "five-axis, {} kinematics: table-table, joint coordinates, no tool length \
         compensation; {} intervals, planned time {total:.6} s",
        kin.name(),
        segments.len(),
    ))?;
    e.comment(&format!(
        "joint chords within {} mm and {} deg of the plan",
        opts.tolerance_mm, opts.tolerance_deg
    ))?;
    let axes = |e: &mut Emitter<'_>, q: &[f64; 5]| {
        for (i, v) in q.iter().enumerate() {
            e.word(names.get(i).copied().unwrap_or("X"), *v, dec);
        }
    };
    let start = printed(&first.eval(0.0)[0]);
    e.begin();
    e.raw("G0");
    axes(&mut e, &start);
    e.end()?;
    e.block(match opts.feed_mode {
        FeedMode::InverseTime => "G93",
        FeedMode::UnitsPerMinute => "G94",
    })?;
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
            let f = match opts.feed_mode {
                FeedMode::InverseTime => Some(1.0 / minutes),
                FeedMode::UnitsPerMinute if dialect == Dialect::Fanuc && lin.hypot(rot) > 0.0 => {
                    Some(lin.hypot(rot) / minutes)
                }
                FeedMode::UnitsPerMinute if lin > 0.0 => Some(lin / minutes),
                FeedMode::UnitsPerMinute if rot > 0.0 => Some(rot / minutes),
                FeedMode::UnitsPerMinute => None,
            };
            e.begin();
            match f {
                Some(f) => {
                    e.raw("G1");
                    axes(&mut e, &q);
                    e.raw(&format!("F{}", sig9(f, keep_point)));
                }
                None => e.raw(&match dialect {
                    Dialect::Fanuc => format!("G04 X{}", sig9(dt, true)),
                    Dialect::Sinumerik => format!("G4 F{}", sig9(dt, false)),
                    Dialect::LinuxCnc | Dialect::Grbl => format!("G4 P{}", sig9(dt, false)),
                }),
            }
            e.count_block();
            e.end()?;
            prev = q;
        }
    }
    if opts.feed_mode == FeedMode::InverseTime {
        e.block("G94")?;
    }
    e.footer()?;
    e.finish().map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::sig9;

    #[test]
    fn nine_significant_digits() {
        assert_eq!(sig9(1234.56789012, false), "1234.56789");
        assert_eq!(sig9(0.0123456789012, false), "0.0123456789");
        assert_eq!(sig9(123_456_789_012.0, false), "123456789012");
        assert_eq!(sig9(123_456_789_012.0, true), "123456789012.");
    }
}
