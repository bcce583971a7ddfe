//! `millpath five-axis`: minimum-time five-axis trajectory on the paper's case or a path file,
//! compared with the paper's GA baseline, optionally replanned around a deflection.

use super::{print, read_text};
use millpath::gcode::five_axis::{FiveAxisGcodeOptions, write_five_axis};
use millpath::geom::Point3;
use millpath::machine::kinematics::{HeadHead, Kinematics, PaperAb, TableTable, TrtKind};
use millpath::motion::five_axis::{self, FiveAxisOptions, Limits, case};
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Arguments of `millpath five-axis`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath five-axis --case paper --json\n  millpath five-axis --case paper --machine ac-trt --csv traj.csv --gcode traj.ngc\n  millpath five-axis path.csv --no-baseline"
)]
pub struct Args {
    /// Built-in case: `paper` (the paper's quarter circle and deflection).
    #[arg(long, conflicts_with = "path")]
    pub case: Option<String>,
    /// Path file: `# unit: mm|m`, header `x,y,z,i,j,k`, one pose per line.
    pub path: Option<PathBuf>,
    /// Machine kinematics: paper-ab, ac-trt, bc-trt, head-head (default: paper-ab).
    #[arg(long, default_value = "paper-ab")]
    pub machine: String,
    /// Deflected tool position `x,y,z` in mm (the paper case uses its own example unless
    /// `--no-deflection`).
    #[arg(long, value_delimiter = ',', num_args = 3)]
    pub deflection: Option<Vec<f64>>,
    /// Skip the deflection replanning of the paper case.
    #[arg(long)]
    pub no_deflection: bool,
    /// Skip the baseline.
    #[arg(long)]
    pub no_baseline: bool,
    /// Print the result as JSON.
    #[arg(long)]
    pub json: bool,
    /// Write sampled t, joints, v, a, j, feed to this CSV file.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Sample step of the CSV, s.
    #[arg(long, default_value_t = 0.005)]
    pub dt: f64,
    /// Write 5-axis G-code (table-table machines only) to this file.
    #[arg(long)]
    pub gcode: Option<PathBuf>,
    /// Use G94 units-per-minute feeds instead of G93 inverse time.
    #[arg(long)]
    pub no_inverse_time: bool,
    /// Write a self-contained HTML report (summary and the feed, velocity, acceleration and
    /// jerk plots).
    #[arg(long)]
    pub html: Option<PathBuf>,
}

fn machine(name: &str) -> Result<Box<dyn Kinematics>, Error> {
    Ok(match name {
        "paper-ab" => Box::new(PaperAb::paper()),
        "ac-trt" => Box::new(TableTable::typical(TrtKind::Ac)),
        "bc-trt" => Box::new(TableTable::typical(TrtKind::Bc)),
        "head-head" => Box::new(HeadHead::typical()),
        other => {
            return Err(InputError::new("machine", other)
                .at("--machine")
                .expected("paper-ab, ac-trt, bc-trt or head-head")
                .into());
        }
    })
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let kin = machine(&args.machine)?;
    if args.gcode.is_some() && !matches!(kin.name(), "ac-trt" | "bc-trt") {
        return Err(InputError::new("--machine", kin.name())
            .at("--gcode")
            .expected("ac-trt or bc-trt: five-axis G-code is written for table-table machines")
            .into());
    }
    let (poses, default_deflection) = match (&args.case, &args.path) {
        (Some(c), _) if c == "paper" => (case::paper_path(), Some(case::paper_deflection())),
        (Some(c), _) => {
            return Err(InputError::new("case", c)
                .at("--case")
                .expected("paper")
                .into());
        }
        (None, Some(p)) => (
            case::parse_path_csv(&read_text(p)?, &p.display().to_string())?,
            None,
        ),
        (None, None) => {
            return Err(InputError::new("input", "none")
                .expected("--case paper or a path file")
                .into());
        }
    };
    let deflection = match &args.deflection {
        Some(v) => {
            let [x, y, z] = v.as_slice() else {
                return Err(InputError::new("--deflection", format!("{v:?}"))
                    .expected("x,y,z")
                    .into());
            };
            Some(Point3::new(*x, *y, *z))
        }
        None if args.no_deflection => None,
        None => default_deflection,
    };
    if !(args.dt.is_finite() && args.dt > 0.0) {
        return Err(InputError::new("--dt", args.dt)
            .expected("a finite number > 0 s")
            .into());
    }
    let mut opts = FiveAxisOptions::default();
    if args.no_baseline {
        opts.baseline = None;
    }
    let out = five_axis::plan(kin.as_ref(), &poses, &Limits::paper(), &opts, deflection)?;
    if let Some(path) = &args.csv {
        let s = five_axis::sample(&out.segments, kin.as_ref(), args.dt);
        millpath::io::write_atomic_with(path, |w| {
            five_axis::write_csv(w, &s, kin.axis_names())
                .map_err(|e| Error::internal(format!("CSV: {e}")))
        })?;
    }
    if let Some(path) = &args.gcode {
        let go = FiveAxisGcodeOptions {
            inverse_time: !args.no_inverse_time,
            ..FiveAxisGcodeOptions::default()
        };
        let segs = out.segments.clone();
        millpath::io::write_atomic_with(path, |w| write_five_axis(w, &segs, kin.as_ref(), &go))?;
    }
    let r = &out.result;
    if let Some(path) = &args.html {
        let s = five_axis::sample(&out.segments, kin.as_ref(), 1e-3);
        let mut html = millpath::report::html::HtmlReport::new("millpath five-axis");
        html.section(
            "summary",
            vec![
                ("machine".to_owned(), r.machine.clone()),
                ("intervals".to_owned(), r.intervals.to_string()),
                ("total time".to_owned(), format!("{:.6} s", r.total_time_s)),
                (
                    "the paper's method (baseline)".to_owned(),
                    r.baseline_time_s
                        .map_or("not run".to_owned(), |b| format!("{b:.6} s")),
                ),
                (
                    "limit violations".to_owned(),
                    r.violations.len().to_string(),
                ),
            ],
        );
        for (_, caption, chart) in
            super::html::five_axis_charts(&s, kin.axis_names(), &Limits::paper())
        {
            html.plot(
                caption,
                &millpath::report::plots::render_svg(
                    &chart,
                    &millpath::report::plots::PlotOptions::default(),
                )?,
            )?;
        }
        super::html::write(path, &html)?;
    }
    if args.json {
        print(&serde_json::to_string_pretty(r).map_err(|e| Error::internal(e.to_string()))?);
    } else {
        print(&format!("machine {}: {} intervals", r.machine, r.intervals));
        print(&format!(
            "ours: {:.6} s (computed in {:.3} s), tightest margin {:.2e} ({}), max feed {:.4} mm/s, path deviation {:.4} mm",
            r.total_time_s,
            r.compute_time_s,
            r.tightest_margin,
            r.tightest_constraint,
            r.max_feed_mm_s,
            r.max_path_deviation_mm
        ));
        if let (Some(b), Some(m), Some(ct)) = (
            r.baseline_time_s,
            r.baseline_tightest_margin,
            r.baseline_compute_time_s,
        ) {
            print(&format!(
                "baseline (paper's GA): {b:.6} s (computed in {ct:.3} s), tightest margin {m:.2e}; ratio baseline/ours {:.4}",
                b / r.total_time_s
            ));
        }
        print(&format!(
            "violations: {} (baseline {})",
            r.violations.len(),
            r.baseline_violations.len()
        ));
        if let Some(d) = &r.deflection {
            print(&format!(
                "deflection ({:.3}, {:.3}, {:.3}) mm -> projection ({:.4}, {:.4}, {:.4}) mm at interval {} u={:.4}, distance {:.4} mm; new intervals {:.6} s + {:.6} s; violations {}",
                d.deflection.x,
                d.deflection.y,
                d.deflection.z,
                d.projection.point.x,
                d.projection.point.y,
                d.projection.point.z,
                d.projection.interval + 1,
                d.projection.u,
                d.projection.distance,
                d.times_s[0],
                d.times_s[1],
                r.deflection_violations.len()
            ));
        }
        for w in &r.ik_warnings {
            print(&format!("warning: {w}"));
        }
    }
    if !r.violations.is_empty() {
        return Err(Error::internal(format!(
            "the verifier found {} violations",
            r.violations.len()
        )));
    }
    Ok(())
}
