//! The G-code writer: a [`Toolpath`] streamed to any [`Write`] in one of four dialects.
//!
//! See the [module docs](super) for what each dialect gets. The writer keeps the modal state
//! it has emitted (motion code, plane, corner mode, feed, and each axis's *rounded* position)
//! and writes a word only when it changes. Arc centre offsets are computed from the rounded
//! start the reader will see, so the centre a reader reconstructs differs from the true one by
//! the rounding of `I`/`J`/`K` alone.

use super::dialect::{Coolant, Dialect, Units};
use super::format::push_number;
use crate::error::{Error, InputError};
use crate::geom::Point3;
use crate::toolpath::{Corner, Move, MoveKind, Plane, Tool, Toolpath};

use std::io::{BufWriter, Write};

mod options;
mod sections;
pub use options::WriterOptions;
pub use sections::{ProgramSection, write_sections};

/// Largest `N` number written; numbering wraps around after it (LinuxCNC refuses N > 99999,
/// Fanuc 0i accepts five digits).
pub const MAX_LINE_NUMBER: u64 = 99_999;

/// Smallest arc radius written as G2/G3, in mm: LinuxCNC's `RADIUS_TOLERANCE` (0.00005 in =
/// 0.00127 mm) below which it calls an arc "zero radius". Smaller arcs are written as lines
/// (the chord is within one diameter, 0.0025 mm, of the arc).
pub const MIN_ARC_RADIUS_MM: f64 = 0.00127;

/// What [`write_program`] wrote.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct WriteSummary {
    /// Lines written (including `%`, comments and the header).
    pub lines: usize,
    /// Motion blocks (G0/G1/G2/G3) and dwell blocks.
    pub blocks: usize,
    /// Decimals used.
    pub decimals: u32,
    /// Arcs written as lines because they were too small or too flat to survive rounding
    /// (radius below [`MIN_ARC_RADIUS_MM`], a sweep that rounding would turn into a full
    /// circle, or a sagitta at most the output rounding: see the `arcs` part of the writer).
    pub arcs_as_lines: usize,
    /// Multi-turn arcs split into single turns (dialects without a turn count).
    pub split_turns: usize,
    /// A rapid to the toolpath's start was written before the first motion, an arc (whose
    /// centre offsets need a known start) or a canned cycle.
    pub start_rapid: bool,
    /// Canned cycles written as cycles (G81…, CYCLE81…); those a dialect lacks are written
    /// as their moves and not counted.
    pub cycles: usize,
}

/// Writes `tp` as a G-code program to `out`, streaming (nothing but one line is buffered
/// beyond [`BufWriter`]'s buffer).
///
/// The toolpath's canned cycles ([`Toolpath::cycles`]) are written as the dialect's cycles
/// (module `cycles`), their moves where it has none.
///
/// Errors: an [`InputError`] naming the move index for non-finite coordinates, a feed move
/// without a positive finite feed, a negative or non-finite dwell, or an arc that rounding to
/// the chosen decimals would make unreadable; a canned cycle whose moves are not its own
/// ([`Toolpath::check_cycles`]); a failing output (I/O error) as an input error.
pub fn write_program(
    tp: &Toolpath,
    opts: &WriterOptions,
    out: &mut dyn Write,
) -> Result<WriteSummary, Error> {
    opts.validate()?;
    tp.check_cycles()?;
    let mut w = Emitter::new(opts, out);
    w.header(Some(&tp.tool))?;
    w.moves(tp)?;
    w.footer()?;
    w.finish()
}

fn check_move(i: usize, m: &Move, from: Point3) -> Result<(), InputError> {
    let at = || format!("move {i}");
    let in_range = |p: Point3| {
        p.is_finite() && p.x.abs().max(p.y.abs()).max(p.z.abs()) <= super::interp::MAX_WORD_VALUE
    };
    if !in_range(m.to) {
        return Err(
            InputError::new("move end point", format_args!("{:?}", m.to))
                .at(at())
                .expected("finite coordinates within ±1e9 mm"),
        );
    }
    if !from.is_finite() {
        return Err(InputError::new("toolpath start", format_args!("{from:?}"))
            .at("toolpath")
            .expected("finite coordinates"));
    }
    match m.kind {
        MoveKind::Rapid => {}
        MoveKind::Line | MoveKind::Arc { .. } => {
            if !(m.feed.is_finite() && m.feed > 0.0) {
                return Err(InputError::new("feed", m.feed)
                    .at(at())
                    .expected("a finite feed > 0 mm/s on a feed move"));
            }
            if let MoveKind::Arc { center, .. } = m.kind
                && !in_range(center)
            {
                return Err(InputError::new("arc centre", format_args!("{center:?}"))
                    .at(at())
                    .expected("finite coordinates"));
            }
        }
        MoveKind::Dwell { seconds } => {
            if !(seconds.is_finite() && seconds >= 0.0) {
                return Err(InputError::new("dwell", seconds)
                    .at(at())
                    .expected("a finite time >= 0 s"));
            }
        }
    }
    let merge = match m.corner {
        Corner::BlendMerge { merge, .. } => merge,
        _ => 0.0,
    };
    if let Some(t) = m.corner.blend_tolerance()
        && !(t.is_finite() && t >= 0.0 && merge.is_finite() && merge >= 0.0)
    {
        return Err(InputError::new("blend tolerance", t)
            .at(at())
            .expected("a finite tolerance >= 0 mm"));
    }
    Ok(())
}

/// Motion codes the writer tracks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Motion {
    G0,
    G1,
    G2,
    G3,
}

/// The writer's state; shared with the five-axis writer ([`super::five_axis`]), which
/// writes its header, blocks and footer through it.
pub(super) struct Emitter<'a> {
    out: BufWriter<&'a mut dyn Write>,
    opts: &'a WriterOptions,
    line: String,
    decimals: u32,
    keep_point: bool,
    unit: f64,
    n: u64,
    summary: WriteSummary,
    motion: Option<Motion>,
    plane: Plane,
    corner: Corner,
    corner_text: String,
    feed: String,
    scratch: String,
    /// Emitted (rounded) position in program units; `None` until first written.
    pos: [Option<f64>; 3],
    first_motion: bool,
    tool: u32,
    /// Spindle speed and coolant the last tool start turned on (stopped by the footer).
    spindle_on: f64,
    coolant_on: Coolant,
    /// The run of canned cycles being written (LinuxCNC, Fanuc), until `G80`.
    cycle_run: Option<cycles::CycleRun>,
}

impl<'a> Emitter<'a> {
    pub(super) fn new(opts: &'a WriterOptions, out: &'a mut dyn Write) -> Self {
        let decimals = opts.effective_decimals();
        Emitter {
            out: BufWriter::new(out),
            opts,
            line: String::with_capacity(128),
            decimals,
            keep_point: opts.dialect.keeps_decimal_point(),
            unit: opts.units.mm_per_unit(),
            n: 0,
            summary: WriteSummary {
                decimals,
                ..WriteSummary::default()
            },
            motion: None,
            plane: Plane::Xy,
            corner: Corner::Machine,
            corner_text: String::new(),
            feed: String::new(),
            scratch: String::with_capacity(32),
            pos: [None; 3],
            first_motion: true,
            tool: 0,
            spindle_on: 0.0,
            coolant_on: Coolant::Off,
            cycle_run: None,
        }
    }

    fn dialect(&self) -> Dialect {
        self.opts.dialect
    }

    /// Starts a block (with its N number when numbering).
    pub(super) fn begin(&mut self) {
        self.line.clear();
        if self.opts.line_numbers {
            self.n += u64::from(self.opts.line_number_step.max(1));
            if self.n > MAX_LINE_NUMBER {
                self.n = u64::from(self.opts.line_number_step.max(1));
            }
            self.line.push('N');
            self.line.push_str(&self.n.to_string());
        }
    }

    pub(super) fn raw(&mut self, s: &str) {
        if !self.line.is_empty() {
            self.line.push(' ');
        }
        self.line.push_str(s);
    }

    pub(super) fn word(&mut self, letter: &str, value: f64, decimals: u32) {
        if !self.line.is_empty() {
            self.line.push(' ');
        }
        self.line.push_str(letter);
        push_number(&mut self.line, value, decimals, self.keep_point);
    }

    pub(super) fn end(&mut self) -> Result<(), Error> {
        self.line.push('\n');
        let r = self.out.write_all(self.line.as_bytes());
        self.line.clear();
        self.summary.lines += 1;
        r.map_err(io_error)
    }

    /// A line without N number (`%`, `O0001`).
    fn bare(&mut self, s: &str) -> Result<(), Error> {
        self.line.clear();
        self.line.push_str(s);
        self.end()
    }

    pub(super) fn block(&mut self, s: &str) -> Result<(), Error> {
        self.begin();
        self.raw(s);
        self.end()
    }

    pub(super) fn comment(&mut self, text: &str) -> Result<(), Error> {
        if !self.opts.comments {
            return Ok(());
        }
        let text = sanitize_comment(text, self.dialect());
        if self.dialect().semicolon_comments() {
            self.block(&format!("; {text}"))
        } else {
            self.block(&format!("({text})"))
        }
    }

    /// The program's header: framing, name and notes, units and safety block, work offset,
    /// path tolerance, tool change, spindle and coolant.
    /// `tool` is described in a comment when given (the five-axis writer has only a number).
    pub(super) fn header(&mut self, tool: Option<&Tool>) -> Result<(), Error> {
        let o = self.opts;
        self.tool = o.tool_number.or(tool.map(|t| t.number)).unwrap_or(0);
        let described = tool.map(|t| {
            (
                self.tool,
                format!("flat end mill D{} mm, {} flutes", t.diameter, t.flutes),
            )
        });
        self.header_common(described.as_slice())?;
        self.tool_start(self.tool, o.spindle_rpm, o.coolant)
    }

    /// The header up to the path tolerance: framing, name, the tools described (number and
    /// description), notes, units and safety block, work offset, path tolerance.
    pub(super) fn header_common(&mut self, tools: &[(u32, String)]) -> Result<(), Error> {
        let d = self.dialect();
        let o = self.opts;
        if d == Dialect::Fanuc {
            self.bare("%")?;
            let mut l = format!("O{:04}", o.program_number);
            if let Some(name) = &o.program_name
                && o.comments
            {
                l.push_str(&format!(" ({})", sanitize_comment(name, d)));
            }
            self.bare(&l)?;
        } else if let Some(name) = &o.program_name {
            self.comment(name)?;
        }
        self.comment(&format!(
            "millpath {} - dialect {d}, units {}, {} decimals",
            env!("CARGO_PKG_VERSION"),
            o.units,
            self.decimals
        ))?;
        for (number, description) in tools {
            self.comment(&format!("tool T{number}: {description}"))?;
        }
        for note in &o.header_notes {
            self.comment(note)?;
        }
        let units = match (d, o.units) {
            (Dialect::Sinumerik, Units::Mm) => "G710",
            (Dialect::Sinumerik, Units::Inch) => "G700",
            (_, Units::Mm) => "G21",
            (_, Units::Inch) => "G20",
        };
        let safety = match d {
            Dialect::LinuxCnc => format!("G17 {units} G90 G91.1 G94 G40 G49 G80"),
            Dialect::Fanuc => format!("G17 {units} G90 G94 G40 G49 G80"),
            Dialect::Sinumerik => format!("G17 {units} G90 G94 G40"),
            Dialect::Grbl => format!("G17 {units} G90 G94"),
        };
        self.block(&safety)?;
        self.block(&format!("G{}", o.work_offset))?;
        if let Some(t) = o.path_tolerance {
            match d {
                Dialect::LinuxCnc | Dialect::Sinumerik => self.corner_block(Corner::Blend(t))?,
                Dialect::Fanuc if self.rounds_to_zero(t) => {
                    self.corner_block(Corner::ExactStop)?;
                }
                Dialect::Fanuc => {
                    self.comment(&format!(
                        "path tolerance {t} mm: AI contour control parameters"
                    ))?;
                    self.block("G05.1 Q1")?;
                    self.corner_text = "G64".to_string();
                }
                Dialect::Grbl => {
                    self.comment(&format!("path tolerance {t} mm: not programmable in grbl"))?;
                }
            }
            // Moves with `Corner::Machine` run in the mode just set.
            self.corner = Corner::Machine;
        }
        Ok(())
    }

    /// Loads tool `tool` (`T n M6`, a comment on Grbl) when the options write tool changes,
    /// and starts the spindle and the coolant. The next motion block carries the tool length
    /// compensation and every axis (the tool's length offset changes what Z means).
    pub(super) fn tool_start(
        &mut self,
        tool: u32,
        rpm: f64,
        coolant: Coolant,
    ) -> Result<(), Error> {
        let d = self.dialect();
        let o = self.opts;
        let changed = self.tool != 0 && self.tool != tool;
        self.tool = tool;
        self.first_motion = true;
        self.pos = [None; 3];
        self.spindle_on = rpm;
        self.coolant_on = coolant;
        if o.tool_change && self.tool > 0 {
            if d == Dialect::Grbl {
                self.comment(&format!(
                    "tool change: load T{} by hand, grbl has no tool-change command",
                    self.tool
                ))?;
                if changed {
                    // The operator changes the tool during the pause.
                    self.block("M0")?;
                }
            } else {
                self.block(&format!("T{} M6", self.tool))?;
            }
        }
        if rpm > 0.0 {
            self.begin();
            self.raw(&format!("S{}", num(rpm, 0, false)));
            self.raw(if o.spindle_cw { "M3" } else { "M4" });
            self.end()?;
        }
        match coolant {
            Coolant::Off => Ok(()),
            Coolant::Flood => self.block("M8"),
            Coolant::Mist => self.block("M7"),
        }
    }

    /// Stops the coolant and the spindle that [`Emitter::tool_start`] started.
    pub(super) fn tool_stop(&mut self) -> Result<(), Error> {
        if self.coolant_on != Coolant::Off {
            self.block("M9")?;
            self.coolant_on = Coolant::Off;
        }
        if self.spindle_on > 0.0 {
            self.block("M5")?;
            self.spindle_on = 0.0;
        }
        Ok(())
    }

    pub(super) fn footer(&mut self) -> Result<(), Error> {
        let d = self.dialect();
        self.tool_stop()?;
        if d == Dialect::Fanuc
            && self
                .opts
                .path_tolerance
                .is_some_and(|t| !self.rounds_to_zero(t))
        {
            self.block("G05.1 Q0")?;
        }
        match d {
            Dialect::LinuxCnc | Dialect::Grbl => self.block("M2")?,
            Dialect::Fanuc | Dialect::Sinumerik => self.block("M30")?,
        }
        if d == Dialect::Fanuc {
            self.bare("%")?;
        }
        Ok(())
    }

    pub(super) fn finish(mut self) -> Result<WriteSummary, Error> {
        self.out.flush().map_err(io_error)?;
        Ok(self.summary)
    }

    /// Decimals of a written tolerance: at least 6.
    fn tolerance_decimals(&self) -> u32 {
        self.decimals.max(6)
    }

    /// A tolerance in mm as written: in program units, rounded *down* to
    /// [`Emitter::tolerance_decimals`], so the controller never gets a looser one.
    fn tolerance_in_units(&self, t: f64) -> f64 {
        let scale = 10f64.powi(self.tolerance_decimals() as i32);
        (t / self.unit * scale + 1e-6).floor() / scale
    }

    /// True when tolerance `t` (mm) is written as 0: exact stop, never `G64 P0` (LinuxCNC
    /// blends without any limit under `G64 P0`, `tc.c` `tcFindBlendTolerance`).
    fn rounds_to_zero(&self, t: f64) -> bool {
        self.tolerance_in_units(t) <= 0.0
    }

    /// The block that selects `corner`, if the dialect has one.
    fn corner_block(&mut self, corner: Corner) -> Result<(), Error> {
        let d = self.dialect();
        // Tolerances are in mm inside and in program units in the text.
        let dec = self.tolerance_decimals();
        let pt = self.opts.path_tolerance.map(|t| self.tolerance_in_units(t));
        let corner_in_units = match corner {
            Corner::Blend(t) if self.rounds_to_zero(t) => Corner::ExactStop,
            Corner::Blend(t) => Corner::Blend(self.tolerance_in_units(t)),
            Corner::Machine if pt.is_some_and(|t| t <= 0.0) => Corner::ExactStop,
            Corner::BlendMerge { tolerance, merge } if d == Dialect::LinuxCnc => {
                Corner::BlendMerge {
                    tolerance: self.tolerance_in_units(tolerance),
                    merge: self.tolerance_in_units(merge),
                }
            }
            // Other dialects have no merge tolerance: the blend alone.
            Corner::BlendMerge { tolerance, .. } => {
                Corner::Blend(self.tolerance_in_units(tolerance))
            }
            c => c,
        };
        let text = match (d, corner_in_units) {
            (Dialect::Grbl, _) => return Ok(()),
            (Dialect::LinuxCnc, Corner::ExactStop) => "G61.1".to_string(),
            (Dialect::LinuxCnc, Corner::ExactPath) => "G61".to_string(),
            (Dialect::LinuxCnc, Corner::Blend(t)) => format!("G64 P{}", num(t, dec, false)),
            (Dialect::LinuxCnc, Corner::BlendMerge { tolerance, merge }) => format!(
                "G64 P{} Q{}",
                num(tolerance, dec, false),
                num(merge, dec, false)
            ),
            (Dialect::LinuxCnc, Corner::Machine) => match pt {
                Some(t) => format!("G64 P{}", num(t, dec, false)),
                None => "G64".to_string(),
            },
            (Dialect::Fanuc, Corner::ExactStop | Corner::ExactPath) => "G61".to_string(),
            (Dialect::Fanuc, Corner::Blend(_) | Corner::BlendMerge { .. } | Corner::Machine) => {
                "G64".to_string()
            }
            (Dialect::Sinumerik, Corner::ExactStop) => "G60".to_string(),
            (Dialect::Sinumerik, Corner::ExactPath) => "G64".to_string(),
            (Dialect::Sinumerik, Corner::Blend(t) | Corner::BlendMerge { tolerance: t, .. }) => {
                format!("CYCLE832({},_FINISH,1)", num(t, dec, false))
            }
            (Dialect::Sinumerik, Corner::Machine) => match pt {
                Some(t) => format!("CYCLE832({},_FINISH,1)", num(t, dec, false)),
                None => "G642".to_string(),
            },
        };
        self.corner = corner;
        if text == self.corner_text {
            return Ok(());
        }
        self.block(&text)?;
        self.corner_text = text;
        Ok(())
    }

    fn set_corner(&mut self, corner: Corner) -> Result<(), Error> {
        if !same_corner(self.corner, corner) {
            self.corner_block(corner)?;
        }
        Ok(())
    }

    fn motion_word(&mut self, m: Motion) {
        if self.motion != Some(m) {
            self.raw(match m {
                Motion::G0 => "G0",
                Motion::G1 => "G1",
                Motion::G2 => "G2",
                Motion::G3 => "G3",
            });
            self.motion = Some(m);
        }
    }

    /// Tool length compensation on the first motion block.
    pub(super) fn first_motion_words(&mut self, tool: u32) {
        if !self.first_motion {
            return;
        }
        self.first_motion = false;
        if self.opts.tool_change && tool > 0 {
            match self.dialect() {
                Dialect::LinuxCnc => self.raw("G43"),
                Dialect::Fanuc => self.raw(&format!("G43 H{tool}")),
                Dialect::Sinumerik | Dialect::Grbl => {}
            }
        }
    }

    /// Writes axis `axis` (0 = X) at `mm` if it changed (or `force`); returns the rounded
    /// value in program units.
    fn axis(&mut self, axis: usize, mm: f64, force: bool) -> f64 {
        let v = mm / self.unit;
        // Format once; the reader's value is the parse of exactly this text.
        self.scratch.clear();
        push_number(&mut self.scratch, v, self.decimals, self.keep_point);
        let rounded: f64 = self.scratch.parse().unwrap_or(v);
        let known = self.pos.get(axis).copied().flatten();
        if force || known.is_none_or(|k| k.to_bits() != rounded.to_bits()) {
            if !self.line.is_empty() {
                self.line.push(' ');
            }
            self.line
                .push_str(["X", "Y", "Z"].get(axis).copied().unwrap_or("X"));
            self.line.push_str(&self.scratch);
        }
        if let Some(p) = self.pos.get_mut(axis) {
            *p = Some(rounded);
        }
        rounded
    }

    fn feed_word(&mut self, feed_mm_s: f64) {
        let f = feed_mm_s * 60.0 / self.unit;
        self.scratch.clear();
        push_number(&mut self.scratch, f, self.decimals, self.keep_point);
        if self.scratch != self.feed {
            if !self.line.is_empty() {
                self.line.push(' ');
            }
            self.line.push('F');
            self.line.push_str(&self.scratch);
            std::mem::swap(&mut self.feed, &mut self.scratch);
        }
    }

    /// Rounded emitted position, or `from` rounded when nothing was written yet.
    fn emitted(&self, from: Point3) -> [f64; 3] {
        let f = [from.x, from.y, from.z];
        let mut r = [0.0; 3];
        for (k, out) in r.iter_mut().enumerate() {
            let fallback = round(f.get(k).copied().unwrap_or(0.0) / self.unit, self.decimals);
            *out = self.pos.get(k).copied().flatten().unwrap_or(fallback);
        }
        r
    }

    /// Every move of `tp`, checked ([`check_move`]) as it is written.
    pub(super) fn moves(&mut self, tp: &Toolpath) -> Result<(), Error> {
        let mut from = tp.start;
        let mut cycles = tp.cycles.iter().peekable();
        let mut i = 0;
        while let Some(m) = tp.moves.get(i) {
            if let Some(c) = cycles.next_if(|c| c.start == i) {
                let run = tp.moves.get(c.start..c.end).unwrap_or_default();
                self.canned_cycle(i, c, run, from)?;
                from = run.last().map_or(from, |m| m.to);
                i = c.end.max(i + 1);
                continue;
            }
            self.end_cycle_run()?;
            check_move(i, m, from)?;
            self.motion(i, m, from)?;
            from = m.to;
            i += 1;
        }
        self.end_cycle_run()?;
        Ok(())
    }

    fn motion(&mut self, i: usize, m: &Move, from: Point3) -> Result<(), Error> {
        match m.kind {
            MoveKind::Dwell { seconds } => self.dwell(seconds),
            MoveKind::Rapid => {
                self.set_corner(m.corner)?;
                self.linear(Motion::G0, m, 0.0)
            }
            MoveKind::Line => {
                self.set_corner(m.corner)?;
                self.linear(Motion::G1, m, m.feed)
            }
            MoveKind::Arc { .. } => {
                self.set_corner(m.corner)?;
                self.arc(i, m, from)
            }
        }
    }

    fn linear(&mut self, motion: Motion, m: &Move, feed: f64) -> Result<(), Error> {
        self.begin();
        self.motion_word(motion);
        self.first_motion_words(self.tool_number());
        let force = self.pos.iter().any(Option::is_none);
        let before = self.line.len();
        let c = [m.to.x, m.to.y, m.to.z];
        for (k, v) in c.iter().enumerate() {
            self.axis(k, *v, force);
        }
        if self.line.len() == before {
            // A zero-length move after rounding: still one block, so readers see one move.
            self.axis(0, m.to.x, true);
        }
        if motion == Motion::G1 {
            self.feed_word(feed);
        }
        self.summary.blocks += 1;
        self.end()
    }

    /// Counts a motion or dwell block the caller wrote.
    pub(super) fn count_block(&mut self) {
        self.summary.blocks += 1;
    }

    fn tool_number(&self) -> u32 {
        self.tool
    }

    pub(super) fn dwell(&mut self, seconds: f64) -> Result<(), Error> {
        let dec = self.decimals.max(3);
        self.begin();
        match self.dialect() {
            Dialect::LinuxCnc | Dialect::Grbl => {
                self.raw(&format!("G4 P{}", num(seconds, dec, false)));
            }
            Dialect::Fanuc => self.raw(&format!("G04 X{}", num(seconds, dec, true))),
            Dialect::Sinumerik => self.raw(&format!("G4 F{}", num(seconds, dec, false))),
        }
        self.summary.blocks += 1;
        self.end()
    }
}

mod arcs;
mod cycles;

/// `v` rounded to `decimals` as a reader of the printed value gets it.
fn round(v: f64, decimals: u32) -> f64 {
    super::format::round_to(v, decimals)
}

fn num(v: f64, decimals: u32, keep_point: bool) -> String {
    super::format::format_number(v, decimals, keep_point)
}

/// Corners compare by mode, and blends by tolerance.
fn same_corner(a: Corner, b: Corner) -> bool {
    match (a, b) {
        (Corner::Blend(x), Corner::Blend(y)) => (x - y).abs() <= 1e-12,
        (
            Corner::BlendMerge {
                tolerance: x,
                merge: p,
            },
            Corner::BlendMerge {
                tolerance: y,
                merge: q,
            },
        ) => (x - y).abs() <= 1e-12 && (p - q).abs() <= 1e-12,
        _ => a == b,
    }
}

/// Comment text safe for the dialect: no line breaks, no parentheses inside `( )`, no `%`;
/// upper case for Fanuc.
fn sanitize_comment(text: &str, dialect: Dialect) -> String {
    let paren = !dialect.semicolon_comments();
    let s: String = text
        .chars()
        .map(|c| match c {
            '\n' | '\r' | '\t' => ' ',
            '(' | ')' if paren => ' ',
            '%' => ' ',
            c if c.is_control() => ' ',
            c => c,
        })
        .collect();
    if dialect == Dialect::Fanuc {
        s.to_uppercase()
    } else {
        s
    }
}

fn io_error(e: std::io::Error) -> Error {
    InputError::new("G-code output", e)
        .expected("a destination that accepts the whole program")
        .into()
}
