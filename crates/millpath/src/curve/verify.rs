//! Verifiers for flattening and offsets, by dense sampling.
//!
//! They share no code with [`super::flatten`] or the offset: the curve is evaluated through
//! `kurbo` (`ParamCurve::eval`, `ParamCurveNearest::nearest`), parameters are mapped to
//! pieces here, and distances to segments are computed here. A flattening or offset bug
//! cannot hide behind the same bug in its checker.

use super::CompositeCurve;
use crate::geom::Point;
use kurbo::{CubicBez, ParamCurve, ParamCurveNearest};

fn kpieces(c: &CompositeCurve) -> Vec<CubicBez> {
    c.pieces().iter().map(|p| p.to_kurbo()).collect()
}

fn seg_dist(p: kurbo::Point, a: kurbo::Point, b: kurbo::Point) -> f64 {
    let (abx, aby) = (b.x - a.x, b.y - a.y);
    let l2 = abx * abx + aby * aby;
    let t = if l2 > 0.0 {
        (((p.x - a.x) * abx + (p.y - a.y) * aby) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.x - a.x - t * abx).hypot(p.y - a.y - t * aby)
}

/// Evaluates the curve at unwrapped global parameter `s`; `end_side` picks the previous
/// piece's end at an integer.
fn eval(k: &[CubicBez], s: f64, end_side: bool) -> kurbo::Point {
    let n = k.len() as f64;
    let mut i = s.floor();
    if end_side && s.fract() == 0.0 {
        i -= 1.0;
    }
    let u = s - i;
    let idx = (i.rem_euclid(n) as usize).min(k.len() - 1);
    k[idx].eval(u)
}

/// The largest distance from the curve to its own chord, sampling `samples` (≥ 1000 in the
/// tests) points per chord uniformly in the parameter, for vertices at the global parameters
/// `params` (as [`super::Flattening::params`]) joined in order.
pub fn chordal_deviation(
    c: &CompositeCurve,
    params: &[f64],
    points: &[Point],
    samples: usize,
) -> f64 {
    let k = kpieces(c);
    let mut worst = 0.0_f64;
    for (w, pw) in params.windows(2).zip(points.windows(2)) {
        let (a, b) = (kurbo::Point::from(pw[0]), kurbo::Point::from(pw[1]));
        for j in 0..=samples {
            let s = w[0] + (w[1] - w[0]) * j as f64 / samples as f64;
            let p = eval(&k, s, j == samples);
            worst = worst.max(seg_dist(p, a, b));
        }
    }
    worst
}

/// The smallest distance from `p` to the curve (kurbo's exact nearest point per piece).
pub fn distance_to_curve(c: &CompositeCurve, p: Point) -> f64 {
    let kp = kurbo::Point::from(p);
    c.pieces()
        .iter()
        .map(|q| q.to_kurbo().nearest(kp, 1e-12).distance_sq.sqrt())
        .fold(f64::INFINITY, f64::min)
}

/// The smallest distance from the closed polyline `poly` (vertices in order, closing segment
/// implied) to the curve, sampling `per_segment` points on each segment plus the vertices.
pub fn polyline_min_distance(c: &CompositeCurve, poly: &[Point], per_segment: usize) -> f64 {
    let k = kpieces(c);
    let boxes: Vec<kurbo::Rect> = k
        .iter()
        .map(kurbo::ParamCurveExtrema::bounding_box)
        .collect();
    let mut worst = f64::INFINITY;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        for j in 0..per_segment.max(1) {
            let p = kurbo::Point::from(a.lerp(b, j as f64 / per_segment.max(1) as f64));
            let mut best = f64::INFINITY;
            for (q, r) in k.iter().zip(&boxes) {
                let dx = (r.x0 - p.x).max(p.x - r.x1).max(0.0);
                let dy = (r.y0 - p.y).max(p.y - r.y1).max(0.0);
                if dx.hypot(dy) >= best {
                    continue;
                }
                best = best.min(q.nearest(p, 1e-12).distance_sq.sqrt());
            }
            worst = worst.min(best);
        }
    }
    worst
}

/// The chordal deviation of each segment of a flattening of `c` on its own
/// ([`chordal_deviation`] segment by segment, `samples` points per segment): the
/// per-segment figure the reports plot against the tolerance.
pub fn segment_deviations(
    c: &CompositeCurve,
    flat: &super::Flattening,
    samples: usize,
) -> Vec<f64> {
    flat.params
        .windows(2)
        .zip(flat.points.windows(2))
        .map(|(p, q)| chordal_deviation(c, p, q, samples))
        .collect()
}
