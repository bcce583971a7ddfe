//! The dense check of a profile against its drawn outline, independent of the offset: the
//! path sampled every `step` mm, each sample's distance to the outline computed from the
//! drawing's own vertices and bulges (a line's nearest point by projection, an arc's by the
//! angle of the sample about its centre), without `cavalier_contours` or the offset code.
//!
//! The distance along a move is 1-Lipschitz in arc length, so the true minimum and maximum
//! between samples `h` apart lie within `h/2` of the sampled ones; the check takes `h` far
//! below the tolerance (the caller's `step`) and states the sampled values.

use crate::geom::{Outline, Point, Vec2};
use crate::toolpath::{MoveKind, Toolpath};
use std::f64::consts::TAU;

/// What the dense check measured on a run of moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandCheck {
    /// Least distance of a sample from the outline, mm.
    pub min_mm: f64,
    /// Greatest distance, mm.
    pub max_mm: f64,
    /// Where the least distance was.
    pub at_min: Point,
    /// Samples taken.
    pub samples: usize,
}

/// Distance from `p` to the segment from `a` with bulge `b` to `e`.
fn segment_distance(a: Point, b: f64, e: Point, p: Point) -> f64 {
    let c = e - a;
    let l2 = c.length_squared();
    if b.abs() < 1e-12 || l2 == 0.0 {
        let t = if l2 > 0.0 {
            ((p - a).dot(c) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        return p.distance(a + c * t);
    }
    // Sweep θ = 4·atan(b); centre on the chord's perpendicular bisector at
    // h = |c|(1 − b²)/(4b) to the left of the chord.
    let len = l2.sqrt();
    let u = c * (1.0 / len);
    let centre = a.lerp(e, 0.5) + Vec2::new(-u.y, u.x) * (len * (1.0 - b * b) / (4.0 * b));
    let rad = (a - centre).length();
    let sweep = 4.0 * b.atan();
    let a0 = (a.y - centre.y).atan2(a.x - centre.x);
    let ap = (p.y - centre.y).atan2(p.x - centre.x);
    let delta = if sweep > 0.0 {
        (ap - a0).rem_euclid(TAU)
    } else {
        (a0 - ap).rem_euclid(TAU)
    };
    if delta <= sweep.abs() {
        ((p - centre).length() - rad).abs()
    } else {
        p.distance(a).min(p.distance(e))
    }
}

/// Distance from `p` to the drawn outline.
pub fn outline_distance(o: &Outline, p: Point) -> f64 {
    let v: Vec<(Point, f64)> = o.vertices().collect();
    let n = v.len();
    (0..n)
        .map(|i| segment_distance(v[i].0, v[i].1, v[(i + 1) % n].0, p))
        .fold(f64::INFINITY, f64::min)
}

/// Samples the moves `range` of `tp` every `step` mm (at least at both ends of each move) and
/// measures their distance to `outline` (module docs); only feed moves count.
pub fn dense_band_check(
    outline: &Outline,
    tp: &Toolpath,
    range: std::ops::Range<usize>,
    step: f64,
) -> BandCheck {
    let mut out = BandCheck {
        min_mm: f64::INFINITY,
        max_mm: 0.0,
        at_min: Point::ORIGIN,
        samples: 0,
    };
    for k in range {
        let Some(m) = tp.moves.get(k) else { break };
        if !m.is_feed() || matches!(m.kind, MoveKind::Dwell { .. }) {
            continue;
        }
        let from = if k == 0 { tp.start } else { tp.moves[k - 1].to };
        let len = m.length_from(from);
        let n = (len / step).ceil().max(1.0) as usize;
        for j in 0..=n {
            let q = m.point_at(from, len * j as f64 / n as f64).xy();
            let d = outline_distance(outline, q);
            out.samples += 1;
            if d < out.min_mm {
                out.min_mm = d;
                out.at_min = q;
            }
            out.max_mm = out.max_mm.max(d);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A half disc of radius 5: distances to its arc and its diameter.
    #[test]
    fn distances_to_lines_and_arcs() {
        let d = Outline::new(
            &[(Point::new(-5.0, 0.0), 0.0), (Point::new(5.0, 0.0), 1.0)],
            "d",
        )
        .unwrap();
        assert!((outline_distance(&d, Point::new(0.0, -2.0)) - 2.0).abs() < 1e-12);
        assert!((outline_distance(&d, Point::new(0.0, 8.0)) - 3.0).abs() < 1e-12);
        assert!((outline_distance(&d, Point::new(0.0, 1.0)) - 1.0).abs() < 1e-12);
        assert!((outline_distance(&d, Point::new(8.0, 4.0)) - (80f64.sqrt() - 5.0)).abs() < 1e-12);
        // Beyond the arc's ends (below the diameter, off to the side): the nearest end.
        assert!((outline_distance(&d, Point::new(8.0, -4.0)) - 5.0).abs() < 1e-12);
        // The lower half: the same circle's arc, run counter-clockwise below the diameter.
        let up = Outline::new(
            &[(Point::new(5.0, 0.0), 0.0), (Point::new(-5.0, 0.0), 1.0)],
            "u",
        )
        .unwrap();
        assert!((outline_distance(&up, Point::new(0.0, -7.0)) - 2.0).abs() < 1e-12);
    }
}
