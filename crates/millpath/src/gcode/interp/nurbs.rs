//! LinuxCNC's NURBS blocks `G5.2 … G5.3`, read as the true curve: a polyline on
//! the NURBS within [`CHORD_TOLERANCE_MM`].
//!
//! # The blocks (LinuxCNC 2.9, `interp_convert.cc` `convert_nurbs`)
//! `G5.2 [X Y] P w [L k]` starts a curve; each following block `X Y P w` (modal G5.2) adds a
//! control point with weight w > 0; `G5.3` ends it and moves along it. The first control
//! point is where the tool is (weight P when the G5.2 block has no X Y, else 1). The order
//! is 3 (quadratic) unless an L > 3 is given. At least `order` control points are needed.
//! After G5.3 no motion mode is in effect.
//!
//! # The curve
//! Order k, control points P₀…Pₙ with weights wᵢ, the clamped uniform knot vector of
//! LinuxCNC's `nurbs_G5_knot_vector_creator`: k zeros, 1, 2, …, n−k+1, k times n−k+2. The
//! point at u ∈ [0, n−k+2] is Σ Nᵢₖ(u) wᵢ Pᵢ / Σ Nᵢₖ(u) wᵢ (Cox–de Boor basis, half-open
//! spans). It starts at P₀ and ends at Pₙ.
//!
//! # Tolerance and what differs from LinuxCNC
//! Each knot span is cut into at least 8 pieces, and a piece is halved while the curve's
//! point at its middle or quarter parameters lies more than 0.8 [`CHORD_TOLERANCE_MM`] from
//! its chord (to 2⁻¹⁶ of a span; the quarter points catch an inflection inside a piece, where
//! the curve crosses its chord near the middle). LinuxCNC's machine moves along biarcs through 4 points per control
//! point (`emccanon.cc` `NURBS_G5_FEED`), whose basis closes both ends of the order-1
//! intervals and so evaluates points exactly on an interior knot off the curve; its path
//! therefore differs from the true curve by more than this tolerance in places. `rs274 -g`
//! prints the whole curve as one `NURBS_FEED`, so the comparison with it checks the blocks
//! around the curve; the curve itself is checked against an independent evaluation
//! (tests/gcode_nurbs.rs).
//!
//! Planes: in G18 (Z X) and G19 (Y Z) the control points are the plane's two axis words and
//! the curve is the same in those axes (LinuxCNC master's `convert_nurbs`; 2.9's rs274
//! refuses them). Refused: G91, the plane's normal axis word, inverse-time feed.
//!
//! # G5 and G5.1 (LinuxCNC's cubic and quadratic splines)
//! Bézier curves, read the same way (a Bézier is the NURBS of one span, unit weights):
//! `G5.1 X Y I J` from the start S to the end E with the control point S + (I, J) (both
//! required); `G5 X Y I J P Q` with the control points S + (I, J) and E + (P, Q); without
//! I J, in a run of G5, the first control point is the previous G5's second one reflected
//! about S: S − (P, Q)ₚᵣₑᵥ. X Y are absolute or incremental as usual; XY plane only, no Z.

use super::{Block, BlockError, FeedMode, ReadMove, State, plane_axes};
use crate::toolpath::{Move, Plane};

/// Largest distance of the curve from the polyline (mm), checked at each piece's middle.
pub(crate) const CHORD_TOLERANCE_MM: f64 = 0.001;

/// A curve being read: control points (program mm, weight) and the order.
#[derive(Debug, Clone, Default)]
pub(crate) struct NurbsState {
    points: Vec<(f64, f64, f64)>,
    order: usize,
    plane: Plane,
}

/// `a[k]`, 0 outside.
fn at(a: &[f64; 3], k: usize) -> f64 {
    a.get(k).copied().unwrap_or(0.0)
}

/// The letter of axis `k` (0 = X).
pub(crate) fn axis_letter(k: usize) -> char {
    char::from(b"XYZ".get(k).copied().unwrap_or(b'?'))
}

/// Pieces are refined until the sampled distances are within this fraction of the
/// tolerance, which leaves room for the largest distance lying between the samples.
const REFINE_TO: f64 = 0.8;

/// The last G5's P Q (program mm), for a following G5 without I J.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SplineState {
    pq: Option<(f64, f64)>,
}

impl State {
    /// A block in G5.2 mode: starts a curve (`same` false) or adds a control point.
    pub(crate) fn nurbs_block(
        &mut self,
        same: bool,
        b: &mut Block,
        axes: [Option<f64>; 3],
    ) -> Result<(), BlockError> {
        let plane = self.modal.plane;
        let (ua, va, na) = plane_axes(plane);
        let normal = axes.get(na).copied().flatten();
        if !self.modal.absolute || normal.is_some() {
            return Err(BlockError::unsupported(
                if normal.is_some() {
                    format!("G5.2 with {}", axis_letter(na))
                } else {
                    "G5.2 in G91".to_string()
                },
                "NURBS (G5.2) in G90 with the active plane's two axis words and P \
                 (G17: X Y, G18: Z X, G19: Y Z)",
            ));
        }
        if same && self.nurbs.as_ref().is_some_and(|c| c.plane != plane) {
            return Err(BlockError::new(
                "G5.2",
                "a plane change inside the curve",
                "one plane (G17, G18 or G19) for the whole G5.2 … G5.3 curve",
            ));
        }
        if self.modal.feed_mode != FeedMode::PerMinute || !self.feed.is_some_and(|f| f > 0.0) {
            return Err(BlockError::new(
                "G5.2",
                "without a feed",
                "an F > 0 in G94 before a NURBS",
            ));
        }
        let p = b.take(b'P');
        let l = b.take(b'L');
        if let Some((letter, v)) = b.leftover() {
            return Err(BlockError::unsupported(
                format!("{}{v}", char::from(letter)),
                "X, Y, P and L in a NURBS block",
            ));
        }
        let unit = self.unit();
        let (x, y) = (
            axes.get(ua).copied().flatten(),
            axes.get(va).copied().flatten(),
        );
        if x.is_some() != y.is_some() {
            return Err(BlockError::new(
                "G5.2",
                format!(
                    "{} without {} or {} without {}",
                    axis_letter(ua),
                    axis_letter(va),
                    axis_letter(va),
                    axis_letter(ua)
                ),
                "both axis words of the plane for a control point",
            ));
        }
        if !same || self.nurbs.is_none() {
            let w = match (x, p) {
                (None, Some(p)) if p > 0.0 => p,
                _ => 1.0,
            };
            let here = self.program_mm();
            self.nurbs = Some(NurbsState {
                points: vec![(at(&here, ua), at(&here, va), w)],
                order: 3,
                plane,
            });
        } else if x.is_none() && p.is_some_and(|p| p > 0.0) {
            return Err(BlockError::new(
                "G5.2 P",
                "without X and Y",
                "P without X and Y only for the first control point",
            ));
        }
        let Some(curve) = self.nurbs.as_mut() else {
            return Ok(());
        };
        if let Some(l) = l {
            if l.fract() != 0.0 || !(0.0..=100.0).contains(&l) {
                return Err(BlockError::new(
                    "G5.2 L",
                    l,
                    "an integer order (at most 100)",
                ));
            }
            if l > 3.0 {
                curve.order = l as usize;
            }
        }
        if let (Some(x), Some(y)) = (x, y) {
            let w = match p {
                Some(p) if p > 0.0 => p,
                _ => {
                    return Err(BlockError::new(
                        "G5.2 P",
                        format!("{p:?}"),
                        "a positive weight P for every control point",
                    ));
                }
            };
            curve.points.push((x * unit, y * unit, w));
        }
        Ok(())
    }

    /// G5 (`m` = 50) or G5.1 (51): a cubic or quadratic Bézier from here to the block's X Y.
    pub(crate) fn spline(
        &mut self,
        m: u16,
        previous: Option<u16>,
        b: &mut Block,
        axes: [Option<f64>; 3],
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let name = if m == 50 { "G5" } else { "G5.1" };
        if self.modal.plane != Plane::Xy || axes[2].is_some() || b.polar.iter().any(Option::is_some)
        {
            return Err(BlockError::unsupported(
                format!("{name} outside G17, or with Z or polar words"),
                "G5/G5.1 in the XY plane (G17) with X Y I J (P Q)",
            ));
        }
        if self.modal.feed_mode != FeedMode::PerMinute || !self.feed.is_some_and(|f| f > 0.0) {
            return Err(BlockError::new(name, "without a feed", "an F > 0 in G94"));
        }
        let unit = self.unit();
        let word = |b: &mut Block, l: u8| b.take(l).map(|v| v * unit);
        let (i, j) = (word(b, b'I'), word(b, b'J'));
        let (p, q) = if m == 50 {
            (word(b, b'P'), word(b, b'Q'))
        } else {
            (None, None)
        };
        if let Some((letter, v)) = b.leftover() {
            return Err(BlockError::unsupported(
                format!("{}{v}", char::from(letter)),
                "X, Y, I, J (and P, Q with G5) in a spline block",
            ));
        }
        let s = self.program_mm();
        let end = |k: usize, v: Option<f64>| match v {
            Some(v) if self.modal.absolute => v * unit,
            Some(v) => s.get(k).copied().unwrap_or(0.0) + v * unit,
            None => s.get(k).copied().unwrap_or(0.0),
        };
        let e = (end(0, axes[0]), end(1, axes[1]));
        let cp = if m == 51 {
            let (Some(i), Some(j)) = (i, j) else {
                return Err(BlockError::new(
                    name,
                    "without I and J",
                    "both I and J with G5.1",
                ));
            };
            vec![
                (s[0], s[1], 1.0),
                (s[0] + i, s[1] + j, 1.0),
                (e.0, e.1, 1.0),
            ]
        } else {
            let (Some(p), Some(q)) = (p, q) else {
                return Err(BlockError::new(
                    name,
                    "without P and Q",
                    "both P and Q with G5",
                ));
            };
            let first = match (i, j, self.spline.pq) {
                (Some(i), Some(j), _) => (s[0] + i, s[1] + j),
                (None, None, Some((pp, pq))) if previous == Some(50) => (s[0] - pp, s[1] - pq),
                _ => {
                    return Err(BlockError::new(
                        name,
                        "without I and J",
                        "both I and J, or neither after another G5",
                    ));
                }
            };
            self.spline.pq = Some((p, q));
            vec![
                (s[0], s[1], 1.0),
                (first.0, first.1, 1.0),
                (e.0 + p, e.1 + q, 1.0),
                (e.0, e.1, 1.0),
            ]
        };
        let t = knots(cp.len(), cp.len());
        self.push_curve(&polyline(&cp, cp.len(), &t), Plane::Xy, line, out);
        Ok(())
    }

    /// G5.3: the curve's moves.
    pub(crate) fn nurbs_end(
        &mut self,
        previous: Option<u16>,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let curve = self.nurbs.take().filter(|_| previous == Some(52));
        let Some(curve) = curve else {
            return Err(BlockError::new("G5.3", "without G5.2", "G5.2 before G5.3"));
        };
        if curve.points.len() < curve.order {
            return Err(BlockError::new(
                "G5.3",
                format!("{} control points", curve.points.len()),
                format!(
                    "at least as many control points as the order L = {}",
                    curve.order
                ),
            ));
        }
        let t = knots(curve.points.len(), curve.order);
        let uv = polyline(&curve.points, curve.order, &t);
        self.push_curve(&uv, curve.plane, line, out);
        Ok(())
    }

    /// Feed moves through the curve's points `uv` (program mm, in the axes of `plane`); the
    /// plane's normal axis stays where it is.
    pub(crate) fn push_curve(
        &mut self,
        uv: &[(f64, f64)],
        plane: Plane,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) {
        let feed = self.feed.unwrap_or(0.0);
        let (ua, va, _) = plane_axes(plane);
        let mut p = self.program_mm();
        for &(u, v) in uv {
            if let Some(c) = p.get_mut(ua) {
                *c = u;
            }
            if let Some(c) = p.get_mut(va) {
                *c = v;
            }
            let to = self.program_to_machine(p);
            out.push(ReadMove {
                mv: Move {
                    corner: self.modal.corner,
                    ..Move::line(to, feed)
                },
                line,
                modal: self.modal,
            });
            self.pos = to;
        }
    }
}

/// The knots of order `k` for `count` control points (LinuxCNC's knot vector).
fn knots(count: usize, k: usize) -> Vec<f64> {
    let n = count - 1;
    (0..=n + k)
        .map(|i| {
            if i < k {
                0.0
            } else if i <= n {
                (i + 1 - k) as f64
            } else {
                (n + 2 - k) as f64
            }
        })
        .collect()
}

/// The curve's point at `u` (de Boor's algorithm in homogeneous coordinates).
pub(crate) fn point(cp: &[(f64, f64, f64)], k: usize, t: &[f64], u: f64) -> (f64, f64) {
    let n = cp.len() - 1;
    let degree = k - 1;
    // The span: t[s] <= u < t[s+1], the last span closed.
    let mut s = degree;
    while s < n && u >= t.get(s + 1).copied().unwrap_or(f64::INFINITY) {
        s += 1;
    }
    let mut d: Vec<[f64; 3]> = (0..=degree)
        .map(|j| {
            let (x, y, w) = cp.get(j + s - degree).copied().unwrap_or((0.0, 0.0, 1.0));
            [x * w, y * w, w]
        })
        .collect();
    for r in 1..=degree {
        for j in (r..=degree).rev() {
            let i = j + s - degree;
            let lo = t.get(i).copied().unwrap_or(0.0);
            let hi = t.get(i + degree + 1 - r).copied().unwrap_or(0.0);
            let a = if hi > lo { (u - lo) / (hi - lo) } else { 0.0 };
            let prev = d.get(j - 1).copied().unwrap_or([0.0; 3]);
            if let Some(dj) = d.get_mut(j) {
                for c in 0..3 {
                    dj[c] = (1.0 - a) * prev[c] + a * dj[c];
                }
            }
        }
    }
    let h = d.get(degree).copied().unwrap_or([0.0, 0.0, 1.0]);
    (h[0] / h[2], h[1] / h[2])
}

/// The polyline's vertices after the start (see the module docs): the curve of order `k`
/// over the knots `t` (`cp.len() + k` of them, the first k equal and the last k equal),
/// span by span over its domain `t[k−1] … t[n+1]`.
pub(crate) fn polyline(cp: &[(f64, f64, f64)], k: usize, t: &[f64]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let domain = t.get(k.saturating_sub(1)..=cp.len()).unwrap_or_default();
    for w in domain.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= a {
            continue;
        }
        for piece in 0..8 {
            let u0 = a + (b - a) * piece as f64 / 8.0;
            let u1 = if piece == 7 {
                b
            } else {
                a + (b - a) * (piece + 1) as f64 / 8.0
            };
            refine(cp, k, t, u0, u1, 13, &mut out);
        }
    }
    // The end is the last control point exactly.
    if let (Some(last), Some(&(x, y, _))) = (out.last_mut(), cp.last()) {
        *last = (x, y);
    }
    out
}

fn refine(
    cp: &[(f64, f64, f64)],
    k: usize,
    t: &[f64],
    u0: f64,
    u1: f64,
    depth: u32,
    out: &mut Vec<(f64, f64)>,
) {
    let p0 = point(cp, k, t, u0);
    let p1 = point(cp, k, t, u1);
    let um = 0.5 * (u0 + u1);
    let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
    let len = dx.hypot(dy);
    // The curve's distance from the chord at the quarter points too: a piece with an
    // inflection can cross its chord near the middle while bulging on both sides.
    let off = [0.25, 0.5, 0.75]
        .iter()
        .map(|f| {
            let pm = point(cp, k, t, u0 + f * (u1 - u0));
            if len > 0.0 {
                ((pm.0 - p0.0) * dy - (pm.1 - p0.1) * dx).abs() / len
            } else {
                (pm.0 - p0.0).hypot(pm.1 - p0.1)
            }
        })
        .fold(0.0, f64::max);
    if off > REFINE_TO * CHORD_TOLERANCE_MM && depth > 0 {
        refine(cp, k, t, u0, um, depth - 1, out);
        refine(cp, k, t, um, u1, depth - 1, out);
    } else {
        out.push(p1);
    }
}
