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
//! `ω = 2 / (1 + sin(πh/L))` (`L` the larger extent), the optimal factor for the model
//! problem, from an initial guess that already interpolates the distances
//! (`u₀ = d_c / (d_c + d_B)`), until no node changes by more than 1e-9.
//!
//! [`Harmonic::value`] interpolates `u` bilinearly; [`Harmonic::gradient`] interpolates the
//! nodal central differences bilinearly, which makes it continuous, so streamlines traced with
//! it are smooth.

use crate::geom::{Point, Vec2};
use crate::strategy::pocket::shape::v2;
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
    /// inside, where u = 0): a circle, or a loop the morph has reached and restarts from.
    pub fn solve_with(b: &Polyline<f64>, inner: impl Fn(Point) -> f64, h: f64) -> Self {
        let e = b.extents();
        let (x0, y0, x1, y1) = e.map_or((0.0, 0.0, 1.0, 1.0), |e| {
            (e.min_x, e.min_y, e.max_x, e.max_y)
        });
        let origin = Point::new(x0 - 2.0 * h, y0 - 2.0 * h);
        let nx = ((x1 - x0) / h).ceil() as usize + 5;
        let ny = ((y1 - y0) / h).ceil() as usize + 5;
        let n = nx * ny;
        let mut u = vec![1.0; n];
        // 0 = free, 1 = fixed.
        let mut fixed = vec![true; n];
        for j in 0..ny {
            for i in 0..nx {
                let p = Point::new(origin.x + h * i as f64, origin.y + h * j as f64);
                let k = j * nx + i;
                let dc = inner(p);
                if dc <= 0.0 {
                    u[k] = 0.0;
                } else if b.winding_number(v2(p)) != 0 {
                    let db = b.closest_point(v2(p), 1e-12).map_or(1.0, |r| r.distance);
                    u[k] = dc / (dc + db);
                    fixed[k] = false;
                }
            }
        }
        let extent = (nx.max(ny) as f64) * h;
        let omega = 2.0 / (1.0 + (std::f64::consts::PI * h / extent).sin());
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
        for j in 0..ny {
            for i in 0..nx {
                let k = j * nx + i;
                let p = Point::new(origin.x + h * i as f64, origin.y + h * j as f64);
                if p.distance(c) <= r0 {
                    u[k] = 0.0;
                } else if inside[k] && g[k].is_finite() {
                    let db = b.closest_point(v2(p), 1e-12).map_or(1.0, |r| r.distance);
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

#[cfg(test)]
mod tests {
    use super::*;
    use cavalier_contours::polyline::PlineSourceMut;

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
