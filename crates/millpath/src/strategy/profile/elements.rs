//! A closed loop of lines and arcs by arc length: built from an outline's bulge vertices,
//! queried for the point and tangent at an arc length, cut at arc lengths, rotated to start
//! anywhere and reversed.
//!
//! A vertex of bulge `b = tan(θ/4)` starts an arc of sweep `θ` over its chord `c`; the arc's
//! radius is `|c|·(1 + b²)/(4|b|)` and its centre lies `|c|·(1 − b²)/(4b)` to the left of the
//! chord's midpoint (right for `b < 0`), so that a positive bulge turns counter-clockwise.

use crate::curve::ArcSeg;
use crate::geom::{Outline, Point, Vec2};

/// Bulges below this are straight segments.
const STRAIGHT: f64 = 1e-12;

/// A closed loop of elements with their arc lengths.
#[derive(Debug, Clone)]
pub(crate) struct Loop {
    /// The elements, each starting where the previous ends (the last ends at the first's
    /// start).
    pub elems: Vec<ArcSeg>,
    /// Arc length at the start of each element, mm (`starts[0] = 0`).
    pub starts: Vec<f64>,
    /// Total length, mm.
    pub length: f64,
}

/// The element from `a` with bulge `b` to `e`.
pub(crate) fn element(a: Point, b: f64, e: Point) -> ArcSeg {
    if b.abs() < STRAIGHT {
        return ArcSeg {
            start: a,
            end: e,
            center: None,
            ccw: true,
            s_end: 0.0,
        };
    }
    let c = e - a;
    let h = c.length() * (1.0 - b * b) / (4.0 * b);
    let mid = a.lerp(e, 0.5);
    let dir = c.normalize().unwrap_or(Vec2::new(1.0, 0.0));
    ArcSeg {
        start: a,
        end: e,
        center: Some(mid + dir.perp() * h),
        ccw: b > 0.0,
        s_end: 0.0,
    }
}

impl Loop {
    /// The loop of an outline's segments, in the outline's direction, from its first vertex.
    pub fn of_outline(o: &Outline) -> Loop {
        let v: Vec<(Point, f64)> = o.vertices().collect();
        let n = v.len();
        let elems = (0..n)
            .map(|i| element(v[i].0, v[i].1, v[(i + 1) % n].0))
            .collect();
        Loop::new(elems)
    }

    /// The loop of `elems` (tags numbered by element).
    pub fn new(mut elems: Vec<ArcSeg>) -> Loop {
        let mut starts = Vec::with_capacity(elems.len());
        let mut s = 0.0;
        for (i, e) in elems.iter_mut().enumerate() {
            starts.push(s);
            s += e.length();
            e.s_end = (i + 1) as f64;
        }
        Loop {
            elems,
            starts,
            length: s,
        }
    }

    /// The element index and the fraction along it at arc length `s` (taken modulo the
    /// length).
    pub fn locate(&self, s: f64) -> (usize, f64) {
        let s = s.rem_euclid(self.length);
        let i = match self.starts.binary_search_by(|x| x.total_cmp(&s)) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        };
        let len = self.elems[i].length();
        let f = if len > 0.0 {
            ((s - self.starts[i]) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (i, f)
    }

    /// The point at arc length `s`.
    pub fn point(&self, s: f64) -> Point {
        let (i, f) = self.locate(s);
        self.elems[i].at(f)
    }

    /// The unit tangent at arc length `s`.
    pub fn tangent(&self, s: f64) -> Vec2 {
        let (i, f) = self.locate(s);
        tangent_at(&self.elems[i], f)
    }

    /// Arc length of the point of the loop nearest `p`, and its distance.
    pub fn project(&self, p: Point) -> (f64, f64) {
        let mut best = (0.0, f64::INFINITY);
        for (i, e) in self.elems.iter().enumerate() {
            let f = nearest_fraction(e, p);
            let d = e.at(f).distance(p);
            if d < best.1 {
                best = (self.starts[i] + f * e.length(), d);
            }
        }
        best
    }

    /// True when some element of the loop comes nearer than `dist` to `p` (each element
    /// first rejected by its bounding box or, for an arc, its ring).
    pub fn nearer_than(&self, p: Point, dist: f64) -> bool {
        self.elems.iter().any(|e| {
            let near_box = match e.center {
                None => {
                    p.x >= e.start.x.min(e.end.x) - dist
                        && p.x <= e.start.x.max(e.end.x) + dist
                        && p.y >= e.start.y.min(e.end.y) - dist
                        && p.y <= e.start.y.max(e.end.y) + dist
                }
                Some(c) => ((p - c).length() - (e.start - c).length()).abs() < dist,
            };
            near_box && e.at(nearest_fraction(e, p)).distance(p) < dist
        })
    }

    /// The loop started at arc length `s` (the element there cut in two).
    pub fn rotated(&self, s: f64) -> Loop {
        let (i, f) = self.locate(s);
        let n = self.elems.len();
        let mut out = Vec::with_capacity(n + 1);
        let e = self.elems[i];
        let cut = (f > 1e-12 && f < 1.0 - 1e-12).then(|| e.at(f));
        match cut {
            Some(p) => out.push(ArcSeg { start: p, ..e }),
            None if f >= 0.5 => {}
            None => out.push(e),
        }
        for k in 1..n {
            out.push(self.elems[(i + k) % n]);
        }
        match cut {
            Some(p) => out.push(ArcSeg { end: p, ..e }),
            None if f >= 0.5 => out.push(e),
            None => {}
        }
        Loop::new(out)
    }

    /// The loop run the other way.
    pub fn reversed(&self) -> Loop {
        let elems = self
            .elems
            .iter()
            .rev()
            .map(|e| ArcSeg {
                start: e.end,
                end: e.start,
                center: e.center,
                ccw: !e.ccw,
                s_end: 0.0,
            })
            .collect();
        Loop::new(elems)
    }

    /// Signed area (positive counter-clockwise): the chords' shoelace plus each arc's
    /// segment area `r²(θ − sin θ)/2` with the sign of its sweep.
    pub fn signed_area(&self) -> f64 {
        let mut a = 0.0;
        for e in &self.elems {
            a += 0.5 * e.start.to_vec2().cross(e.end.to_vec2());
            if let Some(c) = e.center {
                let r = (e.start - c).length();
                let th = e.sweep();
                a += 0.5 * r * r * (th - th.sin());
            }
        }
        a
    }
}

/// The unit tangent of `e` at fraction `f`.
pub(crate) fn tangent_at(e: &ArcSeg, f: f64) -> Vec2 {
    match e.center {
        None => (e.end - e.start).normalize().unwrap_or(Vec2::new(1.0, 0.0)),
        Some(c) => {
            let radial = (e.at(f) - c).normalize().unwrap_or(Vec2::new(1.0, 0.0));
            if e.ccw { radial.perp() } else { -radial.perp() }
        }
    }
}

/// The fraction along `e` of its point nearest `p`.
fn nearest_fraction(e: &ArcSeg, p: Point) -> f64 {
    match e.center {
        None => {
            let d = e.end - e.start;
            let l2 = d.length_squared();
            if l2 > 0.0 {
                ((p - e.start).dot(d) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            }
        }
        Some(c) => {
            let sw = e.sweep();
            let a0 = (e.start - c).angle();
            let ap = (p - c).angle();
            let delta = if sw >= 0.0 {
                (ap - a0).rem_euclid(std::f64::consts::TAU)
            } else {
                (a0 - ap).rem_euclid(std::f64::consts::TAU)
            };
            if delta <= sw.abs() {
                delta / sw.abs()
            } else if p.distance(e.start) <= p.distance(e.end) {
                0.0
            } else {
                1.0
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_circle_of_two_arcs_has_its_length_area_and_tangents() {
        let o = Outline::new(
            &[(Point::new(-5.0, 0.0), 1.0), (Point::new(5.0, 0.0), 1.0)],
            "c",
        )
        .unwrap();
        let l = Loop::of_outline(&o);
        let pi = std::f64::consts::PI;
        assert!((l.length - 10.0 * pi).abs() < 1e-12);
        assert!((l.signed_area() - 25.0 * pi).abs() < 1e-9);
        // A quarter of the way round from (-5, 0) counter-clockwise: (0, -5), heading +x.
        let q = l.point(2.5 * pi);
        assert!(q.distance(Point::new(0.0, -5.0)) < 1e-12, "{q:?}");
        assert!((l.tangent(2.5 * pi) - Vec2::new(1.0, 0.0)).length() < 1e-12);
        let r = l.rotated(2.5 * pi);
        assert_eq!(r.elems.len(), 3);
        assert!((r.length - l.length).abs() < 1e-9);
        assert!(r.elems[0].start.distance(q) < 1e-12);
        assert!(r.elems[2].end.distance(q) < 1e-12);
        let back = l.reversed();
        assert!((back.signed_area() + 25.0 * pi).abs() < 1e-9);
        let (s, d) = l.project(Point::new(0.0, -7.0));
        assert!((s - 2.5 * pi).abs() < 1e-9 && (d - 2.0).abs() < 1e-12);
    }
}
