//! Property tests of the outline geometry (`geom::Outline`, cavalier_contours offsets):
//!
//! * **offset distance**: every point of an inward offset at `d` (sampled densely along its
//!   lines and arcs, not only at vertices) lies at distance `d` from the outline, within
//!   `1e-6·(1 + d)` mm, and inside it;
//! * **area monotonicity**: the area inside the offsets strictly decreases as `d` grows
//!   (`area(d₂) < area(d₁)` for `d₁ < d₂` while the offset exists: the region at `d₂` is the
//!   region at `d₁` minus a band of positive width);
//! * **invariance**: reversing the vertex order (clockwise input) or rotating its start gives
//!   the same offset areas.
//!
//! The verifier is `Outline::distance_to` / `contains` (closest point on the original
//! polyline), which does not share the offset code path. Seeded, bounded case counts.

use millpath::Point;
use millpath::geom::{Outline, Winding};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// A star polygon: evenly spaced angles, radii in [0.4, 1]·r (simple by construction), some
/// edges bulged into arcs (|bulge| ≤ 0.25; where a bulge makes the outline self-intersect,
/// `Outline::new` refuses it and the case is skipped).
fn star(radii: &[f64], bulges: &[f64], r: f64) -> Option<Outline> {
    let n = radii.len();
    let verts: Vec<(Point, f64)> = radii
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            (
                Point::new(r * k * a.cos(), r * k * a.sin()),
                bulges.get(i).copied().unwrap_or(0.0),
            )
        })
        .collect();
    Outline::new(&verts, "prop").ok()
}

/// Points along every segment of `o` (lines and arcs), 16 a segment.
fn dense(o: &Outline) -> Vec<Point> {
    let mut out = Vec::new();
    let v: Vec<(Point, f64)> = o.vertices().collect();
    let n = v.len();
    for i in 0..n {
        let ((a, bulge), (b, _)) = (v[i], v[(i + 1) % n]);
        let (ax, ay, bx, by) = (a.x, a.y, b.x, b.y);
        for k in 0..16 {
            let t = k as f64 / 16.0;
            if bulge.abs() < 1e-12 {
                out.push(Point::new(ax + t * (bx - ax), ay + t * (by - ay)));
            } else {
                // Arc from a to b with sweep θ = 4·atan(bulge): centre on the chord's bisector.
                let theta = 4.0 * bulge.atan();
                let (mx, my) = (0.5 * (ax + bx), 0.5 * (ay + by));
                let (dx, dy) = (bx - ax, by - ay);
                let chord = (dx * dx + dy * dy).sqrt();
                let rad = chord / (2.0 * (theta / 2.0).sin().abs());
                let h = chord / 2.0 / (theta / 2.0).tan();
                let (cx, cy) = (mx - h * dy / chord, my + h * dx / chord);
                let a0 = (ay - cy).atan2(ax - cx);
                let ang = a0 + t * theta;
                out.push(Point::new(cx + rad * ang.cos(), cy + rad * ang.sin()));
            }
        }
    }
    out
}

fn area(loops: &[Outline]) -> f64 {
    loops.iter().map(Outline::signed_area).sum()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, rng_seed: RngSeed::Fixed(11), failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn inward_offsets_keep_their_distance(
        radii in prop::collection::vec(0.4f64..1.0, 4..10),
        bulges in prop::collection::vec(prop_oneof![Just(0.0), -0.25f64..0.25], 10),
        r in 10.0f64..80.0,
        frac in 0.01f64..0.15,
    ) {
        let o = star(&radii, &bulges, r).or_else(|| star(&radii, &[], r));
        prop_assert!(o.is_some(), "a straight star is always a valid outline");
        let o = o.unwrap();
        let o = o.with_winding(Winding::CounterClockwise);
        let d = frac * r;
        let offs = o.offset(d);
        prop_assert!(!offs.is_empty(), "an offset of {d} mm of a star of inradius ≥ {} mm exists", 0.4 * r * (std::f64::consts::PI / radii.len() as f64).cos());
        for pl in offs {
            for p in dense(&pl) {
                let dist = o.distance_to(p);
                prop_assert!((dist - d).abs() <= 1e-6 * (1.0 + d), "point {p:?} at {dist}, offset {d}");
                prop_assert!(o.contains(p), "offset point {p:?} outside the outline");
            }
        }
    }

    #[test]
    fn area_shrinks_as_the_inward_offset_grows(
        radii in prop::collection::vec(0.4f64..1.0, 4..10),
        bulges in prop::collection::vec(prop_oneof![Just(0.0), -0.25f64..0.25], 10),
        r in 10.0f64..80.0,
    ) {
        let o = star(&radii, &bulges, r).or_else(|| star(&radii, &[], r));
        prop_assert!(o.is_some(), "a straight star is always a valid outline");
        let o = o.unwrap();
        let o = o.with_winding(Winding::CounterClockwise);
        let mut prev = o.signed_area();
        prop_assert!(prev > 0.0);
        for k in 1..8 {
            let d = r * 0.03 * k as f64;
            let a = area(&o.offset(d));
            prop_assert!(a <= prev * (1.0 + 1e-9) + 1e-9, "area {a} at d = {d} exceeds {prev}");
            if a > 0.0 {
                prop_assert!(a < prev, "area did not shrink at d = {d}");
            }
            prev = a;
        }
    }

    #[test]
    fn offsets_do_not_depend_on_orientation_or_start(
        radii in prop::collection::vec(0.4f64..1.0, 4..10),
        r in 10.0f64..80.0,
        frac in 0.01f64..0.2,
        rot in 0usize..10,
    ) {
        let o = star(&radii, &[], r);
        prop_assert!(o.is_some(), "a straight star is always a valid outline");
        let o = o.unwrap();
        let n = o.len();
        let verts: Vec<(Point, f64)> = o.vertices().collect();
        let rotated: Vec<(Point, f64)> = (0..n).map(|i| verts[(i + rot) % n]).collect();
        let reversed: Vec<(Point, f64)> = verts.iter().rev().copied().collect();
        let d = frac * r;
        let base = area(&o.with_winding(Winding::CounterClockwise).offset(d));
        for other in [rotated, reversed] {
            let oo = Outline::new(&other, "prop").expect("same polygon");
            let a = area(&oo.with_winding(Winding::CounterClockwise).offset(d));
            prop_assert!((a - base).abs() <= 1e-9 * (1.0 + base.abs()), "{a} vs {base}");
        }
    }
}
