//! HATCH boundary paths (DXF reference, "Boundary Path Data").
//!
//! After the path count (91), each path starts with its type flags (92). A *polyline* path
//! (flag bit 2) gives has-bulge (72), is-closed (73), a vertex count (93) and the vertices
//! (10/20, 42 when has-bulge). An *edge* path gives an edge count (93) and per edge its type
//! (72): 1 line (10/20, 11/21), 2 circular arc (centre 10/20, radius 40, angles 50/51
//! degrees, counter-clockwise flag 73), 3 elliptic arc (centre 10/20, major axis end 11/21
//! relative to the centre, minor/major ratio 40, angles 50/51, flag 73), 4 spline (degree
//! 94, rational 73, periodic 74, knot count 95, control count 96, knots 40, control points
//! 10/20, weights 42, fit count 97, fit points 11/21). A clockwise arc (73 = 0) stores its
//! angles mirrored: it runs clockwise from `−start` to `−end`. Each edge becomes one piece;
//! each path's pieces are joined on their own (paths often share vertices), the chains
//! that do not close left to the drawing's joiner.

use super::codes::{Group, Record};
use super::spline::{self, SplineData};
use crate::error::InputError;
use crate::geom::Point;
use crate::io::affine::Piece;
use std::f64::consts::{PI, TAU};

struct Cursor<'a> {
    g: &'a [Group],
    i: usize,
}

impl Cursor<'_> {
    fn next(&mut self) -> Option<&Group> {
        let g = self.g.get(self.i);
        self.i += 1;
        g
    }
    /// The value of the next group if it has `code` (consumed), else `None`.
    fn take(&mut self, code: i32) -> Option<&Group> {
        match self.g.get(self.i) {
            Some(g) if g.code == code => {
                self.i += 1;
                Some(g)
            }
            _ => None,
        }
    }
    fn real(&mut self, code: i32) -> f64 {
        self.take(code).map_or(0.0, Group::real)
    }
    fn int(&mut self, code: i32) -> i64 {
        self.take(code).map_or(0, Group::int)
    }
    fn point(&mut self, xc: i32) -> Point {
        let x = self.real(xc);
        let y = self.real(xc + 10);
        Point::new(x, y)
    }
}

/// The boundary paths of a HATCH, each a list of pieces (one per edge), in the hatch's own
/// coordinates.
pub fn boundary_paths(rec: &Record, tol: f64, at: &str) -> Result<Vec<Vec<Piece>>, InputError> {
    let bad = |what: &str| {
        InputError::new("HATCH boundary", what.to_owned())
            .at(at.to_owned())
            .expected("boundary paths as the DXF reference lays them out")
    };
    let Some(start) = rec.groups.iter().position(|g| g.code == 91) else {
        return Ok(Vec::new());
    };
    let mut c = Cursor {
        g: &rec.groups,
        i: start,
    };
    let paths = c.next().map_or(0, Group::int).clamp(0, 100_000);
    let mut paths_out: Vec<Vec<Piece>> = Vec::new();
    let out = &mut paths_out;
    for _ in 0..paths {
        // Skip to the path's type flags.
        while c.g.get(c.i).is_some_and(|g| g.code != 92) {
            c.i += 1;
        }
        let Some(flags) = c.next().map(Group::int) else {
            return Err(bad("fewer paths than its count (91)"));
        };
        out.push(Vec::new());
        let Some(out) = out.last_mut() else { break };
        if flags & 2 != 0 {
            let bulges = c.int(72) != 0;
            let closed = c.int(73) != 0;
            let n = c.int(93).clamp(0, 10_000_000);
            let mut v: Piece = Vec::new();
            for _ in 0..n {
                let p = c.point(10);
                let b = if bulges { c.real(42) } else { 0.0 };
                v.push((p, b));
            }
            if (closed || v.len() > 2)
                && let Some(&(p, _)) = v.first()
            {
                v.push((p, 0.0));
            }
            out.push(v);
            continue;
        }
        let edges = c.int(93).clamp(0, 10_000_000);
        for _ in 0..edges {
            while c.g.get(c.i).is_some_and(|g| g.code != 72) {
                c.i += 1;
            }
            match c.next().map(Group::int) {
                Some(1) => {
                    let (a, b) = (c.point(10), c.point(11));
                    out.push(vec![(a, 0.0), (b, 0.0)]);
                }
                Some(2) => {
                    let (ctr, r) = (c.point(10), c.real(40));
                    let (s, e) = (c.real(50).to_radians(), c.real(51).to_radians());
                    let ccw = c.int(73) != 0;
                    let (a0, sweep) = edge_sweep(s, e, ccw);
                    if r > 0.0 {
                        let h = 0.5 * sweep;
                        let b = (h / 4.0).tan();
                        let p = |a: f64| Point::new(ctr.x + r * a.cos(), ctr.y + r * a.sin());
                        out.push(vec![(p(a0), b), (p(a0 + h), b), (p(a0 + sweep), 0.0)]);
                    }
                }
                Some(3) => {
                    let (ctr, m) = (c.point(10), c.point(11));
                    let ratio = c.real(40);
                    let (s, e) = (c.real(50).to_radians(), c.real(51).to_radians());
                    let ccw = c.int(73) != 0;
                    let (t0, sweep) = edge_sweep(s, e, ccw);
                    let n = (-ratio * m.y, ratio * m.x);
                    let a = m.x.hypot(m.y);
                    if a > 0.0 && ratio > 0.0 {
                        let step = if tol >= a {
                            PI
                        } else {
                            2.0 * (1.0 - tol / a).acos()
                        };
                        let k = ((sweep.abs() / step).ceil() as usize).clamp(4, 100_000);
                        out.push(
                            (0..=k)
                                .map(|i| {
                                    let t = t0 + sweep * i as f64 / k as f64;
                                    let (sn, co) = t.sin_cos();
                                    let p = Point::new(
                                        ctr.x + m.x * co + n.0 * sn,
                                        ctr.y + m.y * co + n.1 * sn,
                                    );
                                    (p, 0.0)
                                })
                                .collect(),
                        );
                    }
                }
                Some(4) => {
                    let mut s = SplineData {
                        degree: usize::try_from(c.int(94)).unwrap_or(0),
                        ..Default::default()
                    };
                    let rational = c.int(73) != 0;
                    let _periodic = c.int(74);
                    let nk = c.int(95).clamp(0, 1_000_000);
                    let nc = c.int(96).clamp(0, 1_000_000);
                    for _ in 0..nk {
                        s.knots.push(c.real(40));
                    }
                    for _ in 0..nc {
                        s.control.push(c.point(10));
                        if rational {
                            s.weights.push(c.real(42));
                        }
                    }
                    if let Some(nf) = c.take(97).map(Group::int) {
                        for _ in 0..nf.clamp(0, 1_000_000) {
                            s.fit.push(c.point(11));
                        }
                    }
                    let pts = spline::flatten(&s, tol, at)?;
                    out.push(pts.into_iter().map(|p| (p, 0.0)).collect());
                }
                _ => return Err(bad("an edge type other than 1–4 (72)")),
            }
        }
    }
    Ok(paths_out)
}

/// The start angle and signed sweep of a hatch edge arc stored with angles `s`, `e`.
fn edge_sweep(s: f64, e: f64, ccw: bool) -> (f64, f64) {
    let sweep = {
        let d = (e - s).rem_euclid(TAU);
        if d <= 1e-12 { TAU } else { d }
    };
    if ccw { (s, sweep) } else { (-s, -sweep) }
}
