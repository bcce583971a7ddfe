//! G-code: a writer with four dialects, and a streaming reader (lexer → modal interpreter →
//! [`Move`](crate::Move)s).
//!
//! ```text
//! Toolpath ──write_program──▶ text ──Reader (lexer → interp → arc)──▶ ReadMove { Move, line, modal }
//! ```
//!
//! # Use
//! ```
//! use millpath::gcode::{Dialect, ReaderOptions, Reader, WriterOptions, write_to_string};
//! use millpath::{Move, Point3, Tool, Toolpath};
//! let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 5.0));
//! tp.push(Move::rapid(Point3::new(10.0, 0.0, 5.0)));
//! tp.push(Move::line(Point3::new(10.0, 0.0, -1.0), 5.0));
//! tp.push(Move::arc_xy(Point3::new(10.0, 0.0, -1.0), Point3::new(0.0, 0.0, -1.0), true, 20.0));
//! let opts = WriterOptions { dialect: Dialect::Fanuc, ..WriterOptions::default() };
//! let (text, summary) = write_to_string(&tp, &opts).unwrap();
//! assert_eq!(summary.blocks, 3);
//! let ropts = ReaderOptions { dialect: Dialect::Fanuc, start: tp.start, ..ReaderOptions::default() };
//! let read: Vec<_> = Reader::new(text.as_bytes(), ropts).collect::<Result<_, _>>().unwrap();
//! assert_eq!(read.len(), 3);
//! assert!(read[2].mv.to.distance(tp.moves[2].to) < 1e-12);
//! ```
//! [`write_program`] streams to any `io::Write`; [`Reader`] is an iterator over any
//! `BufRead` yielding [`ReadMove`] (the move in mm and mm/s, its line, the [`Modal`] state);
//! [`read_toolpath`]/[`read_str`] collect a whole program for small inputs.
//!
//! Inside everything is mm, mm/s, s and rad. Inches and per-minute feeds exist only in the
//! text: with G20 the writer divides coordinates by 25.4 and writes F in in/min; the reader
//! multiplies back. A program's rounding error is the only difference between a toolpath and
//! what is read back from its G-code (the round-trip tests check 1e-9 mm with 10 decimals and
//! the rounding bound with the defaults).
//!
//! # What each dialect gets
//! | | LinuxCNC (default) | Fanuc | Sinumerik 840D | Grbl 1.1 |
//! |---|---|---|---|---|
//! | framing | – | `%`, `O0001 (NAME)`, `%` | – | – |
//! | comments | `( )` | `( )`, upper case | `;` | `;` |
//! | units | G21/G20 | G21/G20 | G710/G700 (feeds follow) | G21/G20 |
//! | numbers | `X10` | `X10.` (keeps the point: without decimal point programming `X10` means 10 increments) | `X10` | `X10` |
//! | tool | `T1 M6`, `G43` on the first move | `T1 M6`, `G43 H1` on the first move | `T1 M6` (D1 is active by default) | a comment: no M6 |
//! | dwell | `G4 P`s | `G04 X`s (X with a decimal point is seconds; P would be ms) | `G4 F`s (own block; F does not change the feed) | `G4 P`s |
//! | path tolerance | `G64 P`tol | `G05.1 Q1` (AI contour control; its tolerance is a machine parameter, written as a comment), `G05.1 Q0` at the end | `CYCLE832(tol,_FINISH,1)` | none (a comment) |
//! | path tolerance 0 | `G61.1` (never `G64 P0`: LinuxCNC reads it as no limit) | `G61` | `G60` | none (a comment) |
//! | exact stop / exact path | `G61.1` / `G61` | `G61` / `G61` (no exact-path mode) | `G60` / `G64` (continuous path without rounding) | – (grbl has only its planner) |
//! | blend / machine | `G64 P`t / `G64 P`path or `G64` | `G64` / `G64` | `CYCLE832(t,_FINISH,1)` / CYCLE832 with the path tolerance, or `G642` | – |
//! | multi-turn arcs | `P`turns+1 | split into full turns | `TURN=`n | split into full turns |
//! | arc radii (rounded start and end) | LinuxCNC's rule (`arc`) | LinuxCNC's rule | LinuxCNC's rule | and Grbl 1.1's: 0.005 mm, or 0.1 % and 0.5 mm |
//! | five-axis ([`five_axis`]) | `G93`, `A`/`B` `C` words | the same, decimal points | the same | refused: no rotary axes |
//! | end | `M2` | `M30` | `M30` | `M2` |
//!
//! **The program's path tolerance** ([`WriterOptions::path_tolerance`],
//! [`WriterOptions::with_path_tolerance`]) is stated once in the header, after the work
//! offset. Programs that millpath times state the tolerance they were timed with: `pocket`
//! and the demo's pocket programs the machine's (`--machine`, hsm's 0.01 mm by default),
//! `contour` the machine's or the contour's tolerance where that is tighter. Read back, a
//! LinuxCNC or Sinumerik program's moves carry it as `Blend(t)` (exact stop at 0), so
//! `millpath estimate` plans it with that tolerance whatever machine it is given; Fanuc's
//! `G64` and Grbl's silence read back as the estimating machine's own tolerance. Without it
//! LinuxCNC runs in its default `G64` and blends each corner by up to a quarter of the
//! shorter segment (`tc.c`, `tcFindBlendTolerance`); under `G64 P t` its naive-CAM merging
//! (`Q`, which defaults to `P`: `interp_convert.cc`, `convert_control_mode`) also joins
//! short collinear-within-t line segments of one feed.
//!
//! Corner modes are modal: the writer writes one on its own line only when a move's
//! [`Corner`](crate::toolpath::Corner) differs from the last one written. What a corner mode
//! reads back as: LinuxCNC keeps all four exactly (`G64 P`tol reads as `Blend(tol)`, so a
//! `Machine` move written under a header `G64 P` reads back as the blend it means); Fanuc
//! reads `G61` as exact stop and `G64` as machine; Sinumerik `G60` exact stop, `G64` exact
//! path, `CYCLE832(t,..)` blend, `G642` machine; Grbl programs carry no corner mode (the
//! writer writes none), so they read back as machine.
//!
//! Sources for the dwell words: LinuxCNC's G-code reference (`G4 P` seconds); Siemens'
//! ISO-dialect manual (840D, `G04 X_` seconds with decimal point, `P_` in ms without) and
//! Fanuc's identical convention; Sinumerik's Siemens mode `G4 F…` (seconds, "must be programmed
//! in a separate block"); Grbl 1.1 `G4 P` seconds.
//!
//! # Numbers and the tolerance budget
//! See `format`: trailing zeros trimmed, no `-0`, default 3 decimals in mm and 4 in inches;
//! a point rounds by at most `√2·½·10^(−d)` in XY, and [`required_decimals`] keeps that within
//! 10 % of a tolerance so that chordal deviation plus rounding stays within it.
//!
//! # Limits
//! Numbers in a program are limited to ±1e9 (program units) and must be decimals without
//! exponent; lines to 64 KiB. The reader's position is the machine position: program
//! position + work offset + G92 offset + tool length offset (G43, from
//! [`ReaderOptions::tool_table`]; zero without one). Rotary axes (A/B/C; five-axis joint
//! programs are read by [`five_axis::read_five_axis`]), cutter compensation in G19 or in
//! inverse time (G93), canned cycles other than LinuxCNC's G73/G81–G83/G85/G89, splines other than LinuxCNC's
//! G5, G5.1 and G5.2/G5.3 NURBS (module `interp::nurbs`: the true curve within 1 µm), G92 and canned cycles in
//! rotated systems (`G10 L2 R` itself is read: module `interp::rotation`), Fanuc's modal
//! macro calls G66/G67 and Sinumerik parameters are refused (or skipped when lenient),
//! naming the word and the line.
//!
//! # RS274/NGC (the LinuxCNC dialect)
//! Parameters (`#1`, `#<name>`, `#<_global>`, the machine-state parameters), expressions
//! (module `expr`: LinuxCNC's operators, precedence and functions), O-word subroutines and
//! control flow (module `oword`; subroutine files on [`ReaderOptions::subroutine_path`], a
//! step budget [`ReaderOptions::step_budget`] against endless loops), work offsets G10 L2/L20,
//! G54–G59.3, G92/G92.1/G92.2/G92.3 (`interp::offsets`), polar words `@` (radius) and `^`
//! (angle) about the program origin, lathe diameter mode G7/G8, canned cycles G73, G81–G83, G85,
//! G89 with G98/G99 (`interp::cycles`, expanded as LinuxCNC expands them), cutter radius
//! compensation G40/G41/G42/G41.1/G42.1 (`interp::cutter_comp`: LinuxCNC's entry, corner,
//! arc and exit rules and its refusals, in G17 and G18, D from [`ReaderOptions::tool_table`]),
//! and `(MSG,…)`/`(DEBUG,…)`/`(PRINT,…)`
//! passed to [`Reader::messages`]. Lines with none of these take the plain lexer: the reading
//! speed of plain programs is unchanged. Every construct is compared with LinuxCNC's
//! `rs274 -g` (`tests/gcode_ngc.rs`), and so are LinuxCNC's own 416 programs
//! (`tests/linuxcnc_programs.rs`; the counts are in BENCHMARKS.md).
//!
//! # Fanuc subprograms and custom macro B
//! In the Fanuc dialect the reader runs what a Fanuc 0i/30i with custom macro B runs (module
//! `fanuc` for the program flow, module `macro_b` for variables and expressions): program
//! numbers `O1234`/`:1234` and `%` framing, several programs in one file, `M98 P… L…` (and
//! the packed `M98 P31000`), `M99` and `M99 P n`, `M99` in the main program (an endless
//! loop bounded by the step budget), subprogram files `O1000.nc`/`1000.nc` on
//! [`ReaderOptions::subroutine_path`], `G65 P… L…` with arguments (specifications I and
//! II), locals `#1–#33` per macro level, commons `#100–#199`/`#500–#999`, vacant
//! variables (`#0`), Fanuc's operators and functions, `IF […] GOTO n`, `IF […] THEN`,
//! `GOTO n`, `WHILE […] DO m`/`END m`, and the alarm `#3000`. Nesting: 10 M98 levels and 5
//! G65 levels (the 30i's). G66/G67 and system variables other than `#3000` are refused.
//! Every block takes the plain lexer first; only a block it refuses is read as macro B (a
//! plain G1 line pays for the line store and the program-number check: about 270
//! instructions of its ~2 400, measured with callgrind). The file's lines are kept in memory
//! once read (a jump may go back to any of them). Checked in `tests/gcode_fanuc.rs`
//! against end points computed independently.

//! # The reader's modal rules
//! See `interp`: the state machine follows RS274/NGC's order of execution within a block,
//! accepts each dialect's own forms of what the writer emits, and refuses every word it does
//! not understand with the line and the word (or skips it with a warning when lenient).
//!
//! # The arc-radius rule
//! See `arc`: LinuxCNC's `arc_data_ijk` rule (`Δ > 100τ` or (`Δ/r > 0.1 %` and `Δ > τ`),
//! `τ = 0.0283 mm` or `0.00283 in`), cited from its source and checked against `rs274`.

pub(crate) mod arc;
mod dialect;
mod expr;
mod fanuc;
pub mod five_axis;
pub(crate) mod format;
pub(crate) mod interp;
mod lexer;
mod macro_b;
mod ngc;
mod oword;
mod params;
mod reader;
mod tools;
mod writer;

pub use dialect::{Coolant, Dialect, Units};
pub use format::{required_decimals, rounding_error_mm};
pub use interp::{DEFAULT_STEP_BUDGET, FeedMode, Modal, ReadMove, ReaderOptions};
pub use params::ParamFile;
pub use reader::{MAX_LINE_BYTES, MAX_WARNINGS, Reader, Warning, read_str, read_toolpath};
pub use tools::{ToolEntry, ToolTable};
pub use writer::{MIN_ARC_RADIUS_MM, WriteSummary, WriterOptions, write_program};

/// Writes `tp` into a `String` (convenience for tests and small programs).
pub fn write_to_string(
    tp: &crate::Toolpath,
    opts: &WriterOptions,
) -> Result<(String, WriteSummary), crate::Error> {
    let mut buf = Vec::new();
    let summary = write_program(tp, opts, &mut buf)?;
    let text = String::from_utf8(buf)
        .map_err(|e| crate::Error::internal(format!("writer produced invalid UTF-8: {e}")))?;
    Ok((text, summary))
}
