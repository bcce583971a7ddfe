//! Cutter offset of the exact curve, flattened afterwards, with loop trimming.
//!
//! # Offset tangent (derived)
//! With arc length σ, unit tangent `T`, left normal `N = perp(T)` and signed curvature `κ`
//! (Frenet: `dT/dσ = κN`, `dN/dσ = −κT`), the offset `O = P + d·N` (d > 0: left, which is
//! inside for a counter-clockwise outline) has `dO/dσ = T − dκT = (1 − dκ)·T`, i.e.
//! `O'(s) = P'(s)·(1 − dκ(s))` in any parameter. So `O` is parallel to `P` wherever
//! `1 − dκ > 0`, runs backwards where `1 − dκ < 0` (the concave curvature radius `1/κ` is
//! smaller than `d`: the raw offset forms a swallowtail loop), and has a cusp where
//! `1 − dκ = 0`.
//!
//! # Exact deviation on the offset
//! The distance from `O(s)` to a chord of direction `c` has interior critical points where
//! `cross(O'(s), c) = (1 − dκ)·cross(P'(s), c) = 0`: the tangent-parallel roots of `P` (the
//! same quadratic per piece as for the curve) plus the cusps `1 − dκ = 0`, which are found
//! once per piece (sign changes of `1 − dκ` on 64 samples, then bisection). The offset is
//! then flattened by the same greedy farthest-end machinery as the curve
//! ([`crate::curve::flatten`]), so the chordal tolerance holds *after* the offset.
//!
//! # Corners
//! At a corner (tangent break) the one-sided offsets end at `O⁻ = C + d·N_in` and start at
//! `O⁺ = C + d·N_out`. They are joined by the arc of radius |d| about `C` whose mid point is
//! farther from the curve (the short way for an ordinary convex corner, the long way round a
//! nearly reversing spike), or by a straight crossing when neither arc keeps its distance (a
//! concave corner: the crossing forms a loop that trimming removes).
//!
//! # Trimming
//! The raw flattened offset is cut at its self-intersections (sweep over x-sorted segments);
//! a slice between cuts is dropped when one of its vertices is closer to the curve than the
//! band's inner edge (see [`super`]): that is a loop (local swallowtail or a global overlap)
//! where the tool would gouge. The kept slices are stitched back into closed loops, crossing
//! over at each cut. Dropped slices are reported as places the tool cannot reach.

use crate::curve::{CompositeCurve, PlanarCurve};
use crate::geom::{Point, Vec2};

/// The exact offset of a curve by a signed distance `d` (left positive).
#[derive(Debug, Clone)]
pub struct OffsetCurve<'a> {
    base: &'a CompositeCurve,
    d: f64,
    cusps: Vec<Vec<f64>>,
}

fn unit_normal(base: &CompositeCurve, i: usize, u: f64) -> Vec2 {
    let c = &base.pieces()[i];
    let t = c.d1(u);
    let t = if t.length() > 1e-12 {
        t
    } else {
        c.d2(u) * if u < 0.5 { 1.0 } else { -1.0 }
    };
    t.normalize().map_or(Vec2::ZERO, Vec2::perp)
}

impl<'a> OffsetCurve<'a> {
    /// The offset of `base` by `d` mm (positive: to the left of travel).
    pub fn new(base: &'a CompositeCurve, d: f64) -> Self {
        let cusps = base
            .pieces()
            .iter()
            .map(|c| {
                let g = |u: f64| 1.0 - d * c.curvature(u);
                let m = 64;
                let mut roots = Vec::new();
                let mut prev = (0.0, g(0.0));
                for j in 1..=m {
                    let u = f64::from(j) / f64::from(m);
                    let gu = g(u);
                    if (gu > 0.0) != (prev.1 > 0.0) {
                        let (mut a, mut b) = (prev.0, u);
                        for _ in 0..60 {
                            let mid = 0.5 * (a + b);
                            if (g(mid) > 0.0) == (prev.1 > 0.0) {
                                a = mid;
                            } else {
                                b = mid;
                            }
                        }
                        roots.push(0.5 * (a + b));
                    }
                    prev = (u, gu);
                }
                roots
            })
            .collect();
        OffsetCurve { base, d, cusps }
    }

    /// True where the offset runs forward (`1 − dκ > 0`) at piece `i`, parameter `u`.
    pub fn forward(&self, i: usize, u: f64) -> bool {
        1.0 - self.d * self.base.pieces()[i % self.base.len()].curvature(u) > 0.0
    }
}

impl PlanarCurve for OffsetCurve<'_> {
    fn piece_count(&self) -> usize {
        self.base.len()
    }
    fn point_at(&self, i: usize, u: f64) -> Point {
        let i = i % self.base.len();
        self.base.pieces()[i].eval(u) + unit_normal(self.base, i, u) * self.d
    }
    fn critical(&self, i: usize, dir: Vec2, u0: f64, u1: f64, out: &mut Vec<f64>) {
        let i = i % self.base.len();
        self.base.pieces()[i].parallel_roots(dir, u0, u1, out);
        out.extend(self.cusps[i].iter().copied().filter(|u| *u > u0 && *u < u1));
    }
    fn breaks(&self) -> Vec<usize> {
        self.base.corners().to_vec()
    }
    fn tangent_at(&self, i: usize, u: f64) -> Vec2 {
        // O' = P'(1 − dκ): the base tangent, reversed where the offset runs backwards.
        let t = self.base.tangent_at(i, u);
        if self.forward(i, u) { t } else { -t }
    }
}

/// Approximate distance from `q` to the base curve (bounding-box pruning, 32 samples per
/// candidate piece, Newton refinement). Used for trimming decisions, not for verification.
pub fn distance_to(base: &CompositeCurve, q: Point, hint: f64) -> f64 {
    let mut best = q.distance(base.eval(hint));
    for c in base.pieces() {
        let lo = Point::new(
            c.p0.x.min(c.p1.x).min(c.p2.x).min(c.p3.x),
            c.p0.y.min(c.p1.y).min(c.p2.y).min(c.p3.y),
        );
        let hi = Point::new(
            c.p0.x.max(c.p1.x).max(c.p2.x).max(c.p3.x),
            c.p0.y.max(c.p1.y).max(c.p2.y).max(c.p3.y),
        );
        let dx = (lo.x - q.x).max(q.x - hi.x).max(0.0);
        let dy = (lo.y - q.y).max(q.y - hi.y).max(0.0);
        if dx.hypot(dy) >= best {
            continue;
        }
        let m = 32;
        let mut bu = 0.0;
        let mut bd = f64::INFINITY;
        for j in 0..=m {
            let u = f64::from(j) / f64::from(m);
            let d = q.distance(c.eval(u));
            if d < bd {
                bd = d;
                bu = u;
            }
        }
        let mut u = bu;
        for _ in 0..8 {
            let r = c.eval(u) - q;
            let (d1, d2) = (c.d1(u), c.d2(u));
            let f = r.dot(d1);
            let fp = d1.dot(d1) + r.dot(d2);
            if fp <= 0.0 {
                break;
            }
            u = (u - f / fp).clamp(0.0, 1.0);
        }
        best = best.min(bd).min(q.distance(c.eval(u)));
    }
    best
}

/// A vertex of a raw or trimmed offset loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetVertex {
    /// Position in mm.
    pub p: Point,
    /// Global parameter of the base curve this vertex belongs to.
    pub s: f64,
}

/// Result of trimming: the kept loops and the dropped slices.
#[derive(Debug, Clone, Default)]
pub struct Trimmed {
    /// Closed loops (first vertex not repeated at the end).
    pub loops: Vec<Vec<OffsetVertex>>,
    /// Dropped slices (each a run of vertices where the tool would gouge).
    pub dropped: Vec<Vec<OffsetVertex>>,
}

/// Points (less one) at which [`trim`] measures a slice without a vertex of its own.
const PIECE_SAMPLES: usize = 16;

/// Cuts the closed raw offset `raw` at its self-intersections and keeps the slices whose
/// vertices all stay at least `keep` mm from `base` (see the module docs). A slice between
/// two cuts on one chord has no vertex of its own: it is judged by 17 points along it against
/// `floor`, the least distance a chord of the flattened offset keeps from the curve (its
/// vertices lie on the offset, farther out than `keep`, its chords dip towards the curve by
/// up to the chord tolerance). Judged by its midpoint against `keep`, a chord's piece in the
/// band's lower half was dropped, the walk round the kept slices could not come back to its start, and the loop
/// closed by a chord of its own ran 0.045 mm beyond the band (fuzz corpus `c2eb47c6…`).
pub fn trim(base: &CompositeCurve, raw: &[OffsetVertex], keep: f64, floor: f64) -> Trimmed {
    let m = raw.len();
    let pts: Vec<Point> = raw.iter().map(|v| v.p).collect();
    let xs = crate::curve::intersect::self_intersections(&pts);
    let too_close = |v: &OffsetVertex| distance_to(base, v.p, v.s) < keep;
    let mut out = Trimmed::default();
    if xs.is_empty() {
        if raw.iter().any(too_close) {
            out.dropped.push(raw.to_vec());
        } else {
            out.loops.push(raw.to_vec());
        }
        return out;
    }
    // Cut positions along the polyline: (position, intersection id, point, s).
    let mut cuts: Vec<(f64, usize, Point, f64)> = Vec::new();
    for (id, &(i, ta, j, tb)) in xs.iter().enumerate() {
        let p = raw[i].p.lerp(raw[(i + 1) % m].p, ta);
        let lerp_s = |k: usize, t: f64| {
            let (a, mut b) = (raw[k].s, raw[(k + 1) % m].s);
            if b < a {
                b += base.len() as f64;
            }
            a + (b - a) * t
        };
        cuts.push((i as f64 + ta, id, p, lerp_s(i, ta)));
        cuts.push((j as f64 + tb, id, p, lerp_s(j, tb)));
    }
    cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let nc = cuts.len();
    // Slice k runs from cut k to cut k+1 (cyclically).
    let slices: Vec<Vec<OffsetVertex>> = (0..nc)
        .map(|k| {
            let (a, b) = (cuts[k], cuts[(k + 1) % nc]);
            let mut v = vec![OffsetVertex { p: a.2, s: a.3 }];
            let first = a.0.floor() as usize + 1;
            let mut last = b.0.floor() as usize;
            if k + 1 == nc || b.0 <= a.0 {
                last += m;
            }
            for idx in first..=last {
                v.push(raw[idx % m]);
            }
            v.push(OffsetVertex { p: b.2, s: b.3 });
            v
        })
        .collect();
    let kept: Vec<bool> = slices
        .iter()
        .map(|s| {
            let inner = &s[1..s.len() - 1];
            if inner.is_empty() {
                // Every point of the piece at least `floor` from the curve (to a nanometre of
                // rounding at the cuts): a piece of a swallowtail dips below it.
                let (a, b) = (s[0].p, s[s.len() - 1].p);
                (0..=PIECE_SAMPLES).all(|j| {
                    let p = a.lerp(b, j as f64 / PIECE_SAMPLES as f64);
                    distance_to(base, p, s[0].s) >= floor - 1e-9
                })
            } else {
                !inner.iter().any(too_close)
            }
        })
        .collect();
    // Other cut index of the same intersection.
    let mut partner = vec![0; nc];
    for a in 0..nc {
        for b in 0..nc {
            if a != b && cuts[a].1 == cuts[b].1 {
                partner[a] = b;
            }
        }
    }
    let mut used = vec![false; nc];
    for start in 0..nc {
        if !kept[start] || used[start] {
            continue;
        }
        let mut lp: Vec<OffsetVertex> = Vec::new();
        let mut k = start;
        for _ in 0..=nc {
            used[k] = true;
            let s = &slices[k];
            lp.extend_from_slice(&s[..s.len() - 1]);
            let end_cut = (k + 1) % nc;
            let cross = partner[end_cut];
            let next = if kept[cross] {
                cross
            } else if kept[end_cut] {
                end_cut
            } else {
                break;
            };
            if next == start {
                break;
            }
            if used[next] {
                break;
            }
            k = next;
        }
        if lp.len() >= 3 {
            out.loops.push(lp);
        }
    }
    for (k, s) in slices.into_iter().enumerate() {
        if !kept[k] {
            out.dropped.push(s);
        }
    }
    out
}

/// Signed area of a closed loop (shoelace).
pub fn loop_area(v: &[OffsetVertex]) -> f64 {
    let n = v.len();
    (0..n)
        .map(|i| v[i].p.to_vec2().cross(v[(i + 1) % n].p.to_vec2()))
        .sum::<f64>()
        * 0.5
}
