//! Five-axis plots, in the style of the five-axis paper's Figures 6-7 (feed and axes) and 9-10
//! (deflection).
//!
//! * [`deflection_path`] (Figure 9): the tool tip near the deflected point, drawn in the plane
//!   that holds the reference curve's tangent at the projection and the offset of the
//!   deflection from it — the plane in which the replanned path leaves the deflection and
//!   rejoins the curve. Horizontal: distance along the tangent from the projection (mm);
//!   vertical: distance towards the deflection (mm). Shown: the reference curve, the original
//!   plan's tip path, the replanned tip path, and the deflection, projection and next knot.
//! * [`deflection_profiles`] (Figure 10): every axis through the two new intervals against the
//!   time since the deflection: positions relative to the deflection's (mm, and mrad for the
//!   rotary axes), then velocity, acceleration and jerk as a share of each axis's limit, with
//!   the ±limit lines (a share keeps mm and rad axes on one chart).
//!
//! * [`axis_charts`] (Figures 6-7): the tool tip's feed against its limit, then each motor's
//!   velocity, acceleration and jerk as a share of its own limit.
//!
//! The builders take the library's plain results and return [`Chart`]s; render them with
//! [`super::plots::render_svg`].

use super::plots::{AxisSeries, Chart, HLine, Quantity, Series, SeriesStyle, axis_kinematics};
use crate::geom::{Point3, Vec3};
use crate::machine::kinematics::Kinematics;
use crate::motion::five_axis::{Limits, RefCurve, Replan, Samples, Segment, sample};

/// The local frame of [`deflection_path`]: origin, tangent, normal.
fn frame(curve: &RefCurve, r: &Replan) -> (Point3, Vec3, Vec3) {
    let p = r.projection.point;
    let d1 = curve.eval(r.projection.interval, r.projection.u)[1];
    let t = Vec3::new(d1[0], d1[1], d1[2])
        .normalize()
        .unwrap_or(Vec3::new(1.0, 0.0, 0.0));
    let off = r.deflection - p;
    let n = (off - t * off.dot(t))
        .normalize()
        .or_else(|| t.cross(Vec3::new(0.0, 0.0, 1.0)).normalize())
        .unwrap_or(Vec3::new(0.0, 1.0, 0.0));
    (p, t, n)
}

fn tip_path(segs: &[Segment], kin: &dyn Kinematics, per: usize) -> Vec<Point3> {
    let mut out = Vec::new();
    for s in segs {
        for k in 0..=per {
            let q = s.eval(s.duration * k as f64 / per as f64)[0];
            out.push(kin.forward(&q).tip);
        }
    }
    out
}

/// The replanned path near the deflected point (Figure 9 style); `plan` is the original plan's
/// intervals, `curve` the reference curve. See the module docs.
pub fn deflection_path(
    kin: &dyn Kinematics,
    curve: &RefCurve,
    plan: &[Segment],
    r: &Replan,
) -> Chart {
    let (o, t, n) = frame(curve, r);
    let local = |p: Point3| {
        let v = p - o;
        (v.dot(t), v.dot(n))
    };
    let i = r.projection.interval;
    let mut reference = Vec::new();
    for piece in i.saturating_sub(1)..(i + 2).min(curve.len()) {
        for k in 0..=40 {
            let e = curve.eval(piece, f64::from(k) / 40.0)[0];
            reference.push(local(Point3::new(e[0], e[1], e[2])));
        }
    }
    let original: Vec<(f64, f64)> = plan
        .get(i..(i + 2).min(plan.len()))
        .map(|s| tip_path(s, kin, 60).into_iter().map(local).collect())
        .unwrap_or_default();
    let replanned: Vec<(f64, f64)> = tip_path(&r.segments(), kin, 120)
        .into_iter()
        .map(local)
        .collect();
    let knot = kin.forward(&r.states[2].q).tip;
    let marks = [
        ("deflection", r.deflection, 5),
        ("projection", r.projection.point, 2),
        ("next knot", knot, 6),
    ];
    let mut series = vec![
        Series {
            label: "reference curve".into(),
            points: reference,
            style: SeriesStyle::Line,
            colour: 0,
        },
        Series {
            label: "original plan".into(),
            points: original,
            style: SeriesStyle::Dashed,
            colour: 4,
        },
        Series {
            label: "replanned tip path".into(),
            points: replanned,
            style: SeriesStyle::Line,
            colour: 1,
        },
    ];
    for (label, p, colour) in marks {
        series.push(Series {
            label: label.into(),
            points: vec![local(p)],
            style: SeriesStyle::Points,
            colour,
        });
    }
    Chart {
        title: format!(
            "Replanned path near the deflection ({:.2} mm off the curve)",
            r.projection.distance
        ),
        x_label: "along the path's tangent at the projection (mm)".into(),
        y_label: "towards the deflection (mm)".into(),
        series,
        hlines: vec![],
        y_range: None,
    }
}

/// The axis profiles through the two new intervals (Figure 10 style): positions, then
/// velocity, acceleration and jerk as shares of the limits. Returns
/// `(file stem, caption, chart)`.
pub fn deflection_profiles(
    kin: &dyn Kinematics,
    r: &Replan,
    lim: &Limits,
) -> Vec<(&'static str, String, Chart)> {
    let segs = r.segments();
    let total = r.times_s[0] + r.times_s[1];
    let s = sample(&segs, kin, (total / 400.0).max(1e-6));
    let names = kin.axis_names();
    let q0 = s.q.first().copied().unwrap_or([0.0; 5]);
    let scale = |k: usize| if k < 3 { 1.0 } else { 1000.0 };
    let mut series: Vec<Series> = (0..5)
        .map(|k| Series {
            label: if k < 3 {
                format!("{} (mm)", names[k])
            } else {
                format!("{} (mrad)", names[k])
            },
            points: s
                .t
                .iter()
                .zip(&s.q)
                .map(|(&t, q)| (t, (q[k] - q0[k]) * scale(k)))
                .collect(),
            style: SeriesStyle::Line,
            colour: k,
        })
        .collect();
    // Every axis at the projection (the end of the first new interval).
    let tp = r.times_s[0];
    let qp = segs[0].eval(tp)[0];
    series.push(Series {
        label: format!("at the projection, t = {tp:.4} s"),
        points: (0..5).map(|k| (tp, (qp[k] - q0[k]) * scale(k))).collect(),
        style: SeriesStyle::Points,
        colour: 6,
    });
    let positions = Chart {
        title: "Axis positions through the two new intervals".into(),
        x_label: "time since the deflection (s)".into(),
        y_label: "change of position (mm; mrad for rotary axes)".into(),
        series,
        hlines: vec![],
        y_range: None,
    };
    let mut out = vec![(
        "five_axis_deflection_positions",
        "Five-axis deflection: every axis's position through the two new intervals (deflection → projection → next knot; cf. the five-axis paper's Figure 10)".to_owned(),
        positions,
    )];
    for (quantity, values, l, stem) in [
        (
            Quantity::Velocity,
            &s.v,
            lim.vel,
            "five_axis_deflection_velocity",
        ),
        (
            Quantity::Acceleration,
            &s.a,
            lim.acc,
            "five_axis_deflection_acceleration",
        ),
        (Quantity::Jerk, &s.j, lim.jerk, "five_axis_deflection_jerk"),
    ] {
        let axes: Vec<AxisSeries> = (0..5)
            .map(|k| AxisSeries {
                name: format!("{} / {}", names[k], l[k]),
                unit: "limit".into(),
                values: values.iter().map(|q| q[k] / l[k]).collect(),
                limit: Some(1.0),
            })
            .collect();
        let mut chart = axis_kinematics(quantity, &s.t, &axes);
        chart.title = format!(
            "{} per axis through the two new intervals",
            quantity.title()
        );
        chart.x_label = "time since the deflection (s)".into();
        out.push((
            stem,
            format!(
                "Five-axis deflection: per-axis {} through the two new intervals, as a share of each axis's limit (cf. the five-axis paper's Figure 10)",
                quantity.name()
            ),
            chart,
        ));
    }
    out
}

/// Every deflection chart: the path (Figure 9) then the profiles (Figure 10).
pub fn deflection_charts(
    kin: &dyn Kinematics,
    curve: &RefCurve,
    plan: &[Segment],
    r: &Replan,
    lim: &Limits,
) -> Vec<(&'static str, String, Chart)> {
    let mut out = vec![(
        "five_axis_deflection_path",
        "Five-axis deflection: the replanned tool-tip path near the deflected point, in the plane of the curve's tangent and the deflection (cf. the five-axis paper's Figure 9)".to_owned(),
        deflection_path(kin, curve, plan, r),
    )];
    out.extend(deflection_profiles(kin, r, lim));
    out
}

/// The five-axis plots (the paper's Figures 6-7 style): the tool tip's feed against its limit,
/// then each motor's velocity, acceleration and jerk as a share of its own limit (linear axes
/// in mm and rotary axes in rad differ by three orders of magnitude). Returns
/// `(file stem, caption, chart)`.
pub fn axis_charts(
    samples: &Samples,
    names: [&str; 5],
    limits: &Limits,
) -> Vec<(&'static str, String, Chart)> {
    let mut out = vec![(
        "five_axis_feed",
        "Five-axis: feed rate of the tool tip against time with its limit (cf. the five-axis paper's Figure 6)"
            .to_owned(),
        Chart {
            title: "Feed rate of the tool tip".to_owned(),
            x_label: "time (s)".to_owned(),
            y_label: "feed (mm/s)".to_owned(),
            series: vec![Series {
                label: "feed".to_owned(),
                points: samples.t.iter().copied().zip(samples.feed.iter().copied()).collect(),
                style: SeriesStyle::Line,
                colour: 0,
            }],
            hlines: vec![HLine {
                label: format!("feed limit {} mm/s", limits.feed),
                y: limits.feed,
            }],
            // Room above the limit line for the legend.
            y_range: (limits.feed.is_finite() && limits.feed > 0.0)
                .then_some((0.0, 1.3 * limits.feed)),
        },
    )];
    for (quantity, values, lim, file) in [
        (
            Quantity::Velocity,
            &samples.v,
            limits.vel,
            "five_axis_velocity",
        ),
        (
            Quantity::Acceleration,
            &samples.a,
            limits.acc,
            "five_axis_acceleration",
        ),
        (Quantity::Jerk, &samples.j, limits.jerk, "five_axis_jerk"),
    ] {
        // Linear axes first (mm), then the rotary ones (rad).
        let unit = |k: usize| if k < 3 { "mm" } else { "rad" };
        let per = match quantity {
            Quantity::Velocity => "/s",
            Quantity::Acceleration => "/s²",
            Quantity::Jerk => "/s³",
        };
        let axes: Vec<AxisSeries> = (0..5)
            .map(|k| AxisSeries {
                name: format!("{} (limit {} {}{per})", names[k], lim[k], unit(k)),
                unit: "limit".to_owned(),
                values: values.iter().map(|q| q[k] / lim[k]).collect(),
                limit: Some(1.0),
            })
            .collect();
        let peak = axes
            .iter()
            .flat_map(|a| a.values.iter())
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut chart = axis_kinematics(quantity, &samples.t, &axes);
        // The title names the quantity; a rotated label starting with "J" loses its top in
        // plotters' bitmap text.
        chart.y_label = "share of the axis limit".to_owned();
        if peak < 0.5 {
            // Head room above the curves for the legend (five rows, the upper third).
            let (lo, hi) = axes
                .iter()
                .flat_map(|a| a.values.iter().copied())
                .filter(|v| v.is_finite())
                .fold((0.0_f64, 0.0_f64), |(l, h), v| (l.min(v), h.max(v)));
            let span = (hi - lo).max(1e-9);
            chart.y_range = Some((lo - 0.05 * span, hi + 0.6 * span));
            // Far from every limit: the ±1 lines would flatten the curves to nothing.
            chart.hlines.clear();
            chart.title = format!(
                "{} per axis: peak {:.0} % of its limit (limits ±1 off the chart)",
                quantity.title(),
                100.0 * peak
            );
        } else {
            for h in &mut chart.hlines {
                if !h.label.is_empty() {
                    h.label = "axis limits ±1".to_owned();
                }
            }
            chart.title = format!(
                "{} per axis: peak {:.0} % of its limit",
                quantity.title(),
                100.0 * peak
            );
        }
        out.push((
            file,
            format!(
                "Five-axis: per-axis {} against time, as a share of each axis's limit (linear axes in mm, rotary in rad; cf. the five-axis paper's Figure 7)",
                quantity.name()
            ),
            chart,
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::kinematics::PaperAb;
    use crate::motion::five_axis::{FiveAxisOptions, KnotOptions, case, plan};

    /// Two knot iterations, no baseline: enough for the charts' shapes, quick in a test.
    fn quick_options() -> FiveAxisOptions {
        FiveAxisOptions {
            knots: KnotOptions {
                iterations: 2,
                ..KnotOptions::default()
            },
            baseline: None,
            ..FiveAxisOptions::default()
        }
    }

    /// The path chart puts the deflection off the curve at the distance the replanning
    /// reports, the projection at the origin, and the replanned path starts at the
    /// deflection and ends at the next knot.
    #[test]
    fn deflection_charts_show_the_replanning() {
        let kin = PaperAb::paper();
        let opts = quick_options();
        let poses = case::paper_path();
        let out = plan(
            &kin,
            &poses,
            &Limits::paper(),
            &opts,
            Some(case::paper_deflection()),
        )
        .unwrap();
        let r = out.result.deflection.as_ref().unwrap();
        let knots = &out.poses;
        let curve = RefCurve::through(&knots.iter().map(|p| p.tip).collect::<Vec<_>>());
        let charts = deflection_charts(&kin, &curve, &out.segments, r, &Limits::paper());
        assert_eq!(charts.len(), 5);
        let path = &charts[0].2;
        let find = |l: &str| path.series.iter().find(|s| s.label == l).unwrap();
        let (dx, dy) = find("deflection").points[0];
        assert!(
            dx.abs() < 1e-6 && (dy - r.projection.distance).abs() < 1e-9,
            "{dx} {dy}"
        );
        let (px, py) = find("projection").points[0];
        assert!(px.abs() < 1e-12 && py.abs() < 1e-12);
        let re = &find("replanned tip path").points;
        let first = re[0];
        assert!((first.0 - dx).hypot(first.1 - dy) < 1e-6, "{first:?}");
        let knot = find("next knot").points[0];
        let last = re[re.len() - 1];
        assert!((last.0 - knot.0).hypot(last.1 - knot.1) < 1e-6);
        // Profiles stay within ±1 (shares of the limits) and span both intervals.
        for (_, _, c) in &charts[2..] {
            for s in &c.series {
                assert!(
                    s.points.iter().all(|p| p.1.abs() <= 1.0 + 1e-9),
                    "{}",
                    c.title
                );
                let end = s.points.last().unwrap().0;
                assert!((end - r.times_s[0] - r.times_s[1]).abs() < 1e-9);
            }
        }
    }

    /// The axis charts are the samples as shares of the limits: a verified plan stays within
    /// ±1 on every axis, and the feed chart is the samples' feed under its limit line.
    #[test]
    fn axis_charts_are_shares_of_the_limits() {
        let kin = PaperAb::paper();
        let opts = quick_options();
        let lim = Limits::paper();
        let out = plan(&kin, &case::paper_path(), &lim, &opts, None).unwrap();
        assert!(out.result.violations.is_empty());
        let s = sample(&out.segments, &kin, 1e-3);
        let charts = axis_charts(&s, kin.axis_names(), &lim);
        let files: Vec<_> = charts.iter().map(|c| c.0).collect();
        assert_eq!(
            files,
            [
                "five_axis_feed",
                "five_axis_velocity",
                "five_axis_acceleration",
                "five_axis_jerk"
            ]
        );
        let feed = &charts[0].2;
        assert_eq!(feed.series[0].points.len(), s.t.len());
        assert!(
            feed.series[0]
                .points
                .iter()
                .all(|p| p.1 <= lim.feed * (1.0 + 1e-6))
        );
        assert!((feed.hlines[0].y - lim.feed).abs() <= 1e-12 * lim.feed);
        for (_, _, c) in &charts[1..] {
            assert_eq!(c.series.len(), 5);
            for ser in &c.series {
                assert!(
                    ser.points.iter().all(|p| p.1.abs() <= 1.0 + 1e-6),
                    "{}",
                    c.title
                );
            }
        }
        // The velocity shares are the samples divided by the limits.
        let k = s.t.len() / 2;
        let v = &charts[1].2.series[0].points[k];
        assert!((v.1 - s.v[k][0] / lim.vel[0]).abs() < 1e-12);
    }
}
