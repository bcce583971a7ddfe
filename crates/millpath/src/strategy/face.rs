//! Facing: the stock's top taken down to a depth before anything else.
//!
//! The rectangle given is the stock's top (the drawing's extents plus a margin, or the stock
//! itself): nothing lies outside it. It is cleared in levels `step_down` apart down to
//! `depth` below the top (the last level at the depth exactly), each level a run of rows
//! along the rectangle's longer side:
//!
//! * **Rows**: `n = ⌈(W + 2e − 2r) / s⌉ + 1` rows across the shorter side `W` (one when the
//!   tool covers it), evenly spaced at most the stepover `s` apart, the first and last tool
//!   centres `r − e` inside the rectangle's edges: every point of the rectangle lies within
//!   `r` of a row, the edges with a margin `e` (a twentieth of the diameter) to spare.
//! * **Off the stock**: every row runs from `r + overrun` before the rectangle to `r +
//!   overrun` past it, so the tool goes down, and steps from row to row, clear of the stock:
//!   no plunge into material, and the feed move between rows cuts air.
//! * **Direction**: rows advance across the shorter side, so the uncut material lies on one
//!   side of each row; with a clockwise spindle a row cuts climbing when that side is on its
//!   right. Rows alternate (zigzag) by default; with [`FaceOptions::one_way`] every row
//!   climbs and the tool returns over the stock at the safe height.
//!
//! The module makes the path; the stock simulation (`stock::HeightField`) verifies it:
//! everything inside the rectangle down to the faced z, nothing below it.

use crate::error::{Error, InputError, require_positive};
use crate::geom::{Aabb, Point3};
use crate::toolpath::{Level, LevelKind, Move, Tool, Toolpath};

/// Most levels a facing may have.
const MAX_LEVELS: f64 = 10_000.0;
/// Most rows a level may have.
const MAX_ROWS: f64 = 1_000_000.0;

/// Facing options: every length in mm, feeds in mm/s. Built from [`Default`] with the
/// `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FaceOptions {
    /// The stock's top z.
    pub top_z: f64,
    /// How much is faced off, below the top (> 0).
    pub depth: f64,
    /// Depth per level (> 0); the last level lands on the depth.
    pub step_down: f64,
    /// Distance between rows as a fraction of the tool diameter, in (0, 1].
    pub stepover: f64,
    /// How far beyond the tool radius each row runs past the rectangle (≥ 0).
    pub overrun: f64,
    /// Height above the top for moves over the stock (> 0).
    pub safe_height: f64,
    /// Cutting feed, mm/s.
    pub feed: f64,
    /// Feed going down (outside the stock), mm/s.
    pub plunge_feed: f64,
    /// Every row climbing (with a clockwise spindle), the tool returning over the stock;
    /// rows alternate when false.
    pub one_way: bool,
}

impl Default for FaceOptions {
    fn default() -> Self {
        FaceOptions {
            top_z: 0.0,
            depth: 1.0,
            step_down: 1.0,
            stepover: 0.7,
            overrun: 2.0,
            safe_height: 5.0,
            feed: 25.0,
            plunge_feed: 5.0,
            one_way: false,
        }
    }
}

option_builders! {
    FaceOptions;
    /// Sets [`FaceOptions::top_z`].
    with_top_z => top_z: f64;
    /// Sets [`FaceOptions::depth`].
    with_depth => depth: f64;
    /// Sets [`FaceOptions::step_down`].
    with_step_down => step_down: f64;
    /// Sets [`FaceOptions::stepover`] (fraction of the diameter).
    with_stepover => stepover: f64;
    /// Sets [`FaceOptions::overrun`].
    with_overrun => overrun: f64;
    /// Sets [`FaceOptions::safe_height`].
    with_safe_height => safe_height: f64;
    /// Sets [`FaceOptions::feed`], mm/s.
    with_feed => feed: f64;
    /// Sets [`FaceOptions::plunge_feed`], mm/s.
    with_plunge_feed => plunge_feed: f64;
    /// Sets [`FaceOptions::one_way`].
    with_one_way => one_way: bool;
}

impl FaceOptions {
    /// Checks every field; errors name the field.
    pub fn validate(&self) -> Result<(), InputError> {
        const ORIGIN: &str = "facing options";
        if !self.top_z.is_finite() {
            return Err(InputError::new("facing top z", self.top_z)
                .at(ORIGIN)
                .expected("a finite z, mm"));
        }
        require_positive("facing depth", self.depth, ORIGIN)?;
        require_positive("facing step-down", self.step_down, ORIGIN)?;
        if self.depth / self.step_down > MAX_LEVELS {
            return Err(InputError::new("facing step-down", self.step_down)
                .at(ORIGIN)
                .expected(format!(
                    "at most {MAX_LEVELS} levels over the depth {} mm",
                    self.depth
                )));
        }
        if !(self.stepover > 0.0 && self.stepover <= 1.0) {
            return Err(InputError::new("facing stepover", self.stepover)
                .at(ORIGIN)
                .expected("a fraction of the tool diameter in (0, 1]"));
        }
        if !(self.overrun.is_finite() && self.overrun >= 0.0) {
            return Err(InputError::new("facing overrun", self.overrun)
                .at(ORIGIN)
                .expected("a finite length ≥ 0, mm"));
        }
        require_positive("facing safe height", self.safe_height, ORIGIN)?;
        require_positive("facing feed", self.feed, ORIGIN)?;
        require_positive("facing plunge feed", self.plunge_feed, ORIGIN)?;
        Ok(())
    }
}

/// The facing of `stock_top` (the rectangle of the stock's top) with `tool` (module docs).
/// Errors name an option, the tool or the rectangle when they are not usable.
pub fn face(stock_top: Aabb, tool: &Tool, opts: &FaceOptions) -> Result<Toolpath, Error> {
    tool.validate("facing tool")?;
    opts.validate()?;
    let corners = [
        stock_top.min.x,
        stock_top.min.y,
        stock_top.max.x,
        stock_top.max.y,
    ];
    if corners.iter().any(|v| !v.is_finite())
        || stock_top.width() <= 0.0
        || stock_top.height() <= 0.0
    {
        return Err(InputError::new(
            "facing rectangle",
            format!(
                "({}, {}) to ({}, {})",
                stock_top.min.x, stock_top.min.y, stock_top.max.x, stock_top.max.y
            ),
        )
        .at("facing")
        .expected("a rectangle of positive finite width and height, mm")
        .into());
    }
    let r = tool.radius();
    let margin = 0.05 * tool.diameter;
    let step = opts.stepover * tool.diameter;
    // Rows along the longer side: u along the rows, v across; `to_xy` maps back.
    let along_x = stock_top.width() >= stock_top.height();
    let (u0, u1, v0, v1) = if along_x {
        (
            stock_top.min.x,
            stock_top.max.x,
            stock_top.min.y,
            stock_top.max.y,
        )
    } else {
        (
            stock_top.min.y,
            stock_top.max.y,
            stock_top.min.x,
            stock_top.max.x,
        )
    };
    let to_xy = |u: f64, v: f64, z: f64| {
        if along_x {
            Point3::new(u, v, z)
        } else {
            Point3::new(v, u, z)
        }
    };
    let span = (v1 - v0) + 2.0 * margin - 2.0 * r;
    let rows_f = if span <= 0.0 {
        1.0
    } else {
        (span / step).ceil() + 1.0
    };
    if rows_f > MAX_ROWS {
        return Err(InputError::new("facing stepover", opts.stepover)
            .at("facing")
            .expected(format!("at most {MAX_ROWS} rows across {:.3} mm", v1 - v0))
            .into());
    }
    let rows = rows_f as usize;
    let row_v = |k: usize| {
        if rows == 1 {
            0.5 * (v0 + v1)
        } else {
            v0 + r - margin + span * k as f64 / (rows - 1) as f64
        }
    };
    // Off the stock at both ends: the tool clear of the rectangle by the overrun.
    let (start_u, end_u) = (u0 - r - opts.overrun, u1 + r + opts.overrun);
    // With v increasing across the rows the uncut material lies at +v. Travelling along −u
    // puts +v on the right when (u, v) is (x, y), along +u when it is (y, x).
    let climb_forward = !along_x;
    let top = opts.top_z;
    let safe = top + opts.safe_height;
    let levels = (opts.depth / opts.step_down).ceil().max(1.0) as usize;
    // Row k runs forward (along +u) when climbing does, or, zigzagging, every other row.
    let forward = |k: usize| climb_forward == (opts.one_way || k % 2 == 0);
    let first_u = if forward(0) { start_u } else { end_u };
    let mut tp = Toolpath::new(*tool, to_xy(first_u, row_v(0), safe));
    for level in 1..=levels {
        let z = top - (opts.step_down * level as f64).min(opts.depth);
        let start = tp.moves.len();
        for k in 0..rows {
            let v = row_v(k);
            let (from_u, to_u) = if forward(k) {
                (start_u, end_u)
            } else {
                (end_u, start_u)
            };
            if k == 0 || opts.one_way {
                // Over the stock at the safe height, down outside it.
                let here = tp.end();
                if here.z < safe {
                    tp.push(Move::rapid(Point3::new(here.x, here.y, safe)));
                }
                tp.push(Move::rapid(to_xy(from_u, v, safe)));
                tp.push(Move::rapid(to_xy(
                    from_u,
                    v,
                    top + opts.safe_height.min(1.0),
                )));
                tp.push(Move::line(to_xy(from_u, v, z), opts.plunge_feed));
            } else {
                // The step to the next row, past the end of the stock.
                tp.push(Move::line(to_xy(from_u, v, z), opts.feed));
            }
            tp.push(Move::line(to_xy(to_u, v, z), opts.feed));
        }
        let end = tp.end();
        tp.push(Move::rapid(Point3::new(end.x, end.y, safe)));
        tp.levels.push(Level {
            z,
            kind: if level == levels {
                LevelKind::Finishing
            } else {
                LevelKind::Roughing
            },
            start,
            end: tp.moves.len(),
        });
    }
    Ok(tp)
}
