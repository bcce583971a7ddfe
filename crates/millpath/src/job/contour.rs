//! The contour job behind `millpath contour`: points (CSV/JSON text) or the paper's die
//! cavity → closed curve → exact cutter offset → layers → program text, with the tolerance
//! budget: chord deviation + rounding of the written coordinates ≤ the tolerance, the
//! decimals raised until the rounding ρ = ½·10^−d (mm or inch) leaves room for the chord
//! (T > 2ρ), and the program timed on the machine with the path tolerance the program states.

use super::program::ProgramSettings;
use crate::curve::Flattening;
use crate::curve::flatten::flatten_curve;
use crate::curve::{self, CompositeCurve, CurveKind};
use crate::gcode;
use crate::geom::Outline;
use crate::machine::Machine;
use crate::motion::{Plan, plan_toolpath};
use crate::strategy::contour::{self, ContourOptions, ContourReport, ContourWarning, Side};
use crate::{Error, InputError, Tool, Toolpath};

/// A contour job's settings, named and defaulted as `millpath contour`'s flags (`None`: the
/// sample's or the engine's default).
#[derive(Debug, Clone, PartialEq)]
pub struct ContourSettings {
    /// Tool diameter, mm.
    pub tool_diameter: Option<f64>,
    /// Path tolerance, mm (chord deviation + output rounding).
    pub tolerance: Option<f64>,
    /// Side of the outline the tool runs on.
    pub side: Side,
    /// Depth below the top, mm.
    pub depth: Option<f64>,
    /// Step-down per roughing layer, mm.
    pub step_down: Option<f64>,
    /// Radial stock left by roughing, mm.
    pub finish_allowance: f64,
    /// Curve through the points.
    pub curve: CurveKind,
    /// Biarcs (G2/G3) instead of lines.
    pub arcs: bool,
    /// Cutting feed, mm/min.
    pub feed: f64,
    /// Plunge feed, mm/min.
    pub plunge_feed: f64,
    /// Safe height above the top for rapids, mm.
    pub safe_height: f64,
    /// Clearance height above the top where feeding down starts, mm.
    pub clearance_height: f64,
    /// Lead-in/lead-out arc radius, mm (0: none).
    pub lead_radius: f64,
    /// Machine for the cycle time: a preset name or a TOML profile.
    pub machine: String,
}

impl Default for ContourSettings {
    fn default() -> Self {
        ContourSettings {
            tool_diameter: None,
            tolerance: None,
            side: Side::Inside,
            depth: None,
            step_down: None,
            finish_allowance: 0.2,
            curve: CurveKind::FourPoint,
            arcs: false,
            feed: 1000.0,
            plunge_feed: 300.0,
            safe_height: 10.0,
            clearance_height: 2.0,
            lead_radius: 2.0,
            machine: "hsm".into(),
        }
    }
}

/// Where the contour's points come from.
#[derive(Debug, Clone, Copy)]
pub enum ContourSource<'a> {
    /// A points file's text (CSV or JSON) and its name.
    Points {
        /// The text.
        text: &'a str,
        /// The name in messages.
        name: &'a str,
    },
    /// The paper's die cavity, with its options as the defaults.
    Sample,
}

/// What a contour job made.
#[derive(Debug)]
pub struct ContourRun {
    /// The program text, as written to the `-o` file.
    pub gcode: String,
    /// The report (`--report`), with the written program's blocks, lines and decimals.
    pub report: ContourReport,
    /// The toolpath.
    pub toolpath: Toolpath,
    /// The curve through the points.
    pub curve: CompositeCurve,
    /// The options the contour was cut with.
    pub options: ContourOptions,
    /// The machine the program is timed on, with the path tolerance it states.
    pub machine: Machine,
    /// The input's name (`paper sample` for the sample).
    pub name: String,
    /// Warnings of the contour strategy.
    pub warnings: Vec<ContourWarning>,
}

impl ContourRun {
    /// The program's plan on the machine it states ([`ContourRun::machine`]).
    pub fn plan(&self) -> Result<Plan, Error> {
        plan_toolpath(&self.toolpath, &self.machine)
            .map_err(|e| e.engine_made("timing the contour toolpath"))
    }

    /// The curve flattened at the tolerance, at least 0.001 mm (what a picture or a plot of
    /// the per-segment deviation needs), and that flattening as an outline named after the
    /// input.
    pub fn outline(&self) -> Result<(Flattening, Outline), Error> {
        let flat = flatten_curve(&self.curve, self.options.tolerance.max(1e-3))?;
        let outline = Outline::from_points(&flat.points, &self.name)?;
        Ok((flat, outline))
    }
}

/// The machine a contour program is timed on: `machine` with the path tolerance the
/// program states, the machine's or the contour's tolerance `t` where that is tighter (a
/// controller blending corners by more than `t` would cut outside the contour's budget, and
/// LinuxCNC's `G64 P` also merges short segments within it); `t` where the machine states
/// none (path tolerance 0, as the `linuxcnc-time` preset: the controller's own default,
/// which on LinuxCNC blends without a limit).
pub fn program_machine(machine: &Machine, t: f64) -> Machine {
    let path_tolerance = if machine.path_tolerance > 0.0 {
        t.min(machine.path_tolerance)
    } else {
        t
    };
    Machine {
        path_tolerance,
        ..machine.clone()
    }
}

fn input(what: &str, v: impl std::fmt::Display, flag: &str, expected: &str) -> Error {
    InputError::new(what, v).at(flag).expected(expected).into()
}

/// Runs the contour pipeline on `source` with `settings`, written as `program` says.
pub fn run(
    source: ContourSource<'_>,
    settings: &ContourSettings,
    program: &ProgramSettings,
) -> Result<ContourRun, Error> {
    let args = settings;
    let machine = super::load_machine(&args.machine)?;
    let (curve, mut opt, name) = match source {
        ContourSource::Points { text, name } => {
            let mut groups = crate::io::points::parse(text, name)?;
            if args.curve == CurveKind::FourPoint {
                groups = crate::io::points::regroup_for_four_point(groups);
            }
            (
                curve::build(&groups, args.curve, name)?,
                ContourOptions::default(),
                name.to_owned(),
            )
        }
        ContourSource::Sample => {
            let (c, o) = contour::sample()?;
            (c, o, "paper sample".to_owned())
        }
    };
    if let Some(d) = args.tool_diameter {
        if !(d.is_finite() && d > 0.0) {
            return Err(input(
                "tool diameter",
                d,
                "--tool-diameter",
                "a finite number > 0 mm",
            ));
        }
        opt.tool = Tool {
            diameter: d,
            flute_length: opt.tool.flute_length.max(3.0 * d),
            ..opt.tool
        };
    }
    if let Some(t) = args.tolerance {
        if !(t.is_finite() && t > 0.0) {
            return Err(input(
                "tolerance",
                t,
                "--tolerance",
                "a finite number > 0 mm",
            ));
        }
        opt.tolerance = t;
    }
    // Checked here so the error names the flag (ContourOptions::validate can only say
    // "contour options").
    let max = crate::geom::MAX_COORDINATE_MM;
    if let Some(d) = args.depth {
        if !(d.is_finite() && d > 0.0 && d <= max) {
            return Err(input(
                "depth",
                d,
                "--depth",
                &format!("a finite number > 0 mm and at most {max} mm"),
            ));
        }
        opt.depth = d;
    }
    if let Some(s) = args.step_down {
        if !(s.is_finite() && s > 0.0) {
            return Err(input(
                "step-down",
                s,
                "--step-down",
                "a finite number > 0 mm",
            ));
        }
        opt.step_down = s;
    }
    opt.side = args.side;
    opt.finish_allowance = args.finish_allowance;
    opt.arcs = args.arcs;
    for (what, v, flag) in [
        ("feed", args.feed, "--feed"),
        ("plunge feed", args.plunge_feed, "--plunge-feed"),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(input(what, v, flag, "a finite number > 0 mm/min"));
        }
    }
    opt.feed = args.feed / 60.0;
    opt.plunge_feed = args.plunge_feed / 60.0;
    opt.safe_height = args.safe_height;
    opt.clearance_height = args.clearance_height;
    opt.lead_radius = args.lead_radius;
    let decimals = budget_decimals(&mut opt, program)?;
    let result = contour::contour(&curve, &opt)?;
    let machine = program_machine(&machine, opt.tolerance);
    // The settings carry the user's decimals, spindle and tool number: refused as input
    // there; what the writer refuses after that is in the toolpath the engine made.
    let mut wopt = program
        .writer_options(decimals, format!("millpath contour {name}"))?
        .with_header_notes(vec![format!(
            "tolerance {} mm = chord {:.3e} + rounding {:.3e}; {} segments per pass",
            opt.tolerance,
            opt.chord_tolerance(1.0),
            opt.rounding,
            result.report.segments
        )]);
    // The tolerance alone, at the user's decimals (`with_path_tolerance` would add some).
    wopt.path_tolerance = Some(machine.path_tolerance);
    let (text, summary) = gcode::write_to_string(&result.toolpath, &wopt)
        .map_err(|e| e.engine_made("writing the contour program"))?;
    let mut report = result.report.clone();
    report.blocks = summary.blocks;
    report.lines = summary.lines;
    report.decimals = summary.decimals;
    Ok(ContourRun {
        gcode: text,
        report,
        toolpath: result.toolpath,
        curve,
        options: opt,
        machine,
        name,
        warnings: result.warnings,
    })
}

/// The tolerance budget: the decimals to write (the given ones if their rounding leaves
/// room for the chord, else refused; by default the fewest that do, at least the
/// dialect's), with `opt.rounding` set to their rounding.
fn budget_decimals(opt: &mut ContourOptions, program: &ProgramSettings) -> Result<u32, Error> {
    let decimals = match program.decimals {
        Some(d) => {
            let rho = gcode::rounding_error_mm(d, program.units);
            if opt.tolerance <= 2.0 * rho {
                return Err(input(
                    "decimals",
                    d,
                    "--decimals",
                    &format!(
                        "enough decimals to hold --tolerance {} mm: {d} decimals round by up to {rho:.3e} mm; use at least {}",
                        opt.tolerance,
                        gcode::required_decimals(opt.tolerance, program.units)
                    ),
                ));
            }
            d
        }
        None => gcode::required_decimals(opt.tolerance, program.units)
            .max(program.dialect.default_decimals(program.units)),
    };
    opt.rounding = gcode::rounding_error_mm(decimals, program.units);
    if opt.tolerance <= 2.0 * opt.rounding {
        return Err(input(
            "tolerance",
            opt.tolerance,
            "--tolerance",
            &format!(
                "a tolerance the G-code can hold: even {decimals} decimals round by {:.3e} mm",
                opt.rounding
            ),
        ));
    }
    Ok(decimals)
}

/// The side named `inside`, `outside` or `on`.
pub fn parse_side(s: &str) -> Result<Side, InputError> {
    match s {
        "inside" => Ok(Side::Inside),
        "outside" => Ok(Side::Outside),
        "on" => Ok(Side::On),
        _ => Err(InputError::new("side", s)
            .at("--side")
            .expected("inside, outside or on")),
    }
}

/// The curve named `four-point`, `catmull-rom` or `spline`.
pub fn parse_curve(s: &str) -> Result<CurveKind, InputError> {
    match s {
        "four-point" => Ok(CurveKind::FourPoint),
        "catmull-rom" => Ok(CurveKind::CatmullRom),
        "spline" => Ok(CurveKind::Spline),
        _ => Err(InputError::new("curve", s)
            .at("--curve")
            .expected("four-point, catmull-rom or spline")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::verify::{chordal_deviation, segment_deviations};
    use crate::motion::verify::{VerifyOptions, verify_plan};

    const PAPER: &str = "x,y,group\n60,345,1\n100,325,1\n140,295,1\n180,245,1\n340,205,2\n260,385,2\n140,375,2\n60,345,2\n";

    fn paper_run(tolerance: f64, program: &ProgramSettings) -> Result<ContourRun, Error> {
        let settings = ContourSettings {
            tolerance: Some(tolerance),
            ..ContourSettings::default()
        };
        let source = ContourSource::Points {
            text: PAPER,
            name: "paper.csv",
        };
        run(source, &settings, program)
    }

    #[test]
    fn program_reads_back_and_its_plan_passes_the_verifier() {
        let job = paper_run(0.01, &ProgramSettings::default()).unwrap();
        let (tp, _) = gcode::read_str(&job.gcode, gcode::ReaderOptions::default()).unwrap();
        assert_eq!(tp.moves.len(), job.report.blocks);
        // The budget: rounding of the decimals written plus the chord within the tolerance.
        let rho = gcode::rounding_error_mm(job.report.decimals, gcode::Units::Mm);
        assert!(
            job.report.max_deviation_mm + rho <= 0.01,
            "{:?}",
            job.report
        );
        assert!(job.machine.path_tolerance <= 0.01);
        let plan = job.plan().unwrap();
        let moves: Vec<_> = job.toolpath.segments().map(|(f, m)| (f, *m)).collect();
        let v = verify_plan(&plan, &moves, &job.machine, &VerifyOptions::default()).unwrap();
        assert_eq!(v.violations, 0);
        assert!(plan.total_time() >= job.report.time_at_programmed_feed_s);
    }

    #[test]
    fn outline_segments_stay_within_the_tolerance() {
        let job = paper_run(0.01, &ProgramSettings::default()).unwrap();
        let (flat, outline) = job.outline().unwrap();
        let per = segment_deviations(&job.curve, &flat, 200);
        assert_eq!(per.len(), flat.points.len() - 1);
        let worst = per.iter().copied().fold(0.0, f64::max);
        assert!(worst <= 0.01 && worst > 0.0, "{worst}");
        let whole = chordal_deviation(&job.curve, &flat.params, &flat.points, 200);
        assert!((worst - whole).abs() <= 1e-12, "{worst} vs {whole}");
        assert!(outline.signed_area().abs() > 1000.0);
    }

    #[test]
    fn too_few_decimals_for_the_tolerance_name_the_flag() {
        let program = ProgramSettings {
            decimals: Some(3),
            ..ProgramSettings::default()
        };
        let e = paper_run(0.0001, &program).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--decimals"), "{e}");
        let e = paper_run(-1.0, &ProgramSettings::default()).unwrap_err();
        assert!(e.to_string().contains("--tolerance"), "{e}");
    }
}
