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
//! let opts = WriterOptions::default().with_dialect(Dialect::Fanuc);
//! let (text, summary) = write_to_string(&tp, &opts).unwrap();
//! assert_eq!(summary.blocks, 3);
//! let ropts = ReaderOptions::default().with_dialect(Dialect::Fanuc).with_start(tp.start);
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
//! Tabled on [`Dialect`]: framing, comments, units, numbers, tool change, dwell, path
//! tolerance and corner modes, multi-turn arcs, five-axis words and the end of each; how a
//! program's path tolerance is stated and read back.
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
//! [`ReaderOptions::tool_table`]; zero without one). Rotary words A/B/C are read and left out
//! of the X Y Z path (five-axis joint programs: [`five_axis::read_five_axis`]). What the
//! reader does not know — lathe cycles G70–G72, arcs in a rotated vertical plane, cutter
//! compensation in G19 or G93, Fanuc's modal macros G66/G67, Sinumerik parameters, HAL pins —
//! is refused with the word and the line (or skipped when lenient).
//!
//! **Programs that never end.** Lines run again (in loops and subroutines, after a backward
//! jump) count against [`ReaderOptions::step_budget`] (default [`DEFAULT_STEP_BUDGET`],
//! module `budget`): past it the program is refused naming the loop end, jump or call that
//! ran most often and the number of lines run, so an endless program stops within seconds.
//!
//! **Nesting.** Nothing in the reader recurses once per level of its input: O-word calls nest
//! at most 100 deep, Fanuc's M98 10 and G65 5 levels, `if`/`while`/`do`/`repeat` 1000
//! deep (program flow on vectors, module `oword`, `fanuc`); brackets, signs and functions
//! of an expression 64 deep (modules `expr`, `macro_b`, the only recursive descent); comments
//! do not nest. Input nested deeper is refused with a message, never overflows a stack.
//!
//! # RS274/NGC (the LinuxCNC dialect)
//! LinuxCNC 2.9's language, module by module under `interp`: parameters and expressions
//! (`expr`), O-word subroutines and control flow (`oword`; files on
//! [`ReaderOptions::subroutine_path`], [`ReaderOptions::step_budget`] against endless loops),
//! work and G92 offsets, `G10 L2/L20` (`offsets`), rotated systems (`rotation`), polar words,
//! G7/G8, canned cycles G73, G81–G83, G85, G89 (`cycles`), splines G5, G5.1, G5.2/G5.3 and
//! master's G6.2 as the true curve within 1 µm (`nurbs`, `g6_nurbs`), G33/G33.1/G95
//! (`spindle_sync`), probes G38.2–G38.5 (`probe`), cutter radius compensation
//! G40–G42/G41.1/G42.1 with LinuxCNC's entry, corner, arc and exit rules and refusals
//! (`cutter_comp`), and `(MSG,…)`/`(DEBUG,…)`/`(PRINT,…)` passed to [`Reader::messages`].
//! Lines with none of these take the plain lexer, so plain programs read as fast as before.
//! Every construct is compared with LinuxCNC's `rs274 -g` (`tests/gcode_ngc.rs`), and so are
//! LinuxCNC's own 416 programs (`tests/linuxcnc_programs.rs`; counts in BENCHMARKS.md).
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
//! Every block takes the plain lexer first; only a block it refuses is read as macro B. The
//! file's lines are kept in memory
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
mod budget;
mod detect;
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

pub use detect::{
    Clue, ClueRule, DETECT_BYTES, DialectChoice, DialectGuess, DialectReason, reads_whole,
};
pub use dialect::{Coolant, Dialect, Units};
pub use format::{required_decimals, rounding_error_mm};
pub use interp::{DEFAULT_STEP_BUDGET, FeedMode, Modal, ReadMove, ReaderOptions};
pub use params::ParamFile;
pub use reader::{MAX_LINE_BYTES, MAX_WARNINGS, Reader, Warning, read_str, read_toolpath};
pub use tools::{ToolEntry, ToolTable};
pub use writer::{
    MIN_ARC_RADIUS_MM, ProgramSection, SectionsSummary, WriteSummary, WriterOptions, write_program,
    write_sections,
};

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
