//! Every plot of issue 6 rendered from real data (planner samples, the square/circle table),
//! as SVG and PNG, with checks that the pictures carry their data, limits and labels.
//! Set `MILLPATH_KEEP_PLOTS=DIR` to keep the PNG files for inspection.

use millpath::geom::Point3;
use millpath::machine::Machine;
use millpath::motion::{plan_toolpath, table2};
use millpath::report;
use millpath::report::plots::{self, Chart, PlotOptions, Quantity};
use millpath::toolpath::{Move, Tool, Toolpath};
use std::path::PathBuf;

fn out_dir() -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = std::env::var("MILLPATH_KEEP_PLOTS")
        .map(PathBuf::from)
        .unwrap_or_else(|_| tmp.path().to_path_buf());
    std::fs::create_dir_all(&dir).unwrap();
    (tmp, dir)
}

/// Renders to SVG and PNG; checks the PNG is a picture (not one flat colour).
fn render(chart: &Chart, name: &str, dir: &std::path::Path) -> String {
    let o = PlotOptions::default();
    let svg = plots::render_svg(chart, &o).unwrap();
    assert!(svg.contains(&chart.title), "{name}: title missing");
    assert!(svg.contains(&chart.x_label) && svg.contains(&chart.y_label));
    let png = dir.join(format!("{name}.png"));
    plots::render_png(chart, &o, &png).unwrap();
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (o.width, o.height));
    let px = &buf[..info.buffer_size()];
    let non_white = px
        .chunks(info.color_type.samples())
        .filter(|c| c.iter().take(3).any(|v| *v < 200))
        .count();
    let frac = non_white as f64 / f64::from(info.width * info.height);
    assert!(
        frac > 0.01 && frac < 0.6,
        "{name}: {frac:.3} of pixels drawn"
    );
    svg
}

fn square_job() -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    for (x, y) in [(40.0, 0.0), (40.0, 40.0), (0.0, 40.0), (0.0, 0.0)] {
        tp.push(Move::line(Point3::new(x, y, 0.0), 100.0));
    }
    tp
}

#[test]
fn planner_plots_show_data_within_limits() {
    let (_tmp, dir) = out_dir();
    let m = Machine::preset("hsm").unwrap();
    let plan = plan_toolpath(&square_job(), &m).unwrap();
    let samples = plan.sample(0.002).unwrap();
    let feed = report::feed_points(&samples);
    // The planner slows into each corner: the achieved feed drops well below programmed.
    let fmin_mid = feed
        .iter()
        .filter(|(s, _)| (39.0..41.0).contains(s))
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min);
    assert!(
        fmin_mid < 50.0,
        "no slow-down at the first corner: {fmin_mid}"
    );
    let programmed: Vec<(f64, f64)> = vec![(0.0, 100.0), (160.0, 100.0)];
    render(
        &plots::feed_along_path(&feed, Some(&programmed)),
        "feed_along_path",
        &dir,
    );
    for (q, name) in [
        (Quantity::Velocity, "axis_velocity"),
        (Quantity::Acceleration, "axis_acceleration"),
        (Quantity::Jerk, "axis_jerk"),
    ] {
        let (t, axes) = report::axis_series(&samples, q, &m);
        let chart = plots::axis_kinematics(q, &t, &axes);
        // The chart's range holds every sample and every limit line.
        let (_, _, y0, y1) = chart.ranges();
        for a in &axes {
            let lim = a.limit.unwrap();
            assert!(y0 <= -lim && y1 >= lim, "{name}: limit outside the chart");
            assert!(a.values.iter().all(|v| *v >= y0 && *v <= y1));
        }
        let svg = render(&chart, name, &dir);
        assert!(
            svg.contains("X, Y, Z limit ±"),
            "{name}: limit label missing"
        );
    }
}

#[test]
fn table_and_synthetic_plots_render() {
    let (_tmp, dir) = out_dir();
    let rows = table2::compare(&Machine::preset("hsm").unwrap()).unwrap();
    let chart = plots::square_circle_gain(&rows);
    assert_eq!(chart.series.len(), 6, "3 feeds × (measured, ours)");
    let svg = render(&chart, "square_circle_gain", &dir);
    // 15 measured markers plus 3 legend markers (line legends carry an empty r="0" circle).
    let markers = svg.matches("<circle").count() - svg.matches(r#"r="0""#).count();
    assert_eq!(markers, 15 + 3, "{svg}");
    let curves: Vec<(String, Vec<(f64, f64)>)> = [50.0, 100.0]
        .iter()
        .map(|f| {
            let pts = (1..=9)
                .map(|k| {
                    let c = f64::from(k) * 0.1;
                    (c, 100.0 / f + 3.0 * (c - 0.4).powi(2))
                })
                .collect();
            (format!("{f} mm/s"), pts)
        })
        .collect();
    render(
        &plots::cycle_time_vs_transition(&curves),
        "cycle_time_vs_c",
        &dir,
    );
    let dev: Vec<f64> = (0..40)
        .map(|i| 0.004 * (f64::from(i) * 0.37).sin().abs())
        .collect();
    let svg = render(
        &plots::chordal_deviation(&dev, 0.005),
        "chordal_deviation",
        &dir,
    );
    assert!(svg.contains("tolerance 5 µm"));
}
