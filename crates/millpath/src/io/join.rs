//! Joining open pieces end to end into closed outlines.
//!
//! Drawings often draw one outline as many pieces: LINEs and ARCs in a DXF, several open
//! `<path>`s in an SVG, in any order and direction. [`join`] chains them:
//!
//! 1. Segments shorter than the join tolerance `j` are dropped (zero-length LINEs, repeated
//!    vertices), a piece left with no segment is counted as degenerate.
//! 2. A piece whose ends lie within `j` of each other is a closed outline by itself.
//! 3. Otherwise the chain grows from its end: the nearest free end of another piece within
//!    `j` is attached (the piece reversed when it is its end that matches, bulges moved and
//!    negated), until the chain's end comes within `j` of its start (closed) or nothing more
//!    meets it (an [`OpenChain`], reported with both ends and the gap between them). Then the
//!    same from the start backwards, so an open chain is as long as the pieces allow.
//!
//! Ends are matched through a uniform grid of cell `j`, so joining is linear in the number
//! of pieces. The join moves a vertex by at most `j` (the matched end takes its neighbour's
//! position), which is why `j` should stay well below the machining tolerance: 0.01 mm by
//! default.

use super::affine::Piece;
use crate::geom::Point;
use std::collections::HashMap;

/// A chain of pieces that does not close.
#[derive(Debug, Clone)]
pub struct OpenChain {
    /// Where the chain starts, mm.
    pub start: Point,
    /// Where it ends, mm.
    pub end: Point,
    /// How many pieces it joins.
    pub pieces: usize,
    /// Its length along the straight segments and chords, mm.
    pub length: f64,
}

impl OpenChain {
    /// The distance between the ends, mm.
    pub fn gap(&self) -> f64 {
        self.start.distance(self.end)
    }

    /// One line naming the ends and the gap.
    pub fn describe(&self) -> String {
        format!(
            "open chain of {} piece{}, {:.4} mm long, open at ({:.4}, {:.4}) and ({:.4}, {:.4}): gap {:.4} mm",
            self.pieces,
            if self.pieces == 1 { "" } else { "s" },
            self.length,
            self.start.x,
            self.start.y,
            self.end.x,
            self.end.y,
            self.gap()
        )
    }
}

/// What [`join`] made of a set of pieces.
#[derive(Debug, Clone, Default)]
pub struct Joined {
    /// Closed loops, the closing vertex not repeated.
    pub closed: Vec<Piece>,
    /// Chains that do not close.
    pub open: Vec<OpenChain>,
    /// Pieces with no segment longer than the join tolerance.
    pub degenerate: usize,
    /// The open chains themselves, in the order of `open`.
    pub open_pieces: Vec<Piece>,
}

/// Drops segments shorter than `tol` (keeping the piece's two ends where they were).
pub fn drop_short(piece: &[(Point, f64)], tol: f64) -> Piece {
    let mut out: Piece = Vec::with_capacity(piece.len());
    for &(p, b) in piece {
        match out.last_mut() {
            Some(last) if last.0.distance(p) <= tol => {
                // Keep the first vertex; it takes over the dropped vertex's next segment.
                last.1 = b;
            }
            _ => out.push((p, b)),
        }
    }
    // The last end must stay where it was: move the kept vertex onto it.
    let n = out.len();
    if let (Some(&(p, _)), Some(last)) = (piece.last(), out.last_mut())
        && n > 1
    {
        last.0 = p;
    }
    out
}

/// The piece run backwards: bulges move to the other end of their segment and change sign.
pub fn reverse(p: &[(Point, f64)]) -> Piece {
    let n = p.len();
    (0..n)
        .map(|i| {
            let v = p[n - 1 - i].0;
            let b = if i + 1 < n { -p[n - 2 - i].1 } else { 0.0 };
            (v, b)
        })
        .collect()
}

fn chord_length(p: &[(Point, f64)]) -> f64 {
    p.windows(2).map(|w| w[0].0.distance(w[1].0)).sum()
}

/// Whether a (short-segment-free) piece closes on itself within `tol`.
fn closes(p: &[(Point, f64)], tol: f64) -> bool {
    let (Some(f), Some(l)) = (p.first(), p.last()) else {
        return false;
    };
    let arcs = p[..p.len() - 1].iter().any(|v| v.1 != 0.0);
    (p.len() > 3 || (p.len() == 3 && arcs)) && f.0.distance(l.0) <= tol
}

/// Joins `pieces` end to end within `tol` (see the module doc).
pub fn join(pieces: Vec<Piece>, tol: f64) -> Joined {
    let tol = if tol.is_finite() && tol > 0.0 {
        tol
    } else {
        0.0
    };
    let mut out = Joined::default();
    let mut free: Vec<Option<Piece>> = Vec::new();
    for p in pieces {
        let p = drop_short(&p, tol);
        if p.len() < 2 {
            out.degenerate += 1;
        } else if closes(&p, tol) {
            let mut p = p;
            p.pop();
            out.closed.push(p);
        } else {
            free.push(Some(p));
        }
    }
    // Grid of ends: cell -> (piece index, is_end).
    let cell = if tol > 0.0 { tol } else { 1e-9 };
    let key = |p: Point| ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<(usize, bool)>> = HashMap::new();
    for (i, p) in free.iter().enumerate() {
        if let Some(p) = p {
            grid.entry(key(p[0].0)).or_default().push((i, false));
            grid.entry(key(p[p.len() - 1].0))
                .or_default()
                .push((i, true));
        }
    }
    let nearest = |free: &[Option<Piece>], at: Point| -> Option<(usize, bool)> {
        let (kx, ky) = key(at);
        let mut best: Option<(f64, usize, bool)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &(i, is_end) in grid
                    .get(&(kx.saturating_add(dx), ky.saturating_add(dy)))
                    .into_iter()
                    .flatten()
                {
                    let Some(p) = &free[i] else { continue };
                    let v = if is_end { p[p.len() - 1].0 } else { p[0].0 };
                    let d = v.distance(at);
                    if d <= tol && best.is_none_or(|b| d < b.0) {
                        best = Some((d, i, is_end));
                    }
                }
            }
        }
        best.map(|b| (b.1, b.2))
    };
    for i in 0..free.len() {
        let Some(mut cur) = free[i].take() else {
            continue;
        };
        let mut count = 1;
        let mut closed = false;
        // Forwards from the end, then backwards from the start.
        for pass in 0..2 {
            loop {
                let (start, end) = (cur[0].0, cur[cur.len() - 1].0);
                if count > 1 && start.distance(end) <= tol && closes(&cur, tol) {
                    closed = true;
                    break;
                }
                let Some((j, is_end)) = nearest(&free, end) else {
                    break;
                };
                let Some(p) = free[j].take() else { break };
                let p = if is_end { reverse(&p) } else { p };
                cur.pop();
                cur.extend(p);
                count += 1;
            }
            if closed || pass == 1 {
                break;
            }
            cur = reverse(&cur);
        }
        if closed {
            cur.pop();
            out.closed.push(cur);
        } else {
            // Restore the drawing's direction for the report (it was reversed once).
            let cur = reverse(&cur);
            out.open.push(OpenChain {
                start: cur[0].0,
                end: cur[cur.len() - 1].0,
                pieces: count,
                length: chord_length(&cur),
            });
            out.open_pieces.push(cur);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(a: (f64, f64), b: (f64, f64)) -> Piece {
        vec![(Point::new(a.0, a.1), 0.0), (Point::new(b.0, b.1), 0.0)]
    }

    /// A square of four LINEs in shuffled directions, a zero-length LINE and a gap of 0.005
    /// closes at tolerance 0.01; at 0.001 it is one open chain whose gap is the 0.005.
    #[test]
    fn joins_within_tolerance_and_reports_gaps() {
        let pieces = || {
            vec![
                seg((0.0, 0.0), (10.0, 0.0)),
                seg((10.0, 10.0), (10.0, 0.0)),
                seg((3.0, 3.0), (3.0, 3.0)),
                seg((10.0, 10.0), (0.0, 10.0)),
                seg((0.0, 10.0), (0.0, 0.005)),
            ]
        };
        let j = join(pieces(), 0.01);
        assert_eq!((j.closed.len(), j.open.len(), j.degenerate), (1, 0, 1));
        assert_eq!(j.closed[0].len(), 4);
        let j = join(pieces(), 0.001);
        assert_eq!((j.closed.len(), j.open.len()), (0, 1));
        assert!((j.open[0].gap() - 0.005).abs() < 1e-12, "{:?}", j.open[0]);
        assert_eq!(j.open[0].pieces, 4);
        assert!(j.open[0].describe().contains("gap 0.0050 mm"));
    }

    #[test]
    fn reverse_moves_bulges() {
        let p: Piece = vec![
            (Point::new(0.0, 0.0), 0.5),
            (Point::new(1.0, 0.0), 0.0),
            (Point::new(1.0, 1.0), 0.0),
        ];
        let r = reverse(&p);
        assert_eq!(r[0].0, Point::new(1.0, 1.0));
        assert!(r[0].1.abs() < 1e-12 && (r[1].1 + 0.5).abs() < 1e-12 && r[2].1.abs() < 1e-12);
        assert!((reverse(&r)[0].1 - 0.5).abs() < 1e-12);
    }
}
