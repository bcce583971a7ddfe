//! Holding tabs: where on a drawn outline they go.
//!
//! # Where a tab may sit
//! A tab of top width `w` centred at arc length `s` of the outline is the material the tool
//! leaves where it lifts: on the path beside a line the tool is lifted over `w/2 + r` either
//! side of the tab's centre (`r` the tool radius), so the material left at every depth of the
//! slot is `w` wide. Beside an arc of radius `R` the path is the concentric arc of radius
//! `R_p = R ± d` (`d` the offset; `+` where the path runs on the arc's outer side), and the
//! tool disc clears a radial face of the tab once its centre is `asin(r/R_p)` away in angle,
//! so the lift spans `R_p·(w/(2R) + asin(r/R_p))` of path either side. A tab is placed only
//! where that whole span lies on one element of the outline (a line, or an arc with
//! `R_p ≥ 2r` long enough), away from its ends by `0.05` mm plus, at a corner that cuts the
//! path back (the path on the inside of the turn), `d·tan(|τ|/2)` for a turn of `τ`: never on
//! a corner nor on a short or tight arc.
//!
//! A curve drawn as short lines (a spline flattened, a gear of LINEs) has no line long
//! enough on its own, so a tab may also sit across gentle corners: over a run of lines
//! whose turns within `h` of its centre add up to a bend `β ≤` [`BEND_MAX`] (30°), where
//! `h = w/2 + d·B + r/cos(B/2) + 2d·tan(B/2) + 0.05` with `B = BEND_MAX` bounds the outline
//! the lift can reach. The tool is lifted over `w/2 + d·β + r/cos(β/2)` of path either side:
//! the tab's middle line (its stretch of outline moved `d`) runs at most `d·β` longer on the
//! path than on the outline (the corner arcs), and beyond its end the path's chord is at
//! least `cos(β/2)` of its length, so the tool stays a radius off the tab's ends; inside
//! turns shorten the path by at most `2d·tan(β/2)`, which `h` allows for.
//!
//! A ramped tab's ramps (`TAB_RAMP_RUN·h` of path either side of the lift, `h` the tab's
//! height) on a run stay within its reach: `h` above grows by them. On one element they may
//! run on past its end only where the outline turns outside within their run (a corner the
//! path goes round on an arc, which measured along the outline adds nothing): at an inside
//! corner of turn `τ` the path is cut back, and measured along the outline the material its
//! ramps leave stretches by `2d·tan(τ/2)` per corner, beyond what a tab's bridge may be (a
//! gear's straight root between two flanks: the bridge would fill the root from flank to
//! flank). Where the outline turns inside (a corner, or an arc whose centre lies on the free
//! side with `R_p < 2r`, too tight for a tab) within `TAB_RAMP_RUN·h + 0.05` of an end, the ramp stays on the element: the
//! stretch keeps that much more from the end (on an arc, the ramp's run times `R/R_p`).
//!
//! # On the tool's path
//! The tool's path is the outline's offset at `d` with the loops that would gouge trimmed:
//! along a bay narrower than the tool it cuts across the mouth, far from the outline, and
//! leaves the bay uncut. A tab there has no lift on the path (and no bridge of its own), so
//! a tab is placed only where the path runs along its stretch of outline: at `2·8 + 1`
//! samples over its lift and ramps (the path's half lift and ramp, in outline length on an
//! arc), the point `d` off the outline on the free side lies no nearer than
//! `d·cos β` to the outline (`β` its run's bend, 0 on one element; `1e-6·(1 + d)` allowed):
//! the tool centred there touches the outline only at the foot of that point.
//!
//! # Even spacing
//! With the perimeter `P` and `N` tabs the ideal places are `φ + kP/N`. Each is slid to the
//! nearest allowed place (arc length, cyclically); the phase `φ` minimises the sum of the
//! squared slides over the candidates that put one ideal place on the middle or an end of an
//! allowed stretch, then (among equal slides) the sum of the squared distances of the tabs
//! from the middles of their stretches. The candidates and the costs depend only on the outline's shape, not on
//! where it starts, which way it runs or where it lies, so the tabs move with the outline
//! (ties, which only symmetric outlines have, go to the lowest, then leftmost, first tab).
//! Tabs whose lifts and ramps would come within `r` of each other (by arc length along the
//! outline, path lengths on an arc whose centre lies on the free side counted `R/R_p` times:
//! there the path is the shorter) are dropped (a note says how many fit): between two tabs the tool runs on the
//! floor, so that they stand as two bridges. Else their ramps meet above the floor (one
//! bridge for two tabs); and the path between two tabs is shorter than the outline where it
//! turns inside, by `d·θ` for a turn `θ`, which the `r` covers up to a radian.
//!
//! # Where the other cuts allow a tab
//! A profile passes a test of a tab (its bridge clear of the other outlines' slots and
//! entries, the `bridges` module): each stretch is sampled every `w/2` and cut to the runs of
//! samples the test accepts before the places are chosen, and each tab placed is tested
//! again, so a tab beside another part's cut slides along its outline to where solid
//! material is left between the slots.
//!
//! # Count
//! [`auto_tab_count`]: one tab per started 150 mm of perimeter, at least 2 and at most 16.

use super::elements::{Loop, tangent_at};
use super::{PlacedTab, ProfileSide, TabCount, TabOptions, TabShape};
use crate::geom::Outline;

/// The most tabs per outline.
pub const MAX_TABS: usize = 1000;

/// Perimeter per automatic tab, mm.
pub const PERIMETER_PER_TAB: f64 = 150.0;

/// Distance kept between a tab's lift and the end of its element, mm.
const GUARD: f64 = 0.05;

/// A ramped tab's ramps run this far along the path per unit of height (a 1-in-2 ramp,
/// 26.6°): shallower than the 45° beyond which a flat end mill's way down is a plunge.
pub const TAB_RAMP_RUN: f64 = 2.0;

/// The most a run of lines may turn under a tab and its lift, rad (module docs).
pub const BEND_MAX: f64 = std::f64::consts::PI / 6.0;

/// The tab count `auto` gives an outline of `perimeter` mm: `⌈P / 150⌉`, from 2 to 16.
pub fn auto_tab_count(perimeter: f64) -> usize {
    ((perimeter / PERIMETER_PER_TAB).ceil().max(0.0) as usize).clamp(2, 16)
}

/// Where the tabs of `outline` cut on `side` at offset `d` from it by a tool of radius `r`
/// go (module docs), and the count asked: the places alone, before a profile leaves out
/// those that another cut, or the outline's own across a narrow channel, passes near (so at
/// most what [`super::generate`] places). For choosing a tab width that fits.
pub fn tab_places(
    outline: &Outline,
    side: ProfileSide,
    d: f64,
    r: f64,
    opts: &TabOptions,
) -> (Vec<PlacedTab>, usize) {
    let (tabs, asked) = place(0, outline, side, d, r, opts, (0.0, 0.0), None);
    (tabs.into_iter().map(|t| t.placed).collect(), asked)
}

/// A tab and its lift on the path.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tab {
    /// The tab.
    pub placed: PlacedTab,
    /// The unit normal at the tab's centre towards the free side.
    pub free_normal: crate::geom::Vec2,
    /// On an arc: its radius and whether its centre lies on the free side.
    arc: Option<(f64, bool)>,
    /// On a run of lines: the sum of the turns its lift may reach, rad (0 on one line).
    bend: f64,
    /// The tool radius, mm.
    r: f64,
}

impl Tab {
    /// How far the tab's point moved `d` along its normal may lie off the path at offset
    /// `d`, mm: nothing on one line or arc; across a run's inside corner, the path is cut
    /// back there by at most `d·tan(β/2)` from that point.
    pub fn off_path(&self, d: f64) -> f64 {
        d * (0.5 * self.bend).tan()
    }

    /// Half the length of the path at offset `d` that the tool lifts over, mm (module docs).
    pub fn half_lift(&self, d: f64) -> f64 {
        let (w, r) = (self.placed.width, self.r);
        match self.arc {
            None => 0.5 * w + d * self.bend + r / (0.5 * self.bend).cos(),
            Some((rad, centre_free)) => {
                let rp = if centre_free { rad - d } else { rad + d };
                rp * (0.5 * w / rad + (r / rp).min(1.0).asin())
            }
        }
    }
}

/// A layout of the tabs: the sum of the squared slides, the sum of the squared distances
/// from the stretches' middles, and each tab's place and stretch.
type Layout = (f64, f64, Vec<(f64, usize)>);

/// Where an element allows a tab's centre: arc lengths `[lo, hi]` and the half lift there.
#[derive(Clone, Copy)]
struct Stretch {
    lo: f64,
    hi: f64,
    half_lift: f64,
    arc: Option<(f64, bool)>,
    bend: f64,
}

/// The tabs of `outline` cut on `side` at offset `d` by a tool of radius `r`, or the count
/// asked and placed when fewer fit; with `keep`, only tabs it accepts (module docs).
#[allow(clippy::too_many_arguments)] // the outline, its cut, the tab options and the filter
pub(crate) fn place(
    target: usize,
    outline: &Outline,
    side: ProfileSide,
    d: f64,
    r: f64,
    opts: &TabOptions,
    (top_z, bottom_z): (f64, f64),
    keep: Option<&dyn Fn(&Tab) -> bool>,
) -> (Vec<Tab>, usize) {
    let lp = Loop::of_outline(outline);
    let p = lp.length;
    let asked = match opts.count {
        TabCount::None => 0,
        TabCount::Count(n) => n,
        TabCount::Auto => auto_tab_count(p),
    };
    if asked == 0 || side == ProfileSide::On {
        return (Vec::new(), asked);
    }
    let ccw = lp.signed_area() > 0.0;
    // The free side is left of the outline's travel for a hole drawn counter-clockwise and
    // for a part drawn clockwise.
    let free_left = match side {
        ProfileSide::Inside => ccw,
        _ => !ccw,
    };
    let w = opts.width;
    let n = lp.elems.len();
    let turn = |k: usize| {
        let a = tangent_at(&lp.elems[(k + n - 1) % n], 1.0);
        let b = tangent_at(&lp.elems[k], 0.0);
        a.cross(b).atan2(a.dot(b))
    };
    let cutback = |tau: f64| {
        if tau.abs() > 1e-9 && (tau > 0.0) == free_left {
            if tau.abs() >= std::f64::consts::PI - 1e-6 {
                f64::INFINITY
            } else {
                d * (0.5 * tau.abs()).tan()
            }
        } else {
            0.0
        }
    };
    // A ramped tab's ramps run `TAB_RAMP_RUN·h` of path beyond its lift (module docs).
    let ramp = if opts.shape == TabShape::Ramped {
        TAB_RAMP_RUN * opts.height
    } else {
        0.0
    };
    // The outline turns inside at the start of element `k`, or along it (an arc whose centre
    // lies on the free side, too tight for a tab: its path's radius under `2r`).
    let inside_corner = |k: usize| cutback(turn(k)) > 0.0;
    let inside_arc = |k: usize| {
        let e = &lp.elems[k];
        e.center
            .is_some_and(|c| e.ccw == free_left && (e.start - c).length() - d < 2.0 * r)
    };
    // Within a ramp's run past the end (`forward`) or the start of element `k`, the
    // outline turns inside (module docs).
    let inside_near = |k: usize, forward: bool| -> bool {
        let (mut j, mut run) = (k, 0.0);
        for _ in 0..n {
            if inside_corner(if forward { (j + 1) % n } else { j }) {
                return true;
            }
            j = if forward {
                (j + 1) % n
            } else {
                (j + n - 1) % n
            };
            if inside_arc(j) {
                return true;
            }
            run += lp.elems[j].length();
            if run >= ramp + GUARD {
                break;
            }
        }
        false
    };
    let mut stretches = Vec::new();
    for (k, e) in lp.elems.iter().enumerate() {
        let len = e.length();
        // Outline per unit of path along the element.
        let mut per_path = 1.0;
        let (half_outline, half_lift, arc) = match e.center {
            None => (0.5 * w + r, 0.5 * w + r, None),
            Some(c) => {
                let rad = (e.start - c).length();
                // The centre lies on the free side when the arc turns towards it.
                let centre_free = e.ccw == free_left;
                let rp = if centre_free { rad - d } else { rad + d };
                if !(rp >= 2.0 * r && rp > 0.0) {
                    continue;
                }
                let phi = (r / rp).asin();
                let ang = 0.5 * w / rad + phi;
                per_path = rad / rp;
                (rad * ang, rp * ang, Some((rad, centre_free)))
            }
        };
        // A ramped tab's ramps stay on the element where the outline turns inside near it.
        let ramp_on = |forward: bool| {
            if ramp > 0.0 && inside_near(k, forward) {
                ramp * per_path
            } else {
                0.0
            }
        };
        let lo = lp.starts[k] + half_outline + GUARD + cutback(turn(k)) + ramp_on(false);
        let hi =
            lp.starts[k] + len - half_outline - GUARD - cutback(turn((k + 1) % n)) - ramp_on(true);
        if hi >= lo {
            stretches.push(Stretch {
                lo,
                hi,
                half_lift,
                arc,
                bend: 0.0,
            });
        }
    }
    stretches.extend(run_stretches(&lp, w, d, r, ramp, &turn));
    let make = |s: f64, st: &Stretch| {
        let t = lp.tangent(s);
        Tab {
            placed: PlacedTab {
                target,
                s,
                at: lp.point(s),
                width: w,
                top_z,
                bottom_z,
            },
            free_normal: if free_left { t.perp() } else { -t.perp() },
            arc: st.arc,
            bend: st.bend,
            r,
        }
    };
    // On the tool's path, and where `keep` accepts it (module docs).
    let on_path = |t: &Tab| -> bool {
        let span = match t.arc {
            None => t.half_lift(d) + ramp,
            Some((rad, centre_free)) => {
                let rp = if centre_free { rad - d } else { rad + d };
                (t.half_lift(d) + ramp) * rad / rp
            }
        };
        let least = d * t.bend.cos() - 1e-6 * (1.0 + d);
        (-ON_PATH_SAMPLES..=ON_PATH_SAMPLES).all(|k| {
            let sk = t.placed.s + span * k as f64 / ON_PATH_SAMPLES as f64;
            let tn = lp.tangent(sk);
            let q = lp.point(sk) + if free_left { tn.perp() } else { -tn.perp() } * d;
            !lp.nearer_than(q, least)
        })
    };
    let wanted = |t: &Tab| on_path(t) && keep.is_none_or(|k| k(t));
    stretches = accepted(stretches, w, &|s, st| wanted(&make(s, st)));
    if stretches.is_empty() {
        return (Vec::new(), asked);
    }
    let gap = p / asked as f64;
    // The nearest allowed place to `s` (cyclically): (place, stretch index, slide).
    let nearest = |s: f64| -> (f64, usize, f64) {
        let mut best = (s, 0, f64::INFINITY);
        for (j, st) in stretches.iter().enumerate() {
            for shift in [-p, 0.0, p] {
                let q = s.clamp(st.lo + shift, st.hi + shift);
                let slide = (q - s).abs();
                if slide < best.2 {
                    best = (q.rem_euclid(p), j, slide);
                }
            }
        }
        best
    };
    let mut phases = Vec::new();
    for st in &stretches {
        for s in [st.lo, 0.5 * (st.lo + st.hi), st.hi] {
            phases.push(s.rem_euclid(gap));
        }
    }
    // (sum of squared slides, sum of squared distances from the stretches' middles, places)
    let layout = |phi: f64| -> Layout {
        let (mut cost, mut centre) = (0.0, 0.0);
        let mut out = Vec::with_capacity(asked);
        for k in 0..asked {
            let (q, j, slide) = nearest(phi + k as f64 * gap);
            cost += slide * slide;
            let st = &stretches[j];
            let off = (q - 0.5 * (st.lo + st.hi) + 0.5 * p).rem_euclid(p) - 0.5 * p;
            centre += off * off;
            out.push((q, j));
        }
        (cost, centre, out)
    };
    // The lowest, then leftmost, tab of a layout (to break ties between equal costs).
    let key = |v: &[(f64, usize)]| {
        v.iter()
            .map(|(s, _)| lp.point(*s))
            .min_by(|a, b| a.y.total_cmp(&b.y).then(a.x.total_cmp(&b.x)))
            .map_or((0.0, 0.0), |q| (q.y, q.x))
    };
    let mut best: Option<Layout> = None;
    let tol = 1e-9 * p.max(1.0) * p.max(1.0);
    for phi in phases {
        let cand = layout(phi);
        let better = match &best {
            None => true,
            Some(b) if cand.0 < b.0 - tol => true,
            Some(b) if cand.0 > b.0 + tol => false,
            Some(b) if cand.1 < b.1 - tol => true,
            Some(b) if cand.1 > b.1 + tol => false,
            Some(b) => {
                let (x, y) = (key(&cand.2), key(&b.2));
                x.0 < y.0 - 1e-9 || ((x.0 - y.0).abs() <= 1e-9 && x.1 < y.1 - 1e-9)
            }
        };
        if better {
            best = Some(cand);
        }
    }
    let Some((_, _, mut chosen)) = best else {
        return (Vec::new(), asked);
    };
    chosen.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Drop tabs whose lifts and ramps would come within `r` of a kept one's (cyclically,
    // module docs). Lifts and ramps are lengths of path: on an arc whose centre lies on the
    // free side the path is shorter than the outline by `R_p/R`, so they count `R/R_p`
    // times along the outline there.
    let outline_per_path = |st: &Stretch| match st.arc {
        Some((rad, true)) if rad > d => rad / (rad - d),
        _ => 1.0,
    };
    let mut kept: Vec<(f64, usize)> = Vec::new();
    for c in chosen {
        let clash = |a: &(f64, usize), b: &(f64, usize)| {
            let gap_ab = (b.0 - a.0).rem_euclid(p).min((a.0 - b.0).rem_euclid(p));
            let (sa, sb) = (&stretches[a.1], &stretches[b.1]);
            let (ka, kb) = (outline_per_path(sa), outline_per_path(sb));
            gap_ab
                < (sa.half_lift + ramp + GUARD) * ka
                    + (sb.half_lift + ramp + GUARD) * kb
                    + r * ka.max(kb)
        };
        if kept.iter().all(|k| !clash(k, &c)) {
            kept.push(c);
        }
    }
    let tabs = kept
        .into_iter()
        .map(|(s, j)| make(s, &stretches[j]))
        .filter(|t| wanted(t))
        .collect();
    (tabs, asked)
}

/// Samples either side of a tab's centre on which its path is tested (module docs).
const ON_PATH_SAMPLES: i32 = 8;

/// The most samples [`accepted`] tests on one stretch.
const MAX_SAMPLES: usize = 2000;

/// The parts of `stretches` where `keep` accepts a tab of width `w`: each stretch sampled
/// every `w/2` (at most [`MAX_SAMPLES`] times) and cut to its runs of accepted samples, from
/// the first to the last of each run (a tab between two accepted samples is tested again
/// when placed).
fn accepted(stretches: Vec<Stretch>, w: f64, keep: &dyn Fn(f64, &Stretch) -> bool) -> Vec<Stretch> {
    let mut out = Vec::new();
    for st in stretches {
        let n = (((st.hi - st.lo) / (0.5 * w)).ceil() as usize).clamp(1, MAX_SAMPLES);
        let mut run: Option<(f64, f64)> = None;
        for k in 0..=n {
            let s = st.lo + (st.hi - st.lo) * k as f64 / n as f64;
            if keep(s, &st) {
                run = Some(run.map_or((s, s), |(a, _)| (a, s)));
            } else if let Some((lo, hi)) = run.take() {
                out.push(Stretch { lo, hi, ..st });
            }
        }
        if let Some((lo, hi)) = run {
            out.push(Stretch { lo, hi, ..st });
        }
    }
    out
}

/// The stretches across gentle corners of lines (module docs): the centres whose reach `h`
/// (with a ramped tab's `ramp`)
/// crosses at least one corner, only corners between two lines, turning `BEND_MAX` at most
/// in all; each interval of the same corners is one stretch with its own bend.
fn run_stretches(
    lp: &Loop,
    w: f64,
    d: f64,
    r: f64,
    ramp: f64,
    turn: &dyn Fn(usize) -> f64,
) -> Vec<Stretch> {
    let n = lp.elems.len();
    let p = lp.length;
    let b = BEND_MAX;
    let h = 0.5 * w + d * b + r / (0.5 * b).cos() + 2.0 * d * (0.5 * b).tan() + ramp + GUARD;
    if n < 2 || p <= 2.0 * h {
        return Vec::new();
    }
    // Each corner (the start of element k): its place and its weight, infinite where it
    // turns too far or joins an arc.
    let corner: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let lines = lp.elems[k].center.is_none() && lp.elems[(k + n - 1) % n].center.is_none();
            let t = turn(k).abs();
            (
                lp.starts[k],
                if lines && t <= b { t } else { f64::INFINITY },
            )
        })
        .collect();
    // The corners three times over (shifted by -p, 0, p), sorted by place.
    let all: Vec<(f64, f64)> = [-p, 0.0, p]
        .iter()
        .flat_map(|&sh| corner.iter().map(move |&(s, t)| (s + sh, t)))
        .collect();
    let mut cuts: Vec<f64> = corner
        .iter()
        .flat_map(|&(s, _)| [(s - h).rem_euclid(p), (s + h).rem_euclid(p)])
        .chain([0.0, p])
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    let mut out: Vec<Stretch> = Vec::new();
    for win in cuts.windows(2) {
        let (lo, hi) = (win[0], win[1]);
        if hi - lo < 1e-12 {
            continue;
        }
        let m = 0.5 * (lo + hi);
        let i0 = all.partition_point(|c| c.0 <= m - h);
        let i1 = all.partition_point(|c| c.0 < m + h);
        if i1 <= i0 {
            continue;
        }
        let bend: f64 = all[i0..i1].iter().map(|c| c.1).sum();
        if bend > b {
            continue;
        }
        let half_lift = 0.5 * w + d * bend + r / (0.5 * bend).cos();
        match out.last_mut() {
            Some(last) if (last.hi - lo).abs() < 1e-12 && (last.bend - bend).abs() < 1e-15 => {
                last.hi = hi;
            }
            _ => out.push(Stretch {
                lo,
                hi,
                half_lift,
                arc: None,
                bend,
            }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;

    #[test]
    fn auto_count_follows_the_perimeter() {
        assert_eq!(auto_tab_count(40.0), 2);
        assert_eq!(auto_tab_count(400.0), 3);
        assert_eq!(auto_tab_count(451.0), 4);
        assert_eq!(auto_tab_count(1e5), 16);
    }

    /// Four tabs on a 100 × 60 rectangle: each on a side, its lift clear of the corners.
    #[test]
    fn tabs_sit_on_the_sides_away_from_corners() {
        let o = Outline::from_points(
            &[
                Point::new(0.0, 0.0),
                Point::new(100.0, 0.0),
                Point::new(100.0, 60.0),
                Point::new(0.0, 60.0),
            ],
            "r",
        )
        .unwrap();
        let opts = TabOptions::default().with_count(TabCount::Count(4));
        let (tabs, asked) = place(
            0,
            &o,
            ProfileSide::Outside,
            3.0,
            3.0,
            &opts,
            (-4.0, -6.0),
            None,
        );
        assert_eq!((tabs.len(), asked), (4, 4));
        for t in &tabs {
            let a = t.placed.at;
            let off_x = a.x.min(100.0 - a.x);
            let off_y = a.y.min(60.0 - a.y);
            // On a side, at least half the width plus the tool radius from its corners.
            assert!(off_x.min(off_y) < 1e-9, "{a:?}");
            assert!(off_x.max(off_y) >= 3.0 + 3.0 + GUARD - 1e-9, "{a:?}");
        }
    }

    /// A circle drawn as 240 short lines (each 0.52 mm, shorter than any tab and its lift)
    /// gets the tabs asked for, across its gentle corners, each lift long enough for the
    /// corners its reach crosses (1.5° each) and clear of the next tab's.
    #[test]
    fn tabs_sit_across_gentle_corners_of_short_lines() {
        let k = 240;
        let pts: Vec<Point> = (0..k)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / k as f64;
                Point::new(20.0 * a.cos(), 20.0 * a.sin())
            })
            .collect();
        let o = Outline::from_points(&pts, "c").unwrap();
        let opts = TabOptions::default()
            .with_count(TabCount::Count(3))
            .with_width(2.0);
        let (tabs, asked) = place(
            0,
            &o,
            ProfileSide::Outside,
            1.5,
            1.5,
            &opts,
            (-4.0, -6.0),
            None,
        );
        assert_eq!((tabs.len(), asked), (3, 3));
        let side = 2.0 * 20.0 * (std::f64::consts::PI / k as f64).sin();
        let per_corner = std::f64::consts::TAU / k as f64;
        for t in &tabs {
            // The outline the lift may reach holds at most this many corners.
            let reach = 2.0 * (1.0 + 1.5 * BEND_MAX + 1.5 / (0.5 * BEND_MAX).cos())
                + 4.0 * 1.5 * (0.5 * BEND_MAX).tan()
                + 2.0 * GUARD;
            let corners = (reach / side).ceil() + 1.0;
            assert!(
                t.bend > 0.0 && t.bend <= corners * per_corner + 1e-9,
                "{}",
                t.bend
            );
            // The lift spans the tab and a radius either side, plus the corner arcs.
            assert!(t.half_lift(1.5) >= 1.0 + 1.5 + 1.5 * t.bend - 1e-9);
            assert!(t.half_lift(1.5) <= 1.0 + 1.5 + 1.5 * t.bend + 0.1);
            assert!((t.placed.at.distance(Point::ORIGIN) - 20.0).abs() < 0.01);
        }
    }

    /// Inside a round hole the path (radius `R − d`) is shorter than the outline: two tabs
    /// whose lifts and ramps clear each other along the outline can overlap along the path
    /// and stand as one bridge. Measured on the path (angles about the centre times its
    /// radius, not the placement's arc lengths), every two tabs kept stand at least their
    /// half lifts, ramps and a tool radius apart.
    #[test]
    fn tabs_in_a_hole_stand_apart_along_the_shorter_path() {
        let mut pairs = 0;
        for (rad, r) in [(5.0, 1.0), (8.0, 2.0), (20.0, 3.0)] {
            let o = Outline::new(
                &[(Point::new(rad, 0.0), 1.0), (Point::new(-rad, 0.0), 1.0)],
                "hole",
            )
            .unwrap();
            let d = r + 0.005;
            let rp = rad - d;
            for n in 2..=24 {
                for (w, shape, h) in [
                    (0.5, TabShape::Square, 0.5),
                    (1.0, TabShape::Ramped, 0.3),
                    (2.0, TabShape::Ramped, 1.0),
                ] {
                    let opts = TabOptions::default()
                        .with_count(TabCount::Count(n))
                        .with_width(w)
                        .with_height(h)
                        .with_shape(shape);
                    let (tabs, _) = tab_places(&o, ProfileSide::Inside, d, r, &opts);
                    let ramp = if shape == TabShape::Ramped {
                        TAB_RAMP_RUN * h
                    } else {
                        0.0
                    };
                    // The lift either side on the path, from the geometry alone.
                    let half_lift = rp * (0.5 * w / rad + (r / rp).asin());
                    for (i, a) in tabs.iter().enumerate() {
                        for b in &tabs[i + 1..] {
                            let (ta, tb) = (a.at.y.atan2(a.at.x), b.at.y.atan2(b.at.x));
                            let da = (ta - tb).rem_euclid(std::f64::consts::TAU);
                            let on_path = rp * da.min(std::f64::consts::TAU - da);
                            assert!(
                                on_path >= 2.0 * (half_lift + ramp) + r - 1e-9,
                                "R {rad}, r {r}, {n} tabs of {w} mm: {on_path} apart on the \
                                 path, lifts and ramps {}",
                                2.0 * (half_lift + ramp) + r
                            );
                            pairs += 1;
                        }
                    }
                }
            }
        }
        assert!(pairs >= 100, "{pairs} pairs");
    }
}
