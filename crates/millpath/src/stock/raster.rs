//! A bitset raster of the material in one slab.
//!
//! Cell `(i, j)` covers `[x₀ + i·c, x₀ + (i+1)·c) × [y₀ + j·c, y₀ + (j+1)·c)` and stands for
//! its centre: it holds material when its centre is inside the pocket (even-odd rule over the
//! outline and the islands) and has not been within the tool radius of a tool position. Rows
//! are runs of 64-bit words, so clearing the tool disc costs one masked word operation per
//! 64 cells of each row it spans, and the number of cells it removed is a popcount.

use crate::geom::{Aabb, Point};
use cavalier_contours::polyline::{PlineSource, Polyline, seg_arc_radius_and_center};
use std::f64::consts::TAU;

/// Material cells of one slab.
#[derive(Debug, Clone)]
pub struct Raster {
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    words: usize,
    bits: Vec<u64>,
}

impl Raster {
    /// An empty raster covering `bounds` with square cells of side `cell` mm.
    pub fn new(bounds: Aabb, cell: f64) -> Self {
        let (nx, ny) = Self::dims_of(bounds, cell);
        let words = nx.div_ceil(64);
        Raster {
            origin: Point::new(bounds.min.x - cell, bounds.min.y - cell),
            cell,
            nx,
            ny,
            words,
            bits: vec![0; words * ny],
        }
    }

    /// Cells along x and along y of the raster [`Raster::new`] makes (a cell of margin on
    /// every side).
    pub fn dims_of(bounds: Aabb, cell: f64) -> (usize, usize) {
        (
            ((bounds.width() / cell).ceil() as usize).max(1) + 2,
            ((bounds.height() / cell).ceil() as usize).max(1) + 2,
        )
    }

    fn grid(&self) -> Grid {
        Grid {
            origin: self.origin,
            cell: self.cell,
            nx: self.nx,
            ny: self.ny,
        }
    }

    /// Cell side in mm.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// Cells along x and along y.
    pub fn dims(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// True when cell `(i, j)` holds material.
    pub fn get(&self, i: usize, j: usize) -> bool {
        self.bits[j * self.words + i / 64] >> (i % 64) & 1 == 1
    }

    /// Centre of cell `(i, j)`.
    pub fn centre(&self, i: usize, j: usize) -> Point {
        Point::new(
            self.origin.x + (i as f64 + 0.5) * self.cell,
            self.origin.y + (j as f64 + 0.5) * self.cell,
        )
    }

    /// Sets every cell whose centre is inside an odd number of `loops`.
    pub fn fill(&mut self, loops: &[&Polyline<f64>]) {
        for j in 0..self.ny {
            let y = self.centre(0, j).y;
            let mut xs: Vec<f64> = Vec::new();
            for pl in loops {
                for (v1, v2) in pl.iter_segments() {
                    if v1.bulge_is_zero() {
                        if (v1.y <= y && y < v2.y) || (v2.y <= y && y < v1.y) {
                            xs.push(v1.x + (y - v1.y) / (v2.y - v1.y) * (v2.x - v1.x));
                        }
                    } else {
                        arc_crossings(v1, v2, y, &mut xs);
                    }
                }
            }
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                let i0 = ((pair[0] - self.origin.x) / self.cell - 0.5)
                    .ceil()
                    .max(0.0) as usize;
                let i1 = ((pair[1] - self.origin.x) / self.cell - 0.5).floor();
                if i1 < 0.0 {
                    continue;
                }
                self.set_span(j, i0, (i1 as usize).min(self.nx - 1), true);
            }
        }
    }

    fn set_span(&mut self, j: usize, i0: usize, i1: usize, on: bool) -> u32 {
        if i0 > i1 {
            return 0;
        }
        let row = j * self.words;
        let mut count = 0;
        for (w, mask) in word_masks(i0, i1) {
            let word = &mut self.bits[row + w];
            count += (*word & mask).count_ones();
            if on {
                *word |= mask;
            } else {
                *word &= !mask;
            }
        }
        count
    }

    fn span_count(&self, j: usize, i0: usize, i1: usize) -> u32 {
        if i0 > i1 {
            return 0;
        }
        let row = j * self.words;
        let mut count = 0;
        for (w, mask) in word_masks(i0, i1) {
            count += (self.bits[row + w] & mask).count_ones();
        }
        count
    }

    /// Clears the cells within `r` of the segment from `a` to `b`; returns how many material
    /// cells it removed.
    pub fn clear_capsule(&mut self, a: Point, b: Point, r: f64) -> u64 {
        self.clear_capsule_from(a, b, r, false)
    }

    /// [`Raster::clear_capsule`] when `a_clear` says that the cells within `r` of `a` hold no
    /// material (an earlier clear of a disc or capsule ending at `a` with a radius of at
    /// least `r`): those rows' cells inside `a`'s disc are not visited, only the rest of the
    /// capsule, the crescent a step adds. The cells cleared and the count are the same.
    pub fn clear_capsule_from(&mut self, a: Point, b: Point, r: f64, a_clear: bool) -> u64 {
        let mut n = 0;
        self.grid().capsule_spans(a, b, r, a_clear, |j, i0, i1| {
            n += u64::from(self.set_span(j, i0, i1, false));
        });
        n
    }

    /// Clears the cells within `r` of the segment from `a` to `b`, as `counts.len()` equal
    /// steps would one after the other, and adds to `counts[k]` the material cells the step
    /// from `a + (b − a)·k/n` to `a + (b − a)·(k + 1)/n` is the first to reach (`n` the
    /// steps). A cell at `t` along the segment and `s` across it is within `r` of the
    /// positions from `t − √(r² − s²)` to `t + √(r² − s²)`, so the first step that reaches
    /// it is the one holding the start of that interval (the first step where it starts
    /// before `a`). Each row of the capsule is read once, where the steps one by one would
    /// read it once each.
    pub fn sweep_steps(&mut self, a: Point, b: Point, r: f64, counts: &mut [u64]) {
        let n = counts.len();
        if n == 0 {
            return;
        }
        let d = b - a;
        let len = d.length();
        let (ux, uy) = if len > 0.0 {
            (d.x / len, d.y / len)
        } else {
            (1.0, 0.0)
        };
        let per = if len > 0.0 { n as f64 / len } else { 0.0 };
        let grid = self.grid();
        let words = self.words;
        let bits = &mut self.bits;
        let last = (n - 1) as f64;
        grid.capsule_spans(a, b, r, false, |j, i0, i1| {
            let dy = grid.row_y(j) - a.y;
            let row = j * words;
            for (w, mask) in word_masks(i0, i1) {
                let word = &mut bits[row + w];
                let mut hit = *word & mask;
                *word &= !mask;
                while hit != 0 {
                    let i = w * 64 + hit.trailing_zeros() as usize;
                    hit &= hit - 1;
                    let dx = grid.origin.x + (i as f64 + 0.5) * grid.cell - a.x;
                    let t = dx * ux + dy * uy;
                    let across = dx * uy - dy * ux;
                    let half = (r * r - across * across).max(0.0).sqrt();
                    let k = ((t - half) * per).ceil() - 1.0;
                    counts[k.clamp(0.0, last) as usize] += 1;
                }
            }
        });
    }

    /// Clears the disc of radius `r` about `c`; returns how many material cells it removed.
    pub fn clear_disc(&mut self, c: Point, r: f64) -> u64 {
        self.grid()
            .disc_spans(c, r)
            .map(|(j, i0, i1)| u64::from(self.set_span(j, i0, i1, false)))
            .sum()
    }

    /// How many material cells lie within `r` of `c`.
    pub fn count_disc(&self, c: Point, r: f64) -> u64 {
        self.grid()
            .disc_spans(c, r)
            .map(|(j, i0, i1)| u64::from(self.span_count(j, i0, i1)))
            .sum()
    }

    #[cfg(test)]
    /// Material cells left.
    pub fn count(&self) -> u64 {
        self.bits.iter().map(|w| u64::from(w.count_ones())).sum()
    }

    /// Centres of the material cells left.
    pub fn material_cells(&self) -> impl Iterator<Item = Point> + '_ {
        (0..self.ny).flat_map(move |j| {
            (0..self.words).flat_map(move |w| {
                let mut word = self.bits[j * self.words + w];
                std::iter::from_fn(move || {
                    if word == 0 {
                        return None;
                    }
                    let b = word.trailing_zeros() as usize;
                    word &= word - 1;
                    Some(self.centre(w * 64 + b, j))
                })
            })
        })
    }
}

/// Crossings of the horizontal line at `y` with the arc `v1 → v2`, half-open at the end.
fn arc_crossings(
    v1: cavalier_contours::polyline::PlineVertex<f64>,
    v2: cavalier_contours::polyline::PlineVertex<f64>,
    y: f64,
    xs: &mut Vec<f64>,
) {
    let (radius, centre) = seg_arc_radius_and_center(v1, v2);
    let dy = y - centre.y;
    let q = radius * radius - dy * dy;
    if q <= 0.0 {
        return;
    }
    let sweep = 4.0 * v1.bulge.atan();
    let a0 = (v1.y - centre.y).atan2(v1.x - centre.x);
    let dx = q.sqrt();
    for x in [centre.x - dx, centre.x + dx] {
        let a = dy.atan2(x - centre.x);
        let rel = if sweep > 0.0 { a - a0 } else { a0 - a };
        let rel = rel.rem_euclid(TAU);
        // Half-open: include the start, exclude the end.
        if rel < sweep.abs() - 1e-12 {
            xs.push(x);
        }
    }
}

/// The layout of a raster's cells, apart from its bits (so that spans can be walked while
/// the bits change).
#[derive(Debug, Clone, Copy)]
struct Grid {
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
}

/// The words of a row that cells `i0..=i1` fall in, each with the mask of those cells.
#[inline]
fn word_masks(i0: usize, i1: usize) -> impl Iterator<Item = (usize, u64)> {
    (i0 / 64..=i1 / 64).map(move |w| {
        let lo = if w == i0 / 64 { i0 % 64 } else { 0 };
        let hi = if w == i1 / 64 { i1 % 64 } else { 63 };
        (w, (u64::MAX >> (63 - hi)) & (u64::MAX << lo))
    })
}

/// `x.floor()` without a call into libm (the baseline x86-64 target has no rounding
/// instruction): exact for every `|x| < 2⁶³`, and what the callers clamp beyond.
#[inline]
fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x { t - 1.0 } else { t }
}

/// `x.ceil()`, as [`floor`].
#[inline]
fn ceil(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t < x { t + 1.0 } else { t }
}

impl Grid {
    /// The y of row `j`'s cell centres.
    fn row_y(self, j: usize) -> f64 {
        self.origin.y + (j as f64 + 0.5) * self.cell
    }

    /// Rows and column ranges of the cells whose centres lie within `r` of `c`.
    fn disc_spans(self, c: Point, r: f64) -> impl Iterator<Item = (usize, usize, usize)> {
        self.rows(c.y - r, c.y + r).filter_map(move |j| {
            let dy = self.row_y(j) - c.y;
            let w2 = r * r - dy * dy;
            if w2 < 0.0 {
                return None;
            }
            let w = w2.sqrt();
            self.columns(c.x - w, c.x + w).map(|(i0, i1)| (j, i0, i1))
        })
    }

    /// The rows `j0..=j1` of the cells whose centres lie between `y0` and `y1`.
    fn rows(self, y0: f64, y1: f64) -> std::ops::Range<usize> {
        let j0 = ceil((y0 - self.origin.y) / self.cell - 0.5).max(0.0) as usize;
        let j1 = floor((y1 - self.origin.y) / self.cell - 0.5);
        if j1 < 0.0 || self.ny == 0 {
            return 0..0;
        }
        let j1 = (j1 as usize).min(self.ny - 1);
        if j0 <= j1 { j0..j1 + 1 } else { 0..0 }
    }

    /// The columns `i0..=i1` of the cells whose centres lie between `x0` and `x1`.
    fn columns(self, x0: f64, x1: f64) -> Option<(usize, usize)> {
        self.column_range(
            ceil((x0 - self.origin.x) / self.cell - 0.5),
            floor((x1 - self.origin.x) / self.cell - 0.5),
        )
    }

    /// [`Grid::columns`] from its rounded ends: the first column at or after `x0` and the
    /// last at or before `x1`, in cell units (`⌈(x₀ − o)/c − ½⌉`, `⌊(x₁ − o)/c − ½⌋`),
    /// clamped to the grid; `None` when the last lies before the grid.
    fn column_range(self, first: f64, last: f64) -> Option<(usize, usize)> {
        let i0 = first.max(0.0) as usize;
        (last >= 0.0 && self.nx > 0).then(|| (i0, (last as usize).min(self.nx - 1)))
    }

    /// Rows and column ranges of the cells whose centres lie within `r` of the segment from
    /// `a` to `b` (the area a disc of radius `r` sweeps along it), each passed to `span`.
    /// Each row meets this convex region in one interval: the hull of where it meets the two
    /// end discs and the band `0 ≤ t ≤ |b − a|`, `|s| ≤ r` (`t` along the segment, `s` across
    /// it, both linear in x). The discs' half-widths are found 64 rows at a time, their
    /// square roots in one loop the compiler vectorises (they are most of the work).
    ///
    /// With `a_skip`, a row's cells within `r` of `a` are left out (up to two spans a row):
    /// the caller knows them clear. Only rows whose centre lies inside `a`'s disc by more
    /// than a cell's square (`r² − dy² > c²`) skip: there the disc's columns are found by the
    /// same arithmetic as every disc and capsule ending at `a` with radius `r`, and such a
    /// clear visited that row (a row at the disc's very edge might have been left out of it
    /// by the rounding of its row range).
    fn capsule_spans(
        self,
        a: Point,
        b: Point,
        r: f64,
        a_skip: bool,
        mut span: impl FnMut(usize, usize, usize),
    ) {
        const CHUNK: usize = 64;
        let d = b - a;
        let len = d.length();
        let u = if len > 0.0 { d / len } else { d };
        // The band reaches past the discs' chords only in rows that cross a straight side
        // (`s = ±r`, its y from `min(a.y, b.y) ± u.x·r` to `max(a.y, b.y) ± u.x·r`): elsewhere
        // a row meets the band between points of the two diameters `t = 0` and `t = len`,
        // inside the discs. A row a cell or more from both sides' y skips the band: its
        // points there lie at least that far inside a disc's chord.
        let (y_lo, y_hi) = (a.y.min(b.y), a.y.max(b.y));
        let side = (u.x * r).abs() + self.cell;
        let crosses_a_side = move |y: f64| {
            (y_lo - side..=y_hi + side).contains(&y) && {
                let (d1, d2) = (u.x * r, -u.x * r);
                [d1, d2]
                    .iter()
                    .any(|&dy| (y_lo + dy - self.cell..=y_hi + dy + self.cell).contains(&y))
            }
        };
        let rows = self.rows(a.y.min(b.y) - r, a.y.max(b.y) + r);
        let (ox, c) = (self.origin.x, self.cell);
        let (mut w2, mut w) = ([[0.0; CHUNK]; 2], [[0.0; CHUNK]; 2]);
        let (mut lo, mut hi) = ([0.0; CHUNK], [0.0; CHUNK]);
        // Per row, as floats: the hull's first and last columns, then `a`'s disc's.
        let mut cols = [[0.0; CHUNK]; 4];
        let mut j0 = rows.start;
        while j0 < rows.end {
            let n = (rows.end - j0).min(CHUNK);
            for (e, c) in [a, b].iter().enumerate() {
                for (k, v) in w2[e][..n].iter_mut().enumerate() {
                    let dy = self.row_y(j0 + k) - c.y;
                    *v = r * r - dy * dy;
                }
                for (s, v) in w[e][..n].iter_mut().zip(&w2[e][..n]) {
                    *s = v.max(0.0).sqrt();
                }
            }
            for k in 0..n {
                let (la, ha) = if w2[0][k] >= 0.0 {
                    (a.x - w[0][k], a.x + w[0][k])
                } else {
                    (f64::INFINITY, f64::NEG_INFINITY)
                };
                let (lb, hb) = if w2[1][k] >= 0.0 {
                    (b.x - w[1][k], b.x + w[1][k])
                } else {
                    (f64::INFINITY, f64::NEG_INFINITY)
                };
                lo[k] = la.min(lb);
                hi[k] = ha.max(hb);
            }
            for k in 0..n {
                let y = self.row_y(j0 + k);
                if len > 0.0 && crosses_a_side(y) {
                    // t(x) = u.x·(x − a.x) + u.y·(y − a.y) ∈ [0, len];
                    // s(x) = u.y·(x − a.x) − u.x·(y − a.y) ∈ [−r, r].
                    let (t0, s0) = (u.y * (y - a.y), -u.x * (y - a.y));
                    let band = [(u.x, t0, 0.0, len), (u.y, s0, -r, r)].iter().try_fold(
                        (f64::NEG_INFINITY, f64::INFINITY),
                        |(l, h), &(k, c0, min, max)| {
                            if k.abs() < 1e-12 {
                                (min..=max).contains(&c0).then_some((l, h))
                            } else {
                                let (x0, x1) = ((min - c0) / k + a.x, (max - c0) / k + a.x);
                                Some((l.max(x0.min(x1)), h.min(x0.max(x1))))
                            }
                        },
                    );
                    if let Some((l, h)) = band.filter(|(l, h)| l <= h) {
                        lo[k] = lo[k].min(l);
                        hi[k] = hi[k].max(h);
                    }
                }
            }
            // [`Grid::columns`]' arithmetic, a chunk at a time (the divisions and roundings
            // were most of a row's cost one by one).
            for k in 0..n {
                cols[0][k] = ((lo[k] - ox) / c - 0.5).ceil();
                cols[1][k] = ((hi[k] - ox) / c - 0.5).floor();
            }
            if a_skip {
                for k in 0..n {
                    cols[2][k] = ((a.x - w[0][k] - ox) / c - 0.5).ceil();
                    cols[3][k] = ((a.x + w[0][k] - ox) / c - 0.5).floor();
                }
            }
            for k in 0..n {
                let j = j0 + k;
                if lo[k] > hi[k] {
                    continue;
                }
                let Some((i0, i1)) = self.column_range(cols[0][k], cols[1][k]) else {
                    continue;
                };
                if a_skip
                    && w2[0][k] > c * c
                    && let Some((d0, d1)) = self.column_range(cols[2][k], cols[3][k])
                    && d0 <= d1
                {
                    if d0 > i0 {
                        span(j, i0, (d0 - 1).min(i1));
                    }
                    if d1 < i1 {
                        span(j, (d1 + 1).max(i0), i1);
                    }
                    continue;
                }
                span(j, i0, i1);
            }
            j0 += n;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cavalier_contours::polyline::PlineSourceMut;

    #[test]
    fn circle_fill_area_and_disc_clearing() {
        let mut pl = Polyline::new_closed();
        pl.add(-10.0, 0.0, 1.0);
        pl.add(10.0, 0.0, 1.0);
        let bounds = Aabb {
            min: Point::new(-10.0, -10.0),
            max: Point::new(10.0, 10.0),
        };
        let mut r = Raster::new(bounds, 0.05);
        r.fill(&[&pl]);
        let area = r.count() as f64 * 0.05 * 0.05;
        assert!((area - std::f64::consts::PI * 100.0).abs() < 0.5, "{area}");
        let removed = r.clear_disc(Point::ORIGIN, 5.0) as f64 * 0.0025;
        assert!(
            (removed - std::f64::consts::PI * 25.0).abs() < 0.2,
            "{removed}"
        );
        assert_eq!(r.count_disc(Point::ORIGIN, 4.9), 0);
        assert!(r.count_disc(Point::new(7.0, 0.0), 1.0) > 0);
    }

    /// A raster over `bounds` with every cell holding material.
    fn solid(bounds: Aabb, cell: f64) -> Raster {
        let mut r = Raster::new(bounds, cell);
        let (nx, ny) = r.dims();
        for j in 0..ny {
            r.set_span(j, 0, nx - 1, true);
        }
        r
    }

    /// Uniform draws in `[0, 1)` from a linear congruential generator seeded with `seed`.
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A straight move cut in `n` steps, each step's capsule cleared in turn (as the
    /// simulation did), against [`Raster::sweep_steps`]: the same count per step, the same
    /// cells left, on stock with holes in it and random moves; on moves whose ends and
    /// radius sit on the cells' lattice (where a cell centre lies exactly on a circle), a few
    /// cells may fall to the next step by rounding.
    #[test]
    fn one_sweep_counts_each_step_as_the_steps_one_by_one() {
        let bounds = Aabb {
            min: Point::new(-4.0, -3.0),
            max: Point::new(6.0, 5.0),
        };
        let cell = 0.05;
        let mut stock = solid(bounds, cell);
        let mut next = uniform(1_234_567_891);
        for _ in 0..30 {
            let c = Point::new(-4.0 + 10.0 * next(), -3.0 + 8.0 * next());
            stock.clear_disc(c, 0.1 + 0.8 * next());
        }
        let (mut moves, mut cells_cut, mut lattice_moved) = (0, 0u64, 0u64);
        for case in 0..400 {
            let lattice = case % 2 == 0;
            let snap = |v: f64| {
                if lattice {
                    (v / cell).round() * cell
                } else {
                    v
                }
            };
            let a = Point::new(snap(-5.0 + 12.0 * next()), snap(-4.0 + 10.0 * next()));
            let b = if case % 7 == 0 {
                a
            } else {
                Point::new(
                    snap(a.x + 4.0 * (next() - 0.5)),
                    snap(a.y + 4.0 * (next() - 0.5)),
                )
            };
            let r = if lattice {
                (1.0 + (30.0 * next()).floor()) * cell
            } else {
                0.1 + 1.5 * next()
            };
            let n = 1 + (40.0 * next()) as usize;
            let (mut steps, mut swept) = (stock.clone(), stock.clone());
            let by_step: Vec<u64> = (0..n)
                .map(|k| {
                    let p = a.lerp(b, k as f64 / n as f64);
                    let q = a.lerp(b, (k + 1) as f64 / n as f64);
                    steps.clear_capsule_from(p, q, r, false)
                })
                .collect();
            let mut counts = vec![0; n];
            swept.sweep_steps(a, b, r, &mut counts);
            let left: u64 = steps
                .bits
                .iter()
                .zip(&swept.bits)
                .map(|(x, y)| u64::from((x ^ y).count_ones()))
                .sum();
            if lattice {
                // A cell centre exactly on a step's circle or the capsule's side may fall
                // either way by rounding (a lattice circle passes through several centres at
                // once): a few cells, never more.
                let (mut sa, mut sb, mut worst) = (0i64, 0i64, 0i64);
                for (x, y) in counts.iter().zip(&by_step) {
                    (sa, sb) = (sa + *x as i64, sb + *y as i64);
                    worst = worst.max((sa - sb).abs());
                }
                lattice_moved += worst as u64 + left;
                assert!(
                    worst <= 8 && left <= 2,
                    "case {case}: {counts:?} {by_step:?} {left}"
                );
            } else {
                assert_eq!(
                    counts, by_step,
                    "case {case}: {a:?} → {b:?}, r {r}, {n} steps"
                );
                assert_eq!(left, 0, "case {case}: the cells left differ");
            }
            cells_cut += counts.iter().sum::<u64>();
            moves += 1;
        }
        assert!(moves == 400 && cells_cut > 100_000, "{moves} {cells_cut}");
        assert!(lattice_moved < 400, "{lattice_moved}");
    }

    /// Steps along random chains, each from where the last one ended: the crescent
    /// ([`Raster::clear_capsule_from`] told that the start's disc is clear) clears the same
    /// cells and counts the same as the whole capsule, step by step; a radius growing
    /// between steps (the arcs' widened capsules) and chains crossing the raster's edges
    /// included.
    #[test]
    fn crescent_steps_clear_what_whole_capsules_clear() {
        let bounds = Aabb {
            min: Point::new(-4.0, -3.0),
            max: Point::new(6.0, 5.0),
        };
        let full = solid(bounds, 0.05);
        let mut next = uniform(987_654_321);
        let mut steps = 0;
        let mut skipped_rows_cut = 0u64;
        for chain in 0..40 {
            let (mut whole, mut crescent) = (full.clone(), full.clone());
            let mut p = Point::new(-5.0 + 12.0 * next(), -4.0 + 10.0 * next());
            let mut r = 0.2 + 1.5 * next();
            whole.clear_disc(p, r);
            crescent.clear_disc(p, r);
            let mut heading = TAU * next();
            let mut last_r = r;
            for _ in 0..60 {
                heading += 0.6 * (next() - 0.5);
                let len = if chain % 5 == 0 {
                    0.0
                } else {
                    0.01 + 0.3 * next()
                };
                let q = p + crate::geom::Vec2::new(heading.cos(), heading.sin()) * len;
                if next() < 0.1 {
                    r += 0.02 * next();
                }
                let a = whole.clear_capsule(p, q, r);
                let b = crescent.clear_capsule_from(p, q, r, last_r >= r);
                assert_eq!(a, b, "chain {chain}: {p:?} → {q:?}, r {r}");
                skipped_rows_cut += a;
                steps += 1;
                (p, last_r) = (q, r);
            }
            assert_eq!(whole.bits, crescent.bits, "chain {chain}");
        }
        assert!(
            steps >= 2000 && skipped_rows_cut > 0,
            "{steps} {skipped_rows_cut}"
        );
    }

    /// The capsule's cells against the distance from each cell centre to the segment,
    /// computed directly (projection clamped to the segment): every direction, degenerate
    /// (a point) and axis-parallel segments, centres near the raster's edges.
    #[test]
    fn capsule_clears_exactly_the_cells_within_r_of_the_segment() {
        let bounds = Aabb {
            min: Point::new(-3.0, -2.0),
            max: Point::new(5.0, 4.0),
        };
        let all = |ras: &Raster| -> Vec<Point> { ras.material_cells().collect() };
        let mut full = Raster::new(bounds, 0.07);
        let (nx, ny) = full.dims();
        for j in 0..ny {
            full.set_span(j, 0, nx - 1, true);
        }
        let mut seed = 12345u64;
        let mut next = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut segments = vec![
            (Point::new(0.0, 0.0), Point::new(0.0, 0.0), 0.5),
            (Point::new(-1.0, 1.0), Point::new(3.0, 1.0), 0.7),
            (Point::new(1.0, -1.0), Point::new(1.0, 3.0), 0.3),
            (Point::new(-3.5, -2.5), Point::new(5.5, 4.5), 0.4),
        ];
        for _ in 0..60 {
            let a = Point::new(-4.0 + 10.0 * next(), -3.0 + 8.0 * next());
            let b = a + crate::geom::Vec2::new(4.0 * next() - 2.0, 4.0 * next() - 2.0);
            segments.push((a, b, 0.05 + 1.5 * next()));
        }
        for (a, b, r) in segments {
            let mut ras = full.clone();
            let removed = ras.clear_capsule(a, b, r);
            let left = all(&ras);
            let dist = |p: Point| {
                let d = b - a;
                let l2 = d.length_squared();
                let t = if l2 > 0.0 {
                    ((p - a).dot(d) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                p.distance(a + d * t)
            };
            let expected = all(&full).into_iter().filter(|&p| dist(p) <= r).count();
            assert_eq!(removed as usize, expected, "{a:?} {b:?} {r}");
            // No cell within r left, none beyond r cleared (a margin for rounding).
            assert!(left.iter().all(|&p| dist(p) > r - 1e-9), "{a:?} {b:?} {r}");
            assert_eq!(left.len() + expected, full.count() as usize);
        }
    }
}
