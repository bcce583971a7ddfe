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
//!
//! A neck the tool just fits through (two of the region's loops within `within` of each
//! other: an island's offset touching a wall's where the gap is the tool's diameter) is cut
//! as a slot by whatever goes through first, from either side: the material ahead spans the
//! gap. The floor there is π.
//!
//! Where a loop turns back on itself (two walls' offsets meeting
//! tangent in a notch as wide as the tool), the tangents' cross product is rounding noise:
//! the turn is `+π` (a spike: the region lies only between the way in and the way out) or
//! `−π` (a crack: it lies on both sides), read from a point just beside the way in.

use crate::geom::{Outline, Vec2};

/// A vertex turn within this of π (rad) is a reversal, its sign read from the region.
const REVERSAL: f64 = 1e-6;

/// The engagement, radians, a tool feeding straight into the sharpest corner of the
/// tool-centre region reaches (module docs): `acos(2·cos(τ/2) − 1)` for the largest turn `τ`
/// of [`corner_turn`].
/// Where two of the region's loops come within `within` of each other (a neck the tool
/// just fits through), a slot: π.
pub fn corner_floor(loops: &[Outline], within: f64) -> f64 {
    if pinched(loops, within) {
        return std::f64::consts::PI;
    }
    let tau = corner_turn(loops, within);
    (2.0 * (0.5 * tau).cos() - 1.0).clamp(-1.0, 1.0).acos()
}

/// True when two of `loops` come within `tol` of each other: points of one, at most `tol/2`
/// apart along it (those within `tol` of the other's bounds), measured to the other.
pub fn pinched(loops: &[Outline], tol: f64) -> bool {
    if tol.is_nan() || tol <= 0.0 {
        return false;
    }
    for (i, a) in loops.iter().enumerate() {
        for b in &loops[i + 1..] {
            let near = b.bounds().inflate(tol);
            let ab = a.bounds();
            if ab.min.x > near.max.x
                || ab.max.x < near.min.x
                || ab.min.y > near.max.y
                || ab.max.y < near.min.y
            {
                continue;
            }
            let n = ((a.length() / (0.5 * tol)).ceil() as usize).clamp(16, 1 << 20);
            if a.sample(n)
                .into_iter()
                .any(|p| near.contains(p) && b.distance_to(p) < tol)
            {
                return true;
            }
        }
    }
    false
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
            let prev = (i + n - 1) % n;
            let inc = tangent(prev, true);
            let out = tangent(i, false);
            let turn = inc.cross(out).atan2(inc.dot(out));
            if std::f64::consts::PI - turn.abs() > REVERSAL {
                return turn;
            }
            // The loop turns back on itself: the sign of the tiny cross product says nothing.
            // A spike of the region (a cusp where two walls' offsets meet, a hair as wide as
            // the tool) has no region on the right of the way in; a crack (the outside
            // reaching in) has the region on both sides.
            let (Some(u), len) = (inc.normalize(), segs[prev].0) else {
                return turn;
            };
            let back = (1e-3 * len).min(1e-4);
            let q = v[i].0 - u * back + Vec2::new(u.y, -u.x) * (0.01 * back);
            let inside: i32 = loops.iter().map(|o| o.winding_number(q)).sum();
            if inside > 0 {
                -std::f64::consts::PI
            } else {
                std::f64::consts::PI
            }
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
    use super::{corner_floor, corner_turn, pinched};
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

    /// A 20 × 20 region whose left wall has, at `y = 0`, two quarter arcs of radius 3.175
    /// meeting tangent at a tip 3.175 from the wall: turning `out` (−1) a spike of the
    /// region into a notch of the wall as wide as the tool, (+1) a tooth of the wall reaching
    /// into the region. The loop reverses at the tip either way.
    fn notched(dir: f64) -> Outline {
        let (r, b) = (3.175, (PI / 8.0).tan());
        let v = vec![
            (Point::new(0.0, -10.0), 0.0),
            (Point::new(20.0, -10.0), 0.0),
            (Point::new(20.0, 10.0), 0.0),
            (Point::new(0.0, 10.0), 0.0),
            (Point::new(0.0, r), dir * b),
            (Point::new(dir * r, 0.0), dir * b),
            (Point::new(0.0, -r), 0.0),
        ];
        Outline::new(&v, "test").unwrap()
    }

    #[test]
    fn a_reversal_is_a_spike_or_a_crack_as_the_region_lies() {
        // The spike: a tool in it slots, less what one arc turns back over the window.
        let spike = corner_turn(&[notched(-1.0)], 0.1);
        let want = PI - 0.1 / 3.175;
        assert!((spike - want).abs() < 1e-6, "{}", spike.to_degrees());
        assert!(corner_floor(&[notched(-1.0)], 0.1) > 140f64.to_radians());
        // The tooth: the region wraps round it, the square corners are the sharpest.
        let tooth = corner_turn(&[notched(1.0)], 0.1);
        assert!((tooth - 0.5 * PI).abs() < 1e-6, "{}", tooth.to_degrees());
    }

    #[test]
    fn a_neck_the_tool_just_fits_is_a_slot() {
        // A 20 × 20 region and a disc island whose edge comes `gap` from the top wall.
        let outer = poly(&[(0.0, 0.0), (20.0, 0.0), (20.0, 20.0), (0.0, 20.0)]);
        for (gap, slot) in [(0.0, true), (0.01, true), (0.5, false)] {
            let c = Point::new(10.0, 20.0 - gap - 3.0);
            let island = Outline::new(
                &[
                    (Point::new(c.x - 3.0, c.y), -1.0),
                    (Point::new(c.x + 3.0, c.y), -1.0),
                ],
                "test",
            )
            .unwrap();
            let loops = [outer.clone(), island];
            assert_eq!(pinched(&loops, 0.1), slot, "gap {gap}");
            let f = corner_floor(&loops, 0.1);
            assert_eq!(f > 0.99 * PI, slot, "gap {gap}: {}", f.to_degrees());
        }
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
