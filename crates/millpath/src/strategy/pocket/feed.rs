//! Feed modulation from the measured engagement (the paper's §2.4).
//!
//! With `φ_n` the nominal engagement (the stepover's, `arccos(1 − s/r)`) and `φ_max = 180°`
//! (slotting), a move whose largest measured engagement is `φ` gets
//!
//! ```text
//!   F(φ) = F                                   for φ ≤ φ_n
//!   F(φ) = F · (1 − (1 − k)·(φ − φ_n)/(φ_max − φ_n))   for φ_n < φ ≤ φ_max
//! ```
//!
//! `k` the slowdown (0.75 gives 75% of the feed when slotting). The paper interpolates in the
//! radial depth of cut ("cutting thickness") between the specified and the maximum; we
//! interpolate in the engagement angle, which is what loads the tool (chip thickness and
//! the number of teeth in the cut both follow the angle). Moves that cut nothing keep the
//! full feed; entry moves keep the plunge feed when it is lower.

use crate::stock::MoveEngagement;
use crate::toolpath::Toolpath;
use std::f64::consts::PI;

/// The feed factor for engagement `phi` (rad), nominal `nominal` (rad), slowdown `k`.
pub fn factor(phi: f64, nominal: f64, k: f64) -> f64 {
    if phi <= nominal || nominal >= PI {
        1.0
    } else {
        1.0 - (1.0 - k) * ((phi - nominal) / (PI - nominal)).min(1.0)
    }
}

/// Scales the feed of every cutting move by the factor of its measured engagement.
pub fn modulate(tp: &mut Toolpath, per_move: &[Option<MoveEngagement>], nominal: f64, k: f64) {
    for (m, e) in tp.moves.iter_mut().zip(per_move) {
        if let (true, Some(e)) = (m.is_feed(), e) {
            m.feed *= factor(e.max_angle, nominal, k);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_feed_up_to_nominal_then_linear_to_slowdown() {
        let n = 1.0;
        assert!((factor(0.5, n, 0.75) - 1.0).abs() < 1e-12);
        assert!((factor(n, n, 0.75) - 1.0).abs() < 1e-12);
        assert!((factor(PI, n, 0.75) - 0.75).abs() < 1e-12);
        assert!((factor(0.5 * (n + PI), n, 0.75) - 0.875).abs() < 1e-12);
    }
}
