//! From planar cuts to a 3-D toolpath: step-down levels, entries, heights.
//!
//! The top of the stock is `z = 0` and the pocket goes down to `−depth`. With `n =
//! ⌈(depth − floor stock) / step-down⌉` levels of equal height, level `i` (1-based) cuts at
//! `z_i = −(depth − floor stock)·i/n`; its *slab* is the material between `z_{i−1}` and `z_i`.
//!
//! Every cut starts with an entry that never plunges into material:
//! * **helix**: the tool centre runs on a circle of radius ρ about a point `c` of the region,
//!   descending `2πρ·tan α` per turn from `z_{i−1} + safe` down to `z_i` (through
//!   `(z_{i−1} + safe − z_i) / (ρ·tan α)` radians, not rounded to whole turns), then, where
//!   the strategy asks for it, one flat turn: the disc of radius `ρ + r` about `c` is then
//!   clear. Without it the cut's own path takes the wedge the slope leaves under the last
//!   turn (and, for a helix wider than the tool, the pillar inside it). The path starts on
//!   the disc;
//! * **ramp**: the tool descends along the first `L` mm of the cut's own path, `L·tan α` per
//!   pass, back and forth until it reaches `z_i`, and is back at the path's start;
//! * **ramp along**: the same over at most the first row, an odd number of passes ending at
//!   the head's far end, and the path goes on from there: the row is not cut again at the
//!   level, the passes beside it take what the ramp left above its slope;
//! * **direct**: the tool feeds down in the air above `from`, a point already cleared at this
//!   depth by an earlier cut of the same level (the finishing pass; any later cut of a level
//!   that has a cleared point nearby, see [`direct_entries`]), and leads in.
//!
//! A ramp needs `L ≥ Δz / (passes · tan α)` of path; a cut shorter than
//! `Δz / (MAX_RAMP_PASSES · tan α)` (a sliver loop a few µm long) with no cleared point at
//! hand gets an input error rather than a plunge: the previous fallback, a straight plunge,
//! broke "never a plunge into material". In practice every cut after the first of a level
//! has a cleared point and is entered directly, so the error only meets a pocket whose whole
//! level is a sliver (a tool that barely fits).
//!
//! Between cuts of a level the tool retracts to the clearance height and moves in rapid;
//! rapids go down only to `z_{i−1} + safe`, above material. Between the levels of a prismatic
//! pocket the tool goes straight to the next level's entry at `z_i + safe`, rising as it goes
//! (one rapid), when that segment stays in the region the level's tool centre swept (every
//! point of it was cleared down to `z_i`, and the tool's bottom is at least `z_i`); else it
//! rises to the clearance height.

use super::options::{Direction, Entry, PocketOptions};
use super::segments::{ARC_AS_LINE_SAGITTA, Seg, path_head, path_length, path_tail};
use super::shape::{OffsetRegion, crosses};
use crate::error::InputError;
use crate::geom::{Point, Point3, Vec2};
use crate::toolpath::{Level, LevelKind, Move, Tool, Toolpath};
use std::f64::consts::TAU;

/// How a cut is entered.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CutEntry {
    /// Helix about `center`, radius `radius`; the path starts within `radius + r` of it.
    Helix {
        /// Helix centre.
        center: Point,
        /// Helix radius (tool centre), mm.
        radius: f64,
        /// One flat turn at the level after the descent, so that the disc of radius
        /// `radius + r` is clear before the path starts (a strategy that plans against the
        /// cleared material needs it). Without it the slope leaves a wedge at most one turn's
        /// drop high under the last turn, which the cut's own path (or a later cut of the
        /// level) takes: the pocket strategies' paths sweep their whole region.
        flat_turn: bool,
    },
    /// Ramp along the path itself.
    Ramp,
    /// Ramp along the head of the path as it is cut: back and forth over at most
    /// `max_len` of it an odd number of times, ending at the head's far end at the level,
    /// then on along the rest. The material above the last pass is left to the passes
    /// beside the head, which the strategy places to cover its swath (the zigzag's first
    /// row); `generate` plans again with [`CutEntry::Ramp`] where the stock simulation
    /// finds material left.
    RampAlong {
        /// The longest head, mm (the first row).
        max_len: f64,
    },
    /// Ramp forwards round the closed loop that the path's first `len` mm form (a racetrack
    /// along a long pocket's ridge: an elongated helix), whole laps descending at the ramp
    /// angle, the last ending at the loop's start at the level; then the path, whose head is
    /// the flat lap that clears what the slope left under the last one.
    Lap {
        /// The loop's length, mm.
        len: f64,
    },
    /// Feed down above `from` (already cleared at this level) and lead in to the path.
    Direct {
        /// A cleared point.
        from: Point,
    },
    /// The tool stays down: the path's first segment is a line from where the cut before it
    /// (at the same level) ended, through material that cut cleared, written lifted by
    /// [`super::options::AdaptiveOptions::lift`]. Where the tool is not there (a linked
    /// cut first in its level), the cut is ramped into.
    Linked,
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

/// Emits `seg` at height `z` (a line for an arc flatter than [`ARC_AS_LINE_SAGITTA`]).
///
/// An arc is judged flat by its own sweep, `r·(1 − cos(θ/2))` at most [`ARC_AS_LINE_SAGITTA`]:
/// a `Move` keeps only the arc's end and centre, and one whose ends lie a few ulps apart (a
/// slice of a loop 2·10⁵ mm from the origin, 1e-11 mm long) reads back as a full circle.
fn seg_move(seg: &Seg, z: f64, feed: f64) -> Move {
    let to = Point3::from_xy(seg.b, z);
    match seg.arc {
        Some(arc)
            if arc.radius * (1.0 - (0.5 * arc.sweep.min(TAU)).cos()) > ARC_AS_LINE_SAGITTA =>
        {
            Move::arc_xy(to, Point3::from_xy(arc.center, z), arc.ccw, feed)
        }
        _ => Move::line(to, feed),
    }
}

/// Builds the toolpath: `roughing[i]` is cut at level `i` (the last plan is repeated if
/// there are fewer plans than levels), `finishing` (if any) once at the last level.
/// `regions[i]` (the last repeated, none: no such link) is the region level `i`'s tool centre
/// swept: after a level, the tool rises only to the next level's safe height and goes
/// straight to the next entry where that way stays in the region of every level whose slab
/// reaches that height; elsewhere it rises to the clearance height.
///
/// Fails when a cut can be entered neither by its helix or ramp nor over cleared material
/// (see `emit_cut`).
pub fn assemble(
    tool: Tool,
    opts: &PocketOptions,
    roughing: &[LevelPlan],
    finishing: Option<&LevelPlan>,
    regions: &[OffsetRegion],
) -> Result<Toolpath, InputError> {
    let clear = opts.clearance_height;
    let start_xy = roughing
        .first()
        .and_then(|p| p.cuts.first())
        .and_then(|c| c.path.first())
        .map_or(Point::ORIGIN, |s| s.a);
    let mut tp = Toolpath::new(tool, Point3::from_xy(start_xy, clear));
    let mut top = 0.0;
    let depths = level_depths(opts);
    let mut plans: Vec<(f64, f64, &LevelPlan, LevelKind)> = Vec::with_capacity(depths.len() + 1);
    for (i, &z) in depths.iter().enumerate() {
        let Some(plan) = roughing.get(i).or(roughing.last()) else {
            break;
        };
        plans.push((top, z, plan, LevelKind::Roughing));
        top = z;
    }
    if let (Some(f), Some(&z)) = (finishing, depths.last()) {
        plans.push((z, z, f, LevelKind::Finishing));
    }
    for (k, &(top, z, plan, kind)) in plans.iter().enumerate() {
        let start = tp.moves.len();
        // The previous level's retract ended at this level's safe height when the way to its
        // first entry lies over the region that level cleared.
        let low = tp.end().z < clear - 1e-9 && k > 0;
        for (i, cut) in plan.cuts.iter().enumerate() {
            emit_cut(&mut tp, opts, cut, (top, z), low && i == 0)?;
        }
        let end_xy = tp.end().xy();
        // Over a level just cut, the next level's first entry is reached at that level's
        // safe height (`z + safe`: the tool's bottom above the floor it cleared) when the
        // straight way there stays in the region its tool centre swept; else at the
        // clearance height.
        let next = plans.get(k + 1).and_then(|&(ntop, nz, nplan, _)| {
            let h = ntop + opts.safe_height;
            let (to, _) = cut_approach(nplan.cuts.first()?, opts, ntop, nz).ok()?;
            // Every level whose slab reaches up past `z` to `h` (sections need not nest: a
            // bottom outline can reach out where the top does not) must hold the way.
            let mut inside = false;
            for (j, &(_, zj, _, _)) in plans[..=k].iter().enumerate().rev() {
                if zj >= h {
                    break;
                }
                let region = regions.get(j).or(regions.last())?;
                if crosses(region, end_xy, to) {
                    return None;
                }
                inside = true;
            }
            inside.then_some((h, to))
        });
        match next.filter(|&(h, _)| h < clear) {
            // Up and across in one rapid: every height it passes lies within the slabs the
            // way was checked through, over material cleared down to `z`.
            Some((h, to)) => tp.push(Move::rapid(Point3::from_xy(to, h))),
            None => tp.push(Move::rapid(Point3::from_xy(end_xy, clear))),
        }
        tp.levels.push(Level {
            z,
            kind,
            start,
            end: tp.moves.len(),
        });
    }
    Ok(tp)
}

/// Replaces the ramp of every cut after the first by a direct entry over cleared material
/// where one is at hand: `from` is a point of a segment of an earlier cut of the same
/// level (the nearest one, or an end) (the tool disc there was swept at this depth, and the tool is a cylinder, so the
/// whole column above it is air: feeding down there is no plunge into material), at most
/// `max_link` from the cut's start, joined to it by a straight feed move that crosses no loop
/// of `region` (the tool-centre region: the move cannot gouge). A direct entry costs a feed
/// down through one slab of air and the lead-in; a ramp at angle α costs `Δz / tan α` of path
/// at the plunge feed (114 mm for a 6 mm slab at 3°), so this is both safer for sliver cuts
/// (a cut too short to ramp along) and faster.
///
/// With `only_short`, only the cuts too short to ramp into get one, and the cuts keep their
/// order (a strategy that chose its ramps against the material it had left, in that order,
/// keeps both: a cut moved later would meet material the cuts planned after it counted as
/// gone). Without it, cuts too short to ramp into (shorter than `min_ramp_path`) are first
/// moved after the others, keeping their order, so that an earlier cut has cleared material
/// for them (a zigzag row grazing an island can be a few µm long, and may come first).
pub fn direct_entries(
    plan: &mut LevelPlan,
    region: &OffsetRegion,
    max_link: f64,
    min_ramp_path: f64,
    only_short: bool,
) {
    if !only_short {
        let (long, short): (Vec<Cut>, Vec<Cut>) =
            std::mem::take(&mut plan.cuts).into_iter().partition(|c| {
                !matches!(c.entry, CutEntry::Ramp) || path_length(&c.path) >= min_ramp_path
            });
        plan.cuts = long;
        plan.cuts.extend(short);
    }
    let mut cleared: Vec<Seg> = Vec::new();
    for cut in &mut plan.cuts {
        let short = path_length(&cut.path) < min_ramp_path;
        if let (CutEntry::Ramp, Some(first), true) =
            (cut.entry, cut.path.first(), short || !only_short)
        {
            let start = first.a;
            // Every point of an earlier cut's path was swept at this depth; the nearest
            // first (a row grazing an island beside a long straight of the clean-up pass is
            // far from that straight's ends), then the ends, the first whose link stays
            // inside the region.
            let mut candidates: Vec<(Point, f64)> = cleared
                .iter()
                .flat_map(|sg| [sg.closest_point(start), sg.b])
                .map(|q| (q, q.distance(start)))
                .filter(|&(_, d)| d <= max_link)
                .collect();
            candidates.sort_by(|a, b| a.1.total_cmp(&b.1));
            if let Some(&(q, _)) = candidates
                .iter()
                .take(MAX_ENTRY_CANDIDATES)
                .find(|&&(q, _)| !crosses(region, q, start))
            {
                cut.entry = CutEntry::Direct { from: q };
            }
        }
        cleared.extend(cut.path.iter().copied());
    }
}

/// How many points of earlier cuts, nearest first, [`direct_entries`] tries as a direct
/// entry's start before leaving a cut to its ramp.
const MAX_ENTRY_CANDIDATES: usize = 16;

/// Emits one cut with its entry (see the module docs).
fn emit_cut(
    tp: &mut Toolpath,
    opts: &PocketOptions,
    cut: &Cut,
    (top, z): (f64, f64),
    low_link: bool,
) -> Result<(), InputError> {
    let Some(first) = cut.path.first() else {
        return Ok(());
    };
    let clear = opts.clearance_height;
    let safe = top + opts.safe_height;
    let ccw = opts.direction == Direction::Climb;
    let ramp_angle = match opts.entry {
        Entry::Helix { ramp_angle, .. } | Entry::Ramp { ramp_angle } => ramp_angle,
    };
    let here = tp.end();
    if cut.entry == CutEntry::Linked && here.distance(Point3::from_xy(first.a, z)) <= 1e-9 {
        let rise = opts
            .adaptive
            .lift
            .min(0.5 * first.length() * ramp_angle.tan());
        let dir = (first.b - first.a)
            .normalize()
            .filter(|_| first.arc.is_none());
        if let (true, Some(u)) = (rise > 0.0, dir) {
            let run = rise / ramp_angle.tan();
            tp.push(Move::line(
                Point3::from_xy(first.a + u * run, z + rise),
                opts.feed,
            ));
            if first.length() - 2.0 * run > 1e-9 {
                tp.push(Move::line(
                    Point3::from_xy(first.b - u * run, z + rise),
                    opts.feed,
                ));
            }
            tp.push(Move::line(Point3::from_xy(first.b, z), opts.feed));
        } else {
            tp.push(seg_move(first, z, opts.feed));
        }
        for s in &cut.path[1..] {
            tp.push(seg_move(s, z, opts.feed));
        }
        return Ok(());
    }
    let (approach, ramp) = cut_approach(cut, opts, top, z)?;
    if low_link && (here.z - safe).abs() <= 1e-9 {
        // Over the level above, cleared: straight across at the safe height.
        if here.xy().distance(approach) > 1e-9 {
            tp.push(Move::rapid(Point3::from_xy(approach, safe)));
        }
    } else if here.xy().distance(approach) > 1e-9 || here.z < safe || tp.moves.is_empty() {
        // (The program's first move, even where the toolpath starts above the approach: a
        // program is read from wherever the machine is, and comes to the clearance height
        // before it goes down to the safe height.)
        if here.z < clear {
            tp.push(Move::rapid(Point3::from_xy(here.xy(), clear)));
        }
        tp.push(Move::rapid(Point3::from_xy(approach, clear)));
    }
    if tp.end().distance(Point3::from_xy(approach, safe)) > 1e-9 {
        tp.push(Move::rapid(Point3::from_xy(approach, safe)));
    }
    match cut.entry {
        CutEntry::Helix {
            center,
            radius,
            flat_turn,
        } => {
            let c = |h: f64| Point3::from_xy(center, h);
            let end = helix_approach(center, radius, first.a);
            let sweep = helix_sweep(safe - z, radius, ramp_angle);
            let pieces = (sweep / std::f64::consts::PI).ceil().max(1.0);
            // Bounded like the ramp's passes: a helix of millions of turns (a safe height of
            // 1e300 mm, found by the `pocket` fuzzer, asked for 3.5 GB of moves) is no entry.
            let fits = pieces <= 2.0 * MAX_RAMP_PASSES; // false for NaN
            if !fits {
                return Err(
                    InputError::new("helix entry", format!("{:.3e} turns", sweep / TAU))
                        .at(format!(
                            "--ramp-angle, --safe-height, --helix-radius; level at z = {z:.3}"
                        ))
                        .expected(format!(
                            "at most {MAX_RAMP_PASSES} turns: a lower safe height, a steeper ramp \
                     angle or a larger helix radius"
                        )),
                );
            }
            let pieces = pieces as usize;
            for k in 1..=pieces {
                // The last piece ends at the level's own height (`safe − (safe − z)` can
                // differ from `z` in its last bit, and round to another written depth) and at
                // `end` itself.
                let (h, xy) = if k == pieces {
                    (z, end)
                } else {
                    let f = k as f64 / pieces as f64;
                    (
                        safe - (safe - z) * f,
                        helix_point(center, end, sweep, ccw, sweep * f),
                    )
                };
                let to = Point3::from_xy(xy, h);
                // A piece too short to be an arc (a sweep of a few ulps) would read back as a
                // whole circle: it is a line.
                tp.push(if tp.end().xy().distance(xy) < 1e-6 {
                    Move::line(to, entry_feed(opts, ramp_angle))
                } else {
                    Move::arc_xy(to, c(h), ccw, entry_feed(opts, ramp_angle))
                });
            }
            if flat_turn {
                tp.push(Move::arc_xy(Point3::from_xy(end, z), c(z), ccw, opts.feed));
            }
            if end.distance(first.a) > 1e-9 {
                tp.push(Move::line(Point3::from_xy(first.a, z), opts.feed));
            }
        }
        CutEntry::Lap { len } => {
            let head = path_head(&cut.path, len);
            let drop = safe - z;
            let need = drop / ramp_angle.tan();
            let laps = (need / len).ceil().max(1.0);
            let fits = laps <= MAX_RAMP_PASSES; // false for NaN
            if !fits {
                return Err(
                    InputError::new("pocket entry", format!("{len:.4} mm of lap"))
                        .at(format!("level at z = {z:.3}"))
                        .expected("a loop long enough to ramp round"),
                );
            }
            let slope = drop / (len * laps);
            let feed = entry_feed(opts, ramp_angle);
            let mut h = safe;
            for _ in 0..laps as usize {
                h = descend(tp, &head, h, slope, z, feed);
            }
            finish_descent(tp, first.a, z, feed);
        }
        CutEntry::Direct { from } => {
            tp.push(Move::line(Point3::from_xy(from, z), opts.plunge_feed));
            if from.distance(first.a) > 1e-9 {
                tp.push(Move::line(Point3::from_xy(first.a, z), opts.feed));
            }
        }
        CutEntry::RampAlong { .. } => {
            let Some((head, passes)) = ramp else {
                return Ok(());
            };
            let head_len = path_length(&head);
            let slope = (safe - z) / (head_len * passes as f64);
            let mut h = safe;
            for p in 0..passes {
                let segs: Vec<Seg> = if p % 2 == 0 {
                    head.clone()
                } else {
                    head.iter().rev().map(Seg::reversed).collect()
                };
                h = descend(tp, &segs, h, slope, z, entry_feed(opts, ramp_angle));
            }
            for s in path_tail(&cut.path, head_len) {
                tp.push(seg_move(&s, z, opts.feed));
            }
            return Ok(());
        }
        CutEntry::Ramp | CutEntry::Linked => {
            let Some((head, passes)) = ramp else {
                return Ok(());
            };
            let drop = safe - z;
            let head_len = path_length(&head);
            let slope = drop / (head_len * passes as f64);
            let feed = entry_feed(opts, ramp_angle);
            let mut h = safe;
            for p in 0..passes {
                let segs: Vec<Seg> = if (passes - p) % 2 == 0 {
                    head.clone()
                } else {
                    head.iter().rev().map(Seg::reversed).collect()
                };
                h = descend(tp, &segs, h, slope, z, feed);
            }
            finish_descent(tp, first.a, z, feed);
        }
    }
    for s in &cut.path {
        tp.push(seg_move(s, z, opts.feed));
    }
    Ok(())
}

/// Moves along `segs` at `feed` from the height `h`, dropping `slope` per mm of the plane
/// (never below the level `z`, snapped to it at the end); the height reached.
fn descend(tp: &mut Toolpath, segs: &[Seg], mut h: f64, slope: f64, z: f64, feed: f64) -> f64 {
    for s in segs {
        h = snap_to_level(h - slope * s.length(), z);
        tp.push(seg_move(s, h, feed));
    }
    h
}

/// Where a descent ended above the level `z`, the rest of the way down at `to`.
fn finish_descent(tp: &mut Toolpath, to: Point, z: f64, feed: f64) {
    if tp.end().z > z + 1e-9 {
        tp.push(Move::line(Point3::from_xy(to, z), feed));
    }
}

/// Where the tool comes down for `cut` at the level from `top` to `z` (the helix's start,
/// the ramp's first point, or the cleared point of a direct entry), and the ramp's head and
/// passes when it ramps.
type Ramp = (Vec<Seg>, usize);
fn cut_approach(
    cut: &Cut,
    opts: &PocketOptions,
    top: f64,
    z: f64,
) -> Result<(Point, Option<Ramp>), InputError> {
    let Some(first) = cut.path.first() else {
        return Ok((Point::ORIGIN, None));
    };
    let safe = top + opts.safe_height;
    let ccw = opts.direction == Direction::Climb;
    let ramp_angle = match opts.entry {
        Entry::Helix { ramp_angle, .. } | Entry::Ramp { ramp_angle } => ramp_angle,
    };
    // A ramp: back and forth along the head of the path, descending all the way, ending at
    // the path's start; an odd number of passes starts at the head's far end.
    let ramp = match cut.entry {
        CutEntry::Ramp | CutEntry::Linked => Some(ramp_passes(&cut.path, safe - z, ramp_angle, z)?),
        CutEntry::RampAlong { max_len } => {
            // An odd number of passes over a head of at most `max_len`: the first from the
            // path's start, the last ending at the head's far end.
            let need = (safe - z) / ramp_angle.tan();
            let passes = ((need / max_len - 1e-9).ceil().max(1.0) / 2.0).floor() * 2.0 + 1.0;
            let fits = passes <= MAX_RAMP_PASSES; // false for NaN
            if !fits {
                // As for a ramp along a sliver: no room, and never a plunge.
                return Err(
                    InputError::new("pocket entry", format!("{max_len:.4} mm of row"))
                        .at(format!("level at z = {z:.3}"))
                        .expected("a first row long enough to ramp along"),
                );
            }
            Some((path_head(&cut.path, need / passes), passes as usize))
        }
        _ => None,
    };
    let approach = match (cut.entry, &ramp) {
        (CutEntry::Helix { center, radius, .. }, _) => {
            let end = helix_approach(center, radius, first.a);
            helix_point(
                center,
                end,
                helix_sweep(safe - z, radius, ramp_angle),
                ccw,
                0.0,
            )
        }
        (CutEntry::Ramp | CutEntry::Linked, Some((head, passes))) if passes % 2 == 1 => {
            head.last().map_or(first.a, |g| g.b)
        }
        (CutEntry::Direct { from }, _) => from,
        _ => first.a,
    };
    Ok((approach, ramp))
}

/// The feed of a helical or ramp entry descending at `ramp_angle`: the one whose descent is
/// the plunge feed, `plunge_feed / sin α`, at most the feed (a 3° ramp at 200 in/min plunge
/// runs at 600 in/min). The tool goes down no faster than when plunging; along the ramp it
/// cuts a slot, which the feed modulation slows for like any other.
pub fn entry_feed(opts: &PocketOptions, ramp_angle: f64) -> f64 {
    (opts.plunge_feed / ramp_angle.sin()).min(opts.feed)
}

/// The head of `path` a ramp entry descending `drop` at `ramp_angle` runs along, and how many
/// passes it makes over it (to the level at `z`): the head as long as the ramp needs, or the
/// whole path when shorter, passed over as often as the descent takes.
fn ramp_passes(
    path: &[Seg],
    drop: f64,
    ramp_angle: f64,
    z: f64,
) -> Result<(Vec<Seg>, usize), InputError> {
    let Some(first) = path.first() else {
        return Ok((Vec::new(), 0));
    };
    let cut_path = path;
    let total = path_length(cut_path);
    let need = drop / ramp_angle.tan();
    let len = need.min(total).max(1e-6);
    let head = path_head(cut_path, len);
    let head_len = path_length(&head);
    // Less a rounding's worth: a head cut to exactly the length needed sums a few ulps short
    // of it, and one pass would become two.
    let passes = (need / head_len - 1e-9).ceil().max(1.0);
    let fits = passes <= MAX_RAMP_PASSES; // false for NaN
    if !fits {
        // A sliver cut (a path shorter than need / MAX_RAMP_PASSES, e.g. a loop a few
        // µm long) has no room to ramp along, and no cleared point was at hand for a
        // direct entry ([`direct_entries`]): entering it would take a plunge into
        // material, which we never do.
        return Err(
            InputError::new("pocket entry", format!("{:.4} mm of path", total))
                .at(format!(
                    "the cut from ({:.3}, {:.3}), level at z = {z:.3}",
                    first.a.x, first.a.y
                ))
                .expected(format!(
                    "a cut long enough to ramp into, or beside cleared material: only a \
                     plunge reaches this one (a smaller tool, a pre-drilled entry, or \
                     levels whose descent, the safe height plus the step-down, is at most \
                     {:.3} mm)",
                    total * MAX_RAMP_PASSES * ramp_angle.tan()
                )),
        );
    }
    Ok((head, passes as usize))
}

/// The height `h` of a ramp descending to the level `z`: `z` itself once `h` is within
/// `1e-9·(1 + |z|)` mm of it or below. The ramp's heights are sums of slopes times lengths,
/// and one a few ulps above `z` was written at another depth than the level (`-0.224` and
/// `-0.225` for `z = -0.2245`): the verifier then saw two levels, and the material between
/// them uncut.
pub fn snap_to_level(h: f64, z: f64) -> f64 {
    if h - z <= 1e-9 * (1.0 + z.abs()) {
        z
    } else {
        h
    }
}

/// The angle a helix of `radius` turns through descending `drop` at `ramp_angle`:
/// `drop / (ρ·tan α)` radians, not rounded to whole turns.
fn helix_sweep(drop: f64, radius: f64, ramp_angle: f64) -> f64 {
    drop / (radius * ramp_angle.tan())
}

/// The point of a helix about `center` that ends at `end` after turning `sweep` radians
/// (counter-clockwise when `ccw`), `turned` radians after its start.
fn helix_point(center: Point, end: Point, sweep: f64, ccw: bool, turned: f64) -> Point {
    let back = if ccw { turned - sweep } else { sweep - turned };
    let u = end - center;
    let (s, c) = back.sin_cos();
    center + Vec2::new(u.x * c - u.y * s, u.x * s + u.y * c)
}

/// Where a helix about `center` of `radius` ends (and, turning whole turns, starts): on the ray from the centre to the
/// cut's start `to` (so the lead-in is radial and as short as it can be, and turns with the
/// pocket), or at `+x` when the cut starts at the centre.
pub fn helix_approach(center: Point, radius: f64, to: Point) -> Point {
    center
        + (to - center)
            .normalize()
            .map_or(Vec2::new(radius, 0.0), |u| u * radius)
}

/// The shortest path a ramp entry can use at any level of `opts`: the drop (safe height plus
/// the thickest slab) over `MAX_RAMP_PASSES · tan α`.
pub fn min_ramp_path(opts: &PocketOptions) -> f64 {
    let ramp_angle = match opts.entry {
        Entry::Helix { ramp_angle, .. } | Entry::Ramp { ramp_angle } => ramp_angle,
    };
    let depths = level_depths(opts);
    let slab = depths
        .iter()
        .scan(0.0, |top, &z| {
            let t = *top - z;
            *top = z;
            Some(t)
        })
        .fold(0.0, f64::max);
    (opts.safe_height + slab) / (MAX_RAMP_PASSES * ramp_angle.tan())
}

/// The most back-and-forth passes a ramp entry makes; a cut too short for this many passes to
/// reach the depth at the ramp angle, with no cleared point to enter from, is refused.
const MAX_RAMP_PASSES: f64 = 1000.0;

#[cfg(test)]
mod tests;
