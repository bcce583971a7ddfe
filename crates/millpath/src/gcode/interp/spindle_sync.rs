//! LinuxCNC's spindle-synchronised motion: `G33` (threading), `G33.1` (rigid tapping) and
//! `G95` (feed per revolution), timed at the commanded spindle speed.
//!
//! # What the blocks do (LinuxCNC 2.9, `interp_convert.cc` `convert_straight`)
//! * `G33 X Y Z K p`: a straight move synchronised with the spindle, p program units of
//!   travel along the move per revolution (`START_SPEED_FEED_SYNCH(p)`, `STRAIGHT_FEED`).
//!   The spindle must be turning (M3/M4).
//! * `G33.1 X Y Z K p [I s]`: a rigid tap: in to the end at p per revolution, then the
//!   spindle reverses and the tool comes back out to where it started (`RIGID_TAP`); the
//!   interpreter's position stays at the start. I (LinuxCNC master) scales the speed of the
//!   way out (at least 1).
//! * `G95`: F is units per revolution; a feed move's speed is F · S.
//!
//! # Timing
//! The speed along the path is p · S / 60 (mm/s for p in mm and S in rev/min) with S the
//! commanded speed (`S`), so a move of length L takes L / (p · S/60) at full speed; the planner
//! adds the accelerations as for any feed move (LinuxCNC's synchronised moves accelerate
//! too). The tap's way back is a second feed move at the same speed (times I). LinuxCNC's
//! motion also waits for the spindle's index pulse before a G33 and reverses the spindle at
//! the bottom of a tap; those waits depend on the spindle drive and are not timed.
//!
//! # Refused
//! G33/G33.1 without K > 0 or with the spindle stopped (LinuxCNC: "Spindle not turning"),
//! spindle-synchronised moves and G95 feeds in G96 (the speed would follow the radius), G95
//! feed moves at S0 (LinuxCNC: "Cannot feed with zero spindle speed in feed per rev mode").

use super::{Block, BlockError, ReadMove, State};
use crate::geom::Point3;
use crate::toolpath::Move;

/// A synchronised move's pitch (mm of travel per revolution) and the way-out factor of a tap.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sync {
    pitch: f64,
    retract_scale: f64,
}

impl State {
    /// The K (and G33.1's I) of a G33 (`m` = 330) or G33.1 (331) block.
    pub(crate) fn sync_words(&mut self, m: u16, b: &mut Block) -> Result<Sync, BlockError> {
        let name = if m == 330 { "G33" } else { "G33.1" };
        let k = b.take(b'K');
        let i = if m == 331 { b.take(b'I') } else { None };
        let pitch = match k {
            Some(k) if k > 0.0 => k * self.unit(),
            _ => {
                return Err(BlockError::new(
                    name,
                    format!("K{}", k.map_or("(missing)".to_string(), |k| k.to_string())),
                    format!("a pitch K > 0 (travel per revolution) in every {name} block"),
                ));
            }
        };
        if self.css.is_some() {
            return Err(BlockError::unsupported(
                format!("{name} in G96"),
                "spindle-synchronised moves at a constant spindle speed (G97)",
            ));
        }
        if self.modal.spindle_rpm <= 0.0 {
            return Err(BlockError::new(
                name,
                "with the spindle stopped",
                "the spindle turning (M3 or M4 with S > 0) before G33/G33.1",
            ));
        }
        Ok(Sync {
            pitch,
            retract_scale: i.map_or(1.0, |s| s.max(1.0)),
        })
    }

    /// The speed (mm/s) of a synchronised move at the commanded spindle speed.
    pub(crate) fn sync_feed(&self, s: Sync) -> Result<f64, BlockError> {
        Ok(s.pitch * self.rev_per_second("G33/G33.1")?)
    }

    /// The speed (mm/s) of a G95 feed move: F (mm/rev) times the spindle speed.
    pub(crate) fn per_revolution_feed(&self) -> Result<f64, BlockError> {
        let f = match self.feed {
            Some(f) if f > 0.0 => f,
            _ => {
                return Err(BlockError::new(
                    "feed",
                    "missing or 0 in G95",
                    "an F > 0 (units per revolution) before a feed move in G95",
                ));
            }
        };
        Ok(f * self.rev_per_second("G95")?)
    }

    fn rev_per_second(&self, what: &str) -> Result<f64, BlockError> {
        if self.css.is_some() {
            return Err(BlockError::unsupported(
                format!("{what} in G96"),
                "feeds per revolution at a constant spindle speed (G97)",
            ));
        }
        let rpm = self.spindle_speed(self.spindle_set);
        if rpm <= 0.0 {
            return Err(BlockError::new(
                what,
                format!("at spindle speed S{rpm}"),
                "a spindle speed S > 0 for feeds per revolution",
            ));
        }
        Ok(rpm / 60.0)
    }

    /// G33.1's way out: back to `start` at the tap's speed times I; the position stays there.
    pub(crate) fn tap_retract(
        &mut self,
        start: Point3,
        s: Option<Sync>,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) {
        let Some(last) = out.last().copied() else {
            return;
        };
        let scale = s.map_or(1.0, |s| s.retract_scale);
        out.push(ReadMove {
            mv: Move {
                to: start,
                feed: last.mv.feed * scale,
                ..last.mv
            },
            line,
            modal: self.modal,
        });
        self.pos = start;
    }
}
