//! Pocket outlines from DXF: LWPOLYLINE (with bulges), chained LINE and ARC, CIRCLE, SPLINE.
//!
//! * LWPOLYLINE: its vertices and bulges as they are; it must be closed (flag, or last vertex
//!   on the first) unless it chains with other open pieces.
//! * ARC: centre `c`, radius `R`, start and end angles (degrees, counter-clockwise): sweep
//!   `θ = (end − start) mod 360°` (a zero difference is a full turn), bulge `tan(θ/4)`.
//! * CIRCLE: two half circles (bulge 1).
//! * SPLINE (B-spline or NURBS, control points, knots, weights): evaluated with de Boor's
//!   algorithm and flattened by recursive bisection of the parameter interval until the
//!   curve's mid point lies within `tolerance` of the chord (checked at the quarter points as
//!   well, so that an S-shaped piece is not mistaken for a straight one). Splines given only
//!   by fit points are flattened through the fit points.
//!
//! Open pieces are chained end to start (either direction) when their ends lie within
//! `join_tolerance`; a piece whose end meets nothing makes the outline open, and the error
//! names the dangling point.

use super::outline_json::{Loops, classify};
use crate::error::InputError;
use crate::geom::{Outline, Point};
use dxf::entities::EntityType;

/// Importer tolerances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DxfOptions {
    /// Largest distance between a spline and its flattening, mm.
    pub tolerance: f64,
    /// Largest gap between two piece ends that are joined, mm.
    pub join_tolerance: f64,
}

impl Default for DxfOptions {
    fn default() -> Self {
        DxfOptions {
            tolerance: 0.001,
            join_tolerance: 1e-4,
        }
    }
}

/// An open piece: vertices with bulges, the last vertex's bulge unused.
type Piece = Vec<(Point, f64)>;

/// Reads a DXF drawing from `bytes`; `origin` names the file.
pub fn parse(bytes: &[u8], origin: &str, opts: &DxfOptions) -> Result<Loops, InputError> {
    let mut reader = std::io::Cursor::new(bytes);
    let drawing = dxf::Drawing::load(&mut reader).map_err(|e| {
        InputError::new("DXF", e.to_string())
            .at(origin)
            .expected("a readable DXF drawing")
    })?;
    let mut closed: Vec<Outline> = Vec::new();
    let mut open: Vec<Piece> = Vec::new();
    for (n, ent) in drawing.entities().enumerate() {
        let at = format!("{origin}, entity {n}");
        match &ent.specific {
            EntityType::LwPolyline(lw) => {
                let v: Piece = lw
                    .vertices
                    .iter()
                    .map(|v| (Point::new(v.x, v.y), v.bulge))
                    .collect();
                let ends_meet = match (v.first(), v.last()) {
                    (Some(a), Some(b)) => v.len() > 2 && a.0.distance(b.0) <= opts.join_tolerance,
                    _ => false,
                };
                if lw.is_closed() || ends_meet {
                    closed.push(Outline::new(&v, &format!("{at} (LWPOLYLINE)"))?);
                } else {
                    open.push(v);
                }
            }
            EntityType::Line(l) => open.push(vec![
                (Point::new(l.p1.x, l.p1.y), 0.0),
                (Point::new(l.p2.x, l.p2.y), 0.0),
            ]),
            EntityType::Arc(a) => {
                let sweep = (a.end_angle - a.start_angle).rem_euclid(360.0);
                let sweep = if sweep <= 1e-12 { 360.0 } else { sweep }.to_radians();
                let c = Point::new(a.center.x, a.center.y);
                let at_angle =
                    |t: f64| Point::new(c.x + a.radius * t.cos(), c.y + a.radius * t.sin());
                let t0 = a.start_angle.to_radians();
                // Split in halves so that no bulge exceeds tan(90°).
                let half = 0.5 * sweep;
                open.push(vec![
                    (at_angle(t0), (half / 4.0).tan()),
                    (at_angle(t0 + half), (half / 4.0).tan()),
                    (at_angle(t0 + sweep), 0.0),
                ]);
            }
            EntityType::Circle(c) => {
                let p = |s: f64| Point::new(c.center.x + s * c.radius, c.center.y);
                closed.push(Outline::new(
                    &[(p(-1.0), 1.0), (p(1.0), 1.0)],
                    &format!("{at} (CIRCLE)"),
                )?);
            }
            EntityType::Spline(s) => {
                let pts = flatten_spline(s, opts.tolerance, &at)?;
                let piece: Piece = pts.into_iter().map(|p| (p, 0.0)).collect();
                let ends_meet = match (piece.first(), piece.last()) {
                    (Some(a), Some(b)) => {
                        piece.len() > 2 && a.0.distance(b.0) <= opts.join_tolerance
                    }
                    _ => false,
                };
                if s.is_closed() || ends_meet {
                    closed.push(Outline::new(&piece, &format!("{at} (SPLINE)"))?);
                } else {
                    open.push(piece);
                }
            }
            _ => {}
        }
    }
    for lp in chain(open, opts.join_tolerance, origin)? {
        closed.push(Outline::new(&lp, &format!("{origin}, chained LINE/ARC"))?);
    }
    classify(closed, origin)
}

/// Joins open pieces into closed loops.
fn chain(mut open: Vec<Piece>, tol: f64, origin: &str) -> Result<Vec<Piece>, InputError> {
    let mut loops = Vec::new();
    while let Some(mut cur) = open.pop() {
        while let (Some(&(start, _)), Some(&(end, _))) = (cur.first(), cur.last()) {
            if cur.len() > 2 && start.distance(end) <= tol {
                cur.pop();
                loops.push(cur);
                break;
            }
            let next = open.iter().position(|p| {
                p.first().is_some_and(|v| v.0.distance(end) <= tol)
                    || p.last().is_some_and(|v| v.0.distance(end) <= tol)
            });
            let Some(i) = next else {
                return Err(InputError::new(
                    "outline",
                    format!("open at ({:.4}, {:.4})", end.x, end.y),
                )
                .at(origin)
                .expected("closed outlines: every LINE/ARC end must meet another piece's end"));
            };
            let mut p = open.swap_remove(i);
            if p.first().is_some_and(|v| v.0.distance(end) > tol) {
                p = reverse(&p);
            }
            cur.pop();
            cur.extend(p);
        }
    }
    Ok(loops)
}

/// The piece run backwards: bulges move to the other end of their segment and change sign.
fn reverse(p: &Piece) -> Piece {
    let n = p.len();
    (0..n)
        .map(|i| {
            let v = p[n - 1 - i].0;
            let b = if i + 1 < n { -p[n - 2 - i].1 } else { 0.0 };
            (v, b)
        })
        .collect()
}

/// Flattens a DXF spline within `tol`.
fn flatten_spline(s: &dxf::entities::Spline, tol: f64, at: &str) -> Result<Vec<Point>, InputError> {
    let ctrl: Vec<Point> = s
        .control_points
        .iter()
        .map(|p| Point::new(p.x, p.y))
        .collect();
    if ctrl.is_empty() {
        let fit: Vec<Point> = s.fit_points.iter().map(|p| Point::new(p.x, p.y)).collect();
        if fit.len() < 2 {
            return Err(InputError::new("SPLINE", "no control or fit points")
                .at(at)
                .expected("a spline with points"));
        }
        return Ok(fit);
    }
    let p = usize::try_from(s.degree_of_curve).unwrap_or(0);
    let knots = &s.knot_values;
    let w: Vec<f64> = if s.weight_values.len() == ctrl.len() {
        s.weight_values.clone()
    } else {
        vec![1.0; ctrl.len()]
    };
    // At least `p + 1` control points (de Boor's window of `p + 1` points; a degree-2 spline
    // with two control points indexed past them, found by the outline_importers fuzzer) and
    // non-decreasing, finite knots.
    if p == 0
        || ctrl.len() <= p
        || knots.len() != ctrl.len() + p + 1
        || knots.iter().any(|k| !k.is_finite())
        || knots.windows(2).any(|k| k[1] < k[0])
        || w.iter().any(|x| !x.is_finite() || *x <= 0.0)
    {
        return Err(InputError::new(
            "SPLINE",
            format!(
                "degree {p}, {} knots, {} control points",
                knots.len(),
                ctrl.len()
            ),
        )
        .at(at)
        .expected(
            "degree + 1 control points or more, knots = control points + degree + 1 \
             (non-decreasing, finite), positive weights",
        ));
    }
    let eval = |u: f64| de_boor(p, knots, &ctrl, &w, u);
    let (u0, u1) = (knots[p], knots[ctrl.len()]);
    // Start from the knot spans, then bisect.
    let mut params: Vec<f64> = knots[p..=ctrl.len()].to_vec();
    params.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
    let mut out = vec![eval(u0)];
    for w2 in params.windows(2) {
        bisect(&eval, w2[0], w2[1], tol, 0, &mut out);
    }
    let _ = u1;
    Ok(out)
}

fn bisect(eval: &dyn Fn(f64) -> Point, a: f64, b: f64, tol: f64, depth: u32, out: &mut Vec<Point>) {
    let (pa, pb) = (eval(a), eval(b));
    let dev = |t: f64| {
        let p = eval(a + (b - a) * t);
        let chord = pb - pa;
        let l = chord.length();
        if l < 1e-12 {
            p.distance(pa)
        } else {
            ((p - pa).cross(chord) / l).abs()
        }
    };
    if depth < 24 && (depth < 2 || dev(0.5).max(dev(0.25)).max(dev(0.75)) > tol) {
        let m = 0.5 * (a + b);
        bisect(eval, a, m, tol, depth + 1, out);
        bisect(eval, m, b, tol, depth + 1, out);
    } else {
        out.push(pb);
    }
}

/// Rational de Boor evaluation at `u`.
fn de_boor(p: usize, t: &[f64], c: &[Point], w: &[f64], u: f64) -> Point {
    let n = c.len();
    let mut k = p;
    while k + 1 < n && u >= t[k + 1] {
        k += 1;
    }
    let mut d: Vec<(f64, f64, f64)> = (0..=p)
        .map(|j| {
            let i = j + k - p;
            (c[i].x * w[i], c[i].y * w[i], w[i])
        })
        .collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = j + k - p;
            let den = t[i + p + 1 - r] - t[i];
            let a = if den.abs() < 1e-300 {
                0.0
            } else {
                (u - t[i]) / den
            };
            d[j] = (
                (1.0 - a) * d[j - 1].0 + a * d[j].0,
                (1.0 - a) * d[j - 1].1 + a * d[j].1,
                (1.0 - a) * d[j - 1].2 + a * d[j].2,
            );
        }
    }
    let (x, y, ww) = d[p];
    Point::new(x / ww, y / ww)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reverse_moves_bulges() {
        let p: Piece = vec![
            (Point::new(0.0, 0.0), 0.5),
            (Point::new(1.0, 0.0), 0.0),
            (Point::new(1.0, 1.0), 0.0),
        ];
        let r = reverse(&p);
        assert_eq!(r[0].0, Point::new(1.0, 1.0));
        assert!(r[0].1.abs() < 1e-12 && (r[1].1 + 0.5).abs() < 1e-12 && r[2].1.abs() < 1e-12);
        let r2 = reverse(&r);
        assert!((r2[0].1 - 0.5).abs() < 1e-12);
    }

    /// Found by the outline_importers fuzzer (2026-11-22): a degree-2 SPLINE with two control
    /// points and five knots passed the count check and de Boor indexed a third point.
    #[test]
    fn splines_with_too_few_points_or_bad_knots_are_refused() {
        let spline = |degree: i32, knots: &[f64], n: usize| dxf::entities::Spline {
            degree_of_curve: degree,
            knot_values: knots.to_vec(),
            control_points: (0..n)
                .map(|i| dxf::Point::new(i as f64, (i % 2) as f64, 0.0))
                .collect(),
            ..Default::default()
        };
        for (deg, knots, n) in [
            (2, &[0.0, 0.0, 0.0, 1.0, 1.0][..], 2),
            (3, &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0][..], 2),
            (2, &[0.0, 0.0, 1.0, 0.5, 1.0, 1.0][..], 3),
            (2, &[0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0][..], 3),
        ] {
            let e = flatten_spline(&spline(deg, knots, n), 0.01, "t.dxf, entity 1")
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("t.dxf, entity 1") && e.contains("degree + 1 control points"),
                "{e}"
            );
        }
        assert!(flatten_spline(&spline(2, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3), 0.01, "t").is_ok());
    }

    #[test]
    fn quadratic_bezier_as_bspline() {
        // Clamped quadratic with 3 control points is a Bézier: mid point at (1, 1).
        let c = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(2.0, 0.0),
        ];
        let t = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let m = de_boor(2, &t, &c, &[1.0; 3], 0.5);
        assert!(m.distance(Point::new(1.0, 1.0)) < 1e-12);
    }
}
