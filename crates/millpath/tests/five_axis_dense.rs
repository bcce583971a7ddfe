//! Dense poses, as CAM systems write them (0.1 mm and 0.01 mm apart, six decimals): the same
//! tilting sweep through the pole planned from 100 to 10,000 poses must run as close to its
//! length ÷ feed as the 200-pose one, with no joint over its limits (the independent
//! verifier), on the given path (the planned tip path against the curve through every given
//! pose, and every merged pose against the planned path).

use millpath::job::five_axis::kinematics;
use millpath::machine::kinematics::{Kinematics, Pose};
use millpath::motion::five_axis::{
    FiveAxisOptions, Limits, LimitsFile, plan, tilting_sweep, verify,
};

/// `tilting_sweep(n)`, forwards or backwards.
fn sweep(n: usize, reversed: bool) -> Vec<Pose> {
    let mut v = tilting_sweep(n);
    if reversed {
        v.reverse();
    }
    v
}

/// The CLI's `--machine xyzac-trt` with the paper's limits (a path file's default).
fn machine() -> (Box<dyn Kinematics>, Limits) {
    (
        kinematics("xyzac-trt", &LimitsFile::default()).unwrap(),
        Limits::paper(),
    )
}

#[test]
fn dense_sweeps_run_close_to_length_over_feed_on_the_given_path() {
    let (kin, lim) = machine();
    let opts = FiveAxisOptions::default().with_baseline(None);
    let merge = opts.merge;
    let bound = 100.0 / lim.feed;
    let mut accepted = 0;
    for (n, reversed) in [(100, false), (100, true), (1000, false), (10_000, false)] {
        {
            let poses = sweep(n, reversed);
            let out = plan(kin.as_ref(), &poses, &lim, &opts, None).unwrap();
            let r = &out.result;
            let rep = verify(&out.segments, kin.as_ref(), &lim, 400);
            assert!(rep.violations.is_empty(), "{n}: {:?}", rep.violations);
            let ratio = r.total_time_s / bound;
            assert!(ratio > 1.0 && ratio < 1.05, "{n} poses: {ratio}");
            assert!(
                r.max_path_deviation_mm < 0.005,
                "{n}: {}",
                r.max_path_deviation_mm
            );
            assert!(
                r.max_merged_tip_deviation_mm <= merge.tip_tolerance_mm,
                "{n}"
            );
            assert!(
                r.max_merged_axis_deviation_rad <= merge.axis_tolerance_rad,
                "{n}"
            );
            let knots = out.pose_index.iter().flatten().count();
            assert_eq!(knots + r.merged_poses, n);
            // Every knot is a given pose, in order, the two ends kept.
            let idx: Vec<usize> = out.pose_index.iter().flatten().copied().collect();
            assert!(idx.windows(2).all(|w| w[0] < w[1]));
            assert_eq!((idx[0], idx[idx.len() - 1]), (0, n - 1));
            // The knots' tips are the given ones.
            for ((p, &i), s) in out.poses.iter().zip(&idx).zip(&out.schedule.states) {
                assert!(p.tip.distance(poses[i].tip) < 1e-9);
                assert!(kin.forward(&s.q).tip.distance(poses[i].tip) < 1e-6);
            }
            accepted += 1;
        }
    }
    assert_eq!(accepted, 4);
}

#[test]
fn merging_nothing_plans_every_pose() {
    let (kin, lim) = machine();
    let poses = sweep(100, false);
    let mut opts = FiveAxisOptions::default().with_baseline(None);
    opts.merge = opts.merge.with_min_interval_s(0.0);
    let out = plan(kin.as_ref(), &poses, &lim, &opts, None).unwrap();
    assert_eq!(out.result.merged_poses, 0);
    assert_eq!(out.result.intervals, 99);
    assert!(out.result.violations.is_empty());
}

#[test]
fn the_library_sweep_is_the_file() {
    let text = include_str!("data/five_axis/sweep.csv");
    let file = millpath::motion::five_axis::parse_path_csv(text, "sweep.csv").unwrap();
    let lib = tilting_sweep(200);
    assert_eq!(file.len(), lib.len());
    for (a, b) in file.iter().zip(&lib) {
        assert!(a.tip.distance(b.tip) < 1e-9);
        let (an, bn) = (a.axis.normalize().unwrap(), b.axis.normalize().unwrap());
        assert!((an - bn).length() < 1e-9);
    }
}
