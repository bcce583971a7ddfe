//! Options of hole making, with defaults and validation.
//!
//! Lengths in millimetres, feeds in mm/s. Heights are measured up from the stock's top
//! ([`HoleOptions::top`]); the holes' bottom is [`HoleOptions::depth`] below it.
//! [`HoleOptions::validate`] checks every field against the tool and names the field in the
//! words of `millpath drill`'s flags, for the job layer to show.

use crate::error::InputError;
use crate::strategy::pocket::Direction;
use crate::toolpath::{CycleRetract, Tool};

/// Largest length accepted, mm (as for outlines' coordinates).
const MAX_LENGTH_MM: f64 = 1e6;

/// The smallest diameter tolerance, mm: a hole larger than the tool by more is bored on a
/// helix of radius at least half of it (2.5 µm), above the smallest arc a program can hold
/// (LinuxCNC's 1.27 µm).
pub const MIN_DIAMETER_TOLERANCE: f64 = 0.005;

/// Most helix turns a bore may take (per ring).
pub const MAX_TURNS: f64 = 10_000.0;

/// How a hole the size of the tool is drilled: the canned cycle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum DrillCycle {
    /// Straight down at the feed and out (G81, CYCLE81).
    #[default]
    Drill,
    /// Down, a dwell of `seconds` at the bottom, out (G82, CYCLE82).
    Dwell {
        /// Dwell at the bottom, s.
        seconds: f64,
    },
    /// Pecks of at most `step` mm, out to R after each to clear the chips (G83, CYCLE83).
    Peck {
        /// Largest peck, mm.
        step: f64,
    },
    /// Pecks of at most `step` mm, backing off a little after each to break the chip (G73).
    ChipBreak {
        /// Largest peck, mm.
        step: f64,
    },
}

/// How the holes of a drawing are drilled and bored.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct HoleOptions {
    /// Z of the stock's top, mm.
    pub top: f64,
    /// Depth of the holes below the top, mm (for a through hole, the stock's thickness plus
    /// the break-through).
    pub depth: f64,
    /// Height above the top the tool travels at between holes, mm (G98's initial level).
    pub clearance_height: f64,
    /// Height above the top where feeding starts (the cycles' R plane, the helix's start),
    /// mm.
    pub retract_height: f64,
    /// Where a drilling cycle leaves the tool: the clearance height (G98) or R (G99: the
    /// next hole is reached at R, for parts with nothing standing above the top).
    pub retract: CycleRetract,
    /// The canned cycle of drilled holes.
    pub cycle: DrillCycle,
    /// Drilling feed, mm/s.
    pub drill_feed: f64,
    /// Boring feed (helix and circles), mm/s.
    pub bore_feed: f64,
    /// Helix descent per turn, mm.
    pub pitch: f64,
    /// Climb (counter-clockwise round a hole) or conventional milling.
    pub direction: Direction,
    /// Largest distance between the helix rings of a hole more than twice the tool's
    /// diameter, as a fraction of the tool diameter, in (0, 0.9].
    pub stepover: f64,
    /// Stock left on the wall by the helix for the finishing circle, mm.
    pub finish_allowance: f64,
    /// A hole within this of the tool's diameter is drilled; larger ones are bored, mm (at
    /// least [`MIN_DIAMETER_TOLERANCE`]).
    pub diameter_tolerance: f64,
    /// Drill only: holes larger than the tool are left out rather than bored.
    pub drill_only: bool,
}

impl Default for HoleOptions {
    fn default() -> Self {
        HoleOptions {
            top: 0.0,
            depth: 10.0,
            clearance_height: 5.0,
            retract_height: 1.0,
            retract: CycleRetract::Initial,
            cycle: DrillCycle::Drill,
            drill_feed: 200.0 / 60.0,
            bore_feed: 800.0 / 60.0,
            pitch: 1.0,
            direction: Direction::Climb,
            stepover: 0.5,
            finish_allowance: 0.1,
            diameter_tolerance: crate::geom::CIRCLE_TOLERANCE,
            drill_only: false,
        }
    }
}

option_builders! {
    HoleOptions;
    /// Sets [`HoleOptions::top`], mm.
    with_top => top: f64;
    /// Sets [`HoleOptions::depth`], mm.
    with_depth => depth: f64;
    /// Sets [`HoleOptions::clearance_height`], mm.
    with_clearance_height => clearance_height: f64;
    /// Sets [`HoleOptions::retract_height`], mm.
    with_retract_height => retract_height: f64;
    /// Sets [`HoleOptions::retract`].
    with_retract => retract: CycleRetract;
    /// Sets [`HoleOptions::cycle`].
    with_cycle => cycle: DrillCycle;
    /// Sets [`HoleOptions::drill_feed`], mm/s.
    with_drill_feed => drill_feed: f64;
    /// Sets [`HoleOptions::bore_feed`], mm/s.
    with_bore_feed => bore_feed: f64;
    /// Sets [`HoleOptions::pitch`], mm per turn.
    with_pitch => pitch: f64;
    /// Sets [`HoleOptions::direction`].
    with_direction => direction: Direction;
    /// Sets [`HoleOptions::stepover`], a fraction of the tool diameter.
    with_stepover => stepover: f64;
    /// Sets [`HoleOptions::finish_allowance`], mm.
    with_finish_allowance => finish_allowance: f64;
    /// Sets [`HoleOptions::diameter_tolerance`], mm.
    with_diameter_tolerance => diameter_tolerance: f64;
    /// Sets [`HoleOptions::drill_only`].
    with_drill_only => drill_only: bool;
}

impl HoleOptions {
    /// The holes' bottom, Z mm.
    pub fn bottom(&self) -> f64 {
        self.top - self.depth
    }

    /// The R plane, Z mm.
    pub fn r_plane(&self) -> f64 {
        self.top + self.retract_height
    }

    /// The clearance level, Z mm.
    pub fn clearance(&self) -> f64 {
        self.top + self.clearance_height
    }

    /// Checks every field (named by `millpath drill`'s flag) and the tool.
    pub fn validate(&self, tool: &Tool) -> Result<(), InputError> {
        tool.validate("--tool-diameter")?;
        let length = |what: &str, v: f64, flag: &str, zero_ok: bool| {
            let ok = v.is_finite() && v <= MAX_LENGTH_MM && (v > 0.0 || (zero_ok && v == 0.0));
            if ok {
                Ok(())
            } else {
                Err(InputError::new(what, v).at(flag).expected(format!(
                    "a length {} 0 and at most {MAX_LENGTH_MM} mm",
                    if zero_ok { ">=" } else { ">" }
                )))
            }
        };
        if !(self.top.is_finite() && self.top.abs() <= MAX_LENGTH_MM) {
            return Err(InputError::new("stock top", self.top)
                .at("--top")
                .expected(format!("a finite Z within ±{MAX_LENGTH_MM} mm")));
        }
        length("depth", self.depth, "--depth", false)?;
        length("retract height", self.retract_height, "--retract", true)?;
        length(
            "clearance height",
            self.clearance_height,
            "--clearance-height",
            false,
        )?;
        if self.clearance_height < self.retract_height {
            return Err(InputError::new("clearance height", self.clearance_height)
                .at("--clearance-height")
                .expected(format!(
                    "at least the retract height {} mm (the R plane lies below the \
                         clearance level)",
                    self.retract_height
                )));
        }
        length("drilling feed", self.drill_feed, "--feed", false)?;
        length("boring feed", self.bore_feed, "--bore-feed", false)?;
        length("helix pitch", self.pitch, "--pitch", false)?;
        if (self.depth + self.retract_height) / self.pitch > MAX_TURNS {
            return Err(InputError::new("helix pitch", self.pitch)
                .at("--pitch")
                .expected(format!(
                    "at most {MAX_TURNS} turns from the retract height to the bottom"
                )));
        }
        if !(self.stepover.is_finite() && self.stepover > 0.0 && self.stepover <= 0.9) {
            return Err(InputError::new("bore stepover", self.stepover)
                .at("--stepover")
                .expected("a fraction of the tool diameter in (0, 0.9]"));
        }
        length(
            "finish allowance",
            self.finish_allowance,
            "--finish-allowance",
            true,
        )?;
        if !(self.diameter_tolerance.is_finite()
            && (MIN_DIAMETER_TOLERANCE..=1.0).contains(&self.diameter_tolerance))
        {
            return Err(
                InputError::new("diameter tolerance", self.diameter_tolerance)
                    .at("--diameter-tolerance")
                    .expected(format!(
                        "{MIN_DIAMETER_TOLERANCE} to 1 mm (a hole within less of the tool would \
                         be bored on a helix too small to write)"
                    )),
            );
        }
        match self.cycle {
            DrillCycle::Drill => {}
            DrillCycle::Dwell { seconds } => {
                if !(seconds.is_finite() && (0.0..=3600.0).contains(&seconds)) {
                    return Err(InputError::new("dwell", seconds)
                        .at("--dwell")
                        .expected("a dwell from 0 to 3600 s"));
                }
            }
            DrillCycle::Peck { step } | DrillCycle::ChipBreak { step } => {
                let flag = if matches!(self.cycle, DrillCycle::Peck { .. }) {
                    "--peck"
                } else {
                    "--chip-break"
                };
                length("peck", step, flag, false)?;
                let pecks = (self.depth + self.retract_height) / step;
                if pecks > crate::toolpath::MAX_PECKS {
                    return Err(InputError::new("peck", step).at(flag).expected(format!(
                        "at most {} pecks from the retract height to the bottom",
                        crate::toolpath::MAX_PECKS
                    )));
                }
            }
        }
        Ok(())
    }
}
