//! When an arc is a circle: LinuxCNC's centre-format rule, shared by the G-code reader (which
//! refuses arcs that break it) and the motion planner (which times arcs as circular).
//!
//! With `r₀`, `r₁` the distances from the centre to the start and end, `Δ = |r₁ − r₀|` and the
//! absolute tolerance `τ` (`2·0.01·√2` mm for a program in millimetres), the arc is accepted
//! unless `Δ > 100 τ`, or `Δ / max(r₀, r₁) > 0.001` and `Δ > τ` (LinuxCNC 2.9,
//! `interp_arc.cc`). A radius below [`RADIUS_TOLERANCE_MM`] is no arc at all.

use std::f64::consts::SQRT_2;

/// LinuxCNC's `SPIRAL_RELATIVE_TOLERANCE`.
pub const SPIRAL_RELATIVE_TOLERANCE: f64 = 0.001;

/// LinuxCNC's `RADIUS_TOLERANCE_MM` (0.00005 in): smallest arc radius, and how far an `R`
/// may fall short of half the chord.
pub const RADIUS_TOLERANCE_MM: f64 = 0.00005 * 25.4;

/// LinuxCNC's `CENTER_ARC_RADIUS_TOLERANCE` for a program in millimetres, mm: `2·0.01·√2`.
pub const CENTER_ARC_RADIUS_TOLERANCE_MM: f64 = 2.0 * 0.01 * SQRT_2;

/// Whether start radius `r0` and end radius `r1` (mm) differ beyond LinuxCNC's rule with the
/// absolute tolerance `tau` (mm): such an arc is a spiral, refused by the reader and the planner.
pub fn radii_mismatch(r0: f64, r1: f64, tau: f64) -> bool {
    let delta = (r1 - r0).abs();
    delta > 100.0 * tau || (delta / r0.max(r1) > SPIRAL_RELATIVE_TOLERANCE && delta > tau)
}
