//! Cutting a toolpath for the heights it leaves only: its pieces deepest first, the tiles
//! already at or below a piece's lowest tip skipped (see [`super`]).
//!
//! Every cell ends at the least height any piece gives it (and not below the block's
//! bottom), whatever order the pieces come in: a minimum does not depend on the order of its
//! terms. The pieces are those [`HeightField::cut_with`] sweeps, with the same stamps left
//! alone (a non-descending piece from where the one before it in the program ended leaves
//! that piece's end disc alone; the disc's cells get the end's z or less from it, wherever it
//! comes in the new order).
//!
//! **Tiles.** The field is split into tiles of [`TILE`] × [`TILE`] cells, each with an upper
//! bound of its highest cell (heights only go down, so a bound stays one) and a mark for a
//! tile lowered since its bound was last made exact (the bounds start exact, from one scan of
//! the field). A piece whose lowest tip is `z` gives no cell a height below `z` (less
//! `10⁻⁶` mm for the rounding of the tip's interpolation, and not below the bottom); stored
//! as `f32` (rounding is monotone) such a height is no lower than the `f32` of that bound, so
//! a tile whose highest cell is at or below it keeps every height and is skipped. Where a
//! tile's bound says otherwise and the tile is marked, its cells are read again for the exact
//! highest one, at most once per piece. Within a tile that is swept, a cell at or below the
//! same bound keeps its height the same way and is passed over without its tip. Lines and
//! helices alike (a helix's z is linear in its angle: no tip below its ends'). Deepest
//! first, a profile's deepest level cuts the slot down; the levels above it then find the
//! slot's tiles at or below their tips and read only the tiles along its walls. No report is
//! kept (no bitmap of the cells cut, no volume).

use super::{HeightField, Piece, Tally, push_pieces};
use crate::toolpath::Toolpath;

/// Cells along each side of a tile.
const TILE: usize = 8;

/// The end (exclusive) of the run of columns from `i` that stays in `i`'s tile, at most `end`.
pub(super) fn tile_end(i: usize, end: usize) -> usize {
    ((i / TILE + 1) * TILE).min(end)
}

/// An upper bound of the highest cell of each tile, and which bounds may be loose.
#[derive(Debug)]
pub(super) struct Tiles {
    tx: usize,
    high: Vec<f32>,
    loose: Vec<bool>,
    /// The piece being swept, and the last piece for which each tile was read again: a tile
    /// is read at most once per piece (a piece lowering a tile row by row would otherwise
    /// read it again for each row).
    piece: u32,
    read: Vec<u32>,
}

impl Tiles {
    /// Tiles over `field`, every bound exact.
    fn new(field: &HeightField) -> Self {
        let (tx, ty) = (field.nx.div_ceil(TILE), field.ny.div_ceil(TILE));
        let mut high = vec![f32::NEG_INFINITY; tx * ty];
        for (j, row) in field.h.chunks(field.nx).enumerate() {
            let tiles = &mut high[(j / TILE) * tx..(j / TILE + 1) * tx];
            for (t, cells) in tiles.iter_mut().zip(row.chunks(TILE)) {
                *t = cells.iter().fold(*t, |m, &h| m.max(h));
            }
        }
        Tiles {
            tx,
            high,
            loose: vec![false; tx * ty],
            piece: 0,
            read: vec![0; tx * ty],
        }
    }

    /// Starts the next piece.
    fn next_piece(&mut self) {
        self.piece = self.piece.wrapping_add(1);
    }

    /// True when every cell of the tile holding cell `(i, j)` of `field` is at or below `z`.
    pub(super) fn at_or_below(&mut self, field: &HeightField, i: usize, j: usize, z: f32) -> bool {
        let t = (j / TILE) * self.tx + i / TILE;
        if self.high[t] <= z {
            return true;
        }
        if !self.loose[t] || self.read[t] == self.piece {
            return false;
        }
        self.read[t] = self.piece;
        let (i0, j0) = (i / TILE * TILE, j / TILE * TILE);
        let (i1, j1) = ((i0 + TILE).min(field.nx), (j0 + TILE).min(field.ny));
        let high = (j0..j1)
            .flat_map(|jj| field.h[jj * field.nx + i0..jj * field.nx + i1].iter())
            .fold(f32::NEG_INFINITY, |m, &h| m.max(h));
        self.high[t] = high;
        self.loose[t] = false;
        high <= z
    }

    /// Marks the tile holding cell `(i, j)` as lowered.
    pub(super) fn mark(&mut self, i: usize, j: usize) {
        self.loose[(j / TILE) * self.tx + i / TILE] = true;
    }
}

impl HeightField {
    /// Cuts the toolpaths `paths` (each a flat end mill of its tool's diameter) into the
    /// field for the heights they leave, the same as [`HeightField::cut`] on each in turn
    /// leaves, without the operations' reports: their pieces deepest first, skipping the tiles
    /// they cannot lower (module docs).
    pub(crate) fn cut_deepest_first<'a>(&mut self, paths: impl IntoIterator<Item = &'a Toolpath>) {
        let mut pieces: Vec<Piece> = Vec::new();
        for tp in paths {
            let r = tp.tool.radius().max(0.0);
            let mut last = None;
            for (from, m) in tp.segments() {
                push_pieces(from, m, r, &mut last, &mut pieces);
            }
        }
        // Stable: pieces at one depth keep the program's order.
        pieces.sort_by(|p, q| p.lowest().total_cmp(&q.lowest()));
        // No report: the cells lowered are not kept (a bitmap of the whole field, written
        // wherever the pieces cut).
        let mut tally = Tally {
            ztol: super::DEFAULT_Z_TOLERANCE,
            touched: Vec::new(),
            volume: 0.0,
            changed: false,
        };
        let mut tiles = Tiles::new(self);
        for piece in &pieces {
            tiles.next_piece();
            self.sweep_piece(piece, &mut tally, Some(&mut tiles));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Aabb, Point, Point3};
    use crate::stock::FieldOptions;
    use crate::toolpath::{Move, Tool};
    use std::f64::consts::TAU;

    /// A small deterministic generator.
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
    }

    /// A profile-like program: a ramp down by a helix, then a square loop round the middle at
    /// each of several levels, shallow first, the deepest through the bottom, lifting over a
    /// tab on one side below `tab_z`; then random lines, rapids, arcs and helices.
    fn program(rng: &mut Lcg, d: f64) -> Toolpath {
        let mut tp = Toolpath::new(Tool::flat(d).unwrap(), Point3::new(5.0, 5.0, 3.0));
        let step = rng.range(0.4, 1.5);
        let tab_z = rng.range(-5.0, -3.0);
        tp.push(Move::rapid(Point3::new(5.0, 5.0, 1.0)));
        tp.push(Move::arc_xy(
            Point3::new(5.0, 5.0, 0.0),
            Point3::new(6.0, 5.0, 0.0),
            true,
            1.0,
        ));
        let mut z = 0.0;
        while z > -7.0 {
            z -= step;
            tp.push(Move::line(Point3::new(5.0, 5.0, z), 1.0));
            for (x, y) in [(25.0, 5.0), (25.0, 25.0), (5.0, 25.0), (5.0, 5.0)] {
                if z < tab_z && y > 20.0 && x < 10.0 {
                    // The tab: up over (10..20, 25), across, down.
                    tp.push(Move::line(Point3::new(20.0, 25.0, z), 1.0));
                    tp.push(Move::line(Point3::new(18.0, 25.0, tab_z), 1.0));
                    tp.push(Move::line(Point3::new(12.0, 25.0, tab_z), 1.0));
                    tp.push(Move::line(Point3::new(10.0, 25.0, z), 1.0));
                }
                tp.push(Move::line(Point3::new(x, y, z), 1.0));
            }
        }
        tp.push(Move::rapid(Point3::new(5.0, 5.0, 3.0)));
        let mut at = Point3::new(5.0, 5.0, 3.0);
        for _ in 0..8 {
            let z = if rng.next() < 0.3 {
                at.z
            } else {
                rng.range(-8.0, 4.0)
            };
            let m = match (rng.next() * 5.0) as usize {
                0 => Move::rapid(Point3::new(rng.range(2.0, 28.0), rng.range(2.0, 28.0), z)),
                1 | 2 => Move::line(
                    Point3::new(rng.range(2.0, 28.0), rng.range(2.0, 28.0), z),
                    1.0,
                ),
                _ => {
                    let c = Point3::new(
                        at.x + rng.range(-6.0, 6.0),
                        at.y + rng.range(-6.0, 6.0),
                        0.0,
                    );
                    let r = (at.x - c.x).hypot(at.y - c.y);
                    if r < 0.2 {
                        continue;
                    }
                    let a = rng.range(0.0, TAU);
                    let to = Point3::new(c.x + r * a.cos(), c.y + r * a.sin(), z);
                    Move::arc_xy(to, c, rng.next() < 0.5, 1.0)
                }
            };
            at = m.to;
            tp.push(m);
        }
        tp
    }

    /// The runs of `tp` split at every `k`-th move, each starting where its first move starts.
    fn split(tp: &Toolpath, k: usize) -> Vec<Toolpath> {
        let mut runs: Vec<Toolpath> = Vec::new();
        for (n, (from, m)) in tp.segments().enumerate() {
            if n % k == 0 {
                runs.push(Toolpath::new(tp.tool, from));
            }
            if let Some(run) = runs.last_mut() {
                run.moves.push(*m);
            }
        }
        runs
    }

    /// Deepest first with tiles, the field holds the very heights (bit for bit) the program
    /// cut in order leaves, whole or split into runs; over 60 seeded programs, each cutting a
    /// good part of the field through and leaving some of it at the top.
    #[test]
    fn deepest_first_leaves_the_heights_the_program_in_order_leaves() {
        let mut rng = Lcg(37);
        let block = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(30.0, 30.0),
        };
        let mut checked = 0;
        for case in 0..60 {
            let d = rng.range(2.0, 6.0);
            let cell = rng.range(0.05, 0.2);
            let bottom = rng.range(-7.0, -5.5);
            let tp = program(&mut rng, d);
            let opts = FieldOptions::default().with_cell(cell);
            let mut in_order = HeightField::new(block, bottom, 0.0, &opts).unwrap();
            in_order.cut(&tp);
            let mut deepest = HeightField::new(block, bottom, 0.0, &opts).unwrap();
            deepest.cut_deepest_first([&tp]);
            let mut by_runs = HeightField::new(block, bottom, 0.0, &opts).unwrap();
            by_runs.cut_deepest_first(&split(&tp, 1 + case % 7));
            let (mut through, mut top) = (0, 0);
            for (k, &h) in in_order.heights().iter().enumerate() {
                for other in [&deepest, &by_runs] {
                    let g = other.heights()[k];
                    assert_eq!(
                        h.to_bits(),
                        g.to_bits(),
                        "case {case}, cell {k}: {h} vs {g}"
                    );
                }
                through += usize::from(f64::from(h) <= bottom + 1e-3);
                top += usize::from(h == 0.0);
            }
            let n = in_order.heights().len();
            assert!(
                through > n / 10 && top > n / 10,
                "case {case}: {through}, {top} of {n}"
            );
            checked += 1;
        }
        assert_eq!(checked, 60);
    }
}
