//! Sweeping a helix into the height field, cell by cell in the angle (see [`super`]).

use super::deepest_first::{Tiles, tile_end};
use super::{HeightField, Tally};
use crate::geom::{Point, Point3};
use std::f64::consts::{FRAC_PI_2, TAU};

/// A helix about `centre` on the mean circle of radius `radius`, the tool widened to `rr`:
/// from the angle `theta0`, turning `total` rad in the sense `sigma`, its tip from `z0` by
/// `dz` linearly in the angle.
#[derive(Debug, Clone, Copy)]
struct Turns {
    radius: f64,
    rr: f64,
    theta0: f64,
    sigma: f64,
    total: f64,
    z0: f64,
    dz: f64,
}

impl Turns {
    /// The lowest tip over the angles at which the axis is within `rr` of the cell centre at
    /// `(dx, dy)` from the centre, if any.
    fn lowest_tip(&self, dx: f64, dy: f64) -> Option<f64> {
        let Turns {
            radius,
            rr,
            theta0,
            sigma,
            total,
            z0,
            dz,
        } = *self;
        let rho = dx.hypot(dy);
        // The angles turned (from the start, in [0, total]) at which the axis is within rr of
        // the cell: the least and the greatest.
        let (s_min, s_max) = if rho <= 1e-12 {
            (radius <= rr).then_some((0.0, total))
        } else {
            let k = (radius * radius + rho * rho - rr * rr) / (2.0 * radius * rho);
            if k > 1.0 {
                None
            } else if k <= -1.0 {
                Some((0.0, total))
            } else {
                let alpha = k.acos();
                let m = (sigma * (dy.atan2(dx) - theta0)).rem_euclid(TAU);
                // The first window [m − α, m + α] + 2πj reaching 0, the last one starting by
                // `total`.
                let first = ((-m - alpha) / TAU).ceil();
                let start = m - alpha + TAU * first;
                let last = ((total - (m - alpha)) / TAU).floor();
                let end = m + alpha + TAU * last;
                (start <= total && end >= 0.0).then(|| (start.max(0.0), end.min(total)))
            }
        }?;
        let s = if dz < 0.0 { s_max } else { s_min };
        Some(z0 + dz * s / total)
    }
}

impl HeightField {
    /// Sweeps the tool of radius `r` along the XY helix from `from` to `to` about `centre`,
    /// turning `sweep` rad (signed, counter-clockwise positive, any number of turns), z
    /// linear in the angle turned. Every cell within reach of the circle gets the lowest tip
    /// over the angles at which the axis passes within `r` of its centre. `tiles`, when
    /// given, skips the tiles no lower than the helix's lowest tip (z is linear in the angle:
    /// no cell gets a tip below its ends') and records the tiles it lowers.
    pub(super) fn sweep_helix(
        &mut self,
        (from, to): (Point3, Point3),
        centre: Point,
        sweep: f64,
        r: f64,
        tally: &mut Tally,
        mut tiles: Option<&mut Tiles>,
    ) {
        let (r0, r1) = (from.xy().distance(centre), to.xy().distance(centre));
        let radius = 0.5 * (r0 + r1);
        let rr = r + 0.5 * (r1 - r0).abs();
        let total = sweep.abs();
        if total <= 0.0 || radius <= 0.0 {
            return;
        }
        let sigma = sweep.signum();
        let theta0 = (from.y - centre.y).atan2(from.x - centre.x);
        let turns = Turns {
            radius,
            rr,
            theta0,
            sigma,
            total,
            z0: from.z,
            dz: to.z - from.z,
        };
        // The arc's extent: its ends and the axis directions it passes.
        let mut lo = Point::new(from.x.min(to.x), from.y.min(to.y));
        let mut hi = Point::new(from.x.max(to.x), from.y.max(to.y));
        for q in 0..4 {
            let a = FRAC_PI_2 * q as f64;
            if (sigma * (a - theta0)).rem_euclid(TAU) <= total {
                let p = Point::new(centre.x + radius * a.cos(), centre.y + radius * a.sin());
                lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
                hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
            }
        }
        let reach = rr + 0.5 * (r1 - r0).abs();
        let outer = radius + rr;
        // As for a line: no tip this helix gives, stored as f32, lies below this.
        let floor = ((from.z.min(to.z) - 1e-6).max(self.bottom)) as f32;
        // Deepest first, a cell at or below it is left as it is without its tip.
        let keep = tiles.as_ref().map(|_| floor);
        let mut rows = Vec::new();
        self.for_rows(lo.y - reach, hi.y + reach, |j, y| rows.push((j, y)));
        let nx = self.nx;
        for (j, y) in rows {
            let dy = y - centre.y;
            let w2 = outer * outer - dy * dy;
            if w2 < 0.0 {
                continue;
            }
            let w = w2.sqrt();
            let Some((i0, i1)) = self.columns(
                (centre.x - w).max(lo.x - reach),
                (centre.x + w).min(hi.x + reach),
            ) else {
                continue;
            };
            let mut c0 = i0;
            while c0 <= i1 {
                let c1 = if tiles.is_some() {
                    tile_end(c0, i1 + 1)
                } else {
                    i1 + 1
                };
                if let Some(t) = tiles.as_deref_mut()
                    && t.at_or_below(self, c0, j, floor)
                {
                    c0 = c1;
                    continue;
                }
                tally.changed = false;
                for i in c0..c1 {
                    if keep.is_some_and(|f| self.h[j * nx + i] <= f) {
                        continue;
                    }
                    let dx = self.origin.x + (i as f64 + 0.5) * self.cell - centre.x;
                    if let Some(z) = turns.lowest_tip(dx, dy) {
                        self.lower(j * nx + i, z, tally);
                    }
                }
                if tally.changed
                    && let Some(t) = tiles.as_deref_mut()
                {
                    t.mark(c0, j);
                }
                c0 = c1;
            }
        }
    }
}
