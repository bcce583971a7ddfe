//! Tests of the levels: entries, heights, links between levels.

use super::*;

fn square_region() -> OffsetRegion {
    let mut pl = cavalier_contours::polyline::Polyline::new_closed();
    use cavalier_contours::polyline::PlineSourceMut;
    for (x, y) in [(0.0, 0.0), (20.0, 0.0), (20.0, 20.0), (0.0, 20.0)] {
        pl.add(x, y, 0.0);
    }
    OffsetRegion {
        outers: vec![pl],
        islands: Vec::new(),
    }
}

/// A cut round most of the square region (a triangle) and a sliver cut 1 µm long inside it,
/// both ramps.
fn big_and_sliver() -> (Cut, Cut) {
    use super::super::segments::segs_from_points;
    let p = Point::new;
    let big = Cut {
        entry: CutEntry::Ramp,
        path: segs_from_points(&[p(2.0, 2.0), p(18.0, 2.0), p(18.0, 18.0), p(2.0, 2.0)]),
    };
    let sliver = Cut {
        entry: CutEntry::Ramp,
        path: segs_from_points(&[p(12.0, 12.5), p(12.001, 12.5)]),
    };
    (big, sliver)
}

/// A sliver cut is entered over cleared material, never plunged; alone on its level it
/// is refused.
#[test]
fn sliver_cuts_enter_over_cleared_material_or_are_refused() {
    let p = Point::new;
    let (big, sliver) = big_and_sliver();
    let opts = PocketOptions::default().with_depth(4.0).with_step_down(4.0);
    let tool = Tool::flat(4.0).unwrap();
    // The sliver first: it is moved after the big cut and entered from the big cut's
    // point nearest to it.
    let mut plan = LevelPlan {
        cuts: vec![sliver.clone(), big],
    };
    direct_entries(
        &mut plan,
        &square_region(),
        12.0,
        min_ramp_path(&opts),
        false,
    );
    assert_eq!(plan.cuts[0].entry, CutEntry::Ramp);
    // The nearest point of the big cut's diagonal, (12.25, 12.25), not a segment's end.
    let CutEntry::Direct { from } = plan.cuts[1].entry else {
        panic!("{:?}", plan.cuts[1].entry);
    };
    assert!(from.distance(p(12.25, 12.25)) < 1e-12, "{from:?}");
    let tp = assemble(tool, &opts, &[plan], None, &[]).unwrap();
    // No move steeper than 45° ends below the top except the feed down there.
    for (from, m) in tp.segments() {
        let dz = from.z - m.to.z;
        if m.is_feed() && m.to.z < 0.0 && dz > from.xy().distance(m.to.xy()) {
            assert!(m.to.xy().distance(p(12.25, 12.25)) < 1e-12, "{m:?}");
        }
    }
    // Alone, the sliver cannot be entered.
    let alone = LevelPlan { cuts: vec![sliver] };
    let e = assemble(tool, &opts, &[alone], None, &[]).unwrap_err();
    assert!(e.to_string().contains("entry"), "{e}");
}

/// With `only_short` (the adaptive planner, which planned every cut against the material
/// the cuts before it left) the cuts keep their order: the sliver stays first, still a ramp
/// (no earlier cut to enter from), and the big cut stays second.
#[test]
fn a_planner_that_saw_the_material_keeps_its_order() {
    let (big, sliver) = big_and_sliver();
    let opts = PocketOptions::default().with_depth(4.0).with_step_down(4.0);
    let entered = |cuts: Vec<Cut>| {
        let mut plan = LevelPlan { cuts };
        direct_entries(
            &mut plan,
            &square_region(),
            12.0,
            min_ramp_path(&opts),
            true,
        );
        plan
    };
    let plan = entered(vec![sliver.clone(), big.clone()]);
    assert_eq!(plan.cuts[0].path, sliver.path);
    assert_eq!(plan.cuts[0].entry, CutEntry::Ramp);
    assert_eq!(plan.cuts[1].path, big.path);
    // After the big cut, the sliver is entered from it, in place.
    let plan = entered(vec![big, sliver.clone()]);
    assert_eq!(plan.cuts[1].path, sliver.path);
    assert!(matches!(plan.cuts[1].entry, CutEntry::Direct { .. }));
}

/// An arc piece whose ends lie a few ulps apart is written as a line, not read back as
/// the full circle its end and centre alone describe; a true arc stays an arc.
#[test]
fn an_arc_piece_of_no_sweep_is_a_line() {
    use super::super::segments::Arc;
    let c = Point::new(-240_000.0, 600_000.0);
    let a = c + Vec2::new(2000.0, 0.0);
    let sweep = 5e-15;
    let b = c + Vec2::from_angle(sweep) * 2000.0;
    let tiny = Seg {
        a,
        b,
        arc: Some(Arc {
            center: c,
            radius: 2000.0,
            ccw: true,
            sweep,
        }),
    };
    let m = seg_move(&tiny, -3.0, 10.0);
    assert!(matches!(m.kind, crate::toolpath::MoveKind::Line), "{m:?}");
    assert!(m.length_from(Point3::from_xy(a, -3.0)) < 1e-9);
    let quarter = Seg::from_bulge(
        Point::new(10.0, 0.0),
        Point::new(0.0, 10.0),
        (0.25f64 * std::f64::consts::FRAC_PI_2).tan(),
    );
    let m = seg_move(&quarter, 0.0, 10.0);
    assert!(
        matches!(m.kind, crate::toolpath::MoveKind::Arc { .. }),
        "{m:?}"
    );
}

/// The helix descends at exactly the ramp angle over its whole length, `drop / tan α`
/// mm of it, no whole turn rounded up: each arc's descent over its length (angle about
/// its centre, found here from its ends) is `tan α`, and it ends on the ray to the path.
#[test]
fn a_helix_descends_at_the_ramp_angle_and_no_further() {
    use super::super::segments::segs_from_points;
    use crate::toolpath::MoveKind;
    let p = Point::new;
    let center = p(10.0, 10.0);
    let path = segs_from_points(&[p(16.0, 10.0), p(18.0, 18.0), p(2.0, 18.0), p(16.0, 10.0)]);
    for (angle, radius) in [(3.0f64, 3.0), (2.0, 4.1), (7.0, 1.3)] {
        let alpha = angle.to_radians();
        let opts = PocketOptions::default()
            .with_depth(5.0)
            .with_step_down(5.0)
            .with_entry(Entry::Helix {
                radius,
                ramp_angle: alpha,
            });
        let plan = LevelPlan {
            cuts: vec![Cut {
                entry: CutEntry::Helix {
                    center,
                    radius,
                    flat_turn: true,
                },
                path: path.clone(),
            }],
        };
        let tool = Tool::flat(6.0).unwrap();
        let tp = assemble(tool, &opts, &[plan], None, &[]).unwrap();
        let mut length = 0.0;
        let mut last = None;
        for (from, m) in tp.segments() {
            let MoveKind::Arc { center: c, ccw, .. } = m.kind else {
                continue;
            };
            let dz = from.z - m.to.z;
            if dz <= 0.0 {
                continue;
            }
            let a0 = (from.y - c.y).atan2(from.x - c.x);
            let a1 = (m.to.y - c.y).atan2(m.to.x - c.x);
            let turn = if ccw { a1 - a0 } else { a0 - a1 }.rem_euclid(TAU);
            let r = from.xy().distance(c.xy());
            assert!((r - radius).abs() < 1e-9, "{r}");
            let along = r * turn;
            assert!(
                (dz / along - alpha.tan()).abs() < 1e-9,
                "{angle}°: {dz} over {along}"
            );
            length += along;
            last = Some(m.to);
        }
        let drop = opts.safe_height + 5.0;
        assert!((length - drop / alpha.tan()).abs() < 1e-6, "{length}");
        let end = last.unwrap();
        assert!((end.z + 5.0).abs() < 1e-12);
        let towards = (p(16.0, 10.0) - center).normalize().unwrap();
        assert!(
            end.xy().distance(center + towards * radius) < 1e-9,
            "{end:?}"
        );
    }
}

/// A racetrack entry (`CutEntry::Lap`) descends forwards round the loop at the head of the
/// path at the ramp angle, whole laps, every descending move on the loop and the last
/// ending at its start at the level; then the path follows at the level, its head the flat
/// lap. Checked on the moves: the slope of each, the points against the loop's own
/// geometry (lines and semicircles about the two ends).
#[test]
fn a_racetrack_entry_ramps_round_its_loop_then_runs_it_flat() {
    use super::super::segments::Seg;
    let p = Point::new;
    let (a, b, rho) = (p(0.0, 0.0), p(30.0, 0.0), 4.0);
    let head = vec![
        Seg::line(p(0.0, -rho), p(30.0, -rho)),
        Seg::from_bulge(p(30.0, -rho), p(30.0, rho), 1.0),
        Seg::line(p(30.0, rho), p(0.0, rho)),
        Seg::from_bulge(p(0.0, rho), p(0.0, -rho), 1.0),
    ];
    let len: f64 = head.iter().map(Seg::length).sum();
    assert!((len - (60.0 + TAU * rho)).abs() < 1e-9, "{len}");
    let mut path = head.clone();
    path.push(Seg::line(p(0.0, -rho), p(0.0, -rho - 3.0)));
    let on_loop = |q: Point| {
        let d = if q.x <= a.x {
            q.distance(a)
        } else if q.x >= b.x {
            q.distance(b)
        } else {
            q.y.abs()
        };
        (d - rho).abs() < 1e-9
    };
    for angle in [2.0f64, 3.0, 10.0] {
        let alpha = angle.to_radians();
        let opts = PocketOptions::default()
            .with_depth(5.0)
            .with_step_down(5.0)
            .with_entry(Entry::Helix {
                radius: rho,
                ramp_angle: alpha,
            });
        let plan = LevelPlan {
            cuts: vec![Cut {
                entry: CutEntry::Lap { len },
                path: path.clone(),
            }],
        };
        let tool = Tool::flat(6.0).unwrap();
        let tp = assemble(tool, &opts, &[plan], None, &[]).unwrap();
        let drop = opts.safe_height + 5.0;
        let laps = (drop / alpha.tan() / len).ceil();
        let mut descent = 0.0;
        let mut flat = 0.0;
        let mut bottom = None;
        for (from, m) in tp.segments() {
            let along = m.length_from(from);
            let dz = from.z - m.to.z;
            if dz > 1e-12 && m.kind != crate::toolpath::MoveKind::Rapid {
                assert!(on_loop(from.xy()) && on_loop(m.to.xy()), "{m:?}");
                let slope = dz / (along * along - dz * dz).sqrt();
                assert!(
                    (slope - drop / (laps * len)).abs() < 1e-6,
                    "{angle}°: {slope}"
                );
                descent += (along * along - dz * dz).sqrt();
                bottom = Some(m.to);
            } else if bottom.is_some() && (m.to.z + 5.0).abs() < 1e-12 && flat < len - 1e-9 {
                assert!(on_loop(m.to.xy()), "the flat lap leaves the loop: {m:?}");
                flat += along;
            }
        }
        assert!((descent - laps * len).abs() < 1e-6, "{angle}°: {descent}");
        assert!(drop / (laps * len) <= alpha.tan() + 1e-12);
        let end = bottom.unwrap();
        assert!(end.xy().distance(p(0.0, -rho)) < 1e-9 && (end.z + 5.0).abs() < 1e-12);
        assert!((flat - len).abs() < 1e-6, "{flat}");
    }
}

/// Between levels the tool rises only to the next level's safe height (`z + safe` over
/// the floor just cut) where the straight way to the next entry stays in the region the
/// level's tool centre swept; where an island of the region lies across it, to the
/// clearance height. Checked on the moves: the highest point between the two levels'
/// cutting moves, and every sampled point of a rapid below the clearance height inside
/// the square and outside the island (by coordinates, not by the region's loops).
#[test]
fn between_levels_the_tool_rises_only_over_cleared_ground() {
    use super::super::segments::segs_from_points;
    use cavalier_contours::polyline::{PlineSourceMut, Polyline};
    let p = Point::new;
    // A cut that ends far from where the helix of the next level starts.
    let path = segs_from_points(&[p(10.0, 6.0), p(18.0, 2.0), p(18.0, 18.0), p(2.0, 18.0)]);
    let plan = LevelPlan {
        cuts: vec![Cut {
            entry: CutEntry::Helix {
                center: p(10.0, 10.0),
                radius: 3.0,
                flat_turn: true,
            },
            path,
        }],
    };
    let opts = PocketOptions::default().with_depth(8.0).with_step_down(4.0);
    let tool = Tool::flat(4.0).unwrap();
    let open = square_region();
    let mut island = Polyline::new_closed();
    for (x, y) in [(4.0, 14.0), (4.0, 8.0), (8.0, 8.0), (8.0, 14.0)] {
        island.add(x, y, 0.0);
    }
    let blocked = OffsetRegion {
        outers: open.outers.clone(),
        islands: vec![island],
    };
    for (region, low) in [(open, true), (blocked, false)] {
        let tp = assemble(tool, &opts, std::slice::from_ref(&plan), None, &[region]).unwrap();
        let first = &tp.levels[0];
        let second = &tp.levels[1];
        let top = tp.moves[first.end - 1..second.start + 3]
            .iter()
            .take_while(|m| m.kind == crate::toolpath::MoveKind::Rapid)
            .map(|m| m.to.z)
            .fold(f64::NEG_INFINITY, f64::max);
        let want = if low {
            -4.0 + opts.safe_height
        } else {
            opts.clearance_height
        };
        assert!((top - want).abs() < 1e-12, "low {low}: {top}");
        for (from, m) in tp.segments() {
            if m.kind != crate::toolpath::MoveKind::Rapid || m.to.z >= opts.clearance_height {
                continue;
            }
            for k in 0..=100 {
                let q = from.xy().lerp(m.to.xy(), f64::from(k) / 100.0);
                let in_square = (0.0..=20.0).contains(&q.x) && (0.0..=20.0).contains(&q.y);
                let in_island = (4.0..=8.0).contains(&q.x) && (8.0..=14.0).contains(&q.y);
                assert!(
                    in_square && (low || !in_island),
                    "low {low}: {q:?} in {m:?}"
                );
            }
        }
    }
}

#[test]
fn levels_are_equal_and_reach_the_floor() {
    let o = PocketOptions::default()
        .with_depth(25.0)
        .with_step_down(6.0)
        .with_floor_stock(1.0);
    let d = level_depths(&o);
    assert_eq!(d.len(), 4);
    assert!((d[3] + 24.0).abs() < 1e-12);
    assert!(d.windows(2).all(|w| (w[0] - w[1] - 6.0).abs() < 1e-12));
}
