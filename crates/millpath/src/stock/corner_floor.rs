//! The engagement a pocket's corners force on a program that cuts into them.
//!
//! Let the tool-centre region (the pocket offset inward by the tool's radius `r` and the wall
//! stock) have a corner of interior angle `α < π` at `T`: the path along its walls turns by
//! `τ = π − α` there. Which material can only be cut from near `T`? A point at angle `θ` from
//! the corner's bisector (towards the pocket's corner) and depth `ε` inside the disc of
//! radius `r` about `T` is within `r` of the region point `s` along a wall from `T` once
//! `s ≳ ε / cos(|θ| + α/2)`, and of no region point farther than that (the walls are the
//! best placed: the region's other points lie between them); the points with
//! `|θ| < π/2 − α/2` are reached from nowhere else near `T`. So the material no position
//! farther than `x` from `T` reaches is, to first order in `x`,
//!
//! `E(x) = ∫ r·x·cos(|θ| + α/2) dθ over |θ| < π/2 − α/2 = 2·r·x·(1 − sin(α/2))`.
//!
//! A tool that feeds straight into the corner removes `E(x)` over its last `x` of travel
//! in, an area per travel (the simulation's measure, a radial depth of cut `a_e`) of
//! `2r·(1 − sin(α/2))`, the engagement `acos(1 − a_e/r) = acos(2·sin(α/2) − 1)`: 65.5° at a
//! square corner, 90° at 60°, 180° at a cusp (where an island's offset meets a wall's). The
//! figure is first order in `x` and an estimate for that motion, not a bound on every
//! conceivable one (a tool that wanders about in the corner's last fraction of a millimetre
//! spreads the same area over more travel); `tests/pocket_adaptive.rs` checks it against
//! the simulation of the adaptive toolpath at sharp corners.
//!
//! A corner rounded by less than the simulation resolves acts as a sharp one: the turn is
//! summed over any stretch of a loop no longer than `within` (a vertex's turn, the arcs' turn
//! `θ = 4·atan(bulge)` spread over their length), and `α = π − τ`. The region's loops run
//! with the region on their left (counter-clockwise outer loops, clockwise islands), so a
//! convex corner turns left.

use crate::geom::Outline;

/// The engagement, radians, a tool feeding straight into the sharpest corner of the
/// tool-centre region reaches (module docs): `acos(2·cos(τ/2) − 1)` for the largest turn `τ`
/// of [`corner_turn`].
pub fn corner_floor(loops: &[Outline], within: f64) -> f64 {
    let tau = corner_turn(loops, within);
    (2.0 * (0.5 * tau).cos() - 1.0).clamp(-1.0, 1.0).acos()
}

/// The largest turn of the tool-centre region's loops summed over a stretch at most `within`
/// long, radians in `[0, π]` (module docs). `loops`: the region's loops, the region on their
/// left.
pub fn corner_turn(loops: &[Outline], within: f64) -> f64 {
    let mut best: f64 = 0.0;
    for lp in loops {
        let v: Vec<_> = lp.vertices().collect();
        let n = v.len();
        if n < 2 {
            continue;
        }
        // Per segment i (from v[i] to v[i+1]): length, sweep, and the turn at its start.
        let mut segs = Vec::with_capacity(n);
        for i in 0..n {
            let (a, bulge) = v[i];
            let b = v[(i + 1) % n].0;
            let chord = a.distance(b);
            let sweep = 4.0 * bulge.atan();
            let len = if bulge.abs() < 1e-12 || chord < 1e-15 {
                chord
            } else {
                0.5 * chord * sweep.abs() / (0.5 * sweep).sin().abs()
            };
            segs.push((len, sweep));
        }
        let tangent = |i: usize, at_end: bool| {
            let (a, bulge) = v[i];
            let b = v[(i + 1) % n].0;
            let half = 2.0 * bulge.atan();
            (b - a).rotate(if at_end { half } else { -half })
        };
        let vertex_turn = |i: usize| {
            let inc = tangent((i + n - 1) % n, true);
            let out = tangent(i, false);
            inc.cross(out).atan2(inc.dot(out))
        };
        let turns: Vec<f64> = (0..n).map(vertex_turn).collect();
        // Windows starting at each vertex, forward, and ending at each vertex, backward.
        for i in 0..n {
            for dir in [1usize, n - 1] {
                let mut total = turns[i];
                let mut left = within;
                let mut k = if dir == 1 { i } else { (i + n - 1) % n };
                for _ in 0..n {
                    let (len, sweep) = segs[k];
                    if len >= left {
                        if len > 0.0 {
                            total += sweep * left / len;
                        }
                        break;
                    }
                    total += sweep;
                    left -= len;
                    best = best.max(total);
                    // The vertex beyond this segment.
                    let next_vertex = if dir == 1 { (k + 1) % n } else { k };
                    total += turns[next_vertex];
                    k = (k + dir) % n;
                }
                best = best.max(total);
            }
        }
    }
    best.clamp(0.0, std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::{corner_floor, corner_turn};
    use crate::geom::{Outline, Point};
    use std::f64::consts::PI;

    fn poly(pts: &[(f64, f64)]) -> Outline {
        let p: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
        Outline::from_points(&p, "test").unwrap()
    }

    #[test]
    fn turns_and_floors_at_square_60_and_30_degree_corners() {
        let sq = poly(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        assert!((corner_turn(std::slice::from_ref(&sq), 0.1) - 0.5 * PI).abs() < 1e-9);
        // acos(2·sin 45° − 1) = acos(√2 − 1).
        let want = (2f64.sqrt() - 1.0).acos();
        assert!((corner_floor(&[sq], 0.1) - want).abs() < 1e-9);
        // A 30° corner: the path turns by 150° there.
        let t = poly(&[
            (0.0, 0.0),
            (10.0, 0.0),
            (
                10.0 * 30f64.to_radians().cos(),
                10.0 * 30f64.to_radians().sin(),
            ),
        ]);
        let f = corner_turn(std::slice::from_ref(&t), 0.1);
        assert!((f - 150f64.to_radians()).abs() < 1e-9, "{}", f.to_degrees());
        // A 60° corner: a_e = r, 90°.
        let e = poly(&[(0.0, 0.0), (10.0, 0.0), (5.0, 5.0 * 3f64.sqrt())]);
        assert!((corner_floor(&[e], 0.1) - 0.5 * PI).abs() < 1e-9);
        // Sharper corners force more, up to a slot at a cusp.
        assert!(corner_floor(&[t], 0.1) > 0.5 * PI);
    }

    #[test]
    fn a_clockwise_loop_turns_the_other_way() {
        // A square hole in the region: its corners are reflex for the region, no floor.
        let hole = poly(&[(0.0, 0.0), (0.0, 10.0), (10.0, 10.0), (10.0, 0.0)]);
        assert!(corner_turn(std::slice::from_ref(&hole), 0.1) < 1e-9);
        assert!(corner_floor(&[hole], 0.1) < 1e-9);
    }

    #[test]
    fn a_small_round_counts_a_large_one_does_not() {
        // A 10 mm square with its corners rounded: radius 0.01 reads as the corner, radius 3
        // turns 90° over 4.7 mm, of which a 0.1 mm stretch sees about 1.9°.
        for (rad, want) in [(0.01, 90.0), (3.0, 0.1 / 3.0 * 180.0 / PI)] {
            let b = (PI / 8.0).tan();
            let s = 10.0;
            let v = vec![
                (Point::new(rad, 0.0), 0.0),
                (Point::new(s - rad, 0.0), b),
                (Point::new(s, rad), 0.0),
                (Point::new(s, s - rad), b),
                (Point::new(s - rad, s), 0.0),
                (Point::new(rad, s), b),
                (Point::new(0.0, s - rad), 0.0),
                (Point::new(0.0, rad), b),
            ];
            let o = Outline::new(&v, "test").unwrap();
            let f = corner_turn(&[o], 0.1).to_degrees();
            assert!((f - want).abs() < 0.5, "radius {rad}: {f}° against {want}°");
        }
    }
}
