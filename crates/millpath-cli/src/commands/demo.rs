//! `millpath demo`: every capability on the built-in samples, written into one folder.
//!
//! What it runs, in order (each step prints one line of its summary table):
//! 1. the die cavity of the free-form paper: four-point curve, exact offset, fewest segments
//!    within 0.00004 mm, 8 roughing layers and a finishing pass → G-code, report, SVG preview;
//! 2. the sample part's pockets in all three strategies (zigzag, offset, spiral);
//! 3. the adaptive-spiral paper's Table 2 (square against circle) with the `hsm` preset;
//! 4. the five-axis paper's quarter circle: our minimum-time plan against the paper's method.
//!
//! Every program it writes gets the planner's cycle time on the `hsm` machine, and the motion
//! plan is checked by the independent limit verifier.

use super::print;
use indicatif::{ProgressBar, ProgressStyle};
use millpath::gcode::{Dialect, WriterOptions, write_program};
use millpath::geom::Outline;
use millpath::machine::Machine;
use millpath::motion::verify::{VerifyOptions, verify_plan};
use millpath::motion::{plan_toolpath, table2};
use millpath::report::html::HtmlReport;
use millpath::report::{PreviewOptions, plots, series, toolpath_svg};
use millpath::strategy::contour;
use millpath::{Error, InputError, Tool, Toolpath};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Arguments of `millpath demo`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Example:\n  millpath demo            # writes out/*.ngc, *.json, *.svg\n  millpath demo --out /tmp/mp --machine router"
)]
pub struct Args {
    /// Folder for the outputs (created if missing).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Machine preset whose limits time every program.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
}

/// One line of the demo's summary table.
struct Row {
    what: String,
    cycle_s: f64,
    blocks: usize,
    check: String,
}

/// Runs the demo.
pub fn run(args: &Args) -> Result<(), Error> {
    std::fs::create_dir_all(&args.out).map_err(|e| {
        Error::Input(
            InputError::new("output folder", args.out.display())
                .at("--out")
                .expected(format!("a folder that can be created ({e})")),
        )
    })?;
    let machine = Machine::preset(&args.machine)?;
    print(&format!(
        "millpath demo: writing into {}/ (cycle times on the `{}` machine)",
        args.out.display(),
        machine.name
    ));
    let plots_dir = args.out.join("plots");
    std::fs::create_dir_all(&plots_dir).map_err(|e| {
        Error::Input(
            InputError::new("output folder", plots_dir.display())
                .at("--out")
                .expected(format!("a folder that can be created ({e})")),
        )
    })?;
    let mut html = HtmlReport::new("millpath demo");
    let mut rows = Vec::new();
    rows.push(die_cavity(&args.out, &machine, &mut html)?);
    rows.extend(pockets(&args.out, &machine, &mut html)?);
    table_two(&args.out, &mut html)?;
    rows.push(five_axis(&args.out, &mut html)?);
    let mut summary = vec![super::html::machine_row(&machine)];
    summary.extend(rows.iter().map(|r| {
        (
            r.what.clone(),
            format!(
                "{:.2} s planned, {} blocks; {}",
                r.cycle_s, r.blocks, r.check
            ),
        )
    }));
    html.section("summary", summary);
    let html_path = args.out.join("report.html");
    millpath::io::write_atomic(&html_path, html.to_html().as_bytes())?;

    print("");
    print(&format!(
        "{:<44} {:>12} {:>9}  {}",
        "program", "cycle time", "blocks", "verifier"
    ));
    for r in &rows {
        print(&format!(
            "{:<44} {:>10.2} s {:>9}  {}",
            r.what, r.cycle_s, r.blocks, r.check
        ));
    }
    print(&format!("report: {}", html_path.display()));
    Ok(())
}

/// Renders `chart` to `plots/NAME.svg` and `.png` and adds it to the report.
fn add_plot(
    out: &Path,
    html: &mut HtmlReport,
    name: &str,
    caption: &str,
    chart: &plots::Chart,
) -> Result<(), Error> {
    let svg = plots::render_files(
        chart,
        &plots::PlotOptions::default(),
        &out.join("plots").join(name),
    )?;
    html.plot(caption, &svg)?;
    Ok(())
}

fn spinner(msg: &str) -> ProgressBar {
    let pb = ProgressBar::new_spinner();
    pb.set_style(
        ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    pb.set_message(msg.to_owned());
    pb.enable_steady_tick(Duration::from_millis(120));
    pb
}

/// Writes `tp` as linuxcnc G-code into `path`; returns the number of motion blocks.
pub(crate) fn write_gcode(
    path: &Path,
    tp: &Toolpath,
    opts: &WriterOptions,
) -> Result<usize, Error> {
    let mut blocks = 0;
    millpath::io::write_atomic_with(path, |w| {
        blocks = write_program(tp, opts, w)?.blocks;
        Ok(())
    })?;
    Ok(blocks)
}

/// Plans `tp` on `machine` and checks the plan with the independent 1 kHz verifier.
/// Returns (cycle time, verifier summary).
pub(crate) fn time_and_verify(tp: &Toolpath, machine: &Machine) -> Result<(f64, String), Error> {
    let plan = plan_toolpath(tp, machine)?;
    let moves: Vec<_> = tp.segments().map(|(from, m)| (from, *m)).collect();
    let v = verify_plan(&plan, &moves, machine, &VerifyOptions::default())?;
    let check = if v.violations == 0 {
        format!("limits ok ({} samples)", v.samples)
    } else {
        format!("{} LIMIT VIOLATIONS", v.violations)
    };
    Ok((plan.total_time(), check))
}

fn die_cavity(out: &Path, machine: &Machine, html: &mut HtmlReport) -> Result<Row, Error> {
    let pb = spinner("die cavity: curve, exact offset, flattening at 0.00004 mm");
    let (curve, opt) = contour::sample()?;
    let result = contour::contour(&curve, &opt)?;
    let wopt = WriterOptions {
        dialect: Dialect::LinuxCnc,
        decimals: Some(6),
        program_name: Some("die cavity (Mohamed 2006)".to_owned()),
        ..WriterOptions::default()
    }
    .with_tolerance(machine.path_tolerance.max(1e-3));
    let blocks = write_gcode(&out.join("die_cavity.ngc"), &result.toolpath, &wopt)?;
    pb.set_message("die cavity: cycle time and limit check");
    let (cycle, check) = time_and_verify(&result.toolpath, machine)?;
    let report = serde_json::to_string_pretty(&result.report)
        .map_err(|e| Error::internal(format!("report JSON: {e}")))?;
    millpath::io::write_atomic(&out.join("die_cavity.json"), report.as_bytes())?;
    let outline = outline_for_viewer(&curve)?;
    let svg = toolpath_svg(
        &result.toolpath,
        &[outline],
        &PreviewOptions {
            title: Some(format!(
                "die cavity: finishing pass, {} segments per pass within {} mm",
                result.report.segments, opt.tolerance
            )),
            level: result.toolpath.levels.len().checked_sub(1),
            ..PreviewOptions::default()
        },
    );
    millpath::io::write_atomic(&out.join("die_cavity.svg"), svg.as_bytes())?;
    pb.set_message("die cavity: plots and viewer");
    // Chordal deviation of every segment of one pass at the sample's tolerance (the paper's
    // Figure 10), measured by dense sampling (200 points per segment), not by the flattener.
    let pass = millpath::curve::flatten::flatten_curve(&curve, opt.tolerance)?;
    let per_segment: Vec<f64> = pass
        .params
        .windows(2)
        .zip(pass.points.windows(2))
        .map(|(p, q)| millpath::curve::verify::chordal_deviation(&curve, p, q, 200))
        .collect();
    add_plot(
        out,
        html,
        "die_cavity_deviation",
        "Die cavity: chordal deviation of each segment of the curve against the tolerance (cf. the die-cavity paper's Figure 10)",
        &plots::chordal_deviation(&per_segment, opt.tolerance),
    )?;
    // Feed along the path of the finishing level: the planned (achieved) feed.
    let finishing = level_toolpath(
        &result.toolpath,
        result.toolpath.levels.len().saturating_sub(1),
    );
    let plan = plan_toolpath(&finishing, machine)?;
    let samples = plan.sample((plan.total_time / 20_000.0).max(1e-3))?;
    add_plot(
        out,
        html,
        "die_cavity_feed",
        "Die cavity, finishing pass: planned feed along the path",
        &plots::feed_along_path(&series::feed_along_path(&samples), None),
    )?;
    html.toolpath_viewer(
        "die cavity: finishing pass (colour: achieved feed)",
        &finishing,
        &[outline_for_viewer(&curve)?],
        &plan,
    )?;
    pb.finish_and_clear();
    print(&format!(
        "die cavity: {} segments per pass (T = {} mm, max deviation {:.2e} mm), {} layers, {} blocks; \
         {:.1} s at programmed feed, {:.1} s planned",
        result.report.segments,
        opt.tolerance,
        result.report.max_deviation_mm,
        result.report.layers.len(),
        blocks,
        result.report.time_at_programmed_feed_s,
        cycle
    ));
    for w in &result.warnings {
        print(&format!("  warning: {w}"));
    }
    Ok(Row {
        what: "die cavity (contour, 9 levels)".to_owned(),
        cycle_s: cycle,
        blocks,
        check: format!(
            "{check}; deviation {:.1e} ≤ {:.0e} mm",
            result.report.max_deviation_mm, opt.tolerance
        ),
    })
}

fn table_two(out: &Path, html: &mut HtmlReport) -> Result<(), Error> {
    let hsm = Machine::preset("hsm")?;
    let rows = table2::compare(&hsm)?;
    let text = table2::format_table(&rows);
    millpath::io::write_atomic(&out.join("table2.txt"), text.as_bytes())?;
    add_plot(
        out,
        html,
        "square_circle_gain",
        "Square against circle of equal perimeter: time gain of the circle, measured on the 840D (points) and planned by millpath on `hsm` (lines) (cf. the adaptive-spiral paper's Figures 22-23)",
        &plots::square_circle_gain(&rows),
    )?;
    let wins = rows
        .iter()
        .filter(|r| r.circle_planned < r.square_planned)
        .count();
    print(&format!(
        "square vs circle (adaptive-spiral paper, Table 2, `hsm`): circle faster in {wins} of {} rows; table in table2.txt",
        rows.len()
    ));
    Ok(())
}

fn five_axis(out: &Path, html: &mut HtmlReport) -> Result<Row, Error> {
    use millpath::machine::kinematics::PaperAb;
    use millpath::motion::five_axis::{self, FiveAxisOptions, Limits, case};
    let pb = spinner("five-axis: minimum-time plan and the paper's GA baseline");
    let kin = PaperAb::paper();
    let poses = case::paper_path();
    let outcome = five_axis::plan(
        &kin,
        &poses,
        &Limits::paper(),
        &FiveAxisOptions::default(),
        Some(case::paper_deflection()),
    )?;
    let r = &outcome.result;
    let json =
        serde_json::to_string_pretty(r).map_err(|e| Error::internal(format!("JSON: {e}")))?;
    millpath::io::write_atomic(&out.join("five_axis.json"), json.as_bytes())?;
    let samples = five_axis::sample(&outcome.segments, &kin, 1e-3);
    millpath::io::write_atomic_with(&out.join("five_axis.csv"), |w| {
        five_axis::write_csv(
            w,
            &samples,
            millpath::machine::kinematics::Kinematics::axis_names(&kin),
        )
        .map_err(|e| Error::internal(format!("CSV: {e}")))
    })?;
    let names = millpath::machine::kinematics::Kinematics::axis_names(&kin);
    for (file, caption, chart) in super::html::five_axis_charts(&samples, names, &Limits::paper()) {
        add_plot(out, html, file, &caption, &chart)?;
    }
    pb.finish_and_clear();
    let baseline = r.baseline_time_s.map_or_else(
        || "no baseline".to_owned(),
        |b| {
            format!(
                "the paper's method {b:.4} s ({:.3}× slower)",
                b / r.total_time_s
            )
        },
    );
    print(&format!(
        "five-axis quarter circle: {:.4} s against {baseline}, {} limit violations",
        r.total_time_s,
        r.violations.len()
    ));
    Ok(Row {
        what: "five-axis quarter circle (paper case)".to_owned(),
        cycle_s: r.total_time_s,
        blocks: r.intervals,
        check: format!("{} violations (dense + analytic)", r.violations.len()),
    })
}

/// The moves of one level as a toolpath of their own (starting where the level starts).
fn level_toolpath(tp: &Toolpath, level: usize) -> Toolpath {
    let Some(l) = tp.levels.get(level) else {
        return tp.clone();
    };
    let start = if l.start == 0 {
        tp.start
    } else {
        tp.moves.get(l.start - 1).map_or(tp.start, |m| m.to)
    };
    let mut out = Toolpath::new(tp.tool, start);
    out.moves = tp.moves.get(l.start..l.end).unwrap_or_default().to_vec();
    out.levels = vec![millpath::toolpath::Level {
        start: 0,
        end: out.moves.len(),
        ..l.clone()
    }];
    out
}

/// The curve as an outline for drawing (flattened coarsely: the picture only).
fn outline_for_viewer(curve: &millpath::curve::CompositeCurve) -> Result<Outline, Error> {
    let flat = millpath::curve::flatten::flatten_curve(curve, 0.01)?;
    Ok(Outline::from_points(&flat.points, "die cavity curve")?)
}

/// The sample part's pockets (after the adaptive-spiral paper's Figure 17) in all three
/// strategies: one program per strategy, each pocket verified by the stock simulation.
fn pockets(out: &Path, machine: &Machine, html: &mut HtmlReport) -> Result<Vec<Row>, Error> {
    use millpath::stock::SimOptions;
    use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, samples};
    let part = samples::structural_part();
    let tool = Tool::flat(12.7)?;
    // 12.7 mm end mill, 40 % stepover, 600 in/min, two levels of 6.35 mm.
    let opts = PocketOptions {
        depth: 12.7,
        step_down: 6.35,
        ..PocketOptions::default()
    };
    let sim = SimOptions {
        cell: 0.1,
        step: 0.2,
        ..SimOptions::default()
    };
    let outlines: Vec<Outline> = part.iter().map(|(_, s)| s.outer.clone()).collect();
    let mut rows = Vec::new();
    for (kind, name) in [
        (StrategyKind::Zigzag, "zigzag"),
        (StrategyKind::Offset, "offset"),
        (StrategyKind::Spiral, "spiral"),
    ] {
        let pb = spinner(&format!(
            "pockets: {name} on {} pockets, stock simulation",
            part.len()
        ));
        let mut program: Option<Toolpath> = None;
        let mut problems = Vec::new();
        let mut max_eng = 0.0_f64;
        for (pname, shape) in &part {
            let r = pocket::generate(kind, shape, &tool, &opts, &sim)?;
            for p in r.verification.problems() {
                problems.push(format!("{pname}: {p}"));
            }
            max_eng = max_eng.max(r.verification.max_engagement_deg);
            program = Some(match program {
                None => r.toolpath,
                Some(acc) => append(acc, &r.toolpath),
            });
        }
        let Some(tp) = program else { continue };
        let wopt = WriterOptions {
            program_name: Some(format!("sample part, {name} roughing")),
            ..WriterOptions::default()
        }
        .with_tolerance(machine.path_tolerance);
        let blocks = write_gcode(&out.join(format!("part_{name}.ngc")), &tp, &wopt)?;
        pb.set_message(format!("pockets: {name}: cycle time and limit check"));
        let (cycle, check) = time_and_verify(&tp, machine)?;
        let plan = plan_toolpath(&tp, machine)?;
        let preview = toolpath_svg(
            &tp,
            &outlines,
            &PreviewOptions {
                title: Some(format!(
                    "sample part, {name}: {cycle:.1} s on {}",
                    machine.name
                )),
                achieved_feed: Some(plan.blocks.iter().map(|b| b.peak_feed).collect()),
                ..PreviewOptions::default()
            },
        );
        millpath::io::write_atomic(&out.join(format!("part_{name}.svg")), preview.as_bytes())?;
        if kind == StrategyKind::Spiral {
            html.toolpath_viewer(
                "sample part, adaptive spiral (colour: achieved feed)",
                &tp,
                &outlines,
                &plan,
            )?;
            let samples = plan.sample((plan.total_time / 20_000.0).max(1e-3))?;
            add_plot(
                out,
                html,
                "part_spiral_feed",
                "Sample part, spiral: planned feed along the path (cf. the adaptive-spiral paper's Figure 15)",
                &plots::feed_along_path(&series::feed_along_path(&samples), None),
            )?;
        }
        pb.finish_and_clear();
        let verdict = if problems.is_empty() {
            format!("{check}; no gouge, no uncut, max engagement {max_eng:.0}°")
        } else {
            format!("{check}; {}", problems.join("; "))
        };
        print(&format!(
            "sample part, {name}: {} pockets, {cycle:.1} s planned, {blocks} blocks",
            part.len()
        ));
        rows.push(Row {
            what: format!("sample part, {} pockets, {name}", part.len()),
            cycle_s: cycle,
            blocks,
            check: verdict,
        });
    }
    Ok(rows)
}

/// `b` appended to `a`: a rapid to `b`'s start, then `b`'s moves and levels.
fn append(mut a: Toolpath, b: &Toolpath) -> Toolpath {
    let safe = a.end().z.max(b.start.z);
    let end = a.end();
    a.push(millpath::Move::rapid(millpath::Point3::new(
        end.x, end.y, safe,
    )));
    a.push(millpath::Move::rapid(millpath::Point3::new(
        b.start.x, b.start.y, safe,
    )));
    a.push(millpath::Move::rapid(b.start));
    let offset = a.moves.len();
    a.moves.extend_from_slice(&b.moves);
    a.levels
        .extend(b.levels.iter().map(|l| millpath::toolpath::Level {
            start: l.start + offset,
            end: l.end + offset,
            ..l.clone()
        }));
    a
}
