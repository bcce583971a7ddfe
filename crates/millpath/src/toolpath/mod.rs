//! Toolpaths: ordered moves with feeds, in the workpiece frame.
//!
//! A [`Toolpath`] is what a strategy produces and what the motion planner and the G-code
//! writer consume. Positions are in millimetres, feeds in **mm/s** (the G-code writer turns
//! them into mm/min or in/min).

pub(crate) mod arc_rule;
mod cycle;
mod moves;
mod tool;

pub use cycle::{
    Cycle, CycleKind, CycleRetract, LEVEL_EPS as CYCLE_LEVEL_EPS, MAX_PECKS, PECK_CLEARANCE,
    expand as expand_cycle,
};
pub use moves::{Corner, CurveTag, Move, MoveKind, Plane, Rotary};
pub use tool::{REFERENCE_DIAMETER, Tool, tolerance_scale};

use crate::geom::{Aabb, Point3};
use serde::{Deserialize, Serialize};

/// What a level of a toolpath does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LevelKind {
    /// Roughing at a step-down, leaving stock.
    Roughing,
    /// Finishing to size.
    Finishing,
    /// Moves that are not cutting at a level: approach, retract, linking.
    Other,
}

/// A contiguous run of moves cutting at one depth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Level {
    /// Cutting depth (Z of the tool tip) of this level in mm.
    pub z: f64,
    /// What the level does.
    pub kind: LevelKind,
    /// Index of the first move of the level in [`Toolpath::moves`].
    pub start: usize,
    /// One past the last move of the level.
    pub end: usize,
}

/// An ordered list of moves, grouped by level, with the tool it was made for; runs of moves
/// that are canned drilling cycles are marked in [`Toolpath::cycles`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Toolpath {
    /// The tool.
    pub tool: Tool,
    /// Where the tool is before the first move.
    pub start: Point3,
    /// The moves, in order.
    pub moves: Vec<Move>,
    /// Levels: ranges of `moves`, in order, not overlapping.
    pub levels: Vec<Level>,
    /// Canned cycles: ranges of `moves`, in order, not overlapping, each exactly the moves
    /// its cycle expands to ([`expand_cycle`]); see [`Toolpath::check_cycles`].
    #[serde(default)]
    pub cycles: Vec<Cycle>,
}

impl Toolpath {
    /// An empty toolpath starting at `start`.
    pub fn new(tool: Tool, start: Point3) -> Self {
        Toolpath {
            tool,
            start,
            moves: Vec::new(),
            levels: Vec::new(),
            cycles: Vec::new(),
        }
    }

    /// Appends a move.
    pub fn push(&mut self, m: Move) {
        self.moves.push(m);
    }

    /// Appends canned cycle `cycle` (its `start` and `end` are set here) from where the tool
    /// is: its moves ([`expand_cycle`]) and its annotation.
    pub fn push_cycle(&mut self, mut cycle: Cycle) {
        let moves = expand_cycle(&cycle, self.end());
        cycle.start = self.moves.len();
        cycle.end = cycle.start + moves.len();
        self.moves.extend(moves);
        self.cycles.push(cycle);
    }

    /// Appends `other`'s moves, levels and cycles (their ranges shifted); `other` is taken to
    /// start where this toolpath ends.
    pub fn append(&mut self, other: &Toolpath) {
        let base = self.moves.len();
        self.moves.extend_from_slice(&other.moves);
        self.levels.extend(other.levels.iter().map(|l| Level {
            start: l.start + base,
            end: l.end + base,
            ..*l
        }));
        self.cycles.extend(other.cycles.iter().map(|c| Cycle {
            start: c.start + base,
            end: c.end + base,
            ..*c
        }));
    }

    /// Checks the canned cycles: in order, not overlapping, within the moves, their numbers
    /// valid ([`Cycle::check`]), and each one's moves those it expands to from where the tool
    /// is when it begins (within `1e-9` mm and s).
    pub fn check_cycles(&self) -> Result<(), crate::error::InputError> {
        let mut next = 0;
        for (k, c) in self.cycles.iter().enumerate() {
            let at = format!("canned cycle {k} (moves {}..{})", c.start, c.end);
            c.check(&at)?;
            let Some(run) = self.moves.get(c.start..c.end).filter(|_| c.start >= next) else {
                return Err(crate::error::InputError::new("canned cycle range", &at)
                    .at("toolpath")
                    .expected(format!(
                        "ranges in order, not overlapping, within the {} moves",
                        self.moves.len()
                    )));
            };
            let from = match c.start.checked_sub(1) {
                Some(i) => self.moves.get(i).map_or(self.start, |m| m.to),
                None => self.start,
            };
            let want = expand_cycle(c, from);
            let same = want.len() == run.len()
                && want.iter().zip(run).all(|(a, b)| {
                    a.kind_matches(b, 1e-9)
                        && a.to.distance(b.to) <= 1e-9
                        && (!a.is_feed() || (a.feed - b.feed).abs() <= 1e-9)
                });
            if !same {
                return Err(crate::error::InputError::new("canned cycle", &at)
                    .at("toolpath")
                    .expected(format!(
                        "the {} moves its {} expands to, from ({:.4}, {:.4}, {:.4})",
                        want.len(),
                        c.kind,
                        from.x,
                        from.y,
                        from.z
                    )));
            }
            next = c.end;
        }
        Ok(())
    }

    /// Where the tool is after the last move (the start if there is none).
    pub fn end(&self) -> Point3 {
        self.moves.last().map_or(self.start, |m| m.to)
    }

    /// Iterates over `(from, move)` pairs: each move with the position it starts from.
    pub fn segments(&self) -> impl Iterator<Item = (Point3, &Move)> + '_ {
        let mut from = self.start;
        self.moves.iter().map(move |m| {
            let f = from;
            from = m.to;
            (f, m)
        })
    }

    /// Total length of the feed moves (lines and arcs) in mm.
    pub fn cut_length(&self) -> f64 {
        self.segments()
            .filter(|(_, m)| m.is_feed())
            .map(|(from, m)| m.length_from(from))
            .sum()
    }

    /// Total length of the rapid moves in mm.
    pub fn rapid_length(&self) -> f64 {
        self.segments()
            .filter(|(_, m)| matches!(m.kind, MoveKind::Rapid))
            .map(|(from, m)| m.length_from(from))
            .sum()
    }

    /// Time at the programmed feeds, ignoring acceleration, with rapids at `rapid_speed` mm/s.
    /// This is the naive estimate real controllers beat rarely; see [`crate::motion`] for the
    /// dynamic cycle time.
    pub fn time_at_programmed_feed(&self, rapid_speed: f64) -> f64 {
        self.segments()
            .map(|(from, m)| match m.kind {
                MoveKind::Rapid => m.length_from(from) / rapid_speed,
                MoveKind::Dwell { seconds } => seconds,
                _ if m.feed > 0.0 => m.length_from(from) / m.feed,
                _ => 0.0,
            })
            .sum()
    }

    /// The moves of level `index` as a toolpath of their own, starting where the level starts,
    /// with that one level; the whole toolpath when there is no such level.
    pub fn level(&self, index: usize) -> Toolpath {
        let Some(l) = self.levels.get(index) else {
            return self.clone();
        };
        let start = match l.start.checked_sub(1) {
            Some(before) => self.moves.get(before).map_or(self.start, |m| m.to),
            None => self.start,
        };
        let mut out = Toolpath::new(self.tool, start);
        out.moves = self.moves.get(l.start..l.end).unwrap_or_default().to_vec();
        out.levels = vec![Level {
            start: 0,
            end: out.moves.len(),
            ..l.clone()
        }];
        out.cycles = self
            .cycles
            .iter()
            .filter(|c| c.start >= l.start && c.end <= l.end)
            .map(|c| Cycle {
                start: c.start - l.start,
                end: c.end - l.start,
                ..*c
            })
            .collect();
        out
    }

    /// XY bounding box of the moves' end points and the start (arcs' bulges not included).
    pub fn bounds_xy(&self) -> Aabb {
        Aabb::from_points(
            std::iter::once(self.start.xy()).chain(self.moves.iter().map(|m| m.to.xy())),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_level_starts_where_it_starts_in_the_whole() {
        let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 5.0));
        let at = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        for p in [at(0.0, 0.0, -1.0), at(10.0, 0.0, -1.0), at(10.0, 0.0, 5.0)] {
            tp.push(Move::line(p, 10.0));
        }
        for p in [at(10.0, 0.0, -2.0), at(0.0, 0.0, -2.0), at(0.0, 4.0, -2.0)] {
            tp.push(Move::line(p, 10.0));
        }
        let level = |z, start, end| Level {
            z,
            kind: LevelKind::Roughing,
            start,
            end,
        };
        tp.levels = vec![level(-1.0, 0, 3), level(-2.0, 3, 6)];
        let second = tp.level(1);
        assert_eq!(second.start, at(10.0, 0.0, 5.0));
        assert_eq!(second.moves, tp.moves[3..6]);
        assert_eq!(second.levels, [level(-2.0, 0, 3)]);
        // The lengths add up: the two levels are the whole.
        let sum = tp.level(0).cut_length() + second.cut_length();
        assert!((sum - tp.cut_length()).abs() < 1e-12);
        assert!((second.cut_length() - (7.0 + 10.0 + 4.0)).abs() < 1e-12);
        assert_eq!(tp.level(2), tp);
    }
}
