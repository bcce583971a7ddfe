//! The harmonic morph between the central circle and the boundary offset.
//!
//! On the annular region Ω between the circle `|x − c| = R₀` and the boundary offset `B`,
//! solve Laplace's equation
//!
//! ```text
//!   Δu = 0 in Ω,   u = 0 on the circle,   u = 1 on B
//! ```
//!
//! (Bieterman & Sandstrom 2003). By the maximum principle `0 < u < 1` in Ω, and in a doubly
//! connected region the gradient of this capacity potential never vanishes, so every level
//! set `u = t`, `0 < t < 1`, is a single smooth closed curve around the circle. These curves
//! morph the circle into `B` whatever the shape of `B` (convex or not, star-shaped or not),
//! which is exactly where a radial scan from the centre (the paper's method) fails.
//!
//! ## Discretisation
//! A square grid of spacing `h`; nodes outside `B` are fixed at 1, nodes inside the circle at
//! 0, every other node satisfies the five-point stencil `4u_ij = u_{i±1,j} + u_{i,j±1}`
//! (second-order accurate in the interior, first order at the boundary: the level sets are
//! within about `h` of the true ones next to `B`, which is why the last loop is not a level
//! set but `B` itself). The system is solved by red-black successive over-relaxation with
//! `ω = 2 / (1 + sin(πh/L))`, the optimal factor for the model problem on a square of side `L`
//! (or a strip of width `L`), from an initial guess that already interpolates the distances
//! (`u₀ = d_c / (d_c + d_B)`), until no node changes by more than 1e-9. `L` is twice the
//! largest distance from a free node to a fixed one (the region's inradius, measured by a
//! chamfer transform): the region's lowest Dirichlet eigenvalue is set by its inradius within
//! a constant factor, and on the thin band of a restart (between a lap and `B`) the extent
//! of the grid would overestimate `L` many times, an `ω` so close to 2 that SOR converges
//! like `ω − 1` per sweep (measured: see `relaxation`).
//!
//! [`Harmonic::value`] interpolates `u` bilinearly; [`Harmonic::gradient`] interpolates the
//! nodal central differences bilinearly, which makes it continuous, so streamlines traced with
//! it are smooth.

use crate::geom::{Point, Vec2};
use crate::strategy::pocket::shape::{IndexedLoop, v2};
use cavalier_contours::polyline::{PlineSource, Polyline};

/// The discrete harmonic function on a grid.
#[derive(Debug, Clone)]
pub struct Harmonic {
    origin: Point,
    h: f64,
    nx: usize,
    ny: usize,
    u: Vec<f64>,
    grad: Vec<Vec2>,
}

/// SOR stops when no node changes by more than this.
const SOR_TOL: f64 = 1e-9;
/// And after this many sweeps at most.
const SOR_MAX_SWEEPS: usize = 20_000;

impl Harmonic {
    /// Solves the problem for boundary `b` (counter-clockwise) and the circle about `c` of
    /// radius `r0`, on a grid of spacing `h`.
    pub fn solve(b: &Polyline<f64>, c: Point, r0: f64, h: f64) -> Self {
        Self::solve_with(b, |p| p.distance(c) - r0, h)
    }

    /// Solves with the inner boundary given by its signed distance `inner` (negative or zero
    /// inside, where u = 0): the circle.
    pub fn solve_with(b: &Polyline<f64>, inner: impl Fn(Point) -> f64, h: f64) -> Self {
        let (origin, nx, ny) = Self::grid(b, h);
        Self::solve_on_grid(b, origin, h, nx, ny, |_, p| inner(p))
    }

    /// Solves with the closed polygon `lap` (its vertices; a loop the morph reached and restarts
    /// from) as the inner boundary: `u = 0` on the nodes inside it. Which nodes those are is
    /// found row by row (even-odd crossings of the row's line, `O(rows · n + nodes)`); the
    /// initial guess takes `d_c` from a chamfer distance transform of that mask (within 8% of
    /// the Euclidean distance, `O(nodes)`). Before, a winding number and a closest point per
    /// node cost `O(nodes · n)`: half the time of a restarted morph. Only the initial guess
    /// changes; the solution is the same to the SOR tolerance.
    pub fn solve_from_loop(b: &Polyline<f64>, lap: &[Point], h: f64) -> Self {
        let (origin, nx, ny) = Self::grid(b, h);
        let inside = scanline_inside(lap, origin, h, nx, ny);
        let dist = chamfer(&inside, nx, ny, h);
        Self::solve_on_grid(
            b,
            origin,
            h,
            nx,
            ny,
            |k, _| {
                if inside[k] { 0.0 } else { dist[k] }
            },
        )
    }

    /// The solve on the grid at `origin` (spacing `h`, `nx × ny` nodes); `inner(k, p)` is the
    /// signed distance of node `k` at `p` from the inner boundary.
    fn solve_on_grid(
        b: &Polyline<f64>,
        origin: Point,
        h: f64,
        nx: usize,
        ny: usize,
        inner: impl Fn(usize, Point) -> f64,
    ) -> Self {
        let n = nx * ny;
        let b_index = IndexedLoop::new(b);
        let mut u = vec![1.0; n];
        // 0 = free, 1 = fixed.
        let mut fixed = vec![true; n];
        for j in 0..ny {
            for i in 0..nx {
                let p = Point::new(origin.x + h * i as f64, origin.y + h * j as f64);
                let k = j * nx + i;
                let dc = inner(k, p);
                if dc <= 0.0 {
                    u[k] = 0.0;
                } else if b.winding_number(v2(p)) != 0 {
                    let db = b_index.distance(p);
                    let db = if db.is_finite() { db } else { 1.0 };
                    // (An infinite `dc`: no inner node at all, a degenerate lap.)
                    u[k] = if dc.is_finite() { dc / (dc + db) } else { 1.0 };
                    fixed[k] = false;
                }
            }
        }
        let omega = relaxation(&fixed, nx, ny, h);
        for _ in 0..SOR_MAX_SWEEPS {
            let mut change: f64 = 0.0;
            for colour in 0..2 {
                for j in 1..ny - 1 {
                    let start = 1 + (j + colour) % 2;
                    for i in (start..nx - 1).step_by(2) {
                        let k = j * nx + i;
                        if fixed[k] {
                            continue;
                        }
                        let avg = 0.25 * (u[k - 1] + u[k + 1] + u[k - nx] + u[k + nx]);
                        let d = omega * (avg - u[k]);
                        u[k] += d;
                        change = change.max(d.abs());
                    }
                }
            }
            if change < SOR_TOL {
                break;
            }
        }
        Self::finish(origin, h, nx, ny, u)
    }

    /// The distance-field interpolation `u = g / (g + d_B)`: `g` the geodesic distance from
    /// the circle inside `B` (Dijkstra on the grid's 8-neighbour graph, which overestimates
    /// Euclidean lengths by at most `1/cos(22.5°) − 1 ≈ 8%`), `d_B` the exact distance to `B`.
    /// Its level sets also run from the circle (u = 0) to `B` (u = 1) in any simply connected
    /// pocket, without the exponential flattening of the harmonic function in long arms, but
    /// they have kinks across the medial axis of `B`; it is the fallback.
    pub fn distance_blend(b: &Polyline<f64>, c: Point, r0: f64, h: f64) -> Self {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        let (origin, nx, ny) = Self::grid(b, h);
        let n = nx * ny;
        let mut inside = vec![false; n];
        let mut g = vec![f64::INFINITY; n];
        let mut heap = BinaryHeap::new();
        for j in 0..ny {
            for i in 0..nx {
                let p = Point::new(origin.x + h * i as f64, origin.y + h * j as f64);
                let k = j * nx + i;
                inside[k] = b.winding_number(v2(p)) != 0;
                let dc = p.distance(c) - r0;
                if inside[k] && dc <= h {
                    g[k] = dc.max(0.0);
                    heap.push(Reverse((OrdF64(g[k]), k)));
                }
            }
        }
        while let Some(Reverse((OrdF64(d), k))) = heap.pop() {
            if d > g[k] {
                continue;
            }
            let (i, j) = ((k % nx) as isize, (k / nx) as isize);
            for (di, dj, w) in [
                (1, 0, 1.0),
                (-1, 0, 1.0),
                (0, 1, 1.0),
                (0, -1, 1.0),
                (1, 1, std::f64::consts::SQRT_2),
                (1, -1, std::f64::consts::SQRT_2),
                (-1, 1, std::f64::consts::SQRT_2),
                (-1, -1, std::f64::consts::SQRT_2),
            ] {
                let (ii, jj) = (i + di, j + dj);
                if ii < 0 || jj < 0 || ii >= nx as isize || jj >= ny as isize {
                    continue;
                }
                let kk = jj as usize * nx + ii as usize;
                if !inside[kk] {
                    continue;
                }
                let nd = d + w * h;
                if nd < g[kk] {
                    g[kk] = nd;
                    heap.push(Reverse((OrdF64(nd), kk)));
                }
            }
        }
        let mut u = vec![1.0; n];
        let b_index = IndexedLoop::new(b);
        for j in 0..ny {
            for i in 0..nx {
                let k = j * nx + i;
                let p = Point::new(origin.x + h * i as f64, origin.y + h * j as f64);
                if p.distance(c) <= r0 {
                    u[k] = 0.0;
                } else if inside[k] && g[k].is_finite() {
                    let db = b_index.distance(p);
                    let db = if db.is_finite() { db } else { 1.0 };
                    u[k] = g[k] / (g[k] + db).max(1e-12);
                }
            }
        }
        Self::finish(origin, h, nx, ny, u)
    }

    /// Grid origin and size covering `b` with two spare nodes on every side.
    fn grid(b: &Polyline<f64>, h: f64) -> (Point, usize, usize) {
        let e = b.extents();
        let (x0, y0, x1, y1) = e.map_or((0.0, 0.0, 1.0, 1.0), |e| {
            (e.min_x, e.min_y, e.max_x, e.max_y)
        });
        let origin = Point::new(x0 - 2.0 * h, y0 - 2.0 * h);
        let nx = ((x1 - x0) / h).ceil() as usize + 5;
        let ny = ((y1 - y0) / h).ceil() as usize + 5;
        (origin, nx, ny)
    }

    /// Nodal gradients by central differences.
    fn finish(origin: Point, h: f64, nx: usize, ny: usize, u: Vec<f64>) -> Self {
        let n = nx * ny;
        let mut grad = vec![Vec2::new(0.0, 0.0); n];
        for j in 0..ny {
            for i in 0..nx {
                let at = |ii: usize, jj: usize| u[jj * nx + ii];
                let (il, ir) = (i.saturating_sub(1), (i + 1).min(nx - 1));
                let (jd, ju) = (j.saturating_sub(1), (j + 1).min(ny - 1));
                let gx = (at(ir, j) - at(il, j)) / (h * (ir - il).max(1) as f64);
                let gy = (at(i, ju) - at(i, jd)) / (h * (ju - jd).max(1) as f64);
                grad[j * nx + i] = Vec2::new(gx, gy);
            }
        }
        Harmonic {
            origin,
            h,
            nx,
            ny,
            u,
            grad,
        }
    }

    /// Grid cell and offsets of `p`, clamped to the grid.
    fn locate(&self, p: Point) -> (usize, usize, f64, f64) {
        let fx = ((p.x - self.origin.x) / self.h).clamp(0.0, (self.nx - 2) as f64);
        let fy = ((p.y - self.origin.y) / self.h).clamp(0.0, (self.ny - 2) as f64);
        let (i, j) = (fx.floor() as usize, fy.floor() as usize);
        let i = i.min(self.nx - 2);
        let j = j.min(self.ny - 2);
        (i, j, fx - i as f64, fy - j as f64)
    }

    /// `u` at `p`, bilinearly interpolated.
    pub fn value(&self, p: Point) -> f64 {
        let (i, j, tx, ty) = self.locate(p);
        let k = j * self.nx + i;
        let (a, b, c, d) = (
            self.u[k],
            self.u[k + 1],
            self.u[k + self.nx],
            self.u[k + self.nx + 1],
        );
        (a * (1.0 - tx) + b * tx) * (1.0 - ty) + (c * (1.0 - tx) + d * tx) * ty
    }

    /// ∇u at `p`, bilinearly interpolated from nodal central differences.
    pub fn gradient(&self, p: Point) -> Vec2 {
        let (i, j, tx, ty) = self.locate(p);
        let k = j * self.nx + i;
        let g = &self.grad;
        (g[k] * (1.0 - tx) + g[k + 1] * tx) * (1.0 - ty)
            + (g[k + self.nx] * (1.0 - tx) + g[k + self.nx + 1] * tx) * ty
    }

    /// Grid spacing in mm.
    pub fn spacing(&self) -> f64 {
        self.h
    }

    /// Follows the gradient from `p` until `u` reaches `target`; returns the end point and the
    /// length of the streamline (which bounds the distance between the two level sets there).
    pub fn trace(&self, p: Point, target: f64) -> (Point, f64) {
        let mut q = p;
        let mut len = 0.0;
        for _ in 0..2000 {
            let u = self.value(q);
            if u >= target - 1e-9 {
                break;
            }
            let g = self.gradient(q);
            let gl = g.length();
            let Some(dir) = g.normalize() else { break };
            let step = ((target - u) / gl.max(1e-12)).min(0.25 * self.h);
            // Midpoint rule: direction at the half step.
            let mid = q + dir * (0.5 * step);
            let dir = self.gradient(mid).normalize().unwrap_or(dir);
            q += dir * step;
            len += step;
        }
        (q, len)
    }
}

/// A total order on f64 for the Dijkstra heap (distances are finite and non-negative).
#[derive(Debug, Clone, Copy, PartialEq)]
struct OrdF64(f64);

impl Eq for OrdF64 {}

impl PartialOrd for OrdF64 {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for OrdF64 {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Which nodes of the grid (`origin`, spacing `h`, `nx × ny`, row-major) lie inside the closed
/// polygon `pts`, by the even-odd rule: for each row, the crossings of its line with the edges
/// (half-open in y, so a vertex on the line counts once), sorted, fill the nodes between pairs.
fn scanline_inside(pts: &[Point], origin: Point, h: f64, nx: usize, ny: usize) -> Vec<bool> {
    let mut inside = vec![false; nx * ny];
    let mut xs: Vec<f64> = Vec::new();
    for j in 0..ny {
        let y = origin.y + h * j as f64;
        xs.clear();
        for (i, a) in pts.iter().enumerate() {
            let b = pts[(i + 1) % pts.len()];
            if (a.y <= y) != (b.y <= y) {
                xs.push(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            // Nodes with pair[0] < x < pair[1] (a node exactly on an edge counts as outside,
            // as its distance 0 fixes it at u = 0 anyway).
            let lo = ((pair[0] - origin.x) / h).floor() + 1.0;
            let hi = ((pair[1] - origin.x) / h).ceil() - 1.0;
            let lo = lo.max(0.0) as usize;
            let hi = hi.min(nx as f64 - 1.0);
            if hi < 0.0 {
                continue;
            }
            for i in lo..=(hi as usize) {
                inside[j * nx + i] = true;
            }
        }
    }
    inside
}

/// The over-relaxation factor for the free nodes of `fixed` (grid `nx × ny`, spacing `h`):
/// `ω = 2 / (1 + sin(πh/L))` with `L = 2·ρ + 2h`, `ρ` the largest chamfer distance from a free
/// node to a fixed one (at most the grid's larger extent). The chamfer distance is at most 8%
/// long, which errs on the side of a larger `ω`, where SOR is less sensitive. Measured: a 6°
/// sliver's nine solves (mostly restarts, thin bands) 456 sweeps instead of 4,761; the sample
/// part's L (no restart) 240 and 317 instead of 469 and 464.
fn relaxation(fixed: &[bool], nx: usize, ny: usize, h: f64) -> f64 {
    let d = chamfer(fixed, nx, ny, h);
    let rho = fixed
        .iter()
        .zip(&d)
        .filter(|(f, _)| !**f)
        .map(|(_, &d)| d)
        .fold(0.0, f64::max);
    let extent = (nx.max(ny) as f64) * h;
    let l = (2.0 * rho + 2.0 * h).min(extent);
    2.0 / (1.0 + (std::f64::consts::PI * h / l).sin())
}

/// Distance from each node to the nearest node of `mask`, by the two-pass 8-neighbour chamfer
/// transform (steps `h` and `√2·h`; exact along the axes and diagonals, at most 8% long in
/// between); infinite where `mask` is empty.
fn chamfer(mask: &[bool], nx: usize, ny: usize, h: f64) -> Vec<f64> {
    let d1 = h;
    let d2 = std::f64::consts::SQRT_2 * h;
    let mut d: Vec<f64> = mask
        .iter()
        .map(|&m| if m { 0.0 } else { f64::INFINITY })
        .collect();
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            let mut v = d[k];
            if i > 0 {
                v = v.min(d[k - 1] + d1);
            }
            if j > 0 {
                v = v.min(d[k - nx] + d1);
                if i > 0 {
                    v = v.min(d[k - nx - 1] + d2);
                }
                if i + 1 < nx {
                    v = v.min(d[k - nx + 1] + d2);
                }
            }
            d[k] = v;
        }
    }
    for j in (0..ny).rev() {
        for i in (0..nx).rev() {
            let k = j * nx + i;
            let mut v = d[k];
            if i + 1 < nx {
                v = v.min(d[k + 1] + d1);
            }
            if j + 1 < ny {
                v = v.min(d[k + nx] + d1);
                if i + 1 < nx {
                    v = v.min(d[k + nx + 1] + d2);
                }
                if i > 0 {
                    v = v.min(d[k + nx - 1] + d2);
                }
            }
            d[k] = v;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strategy::pocket::shape::loop_distance;
    use cavalier_contours::polyline::PlineSourceMut;

    /// A thin annulus (radii 17 and 20 on a 40 mm grid, the shape of a restart's band): the
    /// factor follows the band's width, not the grid's extent, and the solution is still
    /// the logarithm.
    #[test]
    fn thin_band_relaxation_and_solution() {
        let mut b = Polyline::new_closed();
        b.add(-20.0, 0.0, 1.0);
        b.add(20.0, 0.0, 1.0);
        let h = 0.25;
        let (origin, nx, ny) = Harmonic::grid(&b, h);
        let fixed: Vec<bool> = (0..nx * ny)
            .map(|k| {
                let p = Point::new(
                    origin.x + h * (k % nx) as f64,
                    origin.y + h * (k / nx) as f64,
                );
                let r = p.distance(Point::ORIGIN);
                r <= 17.0 || r >= 20.0
            })
            .collect();
        let band = relaxation(&fixed, nx, ny, h);
        let box_extent = (nx.max(ny) as f64) * h;
        let boxed = 2.0 / (1.0 + (std::f64::consts::PI * h / box_extent).sin());
        // L = 2ρ + 2h ≈ 3.5 mm against the grid's 41 mm.
        let expect = 2.0 / (1.0 + (std::f64::consts::PI * h / 3.5).sin());
        assert!(
            (band - expect).abs() < 0.05 && band < boxed - 0.2,
            "{band} {boxed}"
        );
        let hm = Harmonic::solve(&b, Point::ORIGIN, 17.0, h);
        for rho in [17.75, 18.5, 19.25] {
            let exact = (rho / 17.0f64).ln() / (20.0f64 / 17.0).ln();
            let got = hm.value(Point::new(rho * 0.8, -rho * 0.6));
            assert!((got - exact).abs() < 0.03, "rho {rho}: {got} vs {exact}");
        }
    }

    /// A star-shaped, non-convex polygon of 61 vertices about the origin, radius 9 to 19.
    fn star() -> Vec<Point> {
        (0..61)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 61.0;
                let r = 9.0 + 10.0 * ((i * 7 % 5) as f64) / 4.0;
                Point::new(r * a.cos() + 0.013, r * a.sin() - 0.007)
            })
            .collect()
    }

    /// The row-by-row inside test agrees with the winding number on every node.
    #[test]
    fn scanline_matches_winding_number() {
        let pts = star();
        let pl = super::super::common::closed_pline(&pts);
        let (origin, h, nx, ny) = (Point::new(-21.0, -20.5), 0.25, 170, 166);
        let inside = scanline_inside(&pts, origin, h, nx, ny);
        let mut disagree = 0;
        for j in 0..ny {
            for i in 0..nx {
                let p = Point::new(origin.x + h * i as f64, origin.y + h * j as f64);
                if inside[j * nx + i] != (pl.winding_number(v2(p)) != 0) {
                    disagree += 1;
                }
            }
        }
        assert_eq!(disagree, 0);
        assert!(inside.iter().filter(|&&x| x).count() > 5000);
    }

    /// The restart solve equals the solve with the brute-force signed distance (the code
    /// before the index and the scanline) to the SOR tolerance.
    #[test]
    fn restart_solve_matches_brute_force() {
        let mut b = Polyline::new_closed();
        b.add(-30.0, 0.0, 1.0);
        b.add(30.0, 0.0, 1.0);
        let pts = star();
        let pl = super::super::common::closed_pline(&pts);
        let fast = Harmonic::solve_from_loop(&b, &pts, 0.5);
        let slow = Harmonic::solve_with(
            &b,
            |p| {
                let d = loop_distance(&pl, p);
                if pl.winding_number(v2(p)) != 0 { -d } else { d }
            },
            0.5,
        );
        let worst = fast
            .u
            .iter()
            .zip(&slow.u)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-6, "{worst}");
        assert!(fast.value(Point::new(25.0, 0.0)) > 0.2);
    }

    /// Between two concentric circles the solution is ln(ρ/R₀)/ln(R₁/R₀).
    #[test]
    fn annulus_matches_the_logarithm() {
        let mut b = Polyline::new_closed();
        b.add(-20.0, 0.0, 1.0);
        b.add(20.0, 0.0, 1.0);
        let hm = Harmonic::solve(&b, Point::ORIGIN, 5.0, 0.25);
        for rho in [8.0, 12.0, 16.0] {
            let exact = (rho / 5.0f64).ln() / (20.0f64 / 5.0).ln();
            let got = hm.value(Point::new(rho * 0.6, rho * 0.8));
            assert!((got - exact).abs() < 0.02, "rho {rho}: {got} vs {exact}");
        }
        let (q, len) = hm.trace(Point::new(6.0, 0.0), 0.5);
        let rho = 5.0 * (4.0f64).powf(0.5);
        assert!((q.distance(Point::ORIGIN) - rho).abs() < 0.2, "{q:?}");
        assert!(q.y.abs() < 0.1 && (len - (rho - 6.0)).abs() < 0.2);
    }
}
