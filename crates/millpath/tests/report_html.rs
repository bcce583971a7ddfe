//! The HTML report as a person would use it: self-contained, well formed, and working in a real
//! browser (headless Chromium renders it, the page's self-test drives the time slider, and the
//! screenshot is not blank).

use millpath::geom::{Outline, Point, Point3};
use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::report::html::{HtmlReport, thin_trajectory, trajectory_of};
use millpath::report::plots::{self, AxisSeries, PlotOptions, Quantity};
use millpath::report::{PreviewOptions, toolpath_svg};
use millpath::toolpath::{Level, LevelKind, Move, Tool, Toolpath};
use std::path::{Path, PathBuf};
use std::process::Command;

mod job_common;

/// A 40 × 30 mm rectangle cut on two levels, each entered by a helix.
fn sample_job() -> (Toolpath, Vec<Outline>) {
    let outline = Outline::from_points(
        &[
            Point::new(0.0, 0.0),
            Point::new(40.0, 0.0),
            Point::new(40.0, 30.0),
            Point::new(0.0, 30.0),
        ],
        "test rectangle",
    )
    .unwrap();
    let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 10.0));
    for (k, z) in [-2.0, -4.0].into_iter().enumerate() {
        tp.push(Move::rapid(Point3::new(24.0, 15.0, 2.0)));
        let start = tp.moves.len();
        tp.push(Move::arc_xy(
            Point3::new(24.0, 15.0, z),
            Point3::new(20.0, 15.0, 0.0),
            true,
            10.0,
        ));
        for (x, y) in [
            (35.0, 15.0),
            (35.0, 25.0),
            (5.0, 25.0),
            (5.0, 5.0),
            (35.0, 5.0),
        ] {
            tp.push(Move::line(Point3::new(x, y, z), 40.0));
        }
        tp.levels.push(Level {
            z,
            kind: if k == 0 {
                LevelKind::Roughing
            } else {
                LevelKind::Finishing
            },
            start,
            end: tp.moves.len(),
        });
        tp.push(Move::rapid(Point3::new(35.0, 5.0, 10.0)));
    }
    (tp, vec![outline])
}

/// Builds the report; returns the HTML and the embedded (thinned) trajectory.
fn build_report() -> (String, Vec<[f64; 4]>, millpath::motion::Plan) {
    let (tp, outlines) = sample_job();
    let machine = Machine::preset("hsm").unwrap();
    let plan = plan_toolpath(&tp, &machine).unwrap();
    let samples = plan.sample(0.005).unwrap();
    let preview = toolpath_svg(
        &tp,
        &outlines,
        &PreviewOptions::default()
            .with_title(Some("rectangle <two levels>".into()))
            .with_achieved_feed(Some(plan.blocks.iter().map(|b| b.peak_feed).collect())),
    );
    let traj = trajectory_of(&samples);
    let mut r = HtmlReport::new("millpath report <test> & co");
    r.section(
        "summary",
        vec![
            ("cycle time".into(), format!("{:.3} s", plan.total_time)),
            ("path length".into(), format!("{:.1} mm", tp.cut_length())),
            ("blocks".into(), tp.moves.len().to_string()),
        ],
    );
    r.viewer(
        "rectangle",
        &preview,
        tp.levels.iter().map(|l| format!("z = {}", l.z)).collect(),
        &traj,
    )
    .unwrap();
    // Feed along the path: distance travelled by integrating the sampled feed.
    let mut s = 0.0;
    let mut feed = Vec::new();
    for w in samples.windows(2) {
        s += 0.5 * (w[0].feed + w[1].feed) * (w[1].t - w[0].t);
        feed.push((s, w[1].feed));
    }
    let o = PlotOptions::default();
    let chart = plots::feed_along_path(&feed, None);
    r.plot(
        "feed along the path",
        &plots::render_svg(&chart, &o).unwrap(),
    )
    .unwrap();
    let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let axes: Vec<AxisSeries> = ["X", "Y", "Z"]
        .iter()
        .enumerate()
        .map(|(k, n)| AxisSeries {
            name: (*n).into(),
            unit: "mm".into(),
            values: samples.iter().map(|s| s.vel[k]).collect(),
            limit: machine.axes.get(k).map(|a| a.max_velocity),
        })
        .collect();
    let chart = plots::axis_kinematics(Quantity::Velocity, &t, &axes);
    r.plot("per-axis velocity", &plots::render_svg(&chart, &o).unwrap())
        .unwrap();
    let thinned = thin_trajectory(&traj, 4000);
    (r.to_html(), thinned, plan)
}

#[test]
fn report_is_self_contained_and_well_formed() {
    let (html, traj, _) = build_report();
    // No resource from the network: the only URL is the SVG namespace identifier.
    let without_ns = html.replace("http://www.w3.org/2000/svg", "");
    let without_ns = without_ns.replace("http://www.w3.org/1999/xlink", "");
    assert!(
        !without_ns.contains("http://"),
        "network reference in report"
    );
    assert!(
        !without_ns.contains("https://"),
        "network reference in report"
    );
    assert!(!html.contains(" src="), "external resource in report");
    // Escaped text.
    assert!(html.contains("millpath report &lt;test&gt; &amp; co"));
    assert!(!html.contains("<test>"));
    // Balanced containers.
    for tag in [
        "html", "head", "body", "section", "table", "figure", "script", "svg", "select",
    ] {
        let open =
            html.matches(&format!("<{tag}>")).count() + html.matches(&format!("<{tag} ")).count();
        let close = html.matches(&format!("</{tag}>")).count();
        assert_eq!(open, close, "<{tag}> opened {open} times, closed {close}");
    }
    assert!(html.starts_with("<!DOCTYPE html>"));
    // The viewer: one option per level plus "all", the trajectory embedded and thinned.
    assert_eq!(html.matches("<option").count(), 3);
    assert!(traj.len() > 10 && traj.len() <= 4000);
}

fn chromium() -> PathBuf {
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        if let Ok(out) = Command::new("sh")
            .args(["-c", &format!("command -v {name}")])
            .output()
            && out.status.success()
        {
            let p = String::from_utf8_lossy(&out.stdout).trim().to_string();
            if !p.is_empty() {
                return PathBuf::from(p);
            }
        }
    }
    panic!(
        "headless Chromium is needed for this test and was not found: install it with \
         `apt-get install -y chromium` (Debian; .ci/run does this when missing)"
    );
}

fn run_chromium(bin: &Path, profile: &Path, extra: &[&str], url: &str) -> (String, String) {
    let out = Command::new(bin)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=3000",
            "--window-size=1200,1500",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(url)
        .output()
        .expect("running chromium");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "chromium failed: {stderr}");
    (stdout, stderr)
}

/// Linear interpolation of the embedded trajectory at `t`, written independently of the
/// page's script.
fn interpolate(traj: &[[f64; 4]], t: f64) -> [f64; 3] {
    let k = traj
        .iter()
        .position(|p| p[0] > t)
        .unwrap_or(traj.len() - 1)
        .max(1);
    let (a, b) = (traj[k - 1], traj[k]);
    let u = if b[0] > a[0] {
        ((t - a[0]) / (b[0] - a[0])).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [
        a[1] + u * (b[1] - a[1]),
        a[2] + u * (b[2] - a[2]),
        a[3] + u * (b[3] - a[3]),
    ]
}

fn field(title: &str, key: &str) -> f64 {
    title
        .split_whitespace()
        .find_map(|w| w.strip_prefix(key))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no {key} in title {title:?}"))
}

#[test]
fn report_works_in_headless_chromium() {
    let bin = chromium();
    let (html, traj, plan) = build_report();
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("report.html");
    std::fs::write(&page, &html).unwrap();
    let url = format!("file://{}#selftest", page.display());

    // 1. The page's self-test moves the slider to mid-cycle and reports the tool marker.
    let (dom, stderr) = run_chromium(&bin, &dir.path().join("p1"), &["--dump-dom"], &url);
    assert!(!stderr.contains("Uncaught"), "script error: {stderr}");
    assert!(dom.contains("data-mp-errors=\"0\""), "page recorded errors");
    let title = dom
        .split("<title>")
        .nth(1)
        .and_then(|s| s.split("</title>").next())
        .expect("title in DOM")
        .to_string();
    assert!(title.starts_with("MP-SELFTEST-OK"), "self-test: {title}");
    let t = field(&title, "t=");
    assert!((t - plan.total_time / 2.0).abs() < 1e-3, "slider at {t}");
    let (x, y) = (field(&title, "x="), field(&title, "y="));
    let want = interpolate(&traj, t);
    assert!(
        (x - want[0]).abs() < 2e-3 && (y - want[1]).abs() < 2e-3,
        "marker at ({x}, {y}), trajectory at {want:?}"
    );
    // The embedded trajectory is faithful to the plan itself at that time.
    let truth = plan.state_at(t).unwrap().position;
    assert!(
        (x - truth.x).hypot(y - truth.y) < 0.05,
        "marker ({x}, {y}) vs plan ({}, {})",
        truth.x,
        truth.y
    );

    // 2. A screenshot that is not blank.
    let shot = dir.path().join("shot.png");
    let (_, stderr) = run_chromium(
        &bin,
        &dir.path().join("p2"),
        &[&format!("--screenshot={}", shot.display())],
        &url,
    );
    assert!(!stderr.contains("Uncaught"), "script error: {stderr}");
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&shot).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let px = &buf[..info.buffer_size()];
    let lum: Vec<f64> = px
        .chunks(channels)
        .map(|c| {
            let g = |i: usize| f64::from(*c.get(i).unwrap_or(&c[0]));
            0.299 * g(0) + 0.587 * g(1) + 0.114 * g(2)
        })
        .collect();
    let mean = lum.iter().sum::<f64>() / lum.len() as f64;
    let var = lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64;
    let dark = lum.iter().filter(|l| **l < 128.0).count() as f64 / lum.len() as f64;
    assert!(
        var > 100.0,
        "screenshot looks blank: luminance variance {var:.1}"
    );
    assert!(
        dark > 0.002,
        "screenshot has almost no drawing: {dark:.4} dark"
    );
    if let Ok(keep) = std::env::var("MILLPATH_KEEP_SCREENSHOT") {
        std::fs::copy(&shot, keep).unwrap();
    }
}

/// The rows of the table with `id` in a DOM dump (its header row left out).
fn table_rows(dom: &str, id: &str) -> Vec<String> {
    let start = dom
        .find(&format!("<table id=\"{id}\">"))
        .unwrap_or_else(|| panic!("no table {id} in the page"));
    let table = &dom[start..];
    let table = &table[..table.find("</table>").expect("table closed")];
    table
        .split("<tr>")
        .skip(2)
        .map(|r| r.split("</tr>").next().unwrap_or("").to_owned())
        .collect()
}

/// A job's report in a real browser: the setup sheet (the tools to load, the operations in
/// order with their tools, what they cut, their times and verdicts) renders with the viewer of
/// the whole job, and the page's self-test runs without errors.
#[test]
fn setup_sheet_renders_in_headless_chromium() {
    let bin = chromium();
    let dir = tempfile::tempdir().unwrap();
    let spec = job_common::spec(dir.path(), job_common::same).unwrap();
    let run = millpath::job::part::run_spec(spec, &mut |_| {}).unwrap();
    let mut html = HtmlReport::new("plate job");
    millpath::job::part::setup_sheet(&mut html, &run.report);
    let plan = run.run.plan().unwrap();
    html.toolpath_viewer(
        "the whole job",
        &run.run.toolpath(),
        &run.run.model.parts,
        &plan,
    )
    .unwrap();
    let page = dir.path().join("job.html");
    std::fs::write(&page, html.to_html()).unwrap();
    let url = format!("file://{}#selftest", page.display());
    let (dom, stderr) = run_chromium(&bin, &dir.path().join("p"), &["--dump-dom"], &url);
    assert!(!stderr.contains("Uncaught"), "script error: {stderr}");
    assert!(dom.contains("data-mp-errors=\"0\""), "page recorded errors");
    assert!(dom.contains("<title>MP-SELFTEST-OK"), "self-test failed");
    let ops = table_rows(&dom, "setup-operations");
    assert_eq!(ops.len(), 5, "{ops:?}");
    for (row, (kind, tool)) in ops.iter().zip([
        ("face", "T1"),
        ("pocket", "T1"),
        ("bore", "T1"),
        ("drill", "T2"),
        ("profile", "T1"),
    ]) {
        assert!(
            row.contains(&format!("<td>{kind}</td>")) && row.contains(&format!("<td>{tool}</td>")),
            "{row}"
        );
    }
    assert!(ops[4].contains("2 tab(s)"), "{}", ops[4]);
    let tools = table_rows(&dom, "setup-tools");
    assert_eq!(tools.len(), 2, "{tools:?}");
    assert!(
        tools[1].contains("drill") && tools[1].contains("4 mm"),
        "{}",
        tools[1]
    );
    assert!(dom.contains("the drawn part, held by its tabs"));
}
