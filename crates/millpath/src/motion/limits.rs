//! Path limits of a block (axis limits projected onto the path) and junction speed caps.
//!
//! # Lines
//! On a line with unit direction `u`, axis `i` sees `v·u_i`, `a·u_i`, `j·u_i`, so the path
//! limits are exactly `V = min_i vmax_i/|u_i|`, `A = min_i amax_i/|u_i|`,
//! `J = min_i jmax_i/|u_i|` (axes with `u_i = 0` impose nothing), and `V` is further bounded
//! by the programmed feed and the machine's maximum feed (rapids: by the rapid velocity per
//! axis, projected the same way).
//!
//! # Arcs and helices
//! On a helix of radius `r` and pitch `2πc` (curvature `κ = r/(r² + c²)`, torsion
//! `τ = c/(r² + c²)`), with path speed `v`, tangential acceleration `a_t` and jerk `j_t`, the
//! Frenet frame gives
//! `acc = a_t·T + κv²·N` and `jerk = (j_t − κ²v³)·T + 3κ·v·a_t·N + κτv³·B`.
//! Each axis component is at most the vector's norm, so it suffices that
//! * `|a_t| + κv² ≤ A_ax`, with `A_ax` the smallest acceleration limit of the axes the block
//!   moves. Following the Siemens 840D's `CURV_EFFECT_ON_PATH_ACCEL` (MD20602), a share
//!   `η_a` of `A_ax` is given to the centripetal part, `κV² ≤ η_a·A_ax`, the rest to the
//!   tangential acceleration: `A = (1 − η_a)·A_ax`.
//! * `|j_t| + κ√(κ² + τ²)·v³ + 3κ·v·|a_t| ≤ J_ax`: a share `η_j` of `J_ax` bounds the
//!   curvature terms at the block's top speed, `κ√(κ²+τ²)·V³ + 3κ·A·V ≤ η_j·J_ax` (a
//!   depressed cubic in `V` with one positive root, solved in the sinh form), and the
//!   tangential jerk gets `J = (1 − η_j)·J_ax`. On a circle at constant speed this is the
//!   familiar `v³/r² ≤ η_j·J`.
//! * on a spiral arc (end radius ≠ start radius, within the G-code tolerance) the parameter
//!   is not arc length and `acc = P''·v² + P'·a_t`, `jerk = P'''·v³ + 3P''·v·a_t + P'·j_t`
//!   with `|P'| ≤ g1`, `|P''| ≤ g2`, `|P'''| ≤ g3` ([`BlockGeometry::derivative_bounds`]; `1`, `κ`,
//!   `κ√(κ²+τ²)` on a helix): the same shares with `κ → g2`, `κ√(κ²+τ²) → g3`, the
//!   tangential limits divided by `g1`, and the feed bounding `g1·v`. (Treating spirals as
//!   circles let the fuzzer's tiny spiral arcs exceed the axis acceleration 1.6×.)
//! * the axis velocities: `V ≤ min_i vmax_i/m_i` with `m_i` the largest tangent component
//!   of axis `i` over the block.
//!
//! # Junctions
//! Between two blocks with unit tangents `t1` (end of the first) and `t2` (start of the
//! next), deflection `θ = acos(t1·t2)`:
//! * **tangent** (`|t2 − t1| ≤ 1e-9`): no direction cap. The curvature may still jump
//!   (line → arc, arc → arc of another radius): the acceleration then steps by
//!   `v²·Δ(κN)`. A real controller spreads that step over its interpolation cycle `T_ipo`
//!   (the 840D bounds it by `PATH_TRANS_JERK_LIM`, MD32432), so we require the mean jerk over
//!   one cycle to stay within each axis's jerk: `v²·|Δ(κN)_i| ≤ jmax_i·T_ipo`. With infinite
//!   jerk there is no such cap.
//!   Where a spiral arc (see [`BlockGeometry::derivatives`]) meets another block, `P'` may also
//!   change length: the axis velocities step by `v·|ΔP'_i|`, capped as at an exact-path
//!   junction below.
//! * **near-tangent** corners (`|t2 − t1| ≤` [`NEAR_TANGENT`], what G-code rounding makes of a
//!   tangent junction) keep the tangent case's curvature-step cap on top of their corner
//!   rule.
//! * **exact stop** (`Corner::ExactStop`, or a path tolerance of 0): the junction speed is 0
//!   at a corner. After a `Corner::ExactStop` move it is 0 at a tangent junction too (the
//!   controller model sets it: `super::controller`); under a zero tolerance the axes pass a
//!   tangent junction at speed. The machine's settling at each stop
//!   ([`Machine::exact_stop_time`]) is the controller model's to add.
//! * **exact path** (`Corner::ExactPath`, G61): the direction changes within one
//!   interpolation cycle, each axis's velocity stepping by `v·|t2_i − t1_i|`; the mean
//!   acceleration over the cycle must stay within `amax_i` and the step of acceleration
//!   within `jmax_i·T_ipo`: `v·|Δt_i| ≤ min(amax_i·T_ipo, jmax_i·T_ipo²)`.
//! * **blend** within a tolerance `ε` (the machine's path tolerance, or `Corner::Blend`): the
//!   corner is rounded by the largest circular arc tangent to both blocks whose distance from
//!   the corner is at most `ε`. The arc's centre lies on the bisector at `R/cos(θ/2)` from the
//!   corner, so its deviation is `R·(1/cos(θ/2) − 1) ≤ ε`, i.e.
//!   `R = ε·cos(θ/2)/(1 − cos(θ/2))`; its tangent points lie `R·tan(θ/2)` from the corner,
//!   which must fit in half of each block, `R ≤ min(L1, L2)/(2·tan(θ/2))`. The blend is
//!   taken at `v_c = min(√(A_ax·R), ∛(J_ax·R²))` (centripetal acceleration and its jerk on
//!   the arc). The planner keeps the programmed sharp path for the timing (the blend is
//!   shorter, so the time is slightly conservative) and does not model the curvature step at
//!   the blend's ends (controllers blend with curvature-continuous polynomials, G642).

use super::path::BlockGeometry;
use super::profile::Limits1;
use crate::geom::Vec3;
use crate::machine::Machine;
use crate::toolpath::{Corner, Move, MoveKind};

/// The path limits of a block of geometry `g` for move `m`.
pub fn block_limits(g: &BlockGeometry, m: &Move, machine: &Machine) -> Limits1 {
    let prog = match m.kind {
        MoveKind::Rapid => f64::INFINITY,
        _ => m.feed.min(machine.max_feed),
    };
    let dir = g.max_direction();
    let mut v = prog;
    let (mut a_ax, mut j_ax, mut a_line, mut j_line) =
        (f64::INFINITY, f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for (i, &d) in dir.iter().enumerate() {
        if d <= 1e-15 {
            continue;
        }
        let ax = machine.axes[i];
        v = v.min(ax.max_velocity / d);
        if matches!(m.kind, MoveKind::Rapid) {
            v = v.min(machine.rapid[i] / d);
        }
        a_line = a_line.min(ax.max_acceleration / d);
        j_line = j_line.min(ax.max_jerk / d);
        a_ax = a_ax.min(ax.max_acceleration);
        j_ax = j_ax.min(ax.max_jerk);
    }
    match *g {
        BlockGeometry::Line { .. } => Limits1 {
            v,
            a: a_line,
            j: j_line,
        },
        BlockGeometry::Helix { .. } | BlockGeometry::Arc3 { .. } => {
            // g1, g2, g3 bound |P'|, |P''|, |P'''| (κ, κ√(κ²+τ²) on a circle; a spiral's
            // radial terms included, see `BlockGeometry::derivative_bounds`).
            let (g1, g2, g3) = g.derivative_bounds();
            let (ea, ej) = (machine.curvature_accel_share, machine.curvature_jerk_share);
            let a = (1.0 - ea) * a_ax / g1;
            // The feed bounds the tool's speed |P'|·ṡ.
            v = v.min(prog / g1);
            v = v.min((ea * a_ax / g2).sqrt());
            let j = if j_ax.is_finite() {
                // g3·V³ + 3·g2·A·V = η_j·J:  V³ + p·V − q = 0.
                let p = 3.0 * g2 * a / g3;
                let q = ej * j_ax / g3;
                let arg = 1.5 * q / p * (3.0 / p).sqrt();
                let vj = if arg > 1e100 {
                    q.cbrt()
                } else {
                    2.0 * (p / 3.0).sqrt() * (arg.asinh() / 3.0).sinh()
                };
                v = v.min(vj * (1.0 - 1e-12));
                (1.0 - ej) * j_ax / g1
            } else {
                f64::INFINITY
            };
            Limits1 { v, a, j }
        }
    }
}

/// How a junction is treated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JunctionMode {
    /// Stop.
    Stop,
    /// Exact path with a velocity step within one interpolation cycle.
    ExactPath,
    /// Blend within this tolerance (mm).
    Blend(f64),
}

/// The junction mode the corner setting of the first block asks for.
pub fn junction_mode(corner: Corner, machine: &Machine) -> JunctionMode {
    let blend = |t: f64| {
        if t > 0.0 {
            JunctionMode::Blend(t)
        } else {
            JunctionMode::Stop
        }
    };
    match corner {
        Corner::Machine => blend(machine.path_tolerance),
        Corner::ExactStop => JunctionMode::Stop,
        Corner::ExactPath => JunctionMode::ExactPath,
        Corner::Blend(t) | Corner::BlendMerge { tolerance: t, .. } => blend(t),
    }
}

/// Deflections (|t2 − t1|, about the angle in radians) up to which a corner counts as
/// near-tangent: the curvature step is capped there as at a tangent junction, on top of the
/// corner rule. G-code rounds coordinates (3 decimals tilt a 1 mm move's direction by up to
/// ~1e-3 rad), so a tangent line → arc junction read back from G-code is rarely tangent
/// within 1e-9; a blend of so small a corner does not remove the arc's curvature, and
/// without this cap the read-back program was timed 0.7 % faster than the program written.
pub const NEAR_TANGENT: f64 = 1e-3;

/// The speed cap at the junction from `g1` (whose corner mode is `mode`) into `g2`.
pub fn junction_cap(
    g1: &BlockGeometry,
    g2: &BlockGeometry,
    mode: JunctionMode,
    machine: &Machine,
) -> f64 {
    let t1 = g1.end_tangent();
    let t2 = g2.start_tangent();
    let du = t2 - t1;
    let dp = g2.derivatives(0.0)[1] - g1.derivatives(g1.length())[1];
    let tipo = machine.ipo_cycle;
    // The curvature step v²·|Δ(P'')_i| spread over one interpolation cycle.
    let (_, k1) = g1.curvature_ends();
    let (k2, _) = g2.curvature_ends();
    let dk = k2 - k1;
    let mut curvature_cap = f64::INFINITY;
    for (i, d) in dk.to_array().iter().enumerate() {
        let jm = machine.axes[i].max_jerk;
        if d.abs() > 1e-12 && jm.is_finite() {
            curvature_cap = curvature_cap.min((jm * tipo / d.abs()).sqrt());
        }
    }
    let deflection = du.length();
    if deflection > 1e-9 {
        let cap = corner_cap(g1, g2, t1, t2, dp, mode, machine);
        return if deflection <= NEAR_TANGENT {
            cap.min(curvature_cap)
        } else {
            cap
        };
    }
    // Tangent: the curvature step, and the step of |P'| where a spiral meets another block.
    curvature_cap.min(speed_step_cap(dp, machine))
}

/// The step of `|P'|` where a spiral meets another block (P' is a unit tangent on lines and
/// circles only): the axis velocities step by `ṡ·(P'₂ − P'₁)` within one interpolation cycle,
/// as at an exact-path corner.
pub(crate) fn speed_step_cap(dp: Vec3, machine: &Machine) -> f64 {
    let tipo = machine.ipo_cycle;
    let mut cap = f64::INFINITY;
    for (i, e) in dp.to_array().iter().enumerate() {
        let ax = machine.axes[i];
        if e.abs() > 1e-15 {
            let step = (ax.max_acceleration * tipo).min(ax.max_jerk * tipo * tipo);
            cap = cap.min(step / e.abs());
        }
    }
    cap
}

/// The cap of a corner (`t1 ≠ t2`) by its mode (see the module docs).
pub(crate) fn corner_cap(
    g1: &BlockGeometry,
    g2: &BlockGeometry,
    t1: Vec3,
    t2: Vec3,
    dp: Vec3,
    mode: JunctionMode,
    machine: &Machine,
) -> f64 {
    let tipo = machine.ipo_cycle;
    let mut cap = f64::INFINITY;
    match mode {
        JunctionMode::Stop => 0.0,
        JunctionMode::ExactPath => {
            // The axis velocities step by ṡ·(P'₂ − P'₁) (unit tangents on lines and
            // circles; a spiral's P' is not unit).
            for (i, d) in dp.to_array().iter().enumerate() {
                let ax = machine.axes[i];
                let step = (ax.max_acceleration * tipo).min(ax.max_jerk * tipo * tipo);
                if d.abs() > 1e-15 {
                    cap = cap.min(step / d.abs());
                }
            }
            cap
        }
        JunctionMode::Blend(tol) => {
            let c = t1.dot(t2).clamp(-1.0, 1.0);
            let half = 0.5 * c.acos();
            let (sh, ch) = half.sin_cos();
            if 1.0 - ch <= 0.0 || ch <= 1e-12 {
                return 0.0;
            }
            let r_tol = tol * ch / (1.0 - ch);
            let r_fit = 0.5 * g1.length().min(g2.length()) * ch / sh;
            let r = r_tol.min(r_fit);
            let a = machine
                .axes
                .iter()
                .map(|x| x.max_acceleration)
                .fold(f64::INFINITY, f64::min);
            let j = machine
                .axes
                .iter()
                .map(|x| x.max_jerk)
                .fold(f64::INFINITY, f64::min);
            cap = (a * r).sqrt();
            if j.is_finite() {
                cap = min_cbrt(cap, j * r * r);
            }
            cap
        }
    }
}

/// Whether [`corner_cap`]'s blend cap (mode `Blend(tol)`, `tol > 0`, unit tangents with
/// `t1·t2 = dot`, shorter block `lmin`) is surely at least `v`, without its trigonometry.
///
/// With `c = t1·t2` (`u = 1 − c`, exact for `c ≥ ½`), `cos(θ/2) = √((1+c)/2)`,
/// `sin(θ/2) = √(u/2)` and `1 − cos(θ/2) = u/(2(1 + cos(θ/2)))` (no cancellation). The blend
/// cap computes `acos`, `sin_cos` and `1 − cos(θ/2)` directly, each within 2e-16 of these
/// (absolute, near 1); the radii here take that and their own rounding as margins (4e-16
/// absolute, 1e-12 relative), so they are at most what the blend cap computes, and the cap is
/// at least `v` when the smaller radius reaches `max(v²/A, √(v³/J))` by 1e-9 more. Only for
/// `½ ≤ c` and `u > 1e-12` (a deflection above 1.4e-6 rad: below, the cap's own
/// `1 − cos(θ/2)` may round to 0); otherwise `false`.
pub(crate) fn blend_cap_reaches(dot: f64, lmin: f64, tol: f64, machine: &Machine, v: f64) -> bool {
    let c = dot.clamp(-1.0, 1.0);
    let u = 1.0 - c;
    if !(c >= 0.5 && u > 1e-12 && tol > 0.0 && v > 0.0 && v.is_finite()) {
        return false;
    }
    let ch = ((1.0 + c) / 2.0).sqrt();
    let sh = (u / 2.0).sqrt();
    let om = u / (2.0 * (1.0 + ch));
    let ch_lo = ch - 4e-16;
    let r_tol = tol * ch_lo / (om * (1.0 + 1e-12) + 4e-16) * (1.0 - 1e-12);
    let r_fit = 0.5 * lmin * ch_lo / (sh * (1.0 + 1e-12)) * (1.0 - 1e-12);
    let r = r_tol.min(r_fit);
    let a = machine
        .axes
        .iter()
        .map(|x| x.max_acceleration)
        .fold(f64::INFINITY, f64::min);
    let j = machine
        .axes
        .iter()
        .map(|x| x.max_jerk)
        .fold(f64::INFINITY, f64::min);
    let mut need = v * v / a;
    if j.is_finite() {
        need = need.max((v * v * v / j).sqrt());
    }
    r.is_finite() && r >= need * (1.0 + 1e-9)
}

/// `cap.min(x.cbrt())`, without the cube root when `x` is above `cap³` by more than the
/// rounding of that cube (then `∛x ≥ cap` exactly, and a correctly or faithfully rounded root
/// is `≥ cap` too): the same value either way, for the caps computed at every junction. Caps
/// below 1e-100 (whose cube would lose precision to underflow) always take the root.
pub(crate) fn min_cbrt(cap: f64, x: f64) -> f64 {
    if above_cube(cap, x) {
        cap
    } else {
        cap.min(x.cbrt())
    }
}

/// Whether `∛x ≥ cap` is sure without the root (see [`min_cbrt`]).
pub(crate) fn above_cube(cap: f64, x: f64) -> bool {
    (1e-100..f64::INFINITY).contains(&cap) && x > cap * cap * cap * (1.0 + 1e-12)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;

    /// When the root-free test says a blend cap reaches `v`, the blend cap computed with its
    /// trigonometry does: a grid of 57,600 cases (corners from 1e-7 to 1.2 rad, blocks of
    /// 1 µm to 1 m, tolerances of 1 µm to 1 mm, `v` within 1e-8 of the cap and far from it,
    /// on the four presets), of which at least 10,000 pass the test.
    #[test]
    fn blend_cap_reaches_only_where_the_cap_does() {
        let mut passed = 0;
        for name in Machine::PRESET_NAMES {
            let m = Machine::preset(name).unwrap();
            for ia in 0..30 {
                let angle = 10f64.powf(-7.0 + 7.08 * f64::from(ia) / 29.0);
                for il in 0..8 {
                    let len = 10f64.powf(-3.0 + 6.0 * f64::from(il) / 7.0);
                    let from = Point3::new(-len, 0.0, 0.0);
                    let g1 = BlockGeometry::of(from, &Move::line(Point3::ORIGIN, 100.0)).unwrap();
                    let to = Point3::new(len * angle.cos(), len * angle.sin(), 0.0);
                    let g2 = BlockGeometry::of(Point3::ORIGIN, &Move::line(to, 100.0)).unwrap();
                    let (t1, t2) = (g1.end_tangent(), g2.start_tangent());
                    let lmin = g1.length().min(g2.length());
                    for it in 0..6 {
                        let tol = 10f64.powf(-3.0 + 0.6 * f64::from(it));
                        let mode = JunctionMode::Blend(tol);
                        let cap = corner_cap(&g1, &g2, t1, t2, t2 - t1, mode, &m);
                        for f in [1e-8, 1e-12, 0.0, -1e-12, -1e-8, -0.5, 0.9, -0.99, 3.0, 0.01] {
                            let v = cap * (1.0 + f);
                            if blend_cap_reaches(t1.dot(t2), lmin, tol, &m, v) {
                                passed += 1;
                                assert!(cap >= v, "{name}: cap {cap} < {v}: {angle} {len} {tol}");
                            }
                        }
                    }
                }
            }
        }
        assert!(passed >= 10_000, "{passed}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(4096))]
        /// The skipped cube root never changes the cap: 4096 pairs around `x = cap³` (within
        /// a few ulps and far from it), over 600 orders of magnitude.
        #[test]
        fn min_cbrt_is_min_of_the_root(
            lc in -120.0f64..120.0, rel in -1e-11f64..1e-11, far in -3.0f64..3.0,
            near in proptest::bool::ANY,
        ) {
            let cap = 10f64.powf(lc);
            let x = if near { cap.powi(3) * (1.0 + rel) } else { cap.powi(3) * 10f64.powf(far) };
            proptest::prop_assert_eq!(min_cbrt(cap, x).to_bits(), cap.min(x.cbrt()).to_bits());
        }
    }

    /// A tangent line → arc junction tilted by G-code rounding (1e-5 rad) keeps the tangent
    /// junction's curvature-step cap: without it the rounded program was timed faster than
    /// the exact one (the demo's read-back estimate, 0.7 %).
    #[test]
    fn near_tangent_corner_keeps_the_curvature_step_cap() {
        let m = Machine::preset("hsm").unwrap();
        let r = 24.51;
        let c = Point3::new(0.0, r, 0.0);
        let arc_from = Point3::ORIGIN;
        let arc = Move::arc_xy(Point3::new(-r, r, 0.0), c, false, 200.0);
        let g2 = BlockGeometry::of(arc_from, &arc).unwrap();
        let cap_of = |tilt: f64| {
            let from = Point3::new(40.0, 40.0 * tilt, 0.0);
            let g1 = BlockGeometry::of(from, &Move::line(arc_from, 200.0)).unwrap();
            junction_cap(&g1, &g2, JunctionMode::Blend(m.path_tolerance), &m)
        };
        let tangent = cap_of(0.0);
        // v²/r ≤ J·T_ipo on the axis the curvature turns into.
        let expected = (m.axes[1].max_jerk * m.ipo_cycle * r).sqrt();
        assert!(
            (tangent - expected).abs() <= 1e-9 * expected,
            "{tangent} vs {expected}"
        );
        for tilt in [1e-7, 1e-5, 5e-4] {
            let near = cap_of(tilt);
            assert!(
                near <= tangent * (1.0 + 1e-3),
                "tilt {tilt}: {near} vs {tangent}"
            );
        }
        // A real corner is a blend, capped by its own rule only.
        assert!(cap_of(0.1) > 0.0);
    }
}
