//! `millpath contour`: the free-form contour pipeline.
//!
//! points (CSV/JSON) → closed curve → exact cutter offset → fewest segments within the
//! tolerance → layers → G-code (any dialect) and a JSON report.

use millpath::curve::{self, CurveKind};
use millpath::job::contour::{ContourRun, ContourSettings, ContourSource};
use millpath::strategy::contour::Side;
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Curve through the points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CurveArg {
    /// Cubic through each group of 4 points at u = 0, 1/3, 2/3, 1, C1 blends between groups.
    FourPoint,
    /// Closed centripetal Catmull-Rom curve through all points (C1).
    CatmullRom,
    /// Closed periodic cubic spline through all points (C2).
    Spline,
}

/// Side of the outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SideArg {
    /// Inside (a cavity).
    Inside,
    /// Outside (a boss).
    Outside,
    /// Tool centre on the outline.
    On,
}

/// Arguments of `millpath contour`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:\n  \
    millpath contour points.csv --tool-diameter 10 --tolerance 0.01 --side inside --depth 20 \\\n    \
    --step-down 2.5 --finish-allowance 0.2 -o cavity.ngc --report cavity.json\n  \
    millpath contour --sample -o die.ngc --report die.json     # the paper's die cavity\n  \
    millpath contour --sample --dialect sinumerik --units in --tool-number 2 -o die.mpf\n  \
    millpath contour --sample --machine my_mill.toml --json --svg die.svg --per-level\n\n\
POINTS: CSV `x,y` per line (mm); a blank line or a third `group` column separates the 4-point\n\
groups; or JSON {\"groups\": [[[x,y],...],...]} or {\"points\": [[x,y],...]}.\n\
Tolerance budget: chord deviation + G-code rounding <= --tolerance; the path stays on the free\n\
side of the nominal offset (never gouges). Decimals are raised as needed.\n\
Exit codes: 0 ok, 1 internal error, 2 bad input (no output file is written).")]
pub struct Args {
    /// Points file (CSV or JSON). Omit with --sample.
    pub points: Option<PathBuf>,
    /// Use the paper's die cavity (400 x 450 x 50 mm block, 10 mm end mill, 8 layers of
    /// 2.5 mm, T = 0.00004 mm) instead of a points file; other flags given explicitly override it.
    #[arg(long)]
    pub sample: bool,
    /// Tool diameter in mm.
    #[arg(long)]
    pub tool_diameter: Option<f64>,
    /// Path tolerance in mm (chord deviation + output rounding).
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Side of the outline the tool runs on.
    #[arg(long, value_enum, default_value = "inside")]
    pub side: SideArg,
    /// Depth below the top in mm.
    #[arg(long)]
    pub depth: Option<f64>,
    /// Step-down per roughing layer in mm.
    #[arg(long)]
    pub step_down: Option<f64>,
    /// Radial stock left by roughing, in mm.
    #[arg(long, default_value_t = 0.2)]
    pub finish_allowance: f64,
    /// Curve through the points.
    #[arg(long, value_enum, default_value = "four-point")]
    pub curve: CurveArg,
    /// Emit biarcs (G2/G3) instead of lines.
    #[arg(long)]
    pub arcs: bool,
    #[command(flatten)]
    pub program: super::output::OutputArgs,
    /// Cutting feed in mm/min.
    #[arg(long, default_value_t = 1000.0)]
    pub feed: f64,
    /// Plunge feed in mm/min.
    #[arg(long, default_value_t = 300.0)]
    pub plunge_feed: f64,
    /// Safe height above the top for rapids, mm.
    #[arg(long, default_value_t = 10.0)]
    pub safe_height: f64,
    /// Clearance height above the top where feeding down starts, mm.
    #[arg(long, default_value_t = 2.0)]
    pub clearance_height: f64,
    /// Lead-in/lead-out arc radius, mm (0: none).
    #[arg(long, default_value_t = 2.0)]
    pub lead_radius: f64,
    /// Output G-code file.
    #[arg(short = 'o', long)]
    pub output: Option<PathBuf>,
    /// Output JSON report.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Write a self-contained HTML report (summary, viewer with playback on the machine,
    /// chordal deviation per segment, feed plot).
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Machine whose limits give the planned cycle time: a preset name (see `millpath
    /// machines`) or a TOML machine profile.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// Print the report (with the planned cycle time) as one JSON object on stdout.
    #[arg(long)]
    pub json: bool,
    /// Write an SVG preview (plan and side view, coloured by achieved feed on the machine).
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// With --svg: also one picture per level, `NAME.level1.svg`, ...
    #[arg(long, requires = "svg")]
    pub per_level: bool,
}

fn input(what: &str, v: impl std::fmt::Display, flag: &str, expected: &str) -> Error {
    InputError::new(what, v).at(flag).expected(expected).into()
}

impl Args {
    /// The contour job's settings these flags give.
    fn settings(&self) -> ContourSettings {
        let args = self;
        ContourSettings {
            tool_diameter: args.tool_diameter,
            tolerance: args.tolerance,
            side: match args.side {
                SideArg::Inside => Side::Inside,
                SideArg::Outside => Side::Outside,
                SideArg::On => Side::On,
            },
            depth: args.depth,
            step_down: args.step_down,
            finish_allowance: args.finish_allowance,
            curve: match args.curve {
                CurveArg::FourPoint => CurveKind::FourPoint,
                CurveArg::CatmullRom => CurveKind::CatmullRom,
                CurveArg::Spline => CurveKind::Spline,
            },
            arcs: args.arcs,
            feed: args.feed,
            plunge_feed: args.plunge_feed,
            safe_height: args.safe_height,
            clearance_height: args.clearance_height,
            lead_radius: args.lead_radius,
            machine: args.machine.clone(),
        }
    }
}

/// The points file's text and name, or `None` for `--sample`.
fn points(args: &Args) -> Result<Option<(String, String)>, Error> {
    match (&args.points, args.sample) {
        (Some(path), false) => Ok(Some((super::read_text(path)?, path.display().to_string()))),
        (None, true) => Ok(None),
        (Some(_), true) => Err(input(
            "POINTS",
            "given with --sample",
            "command line",
            "either a points file or --sample",
        )),
        (None, false) => Err(input(
            "POINTS",
            "missing",
            "command line",
            "a points file (CSV or JSON) or --sample",
        )),
    }
}

/// Runs the contour pipeline.
pub fn run(args: &Args) -> Result<(), Error> {
    // The machine is checked before the points are read (as the job does).
    super::load_machine(&args.machine)?;
    let points = points(args)?;
    let source = match &points {
        Some((text, name)) => ContourSource::Points { text, name },
        None => ContourSource::Sample,
    };
    let job = millpath::job::contour::run(source, &args.settings(), &args.program.settings())?;
    let report = &job.report;
    let json = serde_json::to_string_pretty(report)
        .map_err(|e| Error::internal(format!("report: {e}")))?;
    if let Some(out) = &args.output {
        millpath::io::write_atomic_with(out, |w| {
            w.write_all(job.gcode.as_bytes())
                .map_err(|e| Error::internal(format!("writing {}: {e}", out.display())))
        })?;
    }
    if let Some(rp) = &args.report {
        millpath::io::write_atomic(rp, json.as_bytes())?;
    }
    let plan = job.plan()?;
    let (flat, outline) = job.outline()?;
    let (m, name, tol) = (&job.machine, &job.name, job.options.tolerance);
    let mut pictures = Vec::new();
    if let Some(path) = &args.svg {
        let title = format!(
            "contour {name}: {} segments per pass, {:.1} s on {}",
            report.segments,
            plan.total_time(),
            m.name
        );
        pictures = super::write_previews(
            path,
            &job.toolpath,
            std::slice::from_ref(&outline),
            &millpath::report::PreviewOptions::default()
                .with_title(Some(title))
                .with_achieved_feed(Some(plan.peak_feed_by_move(job.toolpath.moves.len()))),
            args.per_level,
        )?;
    }
    if let Some(path) = &args.html {
        write_html(path, &job, &plan, &flat, outline)?;
    }
    for w in &job.warnings {
        super::eprint(&format!("warning: {w}"));
    }
    if args.json {
        let mut v =
            serde_json::to_value(report).map_err(|e| Error::internal(format!("report: {e}")))?;
        v["cycle_time_s"] = serde_json::json!(plan.total_time());
        v["machine"] = serde_json::json!(m.name);
        v["pictures"] = serde_json::json!(pictures);
        return super::print_json(&v);
    }
    super::print(&format!(
        "contour: {} segments per pass (outline alone: {}, kurbo {}, asymptotic {:.1}), max deviation {:.3e} mm <= {} mm, {} layers, {} blocks, {} lines, {:.1} s at programmed feed, {:.1} s planned on {}",
        report.segments,
        report.curve.segments,
        report.curve.kurbo_segments,
        report.curve.asymptotic_segments,
        report.max_deviation_mm,
        tol,
        report.layers.len(),
        report.blocks,
        report.lines,
        report.time_at_programmed_feed_s,
        plan.total_time(),
        m.name
    ));
    Ok(())
}

/// Writes the `--html` report: summary, viewer, feed plot and the chordal deviation of each
/// segment of the curve flattened at the tolerance.
fn write_html(
    path: &std::path::Path,
    job: &ContourRun,
    plan: &millpath::motion::Plan,
    flat: &curve::Flattening,
    outline: millpath::geom::Outline,
) -> Result<(), Error> {
    let (report, m, name) = (&job.report, &job.machine, &job.name);
    let tol = job.options.tolerance;
    let mut summary = vec![
        super::html::machine_row(m),
        ("input".to_owned(), name.clone()),
        (
            "segments per pass".to_owned(),
            format!(
                "{} (outline alone {}, kurbo {}, asymptotic {:.1})",
                report.segments,
                report.curve.segments,
                report.curve.kurbo_segments,
                report.curve.asymptotic_segments
            ),
        ),
        (
            "max chordal deviation".to_owned(),
            format!("{:.3e} mm (tolerance {tol} mm)", report.max_deviation_mm),
        ),
        (
            "levels, blocks".to_owned(),
            format!("{}, {}", report.layers.len(), report.blocks),
        ),
        (
            "cycle time".to_owned(),
            format!(
                "{:.2} s planned on {}, {:.2} s at programmed feed",
                plan.total_time(),
                m.name,
                report.time_at_programmed_feed_s
            ),
        ),
    ];
    summary.extend(
        job.warnings
            .iter()
            .map(|w| ("warning".to_owned(), w.to_string())),
    );
    let title = format!("millpath contour {name}");
    let outlines = [outline];
    let mut html = super::html::toolpath_report(&title, summary, &job.toolpath, &outlines, plan)?;
    let per_segment = curve::segment_deviations(&job.curve, flat, 200);
    html.plot(
        "Chordal deviation of each segment of the curve flattened at the tolerance (dense sampling, 200 points per segment)",
        &millpath::report::plots::render_svg(
            &millpath::report::plots::chordal_deviation(&per_segment, tol.max(1e-3)),
            &millpath::report::plots::PlotOptions::default(),
        )?,
    )?;
    super::html::write(path, &html)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use millpath::gcode;

    #[derive(Debug, Parser)]
    struct Cli {
        #[command(flatten)]
        args: Args,
    }

    fn run_with(
        dir: &std::path::Path,
        csv: &str,
        extra: &[&str],
    ) -> (Result<(), Error>, bool, bool) {
        let pts = dir.join("pts.csv");
        std::fs::write(&pts, csv).unwrap();
        let (out, rep) = (dir.join("out.ngc"), dir.join("out.json"));
        let mut argv = vec!["contour".to_owned(), pts.display().to_string()];
        argv.extend(extra.iter().map(|s| (*s).to_owned()));
        argv.extend([
            "-o".into(),
            out.display().to_string(),
            "--report".into(),
            rep.display().to_string(),
        ]);
        let cli = Cli::try_parse_from(argv).unwrap();
        let r = run(&cli.args);
        (r, out.exists(), rep.exists())
    }

    const PAPER: &str = "x,y,group\n60,345,1\n100,325,1\n140,295,1\n180,245,1\n340,205,2\n260,385,2\n140,375,2\n60,345,2\n";

    #[test]
    fn bad_input_exits_2_and_writes_nothing() {
        let cases: [(&str, &[&str], &str); 6] = [
            ("1,2\n3,4\n5,7\n", &[], "at least 4"),
            ("1,2\n3,nan\n5,6\n7,1\n", &[], "pts.csv:2"),
            (
                "0,0\n10,0\n10,0\n10,10\n0,10\n",
                &["--curve", "spline"],
                "pts.csv:3",
            ),
            (PAPER, &["--tolerance", "0"], "tolerance"),
            (PAPER, &["--tool-diameter", "400"], "tool diameter"),
            (
                PAPER,
                &["--tolerance", "0.0001", "--decimals", "3"],
                "decimals",
            ),
        ];
        for (csv, extra, needle) in cases {
            let dir = tempfile::tempdir().unwrap();
            let (r, o, j) = run_with(dir.path(), csv, extra);
            let e = r.unwrap_err();
            assert_eq!(e.exit_code(), 2, "{e}");
            assert!(e.to_string().contains(needle), "{needle}: {e}");
            assert!(!o && !j, "{needle}: output written");
        }
    }

    #[test]
    fn writes_gcode_that_reads_back_and_a_report() {
        let dir = tempfile::tempdir().unwrap();
        let (r, o, j) = run_with(dir.path(), PAPER, &["--tolerance", "0.01", "--arcs"]);
        r.unwrap();
        assert!(o && j);
        let rep: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.json")).unwrap())
                .unwrap();
        for k in ["segments", "max_deviation_mm", "layers", "blocks"] {
            assert!(rep.get(k).is_some(), "{k}");
        }
        assert!(rep["max_deviation_mm"].as_f64().unwrap() <= 0.01);
        let text = std::fs::read_to_string(dir.path().join("out.ngc")).unwrap();
        let (tp, _) = gcode::read_str(&text, gcode::ReaderOptions::default()).unwrap();
        assert_eq!(tp.moves.len(), rep["blocks"].as_u64().unwrap() as usize);
    }
}
