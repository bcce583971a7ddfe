//! `millpath demo`: every capability on the built-in samples, written into one folder.
//!
//! What it runs, in order (each step prints one line of its summary table):
//! 1. the die cavity of the free-form paper: four-point curve, exact offset, fewest segments
//!    within 0.00004 mm, 8 roughing layers and a finishing pass → G-code, report, SVG preview;
//! 2. the sample part's pockets in all three strategies (zigzag, offset, spiral);
//! 3. the adaptive-spiral paper's Figure 10: cycle time of the spiral against the transition C
//!    on its aerospace pocket, one level, 6 values of C × 4 feeds, zigzag as reference
//!    (28 toolpaths, about a second);
//! 4. the adaptive-spiral paper's Table 2 (square against circle) with the `hsm` preset;
//! 5. the five-axis paper's quarter circle: our minimum-time plan against the paper's method;
//! 6. the sample part as a whole part: its drawing (`whole_part.dxf`: the plate, its six
//!    pockets, four drilled and two bored holes), a job file made from it as `millpath job
//!    --init` makes one (`whole_part.toml`), and the job: faced, pocketed, drilled, bored and
//!    cut out with its tabs, with four tools in one program, verified as one job, its setup
//!    sheet in the report.
//!
//! Every program it writes gets the planner's cycle time on the `--machine` (default `hsm`),
//! and the motion plan is checked by the independent limit verifier.
//!
//! Pictures: `NAME.svg` previews (plan and side view, coloured by the achieved feed) and, for
//! the die cavity and the spiral, one picture per level (`NAME.level1.svg`, ...); the plots in
//! `plots/` as SVG and PNG; all of them in `report.html`.

use indicatif::{ProgressBar, ProgressStyle};
use millpath::gcode::{Dialect, WriterOptions, write_program};
use millpath::geom::Outline;
use millpath::machine::Machine;
use millpath::motion::{plan_toolpath, table2};
use millpath::report::html::HtmlReport;
use millpath::report::{self, PreviewOptions, plots};
use millpath::strategy::contour;
use millpath::{Error, InputError, Tool, Toolpath};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Arguments of `millpath demo`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath demo            # writes out/*.ngc, *.json, *.svg, out/plots/*, out/report.html\n  millpath demo --out /tmp/mp --machine router --json"
)]
pub struct Args {
    /// Folder for the outputs (created if missing).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Machine whose limits time every program: a preset name (see `millpath machines`) or
    /// a TOML machine profile. (Table 2 and the five-axis case keep their papers' machines.)
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// Print the summary table as one JSON object on stdout (progress lines are left out).
    #[arg(long)]
    pub json: bool,
}

/// One line of the demo's summary table.
#[derive(Debug, serde::Serialize)]
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
    let machine = super::load_machine(&args.machine)?;
    let json = args.json;
    let print = |line: &str| {
        if !json {
            super::print(line);
        }
    };
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
    rows.push(die_cavity(&args.out, &machine, &mut html, &print)?);
    rows.extend(pockets(&args.out, &machine, &mut html, &print)?);
    transition_sweep(&args.out, &machine, &mut html, &print)?;
    table_two(&args.out, &mut html, &print)?;
    rows.push(five_axis(&args.out, &mut html, &print)?);
    rows.push(whole_part(&args.out, &args.machine, &mut html, &print)?);
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
    if json {
        super::print_json(&serde_json::json!({
            "machine": machine.name,
            "out": args.out,
            "report": html_path,
            "programs": rows,
        }))?;
    }
    Ok(())
}

/// The sample part made whole: the drawing, a job file from it, the job (module docs, 6).
fn whole_part(
    out: &Path,
    machine: &str,
    html: &mut HtmlReport,
    print: Say<'_>,
) -> Result<Row, Error> {
    use millpath::job::part;
    let pb = spinner("whole part: face, pockets, holes, profile with tabs, four tools");
    let drawing = out.join("whole_part.dxf");
    millpath::io::write_atomic(
        &drawing,
        millpath::job::sample_part_job_drawing().as_bytes(),
    )?;
    let job_path = out.join("whole_part.toml");
    let text = part::init_file(
        &drawing,
        &job_path,
        &millpath::io::ImportSettings::default(),
        Dialect::LinuxCnc,
        machine,
        &mut |_| {},
    )?;
    millpath::io::write_atomic(&job_path, text.as_bytes())?;
    let run = part::run_file(&job_path, None, None, &mut |n| {
        pb.println(format!("note: {n}"));
    })?;
    millpath::io::write_atomic(&out.join("whole_part.ngc"), &run.run.gcode)?;
    let json = serde_json::to_string_pretty(&run.report)
        .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
    millpath::io::write_atomic(&out.join("whole_part.json"), json.as_bytes())?;
    let tp = run.run.toolpath();
    let plan = run.run.plan()?;
    let model = &run.run.model;
    let mut outlines: Vec<Outline> = model.parts.clone();
    outlines.extend(model.pockets.iter().map(|p| p.outer.clone()));
    for h in &model.holes {
        outlines.push(part::hole_outline(h.center, h.diameter)?);
    }
    let rep = &run.report;
    super::write_previews(
        &out.join("whole_part.svg"),
        &tp,
        &outlines,
        &PreviewOptions::default()
            .with_title(Some(format!(
                "sample part made whole: {} operations, {} tools, {:.0} s on {}",
                rep.operations.len(),
                rep.tools.len(),
                rep.cycle_time_s,
                rep.machine
            )))
            .with_achieved_feed(Some(plan.peak_feed_by_move(tp.moves.len()))),
        false,
    )?;
    part::setup_sheet(html, rep);
    html.toolpath_viewer(
        "sample part made whole: every operation (colour: achieved feed)",
        &tp,
        &outlines,
        &plan,
    )?;
    pb.finish_and_clear();
    let verdict = rep.check.last().map_or(String::new(), |(_, v)| v.clone());
    print(&format!(
        "whole part: {} operations, {} tools, {:.1} s with the tool changes; {verdict}",
        rep.operations.len(),
        rep.tools.len(),
        rep.cycle_time_s
    ));
    let blocks = String::from_utf8_lossy(&run.run.gcode)
        .lines()
        .filter(|l| {
            l.starts_with('G') || l.starts_with('X') || l.starts_with('Y') || l.starts_with('Z')
        })
        .count();
    Ok(Row {
        what: format!(
            "whole part, {} operations, {} tools",
            rep.operations.len(),
            rep.tools.len()
        ),
        cycle_s: rep.cycle_time_s,
        blocks,
        check: verdict,
    })
}

/// Prints a progress line (nothing under `--json`).
type Say<'a> = &'a dyn Fn(&str);

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
    // Written to memory first: what the writer refuses is in a toolpath the engine made (an
    // internal error), what the file system refuses is not.
    let mut buf = Vec::new();
    let blocks = write_program(tp, opts, &mut buf)
        .map_err(|e| e.engine_made(&format!("writing {}", path.display())))?
        .blocks;
    millpath::io::write_atomic(path, &buf)?;
    Ok(blocks)
}

/// Plans `tp` on `machine` and checks the plan with the independent 1 kHz verifier
/// ([`millpath::job::time_and_verify`]). Returns (plan, verifier summary).
pub(crate) fn time_and_verify(
    tp: &Toolpath,
    machine: &Machine,
) -> Result<(millpath::motion::Plan, String), Error> {
    let (plan, v) = millpath::job::time_and_verify(tp, machine)?;
    let check = match v {
        // The linuxcnc model is checked against LinuxCNC, not the limit verifier.
        None => "not verified (linuxcnc model)".to_string(),
        Some(v) if v.violations == 0 => format!("limits ok ({} samples)", v.samples),
        Some(v) => format!("{} LIMIT VIOLATIONS", v.violations),
    };
    Ok((plan, check))
}

fn die_cavity(
    out: &Path,
    machine: &Machine,
    html: &mut HtmlReport,
    print: Say<'_>,
) -> Result<Row, Error> {
    let pb = spinner("die cavity: curve, exact offset, flattening at 0.00004 mm");
    let (curve, opt) = contour::sample()?;
    let result = contour::contour(&curve, &opt)?;
    // Stated in the program and timed with: the machine's path tolerance, or the contour's
    // where that is tighter (see `contour::program_machine`).
    let machine = &millpath::job::contour::program_machine(machine, opt.tolerance);
    let mut wopt = WriterOptions::default()
        .with_dialect(Dialect::LinuxCnc)
        .with_decimals(Some(6))
        .with_program_name(Some("die cavity (Mohamed 2006)".to_owned()));
    // The tolerance alone, at 6 decimals (`with_path_tolerance` would add decimals if needed).
    wopt.path_tolerance = Some(machine.path_tolerance);
    let blocks = write_gcode(&out.join("die_cavity.ngc"), &result.toolpath, &wopt)?;
    pb.set_message("die cavity: cycle time and limit check");
    let (full_plan, check) = time_and_verify(&result.toolpath, machine)?;
    let cycle = full_plan.total_time();
    let report = serde_json::to_string_pretty(&result.report)
        .map_err(|e| Error::internal(format!("report JSON: {e}")))?;
    millpath::io::write_atomic(&out.join("die_cavity.json"), report.as_bytes())?;
    let outline = outline_for_viewer(&curve)?;
    // die_cavity.svg: the finishing pass (the last level); die_cavity.levelK.svg: every level.
    super::write_previews(
        &out.join("die_cavity.svg"),
        &result.toolpath,
        &[outline],
        &PreviewOptions::default()
            .with_title(Some(format!(
                "die cavity: {} segments per pass within {} mm",
                result.report.segments, opt.tolerance
            )))
            .with_level(result.toolpath.levels.len().checked_sub(1))
            .with_achieved_feed(Some(
                full_plan.peak_feed_by_move(result.toolpath.moves.len()),
            )),
        true,
    )?;
    pb.set_message("die cavity: plots and viewer");
    // Chordal deviation of every segment of one pass at the sample's tolerance (the paper's
    // Figure 10), measured by dense sampling (200 points per segment), not by the flattener.
    let pass = millpath::curve::flatten_curve(&curve, opt.tolerance)?;
    let per_segment = millpath::curve::segment_deviations(&curve, &pass, 200);
    add_plot(
        out,
        html,
        "die_cavity_deviation",
        "Die cavity: chordal deviation of each segment of the curve against the tolerance (cf. the die-cavity paper's Figure 10)",
        &plots::chordal_deviation(&per_segment, opt.tolerance),
    )?;
    // Feed along the path of the finishing level: the planned (achieved) feed.
    let finishing = result
        .toolpath
        .level(result.toolpath.levels.len().saturating_sub(1));
    let plan = plan_toolpath(&finishing, machine)
        .map_err(|e| e.engine_made("timing the die cavity's finishing pass"))?;
    let mut chart = report::feed_chart(&plan)?;
    chart.title = format!(
        "Die cavity, finishing pass: feed along the path ({})",
        machine.name
    );
    add_plot(
        out,
        html,
        "die_cavity_feed",
        "Die cavity, finishing pass: feed along the cutting path (rapids left out), achieved by the planner against programmed",
        &chart,
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

/// The adaptive-spiral paper's Figure 10: the spiral's cycle time against C for four feeds on
/// its aerospace pocket (one level of 6.35 mm), zigzag at each feed as the dashed reference.
fn transition_sweep(
    out: &Path,
    machine: &Machine,
    html: &mut HtmlReport,
    print: Say<'_>,
) -> Result<(), Error> {
    use millpath::strategy::pocket::{PocketOptions, builtin};
    let ratios = [0.2, 0.3, 0.4, 0.5, 0.6, 0.7];
    let feeds = [200.0, 300.0, 400.0, 600.0];
    let shape = builtin::aerospace_pocket();
    let tool = Tool::flat(12.7)?;
    let base = PocketOptions::default()
        .with_depth(6.35)
        .with_step_down(6.35);
    let total = (feeds.len() * (1 + ratios.len())) as u64;
    let pb = ProgressBar::new(total);
    pb.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    pb.set_message("transition sweep: spiral and zigzag toolpaths, planned");
    let table = millpath::job::sweep::sweep(
        &shape,
        &tool,
        &base,
        machine,
        &ratios,
        &feeds,
        &mut |done, _| pb.set_position(done as u64),
    )?;
    pb.finish_and_clear();
    let json =
        serde_json::to_string_pretty(&table).map_err(|e| Error::internal(format!("JSON: {e}")))?;
    millpath::io::write_atomic(&out.join("sweep.json"), json.as_bytes())?;
    add_plot(
        out,
        html,
        "cycle_time_vs_transition",
        "Aerospace pocket, one level of 6.35 mm, 12.7 mm tool, 40 % stepover: cycle time of the spiral against the transition C, one curve per feed, zigzag at the same feed dashed (cf. the adaptive-spiral paper's Figure 10)",
        &table.chart(),
    )?;
    let best = |f: usize| {
        ratios
            .iter()
            .enumerate()
            .filter_map(|(c, r)| Some((*r, *table.spiral_s.get(c)?.get(f)?)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    let mut parts = Vec::new();
    for (f, feed) in feeds.iter().enumerate() {
        if let (Some((c, t)), Some(z)) = (best(f), table.zigzag_s.get(f)) {
            parts.push(format!(
                "{feed:.0} in/min: best C = {c} at {t:.1} s (zigzag {z:.1} s)"
            ));
        }
    }
    print(&format!(
        "transition sweep (adaptive-spiral paper, Figure 10): aerospace pocket, one level, C = 0.2..0.7 × {} feeds, {total} toolpaths planned on `{}`; {}; table in sweep.json",
        feeds.len(),
        machine.name,
        parts.join("; ")
    ));
    Ok(())
}

fn table_two(out: &Path, html: &mut HtmlReport, print: Say<'_>) -> Result<(), Error> {
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

fn five_axis(out: &Path, html: &mut HtmlReport, print: Say<'_>) -> Result<Row, Error> {
    use millpath::machine::kinematics::PaperAb;
    use millpath::motion::five_axis::{self, FiveAxisOptions, Limits};
    let pb = spinner("five-axis: minimum-time plan and the paper's GA baseline");
    let kin = PaperAb::paper();
    let poses = five_axis::paper_path();
    let outcome = five_axis::plan(
        &kin,
        &poses,
        &Limits::paper(),
        &FiveAxisOptions::default(),
        Some(five_axis::paper_deflection()),
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
    for (file, caption, chart) in report::axis_charts(&samples, names, &Limits::paper()) {
        add_plot(out, html, file, &caption, &chart)?;
    }
    if let Some(d) = &r.deflection {
        // The paper's Figures 9-10: the replanned path round the deflected point and the axis
        // profiles through the two new intervals.
        // The curve through the knots the plan went through (the replanning's intervals are
        // theirs).
        let tips: Vec<_> = outcome.poses.iter().map(|p| p.tip).collect();
        let curve = five_axis::RefCurve::through(&tips);
        for (file, caption, chart) in
            report::deflection_charts(&kin, &curve, &outcome.segments, d, &Limits::paper())
        {
            add_plot(out, html, file, &caption, &chart)?;
        }
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

/// The curve as an outline for drawing (flattened coarsely: the picture only).
fn outline_for_viewer(curve: &millpath::curve::CompositeCurve) -> Result<Outline, Error> {
    let flat = millpath::curve::flatten_curve(curve, 0.01)?;
    Ok(Outline::from_points(&flat.points, "die cavity curve")?)
}

/// The sample part's pockets (after the adaptive-spiral paper's Figure 17) in all three
/// strategies: one program per strategy, each pocket verified by the stock simulation.
fn pockets(
    out: &Path,
    machine: &Machine,
    html: &mut HtmlReport,
    print: Say<'_>,
) -> Result<Vec<Row>, Error> {
    use millpath::stock::SimOptions;
    use millpath::strategy::pocket::{self, PocketOptions, StrategyKind};
    // The sample part as a drawing, read back through the DXF reader.
    let dxf_path = out.join("sample_part.dxf");
    let (dxf, part) = millpath::job::sample_part_drawing(&dxf_path.display().to_string())?;
    millpath::io::write_atomic(&dxf_path, dxf.as_bytes())?;
    let tool = Tool::flat(12.7)?;
    // 12.7 mm end mill, 40 % stepover, 600 in/min, two levels of 6.35 mm.
    let opts = PocketOptions::default()
        .with_depth(12.7)
        .with_step_down(6.35);
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    let outlines: Vec<Outline> = part.iter().map(|(_, s)| s.outer.clone()).collect();
    let shapes: Vec<(usize, pocket::PocketShape)> = part
        .iter()
        .enumerate()
        .map(|(i, (_, s))| (i + 1, s.clone()))
        .collect();
    let time = |tp: &Toolpath| millpath::motion::cycle_time(tp, machine);
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
        let whole = pocket::generate_part(
            &shapes,
            pocket::PartStrategy::One(kind),
            &tool,
            &opts,
            &sim,
            &time,
        )?;
        let problems = whole.verification.problems();
        let max_eng = whole.verification.total.max_engagement_deg;
        for p in &whole.pockets {
            for n in p.result.iter().flat_map(|r| r.notes.iter()) {
                pb.println(format!("note: pocket {}, {name}: {n}", p.index));
            }
        }
        let program = Some(whole.toolpath);
        let Some(tp) = program else { continue };
        let wopt = WriterOptions::default()
            .with_program_name(Some(format!("sample part, {name} roughing")))
            .with_path_tolerance(machine.path_tolerance);
        let blocks = write_gcode(&out.join(format!("part_{name}.ngc")), &tp, &wopt)?;
        pb.set_message(format!("pockets: {name}: cycle time and limit check"));
        let (plan, check) = time_and_verify(&tp, machine)?;
        let cycle = plan.total_time();
        // part_NAME.svg; for the spiral also one picture per level.
        super::write_previews(
            &out.join(format!("part_{name}.svg")),
            &tp,
            &outlines,
            &PreviewOptions::default()
                .with_title(Some(format!(
                    "sample part, {name}: {cycle:.1} s on {}",
                    machine.name
                )))
                .with_achieved_feed(Some(plan.peak_feed_by_move(tp.moves.len()))),
            kind == StrategyKind::Spiral,
        )?;
        if kind == StrategyKind::Spiral {
            html.toolpath_viewer(
                "sample part, adaptive spiral (colour: achieved feed)",
                &tp,
                &outlines,
                &plan,
            )?;
            // The paper's Figure 15: a rectangular pocket at 600 in/min with 75 % slowdown;
            // here bay 1 (120 × 80 mm), its first level.
            if let Some((bay, shape)) = part.first() {
                let bay_tp = pocket::toolpath(kind, shape, &tool, &opts)?;
                let first = bay_tp.level(0);
                let plan = plan_toolpath(&first, machine)
                    .map_err(|e| e.engine_made("timing the spiral's first level"))?;
                let mut chart = report::feed_chart(&plan)?;
                chart.title = format!(
                    "Spiral, {bay}, first level: feed along the path ({})",
                    machine.name
                );
                add_plot(
                    out,
                    html,
                    "part_spiral_feed",
                    &format!(
                        "Spiral on {bay}, first level: feed along the cutting path (rapids left out); programmed = 600 in/min lowered by the engagement-based modulation (75 % slowdown), achieved = the planner's (cf. the adaptive-spiral paper's Figure 15)"
                    ),
                    &chart,
                )?;
            }
        }
        pb.finish_and_clear();
        let verdict = if problems.is_empty() {
            format!("{check}; no gouge, no uncut, max engagement {max_eng:.0}°")
        } else {
            format!("{check}; {}", millpath::stock::problems_text(&problems))
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
