//! The optimize job behind `millpath optimize`: a LinuxCNC program's feed words rewritten so
//! that each straight feed block states the time its joints allow, kept only when the
//! machine's controller model runs it faster; otherwise the program is returned unchanged
//! with the reason.
//!
//! # The rewrite
//! Each straight feed block (G1, every motion line one move: no loops, subroutines or canned
//! cycles) gets inverse time `G93 F = 1/t`, with `t` the block's time at constant speed
//! under the programmed tool-tip feed and every joint's velocity limit:
//!
//! ```text
//! t = max( L / F ,  maxᵢ |dᵢ| / vᵢ )      L: X Y Z length (the rotary chord on a rotary-only
//!                                           block, F then in deg/s), i over X Y Z A B C
//! ```
//!
//! `F` is written rounded down (the block a little longer), so the tool tip never runs faster
//! than the programmed feed and no joint faster than its limit. Arcs and rapids are left as
//! they are; `G94` and the programmed feed are restated before an arc that follows a
//! rewritten block. Coordinates, motion words and path modes are copied as written.
//!
//! # Merged blocks
//! Before that, runs of straight blocks whose end points lie within the tolerance of one
//! chord are merged into one block (`merge`, [`OptimizeOptions::merge`]): that is where
//! LinuxCNC gains. Its canon already caps each straight block at `min(F, L / maxᵢ(|dᵢ|/vᵢ))`
//! (`getStraightVelocity`), which is `L/t` above, so the feed words alone restate the speed it
//! runs; the time such programs lose is at junctions next to a rotary axis, which LinuxCNC
//! neither blends with an arc nor takes as tangent (`tcRotaryMotionCheck`): parabolic blends
//! at half acceleration, each block planned to end at rest, so that a block of length `L`
//! runs at most about `√(a L / 2)`. Longer blocks run faster. The job times the input and the
//! rewrite on the machine's controller model and keeps the rewrite only when it is faster by
//! more than [`MIN_GAIN_S`]; [`OptimizeOutcome`] says which. Figures in BENCHMARKS.md.
//!
//! # Checks (independent of the rewrite)
//! The output is read back and compared with the input: every output move is one input move
//! or, for a straight feed block, the run of input straight feed blocks up to the one that
//! ends where it ends, every end point in between within the tolerance of the output's chord
//! (the least normalised distance over the chord, `merge::chord_distance`); the same kinds
//! (rapid, line, arc; plane and direction), every end point and rotary position within
//! [`SAME_POINT_MM`], every feed at most the input's (the slowest of a run, relative `1e-9`),
//! and on every straight feed block no joint over its velocity limit at the written feed.

use crate::gcode::{Dialect, FeedMode, ReadMove, Reader, ReaderOptions};
use crate::job::estimate::{Estimate, EstimateSettings, run_text};
use crate::machine::Machine;
use crate::toolpath::{MoveKind, Rotary};
use crate::{Error, InputError, Point3};
use serde::Serialize;
use std::fmt;

mod merge;
pub use merge::MergeTolerance;

/// Options of [`optimize_text`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct OptimizeOptions {
    /// Merge runs of straight blocks within this tolerance of one chord (the module docs); `None`
    /// keeps every block. Default: 0.001 mm and 0.001°.
    pub merge: Option<MergeTolerance>,
}

impl Default for OptimizeOptions {
    fn default() -> Self {
        OptimizeOptions {
            merge: Some(MergeTolerance::default()),
        }
    }
}

option_builders! {
    OptimizeOptions;
    /// Sets [`OptimizeOptions::merge`].
    with_merge => merge: Option<MergeTolerance>;
}

/// The smallest saving (s, by the controller model) for which the rewrite is kept.
pub const MIN_GAIN_S: f64 = 1e-3;

/// How far (mm, and rad for the rotary axes) an end point of the output may be from the
/// input's: the coordinates are copied, so only reading them again may differ.
pub const SAME_POINT_MM: f64 = 1e-9;

/// Decimals of the written inverse-time F.
const F_DECIMALS: i32 = 6;

/// What `optimize` did with a program.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub enum OptimizeOutcome {
    /// The rewrite runs faster on the controller model: the saving in seconds.
    Faster {
        /// Seconds saved.
        saved_s: f64,
    },
    /// The rewrite is not faster (by more than [`MIN_GAIN_S`]): the program is unchanged.
    NothingGained {
        /// The rewrite's time minus the input's, seconds.
        difference_s: f64,
    },
}

impl fmt::Display for OptimizeOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OptimizeOutcome::Faster { saved_s } => write!(f, "faster by {saved_s:.3} s"),
            OptimizeOutcome::NothingGained { difference_s } => write!(
                f,
                "nothing gained (the rewrite's time differs by {difference_s:+.3} s): too few \
                 blocks lie within the tolerance of one chord to merge, the controller already \
                 slows each block to its slowest joint, and the time lost at junctions next to \
                 rotary motion is not changed by feed words"
            ),
        }
    }
}

/// An optimized program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Optimized {
    /// The program text (the input's when nothing was gained).
    pub text: String,
    /// The rewritten text, kept or not.
    pub rewrite: String,
    /// The input's estimate on the machine.
    pub before: Estimate,
    /// The rewrite's estimate on the machine.
    pub after: Estimate,
    /// Straight feed blocks rewritten in inverse time.
    pub rewritten_blocks: usize,
    /// Input blocks merged into the block after them ([`OptimizeOptions::merge`]).
    pub merged_blocks: usize,
    /// Kept or not, and why.
    pub outcome: OptimizeOutcome,
}

/// Optimizes the LinuxCNC program `text` (named `origin` in messages) for `machine`.
pub fn optimize_text(
    text: &str,
    origin: &str,
    machine: &Machine,
    opts: &OptimizeOptions,
) -> Result<Optimized, Error> {
    if let Some(t) = opts.merge
        && !(t.mm.is_finite() && t.mm > 0.0 && t.rad.is_finite() && t.rad > 0.0)
    {
        return Err(
            InputError::new("--tolerance", format!("{} mm, {} rad", t.mm, t.rad))
                .expected("finite tolerances > 0")
                .into(),
        );
    }
    let moves = read(text, origin)?;
    let (rewrite, rewritten_blocks, merged_blocks) =
        rewrite(text, origin, &moves, machine, opts.merge)?;
    check_same_path(&moves, &read(&rewrite, origin)?, machine, opts.merge)?;
    let settings = EstimateSettings {
        dialect: "linuxcnc".into(),
        ..EstimateSettings::default()
    };
    let before = run_text(text, origin, machine, &settings)?.estimate;
    let after = run_text(&rewrite, origin, machine, &settings)?.estimate;
    let difference_s = after.cycle_time_s - before.cycle_time_s;
    let (outcome, text) = if difference_s < -MIN_GAIN_S {
        let saved_s = -difference_s;
        (OptimizeOutcome::Faster { saved_s }, rewrite.clone())
    } else {
        (
            OptimizeOutcome::NothingGained { difference_s },
            text.to_owned(),
        )
    };
    Ok(Optimized {
        text,
        rewrite,
        before,
        after,
        rewritten_blocks,
        merged_blocks,
        outcome,
    })
}

fn read(text: &str, origin: &str) -> Result<Vec<ReadMove>, Error> {
    let opts = ReaderOptions::default()
        .with_dialect(Dialect::LinuxCnc)
        .with_origin(origin.to_owned());
    Reader::new(text.as_bytes(), opts).collect()
}

/// The block's time at constant speed under the tip feed and the joints' velocity limits.
fn block_time(from: (Point3, Rotary), to: (Point3, Rotary), feed: f64, m: &Machine) -> f64 {
    let d = (to.0 - from.0).to_array();
    let r = [to.1.a - from.1.a, to.1.b - from.1.b, to.1.c - from.1.c];
    let xyz = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let mut t = if xyz > 1e-9 {
        xyz / feed
    } else {
        to.1.distance(from.1) / feed
    };
    for (x, a) in d.iter().zip(&m.axes) {
        t = t.max(x.abs() / a.max_velocity);
    }
    for (x, a) in r.iter().zip(&m.rotary) {
        if let Some(a) = a {
            // Rotary limits are in deg/s in LinuxCNC's units, rad/s here.
            t = t.max(x.abs() / a.max_velocity);
        }
    }
    t
}

/// The code part of a line (comments removed), upper case, for finding G93/G94 words.
fn feed_mode_words(line: &str) -> Option<bool> {
    let code = strip_comments(line).to_ascii_uppercase();
    let compact: String = code.chars().filter(|c| !c.is_whitespace()).collect();
    let mut last = None;
    let bytes = compact.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'G' {
            let num: String = compact[i + 1..]
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .collect();
            match num.parse::<f64>() {
                Ok(v) if is(v, 93.0) => last = Some(true),
                Ok(v) if is(v, 94.0) || is(v, 95.0) => last = Some(false),
                _ => {}
            }
        }
        i += 1;
    }
    last
}

/// A G word's number is `g` (G93 and G93.0 alike).
fn is(v: f64, g: f64) -> bool {
    (v - g).abs() < 1e-9
}

fn strip_comments(line: &str) -> String {
    let mut out = String::new();
    let mut depth = 0;
    for c in line.chars() {
        match c {
            ';' if depth == 0 => break,
            '(' => depth += 1,
            ')' if depth > 0 => depth -= 1,
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// The line without its F word and G93/G94 words (comments dropped).
fn without_feed_words(line: &str) -> String {
    let code = strip_comments(line);
    let mut out = String::new();
    let mut chars = code.chars().peekable();
    while let Some(c) = chars.next() {
        let up = c.to_ascii_uppercase();
        if up == 'F' || up == 'G' {
            let mut word = String::new();
            while let Some(&n) = chars.peek() {
                if n.is_ascii_digit() || n == '.' || n == '-' || n == '+' || n == ' ' {
                    word.push(n);
                    chars.next();
                } else {
                    break;
                }
            }
            let value: String = word.chars().filter(|c| !c.is_whitespace()).collect();
            let drop =
                up == 'F' || matches!(value.parse::<f64>(), Ok(v) if is(v, 93.0) || is(v, 94.0));
            if !drop {
                out.push(c);
                out.push_str(value.as_str());
                out.push(' ');
            }
        } else {
            out.push(c);
        }
    }
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn unsupported(origin: &str, line: usize, what: &str) -> Error {
    InputError::new("program", format!("{origin}, line {line}"))
        .expected(format!(
            "a program whose every motion line makes one move ({what}); optimize rewrites \
             the feed word of each line in place"
        ))
        .into()
}

/// The rewritten text, the number of rewritten blocks and of blocks merged away.
fn rewrite(
    text: &str,
    origin: &str,
    moves: &[ReadMove],
    m: &Machine,
    tol: Option<MergeTolerance>,
) -> Result<(String, usize, usize), Error> {
    let lines: Vec<&str> = text.lines().collect();
    // Moves of a called subroutine may come from another file's lines.
    if let Some(n) = lines.iter().position(|l| {
        let code = strip_comments(l).to_ascii_uppercase();
        code.contains("CALL") || code.contains("M98") || code.contains("G65")
    }) {
        return Err(unsupported(origin, n + 1, "a subroutine call"));
    }
    // The move of each line (lines make one move at most, in order).
    let mut by_line: Vec<Option<usize>> = vec![None; lines.len() + 1];
    let mut last_line = 0;
    for (k, rm) in moves.iter().enumerate() {
        if rm.line <= last_line || rm.line > lines.len() {
            return Err(unsupported(
                origin,
                rm.line,
                "a line that makes several moves or runs again",
            ));
        }
        if rm.mv.feed.is_nan() {
            return Err(unsupported(origin, rm.line, "a move without a feed"));
        }
        last_line = rm.line;
        by_line[rm.line] = Some(k);
    }
    // Where each move starts, and the merged runs.
    let mut start = Vec::with_capacity(moves.len());
    let mut at = (Point3::new(0.0, 0.0, 0.0), Rotary::default());
    for rm in moves {
        start.push(at);
        at = (rm.mv.to, rm.mv.rotary.unwrap_or(at.1));
    }
    let groups = match tol {
        Some(t) => merge::groups(moves, &lines, &start, t, strip_comments),
        None => (0..moves.len())
            .map(|k| merge::Group { first: k, last: k })
            .collect(),
    };
    let mut group_of = vec![0; moves.len()];
    for (g, grp) in groups.iter().enumerate() {
        group_of[grp.first..=grp.last].fill(g);
    }
    let mut out = String::with_capacity(text.len() + text.len() / 4);
    let mut pos = (Point3::new(0.0, 0.0, 0.0), Rotary::default());
    let mut in_g93 = false; // the output's feed mode
    let mut rewritten = 0;
    let mut merged = 0;
    for (i, line) in lines.iter().enumerate() {
        let n = i + 1;
        let Some(k) = by_line[n] else {
            if let Some(g93) = feed_mode_words(line) {
                in_g93 = g93;
            }
            out.push_str(line);
            out.push('\n');
            continue;
        };
        let rm = &moves[k];
        let orig_g93 = rm.modal.feed_mode == FeedMode::InverseTime;
        let to = (rm.mv.to, rm.mv.rotary.unwrap_or(pos.1));
        let grp = groups[group_of[k]];
        if k < grp.last {
            // Merged into the run's last block: the line is left out.
            merged += 1;
            pos = to;
            continue;
        }
        let from = start[grp.first];
        let feed = (grp.first..=grp.last)
            .map(|j| moves[j].mv.feed)
            .fold(f64::INFINITY, f64::min);
        // A merged block states every axis the run set (the lines left out set some).
        let words = if grp.last > grp.first {
            merge::merged_words(&lines, moves, grp, strip_comments)
        } else {
            without_feed_words(line)
        };
        match rm.mv.kind {
            MoveKind::Line => {
                let t = block_time(from, to, feed, m);
                if t > 0.0 && t.is_finite() {
                    let scale = 10f64.powi(F_DECIMALS);
                    let f = ((60.0 / t) * scale).floor() / scale;
                    let prefix = if in_g93 { "" } else { "G93 " };
                    out.push_str(&format!("{prefix}{words} F{f}\n"));
                    in_g93 = true;
                    rewritten += 1;
                } else {
                    restore(&mut out, &mut in_g93, orig_g93, rm);
                    out.push_str(line);
                    out.push('\n');
                }
            }
            MoveKind::Rapid => {
                out.push_str(line);
                out.push('\n');
            }
            _ => {
                restore(&mut out, &mut in_g93, orig_g93, rm);
                out.push_str(line);
                out.push('\n');
            }
        }
        pos = to;
    }
    Ok((out, rewritten, merged))
}

/// Before a block kept as written: the input's feed mode (and, in G94, its feed) again.
fn restore(out: &mut String, in_g93: &mut bool, orig_g93: bool, rm: &ReadMove) {
    if *in_g93 == orig_g93 {
        return;
    }
    if orig_g93 {
        out.push_str("G93\n");
    } else {
        let per_min = rm.mv.feed * 60.0 / rm.modal.units.mm_per_unit();
        out.push_str(&format!("G94 F{}\n", fmt_feed(per_min)));
    }
    *in_g93 = orig_g93;
}

fn fmt_feed(v: f64) -> String {
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// The output's moves against the input's: same kinds, same end points (a straight block
/// may end a run of input blocks whose end points lie within `tol` of its chord), feeds no
/// higher, no joint over its velocity limit on a straight feed block.
fn check_same_path(
    input: &[ReadMove],
    output: &[ReadMove],
    m: &Machine,
    tol: Option<MergeTolerance>,
) -> Result<(), Error> {
    let bad = |line: usize, what: &str| {
        Err(Error::internal(format!(
            "optimize: line {line} of the rewrite {what}"
        )))
    };
    let end = |rm: &ReadMove, rot: Rotary| (rm.mv.to, rm.mv.rotary.unwrap_or(rot));
    let same = |p: (Point3, Rotary), q: (Point3, Rotary)| {
        p.0.distance(q.0) <= SAME_POINT_MM && p.1.distance(q.1) <= SAME_POINT_MM
    };
    let mut rot_in = Rotary::default();
    let mut rot = Rotary::default();
    let mut from = Point3::new(0.0, 0.0, 0.0);
    let mut i = 0;
    for b in output {
        if i >= input.len() {
            return bad(b.line, "has more moves than the input");
        }
        let rb = b.mv.rotary.unwrap_or(rot);
        let target = (b.mv.to, rb);
        // The input moves this output move stands for: up to the one ending where it ends.
        let mut j = i;
        let mut r = rot_in;
        let mut mids = Vec::new();
        loop {
            let Some(a) = input.get(j) else {
                return bad(b.line, "ends where no input move ends");
            };
            let e = end(a, r);
            if same(e, target) {
                r = e.1;
                break;
            }
            if tol.is_none()
                || !matches!(a.mv.kind, MoveKind::Line)
                || !matches!(b.mv.kind, MoveKind::Line)
            {
                return bad(b.line, &format!("is not the input's line {} move", a.line));
            }
            mids.push(e);
            r = e.1;
            j += 1;
        }
        let a = &input[j];
        let same_kind = std::mem::discriminant(&a.mv.kind) == std::mem::discriminant(&b.mv.kind);
        let same_arc = match (a.mv.kind, b.mv.kind) {
            (MoveKind::Arc { .. }, MoveKind::Arc { .. }) => a.mv.kind == b.mv.kind,
            _ => true,
        };
        if !same_kind || !same_arc || a.mv.corner != b.mv.corner {
            return bad(b.line, &format!("is not the input's line {} move", a.line));
        }
        if let Some(t) = tol {
            let chord = ((from, rot), target);
            for (k, p) in mids.iter().enumerate() {
                if !matches!(input[i + k].mv.kind, MoveKind::Line)
                    || merge::chord_distance(chord.0, chord.1, *p, t) > 1.0 + 1e-9
                {
                    return bad(
                        b.line,
                        &format!(
                            "leaves line {}'s end point off its tolerance",
                            input[i + k].line
                        ),
                    );
                }
            }
        }
        let slowest = input[i..=j]
            .iter()
            .map(|a| a.mv.feed)
            .fold(f64::INFINITY, f64::min);
        if !matches!(a.mv.kind, MoveKind::Rapid) && b.mv.feed > slowest * (1.0 + 1e-9) {
            return Err(Error::internal(format!(
                "optimize: line {} would run at {} mm/s, above the programmed {} mm/s",
                b.line, b.mv.feed, slowest
            )));
        }
        if matches!(b.mv.kind, MoveKind::Line) && b.mv.feed > 0.0 {
            // The block's time at the feed the reader found in the rewrite, not the rewrite's.
            let d = (b.mv.to - from).to_array();
            let rr = [rb.a - rot.a, rb.b - rot.b, rb.c - rot.c];
            let xyz = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let len = if xyz > 1e-9 { xyz } else { rb.distance(rot) };
            let t = len / b.mv.feed;
            let over =
                d.iter()
                    .zip(&m.axes)
                    .any(|(x, l)| x.abs() > l.max_velocity * t * (1.0 + 1e-9))
                    || rr.iter().zip(&m.rotary).any(|(x, l)| {
                        l.is_some_and(|l| x.abs() > l.max_velocity * t * (1.0 + 1e-9))
                    });
            if over && b.mv.feed < slowest * (1.0 - 1e-9) {
                return Err(Error::internal(format!(
                    "optimize: line {} would drive a joint over its velocity limit",
                    b.line
                )));
            }
        }
        rot_in = r;
        rot = rb;
        from = b.mv.to;
        i = j + 1;
    }
    if i != input.len() {
        return Err(Error::internal(format!(
            "optimize: the rewrite has fewer moves than the input (it ends at the input's move {i} of {})",
            input.len()
        )));
    }
    Ok(())
}
