//! Five-axis minimum-time trajectories: quintic intervals, exact per-interval minimum time,
//! knot optimisation, the paper's GA baseline, deflection replanning, and an independent
//! verifier.
//!
//! Method: Wu, Li, Liu, Perez, *Local minimum time trajectory planning for five-axis machining
//! with or without deflection* (2008). Its machine, equations and simulation case are the
//! starting point; its optimiser (a one-generation GA per interval with knot states fixed in
//! advance) is `baseline_ga`, the baseline to beat.
//!
//! # Pipeline
//! 1. Poses (tool tip + axis, workpiece frame, mm) → joints by inverse kinematics, each nearest
//!    its predecessor ([`crate::machine::kinematics::inverse_path`]); warnings kept. With a
//!    tilt tolerance ([`FiveAxisOptions::tilt_tolerance`]), the axes moved by at most it
//!    where the path passes beside the pole, so that C does not turn round there (`pole`:
//!    the straightest C within each pose's tolerance band, checked through the forward
//!    kinematics; [`PoleWindow`] says where).
//! 2. One quintic per joint per interval (`quintic`). **Deviation from the paper:** the
//!    paper interpolates `x_w, y_w, z_w, A, B` and maps to the linear motors through equation
//!    (6); we interpolate the five *motor* positions, so every motor limit is a polynomial
//!    bound checked exactly, and the feed — the tool-tip speed in the workpiece frame — goes
//!    through the forward kinematics. The tip path between knots then departs from the
//!    reference curve by a small chordal error, reported as `max_path_deviation_mm`.
//! 3. Dense poses merged (`merge`, [`FiveAxisOptions::merge`]): an interval shorter than
//!    10 ms at the feed cannot follow the rounding in the poses, so closer poses are planned
//!    through inside one interval, within 0.005 mm and 1e-4 rad of the path; the first and
//!    last intervals are made 1.5 jerk-limited ramps long, so that the start from rest does
//!    not back up. Every merged pose is then measured against the plan and kept as a knot if
//!    it is out of tolerance. Optionally, poses added along the jerk-limited ramps at the two
//!    ends (`ends`, [`FiveAxisOptions::end_knots`]).
//! 4. Knot states derived from the interval times and iterated (`knots`), each interval at
//!    its minimum time ([`min_time`]): motor limits exact (polynomial extrema), the feed
//!    certified by a rigorous upper bound; then every shorter duration proven infeasible
//!    down to a relative 1e-8 (`certify`, [`prove_minimal`]).
//! 5. The paper's baseline on the given poses (`baseline_ga`); its fixed knot states are also
//!    a candidate of ours when no pose was added.
//! 6. Independent verification ([`verify`]) of both.
//! 7. Optionally, replanning around a deflection (`deflection`).
//!
//! Units: mm, s, rad inside; the paper's metres are converted at the edges (`case`).

pub(crate) mod baseline_ga;
pub(crate) mod case;
pub(crate) mod certify;
pub(crate) mod deflection;
pub(crate) mod ends;
pub(crate) mod knots;
pub(crate) mod merge;
pub(crate) mod min_time;
pub(crate) mod pole;
pub(crate) mod quintic;
pub(crate) mod segment;
pub(crate) mod verify;

pub use baseline_ga::{BaselineOptions, fixed_states, run as run_baseline};
pub use case::{
    LengthUnit, LimitsFile, PAPER_INTERVALS, paper_deflection, paper_path, paper_projection,
    parse_path_csv, parse_path_csv_lines, tilting_sweep,
};
pub use certify::{CertifyOptions, FeedBound, FeedVerdict, certify_infeasible, feed_bound};
pub use deflection::{Projection, RefCurve, Replan, potential_field_projection, project, replan};
pub use ends::{AUTO_END_KNOTS, AUTO_END_RATIO, auto_end_knots, refine_ends};
pub use knots::{Geometry, KnotOptions, Schedule, optimize, prove_minimal, solve_fixed};
pub use merge::{MergeOptions, PoseDeviation};
pub use min_time::{
    Binding, Check, FeedCheck, KnotState, Limits, MinTimeOptions, Segment, check, lower_bound,
    max_feed, min_time, min_time_near,
};
pub use pole::{MAX_TILT_TOLERANCE, PoleWindow, WINDOW_TOLERANCES};
pub use verify::{VerifyReport, Violation, verify};

use crate::error::{Error, InputError};
use crate::geom::Point3;
use crate::machine::kinematics::{IkOptions, Joints, Kinematics, Pose, PoseWarning};
use serde::{Deserialize, Serialize};

/// A clock started now: the returned function gives the wall time since, s (the compute-time
/// figures). `wasm32-unknown-unknown` has no clock (`Instant::now` panics there): it reads 0.
#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
fn stopwatch() -> impl Fn() -> f64 {
    let t0 = std::time::Instant::now();
    move || t0.elapsed().as_secs_f64()
}

/// A clock started now: reads 0, as this target has none (see the other target's).
#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
fn stopwatch() -> impl Fn() -> f64 {
    || 0.0
}

/// Options of [`plan`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct FiveAxisOptions {
    /// Our optimiser.
    pub knots: KnotOptions,
    /// The baseline, or `None` to skip it.
    pub baseline: Option<BaselineOptions>,
    /// Inverse-kinematics options.
    pub ik: IkOptions,
    /// Verifier samples per interval. Default 400.
    pub verify_samples: usize,
    /// Poses added along the jerk-limited ramp at each end ([`refine_ends`]), the optimiser
    /// then starting from the ramps' durations ([`KnotOptions::ramp_start`]); `Some(0)` plans
    /// the poses as given. It shortens the ends where the given poses are far apart against
    /// the ramp's length (the paper's case: 5 mm against 0.37 mm); where they are close (the
    /// tilting sweep, whose end intervals [`MergeOptions`] makes 1.5 ramps long) the knot
    /// optimiser does worse with it. Default `None`: [`auto_end_knots`] decides, three knots
    /// where the end intervals are at least four ramps long, else none. Figures in
    /// BENCHMARKS.md.
    pub end_knots: Option<usize>,
    /// Dense poses merged into longer intervals (`merge`): rounding in the poses costs a
    /// jerk of order `δ/T³`, so intervals shorter than about 10 ms cannot run at the feed.
    pub merge: MergeOptions,
    /// How far each tool axis may be moved to pass the pole without the free rotary axis
    /// whipping round, rad (`pole`: the axes within `4·τ` of the pole, C taken as the
    /// straightest within the tolerance). Default 0: the axes as given.
    pub tilt_tolerance: f64,
}

impl Default for FiveAxisOptions {
    fn default() -> Self {
        FiveAxisOptions {
            knots: KnotOptions::default(),
            baseline: Some(BaselineOptions::default()),
            ik: IkOptions::default(),
            verify_samples: 400,
            end_knots: None,
            merge: MergeOptions::default(),
            tilt_tolerance: 0.0,
        }
    }
}

option_builders! {
    FiveAxisOptions;
    /// Sets [`FiveAxisOptions::knots`].
    with_knots => knots: KnotOptions;
    /// Sets [`FiveAxisOptions::baseline`].
    with_baseline => baseline: Option<BaselineOptions>;
    /// Sets [`FiveAxisOptions::ik`].
    with_ik => ik: IkOptions;
    /// Sets [`FiveAxisOptions::verify_samples`].
    with_verify_samples => verify_samples: usize;
    /// Sets [`FiveAxisOptions::end_knots`].
    with_end_knots => end_knots: Option<usize>;
    /// Sets [`FiveAxisOptions::merge`].
    with_merge => merge: MergeOptions;
    /// Sets [`FiveAxisOptions::tilt_tolerance`].
    with_tilt_tolerance => tilt_tolerance: f64;
}

/// The library result (serialised as the CLI's JSON).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FiveAxisResult {
    /// Machine name.
    pub machine: String,
    /// Joint names.
    pub axis_names: Vec<String>,
    /// Number of intervals (between knots: the given poses and those added at the ends).
    pub intervals: usize,
    /// Poses added along the ramps at the two ends ([`FiveAxisOptions::end_knots`]).
    pub added_poses: usize,
    /// Given poses planned through inside an interval rather than as its knots
    /// ([`FiveAxisOptions::merge`]).
    pub merged_poses: usize,
    /// Largest distance of a merged pose's tip from the planned tip path, mm (0 if none).
    pub max_merged_tip_deviation_mm: f64,
    /// Largest angle between a merged pose's axis and the planned axis, rad (0 if none).
    pub max_merged_axis_deviation_rad: f64,
    /// Our total time, s.
    pub total_time_s: f64,
    /// The baseline's total time, s (`None` if skipped or infeasible).
    pub baseline_time_s: Option<f64>,
    /// `baseline_time_s / total_time_s`.
    pub speedup_vs_baseline: Option<f64>,
    /// Our interval times, s.
    pub interval_times_s: Vec<f64>,
    /// The baseline's interval times, s.
    pub baseline_interval_times_s: Option<Vec<f64>>,
    /// Verifier: smallest `1 − value/limit` of our plan.
    pub tightest_margin: f64,
    /// Which constraint.
    pub tightest_constraint: String,
    /// Verifier: smallest margin of the baseline.
    pub baseline_tightest_margin: Option<f64>,
    /// Verifier: limits our plan exceeds (must be empty).
    pub violations: Vec<Violation>,
    /// Verifier: limits the baseline exceeds.
    pub baseline_violations: Vec<Violation>,
    /// Largest feed, mm/s (verifier, dense sampling).
    pub max_feed_mm_s: f64,
    /// Rigorous upper bound of the feed over our plan, mm/s ([`certify::feed_bound`]).
    pub feed_upper_bound_mm_s: f64,
    /// Largest relative gap `1 − proven_below / T` over our intervals: no interval can be
    /// shortened by more than this fraction (each shorter duration is proven infeasible).
    pub max_minimality_gap: f64,
    /// Largest distance between the planned tip path and the reference curve, mm.
    pub max_path_deviation_mm: f64,
    /// Total time after each iteration of our optimiser, s.
    pub optimizer_history_s: Vec<f64>,
    /// Wall time of our optimiser, s (0 on a target without a clock: wasm32-unknown-unknown).
    pub compute_time_s: f64,
    /// Wall time of the baseline, s (0 on a target without a clock).
    pub baseline_compute_time_s: Option<f64>,
    /// Inverse-kinematics warnings, by pose.
    pub ik_warnings: Vec<PoseWarning>,
    /// Where the axes were moved within [`FiveAxisOptions::tilt_tolerance`] to pass the pole.
    pub pole_windows: Vec<PoleWindow>,
    /// The deflection replanning, if asked for.
    pub deflection: Option<Replan>,
    /// Verifier on the replanned intervals.
    pub deflection_violations: Vec<Violation>,
}

/// Everything [`plan`] computes.
#[derive(Debug, Clone)]
pub struct FiveAxisOutcome {
    /// The serialisable summary.
    pub result: FiveAxisResult,
    /// Our intervals.
    pub segments: Vec<Segment>,
    /// Our knot states and times.
    pub schedule: Schedule,
    /// The baseline's intervals.
    pub baseline_segments: Option<Vec<Segment>>,
    /// The poses planned through, one per knot: the given poses and those added at the ends
    /// ([`FiveAxisOptions::end_knots`]).
    pub poses: Vec<Pose>,
    /// For every knot, its index among the given poses (`None` for an added one).
    pub pose_index: Vec<Option<usize>>,
}

fn validate_poses(poses: &[Pose]) -> Result<(), InputError> {
    if poses.len() < 2 {
        return Err(InputError::new("path", format!("{} poses", poses.len()))
            .expected("at least two poses"));
    }
    for (i, p) in poses.iter().enumerate() {
        Pose::new(p.tip, p.axis).map_err(|e| e.at(format!("path point {i}")))?;
    }
    Ok(())
}

/// Plans the minimum-time trajectory through `poses` (and the baseline, and a deflection
/// replanning if `deflection` is given), verified independently.
pub fn plan(
    kin: &dyn Kinematics,
    poses: &[Pose],
    lim: &Limits,
    opts: &FiveAxisOptions,
    deflection: Option<Point3>,
) -> Result<FiveAxisOutcome, Error> {
    lim.validate("limits")?;
    validate_poses(poses)?;
    let poses: Vec<Pose> = poses
        .iter()
        .map(|p| Pose::new(p.tip, p.axis))
        .collect::<Result<_, _>>()?;
    let (poses, joints0, warnings, pole_windows) =
        pole::straighten(kin, &poses, &opts.ik, opts.tilt_tolerance)?;
    let geo0 = Geometry::new(&joints0);
    let mt = &opts.knots.min_time;

    let mut baseline = None;
    let mut candidates = Vec::new();
    if let Some(bo) = &opts.baseline {
        let states = fixed_states(&geo0, kin, lim, bo);
        let elapsed = stopwatch();
        let run = baseline_ga::run(&states, kin, lim, bo, mt);
        let dt = elapsed();
        if let Some((times, _)) = run {
            let segs: Vec<Segment> = states
                .windows(2)
                .zip(&times)
                .map(|(w, &t)| Segment::new(&w[0], &w[1], t))
                .collect();
            baseline = Some((times, segs, dt));
        }
        candidates.push(states);
    }
    let elapsed = stopwatch();
    // Plan through the merged knots; a merged pose the plan misses is kept as a knot and the
    // path planned again (the last round keeps every pose).
    let mo = &opts.merge;
    let mut keep = vec![false; poses.len()];
    let mut round = 0;
    let (poses_k, pose_index, mut schedule, segments, devs) = loop {
        let last = round >= 3;
        if last {
            keep.fill(true);
        }
        let kept = merge::knots(&poses, &joints0, kin, lim, mo, &keep);
        let sub_poses: Vec<Pose> = kept.iter().map(|&i| poses[i]).collect();
        let sub_joints: Vec<Joints> = kept.iter().map(|&i| joints0[i]).collect();
        let per_end = opts
            .end_knots
            .unwrap_or_else(|| auto_end_knots(&sub_joints, kin, lim));
        let (knots_p, joints, idx) = refine_ends(&sub_poses, &sub_joints, kin, lim, per_end);
        let pose_index: Vec<Option<usize>> = idx.iter().map(|o| o.map(|i| kept[i])).collect();
        let geo = Geometry::new(&joints);
        let mut knot_opts = opts.knots;
        knot_opts.ramp_start |= knots_p.len() > sub_joints.len();
        let schedule = optimize(&geo, kin, lim, &knot_opts, &candidates)?;
        let segs: Vec<Segment> = schedule
            .states
            .windows(2)
            .zip(&schedule.times)
            .map(|(w, &t)| Segment::new(&w[0], &w[1], t))
            .collect();
        let scale = mo.tip_tolerance_mm / mo.axis_tolerance_rad.max(1e-12);
        let devs = merge::pose_deviation(&segs, &pose_index, &poses, kin, 64, scale);
        let bad: Vec<usize> = devs
            .iter()
            .filter(|d| d.tip_mm > mo.tip_tolerance_mm || d.axis_rad > mo.axis_tolerance_rad)
            .map(|d| d.pose)
            .collect();
        if bad.is_empty() || last {
            break (knots_p, pose_index, schedule, segs, devs);
        }
        for b in bad {
            keep[b] = true;
        }
        round += 1;
    };
    let given = poses;
    let poses = poses_k;
    let compute = elapsed();
    // The proof sets the checks' bounds only: the segments stay those planned.
    prove_minimal(&mut schedule, kin, lim, mt);
    let rep = verify(&segments, kin, lim, opts.verify_samples);
    let brep = baseline
        .as_ref()
        .map(|(_, s, _)| verify(s, kin, lim, opts.verify_samples));
    let curve = RefCurve::through(&poses.iter().map(|p| p.tip).collect::<Vec<_>>());
    let given_curve = RefCurve::through(&given.iter().map(|p| p.tip).collect::<Vec<_>>());
    let deviation = path_deviation(&segments, &pose_index, kin, &given_curve, 16);

    let (replan, dviol) = match deflection {
        Some(d) => {
            let axes: Vec<_> = poses.iter().map(|p| p.axis).collect();
            let r = replan(
                kin,
                &curve,
                &axes,
                &schedule.states,
                &schedule.times,
                d,
                lim,
                mt,
            )?;
            let v = verify(&r.segments(), kin, lim, opts.verify_samples).violations;
            (Some(r), v)
        }
        None => (None, vec![]),
    };
    let total = schedule.total();
    let btotal = baseline.as_ref().map(|(t, _, _)| t.iter().sum::<f64>());
    let result = FiveAxisResult {
        machine: kin.name().to_owned(),
        axis_names: kin.axis_names().iter().map(|s| (*s).to_owned()).collect(),
        intervals: segments.len(),
        added_poses: pose_index.iter().filter(|i| i.is_none()).count(),
        merged_poses: devs.len(),
        max_merged_tip_deviation_mm: devs.iter().map(|d| d.tip_mm).fold(0.0, f64::max),
        max_merged_axis_deviation_rad: devs.iter().map(|d| d.axis_rad).fold(0.0, f64::max),
        total_time_s: total,
        baseline_time_s: btotal,
        speedup_vs_baseline: btotal.map(|b| b / total),
        interval_times_s: schedule.times.clone(),
        baseline_interval_times_s: baseline.as_ref().map(|(t, _, _)| t.clone()),
        tightest_margin: rep.tightest_margin,
        tightest_constraint: rep.tightest.clone(),
        baseline_tightest_margin: brep.as_ref().map(|r| r.tightest_margin),
        violations: rep.violations.clone(),
        baseline_violations: brep.map(|r| r.violations).unwrap_or_default(),
        max_feed_mm_s: rep.max_feed,
        feed_upper_bound_mm_s: segments
            .iter()
            .map(|s| feed_bound(s, kin, lim.feed, &mt.certify, false).upper)
            .fold(0.0, f64::max),
        max_minimality_gap: schedule
            .checks
            .iter()
            .zip(&schedule.times)
            .map(|(c, t)| 1.0 - c.proven_below / t)
            .fold(0.0, f64::max),
        max_path_deviation_mm: deviation,
        optimizer_history_s: schedule.history.clone(),
        compute_time_s: compute,
        baseline_compute_time_s: baseline.as_ref().map(|b| b.2),
        ik_warnings: warnings
            .iter()
            .map(|(i, w)| PoseWarning {
                pose: *i,
                warning: w.clone(),
            })
            .collect(),
        pole_windows,
        deflection: replan,
        deflection_violations: dviol,
    };
    Ok(FiveAxisOutcome {
        result,
        segments,
        schedule,
        baseline_segments: baseline.map(|b| b.1),
        poses,
        pose_index,
    })
}

/// Largest distance from the planned tip path (`per` samples per interval) to the reference
/// curve through the given poses, on the curve's pieces between the given poses around the
/// interval and their neighbours (`pose_index`: the given pose of each knot, `None` for an
/// added one).
fn path_deviation(
    segments: &[Segment],
    pose_index: &[Option<usize>],
    kin: &dyn Kinematics,
    curve: &RefCurve,
    per: usize,
) -> f64 {
    let mut worst = 0.0f64;
    let last = curve.len();
    for (j, seg) in segments.iter().enumerate() {
        let lo = pose_index[..=j]
            .iter()
            .rev()
            .flatten()
            .next()
            .copied()
            .unwrap_or(0);
        let hi = pose_index[j + 1..]
            .iter()
            .flatten()
            .next()
            .copied()
            .unwrap_or(last);
        let pieces = lo.saturating_sub(1)..(hi + 1).min(last);
        for s in 0..=per {
            let [q, _, _, _] = seg.eval(seg.duration * s as f64 / per as f64);
            let tip = kin.forward(&q).tip;
            if let Some(p) = deflection::project_within(curve, tip, pieces.clone()) {
                worst = worst.max(p.distance);
            }
        }
    }
    worst
}

/// Sampled trajectory data (for CSV output and plots): time and per-joint position, velocity,
/// acceleration, jerk, plus the feed.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Samples {
    /// Time, s.
    pub t: Vec<f64>,
    /// Joint positions.
    pub q: Vec<Joints>,
    /// Joint velocities.
    pub v: Vec<Joints>,
    /// Joint accelerations.
    pub a: Vec<Joints>,
    /// Joint jerks.
    pub j: Vec<Joints>,
    /// Tool-tip speed in the workpiece frame, mm/s.
    pub feed: Vec<f64>,
}

/// Samples consecutive `segments` every `dt` seconds (and at every interval end).
pub fn sample(segments: &[Segment], kin: &dyn Kinematics, dt: f64) -> Samples {
    let mut out = Samples::default();
    let dt = if dt.is_finite() && dt > 0.0 { dt } else { 1e-3 };
    let mut t0 = 0.0;
    for (si, seg) in segments.iter().enumerate() {
        let n = ((seg.duration / dt).ceil() as usize).max(1);
        let start = usize::from(si > 0);
        for s in start..=n {
            let t = seg.duration * s as f64 / n as f64;
            let [q, v, a, j] = seg.eval(t);
            out.t.push(t0 + t);
            out.q.push(q);
            out.v.push(v);
            out.a.push(a);
            out.j.push(j);
            out.feed.push(seg.feed(kin, t));
        }
        t0 += seg.duration;
    }
    out
}

/// Writes samples as CSV: a unit line, then `t,<axes>,v_<axes>,a_<axes>,j_<axes>,feed`.
pub fn write_csv(
    w: &mut dyn std::io::Write,
    s: &Samples,
    axis_names: [&str; 5],
) -> std::io::Result<()> {
    writeln!(
        w,
        "# units: t s; x y z mm; rotary rad; v mm/s or rad/s; a mm/s^2 or rad/s^2; j mm/s^3 or rad/s^3; feed mm/s"
    )?;
    let names: Vec<String> = axis_names.iter().map(|n| n.to_ascii_lowercase()).collect();
    let mut header = vec!["t".to_owned()];
    header.extend(names.iter().cloned());
    for p in ["v", "a", "j"] {
        header.extend(names.iter().map(|n| format!("{p}_{n}")));
    }
    header.push("feed".into());
    writeln!(w, "{}", header.join(","))?;
    for i in 0..s.t.len() {
        let mut row = vec![format!("{:.9}", s.t[i])];
        for arr in [&s.q[i], &s.v[i], &s.a[i], &s.j[i]] {
            row.extend(arr.iter().map(|x| format!("{x:.9}")));
        }
        row.push(format!("{:.9}", s.feed[i]));
        writeln!(w, "{}", row.join(","))?;
    }
    Ok(())
}
