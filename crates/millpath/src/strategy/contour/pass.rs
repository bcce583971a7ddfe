//! One pass around the outline: exact offset, flattening, corner joins, trimming, and the
//! moves of a closed loop with its lead arcs.

use super::offset::{self, OffsetCurve, OffsetVertex};
use super::{ContourOptions, ContourWarning, Side};
use crate::curve::biarc::{self, ArcSeg};
use crate::curve::flatten::{self, FlattenOptions};
use crate::curve::{CompositeCurve, Lobe, PlanarCurve};
use crate::error::{Error, InputError};
use crate::geom::{Point, Vec2};
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
    pub warnings: Vec<ContourWarning>,
    /// With `--arcs`: per loop, the biarcs (and connecting lines) that replace its chords,
    /// starting at the loop's first vertex. Empty for line output.
    pub arcs: Vec<Vec<ArcSeg>>,
}

impl Pass {
    /// Segments of one pass around the outline (all loops).
    pub fn segments(&self) -> usize {
        if self.arcs.is_empty() {
            self.loops.iter().map(Vec::len).sum()
        } else {
            self.arcs.iter().map(Vec::len).sum()
        }
    }
}

fn join_corner(
    curve: &CompositeCurve,
    k: usize,
    d_eff: f64,
    d_nom: f64,
    t: f64,
    out: &mut Vec<OffsetVertex>,
) {
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
    let (best, dist) = [short, long].into_iter().map(|sw| (sw, score(sw))).fold(
        (0.0, f64::NEG_INFINITY),
        |acc, x| if x.1 > acc.1 { x } else { acc },
    );
    if dist < d_nom.abs() || r <= 0.0 {
        return; // concave: straight crossing, trimmed later
    }
    let phi = 2.0 * (1.0 - (t / r).min(1.0)).acos();
    let steps = (best.abs() / phi.max(1e-9)).ceil().max(1.0) as usize;
    for j in 1..steps {
        let ang = a0 + best * j as f64 / steps as f64;
        out.push(OffsetVertex {
            p: c + Vec2::from_angle(ang) * r,
            s: k as f64,
        });
    }
}

/// Computes the pass at signed offset `d` (left positive; 0: on the outline) for `opt`'s
/// tolerance budget (see the [module docs](super)).
pub fn offset_pass(curve: &CompositeCurve, d: f64, opt: &ContourOptions) -> Result<Pass, Error> {
    let t = opt.chord_tolerance(d);
    let n = curve.len();
    if d == 0.0 {
        let f = flatten::flatten(curve, t)?;
        let mut lp: Vec<OffsetVertex> = Vec::with_capacity(f.points.len());
        for (s, p) in f.params[..f.params.len() - 1].iter().zip(&f.points) {
            lp.push(OffsetVertex { p: *p, s: *s });
            // The curve as drawn runs out to the corner point and back where a fish-tail
            // lobe was cut off there: on the outline, the tool traces it too.
            if s.fract() == 0.0 {
                let k = (*s as usize) % n;
                for lobe in curve.lobes().iter().filter(|l| l.corner == k) {
                    lp.extend(lobe_vertices(lobe, t, *s)?);
                }
            }
        }
        let mut pass = Pass {
            distance: 0.0,
            loops: vec![lp],
            max_deviation: 0.0,
            warnings: Vec::new(),
            arcs: Vec::new(),
        };
        if opt.arcs {
            pass.arcs = pass
                .loops
                .iter()
                .map(|l| loop_arcs(curve, curve, l, opt.arc_tolerance(d)))
                .collect();
        }
        pass.max_deviation = measure(curve, &pass);
        return Ok(pass);
    }
    let d_eff = d.signum() * (d.abs() + opt.rounding + t);
    let oc = OffsetCurve::new(curve, d_eff);
    let f = flatten::flatten_opt(&oc, t, &FlattenOptions::default())?;
    let corners = curve.corners();
    let is_corner = |s: f64| s.fract() == 0.0 && corners.contains(&((s as usize) % n));
    let mut raw = vec![OffsetVertex {
        p: f.points[0],
        s: f.params[0],
    }];
    let last = f.params.len() - 1;
    for j in 1..=last {
        let s = f.params[j];
        if is_corner(s) {
            let k = (s as usize) % n;
            raw.push(OffsetVertex {
                p: oc.point_at((k + n - 1) % n, 1.0),
                s,
            });
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
    let trimmed = offset::trim(curve, &raw, keep, d.abs() + opt.rounding);
    let mut warnings = Vec::new();
    for s in &trimmed.dropped {
        let (Some(first), Some(lastv)) = (s.first(), s.last()) else {
            continue;
        };
        let at = curve.eval(first.s);
        let to = curve.eval(lastv.s);
        warnings.push(ContourWarning::Unreachable {
            offset_mm: d.abs(),
            from: at,
            to,
            params: (first.s, lastv.s),
        });
    }
    // Keep loops running the same way as the outline (counter-clockwise); an inverted loop
    // is an offset that collapsed.
    let loops: Vec<Vec<OffsetVertex>> = trimmed
        .loops
        .into_iter()
        .filter(|l| offset::loop_area(l) > 0.0)
        .map(smooth_start)
        .collect();
    if loops.is_empty() {
        return Err(InputError::new(
            "tool diameter",
            format!("{:.4} mm", 2.0 * opt.tool.radius()),
        )
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
    let mut pass = Pass {
        distance: d,
        loops,
        max_deviation: 0.0,
        warnings,
        arcs: Vec::new(),
    };
    if opt.arcs {
        pass.arcs = pass
            .loops
            .iter()
            .map(|l| loop_arcs(curve, &oc, l, opt.arc_tolerance(d)))
            .collect();
    }
    pass.max_deviation = measure(curve, &pass);
    Ok(pass)
}

/// The vertices of a fish-tail lobe within `t` (the crossing itself excluded at the start,
/// included at the end), all at the corner's parameter `s`: out to the drawn corner point
/// and back.
fn lobe_vertices(lobe: &Lobe, t: f64, s: f64) -> Result<Vec<OffsetVertex>, Error> {
    let mut out = Vec::new();
    for c in [lobe.to_tip, lobe.from_tip] {
        let f = flatten::flatten_opt(&c, t, &FlattenOptions::default())?;
        out.extend(f.points.iter().skip(1).map(|&p| OffsetVertex { p, s }));
    }
    Ok(out)
}

/// The distance from `q` to the curve as drawn: the outline and the lobes cut off it.
fn drawn_distance(curve: &CompositeCurve, q: Point, hint: f64) -> f64 {
    use kurbo::ParamCurveNearest;
    let lobes = curve.lobes().iter().flat_map(|l| [l.to_tip, l.from_tip]);
    lobes
        .map(|c| {
            c.to_kurbo()
                .nearest(kurbo::Point::new(q.x, q.y), 1e-12)
                .distance_sq
                .sqrt()
        })
        .fold(offset::distance_to(curve, q, hint), f64::min)
}

/// Replaces the chords of a loop by biarcs on every smooth stretch: consecutive vertices
/// that lie on the offset curve at their own parameter, with the parameter increasing by at
/// most one piece and no corner in between. Other links (trim cuts, corner joins) stay lines.
fn loop_arcs(
    curve: &CompositeCurve,
    oc: &dyn PlanarCurve,
    lp: &[OffsetVertex],
    t: f64,
) -> Vec<ArcSeg> {
    let m = lp.len();
    let n = curve.len();
    let nf = n as f64;
    let on_curve = |v: &OffsetVertex| {
        let w = v.s.rem_euclid(nf);
        let i = (w.floor() as usize).min(n - 1);
        v.p.distance(oc.point_at(i, w - i as f64)) <= 1e-9 * (1.0 + v.p.to_vec2().length())
    };
    let reg: Vec<bool> = lp.iter().map(on_curve).collect();
    let ds = |i: usize| (lp[(i + 1) % m].s - lp[i].s).rem_euclid(nf);
    // No run wraps through the loop's first vertex, so the elements start exactly there
    // (where the lead-in arrives).
    let link = |i: usize| {
        if i + 1 == m {
            return false;
        }
        let j = (i + 1) % m;
        let d = ds(i);
        reg[i] && reg[j] && d > 0.0 && d <= 1.0 && {
            let a = lp[i].s;
            !curve.corners().iter().any(|&k| {
                let x = (k as f64 - a).rem_euclid(nf);
                x > 0.0 && x < d
            })
        }
    };
    let start = (0..m).find(|&i| !link((i + m - 1) % m)).unwrap_or(0);
    let mut out = Vec::new();
    let mut i = start;
    let mut count = 0;
    while count < m {
        if link(i) {
            let sa = lp[i].s;
            let mut sb = sa;
            while count < m && link(i) {
                sb += ds(i);
                i = (i + 1) % m;
                count += 1;
            }
            out.extend(biarc::fit(oc, sa, sb, t));
        } else {
            let j = (i + 1) % m;
            out.push(ArcSeg {
                start: lp[i].p,
                end: lp[j].p,
                center: None,
                ccw: true,
                s_end: lp[j].s,
            });
            i = j;
            count += 1;
        }
    }
    // Rotate so that the elements start at the loop's first vertex.
    if let Some(k) = out
        .iter()
        .position(|a| a.start.distance(lp[0].p) <= 1e-9 * (1.0 + lp[0].p.to_vec2().length()))
    {
        out.rotate_left(k);
    }
    out
}

/// The loop rotated to start where it is straightest: the vertex with the least turning
/// summed over its ±5 neighbours, away from trim cuts and corner joins, so that the lead
/// arcs sit beside a smooth stretch of the path.
fn smooth_start(mut lp: Vec<OffsetVertex>) -> Vec<OffsetVertex> {
    let m = lp.len();
    if m < 3 {
        return lp;
    }
    let turn = |i: usize| {
        let (a, b, c) = (lp[(i + m - 1) % m].p, lp[i].p, lp[(i + 1) % m].p);
        let (u, v) = (b - a, c - b);
        u.cross(v).atan2(u.dot(v)).abs()
    };
    let turns: Vec<f64> = (0..m).map(turn).collect();
    let w = 5.min(m / 2);
    let score = |i: usize| (0..=2 * w).map(|k| turns[(i + m + k - w) % m]).sum::<f64>();
    let best = (0..m)
        .min_by(|a, b| score(*a).total_cmp(&score(*b)))
        .unwrap_or(0);
    lp.rotate_left(best);
    lp
}

fn measure(curve: &CompositeCurve, pass: &Pass) -> f64 {
    let d = pass.distance.abs();
    // On the outline the pass includes the lobes of the curve as drawn.
    let distance_to = |c: &CompositeCurve, q: Point, s: f64| {
        if d == 0.0 {
            drawn_distance(c, q, s)
        } else {
            offset::distance_to(c, q, s)
        }
    };
    let mut worst = 0.0_f64;
    if !pass.arcs.is_empty() {
        for a in pass.arcs.iter().flatten() {
            for j in 0..16 {
                let q = a.at(f64::from(j) / 16.0);
                worst = worst.max((distance_to(curve, q, a.s_end) - d).abs());
            }
        }
        return worst;
    }
    for lp in &pass.loops {
        let m = lp.len();
        for i in 0..m {
            let (a, b) = (lp[i], lp[(i + 1) % m]);
            for j in 0..16 {
                let q = a.p.lerp(b.p, f64::from(j) / 16.0);
                worst = worst.max((distance_to(curve, q, a.s) - d).abs());
            }
        }
    }
    worst
}
