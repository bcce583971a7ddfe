//! `millpath five-axis`: minimum-time five-axis trajectory on the paper's case or a path file,
//! compared with the paper's GA baseline, optionally replanned around a deflection.

use super::print;
use millpath::Error;
use millpath::job::five_axis::{FiveAxisRun, FiveAxisSettings};
use millpath::motion::five_axis::{self, LimitsFile};
use std::path::PathBuf;

/// Arguments of `millpath five-axis`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath five-axis --case paper --json\n  millpath five-axis --case paper --machine xyzac-trt --csv traj.csv --gcode traj.ngc --g93\n  millpath five-axis --case paper --machine xyzbc-trt --gcode traj.mpf --dialect sinumerik --units in\n  millpath five-axis path.csv --limits limits.toml --feed 25 --no-baseline\n\nPath file: a line `# unit: mm` (or `m`), the header `x,y,z,i,j,k`, then one pose per line\n(tool tip, tool axis from the tip towards the spindle, any non-zero length).\nLimits file (TOML, mm, s, rad; every key optional): feed, linear_velocity,\nlinear_acceleration, linear_jerk, rotary_velocity, rotary_acceleration, rotary_jerk,\ntool_length, z1, z2. Flags override the file; the file overrides the paper's limits."
)]
pub struct Args {
    /// Built-in case: `paper` (the paper's quarter circle and deflection).
    #[arg(long, conflicts_with = "path")]
    pub case: Option<String>,
    /// Path file: `# unit: mm|m`, header `x,y,z,i,j,k`, one pose per line.
    pub path: Option<PathBuf>,
    /// Machine kinematics: paper (A head, B table; alias paper-ab), xyzac-trt (alias ac-trt),
    /// xyzbc-trt (alias bc-trt), head-head.
    #[arg(long, default_value = "paper")]
    pub machine: String,
    /// Limits file (TOML; see below).
    #[arg(long)]
    pub limits: Option<PathBuf>,
    /// Tool-tip feed limit, mm/s.
    #[arg(long, allow_negative_numbers = true)]
    pub feed: Option<f64>,
    /// Velocity limit of X, Y, Z, mm/s.
    #[arg(long, allow_negative_numbers = true)]
    pub linear_velocity: Option<f64>,
    /// Acceleration limit of X, Y, Z, mm/s².
    #[arg(long, allow_negative_numbers = true)]
    pub linear_acceleration: Option<f64>,
    /// Jerk limit of X, Y, Z, mm/s³.
    #[arg(long, allow_negative_numbers = true)]
    pub linear_jerk: Option<f64>,
    /// Velocity limit of the rotary axes, rad/s.
    #[arg(long, allow_negative_numbers = true)]
    pub rotary_velocity: Option<f64>,
    /// Acceleration limit of the rotary axes, rad/s².
    #[arg(long, allow_negative_numbers = true)]
    pub rotary_acceleration: Option<f64>,
    /// Jerk limit of the rotary axes, rad/s³.
    #[arg(long, allow_negative_numbers = true)]
    pub rotary_jerk: Option<f64>,
    /// Tool length, mm (paper: l_t; table-table: the tool offset; head-head: pivot to tip).
    #[arg(long, allow_negative_numbers = true)]
    pub tool_length: Option<f64>,
    /// The paper machine's z1 (lower-ground origin to the tool's initial point), mm.
    #[arg(long, allow_negative_numbers = true)]
    pub z1: Option<f64>,
    /// The paper machine's z2 (table pivot to the workpiece origin), mm.
    #[arg(long, allow_negative_numbers = true)]
    pub z2: Option<f64>,
    /// Deflected tool position `x,y,z` in mm (the paper case uses its own example unless
    /// `--no-deflection`).
    #[arg(
        long,
        value_delimiter = ',',
        num_args = 3,
        allow_negative_numbers = true
    )]
    pub deflection: Option<Vec<f64>>,
    /// Skip the deflection replanning of the paper case.
    #[arg(long)]
    pub no_deflection: bool,
    /// Skip the baseline.
    #[arg(long)]
    pub no_baseline: bool,
    /// Add this many poses along the jerk-limited start and stop at each end (0: plan the
    /// poses as given) [default: 3 where the end intervals are at least 4 ramps long, else 0].
    #[arg(long)]
    pub end_knots: Option<usize>,
    /// Shortest interval to plan, s: poses closer than this (at the feed and the joints'
    /// speeds) are merged into one interval where the path stays within 0.005 mm and 1e-4 rad
    /// of them (0: every pose a knot) [default: 0.01].
    #[arg(long)]
    pub min_interval: Option<f64>,
    /// Move each tool axis by at most this many degrees where the path passes near the pole
    /// (the tool along C), so that C does not whip round; where it did is reported
    /// [default: 0, the axes as given].
    #[arg(long, value_name = "DEG")]
    pub tilt_tolerance: Option<f64>,
    /// Print the result as JSON.
    #[arg(long)]
    pub json: bool,
    /// Write sampled t, joints, v, a, j, feed to this CSV file.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Sample step of the CSV, s.
    #[arg(long, default_value_t = 0.005)]
    pub dt: f64,
    /// Write 5-axis G-code (table-table machines only) to this file, in the dialect of
    /// `--dialect` (linuxcnc, fanuc, sinumerik; grbl has no rotary axes).
    #[arg(long)]
    pub gcode: Option<PathBuf>,
    #[command(flatten)]
    pub program: super::output::OutputArgs,
    /// G-code feeds in inverse time (G93, the default): every block takes its planned time on
    /// any control.
    #[arg(long, conflicts_with = "g94")]
    pub g93: bool,
    /// G-code feeds in mm/min (G94) on the XYZ chord of each block (deg/min for rotary-only
    /// blocks), exact on RS274NGC/LinuxCNC-style controls without tool-centre-point control.
    #[arg(long, alias = "no-inverse-time")]
    pub g94: bool,
    /// Write a self-contained HTML report (summary, the feed, velocity, acceleration and jerk
    /// plots, and the deflection plots).
    #[arg(long)]
    pub html: Option<PathBuf>,
}

impl Args {
    /// The five-axis job's settings these flags give.
    fn settings(&self) -> FiveAxisSettings {
        FiveAxisSettings {
            case: self.case.clone(),
            path: self.path.clone(),
            machine: self.machine.clone(),
            limits: self.limits.clone(),
            flags: LimitsFile {
                feed: self.feed,
                linear_velocity: self.linear_velocity,
                linear_acceleration: self.linear_acceleration,
                linear_jerk: self.linear_jerk,
                rotary_velocity: self.rotary_velocity,
                rotary_acceleration: self.rotary_acceleration,
                rotary_jerk: self.rotary_jerk,
                tool_length: self.tool_length,
                z1: self.z1,
                z2: self.z2,
            },
            deflection: self.deflection.clone(),
            no_deflection: self.no_deflection,
            no_baseline: self.no_baseline,
            end_knots: self.end_knots,
            min_interval: self.min_interval,
            tilt_tolerance_deg: self.tilt_tolerance,
            dt: self.dt,
            gcode: self
                .gcode
                .as_ref()
                .map(|_| (self.program.settings(), self.g94)),
        }
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let job = millpath::job::five_axis::run(&args.settings())?;
    let kin = job.kinematics.as_ref();
    if let Some(path) = &args.csv {
        let s = job.samples(args.dt);
        millpath::io::write_atomic_with(path, |w| {
            five_axis::write_csv(w, &s, kin.axis_names())
                .map_err(|e| Error::internal(format!("CSV: {e}")))
        })?;
    }
    if let (Some(path), Some(text)) = (&args.gcode, &job.gcode) {
        millpath::io::write_atomic(path, text)?;
    }
    let r = &job.outcome.result;
    if let Some(path) = &args.html {
        write_html(path, &job)?;
    }
    if args.json {
        print(&serde_json::to_string_pretty(r).map_err(|e| Error::internal(e.to_string()))?);
    } else {
        let mut line = format!("machine {}: {} intervals", r.machine, r.intervals);
        if r.added_poses > 0 {
            line += &format!(", {} poses added along the start and stop", r.added_poses);
        }
        if r.merged_poses > 0 {
            line += &format!(
                ", {} close poses merged into intervals (within {:.4} mm, {:.1e} rad of the plan)",
                r.merged_poses, r.max_merged_tip_deviation_mm, r.max_merged_axis_deviation_rad
            );
        }
        print(&line);
        print(&format!(
            "ours: {:.6} s (computed in {:.3} s), tightest margin {:.2e} ({}), max feed {:.4} mm/s, path deviation {:.4} mm",
            r.total_time_s,
            r.compute_time_s,
            r.tightest_margin,
            r.tightest_constraint,
            r.max_feed_mm_s,
            r.max_path_deviation_mm
        ));
        print(&format!(
            "certified: feed <= {:.6} mm/s over the whole plan (rigorous bound); no interval can be shortened by more than {:.1e} (relative)",
            r.feed_upper_bound_mm_s, r.max_minimality_gap
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
        for w in &r.pole_windows {
            print(&format!(
                "near the pole: poses {}..{} axes moved by at most {:.3} deg (--tilt-tolerance), largest C step {:.1} -> {:.1} deg",
                w.first_pose,
                w.last_pose,
                w.max_axis_change_rad.to_degrees(),
                w.max_c_step_before_rad.to_degrees(),
                w.max_c_step_after_rad.to_degrees()
            ));
        }
        for w in &r.ik_warnings {
            print(&format!("warning: {w}"));
        }
        let near_pole = r.ik_warnings.iter().any(|w| {
            matches!(
                w.warning,
                millpath::machine::kinematics::IkWarning::NearPole { .. }
            )
        });
        let dev = r.max_path_deviation_mm;
        if dev > millpath::job::five_axis::MAX_GCODE_PATH_DEVIATION {
            print(&format!(
                "warning: the planned tool tip strays up to {dev:.4} mm from the path (the joints \
                 move together between poses); no --gcode is written beyond {} mm",
                millpath::job::five_axis::MAX_GCODE_PATH_DEVIATION
            ));
        }
        // C's largest step between knots: a path through the pole keeps C still.
        let c_step = job
            .outcome
            .schedule
            .states
            .windows(2)
            .map(|w| (w[1].q[4] - w[0].q[4]).abs())
            .fold(0.0, f64::max);
        if near_pole && r.pole_windows.is_empty() && c_step > 10f64.to_radians() {
            print(&format!(
                "hint: the path passes beside the pole and C turns up to {:.0}° between knots; \
                 --tilt-tolerance DEG lets the axes move by up to DEG so that it does not",
                c_step.to_degrees()
            ));
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

/// Writes the `--html` report: summary, the feed and axis plots, the deflection plots.
fn write_html(path: &std::path::Path, job: &FiveAxisRun) -> Result<(), Error> {
    let r = &job.outcome.result;
    let mut html = millpath::report::html::HtmlReport::new("millpath five-axis");
    let baseline = r
        .baseline_time_s
        .map_or("not run".to_owned(), |b| format!("{b:.6} s"));
    html.section(
        "summary",
        vec![
            ("machine".to_owned(), r.machine.clone()),
            ("intervals".to_owned(), r.intervals.to_string()),
            ("total time".to_owned(), format!("{:.6} s", r.total_time_s)),
            ("the paper's method (baseline)".to_owned(), baseline),
            (
                "limit violations".to_owned(),
                r.violations.len().to_string(),
            ),
        ],
    );
    let opts = millpath::report::plots::PlotOptions::default();
    for (_, caption, chart) in job.charts() {
        html.plot(
            caption,
            &millpath::report::plots::render_svg(&chart, &opts)?,
        )?;
    }
    super::html::write(path, &html)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: Args,
    }

    /// Runs the command; returns the exit code and the message of the error.
    fn run_with(argv: &[&str]) -> (i32, String) {
        let mut full = vec!["five-axis"];
        full.extend_from_slice(argv);
        let cli = Cli::try_parse_from(full).expect("arguments parse");
        match run(&cli.args) {
            Ok(()) => (0, String::new()),
            Err(e) => (e.exit_code(), e.to_string()),
        }
    }

    fn file(dir: &tempfile::TempDir, name: &str, text: &str) -> String {
        let p = dir.path().join(name);
        std::fs::write(&p, text).expect("write test file");
        p.display().to_string()
    }

    /// Bad input in a path file, a limits file or a flag: exit code 2, naming the value and
    /// where it came from (file and line for path files).
    #[test]
    fn bad_input_is_exit_code_2_naming_value_and_line() {
        let dir = tempfile::tempdir().expect("temp dir");
        let head = "# unit: mm\nx,y,z,i,j,k\n0,0,10,0,0,1\n";
        let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
            (
                vec![file(&dir, "zero.csv", &format!("{head}10,0,10,0,0,0\n"))],
                vec!["zero.csv:4", "tool axis"],
            ),
            (
                vec![file(&dir, "nan.csv", &format!("{head}10,0,NaN,0,0,1\n"))],
                vec!["nan.csv:4", "NaN"],
            ),
            (
                vec![file(&dir, "range.csv", &format!("{head}10,0,10,0,1,0\n"))],
                vec!["range.csv:4", "reachable"],
            ),
            (
                vec!["--case".into(), "paper".into(), "--feed".into(), "0".into()],
                vec!["feed = 0"],
            ),
            (
                vec![
                    "--case".into(),
                    "paper".into(),
                    "--limits".into(),
                    file(&dir, "l.toml", "rotary_jerk = -5\n"),
                ],
                vec!["rotary_jerk = -5", "l.toml"],
            ),
            (
                vec![
                    "--case".into(),
                    "paper".into(),
                    "--machine".into(),
                    "xyz".into(),
                ],
                vec!["machine = xyz"],
            ),
        ];
        for (argv, needles) in cases {
            let argv: Vec<&str> = argv.iter().map(String::as_str).collect();
            let (code, msg) = run_with(&argv);
            assert_eq!(code, 2, "{argv:?}: {msg}");
            for n in needles {
                assert!(msg.contains(n), "{argv:?}: {msg} lacks {n}");
            }
        }
    }

    /// Every machine name (and the G94 G-code of the table-table ones) runs with a custom feed
    /// limit on a path file.
    #[test]
    fn custom_limits_and_machine_aliases_are_used() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = file(
            &dir,
            "p.csv",
            "# unit: mm\nx,y,z,i,j,k\n0,0,10,0,0,1\n5,0,10,0.05,0,1\n10,1,10,0.1,0,1\n",
        );
        let json = dir.path().join("out.ngc").display().to_string();
        for machine in ["paper", "xyzac-trt", "xyzbc-trt", "head-head"] {
            let mut argv = vec![
                path.as_str(),
                "--machine",
                machine,
                "--no-baseline",
                "--feed",
                "10",
            ];
            if machine.contains("trt") {
                argv.extend(["--gcode", json.as_str(), "--g94"]);
            }
            let (code, msg) = run_with(&argv);
            assert_eq!(code, 0, "{machine}: {msg}");
        }
    }
}
