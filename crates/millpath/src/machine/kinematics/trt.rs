//! Table-table (trunnion) machines: an outer table axis (A about X, or B about Y) carrying a
//! rotary table C about Z, as LinuxCNC's `xyzac-trt` and `xyzbc-trt` kinematics.
//!
//! # Model
//! Parameters as LinuxCNC's `kins_trt_params`: the outer axis's pivot `r` (`x/y/z_rot_point`,
//! machine coordinates with all rotaries at zero), the offset `d` from that pivot to a point of
//! the C axis (`x/y/z_offset`) and the tool length `t` (`tool_offset`). With the rotaries at
//! zero the workpiece frame coincides with the machine frame.
//!
//! The tables rotate the workpiece positively (right hand) about their axes: a workpiece point
//! `p_w` is carried to the machine point
//!
//! ```text
//! p_m = r + R1(a) · (d + Rz(c) · (p_w − r − d))
//! ```
//! and the controlled point is the tool tip `p_m = (X, Y, Z − t)`. Inverting,
//!
//! ```text
//! p_w = r + d + Rz(−c) · (R1(−a) · (p_m − r) − d)          (forward kinematics)
//! k_w = Rz(−c) · R1(−a) · e_z                               (tool axis, workpiece frame)
//! ```
//! For AC (`R1 = Rx`): `k = (sa·sc, sa·cc, ca)`. For BC (`R1 = Ry`): `k = (−sb·cc, sb·sc, cb)`.
//! So the tilt `a` (or `b`) is `±acos k_z` and C follows from the other two components; the
//! two families are `(t, c)` and `(−t, c + π)`. The pole is `t = 0` (tool along the C axis),
//! where C is free.
//!
//! # Jacobian
//! With `dR(θ)/dθ = G R(θ)` (G the generator of the rotation axis), `w = p_m − r`:
//! `∂p_w/∂(X,Y,Z) = Rz(−c) R1(−a)`, `∂p_w/∂a = −Rz(−c) G1 R1(−a) w`,
//! `∂p_w/∂c = −Gz Rz(−c) (R1(−a) w − d)`, and the same for `k` with `w → e_z`, `d → 0`.

use super::{
    GEN_X, GEN_Y, GEN_Z, Jacobian, Joints, Kinematics, M3, Orientation, Pose, RotaryRange, V3, add,
    arr_p, mm, mv, p3, rot_x, rot_y, rot_z, scale, set_col, sub, tilt_swivel, v3,
};
use crate::geom::{Point3, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which outer table axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum TrtKind {
    /// A about X carrying C (LinuxCNC `xyzac-trt`).
    Ac,
    /// B about Y carrying C (LinuxCNC `xyzbc-trt`).
    Bc,
}

/// A table-table machine (lengths in mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TableTable {
    /// AC or BC.
    pub kind: TrtKind,
    /// Pivot of the outer axis, machine coordinates, mm.
    pub pivot: [f64; 3],
    /// Offset from the outer pivot to a point of the C axis, mm.
    pub offset: [f64; 3],
    /// Tool length, mm.
    pub tool_offset: f64,
    /// Range of the tilt axis (A or B), rad.
    pub tilt_range: RotaryRange,
    /// Range of C, rad.
    pub c_range: RotaryRange,
}

impl TableTable {
    /// A typical trunnion: pivot 100 mm below the table, C offset 20 mm in Y (AC) or X (BC),
    /// tilt −120°…+120°, C ±2 turns.
    pub fn typical(kind: TrtKind) -> Self {
        let offset = match kind {
            TrtKind::Ac => [0.0, 20.0, 5.0],
            TrtKind::Bc => [20.0, 0.0, 5.0],
        };
        TableTable {
            kind,
            pivot: [10.0, -5.0, -100.0],
            offset,
            tool_offset: 0.0,
            tilt_range: RotaryRange::new(-120f64.to_radians(), 120f64.to_radians()),
            c_range: RotaryRange::new(-4.0 * PI, 4.0 * PI),
        }
    }

    fn r1(&self, t: f64) -> M3 {
        match self.kind {
            TrtKind::Ac => rot_x(t),
            TrtKind::Bc => rot_y(t),
        }
    }
    fn g1(&self) -> M3 {
        match self.kind {
            TrtKind::Ac => GEN_X,
            TrtKind::Bc => GEN_Y,
        }
    }
}

impl Kinematics for TableTable {
    fn name(&self) -> &'static str {
        match self.kind {
            TrtKind::Ac => "ac-trt",
            TrtKind::Bc => "bc-trt",
        }
    }
    fn axis_names(&self) -> [&'static str; 5] {
        match self.kind {
            TrtKind::Ac => ["X", "Y", "Z", "A", "C"],
            TrtKind::Bc => ["X", "Y", "Z", "B", "C"],
        }
    }
    fn rotary_ranges(&self) -> [RotaryRange; 2] {
        [self.tilt_range, self.c_range]
    }
    fn forward(&self, q: &Joints) -> Pose {
        let pm: V3 = [q[0], q[1], q[2] - self.tool_offset];
        let r1m = self.r1(-q[3]);
        let rzm = rot_z(-q[4]);
        let inner = sub(mv(&r1m, &sub(pm, self.pivot)), self.offset);
        let pw = add(add(self.pivot, self.offset), mv(&rzm, &inner));
        let k = mv(&rzm, &mv(&r1m, &[0.0, 0.0, 1.0]));
        Pose {
            tip: p3(pw),
            axis: v3(k),
        }
    }
    fn jacobian(&self, q: &Joints) -> Jacobian {
        let pm: V3 = [q[0], q[1], q[2] - self.tool_offset];
        let r1m = self.r1(-q[3]);
        let rzm = rot_z(-q[4]);
        let w = sub(pm, self.pivot);
        let rot = mm(&rzm, &r1m);
        let mut j = [[0.0; 5]; 6];
        for (c, col) in [0usize, 1, 2]
            .into_iter()
            .map(|c| (c, [rot[0][c], rot[1][c], rot[2][c]]))
        {
            set_col(&mut j, c, col, [0.0; 3]);
        }
        let g1 = self.g1();
        let rzg1r1 = mm(&rzm, &mm(&g1, &r1m));
        let ez = [0.0, 0.0, 1.0];
        set_col(
            &mut j,
            3,
            scale(mv(&rzg1r1, &w), -1.0),
            scale(mv(&rzg1r1, &ez), -1.0),
        );
        let gzrz = mm(&GEN_Z, &rzm);
        let inner = sub(mv(&r1m, &w), self.offset);
        set_col(
            &mut j,
            4,
            scale(mv(&gzrz, &inner), -1.0),
            scale(mv(&gzrz, &mv(&r1m, &ez)), -1.0),
        );
        j
    }
    fn orientation(&self, k: Vec3, free: f64) -> Orientation {
        let (pairs, pole_distance) = match self.kind {
            TrtKind::Ac => tilt_swivel(k.z, k.y, k.x, free),
            TrtKind::Bc => tilt_swivel(k.z, -k.x, k.y, free),
        };
        Orientation {
            pairs,
            pole_distance,
        }
    }
    fn lever_bound(&self, lo: &Joints, hi: &Joints) -> f64 {
        // With w = p_m − r: rotary derivatives of Rz(−c)(R1(−a) w − d) multiply by generators
        // of norm 1, so every one has norm ≤ |w| + |d|; |w| is bounded over the box per
        // component.
        let sup = |i: usize, shift: f64| (lo[i] - shift).abs().max((hi[i] - shift).abs());
        let w = [
            sup(0, self.pivot[0]),
            sup(1, self.pivot[1]),
            sup(2, self.pivot[2] + self.tool_offset),
        ];
        let n = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        n(w) + n(self.offset)
    }
    fn linear(&self, tip: Point3, t: f64, c: f64) -> Option<[f64; 3]> {
        let rd = add(self.pivot, self.offset);
        let inner = add(mv(&rot_z(c), &sub(arr_p(tip), rd)), self.offset);
        let pm = add(self.pivot, mv(&self.r1(t), &inner));
        Some([pm[0], pm[1], pm[2] + self.tool_offset])
    }
}
