//! The hole job behind `millpath drill`: settings as the command's flags give them → checked
//! hole options → the drawing's circles found and selected (`strategy::drill`) → drilled
//! with canned cycles, helix-bored or left out, in a short order → the program text → read
//! back and checked hole by hole (`stock::verify_holes`: a program that cuts outside a
//! hole, misses one or rapids through material is not given out) → its cycle time read
//! back from that text → the report. Each refusal names the flag it came from.
//!
//! ```text
//! let run = job::drill::run("plate.dxf", &DrillSettings::default(),
//!                           &ProgramSettings::default(), &mut |_| {})?;
//! run.gcode        // the bytes `millpath drill … -o` writes
//! run.report       // the JSON of `--report`
//! ```

use super::program::{ProgramSettings, program_time};
use crate::gcode::{Reader, ReaderOptions, WriterOptions, write_program};
use crate::geom::Point3;
use crate::io::ImportSettings;
use crate::machine::Machine;
use crate::stock::{HoleVerification, verify_holes};
use crate::strategy::drill::{
    self, DrillCycle, Hole, HoleOp, HoleOptions, HoleResult, find_holes, select_holes,
};
use crate::strategy::pocket::Direction;
use crate::toolpath::{CycleRetract, Move, Tool};
use crate::{Error, InputError};
use serde::Serialize;
use std::io::BufReader;

/// A hole job's settings, named and defaulted as `millpath drill`'s flags.
#[derive(Debug, Clone, PartialEq)]
pub struct DrillSettings {
    /// How a DXF or SVG drawing is read (`--layer`, …).
    pub import: ImportSettings,
    /// Tool diameter, mm.
    pub tool_diameter: f64,
    /// Hole depth below the top (Z 0), mm.
    pub depth: f64,
    /// Through holes: the break-through is added below the depth.
    pub through: bool,
    /// How far a through hole goes below the depth, mm.
    pub breakthrough: f64,
    /// Only circles at least this large, mm.
    pub min_diameter: Option<f64>,
    /// Only circles at most this large, mm.
    pub max_diameter: Option<f64>,
    /// Peck drilling (G83) with pecks of at most this, mm.
    pub peck: Option<f64>,
    /// Chip-breaking drilling (G73) with pecks of at most this, mm.
    pub chip_break: Option<f64>,
    /// A dwell at the bottom (G82), s.
    pub dwell: Option<f64>,
    /// The R plane above the top: where feeding starts and pecks retract to, mm.
    pub retract: f64,
    /// Travel height above the top between holes, mm.
    pub clearance_height: f64,
    /// Stay at the R plane between drilled holes (G99) instead of the clearance height.
    pub stay_at_retract: bool,
    /// Drilling feed: mm/min (`200`) or in/min (`8ipm`).
    pub feed: String,
    /// Boring feed (helix and circles): mm/min or in/min.
    pub bore_feed: String,
    /// Helix descent per turn, mm.
    pub pitch: f64,
    /// Bore conventional (clockwise) instead of climb.
    pub conventional: bool,
    /// Largest distance between a wide hole's helix rings, a fraction of the tool diameter.
    pub stepover: f64,
    /// Stock the helix leaves on the wall for the finishing circle, mm.
    pub finish_allowance: f64,
    /// Largest distance between a drawn outline and a circle for it to be a hole, mm.
    pub tolerance: f64,
    /// A hole within this of the tool's diameter is drilled, and every hole is checked to
    /// it (centre, diameter), mm.
    pub diameter_tolerance: f64,
    /// Drill only: holes larger than the tool are left out rather than bored.
    pub drill_only: bool,
    /// Machine for the cycle time: a preset name or a TOML machine profile.
    pub machine: String,
}

impl Default for DrillSettings {
    fn default() -> Self {
        DrillSettings {
            import: ImportSettings::default(),
            tool_diameter: 6.0,
            depth: 10.0,
            through: false,
            breakthrough: 1.0,
            min_diameter: None,
            max_diameter: None,
            peck: None,
            chip_break: None,
            dwell: None,
            retract: 1.0,
            clearance_height: 5.0,
            stay_at_retract: false,
            feed: "200".into(),
            bore_feed: "800".into(),
            pitch: 1.0,
            conventional: false,
            stepover: 0.5,
            finish_allowance: 0.1,
            tolerance: crate::geom::CIRCLE_TOLERANCE,
            diameter_tolerance: crate::geom::CIRCLE_TOLERANCE,
            drill_only: false,
            machine: "hsm".into(),
        }
    }
}

impl DrillSettings {
    /// The tool and the hole options, each setting checked with its flag named.
    pub fn options(&self) -> Result<(Tool, HoleOptions), Error> {
        let tool = Tool::flat(self.tool_diameter).map_err(|e| e.at("--tool-diameter"))?;
        let cycle = match (self.peck, self.chip_break, self.dwell) {
            (None, None, None) => DrillCycle::Drill,
            (Some(step), None, None) => DrillCycle::Peck { step },
            (None, Some(step), None) => DrillCycle::ChipBreak { step },
            (None, None, Some(seconds)) => DrillCycle::Dwell { seconds },
            _ => {
                return Err(InputError::new("drilling cycle", "more than one")
                    .at("--peck / --chip-break / --dwell")
                    .expected("at most one of --peck, --chip-break and --dwell")
                    .into());
            }
        };
        if !(self.breakthrough.is_finite() && self.breakthrough >= 0.0) {
            return Err(InputError::new("break-through", self.breakthrough)
                .at("--breakthrough")
                .expected("a length >= 0 mm")
                .into());
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance <= 1.0) {
            return Err(InputError::new("circle tolerance", self.tolerance)
                .at("--tolerance")
                .expected("a length in (0, 1] mm")
                .into());
        }
        let depth = self.depth + if self.through { self.breakthrough } else { 0.0 };
        let drill_feed = super::pocket::parse_feed(&self.feed)?;
        let bore_feed =
            super::pocket::parse_feed(&self.bore_feed).map_err(|e| e.at("--bore-feed"))?;
        let opts = HoleOptions::default()
            .with_depth(depth)
            .with_retract_height(self.retract)
            .with_clearance_height(self.clearance_height)
            .with_retract(if self.stay_at_retract {
                CycleRetract::R
            } else {
                CycleRetract::Initial
            })
            .with_cycle(cycle)
            .with_drill_feed(drill_feed)
            .with_bore_feed(bore_feed)
            .with_pitch(self.pitch)
            .with_direction(if self.conventional {
                Direction::Conventional
            } else {
                Direction::Climb
            })
            .with_stepover(self.stepover)
            .with_finish_allowance(self.finish_allowance)
            .with_diameter_tolerance(self.diameter_tolerance)
            .with_drill_only(self.drill_only);
        if !self.depth.is_finite() || self.depth <= 0.0 {
            return Err(InputError::new("depth", self.depth)
                .at("--depth")
                .expected("a length > 0 mm")
                .into());
        }
        opts.validate(&tool)?;
        Ok((tool, opts))
    }

    /// The checks made before the drawing is read: the settings, the machine and the output
    /// settings.
    pub fn check_before_loading(&self, program: &ProgramSettings) -> Result<(), Error> {
        self.options()?;
        program_options(&super::load_machine(&self.machine)?, program, self)?;
        Ok(())
    }
}

/// How the program is written: the dialect, units, tool, spindle and coolant of `out`, the
/// machine's path tolerance, and decimals that round a point by at most a tenth of the
/// diameter tolerance (3 in mm, 5 in inches at the default 0.01 mm) and 10 % of the path
/// tolerance; fewer decimals are refused.
pub fn program_options(
    machine: &Machine,
    out: &ProgramSettings,
    settings: &DrillSettings,
) -> Result<WriterOptions, Error> {
    // A machine that states no path tolerance (0) gets the pocket's default, as pockets do.
    let t = if machine.path_tolerance > 0.0 {
        machine.path_tolerance
    } else {
        super::pocket::DEFAULT_PATH_TOLERANCE
    };
    let mut max_rounding = crate::gcode::format::ROUNDING_SHARE * settings.diameter_tolerance;
    let mut why = format!(
        "10 % of the diameter tolerance {} mm",
        settings.diameter_tolerance
    );
    if t > 0.0 && crate::gcode::format::ROUNDING_SHARE * t < max_rounding {
        max_rounding = crate::gcode::format::ROUNDING_SHARE * t;
        why = format!("10 % of the machine's path tolerance {t} mm");
    }
    let decimals = out.decimals_within(max_rounding, &why)?;
    Ok(out
        .writer_options(decimals, "millpath drill".to_owned())?
        .with_path_tolerance(t))
}

/// The holes of a drawing (every circle, by `--tolerance`), numbered from 1 as reports and
/// `--list` show them; a drawing note goes to `note`.
pub fn find(
    drawing: &str,
    settings: &DrillSettings,
    note: &mut dyn FnMut(String),
) -> Result<Vec<Hole>, Error> {
    settings.options()?;
    let (outlines, n) = if super::SAMPLE_OUTLINES.contains(&drawing) {
        let (loops, n) = super::load_outline(drawing, &settings.import)?;
        let all = loops
            .pockets()
            .into_iter()
            .flat_map(|p| std::iter::once(p.outer).chain(p.islands))
            .collect();
        (all, n)
    } else {
        crate::io::read_outlines(drawing, &settings.import)?
    };
    if let Some(n) = n {
        note(n);
    }
    let holes = find_holes(&outlines, settings.tolerance);
    if holes.is_empty() {
        return Err(InputError::new("circles", 0)
            .at(drawing.to_owned())
            .expected(format!(
                "at least one circle: none of the {} closed outlines is a circle within \
                 --tolerance {} mm (or each holds other outlines)",
                outlines.len(),
                settings.tolerance
            ))
            .into());
    }
    Ok(holes)
}

/// One hole of the report.
#[derive(Debug, Clone, Serialize)]
pub struct HoleEntry {
    /// Its index among the drawing's holes (1-based, as `--list` shows them).
    pub index: usize,
    /// Centre X, mm.
    pub x: f64,
    /// Centre Y, mm.
    pub y: f64,
    /// Drawn diameter, mm.
    pub diameter_mm: f64,
    /// `drill`, `bore` or `skipped`.
    pub operation: String,
    /// What was done, in words (the cycle, the bore's rings and turns, why it was left out).
    pub detail: String,
    /// The diameter cut, as the check measured it on the program read back, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cut_diameter_mm: Option<f64>,
    /// How far the cut centre is from the drawn one, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub center_error_mm: Option<f64>,
}

/// The report written by `--report`.
#[derive(Debug, Clone, Serialize)]
pub struct DrillReport {
    /// Tool diameter, mm.
    pub tool_diameter_mm: f64,
    /// Circles found in the drawing.
    pub holes_found: usize,
    /// Holes selected by the diameter range.
    pub holes_selected: usize,
    /// Holes drilled with canned cycles.
    pub drilled: usize,
    /// Holes helix-bored.
    pub bored: usize,
    /// Holes left out.
    pub skipped: usize,
    /// The holes' bottom, Z mm (the top is Z 0).
    pub bottom_z: f64,
    /// Cycle time of the written program, s.
    pub cycle_time_s: f64,
    /// How the cycle time was computed.
    pub cycle_time_model: String,
    /// The machine it was computed for.
    pub machine: String,
    /// Feed path length, mm.
    pub path_length_mm: f64,
    /// Rapid length, mm.
    pub rapid_length_mm: f64,
    /// Moves of the toolpath.
    pub moves: usize,
    /// Canned cycles written as cycles (the dialect's; Grbl has none).
    pub cycles_written: usize,
    /// Largest distance between a cut hole's centre and the drawn one, mm.
    pub max_center_error_mm: f64,
    /// Largest difference between a cut hole's diameter and the drawn one, mm.
    pub max_diameter_error_mm: f64,
    /// The tolerance the holes were checked to, mm.
    pub checked_to_mm: f64,
    /// The holes: cut ones in cutting order, then those left out.
    pub holes: Vec<HoleEntry>,
}

/// What a hole job made.
#[derive(Debug)]
pub struct DrillRun {
    /// The program text, as written to the `-o` file.
    pub gcode: Vec<u8>,
    /// The report (`--report`).
    pub report: DrillReport,
    /// The plan: the toolpath and each hole's operation.
    pub result: HoleResult,
    /// The check of the program read back.
    pub verification: HoleVerification,
    /// The machine the cycle time is for.
    pub machine: Machine,
}

/// Finds, selects, plans, writes and checks the holes of `drawing`; a drawing note goes to
/// `note`.
pub fn run(
    drawing: &str,
    settings: &DrillSettings,
    program: &ProgramSettings,
    note: &mut dyn FnMut(String),
) -> Result<DrillRun, Error> {
    let machine = super::load_machine(&settings.machine)?;
    let wopts = program_options(&machine, program, settings)?;
    let (tool, opts) = settings.options()?;
    let found = find(drawing, settings, note)?;
    let selected = select_holes(&found, settings.min_diameter, settings.max_diameter)?;
    if selected.is_empty() {
        let mut sizes: Vec<f64> = found.iter().map(|h| h.diameter).collect();
        sizes.sort_by(f64::total_cmp);
        sizes.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
        let list: Vec<String> = sizes.iter().take(12).map(|d| format!("{d:.3}")).collect();
        return Err(InputError::new("holes selected", 0)
            .at("--min-diameter / --max-diameter")
            .expected(format!(
                "a range holding some of the drawing's hole diameters: {} mm",
                list.join(", ")
            ))
            .into());
    }
    let result = drill::plan_holes(&selected, &tool, &opts)?;
    let mut gcode = Vec::new();
    let summary = write_program(&result.toolpath, &wopts, &mut gcode)
        .map_err(|e| e.engine_made("writing the drilling program"))?;
    let cut: Vec<Hole> = result
        .holes
        .iter()
        .filter(|p| p.op.is_cut())
        .map(|p| p.hole)
        .collect();
    let verification = check_program(&gcode, &wopts, &cut, &tool, &opts)?;
    if !verification.ok() {
        let text: Vec<String> = verification
            .problems
            .iter()
            .map(|p| p.to_string())
            .collect();
        return Err(Error::internal(format!(
            "the drilling program fails its check, not written: {}",
            text.join("; ")
        )));
    }
    let t = program_time(
        &gcode,
        wopts.dialect,
        "the written drilling program",
        &machine,
    )
    .map_err(|e| e.engine_made("timing the written drilling program"))?;
    let report = report(
        &result,
        &verification,
        found.len(),
        selected.len(),
        &tool,
        &opts,
        t,
        &machine,
        summary.cycles,
    );
    Ok(DrillRun {
        gcode,
        report,
        result,
        verification,
        machine,
    })
}

/// The program read back (as `millpath estimate` reads it) and checked against the holes cut.
fn check_program(
    gcode: &[u8],
    wopts: &WriterOptions,
    cut: &[Hole],
    tool: &Tool,
    opts: &HoleOptions,
) -> Result<HoleVerification, Error> {
    let ropts = ReaderOptions::default()
        .with_dialect(wopts.dialect)
        .with_origin("the written drilling program");
    let mut at = ropts.start;
    let mut moves: Vec<(Point3, Move)> = Vec::new();
    for rm in Reader::new(BufReader::new(gcode), ropts) {
        let rm = rm.map_err(|e| e.engine_made("reading the drilling program back"))?;
        moves.push((at, rm.mv));
        at = rm.mv.to;
    }
    Ok(verify_holes(
        cut,
        &moves,
        tool,
        opts.top,
        opts.bottom(),
        opts.diameter_tolerance,
    ))
}

#[allow(clippy::too_many_arguments)]
fn report(
    result: &HoleResult,
    v: &HoleVerification,
    found: usize,
    selected: usize,
    tool: &Tool,
    opts: &HoleOptions,
    cycle_time_s: f64,
    machine: &Machine,
    cycles_written: usize,
) -> DrillReport {
    let tp = &result.toolpath;
    let mut checks = v.holes.iter();
    let mut max_c = 0.0f64;
    let mut max_d = 0.0f64;
    let holes: Vec<HoleEntry> = result
        .holes
        .iter()
        .map(|p| {
            let check = if p.op.is_cut() {
                checks.next().copied().flatten()
            } else {
                None
            };
            if let Some(c) = check {
                max_c = max_c.max(c.center_error_mm);
                max_d = max_d.max((c.diameter_mm - p.hole.diameter).abs());
            }
            HoleEntry {
                index: p.index,
                x: p.hole.center.x,
                y: p.hole.center.y,
                diameter_mm: p.hole.diameter,
                operation: p.op.name().to_owned(),
                detail: p.op.to_string(),
                cut_diameter_mm: check.map(|c| c.diameter_mm),
                center_error_mm: check.map(|c| c.center_error_mm),
            }
        })
        .collect();
    let count = |f: fn(&HoleOp) -> bool| result.holes.iter().filter(|p| f(&p.op)).count();
    DrillReport {
        tool_diameter_mm: tool.diameter,
        holes_found: found,
        holes_selected: selected,
        drilled: count(|o| matches!(o, HoleOp::Drill(_))),
        bored: count(|o| matches!(o, HoleOp::Bore { .. })),
        skipped: count(|o| !o.is_cut()),
        bottom_z: opts.bottom(),
        cycle_time_s,
        cycle_time_model: super::REPORT_TIME_MODEL.to_owned(),
        machine: machine.name.clone(),
        path_length_mm: tp.cut_length(),
        rapid_length_mm: tp.rapid_length(),
        moves: tp.moves.len(),
        cycles_written,
        max_center_error_mm: max_c,
        max_diameter_error_mm: max_d,
        checked_to_mm: opts.diameter_tolerance,
        holes,
    }
}

/// The summary line `millpath drill` prints.
pub fn summary_line(rep: &DrillReport) -> String {
    format!(
        "{} holes ({} found): {} drilled, {} bored, {} left out; cycle time {:.2} s ({}), \
         path {:.1} mm; checked to {} mm: centres within {:.4} mm, diameters within {:.4} mm",
        rep.holes_selected,
        rep.holes_found,
        rep.drilled,
        rep.bored,
        rep.skipped,
        rep.cycle_time_s,
        rep.cycle_time_model,
        rep.path_length_mm,
        rep.checked_to_mm,
        rep.max_center_error_mm,
        rep.max_diameter_error_mm
    )
}

/// One line per hole, for `--list`.
pub fn list_line(index: usize, hole: &Hole) -> String {
    drill::describe(index, hole)
}
