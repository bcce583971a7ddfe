//! The checks a profile passes before it is written (see [`super::profile`]'s module docs):
//! the dense band check, the exact wall clearance, the tab middle lines and, when tabs were
//! asked for, the bridge verdict of the height-field stock simulation.

use super::profile_runs::{NEAR, near_runs, overlaps, path_box, runs_for_outline};
use crate::geom::{Outline, Point, Point3, Vec2};
use crate::stock::nearest::IndexedWall;
use crate::stock::{BridgeOptions, CutSide, FieldOptions, HeightField, held_by};
use crate::strategy::profile::{
    ProfileOptions, ProfileResult, ProfileSide, ProfileTarget, TabCount, dense_band_check,
};
use crate::toolpath::{Move, MoveKind, Plane, Tool, Toolpath};
use crate::{Error, InputError};
use cavalier_contours::polyline::{PlineSourceMut, PlineVertex, Polyline};
use rayon::prelude::*;
use serde::Serialize;

/// One outline in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetReport {
    /// 1-based index, in cutting order.
    pub index: usize,
    /// Side cut.
    pub side: String,
    /// Perimeter of the drawn outline, mm.
    pub perimeter_mm: f64,
    /// Nominal distance of the finished path from the outline, mm.
    pub offset_mm: f64,
    /// Loops cut.
    pub loops: usize,
    /// Arcs and lines of one finishing pass.
    pub arcs: usize,
    /// See `arcs`.
    pub lines: usize,
    /// The dense check: least and greatest distance of the finishing path from the outline.
    pub band_min_mm: f64,
    /// See `band_min_mm`.
    pub band_max_mm: f64,
    /// Samples of the dense check.
    pub band_samples: usize,
    /// With tabs asked for: the stock simulation's bridge verdict.
    pub tabs: Option<TabVerdict>,
}

/// What the height-field stock simulation finds holding a profiled piece.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct TabVerdict {
    /// `held by N bridges` or `falls free` (empty: not simulated, the cut being on the line
    /// or not through).
    pub hold: String,
    /// Bridges left in the slot.
    pub bridges: usize,
    /// Of these, the ones touching one side only (material in concave corners tighter than
    /// the tool, slivers at a tab's ends): they hold nothing.
    pub loose: usize,
    /// Each bridge's narrowest width along the outline, mm.
    pub necks_mm: Vec<f64>,
    /// The simulation's cell, mm.
    pub cell_mm: f64,
}

/// Spacing of the dense check's samples, mm: an eighth of the tolerance, no finer than the
/// outline's length over 200,000.
fn band_step(t: f64, perimeter: f64) -> f64 {
    (t / 8.0).max(perimeter / 200_000.0)
}

/// The checks of the module docs; the report's rows and the least clearance.
pub(crate) fn verify(
    targets: &[ProfileTarget],
    res: &ProfileResult,
    tool: &Tool,
    opts: &ProfileOptions,
) -> Result<(Vec<TargetReport>, f64), Error> {
    let r = tool.radius();
    let rho = opts.rounding;
    let tp = &res.toolpath;
    let mut rows = Vec::new();
    // Each cut's dense check on its own, side by side; judged below in the cuts' order.
    let bands: Vec<(f64, f64, f64, usize)> = res
        .cuts
        .par_iter()
        .map(|cut| {
            let t = &targets[cut.target];
            let step = band_step(opts.tolerance, t.outline.length());
            let (mut lo, mut hi, mut samples) = (f64::INFINITY, 0.0_f64, 0);
            for range in &cut.finish_moves {
                let b = dense_band_check(&t.outline, tp, range.clone(), step);
                lo = lo.min(b.min_mm);
                hi = hi.max(b.max_mm);
                samples += b.samples;
            }
            (step, lo, hi, samples)
        })
        .collect();
    for (cut, (step, lo, hi, samples)) in res.cuts.iter().zip(bands) {
        let t = &targets[cut.target];
        let d = cut.offset_mm;
        let (want_lo, want_hi) = if t.side == ProfileSide::On {
            (0.0, opts.tolerance - 2.0 * rho)
        } else {
            (d + 2.0 * rho, d + opts.tolerance - rho)
        };
        // The sampling bound (module docs of the check): half a step either way.
        let slack = 0.5 * step + 1e-9;
        let ok_lo = t.side == ProfileSide::On || lo + slack >= want_lo;
        if !(ok_lo && hi - slack <= want_hi) {
            return Err(Error::internal(format!(
                "the profile of outline {} leaves the band [{want_lo:.6}, {want_hi:.6}] mm of its outline: the dense check finds {lo:.6} to {hi:.6} mm; not written",
                cut.target + 1
            )));
        }
        rows.push(TargetReport {
            index: cut.target + 1,
            side: t.side.to_string(),
            perimeter_mm: t.outline.length(),
            offset_mm: d,
            loops: cut.loops,
            arcs: cut.arcs,
            lines: cut.lines,
            band_min_mm: lo,
            band_max_mm: hi,
            band_samples: samples,
            tabs: None,
        });
    }
    // The walls: every outside and inside outline, exactly, for every move below the top.
    let walls: Vec<(usize, &ProfileTarget)> = targets
        .iter()
        .enumerate()
        .filter(|(_, t)| t.side != ProfileSide::On)
        .collect();
    let mut min_clearance = f64::INFINITY;
    if !walls.is_empty() {
        let shifted = shift_to_zero_top(tp, opts.top_z);
        // A finishing loop that passes within the tool radius of another outline: the two
        // outlines are closer than the tool can pass between (the drawing's, not a bug).
        for cut in &res.cuts {
            for range in &cut.finish_moves {
                let part = Toolpath {
                    start: if range.start > 0 {
                        shifted.moves[range.start - 1].to
                    } else {
                        shifted.start
                    },
                    moves: shifted.moves[range.clone()].to_vec(),
                    levels: Vec::new(),
                    ..shifted.clone()
                };
                // Only the outlines whose boxes come within the tool radius of the loop's.
                let reach = path_box(&part).inflate(r);
                for (j, w) in walls
                    .iter()
                    .filter(|(j, w)| *j != cut.target && overlaps(reach, w.outline.bounds()))
                {
                    let spec = crate::stock::StockSpec {
                        outer: &w.outline,
                        islands: &[],
                        wall_stock: 0.0,
                    };
                    let c = crate::stock::min_clearance(&part, spec);
                    if c.distance < r {
                        return Err(InputError::new("tool diameter", 2.0 * r)
                            .at("--tool-diameter")
                            .expected(format!(
                                "a tool that passes between outlines {} and {}: cutting outline {} {} brings the tool centre {:.4} mm from outline {} at ({:.3}, {:.3})",
                                cut.target + 1, j + 1, cut.target + 1, cut.side, c.distance, j + 1, c.at.x, c.at.y
                            ))
                            .into());
                    }
                }
            }
        }
        // Each outline against the runs of moves whose boxes come within `NEAR` of its box:
        // a move farther off is farther than the tool radius from it, and each outline cut
        // has its own pass within the tool radius and its offset (the least clearance is
        // among the runs; measured against the whole path where no run is that near).
        let near = r + NEAR;
        let mut clearances = Vec::with_capacity(walls.len());
        for (_, w) in &walls {
            let spec = crate::stock::StockSpec {
                outer: &w.outline,
                islands: &[],
                wall_stock: 0.0,
            };
            let b = w.outline.bounds().inflate(near);
            let c = near_runs(&shifted, b)
                .iter()
                .map(|run| crate::stock::min_clearance(run, spec))
                .min_by(|a, b| a.distance.total_cmp(&b.distance));
            clearances.push((spec, c));
        }
        if clearances
            .iter()
            .all(|(_, c)| c.as_ref().is_none_or(|c| c.distance > near))
        {
            for (spec, c) in &mut clearances {
                *c = Some(crate::stock::min_clearance(&shifted, *spec));
            }
        }
        for c in clearances.into_iter().filter_map(|(_, c)| c) {
            min_clearance = min_clearance.min(c.distance);
            if c.distance < r - 1e-9 {
                return Err(Error::internal(format!(
                    "the profile would gouge: the tool centre comes {:.6} mm from an outline at ({:.4}, {:.4}, {:.4}) (move {}), less than the tool radius {r} mm; not written",
                    c.distance, c.at.x, c.at.y, c.at.z, c.move_index
                )));
            }
        }
        let boxes: Vec<_> = walls.iter().map(|(_, w)| w.outline.bounds()).collect();
        let within = |side: ProfileSide, p: Point| {
            walls
                .iter()
                .zip(&boxes)
                .filter(|((_, w), b)| w.side == side && b.contains(p) && w.outline.contains(p))
                .count()
        };
        let material = |p: Point| {
            let outside = within(ProfileSide::Outside, p);
            let inside = within(ProfileSide::Inside, p);
            outside > inside
        };
        for (k, m) in tp.moves.iter().enumerate() {
            if m.is_feed() && m.to.z < opts.top_z - 1e-9 && material(m.to.xy()) {
                return Err(Error::internal(format!(
                    "the profile would cut into the part at ({:.4}, {:.4}, {:.4}) (move {k}); not written",
                    m.to.x, m.to.y, m.to.z
                )));
            }
        }
    }
    check_tabs(targets, res, r)?;
    if opts.tabs.count != TabCount::None {
        // Each outline's verdict reads its own field: they run side by side, and the first
        // failure in the outlines' order is the one reported.
        let verdicts: Vec<Result<TabVerdict, Error>> = rows
            .par_iter()
            .map(|row| bridge_verdict(targets, res, row.index - 1, r, opts))
            .collect();
        for (row, v) in rows.iter_mut().zip(verdicts) {
            row.tabs = Some(v?);
        }
    }
    Ok((rows, min_clearance))
}

/// The toolpath with Z moved so that the stock top is at 0 (the clearance check measures
/// moves below Z = 0).
fn shift_to_zero_top(tp: &Toolpath, top: f64) -> Toolpath {
    if top == 0.0 {
        return tp.clone();
    }
    let mut t = tp.clone();
    t.start.z -= top;
    for m in &mut t.moves {
        m.to.z -= top;
        if let MoveKind::Arc { ref mut center, .. } = m.kind {
            center.z -= top;
        }
    }
    t
}

/// No move below a tab's top comes within the tool radius of the tab's middle line, measured
/// exactly: the middle line is the outline's stretch under the tab moved `d` to the free side
/// (lines and concentric arcs, [`tab_middle`]), and each feed move's part below the tab's top
/// (a line, or an arc in XY, cut where its z crosses the top) is measured whole against it
/// ([`IndexedWall::distance_to_segment`], `distance_to_arc`), whatever the drawing's scale.
fn check_tabs(targets: &[ProfileTarget], res: &ProfileResult, r: f64) -> Result<(), Error> {
    let tp = &res.toolpath;
    for tab in &res.tabs {
        let o = &targets[tab.target].outline;
        let d = res
            .cuts
            .iter()
            .find(|c| c.target == tab.target)
            .map_or(r, |c| c.offset_used_mm);
        let line = tab_middle(o, tab.at, tab.width, d, targets[tab.target].side);
        let wall = IndexedWall::new(&line);
        // Nothing of a move is nearer the tab than its start less its length.
        let reach = 0.5 * tab.width + d + r + 1.0;
        for (k, (from, m)) in tp.segments().enumerate() {
            if !m.is_feed() || (from.z >= tab.top_z - 1e-9 && m.to.z >= tab.top_z - 1e-9) {
                continue;
            }
            let len = m.length_from(from);
            if from.xy().distance(tab.at) - len > reach {
                continue;
            }
            let (near, q) = below_distance(&wall, from, m, tab.top_z - 1e-9);
            if near < r - 1e-6 {
                return Err(Error::internal(format!(
                    "the profile would cut the tab at ({:.4}, {:.4}) of outline {} (move {k} from ({:.4}, {:.4}, {:.4}) to ({:.4}, {:.4}, {:.4}), at ({:.4}, {:.4}, {:.4}) {near:.6} mm from the tab's middle line, below its top {:.4}); not written",
                    tab.at.x,
                    tab.at.y,
                    tab.target + 1,
                    from.x,
                    from.y,
                    from.z,
                    m.to.x,
                    m.to.y,
                    m.to.z,
                    q.x,
                    q.y,
                    q.z,
                    tab.top_z
                )));
            }
        }
    }
    Ok(())
}

/// The least XY distance from the part of move `m` (from `from`) below `top` to `wall`, and a
/// point of the move there. The part below is the path-length interval where the move's z
/// (linear along a line, and along a helix's sweep) is under `top`; a line and an arc in XY
/// are measured whole and exactly, an arc in another plane every 0.01 mm (times the
/// tool-size scale of the arc's radius), within half that.
fn below_distance(wall: &IndexedWall<'_>, from: Point3, m: &Move, top: f64) -> (f64, Point3) {
    let len = m.length_from(from);
    let (z0, z1) = (from.z, m.to.z);
    // The path-length interval [t0, t1] below the top.
    let (t0, t1) = if z0 < top && z1 < top {
        (0.0, len)
    } else {
        let t = len * ((top - z0) / (z1 - z0)).clamp(0.0, 1.0);
        if z0 < top { (0.0, t) } else { (t, len) }
    };
    let a = m.point_at(from, t0);
    if t1 - t0 <= 0.0 {
        return (wall.distance(a.xy()), a);
    }
    let piece = m.piece(from, t0, t1);
    match (piece.kind, piece.sweep_from(a)) {
        (
            MoveKind::Arc {
                center,
                plane: Plane::Xy,
                ..
            },
            Some((radius, sweep)),
        ) => {
            let a0 = (a.y - center.y).atan2(a.x - center.x);
            let (dist, rel) = wall.distance_to_arc(center.xy(), radius, a0, sweep);
            let f = if sweep != 0.0 {
                (rel / sweep).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (dist, piece.point_at(a, f * piece.length_from(a)))
        }
        (MoveKind::Arc { .. }, Some((radius, _))) => {
            let step = 0.01 * crate::toolpath::tolerance_scale(2.0 * radius);
            let n = ((t1 - t0) / step).ceil().max(1.0) as usize;
            (0..=n)
                .map(|j| {
                    let q = piece.point_at(a, (t1 - t0) * j as f64 / n as f64);
                    (wall.distance(q.xy()), q)
                })
                .fold((f64::INFINITY, a), |b, c| if c.0 < b.0 { c } else { b })
        }
        _ => {
            let (dist, p) = wall.distance_to_segment(a.xy(), piece.to.xy());
            let l = a.xy().distance(piece.to.xy());
            let f = if l > 0.0 { a.xy().distance(p) / l } else { 0.0 };
            (dist, a.lerp(piece.to, f.clamp(0.0, 1.0)))
        }
    }
}

/// An outline's line or arc: start, end, bulge, and for an arc its centre, radius and start
/// angle.
type Elem = (Point, Point, f64, Option<(Point, f64, f64)>);

/// The tab's middle line as a closed polyline traced there and back (so that the loop's
/// distance is the line's): the outline's stretch of `w` centred at its point nearest the
/// tab's `centre`, each line or arc of it moved `d` to the free side (a line parallel, an arc
/// concentric with the same sweep), from the outline's own vertices and bulges.
fn tab_middle(o: &Outline, centre: Point, w: f64, d: f64, side: ProfileSide) -> Polyline<f64> {
    let v: Vec<(Point, f64)> = o.vertices().collect();
    let n = v.len();
    let free_left = match side {
        ProfileSide::Inside => o.signed_area() > 0.0,
        _ => o.signed_area() <= 0.0,
    };
    // Each element: start, end, bulge, and for an arc its centre, radius and start angle.
    let elems: Vec<Elem> = (0..n)
        .map(|i| {
            let (a, b) = v[i];
            let e = v[(i + 1) % n].0;
            if b.abs() < 1e-12 {
                return (a, e, 0.0, None);
            }
            let chord = e.distance(a);
            let u = (e - a).normalize().unwrap_or(Vec2::new(1.0, 0.0));
            let c = a.lerp(e, 0.5) + u.perp() * (chord * (1.0 - b * b) / (4.0 * b));
            (a, e, b, Some((c, c.distance(a), (a - c).angle())))
        })
        .collect();
    let length = |e: &Elem| match e.3 {
        None => e.0.distance(e.1),
        Some((_, rad, _)) => rad * 4.0 * e.2.atan().abs(),
    };
    let lens: Vec<f64> = elems.iter().map(length).collect();
    let total: f64 = lens.iter().sum();
    // The point and the free-side normal of element `i` at the fraction `f`.
    let at = |i: usize, f: f64| -> (Point, Vec2) {
        let (a, e, b, arc) = elems[i];
        match arc {
            None => {
                let t = (e - a).normalize().unwrap_or(Vec2::new(1.0, 0.0));
                (a.lerp(e, f), if free_left { t.perp() } else { -t.perp() })
            }
            Some((c, rad, a0)) => {
                let phi = a0 + 4.0 * b.atan() * f;
                let radial = Vec2::new(phi.cos(), phi.sin());
                let t = if b > 0.0 {
                    radial.perp()
                } else {
                    -radial.perp()
                };
                (
                    c + radial * rad,
                    if free_left { t.perp() } else { -t.perp() },
                )
            }
        }
    };
    // The tab's centre: the outline's point nearest `centre` (the profile's arc lengths are its
    // own; the outline's, from its first vertex, are found here).
    let mut s = 0.0;
    let mut best = f64::INFINITY;
    let mut start = 0.0;
    for (i, e) in elems.iter().enumerate() {
        let (a, b, _, arc) = *e;
        let f = match arc {
            None => {
                let ab = b - a;
                let l2 = ab.dot(ab);
                if l2 > 0.0 {
                    ((centre - a).dot(ab) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                }
            }
            Some((c, _, a0)) => {
                let sweep = 4.0 * e.2.atan();
                let phi = (centre - c).angle() - a0;
                // The angle from the start along the sweep's turning sense, in [0, 2π).
                let rel = if sweep > 0.0 { phi } else { -phi }.rem_euclid(std::f64::consts::TAU);
                (rel / sweep.abs()).min(1.0)
            }
        };
        let mut cands = vec![f, 0.0, 1.0];
        cands.dedup();
        for f in cands {
            let q = at(i, f).0;
            let dist = q.distance(centre);
            if dist < best {
                best = dist;
                s = start + f * lens[i];
            }
        }
        start += lens[i];
    }
    let w = w.min(total);
    let mut pts: Vec<(Point, f64)> = Vec::new();
    let (mut i, mut u) = (0, (s - 0.5 * w).rem_euclid(total.max(1e-12)));
    while i < n && u > lens[i] {
        u -= lens[i];
        i += 1;
    }
    let mut left = w;
    for _ in 0..=n {
        if i >= n {
            i = 0;
        }
        let li = lens[i].max(1e-300);
        let take = (li - u).min(left).max(0.0);
        let (f0, f1) = (u / li, (u + take) / li);
        let (p0, n0) = at(i, f0);
        let (p1, n1) = at(i, f1);
        let bulge = (elems[i].2.atan() * (f1 - f0)).tan();
        let (q0, q1) = (p0 + n0 * d, p1 + n1 * d);
        if pts.last().is_none_or(|l| l.0.distance(q0) > 1e-12) {
            pts.push((q0, 0.0));
        }
        if q0.distance(q1) > 1e-12 {
            if let Some(l) = pts.last_mut() {
                l.1 = bulge;
            }
            pts.push((q1, 0.0));
        }
        left -= take;
        if left <= 1e-12 {
            break;
        }
        i += 1;
        u = 0.0;
    }
    let mut pl = Polyline::new_closed();
    for &(p, b) in &pts {
        pl.add(p.x, p.y, b);
    }
    // Back along the same pieces: each piece reversed is the same arc with its bulge negated.
    for k in (1..pts.len().saturating_sub(1)).rev() {
        pl.add(pts[k].0.x, pts[k].0.y, -pts[k - 1].1);
    }
    if pts.len() >= 2 {
        // The last point starts the way back: its bulge is the last piece's, negated.
        let last = pts.len() - 1;
        let b = -pts[last - 1].1;
        pl.set_vertex(last, PlineVertex::new(pts[last].0.x, pts[last].0.y, b));
    }
    pl
}

/// The cell of a bridge verdict's field for a tool of radius `r`, mm: the stock's default
/// cell ([`crate::stock::DEFAULT_CELL`] scaled with the tool, at most `r/8`), but no finer
/// than `r/16`. The band is then at least `2r − 4c − 2 µm ≥ 1.75 r` (28 cells) across and a
/// bridge's extent and neck are measured within `2c ≤ r/4`; finer cells only multiply the
/// field's cost (at 0.05 mm the slot of a 6 mm tool is 120 cells across).
fn verdict_cell(r: f64) -> f64 {
    let default = (crate::stock::DEFAULT_CELL * crate::toolpath::tolerance_scale(2.0 * r))
        .min(crate::stock::MAX_CELL_RADII * r);
    default.max(r / 16.0)
}

/// The height-field stock cut by the whole program, read for the bridges left in target
/// `ti`'s slot: each of its tabs must be matched by exactly one bridge holding the piece to the
/// stock, and every holding bridge by exactly one tab (a tab cut off, a tab missing or
/// material left across the slot is a failure). Every path from the piece to the stock
/// crosses the slot's band, so the piece is held by exactly those bridges and falls free
/// without them ([`crate::stock::held_by`]). Bridges touching one side only hold nothing:
/// material in concave corners tighter than the tool, which no tool position reaches, and
/// slivers a cell wide at a tab's ends; they are counted in the verdict.
fn bridge_verdict(
    targets: &[ProfileTarget],
    res: &ProfileResult,
    ti: usize,
    r: f64,
    opts: &ProfileOptions,
) -> Result<TabVerdict, Error> {
    let t = &targets[ti];
    let tabs: Vec<_> = res.tabs.iter().filter(|x| x.target == ti).collect();
    if t.side == ProfileSide::On || !opts.cuts_through() {
        return Ok(TabVerdict::default());
    }
    let reach = 2.0 * r + 2.0 * opts.lead_radius + 2.0 * opts.helix_radius + 1.0;
    let block = t.outline.bounds().inflate(reach);
    let mut field = HeightField::new(
        block,
        opts.bottom_z(),
        opts.top_z,
        &FieldOptions::default().with_cell(verdict_cell(r)),
    )?;
    // Only the runs of moves whose boxes come within the tool radius (and a chord's sagitta,
    // under 1 mm) of the field's cut it: a move farther off lowers none of its cells. Of
    // those, only the moves that come within `3r + 4c` (and that) of the outline: the bridge
    // verdict reads the cells within `2r + 3c` of it (the band, `2r` wide less its rims, where
    // the transform's distance is within a cell of the exact one, and the band's neighbours),
    // and a move lowers the cells within `r` of its path (`held_slot_reach`). Each cell ends
    // at the least height any move gives it, in whatever order the moves come, so the field
    // is the one the whole program leaves over those cells; so they are cut deepest first.
    field.cut_deepest_first(&runs_for_outline(&res.toolpath, &t.outline, &field));
    let side = match t.side {
        ProfileSide::Inside => CutSide::Inside,
        _ => CutSide::Outside,
    };
    let v = held_by(
        &field,
        &t.outline,
        opts.bottom_z(),
        r,
        &BridgeOptions::default().with_side(side),
    )?;
    let p = v.perimeter_mm;
    let covers = |b: &crate::stock::Bridge, s: f64| (s - b.start_mm).rem_euclid(p) <= b.length_mm;
    let holding: Vec<_> = v.holding().collect();
    let matched = tabs
        .iter()
        .all(|tab| holding.iter().filter(|b| covers(b, tab.s)).count() == 1)
        && holding
            .iter()
            .all(|b| tabs.iter().filter(|tab| covers(b, tab.s)).count() == 1);
    if !(matched && holding.len() == tabs.len()) {
        return Err(Error::internal(format!(
            "outline {}: the stock simulation finds {} where the profile placed {} tabs ({v}); not written",
            ti + 1,
            v.hold(),
            tabs.len()
        )));
    }
    Ok(TabVerdict {
        hold: v.hold().to_string(),
        bridges: v.bridges.len(),
        loose: v.bridges.len() - holding.len(),
        necks_mm: v.bridges.iter().map(|b| b.neck_mm).collect(),
        cell_mm: v.cell_mm,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::profile_runs::{move_box, runs_within, swept_box};

    /// A closed loop of lines through `pts`.
    fn outline(pts: &[(f64, f64)]) -> Outline {
        let v: Vec<(Point, f64)> = pts.iter().map(|&(x, y)| (Point::new(x, y), 0.0)).collect();
        Outline::new(&v, "test").unwrap()
    }

    /// Around an L-shaped part whose box holds a neighbour's slot in its notch (13 mm off
    /// its walls), the moves kept for its bridge field leave the neighbour's out, and the
    /// field they cut holds the whole program's heights at every cell within `2r + 3c` of
    /// the outline (the cells the verdict reads); the verdicts are the same.
    #[test]
    fn an_outlines_field_is_cut_by_the_moves_near_it() {
        let r = 3.0;
        let part = outline(&[
            (0.0, 0.0),
            (60.0, 0.0),
            (60.0, 20.0),
            (20.0, 20.0),
            (20.0, 60.0),
            (0.0, 60.0),
        ]);
        // A loop at `d` outside a rectangle, at each z, lifted to `tab` over x in `lift`.
        let slot = |tp: &mut Toolpath, (x0, y0, x1, y1): (f64, f64, f64, f64), lift: (f64, f64)| {
            let (x0, y0, x1, y1) = (x0 - r, y0 - r, x1 + r, y1 + r);
            tp.push(Move::rapid(Point3::new(x0, y0, 5.0)));
            for z in [-2.0, -4.0, -6.5] {
                tp.push(Move::line(Point3::new(x0, y0, z), 5.0));
                // Along the bottom edge, over the tab at z −4 or above.
                tp.push(Move::line(Point3::new(lift.0, y0, z), 10.0));
                let zt = z.max(-4.0);
                tp.push(Move::line(Point3::new(lift.0, y0, zt), 10.0));
                tp.push(Move::line(Point3::new(lift.1, y0, zt), 10.0));
                tp.push(Move::line(Point3::new(lift.1, y0, z), 10.0));
                for (x, y) in [(x1, y0), (x1, y1), (x0, y1), (x0, y0)] {
                    tp.push(Move::line(Point3::new(x, y, z), 10.0));
                }
            }
            tp.push(Move::rapid(Point3::new(x0, y0, 5.0)));
        };
        let mut tp = Toolpath::new(Tool::flat(2.0 * r).unwrap(), Point3::new(-10.0, -10.0, 5.0));
        // The neighbour in the notch, then the L (its outside, square corners: the slot
        // round the L's outside is what the rectangle's passes along x = 20, y = 20 would
        // cut; here the L's own loop goes round its six corners).
        slot(&mut tp, (36.0, 36.0, 55.0, 55.0), (44.0, 50.0));
        let d = r;
        tp.push(Move::rapid(Point3::new(-d, -d, 5.0)));
        for z in [-2.0, -4.0, -6.5] {
            tp.push(Move::line(Point3::new(-d, -d, z), 5.0));
            tp.push(Move::line(Point3::new(22.0, -d, z), 10.0));
            let zt = z.max(-4.0);
            tp.push(Move::line(Point3::new(22.0, -d, zt), 10.0));
            tp.push(Move::line(Point3::new(36.0, -d, zt), 10.0));
            tp.push(Move::line(Point3::new(36.0, -d, z), 10.0));
            for (x, y) in [
                (60.0 + d, -d),
                (60.0 + d, 20.0 + d),
                (20.0 + d, 20.0 + d),
                (20.0 + d, 60.0 + d),
                (-d, 60.0 + d),
                (-d, -d),
            ] {
                tp.push(Move::line(Point3::new(x, y, z), 10.0));
            }
        }
        tp.push(Move::rapid(Point3::new(-d, -d, 5.0)));
        let block = part.bounds().inflate(2.0 * r + 1.0);
        let opts = FieldOptions::default().with_cell(0.1);
        let mut whole = HeightField::new(block, -6.0, 0.0, &opts).unwrap();
        whole.cut(&tp);
        let mut near = HeightField::new(block, -6.0, 0.0, &opts).unwrap();
        let runs = runs_for_outline(&tp, &part, &near);
        near.cut_deepest_first(&runs);
        let kept: usize = runs.iter().map(|r| r.moves.len()).sum();
        // The neighbour's moves at and below its top (the rapids to it cross the L).
        let neighbour = 3 * 9;
        assert!(
            kept + neighbour <= tp.moves.len(),
            "{kept} of {} kept",
            tp.moves.len()
        );
        // The neighbour's slot is in the whole program's field and not in this one.
        let q = Point::new(36.0 - r, 45.0);
        assert!(whole.height_at(q).is_some_and(|h| h < -5.0));
        assert!(near.height_at(q).is_some_and(|h| h > -0.5));
        let wall = IndexedWall::new(part.polyline());
        let (c, (nx, ny)) = (near.cell(), near.dims());
        let mut read = 0;
        for j in 0..ny {
            for i in 0..nx {
                if wall.distance(near.centre(i, j)) > 2.0 * r + 3.0 * c {
                    continue;
                }
                read += 1;
                let (a, b) = (whole.height(i, j).unwrap(), near.height(i, j).unwrap());
                assert!(a.to_bits() == b.to_bits(), "cell ({i}, {j}): {a} vs {b}");
            }
        }
        assert!(read > nx * ny / 4, "{read} cells compared");
        let verdict = |f: &HeightField| {
            held_by(f, &part, -6.0, r, &BridgeOptions::default())
                .unwrap()
                .to_string()
        };
        let v = verdict(&near);
        assert_eq!(v, verdict(&whole));
        assert!(v.starts_with("held by 1 bridge"), "{v}");
    }

    /// The field cut by the runs of moves near it is the field the whole program leaves, cell
    /// by cell: lines, an arc and a helix in XY, and arcs in ZX whose ends lie far off while
    /// their middle passes over the field; moves far off are left out.
    #[test]
    fn the_runs_near_a_field_cut_it_as_the_whole_program_does() {
        let p = Point3::new;
        let xz = |to: Point3, center: Point3| Move {
            kind: MoveKind::Arc {
                center,
                plane: Plane::Zx,
                ccw: true,
                turns: 0,
            },
            ..Move::line(to, 10.0)
        };
        let mut tp = Toolpath::new(Tool::flat(6.0).unwrap(), p(-80.0, 0.0, 5.0));
        for m in [
            Move::line(p(-80.0, 0.0, -2.0), 5.0),
            Move::line(p(-60.0, 0.0, -2.0), 10.0),
            Move::rapid(p(-60.0, 0.0, 5.0)),
            Move::rapid(p(-20.0, 0.0, 5.0)),
            Move::line(p(-20.0, 0.0, -2.0), 5.0),
            Move::line(p(40.0, 0.0, -2.0), 10.0),
            Move::arc_xy(p(40.0, 20.0, -2.0), p(40.0, 10.0, -2.0), true, 10.0),
            Move::arc_xy(p(40.0, 0.0, -4.0), p(40.0, 10.0, -4.0), true, 10.0),
            Move::line(p(-20.0, 10.0, -4.0), 10.0),
            Move::rapid(p(-20.0, 10.0, 24.0)),
            xz(p(-20.0, 10.0, -26.0), p(-20.0, 10.0, -1.0)),
            xz(p(-20.0, 10.0, 24.0), p(-20.0, 10.0, -1.0)),
            Move::rapid(p(-80.0, 60.0, 5.0)),
            Move::line(p(-80.0, 60.0, -3.0), 5.0),
            Move::line(p(-70.0, 70.0, -3.0), 10.0),
            Move::rapid(p(-70.0, 70.0, 5.0)),
        ] {
            tp.push(m);
        }
        let block = crate::geom::Aabb {
            min: Point::new(0.0, -5.0),
            max: Point::new(30.0, 25.0),
        };
        let opts = FieldOptions::default().with_cell(0.1);
        let mut whole = HeightField::new(block, -10.0, 0.0, &opts).unwrap();
        whole.cut(&tp);
        let mut near = HeightField::new(block, -10.0, 0.0, &opts).unwrap();
        let runs = runs_within(&tp, near.bounds().inflate(3.0 + NEAR), swept_box);
        near.cut_deepest_first(&runs);
        let kept: usize = runs.iter().map(|r| r.moves.len()).sum();
        assert!(
            kept < tp.moves.len() - 4,
            "{kept} of {} kept",
            tp.moves.len()
        );
        let (nx, ny) = whole.dims();
        let mut cut = 0;
        for j in 0..ny {
            for i in 0..nx {
                let (a, b) = (whole.height(i, j).unwrap(), near.height(i, j).unwrap());
                assert!((a - b).abs() < 1e-12, "cell ({i}, {j}): {a} vs {b}");
                cut += usize::from(a < -0.5);
            }
        }
        assert!(cut > nx * ny / 10, "{cut} cells cut");
        // Only the ZX arcs (ends at x = −20, axis out to x = 5) reach (6, 12.5): the box of
        // their ends in XY would leave them out.
        let q = Point::new(6.0, 12.5);
        assert!(
            whole.height_at(q).is_some_and(|h| h < -5.0),
            "{:?}",
            whole.height_at(q)
        );
        let mut by_ends = HeightField::new(block, -10.0, 0.0, &opts).unwrap();
        for run in runs_within(&tp, near.bounds().inflate(3.0 + NEAR), move_box) {
            by_ends.cut(&run);
        }
        assert!(by_ends.height_at(q).is_some_and(|h| h > -0.5));
    }
}
