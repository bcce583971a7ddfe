//! The paper's machine: A rotates the head about X, B rotates the table about Y
//! (Wu, Li, Liu, Perez, *Local minimum time trajectory planning for five-axis machining*).
//!
//! # Derivation (equations 1–6 of the paper, re-derived)
//! Joints: `x`, `y` (table slides), `z_gt` (head slide), `A` (head about X), `B` (table about
//! Y). Structural constants `z1` (lower-ground origin to the tool's initial point), `z2` (table
//! pivot to the workpiece origin) and tool length `l_t`.
//!
//! The tool hangs from the head: in the tool frame its nose is at `(0, 0, −l_t)`. The head
//! frame is rotated by `A` about X and raised by `z_gt + z1`:
//!
//! ```text
//! T_t^lg = [1 0 0 0; 0 cA −sA 0; 0 sA cA z_gt+z1; 0 0 0 1]            (1)
//! P_t^lg = T_t^lg (0, 0, −l_t, 1)ᵀ = (0, l_t sA, z1 + z_gt − l_t cA, 1)ᵀ  (2)
//! ```
//! The workpiece frame sees the lower-ground frame through the table rotation `B` about Y and
//! the slides:
//!
//! ```text
//! T_lg^w = [cB 0 −sB −x; 0 1 0 −y; sB 0 cB −z2; 0 0 0 1]                 (3)
//! ```
//! so with `h = z1 + z_gt − l_t cA` (the nose height above the table pivot, measured along
//! the head's Z):
//!
//! ```text
//! x_w = −x − h sB,   y_w = l_t sA − y,   z_w = h cB − z2                   (4), (5)
//! ```
//! The tool axis (nose → spindle) is `(0, 0, 1)` in the tool frame, `(0, −sA, cA)` in the
//! lower-ground frame and `k = (−sB cA, −sA, cB cA)` in the workpiece frame.
//!
//! Inverse: the axis gives `sA = −k_y` and `(cB, −sB)·cA = (k_z, k_x)`: two families
//! `(A, B)` and `(π − A, B + π)`. Then `h = (z_w + z2)/cB`, and
//!
//! ```text
//! x = −x_w − (z_w + z2) tan B,   y = l_t sA − y_w,   z_gt = (z_w + z2) sec B + l_t cA − z1   (6)
//! ```
//! which needs `cB ≠ 0` (the table vertical cannot reach other heights).
//!
//! # Misprints in the paper
//! 1. The tool nose is written `P_t = (0, 0, l_t, 1)ᵀ`; equation (2) only follows from (1) with
//!    `(0, 0, −l_t, 1)ᵀ`.
//! 2. Equation (3) is labelled `T_lg^w = (T_t^lg)⁻¹`; it is not the inverse of (1), it is the
//!    table transform, and only this reading gives (4).
//! 3. Equations (4)–(5) write `z_g` for `z_gt` in `x_w`.
//! 4. Equation (6) ends `z_gt = (z2 + z_w) sec B + l_t sin A − z1`; solving (5) gives
//!    `+ l_t cos A`.
//!
//! Pole: `cA = 0` (tool axis along ±Y, the B axis): B is free there.

use super::{Jacobian, Joints, Kinematics, Orientation, Pose, RotaryRange, set_col, tilt_swivel};
use crate::geom::{Point3, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;

/// The paper's A-head / B-table machine (all lengths mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PaperAb {
    /// Structural constant z1, mm.
    pub z1: f64,
    /// Structural constant z2, mm.
    pub z2: f64,
    /// Tool length l_t, mm.
    pub tool_length: f64,
    /// Range of A, rad.
    pub a_range: RotaryRange,
    /// Range of B, rad.
    pub b_range: RotaryRange,
}

impl PaperAb {
    /// The machine of the paper's simulation: z1 = 300 mm, z2 = 30 mm, l_t = 50 mm; A and B
    /// within ±1.4 rad (B = ±90° is unreachable, see the module docs).
    pub fn paper() -> Self {
        PaperAb {
            z1: 300.0,
            z2: 30.0,
            tool_length: 50.0,
            a_range: RotaryRange::new(-1.4, 1.4),
            b_range: RotaryRange::new(-1.4, 1.4),
        }
    }
}

impl Kinematics for PaperAb {
    fn name(&self) -> &'static str {
        "paper-ab"
    }
    fn axis_names(&self) -> [&'static str; 5] {
        ["X", "Y", "Z", "A", "B"]
    }
    fn rotary_ranges(&self) -> [RotaryRange; 2] {
        [self.a_range, self.b_range]
    }
    fn forward(&self, q: &Joints) -> Pose {
        let [x, y, z, a, b] = *q;
        let (sa, ca) = a.sin_cos();
        let (sb, cb) = b.sin_cos();
        let h = self.z1 + z - self.tool_length * ca;
        Pose {
            tip: Point3::new(-x - h * sb, self.tool_length * sa - y, h * cb - self.z2),
            axis: Vec3::new(-sb * ca, -sa, cb * ca),
        }
    }
    fn jacobian(&self, q: &Joints) -> Jacobian {
        let [_, _, z, a, b] = *q;
        let lt = self.tool_length;
        let (sa, ca) = a.sin_cos();
        let (sb, cb) = b.sin_cos();
        let h = self.z1 + z - lt * ca;
        let mut j = [[0.0; 5]; 6];
        set_col(&mut j, 0, [-1.0, 0.0, 0.0], [0.0; 3]);
        set_col(&mut j, 1, [0.0, -1.0, 0.0], [0.0; 3]);
        set_col(&mut j, 2, [-sb, 0.0, cb], [0.0; 3]);
        // ∂h/∂A = l_t sA
        set_col(
            &mut j,
            3,
            [-lt * sa * sb, lt * ca, lt * sa * cb],
            [sb * sa, -ca, -cb * sa],
        );
        set_col(
            &mut j,
            4,
            [-h * cb, 0.0, -h * sb],
            [-cb * ca, 0.0, -sb * ca],
        );
        j
    }
    fn orientation(&self, k: Vec3, free: f64) -> Orientation {
        // ct = sA = −k_y, (u, v) = cA (cB, sB) = (k_z, −k_x); t = π/2 − A, θ = B.
        let (pairs, pole_distance) = tilt_swivel(-k.y, k.z, -k.x, free);
        Orientation {
            pairs: pairs
                .into_iter()
                .map(|(t, th)| (super::wrap(FRAC_PI_2 - t), th))
                .collect(),
            pole_distance,
        }
    }
    fn lever_bound(&self, lo: &Joints, hi: &Joints) -> f64 {
        // Rotary-only derivatives of the tip: ∂/∂A and its A/B derivatives have norm l_t
        // (or l_t|sA|, l_t|cA|), ∂/∂B and ∂³/∂B³ norm |h| with h = z1 + z − l_t cA, so
        // R = max(l_t, sup|h|) and sup|h| ≤ max(|z1 + z_lo|, |z1 + z_hi|) + l_t.
        let lt = self.tool_length.abs();
        let h = (self.z1 + lo[2]).abs().max((self.z1 + hi[2]).abs()) + lt;
        lt.max(h)
    }
    fn linear(&self, tip: Point3, a: f64, b: f64) -> Option<[f64; 3]> {
        let cb = b.cos();
        if cb.abs() < 1e-9 {
            return None;
        }
        let (sa, ca) = a.sin_cos();
        let h = (tip.z + self.z2) / cb;
        let x = -tip.x - (tip.z + self.z2) * b.tan();
        let y = self.tool_length * sa - tip.y;
        let z = h + self.tool_length * ca - self.z1;
        Some([x, y, z])
    }
}
