//! `millpath drill`: a drawing's circles drilled with canned cycles or helix-bored (the
//! flags; the job itself is [`millpath::job::drill`]).

use millpath::Error;
use millpath::job::DrillSettings;
use std::path::PathBuf;

/// Arguments of `millpath drill`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath drill plate.dxf --tool-diameter 5 --depth 6 --through -o plate.ngc --report plate.json\n  millpath drill plate.dxf --list                                   # the circles found, by index\n  millpath drill plate.dxf --tool-diameter 3 --max-diameter 3.2 --peck 2 --depth 12 -o small.ngc\n  millpath drill plate.dxf --tool-diameter 6 --min-diameter 6 --depth 8 --dialect sinumerik -o bores.mpf\n  millpath drill part.svg --layer holes --tool-diameter 4 --drill-only --stay-at-retract --dialect fanuc"
)]
pub struct Args {
    /// Drawing (.dxf, .svg), JSON outline or `sample:part`, whose circles are the holes.
    pub drawing: String,
    /// How a DXF or SVG drawing is read.
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
    /// Tool diameter, mm: holes of this diameter (within --diameter-tolerance) are drilled,
    /// larger ones helix-bored, smaller ones left out.
    #[arg(long, default_value_t = 6.0)]
    pub tool_diameter: f64,
    /// Hole depth below the top (Z 0), mm; with --through, the stock's thickness.
    #[arg(long, default_value_t = 10.0)]
    pub depth: f64,
    /// Through holes: go --breakthrough below the depth.
    #[arg(long)]
    pub through: bool,
    /// How far a through hole goes below --depth, mm.
    #[arg(long, default_value_t = 1.0)]
    pub breakthrough: f64,
    /// Only circles at least this large, mm.
    #[arg(long)]
    pub min_diameter: Option<f64>,
    /// Only circles at most this large, mm.
    #[arg(long)]
    pub max_diameter: Option<f64>,
    /// Peck drilling (G83, CYCLE83) with pecks of at most Q mm, out to R after each.
    #[arg(long, value_name = "Q")]
    pub peck: Option<f64>,
    /// Chip-breaking drilling (G73) with pecks of at most Q mm.
    #[arg(long, value_name = "Q")]
    pub chip_break: Option<f64>,
    /// Dwell at the bottom (G82, CYCLE82), s.
    #[arg(long)]
    pub dwell: Option<f64>,
    /// The R plane above the top, mm: where feeding starts and pecks retract to.
    #[arg(long, default_value_t = 1.0)]
    pub retract: f64,
    /// Travel height above the top between holes, mm (G98's initial level).
    #[arg(long, default_value_t = 5.0)]
    pub clearance_height: f64,
    /// Stay at the R plane between drilled holes (G99), for parts with nothing standing
    /// above the top.
    #[arg(long)]
    pub stay_at_retract: bool,
    /// Drilling feed: mm/min (`200`) or in/min (`8ipm`).
    #[arg(long, default_value = "200")]
    pub feed: String,
    /// Boring feed (helix and circles): mm/min or in/min.
    #[arg(long, default_value = "800")]
    pub bore_feed: String,
    /// Helix descent per turn when boring, mm.
    #[arg(long, default_value_t = 1.0)]
    pub pitch: f64,
    /// Bore conventional (clockwise) instead of climb.
    #[arg(long)]
    pub conventional: bool,
    /// Largest distance between the helix rings of a hole over twice the tool's diameter,
    /// a fraction of the tool diameter.
    #[arg(long, default_value_t = 0.5)]
    pub stepover: f64,
    /// Stock the helix leaves on the wall for the finishing circle, mm.
    #[arg(long, default_value_t = 0.1)]
    pub finish_allowance: f64,
    /// Largest distance between a drawn outline and a circle for it to be a hole, mm.
    #[arg(long, default_value_t = millpath::geom::CIRCLE_TOLERANCE)]
    pub tolerance: f64,
    /// Holes within this of the tool's diameter are drilled; every hole is checked to it
    /// (centre and diameter of the program read back), mm.
    #[arg(long, default_value_t = millpath::geom::CIRCLE_TOLERANCE)]
    pub diameter_tolerance: f64,
    /// Drill only: leave out holes larger than the tool rather than bore them.
    #[arg(long)]
    pub drill_only: bool,
    /// Machine for the cycle time: a preset name or a TOML machine profile.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// G-code output (the dialect and units of `--dialect`, `--units`).
    #[arg(short = 'o', long)]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub program: super::output::OutputArgs,
    /// JSON report output.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Print the report (as written by `--report`) as one JSON object on stdout instead of
    /// the summary line.
    #[arg(long)]
    pub json: bool,
    /// List the drawing's circles (index, centre, diameter) and exit.
    #[arg(long)]
    pub list: bool,
}

impl Args {
    /// The engine's settings these flags give.
    pub fn settings(&self) -> DrillSettings {
        DrillSettings {
            import: self.import.settings(),
            tool_diameter: self.tool_diameter,
            depth: self.depth,
            through: self.through,
            breakthrough: self.breakthrough,
            min_diameter: self.min_diameter,
            max_diameter: self.max_diameter,
            peck: self.peck,
            chip_break: self.chip_break,
            dwell: self.dwell,
            retract: self.retract,
            clearance_height: self.clearance_height,
            stay_at_retract: self.stay_at_retract,
            feed: self.feed.clone(),
            bore_feed: self.bore_feed.clone(),
            pitch: self.pitch,
            conventional: self.conventional,
            stepover: self.stepover,
            finish_allowance: self.finish_allowance,
            tolerance: self.tolerance,
            diameter_tolerance: self.diameter_tolerance,
            drill_only: self.drill_only,
            machine: self.machine.clone(),
        }
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let settings = args.settings();
    let program = args.program.settings();
    let mut note = |n: String| super::eprint(&format!("note: {n}"));
    if args.list {
        settings.options()?;
        for (i, h) in millpath::job::drill::find(&args.drawing, &settings, &mut note)?
            .iter()
            .enumerate()
        {
            super::print(&millpath::job::drill::list_line(i + 1, h));
        }
        return Ok(());
    }
    // The settings and output flags are checked before the drawing is read (exit 2 at once).
    settings.check_before_loading(&program)?;
    let job = millpath::job::drill::run(&args.drawing, &settings, &program, &mut note)?;
    let rep = &job.report;
    if let Some(out) = &args.output {
        millpath::io::write_atomic(out, &job.gcode)?;
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(rep)
            .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    if args.json {
        return super::print_json(rep);
    }
    for h in rep.holes.iter().filter(|h| h.operation == "skipped") {
        super::eprint(&format!(
            "note: hole {} (⌀{:.3} mm at ({:.3}, {:.3})) {}",
            h.index, h.diameter_mm, h.x, h.y, h.detail
        ));
    }
    super::print(&millpath::job::drill::summary_line(rep));
    Ok(())
}
