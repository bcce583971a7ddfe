//! `millpath pocket`: 2.5D pocket roughing with zigzag, contour-offset or the adaptive spiral
//! (the flags; the job itself is [`millpath::job::pocket`]).

use millpath::Error;
use millpath::io::outline_json::Loops;
use millpath::job::PocketSettings;
use millpath::job::pocket::{default_step_down, default_stepover};
use millpath::strategy::pocket::PocketShape;
use millpath::toolpath::Tool;
use std::path::PathBuf;

/// Arguments of `millpath pocket`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath pocket sample:aerospace --strategy spiral --tool-diameter 12.7 --stepover 0.4 \\\n      --depth 25 --step-down 6.35 --feed 600ipm -o pocket.ngc --report pocket.json\n  millpath pocket sample:aerospace --strategy auto --depth 5 --step-down 5 -o best.ngc   # fastest verified of three\n  millpath pocket sample:aerospace --depth 5 --step-down 5 --dialect fanuc --units in --tool-number 3 -o pocket.nc\n  millpath pocket part.dxf --strategy offset --tool-diameter 10 --stepover 4mm --depth 12 --step-down 4\n  millpath pocket sample:aerospace --strategy adaptive --depth 25 -o adaptive.ngc   # one level, 10 % engagement\n  millpath pocket sheet.dxf --list                       # the drawing's pockets, by index\n  millpath pocket sheet.dxf --select 1,3 --tool-diameter 6 --depth 3 --step-down 3 -o two.ngc"
)]
pub struct Args {
    /// Outline file (.json, .dxf, .svg) or a built-in sample: `sample:aerospace`, `sample:part`.
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
    /// Rest machining: cut only what this previous program (ours or another CAM's) left in
    /// the pockets, with the smaller `--tool-diameter`; the pair is checked on the stock
    /// simulation before anything is written.
    #[arg(long, value_name = "PREVIOUS.ngc")]
    pub rest_from: Option<String>,
    /// The previous program's tool diameter, mm [default: read from its header]
    #[arg(long, requires = "rest_from")]
    pub rest_from_diameter: Option<f64>,
    /// The program's path tolerance, mm: how far the controller may round a corner (`G64 P`
    /// on LinuxCNC); 0 asks for exact stop at every corner [default: the machine's where
    /// above 0, else 0.01]
    #[arg(long)]
    pub tolerance: Option<f64>,
}

/// Options shared by `pocket` and `sweep`.
#[derive(Debug, Clone, clap::Args)]
pub struct CommonArgs {
    /// How a DXF or SVG drawing is read.
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
    /// Strategy: spiral, offset, zigzag, adaptive (the engagement held at the stepover's at
    /// every step, full depth), or auto (plan spiral, offset and zigzag, and adaptive at its
    /// defaults where --flute-length is given, verify and time each on --machine, write the
    /// fastest verified one).
    #[arg(long, default_value = "spiral")]
    pub strategy: String,
    /// Tool diameter, mm.
    #[arg(long, default_value_t = 12.7)]
    pub tool_diameter: f64,
    /// Flute length, mm: no level is deeper [default: 3 × the tool diameter]
    #[arg(long)]
    pub flute_length: Option<f64>,
    /// Stepover: a fraction of the diameter (0.4) or a distance (5mm); for adaptive, the
    /// width of the straight cut whose engagement every step holds [default: 0.4; 0.1 for
    /// adaptive, which cuts the whole flute length at once]
    #[arg(long)]
    pub stepover: Option<String>,
    /// Pocket depth, mm.
    #[arg(long, default_value_t = 25.0)]
    pub depth: f64,
    /// Step-down per level, mm [default: half the tool diameter (6.35), at most the flute
    /// length; with --strategy adaptive the flute length, one level as deep as the tool cuts]
    #[arg(long)]
    pub step_down: Option<f64>,
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
    /// Helix radius, mm [default: 0.45 × the tool diameter; smaller where it does not fit]
    #[arg(long)]
    pub helix_radius: Option<f64>,
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
    /// Spiral laps and adaptive passes as tangent-continuous arcs (G2/G3 biarcs within a few
    /// microns of the smooth curve through the samples) instead of G1 chords; planned both
    /// ways, the chords are kept where they are faster
    #[arg(long)]
    pub arcs: bool,
    /// Adaptive passes may run either way: against the milling direction where that starts
    /// a pass nearer the tool by more than its radius (short passes in corners cut to and
    /// fro instead of linking back)
    #[arg(long)]
    pub both_ways: bool,
    /// Adaptive links through cleared material rise this far over the floor, mm (the tool
    /// stays down; the link rises and settles at the ramp angle) [default: 0, at the level]
    #[arg(long, default_value_t = 0.0, hide_default_value = true)]
    pub lift: f64,
    /// Finishing pass along the walls.
    #[arg(long)]
    pub finish: bool,
    /// Keep the programmed feed (no engagement-based modulation).
    #[arg(long)]
    pub no_feed_modulation: bool,
    /// Machine for the cycle time: a preset name or a TOML machine profile.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// Raster cell of the stock simulation, mm [default: 0.05 up to a 12.7 mm tool, then
    /// 1/254 of the diameter: the simulation's resolution, like every tolerance, scales
    /// with the tool above 12.7 mm]
    #[arg(long)]
    pub cell: Option<f64>,
    /// Draft angle of the walls, degrees (the walls lean into the pocket going down; each
    /// level is cut in its own section).
    #[arg(long, conflicts_with = "bottom_outline")]
    pub draft: Option<f64>,
    /// Outline of the pocket's bottom (same vertex count and islands as the top): each level
    /// is cut in the section interpolated at its depth.
    #[arg(long)]
    pub bottom_outline: Option<String>,
}

impl CommonArgs {
    /// The engine's pocket settings these flags give.
    pub fn settings(&self) -> PocketSettings {
        PocketSettings {
            import: self.import.settings(),
            strategy: self.strategy.clone(),
            tool_diameter: self.tool_diameter,
            stepover: self
                .stepover
                .clone()
                .unwrap_or_else(|| default_stepover(&self.strategy).to_owned()),
            depth: self.depth,
            flute_length: self.flute_length,
            step_down: self.step_down.unwrap_or_else(|| {
                default_step_down(&self.strategy, self.tool_diameter, self.flute_length)
            }),
            wall_stock: self.wall_stock,
            floor_stock: self.floor_stock,
            conventional: self.conventional,
            entry: self.entry.clone(),
            helix_radius: self.helix_radius,
            ramp_angle: self.ramp_angle,
            safe_height: self.safe_height,
            clearance_height: self.clearance_height,
            feed: self.feed.clone(),
            slowdown: self.slowdown,
            angle: self.angle,
            transition: self.transition,
            min_radius: self.min_radius,
            morph: self.morph.clone(),
            arcs: self.arcs,
            both_ways: self.both_ways,
            lift: self.lift,
            finish: self.finish,
            no_feed_modulation: self.no_feed_modulation,
            machine: self.machine.clone(),
            cell: self.cell,
            draft: self.draft,
            bottom_outline: self.bottom_outline.clone(),
            tolerance: None,
        }
    }

    /// The tool and the pocketing options ([`PocketSettings::options`]).
    pub fn options(&self) -> Result<(Tool, millpath::strategy::pocket::PocketOptions), Error> {
        self.settings().options()
    }

    /// The pocket with the walls asked for ([`PocketSettings::with_walls`]).
    pub fn with_walls(&self, shape: PocketShape) -> Result<PocketShape, Error> {
        self.settings()
            .with_walls(shape, &mut |n| super::eprint(&format!("note: {n}")))
    }
}

pub use super::outline_input::load_outline;

use millpath::job::pocket::list_lines;
use millpath::job::{auto_line, pocket_line};

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let mut settings = args.common.settings();
    settings.tolerance = args.tolerance;
    let program = args.program.settings();
    // The output flags are checked before the pocket is planned (exit 2 at once).
    settings.check_before_loading(&program)?;
    let loops = load_outline(&args.outline, &args.common.import)?;
    if args.list {
        for line in list_lines(&loops) {
            super::print(&line);
        }
        return Ok(());
    }
    if let Some(from) = &args.rest_from {
        return rest(args, &loops, &settings, &program, from);
    }
    let job = millpath::job::pocket::run(
        &loops,
        &args.outline,
        &settings,
        &program,
        args.select.as_deref(),
        &mut |n| super::eprint(&format!("note: {n}")),
    )?;
    let rep = &job.report;
    if let Some(out) = &args.output {
        millpath::io::write_atomic(out, &job.gcode)?;
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(rep)
            .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    if let Some(path) = &args.html {
        write_html(path, &args.outline, &job)?;
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
        super::print_json(rep)?;
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
    super::print(&summary_line(rep));
    super::print(&removal_line(rep));
    for p in &rep.problems {
        super::eprint(&format!("verification: {p}"));
    }
    Ok(())
}

/// The summary line printed without `--json`.
fn summary_line(rep: &millpath::job::PocketReport) -> String {
    format!(
        "{}{}: cycle time {:.2} s ({}; {:.2} s at the programmed feeds), path {:.1} mm, engagement max {:.1}° mean {:.1}° (nominal {:.1}°), \
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
        rep.time_at_programmed_feed_s,
        rep.path_length_mm,
        rep.max_engagement_deg,
        rep.mean_engagement_deg,
        rep.nominal_engagement_deg,
        100.0 * rep.share_above_nominal,
        rep.verification.min_clearance_mm,
        rep.verification.required_clearance_mm,
        rep.verification.uncut_area_mm2,
    )
}

/// The second line printed without `--json`: the removal rate, the time not cutting, and
/// the engagement's distribution outside the entries beside what the corners force.
fn removal_line(rep: &millpath::job::PocketReport) -> String {
    let e = &rep.verification.engagement;
    format!(
        "removal {:.0} mm³ at {:.0} mm³/s; entries {:.2} s; not cutting {:.2} s (rapids {:.2} s); \
         engagement outside entries mean {:.1}° p95 {:.1}° max {:.1}°, {:.2}% above 1.1 × \
         nominal; the sharpest corner forces {:.1}°",
        rep.verification.removed_mm3,
        rep.removal_rate_mm3_s,
        rep.entry_time_s,
        rep.air_time_s,
        rep.rapid_time_s,
        e.mean_deg,
        e.p95_deg,
        e.max_deg,
        100.0 * e.share_above_bound,
        rep.engagement_floor_deg
    )
}

/// Writes the `--html` report: summary, viewer with playback on the machine, feed plot.
fn write_html(
    path: &std::path::Path,
    outline: &str,
    job: &millpath::job::PocketRun,
) -> Result<(), Error> {
    super::html::write(path, &job.html(outline)?)
}

/// `--rest-from`: the rest pass, written and summed up in one line.
fn rest(
    args: &Args,
    loops: &Loops,
    settings: &PocketSettings,
    program: &millpath::job::ProgramSettings,
    from: &str,
) -> Result<(), Error> {
    let run = millpath::job::rest::run(
        loops,
        &args.outline,
        settings,
        program,
        args.select.as_deref(),
        &millpath::job::rest::RestFrom {
            program: from.to_owned(),
            diameter: args.rest_from_diameter,
        },
    )?;
    if let Some(out) = &args.output {
        millpath::io::write_atomic(out, &run.gcode)?;
    }
    super::print(&run.summary());
    Ok(())
}
