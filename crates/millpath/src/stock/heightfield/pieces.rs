//! The pieces a move is swept as (see [`super`]): a line or a rapid whole, an XY arc whole
//! (a helix, or an arc at one z), an arc in another plane (or of a radius within
//! [`ARC_SAGITTA`]) as chords of at most [`ARC_SAGITTA`] sagitta.

use super::{ARC_SAGITTA, Stamp, arc_pieces};
use crate::geom::{Point, Point3};
use crate::toolpath::{Move, MoveKind, Plane};

/// One sweep a move is cut as: a straight piece (a line, a rapid, or one of an arc's
/// chords, with the disc the move before it stamped) or an XY arc, its z linear in the
/// angle turned (a helix; constant on an arc at one z).
#[derive(Debug, Clone, Copy)]
pub(super) enum Piece {
    Line {
        a: Point3,
        b: Point3,
        r: f64,
        last: Option<Stamp>,
    },
    Arc {
        from: Point3,
        to: Point3,
        centre: Point,
        sweep: f64,
        r: f64,
    },
}

impl Piece {
    /// The lowest tip z over the piece, mm.
    pub(super) fn lowest(&self) -> f64 {
        match *self {
            Piece::Line { a, b, .. } => a.z.min(b.z),
            Piece::Arc { from, to, .. } => from.z.min(to.z),
        }
    }
}

/// Appends to `out` the pieces the move `m` from `from` is swept as, a tool of radius `r`
/// (see [`super`]); `last` is the disc the move before stamped, and becomes this move's.
pub(super) fn push_pieces(
    from: Point3,
    m: &Move,
    r: f64,
    last: &mut Option<Stamp>,
    out: &mut Vec<Piece>,
) {
    match m.kind {
        MoveKind::Dwell { .. } => {}
        MoveKind::Rapid | MoveKind::Line => {
            out.push(Piece::Line {
                a: from,
                b: m.to,
                r,
                last: *last,
            });
            *last = Some(Stamp {
                at: m.to.xy(),
                z: m.to.z,
                r,
            });
        }
        MoveKind::Arc { center, plane, .. } => {
            if let (Plane::Xy, Some((r0, sweep))) = (plane, m.sweep_from(from))
                && r0 > ARC_SAGITTA
            {
                // Whole: each cell's lowest tip over the angles that pass over it.
                out.push(Piece::Arc {
                    from,
                    to: m.to,
                    centre: center.xy(),
                    sweep,
                    r,
                });
                *last = Some(Stamp {
                    at: m.to.xy(),
                    z: m.to.z,
                    r,
                });
                return;
            }
            let len = m.length_from(from);
            let (n, sagitta) = arc_pieces(m.sweep_from(from));
            let mut a = from;
            for piece in 1..=n {
                let b = if piece == n {
                    m.to
                } else {
                    m.point_at(from, len * piece as f64 / n as f64)
                };
                let rr = r + sagitta;
                out.push(Piece::Line {
                    a,
                    b,
                    r: rr,
                    last: *last,
                });
                *last = Some(Stamp {
                    at: b.xy(),
                    z: b.z,
                    r: rr,
                });
                a = b;
            }
        }
    }
}
