//! `millpath profile`: a drawing's closed outlines cut out (the flags; the job itself is
//! [`millpath::job::profile`]).

use millpath::Error;
use millpath::job::profile::{ProfileReport, ProfileSettings, ProfileSource};
use std::path::PathBuf;

/// Arguments of `millpath profile`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath profile part.dxf --tool-diameter 6 --depth 6 --step-down 2 -o part.ngc   # parts outside, holes inside\n  millpath profile part.dxf --depth 6 --tabs auto --tab-width 6 --tab-height 2 -o part.ngc\n  millpath profile sign.svg --side on --depth 1 --step-down 1 --tool-diameter 3 -o sign.ngc\n  millpath profile part.dxf --stock-to-leave 0.2 --entry helix --conventional --report part.json\n  millpath profile part.dxf --dialect fanuc --units in --tool-number 2 -o part.nc\n  millpath profile --sample -o die.ngc      # the paper's die cavity, as contour --sample cuts it"
)]
pub struct Args {
    /// Drawing (.dxf, .svg), outline file (.json) or a built-in sample (`sample:part`). Omit
    /// with --sample.
    #[arg(required_unless_present = "sample")]
    pub drawing: Option<String>,
    /// Cut the paper's die cavity (the curve of `contour --sample`, fitted by arcs within a
    /// tenth of the tolerance) with that sample's settings (10 mm tool, 20 mm deep in 2.5 mm
    /// levels, 0.2 mm stock for the finishing pass, T = 0.00004 mm, inside); flags given
    /// override them.
    #[arg(long, conflicts_with = "drawing")]
    pub sample: bool,
    /// How a DXF or SVG drawing is read.
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
    /// Side: auto (outermost outlines outside, their holes inside), outside, inside or on.
    #[arg(long, default_value = "auto")]
    pub side: String,
    /// Tool diameter, mm [default: 6].
    #[arg(long)]
    pub tool_diameter: Option<f64>,
    /// Depth of the cut below the top, mm [default: 6].
    #[arg(long)]
    pub depth: Option<f64>,
    /// Stock thickness, mm [default: the depth: the cut goes through]. Tabs are placed only
    /// when the depth reaches it.
    #[arg(long)]
    pub stock_thickness: Option<f64>,
    /// Step-down per level, mm [default: 2].
    #[arg(long)]
    pub step_down: Option<f64>,
    /// Radial stock the levels leave for a finishing pass at full depth, mm [default: 0, no
    /// finishing pass].
    #[arg(long)]
    pub stock_to_leave: Option<f64>,
    /// Conventional milling instead of climb.
    #[arg(long)]
    pub conventional: bool,
    /// Tangent lead-in and lead-out arc radius, mm (0: none).
    #[arg(long, default_value_t = 2.0)]
    pub lead_radius: f64,
    /// Entry at each level: ramp (along the profile) or helix (beside it, where it fits).
    #[arg(long, default_value = "ramp")]
    pub entry: String,
    /// Helix radius, mm.
    #[arg(long, default_value_t = 2.0)]
    pub helix_radius: f64,
    /// Ramp and helix angle, degrees.
    #[arg(long, default_value_t = 3.0)]
    pub ramp_angle: f64,
    /// Path tolerance, mm: the path stays within it of the exact offset, never nearer the
    /// wall [default: 0.01].
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Feed: mm/min (`1000`) or in/min (`40ipm`).
    #[arg(long, default_value = "1000")]
    pub feed: String,
    /// Plunge feed, mm/min.
    #[arg(long, default_value_t = 300.0)]
    pub plunge_feed: f64,
    /// Safe height above the top for rapids between outlines, mm.
    #[arg(long, default_value_t = 10.0)]
    pub safe_height: f64,
    /// Clearance height above the top where feeding down starts, mm.
    #[arg(long, default_value_t = 2.0)]
    pub clearance_height: f64,
    /// Holding tabs per outline: a number, or auto (one per started 150 mm of perimeter, 2 to
    /// 16); 0 for none.
    #[arg(long, default_value = "0")]
    pub tabs: String,
    /// Tab width along the outline, mm.
    #[arg(long, default_value_t = 6.0)]
    pub tab_width: f64,
    /// Tab height above the stock's bottom, mm.
    #[arg(long, default_value_t = 2.0)]
    pub tab_height: f64,
    /// Tab shape: square or ramped (45° ramps).
    #[arg(long, default_value = "square")]
    pub tab_shape: String,
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
    /// Print the report as one JSON object on stdout instead of the summary line.
    #[arg(long)]
    pub json: bool,
}

impl Args {
    /// The engine's profile settings these flags give.
    pub fn settings(&self) -> ProfileSettings {
        ProfileSettings {
            import: self.import.settings(),
            side: self.side.clone(),
            tool_diameter: self.tool_diameter,
            depth: self.depth,
            stock_thickness: self.stock_thickness,
            step_down: self.step_down,
            stock_to_leave: self.stock_to_leave,
            conventional: self.conventional,
            lead_radius: self.lead_radius,
            entry: self.entry.clone(),
            helix_radius: self.helix_radius,
            ramp_angle: self.ramp_angle,
            tolerance: self.tolerance,
            feed: self.feed.clone(),
            plunge_feed: self.plunge_feed,
            safe_height: self.safe_height,
            clearance_height: self.clearance_height,
            tabs: self.tabs.clone(),
            tab_width: self.tab_width,
            tab_height: self.tab_height,
            tab_shape: self.tab_shape.clone(),
            machine: self.machine.clone(),
        }
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let settings = args.settings();
    let program = args.program.settings();
    // The flags are checked before the drawing is read (exit 2 at once).
    settings.options(args.sample)?;
    let job = match &args.drawing {
        Some(name) => {
            let loops = super::outline_input::load_outline(name, &args.import)?;
            millpath::job::profile::run(
                ProfileSource::Drawing {
                    loops: &loops,
                    name,
                },
                &settings,
                &program,
            )?
        }
        None => millpath::job::profile::run(ProfileSource::Sample, &settings, &program)?,
    };
    let rep = &job.report;
    if let Some(out) = &args.output {
        millpath::io::write_atomic(out, job.gcode.as_bytes())?;
    }
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(rep)
            .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    for n in &rep.notes {
        super::eprint(&format!("note: {n}"));
    }
    if args.json {
        return super::print_json(rep);
    }
    super::print(&summary_line(rep));
    Ok(())
}

/// The summary line printed without `--json`.
fn summary_line(rep: &ProfileReport) -> String {
    let (arcs, lines) = rep
        .outlines
        .iter()
        .fold((0, 0), |(a, l), o| (a + o.arcs, l + o.lines));
    let band = rep
        .outlines
        .iter()
        .map(|o| o.band_max_mm - o.offset_mm)
        .fold(0.0, f64::max);
    format!(
        "profile: {} outlines ({arcs} arcs, {lines} lines per finishing pass), {} tabs, path within {band:.2e} mm of the exact offset (T = {} mm), min clearance {:.6} mm (needs {:.6}), {} levels, cycle time {:.2} s on {}",
        rep.outlines.len(),
        rep.tabs.len(),
        rep.tolerance_mm,
        rep.min_clearance_mm,
        rep.required_clearance_mm,
        rep.levels,
        rep.cycle_time_s,
        rep.machine,
    )
}
