//! Where the next pass starts: the coarse map of the distance to the material, kept up to
//! date where the field changed, and the band of blocks a pass may start from (see the
//! parent module's "Passes and links").

use super::field::Coarse;
use super::{BLOCK, Planner};
use crate::geom::{Point, Vec2};

impl Planner<'_, '_> {
    /// The start of the next pass: the block nearest the tool that is clear of material by
    /// one to three blocks' width beyond `r`, inside the reach, not tried before, whose
    /// first step can cut; and the heading with the material on the cutting side.
    pub(super) fn start(&mut self) -> Option<(Point, f64, usize)> {
        // The map is the same while the field is (it only loses cells, and an undo restores
        // what its record removed): a pass that cut nothing leaves it as it was.
        let cells = self.field.material_cells();
        let changed = self.field.take_changed();
        // The distances `start_on` reads: a candidate's and its neighbours', at most
        // `r + 3` blocks.
        let cap = self.stepper.r + 4.0 * self.field.h * BLOCK as f64;
        let (coarse, fresh) = match (self.coarse.take(), changed) {
            (Some((n, c)), _) if n == cells => (c, false),
            (Some((_, c)), Some(changed)) => {
                (self.field.coarse_update(BLOCK, c, changed, cap), true)
            }
            _ => (self.field.coarse_distance(BLOCK), true),
        };
        if fresh {
            self.refresh_band(&coarse);
        }
        let found = self.start_on(&coarse);
        self.coarse = Some((cells, coarse));
        found
    }

    /// Brings the band of start blocks up to date with the map `coarse`, just made or
    /// updated: the blocks (the map's edge aside) whose distance lies from `r` less one block
    /// to `r` plus two, where the tool centre may stand. Only the blocks the update
    /// recomputed are looked at again.
    fn refresh_band(&mut self, coarse: &Coarse) {
        let n = coarse.dist.len();
        let window = if self.tried.len() == n {
            coarse.window
        } else {
            self.tried = vec![false; n];
            self.block_allowed = vec![0; n];
            self.in_band = vec![false; n];
            None
        };
        let (nx, ny) = (coarse.nx, coarse.ny);
        if nx < 3 || ny < 3 {
            self.band.clear();
            return;
        }
        let [i0, i1, j0, j1] = match window {
            Some([i0, i1, j0, j1]) => [i0.max(1), i1.min(nx - 2), j0.max(1), j1.min(ny - 2)],
            None => {
                self.band.clear();
                self.in_band.fill(false);
                [1, nx - 2, 1, ny - 2]
            }
        };
        let st = self.stepper;
        let hc = self.field.h * BLOCK as f64;
        for j in j0..=j1 {
            for i in i0..=i1 {
                let k = j * nx + i;
                let d = coarse.dist[k];
                let mut now = d >= st.r - hc && d <= st.r + 2.0 * hc;
                // Whether a block's centre may hold the tool never changes: it is found once.
                if now && self.block_allowed[k] == 0 {
                    let c = self.field.coarse_centre(BLOCK, i, j);
                    self.block_allowed[k] = if st.walls.allows(self.field, c) { 1 } else { 2 };
                }
                now &= self.block_allowed[k] == 1;
                if now && !self.in_band[k] {
                    self.band.push(k);
                }
                self.in_band[k] = now;
            }
        }
        let in_band = &self.in_band;
        self.band.retain(|&k| in_band[k]);
        debug_assert_eq!(self.band_by_scan(coarse), {
            let mut b = self.band.clone();
            b.sort_unstable();
            b
        });
    }

    /// The band [`Planner::refresh_band`] keeps, found by reading every block of `coarse`
    /// (its check in debug builds), in the order of the blocks' indices.
    fn band_by_scan(&self, coarse: &Coarse) -> Vec<usize> {
        let (st, hc) = (self.stepper, self.field.h * BLOCK as f64);
        let mut out = Vec::new();
        for j in 1..coarse.ny.saturating_sub(1) {
            for i in 1..coarse.nx.saturating_sub(1) {
                let d = coarse.dist[j * coarse.nx + i];
                if (st.r - hc..=st.r + 2.0 * hc).contains(&d)
                    && st
                        .walls
                        .allows(self.field, self.field.coarse_centre(BLOCK, i, j))
                {
                    out.push(j * coarse.nx + i);
                }
            }
        }
        out
    }

    /// [`Self::start`] on the coarse map `coarse` of the field as it is.
    fn start_on(&mut self, coarse: &Coarse) -> Option<(Point, f64, usize)> {
        let st = self.stepper;
        let hc = self.field.h * BLOCK as f64;
        let here = self.pos?;
        // Nearest first; blocks equally near in the order of their index.
        let mut cands: Vec<(f64, usize)> = self
            .band
            .iter()
            .filter(|&&k| !self.tried[k])
            .map(|&k| {
                let c = self
                    .field
                    .coarse_centre(BLOCK, k % coarse.nx, k / coarse.nx);
                (c.distance(here), k)
            })
            .collect();
        cands.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for &(_, k) in &cands {
            let (i, j) = (k % coarse.nx, k / coarse.nx);
            let c = self.field.coarse_centre(BLOCK, i, j);
            // Towards the material: down the distance map's slope.
            let at = |ii: usize, jj: usize| coarse.dist[jj * coarse.nx + ii];
            let g = Vec2::new(at(i + 1, j) - at(i - 1, j), at(i, j + 1) - at(i, j - 1));
            let Some(n) = (-g).normalize() else {
                self.tried[k] = true;
                continue;
            };
            // The point on the line through the block along `n` nearest the material with
            // the tool's disc clear of it (bisection between clear and not).
            let (mut lo, mut hi) = (-3.0 * hc, 3.0 * hc);
            let clear_at = |t: f64| {
                let q = c + n * t;
                st.walls.allows(self.field, q) && !self.field.disc_holds_more_than(q, st.r, 0)
            };
            if !clear_at(lo) {
                self.tried[k] = true;
                continue;
            }
            if clear_at(hi) {
                lo = hi;
            } else {
                for _ in 0..8 {
                    let mid = 0.5 * (lo + hi);
                    if clear_at(mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
            }
            let c = c + n * lo;
            // The heading with `n` on the cutting side: `n` turned a quarter the other way.
            let theta = n.y.atan2(n.x) + st.side * std::f64::consts::FRAC_PI_2;
            let need = st.first_bite_need(self.field, c);
            if st.first_bite_reaches(self.field, c, theta, need) {
                return Some((c, theta, k));
            }
            self.tried[k] = true;
        }
        None
    }

    pub(super) fn mark_tried(&mut self, p: Point) {
        let hc = self.field.h * BLOCK as f64;
        let (nx, _) = self.field.size();
        let cx = nx.div_ceil(BLOCK);
        let o = self.field.centre(0, 0);
        let i = ((p.x - o.x) / hc + 0.5).floor().max(0.0) as usize;
        let j = ((p.y - o.y) / hc + 0.5).floor().max(0.0) as usize;
        if let Some(t) = self.tried.get_mut(j * cx + i) {
            *t = true;
        }
    }
}
