//! The holes verifier: a drilling or boring program's moves (as read back from its G-code)
//! against the holes it is meant to cut, with exact geometry on the moves.
//!
//! The tool is a flat end mill of radius `r`: at a position `(p, z)` it has removed the disc
//! of radius `r` about `p` from `z` up. The material is the slab above `bottom` up to `top`
//! (the holes' bottom and the stock's top). [`verify_holes`] checks:
//!
//! * **Nothing cut outside a hole.** Every feed move (line, arc, helix) where it is below
//!   `top` keeps the tool disc inside the disc of the hole nearest to it: the largest
//!   distance of the tool centre from the hole's centre, plus `r`, is at most the hole's
//!   radius plus the tolerance. The largest distance is exact: at a line's ends (the line
//!   clipped to the part below the top; distance is convex along a line), and on an arc at
//!   its ends or at the point farthest from the hole's centre when the sweep holds it (an
//!   arc is taken whole when any of it is below the top). No move goes below
//!   `bottom − tolerance`.
//! * **No rapid in material.** A rapid that goes below `top` goes straight along Z, at a
//!   position where an earlier feed move ended at least as deep (the column is already cut):
//!   the retract of a drilling cycle, a peck's way out and back in, the way up from a bore's
//!   last circle.
//! * **Each hole cut to size and depth.** The feed moves of a hole that reach within the
//!   tolerance of `bottom` (the parts of them that do) sweep the tool disc over an envelope
//!   whose support function in the direction `u` is `h(u) = max (p − c)·u + r` over those
//!   positions (`c` the hole's centre; exact on lines and arcs). For a disc of centre
//!   `c + e` and radius `ρ`, `h(u) = e·u + ρ`: over 360 directions the mean of `h` is the
//!   measured radius and twice the mean of `h·u` the centre's offset. The hole passes when
//!   the measured centre and diameter are within the tolerance of the drawn ones and `h`
//!   is within the tolerance of the drawn radius in every direction (a bottom swept all the
//!   way round). The bottom must also be cleared: points of the hole's disc (radius less
//!   the tolerance, on rings a quarter of the tool radius apart) each within `r` of the
//!   bottom positions (a bore's rings leave no core).
//!
//! The tolerance is the accuracy the holes are checked to, mm (0.01 mm by default in the
//! jobs): it must also cover the program's rounding (0.0005 mm at 3 decimals).

use crate::geom::{Hole, Point, Point3, Vec2};
use crate::toolpath::{Move, MoveKind, Tool};
use serde::Serialize;
use std::collections::HashMap;
use std::f64::consts::TAU;

/// Directions the envelope's support function is measured in.
const DIRECTIONS: usize = 360;

/// What the holes verifier found wrong.
#[derive(Debug, Clone, PartialEq)]
pub enum HoleProblem {
    /// A feed move below the top cuts outside every hole (by `by` mm beyond the nearest).
    CutOutside {
        /// Index of the move.
        index: usize,
        /// The nearest hole.
        hole: Hole,
        /// How far the tool reaches beyond that hole, mm.
        by: f64,
    },
    /// A move goes deeper than the holes' bottom.
    TooDeep {
        /// Index of the move.
        index: usize,
        /// Its lowest point.
        at: Point3,
    },
    /// A rapid moves through material.
    RapidInMaterial {
        /// Index of the move.
        index: usize,
        /// Where it ends.
        at: Point3,
    },
    /// A hole never reached its bottom.
    NotCut {
        /// The hole.
        hole: Hole,
        /// The deepest the tool went inside it, Z mm (`None`: never below the top).
        deepest: Option<f64>,
    },
    /// A hole cut off its centre, too large, too small or not round.
    OffSize {
        /// The hole.
        hole: Hole,
        /// Its check.
        check: HoleCheck,
    },
    /// Material left on a hole's bottom.
    BottomLeft {
        /// The hole.
        hole: Hole,
        /// A point of the bottom no tool position reached.
        at: Point,
    },
}

impl std::fmt::Display for HoleProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let h = |h: &Hole| {
            format!(
                "hole ⌀{:.3} mm at ({:.3}, {:.3})",
                h.diameter, h.center.x, h.center.y
            )
        };
        match self {
            HoleProblem::CutOutside { index, hole, by } => write!(
                f,
                "move {index} cuts {by:.4} mm outside the nearest hole, {}",
                h(hole)
            ),
            HoleProblem::TooDeep { index, at } => write!(
                f,
                "move {index} goes below the holes' bottom, to ({:.3}, {:.3}, {:.4})",
                at.x, at.y, at.z
            ),
            HoleProblem::RapidInMaterial { index, at } => write!(
                f,
                "rapid move {index} to ({:.3}, {:.3}, {:.4}) goes through material",
                at.x, at.y, at.z
            ),
            HoleProblem::NotCut { hole, deepest } => match deepest {
                Some(z) => write!(f, "{} is cut only to Z {z:.4}", h(hole)),
                None => write!(f, "{} is not cut", h(hole)),
            },
            HoleProblem::OffSize { hole, check } => write!(
                f,
                "{} is cut ⌀{:.4} mm, its centre {:.4} mm off, {:.4} mm out of round",
                h(hole),
                check.diameter_mm,
                check.center_error_mm,
                check.roundness_mm
            ),
            HoleProblem::BottomLeft { hole, at } => write!(
                f,
                "{} keeps material on its bottom at ({:.3}, {:.3})",
                h(hole),
                at.x,
                at.y
            ),
        }
    }
}

/// One hole as cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HoleCheck {
    /// Diameter of the envelope at the bottom, mm.
    pub diameter_mm: f64,
    /// Distance of its centre from the drawn centre, mm.
    pub center_error_mm: f64,
    /// Largest difference between the envelope's support function and the drawn radius,
    /// mm.
    pub roundness_mm: f64,
    /// The deepest the tool went inside the hole, Z mm.
    pub deepest: f64,
}

/// What [`verify_holes`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct HoleVerification {
    /// Each hole's check, in the order given (`None` for a hole never cut to its bottom).
    pub holes: Vec<Option<HoleCheck>>,
    /// Everything wrong; empty when the program cuts the holes and nothing else.
    pub problems: Vec<HoleProblem>,
}

impl HoleVerification {
    /// True when nothing is wrong.
    pub fn ok(&self) -> bool {
        self.problems.is_empty()
    }
}

/// A piece of tool-centre path in the plane.
#[derive(Debug, Clone, Copy)]
enum Piece {
    Line(Point, Point),
    Arc {
        c: Point,
        r: f64,
        a0: f64,
        sweep: f64,
    },
}

impl Piece {
    fn point(&self, f: f64) -> Point {
        match *self {
            Piece::Line(a, b) => a.lerp(b, f),
            Piece::Arc { c, r, a0, sweep } => c + Vec2::from_angle(a0 + sweep * f) * r,
        }
    }

    /// Whether angle `a` lies within the arc's sweep.
    fn holds_angle(a0: f64, sweep: f64, a: f64) -> bool {
        if sweep.abs() >= TAU {
            return true;
        }
        let d = if sweep >= 0.0 { a - a0 } else { a0 - a };
        d.rem_euclid(TAU) <= sweep.abs()
    }

    /// The largest of `(p − q)·u` over the piece.
    fn support(&self, q: Point, u: Vec2) -> f64 {
        let ends = (self.point(0.0) - q)
            .dot(u)
            .max((self.point(1.0) - q).dot(u));
        match *self {
            Piece::Line(..) => ends,
            Piece::Arc { c, r, a0, sweep } => {
                if Piece::holds_angle(a0, sweep, u.angle()) {
                    ends.max((c - q).dot(u) + r)
                } else {
                    ends
                }
            }
        }
    }

    /// The largest distance from `q` to the piece.
    fn max_distance(&self, q: Point) -> f64 {
        let ends = self.point(0.0).distance(q).max(self.point(1.0).distance(q));
        match *self {
            Piece::Line(..) => ends,
            Piece::Arc { c, r, a0, sweep } => {
                let away = (c - q).angle();
                if c.distance(q) > 1e-12 && Piece::holds_angle(a0, sweep, away) {
                    ends.max(c.distance(q) + r)
                } else if c.distance(q) <= 1e-12 {
                    r
                } else {
                    ends
                }
            }
        }
    }

    /// The distance from `q` to the piece.
    fn distance(&self, q: Point) -> f64 {
        match *self {
            Piece::Line(a, b) => {
                let ab = b - a;
                let l2 = ab.length_squared();
                let t = if l2 > 0.0 {
                    ((q - a).dot(ab) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                a.lerp(b, t).distance(q)
            }
            Piece::Arc { c, r, a0, sweep } => {
                let ends = self.point(0.0).distance(q).min(self.point(1.0).distance(q));
                if Piece::holds_angle(a0, sweep, (q - c).angle()) {
                    ends.min((c.distance(q) - r).abs())
                } else {
                    ends
                }
            }
        }
    }
}

/// The part of feed move `m` (from `from`) in the plane between path fractions `f0 ≤ f1`.
fn piece(from: Point3, m: &Move, f0: f64, f1: f64) -> Piece {
    match (m.kind, m.sweep_from(from)) {
        (MoveKind::Arc { center, .. }, Some((r, sweep))) => {
            let c = center.xy();
            let a0 = (from.xy() - c).angle();
            Piece::Arc {
                c,
                r,
                a0: a0 + sweep * f0,
                sweep: sweep * (f1 - f0),
            }
        }
        _ => Piece::Line(from.xy().lerp(m.to.xy(), f0), from.xy().lerp(m.to.xy(), f1)),
    }
}

/// The fractions of a move from `from` (Z changing linearly along it) where Z ≤ `level`.
fn below(from: Point3, to: Point3, level: f64) -> Option<(f64, f64)> {
    let (z0, z1) = (from.z, to.z);
    if z0 > level && z1 > level {
        return None;
    }
    if z0 <= level && z1 <= level {
        return Some((0.0, 1.0));
    }
    let f = ((level - z0) / (z1 - z0)).clamp(0.0, 1.0);
    Some(if z0 <= level { (0.0, f) } else { (f, 1.0) })
}

/// The hole nearest to `p` (index).
fn nearest(holes: &[Hole], p: Point) -> Option<usize> {
    holes
        .iter()
        .enumerate()
        .map(|(i, h)| (i, h.center.distance(p) - h.radius()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// Checks a program's moves `(from, move)` against `holes` for a tool `tool`, the stock's
/// top at `top` and the holes' bottom at `bottom` (Z, mm), to `tolerance` mm (module docs).
pub fn verify_holes(
    holes: &[Hole],
    moves: &[(Point3, Move)],
    tool: &Tool,
    top: f64,
    bottom: f64,
    tolerance: f64,
) -> HoleVerification {
    let r = tool.radius();
    let mut problems = Vec::new();
    let key = |p: Point| ((p.x * 1e5).round() as i64, (p.y * 1e5).round() as i64);
    // The deepest feed end at each position (the columns already cut).
    let mut reached: HashMap<(i64, i64), f64> = HashMap::new();
    let mut bottoms: Vec<Vec<Piece>> = vec![Vec::new(); holes.len()];
    let mut deepest: Vec<Option<f64>> = vec![None; holes.len()];
    let depth_level = bottom + tolerance;
    for (index, (from, m)) in moves.iter().enumerate() {
        let low = from.z.min(m.to.z);
        match m.kind {
            MoveKind::Dwell { .. } => continue,
            MoveKind::Rapid => {
                if low >= top {
                    continue;
                }
                let straight = from.xy().distance(m.to.xy()) <= 1e-6;
                let (kx, ky) = key(m.to.xy());
                let cut_deep = (-1..=1).any(|dx| {
                    (-1..=1).any(|dy| {
                        reached
                            .get(&(kx + dx, ky + dy))
                            .is_some_and(|&z| z <= low + 1e-6)
                    })
                });
                if !(straight && cut_deep) {
                    problems.push(HoleProblem::RapidInMaterial { index, at: m.to });
                }
                continue;
            }
            MoveKind::Line | MoveKind::Arc { .. } => {}
        }
        let slot = reached.entry(key(m.to.xy())).or_insert(f64::INFINITY);
        *slot = slot.min(m.to.z);
        if low >= top {
            continue;
        }
        if low < bottom - tolerance {
            let at = if m.to.z <= from.z { m.to } else { *from };
            problems.push(HoleProblem::TooDeep { index, at });
        }
        // The part below the top (a whole arc when any of it is).
        let cut = match m.kind {
            MoveKind::Arc { .. } => piece(*from, m, 0.0, 1.0),
            _ => {
                let (f0, f1) = below(*from, m.to, top).unwrap_or((0.0, 1.0));
                piece(*from, m, f0, f1)
            }
        };
        let Some(k) = nearest(holes, cut.point(0.0)) else {
            problems.push(HoleProblem::CutOutside {
                index,
                hole: Hole::new(Point::ORIGIN, 0.0),
                by: f64::INFINITY,
            });
            continue;
        };
        let hole = holes[k];
        let by = cut.max_distance(hole.center) + r - hole.radius();
        if by > tolerance {
            problems.push(HoleProblem::CutOutside { index, hole, by });
        }
        let d = deepest[k].get_or_insert(low);
        *d = d.min(low);
        if let Some((f0, f1)) = below(*from, m.to, depth_level) {
            bottoms[k].push(piece(*from, m, f0, f1));
        }
    }
    let mut checks = Vec::with_capacity(holes.len());
    for (k, hole) in holes.iter().enumerate() {
        let pieces = &bottoms[k];
        if pieces.is_empty() {
            problems.push(HoleProblem::NotCut {
                hole: *hole,
                deepest: deepest[k],
            });
            checks.push(None);
            continue;
        }
        let check = envelope(hole, pieces, r, deepest[k].unwrap_or(bottom));
        if check.center_error_mm > tolerance
            || (check.diameter_mm - hole.diameter).abs() > tolerance
            || check.roundness_mm > tolerance
        {
            problems.push(HoleProblem::OffSize { hole: *hole, check });
        }
        if let Some(at) = uncut_bottom(hole, pieces, r, tolerance) {
            problems.push(HoleProblem::BottomLeft { hole: *hole, at });
        }
        checks.push(Some(check));
    }
    HoleVerification {
        holes: checks,
        problems,
    }
}

/// The envelope of the tool disc over `pieces` about `hole` (module docs).
fn envelope(hole: &Hole, pieces: &[Piece], r: f64, deepest: f64) -> HoleCheck {
    let c = hole.center;
    let mut mean = 0.0;
    let mut first = Vec2::new(0.0, 0.0);
    let mut worst = 0.0f64;
    for k in 0..DIRECTIONS {
        let u = Vec2::from_angle(TAU * k as f64 / DIRECTIONS as f64);
        let h = pieces
            .iter()
            .map(|p| p.support(c, u))
            .fold(f64::NEG_INFINITY, f64::max)
            + r;
        mean += h;
        first += u * h;
        worst = worst.max((h - hole.radius()).abs());
    }
    let n = DIRECTIONS as f64;
    HoleCheck {
        diameter_mm: 2.0 * mean / n,
        center_error_mm: (first * (2.0 / n)).length(),
        roundness_mm: worst,
        deepest,
    }
}

/// A point of the hole's bottom (within its radius less the tolerance) farther than `r`
/// from every bottom position, if any.
fn uncut_bottom(hole: &Hole, pieces: &[Piece], r: f64, tolerance: f64) -> Option<Point> {
    let outer = (hole.radius() - tolerance).max(0.0);
    let step = (0.25 * r).max(1e-3);
    let rings = (outer / step).ceil().max(1.0) as usize;
    for i in 0..=rings {
        let rho = outer * i as f64 / rings as f64;
        let around = ((TAU * rho / step).ceil() as usize).max(1);
        for j in 0..around {
            let q = hole.center + Vec2::from_angle(TAU * j as f64 / around as f64) * rho;
            let d = pieces
                .iter()
                .map(|p| p.distance(q))
                .fold(f64::INFINITY, f64::min);
            if d > r + 1e-6 {
                return Some(q);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(moves: &[Move], start: Point3) -> Vec<(Point3, Move)> {
        let mut at = start;
        moves
            .iter()
            .map(|m| {
                let f = at;
                at = m.to;
                (f, *m)
            })
            .collect()
    }

    #[test]
    fn a_drilled_hole_passes_and_a_shifted_one_does_not() {
        let tool = Tool::flat(5.0).unwrap();
        let hole = Hole::new(Point::new(10.0, 10.0), 5.0);
        let p = |z: f64| Point3::new(10.0, 10.0, z);
        let moves = [
            Move::rapid(p(5.0)),
            Move::rapid(p(1.0)),
            Move::line(p(-3.0), 2.0),
            Move::rapid(p(1.0)),
            Move::rapid(p(-2.7)),
            Move::line(p(-6.0), 2.0),
            Move::rapid(p(5.0)),
        ];
        let v = verify_holes(
            &[hole],
            &seg(&moves, Point3::new(0.0, 0.0, 5.0)),
            &tool,
            0.0,
            -6.0,
            0.01,
        );
        assert!(v.ok(), "{:?}", v.problems);
        let c = v.holes[0].unwrap();
        assert!((c.diameter_mm - 5.0).abs() < 1e-9 && c.center_error_mm < 1e-9);
        // Drawn 0.05 mm elsewhere: off centre and cutting outside it.
        let off = Hole::new(Point::new(10.05, 10.0), 5.0);
        let v = verify_holes(
            &[off],
            &seg(&moves, Point3::new(0.0, 0.0, 5.0)),
            &tool,
            0.0,
            -6.0,
            0.01,
        );
        assert!(
            v.problems
                .iter()
                .any(|p| matches!(p, HoleProblem::OffSize { .. }))
        );
        assert!(
            v.problems
                .iter()
                .any(|p| matches!(p, HoleProblem::CutOutside { .. }))
        );
        // A peck coming back down by rapid below the depth already cut.
        let mut bad = moves;
        bad[4] = Move::rapid(p(-3.5));
        let v = verify_holes(
            &[hole],
            &seg(&bad, Point3::new(0.0, 0.0, 5.0)),
            &tool,
            0.0,
            -6.0,
            0.01,
        );
        assert!(
            v.problems
                .iter()
                .any(|p| matches!(p, HoleProblem::RapidInMaterial { index: 4, .. })),
            "{:?}",
            v.problems
        );
        // Not deep enough.
        let v = verify_holes(
            &[hole],
            &seg(&moves, Point3::new(0.0, 0.0, 5.0)),
            &tool,
            0.0,
            -7.0,
            0.01,
        );
        assert!(matches!(v.problems[..], [HoleProblem::NotCut { .. }]));
    }

    #[test]
    fn a_circle_at_the_bottom_is_a_hole_and_a_ring_too_far_out_keeps_a_core() {
        let tool = Tool::flat(4.0).unwrap();
        let c = Point::new(0.0, 0.0);
        let at = |x: f64, z: f64| Point3::new(x, 0.0, z);
        let circle = |rho: f64| {
            vec![
                Move::rapid(at(rho, 1.0)),
                Move::arc_xy(at(rho, -2.0), Point3::new(0.0, 0.0, -2.0), true, 5.0),
                Move::arc_xy(at(rho, -2.0), Point3::new(0.0, 0.0, -2.0), true, 5.0),
                Move::rapid(at(rho, 1.0)),
            ]
        };
        // ⌀8 with a ⌀4 tool: a circle of radius 2 covers the centre.
        let v = verify_holes(
            &[Hole::new(c, 8.0)],
            &seg(&circle(2.0), at(0.0, 5.0)),
            &tool,
            0.0,
            -2.0,
            0.01,
        );
        assert!(v.ok(), "{:?}", v.problems);
        // ⌀12: one circle of radius 4 leaves a core of radius 2.
        let v = verify_holes(
            &[Hole::new(c, 12.0)],
            &seg(&circle(4.0), at(0.0, 5.0)),
            &tool,
            0.0,
            -2.0,
            0.01,
        );
        assert!(
            matches!(v.problems[..], [HoleProblem::BottomLeft { .. }]),
            "{:?}",
            v.problems
        );
    }
}
