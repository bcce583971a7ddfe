//! Properties of the profile strategy:
//! - invariance: the same outline rotated about the origin, run the other way, or started at
//!   another vertex gives the same toolpath (every move's end rotated alike, the same kinds)
//!   and the same tabs, on random star-shaped outlines of lines and arcs, cut outside and
//!   inside, [`CASES`] cases, at least [`MIN_ACCEPTED`] of them planned with tabs;
//! - the paper's die cavity: `profile --sample` and `contour --sample` cut the same levels
//!   and their finishing passes lie within the tolerance of each other and within
//!   `[r, r + T]` (give or take the arc fit) of the exact curve.

use millpath::curve::{self, ArcSeg};
use millpath::geom::{Outline, Point};
use millpath::job::ProgramSettings;
use millpath::job::profile::{self as job_profile, ProfileSettings, ProfileSource};
use millpath::strategy::contour;
use millpath::strategy::profile::{
    self, ProfileOptions, ProfileSide, ProfileTarget, TabCount, TabOptions,
};
use millpath::toolpath::{MoveKind, Tool, Toolpath};
use proptest::prelude::*;
use proptest::test_runner::{RngSeed, TestCaseError, TestRunner};

/// Random cases.
const CASES: u32 = 24;
/// Cases that must be planned with at least one tab.
const MIN_ACCEPTED: usize = 16;

/// A star-shaped outline: `n` vertices at increasing angles and random radii about the
/// origin-shifted centre, each segment a line or a shallow arc.
fn star() -> impl Strategy<Value = (Vec<(Point, f64)>, f64, usize, bool)> {
    (5usize..9)
        .prop_flat_map(|n| {
            (
                prop::collection::vec((0.2f64..1.0, 40.0f64..70.0, -0.15f64..0.15), n),
                0.0f64..std::f64::consts::TAU,
                0..n,
                any::<bool>(),
            )
        })
        .prop_map(|(pts, rot, shift, inside)| {
            let n = pts.len();
            let total: f64 = pts.iter().map(|p| p.0).sum();
            let mut a: f64 = 0.0;
            let v = pts
                .iter()
                .map(|&(gap, rad, bulge)| {
                    let p = Point::new(15.0 + rad * a.cos(), -7.0 + rad * a.sin());
                    a += std::f64::consts::TAU * gap / total;
                    (p, if bulge.abs() < 0.05 { 0.0 } else { bulge })
                })
                .collect::<Vec<_>>();
            debug_assert_eq!(v.len(), n);
            (v, rot, shift, inside)
        })
}

fn rotate(p: Point, a: f64) -> Point {
    Point::new(p.x * a.cos() - p.y * a.sin(), p.x * a.sin() + p.y * a.cos())
}

fn plan(v: &[(Point, f64)], side: ProfileSide) -> Option<profile::ProfileResult> {
    let o = Outline::new(v, "star").ok()?;
    let tool = Tool::flat(6.0).unwrap();
    let opts = ProfileOptions::default()
        .with_depth(4.0)
        .with_step_down(2.0)
        .with_tabs(
            TabOptions::default()
                .with_count(TabCount::Count(3))
                .with_width(5.0),
        );
    profile::generate(&[ProfileTarget { outline: o, side }], &tool, &opts).ok()
}

/// `b` is `a` with every point rotated by `rot`: the same moves, the same tabs.
fn same(
    a: &profile::ProfileResult,
    b: &profile::ProfileResult,
    rot: f64,
    what: &str,
) -> Result<(), TestCaseError> {
    let (ta, tb): (&Toolpath, &Toolpath) = (&a.toolpath, &b.toolpath);
    prop_assert_eq!(ta.moves.len(), tb.moves.len(), "{}: move counts", what);
    for (k, (ma, mb)) in ta.moves.iter().zip(&tb.moves).enumerate() {
        let pa = rotate(ma.to.xy(), rot);
        prop_assert!(
            pa.distance(mb.to.xy()) < 1e-6 && (ma.to.z - mb.to.z).abs() < 1e-9,
            "{}: move {} ends at {:?}, rotated {:?}, vs {:?}",
            what,
            k,
            ma.to,
            pa,
            mb.to
        );
        let kind = |m: &millpath::toolpath::Move| match m.kind {
            MoveKind::Arc { ccw, .. } => (1, ccw),
            MoveKind::Line => (2, false),
            MoveKind::Rapid => (3, false),
            MoveKind::Dwell { .. } => (4, false),
        };
        prop_assert_eq!(kind(ma), kind(mb), "{}: move {} kind", what, k);
    }
    prop_assert_eq!(a.tabs.len(), b.tabs.len(), "{}: tab counts", what);
    for t in &a.tabs {
        let p = rotate(t.at, rot);
        prop_assert!(
            b.tabs.iter().any(|u| u.at.distance(p) < 1e-6),
            "{}: tab at {:?} (rotated {:?}) missing from {:?}",
            what,
            t.at,
            p,
            b.tabs.iter().map(|u| u.at).collect::<Vec<_>>()
        );
    }
    Ok(())
}

#[test]
fn profile_and_tabs_are_invariant_under_rotation_reversal_and_start_shift() {
    let config = ProptestConfig {
        cases: CASES,
        rng_seed: RngSeed::Fixed(37),
        failure_persistence: None,
        ..ProptestConfig::default()
    };
    let accepted = std::sync::atomic::AtomicUsize::new(0);
    let mut runner = TestRunner::new(config);
    let result = runner.run(&star(), |(v, rot, shift, inside)| {
        let side = if inside {
            ProfileSide::Inside
        } else {
            ProfileSide::Outside
        };
        let Some(base) = plan(&v, side) else {
            return Ok(());
        };
        if base.tabs.is_empty() {
            return Ok(());
        }
        let n = v.len();
        let rotated: Vec<(Point, f64)> = v.iter().map(|&(p, b)| (rotate(p, rot), b)).collect();
        let reversed: Vec<(Point, f64)> = (0..n)
            .map(|k| (v[n - 1 - k].0, -v[(2 * n - 2 - k) % n].1))
            .collect();
        let mut shifted = v.clone();
        shifted.rotate_left(shift);
        for (what, w, a) in [
            ("rotated", rotated, rot),
            ("reversed", reversed, 0.0),
            ("start shifted", shifted, 0.0),
        ] {
            let Some(other) = plan(&w, side) else {
                return Err(TestCaseError::fail(format!("{what}: not planned")));
            };
            same(&base, &other, a, what)?;
        }
        accepted.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    let accepted = accepted.into_inner();
    assert!(
        accepted >= MIN_ACCEPTED,
        "only {accepted} of {CASES} cases planned with tabs"
    );
}

/// The finishing pass's feed moves of a toolpath as line and arc pieces (leads excluded:
/// the level's first and last feed moves).
fn finishing(tp: &Toolpath) -> Vec<ArcSeg> {
    let lv = tp.levels.last().expect("levels");
    let mut out = Vec::new();
    let feeds: Vec<usize> = (lv.start..lv.end)
        .filter(|&k| {
            let from = if k == 0 { tp.start } else { tp.moves[k - 1].to };
            tp.moves[k].is_feed()
                && (tp.moves[k].to.z - lv.z).abs() < 1e-9
                && (from.z - lv.z).abs() < 1e-9
        })
        .collect();
    for &k in &feeds[1..feeds.len() - 1] {
        let from = tp.moves[k - 1].to.xy();
        let m = &tp.moves[k];
        out.push(match m.kind {
            MoveKind::Arc { center, ccw, .. } => ArcSeg {
                start: from,
                end: m.to.xy(),
                center: Some(center.xy()),
                ccw,
                s_end: 0.0,
            },
            _ => ArcSeg {
                start: from,
                end: m.to.xy(),
                center: None,
                ccw: true,
                s_end: 0.0,
            },
        });
    }
    out
}

#[test]
fn die_cavity_profile_matches_contour_sample() {
    let (c, copt) = contour::sample().unwrap();
    let cont = contour::contour(&c, &copt).unwrap();
    let prof = job_profile::run(
        ProfileSource::Sample,
        &ProfileSettings::default(),
        &ProgramSettings::default(),
    )
    .unwrap();
    let tp = &prof.result.toolpath;
    let zs = |t: &Toolpath| t.levels.iter().map(|l| (l.z, l.kind)).collect::<Vec<_>>();
    assert_eq!(zs(&cont.toolpath), zs(tp));
    let (r, t) = (copt.tool.radius(), copt.tolerance);
    let fit = job_profile::SAMPLE_FIT_SHARE * t;
    let a = finishing(&cont.toolpath);
    let b = finishing(tp);
    assert!(a.len() > 1000 && b.len() > 100, "{} {}", a.len(), b.len());
    // Both within [r, r + T] of the exact curve (the profile's give or take its arc fit),
    // sampled every 0.5 mm.
    let band = |segs: &[ArcSeg], slack: f64| {
        for s in segs {
            let n = (s.length() / 0.5).ceil().max(1.0) as usize;
            for j in 0..=n {
                let q = s.at(j as f64 / n as f64);
                let d = curve::distance_to_curve(&c, q);
                assert!(
                    d >= r - slack - 1e-9 && d <= r + t + slack + 1e-9,
                    "{q:?}: {d} mm from the curve"
                );
            }
        }
    };
    band(&a, 0.0);
    band(&b, fit);
    // Each within T (+ the fit) of the other: every vertex of one to the other's pieces.
    let near = |p: Point, segs: &[ArcSeg]| {
        segs.iter()
            .map(|s| s.distance(p))
            .fold(f64::INFINITY, f64::min)
    };
    for s in a.iter().step_by(7) {
        let d = near(s.end, &b);
        assert!(
            d <= t + fit,
            "contour vertex {:?} is {d} mm from the profile",
            s.end
        );
    }
    for s in &b {
        let d = near(s.at(0.5), &a);
        assert!(
            d <= t + fit,
            "profile point {:?} is {d} mm from the contour",
            s.at(0.5)
        );
    }
    let len = |segs: &[ArcSeg]| segs.iter().map(ArcSeg::length).sum::<f64>();
    assert!(
        (len(&a) - len(&b)).abs() < 1e-3 * len(&a),
        "{} vs {}",
        len(&a),
        len(&b)
    );
}
