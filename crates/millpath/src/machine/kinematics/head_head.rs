//! A head-head machine: the spindle head swivels C about Z and tilts B about its (rotated) Y;
//! the table does not rotate, so the workpiece frame is the machine frame.
//!
//! # Model
//! The linear joints `(X, Y, Z)` place the head's pivot (the intersection of the rotary axes).
//! The tool axis is `k = Rz(c) Ry(b) e_z = (cc·sb, sc·sb, cb)` and the tip lies `L` below the
//! pivot along it, `L` = pivot length + tool length:
//!
//! ```text
//! tip = (X, Y, Z) − L · k
//! ```
//! Inverse: `b = ±acos k_z`, `c = atan2(k_y, k_x)` (for `+b`; `c + π` for `−b`), then
//! `(X, Y, Z) = tip + L k`. The pole is `b = 0` (tool vertical), where C is free.
//!
//! Jacobian: `∂tip/∂(X,Y,Z) = I`, `∂k/∂b = Rz(c) G_y Ry(b) e_z`, `∂k/∂c = G_z Rz(c) Ry(b) e_z`,
//! `∂tip/∂(b, c) = −L ∂k/∂(b, c)`.

use super::{
    GEN_Y, GEN_Z, Jacobian, Joints, Kinematics, Orientation, Pose, RotaryRange, V3, arr_p, mm, mv,
    rot_y, rot_z, scale, set_col, tilt_swivel,
};
use crate::geom::{Point3, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A B/C head-head machine (lengths in mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HeadHead {
    /// Pivot length plus tool length, mm.
    pub length: f64,
    /// Range of the tilt B, rad.
    pub b_range: RotaryRange,
    /// Range of the swivel C, rad.
    pub c_range: RotaryRange,
}

impl HeadHead {
    /// A typical fork head: 150 mm pivot + tool, B ±110°, C ±360°.
    pub fn typical() -> Self {
        HeadHead {
            length: 150.0,
            b_range: RotaryRange::new(-110f64.to_radians(), 110f64.to_radians()),
            c_range: RotaryRange::new(-2.0 * PI, 2.0 * PI),
        }
    }
}

impl Kinematics for HeadHead {
    fn name(&self) -> &'static str {
        "head-head"
    }
    fn axis_names(&self) -> [&'static str; 5] {
        ["X", "Y", "Z", "B", "C"]
    }
    fn rotary_ranges(&self) -> [RotaryRange; 2] {
        [self.b_range, self.c_range]
    }
    fn forward(&self, q: &Joints) -> Pose {
        let k = mv(&mm(&rot_z(q[4]), &rot_y(q[3])), &[0.0, 0.0, 1.0]);
        Pose {
            tip: Point3::new(
                q[0] - self.length * k[0],
                q[1] - self.length * k[1],
                q[2] - self.length * k[2],
            ),
            axis: Vec3::new(k[0], k[1], k[2]),
        }
    }
    fn jacobian(&self, q: &Joints) -> Jacobian {
        let ez = [0.0, 0.0, 1.0];
        let rz = rot_z(q[4]);
        let ry = rot_y(q[3]);
        let dkb: V3 = mv(&mm(&rz, &mm(&GEN_Y, &ry)), &ez);
        let dkc: V3 = mv(&mm(&GEN_Z, &mm(&rz, &ry)), &ez);
        let mut j = [[0.0; 5]; 6];
        set_col(&mut j, 0, [1.0, 0.0, 0.0], [0.0; 3]);
        set_col(&mut j, 1, [0.0, 1.0, 0.0], [0.0; 3]);
        set_col(&mut j, 2, [0.0, 0.0, 1.0], [0.0; 3]);
        set_col(&mut j, 3, scale(dkb, -self.length), dkb);
        set_col(&mut j, 4, scale(dkc, -self.length), dkc);
        j
    }
    fn orientation(&self, k: Vec3, free: f64) -> Orientation {
        let (pairs, pole_distance) = tilt_swivel(k.z, k.x, k.y, free);
        Orientation {
            pairs,
            pole_distance,
        }
    }
    fn lever_bound(&self, _lo: &Joints, _hi: &Joints) -> f64 {
        // tip = P − L k(b, c): every rotary derivative of the unit vector k has norm ≤ 1.
        self.length.abs()
    }
    fn linear(&self, tip: Point3, b: f64, c: f64) -> Option<[f64; 3]> {
        let k = mv(&mm(&rot_z(c), &rot_y(b)), &[0.0, 0.0, 1.0]);
        let t = arr_p(tip);
        Some([
            t[0] + self.length * k[0],
            t[1] + self.length * k[1],
            t[2] + self.length * k[2],
        ])
    }
}
