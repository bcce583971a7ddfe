//! The `sinumerik` controller model: a Siemens 840D-class controller (jerk-limited, `G64` /
//! `G642` rounding within the path tolerance), as the `hsm` preset uses it, fitted to the
//! adaptive-spiral paper's Table 2 ([`crate::motion::table2`] has the fit and its residuals).
//!
//! It keeps the generic model's block limits and corner rules ([`crate::motion::limits`]) and
//! replaces how a change of curvature is timed, so that a path costs the same whether it is
//! written as exact arcs or as the chords of a CAM polyline:
//!
//! # Curvature samples
//! The controller sees the path's curvature (the vector `κN`) at the junctions of blocks:
//! on an arc its own `κN`, and at a corner of deflection `θ` between two blocks, the curvature
//! of the circle through the corner and the blocks' far ends (Menger curvature,
//! `2·sin θ / |P₀P₂|`, towards the inside of the corner): on chords of a circle of radius `r`
//! that is `1/r`, on a corner after a long line nearly 0.
//!
//! # Rules
//! * **Smooth corners** (deflection ≤ [`SMOOTH_CORNER`] and a blend within the tolerance):
//!   the corner is part of a curve of curvature `κ` and gets an arc's speed cap,
//!   `min(√(η_a·A/κ), ∛(η_j·J/κ²))`, on top of the blend rule — the same cap the arc it
//!   approximates has.
//! * **Curvature ramps**: between consecutive samples the curvature changes by `Δ(κN)`; the
//!   centripetal acceleration then ramps by `v²·Δκ` over the distance `L` available, a jerk of
//!   `v³·Δκ/L`, which must stay within the share `η_j·J` of the jerk (`J` the smallest of the
//!   axes the step involves, `|Δκ|` the vector's length, so that a rotated path costs the
//!   same): `v ≤ ∛(η_j·J·L/|Δκ|)`. Along a line between two corners `L` is the line's length; at a
//!   junction of exact blocks (a line into an arc) the controller smooths the step within the
//!   path tolerance `ε` (`G642`): a curvature ramp of length `L` shifts the path by about
//!   `Δκ·L²/24`, so `L = √(24ε/Δκ)` (at most the shorter block). Either way `L` is at least
//!   that smoothing length. With `ε = 0` the step falls within one interpolation cycle:
//!   `v²·|Δκᵢ| ≤ J·T_ipo`, the generic rule.
//!
//! Before this rule, a 100 × 60 mm rounded rectangle (r = 10 mm, 5 laps, F15240) took 9.30 s
//! on `hsm` with G1/G3 arcs and 6.60 s as 0.5 mm chords: the line→arc curvature step was
//! charged over one IPO cycle while the same step along the chords was not seen at all.

use crate::geom::Vec3;
use crate::machine::Machine;
use crate::motion::limits::{
    JunctionMode, NEAR_TANGENT, above_cube, blend_cap_reaches, corner_cap, min_cbrt, speed_step_cap,
};
use crate::motion::path::BlockGeometry;

/// Largest deflection (|t₂ − t₁|, about the angle in radians) of a corner taken as part of a
/// curve (a CAM polyline's chord junction) rather than a corner of the part: 0.35 (20°).
pub const SMOOTH_CORNER: f64 = 0.35;

/// How far back (mm) curvature samples are compared: beyond it the ramp is long enough.
const HORIZON: f64 = 50.0;
/// Samples kept at most.
const MAX_SAMPLES: usize = 32;

/// The sinumerik model's state between junctions: the recent curvature samples.
#[derive(Debug, Clone, Default)]
pub(crate) struct Curvature {
    /// Path length to the end of the last block, mm.
    s: f64,
    /// Recent samples: (position along the path, `κN`).
    samples: std::collections::VecDeque<(f64, Vec3)>,
    /// The sample horizon of the last tolerance seen: (tolerance, horizon), both mm.
    horizon: Option<(f64, f64)>,
}

impl Curvature {
    /// The speed cap at the junction from `g1` (corner mode `mode`) into `g2`. `ceiling` is
    /// the blocks' own speed limit there (the smaller of the two; `∞` if none): the planner
    /// keeps `min(cap, ceiling)` and asks only whether the cap reaches the ceiling, so a ramp
    /// at least 1e-9 above it is not computed (a ramp's tests then fail with a margin far
    /// beyond their rounding). A cap below the ceiling is the cap; one at or above it is some
    /// value at or above it.
    pub(crate) fn junction_cap(
        &mut self,
        g1: &BlockGeometry,
        g2: &BlockGeometry,
        mode: JunctionMode,
        machine: &Machine,
        ceiling: f64,
    ) -> f64 {
        let t1 = g1.end_tangent();
        let t2 = g2.start_tangent();
        let deflection = (t2 - t1).length();
        let tol = match mode {
            JunctionMode::Blend(t) => t,
            _ => 0.0,
        };
        // The generic corner rules without their one-IPO-cycle curvature step (replaced by
        // the ramp below), and the speed step where a spiral arc meets another block.
        let dp = g2.derivatives(0.0)[1] - g1.derivatives(g1.length())[1];
        // No cap above the fastest the path can go matters, nor one above the ceiling (see
        // above): a blend cap surely above both is not computed (its trigonometry is the
        // costliest part of a smooth junction) and stands as ∞.
        let vmax = 3f64.sqrt()
            * machine
                .axes
                .iter()
                .map(|a| a.max_velocity)
                .fold(0.0, f64::max);
        let vtop = vmax.min(ceiling * (1.0 + 1e-9));
        let mut cap = if deflection > 1e-9 {
            let lmin = g1.length().min(g2.length());
            if tol > 0.0 && blend_cap_reaches(t1.dot(t2), lmin, tol, machine, vtop) {
                f64::INFINITY
            } else {
                corner_cap(g1, g2, t1, t2, dp, mode, machine)
            }
        } else {
            speed_step_cap(dp, machine)
        };
        if self.samples.is_empty() {
            // The program (or the run after a dwell) starts from rest on a straight line's
            // zero curvature, or on its first arc's.
            let (k0, _) = g1.curvature_ends();
            self.samples.push_back((self.s, k0));
        }
        self.s += g1.length();
        let (_, k1_end) = g1.curvature_ends();
        let (k2_start, _) = g2.curvature_ends();
        let lines =
            matches!(g1, BlockGeometry::Line { .. }) && matches!(g2, BlockGeometry::Line { .. });
        // The samples at this junction: the curvature at the end of `g1`, then a corner's
        // Menger curvature, then the curvature at the start of `g2` — except that a corner
        // between two lines (a polyline's vertex) is sampled by its Menger curvature alone:
        // its lines are chords of a curve, not straight pieces of the part.
        let menger = deflection > 1e-9 && (lines || deflection > NEAR_TANGENT);
        let mut new = [Vec3::ZERO; 3];
        let mut n_new = 0;
        if !(lines && menger) {
            new[n_new] = k1_end;
            n_new += 1;
        }
        if menger {
            let p0 = g1.point(0.0);
            let p2 = g2.point(g2.length());
            let chord = (p2 - p0).length();
            let c = t1.dot(t2).clamp(-1.0, 1.0);
            let sin = (1.0 - c * c).max(0.0).sqrt();
            let inward = (t2 - t1).normalize().unwrap_or(Vec3::ZERO);
            let k = if chord > 0.0 {
                inward * (2.0 * sin / chord)
            } else {
                Vec3::ZERO
            };
            // A smooth corner is part of a curve: an arc's speed cap for its curvature.
            let kappa = k.length();
            if deflection <= SMOOTH_CORNER && tol > 0.0 && kappa > 0.0 {
                let (ea, ej) = (machine.curvature_accel_share, machine.curvature_jerk_share);
                let (a, j) = weakest(k, machine);
                cap = cap.min((ea * a / kappa).sqrt());
                let cube = ej * j / (kappa * kappa);
                if j.is_finite() && cube < cap.min(vtop).powi(3) {
                    cap = min_cbrt(cap, cube);
                }
            }
            new[n_new] = k;
            n_new += 1;
        }
        if !(lines && menger) {
            new[n_new] = k2_start;
            n_new += 1;
        }
        let jmin = machine
            .axes
            .iter()
            .map(|a| a.max_jerk)
            .fold(f64::INFINITY, f64::min);
        // Each ramp's cheap tests (a step too small, a cap above `min(cap, v_top)` by the
        // smallest jerk and the plain distance, a pair farther apart than the smoothing
        // length; see `ramp_cap`) with the products that do not change hoisted out of the
        // loop, the same operations in the same order.
        let ej = machine.curvature_jerk_share * jmin;
        let smooth2 = (24.0 * tol).powi(2);
        // Past those tests, with ε > 0, the ramp is at least `η_j·J_min·√(24ε/|Δκ|)/|Δκ|`
        // (the smoothing length); its fourth power `(η_j·J_min)⁴·(24ε)²/|Δκ|⁶` is compared
        // with `cap¹²` without roots, 1e-8 above the rounding of either side: a ramp above
        // `cap` cannot bind (`ramp_cap` would compute it and keep `cap`).
        let smooth_reach = (ej * ej).powi(2) * smooth2;
        let cap12 = |cap: f64| {
            if (1e-20..1e20).contains(&cap) {
                (cap * cap * cap).powi(4)
            } else {
                f64::NAN
            }
        };
        for &k in new.iter().take(n_new) {
            let mut bound6 = cap.min(vtop).powi(6);
            let mut above = cap12(cap.min(vtop));
            // The oldest samples fail one of the last two tests whatever their step: with
            // `(η_j·J_min·D)²·D⁴ ≥ bound⁶·(24ε)²` a step small enough to pass the smoothing
            // test (`D⁴·|Δκ|² ≤ (24ε)²`) is also small enough to fail the bound test
            // (a 1e-9 margin covers the rounding of both). The distances decrease along the
            // samples, so they are a leading run, found from the newest sample back (only a
            // few are near enough to bind) and passed over.
            let reach = bound6 * smooth2 * (1.0 + 1e-9);
            let far = |&(sk, _): &(f64, Vec3)| {
                let d = self.s - sk;
                (ej * d).powi(2) * (d * d).powi(2) >= reach
            };
            let mut first = 0;
            if tol > 0.0 && reach.is_finite() {
                first = self.samples.len();
                while first > 0 && !self.samples.get(first - 1).is_some_and(far) {
                    first -= 1;
                }
            }
            if first > 0 {
                cap = cap.min(f64::INFINITY);
            }
            for &(sk, kk) in self.samples.range(first..) {
                let step = k - kk;
                let distance = self.s - sk;
                let dk2 = step.dot(step);
                if dk2 <= 1e-24
                    || (ej * distance).powi(2) >= bound6 * dk2
                    || (tol > 0.0 && (distance * distance).powi(2) * dk2 > smooth2)
                {
                    cap = cap.min(f64::INFINITY);
                    continue;
                }
                if tol > 0.0
                    && smooth_reach.is_finite()
                    && smooth_reach > above * (dk2 * dk2 * dk2) * (1.0 + 1e-8)
                {
                    cap = cap.min(f64::INFINITY);
                    continue;
                }
                let before = cap.to_bits();
                cap = ramp_cap(cap, step, distance, tol, machine, jmin, cap.min(vtop));
                if cap.to_bits() != before {
                    bound6 = cap.min(vtop).powi(6);
                    above = cap12(cap.min(vtop));
                }
            }
            match self.samples.back_mut() {
                // A run of equal samples (a straight line's zeros): only the latest one can
                // bind (the nearest gives the tightest ramp).
                Some(last) if (last.1 - k).length() <= 1e-12 => *last = (self.s, k),
                _ => self.samples.push_back((self.s, k)),
            }
        }
        // Samples farther back than any ramp that could bind: a ramp over `D` binds only if
        // `∛(η_j·J·D/Δκ) < v_max` while `D ≤ √(24ε/Δκ)`, i.e. `D < v_max·∛(24ε/(η_j·J))`.
        let horizon = match self.horizon {
            Some((t, h)) if t.to_bits() == tol.to_bits() => h,
            _ => {
                let h = horizon(tol, machine);
                self.horizon = Some((tol, h));
                h
            }
        };
        while self.samples.len() > MAX_SAMPLES
            || self
                .samples
                .front()
                .is_some_and(|&(sk, _)| self.s - sk > horizon)
        {
            self.samples.pop_front();
        }
        cap
    }
}

/// Samples farther back than this (mm) cannot bind a ramp at tolerance `tol` (see
/// [`Curvature::junction_cap`]).
fn horizon(tol: f64, machine: &Machine) -> f64 {
    if tol > 0.0 {
        let (vmax, jmin) = machine
            .axes
            .iter()
            .fold((0.0f64, f64::INFINITY), |(v, j), a| {
                (v.max(a.max_velocity), j.min(a.max_jerk))
            });
        (3f64.sqrt() * vmax * (24.0 * tol / (machine.curvature_jerk_share * jmin)).cbrt())
            .min(HORIZON)
    } else {
        HORIZON
    }
}

/// `cap` lowered to the speed at which the curvature may change by `step` over `distance`
/// mm of path, the controller smoothing the change within the tolerance `tol` (see the
/// module docs); `jmin` is the machine's smallest axis jerk. Ramp caps at or above `bound`
/// (≤ `cap`) are not computed (they would not bind), nor, in cube space, those at or above
/// `cap`.
fn ramp_cap(
    cap: f64,
    step: Vec3,
    distance: f64,
    tol: f64,
    machine: &Machine,
    jmin: f64,
    bound: f64,
) -> f64 {
    // (`cap.min(∞)` where the original rule's cap is infinite: `cap` itself, unless NaN.)
    let dk2 = step.dot(step);
    if dk2 <= 1e-24 {
        return cap.min(f64::INFINITY);
    }
    // The cap is at least ∛(η_j·J_min·D/|Δκ|): skip it when that is above the bound
    // (compared as cubes, without roots).
    if (machine.curvature_jerk_share * jmin * distance).powi(2) >= bound.powi(6) * dk2 {
        return cap.min(f64::INFINITY);
    }
    // Farther apart than the smoothing length (`D² > 24ε/|Δκ|`, checked without roots):
    // the step between them was already met (and smoothed) by the samples in between.
    if tol > 0.0 && (distance * distance).powi(2) * dk2 > (24.0 * tol).powi(2) {
        return cap.min(f64::INFINITY);
    }
    let dk = dk2.sqrt();
    let smoothing = if tol > 0.0 {
        (24.0 * tol / dk).sqrt()
    } else {
        0.0
    };
    let avail = distance.max(smoothing);
    // With the smallest jerk the cube `η_j·J·L/|Δκ|` is at most what it is with the axes'
    // own (J ≥ J_min, rounding is monotonic): above `cap³` it cannot bind.
    if avail > 0.0 && above_cube(cap, machine.curvature_jerk_share * jmin * avail / dk) {
        return cap.min(f64::INFINITY);
    }
    let (_, j) = weakest(step, machine);
    if !j.is_finite() {
        return cap.min(f64::INFINITY);
    }
    if avail > 0.0 {
        min_cbrt(cap, machine.curvature_jerk_share * j * avail / dk)
    } else {
        // Within one interpolation cycle (the generic rule).
        cap.min((j * machine.ipo_cycle / dk).sqrt())
    }
}

/// The smallest acceleration and jerk of the axes `v` has a component along: the rules take
/// the vector's length against them, so that they do not change when the path is rotated on
/// a machine whose axes are alike (a per-axis bound would: `|vᵢ| ≤ |v|`, the verifier's
/// per-axis check is met either way).
fn weakest(v: Vec3, machine: &Machine) -> (f64, f64) {
    let n = v.length();
    let mut a = f64::INFINITY;
    let mut j = f64::INFINITY;
    for (c, ax) in v.to_array().iter().zip(&machine.axes) {
        if c.abs() > 1e-9 * n {
            a = a.min(ax.max_acceleration);
            j = j.min(ax.max_jerk);
        }
    }
    (a, j)
}
