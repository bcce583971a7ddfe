//! Where the tool can reach, on the verifier's grid, without offsetting a curve.
//!
//! The coverage check needs the region the tool centre may visit, `R = {x in the pocket :
//! dist(x, walls) ≥ d}` (`d = r + wall stock`), and, for each material cell left, whether its
//! centre lies within `r − 2c` of `R` (`c` the cell side). The strategies build their loops
//! from cavalier_contours' shape offset; were `R` built the same way, an offset that drops a
//! loop would hide the material it leaves from the very check meant to catch it. So `R` is
//! computed here from distances alone, on the raster of the slab:
//!
//! 1. **Distance to the walls** at every cell centre: a Euclidean distance transform
//!    (Felzenszwalb & Huttenlocher's lower envelope of parabolas, two 1-D passes, exact on
//!    the grid) from the seed cells: every cell outside the pocket and every cell holding a
//!    point of the walls sampled every `c/2`. A seed cell's centre lies within `c/√2` of the
//!    walls, and every wall point within `c/4` of a sample, so the transform `D̃` is within
//!    `c` of the exact distance `D` wherever the pocket is a cell wide.
//! 2. **Reach cells**: the cells inside the pocket with `D ≥ d` at their centre: those with
//!    `D̃ ≥ d + c` outright, those with `|D̃ − d| < c` (a band along `R`'s edge, a few cells
//!    wide) after the exact distance to the walls ([`super::nearest::IndexedWall`]).
//! 3. **Reachable material**: a second transform from the reach cells gives every cell's
//!    distance to the nearest reach cell centre; a material cell is reachable when that is at
//!    most `r − 2c`.
//!
//! Reach cells lie in `R`, so a cell flagged here is within `r − 2c` of `R` (no false
//! alarm); a part of `R` thinner than a cell may hold no cell centre and go unseen, and the
//! material within a cell of `R`'s edge counts from the cell centres inside it.
//!
//! **Whether the tool fits at all** ([`ReachMap::fits`]): yes with a reach cell; without one,
//! every cell whose transform allows a point at `d` (`D̃ + 2c ≥ d`) is searched by branch and
//! bound on the exact distance (1-Lipschitz: a square of half-side `h` about `p` holds no
//! point farther than `D(p) + h·√2`), down to squares of `c/2^20`. A pocket then counts as out
//! of the tool's reach only where the exact distance rules it out, not within a cell of it.
//!
//! Cost: two transforms over the raster, `O(cells)` each (`f32` distances: 4 bytes a cell),
//! and an exact distance query per cell of the band.

use super::nearest::IndexedWall;
use super::raster::Raster;
use crate::geom::Point;
use cavalier_contours::polyline::{PlineSource, Polyline};

/// Distance from every cell of a raster to the nearest cell whose centre the tool centre may
/// reach.
#[derive(Debug, Clone)]
pub struct ReachMap {
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Squared distance to the nearest reach cell, in cells².
    d2: Vec<f32>,
    /// Whether a tool centre fits somewhere ([`ReachMap::fits`]).
    fits: bool,
}

/// Deepest subdivision of [`fits_near`]: squares of `c / 2^20`.
const MAX_DEPTH: u32 = 20;

/// True when the square of centre `p` and half-side `h` holds a point of the pocket at least
/// `d` from the walls, by branch and bound on the exact distance `exact` (1-Lipschitz: no
/// point of the square is farther than `exact(p) + h·√2`): found at `p`, ruled out by the
/// bound (or, outside the pocket, by the disc of radius `exact(p)` about `p` holding no wall),
/// else the four quarters. A square still undecided after [`MAX_DEPTH`] halvings counts as
/// fitting (within `c / 2^20` of it).
fn fits_near(
    p: Point,
    h: f64,
    d: f64,
    exact: &dyn Fn(Point) -> f64,
    inside: &dyn Fn(Point) -> bool,
    depth: u32,
) -> bool {
    let e = exact(p);
    let reach = h * std::f64::consts::SQRT_2;
    if e + reach < d {
        return false;
    }
    let within = inside(p);
    if within && e >= d {
        return true;
    }
    if !within && reach <= e {
        return false;
    }
    if depth >= MAX_DEPTH {
        return true;
    }
    let q = 0.5 * h;
    [(-q, -q), (q, -q), (-q, q), (q, q)]
        .iter()
        .any(|&(dx, dy)| {
            fits_near(
                Point::new(p.x + dx, p.y + dy),
                q,
                d,
                exact,
                inside,
                depth + 1,
            )
        })
}

impl ReachMap {
    /// The reach map of the pocket whose material `pristine` holds (every cell inside the
    /// pocket set) and whose walls are `walls`, for tool-centre distance `d` from them.
    pub fn new(pristine: &Raster, walls: &[&Polyline<f64>], d: f64) -> Self {
        let (nx, ny) = pristine.dims();
        let c = pristine.cell();
        let origin = pristine.centre(0, 0);
        let mut seeds: Vec<bool> = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| !pristine.get(i, j))
            .collect();
        for pl in walls {
            let n = ((pl.path_length() / (0.5 * c)).ceil() as usize).max(8);
            for p in crate::geom::region::sample_loop(pl, n) {
                if let Some((i, j)) = cell_of(origin, c, nx, ny, p) {
                    seeds[j * nx + i] = true;
                }
            }
        }
        let wall_d2 = edt(&seeds, nx, ny);
        let indexed: Vec<IndexedWall<'_>> = walls.iter().map(|p| IndexedWall::new(p)).collect();
        let reach: Vec<bool> = (0..nx * ny)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                if !pristine.get(i, j) {
                    return false;
                }
                let approx = f64::from(wall_d2[k]).sqrt() * c;
                if approx >= d + c {
                    true
                } else if approx > d - c {
                    let p = pristine.centre(i, j);
                    let exact = indexed
                        .iter()
                        .map(|w| w.distance(p))
                        .fold(f64::INFINITY, f64::min);
                    exact >= d
                } else {
                    false
                }
            })
            .collect();
        // The transform is within c of the exact distance at a cell centre, and a point of
        // the pocket lies within c/√2 of one: 2c over the largest value bounds every point.
        let max_wall = (0..nx * ny)
            .filter(|&k| pristine.get(k % nx, k / nx))
            .map(|k| f64::from(wall_d2[k]).sqrt() * c)
            .fold(0.0, f64::max)
            + 2.0 * c;
        // Whether a tool centre fits: a reach cell says so; without one, the cells whose
        // bound allows it are searched with the exact distance (`fits_near`).
        let fits = reach.iter().any(|&b| b)
            || (max_wall >= d && {
                let inside = |p: Point| {
                    walls
                        .iter()
                        .map(|w| {
                            w.winding_number(cavalier_contours::core::math::Vector2::new(p.x, p.y))
                        })
                        .sum::<i32>()
                        != 0
                };
                let exact = |p: Point| {
                    indexed
                        .iter()
                        .map(|w| w.distance(p))
                        .fold(f64::INFINITY, f64::min)
                };
                (0..nx * ny).any(|k| {
                    let (i, j) = (k % nx, k / nx);
                    f64::from(wall_d2[k]).sqrt() * c + 2.0 * c >= d
                        && fits_near(pristine.centre(i, j), 0.5 * c, d, &exact, &inside, 0)
                })
            });
        drop(wall_d2);
        ReachMap {
            origin,
            cell: c,
            nx,
            ny,
            d2: edt(&reach, nx, ny),
            fits,
        }
    }

    /// True when some point of the pocket lies at least `d` from its walls (a tool centre
    /// fits): a reach cell, or a point the exact search finds (`fits_near`). False only when
    /// the exact distance's bound rules out every cell.
    pub fn fits(&self) -> bool {
        self.fits
    }

    /// Distance from `p` (a cell centre of the raster) to the nearest reach cell centre, mm;
    /// infinite off the raster or with no reach cell at all.
    pub fn distance(&self, p: Point) -> f64 {
        match cell_of(self.origin, self.cell, self.nx, self.ny, p) {
            Some((i, j)) => f64::from(self.d2[j * self.nx + i]).sqrt() * self.cell,
            None => f64::INFINITY,
        }
    }
}

/// The cell whose centre is nearest to `p`, if on the grid (`origin`: centre of cell 0, 0).
fn cell_of(origin: Point, c: f64, nx: usize, ny: usize, p: Point) -> Option<(usize, usize)> {
    let i = ((p.x - origin.x) / c).round();
    let j = ((p.y - origin.y) / c).round();
    (i >= 0.0 && j >= 0.0 && (i as usize) < nx && (j as usize) < ny)
        .then_some((i as usize, j as usize))
}

/// Squared Euclidean distance, in cells², from every cell of an `nx × ny` grid to the nearest
/// seed (`f32::INFINITY` without seeds): columns, then rows, exact on the grid. On the seeds
/// alone (0 or far) the columns' lower envelope is the squared distance to the column's
/// nearest seed, found by a scan up and one down, row by row (rows are contiguous in memory);
/// the rows take the lower envelope of parabolas (Felzenszwalb & Huttenlocher 2012), a run of
/// seeds by its two ends (the cells inside it are 0).
pub(crate) fn edt(seeds: &[bool], nx: usize, ny: usize) -> Vec<f32> {
    const FAR: f64 = 1e20;
    let far = FAR as f32;
    // Written once, row by row (no fill first).
    let mut g: Vec<f32> = Vec::with_capacity(nx * ny);
    let mut near: Vec<Option<usize>> = vec![None; nx];
    for j in 0..ny {
        let row = j * nx..(j + 1) * nx;
        g.extend(
            near.iter_mut()
                .zip(&seeds[row])
                .map(|(n, &s)| match (s, *n) {
                    (true, _) => {
                        *n = Some(j);
                        0.0
                    }
                    (false, Some(p)) => {
                        let d = (j - p) as f64;
                        (d * d) as f32
                    }
                    (false, None) => far,
                }),
        );
    }
    near.fill(None);
    for j in (0..ny).rev() {
        let row = j * nx..(j + 1) * nx;
        for ((n, &s), o) in near.iter_mut().zip(&seeds[row.clone()]).zip(&mut g[row]) {
            if s {
                *n = Some(j);
            } else if let Some(p) = *n {
                let d = (p - j) as f64;
                *o = o.min((d * d) as f32);
            }
        }
    }
    let mut f = vec![0.0; nx.max(ny)];
    let mut out = vec![0.0; nx.max(ny)];
    let mut v = vec![0usize; nx.max(ny)];
    let mut z = vec![0.0; nx.max(ny) + 1];
    for j in 0..ny {
        for i in 0..nx {
            f[i] = f64::from(g[j * nx + i]);
        }
        envelope(&f[..nx], &mut out[..nx], &mut v, &mut z);
        for i in 0..nx {
            g[j * nx + i] = if out[i] >= 0.5 * FAR {
                f32::INFINITY
            } else {
                out[i] as f32
            };
        }
    }
    g
}

/// Squared Euclidean distances, in cells², from the cells of a grid to the nearest of a set
/// of seed cells, kept only where they are at most `radius²`: the transform of a band about
/// the seeds. Exact on the grid like [`edt`] (the same two passes, each over the band alone):
/// the columns give each cell within `radius` of a seed of its column the squared distance to
/// the nearest one; each row takes the lower envelope of the parabolas of its entries, and
/// is read at the cells within `radius` of one. A cell within `radius` of its nearest seed
/// `s` is reached: `s`'s column has an entry in the cell's row no larger than the row offset
/// squared, whose interval holds the cell. The cost is in the band's cells, not the grid's.
#[derive(Debug, Clone)]
pub(crate) struct BandDistance {
    /// `d² + 1` per cell of the grid, 0 beyond `radius` (a zeroed allocation: pages away
    /// from the band are never written).
    plus_one: Vec<u32>,
    /// The cells within `radius`, in ascending index (row by row).
    within: Vec<usize>,
}

impl BandDistance {
    /// The transform of `seeds` (cell `(i, j)` of an `nx × ny` grid; duplicates allowed,
    /// cells off the grid ignored) out to `radius` cells.
    pub(crate) fn new(seeds: &[(usize, usize)], nx: usize, ny: usize, radius: f64) -> Self {
        let reach = radius.max(0.0).floor() as usize;
        let r2 = radius.max(0.0).powi(2);
        let mut columns: Vec<Vec<usize>> = vec![Vec::new(); nx];
        for &(i, j) in seeds {
            if i < nx && j < ny {
                columns[i].push(j);
            }
        }
        // The columns: (column, squared row offset) entries of each row, in column order.
        let mut rows: Vec<Vec<(usize, u64)>> = vec![Vec::new(); ny];
        for (i, col) in columns.iter_mut().enumerate() {
            if col.is_empty() {
                continue;
            }
            col.sort_unstable();
            col.dedup();
            let mut at = 0;
            let mut next = 0;
            for &s in col.iter() {
                let lo = s.saturating_sub(reach).max(next);
                let hi = (s + reach).min(ny - 1);
                for (j, row) in rows.iter_mut().enumerate().take(hi + 1).skip(lo) {
                    while at + 1 < col.len() && col[at + 1].abs_diff(j) <= col[at].abs_diff(j) {
                        at += 1;
                    }
                    let d = col[at].abs_diff(j) as u64;
                    row.push((i, d * d));
                }
                next = next.max(hi + 1);
            }
        }
        let mut plus_one = vec![0u32; nx * ny];
        let mut within = Vec::new();
        let (mut v, mut z) = (Vec::new(), Vec::new());
        let mut spans: Vec<(usize, usize)> = Vec::new();
        for (j, row) in rows.iter().enumerate() {
            if row.is_empty() {
                continue;
            }
            // The lower envelope of `(x − a)² + g` over the row's entries.
            let key = |e: &(usize, u64)| e.1 as f64 + (e.0 as f64).powi(2);
            v.clear();
            z.clear();
            v.push(0usize);
            z.push(f64::NEG_INFINITY);
            for q in 1..row.len() {
                let cross = |p: usize| {
                    (key(&row[q]) - key(&row[p])) / (2.0 * (row[q].0 as f64 - row[p].0 as f64))
                };
                let mut s = cross(v[v.len() - 1]);
                while s <= z[z.len() - 1] {
                    v.pop();
                    z.pop();
                    s = cross(v[v.len() - 1]);
                }
                v.push(q);
                z.push(s);
            }
            // The cells within `radius` of an entry, merged into spans.
            spans.clear();
            spans.extend(row.iter().map(|&(a, g)| {
                let w = (r2 - g as f64).max(0.0).sqrt().floor() as usize;
                (a.saturating_sub(w), (a + w).min(nx - 1))
            }));
            spans.sort_unstable();
            let mut k = 0;
            let mut last = None;
            for &(lo, hi) in &spans {
                let lo = match last {
                    Some(l) if l >= hi => continue,
                    Some(l) if l >= lo => l + 1,
                    _ => lo,
                };
                for x in lo..=hi {
                    while k + 1 < v.len() && z[k + 1] < x as f64 {
                        k += 1;
                    }
                    let (a, g) = row[v[k]];
                    let dx = x.abs_diff(a) as u64;
                    let d2 = dx * dx + g;
                    if d2 as f64 <= r2 {
                        let cell = j * nx + x;
                        plus_one[cell] = u32::try_from(d2 + 1).unwrap_or(u32::MAX);
                        within.push(cell);
                    }
                }
                last = Some(hi);
            }
        }
        BandDistance { plus_one, within }
    }

    /// The squared distance of cell `k` (row-major index), cells², or `None` beyond the
    /// radius.
    pub(crate) fn d2(&self, k: usize) -> Option<u32> {
        self.plus_one[k].checked_sub(1)
    }

    /// The cells within the radius, in ascending index.
    pub(crate) fn within(&self) -> &[usize] {
        &self.within
    }
}

/// The 1-D squared distance transform of the sampled function `f`: `out[q] = min_p (q − p)² +
/// f[p]`.
fn envelope(f: &[f64], out: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    if n == 0 {
        return;
    }
    let mut k = 0usize;
    v[0] = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in 1..n {
        // Inside a run of zeros (seeds) a parabola is lower than both ends' only at its own
        // cell, where the value is 0 anyway (set below): it is left out of the envelope.
        if f[q] == 0.0 && f[q - 1] == 0.0 && f.get(q + 1) == Some(&0.0) {
            continue;
        }
        let fq = f[q] + (q * q) as f64;
        let cross = |p: usize| (fq - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64));
        let mut s = cross(v[k]);
        // z[0] = −∞ ends the loop at k = 0.
        while s <= z[k] {
            k -= 1;
            s = cross(v[k]);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    let mut k = 0usize;
    for (q, o) in out.iter_mut().enumerate() {
        if f[q] == 0.0 {
            *o = 0.0;
            continue;
        }
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let dq = q as f64 - p as f64;
        *o = dq * dq + f[p];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` cells, each a seed with chance `1/every` (none for 0), from a linear congruential
    /// generator.
    fn random_seeds(state: &mut u64, n: usize, every: u64) -> Vec<bool> {
        (0..n)
            .map(|_| {
                *state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                every > 0 && (*state >> 33) % every == 0
            })
            .collect()
    }

    /// The transform against brute force on random grids: sparse seeds (columns and rows
    /// without one), dense ones, thin grids and none at all.
    #[test]
    fn edt_matches_brute_force() {
        let mut state = 12345u64;
        for (nx, ny, every) in [
            (23, 17, 29),
            (40, 3, 7),
            (3, 40, 61),
            (31, 29, 2),
            (6, 5, 0),
        ] {
            let seeds = random_seeds(&mut state, nx * ny, every);
            let got = edt(&seeds, nx, ny);
            assert_eq!(got.len(), nx * ny);
            for (k, &g) in got.iter().enumerate() {
                let (i, j) = ((k % nx) as f64, (k / nx) as f64);
                let want = (0..nx * ny)
                    .filter(|&s| seeds[s])
                    .map(|s| {
                        let (a, b) = ((s % nx) as f64, (s / nx) as f64);
                        (a - i).powi(2) + (b - j).powi(2)
                    })
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    (f64::from(g) - want).abs() < 1e-9 || (g.is_infinite() && want.is_infinite()),
                    "{nx} × {ny}, cell {k}: {g} vs {want}"
                );
            }
        }
    }

    /// The transform against brute force where the seeds fill a region (a ring and its
    /// hole's island, a piece's inside): rows crossing long runs of seeds.
    #[test]
    fn edt_matches_brute_force_over_filled_regions() {
        let (nx, ny) = (47, 39);
        let seeds: Vec<bool> = (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 - 20.0, (k / nx) as f64 - 18.0);
                let d = x.hypot(y);
                (9.0..=15.5).contains(&d) || d <= 3.0 || (x > 18.0 && y.abs() < 4.0)
            })
            .collect();
        let got = edt(&seeds, nx, ny);
        let mut zero_runs = 0;
        for (k, &g) in got.iter().enumerate() {
            let (i, j) = ((k % nx) as f64, (k / nx) as f64);
            let want = (0..nx * ny)
                .filter(|&s| seeds[s])
                .map(|s| {
                    let (a, b) = ((s % nx) as f64, (s / nx) as f64);
                    (a - i).powi(2) + (b - j).powi(2)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(
                (f64::from(g) - want).abs() < 1e-9,
                "cell {k}: {g} vs {want}"
            );
            zero_runs += usize::from(
                k % nx > 0 && k % nx + 1 < nx && seeds[k - 1] && seeds[k] && seeds[k + 1],
            );
        }
        assert!(
            zero_runs > nx * ny / 10,
            "{zero_runs} cells inside runs of seeds"
        );
    }

    /// The band transform against the full one on random grids and radii: the same squared
    /// distance at every cell within the radius, nothing beyond it, and the cells listed in
    /// ascending order.
    #[test]
    fn band_distance_matches_the_full_transform_within_its_radius() {
        let mut state = 99u64;
        let mut checked = 0;
        for (nx, ny, every, radius) in [
            (23, 17, 29, 3.5),
            (40, 9, 7, 2.0),
            (9, 40, 61, 6.3),
            (31, 29, 3, 1.0),
            (50, 44, 97, 8.9),
            (6, 5, 0, 4.0),
            (64, 64, 400, 30.0),
        ] {
            let seeds = random_seeds(&mut state, nx * ny, every);
            let list: Vec<(usize, usize)> = (0..nx * ny)
                .filter(|&k| seeds[k])
                .flat_map(|k| [(k % nx, k / nx), (k % nx, k / nx)])
                .collect();
            let full = edt(&seeds, nx, ny);
            let band = BandDistance::new(&list, nx, ny, radius);
            let mut want_within = Vec::new();
            for (k, &g) in full.iter().enumerate() {
                let inside = f64::from(g) <= radius * radius;
                if inside {
                    want_within.push(k);
                    checked += 1;
                }
                let got = band.d2(k);
                match got {
                    Some(d2) => assert!(
                        inside && (f64::from(d2) - f64::from(g)).abs() < 1e-9,
                        "{nx} × {ny} r {radius}, cell {k}: {d2} vs {g}"
                    ),
                    None => assert!(!inside, "{nx} × {ny} r {radius}, cell {k}: none vs {g}"),
                }
            }
            assert_eq!(band.within(), &want_within[..], "{nx} × {ny} r {radius}");
        }
        assert!(checked > 2000, "{checked} cells within a radius");
    }

    /// A 20 × 10 rectangle at d = 2: the reach region is the 16 × 6 rectangle inside; a cell
    /// centre 1 mm outside it is at distance 1, one inside it at 0.
    #[test]
    fn rectangle_reach() {
        let pts = [(0.0, 0.0), (20.0, 0.0), (20.0, 10.0), (0.0, 10.0)];
        let v: Vec<(Point, f64)> = pts.iter().map(|&(x, y)| (Point::new(x, y), 0.0)).collect();
        let o = crate::geom::Outline::new(&v, "rect").expect("outline");
        let mut ras = Raster::new(o.bounds(), 0.05);
        ras.fill(&[o.polyline()]);
        let map = ReachMap::new(&ras, &[o.polyline()], 2.0);
        let near = |x: f64, y: f64| {
            let (i, j) = cell_of(map.origin, map.cell, map.nx, map.ny, Point::new(x, y))
                .expect("on the grid");
            map.distance(ras.centre(i, j))
        };
        assert!(near(10.0, 5.0) < 1e-9);
        assert!((near(1.0, 5.0) - 1.0).abs() < 0.06, "{}", near(1.0, 5.0));
        assert!(
            (near(0.5, 0.5) - 1.5 * 2f64.sqrt()).abs() < 0.08,
            "{}",
            near(0.5, 0.5)
        );
    }
}
