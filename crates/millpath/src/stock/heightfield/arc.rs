//! Sweeping an XY arc into the height field whole, cell by cell in the angle (see
//! [`super`]): a helix, or an arc at one z (its tip constant in the angle).
//!
//! The cells a tool of radius `r` on a circle of radius `R` can reach lie in the annulus
//! `R − r ≤ ρ ≤ R + r` about the centre (`ρ` a cell centre's distance from it): each row is
//! read over the annulus only, one span either side of the inner disc where the row crosses
//! it (a cell within `10⁻⁶` mm of the inner circle is read all the same), clipped to the
//! arc's box grown by the reach. An arc of a metre's radius thus costs the cells along its
//! band, not its box's, and not the thousands of chords of a micrometre's sagitta it would
//! take as lines.

use super::deepest_first::{Tiles, tile_end};
use super::{HeightField, Tally};
use crate::geom::{Point, Point3};
use std::f64::consts::{FRAC_PI_2, TAU};

/// An XY arc about `centre` on the mean circle of radius `radius`, the tool widened to `rr`:
/// from the angle `theta0`, turning `total` rad in the sense `sigma`, its tip from `z0` by
/// `dz` linearly in the angle.
#[derive(Debug, Clone, Copy)]
struct Turns {
    /// The centre's x, mm.
    cx: f64,
    /// No tip the arc gives, stored as `f32`, lies below this (as for a line).
    floor: f32,
    /// The squared distances from the centre between which a cell may be reached: the
    /// annulus `|ρ − R| ≤ rr` grown by [`BAND_MARGIN`] either way (the inner one negative
    /// where the annulus has no hole).
    band2: (f64, f64),
    /// The unit directions from the centre to the start and to the end.
    dirs: [(f64, f64); 2],
    radius: f64,
    rr: f64,
    theta0: f64,
    sigma: f64,
    total: f64,
    z0: f64,
    dz: f64,
}

/// How far beyond the annulus `|ρ − R| ≤ rr` a cell is still measured, mm: past it the
/// angles' test finds no reach whatever its rounding (a cell out by `10⁻⁶` mm is out by far
/// more than the rounding of `(R² + ρ² − rr²) / 2Rρ`).
const BAND_MARGIN: f64 = 1e-6;

impl Turns {
    /// The lowest tip over the angles at which the axis is within `rr` of the cell centre at
    /// `(dx, dy)` from the centre, if any.
    fn lowest_tip(&self, dx: f64, dy: f64) -> Option<f64> {
        let rho2 = dx * dx + dy * dy;
        if rho2 > self.band2.1 || rho2 < self.band2.0 {
            return None;
        }
        if self.dz == 0.0 {
            return self.reaches_flat(dx, dy, rho2).then_some(self.z0);
        }
        let Turns {
            radius,
            rr,
            theta0,
            sigma,
            total,
            z0,
            dz,
            ..
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

    /// True when the arc (at one z) passes within `rr` of the cell centre at `(dx, dy)` from
    /// the centre (`rho2` its squared distance), without its angle: a centre whose direction
    /// lies in the arc's sector is `|ρ − R|` from the arc; one outside it is nearest one of
    /// the arc's ends (the distance to the circle's point grows with the angle between them,
    /// up to a half turn).
    fn reaches_flat(&self, dx: f64, dy: f64, rho2: f64) -> bool {
        let (rr, sigma) = (self.rr, self.sigma);
        let [(ux0, uy0), (ux1, uy1)] = self.dirs;
        let in_sector = if self.total >= TAU {
            true
        } else {
            // Left of the start direction and right of the end one (in the sense turned);
            // beyond a half turn, not within the rest of the turn.
            let c0 = sigma * (ux0 * dy - uy0 * dx);
            let c1 = sigma * (dx * uy1 - dy * ux1);
            if self.total <= std::f64::consts::PI {
                c0 >= 0.0 && c1 >= 0.0
            } else {
                !(c0 < 0.0 && c1 < 0.0)
            }
        };
        if in_sector {
            return (rho2.sqrt() - self.radius).abs() <= rr;
        }
        self.dirs.iter().any(|&(ux, uy)| {
            let (ex, ey) = (dx - self.radius * ux, dy - self.radius * uy);
            ex * ex + ey * ey <= rr * rr
        })
    }
}

impl HeightField {
    /// Sweeps the tool of radius `r` along the XY arc from `from` to `to` about `centre`,
    /// turning `sweep` rad (signed, counter-clockwise positive, any number of turns), z
    /// linear in the angle turned (a helix, or constant). Every cell within reach of the arc
    /// gets the lowest tip over the angles at which the axis passes within `r` of its
    /// centre. `tiles`, when given, skips the tiles no lower than the arc's lowest tip (z is
    /// linear in the angle: no cell gets a tip below its ends') and records the tiles it
    /// lowers.
    pub(super) fn sweep_arc(
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
        // As for a line: no tip this arc gives, stored as f32, lies below this.
        let floor = ((from.z.min(to.z) - 1e-6).max(self.bottom)) as f32;
        let theta1 = theta0 + sweep;
        let (outer_band, inner_band) = (radius + rr + BAND_MARGIN, radius - rr - BAND_MARGIN);
        let turns = Turns {
            cx: centre.x,
            floor,
            band2: (
                if inner_band > 0.0 {
                    inner_band * inner_band
                } else {
                    -1.0
                },
                outer_band * outer_band,
            ),
            dirs: [(theta0.cos(), theta0.sin()), (theta1.cos(), theta1.sin())],
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
        // Within the inner circle no cell is reached (`|R − ρ| > rr`): rows skip it, less a
        // margin for the rounding of the spans.
        let inner = radius - rr - BAND_MARGIN;
        let mut rows = Vec::new();
        self.for_rows(lo.y - reach, hi.y + reach, |j, y| rows.push((j, y)));
        for (j, y) in rows {
            let dy = y - centre.y;
            let w2 = outer * outer - dy * dy;
            if w2 < 0.0 {
                continue;
            }
            let w = w2.sqrt();
            let (x0, x1) = (lo.x - reach, hi.x + reach);
            let hole2 = inner * inner - dy * dy;
            let spans = if inner > 0.0 && hole2 > 0.0 {
                let h = hole2.sqrt();
                [
                    ((centre.x - w).max(x0), (centre.x - h).min(x1)),
                    ((centre.x + h).max(x0), (centre.x + w).min(x1)),
                ]
            } else {
                [
                    ((centre.x - w).max(x0), (centre.x + w).min(x1)),
                    (f64::INFINITY, f64::NEG_INFINITY),
                ]
            };
            for (s0, s1) in spans {
                if s0 > s1 {
                    continue;
                }
                let Some((i0, i1)) = self.columns(s0, s1) else {
                    continue;
                };
                self.sweep_arc_span((j, dy), (i0, i1), &turns, tally, &mut tiles);
            }
        }
    }

    /// Sweeps the cells `i0..=i1` of row `j` (at `dy` from the arc's centre) for `turns`,
    /// as [`HeightField::sweep_arc`] does.
    fn sweep_arc_span(
        &mut self,
        (j, dy): (usize, f64),
        (i0, i1): (usize, usize),
        turns: &Turns,
        tally: &mut Tally,
        tiles: &mut Option<&mut Tiles>,
    ) {
        let nx = self.nx;
        let floor = turns.floor;
        // Deepest first, a cell at or below it is left as it is without its tip.
        let keep = tiles.as_ref().map(|_| floor);
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
                let dx = self.origin.x + (i as f64 + 0.5) * self.cell - turns.cx;
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
