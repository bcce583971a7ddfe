//! DXF SPLINE (B-spline or NURBS) evaluation and flattening.
//!
//! The curve is evaluated with de Boor's algorithm (rational: on the homogeneous points
//! `(w·x, w·y, w)`) and flattened by recursive bisection of each knot span until the curve's
//! mid point lies within `tolerance` of the chord, checked at the quarter points as well, so
//! that an S-shaped piece is not mistaken for a straight one (at least two bisections per
//! span, at most 24). Splines given only by fit points are read as the polyline through the
//! fit points.

use crate::error::InputError;
use crate::geom::Point;

/// The data of a SPLINE entity (or a HATCH spline edge), in its own coordinates.
#[derive(Debug, Clone, Default)]
pub struct SplineData {
    /// Degree (group 71).
    pub degree: usize,
    /// Knots (group 40).
    pub knots: Vec<f64>,
    /// Control points (groups 10/20).
    pub control: Vec<Point>,
    /// Weights (group 41), empty for a non-rational spline.
    pub weights: Vec<f64>,
    /// Fit points (groups 11/21).
    pub fit: Vec<Point>,
}

/// The polyline flattening `s` within `tol`; `at` names the entity.
pub fn flatten(s: &SplineData, tol: f64, at: &str) -> Result<Vec<Point>, InputError> {
    let ctrl = &s.control;
    if ctrl.is_empty() {
        if s.fit.len() < 2 {
            return Err(InputError::new("SPLINE", "no control or fit points")
                .at(at)
                .expected("a spline with points"));
        }
        return Ok(s.fit.clone());
    }
    let p = s.degree;
    let knots = &s.knots;
    let w: Vec<f64> = if s.weights.len() == ctrl.len() {
        s.weights.clone()
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
    let eval = |u: f64| de_boor(p, knots, ctrl, &w, u);
    let mut params: Vec<f64> = knots[p..=ctrl.len()].to_vec();
    params.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
    let mut out = vec![eval(knots[p])];
    for w2 in params.windows(2) {
        bisect(&eval, w2[0], w2[1], tol, 0, &mut out);
    }
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

    /// Found by the outline_importers fuzzer (2026-11-22): a degree-2 SPLINE with two control
    /// points and five knots passed the count check and de Boor indexed a third point.
    #[test]
    fn splines_with_too_few_points_or_bad_knots_are_refused() {
        let spline = |degree: usize, knots: &[f64], n: usize| SplineData {
            degree,
            knots: knots.to_vec(),
            control: (0..n)
                .map(|i| Point::new(i as f64, (i % 2) as f64))
                .collect(),
            ..Default::default()
        };
        for (deg, knots, n) in [
            (2, &[0.0, 0.0, 0.0, 1.0, 1.0][..], 2),
            (3, &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0][..], 2),
            (2, &[0.0, 0.0, 1.0, 0.5, 1.0, 1.0][..], 3),
            (2, &[0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0][..], 3),
        ] {
            let e = flatten(&spline(deg, knots, n), 0.01, "t.dxf, entity 1")
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("t.dxf, entity 1") && e.contains("degree + 1 control points"),
                "{e}"
            );
        }
        assert!(flatten(&spline(2, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3), 0.01, "t").is_ok());
    }

    /// A clamped quadratic with 3 control points is a Bézier: its flattening's vertices lie on
    /// the parabola `y = 2x − x²` (control points (0,0), (1,2), (2,0)) and every chord's mid
    /// point within the tolerance of it.
    #[test]
    fn quadratic_bezier_flattened_within_tolerance() {
        let s = SplineData {
            degree: 2,
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            control: vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(2.0, 0.0),
            ],
            ..Default::default()
        };
        let m = de_boor(2, &s.knots, &s.control, &[1.0; 3], 0.5);
        assert!(m.distance(Point::new(1.0, 1.0)) < 1e-12);
        let pts = flatten(&s, 1e-3, "t").unwrap();
        for w in pts.windows(2) {
            for p in [w[0], w[1]] {
                assert!((p.y - (2.0 * p.x - p.x * p.x)).abs() < 1e-12);
            }
            let mx = 0.5 * (w[0].x + w[1].x);
            let my = 0.5 * (w[0].y + w[1].y);
            // Vertical gap bounds the distance to the curve from above.
            assert!((2.0 * mx - mx * mx - my).abs() <= 2e-3, "{mx}");
        }
    }
}
