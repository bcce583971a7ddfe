//! The XY rotation of a coordinate system (`G10 L2 P p R deg`, LinuxCNC 2.9: parameter
//! `#5210 + 20·p`, `interp_convert.cc` `convert_setup`; the canon's `rotate_and_offset_pos`).
//!
//! machine = tool offset + G5x origin + rot_θ(program + G92) in X and Y (Z is not rotated):
//! the rotation turns the program's XY frame, G92 offset included, about the system's origin.
//! Incremental moves, arc centre offsets (I J) and polar words are taken in the rotated frame.
//!
//! ```text
//!   program (1, 0) with R90 at origin (5, 5)  →  machine (5, 6)
//! ```
//!
//! Refused while the active system is rotated (LinuxCNC's rules for them are not followed
//! here): G92 (set before or after the rotation), G10 L20, canned cycles, and arcs outside the XY plane (they would leave
//! their plane).

use super::State;
use crate::geom::Point3;

/// `(x, y)` turned by `theta` (rad) counter-clockwise.
pub(crate) fn rotate(x: f64, y: f64, theta: f64) -> (f64, f64) {
    let (s, c) = theta.sin_cos();
    (x * c - y * s, x * s + y * c)
}

impl State {
    /// The active system's rotation (rad; 0 when not rotated).
    pub(crate) fn rotation(&self) -> f64 {
        self.rotation
    }

    /// The machine position of program coordinates `p` (mm).
    pub(crate) fn program_to_machine(&self, p: [f64; 3]) -> Point3 {
        let (x, y) = rotate(p[0] + self.g92.x, p[1] + self.g92.y, self.rotation);
        let o = self.origin + self.tool_offset;
        Point3::new(x + o.x, y + o.y, p[2] + self.g92.z + o.z)
    }

    /// The program coordinates (mm) of the present position.
    pub(crate) fn program_mm(&self) -> [f64; 3] {
        let m = self.pos - self.origin - self.tool_offset;
        let (x, y) = rotate(m.x, m.y, -self.rotation);
        [x - self.g92.x, y - self.g92.y, m.z - self.g92.z]
    }
}

#[cfg(test)]
mod tests {
    use super::rotate;

    #[test]
    fn a_quarter_turn_maps_x_to_y() {
        let (x, y) = rotate(1.0, 0.0, std::f64::consts::FRAC_PI_2);
        assert!(x.abs() < 1e-15 && (y - 1.0).abs() < 1e-15);
        let (x, y) = rotate(x, y, -std::f64::consts::FRAC_PI_2);
        assert!((x - 1.0).abs() < 1e-15 && y.abs() < 1e-15);
    }
}
