//! Toolpaths: ordered moves with feeds, in the workpiece frame.
//!
//! A [`Toolpath`] is what a strategy produces and what the motion planner and the G-code
//! writer consume. Positions are in millimetres, feeds in **mm/s** (the G-code writer turns
//! them into mm/min or in/min).

pub mod arc_rule;
mod moves;
mod tool;

pub use moves::{Corner, CurveTag, Move, MoveKind, Plane};
pub use tool::Tool;

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

/// An ordered list of moves, grouped by level, with the tool it was made for.
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
}

impl Toolpath {
    /// An empty toolpath starting at `start`.
    pub fn new(tool: Tool, start: Point3) -> Self {
        Toolpath {
            tool,
            start,
            moves: Vec::new(),
            levels: Vec::new(),
        }
    }

    /// Appends a move.
    pub fn push(&mut self, m: Move) {
        self.moves.push(m);
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

    /// XY bounding box of the moves' end points and the start (arcs' bulges not included).
    pub fn bounds_xy(&self) -> Aabb {
        Aabb::from_points(
            std::iter::once(self.start.xy()).chain(self.moves.iter().map(|m| m.to.xy())),
        )
    }
}
