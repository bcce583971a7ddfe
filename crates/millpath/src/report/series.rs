//! Data series for the plots, extracted from planner samples.
//!
//! These are the only report functions that read planner types; the plots themselves take
//! plain slices. The distance travelled is integrated from the sampled path speed by the
//! trapezoidal rule, `s_{k+1} = s_k + (v_k + v_{k+1})/2 · (t_{k+1} − t_k)`; its error per step
//! is bounded by `|v̈| Δt³ / 12`, which at 5 ms sampling is far below a micrometre for any
//! machine's jerk (v̈ = jerk along the path). Because it is integrated and not read from the
//! planner's block lengths, it also cross-checks the plan: the final `s` should equal the
//! toolpath's length.

use super::plots::{AxisSeries, Quantity};
use crate::machine::Machine;
use crate::motion::{Plan, Sample};
use crate::toolpath::MoveKind;

/// `(distance travelled in mm, path speed in mm/s)` along the samples.
pub fn feed_along_path(samples: &[Sample]) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(samples.len());
    let mut s = 0.0;
    let mut prev: Option<&Sample> = None;
    for x in samples {
        if let Some(p) = prev {
            s += 0.5 * (p.feed + x.feed) * (x.t - p.t);
        }
        out.push((s, x.feed));
        prev = Some(x);
    }
    out
}

/// `(distance in mm, feed in mm/s)` points of a feed plot.
pub type FeedPoints = Vec<(f64, f64)>;

/// The feed along the **cutting** path, for the adaptive-spiral paper's Figure 15: returns
/// `(achieved, programmed)`, both as `(cutting distance in mm, feed in mm/s)`. Samples in
/// rapids and dwells are left out and the distance is integrated (as in [`feed_along_path`])
/// over cutting samples only, so rapids neither stretch the x axis nor spike the feed. Where
/// two consecutive samples are separated by a rapid, the trapezoid between them is skipped.
/// `programmed` is the feed the block asked for (after the strategy's feed modulation).
pub fn feed_along_cut(plan: &Plan, samples: &[Sample]) -> (FeedPoints, FeedPoints) {
    let mut achieved = Vec::with_capacity(samples.len());
    let mut programmed = Vec::with_capacity(samples.len());
    let mut s = 0.0;
    let mut prev: Option<&Sample> = None;
    for x in samples {
        let Some(b) = plan.blocks.get(x.block) else {
            continue;
        };
        if !matches!(b.kind, MoveKind::Line | MoveKind::Arc { .. }) {
            prev = None;
            continue;
        }
        if let Some(p) = prev {
            s += 0.5 * (p.feed + x.feed) * (x.t - p.t);
        }
        achieved.push((s, x.feed));
        programmed.push((s, b.programmed_feed));
        prev = Some(x);
    }
    (achieved, programmed)
}

/// The feed-along-the-cut chart of a whole plan (achieved against programmed, rapids left
/// out): the plan sampled 20,000 times (at most every millisecond), [`feed_along_cut`],
/// drawn by [`super::plots::feed_along_path`].
pub fn feed_chart(plan: &Plan) -> Result<super::plots::Chart, crate::Error> {
    let samples = plan.sample((plan.total_time / 20_000.0).max(1e-3))?;
    let (achieved, programmed) = feed_along_cut(plan, &samples);
    Ok(super::plots::feed_along_path(&achieved, Some(&programmed)))
}

/// Time stamps and the X, Y, Z series of `quantity`, with the machine's axis limits.
pub fn axis_series(
    samples: &[Sample],
    quantity: Quantity,
    machine: &Machine,
) -> (Vec<f64>, Vec<AxisSeries>) {
    let t = samples.iter().map(|s| s.t).collect();
    let axes = ["X", "Y", "Z"]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let limit = machine.axes.get(k).map(|a| match quantity {
                Quantity::Velocity => a.max_velocity,
                Quantity::Acceleration => a.max_acceleration,
                Quantity::Jerk => a.max_jerk,
            });
            AxisSeries {
                name: (*name).into(),
                unit: "mm".into(),
                values: samples
                    .iter()
                    .map(|s| {
                        let v = match quantity {
                            Quantity::Velocity => s.vel,
                            Quantity::Acceleration => s.acc,
                            Quantity::Jerk => s.jerk,
                        };
                        v.get(k).copied().unwrap_or(f64::NAN)
                    })
                    .collect(),
                limit: limit.filter(|l| l.is_finite()),
            }
        })
        .collect();
    (t, axes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::motion::plan_toolpath;
    use crate::toolpath::{Move, Tool, Toolpath};

    #[test]
    fn integrated_distance_matches_path_length() {
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp.push(Move::line(Point3::new(30.0, 0.0, 0.0), 50.0));
        tp.push(Move::line(Point3::new(30.0, 20.0, 0.0), 50.0));
        let m = Machine::preset("hsm").unwrap();
        let plan = plan_toolpath(&tp, &m).unwrap();
        let f = feed_along_path(&plan.sample(0.002).unwrap());
        let s_end = f.last().unwrap().0;
        assert!(
            (s_end - 50.0).abs() < 0.01,
            "integrated {s_end} mm, path 50 mm"
        );
        // Cutting only: a rapid approach adds nothing to the cutting distance.
        let mut tp2 = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp2.push(Move::rapid(Point3::new(0.0, 0.0, 10.0)));
        tp2.push(Move::line(Point3::new(40.0, 0.0, 10.0), 40.0));
        let plan2 = plan_toolpath(&tp2, &m).unwrap();
        let (ach, prog) = feed_along_cut(&plan2, &plan2.sample(0.002).unwrap());
        let cut = ach.last().unwrap().0;
        assert!(
            (cut - 40.0).abs() < 0.05,
            "cutting distance {cut} mm, line 40 mm"
        );
        assert!(prog.iter().all(|p| (p.1 - 40.0).abs() < 1e-12));
        assert!(
            ach.iter().all(|p| p.1 <= 40.0 + 1e-6),
            "a rapid sample leaked in"
        );
        let (t, axes) = axis_series(&plan.sample(0.01).unwrap(), Quantity::Jerk, &m);
        assert_eq!(axes.len(), 3);
        assert!(axes.iter().all(|a| a.values.len() == t.len()));
    }

    #[test]
    fn feed_chart_spans_the_cut() {
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp.push(Move::rapid(Point3::new(0.0, 0.0, 10.0)));
        tp.push(Move::line(Point3::new(40.0, 0.0, 10.0), 40.0));
        tp.push(Move::line(Point3::new(40.0, 30.0, 10.0), 20.0));
        let m = Machine::preset("hsm").unwrap();
        let chart = feed_chart(&plan_toolpath(&tp, &m).unwrap()).unwrap();
        assert_eq!(chart.series.len(), 2);
        for s in &chart.series {
            let end = s.points.last().unwrap().0;
            assert!((end - 70.0).abs() < 0.1, "{}: ends at {end} mm", s.label);
        }
    }
}
