//! Block geometry as the planner sees it: lines and helical arcs (arcs are helices with zero
//! pitch), parametrised by arc length, with the derivatives the planner needs.

use crate::error::Error;
use crate::geom::{MAX_COORDINATE_MM, Point3, Vec3};
use crate::toolpath::{Move, MoveKind, Plane};

/// The geometry of one block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlockGeometry {
    /// A straight line; with `dir` zero, a move of the rotary axes alone (the `linuxcnc`
    /// model's), whose `length` is their chord (in degrees, as LinuxCNC measures it).
    Line {
        /// Start point.
        from: Point3,
        /// Unit direction (zero on a rotary-only block).
        dir: Vec3,
        /// Length in mm (degrees on a rotary-only block).
        length: f64,
    },
    /// A circular arc or helix.
    Helix {
        /// The plane.
        plane: Plane,
        /// Centre, in-plane coordinates.
        cu: f64,
        /// Centre, in-plane coordinates.
        cv: f64,
        /// Start angle.
        theta0: f64,
        /// Signed sweep (positive counter-clockwise).
        sweep: f64,
        /// Start radius.
        r0: f64,
        /// End radius (differs from `r0` by the input's rounding or within LinuxCNC's
        /// tolerance: the arc is then a spiral, see [`BlockGeometry::derivatives`]).
        r1: f64,
        /// Axial start.
        w0: f64,
        /// Axial change.
        dw: f64,
        /// Length in mm.
        length: f64,
    },
    /// A circular arc in any plane, after an optional straight lead (a blend arc of the
    /// `linuxcnc` controller model, which also takes the rest of a short line it consumes).
    Arc3 {
        /// Where the lead starts (the arc starts `lead` further along `lead_dir`).
        start: Point3,
        /// Unit direction of the lead (the arc's start tangent).
        lead_dir: Vec3,
        /// Length of the lead in mm (0 without one).
        lead: f64,
        /// Centre of the arc.
        center: Point3,
        /// Unit vector from the centre to the arc's start.
        e0: Vec3,
        /// Unit vector in the arc's plane, perpendicular to `e0`, along the motion.
        e1: Vec3,
        /// Radius in mm.
        radius: f64,
        /// Angle in radians (> 0).
        angle: f64,
        /// Length in mm (`lead + radius·angle`).
        length: f64,
    },
}

impl BlockGeometry {
    /// The geometry of `m` starting at `from`; `None` for dwells and zero-length moves.
    pub fn of(from: Point3, m: &Move) -> Option<BlockGeometry> {
        match m.kind {
            MoveKind::Dwell { .. } => None,
            MoveKind::Rapid | MoveKind::Line => {
                let d = m.to - from;
                let length = d.length();
                if length.is_nan() || length <= 1e-12 {
                    return None;
                }
                Some(BlockGeometry::Line {
                    from,
                    dir: d / length,
                    length,
                })
            }
            MoveKind::Arc { center, plane, .. } => {
                let (r0, sweep) = m.sweep_from(from)?;
                let (su, sv, w0) = plane.split(from - Point3::ORIGIN);
                let (cu, cv, _) = plane.split(center - Point3::ORIGIN);
                let (eu, ev, w1) = plane.split(m.to - Point3::ORIGIN);
                let r1 = (eu - cu).hypot(ev - cv);
                let dw = w1 - w0;
                let length = (0.5 * (r0 + r1) * sweep).hypot(dw);
                if length.is_nan() || length <= 1e-12 || r0.is_nan() || r0 <= 1e-12 {
                    return None;
                }
                Some(BlockGeometry::Helix {
                    plane,
                    cu,
                    cv,
                    theta0: (sv - cv).atan2(su - cu),
                    sweep,
                    r0,
                    r1,
                    w0,
                    dw,
                    length,
                })
            }
        }
    }

    /// Length in mm.
    pub fn length(&self) -> f64 {
        match *self {
            BlockGeometry::Line { length, .. }
            | BlockGeometry::Helix { length, .. }
            | BlockGeometry::Arc3 { length, .. } => length,
        }
    }

    /// Position and the first three derivatives with respect to the block's parameter `s`
    /// (arc length on lines and circles) at `s`.
    ///
    /// An arc is the spiral `P(s) = c + r(s)·e_r(θ(s)) + w(s)·e_w` with `r`, `θ` and `w`
    /// linear in `s` (`r' = (r1 − r0)/L`, `θ' = sweep/L`, `h = w' = dw/L`, `L` the nominal
    /// length of [`Move::length_from`]); with `e_r' = θ'·e_θ` and `e_θ' = −θ'·e_r`:
    /// * `P'   = r'·e_r + r·θ'·e_θ + h·e_w`
    /// * `P''  = −r·θ'²·e_r + 2r'·θ'·e_θ`
    /// * `P''' = −3r'·θ'²·e_r − r·θ'³·e_θ`
    ///
    /// For a circle (`r' = 0`) `|P'| = 1` and `P''` is the curvature vector `κN`. For a
    /// spiral (an arc whose end is off its start circle by the input's rounding, or a tiny
    /// arc within LinuxCNC's absolute tolerance) `s` is not exactly arc length and the radial
    /// terms matter: on an arc of radius 5e-8 mm → 9e-7 mm found by the fuzzer they
    /// dominate.
    pub fn derivatives(&self, s: f64) -> [Vec3; 4] {
        match *self {
            BlockGeometry::Line { from, dir, length } => {
                let p = from + dir * s.clamp(0.0, length);
                [p - Point3::ORIGIN, dir, Vec3::ZERO, Vec3::ZERO]
            }
            BlockGeometry::Helix {
                plane,
                cu,
                cv,
                theta0,
                sweep,
                r0,
                r1,
                w0,
                dw,
                length,
            } => {
                let f = (s / length).clamp(0.0, 1.0);
                let r = r0 + (r1 - r0) * f;
                let rp = (r1 - r0) / length;
                let om = sweep / length;
                let th = theta0 + sweep * f;
                let (sn, cs) = th.sin_cos();
                let h = dw / length;
                // Components along e_r = (cs, sn) and e_θ = (−sn, cs).
                let polar =
                    |er: f64, et: f64, w: f64| plane.join(er * cs - et * sn, er * sn + et * cs, w);
                [
                    plane.join(cu + r * cs, cv + r * sn, w0 + dw * f),
                    polar(rp, r * om, h),
                    polar(-r * om * om, 2.0 * rp * om, 0.0),
                    polar(-3.0 * rp * om * om, -r * om.powi(3), 0.0),
                ]
            }
            BlockGeometry::Arc3 {
                start,
                lead_dir,
                lead,
                center,
                e0,
                e1,
                radius,
                angle,
                ..
            } => {
                let s = s.clamp(0.0, lead + radius * angle);
                if s < lead {
                    return [
                        (start + lead_dir * s) - Point3::ORIGIN,
                        lead_dir,
                        Vec3::ZERO,
                        Vec3::ZERO,
                    ];
                }
                let (sn, cs) = ((s - lead) / radius).sin_cos();
                let radial = e0 * cs + e1 * sn;
                let tangent = e1 * cs - e0 * sn;
                [
                    (center + radial * radius) - Point3::ORIGIN,
                    tangent,
                    radial * (-1.0 / radius),
                    tangent * (-1.0 / (radius * radius)),
                ]
            }
        }
    }

    /// Bounds `(g1, g2, g3)` of `|P'|`, `|P''|`, `|P'''|` over the block (see
    /// [`BlockGeometry::derivatives`]): with `r ≤ r_max = max(r0, r1)`,
    /// `g1 = √(r'² + r_max²θ'² + h²)`, `g2 = |θ'|·√(r_max²θ'² + 4r'²)`,
    /// `g3 = θ'²·√(r_max²θ'² + 9r'²)`. Lines: `(1, 0, 0)`. For a helix of radius `r` and
    /// pitch `2πc` these are `1`, the curvature `κ = r/(r² + c²)` and `κ·√(κ² + τ²)`.
    pub fn derivative_bounds(&self) -> (f64, f64, f64) {
        match *self {
            BlockGeometry::Line { .. } => (1.0, 0.0, 0.0),
            BlockGeometry::Helix {
                sweep,
                r0,
                r1,
                dw,
                length,
                ..
            } => {
                let rm = r0.max(r1);
                let rp = (r1 - r0) / length;
                let om = (sweep / length).abs();
                let h = dw / length;
                let g1 = rp.hypot(rm * om).hypot(h);
                let g2 = om * (rm * om).hypot(2.0 * rp);
                let g3 = om * om * (rm * om).hypot(3.0 * rp);
                (g1, g2, g3)
            }
            BlockGeometry::Arc3 { radius, .. } => (1.0, 1.0 / radius, 1.0 / (radius * radius)),
        }
    }

    /// Position at arc length `s`.
    pub fn point(&self, s: f64) -> Point3 {
        Point3::ORIGIN + self.derivatives(s)[0]
    }

    /// Unit tangent at the start.
    pub fn start_tangent(&self) -> Vec3 {
        unit(self.derivatives(0.0)[1])
    }

    /// Unit tangent at the end.
    pub fn end_tangent(&self) -> Vec3 {
        unit(self.derivatives(self.length())[1])
    }

    /// `P''` at the start and at the end (the curvature vector `κN` on circles; zero on
    /// lines).
    pub fn curvature_ends(&self) -> (Vec3, Vec3) {
        (self.derivatives(0.0)[2], self.derivatives(self.length())[2])
    }

    /// The largest absolute component of `P'` along each axis over the block.
    pub fn max_direction(&self) -> [f64; 3] {
        match *self {
            BlockGeometry::Line { dir, .. } => [dir.x.abs(), dir.y.abs(), dir.z.abs()],
            BlockGeometry::Helix {
                plane,
                r0,
                r1,
                sweep,
                dw,
                length,
                ..
            } => {
                // In the plane |P'| = √(r'² + r²θ'²): at most 1 on a circle, possibly more on
                // a spiral, whose parameter is not exactly arc length.
                let inplane = ((r1 - r0) / length).hypot(r0.max(r1) * sweep / length);
                let axial = (dw / length).abs();
                let v = plane.join(inplane, inplane, axial);
                [v.x.abs(), v.y.abs(), v.z.abs()]
            }
            BlockGeometry::Arc3 {
                lead_dir,
                lead,
                e0,
                e1,
                ..
            } => {
                // The tangent −sin·e0 + cos·e1 has components at most √(e0ᵢ² + e1ᵢ²).
                let arc = |i: usize| e0.to_array()[i].hypot(e1.to_array()[i]);
                let line = |i: usize| {
                    if lead > 0.0 {
                        lead_dir.to_array()[i].abs()
                    } else {
                        0.0
                    }
                };
                [
                    arc(0).max(line(0)),
                    arc(1).max(line(1)),
                    arc(2).max(line(2)),
                ]
            }
        }
    }
}

fn unit(v: Vec3) -> Vec3 {
    v.normalize().unwrap_or(Vec3::ZERO)
}

/// The slowest feed a feed move may have, mm/s (0.00006 mm/min): below it the time of a
/// block overflows long before it means anything.
pub const MIN_FEED: f64 = 1e-6;

/// The longest dwell, s (11.6 days): keeps the total time of any program finite.
pub const MAX_DWELL: f64 = 1e6;

/// Checks move `i` (from `from`) and returns its geometry (`None` for dwells and zero-length
/// moves): coordinates within range, arcs circular within LinuxCNC's tolerance, a feed on
/// every feed move, dwells within [`MAX_DWELL`].
pub(crate) fn check_move(i: usize, from: Point3, m: &Move) -> Result<Option<BlockGeometry>, Error> {
    // Coordinates beyond ±1e6 mm overflow lengths and times (a target at 1e300 gave an
    // infinite cycle time; found by the `planner` fuzzer).
    let far = |p: Point3| {
        !(p.x.abs() <= MAX_COORDINATE_MM
            && p.y.abs() <= MAX_COORDINATE_MM
            && p.z.abs() <= MAX_COORDINATE_MM)
    };
    let centre = match m.kind {
        MoveKind::Arc { center, .. } => Some(center),
        _ => None,
    };
    for (what, p) in [
        ("start point", Some(from)),
        ("end point", Some(m.to)),
        ("arc centre", centre),
    ] {
        if let Some(p) = p
            && far(p)
        {
            return Err(
                crate::InputError::new(what, format!("({}, {}, {})", p.x, p.y, p.z))
                    .at(format!("move {}", i + 1))
                    .expected(format!("finite coordinates within ±{MAX_COORDINATE_MM} mm"))
                    .into(),
            );
        }
    }
    let g = BlockGeometry::of(from, m);
    if g.is_none()
        && matches!(m.kind, MoveKind::Arc { .. })
        && (from.distance(m.to) > 1e-12 || m.length_from(from) > 1e-12)
    {
        // An arc whose start is its centre has no circle to follow; skipping it as a
        // zero-length move teleported the tool to its end (a 32 mm jump found by the
        // `planner` fuzzer).
        let r0 = m.sweep_from(from).map_or(0.0, |(r, _)| r);
        return Err(crate::InputError::new("arc start radius", r0)
            .at(format!("move {}", i + 1))
            .expected("a start point more than 1e-12 mm from the arc's centre")
            .into());
    }
    if let Some(BlockGeometry::Helix { r0, r1, .. }) = g {
        // The block limits take the arc as circular (a spiral's radial terms are not
        // modelled): arcs whose end radius differs from the start radius beyond what
        // LinuxCNC accepts (and the G-code reader with it) are refused, not mistimed.
        let tau = crate::toolpath::arc_rule::CENTER_ARC_RADIUS_TOLERANCE_MM;
        if crate::toolpath::arc_rule::radii_mismatch(r0, r1, tau) {
            return Err(crate::InputError::new("arc end radius", r1)
                .at(format!("move {}", i + 1))
                .expected(format!(
                    "within {tau:.4} mm or 0.1 % of the start radius {r0} mm (a circular arc)"
                ))
                .into());
        }
    }
    let length = g.as_ref().map_or(0.0, BlockGeometry::length);
    if m.is_feed() && !(m.feed.is_finite() && m.feed >= MIN_FEED) && length > 0.0 {
        return Err(crate::InputError::new("feed", m.feed)
            .at(format!("move {}", i + 1))
            .expected(format!("a finite feed >= {MIN_FEED} mm/s on a feed move"))
            .into());
    }
    if let MoveKind::Dwell { seconds } = m.kind
        && !(seconds.is_finite() && (0.0..=MAX_DWELL).contains(&seconds))
    {
        return Err(crate::InputError::new("dwell", seconds)
            .at(format!("move {}", i + 1))
            .expected(format!("a number of seconds in [0, {MAX_DWELL}]"))
            .into());
    }
    Ok(g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// Root cause of the fuzzer's acceleration/jerk violations on tiny arcs: a spiral arc
        /// (end radius ≠ start radius) was differentiated as a circle. The derivatives must
        /// match central differences of the position, and `derivative_bounds` must bound them
        /// everywhere on the block.
        #[test]
        fn spiral_derivatives_match_finite_differences_and_bounds(
            r0 in 0.5f64..5.0, ratio in 0.2f64..5.0, a0 in -3.0f64..3.0, a1 in -3.0f64..3.0,
            dz in -2.0f64..2.0, ccw in any::<bool>(), turns in 0u32..2, plane in 0usize..3,
        ) {
            let plane = [Plane::Xy, Plane::Zx, Plane::Yz][plane];
            let c = Point3::new(1.0, -2.0, 0.5);
            let (su, sv) = (r0 * a0.cos(), r0 * a0.sin());
            let r1 = r0 * ratio;
            let (eu, ev) = (r1 * a1.cos(), r1 * a1.sin());
            let from = c + plane.join(su, sv, 0.0);
            let to = c + plane.join(eu, ev, dz);
            let mut m = Move::arc_xy(to, c, ccw, 10.0);
            if let MoveKind::Arc { plane: p, turns: t, .. } = &mut m.kind {
                *p = plane;
                *t = turns;
            }
            let g = BlockGeometry::of(from, &m).expect("geometry");
            prop_assert!((g.length() - m.length_from(from)).abs() <= 1e-12 * g.length());
            prop_assert!((g.point(g.length()) - to).length() <= 1e-9);
            let (g1, g2, g3) = g.derivative_bounds();
            let l = g.length();
            let h = 1e-4 * l;
            for k in 1..20 {
                let s = l * f64::from(k) / 20.0;
                let [_, d1, d2, d3] = g.derivatives(s);
                let fd = |i: usize| {
                    (g.derivatives(s + h)[i] - g.derivatives(s - h)[i]) / (2.0 * h)
                };
                for (i, (d, lower)) in [(d1, 0usize), (d2, 1), (d3, 2)].into_iter().enumerate() {
                    let e = fd(lower);
                    prop_assert!((d - e).length() <= 1e-5 * (1.0 + d.length()),
                        "derivative {}: {d:?} vs {e:?}", i + 1);
                }
                prop_assert!(d1.length() <= g1 * (1.0 + 1e-12));
                prop_assert!(d2.length() <= g2 * (1.0 + 1e-12));
                prop_assert!(d3.length() <= g3 * (1.0 + 1e-12));
                let md = g.max_direction();
                for (x, m) in d1.to_array().iter().zip(md) {
                    prop_assert!(x.abs() <= m * (1.0 + 1e-12) + 1e-15);
                }
            }
        }
    }
}
