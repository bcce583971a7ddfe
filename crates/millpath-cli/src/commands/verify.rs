//! `millpath verify`: checks a G-code program against a pocket outline.

use millpath::gcode::{ReaderOptions, read_str};
use millpath::stock::{self, StockSpec};
use millpath::strategy::pocket::{Stepover, nominal_engagement};
use millpath::toolpath::Tool;
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Arguments of `millpath verify`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath verify pocket.ngc --outline sample:aerospace --tool-diameter 12.7\n  millpath verify pocket.ngc --outline part.dxf --tool-diameter 10 --json --svg pocket.svg --per-level\n\nExit code 2 when the program fails verification (the findings are printed first)."
)]
pub struct Args {
    /// The G-code program (LinuxCNC dialect).
    pub program: PathBuf,
    /// The pocket outline (.json, .dxf, .svg or sample:aerospace).
    #[arg(long)]
    pub outline: String,
    /// How a DXF or SVG drawing is read.
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
    /// Tool diameter, mm.
    #[arg(long)]
    pub tool_diameter: f64,
    /// Wall stock the program must leave, mm.
    #[arg(long, default_value_t = 0.0)]
    pub wall_stock: f64,
    /// The nominal stepover, for the share above the nominal engagement.
    #[arg(long, default_value = "0.4")]
    pub stepover: String,
    /// Raster cell, mm.
    #[arg(long, default_value_t = 0.05)]
    pub cell: f64,
    /// Write the findings as JSON.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Print the findings as one JSON object on stdout instead of the text line.
    #[arg(long)]
    pub json: bool,
    /// Write an SVG preview of the program over the outline and islands (plan and side view,
    /// coloured by programmed feed, rapids dashed, entries marked).
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// With --svg: also one picture per level, `NAME.level1.svg`, ...
    #[arg(long, requires = "svg")]
    pub per_level: bool,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let tool = Tool::flat(args.tool_diameter).map_err(|e| e.at("--tool-diameter"))?;
    if !(args.wall_stock.is_finite() && args.wall_stock >= 0.0) {
        return Err(InputError::new("wall stock", args.wall_stock)
            .at("--wall-stock")
            .expected("a stock >= 0 mm")
            .into());
    }
    if !(args.cell.is_finite() && args.cell > 0.0) {
        return Err(InputError::new("cell", args.cell)
            .at("--cell")
            .expected("a cell > 0 mm")
            .into());
    }
    let s = Stepover::parse(&args.stepover)?.distance(tool.diameter);
    let loops = super::pocket::load_outline(&args.outline, &args.import)?;
    let text = super::read_text(&args.program)?;
    let ropts = ReaderOptions {
        origin: args.program.display().to_string(),
        ..ReaderOptions::default()
    };
    let (mut tp, _warnings) = read_str(&text, ropts)?;
    tp.tool = tool;
    stock::infer_levels(&mut tp);
    let spec = StockSpec {
        outer: &loops.outer,
        islands: &loops.islands,
        wall_stock: args.wall_stock,
    };
    let sim = stock::SimOptions {
        cell: args.cell,
        step: (2.0 * args.cell).max(0.1),
        ..stock::SimOptions::default()
    };
    let v = stock::verify(
        &tp,
        spec,
        nominal_engagement(s, tool.radius()).to_degrees(),
        &sim,
    );
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&v)
            .map_err(|e| Error::internal(format!("report: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    let mut pictures = Vec::new();
    if let Some(out) = &args.svg {
        let mut outlines = vec![loops.outer.clone()];
        outlines.extend(loops.islands.iter().cloned());
        pictures = super::write_previews(
            out,
            &tp,
            &outlines,
            &millpath::report::PreviewOptions {
                title: Some(format!("{} over {}", args.program.display(), args.outline)),
                ..millpath::report::PreviewOptions::default()
            },
            args.per_level,
        )?;
    }
    let problems = v.problems();
    if args.json {
        super::print_json(&serde_json::json!({
            "passed": problems.is_empty(),
            "problems": problems,
            "levels": tp.levels.len(),
            "verification": v,
            "pictures": pictures,
        }))?;
    } else {
        print_text(&tp, &v);
    }
    if problems.is_empty() {
        if !args.json {
            super::print("verification passed");
        }
        Ok(())
    } else {
        Err(InputError::new("program", args.program.display())
            .expected(format!(
                "a program that passes verification: {}",
                problems.join("; ")
            ))
            .into())
    }
}

fn print_text(tp: &millpath::Toolpath, v: &stock::Verification) {
    super::print(&format!(
        "levels {}, min clearance {:.6} mm (needs {:.6}), uncut {:.3} mm², rapids through material {}, \
         plunges {}, engagement max {:.1}° mean {:.1}°",
        tp.levels.len(),
        v.min_clearance_mm,
        v.required_clearance_mm,
        v.uncut_area_mm2,
        v.rapids_through_material,
        v.plunges,
        v.max_engagement_deg,
        v.mean_engagement_deg
    ));
}
