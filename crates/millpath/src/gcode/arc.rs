//! Arc geometry of G2/G3 blocks: the centre from `I J K` offsets or from `R`, the sweep, and
//! LinuxCNC's rule for start and end radii that disagree.
//!
//! All functions work in the two in-plane coordinates `(u, v)` of the active plane (see
//! [`crate::toolpath::Plane::split`]); G3 is counter-clockwise in `(u, v)`, seen from the
//! plane's positive normal, in all three planes.
//!
//! # The radius rule (LinuxCNC)
//! In centre format the radius to the start `r₁ = |s − c|` and to the end `r₂ = |e − c|` are
//! both known and rounding makes them disagree slightly. LinuxCNC's `Interp::arc_data_ijk`
//! (`src/emc/rs274ngc/interp_arc.cc`, LinuxCNC 2.8 and later) refuses the block
//! ("Radius to end of arc differs from radius to start") when, with `Δ = |r₁ − r₂|`,
//! `ρ = Δ / max(r₁, r₂)` and the absolute tolerance `τ`:
//!
//! ```text
//! Δ > 100·τ   or   (ρ > 0.001  and  Δ > τ)
//! ```
//!
//! where `τ = CENTER_ARC_RADIUS_TOLERANCE = 2·0.01·√2 mm ≈ 0.0283 mm` in G21 programs and
//! `2·0.001·√2 in ≈ 0.00283 in` in G20 programs (`interp_internal.hh`), and `0.001` is
//! `SPIRAL_RELATIVE_TOLERANCE`. Both radii below `RADIUS_TOLERANCE` (0.00005 in, 0.00127 mm)
//! make a "zero radius arc". We checked the rule against the installed `rs274`
//! (linuxcnc-uspace 2.9): r = 10 mm accepts Δ = 0.028 and refuses 0.029; r = 10 000 mm accepts
//! Δ = 2.8 (ρ < 0.1 %) and refuses 2.9 (> 100 τ). The estimator's reader applies the same rule,
//! so a program it accepts is one LinuxCNC accepts.
//!
//! # R format
//! With chord half-length `h = |e − s|/2` and radius `|R|`, the centre lies on the chord's
//! perpendicular bisector at distance `d = √(R² − h²)` from the midpoint `m`. For G2 with
//! `R > 0` (or G3 with `R < 0`) the centre is on the right of the chord direction
//! `t = (e − s)/|e − s|` (a clockwise arc of at most half a turn bends right around its centre),
//! so `c = m − d·perp(t)` with `perp(t) = (−t_v, t_u)`; otherwise `c = m + d·perp(t)`. As in
//! LinuxCNC, `h − |R| > RADIUS_TOLERANCE` is an error ("radius too small to reach the end
//! point") and `h` is clamped to `|R|` below it; `s = e` is an error (a full circle needs
//! centre format).

use super::Units;
pub use crate::toolpath::arc_rule::RADIUS_TOLERANCE_MM;
use crate::toolpath::arc_rule::{CENTER_ARC_RADIUS_TOLERANCE_MM, radii_mismatch};
use std::f64::consts::{SQRT_2, TAU};

/// LinuxCNC's `CENTER_ARC_RADIUS_TOLERANCE` in mm for a program in `units`: `2·0.01·√2` mm
/// (G21) or `2·0.001·√2` in (G20).
pub fn center_arc_radius_tolerance_mm(units: Units) -> f64 {
    match units {
        Units::Mm => CENTER_ARC_RADIUS_TOLERANCE_MM,
        Units::Inch => 2.0 * 0.001 * SQRT_2 * 25.4,
    }
}

/// Why an arc cannot be executed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ArcProblem {
    /// Start and end radii differ beyond the rule (radii in mm).
    RadiusMismatch {
        /// Radius to the start.
        start: f64,
        /// Radius to the end.
        end: f64,
    },
    /// A radius below [`RADIUS_TOLERANCE_MM`].
    ZeroRadius,
    /// `R` format: the radius cannot reach the end point (half chord and |R| in mm).
    RadiusTooSmall {
        /// Half the chord.
        half_chord: f64,
        /// |R|.
        radius: f64,
    },
    /// `R` format with the end equal to the start.
    SamePoint,
}

impl std::fmt::Display for ArcProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            ArcProblem::RadiusMismatch { start, end } => write!(
                f,
                "radius to end {end:.6} mm differs from radius to start {start:.6} mm by {:.6} mm",
                (end - start).abs()
            ),
            ArcProblem::ZeroRadius => {
                write!(f, "zero-radius arc (radius < {RADIUS_TOLERANCE_MM} mm)")
            }
            ArcProblem::RadiusTooSmall { half_chord, radius } => write!(
                f,
                "radius {radius:.6} mm too small to reach the end point (half chord {half_chord:.6} mm)"
            ),
            ArcProblem::SamePoint => write!(f, "R-format arc whose end is its start"),
        }
    }
}

/// Checks LinuxCNC's centre-format rule on the radii `r1` (start) and `r2` (end), in mm, for a
/// program in `units`.
pub fn check_radii(r1: f64, r2: f64, units: Units) -> Result<(), ArcProblem> {
    if !(r1 >= RADIUS_TOLERANCE_MM && r2 >= RADIUS_TOLERANCE_MM) {
        return Err(ArcProblem::ZeroRadius);
    }
    if radii_mismatch(r1, r2, center_arc_radius_tolerance_mm(units)) {
        return Err(ArcProblem::RadiusMismatch { start: r1, end: r2 });
    }
    Ok(())
}

/// The centre `(u, v)` of an `R`-format arc from `s` to `e` (in-plane, mm).
pub fn center_from_radius(
    s: (f64, f64),
    e: (f64, f64),
    radius: f64,
    ccw: bool,
) -> Result<(f64, f64), ArcProblem> {
    let (du, dv) = (e.0 - s.0, e.1 - s.1);
    let chord = du.hypot(dv);
    if chord == 0.0 {
        return Err(ArcProblem::SamePoint);
    }
    let r = radius.abs();
    let mut h = chord / 2.0;
    if r.is_nan() || r <= 0.0 || h - r > RADIUS_TOLERANCE_MM {
        return Err(ArcProblem::RadiusTooSmall {
            half_chord: h,
            radius: r,
        });
    }
    h = h.min(r);
    let d = (r * r - h * h).max(0.0).sqrt();
    let (tu, tv) = (du / chord, dv / chord);
    let (pu, pv) = (-tv, tu);
    let right = (!ccw && radius > 0.0) || (ccw && radius < 0.0);
    let sign = if right { -1.0 } else { 1.0 };
    let (mu, mv) = ((s.0 + e.0) / 2.0, (s.1 + e.1) / 2.0);
    Ok((mu + sign * d * pu, mv + sign * d * pv))
}

/// The sweep in `(0, 2π]` (unsigned) of an arc from `s` to `e` about `c`, as
/// [`crate::toolpath::Move::sweep_from`] reads it: end on start is a full circle.
pub fn unsigned_sweep(s: (f64, f64), e: (f64, f64), c: (f64, f64), ccw: bool) -> f64 {
    let a0 = (s.1 - c.1).atan2(s.0 - c.0);
    let a1 = (e.1 - c.1).atan2(e.0 - c.0);
    let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
    sweep = sweep.rem_euclid(TAU);
    if sweep <= 1e-12 { TAU } else { sweep }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn radius_rule_matches_rs274_thresholds() {
        // Measured with rs274 (see module docs).
        assert!(check_radii(10.0, 10.028, Units::Mm).is_ok());
        assert!(check_radii(10.0, 10.029, Units::Mm).is_err());
        assert!(check_radii(10_000.0, 10_002.8, Units::Mm).is_ok());
        assert!(check_radii(10_000.0, 10_002.9, Units::Mm).is_err());
        assert!(check_radii(25.4, 25.4 * 1.0028, Units::Inch).is_ok());
        assert!(check_radii(25.4, 25.4 * 1.0029, Units::Inch).is_err());
        assert_eq!(
            check_radii(0.001, 0.001, Units::Mm),
            Err(ArcProblem::ZeroRadius)
        );
        assert_eq!(
            check_radii(f64::NAN, 1.0, Units::Mm),
            Err(ArcProblem::ZeroRadius)
        );
    }

    #[test]
    fn r_format_picks_the_short_and_long_arcs() {
        // Quarter circle of radius 10 from (10,0) to (0,10): centre (0,0) for a short CCW arc.
        let c = center_from_radius((10.0, 0.0), (0.0, 10.0), 10.0, true).unwrap();
        assert!(c.0.abs() < 1e-12 && c.1.abs() < 1e-12, "{c:?}");
        assert!((unsigned_sweep((10.0, 0.0), (0.0, 10.0), c, true) - PI / 2.0).abs() < 1e-12);
        // R < 0: the long way round, centre (10,10).
        let c = center_from_radius((10.0, 0.0), (0.0, 10.0), -10.0, true).unwrap();
        assert!(
            (c.0 - 10.0).abs() < 1e-12 && (c.1 - 10.0).abs() < 1e-12,
            "{c:?}"
        );
        assert!((unsigned_sweep((10.0, 0.0), (0.0, 10.0), c, true) - 1.5 * PI).abs() < 1e-12);
        // Short CW arc: centre (10,10) as well, sweep a quarter.
        let c = center_from_radius((10.0, 0.0), (0.0, 10.0), 10.0, false).unwrap();
        assert!((unsigned_sweep((10.0, 0.0), (0.0, 10.0), c, false) - PI / 2.0).abs() < 1e-12);
        assert!(center_from_radius((0.0, 0.0), (30.0, 0.0), 10.0, true).is_err());
        assert!(center_from_radius((1.0, 1.0), (1.0, 1.0), 10.0, true).is_err());
    }
}
