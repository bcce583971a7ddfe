//! Canned drilling cycles of the writer ([`crate::toolpath::Cycle`]).
//!
//! | cycle | LinuxCNC, Fanuc | Sinumerik | Grbl |
//! |---|---|---|---|
//! | drill | `G98 G81 X Y Z R F` | `G0 X Y`, `CYCLE81(RTP,RFP,0,DP)` | the moves |
//! | dwell | `G82 … P` (s; Fanuc: ms) | `CYCLE82(RTP,RFP,0,DP,,DTB)` | the moves |
//! | peck | `G83 … Q` | `CYCLE83(RTP,RFP,0,DP,,FDEP,,DAM,0,0,1,1,,,,,_DIS1)` | the moves |
//! | chip break | `G73 … Q` | the moves | the moves |
//!
//! **LinuxCNC and Fanuc.** A run of cycles, each starting where the one before left the tool
//! with the same retract mode, is written as one run (`G98`/`G99` once, every block with all
//! its words); anything else ends the run with `G80` first, so the reader's initial level is
//! the level the written cycle starts from. Z is the bottom, R the R plane, Q the peck (as in
//! the toolpath: its moves are what LinuxCNC 2.9 makes of these words). Fanuc's G82 dwell is
//! in milliseconds; its G73/G83 clearances are the parameters 5114/5115 (set to
//! [`crate::toolpath::PECK_CLEARANCE`]).
//!
//! **Sinumerik.** One call per hole: the moves up to the hole at the start's level as `G0`
//! blocks, the feed as an `F` block when it changes, then the cycle with RTP the retract
//! level, RFP the R plane with no safety distance (SDIS 0), DP the bottom; CYCLE83 in chip
//! removal (VARI 1) with the first depth FDEP one peck below R, the degression DAM equal to
//! the peck (every stroke one peck: a stroke is the one before less DAM, but never less than
//! DAM), no dwells, feed factor 1 and the re-entry distance `_DIS1` the peck clearance.
//! Chip breaking (VARI 0) backs off with a feed move on a Sinumerik, not with G73's rapid,
//! so a chip-breaking cycle is written as its moves.
//!
//! **Grbl** has no canned cycles: the moves are written.

use super::{Dialect, Emitter, num};
use crate::error::Error;
use crate::geom::Point3;
use crate::toolpath::{Cycle, CycleKind, CycleRetract, Move, PECK_CLEARANCE, Plane};

/// The run of cycles the writer is in (LinuxCNC and Fanuc: cycle mode until `G80`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct CycleRun {
    /// Where the last cycle left the tool (its last move's end).
    end: Point3,
    /// Its retract mode.
    retract: CycleRetract,
}

impl Emitter<'_> {
    /// Writes cycle `c` whose moves are `moves` (its expansion), the tool at `from`.
    pub(super) fn canned_cycle(
        &mut self,
        first: usize,
        c: &Cycle,
        moves: &[Move],
        from: Point3,
    ) -> Result<(), Error> {
        let d = self.dialect();
        let expanded = d == Dialect::Grbl
            || (d == Dialect::Sinumerik && matches!(c.kind, CycleKind::ChipBreak { .. }));
        if expanded {
            self.end_cycle_run()?;
            return self.plain(first, moves, from);
        }
        if self.pos.iter().any(Option::is_none) {
            self.end_cycle_run()?;
            self.summary.start_rapid = true;
            self.linear(super::Motion::G0, &Move::rapid(from), 0.0)?;
        }
        if self.plane != Plane::Xy {
            self.end_cycle_run()?;
            self.block("G17")?;
            self.plane = Plane::Xy;
        }
        self.summary.cycles += 1;
        match d {
            Dialect::Sinumerik => self.sinumerik_cycle(first, c, moves, from),
            _ => self.iso_cycle(c, moves, from),
        }
    }

    /// Writes `moves` one by one.
    fn plain(&mut self, first: usize, moves: &[Move], mut from: Point3) -> Result<(), Error> {
        for (k, m) in moves.iter().enumerate() {
            super::check_move(first + k, m, from)?;
            self.motion(first + k, m, from)?;
            from = m.to;
        }
        Ok(())
    }

    /// Ends a run of LinuxCNC or Fanuc cycles (`G80`), if in one.
    pub(super) fn end_cycle_run(&mut self) -> Result<(), Error> {
        if self.cycle_run.take().is_some() {
            self.block("G80")?;
            self.motion = None;
        }
        Ok(())
    }

    /// A length in mm as written in program units.
    fn length(&self, mm: f64) -> String {
        num(mm / self.unit, self.decimals, self.keep_point)
    }

    /// `G98 G81 X Y Z R F` and the like.
    fn iso_cycle(&mut self, c: &Cycle, moves: &[Move], from: Point3) -> Result<(), Error> {
        let continues = self
            .cycle_run
            .is_some_and(|run| run.retract == c.retract && run.end == from);
        if !continues {
            self.end_cycle_run()?;
        }
        let initial = self.pos[2];
        self.begin();
        if !continues {
            self.raw(match c.retract {
                CycleRetract::Initial => "G98",
                CycleRetract::R => "G99",
            });
        }
        self.raw(match c.kind {
            CycleKind::Drill => "G81",
            CycleKind::Dwell { .. } => "G82",
            CycleKind::Peck { .. } => "G83",
            CycleKind::ChipBreak { .. } => "G73",
        });
        self.motion = None;
        let x = self.axis(0, c.at.x, true);
        let y = self.axis(1, c.at.y, true);
        let _ = (x, y);
        let z = self.length(c.bottom);
        self.raw(&format!("Z{z}"));
        let r = self.length(c.r);
        self.raw(&format!("R{r}"));
        match c.kind {
            CycleKind::Dwell { seconds } if self.dialect() == Dialect::Fanuc => {
                self.raw(&format!("P{}", num((seconds * 1000.0).round(), 0, false)));
            }
            CycleKind::Dwell { seconds } => {
                let dec = self.decimals.max(3);
                self.raw(&format!("P{}", num(seconds, dec, false)));
            }
            CycleKind::Peck { step } | CycleKind::ChipBreak { step } => {
                let q = self.length(step);
                self.raw(&format!("Q{q}"));
            }
            CycleKind::Drill => {}
        }
        self.feed_word(c.feed);
        self.summary.blocks += 1;
        self.end()?;
        // Where the reader leaves the tool: the run's initial level (the level the run
        // started from, as written) with G98, R with G99.
        let r_read: f64 = r.parse().unwrap_or(c.r / self.unit);
        self.pos[2] = match c.retract {
            CycleRetract::Initial if continues => initial,
            CycleRetract::Initial => initial.map(|z| z.max(r_read)),
            CycleRetract::R => Some(r_read),
        };
        let end = moves.last().map_or(from, |m| m.to);
        self.cycle_run = Some(CycleRun {
            end,
            retract: c.retract,
        });
        Ok(())
    }

    /// `G0 X Y` and `CYCLE81(…)` and the like.
    fn sinumerik_cycle(
        &mut self,
        first: usize,
        c: &Cycle,
        moves: &[Move],
        from: Point3,
    ) -> Result<(), Error> {
        // The moves before the cycle's: up to R where the start is below it, across.
        let before = if from.z < c.r { 2 } else { 1 };
        let lead = moves.get(..before).unwrap_or_default();
        self.plain(first, lead, from)?;
        let level = lead.last().map_or(from, |m| m.to).z;
        let rtp = c.retract_level(level.max(c.r));
        self.begin();
        self.feed_word(c.feed);
        if !self.line.is_empty() {
            self.end()?;
        }
        let (rtp_t, rfp, dp) = (self.length(rtp), self.length(c.r), self.length(c.bottom));
        let call = match c.kind {
            CycleKind::Drill => format!("CYCLE81({rtp_t},{rfp},0,{dp})"),
            CycleKind::Dwell { seconds } => format!(
                "CYCLE82({rtp_t},{rfp},0,{dp},,{})",
                num(seconds, self.decimals.max(3), false)
            ),
            CycleKind::Peck { step } | CycleKind::ChipBreak { step } => format!(
                "CYCLE83({rtp_t},{rfp},0,{dp},,{},,{},0,0,1,1,,,,,{})",
                self.length(c.r - step),
                self.length(step),
                self.length(PECK_CLEARANCE)
            ),
        };
        self.begin();
        self.raw(&call);
        self.summary.blocks += 1;
        self.end()?;
        self.motion = None;
        self.pos[2] = Some(rtp_t.parse().unwrap_or(rtp / self.unit));
        Ok(())
    }
}
