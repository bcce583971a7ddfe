//! The moves of a profile: per target, its offset loops, their levels (entry, loop with the
//! tabs lifted over, lead-out), then the finishing pass.
//!
//! # Entries and leads
//! Ramp entry: the tool feeds down to the level above at the point the ramp length before the
//! loop's start (to a tab's top, when that point is over a tab's lift), descends along the
//! loop to its start, cuts the loop and leaves by the
//! lead-out arc (the ramp's stretch is cut again at full depth at the end of the loop).
//! Helix entry: a helix of the helix radius beside the lead-in arc's start on the free side,
//! then the lead-in arc, the loop and the lead-out. The finishing pass enters and leaves
//! along half circles of diameter the stock left, from and to the roughing loop (cleared to
//! full depth), tangent to the finishing loop.

use super::bridges::{self, Bridge, Entry};
use super::elements::Loop;
use super::placing::{TabPlan, Walls, lifts_on, offset_loops};
use super::tabs::{TAB_RAMP_RUN, Tab};
use super::zpath::{ZProfile, along};
use super::{
    PlacedTab, ProfileEntry, ProfileNote, ProfileOptions, ProfileResult, ProfileSide,
    ProfileTarget, TabShape, TargetCut,
};
use crate::error::Error;
use crate::geom::{Outline, Point, Point3, Vec2};
use crate::strategy::contour::layer_depths;
use crate::strategy::contour::leads::{Lead, loop_moves};
use crate::strategy::contour::offset::OffsetVertex;
use crate::strategy::pocket::Direction;
use crate::toolpath::{Level, LevelKind, Move, Tool, Toolpath};
use std::f64::consts::PI;

/// The most helix turns per level; beyond it the entry is a ramp.
const MAX_HELIX_TURNS: f64 = 1000.0;

/// A loop ready to cut: its elements from its start, its free side and its tabs' lifts.
#[derive(Clone)]
struct Cut {
    lp: Loop,
    left: bool,
    /// Tab lifts as (centre arc length, half lift, top z).
    lifts: Vec<(f64, f64, f64)>,
}

/// True when the loop runs clockwise for this side and direction (module docs of `profile`).
fn clockwise(side: ProfileSide, direction: Direction) -> bool {
    let climb_cw = side == ProfileSide::Outside;
    climb_cw == (direction == Direction::Climb)
}

/// The free side is left of travel: inside a hole running counter-clockwise, outside a part
/// (or a line) running clockwise.
fn free_left(side: ProfileSide, cw: bool) -> bool {
    match side {
        ProfileSide::Inside => !cw,
        _ => cw,
    }
}

/// The arc length where the loop starts: the middle of its longest element stretch clear of
/// every lift (ties: the lowest, then leftmost, point).
fn start_of(lp: &Loop, lifts: &[(f64, f64, f64)], ramp_extra: f64) -> f64 {
    let len = lp.length;
    let mut best = (f64::NEG_INFINITY, 0.0, Point::ORIGIN);
    for (i, e) in lp.elems.iter().enumerate() {
        let (a, b) = (lp.starts[i], lp.starts[i] + e.length());
        let mut cuts: Vec<(f64, f64)> = Vec::new();
        for &(c, h, _) in lifts {
            let h = h + ramp_extra;
            for shift in [-len, 0.0, len] {
                let (lo, hi) = (c - h + shift, c + h + shift);
                if hi > a && lo < b {
                    cuts.push((lo.max(a), hi.min(b)));
                }
            }
        }
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut at = a;
        let mut free = Vec::new();
        for (lo, hi) in cuts {
            if lo > at {
                free.push((at, lo));
            }
            at = at.max(hi);
        }
        if b > at {
            free.push((at, b));
        }
        for (lo, hi) in free {
            let mid = 0.5 * (lo + hi);
            let p = lp.point(mid);
            let l = hi - lo;
            let tol = 1e-9 * (1.0 + len);
            let better = l > best.0 + tol
                || (l >= best.0 - tol
                    && (p.y < best.2.y - 1e-9
                        || (p.y - best.2.y).abs() <= 1e-9 && p.x < best.2.x - 1e-9));
            if better {
                best = (l, mid, p);
            }
        }
    }
    best.1
}

/// Samples of a circle of radius `rad` about `c`.
fn circle(c: Point, rad: f64) -> impl Iterator<Item = Point> {
    (0..32).map(move |k| c + Vec2::from_angle(f64::from(k) * PI / 16.0) * rad)
}

/// Goes to `p` (XY) at the clearance height (up first if lower), then feeds down to `z`.
fn approach(tp: &mut Toolpath, p: Point, z: f64, opts: &ProfileOptions) {
    let clear = opts.top_z + opts.clearance_height;
    let here = tp.end();
    let high = here.z.max(clear);
    if here.z < high {
        tp.push(Move::rapid(Point3::from_xy(here.xy(), high)));
    }
    if here.xy().distance(p) > 1e-9 {
        tp.push(Move::rapid(Point3::from_xy(p, high)));
    }
    if high > clear {
        tp.push(Move::rapid(Point3::from_xy(p, clear)));
    }
    tp.push(Move::line(Point3::from_xy(p, z), opts.plunge_feed));
}

/// The lead arc radius (`want`, halved up to four times, else 0) whose arcs keep `d` from
/// the outline on the free side and whose disc (`bridges` module docs, the tool's `sweep`
/// beyond it) reaches no other target's tab bridge.
fn lead_radius(
    cut: &Cut,
    (walls, bridges, sweep): (&Walls<'_>, &[Bridge], f64),
    own: (usize, &Outline, ProfileSide),
    d: f64,
    want: f64,
) -> f64 {
    let v0 = cut.lp.elems[0].start;
    let lp = [OffsetVertex { p: v0, s: 0.0 }];
    let mut rl = want;
    for _ in 0..5 {
        if rl <= 0.0 {
            break;
        }
        let lead = Lead {
            radius: rl,
            left: cut.left,
            feed: 1.0,
        };
        let (entry, moves) = loop_moves(&lp, Some(&cut.lp.elems), 0.0, &lead, 1);
        let mut pts = Vec::new();
        for (m, from) in [(moves.first(), entry), (moves.last(), v0)] {
            if let Some(m) = m {
                let from = Point3::from_xy(from, 0.0);
                let l = m.length_from(from);
                pts.extend((0..=8).map(|k| m.point_at(from, l * f64::from(k) / 8.0).xy()));
            }
        }
        if walls.clear(own, d, pts) && bridges::entry_clear(bridges, own.0, v0, 2.0 * rl + sweep) {
            return rl;
        }
        rl *= 0.5;
    }
    0.0
}

/// A move of `plain` (made at z = 0) at height `z`.
fn at_z(m: &Move, z: f64) -> Move {
    let mut m = *m;
    m.to.z = z;
    if let crate::toolpath::MoveKind::Arc { ref mut center, .. } = m.kind {
        center.z = z;
    }
    m
}

/// True when the loops `cuts` (at offset `d`) keep the tool radius, with a quarter of a
/// millimetre to spare for their sampling every 0.25 mm, from the tab's middle line (the
/// drawn outline under it moved `d` to the free side, sampled every 0.5 mm) and from the
/// line just beyond the slot, except over the tab's own lift and a millimetre either side.
/// The millimetres are those of a tool up to 12.7 mm, scaled with larger tools
/// ([`crate::toolpath::tolerance_scale`]): a 3.7 m tool on a 56 × 70 m drawing sampled its
/// 250 m loops every 0.25 mm against a 7.4 m tab line every 0.5 mm, for hours.
fn clear_of_own_path(tab: &Tab, drawn: &Loop, cuts: &[Cut], d: f64, r: f64) -> bool {
    let (s, w) = (tab.placed.s, tab.placed.width);
    let scale = crate::toolpath::tolerance_scale(2.0 * r);
    let left = tab.free_normal.dot(drawn.tangent(s).perp()) > 0.0;
    let n = ((w / (0.5 * scale)).ceil() as usize).max(2);
    // The middle line, and the line just beyond the slot's far wall: the material the tab
    // joins there must stand too (a pass across a narrow channel can take it away).
    let line: Vec<Point> = [d, d + r + 0.5 * scale]
        .into_iter()
        .flat_map(|off| {
            (0..=n).map(move |k| {
                let sk = s - 0.5 * w + w * k as f64 / n as f64;
                let t = drawn.tangent(sk);
                drawn.point(sk) + if left { t.perp() } else { -t.perp() } * off
            })
        })
        .collect();
    let mid = tab.placed.at + tab.free_normal * d;
    cuts.iter().all(|cut| {
        let (c, dist) = cut.lp.project(mid);
        let skip = if dist <= 1e-6 * (1.0 + d) + tab.off_path(d) {
            tab.half_lift(d) + scale
        } else {
            -1.0
        };
        let len = cut.lp.length;
        let m = ((len / (0.25 * scale)).ceil() as usize).max(1);
        (0..m).all(|k| {
            let sk = len * k as f64 / m as f64;
            let off = ((sk - c + 0.5 * len).rem_euclid(len) - 0.5 * len).abs();
            off <= skip || {
                let q = cut.lp.point(sk);
                line.iter().all(|p| p.distance(q) >= r + 0.25 * scale)
            }
        })
    })
}

/// Per target, the tabs [`generate`] places (before any entry is made: an entry's disc may
/// still take one away) and the count asked for.
pub(super) fn tab_counts(
    targets: &[ProfileTarget],
    tool: &Tool,
    opts: &ProfileOptions,
) -> Vec<(usize, usize)> {
    let r = tool.radius();
    let m = bridges::margin(r);
    let plan = TabPlan::new(targets, r, m, opts);
    targets
        .iter()
        .enumerate()
        .map(|(ti, t)| {
            if opts.tabs.count == super::TabCount::None
                || t.side == ProfileSide::On
                || !opts.cuts_through()
            {
                return (0, 0);
            }
            let d_fin = r + 0.5 * opts.tolerance;
            let d_rough = d_fin + opts.stock_to_leave;
            let (mut tabs, asked) = plan.place(ti, d_fin, d_rough, &[]);
            let drawn = Loop::of_outline(&t.outline);
            let cuts = |d: f64| -> Vec<Cut> {
                offset_loops(&t.outline, t.side, d)
                    .into_iter()
                    .map(|lp| Cut {
                        lp,
                        left: false,
                        lifts: Vec::new(),
                    })
                    .collect()
            };
            let (fin, rough) = (cuts(d_fin), cuts(d_rough));
            tabs.retain(|tab| {
                clear_of_own_path(tab, &drawn, &fin, d_fin, r)
                    && clear_of_own_path(tab, &drawn, &rough, d_rough, r)
            });
            (tabs.len(), asked)
        })
        .collect()
}

/// Plans every target.
pub(super) fn generate(
    targets: &[ProfileTarget],
    tool: &Tool,
    opts: &ProfileOptions,
) -> Result<ProfileResult, Error> {
    let r = tool.radius();
    let safe = opts.top_z + opts.safe_height;
    let mut tp = Toolpath::new(*tool, Point3::new(0.0, 0.0, safe));
    let mut notes = Vec::new();
    let mut placed: Vec<PlacedTab> = Vec::new();
    let mut cuts_out = Vec::new();
    let zs = layer_depths(opts.top_z, opts.depth, opts.step_down);
    let bottom = opts.top_z - opts.depth;
    // The tabs' bridges and the entries' discs so far, and the slack on their tests.
    let mut bridges: Vec<Bridge> = Vec::new();
    let mut entries: Vec<Entry> = Vec::new();
    let m = bridges::margin(r);
    let plan = TabPlan::new(targets, r, m, opts);
    let walls = &plan.walls;
    for (ti, t) in targets.iter().enumerate() {
        let side = t.side;
        let own = (ti, &t.outline, side);
        let band = if side == ProfileSide::On {
            0.0
        } else {
            0.5 * opts.tolerance
        };
        let nominal = if side == ProfileSide::On { 0.0 } else { r };
        let d_fin = nominal + band;
        let stock = if side == ProfileSide::On {
            0.0
        } else {
            opts.stock_to_leave
        };
        let d_rough = d_fin + stock;
        let mut asked_tabs = 0;
        let drawn = Loop::of_outline(&t.outline);
        let mut tabs_here: Vec<Tab> = if opts.tabs.count == super::TabCount::None {
            Vec::new()
        } else if side == ProfileSide::On {
            notes.push(ProfileNote::NoTabs {
                target: ti,
                reason: "the cut is on the line",
            });
            Vec::new()
        } else if !opts.cuts_through() {
            notes.push(ProfileNote::NoTabs {
                target: ti,
                reason: "the cut does not reach the stock's bottom",
            });
            Vec::new()
        } else {
            let (v, asked) = plan.place(ti, d_fin, d_rough, &entries);
            asked_tabs = asked;
            v
        };
        let cw = clockwise(side, opts.direction);
        let left = free_left(side, cw);
        let make = |d: f64, tabs_here: &[Tab]| -> Vec<Cut> {
            offset_loops(&t.outline, side, d)
                .into_iter()
                .map(|l| {
                    let l = if cw { l.reversed() } else { l };
                    let lifts = lifts_on(&l, tabs_here, d);
                    let extra = if opts.tabs.shape == TabShape::Ramped {
                        TAB_RAMP_RUN * opts.tabs.height
                    } else {
                        0.0
                    };
                    let s0 = start_of(&l, &lifts, extra);
                    let l = l.rotated(s0);
                    let lifts = lifts_on(&l, tabs_here, d);
                    Cut { lp: l, left, lifts }
                })
                .collect()
        };
        let mut fin = make(d_fin, &tabs_here);
        if fin.is_empty() {
            notes.push(ProfileNote::NoRoom {
                target: ti,
                offset_mm: d_rough,
            });
            continue;
        }
        let mut rough = if stock > 0.0 {
            make(d_rough, &tabs_here)
        } else {
            fin.clone()
        };
        if rough.is_empty() {
            notes.push(ProfileNote::NoRoom {
                target: ti,
                offset_mm: d_rough,
            });
            continue;
        }
        // Not where the outline's own cut passes near elsewhere (across a narrow channel).
        if !tabs_here.is_empty() {
            let n0 = tabs_here.len();
            tabs_here.retain(|tab| {
                clear_of_own_path(tab, &drawn, &fin, d_fin, r)
                    && clear_of_own_path(tab, &drawn, &rough, d_rough, r)
            });
            if tabs_here.len() < n0 {
                fin = make(d_fin, &tabs_here);
                rough = if stock > 0.0 {
                    make(d_rough, &tabs_here)
                } else {
                    fin.clone()
                };
            }
        }
        if tabs_here.len() < asked_tabs {
            notes.push(ProfileNote::FewerTabs {
                target: ti,
                asked: asked_tabs,
                placed: tabs_here.len(),
            });
        }
        if fin.len() > 1 {
            notes.push(ProfileNote::SplitLoops {
                target: ti,
                loops: fin.len(),
            });
        }
        placed.extend(tabs_here.iter().map(|t| t.placed));
        bridges.extend(
            tabs_here
                .iter()
                .map(|tab| Bridge::of(ti, tab, &drawn, d_rough, r, m)),
        );
        let first_move = tp.moves.len();
        let mut finish_moves = Vec::new();
        let mut entry_note = false;
        let mut lead_note = false;
        let mut steep_note = false;
        for cut in &rough {
            let rl = lead_radius(
                cut,
                (walls, &bridges, r + m),
                own,
                d_rough - band,
                opts.lead_radius,
            );
            if rl < opts.lead_radius && !lead_note {
                lead_note = true;
                notes.push(ProfileNote::LeadReduced {
                    target: ti,
                    radius: rl,
                });
            }
            let lead = Lead {
                radius: rl,
                left: cut.left,
                feed: opts.feed,
            };
            let lp0 = [OffsetVertex {
                p: cut.lp.elems[0].start,
                s: 0.0,
            }];
            let n = cut.lp.elems.len();
            let (lead_entry, plain) = loop_moves(&lp0, Some(&cut.lp.elems), 0.0, &lead, n);
            // The helix beside the lead-in's start, on the free side, where it fits.
            let mut entry = opts.entry;
            let mut helix_c = Point::ORIGIN;
            if entry == ProfileEntry::Helix {
                // Centred `helix radius` ahead of the lead-in's start along the loop's start
                // tangent: the helix leaves tangent to the lead-in arc (the same circle when
                // the two radii are equal).
                helix_c = lead_entry + cut.lp.tangent(0.0) * opts.helix_radius;
                let pts = circle(helix_c, opts.helix_radius);
                // Turns per level, bounded (a ramp angle of 1e-7 rad asked for 10⁸).
                let pitch = 2.0 * PI * opts.helix_radius * opts.ramp_angle.tan();
                let turns = opts.step_down.min(opts.depth) / pitch;
                if rl <= 0.0
                    || turns > MAX_HELIX_TURNS
                    || !walls.clear(own, d_rough - band, pts)
                    || !bridges::entry_clear(&bridges, ti, helix_c, opts.helix_radius + r + m)
                {
                    entry = ProfileEntry::Ramp;
                    if !entry_note {
                        entry_note = true;
                        notes.push(ProfileNote::HelixToRamp { target: ti });
                    }
                }
            }
            // The discs this entry's lead arcs and helix sweep (`bridges` module docs).
            entries.push((cut.lp.elems[0].start, 2.0 * rl + r + m));
            if entry == ProfileEntry::Helix {
                entries.push((helix_c, opts.helix_radius + r + m));
            }
            let len = cut.lp.length;
            let mut z_prev = opts.top_z;
            for (li, &z) in zs.iter().enumerate() {
                let last = li + 1 == zs.len();
                let start = tp.moves.len();
                let mut at;
                match entry {
                    ProfileEntry::Ramp => {
                        let want = (z_prev - z) / opts.ramp_angle.tan();
                        let l = want.min(len);
                        if want > len && !steep_note {
                            steep_note = true;
                            notes.push(ProfileNote::SteepRamp {
                                target: ti,
                                angle_deg: ((z_prev - z) / len).atan().to_degrees(),
                            });
                        }
                        let s_from = len - l;
                        let p = cut.lp.point(s_from);
                        let zp = ZProfile {
                            z,
                            ramp: Some((s_from, l, z_prev)),
                            lifts: &cut.lifts,
                            shape: opts.tabs.shape,
                            bottom_z: opts.bottom_z(),
                            len,
                        };
                        // Down to the level above, or to a tab's top where the ramp starts
                        // over a tab's lift (a short loop's ramp can start there).
                        let z_start = zp.base(s_from).max(zp.tab(s_from, s_from));
                        approach(&mut tp, p, z_start, opts);
                        at = tp.end();
                        let mut mv = Vec::new();
                        along(&cut.lp, s_from, len, &zp, opts, &mut at, &mut mv);
                        tp.moves.extend(mv);
                    }
                    ProfileEntry::Helix => {
                        approach(&mut tp, lead_entry, z_prev, opts);
                        // Whole half turns at the ramp angle, about the helix centre.
                        let pitch = 2.0 * PI * opts.helix_radius * opts.ramp_angle.tan();
                        let halves = 2 * ((z_prev - z) / pitch).ceil().max(1.0) as usize;
                        let ang0 = (lead_entry - helix_c).angle();
                        for k in 1..=halves {
                            let a = ang0 + if cut.left { 1.0 } else { -1.0 } * PI * k as f64;
                            let zk = z_prev + (z - z_prev) * k as f64 / halves as f64;
                            let p = helix_c + Vec2::from_angle(a) * opts.helix_radius;
                            let p = if k % 2 == 0 { lead_entry } else { p };
                            tp.push(Move::arc_xy(
                                Point3::from_xy(p, zk),
                                Point3::from_xy(helix_c, zk),
                                cut.left,
                                opts.feed,
                            ));
                        }
                        // The lead-in arc at the level.
                        if let Some(m) = plain.first() {
                            tp.push(at_z(m, z));
                        }
                        at = tp.end();
                    }
                }
                let zp = ZProfile {
                    z,
                    ramp: None,
                    lifts: &cut.lifts,
                    shape: opts.tabs.shape,
                    bottom_z: opts.bottom_z(),
                    len,
                };
                let loop_start = tp.moves.len();
                let mut mv = Vec::new();
                along(&cut.lp, 0.0, len, &zp, opts, &mut at, &mut mv);
                tp.moves.extend(mv);
                let loop_end = tp.moves.len();
                if rl > 0.0 {
                    if let Some(m) = plain.last() {
                        tp.push(at_z(m, z));
                    }
                }
                tp.push(Move::rapid(Point3::from_xy(
                    tp.end().xy(),
                    opts.top_z + opts.clearance_height,
                )));
                tp.levels.push(Level {
                    z,
                    kind: if stock > 0.0 || !last {
                        LevelKind::Roughing
                    } else {
                        LevelKind::Finishing
                    },
                    start,
                    end: tp.moves.len(),
                });
                if stock <= 0.0 && last {
                    finish_moves.push(loop_start..loop_end);
                }
                z_prev = z;
            }
        }
        if stock > 0.0 {
            for cut in &fin {
                let start = tp.moves.len();
                let v0 = cut.lp.elems[0].start;
                let t0 = cut.lp.tangent(0.0);
                let n0 = if cut.left { t0.perp() } else { -t0.perp() };
                let entry = v0 + n0 * stock;
                approach(&mut tp, entry, bottom, opts);
                tp.push(Move::arc_xy(
                    Point3::from_xy(v0, bottom),
                    Point3::from_xy(v0 + n0 * (0.5 * stock), bottom),
                    cut.left,
                    opts.feed,
                ));
                let mut at = tp.end();
                let zp = ZProfile {
                    z: bottom,
                    ramp: None,
                    lifts: &cut.lifts,
                    shape: opts.tabs.shape,
                    bottom_z: opts.bottom_z(),
                    len: cut.lp.length,
                };
                let loop_start = tp.moves.len();
                let mut mv = Vec::new();
                along(&cut.lp, 0.0, cut.lp.length, &zp, opts, &mut at, &mut mv);
                tp.moves.extend(mv);
                finish_moves.push(loop_start..tp.moves.len());
                let t1 = super::elements::tangent_at(&cut.lp.elems[cut.lp.elems.len() - 1], 1.0);
                let n1 = if cut.left { t1.perp() } else { -t1.perp() };
                tp.push(Move::arc_xy(
                    Point3::from_xy(v0 + n1 * stock, bottom),
                    Point3::from_xy(v0 + n1 * (0.5 * stock), bottom),
                    cut.left,
                    opts.feed,
                ));
                tp.push(Move::rapid(Point3::from_xy(
                    tp.end().xy(),
                    opts.top_z + opts.clearance_height,
                )));
                tp.levels.push(Level {
                    z: bottom,
                    kind: LevelKind::Finishing,
                    start,
                    end: tp.moves.len(),
                });
            }
        }
        tp.push(Move::rapid(Point3::from_xy(tp.end().xy(), safe)));
        let (arcs, lines) = fin
            .iter()
            .flat_map(|c| c.lp.elems.iter())
            .fold((0, 0), |(a, l), e| {
                if e.center.is_some() {
                    (a + 1, l)
                } else {
                    (a, l + 1)
                }
            });
        cuts_out.push(TargetCut {
            target: ti,
            side,
            offset_mm: nominal,
            offset_used_mm: d_fin,
            loops: fin.len(),
            arcs,
            lines,
            moves: first_move..tp.moves.len(),
            finish_moves,
        });
    }
    Ok(ProfileResult {
        toolpath: tp,
        tabs: placed,
        cuts: cuts_out,
        notes,
    })
}
