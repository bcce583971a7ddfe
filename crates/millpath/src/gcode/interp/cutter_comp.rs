//! Cutter radius compensation: `G41`/`G42` (D = a tool of the tool table, the tool in the
//! spindle without D), `G41.1`/`G42.1 D<diameter> [L<orientation>]` and `G40`, as LinuxCNC
//! 2.9's interpreter does it (`interp_convert.cc`: `convert_cutter_compensation_on/off`,
//! `convert_straight_comp1/2`, `convert_arc_comp1/2`; `interp_queue.cc`).
//!
//! # How the path is offset
//! The reader keeps the programmed path (its position is the programmed point); this module
//! turns each programmed move into the tool centre's moves, at the tool radius r to the left
//! (G41) or right (G42) of the path, in the active plane (G17 XY or G18 XZ; G19 is refused as
//! LinuxCNC refuses it). A negative radius swaps the side.
//!
//! * **Entry** (the first move after G41/G42): a line ends at the programmed end moved by r
//!   perpendicular to the line from the tool to it (the line's length must exceed r); an arc
//!   ends r off the programmed end along its radius, on a new centre so that it still starts
//!   where the tool is (`convert_arc_comp1`).
//! * **Following moves**: each move ends r off its programmed end, perpendicular to its
//!   direction there. At the corner with the move before:
//!   - convex (the tool goes round the outside, turn β > 0.05 rad): an arc of radius r about
//!     the programmed corner joins the two offset moves (a G0 gets a straight traverse
//!     instead);
//!   - concave (β < −0.05 or β > π + 0.05 rad): the previous move is cut back to where the two
//!     offset moves meet (line–line, arc–line, line–arc, arc–arc intersections); a corner
//!     where they do not meet, or where the cut-back reverses a move, is refused ("cannot be
//!     reached by the tool without gouging");
//!   - tangent (|β| ≤ 0.05): the moves join as they are.
//!
//!   So the end of each offset move depends on the next one: moves wait in a queue (with
//!   the dwells programmed after them) until the next move, G40, M0/M1/M2/M30 or the end of
//!   the program decides their end.
//! * **Arcs** are offset to radius R ± r about the same centre; the inside of an arc must be
//!   larger than the tool ("tool radius not less than arc radius with comp").
//! * **Exit** (G40): the last offset move keeps its end; the next move (which must be a line,
//!   not an arc) goes from there to its programmed end. Positions left out of the next moves
//!   are the programmed point's, until a tool change (M6) synchronises the position with the
//!   tool's, as LinuxCNC's does.
//! * **Refused while compensation is on**, as LinuxCNC refuses them: G41/G42 again, changing
//!   the plane, a tool change, G43/G49, G54–G59.3, G61/G64, G98/G99, G92/G52, G10 L2/L20 of
//!   the active system, G28/G30, canned cycles, splines, G53 moves; also inverse time (G93),
//!   which this reader does not compensate.
//!
//! # Tolerances
//! LinuxCNC's: corners are classified with 0.05 rad; the cut-back of a queued arc may grow
//! its sweep by at most 0.0254 (rad, as LinuxCNC compares it); the compensated moves are then
//! exact (to rounding). `tests/gcode_cutter_comp.rs` compares them with `rs274 -g` and
//! measures every compensated move's distance from the programmed path (= r within 1e-6 mm).
//!
//! ```text
//!  G41 (left), a convex corner:           a concave corner:
//!        ╭─── offset line 2                  offset 1 ───────┐  ← cut back to the
//!       ╱ arc r about the corner                             │    intersection
//!  ────╯ ┐ programmed path                  programmed ────┐ │ offset 2
//!  offset 1                                                │ │
//! ```

mod geometry;

use super::{Block, BlockError, ReadMove, State, plane_axes};
use crate::gcode::Dialect;
use crate::gcode::dialect::Units;
use crate::geom::Point3;
use crate::toolpath::{MoveKind, Plane};

/// Side of the path the tool is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    /// G41.
    Left,
    /// G42.
    Right,
}

/// A move (or dwell) waiting for the next move to decide its end.
#[derive(Debug, Clone, Copy)]
struct Queued {
    rm: ReadMove,
    /// LinuxCNC's direction of a queued line (its cut-back must not reverse it).
    dir: (f64, f64),
    /// LinuxCNC's `original_turns` of a queued arc: its sweep (rad), 0 for a corner arc.
    original_turns: f64,
}

/// The compensation state between blocks.
#[derive(Debug, Clone)]
pub(crate) struct Comp {
    side: Option<Side>,
    /// The tool radius (mm, ≥ 0).
    radius: f64,
    /// The lathe tool orientation (0 or 9: a mill tool).
    orientation: u8,
    /// The plane compensation was turned on in.
    plane: Plane,
    /// The next move is the entry move.
    first: bool,
    /// Where the tool centre is (after the entry move).
    current: Point3,
    queue: Vec<Queued>,
    /// LinuxCNC's `endpoint`: the start of the queued move (in-plane), and whether it is set.
    endpoint: (f64, f64),
    endpoint_valid: bool,
    /// The move after G40 must be a line.
    arc_not_allowed: bool,
    /// The end of the last move put out while it differs from the programmed point.
    tool: Option<Point3>,
}

impl Default for Comp {
    fn default() -> Self {
        Comp {
            side: None,
            radius: 0.0,
            orientation: 0,
            plane: Plane::Xy,
            first: true,
            current: Point3::ORIGIN,
            queue: Vec::new(),
            endpoint: (0.0, 0.0),
            endpoint_valid: false,
            arc_not_allowed: false,
            tool: None,
        }
    }
}

/// The compensation words of a block, taken before the block runs.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct CompWords {
    /// 400, 410, 411, 420 or 421 (G40, G41, G41.1, G42, G42.1).
    code: Option<u16>,
    d: Option<f64>,
    l: Option<f64>,
}

fn refuse(message: &str, expected: &str) -> BlockError {
    BlockError::new("cutter compensation", message, expected)
}

const OFF_FIRST: &str = "G40 (compensation off) first";

impl Comp {
    fn engaged(&self) -> bool {
        self.side.is_some() && self.radius > 0.0
    }

    /// Nothing left to do: the state can be dropped.
    fn idle(&self) -> bool {
        self.side.is_none() && self.queue.is_empty() && self.tool.is_none() && !self.arc_not_allowed
    }
}

impl State {
    /// Takes the block's D (and, with G41.1/G42.1, L) word and refuses what LinuxCNC refuses
    /// with compensation on; runs before the block changes any state.
    pub(crate) fn cutter_comp_check(
        &mut self,
        b: &mut Block,
        dialect: Dialect,
    ) -> Result<Option<CompWords>, BlockError> {
        let d = b.take(b'D');
        let code = if dialect == Dialect::LinuxCnc {
            b.g.iter()
                .map(|&(g, _)| g)
                .find(|g| matches!(g, 400 | 410 | 411 | 420 | 421))
        } else {
            None
        };
        if self.comp.is_none() && !matches!(code, Some(410 | 411 | 420 | 421)) {
            return Ok(None);
        }
        let on_before = self.comp.as_ref().is_some_and(|c| c.side.is_some());
        if !on_before
            && b.m.contains(&6)
            && let Some(comp) = &mut self.comp
            && let Some(t) = comp.tool.take()
        {
            // A tool change synchronises LinuxCNC's interpreter with the machine: after G40
            // its position becomes where the tool is, not the programmed point.
            self.pos = t;
        }
        let turning_on = matches!(code, Some(410 | 411 | 420 | 421));
        let on_after = turning_on || (on_before && code != Some(400));
        if on_before && b.m.contains(&6) {
            return Err(refuse(
                "cannot change tools with cutter radius compensation on",
                OFF_FIRST,
            ));
        }
        let plane_after =
            b.g.iter()
                .rev()
                .find_map(|&(g, _)| match g {
                    170 => Some(Plane::Xy),
                    180 => Some(Plane::Zx),
                    190 => Some(Plane::Yz),
                    _ => None,
                })
                .unwrap_or(self.modal.plane);
        if on_before && plane_after != self.modal.plane {
            return Err(refuse(
                "cannot change planes with cutter radius compensation on",
                OFF_FIRST,
            ));
        }
        if turning_on && on_before {
            return Err(refuse(
                "cannot turn cutter radius comp on when already on",
                OFF_FIRST,
            ));
        }
        if turning_on && plane_after == Plane::Yz {
            return Err(refuse(
                "cutter radius compensation in G19",
                "compensation in the XY (G17) or XZ (G18) plane, as LinuxCNC",
            ));
        }
        let l = if matches!(code, Some(411 | 421)) {
            b.take(b'L')
        } else {
            None
        };
        if l.is_some() && plane_after != Plane::Zx {
            return Err(refuse(
                "G41.1/G42.1 with an L word (lathe orientation) outside G18",
                "L only in the XZ plane (G18)",
            ));
        }
        if on_after {
            self.refused_with_comp(b)?;
        }
        Ok(Some(CompWords { code, d, l }))
    }

    /// What LinuxCNC refuses in a block that runs with compensation on.
    fn refused_with_comp(&self, b: &Block) -> Result<(), BlockError> {
        for &(g, _) in &b.g {
            let what = match g {
                430 | 431 | 490 => "cannot change tool offset with cutter radius compensation on",
                540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => {
                    "cannot change coordinate systems with cutter radius compensation on"
                }
                610 | 611 | 640 => "cannot change control mode with cutter radius compensation on",
                980 | 990 => "cannot change retract mode with cutter radius compensation on",
                520 | 920 | 921 | 922 | 923 => {
                    "cannot change axis offsets with cutter radius compensation on"
                }
                280 | 300 => "cannot use G28 or G30 with cutter radius compensation on",
                50..=52 => "cannot convert spline with cutter radius compensation on",
                930 => "inverse time feed (G93) with cutter radius compensation",
                g if super::cycles::is_cycle(g) => {
                    "cannot use canned cycles with cutter compensation on"
                }
                100 => {
                    let p = b.words[usize::from(b'P' - b'A')].unwrap_or(0.0).round();
                    let active = p == 0.0 || (p - 1.0) as usize == self.system;
                    if active {
                        "cannot change the active coordinate system with cutter radius \
                         compensation on"
                    } else {
                        continue;
                    }
                }
                _ => continue,
            };
            return Err(refuse(what, OFF_FIRST));
        }
        let axis_words = [b'X', b'Y', b'Z']
            .iter()
            .any(|&l| b.words[usize::from(l - b'A')].is_some());
        if axis_words && self.motion.is_some_and(super::cycles::is_cycle) {
            return Err(refuse(
                "cannot use canned cycles with cutter compensation on",
                OFF_FIRST,
            ));
        }
        if self.motion.is_some_and(|m| matches!(m, 50..=52)) && axis_words {
            return Err(refuse(
                "cannot convert spline with cutter radius compensation on",
                OFF_FIRST,
            ));
        }
        if self.modal.feed_mode == super::FeedMode::InverseTime {
            return Err(BlockError {
                unsupported: true,
                ..refuse(
                    "inverse time feed (G93) with cutter radius compensation",
                    "G94 while compensation is on",
                )
            });
        }
        Ok(())
    }

    /// Runs the block's G40/G41/G42 and offsets the moves the block made (`out[start..]`;
    /// the motion from `out[before..]`, programmed from `from`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn cutter_comp_moves(
        &mut self,
        words: Option<CompWords>,
        b: &Block,
        start: usize,
        before: usize,
        from: Point3,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        if words.is_none() && self.comp.is_none() {
            return Ok(());
        }
        let mut comp = self.comp.take().unwrap_or_default();
        let r = self.comp_block(
            &mut comp,
            words.unwrap_or_default(),
            b,
            start,
            before,
            from,
            out,
        );
        if !comp.idle() {
            self.comp = Some(comp);
        }
        r
    }

    #[allow(clippy::too_many_arguments)]
    fn comp_block(
        &mut self,
        comp: &mut Comp,
        words: CompWords,
        b: &Block,
        start: usize,
        before: usize,
        from: Point3,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let units = self.modal.units;
        let made = out.split_off(start.min(out.len()));
        let split = before.saturating_sub(start).min(made.len());
        let (early, rest) = made.split_at(split);
        for rm in early {
            comp.dwell(*rm, out);
        }
        match words.code {
            Some(400) => comp.off(units, out)?,
            Some(code @ (410 | 411 | 420 | 421)) => self.comp_on(comp, code, words)?,
            _ => {}
        }
        let g53 = b.has_g(530);
        for rm in rest {
            let arc = matches!(rm.mv.kind, MoveKind::Arc { .. });
            match rm.mv.kind {
                MoveKind::Dwell { .. } => {
                    comp.dwell(*rm, out);
                    continue;
                }
                _ if arc && comp.arc_not_allowed => {
                    return Err(refuse(
                        "the move just after exiting cutter compensation mode must be \
                         straight, not an arc",
                        "a line (G0/G1) after G40",
                    ));
                }
                _ => comp.arc_not_allowed = false,
            }
            if !comp.engaged() {
                comp.tool = None;
                out.push(*rm);
                continue;
            }
            if g53 {
                return Err(refuse(
                    "cannot use G53 with cutter radius compensation on",
                    OFF_FIRST,
                ));
            }
            match (comp.first, arc) {
                (true, false) => comp.straight_entry(*rm, from)?,
                (false, false) => comp.straight(*rm, from, units, out)?,
                (true, true) => comp.arc_entry(*rm, from, units)?,
                (false, true) => comp.arc(*rm, from, units, out)?,
            }
        }
        if b.m.iter().any(|m| matches!(m, 0 | 1 | 2 | 30)) {
            // convert_stop: the queue ends where the tool is.
            let at = comp.uv(comp.current);
            if comp.engaged() && !comp.first {
                comp.move_endpoint_and_flush(at, units, out)?;
            }
            comp.dequeue(out);
            if b.m.iter().any(|m| matches!(m, 2 | 30)) {
                comp.side = None;
                comp.first = true;
            }
        }
        Ok(())
    }

    fn comp_on(&self, comp: &mut Comp, code: u16, words: CompWords) -> Result<(), BlockError> {
        let unit = self.unit();
        let name = if code >= 420 { "G42" } else { "G41" };
        let (radius, orientation) = if matches!(code, 411 | 421) {
            let Some(d) = words.d else {
                return Err(refuse(
                    &format!("{name}.1 with no D word"),
                    "G41.1/G42.1 D<diameter>",
                ));
            };
            let l = words.l.unwrap_or(0.0);
            if !(0.0..=9.0).contains(&l) || l.fract() != 0.0 {
                return Err(refuse(
                    &format!("{name}.1 L{l}"),
                    "an orientation L of 0..9",
                ));
            }
            (d * unit / 2.0, l as u8)
        } else {
            let Some(table) = &self.tool_table else {
                return Err(refuse(
                    &format!("{name} without a tool table"),
                    "a tool table (--tool-table) for the tool's diameter, or G41.1/G42.1 \
                     D<diameter>",
                ));
            };
            let n = match words.d {
                None => self.modal.tool,
                Some(d) if (d - d.round()).abs() > 1e-4 => {
                    return Err(refuse(
                        &format!("{name} requires D word to be a whole number (D{d})"),
                        "D = a tool number",
                    ));
                }
                Some(d) if d < 0.0 => {
                    return Err(refuse(
                        &format!("negative D word tool radius index used (D{d})"),
                        "D = a tool number >= 0",
                    ));
                }
                Some(d) if d > f64::from(u32::MAX) => {
                    return Err(refuse(&format!("D{d}"), "D = a tool number"));
                }
                Some(d) => d.round() as u32,
            };
            let Some(tool) = table.get(n) else {
                return Err(refuse(
                    &format!("requested tool {n} not found in the tool table"),
                    &format!("a tool of the tool table ({} tools)", table.len()),
                ));
            };
            let plane = self.modal.plane;
            if plane != Plane::Zx && !matches!(tool.orientation, 0 | 9) {
                return Err(refuse(
                    &format!("{name} with lathe tool, but plane is not G18"),
                    "a lathe tool (orientation 1..8) only in G18",
                ));
            }
            (tool.diameter / 2.0, tool.orientation)
        };
        let mut side = if code >= 420 { Side::Right } else { Side::Left };
        if radius < 0.0 {
            side = match side {
                Side::Left => Side::Right,
                Side::Right => Side::Left,
            };
        }
        comp.side = Some(side);
        comp.radius = radius.abs();
        comp.orientation = orientation;
        comp.plane = self.modal.plane;
        Ok(())
    }

    /// At the end of the program: the queued moves keep their ends.
    pub(crate) fn cutter_comp_end(&mut self, out: &mut Vec<ReadMove>) {
        if let Some(comp) = &mut self.comp {
            comp.dequeue(out);
        }
    }
}

impl Comp {
    fn axes(&self) -> (usize, usize) {
        let (u, v, _) = plane_axes(self.plane);
        (u, v)
    }

    /// The in-plane coordinates of `p` (LinuxCNC's first and second: X Y in G17, Z X in G18).
    fn uv(&self, p: Point3) -> (f64, f64) {
        let (u, v) = self.axes();
        let a = [p.x, p.y, p.z];
        (a[u], a[v])
    }

    /// `p` with its in-plane coordinates set to `q`.
    fn with_uv(&self, p: Point3, q: (f64, f64)) -> Point3 {
        let (u, v) = self.axes();
        let mut a = [p.x, p.y, p.z];
        a[u] = q.0;
        a[v] = q.1;
        Point3::new(a[0], a[1], a[2])
    }

    /// G40 (`convert_cutter_compensation_off`).
    fn off(&mut self, units: Units, out: &mut Vec<ReadMove>) -> Result<(), BlockError> {
        if self.engaged() && !self.first {
            let at = self.uv(self.current);
            self.move_endpoint_and_flush(at, units, out)?;
            self.dequeue(out);
            self.arc_not_allowed = true;
        }
        self.side = None;
        self.first = true;
        Ok(())
    }

    /// A dwell: after the queued moves, or at once where the tool is.
    fn dwell(&mut self, mut rm: ReadMove, out: &mut Vec<ReadMove>) {
        if self.queue.is_empty() {
            if let Some(t) = self.tool {
                rm.mv.to = t;
            }
            out.push(rm);
        } else {
            self.queue.push(Queued {
                rm,
                dir: (0.0, 0.0),
                original_turns: 0.0,
            });
        }
    }

    fn set_endpoint(&mut self, p: (f64, f64)) {
        self.endpoint = p;
        self.endpoint_valid = true;
    }

    fn enqueue(&mut self, rm: ReadMove, dir: (f64, f64), original_turns: f64) {
        self.queue.push(Queued {
            rm,
            dir,
            original_turns,
        });
    }

    /// LinuxCNC's lathe tool origin: the controlled point is the tool's nose centre, the
    /// machine's point a corner of the tool (`latheorigin_x/z`, orientations 1..8 in G18).
    fn lathe_origin(&self, p: Point3) -> Point3 {
        if self.plane != Plane::Zx {
            return p;
        }
        let (o, r) = (self.orientation, self.radius);
        let mut q = p;
        if matches!(o, 2 | 6 | 1) {
            q.x -= r;
        }
        if matches!(o, 3 | 8 | 4) {
            q.x += r;
        }
        if matches!(o, 2 | 7 | 3) {
            q.z -= r;
        }
        if matches!(o, 1 | 5 | 4) {
            q.z += r;
        }
        q
    }

    /// Puts the queued moves out (`dequeue_canons`).
    fn dequeue(&mut self, out: &mut Vec<ReadMove>) {
        self.endpoint_valid = false;
        for q in std::mem::take(&mut self.queue) {
            let mut rm = q.rm;
            match &mut rm.mv.kind {
                MoveKind::Dwell { .. } => {
                    if let Some(t) = self.tool {
                        rm.mv.to = t;
                    }
                }
                MoveKind::Arc { center, .. } => {
                    *center = self.lathe_origin(*center);
                    rm.mv.to = self.lathe_origin(rm.mv.to);
                    self.tool = Some(rm.mv.to);
                }
                _ => {
                    rm.mv.to = self.lathe_origin(rm.mv.to);
                    self.tool = Some(rm.mv.to);
                }
            }
            out.push(rm);
        }
    }
}
