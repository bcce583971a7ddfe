//! A closed loop of lines and arcs parametrised by arc length: points, tangents, projection,
//! exact sub-paths and how much the loop turns along a stretch.

use super::super::segments::{Arc, Seg};
use super::super::shape::closed_chain;
use crate::geom::Point;
use cavalier_contours::polyline::Polyline;

/// A closed loop by arc length `s ∈ [0, len)`; positions wrap around.
#[derive(Debug, Clone)]
pub struct Ring {
    segs: Vec<Seg>,
    /// Arc length at the start of each segment.
    cum: Vec<f64>,
    len: f64,
}

impl Ring {
    /// The loop `pl` (closed, any orientation), from its first vertex.
    pub fn new(pl: &Polyline<f64>) -> Self {
        let segs: Vec<Seg> = closed_chain(pl)
            .windows(2)
            .filter(|w| w[0].0.distance(w[1].0) > 1e-12)
            .map(|w| Seg::from_bulge(w[0].0, w[1].0, w[0].1))
            .collect();
        Ring::from_segs(segs)
    }

    /// A loop from segments that join end to start and close.
    pub fn from_segs(segs: Vec<Seg>) -> Self {
        let mut cum = Vec::with_capacity(segs.len());
        let mut acc = 0.0;
        for s in &segs {
            cum.push(acc);
            acc += s.length();
        }
        Ring {
            segs,
            cum,
            len: acc,
        }
    }

    /// Length in mm.
    pub fn len(&self) -> f64 {
        self.len
    }

    /// True for a loop without length.
    pub fn is_empty(&self) -> bool {
        self.segs.is_empty() || self.len <= 0.0
    }

    /// `s` wrapped into `[0, len)`.
    pub fn wrap(&self, s: f64) -> f64 {
        if self.len <= 0.0 {
            return 0.0;
        }
        let w = s.rem_euclid(self.len);
        if w >= self.len { 0.0 } else { w }
    }

    /// The segment index and the arc length into it at position `s`.
    fn locate(&self, s: f64) -> (usize, f64) {
        let s = self.wrap(s);
        let i = self.cum.partition_point(|&c| c <= s).saturating_sub(1);
        (i, s - self.cum.get(i).copied().unwrap_or(0.0))
    }

    /// The point at position `s`.
    pub fn point(&self, s: f64) -> Point {
        let (i, t) = self.locate(s);
        self.segs.get(i).map_or(Point::ORIGIN, |g| g.point_at(t))
    }

    /// The position of the point of the loop nearest to `p`, and the distance.
    pub fn project(&self, p: Point) -> (f64, f64) {
        let mut best = (0.0, f64::INFINITY);
        for (g, &c) in self.segs.iter().zip(&self.cum) {
            let (t, d) = seg_project(g, p);
            if d < best.1 {
                best = (c + t, d);
            }
        }
        (self.wrap(best.0), best.1)
    }

    /// The position of the point nearest to `p` among those within `back` mm behind and
    /// `ahead` mm ahead of position `hint`, and the distance: a projection that follows a
    /// point moving along the loop without jumping to another part of it.
    pub fn project_near(&self, p: Point, hint: f64, back: f64, ahead: f64) -> (f64, f64) {
        let mut best = (hint, f64::INFINITY);
        let (lo, hi) = (hint - back, hint + ahead);
        // Segments are visited once per wrap of the window, at most twice round.
        for lap in [-1.0, 0.0, 1.0] {
            let shift = lap * self.len;
            for (g, &c) in self.segs.iter().zip(&self.cum) {
                let (c0, c1) = (c + shift, c + shift + g.length());
                if c1 < lo || c0 > hi {
                    continue;
                }
                let (t, _) = seg_project(g, p);
                let t = (c0 + t).clamp(lo.max(c0), hi.min(c1)) - c0;
                let d = g.point_at(t).distance(p);
                if d < best.1 {
                    best = (c0 + t, d);
                }
            }
        }
        (best.0, best.1)
    }

    /// The stretch from position `s` forward `len` mm (at most once round), as exact
    /// segments.
    pub fn slice(&self, s: f64, len: f64) -> Vec<Seg> {
        let mut out = Vec::new();
        if self.is_empty() || len <= 1e-12 {
            return out;
        }
        let len = len.min(self.len);
        let (mut i, mut t) = self.locate(s);
        let mut left = len;
        let n = self.segs.len();
        let mut guard = 0;
        // Pieces shorter than this are rounding (1e-11 mm at 2·10⁵ mm from the origin), left
        // out: the next piece starts where they end within it.
        let tiny = 1e-12 * self.len.max(1.0);
        while left > tiny && guard <= 2 * n + 2 {
            let g = &self.segs[i % n];
            let l = g.length();
            let take = (l - t).min(left);
            if take > tiny {
                out.push(sub(g, t, t + take));
            }
            left -= take;
            t = 0.0;
            i = (i + 1) % n;
            guard += 1;
        }
        out
    }

    /// How much the tangent turns, in absolute value, along the stretch from `s` forward
    /// `len` mm (arcs' sweeps and the kinks at vertices), rad.
    pub fn turning(&self, s: f64, len: f64) -> f64 {
        let segs = self.slice(s, len);
        let mut total = 0.0;
        for (k, g) in segs.iter().enumerate() {
            if let Some(a) = g.arc {
                total += a.sweep;
            }
            if k + 1 < segs.len() {
                let t0 = g.tangent_at(g.length());
                let t1 = segs[k + 1].tangent_at(0.0);
                total += t0.cross(t1).atan2(t0.dot(t1)).abs();
            }
        }
        total
    }
}

/// The part of `g` between arc lengths `t0` and `t1`.
pub fn sub(g: &Seg, t0: f64, t1: f64) -> Seg {
    let a = g.point_at(t0);
    let b = g.point_at(t1);
    let len = g.length();
    Seg {
        a,
        b,
        arc: g.arc.map(|arc| Arc {
            sweep: if len > 0.0 {
                arc.sweep * ((t1 - t0) / len).clamp(0.0, 1.0)
            } else {
                0.0
            },
            ..arc
        }),
    }
}

/// The arc length along `g` of its point nearest to `p`, and the distance.
fn seg_project(g: &Seg, p: Point) -> (f64, f64) {
    match g.arc {
        None => {
            let d = g.b - g.a;
            let l2 = d.dot(d);
            let f = if l2 > 0.0 {
                ((p - g.a).dot(d) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let q = g.a.lerp(g.b, f);
            (f * l2.sqrt(), q.distance(p))
        }
        Some(arc) => {
            // Angle from the start, measured in the arc's direction, in [0, 2π).
            let a0 = (g.a - arc.center).angle();
            let ap = (p - arc.center).angle();
            let dir = if arc.ccw { 1.0 } else { -1.0 };
            let phi = (dir * (ap - a0)).rem_euclid(std::f64::consts::TAU);
            let len = g.length();
            let t = if phi <= arc.sweep {
                phi * arc.radius
            } else if p.distance(g.a) <= p.distance(g.b) {
                0.0
            } else {
                len
            };
            let q = g.point_at(t);
            (t, q.distance(p))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cavalier_contours::polyline::PlineSourceMut;

    fn rounded_square() -> Ring {
        // 10 × 10 square with corners rounded at radius 1, counter-clockwise.
        let b = (std::f64::consts::FRAC_PI_8).tan();
        let mut pl = Polyline::new_closed();
        for (x, y, bulge) in [
            (1.0, 0.0, 0.0),
            (9.0, 0.0, b),
            (10.0, 1.0, 0.0),
            (10.0, 9.0, b),
            (9.0, 10.0, 0.0),
            (1.0, 10.0, b),
            (0.0, 9.0, 0.0),
            (0.0, 1.0, b),
        ] {
            pl.add(x, y, bulge);
        }
        Ring::new(&pl)
    }

    #[test]
    fn length_points_projection_and_slices() {
        let r = rounded_square();
        let want = 32.0 + std::f64::consts::TAU;
        assert!((r.len() - want).abs() < 1e-9);
        assert!(r.point(0.0).distance(Point::new(1.0, 0.0)) < 1e-12);
        assert!(r.point(r.len() + 4.0).distance(Point::new(5.0, 0.0)) < 1e-9);
        let (s, d) = r.project(Point::new(5.0, -2.0));
        assert!((s - 4.0).abs() < 1e-9 && (d - 2.0).abs() < 1e-9);
        // A corner point projects onto the arc's middle.
        let (s, d) = r.project(Point::new(11.0, -1.0));
        let mid = 8.0 + 0.25 * std::f64::consts::PI;
        assert!((s - mid).abs() < 1e-9, "{s} {mid}");
        assert!((d - (2.0_f64.sqrt() * 2.0 - 1.0)).abs() < 1e-9);
        // A slice across the start wraps and keeps its length; the turning counts the arcs.
        let sl = r.slice(r.len() - 2.0, 5.0);
        let l: f64 = sl.iter().map(Seg::length).sum();
        assert!((l - 5.0).abs() < 1e-9);
        assert!(sl.windows(2).all(|w| w[0].b.distance(w[1].a) < 1e-9));
        assert!((r.turning(1.0, 6.0)).abs() < 1e-9);
        let turn = r.turning(7.0, 4.0);
        assert!((turn - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{turn}");
    }
}
