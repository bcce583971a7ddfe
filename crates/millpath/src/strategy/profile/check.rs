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

/// The drawn outline's segments in a uniform grid of square cells: a query visits the cells
/// ring by ring round its own and stops once the nearest segment found is nearer than any
/// cell not yet visited (the cells at Chebyshev ring `k` lie at least `(k − 1)·g` away).
struct Index {
    segs: Vec<(Point, f64, Point)>,
    origin: Point,
    g: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

impl Index {
    /// The grid over `o` and `extent` (where the queries lie).
    fn new(o: &Outline, extent: crate::geom::Aabb) -> Index {
        let v: Vec<(Point, f64)> = o.vertices().collect();
        let n = v.len();
        let segs: Vec<(Point, f64, Point)> =
            (0..n).map(|i| (v[i].0, v[i].1, v[(i + 1) % n].0)).collect();
        let b = o.bounds();
        let lo = Point::new(b.min.x.min(extent.min.x), b.min.y.min(extent.min.y));
        let hi = Point::new(b.max.x.max(extent.max.x), b.max.y.max(extent.max.y));
        let (w, h) = ((hi.x - lo.x).max(1e-9), (hi.y - lo.y).max(1e-9));
        let g = (w * h / 1e6).sqrt().max(o.length() / n as f64).max(1e-9);
        let nx = ((w / g).ceil() as usize).max(1);
        let ny = ((h / g).ceil() as usize).max(1);
        let mut cells = vec![Vec::new(); nx * ny];
        let cell =
            |x: f64, lo: f64, n: usize| (((x - lo) / g).floor().max(0.0) as usize).min(n - 1);
        for (k, &(a, bulge, e)) in segs.iter().enumerate() {
            // The chord's box, widened by the sagitta (a whole circle's box past half a turn).
            let chord = e.distance(a);
            let pad = if bulge.abs() <= 1.0 {
                0.5 * bulge.abs() * chord
            } else {
                chord * (1.0 + bulge * bulge) / (4.0 * bulge.abs()) * 2.0
            };
            let (x0, x1) = (a.x.min(e.x) - pad, a.x.max(e.x) + pad);
            let (y0, y1) = (a.y.min(e.y) - pad, a.y.max(e.y) + pad);
            for j in cell(y0, lo.y, ny)..=cell(y1, lo.y, ny) {
                for i in cell(x0, lo.x, nx)..=cell(x1, lo.x, nx) {
                    cells[j * nx + i].push(k as u32);
                }
            }
        }
        Index {
            segs,
            origin: lo,
            g,
            nx,
            ny,
            cells,
        }
    }

    fn distance(&self, p: Point) -> f64 {
        let c = |x: f64, lo: f64, n: usize| {
            (((x - lo) / self.g).floor().max(0.0) as usize).min(n - 1) as i64
        };
        let (ci, cj) = (
            c(p.x, self.origin.x, self.nx),
            c(p.y, self.origin.y, self.ny),
        );
        let mut best = f64::INFINITY;
        let rings = self.nx.max(self.ny) as i64;
        for k in 0..=rings {
            for j in (cj - k).max(0)..=(cj + k).min(self.ny as i64 - 1) {
                for i in (ci - k).max(0)..=(ci + k).min(self.nx as i64 - 1) {
                    if (i - ci).abs() != k && (j - cj).abs() != k {
                        continue;
                    }
                    for &s in &self.cells[j as usize * self.nx + i as usize] {
                        let (a, b, e) = self.segs[s as usize];
                        best = best.min(segment_distance(a, b, e, p));
                    }
                }
            }
            if best <= k as f64 * self.g {
                break;
            }
        }
        best
    }
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
    let mut pts = Vec::new();
    for k in range {
        let Some(m) = tp.moves.get(k) else { break };
        if !m.is_feed() || matches!(m.kind, MoveKind::Dwell { .. }) {
            continue;
        }
        let from = if k == 0 { tp.start } else { tp.moves[k - 1].to };
        let len = m.length_from(from);
        let n = (len / step).ceil().max(1.0) as usize;
        pts.extend((0..=n).map(|j| m.point_at(from, len * j as f64 / n as f64).xy()));
    }
    if pts.is_empty() {
        return out;
    }
    let index = Index::new(outline, crate::geom::Aabb::from_points(pts.iter().copied()));
    for q in pts {
        let d = index.distance(q);
        out.samples += 1;
        if d < out.min_mm {
            out.min_mm = d;
            out.at_min = q;
        }
        out.max_mm = out.max_mm.max(d);
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

    /// The grid's answer is the brute force's, on a wavy outline of lines and arcs, at points
    /// inside, outside and far off.
    #[test]
    fn the_index_finds_the_nearest_segment() {
        let n = 60;
        let v: Vec<(Point, f64)> = (0..n)
            .map(|i| {
                let a = TAU * f64::from(i) / f64::from(n);
                let r = 40.0 + 6.0 * (5.0 * a).sin();
                (
                    Point::new(r * a.cos(), r * a.sin()),
                    if i % 3 == 0 { 0.2 } else { 0.0 },
                )
            })
            .collect();
        let o = Outline::new(&v, "wave").unwrap();
        let extent = crate::geom::Aabb {
            min: Point::new(-120.0, -120.0),
            max: Point::new(120.0, 120.0),
        };
        let index = Index::new(&o, extent);
        for k in 0..2000 {
            let t = f64::from(k) * 0.618_034;
            let p = Point::new(110.0 * (7.0 * t).sin(), 110.0 * (3.0 * t).cos() * t.fract());
            let (a, b) = (index.distance(p), outline_distance(&o, p));
            assert!((a - b).abs() < 1e-12, "{p:?}: {a} vs {b}");
        }
    }
}
