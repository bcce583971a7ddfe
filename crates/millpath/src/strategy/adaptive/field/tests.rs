use super::*;
use crate::geom::Outline;

#[test]
fn edt_matches_brute_force() {
    let (nx, ny) = (23, 17);
    let mut src = vec![false; nx * ny];
    for k in [3, 40, 77, 200, 333, 390] {
        src[k] = true;
    }
    let mut d2: Vec<f64> = src.iter().map(|&s| if s { 0.0 } else { 1e9 }).collect();
    edt_2d(&mut d2, nx, ny);
    for j in 0..ny {
        for i in 0..nx {
            let best = (0..nx * ny)
                .filter(|&k| src[k])
                .map(|k| {
                    let (a, b) = ((k % nx) as f64 - i as f64, (k / nx) as f64 - j as f64);
                    a * a + b * b
                })
                .fold(f64::INFINITY, f64::min);
            assert!((d2[j * nx + i] - best).abs() < 1e-9, "cell ({i}, {j})");
        }
    }
}

#[test]
fn disc_counts_agree_with_the_cells_one_by_one() {
    let mut f = Field::new(&rect(30.0, 20.0), 0.25, 1.0);
    let total = f.material_cells();
    assert_eq!(total, 120 * 80, "every cell centre inside the square");
    let q = Point::new(10.3, 7.9);
    let brute = (0..f.ny)
        .flat_map(|j| (0..f.nx).map(move |i| (i, j)))
        .filter(|&(i, j)| f.get(i, j) && f.centre(i, j).distance(q) <= 4.0)
        .count() as u32;
    assert_eq!(f.count_disc(q, 4.0), brute);
    assert_eq!(f.clear_disc(q, 4.0), brute);
    assert_eq!(f.count_disc(q, 4.0), 0);
    assert_eq!(f.material_cells(), total - u64::from(brute));
    // The wall distance of a centre cell is its distance to the nearest outside centre.
    let d = f.wall_distance(Point::new(15.1, 3.1));
    assert!((d - 3.25).abs() < 0.26, "{d}");
}

/// A tool above a straight edge of material, dipping `s` into it and moving along it,
/// touches it over `acos(1 − s/r)` of its front half (the straight cut's engagement), to
/// within the arc two cells subtend; over a slot, the whole half.
#[test]
fn the_contact_arc_is_the_straight_cuts_engagement() {
    let f = Field::new(&square(40.0), 0.05, 1.0);
    let r = 5.0;
    for s in [0.5, 1.0, 2.5, 4.0, 5.0, 7.5] {
        // Material below y = 40 (the square's top edge); the tool centre `r − s` above.
        let q = Point::new(20.0, 40.0 + r - s);
        let want = (1.0 - s / r).acos();
        let tol = 2.0 * 0.05 / (r * want.sin().max(0.3)) + std::f64::consts::PI / 48.0;
        let east = f.contact_arc(q, Vec2::new(1.0, 0.0), r);
        assert!((east - want).abs() <= tol, "s {s}: {east} against {want}");
        // Heading west the material is on the left: the same arc.
        let west = f.contact_arc(q, Vec2::new(-1.0, 0.0), r);
        assert!((west - want).abs() <= tol, "s {s}: {west} against {want}");
    }
    let mid = f.contact_arc(Point::new(20.0, 20.0), Vec2::new(0.0, 1.0), r);
    assert!((mid - std::f64::consts::PI).abs() < 1e-12, "{mid}");
    let none = f.contact_arc(Point::new(20.0, 60.0), Vec2::new(1.0, 0.0), r);
    assert!(none.abs() < 1e-12, "{none}");
}

/// A wall thinner than a cell (the outline runs in from the right wall to `x = 10` and
/// back, 1 µm apart) is no cell's outside: `wall_distance` does not see it, the
/// distance to thin walls does; a pocket without one has none.
#[test]
fn a_slit_is_a_wall_the_grid_is_not_sure_beside() {
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(40.0, 0.0),
        Point::new(40.0, 20.0),
        Point::new(10.0, 20.0),
        Point::new(40.0, 20.001),
        Point::new(40.0, 40.0),
        Point::new(0.0, 40.0),
    ];
    let shape = PocketShape::simple(Outline::from_points(&pts, "slit").unwrap());
    let f = Field::new(&shape, 0.1, 1.0);
    for q in [
        Point::new(20.0, 20.5),
        Point::new(30.0, 19.6),
        Point::new(9.0, 20.0),
    ] {
        assert!(f.wall_distance(q) > 5.0, "{q:?} {}", f.wall_distance(q));
        let want = if q.x < 10.0 {
            10.0 - q.x
        } else {
            (q.y - 20.0).abs()
        };
        let got = f.sure_distance(q);
        assert!(got <= want + 0.15, "{q:?}: {got} against {want}");
    }
    let plain = Field::new(&square(30.0), 0.1, 1.0);
    assert!(plain.thin.is_empty());
    let q = Point::new(12.0, 7.0);
    assert!((plain.sure_distance(q) - plain.wall_distance(q)).abs() < 1e-12);
}

fn square(side: f64) -> PocketShape {
    rect(side, side)
}

/// The rectangle `[0, w] × [0, h]`.
fn rect(w: f64, h: f64) -> PocketShape {
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(w, 0.0),
        Point::new(w, h),
        Point::new(0.0, h),
    ];
    PocketShape::simple(Outline::from_points(&pts, "t").unwrap())
}

/// Spans over several 64-bit words (a disc 160 cells wide) count as the cells one by one.
#[test]
fn wide_discs_count_across_words() {
    let f = Field::new(&square(30.0), 0.1, 1.0);
    for (q, r) in [
        (Point::new(15.03, 14.97), 8.0),
        (Point::new(6.4, 25.0), 12.5),
        (Point::new(-0.5, 0.2), 3.0),
    ] {
        let brute = (0..f.ny)
            .flat_map(|j| (0..f.nx).map(move |i| (i, j)))
            .filter(|&(i, j)| f.get(i, j) && f.centre(i, j).distance(q) <= r)
            .count() as u32;
        assert!(brute > 0);
        assert_eq!(f.count_disc(q, r), brute, "{q:?} {r}");
    }
}

/// The early-stopping test agrees with the cells counted one by one, on a field with
/// holes cleared in it, for thresholds below, at and above each disc's count.
#[test]
fn disc_thresholds_agree_with_the_cells_one_by_one() {
    let mut f = Field::new(&square(30.0), 0.1, 1.0);
    f.clear_disc(Point::new(10.0, 10.0), 6.0);
    f.clear_capsule(Point::new(3.0, 25.0), Point::new(28.0, 20.0), 2.5);
    let mut checked = 0;
    for k in 0..200 {
        let t = f64::from(k);
        let q = Point::new(-2.0 + (t * 7.31) % 34.0, -2.0 + (t * 3.77) % 34.0);
        let r = 0.3 + (t * 1.13) % 7.0;
        let brute = (0..f.ny)
            .flat_map(|j| (0..f.nx).map(move |i| (i, j)))
            .filter(|&(i, j)| f.get(i, j) && f.centre(i, j).distance(q) <= r)
            .count() as u32;
        for k in [0, 1, brute.saturating_sub(1), brute, brute + 1, 4] {
            assert_eq!(f.disc_holds_more_than(q, r, k), brute > k, "{q:?} {r} {k}");
        }
        checked += u32::from(brute == 0) + u32::from(brute > 0) * 2;
    }
    assert!(
        checked > 250,
        "both empty and holding discs are tried: {checked}"
    );
}

/// The distance from `p` to the segment `a`–`b`.
fn to_segment(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let t = if ab.length() < 1e-12 {
        0.0
    } else {
        ((p - a).dot(ab) / ab.dot(ab)).clamp(0.0, 1.0)
    };
    p.distance(a + ab * t)
}

/// A capsule clears every material cell whose centre lies within `r` of the segment and
/// none beyond (1e-9 mm either side of the boundary aside), and counts what it cleared:
/// segments along the axes, slanted, shorter than a cell, of zero length, and leaving the
/// grid.
#[test]
fn capsules_clear_the_band_a_segment_sweeps() {
    let cases = [
        (Point::new(5.0, 5.0), Point::new(20.0, 5.0), 3.0),
        (Point::new(12.1, 3.3), Point::new(12.1, 24.7), 4.2),
        (Point::new(3.3, 4.1), Point::new(24.9, 21.7), 6.35),
        (Point::new(22.0, 6.0), Point::new(7.5, 19.0), 2.5),
        (Point::new(15.0, 15.0), Point::new(15.07, 15.02), 5.0),
        (Point::new(10.0, 10.0), Point::new(10.0, 10.0), 4.0),
        (Point::new(-3.0, 12.0), Point::new(40.0, 30.0), 5.5),
    ];
    for (a, b, r) in cases {
        let mut f = Field::new(&square(30.0), 0.2, 1.0);
        let before = f.clone();
        let n = f.clear_capsule(a, b, r);
        let mut cleared = 0;
        for j in 0..f.ny {
            for i in 0..f.nx {
                let d = to_segment(f.centre(i, j), a, b);
                let (was, is) = (before.get(i, j), f.get(i, j));
                if was && !is {
                    cleared += 1;
                    assert!(d <= r + 1e-9, "{a:?}-{b:?}: cleared at {d}");
                }
                if was && is {
                    assert!(d >= r - 1e-9, "{a:?}-{b:?}: left at {d}");
                }
            }
        }
        assert!(cleared > 0, "{a:?}-{b:?}");
        assert_eq!(n, cleared, "{a:?}-{b:?}");
    }
}

#[test]
fn coarse_updates_agree_with_the_blocks_one_by_one() {
    let mut f = Field::new(&rect(60.0, 40.0), 0.25, 1.0);
    let k = 4;
    let hc = f.h * k as f64;
    let cap = 1.0 + 4.0 * hc;
    // The nearest block holding material, each block's cells read one by one.
    let brute = |f: &Field| -> Vec<f64> {
        let (cx, cy) = (f.nx.div_ceil(k), f.ny.div_ceil(k));
        let full: Vec<bool> = (0..cx * cy)
            .map(|b| {
                let (bi, bj) = (b % cx, b / cx);
                (bj * k..((bj + 1) * k).min(f.ny))
                    .any(|j| (bi * k..((bi + 1) * k).min(f.nx)).any(|i| f.get(i, j)))
            })
            .collect();
        (0..cx * cy)
            .map(|b| {
                let (bi, bj) = ((b % cx) as f64, (b / cx) as f64);
                (0..cx * cy)
                    .filter(|&m| full[m])
                    .map(|m| ((m % cx) as f64 - bi).hypot((m / cx) as f64 - bj) * hc)
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    };
    let mut map = f.coarse_distance(k);
    f.take_changed();
    let mut incremental = 0;
    let cuts = [
        (Point::new(10.0, 10.0), Point::new(14.0, 11.0)),
        (Point::new(30.0, 20.0), Point::new(30.0, 20.0)),
        (Point::new(31.0, 20.5), Point::new(35.0, 24.0)),
        (Point::new(50.0, 35.0), Point::new(52.0, 30.0)),
        (Point::new(12.0, 12.0), Point::new(8.0, 9.0)),
    ];
    for (n, &(a, b)) in cuts.iter().enumerate() {
        if n == 3 {
            // Cleared, then put back: the map must see the material again.
            f.record();
            f.clear_capsule(a, b, 1.0);
            let changed = f.take_changed().unwrap();
            map = f.coarse_update(k, map, changed, cap);
            f.undo();
        } else {
            f.clear_capsule(a, b, 1.0);
        }
        let changed = f.take_changed().unwrap();
        let (cx, cy) = (map.nx, map.ny);
        map = f.coarse_update(k, map, changed, cap);
        let m = (cap / hc).ceil() as usize + 2;
        let span = |lo: usize, hi: usize, n: usize| (hi / k - lo / k + 4 * m + 1).min(n);
        let wide = span(changed[0], changed[1], cx) * span(changed[2], changed[3], cy);
        incremental += usize::from(2 * wide <= cx * cy);
        let want = brute(&f);
        for (b, (&got, &want)) in map.dist.iter().zip(&want).enumerate() {
            if want <= cap {
                assert!(
                    (got - want).abs() < 1e-9,
                    "cut {n}, block {b}: {got} against {want}"
                );
            } else {
                assert!(
                    got > cap,
                    "cut {n}, block {b}: {got} within the cap, {want} is not"
                );
            }
        }
    }
    assert!(incremental >= 3, "{incremental} updates were windowed");
}
