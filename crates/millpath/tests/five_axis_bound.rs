//! How close the planner comes to the physical bound, judged by the independent verifier
//! (dense sampling plus analytic extrema, no joint over its limits): the paper's case against
//! its length ÷ feed plus a jerk-limited start and stop, and the 200-pose tilting sweep
//! through the pole against its length ÷ feed. (Planning speed is a criterion benchmark,
//! `--bench five_axis`, not a test.)

use millpath::job::five_axis::{FiveAxisSettings, run};
use millpath::machine::kinematics::PaperAb;
use millpath::motion::five_axis::{self, FiveAxisOptions, Limits, plan, verify};

/// The paper's quarter circle (radius 100 mm) at 30 mm/s, plus `√(F/J)` at each end for the
/// linear axes' jerk-limited start and stop (200 000 mm/s³): 5.2605 s.
fn paper_bound() -> f64 {
    50.0 * std::f64::consts::PI / 30.0 + 2.0 * (30.0f64 / 200_000.0).sqrt()
}

#[test]
fn paper_case_within_its_bound_and_every_limit() {
    let kin = PaperAb::paper();
    let lim = Limits::paper();
    let poses = five_axis::paper_path();
    let bound = paper_bound();
    assert!((bound - 5.2605).abs() < 1e-4, "{bound}");
    // `None`: the planner's choice (three knots along each end's ramp here).
    for (end_knots, ratio) in [(None, 1.02), (Some(0), 1.029), (Some(4), 1.025)] {
        let opts = FiveAxisOptions::default()
            .with_baseline(None)
            .with_end_knots(end_knots);
        let out = plan(&kin, &poses, &lim, &opts, None).unwrap();
        let r = &out.result;
        assert!(r.violations.is_empty(), "{:?}", r.violations);
        let rep = verify(&out.segments, &kin, &lim, 2000);
        assert!(rep.violations.is_empty(), "{:?}", rep.violations);
        assert!(rep.continuity_error < 1e-9, "{}", rep.continuity_error);
        assert!(
            r.total_time_s <= ratio * bound,
            "end knots {end_knots:?}: {} s = {:.5} × the bound",
            r.total_time_s,
            r.total_time_s / bound
        );
        assert!(r.total_time_s > bound - 0.0245, "{}", r.total_time_s);
        assert_eq!(r.added_poses, out.poses.len() - poses.len());
        assert_eq!(r.intervals, 31 + r.added_poses);
        if end_knots.is_none() {
            assert!(r.added_poses > 0);
        }
        assert!(
            r.max_minimality_gap <= 1.0001e-8,
            "{}",
            r.max_minimality_gap
        );
        assert!(
            r.max_path_deviation_mm < 0.05,
            "{}",
            r.max_path_deviation_mm
        );
    }
}

#[test]
fn tilting_sweep_runs_close_to_length_over_feed() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/five_axis");
    let job = run(&FiveAxisSettings {
        path: Some(dir.join("sweep.csv")),
        machine: "xyzac-trt".into(),
        no_baseline: true,
        ..FiveAxisSettings::default()
    })
    .unwrap();
    let o = &job.outcome;
    // Every given pose is a knot or merged into an interval.
    let knots = o.pose_index.iter().flatten().count();
    assert_eq!(knots + o.result.merged_poses, 200);
    // The sweep passes the pole (the tool along C): the warnings say where.
    assert!(!o.result.ik_warnings.is_empty());
    assert!(o.result.violations.is_empty(), "{:?}", o.result.violations);
    let rep = verify(&o.segments, job.kinematics.as_ref(), &job.limits, 1000);
    assert!(rep.violations.is_empty(), "{:?}", rep.violations);
    let length: f64 = o
        .poses
        .windows(2)
        .map(|w| w[0].tip.distance(w[1].tip))
        .sum();
    let ratio = o.result.total_time_s / (length / job.limits.feed);
    assert!(ratio <= 1.05, "{ratio}");
    assert!(ratio > 1.0, "{ratio}");
    // The planned tip path stays on the given path, the ends included.
    assert!(
        o.result.max_path_deviation_mm < 0.005,
        "{}",
        o.result.max_path_deviation_mm
    );
}
