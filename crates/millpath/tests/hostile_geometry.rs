//! "No panic on any input" for the geometry pipelines: the contour strategy from arbitrary
//! points (curve construction + offsetting + toolpath) and pocket toolpaths from arbitrary
//! polygons and parameters.
//!
//! What succeeds is verified, not only run: every contour's finishing pass is sampled against
//! the exact curve (kurbo's nearest point, `curve::verify`): within `[r − ρ, r + T]` of it
//! inside and outside, within `T` on it; every pocket is planned by `pocket::generate` with
//! its stock simulation (a coarse raster) and must pass it: no gouge, no uncut material, no
//! rapid through material. `HOSTILE_SEED=N` explores other seeds (printed with a failure).
//!
//! Inputs are mostly plausible (star-shaped polygons of random size, sane options) so the
//! calls get deep into the algorithms, with a hostile value (NaN, ±∞, 1e300, 0, negative,
//! tiny) substituted now and then. Seeded and bounded; a panic fails with the input.

mod hostile_common;

use hostile_common::{Harness, env_or, hostile_f64, mostly_sane, rng};
use millpath::curve::{self, CurveKind, LabeledPoint};
use millpath::geom::Outline;
use millpath::strategy::contour::{self, ContourOptions, Side};
use millpath::strategy::pocket::{
    self, Direction, Entry, PocketOptions, PocketShape, Stepover, StrategyKind,
};
use millpath::{Point, Tool};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// A star-shaped polygon around `(cx, cy)` (angles sorted, radii random), or with probability
/// `p_chaos` points in random order (self-intersecting, repeated, collinear...).
fn polygon(r: &mut ChaCha8Rng, n: usize, size: f64, p_chaos: f64) -> Vec<Point> {
    let (cx, cy) = (r.random_range(-50.0..50.0), r.random_range(-50.0..50.0));
    if r.random_bool(p_chaos) {
        // A hostile `size` keeps its effect on the star branch; here it must give a range.
        let size = if size.is_finite() && size > 1e-9 {
            size.min(1e6)
        } else {
            1.0
        };
        return (0..n)
            .map(|_| {
                if r.random_bool(0.1) {
                    Point::new(hostile_f64(r), hostile_f64(r))
                } else if r.random_bool(0.1) {
                    Point::new(cx, cy)
                } else {
                    Point::new(
                        cx + r.random_range(-size..size),
                        cy + r.random_range(-size..size),
                    )
                }
            })
            .collect();
    }
    let mut angles: Vec<f64> = (0..n)
        .map(|_| r.random_range(0.0..std::f64::consts::TAU))
        .collect();
    angles.sort_by(f64::total_cmp);
    angles
        .into_iter()
        .map(|a| {
            let rad = size * r.random_range(0.3..1.0);
            Point::new(cx + rad * a.cos(), cy + rad * a.sin())
        })
        .collect()
}

fn tool(r: &mut ChaCha8Rng) -> Tool {
    Tool {
        diameter: mostly_sane(r, 0.5, 20.0, 0.1),
        flutes: r.random_range(0..5),
        flute_length: mostly_sane(r, 5.0, 50.0, 0.05),
        number: r.random_range(0..100),
    }
}

#[test]
fn contour_pipeline_survives_arbitrary_points() {
    let mut h = Harness::new("contour pipeline");
    let seed = env_or("HOSTILE_SEED", 0xc047u64);
    let mut r = rng(seed);
    let mut ok = 0;
    for _ in 0..100 {
        let n = 4 * r.random_range(1..4);
        let size = mostly_sane(&mut r, 5.0, 80.0, 0.05);
        let pts = polygon(&mut r, n, size, 0.25);
        let groups: Vec<Vec<LabeledPoint>> = pts
            .chunks(4)
            .map(|c| {
                c.iter()
                    .enumerate()
                    .map(|(i, p)| LabeledPoint {
                        p: *p,
                        origin: format!("point {i}"),
                    })
                    .collect()
            })
            .collect();
        let kind = match r.random_range(0..3) {
            0 => CurveKind::FourPoint,
            1 => CurveKind::CatmullRom,
            _ => CurveKind::Spline,
        };
        let opt = ContourOptions::default()
            .with_tool(tool(&mut r))
            .with_tolerance(mostly_sane(&mut r, 0.01, 0.2, 0.05))
            .with_side(match r.random_range(0..3) {
                0 => Side::Inside,
                1 => Side::Outside,
                _ => Side::On,
            })
            .with_top_z(mostly_sane(&mut r, -5.0, 5.0, 0.05))
            .with_depth(mostly_sane(&mut r, 0.5, 6.0, 0.05))
            .with_step_down(mostly_sane(&mut r, 1.0, 4.0, 0.05))
            .with_finish_allowance(mostly_sane(&mut r, 0.0, 1.0, 0.05))
            .with_safe_height(mostly_sane(&mut r, 1.0, 10.0, 0.03))
            .with_clearance_height(mostly_sane(&mut r, 0.5, 2.0, 0.03))
            .with_feed(mostly_sane(&mut r, 1.0, 50.0, 0.03))
            .with_plunge_feed(mostly_sane(&mut r, 1.0, 20.0, 0.03))
            .with_lead_radius(mostly_sane(&mut r, 0.0, 5.0, 0.05))
            .with_rapid_speed(mostly_sane(&mut r, 50.0, 200.0, 0.03))
            .with_arcs(r.random_bool(0.5));
        let done = h.run(&(seed, &pts, kind, &opt), || {
            let Ok(c) = curve::build(&groups, kind, "fuzz") else {
                return false;
            };
            let Ok(res) = contour::contour(&c, &opt) else {
                return false;
            };
            let (lo, hi) = finishing_distance(&c, &res.toolpath, opt.side == Side::On);
            let rad = if opt.side == Side::On {
                0.0
            } else {
                opt.tool.radius()
            };
            assert!(
                lo >= rad - opt.rounding - 1e-9 && hi <= rad + opt.tolerance + 1e-9,
                "seed {seed:#x}: the finishing pass lies {lo:.6}..{hi:.6} mm from the curve, \
                 the band is [{:.6}, {:.6}]",
                rad - opt.rounding,
                rad + opt.tolerance
            );
            true
        });
        ok += usize::from(done == Some(true));
    }
    // The pass must reach the offsetting and toolpath code, not only the input checks.
    assert!(ok >= 15, "seed {seed:#x}: only {ok} contours generated");
    h.finish(100);
}

/// The smallest and largest distance from the finishing level's cutting moves (those tagged
/// with a curve parameter: the loop, not its lead arcs) to the exact curve, sampled at 8
/// points a move (arcs on the arc); with `drawn`, to the curve as drawn (the fish-tail lobes
/// cut off its corners included, which a pass on the outline traces).
fn finishing_distance(
    c: &curve::CompositeCurve,
    tp: &millpath::Toolpath,
    drawn: bool,
) -> (f64, f64) {
    let lobes: Vec<Vec<Point>> = if drawn {
        c.lobes()
            .iter()
            .flat_map(|l| [l.to_tip, l.from_tip])
            .map(|k| (0..=256).map(|j| k.eval(f64::from(j) / 256.0)).collect())
            .collect()
    } else {
        Vec::new()
    };
    let Some(lv) = tp.levels.last() else {
        return (f64::INFINITY, f64::NEG_INFINITY);
    };
    let segs: Vec<_> = tp.segments().collect();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (from, m) in &segs[lv.start..lv.end] {
        if m.tag.is_none() || !m.is_feed() {
            continue;
        }
        for j in 0..=8 {
            let f = f64::from(j) / 8.0;
            let p = match (m.kind, m.sweep_from(*from)) {
                (millpath::toolpath::MoveKind::Arc { center, .. }, Some((rad, sweep))) => {
                    let a0 = (from.xy() - center.xy()).angle();
                    center.xy() + millpath::Vec2::from_angle(a0 + sweep * f) * rad
                }
                _ => from.xy().lerp(m.to.xy(), f),
            };
            let d = lobes
                .iter()
                .flat_map(|l| l.windows(2))
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let e = b - a;
                    let t = ((p - a).dot(e) / e.dot(e).max(1e-300)).clamp(0.0, 1.0);
                    p.distance(a + e * t)
                })
                .fold(curve::distance_to_curve(c, p), f64::min);
            lo = lo.min(d);
            hi = hi.max(d);
        }
    }
    (lo, hi)
}

#[test]
fn pocket_toolpaths_survive_arbitrary_polygons_and_options() {
    let mut h = Harness::new("pocket toolpath");
    let seed = env_or("HOSTILE_SEED", 0x90c4e7u64);
    let mut r = rng(seed);
    let mut ok = 0;
    for _ in 0..120 {
        let n = r.random_range(3..12);
        let size = mostly_sane(&mut r, 8.0, 60.0, 0.05);
        let pts = polygon(&mut r, n, size, 0.2);
        let island = if r.random_bool(0.3) {
            let k = r.random_range(3..6);
            Some(polygon(&mut r, k, size * 0.2, 0.1))
        } else {
            None
        };
        let t = tool(&mut r);
        let kind = match r.random_range(0..3) {
            0 => StrategyKind::Zigzag,
            1 => StrategyKind::Offset,
            _ => StrategyKind::Spiral,
        };
        let opts = PocketOptions::default()
            .with_stepover(if r.random_bool(0.5) {
                Stepover::Fraction(mostly_sane(&mut r, 0.1, 1.0, 0.05))
            } else {
                Stepover::Distance(mostly_sane(&mut r, 0.5, 5.0, 0.05))
            })
            .with_depth(mostly_sane(&mut r, 0.5, 8.0, 0.05))
            .with_step_down(mostly_sane(&mut r, 2.0, 5.0, 0.05))
            .with_wall_stock(mostly_sane(&mut r, 0.0, 0.5, 0.05))
            .with_floor_stock(mostly_sane(&mut r, 0.0, 0.3, 0.05))
            .with_direction(if r.random_bool(0.5) {
                Direction::Climb
            } else {
                Direction::Conventional
            })
            .with_entry(if r.random_bool(0.5) {
                Entry::Helix {
                    radius: mostly_sane(&mut r, 0.5, 5.0, 0.05),
                    ramp_angle: mostly_sane(&mut r, 0.02, 0.2, 0.05),
                }
            } else {
                Entry::Ramp {
                    ramp_angle: mostly_sane(&mut r, 0.02, 0.2, 0.05),
                }
            })
            .with_safe_height(mostly_sane(&mut r, 0.5, 2.0, 0.03))
            .with_clearance_height(mostly_sane(&mut r, 2.0, 10.0, 0.03))
            .with_feed(mostly_sane(&mut r, 1.0, 50.0, 0.03))
            .with_plunge_feed(mostly_sane(&mut r, 1.0, 20.0, 0.03))
            .with_slowdown(mostly_sane(&mut r, 0.2, 1.0, 0.03))
            .with_zigzag_angle(mostly_sane(&mut r, -3.0, 3.0, 0.05))
            .with_transition(mostly_sane(&mut r, 0.0, 1.0, 0.05))
            .with_min_radius(mostly_sane(&mut r, 0.1, 2.0, 0.05))
            .with_morph(Default::default())
            .with_arcs(false)
            .with_curvature_ramps(true)
            .with_finish(r.random_bool(0.3))
            .with_modulate_feed(false);
        // Half the cases with `--arcs`, derived from a drawn value so that the seeded
        // sequence (and the cases the other fields get) stays as it was.
        let arcs = opts.spiral.min_radius > 1.05;
        let opts = opts.with_arcs(arcs);
        let done = h.run(&(seed, &pts, &island, &t, kind, &opts), || {
            let Ok(outer) = Outline::from_points(&pts, "fuzz outer") else {
                return false;
            };
            let islands: Vec<Outline> = island
                .iter()
                .filter_map(|p| Outline::from_points(p, "fuzz island").ok())
                .collect();
            let Ok(shape) = PocketShape::new(outer, islands, "fuzz") else {
                return false;
            };
            // A coarse raster (about 60 cells across) keeps the pass to seconds.
            let b = shape.outer.bounds();
            let cell = (b.width().max(b.height()) / 60.0).max(0.05);
            let sim = millpath::stock::SimOptions::default()
                .with_cell(cell)
                .with_step(2.0 * cell);
            match pocket::generate(kind, &shape, &t, &opts, &sim) {
                Ok(res) => {
                    let p = res.verification.problems();
                    assert!(p.is_empty(), "seed {seed:#x}: {kind:?}: {p:?}");
                    true
                }
                Err(millpath::Error::Internal(e)) => {
                    panic!("seed {seed:#x}: {kind:?}: internal error: {e}")
                }
                Err(_) => false,
            }
        });
        ok += usize::from(done == Some(true));
    }
    // The pass must reach the strategies, not only the input checks.
    assert!(ok >= 20, "seed {seed:#x}: only {ok} pockets generated");
    h.finish(120);
}
