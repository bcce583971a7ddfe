//! The modal interpreter: lexed words of one block → moves, with the modal state carried
//! from block to block.
//!
//! # Modal rules
//! Within a block the order of execution is RS274/NGC's (LinuxCNC's "order of execution"):
//! feed mode (G93/G94/G95) → F → units (G20/G21; in the other dialects units come before F,
//! so that `G20 F10` means 10 in/min) → S → T → M6 → M3/M4/M5 → M7/M8/M9 → dwell
//! (G4) → plane (G17–G19) → cutter compensation off (G40) → tool length (G43/G49) →
//! work offset (G54–G59) → path mode (G61, G61.1, G64; G60/G642/CYCLE832 on Sinumerik) →
//! distance mode (G90/G91) → arc-centre mode (G90.1/G91.1) → G53 → motion (G0–G3, G80) →
//! program end (M2/M30; the reader stops there). A block may therefore yield a dwell and a
//! move, in that order.
//!
//! * Motion (G0–G3) is modal: axis words without a motion code move in the last one; after
//!   G80 (or before any motion code) axis words are an error.
//! * F is modal in G94 (units per minute, converted to mm/s when it is read, in the units then
//!   active). In G93 (inverse time) each feed move needs its own F (1/min: the move takes
//!   60/F s) and the move's feed becomes `length · F / 60` mm/s. Switching G93/G94 forgets F,
//!   so the next feed move needs a new F. A feed move without F, or with F ≤ 0, is an error
//!   naming the line.
//! * Work offsets G54–G59.3 come from the parameters (a `.var` file,
//!   [`ReaderOptions::parameters`], or [`ReaderOptions::work_offsets`]) and G10 L2/L20; G92
//!   adds its offset; G43 (H) the tool table's length offset (module `offsets`). Positions
//!   are machine positions: program position plus the active offsets. G53 moves the block in
//!   machine coordinates (G90 only).
//! * Corner modes: G61.1 → exact stop, G61 → exact path (Fanuc: exact stop, its G61 is the
//!   exact stop check mode), `G64 P t` → blend within t (LinuxCNC; `G64 P t Q q` with q ≠ t →
//!   [`Corner::BlendMerge`]: q is the merge tolerance of LinuxCNC's naive-CAM detector, which
//!   defaults to P), G64 without P → machine (LinuxCNC, Fanuc, Grbl; Sinumerik:
//!   exact path, its G64 is continuous path without rounding), G60 → exact stop, G642 →
//!   machine, `CYCLE832(t, …)` → blend within t (`CYCLE832(0,_OFF,…)` → machine), G9/G09 →
//!   exact stop for its block only. Dwells are exact stops.
//! * Dwell: `G4 P` seconds (Fanuc: milliseconds), `G4 X` seconds (Fanuc), `G4 F` seconds
//!   (Sinumerik; F in a G4 block is no feed).
//! * Arcs: `I J K` centre offsets, incremental (G91.1, default) or absolute (G90.1), or `R`
//!   (negative for more than half a turn); a full circle is end = start with offsets; `P n`
//!   (LinuxCNC: n turns in all) or `TURN=n` (Sinumerik: n extra full turns) makes a
//!   multi-turn arc (`turns` = n − 1, resp. n); an axis move along the plane's normal
//!   makes a helix. Radii are checked with LinuxCNC's rule ([`super::arc`]).
//! * Cutter radius compensation (LinuxCNC: G40/G41/G42/G41.1/G42.1 with D, module
//!   `cutter_comp`): the reader's position stays the programmed point; the moves put out are
//!   the tool centre's, each held until the next move decides its end.
//! * Accepted and without effect on motion: N, O (program number), S, T, D (outside G41/G42),
//!   H, M0/M1, M3–M9, G40 (other dialects), G80, `G05.1 Q`, comments, `%`, and `/` lines (skipped only when
//!   [`ReaderOptions::block_delete`] is on); in LinuxCNC programs also G7/G8, G96/G97,
//!   M48–M53, M61–M66 (module `machine_codes`) and M70–M73 (module `modal_save`).
//! * LinuxCNC's and Fanuc's canned cycles G73, G81, G82, G83 (LinuxCNC also G85, G89;
//!   module `cycles`), Sinumerik's CYCLE81, CYCLE82, CYCLE83 (module `sinumerik_cycles`),
//!   polar words, rotated systems (module `rotation`), splines G5, G5.1, G5.2 (module `nurbs`) and LinuxCNC master's G6.2 NURBS
//!   (module `g6_nurbs`) expand into ordinary moves.
//! * LinuxCNC's spindle-synchronised G33, G33.1 and feed per revolution G95 (module
//!   `spindle_sync`: speed = pitch or F × the commanded S) and straight probes G38.2–G38.5
//!   (module `probe`: to the target, as LinuxCNC's standalone interpreter models them) are
//!   feed moves.
//! * Rotary axes A, B, C (LinuxCNC, in degrees, absolute in G90 and incremental in G91;
//!   work offsets and G92 do not move them): a move that turns them carries where they end
//!   ([`Move::rotary`], in radians) beside its X Y Z path. Feeds follow RS274/NGC
//!   (`emccanon.cc`, `interp_inverse.cc`): F is along the X Y Z path when X Y Z move, and in
//!   degrees per minute along the rotary chord `√(ΔA² + ΔB² + ΔC²)` when only rotary axes
//!   move (that move's feed is in rad/s); in G93 the block takes 60/F s along whichever of
//!   the two is its length.
//! * Anything else is refused with its line and word, or skipped with a warning when
//!   [`ReaderOptions::lenient`].

use super::arc::ArcProblem;
use super::dialect::{Dialect, Units};
use super::params::{ParamFile, Store};
use super::tools::ToolTable;
use crate::geom::{Point3, Vec3};
use crate::toolpath::{Corner, Move, Plane};

/// How the reader reads. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ReaderOptions {
    /// The dialect: decides what G64, G61, `G4 P` and G70/G71 mean.
    pub dialect: Dialect,
    /// Skip unsupported words with a warning instead of refusing them.
    pub lenient: bool,
    /// Where the tool is before the first move (machine coordinates, mm).
    pub start: Point3,
    /// Offsets of G54..G59 in mm (zero by default).
    pub work_offsets: [Vec3; 6],
    /// The block-delete switch: when on, lines starting with `/` are skipped.
    pub block_delete: bool,
    /// Name of the source for messages (`part.ngc`).
    pub origin: String,
    /// Emit a dwell of this many seconds where LinuxCNC's task waits for the motion to stop
    /// before it goes on, once the program has moved: spindle, coolant and tool commands
    /// (M3–M9, an S that changes the speed, G43/G49) before the block's motion, M0/M1 after
    /// it (`emcTaskCheckPreconditions`). Set it (to the machine's
    /// [`crate::machine::Machine::sync_wait`]) when timing for a LinuxCNC controller; other
    /// controllers output such functions without stopping the path.
    pub sync_points: Option<f64>,
    /// Emit a dwell of this many seconds at every tool change (`M6`) that changes the tool:
    /// the machine's tool change time ([`crate::machine::Machine::tool_change_time`]) when
    /// timing a program. The program's first `M6` is free (its tool is in the spindle when
    /// the program starts: loading it is part of the setup), as is an `M6` of the tool
    /// already loaded. `None` (the default) reads every `M6` as taking no time.
    pub tool_change_time: Option<f64>,
    /// The tool table (LinuxCNC `tool.tbl`): G43 applies its length offsets, and a T word
    /// must name one of its tools. Without one, tool length offsets are zero.
    pub tool_table: Option<std::sync::Arc<ToolTable>>,
    /// Folders searched for a subroutine file `NAME.ngc` (after the program's own folder,
    /// which the caller puts first when it has one); in the Fanuc dialect for subprogram
    /// files `O1000.nc` or `1000.nc` (module `fanuc`).
    pub subroutine_path: Vec<std::path::PathBuf>,
    /// Parameters from a LinuxCNC `.var` file (the persistent range: work offsets, G92, …),
    /// in mm. Without one, G54..G59 take [`ReaderOptions::work_offsets`].
    pub parameters: Option<std::sync::Arc<ParamFile>>,
    /// Lines run inside loops and subroutines (Fanuc: and lines run again after a backward
    /// GOTO, END or M99) before the program is refused as endless, naming the loop (see
    /// the step budget in the [module docs](super#limits)).
    pub step_budget: u64,
}

/// The default [`ReaderOptions::step_budget`]: 300,000 lines run again. An endless
/// loop whose every line moves the tool then stops within seconds of estimating in a release
/// build (reader, planner and limit verifier), and a real program's loops stay far below it
/// (of LinuxCNC's own programs, its recursive fractals come closest).
pub const DEFAULT_STEP_BUDGET: u64 = 300_000;

impl Default for ReaderOptions {
    fn default() -> Self {
        ReaderOptions {
            dialect: Dialect::LinuxCnc,
            lenient: false,
            start: Point3::ORIGIN,
            work_offsets: [Vec3::ZERO; 6],
            block_delete: false,
            origin: "G-code".to_string(),
            sync_points: None,
            tool_change_time: None,
            tool_table: None,
            subroutine_path: Vec::new(),
            parameters: None,
            step_budget: DEFAULT_STEP_BUDGET,
        }
    }
}

option_builders! {
    ReaderOptions;
    /// Sets [`ReaderOptions::dialect`].
    with_dialect => dialect: Dialect;
    /// Sets [`ReaderOptions::lenient`].
    with_lenient => lenient: bool;
    /// Sets [`ReaderOptions::start`], machine coordinates, mm.
    with_start => start: Point3;
    /// Sets [`ReaderOptions::work_offsets`], mm.
    with_work_offsets => work_offsets: [Vec3; 6];
    /// Sets [`ReaderOptions::block_delete`].
    with_block_delete => block_delete: bool;
    /// Sets [`ReaderOptions::sync_points`], s.
    with_sync_points => sync_points: Option<f64>;
    /// Sets [`ReaderOptions::tool_change_time`], s.
    with_tool_change_time => tool_change_time: Option<f64>;
    /// Sets [`ReaderOptions::tool_table`].
    with_tool_table => tool_table: Option<std::sync::Arc<ToolTable>>;
    /// Sets [`ReaderOptions::subroutine_path`].
    with_subroutine_path => subroutine_path: Vec<std::path::PathBuf>;
    /// Sets [`ReaderOptions::parameters`], mm.
    with_parameters => parameters: Option<std::sync::Arc<ParamFile>>;
    /// Sets [`ReaderOptions::step_budget`], lines.
    with_step_budget => step_budget: u64;
}

impl ReaderOptions {
    /// Sets [`ReaderOptions::origin`].
    #[must_use]
    pub fn with_origin(mut self, origin: impl Into<String>) -> Self {
        self.origin = origin.into();
        self
    }
}

/// Feed mode (G94 units per minute or G93 inverse time).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FeedMode {
    /// G94.
    #[default]
    PerMinute,
    /// G93.
    InverseTime,
    /// G95 (LinuxCNC): units per spindle revolution (module `spindle_sync`).
    PerRevolution,
}

/// The modal state that matters downstream, as it was for a move.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Modal {
    /// Program units.
    pub units: Units,
    /// Feed mode.
    pub feed_mode: FeedMode,
    /// Active plane.
    pub plane: Plane,
    /// G90 (true) or G91.
    pub absolute: bool,
    /// The corner mode in effect (before a per-block G9).
    pub corner: Corner,
    /// Tool number (after the last M6; 0 before).
    pub tool: u32,
    /// Spindle speed in rev/min (0 when stopped).
    pub spindle_rpm: f64,
}

/// A move read from a program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReadMove {
    /// The move, in mm and mm/s.
    pub mv: Move,
    /// Its line number (1-based).
    pub line: usize,
    /// The modal state it ran in.
    pub modal: Modal,
}

/// The interpreter's state between blocks.
#[derive(Debug, Clone)]
pub(crate) struct State {
    pub(crate) modal: Modal,
    pos: Point3,
    motion: Option<u16>,
    /// Feed in mm/s (G94) or the last F number (G93); `None` when unset.
    feed: Option<f64>,
    /// The last F number as written (LinuxCNC's `#<_feed>`: not converted by G20/G21).
    f_word: f64,
    /// Where the rotary axes A, B, C stand (rad; LinuxCNC programs only).
    rotary: crate::toolpath::Rotary,
    arc_absolute: bool,
    /// The active work coordinate system, 0..9 for G54..G59.3.
    system: usize,
    /// Its origin (mm).
    origin: Vec3,
    /// The G92 offset (mm).
    g92: Vec3,
    spindle_set: f64,
    pending_tool: u32,
    /// The tool the last `M6` loaded (`None` before the first).
    loaded_tool: Option<u32>,
    /// The active tool length offset (G43), mm.
    pub(crate) tool_offset: Vec3,
    tool_table: Option<std::sync::Arc<ToolTable>>,
    /// A motion has been emitted (sync points before the first one do nothing).
    moved: bool,
    pub(crate) ended: bool,
    /// G7 (diameter mode) in effect.
    diameter: bool,
    /// G96 in effect: its speed limit D (0 without one).
    css: Option<f64>,
    /// The canned cycles' modal numbers.
    cyc: cycles::CycleState,
    /// The active system's XY rotation (rad).
    rotation: f64,
    /// A NURBS being read (G5.2).
    nurbs: Option<nurbs::NurbsState>,
    /// The last G5's P Q.
    spline: nurbs::SplineState,
    /// A G6.2 NURBS being read.
    g6: Option<g6_nurbs::G6State>,
    /// The end of the last probe move (program mm), for #5061–#5063 (module `probe`).
    probed: Option<[f64; 3]>,
    /// Modal states saved by M70/M73.
    saved: Vec<modal_save::Saved>,
    /// Cutter radius compensation (G41/G42), while it is on or has moves queued.
    comp: Option<Box<cutter_comp::Comp>>,
    /// Warnings of the last block (lenient mode), for the reader to collect.
    pub(crate) notes: Vec<String>,
}

impl State {
    pub(crate) fn new(opts: &ReaderOptions) -> Self {
        State {
            modal: Modal {
                absolute: true,
                ..Modal::default()
            },
            pos: opts.start,
            motion: None,
            feed: None,
            f_word: 0.0,
            rotary: crate::toolpath::Rotary::default(),
            arc_absolute: false,
            system: 0,
            origin: Vec3::ZERO,
            g92: Vec3::ZERO,
            spindle_set: 0.0,
            pending_tool: 0,
            loaded_tool: None,
            tool_offset: Vec3::ZERO,
            tool_table: opts.tool_table.clone(),
            moved: false,
            ended: false,
            diameter: false,
            css: None,
            cyc: cycles::CycleState::default(),
            rotation: 0.0,
            nurbs: None,
            saved: Vec::new(),
            comp: None,
            spline: nurbs::SplineState::default(),
            g6: None,
            probed: None,
            notes: Vec::new(),
        }
    }

    /// The current position (machine coordinates, mm).
    pub(crate) fn position(&self) -> Point3 {
        self.pos
    }

    /// The parameter store a program starts with: the `.var` file's values, or else the
    /// work offsets of `opts` in G54..G59.
    pub(crate) fn initial_params(opts: &ReaderOptions) -> Store {
        let mut store = Store::new(opts.parameters.as_deref());
        if opts.parameters.is_none() {
            for (k, o) in opts.work_offsets.iter().enumerate() {
                let b = 5221 + 20 * k;
                store.set(b, o.x);
                store.set(b + 1, o.y);
                store.set(b + 2, o.z);
            }
        }
        store
    }

    /// The last F number as written (0 before any).
    pub(crate) fn feed_number(&self) -> f64 {
        self.f_word
    }

    fn unit(&self) -> f64 {
        self.modal.units.mm_per_unit()
    }

    /// Executes `b`; pushes the moves it makes (at most two: a dwell, then a motion).
    pub(crate) fn execute(
        &mut self,
        b: &mut Block,
        line: usize,
        opts: &ReaderOptions,
        store: &mut Store,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let dialect = opts.dialect;
        let start = out.len();
        b.take(b'N');
        b.take(b'O');
        if dialect == Dialect::LinuxCnc {
            self.diameter_mode(b);
        }
        let dwell = b.has_g(40);
        // Feed mode, then F.
        let mode = if b.has_g(930) {
            Some(FeedMode::InverseTime)
        } else if b.has_g(940) {
            Some(FeedMode::PerMinute)
        } else if b.has_g(950) {
            Some(FeedMode::PerRevolution)
        } else {
            None
        };
        if let Some(mode) = mode
            && mode != self.modal.feed_mode
        {
            self.modal.feed_mode = mode;
            self.feed = None;
        }
        // Units and F. RS274/NGC's order of execution sets the feed rate before the length
        // units (LinuxCNC: `G20 F60` after G21 is 60 mm/min); the other dialects take the units
        // first, so that `G20 F10` in one block is 10 in/min. An F read earlier keeps its
        // physical value (it is stored in mm/s).
        let units = b.g.iter().rev().find_map(|&(g, _)| match g {
            200 | 700 | 7000 => Some(Units::Inch),
            210 | 710 | 7100 => Some(Units::Mm),
            _ => None,
        });
        let f_first = dialect == Dialect::LinuxCnc;
        if !f_first && let Some(u) = units {
            self.modal.units = u;
        }
        let f_is_dwell = dwell && dialect == Dialect::Sinumerik;
        let mut block_f = None;
        if !f_is_dwell && let Some(f) = b.take(b'F') {
            if f < 0.0 {
                return Err(BlockError::new("feed", format!("F{f}"), "F >= 0"));
            }
            self.f_word = f;
            match self.modal.feed_mode {
                FeedMode::PerMinute => self.feed = Some(f * self.unit() / 60.0),
                FeedMode::PerRevolution => self.feed = Some(f * self.unit()),
                FeedMode::InverseTime => block_f = Some(f),
            }
        }
        if f_first && let Some(u) = units {
            self.modal.units = u;
        }
        let mut sync = b.m.iter().any(|m| matches!(m, 3..=9 | 66)) || b.has_g(430) || b.has_g(490);
        if let Some(s) = b.take(b'S') {
            if s < 0.0 {
                return Err(BlockError::new("spindle speed", format!("S{s}"), "S >= 0"));
            }
            sync |= (s - self.spindle_set).abs() > 0.0;
            self.spindle_set = s;
        }
        if let Some(wait) = opts.sync_points
            && sync
            && self.moved
            && !dwell
        {
            out.push(ReadMove {
                mv: Move::dwell(self.pos, wait),
                line,
                modal: self.modal,
            });
        }
        if let Some(t) = b.take(b'T') {
            if t < 0.0 || t.fract() != 0.0 {
                return Err(BlockError::new(
                    "tool",
                    format!("T{t}"),
                    "a tool number >= 0",
                ));
            }
            if let Some(table) = &self.tool_table
                && table.get(t as u32).is_none()
            {
                return Err(BlockError::new(
                    "tool",
                    format!("T{t}"),
                    format!("a tool of the tool table ({} tools)", table.len()),
                ));
            }
            self.pending_tool = t as u32;
        }
        if dialect == Dialect::LinuxCnc {
            self.machine_codes(b)?;
            if b.m.contains(&66) {
                store.set(5399, 0.0);
            }
            // M70–M73 (LinuxCNC runs them after the spindle, coolant and tool codes; here
            // before them: a block with both is not expected).
            for m in b.m.clone() {
                if (70..=73).contains(&m) {
                    self.modal_save(m, store.call_level(), store)?;
                }
            }
        }
        // D (and G41.1's L) words; what compensation refuses (module `cutter_comp`).
        let comp_words = self.cutter_comp_check(b, dialect)?;
        if b.m.contains(&6) {
            let changed = self.loaded_tool.is_some_and(|t| t != self.pending_tool);
            self.loaded_tool = Some(self.pending_tool);
            self.modal.tool = self.pending_tool;
            if let Some(t) = opts.tool_change_time
                && t > 0.0
                && changed
            {
                out.push(ReadMove {
                    mv: Move::dwell(self.pos, t),
                    line,
                    modal: self.modal,
                });
            }
        }
        if b.m.contains(&3) || b.m.contains(&4) {
            self.modal.spindle_rpm = self.spindle_speed(self.spindle_set);
        }
        if b.m.contains(&5) {
            self.modal.spindle_rpm = 0.0;
        }
        if dwell {
            let seconds = self.dwell_seconds(b, dialect)?;
            out.push(ReadMove {
                mv: Move::dwell(self.pos, seconds),
                line,
                modal: self.modal,
            });
        }
        self.modal_groups(b, dialect, store)?;
        if b.has_g(100) {
            self.g10(b, store)?;
        }
        if let Some(&(g, _)) = b.g.iter().find(|(g, _)| (920..=923).contains(g)) {
            self.g92(g, b, store)?;
        }
        let before = out.len();
        let from = self.pos;
        if let Some(&(g, _)) = b.g.iter().find(|(g, _)| matches!(g, 280 | 300)) {
            self.home(g, b, store, line, out)?;
        } else {
            self.motion(b, block_f, line, opts, out)?;
        }
        if let Some((name, args)) = b.drill_cycle.take() {
            self.sinumerik_drill(&name, &args, line, out)?;
        }
        if let Some(p) = self.probed.take() {
            self.set_probe_parameters(p, store);
        }
        // A move that goes somewhere (a zero-length G0 to where the tool is does not).
        self.moved |= out
            .get(before..)
            .unwrap_or_default()
            .iter()
            .any(|m| m.mv.is_feed() || m.mv.kind == crate::toolpath::MoveKind::Rapid)
            && out
                .get(before..)
                .unwrap_or_default()
                .iter()
                .any(|m| m.mv.length_from(from) > 1e-12);
        if let Some(wait) = opts.sync_points
            && self.moved
            && (b.m.contains(&0) || b.m.contains(&1))
        {
            out.push(ReadMove {
                mv: Move::dwell(self.pos, wait),
                line,
                modal: self.modal,
            });
        }
        self.cutter_comp_moves(comp_words, b, start, before, from, out)?;
        if b.m.contains(&2) || b.m.contains(&30) {
            self.ended = true;
        }
        Ok(())
    }

    fn modal_groups(
        &mut self,
        b: &mut Block,
        dialect: Dialect,
        store: &Store,
    ) -> Result<(), BlockError> {
        let gs = std::mem::take(&mut b.g);
        let r = self.modal_codes(&gs, b, dialect, store);
        b.g = gs;
        r?;
        if let Some(args) = b.cycle832.take() {
            self.modal.corner = cycle832(&args, self.unit())?;
        }
        Ok(())
    }

    fn modal_codes(
        &mut self,
        gs: &[(u16, usize)],
        b: &mut Block,
        dialect: Dialect,
        store: &Store,
    ) -> Result<(), BlockError> {
        for &(g, _) in gs {
            match g {
                170 => self.modal.plane = Plane::Xy,
                180 => self.modal.plane = Plane::Zx,
                190 => self.modal.plane = Plane::Yz,
                200 | 700 | 7000 => self.modal.units = Units::Inch,
                210 | 710 | 7100 => self.modal.units = Units::Mm,
                540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => {
                    self.system = match g {
                        591..=593 => usize::from(g - 591) + 6,
                        _ => usize::from((g - 540) / 10),
                    };
                    self.load_origin(store);
                }
                611 | 600 => self.modal.corner = Corner::ExactStop,
                610 if dialect == Dialect::Fanuc => self.modal.corner = Corner::ExactStop,
                610 => self.modal.corner = Corner::ExactPath,
                640 if dialect == Dialect::Sinumerik => self.modal.corner = Corner::ExactPath,
                640 => {
                    let q = b.take(b'Q');
                    let p = b.take(b'P');
                    for (word, v) in [("G64 P", p), ("G64 Q", q)] {
                        if let Some(v) = v
                            && (v.is_nan() || v < 0.0)
                        {
                            return Err(BlockError::new(word, v, "a tolerance >= 0"));
                        }
                    }
                    let u = self.unit();
                    self.modal.corner = match (p, q) {
                        _ if dialect != Dialect::LinuxCnc => Corner::Machine,
                        (None, None) => Corner::Machine,
                        // Q defaults to P (LinuxCNC's convert_control_mode).
                        (Some(p), None) => Corner::Blend(p * u),
                        (Some(p), Some(q)) if (q - p).abs() <= 0.0 => Corner::Blend(p * u),
                        (p, Some(q)) => Corner::BlendMerge {
                            tolerance: p.unwrap_or(0.0) * u,
                            merge: q * u,
                        },
                    };
                }
                6420 => self.modal.corner = Corner::Machine,
                900 => self.modal.absolute = true,
                910 => self.modal.absolute = false,
                901 => self.arc_absolute = true,
                911 => self.arc_absolute = false,
                430 => {
                    // G43 H n: tool n's offsets; G43: the tool in the spindle's (LinuxCNC's
                    // convert_tool_length_offset).
                    let h = b.take(b'H');
                    let n = match h {
                        Some(h) if h >= 0.0 && h.fract() == 0.0 && h <= f64::from(u32::MAX) => {
                            h as u32
                        }
                        Some(h) => {
                            return Err(BlockError::new("G43 H", h, "a tool number >= 0"));
                        }
                        None => self.modal.tool,
                    };
                    self.tool_offset = match &self.tool_table {
                        None => Vec3::ZERO,
                        Some(t) => match t.get(n) {
                            Some(e) => e.offset,
                            None => {
                                return Err(BlockError::new(
                                    "G43 tool",
                                    n,
                                    format!("a tool of the tool table ({} tools)", t.len()),
                                ));
                            }
                        },
                    };
                }
                490 => self.tool_offset = Vec3::ZERO,
                980 => self.cyc.old_z = true,
                990 => self.cyc.old_z = false,
                51 => {
                    b.take(b'Q');
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// `CYCLE832(tol, mode, …)`: blend within tol, or machine for `_OFF` / tol 0.
fn cycle832(args: &str, unit: f64) -> Result<Corner, BlockError> {
    let mut parts = args.split(',').map(str::trim);
    let tol = parts.next().unwrap_or("");
    let tol: f64 = tol
        .parse()
        .ok()
        .filter(|t: &f64| t.is_finite() && *t >= 0.0)
        .ok_or_else(|| BlockError::new("CYCLE832 tolerance", tol, "a number >= 0"))?;
    let mode = parts.next().unwrap_or("").to_ascii_uppercase();
    Ok(if tol == 0.0 || mode == "_OFF" || mode == "0" {
        Corner::Machine
    } else {
        Corner::Blend(tol * unit)
    })
}

mod block;
mod cutter_comp;
mod cycles;
mod g6_nurbs;
mod home;
mod machine_codes;
mod modal_save;
mod motion;
mod nurbs;
mod offsets;
mod probe;
mod rotation;
mod sinumerik_cycles;
mod spindle_sync;
pub use block::MAX_WORD_VALUE;
pub(crate) use block::{Block, BlockError, letter_index};
pub(crate) use offsets::Scope;

/// The axis indices `(u, v, normal)` of a plane (0 = X), in [`Plane::split`] order.
pub(crate) fn plane_axes(plane: Plane) -> (usize, usize, usize) {
    match plane {
        Plane::Xy => (0, 1, 2),
        Plane::Zx => (2, 0, 1),
        Plane::Yz => (1, 2, 0),
    }
}

fn arc_error(p: ArcProblem) -> BlockError {
    BlockError::new(
        "arc",
        p,
        "an arc LinuxCNC accepts (see millpath::gcode::arc)",
    )
}
