//! A tab's bridge, and what the profile's other cuts may not reach of it.
//!
//! # The bridge
//! A tab of width `w` centred at arc length `s` of its outline is the material the tool leaves
//! across its slot: the outline's stretch `[s − w/2, s + w/2]` swept from the outline out to
//! `D = d + r + m` on the free side (`d` the finishing offset, `r` the tool radius, `m` the
//! margin below), that is the slot and a strip `m` wide of the material beyond its far wall,
//! which joins the tab to the stock. It is held as a polygon: the outline's stretch sampled
//! every `h` ([`SAMPLE`]) and the same points moved `D` along the outline's normal there
//! (tabs sit on lines, long arcs and runs of lines bending [`super::tabs::BEND_MAX`] at most,
//! so the moved points do not fold over).
//!
//! # What may not reach it
//! Another outline's slot is the band of its free side within `d' + r` of it (`d'` its
//! roughing offset): a tab is kept only where every point of its bridge lies farther than
//! `d' + r + m + h/2` from every other outline the profile cuts (the distance is sampled along
//! the bridge's boundary every `h`, and the nearest point of a region to a curve outside it
//! lies on its boundary, within `h/2` of a sample). Nearness alone does not matter: material
//! between the slots leaves the bridge standing.
//!
//! Another loop's lead arcs of radius `ρ` lie within `2ρ` of the loop's start `v`, and its
//! helix of radius `ρ_h` within `ρ_h` of its centre `c`: an entry is a disc (`v`, `2ρ + r +
//! m`) and (`c`, `ρ_h + r + m`) the tool sweeps, and a bridge keeps out of every disc of the
//! others' entries (a later loop's lead is shortened, its helix becomes a ramp; a later tab is
//! left out).
//!
//! `m` ([`margin`]) is the tool's tolerance scale (`toolpath::tolerance_scale`, 1 mm for
//! tools up to the reference diameter), at most the tool's diameter: the strip of frame a
//! bridge must keep, and the slack on every test. Below 1 mm the strip is as wide as the
//! slot: a 0.34 mm end mill cuts letters drawn 0.7 mm apart, and a 1 mm strip would keep
//! every tab off them.

use super::elements::Loop;
use super::tabs::Tab;
use crate::geom::{Outline, Point};

/// Spacing of the samples along a bridge's boundary, mm.
pub(super) const SAMPLE: f64 = 0.25;

/// The margin `m` of a tool of radius `r` (module docs), mm.
pub(super) fn margin(r: f64) -> f64 {
    crate::toolpath::tolerance_scale(2.0 * r).min(2.0 * r)
}

/// The material a placed tab leaves across its slot (module docs).
pub(super) struct Bridge {
    /// The target the tab holds.
    pub target: usize,
    /// The bridge's boundary, sampled every [`SAMPLE`] at most.
    boundary: Vec<Point>,
    /// The same as a closed outline (for inside tests and exact distances).
    region: Option<Outline>,
}

impl Bridge {
    /// The bridge of `tab` on its drawn outline `drawn`, cut at offset `d` by a tool of radius
    /// `r`, reaching `m` beyond the slot's far wall.
    pub fn of(target: usize, tab: &Tab, drawn: &Loop, d: f64, r: f64, m: f64) -> Bridge {
        let (s, w) = (tab.placed.s, tab.placed.width);
        let left = tab.free_normal.dot(drawn.tangent(s).perp()) > 0.0;
        let far = d + r + m;
        let n = ((w / SAMPLE).ceil() as usize).max(2);
        let mut inner = Vec::with_capacity(n + 1);
        let mut outer = Vec::with_capacity(n + 1);
        for k in 0..=n {
            let sk = s - 0.5 * w + w * k as f64 / n as f64;
            let t = drawn.tangent(sk);
            let nrm = if left { t.perp() } else { -t.perp() };
            let p = drawn.point(sk);
            inner.push(p);
            outer.push(p + nrm * far);
        }
        let ends = ((far / SAMPLE).ceil() as usize).max(1);
        let mut boundary = inner.clone();
        boundary.extend(outer.iter().copied());
        for (a, b) in [(inner[0], outer[0]), (inner[n], outer[n])] {
            boundary.extend((1..ends).map(|k| a + (b - a) * (k as f64 / ends as f64)));
        }
        let mut ring = inner;
        ring.extend(outer.into_iter().rev());
        let region = Outline::from_points(&ring, "a tab's bridge").ok();
        Bridge {
            target,
            boundary,
            region,
        }
    }

    /// Least distance from `p` to the bridge, mm: 0 inside it. Without a region (a bridge
    /// too small to make one), the distance to its nearest boundary sample less the spacing.
    pub fn distance(&self, p: Point) -> f64 {
        match &self.region {
            Some(o) if o.contains(p) => 0.0,
            Some(o) => o.distance_to(p),
            None => {
                self.boundary
                    .iter()
                    .map(|q| q.distance(p))
                    .fold(f64::INFINITY, f64::min)
                    - SAMPLE
            }
        }
    }

    /// Least distance from the bridge to `outline` (sampled: within [`SAMPLE`]` / 2` above the
    /// exact one for an outline outside the bridge), mm.
    pub fn distance_to_outline(&self, outline: &Outline) -> f64 {
        self.boundary
            .iter()
            .map(|&q| outline.distance_to(q))
            .fold(f64::INFINITY, f64::min)
    }
}

/// The discs the tool sweeps entering a loop: (centre, radius), the tool's radius included.
pub(super) type Entry = (Point, f64);

/// True when no disc of `entries` reaches `bridge`.
pub(super) fn clear_of_entries(bridge: &Bridge, entries: &[Entry]) -> bool {
    entries.iter().all(|&(c, rad)| bridge.distance(c) >= rad)
}

/// True when the disc (`c`, `rad`) reaches no bridge of `bridges` but those of target `own`.
pub(super) fn entry_clear(bridges: &[Bridge], own: usize, c: Point, rad: f64) -> bool {
    bridges
        .iter()
        .filter(|b| b.target != own)
        .all(|b| b.distance(c) >= rad)
}
