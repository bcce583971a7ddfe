//! Exactness with jerk unlimited: the planner's time is within 1% of the time-optimal
//! parameterisation under the same velocity and acceleration limits, computed here by an
//! independent fine-grid reference (numerical-integration TOPP on a grid of arc length: the
//! maximum-velocity curve from the per-axis limits, a backward pass with the largest
//! deceleration and a forward pass with the largest acceleration that the per-axis limits
//! `|P''_i·v² + P'_i·s̈| ≤ A_i` allow, `v² ← v² + 2·s̈·Δs`).
//!
//! The reference stops at non-tangent corners (finite acceleration cannot turn a velocity
//! vector instantly), which is the planner's exact-stop mode, so the corpus uses a machine with
//! path tolerance 0. Arcs are run at feeds below their centripetal caps: there the planner
//! deliberately gives only a share of the acceleration to the tangential direction (see
//! `motion::limits`), which the reference does not, and that conservatism is not what this
//! test measures.

use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::toolpath::{Move, MoveKind, Tool, Toolpath};
use millpath::{Point3, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Position derivatives (P', P'') by arc length at fraction `u` of a move.
fn derivs(from: Point3, m: &Move, u: f64) -> (Vec3, Vec3) {
    let len = m.length_from(from);
    match m.kind {
        MoveKind::Arc { center, plane, .. } => {
            let (r, sweep) = m.sweep_from(from).expect("arc");
            let (fu, fv, fw) = plane.split(from - center);
            let (_, _, tw) = plane.split(m.to - center);
            let a = fv.atan2(fu) + sweep * u;
            let w = sweep / len;
            (
                plane.join(-r * w * a.sin(), r * w * a.cos(), (tw - fw) / len),
                plane.join(-r * w * w * a.cos(), -r * w * w * a.sin(), 0.0),
            )
        }
        _ => ((m.to - from) / len, Vec3::ZERO),
    }
}

fn topp_time(tp: &Toolpath, mach: &Machine, per_block: usize) -> f64 {
    // Grid: (P', P'', feed cap, is the first point of a block after a corner).
    let mut pts: Vec<(Vec3, Vec3, f64, f64)> = Vec::new(); // P', P'', vcap, ds to next
    let mut prev_dir: Option<Vec3> = None;
    let mut stops = Vec::new();
    for (from, m) in tp.segments() {
        let len = m.length_from(from);
        let ds = len / per_block as f64;
        let (d0, _) = derivs(from, m, 0.0);
        if let Some(pd) = prev_dir
            && (pd - d0).length() > 1e-9
        {
            stops.push(pts.len());
        }
        for k in 0..per_block {
            let u = (k as f64 + 0.5) / per_block as f64;
            let (d1, d2) = derivs(from, m, u);
            let mut cap = m.feed.min(mach.max_feed);
            for i in 0..3 {
                let p1 = d1.to_array()[i].abs();
                let p2 = d2.to_array()[i].abs();
                if p1 > 1e-12 {
                    cap = cap.min(mach.axes[i].max_velocity / p1);
                }
                if p2 > 1e-12 {
                    cap = cap.min((mach.axes[i].max_acceleration / p2).sqrt());
                }
            }
            pts.push((d1, d2, cap, ds));
        }
        prev_dir = Some(derivs(from, m, 1.0).0);
    }
    // s̈ range at velocity v at grid point k.
    let range = |k: usize, v: f64| -> (f64, f64) {
        let (d1, d2, _, _) = pts[k];
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for i in 0..3 {
            let p1 = d1.to_array()[i];
            let c = d2.to_array()[i] * v * v;
            let a = mach.axes[i].max_acceleration;
            if p1.abs() > 1e-12 {
                let (x, y) = ((-a - c) / p1, (a - c) / p1);
                lo = lo.max(x.min(y));
                hi = hi.min(x.max(y));
            }
        }
        (lo, hi)
    };
    let n = pts.len();
    // Velocities at the n + 1 grid nodes (node k is the start of cell k).
    let mut v: Vec<f64> = (0..=n)
        .map(|k| {
            let a = if k > 0 { pts[k - 1].2 } else { 0.0 };
            let b = if k < n { pts[k].2 } else { 0.0 };
            a.min(b)
        })
        .collect();
    v[0] = 0.0;
    v[n] = 0.0;
    for &s in &stops {
        v[s] = 0.0;
    }
    for k in (0..n).rev() {
        let (lo, _) = range(k, v[k + 1]);
        let w = (v[k + 1] * v[k + 1] - 2.0 * lo.min(0.0) * pts[k].3).sqrt();
        v[k] = v[k].min(w);
    }
    for k in 0..n {
        let (_, hi) = range(k, v[k]);
        let w = (v[k] * v[k] + 2.0 * hi.max(0.0) * pts[k].3).sqrt();
        v[k + 1] = v[k + 1].min(w);
    }
    (0..n)
        .map(|k| {
            let s = v[k] + v[k + 1];
            if s > 0.0 { 2.0 * pts[k].3 / s } else { 0.0 }
        })
        .sum()
}

fn trapezoidal_machine() -> Machine {
    let mut m = Machine::preset("linuxcnc-sim").expect("preset");
    m.path_tolerance = 0.0;
    m.max_feed = 200.0;
    m.axes[2].max_acceleration = 1000.0;
    m.axes[0].max_velocity = 150.0;
    m
}

#[test]
fn polylines_within_one_percent_of_topp() {
    let mach = trapezoidal_machine();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for case in 0..20 {
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        let mut p = Point3::ORIGIN;
        for _ in 0..8 {
            p = p + Vec3::new(
                rng.random_range(-30.0..30.0),
                rng.random_range(-30.0..30.0),
                rng.random_range(-2.0..2.0),
            );
            tp.push(Move::line(p, rng.random_range(20.0..200.0)));
        }
        let ours = plan_toolpath(&tp, &mach).expect("plan").total_time();
        let reference = topp_time(&tp, &mach, 2000);
        let rel = (ours - reference) / reference;
        assert!(
            rel.abs() < 0.01,
            "case {case}: ours {ours} topp {reference}"
        );
    }
}

#[test]
fn racetrack_with_tangent_arcs_within_one_percent_of_topp() {
    let mach = trapezoidal_machine();
    for (len, r, feed) in [(80.0, 20.0, 60.0), (40.0, 40.0, 100.0), (150.0, 10.0, 40.0)] {
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp.push(Move::line(Point3::new(len, 0.0, 0.0), feed));
        tp.push(Move::arc_xy(
            Point3::new(len, 2.0 * r, 0.0),
            Point3::new(len, r, 0.0),
            true,
            feed,
        ));
        tp.push(Move::line(Point3::new(0.0, 2.0 * r, 0.0), feed));
        tp.push(Move::arc_xy(
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(0.0, r, 0.0),
            true,
            feed,
        ));
        tp.push(Move::line(Point3::new(len, 0.0, 0.0), feed));
        let ours = plan_toolpath(&tp, &mach).expect("plan").total_time();
        let reference = topp_time(&tp, &mach, 4000);
        let rel = (ours - reference) / reference;
        assert!(
            rel.abs() < 0.01,
            "len {len} r {r}: ours {ours} topp {reference}"
        );
    }
}
