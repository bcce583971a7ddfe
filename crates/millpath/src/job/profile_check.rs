//! The checks a profile passes before it is written (see [`super::profile`]'s module docs):
//! the dense band check, the exact wall clearance, the tab middle lines and, when tabs were
//! asked for, the bridge verdict of the height-field stock simulation.

use crate::geom::{Outline, Point, Point3};
use crate::stock::{BridgeOptions, CutSide, FieldOptions, HeightField, held_by};
use crate::strategy::profile::{
    ProfileOptions, ProfileResult, ProfileSide, ProfileTarget, TabCount, dense_band_check,
};
use crate::toolpath::{Move, MoveKind, Tool, Toolpath};
use crate::{Error, InputError};
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
    for cut in &res.cuts {
        let t = &targets[cut.target];
        let step = band_step(opts.tolerance, t.outline.length());
        let (mut lo, mut hi, mut samples) = (f64::INFINITY, 0.0_f64, 0);
        for range in &cut.finish_moves {
            let b = dense_band_check(&t.outline, tp, range.clone(), step);
            lo = lo.min(b.min_mm);
            hi = hi.max(b.max_mm);
            samples += b.samples;
        }
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
        for row in &mut rows {
            row.tabs = Some(bridge_verdict(targets, res, row.index - 1, r, opts)?);
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

/// No move below a tab's top comes within the tool radius of the tab's middle line.
fn check_tabs(targets: &[ProfileTarget], res: &ProfileResult, r: f64) -> Result<(), Error> {
    let tp = &res.toolpath;
    for tab in &res.tabs {
        let o = &targets[tab.target].outline;
        let d = res
            .cuts
            .iter()
            .find(|c| c.target == tab.target)
            .map_or(r, |c| c.offset_used_mm);
        let line = tab_line(o, tab.s, tab.width, d, targets[tab.target].side);
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
            let n = (len / 0.01).ceil().max(1.0) as usize;
            for j in 0..=n {
                let q = m.point_at(from, len * j as f64 / n as f64);
                if q.z >= tab.top_z - 1e-9 {
                    continue;
                }
                let near = line
                    .iter()
                    .map(|p| p.distance(q.xy()))
                    .fold(f64::INFINITY, f64::min);
                if near < r - 1e-6 {
                    return Err(Error::internal(format!(
                        "the profile would cut the tab at ({:.4}, {:.4}) of outline {} (move {k} at z {:.4}); not written",
                        tab.at.x,
                        tab.at.y,
                        tab.target + 1,
                        q.z
                    )));
                }
            }
        }
    }
    Ok(())
}

/// The tab's middle line: the outline's stretch under it, every 0.01 mm, moved `d` to the free
/// side (the outline's own geometry: points and normals by arc length).
fn tab_line(o: &Outline, s: f64, w: f64, d: f64, side: ProfileSide) -> Vec<Point> {
    let n = (w / 0.01).ceil().max(2.0) as usize;
    let ccw = o.signed_area() > 0.0;
    let free_left = match side {
        ProfileSide::Inside => ccw,
        _ => !ccw,
    };
    let h = 1e-4;
    (0..=n)
        .map(|j| {
            let sj = s - 0.5 * w + w * j as f64 / n as f64;
            let p = point_at_length(o, sj);
            let t = (point_at_length(o, sj + h) - point_at_length(o, sj - h))
                .normalize()
                .unwrap_or(crate::geom::Vec2::new(1.0, 0.0));
            p + if free_left { t.perp() } else { -t.perp() } * d
        })
        .collect()
}

/// The point of the outline at arc length `s` from its first vertex (the outline's own
/// sampling, [`Outline::sample`] style, by walking its segments).
fn point_at_length(o: &Outline, s: f64) -> Point {
    let v: Vec<(Point, f64)> = o.vertices().collect();
    let n = v.len();
    let total = o.length();
    let mut s = s.rem_euclid(total);
    for i in 0..n {
        let (a, b) = v[i];
        let e = v[(i + 1) % n].0;
        let chord = e.distance(a);
        let sweep = 4.0 * b.atan();
        let len = if b.abs() < 1e-12 {
            chord
        } else {
            chord * 0.5 * sweep.abs() / (0.5 * sweep).sin().abs()
        };
        if s <= len || i + 1 == n {
            let f = if len > 0.0 {
                (s / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if b.abs() < 1e-12 {
                return a.lerp(e, f);
            }
            // Rotate the start about the centre by the swept fraction.
            let u = (e - a)
                .normalize()
                .unwrap_or(crate::geom::Vec2::new(1.0, 0.0));
            let centre = a.lerp(e, 0.5) + u.perp() * (chord * (1.0 - b * b) / (4.0 * b));
            return centre + (a - centre).rotate(sweep * f);
        }
        s -= len;
    }
    v[0].0
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
        &FieldOptions::default().with_tool_diameter(2.0 * r),
    )?;
    field.cut(&res.toolpath);
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

/// How far beyond the tool radius a move's box may lie from an outline's box and still be
/// measured against it, mm (the finishing offset's tolerance and stock to leave are less).
const NEAR: f64 = 1.0;

/// True when two boxes share a point.
fn overlaps(a: crate::geom::Aabb, b: crate::geom::Aabb) -> bool {
    a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y
}

/// The box (in XY) of a move from `from`: its ends, and for an arc its whole circle.
fn move_box(from: Point3, m: &Move) -> crate::geom::Aabb {
    let b = crate::geom::Aabb::EMPTY
        .with_point(from.xy())
        .with_point(m.to.xy());
    match m.kind {
        MoveKind::Arc { center, .. } => {
            let c = center.xy();
            let rad = c.distance(from.xy()).max(c.distance(m.to.xy()));
            b.union(crate::geom::Aabb::EMPTY.with_point(c).inflate(rad))
        }
        _ => b,
    }
}

/// The box of a whole toolpath's moves.
fn path_box(tp: &Toolpath) -> crate::geom::Aabb {
    tp.segments().fold(
        crate::geom::Aabb::EMPTY.with_point(tp.start.xy()),
        |b, (f, m)| b.union(move_box(f, m)),
    )
}

/// The runs of consecutive moves of `tp` whose boxes meet `near`, each a toolpath starting
/// where its first move starts.
fn near_runs(tp: &Toolpath, near: crate::geom::Aabb) -> Vec<Toolpath> {
    let mut runs: Vec<Toolpath> = Vec::new();
    let mut open = false;
    for (from, m) in tp.segments() {
        if overlaps(move_box(from, m), near) {
            if !open {
                runs.push(Toolpath::new(tp.tool, from));
                open = true;
            }
            if let Some(run) = runs.last_mut() {
                run.moves.push(*m);
            }
        } else {
            open = false;
        }
    }
    runs
}
