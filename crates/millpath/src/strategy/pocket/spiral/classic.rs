//! The paper's construction, made valid for any simply connected pocket: a central spiral of
//! radius `R₀ = C·ρ_B` grown into the walls' loop by offset fronts ([`super::fronts`],
//! [`super::laps`], `--morph fronts`) or by level sets of a harmonic field
//! ([`super::harmonic`], `--morph harmonic`). Both refuse islands.
//!
//! # The harmonic morph
//!
//! 1. **Boundary offset** `B`: the outline offset inward by `r + stock` (exact arcs); one loop.
//! 2. **Centre** `c`: the centre of the largest circle inscribed in `B`, radius `ρ_B`.
//! 3. **Central spiral**: `ρ(θ) = ρ_h + (R₀ − ρ_h)·θ/(2πn)` about `c`, entered by a helix of
//!    radius `ρ_h`, out to `R₀ = C·ρ_B` (clamped to `[ρ_h, 0.9·ρ_B]`), `n = ⌈(R₀ − ρ_h)/s'⌉`
//!    turns so that its pitch is at most `s' = 0.95·s`. The paper defines `C` against the
//!    pocket width `l` (`φ = C·l`); in tool-centre space the width is `2ρ_B`, so `C = 1`
//!    means the spiral touches `B`.
//! 4. **Morph**: loops `L_k` on level sets `u = t_k` of the harmonic function of
//!    [`super::harmonic`]; `L_{k+1}` is the image of `L_k` along the gradient's streamlines,
//!    `Δt` chosen lap by lap so that the longest streamline is at most `s'`: every point of
//!    `L_{k+1}` is within `s'` of `L_k`, measured, also where `|∇u|` is small (corners).
//!    Once `B` is within `s'` of `L_k` both ways (sampled), the next lap goes onto `B_ε`.
//! 5. **One spiral**: lap `k`'s point at arc-length fraction `f` of `L_k` is `p + f·(q − p)`,
//!    `q` the image of `p`, so the laps join without a corner.
//! 6. **Last loop** `B_ε`: `B` moved inward by `ε` =
//!    [`LAST_LOOP_MARGIN`], cut once with exact arcs; every
//!    lap is kept inside it (`spiral/keep_inside.rs`), so the tool centre stays at least `ε/4`
//!    inside `B`.
//! 7. **Restarts**: where `1 − u` decays like `exp(−πx/w)` (long arms) the field is solved
//!    again from the lap reached; should the laps still stall, the distance-field
//!    interpolation `g/(g + d_B)` is tried; then the pocket is refused, suggesting `offset`.
//! 8. **Frame**: the grid is axis-aligned, so the spiral is planned in the pocket's principal
//!    frame and in that frame turned by 45°, and the shorter result kept ([`plan`]).
//!
//! **Limits.** The lap count is bounded below by the Hausdorff distance between the central
//! circle and `B` over the stepover: the laps lie about twice as densely as contour-parallel
//! loops on elongated pockets. Both morphs are kept for the paper's comparisons (the transition
//! sweep, `millpath sweep`); the default morph is [`super::offsets`].

use super::super::levels::{Cut, CutEntry, LevelPlan};
use super::super::offset::too_large;
use super::super::options::{Direction, Entry, PocketOptions, SpiralMorph};
use super::super::segments::{Seg, segs_from_vertices};
use super::super::shape::{
    IndexedLoop, PocketShape, closed_chain, inscribed_centre, restart_near, reversed, v2,
};
use super::common::{
    Construction, LAST_LOOP_MARGIN, LoopWalker, SpiralStats, blend_lap, closed_pline, fractions,
    last_loop, resample, sample_every,
};
use super::harmonic::Harmonic;
use super::{fronts, keep_inside, laps};
use crate::error::InputError;
use crate::geom::{Point, Vec2};
use crate::toolpath::Tool;
use cavalier_contours::polyline::{PlineSource, Polyline};
use std::f64::consts::TAU;

/// Most restarts of the harmonic field from an intermediate lap.
const MAX_RESTARTS: usize = 20;
/// Most laps the morph may take.
const MAX_LAPS: usize = 400;

/// The spiral of the fronts or the harmonic morph, planned in the pocket's own frame.
///
/// The harmonic grid is axis-aligned, so the result would depend on how the pocket is turned.
/// To make it a property of the pocket alone, the planning happens in the pocket's own frame:
/// its principal axes (from the second moments of its boundary, sampled by arc length; for an
/// isotropic shape such as a square, the direction of its longest straight edge), and in that
/// frame turned by 45°; the shorter of the two spirals is kept and turned back.
pub fn plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<(LevelPlan, SpiralStats), InputError> {
    let theta = crate::geom::region::principal_angle(&shape.outer);
    if opts.spiral.morph == SpiralMorph::Fronts {
        if let Some(found) = plan_fronts(shape, tool, opts, theta)? {
            return Ok(found);
        }
    }
    let mut best: Option<(LevelPlan, SpiralStats, f64)> = None;
    let mut last_err = None;
    for extra in [0.0, std::f64::consts::FRAC_PI_4] {
        let a = theta + extra;
        let turned = turn_shape(shape, -a)?;
        match plan_in_frame(&turned, tool, opts) {
            Ok((plan, stats)) => {
                let plan = turn_plan(&plan, a);
                let len: f64 = plan
                    .cuts
                    .iter()
                    .map(|c| super::super::segments::path_length(&c.path))
                    .sum();
                if best.as_ref().is_none_or(|b| len < b.2 - 1e-9) {
                    best = Some((plan, stats, len));
                }
            }
            Err(e) => last_err = Some(e),
        }
    }
    match (best, last_err) {
        (Some((plan, stats, _)), _) => Ok((plan, stats)),
        (None, Some(e)) => Err(name_sharp_corner(e, shape)),
        (None, None) => Err(InputError::new("pocket shape", "no spiral").at("--strategy spiral")),
    }
}

/// A spiral that did not converge on a pocket with a corner sharper than 60°: the corner is
/// the likely cause (the loops' rounded tips cannot reach into it within the spacing bound,
/// README: Known limits), so the message names it.
fn name_sharp_corner(e: InputError, shape: &PocketShape) -> InputError {
    match shape.outer.sharpest_corner() {
        Some((angle, at)) if e.value == NO_CONVERGENCE && angle < 60f64.to_radians() => {
            InputError::new(
                "pocket shape",
                format!(
                    "{NO_CONVERGENCE}; its sharpest corner is {:.1}° at ({:.3}, {:.3})",
                    angle.to_degrees(),
                    at.x,
                    at.y
                ),
            )
            .at("--strategy spiral")
            .expected(
                "a pocket the spiral can morph into within 400 laps; corners much sharper \
                 than 60° often are not (use --strategy offset)",
            )
        }
        _ => e,
    }
}

/// The value of the error of a spiral that does not reach the boundary.
const NO_CONVERGENCE: &str = "spiral did not converge";

/// The spiral on offset fronts ([`fronts`], [`laps`]); `None` when the fronts do not reach
/// the boundary and the harmonic morph must be used.
fn plan_fronts(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    start_angle: f64,
) -> Result<Option<(LevelPlan, SpiralStats)>, InputError> {
    if !shape.islands.is_empty() {
        return Ok(None);
    }
    let s = opts.stepover_mm(tool);
    // The fronts are up to √2 steps apart at right-angle corners: the step is capped so that
    // this stays below the tool's diameter (1.3·r·√2 = 1.84·r), or a ridge of material would
    // stand between two laps (large stepovers).
    let sp = (FRONT_STEP * s).min(1.3 * tool.radius());
    let d0 = tool.radius() + opts.wall_stock;
    let region = shape.offset(d0);
    let b = match region.outers.as_slice() {
        [one] => one.clone(),
        _ => return Ok(None),
    };
    let k = tool.tolerance_scale();
    let margin = LAST_LOOP_MARGIN * k;
    let b_eps = last_loop(&b, margin);
    let Some((c, rho_b)) = fronts::ridge_centre(&b) else {
        return Ok(None);
    };
    let (rho_h, r0) = centre_radii(tool, opts, rho_b)?;
    let ds = (s / 3.0).clamp(0.05 * k, FRONT_SAMPLE * k);
    let ridge = fronts::ridge_segment(&b, c, rho_b, r0, 0.5 * sp, Vec2::from_angle(start_angle));
    // Both smoothing radii; the shorter spiral is kept. The larger radius runs faster where
    // it takes no more laps; where its rounded fronts need an extra (halved) step, or cannot
    // reach `B` within the spacing bound at all (acute corners, where rounding moves the
    // corner point by `ρ_o·(1/sin(α/2) − 1)`), the smaller one is shorter. Neither: the
    // harmonic morph.
    let mut best: Option<(LevelPlan, SpiralStats, f64)> = None;
    for fraction in [SMOOTH_FRACTION, SMOOTH_FALLBACK] {
        let spiral = laps::FrontSpiral {
            b: &b,
            b_eps: &b_eps,
            c,
            rho_b,
            r0,
            rho_h,
            sp,
            ds,
            ds_last: ds.min(0.9 * (8.0 * d0 * margin).sqrt()),
            tool_radius: tool.radius(),
            smooth: opts.spiral.min_radius.max(fraction * s),
            ccw: opts.direction == Direction::Climb,
            start_angle,
            ridge,
            arcs: opts.spiral.arcs,
            max_gap: (CORNER_GAP * sp).min(CORNER_GAP * tool.radius()),
            scale: k,
        };
        // cavalier_contours panics on some degenerate booleans of the fronts (its slices
        // fail to stitch into closed loops): the fronts then fail, like any failed front.
        let planned = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| spiral.plan()));
        if let Ok(Some((plan, stats))) = planned {
            let len: f64 = plan
                .cuts
                .iter()
                .map(|c| super::super::segments::path_length(&c.path))
                .sum();
            // Ties (within 1%) go to the larger radius, tried first.
            if best.as_ref().is_none_or(|b| len < 0.99 * b.2) {
                best = Some((plan, stats, len));
            }
        }
    }
    Ok(best.map(|(plan, stats, _)| (plan, stats)))
}

/// The entry helix's radius `ρ_h` and the central spiral's outer radius `R₀ = C·ρ_B`, both
/// morphs alike. A helix wider than the tool would leave a pillar at its centre.
fn centre_radii(tool: &Tool, opts: &PocketOptions, rho_b: f64) -> Result<(f64, f64), InputError> {
    let helix = match opts.entry {
        Entry::Helix { radius, .. } => radius,
        Entry::Ramp { .. } => 0.25 * tool.radius(),
    };
    let rho_h = helix.min(0.9 * tool.radius()).min(0.45 * rho_b);
    if rho_h < 1e-3 {
        return Err(too_large(tool));
    }
    Ok((
        rho_h,
        (opts.spiral.transition * rho_b).max(rho_h).min(0.9 * rho_b),
    ))
}

/// The fronts' smoothing radius as a fraction of the stepover (at least `--min-radius`).
/// Measured on the built-in pocket (C = 0.5, capsule core, 600 in/min, `hsm`; cycle time and
/// the share of the path above the nominal engagement): 0.8 → 75.3 s / 11.8%, 1.0 → 74.1 s /
/// 12.4%, 1.2 → 73.1 s / 13.0%, 1.4 → 72.3 s / 13.6%, 1.6 → 72.7 s / 14.6%, 2.0 → 79.9 s
/// (a halved step at the last front). Larger radii run faster on the `hsm` preset until the
/// rounding of `B`'s corners (the last front) takes a halved step; the share rises slowly
/// (longer corner arcs) and stays below the `offset` strategy's (17.4%).
const SMOOTH_FRACTION: f64 = 1.4;
/// The smoothing radius also tried, the shorter spiral kept (the sample part's triangle:
/// 1.4 → harmonic fallback, 3.1 m; 1.0 → fronts, 2.3 m; its trapezoid: 1.7 m against 1.5 m).
const SMOOTH_FALLBACK: f64 = 1.0;
/// The largest gap between consecutive fronts (measured from the new front to the previous
/// one) as a multiple of the step `s'`, and at most this multiple of the tool radius (so that
/// no ridge stands between two passes: `1.8·r < 2r`). Contour-parallel loops are
/// `s'/sin(α/2)` apart at a convex corner of angle `α` (`√2·s'` at right angles, the least
/// this may be); 1.8 lets corners down to 67° through with uniform steps, sharper ones take
/// halved steps. Sample part (zigzag / offset / spiral, s): triangle 23.1 / 15.8 / 19.7 (at
/// `√2`: 28.4), trapezoid 22.0 / 16.9 / 16.2 (23.8), square 25.5 / 21.6 / 18.3 (19.8); the
/// share above the nominal engagement stays below offset's on each; the aerospace pocket is
/// unchanged (right-angle corners).
const CORNER_GAP: f64 = 1.8;
/// Largest step between fronts as a fraction of the stepover: the straight parts of the laps
/// then sit just below the nominal engagement (at exactly `s` the raster's noise puts half of
/// them above it).
const FRONT_STEP: f64 = 0.98;
/// Largest sample spacing along the fronts' laps, mm (times the tool's
/// [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale), as the smallest, 0.05 mm,
/// and the margin of the last loop). The laps are output as G1 polylines; a
/// controller's look-ahead sees their curvature only through the vertices, and at 0.01 mm
/// path tolerance the corner blend at a vertex is as wide as the curve itself only when
/// `h² ≤ 8·ε·R` (chord `h`, radius `R`): 0.5 mm keeps that for `R ≥ 3 mm`.
const FRONT_SAMPLE: f64 = 0.5;

/// The shape turned by `a` about the origin.
fn turn_shape(shape: &PocketShape, a: f64) -> Result<PocketShape, InputError> {
    let v: Vec<(Point, f64)> = shape
        .outer
        .vertices()
        .map(|(p, b)| (p.rotate_about(Point::ORIGIN, a), b))
        .collect();
    Ok(PocketShape::simple(crate::geom::Outline::new(
        &v,
        "turned pocket",
    )?))
}

/// The plan turned by `a` about the origin.
fn turn_plan(plan: &LevelPlan, a: f64) -> LevelPlan {
    let o = Point::ORIGIN;
    let turn = |p: Point| p.rotate_about(o, a);
    LevelPlan {
        cuts: plan
            .cuts
            .iter()
            .map(|c| Cut {
                entry: match c.entry {
                    CutEntry::Helix {
                        center,
                        radius,
                        flat_turn,
                    } => CutEntry::Helix {
                        center: turn(center),
                        radius,
                        flat_turn,
                    },
                    CutEntry::Direct { from } => CutEntry::Direct { from: turn(from) },
                    e @ (CutEntry::Ramp
                    | CutEntry::RampAlong { .. }
                    | CutEntry::Lap { .. }
                    | CutEntry::Linked) => e,
                },
                path: c
                    .path
                    .iter()
                    .map(|sg| Seg {
                        a: turn(sg.a),
                        b: turn(sg.b),
                        arc: sg.arc.map(|arc| super::super::segments::Arc {
                            center: turn(arc.center),
                            ..arc
                        }),
                    })
                    .collect(),
            })
            .collect(),
    }
}

/// The spiral planned in the shape's own coordinates.
fn plan_in_frame(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<(LevelPlan, SpiralStats), InputError> {
    if !shape.islands.is_empty() {
        return Err(InputError::new("islands", shape.islands.len())
            .at("--strategy spiral")
            .expected("a pocket without islands for the spiral (use --strategy offset)"));
    }
    let s = opts.stepover_mm(tool);
    let sp = 0.95 * s;
    let d0 = tool.radius() + opts.wall_stock;
    let region = shape.offset(d0);
    let b =
        match region.outers.as_slice() {
            [] => return Err(too_large(tool)),
            [one] => one.clone(),
            _ => return Err(
                InputError::new("boundary offset loops", region.outers.len())
                    .at("--strategy spiral")
                    .expected(
                        "a pocket whose tool-centre region is one piece (use --strategy offset)",
                    ),
            ),
        };
    let k = tool.tolerance_scale();
    let margin = LAST_LOOP_MARGIN * k;
    let b_eps = last_loop(&b, margin);
    let (c, rho_b) = inscribed_centre(&b, &[], 48);
    let (rho_h, r0) = centre_radii(tool, opts, rho_b)?;
    let ccw = opts.direction == Direction::Climb;
    let sign = if ccw { 1.0 } else { -1.0 };
    let mut stats = SpiralStats {
        r0,
        ..SpiralStats::default()
    };

    // Sample spacing: a fraction of the stepover, and fine enough on the last lap that chords
    // stay within B_ε at concave arcs of radius ≥ d0.
    let ds = (s / 3.0).clamp(0.05 * k, 2.0 * k);
    let ds_last = ds.min(0.9 * (8.0 * d0 * margin).sqrt());

    // Central Archimedean spiral.
    let mut pts: Vec<Point> = Vec::new();
    let turns = ((r0 - rho_h) / sp).ceil().max(0.0) as usize;
    stats.central_turns = turns;
    if turns > 0 {
        let total = TAU * turns as f64;
        let mut th = 0.0;
        while th < total {
            let rho = rho_h + (r0 - rho_h) * th / total;
            pts.push(c + Vec2::from_angle(sign * th) * rho);
            th += (ds / rho.max(1e-3)).min(0.2);
        }
    }
    // L_0: the circle of radius r0, from angle 0.
    let n0 = ((TAU * r0 / ds).ceil() as usize).max(16);
    let lap0: Vec<Point> = (0..n0)
        .map(|i| c + Vec2::from_angle(sign * TAU * i as f64 / n0 as f64) * r0)
        .collect();
    let h = grid_spacing(&b, s);
    let ctx = Morph {
        b: &b,
        b_dir: if ccw { b_eps.clone() } else { reversed(&b_eps) },
        b_samples: sample_every(&b, ds),
        sp,
        ds,
        ds_last,
    };
    // The harmonic morph first; where it stalls (long arms, where u − 1 decays like
    // exp(−πx/w) and the level sets cannot reach the end within f64 and grid accuracy), the
    // distance-field morph of [`Harmonic::distance_blend`].
    for attempt in 0..2 {
        let make = |lap: &[Point], restart: bool| -> Harmonic {
            if !restart {
                if attempt == 0 {
                    Harmonic::solve(&b, c, r0, h)
                } else {
                    Harmonic::distance_blend(&b, c, r0, h)
                }
            } else {
                Harmonic::solve_from_loop(&b, lap, h)
            }
        };
        if let Some(m) = ctx.run(&make, lap0.clone()) {
            stats.morph_laps = m.laps;
            stats.max_loop_distance = m.max_distance;
            stats.construction = if attempt == 1 {
                Construction::DistanceField
            } else {
                Construction::Harmonic
            };
            pts.extend(m.points);
            let mut path = keep_inside::lap_path(&pts, &b_eps, ds_last, opts.spiral.arcs, k);
            path.extend(segs_from_vertices(&closed_chain(&m.last_loop)));
            let plan = LevelPlan {
                cuts: vec![Cut {
                    entry: CutEntry::Helix {
                        center: c,
                        radius: rho_h,
                        flat_turn: false,
                    },
                    path,
                }],
            };
            return Ok((plan, stats));
        }
    }
    Err(InputError::new("pocket shape", NO_CONVERGENCE)
        .at("--strategy spiral")
        .expected("a pocket the spiral can morph into within 400 laps (use --strategy offset)"))
}

/// The fixed data of the morph.
struct Morph<'a> {
    b: &'a Polyline<f64>,
    b_dir: Polyline<f64>,
    b_samples: Vec<Point>,
    sp: f64,
    ds: f64,
    ds_last: f64,
}

/// A finished morph.
struct MorphResult {
    points: Vec<Point>,
    last_loop: Polyline<f64>,
    laps: usize,
    max_distance: f64,
}

impl Morph<'_> {
    /// Runs the laps from `lap` (on u = 0) to the boundary; `None` when the field stalls.
    fn run(
        &self,
        make: &dyn Fn(&[Point], bool) -> Harmonic,
        mut lap: Vec<Point>,
    ) -> Option<MorphResult> {
        let mut field = make(&lap, false);
        let mut restarts = 0;
        let (b, sp, ds) = (self.b, self.sp, self.ds);
        // Intermediate laps stay at least `margin` inside B: next to B the discrete level sets
        // are only good to the grid spacing, and may even cross it.
        let margin = 2.0 * field.spacing();
        let b_inner = match crate::geom::region::offset_loops(b, margin).as_slice() {
            [one] => Some(one.clone()),
            _ => None,
        };
        let b_index = IndexedLoop::new(b);
        let mut pts = Vec::new();
        let mut t = 0.0;
        let mut dt: f64 = 0.25;
        let mut max_distance: f64 = 0.0;
        let mut history: Vec<f64> = Vec::new();
        for laps in 0..MAX_LAPS {
            let fr = fractions(&lap);
            let lap_poly = closed_pline(&lap);
            let lap_index = IndexedLoop::new(&lap_poly);
            let haus_b = self
                .b_samples
                .iter()
                .map(|&q| lap_index.distance(q))
                .fold(0.0, f64::max);
            let haus_l = lap.iter().map(|&p| b_index.distance(p)).fold(0.0, f64::max);
            if haus_b <= sp && haus_l <= sp {
                // The last lap: onto B_ε at equal arc-length fractions.
                let fine = resample(&lap, self.ds_last);
                let start = restart_near(&self.b_dir, fine[0]);
                blend_lap(
                    &fine,
                    &LoopWalker::new(&start),
                    start.path_length(),
                    &mut pts,
                );
                let close = start.at(0).pos();
                pts.push(Point::new(close.x, close.y));
                return Some(MorphResult {
                    points: pts,
                    last_loop: start,
                    laps: laps + 1,
                    max_distance: max_distance.max(haus_b.max(haus_l)),
                });
            }
            // Near u = 1 the level sets are within rounding of each other (the arms of long
            // pockets, where u − 1 decays like exp(−πx/w)): restart the morph with the lap
            // reached as the new inner boundary, a fresh, well-conditioned field.
            if t >= 1.0 - 1e-6 && restarts < MAX_RESTARTS {
                field = make(&lap, true);
                restarts += 1;
                t = 0.0;
                dt = 0.25;
            }
            // Stalled: no progress towards B over the last six laps.
            history.push(haus_b);
            if t >= 1.0 - 2e-11
                || (history.len() > 6 && history[history.len() - 7] - haus_b < 0.2 * sp)
            {
                return None;
            }
            // An intermediate lap: grow Δt until the longest streamline reaches s'.
            let mut step = dt.min(1.0 - t);
            let mut images: Vec<(Point, f64)>;
            let mut longest;
            let mut tries = 0;
            loop {
                let target = (t + step).min(1.0 - 1e-11);
                images = lap
                    .iter()
                    .map(|&p| {
                        let q = clamp_inside(b_inner.as_ref(), field.trace(p, target).0);
                        (q, q.distance(p))
                    })
                    .collect();
                longest = images.iter().map(|x| x.1).fold(0.0, f64::max);
                tries += 1;
                if longest <= sp || tries > 30 {
                    break;
                }
                step *= 0.97 * sp / longest.max(1e-9);
            }
            if longest > sp {
                return None;
            }
            max_distance = max_distance.max(longest);
            for ((p, f), (q, _)) in lap.iter().zip(&fr).zip(&images) {
                pts.push(*p + (*q - *p) * *f);
            }
            t = (t + step).min(1.0 - 1e-11);
            dt = step * (0.99 * sp / longest.max(1e-9)).min(2.0);
            let next: Vec<Point> = images.into_iter().map(|x| x.0).collect();
            lap = resample(&next, ds);
        }
        None
    }
}

/// `q` if it lies inside `inner`, else its closest point on `inner`.
fn clamp_inside(inner: Option<&Polyline<f64>>, q: Point) -> Point {
    let Some(inner) = inner else { return q };
    if inner.winding_number(v2(q)) != 0 {
        return q;
    }
    inner
        .closest_point(v2(q), 1e-12)
        .map_or(q, |c| Point::new(c.seg_point.x, c.seg_point.y))
}

/// Grid spacing of the harmonic solve: about 160 cells across, at most a third of the
/// stepover, and no more than ~60 000 nodes.
fn grid_spacing(b: &Polyline<f64>, s: f64) -> f64 {
    let e = b
        .extents()
        .map_or((1.0, 1.0), |e| (e.max_x - e.min_x, e.max_y - e.min_y));
    let h = (e.0.max(e.1) / 160.0).min(s / 3.0);
    h.max((e.0 * e.1 / 60_000.0).sqrt()).max(1e-3)
}
