//! The five-axis job behind `millpath five-axis`: the limits (the paper's, overridden by a
//! limits file, overridden by the flags), the machine's kinematics by name (with the
//! structural overrides: tool length, the paper machine's z1 and z2), the poses of the
//! paper's case or of a path file, each pose checked reachable, the plan
//! ([`crate::motion::five_axis::plan`], verified by dense sampling and the quintics' analytic
//! extrema) and, for table-table machines, the joint program (G93 inverse time or G94).
//! Every setting is checked before planning.

use super::program::ProgramSettings;
use crate::gcode::five_axis::{FeedMode, FiveAxisGcodeOptions, check_five_axis, write_five_axis};
use crate::geom::Point3;
use crate::machine::kinematics::{HeadHead, Kinematics, PaperAb, Pose, TableTable, TrtKind};
use crate::motion::five_axis::case::{self, LimitsFile};
use crate::motion::five_axis::{self as planner, FiveAxisOptions, FiveAxisOutcome, Limits};
use crate::{Error, InputError};
use std::path::PathBuf;

/// The longest `--min-interval`, s: longer intervals would merge whole features.
const MAX_MIN_INTERVAL: f64 = 1.0;

/// Most poses `--end-knots` may add at each end: each is a knot of the plan, and a few
/// already take what they can (four gain the paper's case 0.4 %; beyond eight the iteration
/// converges badly). A number past this is a mistake, not a request for a finer plan.
pub const MAX_END_KNOTS: usize = 64;

/// The farthest the planned tip path may stray from the curve through the given poses for
/// the joint program to be written, mm. Between two poses the joints move together, so the
/// tip leaves the path by a chordal error that grows with the rotary step: 0.022 mm on the
/// paper's case, 0.08 mm on a path tilting 3° per 5 mm about a pivot 100 mm below, and
/// 0.42 mm where C turns fast beside the pole (the tilting sweep 0.5° beside it). Denser
/// poses shorten it; the planner does not add them.
pub const MAX_GCODE_PATH_DEVIATION: f64 = 0.1;

/// A five-axis job's settings, named as `millpath five-axis`'s flags.
#[derive(Debug, Clone)]
pub struct FiveAxisSettings {
    /// Built-in case (`paper`).
    pub case: Option<String>,
    /// Path file (`# unit: mm|m`, header `x,y,z,i,j,k`).
    pub path: Option<PathBuf>,
    /// Machine kinematics by name ([`MACHINES`] and their aliases).
    pub machine: String,
    /// Limits file (TOML).
    pub limits: Option<PathBuf>,
    /// Limits and structural overrides given as flags (over the file's).
    pub flags: LimitsFile,
    /// Deflected tool position `x,y,z`, mm (three values).
    pub deflection: Option<Vec<f64>>,
    /// Skip the case's own deflection.
    pub no_deflection: bool,
    /// Skip the paper's GA baseline.
    pub no_baseline: bool,
    /// Poses added along the jerk-limited ramp at each end
    /// ([`crate::motion::five_axis::FiveAxisOptions::end_knots`]).
    pub end_knots: Option<usize>,
    /// Shortest interval planned, s: closer poses are merged
    /// ([`crate::motion::five_axis::MergeOptions::min_interval_s`]); `None` for its default,
    /// 0 to plan every pose as a knot.
    pub min_interval: Option<f64>,
    /// How far each tool axis may move to pass the pole without C whipping round, degrees
    /// ([`crate::motion::five_axis::FiveAxisOptions::tilt_tolerance`]); `None`: not at all.
    pub tilt_tolerance_deg: Option<f64>,
    /// Sample step of [`FiveAxisRun::samples`], s.
    pub dt: f64,
    /// Write a joint program with these settings; `g94` for feeds in mm/min instead of G93.
    pub gcode: Option<(ProgramSettings, bool)>,
}

impl Default for FiveAxisSettings {
    fn default() -> Self {
        FiveAxisSettings {
            case: None,
            path: None,
            machine: "paper".into(),
            limits: None,
            flags: LimitsFile::default(),
            deflection: None,
            no_deflection: false,
            no_baseline: false,
            end_knots: None,
            min_interval: None,
            tilt_tolerance_deg: None,
            dt: 0.005,
            gcode: None,
        }
    }
}

/// What a five-axis job made.
pub struct FiveAxisRun {
    /// The machine.
    pub kinematics: Box<dyn Kinematics>,
    /// The limits planned with.
    pub limits: Limits,
    /// The plan, its verification and the baseline.
    pub outcome: FiveAxisOutcome,
    /// The joint program, when asked for.
    pub gcode: Option<Vec<u8>>,
}

impl std::fmt::Debug for FiveAxisRun {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FiveAxisRun")
            .field("kinematics", &self.kinematics.name())
            .field("limits", &self.limits)
            .field("result", &self.outcome.result)
            .field("gcode_bytes", &self.gcode.as_ref().map(Vec::len))
            .finish_non_exhaustive()
    }
}

impl FiveAxisRun {
    /// The plan sampled every `dt` s.
    pub fn samples(&self, dt: f64) -> planner::Samples {
        planner::sample(&self.outcome.segments, self.kinematics.as_ref(), dt)
    }

    /// The feed and per-axis charts, then (with a deflection) the replanning's:
    /// `(file stem, caption, chart)`, the axes sampled every millisecond.
    pub fn charts(&self) -> Vec<(&'static str, String, crate::report::plots::Chart)> {
        use crate::report::five_axis_plots::{axis_charts, deflection_charts};
        let kin = self.kinematics.as_ref();
        let mut charts = axis_charts(&self.samples(1e-3), kin.axis_names(), &self.limits);
        if let Some(d) = &self.outcome.result.deflection {
            let tips: Vec<_> = self.outcome.poses.iter().map(|p| p.tip).collect();
            let curve = planner::RefCurve::through(&tips);
            let segs = &self.outcome.segments;
            charts.extend(deflection_charts(kin, &curve, segs, d, &self.limits));
        }
        charts
    }
}

/// The limits and structural overrides: the paper's limits, then the file, then the flags.
fn overrides(s: &FiveAxisSettings) -> Result<LimitsFile, Error> {
    let file = match &s.limits {
        Some(p) => LimitsFile::parse(&crate::io::read_text(p)?, &p.display().to_string())?,
        None => LimitsFile::default(),
    };
    s.flags.validate("command-line flags")?;
    Ok(file.overridden_by(&s.flags))
}

/// The G-code options, checked before planning: a dialect without rotary axes, bad
/// decimals or spindle are refused at once.
fn gcode_options(
    kin: &dyn Kinematics,
    program: &ProgramSettings,
    g94: bool,
) -> Result<FiveAxisGcodeOptions, Error> {
    if !matches!(kin.name(), "ac-trt" | "bc-trt") {
        return Err(InputError::new("--machine", kin.name())
            .at("--gcode")
            .expected(
                "xyzac-trt or xyzbc-trt: five-axis G-code is written for table-table machines",
            )
            .into());
    }
    let decimals = program
        .decimals
        .unwrap_or_else(|| program.dialect.default_decimals(program.units) + 1);
    let go = FiveAxisGcodeOptions {
        feed_mode: if g94 {
            FeedMode::UnitsPerMinute
        } else {
            FeedMode::InverseTime
        },
        program: program.writer_options(decimals, format!("millpath five-axis {}", kin.name()))?,
        ..FiveAxisGcodeOptions::default()
    };
    check_five_axis(kin, &go)?;
    Ok(go)
}

/// Runs the five-axis job: settings checked, poses read, planned, the program written.
pub fn run(s: &FiveAxisSettings) -> Result<FiveAxisRun, Error> {
    let over = overrides(s)?;
    let limits = over.apply(&Limits::paper());
    limits.validate("limits")?;
    let kin = kinematics(&s.machine, &over)?;
    let gcode = match &s.gcode {
        Some((program, g94)) => Some(gcode_options(kin.as_ref(), program, *g94)?),
        None => None,
    };
    let text = match &s.path {
        Some(p) if s.case.is_none() => Some((crate::io::read_text(p)?, p.display().to_string())),
        _ => None,
    };
    let path = text.as_ref().map(|(t, n)| (t.as_str(), n.as_str()));
    let (poses, default_deflection) = poses(s.case.as_deref(), path, kin.as_ref())?;
    let deflection = match &s.deflection {
        Some(v) => {
            let [x, y, z] = v.as_slice() else {
                return Err(InputError::new("--deflection", format!("{v:?}"))
                    .expected("x,y,z")
                    .into());
            };
            Some(Point3::new(*x, *y, *z))
        }
        None if s.no_deflection => None,
        None => default_deflection,
    };
    if !(s.dt.is_finite() && s.dt > 0.0) {
        return Err(InputError::new("--dt", s.dt)
            .expected("a finite number > 0 s")
            .into());
    }
    if let Some(k) = s.end_knots
        && k > MAX_END_KNOTS
    {
        return Err(InputError::new("--end-knots", k)
            .expected(format!(
                "at most {MAX_END_KNOTS} poses added at each end (4 helps the paper's case)"
            ))
            .into());
    }
    let mut opts = FiveAxisOptions::default();
    if s.no_baseline {
        opts.baseline = None;
    }
    opts.end_knots = s.end_knots;
    if let Some(t) = s.min_interval {
        if !(t.is_finite() && (0.0..=MAX_MIN_INTERVAL).contains(&t)) {
            return Err(InputError::new("--min-interval", t)
                .expected(format!(
                    "a time from 0 (every pose a knot) to {MAX_MIN_INTERVAL} s"
                ))
                .into());
        }
        opts.merge.min_interval_s = t;
    }
    if let Some(t) = s.tilt_tolerance_deg {
        let max = planner::MAX_TILT_TOLERANCE.to_degrees();
        if !(t.is_finite() && (0.0..=max).contains(&t)) {
            return Err(InputError::new("--tilt-tolerance", t)
                .expected(format!(
                    "an angle from 0 (the axes as given) to {max:.0} degrees"
                ))
                .into());
        }
        opts.tilt_tolerance = t.to_radians();
    }
    let outcome = planner::plan(kin.as_ref(), &poses, &limits, &opts, deflection)?;
    let gcode = match gcode {
        Some(go) => {
            let dev = outcome.result.max_path_deviation_mm;
            if dev.is_nan() || dev > MAX_GCODE_PATH_DEVIATION {
                return Err(InputError::new(
                    "path",
                    format!("the planned tool tip {dev:.4} mm from it"),
                )
                .at("--gcode")
                .expected(format!(
                    "poses close enough that the joints' motion between them keeps the tip \
                     within {MAX_GCODE_PATH_DEVIATION} mm of the path: where C turns fast \
                     beside the pole, --tilt-tolerance DEG; else denser poses"
                ))
                .into());
            }
            let mut buf = Vec::new();
            write_five_axis(&mut buf, &outcome.segments, kin.as_ref(), &go)?;
            Some(buf)
        }
        None => None,
    };
    Ok(FiveAxisRun {
        kinematics: kin,
        limits,
        outcome,
        gcode,
    })
}

/// The machines [`kinematics`] takes.
pub const MACHINES: &[&str] = &["paper", "xyzac-trt", "xyzbc-trt", "head-head"];

/// The machine named `name` with the given structural overrides.
pub fn kinematics(name: &str, over: &LimitsFile) -> Result<Box<dyn Kinematics>, Error> {
    let only_paper = |key: &str, v: Option<f64>| -> Result<(), Error> {
        match v {
            Some(v) => Err(InputError::new(key, v)
                .at(format!("--machine {name}"))
                .expected(format!("{key} only with --machine paper"))
                .into()),
            None => Ok(()),
        }
    };
    Ok(match name {
        "paper" | "paper-ab" => {
            let mut m = PaperAb::paper();
            m.tool_length = over.tool_length.unwrap_or(m.tool_length);
            m.z1 = over.z1.unwrap_or(m.z1);
            m.z2 = over.z2.unwrap_or(m.z2);
            Box::new(m)
        }
        "xyzac-trt" | "ac-trt" | "xyzbc-trt" | "bc-trt" => {
            only_paper("z1", over.z1)?;
            only_paper("z2", over.z2)?;
            let kind = if name.contains("ac") {
                TrtKind::Ac
            } else {
                TrtKind::Bc
            };
            let mut m = TableTable::typical(kind);
            m.tool_offset = over.tool_length.unwrap_or(m.tool_offset);
            Box::new(m)
        }
        "head-head" => {
            only_paper("z1", over.z1)?;
            only_paper("z2", over.z2)?;
            let mut m = HeadHead::typical();
            m.length = over.tool_length.unwrap_or(m.length);
            Box::new(m)
        }
        other => {
            return Err(InputError::new("machine", other)
                .at("--machine")
                .expected("paper, xyzac-trt, xyzbc-trt or head-head")
                .into());
        }
    })
}

/// The poses to plan: `case` (only `paper`) or a path file's text `(text, name)`, each pose
/// checked reachable on `kin` (the error names its line); with the case's default deflection.
pub fn poses(
    case_name: Option<&str>,
    path: Option<(&str, &str)>,
    kin: &dyn Kinematics,
) -> Result<(Vec<Pose>, Option<Point3>), Error> {
    match (case_name, path) {
        (Some("paper"), _) => Ok((case::paper_path(), Some(case::paper_deflection()))),
        (Some(c), _) => Err(InputError::new("case", c)
            .at("--case")
            .expected("paper")
            .into()),
        (None, Some((text, name))) => {
            let lines = case::parse_path_csv_lines(text, name)?;
            // Every pose must be reachable: name its line.
            for (line, pose) in &lines {
                kin.inverse(pose)
                    .map_err(|e| e.at(format!("{name}:{line}")))?;
            }
            Ok((lines.into_iter().map(|(_, p)| p).collect(), None))
        }
        (None, None) => Err(InputError::new("input", "none")
            .expected("--case paper or a path file")
            .into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gcode::five_axis::read_five_axis;

    fn settings(machine: &str) -> FiveAxisSettings {
        FiveAxisSettings {
            case: Some("paper".into()),
            machine: machine.into(),
            no_baseline: true,
            ..FiveAxisSettings::default()
        }
    }

    /// The paper's case on a table-table machine: the verifier finds no violation, and the
    /// G93 program read back takes the plan's time block by block.
    #[test]
    fn paper_case_program_takes_the_planned_time() {
        let s = FiveAxisSettings {
            gcode: Some((ProgramSettings::default(), false)),
            no_deflection: true,
            ..settings("xyzac-trt")
        };
        let job = run(&s).unwrap();
        let r = &job.outcome.result;
        assert!(r.violations.is_empty(), "{:?}", r.violations);
        assert!(r.baseline_time_s.is_none() && r.deflection.is_none());
        let text = String::from_utf8(job.gcode.clone().unwrap()).unwrap();
        let names = job.kinematics.axis_names();
        let blocks = read_five_axis(&text, crate::gcode::Dialect::LinuxCnc, names, "t").unwrap();
        let secs: f64 = blocks.iter().filter(|b| !b.rapid).map(|b| b.seconds).sum();
        assert!(
            (secs - r.total_time_s).abs() < 1e-3 * r.total_time_s,
            "{secs} vs {}",
            r.total_time_s
        );
        let samples = job.samples(0.01);
        assert!((samples.t.last().unwrap() - r.total_time_s).abs() < 1e-9);
        assert_eq!(job.charts().len(), 4);
    }

    /// The paper machine with its deflection: the replanning's charts follow the axis
    /// charts, and the replanned intervals pass the verifier too.
    #[test]
    fn paper_case_with_its_deflection() {
        let job = run(&settings("paper")).unwrap();
        let r = &job.outcome.result;
        assert!(r.violations.is_empty() && r.deflection_violations.is_empty());
        assert!(r.deflection.is_some());
        assert_eq!(job.charts().len(), 4 + 5);
    }

    #[test]
    fn bad_settings_name_their_flag_before_planning() {
        let cases: [(FiveAxisSettings, &str); 5] = [
            (
                FiveAxisSettings {
                    gcode: Some((ProgramSettings::default(), false)),
                    ..settings("paper")
                },
                "--gcode",
            ),
            (
                FiveAxisSettings {
                    dt: 0.0,
                    ..settings("paper")
                },
                "--dt",
            ),
            (
                FiveAxisSettings {
                    deflection: Some(vec![1.0, 2.0]),
                    ..settings("paper")
                },
                "--deflection",
            ),
            (
                FiveAxisSettings {
                    flags: LimitsFile {
                        feed: Some(0.0),
                        ..LimitsFile::default()
                    },
                    ..settings("paper")
                },
                "feed = 0",
            ),
            (
                FiveAxisSettings {
                    case: Some("other".into()),
                    ..settings("paper")
                },
                "--case",
            ),
        ];
        for (s, needle) in cases {
            let e = run(&s).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{e}");
            assert!(e.to_string().contains(needle), "{needle}: {e}");
        }
    }
}
