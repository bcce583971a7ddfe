//! Block geometry as the planner sees it: lines and helical arcs (arcs are helices with zero
//! pitch), parametrised by arc length, with the derivatives the planner needs.

use crate::geom::{Point3, Vec3};
use crate::toolpath::{Move, MoveKind, Plane};

/// The geometry of one block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Geom {
    /// A straight line.
    Line {
        /// Start point.
        from: Point3,
        /// Unit direction.
        dir: Vec3,
        /// Length in mm.
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
        /// End radius (differs from `r0` only by the input's rounding).
        r1: f64,
        /// Axial start.
        w0: f64,
        /// Axial change.
        dw: f64,
        /// Length in mm.
        length: f64,
    },
}

impl Geom {
    /// The geometry of `m` starting at `from`; `None` for dwells and zero-length moves.
    pub fn of(from: Point3, m: &Move) -> Option<Geom> {
        match m.kind {
            MoveKind::Dwell { .. } => None,
            MoveKind::Rapid | MoveKind::Line => {
                let d = m.to - from;
                let length = d.length();
                if length.is_nan() || length <= 1e-12 {
                    return None;
                }
                Some(Geom::Line {
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
                Some(Geom::Helix {
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
            Geom::Line { length, .. } | Geom::Helix { length, .. } => length,
        }
    }

    /// Position and the first three derivatives with respect to arc length at `s`.
    pub fn derivatives(&self, s: f64) -> [Vec3; 4] {
        match *self {
            Geom::Line { from, dir, length } => {
                let p = from + dir * s.clamp(0.0, length);
                [p - Point3::ORIGIN, dir, Vec3::ZERO, Vec3::ZERO]
            }
            Geom::Helix {
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
                let om = sweep / length;
                let th = theta0 + sweep * f;
                let (sn, cs) = th.sin_cos();
                let h = dw / length;
                [
                    plane.join(cu + r * cs, cv + r * sn, w0 + dw * f),
                    plane.join(-r * om * sn, r * om * cs, h),
                    plane.join(-r * om * om * cs, -r * om * om * sn, 0.0),
                    plane.join(r * om.powi(3) * sn, -r * om.powi(3) * cs, 0.0),
                ]
            }
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

    /// Curvature vector (κ·N) at the start and at the end (zero for lines).
    pub fn curvature_ends(&self) -> (Vec3, Vec3) {
        (self.derivatives(0.0)[2], self.derivatives(self.length())[2])
    }

    /// Curvature κ and torsion τ (constant on a helix; 0 for lines).
    pub fn curvature_torsion(&self) -> (f64, f64) {
        match *self {
            Geom::Line { .. } => (0.0, 0.0),
            Geom::Helix {
                sweep, r0, r1, dw, ..
            } => {
                let r = r0.min(r1);
                let c = dw / sweep; // pitch / 2π
                let den = r * r + c * c;
                (r0.max(r1) / den, c.abs() / den)
            }
        }
    }

    /// The largest absolute tangent component of each axis over the block.
    pub fn max_direction(&self) -> [f64; 3] {
        match *self {
            Geom::Line { dir, .. } => [dir.x.abs(), dir.y.abs(), dir.z.abs()],
            Geom::Helix {
                plane,
                r0,
                r1,
                sweep,
                dw,
                length,
                ..
            } => {
                let inplane = (r0.max(r1) * sweep.abs() / length).min(1.0);
                let axial = (dw / length).abs();
                let v = plane.join(inplane, inplane, axial);
                [v.x.abs(), v.y.abs(), v.z.abs()]
            }
        }
    }
}

fn unit(v: Vec3) -> Vec3 {
    v.normalize().unwrap_or(Vec3::ZERO)
}
