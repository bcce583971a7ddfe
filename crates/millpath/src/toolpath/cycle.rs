//! Canned drilling cycles: an annotation over a run of a toolpath's moves that says "these
//! moves are one canned cycle", so that the G-code writer can write the cycle (G81, G82, G83,
//! G73, Sinumerik's CYCLE81/82/83) while the motion planner and the stock simulation see its
//! moves like any others.
//!
//! A [`Cycle`] names its kind, the hole's position, the R plane, the bottom, the retract mode
//! and the feed, and the range `start..end` of [`Toolpath::moves`](super::Toolpath) it
//! stands for. Those moves are exactly what LinuxCNC 2.9 expands the cycle to
//! (`interp_cycles.cc`), from the position the tool is at when the cycle begins ([`expand`]):
//!
//! * A start below R first rapids straight up to R. From a start above R (more than
//!   [`LEVEL_EPS`]): a rapid across to the hole at the start's height, then a rapid down to
//!   R; from a start at R: the rapid across at the retract level (it may have no length).
//! * Bodies: drill (G81) feeds to the bottom; dwell (G82) feeds to the bottom and dwells;
//!   peck (G83) feeds down by the step from R, rapids out to R and back down to
//!   [`PECK_CLEARANCE`] above the depth reached, and so on; chip-break (G73) likewise without
//!   going out to R (a rapid back by the clearance). The last feed reaches the bottom.
//! * Then a rapid out to the retract level: the start's height ([`CycleRetract::Initial`],
//!   G98, when it is above R) or R ([`CycleRetract::R`], G99).
//! * Every move of a cycle runs in exact-path mode ([`Corner::ExactPath`]): LinuxCNC switches
//!   to `G61` around a cycle.
//!
//! ```text
//!   start ──┐            ┌── G98 (the start's level)
//!   R  ─ ─ ─│─ ─ ─ ─ ─ ─ │─ G99
//!           │ feed       │ rapid
//!   bottom ─┴────────────┘
//! ```
//!
//! The G-code reader expands the cycles it reads with its own code (`gcode::interp`); the
//! round-trip tests compare the two.

use super::{Corner, Move};
use crate::error::InputError;
use crate::geom::{Point, Point3};
use serde::{Deserialize, Serialize};

/// The peck clearance of G73 and G83, mm: after each peck the tool comes back down (G83) or
/// stays (G73) this far above the depth reached. LinuxCNC 2.9's built-in 0.010 in; on Fanuc
/// controls parameters 5114 (G73) and 5115 (G83), to be set to it.
pub const PECK_CLEARANCE: f64 = 0.254;

/// Two levels closer than this, mm, are one level (the reader's rule: a rapid of no length
/// down to R is not made).
pub const LEVEL_EPS: f64 = 1e-9;

/// Most pecks one cycle may make (a step far smaller than the depth is a mistake).
pub const MAX_PECKS: f64 = 10_000.0;

/// What a cycle does at the hole.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum CycleKind {
    /// G81 / CYCLE81: feed to the bottom, rapid out.
    Drill,
    /// G82 / CYCLE82: feed to the bottom, dwell, rapid out.
    Dwell {
        /// Dwell at the bottom, s.
        seconds: f64,
    },
    /// G83 / CYCLE83 (chip removal): pecks of `step`, out to R after each.
    Peck {
        /// Depth of each peck, mm.
        step: f64,
    },
    /// G73 (chip breaking): pecks of `step`, backing off by [`PECK_CLEARANCE`] after each.
    ChipBreak {
        /// Depth of each peck, mm.
        step: f64,
    },
}

impl std::fmt::Display for CycleKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CycleKind::Drill => write!(f, "drill (G81)"),
            CycleKind::Dwell { seconds } => write!(f, "drill with a {seconds} s dwell (G82)"),
            CycleKind::Peck { step } => write!(f, "peck drill, {step} mm pecks (G83)"),
            CycleKind::ChipBreak { step } => {
                write!(f, "chip-breaking drill, {step} mm pecks (G73)")
            }
        }
    }
}

/// Where a cycle leaves the tool.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CycleRetract {
    /// G98: back to the level the tool started the cycle at (the initial level).
    #[default]
    Initial,
    /// G99: back to R.
    R,
}

/// One canned cycle over the moves `start..end` of a toolpath.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cycle {
    /// What it does.
    pub kind: CycleKind,
    /// The hole's position in the plane, mm.
    pub at: Point,
    /// The R plane (Z), mm: where feeding starts and pecks go out to.
    pub r: f64,
    /// The bottom (Z), mm.
    pub bottom: f64,
    /// Where the tool goes after the hole.
    pub retract: CycleRetract,
    /// Feed into the material, mm/s.
    pub feed: f64,
    /// Index of the cycle's first move.
    pub start: usize,
    /// One past its last move.
    pub end: usize,
}

impl Cycle {
    /// The level the cycle leaves the tool at when it starts from `from_z`: the start's level
    /// with G98 (R if the start is below R), R with G99.
    pub fn retract_level(&self, from_z: f64) -> f64 {
        match self.retract {
            CycleRetract::Initial => from_z.max(self.r),
            CycleRetract::R => self.r,
        }
    }

    /// Checks the numbers (finite; R at or above the bottom; a feed, step and dwell > 0, ≥ 0;
    /// at most [`MAX_PECKS`] pecks); `at` names the cycle in messages.
    pub fn check(&self, at: &str) -> Result<(), InputError> {
        let finite = self.at.is_finite() && self.r.is_finite() && self.bottom.is_finite();
        if !finite || self.r < self.bottom {
            return Err(InputError::new(
                "canned cycle",
                format!(
                    "at ({}, {}), R {} bottom {}",
                    self.at.x, self.at.y, self.r, self.bottom
                ),
            )
            .at(at.to_owned())
            .expected("finite numbers, R at or above the bottom"));
        }
        if !(self.feed.is_finite() && self.feed > 0.0) {
            return Err(InputError::new("canned cycle feed", self.feed)
                .at(at.to_owned())
                .expected("a feed > 0 mm/s"));
        }
        match self.kind {
            CycleKind::Drill => {}
            CycleKind::Dwell { seconds } if seconds.is_finite() && seconds >= 0.0 => {}
            CycleKind::Dwell { seconds } => {
                return Err(InputError::new("canned cycle dwell", seconds)
                    .at(at.to_owned())
                    .expected("a finite dwell >= 0 s"));
            }
            CycleKind::Peck { step } | CycleKind::ChipBreak { step } => {
                if !(step.is_finite() && step > 0.0 && (self.r - self.bottom) / step <= MAX_PECKS) {
                    return Err(InputError::new("canned cycle peck", step)
                        .at(at.to_owned())
                        .expected(format!(
                            "a peck > 0 mm, at most {MAX_PECKS} of them from R to the bottom"
                        )));
                }
            }
        }
        Ok(())
    }
}

/// The moves LinuxCNC 2.9 makes for `cycle` when the tool is at `from` as it begins (module
/// docs), every one in exact-path mode. The cycle's numbers are taken as given: see
/// [`Cycle::check`].
pub fn expand(cycle: &Cycle, from: Point3) -> Vec<Move> {
    let (x, y) = (cycle.at.x, cycle.at.y);
    let r = cycle.r;
    let mut out: Vec<Move> = Vec::new();
    let at = |z: f64| Point3::new(x, y, z);
    let rapid = |out: &mut Vec<Move>, p: Point3| {
        out.push(Move::rapid(p).with_corner(Corner::ExactPath));
    };
    let feed = |out: &mut Vec<Move>, z: f64| {
        out.push(Move::line(at(z), cycle.feed).with_corner(Corner::ExactPath));
    };
    let mut current = from.z;
    if current < r {
        rapid(&mut out, Point3::new(from.x, from.y, r));
        current = r;
    }
    let clear = cycle.retract_level(current);
    if current > r + LEVEL_EPS {
        rapid(&mut out, at(current));
        rapid(&mut out, at(r));
    } else {
        rapid(&mut out, at(clear));
        if clear > r + LEVEL_EPS {
            rapid(&mut out, at(r));
        }
    }
    match cycle.kind {
        CycleKind::Drill => feed(&mut out, cycle.bottom),
        CycleKind::Dwell { seconds } => {
            feed(&mut out, cycle.bottom);
            out.push(Move::dwell(at(cycle.bottom), seconds).with_corner(Corner::ExactPath));
        }
        CycleKind::Peck { step } | CycleKind::ChipBreak { step } => {
            let out_to_r = matches!(cycle.kind, CycleKind::Peck { .. });
            let mut depth = r - step;
            while depth > cycle.bottom {
                feed(&mut out, depth);
                if out_to_r {
                    rapid(&mut out, at(r));
                }
                rapid(&mut out, at(depth + PECK_CLEARANCE));
                depth -= step;
            }
            feed(&mut out, cycle.bottom);
        }
    }
    rapid(&mut out, at(clear));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::MoveKind;

    fn cycle(kind: CycleKind, retract: CycleRetract) -> Cycle {
        Cycle {
            kind,
            at: Point::new(10.0, 20.0),
            r: 1.0,
            bottom: -5.0,
            retract,
            feed: 2.0,
            start: 0,
            end: 0,
        }
    }

    fn zs(moves: &[Move]) -> Vec<(char, f64)> {
        moves
            .iter()
            .map(|m| {
                let c = match m.kind {
                    MoveKind::Rapid => 'r',
                    MoveKind::Line => 'f',
                    MoveKind::Dwell { .. } => 'd',
                    MoveKind::Arc { .. } => 'a',
                };
                (c, (m.to.z * 1e6).round() / 1e6)
            })
            .collect()
    }

    #[test]
    fn drill_from_above_and_from_r() {
        let c = cycle(CycleKind::Drill, CycleRetract::Initial);
        let m = expand(&c, Point3::new(0.0, 0.0, 5.0));
        assert_eq!(
            zs(&m),
            [('r', 5.0), ('r', 1.0), ('f', -5.0), ('r', 5.0)],
            "{m:?}"
        );
        assert_eq!(m[0].to.xy(), c.at);
        assert!(m.iter().all(|m| m.corner == Corner::ExactPath));
        let g99 = cycle(CycleKind::Drill, CycleRetract::R);
        assert_eq!(
            zs(&expand(&g99, Point3::new(0.0, 0.0, 5.0))),
            [('r', 5.0), ('r', 1.0), ('f', -5.0), ('r', 1.0)]
        );
        // From R: across at R, no rapid of no length down.
        assert_eq!(
            zs(&expand(&g99, Point3::new(0.0, 0.0, 1.0))),
            [('r', 1.0), ('f', -5.0), ('r', 1.0)]
        );
        // From below R: up first, where the tool is.
        let m = expand(&c, Point3::new(3.0, 4.0, -1.0));
        assert_eq!(m[0].to, Point3::new(3.0, 4.0, 1.0));
        assert_eq!(zs(&m), [('r', 1.0), ('r', 1.0), ('f', -5.0), ('r', 1.0)]);
    }

    #[test]
    fn pecks_go_down_by_the_step_and_back_by_the_clearance() {
        let g83 = cycle(CycleKind::Peck { step: 2.5 }, CycleRetract::Initial);
        let m = expand(&g83, Point3::new(0.0, 0.0, 5.0));
        let c = PECK_CLEARANCE;
        assert_eq!(
            zs(&m),
            [
                ('r', 5.0),
                ('r', 1.0),
                ('f', -1.5),
                ('r', 1.0),
                ('r', -1.5 + c),
                ('f', -4.0),
                ('r', 1.0),
                ('r', -4.0 + c),
                ('f', -5.0),
                ('r', 5.0)
            ]
        );
        let g73 = cycle(CycleKind::ChipBreak { step: 2.5 }, CycleRetract::R);
        let m = expand(&g73, Point3::new(0.0, 0.0, 5.0));
        assert_eq!(
            zs(&m),
            [
                ('r', 5.0),
                ('r', 1.0),
                ('f', -1.5),
                ('r', -1.5 + c),
                ('f', -4.0),
                ('r', -4.0 + c),
                ('f', -5.0),
                ('r', 1.0)
            ]
        );
        let g82 = cycle(CycleKind::Dwell { seconds: 0.5 }, CycleRetract::Initial);
        let m = expand(&g82, Point3::new(0.0, 0.0, 5.0));
        assert_eq!(m[3].kind, MoveKind::Dwell { seconds: 0.5 });
    }

    #[test]
    fn bad_numbers_are_refused() {
        let mut c = cycle(CycleKind::Peck { step: 1e-9 }, CycleRetract::R);
        assert!(c.check("cycle 0").is_err());
        c.kind = CycleKind::Drill;
        assert!(c.check("cycle 0").is_ok());
        c.bottom = 2.0;
        assert!(c.check("cycle 0").is_err());
        c.bottom = -2.0;
        c.feed = 0.0;
        assert!(c.check("cycle 0").is_err());
    }
}
