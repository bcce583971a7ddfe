//! From planar cuts to a 3-D toolpath: step-down levels, entries, heights.
//!
//! The top of the stock is `z = 0` and the pocket goes down to `−depth`. With `n =
//! ⌈(depth − floor stock) / step-down⌉` levels of equal height, level `i` (1-based) cuts at
//! `z_i = −(depth − floor stock)·i/n`; its *slab* is the material between `z_{i−1}` and `z_i`.
//!
//! Every cut starts with an entry that never plunges into material:
//! * **helix**: the tool centre runs on a circle of radius ρ about a point `c` of the region,
//!   descending `2πρ·tan α` per turn from `z_{i−1} + safe` down to `z_i`, then one flat turn.
//!   The disc of radius `ρ + r` about `c` is then clear, and the cut's path starts on it;
//! * **ramp**: the tool descends along the first `L` mm of the cut's own path, `L·tan α` per
//!   pass, back and forth until it reaches `z_i`, and is back at the path's start;
//! * **direct**: used by the finishing pass, which starts over material already cleared at
//!   that level: the tool feeds down in the air above `from` and leads in.
//!
//! Between cuts of a level and between levels the tool retracts to the clearance height and
//! moves in rapid; rapids go down only to `z_{i−1} + safe`, above material.

use super::chain::{Seg, path_head, path_length};
use super::options::{Direction, Entry, PocketOptions};
use crate::geom::{Point, Point3, Vec2};
use crate::toolpath::{Level, LevelKind, Move, Tool, Toolpath};

/// How a cut is entered.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CutEntry {
    /// Helix about `center`, radius `radius`; the path starts within `radius + r` of it.
    Helix {
        /// Helix centre.
        center: Point,
        /// Helix radius (tool centre), mm.
        radius: f64,
    },
    /// Ramp along the path itself.
    Ramp,
    /// Feed down above `from` (already cleared at this level) and lead in to the path.
    Direct {
        /// A cleared point.
        from: Point,
    },
}

/// One continuous cut at a level, after one entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// How the tool gets down.
    pub entry: CutEntry,
    /// The cutting path, in order.
    pub path: Vec<Seg>,
}

/// The cuts of one level, in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LevelPlan {
    /// The cuts.
    pub cuts: Vec<Cut>,
}

/// The depths of the roughing levels, top to bottom (negative z).
pub fn level_depths(opts: &PocketOptions) -> Vec<f64> {
    let total = opts.depth - opts.floor_stock;
    let n = (total / opts.step_down - 1e-9).ceil().max(1.0) as usize;
    (1..=n).map(|i| -total * i as f64 / n as f64).collect()
}

/// Emits `seg` at height `z`.
fn seg_move(seg: &Seg, z: f64, feed: f64) -> Move {
    let to = Point3::from_xy(seg.b, z);
    match seg.arc {
        None => Move::line(to, feed),
        Some(arc) => Move::arc_xy(to, Point3::from_xy(arc.center, z), arc.ccw, feed),
    }
}

/// Builds the toolpath: `roughing` is cut at every level, `finishing` (if any) once at the
/// last level.
pub fn assemble(
    tool: Tool,
    opts: &PocketOptions,
    roughing: &LevelPlan,
    finishing: Option<&LevelPlan>,
) -> Toolpath {
    let clear = opts.clearance_height;
    let start_xy = roughing
        .cuts
        .first()
        .and_then(|c| c.path.first())
        .map_or(Point::ORIGIN, |s| s.a);
    let mut tp = Toolpath::new(tool, Point3::from_xy(start_xy, clear));
    let mut top = 0.0;
    let depths = level_depths(opts);
    let mut plans: Vec<(f64, f64, &LevelPlan, LevelKind)> = depths
        .iter()
        .map(|&z| {
            let t = top;
            top = z;
            (t, z, roughing, LevelKind::Roughing)
        })
        .collect();
    if let (Some(f), Some(&z)) = (finishing, depths.last()) {
        plans.push((z, z, f, LevelKind::Finishing));
    }
    for (top, z, plan, kind) in plans {
        let start = tp.moves.len();
        for cut in &plan.cuts {
            emit_cut(&mut tp, opts, cut, top, z);
        }
        let end_xy = tp.end().xy();
        tp.push(Move::rapid(Point3::from_xy(end_xy, clear)));
        tp.levels.push(Level {
            z,
            kind,
            start,
            end: tp.moves.len(),
        });
    }
    tp
}

fn emit_cut(tp: &mut Toolpath, opts: &PocketOptions, cut: &Cut, top: f64, z: f64) {
    let Some(first) = cut.path.first() else {
        return;
    };
    let clear = opts.clearance_height;
    let safe = top + opts.safe_height;
    let ccw = opts.direction == Direction::Climb;
    let ramp_angle = match opts.entry {
        Entry::Helix { ramp_angle, .. } | Entry::Ramp { ramp_angle } => ramp_angle,
    };
    let here = tp.end();
    let approach = match cut.entry {
        CutEntry::Helix { center, radius } => center + Vec2::new(radius, 0.0),
        CutEntry::Ramp => first.a,
        CutEntry::Direct { from } => from,
    };
    if here.xy().distance(approach) > 1e-9 || here.z < safe {
        if here.z < clear {
            tp.push(Move::rapid(Point3::from_xy(here.xy(), clear)));
        }
        tp.push(Move::rapid(Point3::from_xy(approach, clear)));
    }
    tp.push(Move::rapid(Point3::from_xy(approach, safe)));
    match cut.entry {
        CutEntry::Helix { center, radius } => {
            let c = |h: f64| Point3::from_xy(center, h);
            let per_turn = std::f64::consts::TAU * radius * ramp_angle.tan();
            let turns = ((safe - z) / per_turn).ceil().max(1.0) as usize;
            for k in 1..=turns {
                let h = safe - (safe - z) * k as f64 / turns as f64;
                tp.push(Move::arc_xy(
                    Point3::from_xy(approach, h),
                    c(h),
                    ccw,
                    opts.plunge_feed,
                ));
            }
            tp.push(Move::arc_xy(
                Point3::from_xy(approach, z),
                c(z),
                ccw,
                opts.feed,
            ));
            tp.push(Move::line(Point3::from_xy(first.a, z), opts.feed));
        }
        CutEntry::Direct { from } => {
            tp.push(Move::line(Point3::from_xy(from, z), opts.plunge_feed));
            tp.push(Move::line(Point3::from_xy(first.a, z), opts.feed));
        }
        CutEntry::Ramp => {
            // Back and forth along the head of the path, descending all the way.
            let total = path_length(&cut.path);
            let drop = safe - z;
            let need = drop / ramp_angle.tan();
            let len = need.min(total).max(1e-6);
            let head = path_head(&cut.path, len);
            let head_len = path_length(&head);
            let passes = (need / head_len).ceil().max(1.0);
            let fits = passes <= MAX_RAMP_PASSES; // false for NaN
            if !fits {
                // A degenerate cut (a path shorter than need / MAX_RAMP_PASSES, e.g. a sliver
                // region a few µm long) has no room to ramp along: without this cap the pass
                // count grew without bound and the toolpath exhausted memory. Plunge straight
                // down instead, as a direct entry does.
                tp.push(Move::line(Point3::from_xy(first.a, z), opts.plunge_feed));
                for s in &cut.path {
                    tp.push(seg_move(s, z, opts.feed));
                }
                return;
            }
            let passes = passes as usize;
            let passes = passes + passes % 2; // end back at the start
            let slope = drop / (head_len * passes as f64);
            let mut h = safe;
            for p in 0..passes {
                let segs: Vec<Seg> = if p % 2 == 0 {
                    head.clone()
                } else {
                    head.iter().rev().map(Seg::reversed).collect()
                };
                for s in &segs {
                    h = (h - slope * s.length()).max(z);
                    tp.push(seg_move(s, h, opts.plunge_feed));
                }
            }
            if tp.end().z > z + 1e-9 {
                tp.push(Move::line(Point3::from_xy(first.a, z), opts.plunge_feed));
            }
        }
    }
    for s in &cut.path {
        tp.push(seg_move(s, z, opts.feed));
    }
}

/// The most back-and-forth passes a ramp entry makes; a cut too short for this many passes to
/// reach the depth at the ramp angle is entered by a straight plunge.
const MAX_RAMP_PASSES: f64 = 1000.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_equal_and_reach_the_floor() {
        let o = PocketOptions {
            depth: 25.0,
            step_down: 6.0,
            floor_stock: 1.0,
            ..PocketOptions::default()
        };
        let d = level_depths(&o);
        assert_eq!(d.len(), 4);
        assert!((d[3] + 24.0).abs() < 1e-12);
        assert!(d.windows(2).all(|w| (w[0] - w[1] - 6.0).abs() < 1e-12));
    }
}
