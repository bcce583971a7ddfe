//! The adaptive planner's own picture of the stock: which cells still hold material, and how
//! far each cell lies from the walls.
//!
//! A square grid of side `h` covers the pocket. A cell stands for its centre. `material` is
//! one bit per cell (rows of 64-bit words): set while the cell's centre lies inside the
//! pocket (inside the outer loop, outside every island) and no tool disc has covered it.
//! `wall` is the Euclidean distance from each cell's centre to the nearest centre of a cell
//! outside the pocket (the exact distance transform of the grid, Felzenszwalb and
//! Huttenlocher's lower envelope of parabolas, columns then rows): within `h` of the
//! distance from the centre to the pocket's walls.
//!
//! The tool at `q` covers the cells whose centres lie within `r` of `q`; a disc's cells are
//! found row by row (the chord of the circle at the row's height), so counting or clearing
//! them costs one word operation per row and 64 cells.

use crate::geom::{Point, Vec2};

/// Points on a tool's front half its contact arc is read at ([`Field::contact_arc`]).
pub(crate) const ARC_SAMPLES: usize = 48;
use crate::strategy::pocket::segments::{Seg, segs_from_vertices};
use crate::strategy::pocket::shape::{PocketShape, closed_chain};

/// The grid: material bits and the distance to the walls.
#[derive(Debug, Clone)]
pub(crate) struct Field {
    /// Centre of cell (0, 0) minus half a cell: the grid's lower-left corner.
    x0: f64,
    y0: f64,
    /// Cell side, mm.
    pub h: f64,
    nx: usize,
    ny: usize,
    /// 64-bit words per row.
    words: usize,
    material: Vec<u64>,
    wall: Vec<f32>,
    /// The distance to the nearest cell a wall thinner than a cell runs through (a slit, a
    /// needle of an island: no cell centre lies outside the pocket there, and `wall` does
    /// not see it), mm; empty where the pocket has none.
    thin: Vec<f32>,
    /// While a pass is tried: the words [`Field::clear_disc`] changed, with the bits it
    /// cleared, so that [`Field::undo`] puts them back.
    log: Option<Vec<(usize, u64)>>,
    /// The cells whose material changed since [`Field::take_changed`] last looked, as a box
    /// `[i0, i1, j0, j1]`.
    changed: Option<[usize; 4]>,
}

impl Field {
    /// The field of `shape` at cell `h`, the grid reaching `pad` beyond the outer loop.
    pub(crate) fn new(shape: &PocketShape, h: f64, pad: f64) -> Field {
        let b = shape.outer.bounds();
        let x0 = b.min.x - pad;
        let y0 = b.min.y - pad;
        let nx = (((b.max.x + pad - x0) / h).ceil() as usize).max(1);
        let ny = (((b.max.y + pad - y0) / h).ceil() as usize).max(1);
        let words = nx.div_ceil(64);
        let mut f = Field {
            x0,
            y0,
            h,
            nx,
            ny,
            words,
            material: vec![0; words * ny],
            wall: Vec::new(),
            thin: Vec::new(),
            log: None,
            changed: None,
        };
        f.fill(shape);
        f.wall = f.distance_to_outside();
        f.thin = f.distance_to_thin_walls(shape);
        f
    }

    /// [`Field::thin`]: the cells the loops (flattened to `h/8`, each piece read every `h/2`)
    /// run through that lie farther
    /// than `1.5·h` from every cell outside the pocket (a wall's own cells lie within `√2·h`
    /// of one), and the distance from each cell to the nearest of them; empty where there
    /// are none.
    fn distance_to_thin_walls(&self, shape: &PocketShape) -> Vec<f32> {
        let mut seeds = Vec::new();
        for outline in shape.loops() {
            let pts = flatten_loop(&segs_from_vertices(&closed_chain(outline.polyline())), {
                self.h / 8.0
            });
            for w in pts.windows(2) {
                let n = (w[0].distance(w[1]) / (0.5 * self.h))
                    .ceil()
                    .clamp(1.0, 1e7) as usize;
                for t in 0..=n {
                    let Some((i, j)) = self.cell_of(w[0].lerp(w[1], t as f64 / n as f64)) else {
                        continue;
                    };
                    let k = j * self.nx + i;
                    if f64::from(self.wall[k]) > 1.5 * self.h {
                        seeds.push(k);
                    }
                }
            }
        }
        if seeds.is_empty() {
            return Vec::new();
        }
        let big = ((self.nx + self.ny) as f64).powi(2);
        let mut d2 = vec![big; self.nx * self.ny];
        for k in seeds {
            d2[k] = 0.0;
        }
        edt_2d(&mut d2, self.nx, self.ny);
        d2.iter().map(|&v| (v.sqrt() * self.h) as f32).collect()
    }

    /// Sets the cells whose centres lie inside the pocket: each row's crossings with the
    /// loops (flattened to `h/8`), filled between odd and even crossings.
    fn fill(&mut self, shape: &PocketShape) {
        let mut crossings: Vec<Vec<f64>> = vec![Vec::new(); self.ny];
        for outline in shape.loops() {
            let pts = flatten_loop(&segs_from_vertices(&closed_chain(outline.polyline())), {
                self.h / 8.0
            });
            for w in pts.windows(2) {
                let (a, b) = (w[0], w[1]);
                let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
                // Rows whose centre height lies in [lo.y, hi.y): each crossing counted once.
                let j0 = ((lo.y - self.y0) / self.h - 0.5).ceil().max(0.0) as usize;
                let mut j = j0;
                while j < self.ny {
                    let y = self.y0 + (j as f64 + 0.5) * self.h;
                    if y >= hi.y {
                        break;
                    }
                    let t = (y - lo.y) / (hi.y - lo.y);
                    crossings[j].push(lo.x + t * (hi.x - lo.x));
                    j += 1;
                }
            }
        }
        for (j, xs) in crossings.iter_mut().enumerate() {
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                let i0 = ((pair[0] - self.x0) / self.h - 0.5).ceil().max(0.0);
                let i1 = ((pair[1] - self.x0) / self.h - 0.5).floor();
                if i1 >= i0 {
                    let i1 = (i1 as usize).min(self.nx - 1);
                    self.set_span(j, i0 as usize, i1, true);
                }
            }
        }
    }

    /// The distance from every cell's centre to the nearest cell outside the pocket, mm.
    fn distance_to_outside(&self) -> Vec<f32> {
        let big = ((self.nx + self.ny) as f64).powi(2);
        let mut d2: Vec<f64> = (0..self.nx * self.ny)
            .map(|k| {
                if self.get(k % self.nx, k / self.nx) {
                    big
                } else {
                    0.0
                }
            })
            .collect();
        edt_2d(&mut d2, self.nx, self.ny);
        d2.iter().map(|&v| (v.sqrt() * self.h) as f32).collect()
    }

    fn get(&self, i: usize, j: usize) -> bool {
        self.material[j * self.words + i / 64] >> (i % 64) & 1 == 1
    }

    /// Sets or clears the cells `i0..=i1` of row `j`.
    fn set_span(&mut self, j: usize, i0: usize, i1: usize, on: bool) {
        let row = &mut self.material[j * self.words..(j + 1) * self.words];
        for (w, m) in span_masks(i0, i1) {
            if on {
                row[w] |= m;
            } else {
                row[w] &= !m;
            }
        }
    }

    /// The cells a disc about `q` of radius `r` covers, row by row: `(j, i0, i1)`, the cells
    /// `i0..=i1` of row `j` (worked in cell units: one square root per row).
    fn disc_spans(&self, q: Point, r: f64) -> impl Iterator<Item = (usize, usize, usize)> + use<> {
        let (cx, cy, rc, lo, hi) = self.disc_in_cells(q, r);
        let last = self.nx as i64 - 1;
        (lo..hi).filter_map(move |j| {
            let dy = j as f64 - cy;
            let half2 = rc * rc - dy * dy;
            if half2 < 0.0 {
                return None;
            }
            let half = half2.sqrt();
            let i0 = ceil_i(cx - half).max(0);
            let i1 = floor_i(cx + half).min(last);
            (i0 <= i1).then_some((j, i0 as usize, i1 as usize))
        })
    }

    /// [`Field::disc_spans`], each passed to `span` until it returns false, the rows'
    /// half-widths and end columns found 64 rows at a time (loops the compiler vectorises:
    /// the same arithmetic, the same spans).
    fn each_disc_span(&self, q: Point, r: f64, mut span: impl FnMut(usize, usize, usize) -> bool) {
        const CHUNK: usize = 64;
        let (cx, cy, rc, lo, hi) = self.disc_in_cells(q, r);
        let last = self.nx as i64 - 1;
        let (mut half2, mut first, mut end) = ([0.0; CHUNK], [0.0; CHUNK], [0.0; CHUNK]);
        let mut j0 = lo;
        while j0 < hi {
            let n = (hi - j0).min(CHUNK);
            for (k, v) in half2[..n].iter_mut().enumerate() {
                let dy = (j0 + k) as f64 - cy;
                *v = rc * rc - dy * dy;
            }
            for k in 0..n {
                let half = half2[k].max(0.0).sqrt();
                first[k] = (cx - half).ceil();
                end[k] = (cx + half).floor();
            }
            for k in 0..n {
                if half2[k] < 0.0 {
                    continue;
                }
                let i0 = (first[k] as i64).max(0);
                let i1 = (end[k] as i64).min(last);
                if i0 <= i1 && !span(j0 + k, i0 as usize, i1 as usize) {
                    return;
                }
            }
            j0 += n;
        }
    }

    /// A disc about `q` of radius `r` in cell units (the centre `cx, cy` measured from cell
    /// `(0, 0)`'s centre, the radius `rc`) and the rows `lo..hi` it covers.
    fn disc_in_cells(&self, q: Point, r: f64) -> (f64, f64, f64, usize, usize) {
        let inv = 1.0 / self.h;
        let cx = (q.x - self.x0) * inv - 0.5;
        let cy = (q.y - self.y0) * inv - 0.5;
        let rc = r * inv;
        let (lo, hi) = self.rows(cy - rc, cy + rc);
        (cx, cy, rc, lo, hi)
    }

    /// The rows whose centres lie in `[y0, y1]` (cell units), clipped to the grid.
    fn rows(&self, y0: f64, y1: f64) -> (usize, usize) {
        let lo = ceil_i(y0).max(0) as usize;
        let hi = (floor_i(y1) + 1).clamp(0, self.ny as i64) as usize;
        (lo, hi.max(lo))
    }

    /// Whether the cells within `r` of `q` hold more than `k` material cells: the count of
    /// [`Field::count_disc`] compared with `k`, stopping once it is decided. The square
    /// around the disc is looked at first, a word at a time: where it holds no material,
    /// neither does the disc.
    pub(crate) fn disc_holds_more_than(&self, q: Point, r: f64, k: u32) -> bool {
        let (cx, _, rc, lo, hi) = self.disc_in_cells(q, r);
        let i0 = ceil_i(cx - rc).max(0);
        let i1 = floor_i(cx + rc).min(self.nx as i64 - 1);
        if i0 > i1 || lo == hi {
            return false;
        }
        let (i0, i1) = (i0 as usize, i1 as usize);
        let any = (lo..hi).any(|j| {
            let base = j * self.words;
            span_masks(i0, i1).any(|(w, m)| self.material[base + w] & m != 0)
        });
        if !any {
            return false;
        }
        let mut n = 0;
        self.each_disc_span(q, r, |j, i0, i1| {
            let base = j * self.words;
            for (w, m) in span_masks(i0, i1) {
                n += (self.material[base + w] & m).count_ones();
            }
            n <= k
        });
        n > k
    }

    /// Whether the cell that holds `q` holds material (`false` off the grid).
    pub(crate) fn material_at(&self, q: Point) -> bool {
        self.cell_of(q)
            .is_some_and(|(i, j)| self.material[j * self.words + i / 64] >> (i % 64) & 1 == 1)
    }

    /// The arc of the front half (heading `u`) of the tool of radius `r` at `q` that touches
    /// material: from the first to the last of [`ARC_SAMPLES`] points half a cell inside the
    /// tool's circle that lie in a material cell, rad (0 where none does).
    pub(crate) fn contact_arc(&self, q: Point, u: Vec2, r: f64) -> f64 {
        let rr = r - 0.5 * self.h;
        let table = arc_table();
        let hit = |k: usize| {
            let (cs, sn) = table[k];
            self.material_at(q + Vec2::new(u.x * cs - u.y * sn, u.x * sn + u.y * cs) * rr)
        };
        let Some(first) = (0..=ARC_SAMPLES).find(|&k| hit(k)) else {
            return 0.0;
        };
        let last = (first..=ARC_SAMPLES)
            .rev()
            .find(|&k| hit(k))
            .unwrap_or(first);
        std::f64::consts::PI * (last - first) as f64 / ARC_SAMPLES as f64
    }

    /// The material cells within `r` of `q`.
    pub(crate) fn count_disc(&self, q: Point, r: f64) -> u32 {
        let mut n = 0;
        self.each_disc_span(q, r, |j, i0, i1| {
            let row = &self.material[j * self.words..(j + 1) * self.words];
            let (w0, w1) = (i0 / 64, i1 / 64);
            let first = u64::MAX << (i0 % 64);
            let last = u64::MAX >> (63 - i1 % 64);
            if w0 == w1 {
                n += (row[w0] & first & last).count_ones();
            } else {
                n += (row[w0] & first).count_ones() + (row[w1] & last).count_ones();
                for &word in &row[w0 + 1..w1] {
                    n += word.count_ones();
                }
            }
            true
        });
        n
    }

    /// Clears the cells within `r` of `q`; returns how many held material.
    pub(crate) fn clear_disc(&mut self, q: Point, r: f64) -> u32 {
        let mut n = 0;
        for (j, i0, i1) in self.disc_spans(q, r) {
            n += self.clear_span(j, i0, i1);
        }
        n
    }

    /// Clears the cells `i0..=i1` of row `j` (logged while recording); how many held
    /// material.
    fn clear_span(&mut self, j: usize, i0: usize, i1: usize) -> u32 {
        let mut n = 0;
        let base = j * self.words;
        let (w0, w1) = (i0 / 64, i1 / 64);
        for w in w0..=w1 {
            let mut m = u64::MAX;
            if w == w0 {
                m &= u64::MAX << (i0 % 64);
            }
            if w == w1 {
                m &= u64::MAX >> (63 - i1 % 64);
            }
            let bits = self.material[base + w] & m;
            if bits != 0 {
                self.mark_changed(j, w, bits);
                n += bits.count_ones();
                self.material[base + w] &= !m;
                if let Some(log) = &mut self.log {
                    log.push((base + w, bits));
                }
            }
        }
        n
    }

    /// Clears the cells within `r` of the segment from `a` to `b` (the band a tool of radius
    /// `r` sweeps along it); returns how many held material. Row by row, the band's slice is
    /// one interval (the band is convex): the union of the end discs' slices and the slice
    /// of the rectangle between them.
    pub(crate) fn clear_capsule(&mut self, a: Point, b: Point, r: f64) -> u32 {
        let inv = 1.0 / self.h;
        let (ax, ay) = ((a.x - self.x0) * inv - 0.5, (a.y - self.y0) * inv - 0.5);
        let (bx, by) = ((b.x - self.x0) * inv - 0.5, (b.y - self.y0) * inv - 0.5);
        let rc = r * inv;
        let (dx, dy) = (bx - ax, by - ay);
        let len = dx.hypot(dy);
        if len < 1e-9 {
            return self.clear_disc(a, r);
        }
        let (ux, uy) = (dx / len, dy / len);
        let (nx_, ny_) = (-uy, ux);
        // The x-interval where `lo ≤ (x − ax)·cx + (y − ay)·cy ≤ hi` on row `y`.
        let band = |y: f64, cx: f64, cy: f64, lo: f64, hi: f64| -> Option<(f64, f64)> {
            let rest = (y - ay) * cy;
            if cx.abs() < 1e-12 {
                return (rest >= lo && rest <= hi).then_some((f64::NEG_INFINITY, f64::INFINITY));
            }
            let (x1, x2) = (ax + (lo - rest) / cx, ax + (hi - rest) / cx);
            Some((x1.min(x2), x1.max(x2)))
        };
        let disc = |y: f64, px: f64, py: f64| -> Option<(f64, f64)> {
            let h2 = rc * rc - (y - py) * (y - py);
            (h2 >= 0.0).then(|| {
                let w = h2.sqrt();
                (px - w, px + w)
            })
        };
        let lo_row = ceil(ay.min(by) - rc).max(0.0) as usize;
        let hi_row = floor(ay.max(by) + rc);
        if hi_row < 0.0 {
            return 0;
        }
        let hi_row = (hi_row as usize + 1).min(self.ny);
        let last = self.nx - 1;
        let mut n = 0;
        for j in lo_row..hi_row.max(lo_row) {
            let y = j as f64;
            let rect = match (band(y, ux, uy, 0.0, len), band(y, nx_, ny_, -rc, rc)) {
                (Some((a0, a1)), Some((b0, b1))) if a0.max(b0) <= a1.min(b1) => {
                    Some((a0.max(b0), a1.min(b1)))
                }
                _ => None,
            };
            let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
            for part in [disc(y, ax, ay), disc(y, bx, by), rect]
                .into_iter()
                .flatten()
            {
                x0 = x0.min(part.0);
                x1 = x1.max(part.1);
            }
            if x1 < x0 {
                continue;
            }
            let i0 = ceil(x0).max(0.0);
            let i1 = floor(x1);
            if i1 < i0 || i1 < 0.0 {
                continue;
            }
            let (i0, i1) = (i0 as usize, (i1 as usize).min(last));
            if i0 > i1 {
                continue;
            }
            n += self.clear_span(j, i0, i1);
        }
        n
    }

    /// Starts recording what [`Field::clear_disc`] clears.
    pub(crate) fn record(&mut self) {
        self.log = Some(Vec::new());
    }

    /// Puts back every cell cleared since [`Field::record`], and stops recording.
    pub(crate) fn undo(&mut self) {
        for (k, bits) in self.log.take().unwrap_or_default() {
            self.material[k] |= bits;
            self.mark_changed(k / self.words, k % self.words, bits);
        }
    }

    /// Adds the cells `bits` of word `w` of row `j` to the box of changed cells.
    fn mark_changed(&mut self, j: usize, w: usize, bits: u64) {
        let i0 = w * 64 + bits.trailing_zeros() as usize;
        let i1 = w * 64 + 63 - bits.leading_zeros() as usize;
        self.changed = Some(match self.changed {
            Some([a0, a1, b0, b1]) => [a0.min(i0), a1.max(i1), b0.min(j), b1.max(j)],
            None => [i0, i1, j, j],
        });
    }

    /// The box `[i0, i1, j0, j1]` of the cells whose material changed since the last call.
    pub(crate) fn take_changed(&mut self) -> Option<[usize; 4]> {
        self.changed.take()
    }

    /// The distance from `q` to the walls as the grid knows it: the value of the cell that
    /// holds `q` (0 off the grid).
    pub(crate) fn wall_distance(&self, q: Point) -> f64 {
        match self.cell_of(q) {
            Some((i, j)) => f64::from(self.wall[j * self.nx + i]),
            None => 0.0,
        }
    }

    /// [`Field::wall_distance`], or the distance to the nearest wall thinner than a cell
    /// ([`Field::thin`]) where that is less: what a point must clear to be inside for sure.
    pub(crate) fn sure_distance(&self, q: Point) -> f64 {
        match self.cell_of(q) {
            Some((i, j)) => {
                let k = j * self.nx + i;
                let w = f64::from(self.wall[k]);
                self.thin.get(k).map_or(w, |&t| w.min(f64::from(t)))
            }
            None => 0.0,
        }
    }

    fn cell_of(&self, q: Point) -> Option<(usize, usize)> {
        let fx = (q.x - self.x0) / self.h;
        let fy = (q.y - self.y0) / self.h;
        if !(fx >= 0.0 && fy >= 0.0) {
            return None;
        }
        let (i, j) = (fx as usize, fy as usize);
        (i < self.nx && j < self.ny).then_some((i, j))
    }

    /// The centre of cell `(i, j)`.
    pub(crate) fn centre(&self, i: usize, j: usize) -> Point {
        Point::new(
            self.x0 + (i as f64 + 0.5) * self.h,
            self.y0 + (j as f64 + 0.5) * self.h,
        )
    }

    /// Grid size in cells.
    pub(crate) fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The wall distance of cell `(i, j)`.
    pub(crate) fn wall_at(&self, i: usize, j: usize) -> f64 {
        f64::from(self.wall[j * self.nx + i])
    }

    /// A coarse picture of the material: `k × k` blocks of cells, a block set when any of
    /// its cells holds material; with its distance transform in mm (from each block's
    /// centre to the nearest set block's centre).
    pub(crate) fn coarse_distance(&self, k: usize) -> Coarse {
        let (cx, cy) = (self.nx.div_ceil(k), self.ny.div_ceil(k));
        let mut d2 = vec![((cx + cy) as f64).powi(2); cx * cy];
        for j in 0..self.ny {
            let row = &self.material[j * self.words..(j + 1) * self.words];
            for (w, &bits) in row.iter().enumerate() {
                let mut b = bits;
                while b != 0 {
                    let i = w * 64 + b.trailing_zeros() as usize;
                    d2[(j / k) * cx + i / k] = 0.0;
                    // The rest of this block's bits in the word say nothing more.
                    let next = (i / k + 1) * k;
                    b = if next >= (w + 1) * 64 {
                        0
                    } else {
                        b & (u64::MAX << (next - w * 64))
                    };
                }
            }
        }
        edt_2d(&mut d2, cx, cy);
        Coarse {
            nx: cx,
            ny: cy,
            dist: d2.iter().map(|v| v.sqrt() * self.h * k as f64).collect(),
            window: None,
        }
    }

    /// `old`, the coarse map [`Field::coarse_distance`]`(k)` made of this field before the
    /// cells in the box `changed` changed, brought up to date: every distance up to `cap`
    /// (mm) as the whole map has it, the others above `cap`. Only the blocks within `cap`
    /// (plus two blocks) of the box are computed again, from the material within twice that
    /// (no block farther from the box has its nearest material within `cap` in the box, and
    /// the material within `cap` of a block near it lies within the larger window); where
    /// that window is more than half the map, the whole map is made again.
    pub(crate) fn coarse_update(
        &self,
        k: usize,
        old: Coarse,
        changed: [usize; 4],
        cap: f64,
    ) -> Coarse {
        let (cx, cy) = (old.nx, old.ny);
        let m = (cap / (self.h * k as f64)).ceil().max(0.0) as usize + 2;
        let [i0, i1, j0, j1] = changed;
        let grow = |lo: usize, hi: usize, n: usize| (lo.saturating_sub(m), (hi + m).min(n - 1));
        let (ii0, ii1) = grow(i0 / k, i1 / k, cx);
        let (ij0, ij1) = grow(j0 / k, j1 / k, cy);
        let (oi0, oi1) = grow(ii0, ii1, cx);
        let (oj0, oj1) = grow(ij0, ij1, cy);
        let (wx, wy) = (oi1 + 1 - oi0, oj1 + 1 - oj0);
        if 2 * wx * wy > cx * cy || ii0 > ii1 || ij0 > ij1 {
            return self.coarse_distance(k);
        }
        let mut d2 = vec![((cx + cy) as f64).powi(2); wx * wy];
        let (c0, c1) = (oi0 * k, ((oi1 + 1) * k).min(self.nx) - 1);
        for j in oj0 * k..((oj1 + 1) * k).min(self.ny) {
            let row = &self.material[j * self.words..(j + 1) * self.words];
            for (w, &word) in row.iter().enumerate().take(c1 / 64 + 1).skip(c0 / 64) {
                let lo = if w == c0 / 64 { c0 % 64 } else { 0 };
                let hi = if w == c1 / 64 { c1 % 64 } else { 63 };
                let mut b = word & (u64::MAX << lo) & (u64::MAX >> (63 - hi));
                while b != 0 {
                    let i = w * 64 + b.trailing_zeros() as usize;
                    d2[(j / k - oj0) * wx + i / k - oi0] = 0.0;
                    let next = (i / k + 1) * k;
                    b = if next >= (w + 1) * 64 {
                        0
                    } else {
                        b & (u64::MAX << (next - w * 64))
                    };
                }
            }
        }
        edt_2d(&mut d2, wx, wy);
        let mut new = old;
        new.window = Some([ii0, ii1, ij0, ij1]);
        for bj in ij0..=ij1 {
            for bi in ii0..=ii1 {
                let v = d2[(bj - oj0) * wx + bi - oi0];
                new.dist[bj * cx + bi] = v.sqrt() * self.h * k as f64;
            }
        }
        new
    }

    /// The centre of coarse block `(i, j)` of [`Field::coarse_distance`]`(k)`.
    pub(crate) fn coarse_centre(&self, k: usize, i: usize, j: usize) -> Point {
        Point::new(
            self.x0 + (i as f64 + 0.5) * self.h * k as f64,
            self.y0 + (j as f64 + 0.5) * self.h * k as f64,
        )
    }

    /// Material cells left in the whole field.
    pub(crate) fn material_cells(&self) -> u64 {
        self.material
            .iter()
            .map(|w| u64::from(w.count_ones()))
            .sum()
    }
}

/// A coarse distance-to-material map (see [`Field::coarse_distance`]).
#[derive(Debug, Clone)]
pub(crate) struct Coarse {
    pub nx: usize,
    pub ny: usize,
    /// Distance from each block's centre to the nearest block holding material, mm.
    pub dist: Vec<f64>,
    /// The blocks whose distance [`Field::coarse_update`] recomputed (first and last column,
    /// first and last row); `None` where the whole map was made.
    pub window: Option<[usize; 4]>,
}

/// `x.floor()` without the library call (`f64::floor` is one on x86-64 without SSE 4.1, a
/// fifth of the planner's time): the same value for every `x`.
fn floor(x: f64) -> f64 {
    if x.abs() < 4.0e15 {
        let t = x as i64 as f64;
        if t > x { t - 1.0 } else { t }
    } else {
        x.floor()
    }
}

/// `x.ceil()` without the library call (see [`floor`]).
fn ceil(x: f64) -> f64 {
    if x.abs() < 4.0e15 {
        let t = x as i64 as f64;
        if t < x { t + 1.0 } else { t }
    } else {
        x.ceil()
    }
}

/// `⌊x⌋` as an integer: exact where it fits in an `i64` (cell indices do), saturated beyond,
/// 0 for NaN.
fn floor_i(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) > x { t - 1 } else { t }
}

/// `⌈x⌉` as an integer (see [`floor_i`]).
fn ceil_i(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) < x { t + 1 } else { t }
}

/// The (word, mask) pairs covering bits `i0..=i1`.
fn span_masks(i0: usize, i1: usize) -> impl Iterator<Item = (usize, u64)> {
    let (w0, w1) = (i0 / 64, i1 / 64);
    (w0..=w1).map(move |w| {
        let lo = if w == w0 { i0 % 64 } else { 0 };
        let hi = if w == w1 { i1 % 64 } else { 63 };
        let m = if hi - lo == 63 {
            u64::MAX
        } else {
            ((1u64 << (hi - lo + 1)) - 1) << lo
        };
        (w, m)
    })
}

/// Points along the loop of `segs`, arcs flattened within `tol`.
fn flatten_loop(segs: &[Seg], tol: f64) -> Vec<Point> {
    let mut pts = Vec::new();
    for s in segs {
        if pts.is_empty() {
            pts.push(s.a);
        }
        let n = match s.arc {
            Some(a) if a.radius > tol => {
                let step = 2.0 * (1.0 - tol / a.radius).clamp(-1.0, 1.0).acos();
                ((a.sweep / step.max(1e-6)).ceil() as usize).clamp(1, 100_000)
            }
            _ => 1,
        };
        for k in 1..=n {
            pts.push(if k == n {
                s.b
            } else {
                s.point_at(s.length() * k as f64 / n as f64)
            });
        }
    }
    pts
}

/// The exact squared Euclidean distance transform of a grid (in cells²): `d2` holds 0 at the
/// sources and a large value elsewhere, and is replaced by the squared distance to the
/// nearest source (Felzenszwalb and Huttenlocher, columns then rows).
fn edt_2d(d2: &mut [f64], nx: usize, ny: usize) {
    let n = nx.max(ny);
    let mut buf = vec![0.0; n];
    let mut out = vec![0.0; n];
    let mut v = vec![0usize; n];
    let mut z = vec![0.0; n + 1];
    // A line whose values are all equal is its own transform: `min_p (q − p)² + c = c`.
    let flat = |b: &[f64]| b.iter().all(|&x| x.to_bits() == b[0].to_bits());
    for i in 0..nx {
        for j in 0..ny {
            buf[j] = d2[j * nx + i];
        }
        if flat(&buf[..ny]) {
            continue;
        }
        edt_1d(&buf[..ny], &mut out[..ny], &mut v, &mut z);
        for j in 0..ny {
            d2[j * nx + i] = out[j];
        }
    }
    for j in 0..ny {
        buf[..nx].copy_from_slice(&d2[j * nx..(j + 1) * nx]);
        if flat(&buf[..nx]) {
            continue;
        }
        edt_1d(&buf[..nx], &mut out[..nx], &mut v, &mut z);
        d2[j * nx..(j + 1) * nx].copy_from_slice(&out[..nx]);
    }
}

/// One dimension of [`edt_2d`]: `out[q] = min_p (q − p)² + f[p]`.
fn edt_1d(f: &[f64], out: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    if n == 0 {
        return;
    }
    let mut k = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in 1..n {
        loop {
            let p = v[k];
            let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q - p) as f64);
            // z[0] = −∞: a finite `s` never passes below the first parabola's start.
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
            break;
        }
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let d = q as f64 - p as f64;
        *o = d * d + f[p];
    }
}

/// The cosines and sines of [`Field::contact_arc`]'s sample angles, from −90° to 90°.
fn arc_table() -> &'static [(f64, f64); ARC_SAMPLES + 1] {
    static TABLE: std::sync::OnceLock<[(f64, f64); ARC_SAMPLES + 1]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|k| {
            let a =
                -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / ARC_SAMPLES as f64;
            (a.cos(), a.sin())
        })
    })
}

#[cfg(test)]
mod tests;
