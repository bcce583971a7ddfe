//! Where a profile's cuts run and where its tabs may stand: the offset loops of an outline
//! (around the piece, and around a bay whose mouth is narrower than the tool), the walls of
//! the other targets, and the rule that keeps a tab's bridge clear of every other cut.
//!
//! A tab stands on the stretch of the outline whose offset at the finishing and the roughing
//! distance lies on a loop around the piece (never in a bay: the bay's stock is cut off from
//! the rest by the slot across its mouth, and holds nothing), and where no other target's
//! slot (`d + r + m` from its wall, plus half the bridge's sampling step) nor an entry's disc
//! made so far reaches its bridge (`bridges` module docs). [`TabPlan::place`] applies it
//! with `strategy::profile::tabs`' spacing rules; `generate` and [`super::tab_counts`] share it,
//! so that a job's starting file sizes its tabs by the rule its profile is planned with.

use super::bridges::{self, Bridge, Entry};
use super::elements::Loop;
use super::tabs::{self, Tab};
use super::{ProfileOptions, ProfileSide, ProfileTarget};
use crate::geom::{Outline, Point, Winding};

/// The offset loops of `outline` on `side` at distance `d`, counter-clockwise.
pub(super) fn offset_loops(outline: &Outline, side: ProfileSide, d: f64) -> Vec<Loop> {
    let ccw = outline.clone().with_winding(Winding::CounterClockwise);
    let raw = match side {
        ProfileSide::Inside => ccw.offset(d),
        ProfileSide::Outside => ccw.offset(-d),
        ProfileSide::On => vec![ccw],
    };
    // Outside, a loop running clockwise rings a bay of the outline whose mouth is narrower
    // than the tool: cut as well, where the tool fits in it.
    raw.iter()
        .map(Loop::of_outline)
        .filter(|l| l.elems.len() >= 2 && (l.signed_area() > 0.0 || side == ProfileSide::Outside))
        .collect()
}

/// The loops of [`offset_loops`] around the piece (no bay's).
pub(super) fn outer_loops(outline: &Outline, side: ProfileSide, d: f64) -> Vec<Loop> {
    let mut v = offset_loops(outline, side, d);
    v.retain(|l| l.signed_area() > 0.0);
    v
}

/// The loop's tab lifts at offset `d`: each tab whose path point lies on this loop (within
/// what a run's inside corner cuts the path back, [`Tab::off_path`]).
pub(super) fn lifts_on(lp: &Loop, tabs: &[Tab], d: f64) -> Vec<(f64, f64, f64)> {
    let eps = 1e-6 * (1.0 + d);
    tabs.iter()
        .filter_map(|t| {
            let q = t.placed.at + t.free_normal * d;
            let (s, dist) = lp.project(q);
            (dist <= eps + t.off_path(d)).then(|| (s, t.half_lift(d), t.placed.top_z))
        })
        .collect()
}

/// The walls of every target cut outside or inside: what the tool must keep clear of.
pub(super) struct Walls<'a> {
    all: Vec<(usize, &'a Outline, ProfileSide)>,
}

impl<'a> Walls<'a> {
    pub(super) fn new(targets: &'a [ProfileTarget]) -> Self {
        let all = targets
            .iter()
            .enumerate()
            .filter(|(_, t)| t.side != ProfileSide::On)
            .map(|(i, t)| (i, &t.outline, t.side))
            .collect();
        Walls { all }
    }

    /// Inside more parts than holes: the part's material.
    pub(super) fn material(&self, p: Point) -> bool {
        let count = |s: ProfileSide| {
            self.all
                .iter()
                .filter(|(_, o, side)| *side == s && o.contains(p))
                .count()
        };
        count(ProfileSide::Outside) > count(ProfileSide::Inside)
    }

    /// Least distance from `p` to a wall other than target `own`'s, among the targets
    /// `counted` (indexed by target) lets in.
    pub(super) fn others(&self, own: usize, p: Point, counted: &[bool]) -> f64 {
        self.all
            .iter()
            .filter(|(i, _, _)| *i != own && counted.get(*i).copied().unwrap_or(true))
            .map(|(_, o, _)| o.distance_to(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The walls of the targets `counted` lets in, other than `own`'s, within `within` of `p`.
    pub(super) fn near_others(
        &self,
        own: usize,
        p: Point,
        within: f64,
        counted: &[bool],
    ) -> Vec<&'a Outline> {
        self.all
            .iter()
            .filter(|(i, _, _)| *i != own && counted.get(*i).copied().unwrap_or(true))
            .filter(|(_, o, _)| o.distance_to(p) < within)
            .map(|(_, o, _)| *o)
            .collect()
    }

    /// True when every point lies on target `own`'s free side, out of the material, and keeps
    /// `d` from every wall.
    pub(super) fn clear(
        &self,
        own: (usize, &Outline, ProfileSide),
        d: f64,
        pts: impl IntoIterator<Item = Point>,
    ) -> bool {
        let (i, outline, side) = own;
        pts.into_iter().all(|p| {
            let free = match side {
                ProfileSide::Inside => outline.contains(p),
                ProfileSide::Outside => !outline.contains(p),
                ProfileSide::On => true,
            };
            free && !self.material(p)
                && (side == ProfileSide::On || outline.distance_to(p) >= d - 1e-9)
                && self.others(i, p, &[]) >= d - 1e-9
        })
    }
}

/// The targets and the rule their tabs are placed by (module docs).
pub(super) struct TabPlan<'a> {
    targets: &'a [ProfileTarget],
    /// Every target's walls.
    pub walls: Walls<'a>,
    /// The targets the tool fits in (at the rough and the finishing offset): only their cuts
    /// can take a tab away; an outline too small for the tool (a hole left for a drill) is
    /// not cut at all and keeps no tab from its neighbour.
    cut: Vec<bool>,
    r: f64,
    m: f64,
    opts: &'a ProfileOptions,
}

impl<'a> TabPlan<'a> {
    /// The plan for `targets` cut by a tool of radius `r`, with the tests' slack `m`.
    pub(super) fn new(
        targets: &'a [ProfileTarget],
        r: f64,
        m: f64,
        opts: &'a ProfileOptions,
    ) -> Self {
        let cut = targets
            .iter()
            .map(|t| {
                if t.side == ProfileSide::On {
                    return true;
                }
                let d_fin = r + 0.5 * opts.tolerance;
                [d_fin, d_fin + opts.stock_to_leave]
                    .iter()
                    .all(|&d| !offset_loops(&t.outline, t.side, d).is_empty())
            })
            .collect();
        TabPlan {
            targets,
            walls: Walls::new(targets),
            cut,
            r,
            m,
            opts,
        }
    }

    /// The tabs of target `ti` cut at the finishing and roughing distances `d_fin`,
    /// `d_rough`, clear of the `entries` made so far, and the count asked for.
    pub(super) fn place(
        &self,
        ti: usize,
        d_fin: f64,
        d_rough: f64,
        entries: &[Entry],
    ) -> (Vec<Tab>, usize) {
        let (r, m, opts) = (self.r, self.m, self.opts);
        let t = &self.targets[ti];
        let side = t.side;
        let drawn = Loop::of_outline(&t.outline);
        let tab_top = opts.bottom_z() + opts.tabs.height;
        let walls = &self.walls;
        let cut = &self.cut;
        // Only where no other outline's slot, nor an entry made so far, reaches the
        // tab's bridge (`bridges` module docs).
        let slot = d_rough + r + m + 0.5 * bridges::SAMPLE;
        let far = d_rough + r + m;
        // Only on the loops around the piece: a bay of the outline closed off by a
        // mouth narrower than the tool holds no stock to hold it to.
        let outer: Vec<Loop> = [d_fin, d_rough]
            .iter()
            .flat_map(|&d| outer_loops(&t.outline, side, d))
            .collect();
        let keep = |tab: &Tab| -> bool {
            if ![d_fin, d_rough].iter().all(|&d| {
                outer
                    .iter()
                    .any(|l| !lifts_on(l, std::slice::from_ref(tab), d).is_empty())
            }) {
                return false;
            }
            let (at, w) = (tab.placed.at, tab.placed.width);
            let within = 0.5 * w + far;
            let near: Vec<&Outline> = walls.near_others(ti, at, within + slot, cut);
            let entered = entries
                .iter()
                .any(|&(c, rad): &Entry| c.distance(at) < within + rad);
            if near.is_empty() && !entered {
                return true;
            }
            let b = Bridge::of(ti, tab, &drawn, d_rough, r, m);
            near.iter().all(|o| b.distance_to_outline(o) >= slot)
                && bridges::clear_of_entries(&b, entries)
        };
        let (v, asked) = tabs::place(
            ti,
            &t.outline,
            side,
            d_fin,
            r,
            &opts.tabs,
            (tab_top, opts.bottom_z()),
            Some(&keep),
        );
        (v, asked)
    }
}
