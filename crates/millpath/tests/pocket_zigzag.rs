//! The zigzag as lean as the peers': its rows turn on half circles inside the pocket, no row
//! runs along the walls' loop that the clean-up pass cuts nor nearer it than 1.5 tool radii
//! (the pass covers the band between), and the entry ramps down once at the plunge rate. Checked on the moves and by the stock simulation, on the aerospace pocket
//! and on rounded rectangles of aspect 1:1 to 4:1.

use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::toolpath::{MoveKind, Tool, Toolpath};

fn pockets() -> Vec<(&'static str, PocketShape)> {
    let rect =
        |w: f64, h: f64| PocketShape::simple(builtin::rounded_rectangle(0.0, 0.0, w, h, 6.0));
    vec![
        ("aerospace", builtin::aerospace_pocket()),
        ("1:1", rect(100.0, 100.0)),
        ("2:1", rect(160.0, 80.0)),
        ("4:1", rect(200.0, 50.0)),
    ]
}

fn opts() -> PocketOptions {
    PocketOptions::default().with_depth(5.0).with_step_down(5.0)
}

/// The half turns at the level: two quarter arcs in a row, of one radius, turning one way.
fn half_turns(tp: &Toolpath, z: f64) -> usize {
    let mut from = tp.start;
    let mut prev: Option<(f64, bool)> = None;
    let mut n = 0;
    for m in &tp.moves {
        let flat = (from.z - z).abs() < 1e-9 && (m.to.z - z).abs() < 1e-9;
        let arc = match m.kind {
            MoveKind::Arc { center, ccw, .. } if flat => {
                Some((from.xy().distance(center.xy()), ccw))
            }
            _ => None,
        };
        if let (Some((r0, c0)), Some((r1, c1))) = (prev, arc)
            && (r0 - r1).abs() < 1e-6
            && c0 == c1
        {
            n += 1;
            prev = None;
        } else {
            prev = arc;
        }
        from = m.to;
    }
    n
}

#[test]
fn rows_turn_on_half_circles_and_leave_nothing() {
    let tool = Tool::flat(12.7).unwrap();
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    for (name, shape) in pockets() {
        let r = pocket::generate(StrategyKind::Zigzag, &shape, &tool, &opts(), &sim).unwrap();
        assert!(
            r.verification.problems().is_empty(),
            "{name}: {:?}",
            r.verification.problems()
        );
        let tp = &r.toolpath;
        let z = tp.levels[0].z;
        // Rows across the pocket's short side, a stepover apart, the first and the last
        // within 1.5 tool radii of the walls' loop, which the clean-up pass cuts (every
        // point between within 0.75 r of one of the two passes): as few as that allows, and
        // a half turn between each two.
        let b = shape.outer.bounds();
        let short = (b.max.x - b.min.x).min(b.max.y - b.min.y) - tool.diameter;
        let edge = 1.5 * tool.radius();
        let rows = ((short - 2.0 * edge) / (0.4 * tool.diameter) - 1e-9).ceil() as usize + 1;
        let turns = half_turns(tp, z);
        assert_eq!(
            turns,
            rows - 1,
            "{name}: {turns} half turns for {rows} rows"
        );
        // The rows (feed moves at the level along the long side, together longer than half
        // of it at one height: the feed modulation splits a row) lie between the walls'
        // loop's long sides, the outermost within 1.5 r of them.
        let along_x = b.max.x - b.min.x >= b.max.y - b.min.y;
        let (lo, hi) = if along_x {
            (b.min.y + tool.radius(), b.max.y - tool.radius())
        } else {
            (b.min.x + tool.radius(), b.max.x - tool.radius())
        };
        let long = (b.max.x - b.min.x).max(b.max.y - b.min.y) - tool.diameter;
        let mut heights: Vec<(f64, f64)> = Vec::new();
        // (In plan: the first row's ramp runs along it.)
        for (f, m) in tp.segments() {
            if !m.is_feed() || f.z < z - 1e-9 || m.to.z < z - 1e-9 {
                continue;
            }
            let (c, d_along, d_across) = if along_x {
                (f.y, (m.to.x - f.x).abs(), (m.to.y - f.y).abs())
            } else {
                (f.x, (m.to.y - f.y).abs(), (m.to.x - f.x).abs())
            };
            if d_across > 1e-9 || c < lo + 1e-6 || c > hi - 1e-6 {
                continue;
            }
            match heights.iter_mut().find(|h| (h.0 - c).abs() < 1e-6) {
                Some(h) => h.1 += d_along,
                None => heights.push((c, d_along)),
            }
        }
        let across: Vec<f64> = heights
            .iter()
            .filter(|h| h.1 > 0.5 * long)
            .map(|h| h.0)
            .collect();
        assert_eq!(across.len(), rows, "{name}: rows at {across:?}");
        let first = across.iter().copied().fold(f64::INFINITY, f64::min);
        let last = across.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            first - lo <= edge + 1e-6 && hi - last <= edge + 1e-6,
            "{name}: outermost rows {:.3} and {:.3} mm from the walls' loop, bound {edge:.3}",
            first - lo,
            hi - last
        );
        // Cut length: the rows, the turns and the walls' loop once, not a row along it.
        let bound = rows as f64 * long + 2.0 * (long + short) + turns as f64 * 0.5 * tool.diameter;
        let cut: f64 = tp
            .segments()
            .filter(|(f, m)| m.is_feed() && (f.z - z).abs() < 1e-9 && (m.to.z - z).abs() < 1e-9)
            .map(|(f, m)| m.length_from(f))
            .sum();
        assert!(
            cut <= bound,
            "{name}: {cut:.1} mm cut at the level, bound {bound:.1}"
        );
    }
}

/// The first cut's ramp runs down the head of its first row once, from its far end back to
/// its start, no steeper than the ramp angle, descending no faster than the plunge feed and
/// moving no faster than the feed.
#[test]
fn the_ramp_runs_down_once_at_the_plunge_rate() {
    let tool = Tool::flat(12.7).unwrap();
    let o = opts().with_entry(pocket::Entry::Ramp {
        ramp_angle: 3f64.to_radians(),
    });
    for (name, shape) in pockets() {
        let tp = pocket::toolpath(StrategyKind::Zigzag, &shape, &tool, &o).unwrap();
        let z = tp.levels[0].z;
        let top = 0.0 + o.safe_height;
        let mut ramp = 0.0;
        for (f, m) in tp.segments() {
            // The first cut's ramp: every feed move before the first at the level.
            if m.is_feed() && f.z <= z + 1e-9 {
                break;
            }
            if !m.is_feed() {
                continue;
            }
            // Along the path in plan (arcs and lines alike): the length the ramp angle is
            // measured on.
            let drop = f.z - m.to.z;
            let len = (m.length_from(f).powi(2) - drop * drop).max(0.0).sqrt();
            assert!(drop >= -1e-9, "{name}: the ramp climbs");
            assert!(
                drop <= len * 3f64.to_radians().tan() + 1e-6,
                "{name}: steeper than 3°"
            );
            assert!(m.feed <= o.feed + 1e-9, "{name}: ramp faster than the feed");
            assert!(
                m.feed * drop <= o.plunge_feed * m.length_from(f) * (1.0 + 1e-9),
                "{name}: descends faster than the plunge feed"
            );
            ramp += len;
        }
        let once = (top - z) / 3f64.to_radians().tan();
        assert!(
            (ramp - once).abs() < 1e-3,
            "{name}: ramp {ramp:.3} mm, once down is {once:.3} mm"
        );
    }
}

/// Where the walls' loop and the second row cover the first row's swath (the first row
/// `1.9 r − s` or nearer the walls' loop, the second within `1.9 r` of it) without costing a
/// row, the first row is ramped along as it is cut: the ramp's passes run back and forth on
/// the first row, the last one on in the row's direction, and no feed move at the level comes
/// back over the ramp's span (the second row, a stepover away, takes what the ramp left).
/// Where that would cost a row (the 4:1 strip: 37.3 mm between the walls' loop's long sides,
/// four stepovers and two gaps of at most 1.5 r without it, five with it), the ramp runs back
/// along the row, which is cut again at the level. The stock simulation finds nothing left
/// either way, and with `ZigzagOptions::ramp_recut` (the fallback where it does not) the
/// ramp runs back along the row everywhere.
#[test]
fn the_first_row_is_ramped_along_as_it_is_cut() {
    let tool = Tool::flat(12.7).unwrap();
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    let cases = pockets()
        .into_iter()
        .map(|(name, shape)| (name, shape, false))
        .chain(std::iter::once((
            "1:1 recut",
            pockets().swap_remove(1).1,
            true,
        )));
    for (name, shape, recut) in cases {
        let o = opts().with_zigzag_ramp_recut(recut);
        let r = pocket::generate(StrategyKind::Zigzag, &shape, &tool, &o, &sim).unwrap();
        assert!(
            r.verification.problems().is_empty(),
            "{name}: {:?}",
            r.verification.problems()
        );
        let tp = &r.toolpath;
        let z = tp.levels[0].z;
        // The ramp: the feed moves before the first at the level, in plan.
        let mut ramp: Vec<(millpath::geom::Point, millpath::geom::Point)> = Vec::new();
        let mut after: Option<millpath::geom::Vec2> = None;
        let mut last: Option<millpath::geom::Vec2> = None;
        let mut at_level: Vec<(millpath::geom::Point, millpath::geom::Point)> = Vec::new();
        for (f, m) in tp.segments() {
            if !m.is_feed() {
                continue;
            }
            let (a, b) = (f.xy(), m.to.xy());
            if f.z > z + 1e-9 {
                ramp.push((a, b));
                last = (b - a).normalize();
            } else if (m.to.z - z).abs() < 1e-9 {
                if after.is_none() {
                    after = (b - a).normalize();
                }
                at_level.push((a, b));
            }
        }
        // The middle of the longest ramp move: on the first row.
        let (a, b) = ramp
            .iter()
            .copied()
            .max_by(|x, y| x.0.distance(x.1).total_cmp(&y.0.distance(y.1)))
            .unwrap();
        let mid = a + (b - a) * 0.5;
        let near = at_level
            .iter()
            .map(|&(a, b)| distance_to_segment(mid, a, b))
            .fold(f64::INFINITY, f64::min);
        let s = 0.4 * tool.diameter;
        if name == "4:1" || recut {
            assert!(near < 1e-6, "{name}: the row is cut again ({near:.3} mm)");
        } else {
            // On one line: every ramp move along the first.
            let u = (ramp[0].1 - ramp[0].0).normalize().unwrap();
            for &(a, b) in &ramp {
                assert!(
                    (b - a).cross(u).abs() < 1e-6 && (a - ramp[0].0).cross(u).abs() < 1e-6,
                    "{name}: a ramp move off the first row"
                );
            }
            assert!(
                after.unwrap().dot(last.unwrap()) > 0.999,
                "{name}: the row turns back after the ramp"
            );
            assert!(
                near > 0.25 * s,
                "{name}: a move at the level comes {near:.3} mm from the ramp's middle"
            );
        }
    }
}

fn distance_to_segment(
    p: millpath::geom::Point,
    a: millpath::geom::Point,
    b: millpath::geom::Point,
) -> f64 {
    let d = b - a;
    let l2 = d.dot(d);
    let t = if l2 > 0.0 {
        ((p - a).dot(d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + d * t)
}
