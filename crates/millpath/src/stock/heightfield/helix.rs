//! Sweeping a helix into the height field, cell by cell in the angle (see [`super`]).

use super::{HeightField, Tally};
use crate::geom::{Point, Point3};
use std::f64::consts::{FRAC_PI_2, TAU};

impl HeightField {
    /// Sweeps the tool of radius `r` along the XY helix from `from` to `to` about `centre`,
    /// turning `sweep` rad (signed, counter-clockwise positive, any number of turns), z
    /// linear in the angle turned. Every cell within reach of the circle gets the lowest tip
    /// over the angles at which the axis passes within `r` of its centre.
    pub(super) fn sweep_helix(
        &mut self,
        from: Point3,
        to: Point3,
        centre: Point,
        sweep: f64,
        r: f64,
        tally: &mut Tally,
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
        let (z0, dz) = (from.z, to.z - from.z);
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
            for i in i0..=i1 {
                let dx = self.origin.x + (i as f64 + 0.5) * self.cell - centre.x;
                let rho = dx.hypot(dy);
                // The angles turned (from the start, in [0, total]) at which the axis is
                // within rr of the cell: the least and the greatest.
                let span = if rho <= 1e-12 {
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
                        // The first window [m − α, m + α] + 2πj reaching 0, the last one
                        // starting by `total`.
                        let first = ((-m - alpha) / TAU).ceil();
                        let start = m - alpha + TAU * first;
                        let last = ((total - (m - alpha)) / TAU).floor();
                        let end = m + alpha + TAU * last;
                        (start <= total && end >= 0.0).then(|| (start.max(0.0), end.min(total)))
                    }
                };
                let Some((s_min, s_max)) = span else {
                    continue;
                };
                let s = if dz < 0.0 { s_max } else { s_min };
                self.lower(j * nx + i, z0 + dz * s / total, tally);
            }
        }
    }
}
