//! `--html OUT.html` for the commands: one self-contained report per run, built from the
//! engine's report pieces (`millpath::report`).

use millpath::geom::Outline;
use millpath::machine::Machine;
use millpath::motion::Plan;
use millpath::report::html::HtmlReport;
use millpath::report::{plots, series};
use millpath::{Error, Toolpath};
use std::path::Path;

/// A report with a summary table, the toolpath viewer (preview coloured by achieved feed,
/// playback along `plan`) and the feed-along-path plot.
pub fn toolpath_report(
    title: &str,
    summary: Vec<(String, String)>,
    tp: &Toolpath,
    outlines: &[Outline],
    plan: &Plan,
) -> Result<HtmlReport, Error> {
    let mut html = HtmlReport::new(title);
    html.section("summary", summary);
    html.toolpath_viewer(title, tp, outlines, plan)?;
    let samples = plan.sample((plan.total_time / 20_000.0).max(1e-3))?;
    let (achieved, programmed) = series::feed_along_cut(plan, &samples);
    html.plot(
        "Feed along the cutting path (rapids left out): achieved by the planner against programmed",
        &plots::render_svg(
            &plots::feed_along_path(&achieved, Some(&programmed)),
            &plots::PlotOptions::default(),
        )?,
    )?;
    Ok(html)
}

/// The machine's limits as one summary row.
pub fn machine_row(m: &Machine) -> (String, String) {
    let a = &m.axes[0];
    let jerk = if a.max_jerk.is_finite() {
        format!("{:.0}", a.max_jerk)
    } else {
        "unlimited".to_owned()
    };
    (
        "machine".to_owned(),
        format!(
            "{}: X v {:.0} mm/s, a {:.0} mm/s², j {jerk} mm/s³, path tolerance {} mm",
            m.name, a.max_velocity, a.max_acceleration, m.path_tolerance
        ),
    )
}

/// Writes `html` to `path` atomically.
pub fn write(path: &Path, html: &HtmlReport) -> Result<(), Error> {
    millpath::io::write_atomic(path, html.to_html().as_bytes())
}

/// The five-axis plots (the paper's Figures 6-7 style): the tool tip's feed against its limit,
/// then each motor's velocity, acceleration and jerk as a share of its own limit (linear axes
/// in mm and rotary axes in rad differ by three orders of magnitude). Returns
/// `(file stem, caption, chart)`.
pub fn five_axis_charts(
    samples: &millpath::motion::five_axis::Samples,
    names: [&str; 5],
    limits: &millpath::motion::five_axis::Limits,
) -> Vec<(&'static str, String, plots::Chart)> {
    let mut out = vec![(
        "five_axis_feed",
        "Five-axis: feed rate of the tool tip against time with its limit (cf. the five-axis paper's Figure 6)"
            .to_owned(),
        plots::Chart {
            title: "Feed rate of the tool tip".to_owned(),
            x_label: "time (s)".to_owned(),
            y_label: "feed (mm/s)".to_owned(),
            series: vec![plots::Series {
                label: "feed".to_owned(),
                points: samples.t.iter().copied().zip(samples.feed.iter().copied()).collect(),
                style: plots::SeriesStyle::Line,
                colour: 0,
            }],
            hlines: vec![plots::HLine {
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
            plots::Quantity::Velocity,
            &samples.v,
            limits.vel,
            "five_axis_velocity",
        ),
        (
            plots::Quantity::Acceleration,
            &samples.a,
            limits.acc,
            "five_axis_acceleration",
        ),
        (
            plots::Quantity::Jerk,
            &samples.j,
            limits.jerk,
            "five_axis_jerk",
        ),
    ] {
        // Linear axes first (mm), then the rotary ones (rad).
        let unit = |k: usize| if k < 3 { "mm" } else { "rad" };
        let per = match quantity {
            plots::Quantity::Velocity => "/s",
            plots::Quantity::Acceleration => "/s²",
            plots::Quantity::Jerk => "/s³",
        };
        let axes: Vec<plots::AxisSeries> = (0..5)
            .map(|k| plots::AxisSeries {
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
        let mut chart = plots::axis_kinematics(quantity, &samples.t, &axes);
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
