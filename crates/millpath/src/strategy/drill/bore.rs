//! Helix boring: a hole larger than the tool cut by helices and a finishing circle.
//!
//! With `c` the hole's centre, `R` its radius, `r` the tool's and `ρ = R − r` the radius the
//! tool centre must reach:
//!
//! * **Rings.** The helix runs at `ρ_h = ρ − a` (`a` the finish allowance, at most `ρ/2`;
//!   none when that is under twice [`MIN_LEAD_RADIUS`]: the helix then runs on the wall
//!   circle, which its last full circle finishes). When `ρ_h ≤ r` the tool covers the centre on that
//!   one helix. A wider hole would keep a core: it gets rings from `r/2` out to `ρ_h`, at
//!   most the stepover apart, each helixed down from the retract height (the tool discs of
//!   neighbouring rings overlap by at least `D − stepover`, the innermost covers the centre).
//! * **Helix.** From the R plane down to the bottom in `N = ⌈(R plane − bottom)/pitch⌉` full
//!   turns of equal descent, each one G2/G3 whose end is its start, then one full circle at
//!   the bottom, which flattens the ramp the helix left.
//! * **Finish.** On the outermost ring, where the allowance is left: a tangent half-circle
//!   lead-in from the helix circle out to the wall circle `ρ` (its centre on the same ray at
//!   `(ρ + ρ_h)/2`, so it touches the wall circle from inside at the lead-in's end and the
//!   tool meets the wall moving along it), the full wall circle, and the same half-circle
//!   back in as the lead-out: no mark where the tool arrives at or leaves the wall.
//! * **Direction.** Climb milling (a clockwise spindle) runs counter-clockwise round a hole
//!   (G3), conventional clockwise (G2).
//! * The tool goes between rings at the R plane and leaves the hole straight up from a point
//!   of the last circle it cut at the bottom.

use super::HoleOptions;
use crate::geom::{Hole, Point, Point3, Vec2};
use crate::strategy::pocket::Direction;
use crate::toolpath::{Move, Tool, Toolpath};

/// The smallest lead-in radius, mm: an allowance under twice it is not left (the helix runs
/// on the wall circle), so that no arc is too small to write (0.00127 mm, LinuxCNC's
/// smallest radius) or to survive the program's rounding.
pub const MIN_LEAD_RADIUS: f64 = 0.01;

/// What boring one hole made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Bored {
    /// Helix rings.
    pub rings: usize,
    /// Helix turns per ring.
    pub turns: usize,
}

/// The helix radii of a hole whose tool centre must reach `rho` (ascending; the last is the
/// helix radius of the outermost ring), for a tool of radius `r`.
pub(crate) fn ring_radii(rho: f64, r: f64, opts: &HoleOptions) -> Vec<f64> {
    let a = opts.finish_allowance.min(0.5 * rho);
    let helix = if a >= 2.0 * MIN_LEAD_RADIUS {
        rho - a
    } else {
        rho
    };
    if helix <= r {
        return vec![helix];
    }
    let step = opts.stepover * 2.0 * r;
    let inner = 0.5 * r;
    let gaps = ((helix - inner) / step).ceil().max(1.0);
    let m = gaps as usize;
    (0..=m)
        .map(|k| inner + (helix - inner) * k as f64 / gaps)
        .collect()
}

/// Appends the boring of `hole` to `tp` (the tool anywhere at or above the clearance level;
/// it ends at the R plane above the hole), with the tool centre reaching `rho = R − r`.
pub(crate) fn bore_hole(tp: &mut Toolpath, hole: &Hole, tool: &Tool, opts: &HoleOptions) -> Bored {
    let c = hole.center;
    let rho = hole.radius() - tool.radius();
    let rings = ring_radii(rho, tool.radius(), opts);
    let ccw = opts.direction == Direction::Climb;
    let (r_plane, bottom) = (opts.r_plane(), opts.bottom());
    let turns = ((r_plane - bottom) / opts.pitch).ceil().max(1.0);
    let f = opts.bore_feed;
    let at = |p: Point, z: f64| Point3::from_xy(p, z);
    let centre = |z: f64| at(c, z);
    let last = rings.len() - 1;
    for (k, &rh) in rings.iter().enumerate() {
        let start = c + Vec2::new(rh, 0.0);
        let here = tp.end();
        if here.xy().distance(start) > 0.0 || here.z < r_plane {
            if here.z < r_plane {
                tp.push(Move::rapid(at(here.xy(), r_plane)));
            }
            tp.push(Move::rapid(at(start, tp.end().z)));
        }
        if tp.end().z > r_plane {
            tp.push(Move::rapid(at(start, r_plane)));
        }
        for t in 1..=turns as usize {
            let z = r_plane - (r_plane - bottom) * t as f64 / turns;
            tp.push(Move::arc_xy(at(start, z), centre(z), ccw, f));
        }
        tp.push(Move::arc_xy(at(start, bottom), centre(bottom), ccw, f));
        if k == last && rho - rh > 1e-6 {
            let wall = c + Vec2::new(rho, 0.0);
            let lead = at(c + Vec2::new(0.5 * (rho + rh), 0.0), bottom);
            tp.push(Move::arc_xy(at(wall, bottom), lead, ccw, f));
            tp.push(Move::arc_xy(at(wall, bottom), centre(bottom), ccw, f));
            tp.push(Move::arc_xy(at(start, bottom), lead, ccw, f));
        }
        tp.push(Move::rapid(at(start, r_plane)));
    }
    Bored {
        rings: rings.len(),
        turns: turns as usize,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rings_cover_the_centre_and_stay_a_stepover_apart() {
        let opts = HoleOptions::default();
        let r = 3.0;
        for rho in [0.05, 0.5, 2.9, 3.2, 10.0, 47.0] {
            let rings = ring_radii(rho, r, &opts);
            assert!(rings[0] <= r, "{rho}: {rings:?}");
            assert!(*rings.last().unwrap() <= rho);
            for w in rings.windows(2) {
                assert!(w[1] > w[0] && w[1] - w[0] <= opts.stepover * 2.0 * r + 1e-9);
            }
        }
        assert_eq!(ring_radii(2.0, r, &opts), vec![1.9]);
        assert_eq!(ring_radii(0.1, r, &opts), vec![0.05]);
        assert_eq!(ring_radii(0.03, r, &opts), vec![0.03]);
    }
}
