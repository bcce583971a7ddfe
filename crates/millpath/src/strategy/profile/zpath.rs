//! The tool's height along a profile's loop at one level: the level, the ramp entry and the
//! tabs lifted over.
//!
//! At a level of depth `z` the tool's height along the loop is, by arc length `σ`,
//! `max(base(σ), tab₁(σ), …)`: `base` is `z`, or for the ramp entry the line from the level
//! above down to `z` over the ramp's length; a square tab is its top over its lift (straight
//! up and down at the ends); a ramped tab adds 1-in-2 ramps (26.6°, `TAB_RAMP_RUN`) outside
//! its lift. All of these are linear between breakpoints (element ends, ramp end, tab ends,
//! where the ramp crosses a tab), so each element is cut at them and each piece is a line or
//! a helical arc.

use super::elements::Loop;
use super::tabs::TAB_RAMP_RUN;
use super::{ProfileOptions, TabShape};
use crate::geom::Point3;
use crate::toolpath::Move;

/// Z components along a loop: the base (level, or ramp) and the lifts.
pub(super) struct ZProfile<'a> {
    /// The level's depth, mm.
    pub(super) z: f64,
    /// Ramp: (from arc length, over length, from z); `None`: flat at `z`.
    pub(super) ramp: Option<(f64, f64, f64)>,
    /// The tabs' lifts: (centre arc length, half length, top z).
    pub(super) lifts: &'a [(f64, f64, f64)],
    /// The tabs' shape.
    pub(super) shape: TabShape,
    /// The stock's bottom, mm (the ramps' foot).
    pub(super) bottom_z: f64,
    /// The loop's length, mm.
    pub(super) len: f64,
}

impl ZProfile<'_> {
    /// The level's height at `s`: `z`, or on the ramp the line down to it.
    pub(super) fn base(&self, s: f64) -> f64 {
        match self.ramp {
            Some((a, l, z0)) if l > 0.0 => self.z.max(z0 + (self.z - z0) * ((s - a) / l)),
            _ => self.z,
        }
    }

    /// The highest tab at `s`, in the region that `mid` (a point inside the piece) is in.
    pub(super) fn tab(&self, s: f64, mid: f64) -> f64 {
        let mut out = f64::NEG_INFINITY;
        for &(c, h, top) in self.lifts {
            if top <= self.z {
                continue;
            }
            let off =
                |x: f64| ((x - c + 0.5 * self.len).rem_euclid(self.len) - 0.5 * self.len).abs();
            let (dm, ds) = (off(mid), off(s));
            let v = match self.shape {
                TabShape::Square if dm < h => top,
                TabShape::Ramped if dm <= h => top,
                TabShape::Ramped if dm < h + TAB_RAMP_RUN * (top - self.bottom_z) => {
                    top - (ds - h) / TAB_RAMP_RUN
                }
                _ => continue,
            };
            out = out.max(v);
        }
        out
    }

    fn breaks(&self, a: f64, b: f64) -> Vec<f64> {
        let mut v = vec![a, b];
        if let Some((s0, l, _)) = self.ramp {
            v.push(s0 + l);
        }
        for &(c, h, top) in self.lifts.iter().filter(|l| l.2 > self.z) {
            let mut ends = vec![h];
            if self.shape == TabShape::Ramped {
                ends.push(h + TAB_RAMP_RUN * (top - self.bottom_z));
            }
            for e in ends {
                for shift in [-self.len, 0.0, self.len] {
                    v.extend([c - e + shift, c + e + shift]);
                }
            }
        }
        v.retain(|s| *s >= a && *s <= b);
        v.sort_by(f64::total_cmp);
        v.dedup_by(|x, y| (*x - *y).abs() <= 1e-9);
        v
    }
}

/// Appends the moves along `lp` from arc length `a` to `b` (`0 ≤ a < b ≤ len`), heights as
/// `zp` says; `at` is the tool's position, updated.
pub(super) fn along(
    lp: &Loop,
    a: f64,
    b: f64,
    zp: &ZProfile<'_>,
    opts: &ProfileOptions,
    at: &mut Point3,
    out: &mut Vec<Move>,
) {
    let mut ks = zp.breaks(a, b);
    ks.extend(lp.starts.iter().copied().filter(|s| *s > a && *s < b));
    ks.sort_by(f64::total_cmp);
    ks.dedup_by(|x, y| (*x - *y).abs() <= 1e-9);
    let mut pieces: Vec<(f64, f64)> = Vec::new();
    for w in ks.windows(2) {
        let (s0, s1) = (w[0], w[1]);
        let mid = 0.5 * (s0 + s1);
        // Split where the ramp crosses a tab (the higher of the two changes there).
        let g = |s: f64| zp.base(s) - zp.tab(s, mid);
        let (g0, g1) = (g(s0), g(s1));
        if g0.is_finite() && g1.is_finite() && g0 * g1 < 0.0 {
            let x = s0 + (s1 - s0) * g0 / (g0 - g1);
            pieces.push((s0, x));
            pieces.push((x, s1));
        } else {
            pieces.push((s0, s1));
        }
    }
    for (s0, s1) in pieces {
        if s1 - s0 <= 1e-9 {
            continue;
        }
        let mid = 0.5 * (s0 + s1);
        let z = |s: f64| zp.base(s).max(zp.tab(s, mid));
        let (z0, z1) = (z(s0), z(s1));
        if (at.z - z0).abs() > 1e-12 {
            let feed = if z0 < at.z {
                opts.plunge_feed
            } else {
                opts.feed
            };
            *at = Point3::from_xy(at.xy(), z0);
            out.push(Move::line(*at, feed));
        }
        let (i, _) = lp.locate(mid);
        let e = &lp.elems[i];
        let len = e.length();
        let f1 = if len > 0.0 {
            ((s1 - lp.starts[i]) / len).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let end = if f1 >= 1.0 { e.end } else { e.at(f1) };
        let to = Point3::from_xy(end, z1);
        let m = match e.center {
            Some(c) => Move::arc_xy(to, Point3::from_xy(c, z1), e.ccw, opts.feed),
            None => Move::line(to, opts.feed),
        };
        out.push(m.with_tag(i as u32, f1));
        *at = to;
    }
}
