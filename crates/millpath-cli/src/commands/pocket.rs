//! `millpath pocket`: 2.5D pocket roughing with zigzag, contour-offset or the adaptive spiral.

use millpath::gcode::{WriterOptions, write_program};
use millpath::machine::Machine;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{
    self, Direction, Entry, PocketOptions, PocketResult, PocketShape, Stepover, StrategyKind, Walls,
};
use millpath::toolpath::Tool;
use millpath::{Error, InputError};
use serde::Serialize;
use std::path::PathBuf;

/// Arguments of `millpath pocket`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath pocket sample:aerospace --strategy spiral --tool-diameter 12.7 --stepover 0.4 \\\n      --depth 25 --step-down 6.35 --feed 600ipm -o pocket.ngc --report pocket.json\n  millpath pocket sample:aerospace --strategy auto --depth 5 --step-down 5 -o best.ngc   # fastest verified of three\n  millpath pocket sample:aerospace --depth 5 --step-down 5 --dialect fanuc --units in --tool-number 3 -o pocket.nc\n  millpath pocket part.dxf --strategy offset --tool-diameter 10 --stepover 4mm --depth 12 --step-down 4"
)]
pub struct Args {
    /// Outline file (.json, .dxf, .svg) or a built-in sample: `sample:aerospace`.
    pub outline: String,
    #[command(flatten)]
    pub common: CommonArgs,
    /// G-code output (the dialect and units of `--dialect`, `--units`).
    #[arg(short = 'o', long)]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub program: super::output::OutputArgs,
    /// JSON report output.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Write a self-contained HTML report (summary, viewer with playback, feed plot).
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Print the report (as written by `--report`) as one JSON object on stdout instead of
    /// the summary line.
    #[arg(long)]
    pub json: bool,
}

/// Options shared by `pocket` and `sweep`.
#[derive(Debug, Clone, clap::Args)]
pub struct CommonArgs {
    /// How a DXF or SVG drawing is read.
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
    /// Strategy: spiral, offset, zigzag, or auto (plan all three, verify and time each on
    /// --machine, write the fastest verified one).
    #[arg(long, default_value = "spiral")]
    pub strategy: String,
    /// Tool diameter, mm.
    #[arg(long, default_value_t = 12.7)]
    pub tool_diameter: f64,
    /// Stepover: a fraction of the diameter (0.4) or a distance (5mm).
    #[arg(long, default_value = "0.4")]
    pub stepover: String,
    /// Pocket depth, mm.
    #[arg(long, default_value_t = 25.0)]
    pub depth: f64,
    /// Step-down per level, mm.
    #[arg(long, default_value_t = 6.35)]
    pub step_down: f64,
    /// Wall stock, mm.
    #[arg(long, default_value_t = 0.0)]
    pub wall_stock: f64,
    /// Floor stock, mm.
    #[arg(long, default_value_t = 0.0)]
    pub floor_stock: f64,
    /// Conventional milling instead of climb.
    #[arg(long)]
    pub conventional: bool,
    /// Entry: helix or ramp.
    #[arg(long, default_value = "helix")]
    pub entry: String,
    /// Helix radius, mm.
    #[arg(long, default_value_t = 2.5)]
    pub helix_radius: f64,
    /// Ramp angle, degrees.
    #[arg(long, default_value_t = 3.0)]
    pub ramp_angle: f64,
    /// Safe height above the level's top, mm.
    #[arg(long, default_value_t = 1.0)]
    pub safe_height: f64,
    /// Clearance height above the stock, mm.
    #[arg(long, default_value_t = 5.0)]
    pub clearance_height: f64,
    /// Feed: mm/min (`1500`) or in/min (`600ipm`).
    #[arg(long, default_value = "600ipm")]
    pub feed: String,
    /// Fraction of the feed at full slotting.
    #[arg(long, default_value_t = 0.75)]
    pub slowdown: f64,
    /// Zigzag angle, degrees, from the pocket's principal axis (its long direction).
    #[arg(long, default_value_t = 0.0)]
    pub angle: f64,
    /// Spiral transition ratio C in [0, 1] of the paper's central spiral (the `fronts` and
    /// `harmonic` morphs, default 0.5; giving it selects `fronts` unless `--morph` is given)
    #[arg(long)]
    pub transition: Option<f64>,
    /// Smallest curvature radius wanted on the spiral's interior loops, mm.
    #[arg(long, default_value_t = 1.0)]
    pub min_radius: f64,
    /// Spiral morph: `offsets` (default: the contour-parallel loops, rounded, joined by lane
    /// changes), `fronts` (the paper's central spiral of radius C·ρ grown by offset fronts) or
    /// `harmonic` (stepover held at corners too, more laps)
    #[arg(long)]
    pub morph: Option<String>,
    /// Spiral laps as tangent-continuous arcs (G2/G3 biarcs within 0.004 mm of the smooth
    /// curve through the samples) instead of G1 chords
    #[arg(long)]
    pub arcs: bool,
    /// Finishing pass along the walls.
    #[arg(long)]
    pub finish: bool,
    /// Keep the programmed feed (no engagement-based modulation).
    #[arg(long)]
    pub no_feed_modulation: bool,
    /// Machine for the cycle time: a preset name or a TOML machine profile.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// Raster cell of the stock simulation, mm.
    #[arg(long, default_value_t = 0.05)]
    pub cell: f64,
    /// Draft angle of the walls, degrees (the walls lean into the pocket going down; each
    /// level is cut in its own section).
    #[arg(long, conflicts_with = "bottom_outline")]
    pub draft: Option<f64>,
    /// Outline of the pocket's bottom (same vertex count and islands as the top): each level
    /// is cut in the section interpolated at its depth.
    #[arg(long)]
    pub bottom_outline: Option<String>,
}

/// Parses a feed: `600ipm` / `600in/min` in inches per minute, else mm/min; returns mm/s.
pub fn parse_feed(text: &str) -> Result<f64, InputError> {
    let t = text.trim();
    let (num, scale) = if let Some(n) = t.strip_suffix("ipm").or_else(|| t.strip_suffix("in/min")) {
        (n, 25.4 / 60.0)
    } else if let Some(n) = t.strip_suffix("mm/min") {
        (n, 1.0 / 60.0)
    } else {
        (t, 1.0 / 60.0)
    };
    num.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .map(|v| v * scale)
        .ok_or_else(|| {
            InputError::new("feed", text)
                .at("--feed")
                .expected("a feed > 0 in mm/min (1500) or in/min (600ipm)")
        })
}

/// What `--strategy` asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Choice {
    /// One strategy.
    One(StrategyKind),
    /// All three, the fastest verified one written (`pocket::auto`).
    Auto,
}

/// `--strategy` of `pocket`: a strategy or `auto`.
pub fn parse_choice(s: &str) -> Result<Choice, InputError> {
    match s {
        "spiral" => Ok(Choice::One(StrategyKind::Spiral)),
        "offset" => Ok(Choice::One(StrategyKind::Offset)),
        "zigzag" => Ok(Choice::One(StrategyKind::Zigzag)),
        "auto" => Ok(Choice::Auto),
        _ => Err(InputError::new("strategy", s)
            .at("--strategy")
            .expected("spiral, offset, zigzag or auto")),
    }
}

impl CommonArgs {
    /// The tool and the pocketing options.
    pub fn options(&self) -> Result<(Tool, PocketOptions), Error> {
        let tool = Tool::flat(self.tool_diameter).map_err(|e| e.at("--tool-diameter"))?;
        let ramp = self.ramp_angle.to_radians();
        let entry = match self.entry.as_str() {
            "helix" => Entry::Helix {
                radius: self.helix_radius,
                ramp_angle: ramp,
            },
            "ramp" => Entry::Ramp { ramp_angle: ramp },
            e => {
                return Err(InputError::new("entry", e)
                    .at("--entry")
                    .expected("helix or ramp")
                    .into());
            }
        };
        let feed = parse_feed(&self.feed)?;
        let mut opts = PocketOptions {
            stepover: Stepover::parse(&self.stepover)?,
            depth: self.depth,
            step_down: self.step_down,
            wall_stock: self.wall_stock,
            floor_stock: self.floor_stock,
            direction: if self.conventional {
                Direction::Conventional
            } else {
                Direction::Climb
            },
            entry,
            safe_height: self.safe_height,
            clearance_height: self.clearance_height,
            feed,
            plunge_feed: feed / 3.0,
            slowdown: self.slowdown,
            zigzag_angle: self.angle.to_radians(),
            transition: self.transition.unwrap_or(DEFAULT_TRANSITION),
            min_radius: self.min_radius,
            morph: self.morph()?,
            arcs: self.arcs,
            curvature_ramps: true,
            finish: self.finish,
            modulate_feed: !self.no_feed_modulation,
        };
        // Shaped for the machine: curvature ramps for a jerk-limited controller.
        let machine = super::load_machine(&self.machine)?;
        opts.curvature_ramps = machine.axes.iter().any(|a| a.max_jerk.is_finite());
        opts.validate(&tool)?;
        if !(self.cell.is_finite() && self.cell > 0.0) {
            return Err(InputError::new("cell", self.cell)
                .at("--cell")
                .expected("a cell > 0 mm")
                .into());
        }
        Ok((tool, opts))
    }

    /// The spiral's morph: `--morph`, else `fronts` when `--transition` is given (the
    /// paper's central spiral is the fronts' and harmonic morphs'), else `offsets`.
    fn morph(&self) -> Result<pocket::spiral::SpiralMorph, Error> {
        use pocket::spiral::SpiralMorph;
        match (self.morph.as_deref(), self.transition) {
            (None | Some("offsets"), None) => Ok(SpiralMorph::Offsets),
            (None | Some("fronts"), _) => Ok(SpiralMorph::Fronts),
            (Some("harmonic"), _) => Ok(SpiralMorph::Harmonic),
            (Some("offsets"), Some(c)) => Err(InputError::new("transition", c)
                .at("--transition with --morph offsets")
                .expected(
                    "no --transition with the offsets morph (its spiral has no central circle); \
                     --morph fronts or harmonic for the paper's transition C",
                )
                .into()),
            (Some(other), _) => Err(InputError::new("morph", other)
                .at("--morph")
                .expected("offsets, fronts or harmonic")
                .into()),
        }
    }

    /// The pocket with the walls asked for (`--draft`, `--bottom-outline`).
    pub fn with_walls(&self, shape: PocketShape) -> Result<PocketShape, Error> {
        if let Some(deg) = self.draft {
            return Ok(shape.with_walls(Walls::Draft(deg.to_radians()), "--draft")?);
        }
        if let Some(path) = &self.bottom_outline {
            let b = load_outline(path, &self.import)?;
            return Ok(shape.with_walls(
                Walls::Bottom {
                    outer: b.outer,
                    islands: b.islands,
                },
                &format!("--bottom-outline {path}"),
            )?);
        }
        Ok(shape)
    }

    /// Simulation options.
    pub fn sim(&self) -> SimOptions {
        SimOptions {
            cell: self.cell,
            step: (2.0 * self.cell).max(0.1),
            ..SimOptions::default()
        }
    }
}

/// The paper's transition C when `--transition` is not given (its Table 1 and Figure 10 go
/// from 0.2 to 0.7; 0.5 is their middle).
pub const DEFAULT_TRANSITION: f64 = 0.5;

pub use super::outline_input::load_outline;

/// The report written by `--report`.
#[derive(Debug, Serialize)]
pub struct Report {
    /// Strategy name.
    pub strategy: String,
    /// Cycle time, s.
    pub cycle_time_s: f64,
    /// How the cycle time was computed.
    pub cycle_time_model: String,
    /// Cutting path length, mm.
    pub path_length_mm: f64,
    /// Rapid length, mm.
    pub rapid_length_mm: f64,
    /// Largest engagement, degrees.
    pub max_engagement_deg: f64,
    /// Mean engagement, degrees.
    pub mean_engagement_deg: f64,
    /// Nominal engagement, degrees.
    pub nominal_engagement_deg: f64,
    /// Share of the cutting length above the nominal engagement.
    pub share_above_nominal: f64,
    /// The stepover asked for, mm.
    pub stepover_mm: f64,
    /// Largest radial depth of cut measured (slotting included), mm.
    pub max_stepover_mm: f64,
    /// Levels.
    pub levels: usize,
    /// Moves.
    pub moves: usize,
    /// The verifier's findings.
    pub verification: millpath::stock::Verification,
    /// Problems found (empty when the path passes).
    pub problems: Vec<String>,
    /// What was changed from the options asked for, and why (a fallback after a gouge).
    pub notes: Vec<String>,
    /// With `--strategy auto`: every strategy tried, in `pocket::auto::ORDER`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub auto: Option<Vec<AutoEntry>>,
}

/// One strategy tried by `--strategy auto`.
#[derive(Debug, Serialize)]
pub struct AutoEntry {
    /// Strategy name.
    pub strategy: String,
    /// Cycle time on the machine, s (`null` when not planned or not timed).
    pub cycle_time_s: Option<f64>,
    /// Cutting path length, mm (`null` when not planned).
    pub path_length_mm: Option<f64>,
    /// The verifier found no problem.
    pub verified: bool,
    /// Why it was not verified, or why it could not be planned.
    pub why_not: Option<String>,
    /// This one was written: the fastest verified.
    pub chosen: bool,
}

/// The report's entries of `auto`'s candidates; `chosen` is the index written.
pub fn auto_entries(candidates: &[pocket::auto::Candidate], chosen: usize) -> Vec<AutoEntry> {
    candidates
        .iter()
        .enumerate()
        .map(|(i, c)| AutoEntry {
            strategy: c.kind.name().to_owned(),
            cycle_time_s: c.cycle_time_s(),
            path_length_mm: c.path_length_mm(),
            verified: c.verified(),
            why_not: c.why_not(),
            chosen: i == chosen,
        })
        .collect()
}

/// One line per strategy `auto` tried.
fn auto_line(e: &AutoEntry) -> String {
    let mut line = format!("auto: {}:", e.strategy);
    if let Some(t) = e.cycle_time_s {
        line.push_str(&format!(" cycle time {t:.2} s,"));
    }
    if let Some(l) = e.path_length_mm {
        line.push_str(&format!(" path {l:.1} mm,"));
    }
    match (&e.why_not, e.path_length_mm) {
        (None, _) => line.push_str(" verified"),
        (Some(w), Some(_)) => line.push_str(&format!(" not verified: {w}")),
        (Some(w), None) => line.push_str(&format!(" not planned: {w}")),
    }
    if e.chosen {
        line.push_str(" (fastest verified: written)");
    }
    line
}

/// Builds the report of a generated pocket.
pub fn report(kind: StrategyKind, r: &PocketResult, machine: &str) -> Result<Report, Error> {
    let m = super::load_machine(machine)?;
    Ok(Report {
        strategy: kind.name().to_owned(),
        cycle_time_s: pocket::cycle_time_on(&r.toolpath, &m)
            .map_err(|e| e.engine_made("timing the pocket toolpath"))?,
        cycle_time_model: pocket::CYCLE_TIME_MODEL.to_owned(),
        path_length_mm: r.toolpath.cut_length(),
        rapid_length_mm: r.toolpath.rapid_length(),
        max_engagement_deg: r.verification.max_engagement_deg,
        mean_engagement_deg: r.verification.mean_engagement_deg,
        nominal_engagement_deg: r.nominal_engagement_deg,
        share_above_nominal: r.verification.share_above_nominal,
        stepover_mm: r.stepover_mm,
        max_stepover_mm: r.verification.max_radial_depth_mm,
        levels: r.toolpath.levels.len(),
        moves: r.toolpath.moves.len(),
        verification: r.verification.clone(),
        problems: r.verification.problems(),
        notes: r.notes.clone(),
        auto: None,
    })
}

/// How the pocket program is written: the dialect, units, tool, spindle and coolant of
/// `out`, stating the machine's path tolerance (`G64 P t`, `CYCLE832(t,_FINISH,1)`, Fanuc's
/// `G05.1 Q1` with t in a comment, a comment on Grbl), the tolerance its cycle time was
/// planned with and the one `millpath estimate` reads back. The decimals keep the rounding
/// within the pocket's own resolution (arcs flatter than
/// [`pocket::chain::ARC_AS_LINE_SAGITTA`], 0.0007 mm, are lines in the toolpath: 3 decimals
/// in mm, 5 in inches) and within 10 % of the path tolerance; fewer `--decimals` are refused.
pub fn program_options(
    kind: StrategyKind,
    machine: &Machine,
    out: &super::output::OutputArgs,
) -> Result<WriterOptions, Error> {
    let t = machine.path_tolerance;
    let mut max_rounding = pocket::chain::ARC_AS_LINE_SAGITTA;
    let mut why = "the pocket's resolution".to_owned();
    if t > 0.0 && millpath::gcode::format::ROUNDING_SHARE * t < max_rounding {
        max_rounding = millpath::gcode::format::ROUNDING_SHARE * t;
        why = format!("10 % of the machine's path tolerance {t} mm");
    }
    let decimals = out.decimals_within(max_rounding, &why)?;
    Ok(out
        .writer_options(decimals, format!("millpath pocket {}", kind.name()))?
        .with_path_tolerance(t))
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let choice = parse_choice(&args.common.strategy)?;
    // The output flags are checked before the pocket is planned (exit 2 at once).
    let wopts = program_options(
        StrategyKind::Spiral,
        &super::load_machine(&args.common.machine)?,
        &args.program,
    )?;
    let (tool, opts) = args.common.options()?;
    let loops = load_outline(&args.outline, &args.common.import)?;
    let shape =
        args.common
            .with_walls(PocketShape::new(loops.outer, loops.islands, &args.outline)?)?;
    let (kind, r, auto) = match choice {
        Choice::One(kind) if opts.arcs => {
            let m = super::load_machine(&args.common.machine)?;
            let time = |tp: &millpath::toolpath::Toolpath| pocket::cycle_time_on(tp, &m);
            let sim = args.common.sim();
            let (r, _) = pocket::auto::arcs_or_chords(kind, &shape, &tool, &opts, &sim, &time)?;
            (kind, r, None)
        }
        Choice::One(kind) => (
            kind,
            pocket::generate(kind, &shape, &tool, &opts, &args.common.sim())?,
            None,
        ),
        Choice::Auto => {
            let m = super::load_machine(&args.common.machine)?;
            let time = |tp: &millpath::toolpath::Toolpath| pocket::cycle_time_on(tp, &m);
            let cands = pocket::auto::plan_all(&shape, &tool, &opts, &args.common.sim(), &time);
            let Some(i) = pocket::auto::choose(&cands) else {
                return Err(pocket::auto::none_verified(&cands));
            };
            let Some(r) = cands.get(i).and_then(|c| c.result()).cloned() else {
                return Err(Error::internal(
                    "--strategy auto: the chosen path is missing",
                ));
            };
            (cands[i].kind, r, Some(auto_entries(&cands, i)))
        }
    };
    let mut rep = report(kind, &r, &args.common.machine)?;
    rep.auto = auto;
    if let Some(out) = &args.output {
        let wopts = WriterOptions {
            program_name: Some(format!("millpath pocket {}", kind.name())),
            ..wopts
        };
        let mut buf = Vec::new();
        write_program(&r.toolpath, &wopts, &mut buf)
            .map_err(|e| e.engine_made("writing the pocket program"))?;
        millpath::io::write_atomic(out, &buf)?;
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&rep)
            .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    if let Some(path) = &args.html {
        let m = super::load_machine(&args.common.machine)?;
        let plan = millpath::motion::plan_toolpath(&r.toolpath, &m)
            .map_err(|e| e.engine_made("timing the pocket toolpath"))?;
        let mut summary = vec![
            super::html::machine_row(&m),
            ("strategy".to_owned(), kind.name().to_owned()),
            (
                "cycle time".to_owned(),
                format!("{:.2} s", rep.cycle_time_s),
            ),
            (
                "path length".to_owned(),
                format!("{:.1} mm", rep.path_length_mm),
            ),
            (
                "levels, moves".to_owned(),
                format!("{}, {}", rep.levels, rep.moves),
            ),
            (
                "engagement".to_owned(),
                format!(
                    "max {:.1}°, mean {:.1}°, nominal {:.1}°, {:.1}% of the path above nominal",
                    rep.max_engagement_deg,
                    rep.mean_engagement_deg,
                    rep.nominal_engagement_deg,
                    100.0 * rep.share_above_nominal
                ),
            ),
            (
                "verifier".to_owned(),
                format!(
                    "min clearance {:.6} mm (needs {:.6}), uncut {:.3} mm², rapids through material {}",
                    rep.verification.min_clearance_mm,
                    rep.verification.required_clearance_mm,
                    rep.verification.uncut_area_mm2,
                    rep.verification.rapids_through_material
                ),
            ),
        ];
        summary.extend(
            rep.problems
                .iter()
                .map(|p| ("problem".to_owned(), p.clone())),
        );
        summary.extend(
            rep.auto
                .iter()
                .flatten()
                .map(|e| ("--strategy auto".to_owned(), auto_line(e))),
        );
        let mut outlines = vec![shape.outer.clone()];
        outlines.extend(shape.islands.iter().cloned());
        let html = super::html::toolpath_report(
            &format!("millpath pocket {} {}", args.outline, kind.name()),
            summary,
            &r.toolpath,
            &outlines,
            &plan,
        )?;
        super::html::write(path, &html)?;
    }
    for n in &rep.notes {
        super::eprint(&format!("note: {n}"));
    }
    if let (Some(entries), false) = (&rep.auto, args.json) {
        for e in entries {
            super::print(&auto_line(e));
        }
    }
    if args.json {
        super::print_json(&rep)?;
        for p in &rep.problems {
            super::eprint(&format!("verification: {p}"));
        }
        return Ok(());
    }
    super::print(&format!(
        "{}: cycle time {:.2} s ({}), path {:.1} mm, engagement max {:.1}° mean {:.1}° (nominal {:.1}°), \
         {:.1}% above nominal, min clearance {:.6} mm (needs {:.6}), uncut {:.3} mm²",
        kind.name(),
        rep.cycle_time_s,
        rep.cycle_time_model,
        rep.path_length_mm,
        rep.max_engagement_deg,
        rep.mean_engagement_deg,
        rep.nominal_engagement_deg,
        100.0 * rep.share_above_nominal,
        rep.verification.min_clearance_mm,
        rep.verification.required_clearance_mm,
        rep.verification.uncut_area_mm2,
    ));
    for p in &rep.problems {
        super::eprint(&format!("verification: {p}"));
    }
    Ok(())
}
