//! `millpath pocket`: 2.5D pocket roughing with zigzag, contour-offset or the adaptive spiral.

use millpath::gcode::{WriterOptions, write_program};
use millpath::io::outline_json::Loops;
use millpath::machine::Machine;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::part::{PartStrategy, generate_part};
use millpath::strategy::pocket::{
    self, Direction, Entry, PocketOptions, PocketShape, Stepover, StrategyKind, Walls,
};
use millpath::toolpath::Tool;
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Arguments of `millpath pocket`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath pocket sample:aerospace --strategy spiral --tool-diameter 12.7 --stepover 0.4 \\\n      --depth 25 --step-down 6.35 --feed 600ipm -o pocket.ngc --report pocket.json\n  millpath pocket sample:aerospace --strategy auto --depth 5 --step-down 5 -o best.ngc   # fastest verified of three\n  millpath pocket sample:aerospace --depth 5 --step-down 5 --dialect fanuc --units in --tool-number 3 -o pocket.nc\n  millpath pocket part.dxf --strategy offset --tool-diameter 10 --stepover 4mm --depth 12 --step-down 4\n  millpath pocket sheet.dxf --list                       # the drawing's pockets, by index\n  millpath pocket sheet.dxf --select 1,3 --tool-diameter 6 --depth 3 --step-down 3 -o two.ngc"
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
    /// Cut only these pockets of the drawing, by their index in `--list` and the report
    /// (1-based): `1,3`, `2-4`.
    #[arg(long)]
    pub select: Option<String>,
    /// List the drawing's pockets (index, area, islands, bounds) and exit.
    #[arg(long)]
    pub list: bool,
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

/// How the pocket program is written: the dialect, units, tool, spindle and coolant of
/// `out`, stating the machine's path tolerance (`G64 P t`, `CYCLE832(t,_FINISH,1)`, Fanuc's
/// `G05.1 Q1` with t in a comment, a comment on Grbl), the tolerance its cycle time was
/// planned with and the one `millpath estimate` reads back; `name` is the strategy's (or
/// `mixed`). The decimals keep the rounding within the pocket's own resolution (arcs flatter
/// than [`pocket::chain::ARC_AS_LINE_SAGITTA`], 0.0007 mm, are lines in the toolpath: 3
/// decimals in mm, 5 in inches) and within 10 % of the path tolerance; fewer `--decimals`
/// are refused.
pub fn program_options(
    name: &str,
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
        .writer_options(decimals, format!("millpath pocket {name}"))?
        .with_path_tolerance(t))
}

/// The indices `--select` asks for (1-based, sorted, each once) among `n` pockets; all when
/// not given.
pub fn parse_select(text: Option<&str>, n: usize) -> Result<Vec<usize>, InputError> {
    let Some(text) = text else {
        return Ok((1..=n).collect());
    };
    let bad = || {
        InputError::new("pocket selection", text)
            .at("--select")
            .expected(format!(
                "pocket indices from 1 to {n} (as pocket --list shows them), separated by commas, \
                 or ranges: 1,3 or 2-4"
            ))
    };
    let mut out = Vec::new();
    for item in text.split(',') {
        let item = item.trim();
        let (a, b) = match item.split_once('-') {
            Some((a, b)) => (a.trim(), b.trim()),
            None => (item, item),
        };
        let (Ok(a), Ok(b)) = (a.parse::<usize>(), b.parse::<usize>()) else {
            return Err(bad());
        };
        if a == 0 || b < a || b > n {
            return Err(bad());
        }
        out.extend(a..=b);
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// One line per pocket of the drawing, for `--list`.
fn list_lines(loops: &Loops) -> Vec<String> {
    loops
        .pockets()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let b = p.outer.bounds();
            format!(
                "pocket {}: area {:.3} mm², {} islands, bounds ({:.3}, {:.3}) to ({:.3}, {:.3})",
                i + 1,
                p.area(),
                p.islands.len(),
                b.min.x,
                b.min.y,
                b.max.x,
                b.max.y
            )
        })
        .collect()
}

use super::pocket_report::{auto_line, pocket_line, report};

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let choice = parse_choice(&args.common.strategy)?;
    // The output flags are checked before the pocket is planned (exit 2 at once).
    program_options(
        "spiral",
        &super::load_machine(&args.common.machine)?,
        &args.program,
    )?;
    let loops = load_outline(&args.outline, &args.common.import)?;
    if args.list {
        for line in list_lines(&loops) {
            super::print(&line);
        }
        return Ok(());
    }
    let (tool, opts) = args.common.options()?;
    let selected = parse_select(args.select.as_deref(), loops.len())?;
    if selected.len() > 1 && (args.common.draft.is_some() || args.common.bottom_outline.is_some()) {
        return Err(InputError::new("pockets", selected.len())
            .at(format!("{} with --draft or --bottom-outline", args.outline))
            .expected("one pocket with inclined walls: --select one of them")
            .into());
    }
    let all = loops.pockets();
    let mut shapes = Vec::with_capacity(selected.len());
    for &i in &selected {
        let p = &all[i - 1];
        let origin = if all.len() > 1 {
            format!("{}, pocket {i}", args.outline)
        } else {
            args.outline.clone()
        };
        let shape = PocketShape::new(p.outer.clone(), p.islands.clone(), &origin)?;
        shapes.push((i, args.common.with_walls(shape)?));
    }
    let m = super::load_machine(&args.common.machine)?;
    let time = |tp: &millpath::toolpath::Toolpath| millpath::motion::cycle_time(tp, &m);
    let strategy = match choice {
        Choice::One(kind) => PartStrategy::One(kind),
        Choice::Auto => PartStrategy::Auto,
    };
    let part = generate_part(&shapes, strategy, &tool, &opts, &args.common.sim(), &time)?;
    let name = match part.pockets.iter().find(|p| p.result.is_some()) {
        Some(f)
            if part
                .pockets
                .iter()
                .filter(|p| p.result.is_some())
                .all(|p| p.kind == f.kind) =>
        {
            f.kind.name().to_owned()
        }
        _ => "mixed".to_owned(),
    };
    let wopts = program_options(&name, &m, &args.program)?;
    let mut buf = Vec::new();
    write_program(&part.toolpath, &wopts, &mut buf)
        .map_err(|e| e.engine_made("writing the pocket program"))?;
    let t = super::estimate::program_time(&buf, wopts.dialect, "the written pocket program", &m)
        .map_err(|e| e.engine_made("timing the written pocket program"))?;
    let mut rep = report(&part, t);
    if part.pockets.len() == 1 {
        rep.auto = rep.pockets.first_mut().and_then(|p| p.auto.take());
    }
    if let Some(out) = &args.output {
        millpath::io::write_atomic(out, &buf)?;
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&rep)
            .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    if let Some(path) = &args.html {
        let m = super::load_machine(&args.common.machine)?;
        let plan = millpath::motion::plan_toolpath(&part.toolpath, &m)
            .map_err(|e| e.engine_made("timing the pocket toolpath"))?;
        let mut summary = vec![
            super::html::machine_row(&m),
            ("strategy".to_owned(), name.clone()),
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
        let outlines: Vec<_> = shapes
            .iter()
            .flat_map(|(_, s)| std::iter::once(s.outer.clone()).chain(s.islands.iter().cloned()))
            .collect();
        let html = super::html::toolpath_report(
            &format!("millpath pocket {} {}", args.outline, name),
            summary,
            &part.toolpath,
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
    if !args.json && rep.pockets.len() > 1 {
        for p in &rep.pockets {
            for e in p.auto.iter().flatten() {
                super::print(&format!("pocket {}: {}", p.index, auto_line(e)));
            }
        }
    }
    if args.json {
        super::print_json(&rep)?;
        for p in &rep.problems {
            super::eprint(&format!("verification: {p}"));
        }
        return Ok(());
    }
    if rep.pockets.len() > 1 {
        for p in &rep.pockets {
            super::print(&pocket_line(p));
        }
    }
    super::print(&format!(
        "{}{}: cycle time {:.2} s ({}), path {:.1} mm, engagement max {:.1}° mean {:.1}° (nominal {:.1}°), \
         {:.1}% above nominal, min clearance {:.6} mm (needs {:.6}), uncut {:.3} mm²",
        if rep.pockets.len() > 1 {
            format!(
                "total of {} pockets, ",
                rep.pockets.iter().filter(|p| p.skipped.is_none()).count()
            )
        } else {
            String::new()
        },
        rep.strategy,
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
