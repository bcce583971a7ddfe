//! One pass around the outline: exact offset, flattening, corner joins, trimming, and the
//! moves of a closed loop with its lead arcs.

use super::offset::{self, OffsetCurve, OffsetVertex};
use super::{ContourOptions, Side};
use crate::curve::flatten::{self, FlattenOptions};
use crate::curve::{CompositeCurve, PlanarCurve};
use crate::error::{Error, InputError};
use crate::geom::{Point, Point3, Vec2};
use crate::toolpath::Move;
use std::f64::consts::{PI, TAU};

/// A trimmed, flattened offset pass.
#[derive(Debug, Clone)]
pub struct Pass {
    /// Nominal signed offset `d` (left positive).
    pub distance: f64,
    /// The closed loops to cut (first vertex not repeated).
    pub loops: Vec<Vec<OffsetVertex>>,
    /// Measured max distance of the loops from the nominal offset (mm): sampled
    /// `|dist(q, outline) − |d||` over 16 points per segment.
    pub max_deviation: f64,
    /// Places the tool cannot reach.
    pub warnings: Vec<String>,
}

impl Pass {
    /// Segments of one pass around the outline (all loops).
    pub fn segments(&self) -> usize {
        self.loops.iter().map(Vec::len).sum()
    }
}

fn join_corner(curve: &CompositeCurve, k: usize, d_eff: f64, d_nom: f64, t: f64, out: &mut Vec<OffsetVertex>) {
    let c = curve.pieces()[k].p0;
    let n = curve.len();
    let oc = OffsetCurve::new(curve, d_eff);
    let (a, b) = (oc.point_at((k + n - 1) % n, 1.0), oc.point_at(k, 0.0));
    let r = d_eff.abs();
    let (a0, a1) = ((a - c).angle(), (b - c).angle());
    let mut short = (a1 - a0).rem_euclid(TAU);
    if short > PI {
        short -= TAU;
    }
    let long = short - TAU * short.signum();
    let mid = |sw: f64| c + Vec2::from_angle(a0 + 0.5 * sw) * r;
    let score = |sw: f64| offset::distance_to(curve, mid(sw), k as f64);
    let (best, dist) = [short, long]
        .into_iter()
        .map(|sw| (sw, score(sw)))
        .fold((0.0, f64::NEG_INFINITY), |acc, x| if x.1 > acc.1 { x } else { acc });
    if dist < d_nom.abs() || r <= 0.0 {
        return; // concave: straight crossing, trimmed later
    }
    let phi = 2.0 * (1.0 - (t / r).min(1.0)).acos();
    let steps = (best.abs() / phi.max(1e-9)).ceil().max(1.0) as usize;
    for j in 1..steps {
        let ang = a0 + best * j as f64 / steps as f64;
        out.push(OffsetVertex { p: c + Vec2::from_angle(ang) * r, s: k as f64 });
    }
}

/// Computes the pass at signed offset `d` (left positive; 0: on the outline) for `opt`'s
/// tolerance budget (see the [module docs](super)).
pub fn offset_pass(curve: &CompositeCurve, d: f64, opt: &ContourOptions) -> Result<Pass, Error> {
    let t = opt.chord_tolerance(d);
    let n = curve.len();
    if d == 0.0 {
        let f = flatten::flatten(curve, t)?;
        let lp: Vec<OffsetVertex> = f.params[..f.params.len() - 1]
            .iter()
            .zip(&f.points)
            .map(|(s, p)| OffsetVertex { p: *p, s: *s })
            .collect();
        let mut pass = Pass { distance: 0.0, loops: vec![lp], max_deviation: 0.0, warnings: Vec::new() };
        pass.max_deviation = measure(curve, &pass);
        return Ok(pass);
    }
    let d_eff = d.signum() * (d.abs() + opt.rounding + t);
    let oc = OffsetCurve::new(curve, d_eff);
    let f = flatten::flatten_opt(&oc, t, &FlattenOptions::default())?;
    let corners = curve.corners();
    let is_corner = |s: f64| s.fract() == 0.0 && corners.contains(&((s as usize) % n));
    let mut raw = vec![OffsetVertex { p: f.points[0], s: f.params[0] }];
    let last = f.params.len() - 1;
    for j in 1..=last {
        let s = f.params[j];
        if is_corner(s) {
            let k = (s as usize) % n;
            raw.push(OffsetVertex { p: oc.point_at((k + n - 1) % n, 1.0), s });
            join_corner(curve, k, d_eff, d, t, &mut raw);
            if j < last {
                raw.push(OffsetVertex { p: f.points[j], s });
            }
        } else if j < last {
            raw.push(OffsetVertex { p: f.points[j], s });
        }
    }
    for v in &mut raw {
        v.s = v.s.rem_euclid(n as f64);
    }
    let keep = d.abs() + opt.rounding + 0.5 * t;
    let trimmed = offset::trim(curve, &raw, keep);
    let mut warnings = Vec::new();
    for s in &trimmed.dropped {
        let (Some(first), Some(lastv)) = (s.first(), s.last()) else { continue };
        let at = curve.eval(first.s);
        let to = curve.eval(lastv.s);
        warnings.push(format!(
            "the tool (offset {:.4} mm) cannot reach the outline between ({:.3}, {:.3}) and ({:.3}, {:.3}) (curve parameter {:.4} to {:.4}): concave radius or corner tighter than the offset; left uncut",
            d.abs(), at.x, at.y, to.x, to.y, first.s, lastv.s
        ));
    }
    // Keep loops running the same way as the outline (counter-clockwise); an inverted loop
    // is an offset that collapsed.
    let loops: Vec<Vec<OffsetVertex>> = trimmed.loops.into_iter().filter(|l| offset::loop_area(l) > 0.0).collect();
    if loops.is_empty() {
        return Err(InputError::new("tool diameter", format!("{:.4} mm", 2.0 * opt.tool.radius()))
            .at(match opt.side {
                Side::Inside => "contour inside the outline",
                Side::Outside => "contour outside the outline",
                Side::On => "contour on the outline",
            })
            .expected(format!(
                "a tool whose radius plus allowance ({:.4} mm) fits inside the outline",
                d.abs()
            ))
            .into());
    }
    let mut pass = Pass { distance: d, loops, max_deviation: 0.0, warnings };
    pass.max_deviation = measure(curve, &pass);
    Ok(pass)
}

fn measure(curve: &CompositeCurve, pass: &Pass) -> f64 {
    let d = pass.distance.abs();
    let mut worst = 0.0_f64;
    for lp in &pass.loops {
        let m = lp.len();
        for i in 0..m {
            let (a, b) = (lp[i], lp[(i + 1) % m]);
            for j in 0..16 {
                let q = a.p.lerp(b.p, f64::from(j) / 16.0);
                worst = worst.max((offset::distance_to(curve, q, a.s) - d).abs());
            }
        }
    }
    worst
}

/// The moves of one closed loop at depth `z`: the XY entry point (start of the lead-in) and
/// the feed moves (lead-in arc, the loop tagged with the curve parameter, lead-out arc).
pub fn loop_moves(lp: &[OffsetVertex], z: f64, opt: &ContourOptions, pieces: usize) -> (Point, Vec<Move>) {
    let tag = |m: Move, s: f64| {
        let w = s.rem_euclid(pieces as f64);
        let i = w.floor();
        m.with_tag(i as u32, w - i)
    };
    let v0 = lp[0];
    let dir = lp.get(1).map_or(Vec2::new(1.0, 0.0), |v1| v1.p - v0.p).normalize().unwrap_or(Vec2::new(1.0, 0.0));
    // The free side: left of travel inside (towards the cavity's middle), right outside.
    let left = opt.side != Side::Outside;
    let nrm = if left { dir.perp() } else { -dir.perp() };
    let rl = opt.lead_radius;
    let p3 = |p: Point| Point3::from_xy(p, z);
    let mut moves = Vec::new();
    let entry;
    if rl > 0.0 {
        let c = v0.p + nrm * rl;
        entry = c - dir * rl;
        moves.push(Move::arc_xy(p3(v0.p), p3(c), left, opt.feed));
    } else {
        entry = v0.p;
    }
    for v in lp.iter().skip(1) {
        moves.push(tag(Move::line(p3(v.p), opt.feed), v.s));
    }
    moves.push(tag(Move::line(p3(v0.p), opt.feed), v0.s));
    if rl > 0.0 {
        let m = lp.len();
        let last = lp[m - 1];
        let dir_end = (v0.p - last.p).normalize().unwrap_or(dir);
        let nrm_end = if left { dir_end.perp() } else { -dir_end.perp() };
        let c = v0.p + nrm_end * rl;
        moves.push(Move::arc_xy(p3(c + dir_end * rl), p3(c), left, opt.feed));
    }
    (entry, moves)
}
