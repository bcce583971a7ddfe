//! LinuxCNC's circle (`PmCircle` of `libnml/posemath/_posemath.c`): the arcs and helices of
//! its segment queue, in 3-D vectors, with the point, tangent and stretch functions its blend
//! code uses.
//!
//! A circle is `P(φ) = c + ρ(φ)·(cos φ·r̂_t + sin φ·r̂_p) + (φ/Φ)·h` for `φ ∈ [0, Φ]`, with
//! `r_t` the start radius vector, `r_p = n × r_t`, `ρ(φ) = r + (φ/Φ)·spiral` and `h` the
//! helical displacement along the normal `n` (the arc turns counter-clockwise about `n`).

use crate::geom::{Point3, Vec3};
use crate::motion::path::BlockGeometry;
use crate::toolpath::Plane;

/// A LinuxCNC circle, with the plane it came from (to turn it back into a [`BlockGeometry`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Circle {
    /// Centre (at the start's height along the normal).
    pub center: Point3,
    /// Unit normal; the arc turns counter-clockwise about it.
    pub normal: Vec3,
    /// Centre → start, length `radius`.
    pub r_tan: Vec3,
    /// `normal × r_tan`.
    pub r_perp: Vec3,
    /// Displacement along the normal over the whole arc.
    pub r_helix: Vec3,
    /// Start radius.
    pub radius: f64,
    /// Total angle (> 0).
    pub angle: f64,
    /// End radius − start radius.
    pub spiral: f64,
    /// The G-code plane.
    pub plane: Plane,
}

impl Circle {
    /// The circle of an arc block; `None` for other geometry.
    pub fn of(g: &BlockGeometry) -> Option<Circle> {
        let BlockGeometry::Helix {
            plane,
            cu,
            cv,
            theta0,
            sweep,
            r0,
            r1,
            w0,
            dw,
            ..
        } = *g
        else {
            return None;
        };
        let n = plane.join(0.0, 0.0, 1.0);
        let normal = if sweep >= 0.0 { n } else { -n };
        let (sn, cs) = theta0.sin_cos();
        let r_tan = plane.join(r0 * cs, r0 * sn, 0.0);
        Some(Circle {
            center: Point3::ORIGIN + plane.join(cu, cv, w0),
            normal,
            r_tan,
            r_perp: normal.cross(r_tan),
            r_helix: plane.join(0.0, 0.0, dw),
            radius: r0,
            angle: sweep.abs(),
            spiral: r1 - r0,
            plane,
        })
    }

    /// `pmCirclePoint`: the point at angle `phi` from the start.
    pub fn point(&self, phi: f64) -> Point3 {
        let (sn, cs) = phi.sin_cos();
        let radial = self.r_tan * cs + self.r_perp * sn;
        let scale = phi / self.angle;
        let unit = radial.normalize().unwrap_or(Vec3::ZERO);
        self.center + radial + unit * (scale * self.spiral) + self.r_helix * scale
    }

    /// `pmCircleTangentVector`: the unit tangent at angle `phi`.
    pub fn tangent(&self, phi: f64) -> Vec3 {
        let radius = self.point(phi) - self.center;
        let u_tan = self.normal.cross(radius);
        let d_helix = self.r_helix * (1.0 / self.angle);
        let d_radial = radius.normalize().unwrap_or(Vec3::ZERO) * (self.spiral / self.angle);
        (u_tan + d_helix + d_radial)
            .normalize()
            .unwrap_or(Vec3::ZERO)
    }

    /// `pmCircleEffectiveMinRadius`: the radius of curvature the speed cap uses.
    pub fn effective_min_radius(&self) -> f64 {
        let dr = self.spiral / self.angle;
        let h2 = self.r_helix.dot(self.r_helix);
        let n_inner = dr * dr + self.radius * self.radius;
        let den = n_inner + dr * dr;
        let r_spiral = (n_inner * n_inner * n_inner).sqrt() / den;
        h2 / r_spiral + r_spiral
    }

    /// `pmCircleStretch`: keeps `new_angle` of the arc, cutting its end (`from_end` false) or
    /// its start (`from_end` true); `None` where LinuxCNC refuses (helices, angles ≤ 1e-10).
    pub fn stretched(&self, new_angle: f64, from_end: bool) -> Option<Circle> {
        if new_angle <= 1e-10 || self.r_helix.dot(self.r_helix) > 1e-6 {
            return None;
        }
        let mut c = *self;
        if from_end {
            let start = self.point(self.angle - new_angle);
            c.r_tan = start - self.center;
            c.r_perp = c.normal.cross(c.r_tan);
            c.radius = c.r_tan.length();
        }
        c.spiral *= new_angle / self.angle;
        c.angle = new_angle;
        Some(c)
    }

    /// Arc length (the planner's, with the mean radius).
    pub fn length(&self) -> f64 {
        ((self.radius + 0.5 * self.spiral) * self.angle).hypot(self.r_helix.length())
    }

    /// The circle as planner geometry.
    pub fn geom(&self) -> BlockGeometry {
        let (su, sv, w0) = self
            .plane
            .split(self.r_tan + (self.center - Point3::ORIGIN));
        let (cu, cv, _) = self.plane.split(self.center - Point3::ORIGIN);
        let n = self.plane.join(0.0, 0.0, 1.0);
        let sign = if self.normal.dot(n) >= 0.0 { 1.0 } else { -1.0 };
        let (_, _, dw) = self.plane.split(self.r_helix);
        BlockGeometry::Helix {
            plane: self.plane,
            cu,
            cv,
            theta0: (sv - cv).atan2(su - cu),
            sweep: sign * self.angle,
            r0: self.radius,
            r1: self.radius + self.spiral,
            w0,
            dw,
            length: self.length(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::Move;

    /// The circle of an arc block reproduces the block's own points, tangents and length,
    /// both ways round, and stretching keeps the remaining arc on the circle.
    #[test]
    fn circle_matches_the_block_geometry() {
        for ccw in [true, false] {
            let from = Point3::new(5.0, 0.0, 1.0);
            let m = Move::arc_xy(
                Point3::new(0.0, 5.0, 1.0),
                Point3::new(0.0, 0.0, 1.0),
                ccw,
                10.0,
            );
            let g = BlockGeometry::of(from, &m).unwrap();
            let c = Circle::of(&g).unwrap();
            assert!((c.length() - g.length()).abs() < 1e-12);
            for k in 0..=10 {
                let f = f64::from(k) / 10.0;
                let p = c.point(f * c.angle);
                let q = g.point(f * g.length());
                assert!(p.distance(q) < 1e-9, "{p:?} {q:?}");
                let t = c.tangent(f * c.angle);
                let u = g.derivatives(f * g.length())[1];
                assert!((t - u).length() < 1e-9);
            }
            let back = c.geom();
            assert!(back.point(0.0).distance(from) < 1e-12);
            let cut = c.stretched(0.5 * c.angle, true).unwrap();
            assert!(cut.point(0.0).distance(c.point(0.5 * c.angle)) < 1e-12);
            assert!(cut.point(cut.angle).distance(m.to) < 1e-9);
            let g2 = cut.geom();
            assert!(g2.point(g2.length()).distance(m.to) < 1e-9);
        }
    }
}
