//! Passing beside the pole: the tilting sweep moved off the pole by a small angle (the tool
//! never quite vertical) makes a table-table machine's C turn round near the closest pose.
//! Within a tilt tolerance at least that angle, the planner moves the axes to pass the pole
//! and the sweep runs as close to its length ÷ feed as the sweep through the pole. Checked
//! here without the straightening's own model: every knot's joints through the forward
//! kinematics against the given pose (the axis within the tolerance, the tip in place), the
//! independent limit verifier, and C's travel.

use millpath::geom::{Point3, Vec3};
use millpath::job::five_axis::kinematics;
use millpath::machine::kinematics::Pose;
use millpath::motion::five_axis::{FiveAxisOptions, Limits, LimitsFile, plan, verify};

/// The 200-pose tilting sweep (tip from x = −50 to 50 mm, the tool tilting from −30° to 30°
/// in the vertical plane at `plane` rad to X), each axis turned `miss` rad out of that plane,
/// so that it passes the pole at `miss`.
fn sweep_beside(miss: f64, plane: f64) -> Vec<Pose> {
    let (s, c) = plane.sin_cos();
    (0..200)
        .map(|k| {
            let u = f64::from(k) / 199.0;
            let t = (-30.0 + 60.0 * u).to_radians();
            let along = Vec3::new(c, s, 0.0) * t.sin();
            let across = Vec3::new(-s, c, 0.0) * (miss.sin() * t.cos());
            let up = Vec3::new(0.0, 0.0, t.cos() * miss.cos());
            let axis = (along + across + up).normalize().unwrap();
            Pose {
                tip: Point3::new(-50.0 + 100.0 * u, 0.0, 0.0),
                axis,
            }
        })
        .collect()
}

fn angle(u: Vec3, v: Vec3) -> f64 {
    u.cross(v).length().atan2(u.dot(v))
}

/// C's total travel over the plan's knots, rad.
fn c_travel(states: &[[f64; 5]]) -> f64 {
    states.windows(2).map(|w| (w[1][4] - w[0][4]).abs()).sum()
}

#[test]
fn a_sweep_beside_the_pole_runs_like_one_through_it_within_the_tolerance() {
    let kin = kinematics("xyzac-trt", &LimitsFile::default()).unwrap();
    let lim = Limits::paper();
    let bound = 100.0 / lim.feed;
    let mut checked = 0;
    for (miss_deg, plane_deg, reversed) in
        [(0.5, 45.0, false), (0.2, 45.0, true), (0.8, 20.0, false)]
    {
        let mut poses = sweep_beside(f64::to_radians(miss_deg), f64::to_radians(plane_deg));
        if reversed {
            poses.reverse();
        }
        let tol = 1f64.to_radians();
        let plain = FiveAxisOptions::default().with_baseline(None);
        let before = plan(kin.as_ref(), &poses, &lim, &plain, None).unwrap();
        let out = plan(
            kin.as_ref(),
            &poses,
            &lim,
            &plain.with_tilt_tolerance(tol),
            None,
        )
        .unwrap();
        let r = &out.result;
        let case = format!("miss {miss_deg}°, plane {plane_deg}°, reversed {reversed}");
        // Beside the pole, C turns round: the plain plan is far slower than the sweep.
        assert!(
            before.result.total_time_s > 2.0 * bound,
            "{case}: {}",
            before.result.total_time_s
        );
        assert!(!r.pole_windows.is_empty(), "{case}");
        let ratio = r.total_time_s / bound;
        assert!(ratio > 1.0 && ratio < 1.1, "{case}: {ratio}");
        assert!(
            verify(&out.segments, kin.as_ref(), &lim, 400)
                .violations
                .is_empty()
        );
        assert!(r.max_path_deviation_mm < 0.005, "{case}");
        // Every knot against its given pose, through the forward kinematics.
        for (k, idx) in out.pose_index.iter().enumerate() {
            let Some(i) = *idx else { continue };
            let got = kin.forward(&out.schedule.states[k].q);
            let a = angle(got.axis, poses[i].axis);
            assert!(a <= tol * (1.0 + 1e-9), "{case}: pose {i} moved {a}");
            assert!(got.tip.distance(poses[i].tip) < 1e-6, "{case}: pose {i}");
            checked += 1;
        }
        let q: Vec<[f64; 5]> = out.schedule.states.iter().map(|s| s.q).collect();
        let q0: Vec<[f64; 5]> = before.schedule.states.iter().map(|s| s.q).collect();
        assert!(c_travel(&q) < 0.25 * c_travel(&q0), "{case}");
    }
    assert!(checked > 100, "{checked} knots checked");
}

/// A tolerance smaller than the miss cannot pass the pole: the plan may improve but every
/// axis stays within the tolerance; no tolerance leaves the axes as given.
#[test]
fn the_axes_stay_within_the_tolerance_and_as_given_without_one() {
    let kin = kinematics("xyzac-trt", &LimitsFile::default()).unwrap();
    let lim = Limits::paper();
    let poses = sweep_beside(1f64.to_radians(), 45f64.to_radians());
    let plain = FiveAxisOptions::default().with_baseline(None);
    let none = plan(kin.as_ref(), &poses, &lim, &plain, None).unwrap();
    assert!(none.result.pole_windows.is_empty());
    for (k, idx) in none.pose_index.iter().enumerate() {
        if let Some(i) = *idx {
            let got = kin.forward(&none.schedule.states[k].q);
            assert!(angle(got.axis, poses[i].axis) < 1e-9);
        }
    }
    let tol = 0.5f64.to_radians();
    let out = plan(
        kin.as_ref(),
        &poses,
        &lim,
        &plain.with_tilt_tolerance(tol),
        None,
    )
    .unwrap();
    assert!(out.result.total_time_s <= none.result.total_time_s * 1.001);
    for (k, idx) in out.pose_index.iter().enumerate() {
        if let Some(i) = *idx {
            let got = kin.forward(&out.schedule.states[k].q);
            assert!(
                angle(got.axis, poses[i].axis) <= tol * (1.0 + 1e-9),
                "pose {i}"
            );
        }
    }
    assert!(
        verify(&out.segments, kin.as_ref(), &lim, 400)
            .violations
            .is_empty()
    );
}
