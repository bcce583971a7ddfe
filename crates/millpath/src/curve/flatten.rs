//! The fewest chords within a chordal tolerance, with an exact deviation.
//!
//! # Tolerance
//! `tol` (mm) bounds the distance from every point of the curve between two consecutive
//! vertices to the chord joining them (the chordal deviation, paper Fig. 3). Vertices lie on
//! the curve. The count grows like `∫√(|κ|/(8·tol)) ds` (a circle arc of radius `R` spanned
//! by a chord of length `L` sags `≈ L²/(8R)`).
//!
//! # Exact deviation
//! For the chord `A = C(s0)`, `B = C(s1)`, direction `c = B − A`, the distance of `C(s)` to the
//! line is `|cross(C(s) − A, ĉ)|`, whose derivative is `cross(C'(s), ĉ)`: its interior maxima
//! are where the tangent is parallel to the chord. On a cubic piece that is a quadratic
//! ([`Cubic::parallel_roots`]), solved in closed form; piece boundaries are added as
//! candidates (a junction may be only C0). The deviation is the largest distance from a
//! candidate to the chord *segment* (not the line), so it is exact where the maximum of the
//! line distance is attained and conservative otherwise. No scan step is involved: the paper
//! scans `u` with a fixed `du`; here each deviation is a handful of root evaluations.
//!
//! # Farthest reachable end, and why greedy is optimal
//! From a vertex `s0` we take the largest `s1` with `dev(s0, s1) ≤ tol`: a square-law
//! predictor (`dev ∝ step²` on a smooth arc) scales the previous step to the tolerance, the
//! end is bracketed (doubling while feasible, halving while not) and bisected to a relative
//! 1e-7 of the step. `dev(s0, ·)` is not monotone in general: past an inflection the chord can cross
//! the curve and become feasible again. After bisecting, four probes at 1.25…2× the found
//! length test for such a return; a feasible probe restarts the doubling from it.
//!
//! Optimality: call the problem *nested* if every sub-chord of a feasible chord is feasible.
//! Then the greedy "farthest end" is optimal for an open run by the usual exchange argument:
//! if an optimal chain has its k-th vertex at `y_k` and greedy at `x_k ≥ y_k`, the chord
//! `(x_k, y_{k+1})` is a sub-chord of `(y_k, y_{k+1})`, so `x_{k+1} ≥ y_{k+1}`. Nesting holds
//! on every arc of constant curvature sign that turns by less than π: such an arc is a graph
//! over its chord, the sub-chord's end points lie between the chord and the far support line
//! (at height ≤ tol), so at any abscissa the sub-chord lies between them and every sub-arc
//! point is within tol of it vertically, hence perpendicularly. Across inflections nesting
//! can fail by a small margin and the count can exceed the optimum by a vertex or so. For a
//! closed curve without corners, greedy from any start uses at most one chord more than the
//! optimum `N*` (the start lies inside some optimal chord; splitting it gives an open chain
//! of `N* + 1` chords that greedy matches), so `N* ≥ N_greedy − 1`: that is the lower bound
//! [`Flattening::lower_bound`] reports, and the 2 % acceptance test is checked against it.
//! With corners the runs between corners are open problems and greedy is optimal on each.

use super::{CompositeCurve, Cubic};
use crate::error::InputError;
use crate::geom::{Point, Vec2};
use serde::{Deserialize, Serialize};

/// A curve the flattener can work on: pieces with a local parameter in `[0, 1]`.
pub trait PlanarCurve {
    /// Number of pieces (the parameter period of the closed curve).
    fn piece_count(&self) -> usize;
    /// The point of piece `i` at local parameter `u`.
    fn point_at(&self, i: usize, u: f64) -> Point;
    /// Appends to `out` every local parameter in `(u0, u1)` of piece `i` where the curve's
    /// distance to a line of direction `dir` can have an interior maximum (tangent parallel to
    /// `dir`, or a cusp).
    fn critical(&self, i: usize, dir: Vec2, u0: f64, u1: f64, out: &mut Vec<f64>);
    /// Pieces whose start must be a vertex (corners, discontinuities), ascending.
    fn breaks(&self) -> Vec<usize>;
    /// Unit tangent (direction of travel) of piece `i` at `u`; by default a central
    /// difference of [`PlanarCurve::point_at`].
    fn tangent_at(&self, i: usize, u: f64) -> Vec2 {
        let h = 1e-7;
        let (a, b) = ((u - h).max(0.0), (u + h).min(1.0));
        (self.point_at(i, b) - self.point_at(i, a))
            .normalize()
            .unwrap_or(Vec2::new(1.0, 0.0))
    }
}

impl PlanarCurve for CompositeCurve {
    fn piece_count(&self) -> usize {
        self.len()
    }
    fn point_at(&self, i: usize, u: f64) -> Point {
        self.pieces()[i % self.len()].eval(u)
    }
    fn critical(&self, i: usize, dir: Vec2, u0: f64, u1: f64, out: &mut Vec<f64>) {
        self.pieces()[i % self.len()].parallel_roots(dir, u0, u1, out);
    }
    fn breaks(&self) -> Vec<usize> {
        self.corners().to_vec()
    }
    fn tangent_at(&self, i: usize, u: f64) -> Vec2 {
        let c = &self.pieces()[i % self.len()];
        c.d1(u)
            .normalize()
            .or_else(|| c.d2(u).normalize())
            .unwrap_or(Vec2::new(1.0, 0.0))
    }
}

impl PlanarCurve for Cubic {
    fn piece_count(&self) -> usize {
        1
    }
    fn point_at(&self, _: usize, u: f64) -> Point {
        self.eval(u)
    }
    fn critical(&self, _: usize, dir: Vec2, u0: f64, u1: f64, out: &mut Vec<f64>) {
        self.parallel_roots(dir, u0, u1, out);
    }
    fn breaks(&self) -> Vec<usize> {
        vec![0]
    }
}

/// The vertices of a flattening.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Flattening {
    /// Global curve parameter of each vertex (piece index + local u), increasing, unwrapped:
    /// the last equals the first plus the piece count (the polygon is closed).
    pub params: Vec<f64>,
    /// The vertices (`points[i]` is the curve at `params[i]`; last = first).
    pub points: Vec<Point>,
    /// The largest exact chordal deviation over all chords (mm).
    pub max_deviation: f64,
    /// The tolerance it was made for (mm).
    pub tolerance: f64,
}

impl Flattening {
    /// Number of chords (G1 blocks for one pass).
    pub fn segments(&self) -> usize {
        self.points.len().saturating_sub(1)
    }
    /// A lower bound on the fewest chords any flattening within the tolerance can use (see
    /// the module docs: greedy is within one chord of the optimum on a closed smooth curve
    /// and optimal between corners).
    pub fn lower_bound(&self, corners: usize) -> usize {
        if corners == 0 {
            self.segments().saturating_sub(1)
        } else {
            self.segments()
        }
    }
}

/// Options of [`flatten`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FlattenOptions {
    /// Parameter of the first vertex when the curve has no corner (with corners, the first
    /// corner at or after it).
    pub start: f64,
    /// Probe past the bisected end for a farther feasible end (non-monotone deviation).
    pub probe: bool,
}

impl Default for FlattenOptions {
    fn default() -> Self {
        FlattenOptions {
            start: 0.0,
            probe: true,
        }
    }
}

option_builders! {
    FlattenOptions;
    /// Sets [`FlattenOptions::start`], curve parameter.
    with_start => start: f64;
    /// Sets [`FlattenOptions::probe`].
    with_probe => probe: bool;
}

struct Run<'a, C: PlanarCurve + ?Sized> {
    c: &'a C,
    hi: f64,
    n: usize,
    buf: Vec<f64>,
}

impl<C: PlanarCurve + ?Sized> Run<'_, C> {
    /// The point at global `s` in this run; `s == hi` at an integer is the previous piece's end.
    fn pt(&self, s: f64) -> Point {
        let (i, u) = self.locate(s);
        self.c.point_at(i, u)
    }
    fn locate(&self, s: f64) -> (usize, f64) {
        let mut k = s.floor();
        if s >= self.hi && self.hi.fract() == 0.0 {
            k = self.hi - 1.0;
        }
        let i = (k.rem_euclid(self.n as f64) as usize).min(self.n - 1);
        (i, (s - k).clamp(0.0, 1.0))
    }
    fn dev(&mut self, s0: f64, s1: f64) -> f64 {
        let (a, b) = (self.pt(s0), self.pt(s1));
        let dir = b - a;
        let mut worst = 0.0_f64;
        let mut k = s0.floor();
        while k < s1 {
            let (u0, u1) = ((s0 - k).max(0.0), (s1 - k).min(1.0));
            let i = (k.rem_euclid(self.n as f64) as usize).min(self.n - 1);
            self.buf.clear();
            if dir.length_squared() > 0.0 {
                self.c.critical(i, dir, u0, u1, &mut self.buf);
            } else {
                // A closed chord: its "line" is a point; sample the extremes instead.
                self.buf
                    .extend((1..32).map(|j| u0 + (u1 - u0) * f64::from(j) / 32.0));
            }
            if k + 1.0 < s1 {
                // A piece boundary strictly inside the chord (possibly only C0).
                self.buf.push(1.0);
            }
            for &u in &self.buf {
                worst = worst.max(dist_to_segment(self.c.point_at(i, u), a, b));
            }
            k += 1.0;
        }
        worst
    }
}

/// Distance from `p` to the segment `a`–`b`.
pub fn dist_to_segment(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    if l2 == 0.0 {
        return p.distance(a);
    }
    let t = ((p - a).dot(ab) / l2).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

#[cfg(test)]
/// The exact chordal deviation of the chord from global parameter `s0` to `s1` (`s0 < s1`,
/// unwrapped; no corner strictly inside).
pub fn deviation<C: PlanarCurve + ?Sized>(c: &C, s0: f64, s1: f64) -> f64 {
    let mut run = Run {
        c,
        hi: s1,
        n: c.piece_count(),
        buf: Vec::new(),
    };
    run.dev(s0, s1)
}

const PARAM_EPS: f64 = 1e-12;
const BISECT_REL: f64 = 1e-7;
/// Relative margin the flattener keeps below the tolerance (see [`flatten_opt`]).
pub const TOL_MARGIN: f64 = 1e-6;

fn farthest<C: PlanarCurve + ?Sized>(
    run: &mut Run<'_, C>,
    s: f64,
    tol: f64,
    h0: f64,
    probe: bool,
) -> f64 {
    let hi = run.hi;
    let eps = PARAM_EPS * (1.0 + s.abs());
    let mut lo;
    let mut up;
    // What is left of the range is below the parameter resolution: one chord to its end
    // (`clamp` below would panic on an empty range; found by the seeded mutation pass,
    // tests/hostile_mutate.rs, and kept as fuzz/corpus-min/contour/regression-clamp-min-gt-max).
    if hi - s <= eps || hi.is_nan() || s.is_nan() {
        return hi;
    }
    let mut h = h0.clamp(eps, hi - s);
    // Predictor: on a smooth arc the deviation grows like the square of the step, so
    // h·√(tol/dev(h)) lands close to the end; a few rounds, then a tight bracket.
    for _ in 0..3 {
        let d = run.dev(s, s + h);
        if d.is_nan() || d <= 0.0 || h >= hi - s {
            break;
        }
        let ratio = (tol / d).sqrt();
        if (ratio - 1.0).abs() < 2e-3 {
            break;
        }
        h = (h * ratio * 0.999).clamp(eps, hi - s);
    }
    if run.dev(s, s + h) <= tol {
        lo = s + h;
        let t = s + h * 1.002;
        up = if t < hi && run.dev(s, t) > tol { t } else { hi };
    } else {
        loop {
            h *= 0.5;
            if h <= eps {
                return (s + eps).min(hi);
            }
            if run.dev(s, s + h) <= tol {
                lo = s + h;
                up = s + 2.0 * h;
                break;
            }
        }
    }
    for _restart in 0..8 {
        // Double while feasible.
        while up >= hi && lo < hi {
            let t = s + 2.0 * (lo - s);
            if t >= hi {
                if run.dev(s, hi) <= tol {
                    return hi;
                }
                up = hi;
                break;
            }
            if run.dev(s, t) <= tol {
                lo = t;
            } else {
                up = t;
            }
        }
        // Bisect to a relative 1e-7 of the step (the count cannot notice less).
        while up - lo > (BISECT_REL * (up - s)).max(eps) {
            let m = 0.5 * (lo + up);
            if run.dev(s, m) <= tol {
                lo = m;
            } else {
                up = m;
            }
        }
        if !probe {
            return lo;
        }
        let len = lo - s;
        let far = (1..=4)
            .rev()
            .map(|k| up + len * f64::from(k) / 4.0)
            .filter(|t| *t < hi)
            .find(|t| run.dev(s, *t) <= tol);
        match far {
            Some(t) => {
                lo = t;
                up = hi;
            }
            None => return lo,
        }
    }
    lo
}

/// Flattens the closed curve `c` within `tol` (mm) with default options (see the module docs).
pub fn flatten<C: PlanarCurve + ?Sized>(c: &C, tol: f64) -> Result<Flattening, InputError> {
    flatten_opt(c, tol, &FlattenOptions::default())
}

/// [`flatten`] for a [`CompositeCurve`] (convenience for callers that do not import the trait).
pub fn flatten_curve(c: &CompositeCurve, tol: f64) -> Result<Flattening, InputError> {
    flatten(c, tol)
}

/// Flattens the closed curve `c` within `tol` (mm).
pub fn flatten_opt<C: PlanarCurve + ?Sized>(
    c: &C,
    tol: f64,
    opt: &FlattenOptions,
) -> Result<Flattening, InputError> {
    crate::error::require_positive("tolerance", tol, "flattening")?;
    let n = c.piece_count();
    if n == 0 {
        return Err(InputError::new("curve pieces", 0).expected("a non-empty curve"));
    }
    let mut b: Vec<f64> = c.breaks().into_iter().map(|i| i as f64).collect();
    let start = if b.is_empty() {
        opt.start
    } else {
        let s = opt.start.rem_euclid(n as f64);
        let first = b
            .iter()
            .copied()
            .find(|x| *x >= s - 1e-12)
            .unwrap_or(b[0] + n as f64);
        b.retain(|x| (*x - first).abs() > 0.5 && (*x - (first - n as f64)).abs() > 0.5);
        first
    };
    // Break points in (start, start + n), ascending, then the end.
    let mut stops: Vec<f64> = b
        .iter()
        .map(|x| if *x < start { x + n as f64 } else { *x })
        .collect();
    stops.sort_by(f64::total_cmp);
    stops.push(start + n as f64);
    // Aim a hair below tol so that floating-point differences between evaluators (about
    // 1e-13 mm at 400 mm) cannot push an independently verified deviation over tol.
    let tol = tol * (1.0 - TOL_MARGIN);
    let mut params = vec![start];
    let mut h = 0.01;
    let mut s = start;
    let mut max_dev = 0.0_f64;
    for hi in stops {
        let mut run = Run {
            c,
            hi,
            n,
            buf: Vec::new(),
        };
        while s < hi {
            let t = farthest(&mut run, s, tol, h, opt.probe);
            max_dev = max_dev.max(run.dev(s, t));
            if t < hi {
                h = t - s;
            }
            params.push(t);
            s = t;
        }
        s = hi;
    }
    let points = {
        let run = Run {
            c,
            hi: start + n as f64,
            n,
            buf: Vec::new(),
        };
        params.iter().map(|s| run.pt(*s)).collect()
    };
    Ok(Flattening {
        params,
        points,
        max_deviation: max_dev,
        tolerance: tol / (1.0 - TOL_MARGIN),
    })
}

/// The asymptotic optimum `∫√(|κ|/(8·tol)) ds` over the curve (composite Simpson, 512
/// intervals per piece): the chord count an optimal flattening approaches as `tol → 0`.
pub fn asymptotic_count(c: &CompositeCurve, tol: f64) -> f64 {
    let m = 512;
    let f = |p: &Cubic, u: f64| (p.curvature(u).abs() / (8.0 * tol)).sqrt() * p.d1(u).length();
    c.pieces()
        .iter()
        .map(|p| {
            let h = 1.0 / f64::from(m);
            let mut sum = f(p, 0.0) + f(p, 1.0);
            for j in 1..m {
                let w = if j % 2 == 1 { 4.0 } else { 2.0 };
                sum += w * f(p, f64::from(j) * h);
            }
            sum * h / 3.0
        })
        .sum()
}

/// The number of line segments `kurbo::flatten` makes for the same curve at the same
/// tolerance.
pub fn kurbo_count(c: &CompositeCurve, tol: f64) -> usize {
    let mut count = 0;
    let mut last = kurbo::Point::ZERO;
    let mut first = kurbo::Point::ZERO;
    kurbo::flatten(c.to_bez_path(), tol, |el| match el {
        kurbo::PathEl::MoveTo(p) => {
            first = p;
            last = p;
        }
        kurbo::PathEl::LineTo(p) => {
            count += 1;
            last = p;
        }
        kurbo::PathEl::ClosePath if last.distance(first) > 0.0 => count += 1,
        _ => {}
    });
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circleish() -> CompositeCurve {
        let pts: Vec<Point> = (0..8)
            .map(|i| {
                Point::ORIGIN + Vec2::from_angle(f64::from(i) * std::f64::consts::TAU / 8.0) * 100.0
            })
            .collect();
        let pieces = super::super::spline::closed(&pts).unwrap();
        let kinds = vec![super::super::PieceKind::Interpolating; 8];
        CompositeCurve::new(pieces, kinds, "t").unwrap()
    }

    #[test]
    fn exact_deviation_matches_dense_sampling() {
        let c = circleish();
        for (s0, s1) in [(0.1, 0.7), (0.5, 1.9), (2.0, 2.3)] {
            let d = deviation(&c, s0, s1);
            let (a, b) = (c.eval(s0), c.eval(s1));
            let dense = (0..=10000)
                .map(|j| dist_to_segment(c.eval(s0 + (s1 - s0) * f64::from(j) / 10000.0), a, b))
                .fold(0.0, f64::max);
            // Exact is never below sampling, and sampling misses at most its own grid error.
            assert!(
                d >= dense - 1e-12 && d - dense < 1e-7 * (1.0 + d),
                "{d} vs {dense}"
            );
        }
    }

    #[test]
    fn flattening_is_within_tolerance_and_near_optimal_on_a_circle() {
        let c = circleish();
        let f = flatten(&c, 0.01).unwrap();
        assert!(f.max_deviation <= 0.01);
        // Circle of radius ~100: optimum ≈ 2π/(2·acos(1 − 0.01/100)).
        let opt = std::f64::consts::TAU / (2.0 * (1.0 - 0.01 / 100.0_f64).acos());
        let n = f.segments() as f64;
        assert!(
            n <= opt.ceil() + 1.0 && n >= opt.floor() - 1.0,
            "{n} vs {opt}"
        );
        assert!(f.segments() <= kurbo_count(&c, 0.01));
    }
}
