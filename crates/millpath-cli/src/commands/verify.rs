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
    /// Subroutine folders and tool table.
    #[command(flatten)]
    pub files: super::ProgramFiles,
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
    /// Decimals the program was written with (the gouge test allows for its rounding,
    /// 2·½·10^−d·√2 mm); default: the most found in the program's X, Y, Z, I, J, R words.
    #[arg(long)]
    pub decimals: Option<u32>,
    /// Check only these pockets of the drawing (as `pocket --select` cut them): `1,3`.
    #[arg(long)]
    pub select: Option<String>,
}

/// The most decimals written in the program's coordinate words (X, Y, Z, I, J, K, R), 3 when
/// none has any.
pub fn program_decimals(text: &str) -> u32 {
    let mut best = 0u32;
    for line in text.lines() {
        let code = line.split([';', '(']).next().unwrap_or("");
        let b = code.as_bytes();
        for (i, &c) in b.iter().enumerate() {
            if !matches!(
                c.to_ascii_uppercase(),
                b'X' | b'Y' | b'Z' | b'I' | b'J' | b'K' | b'R'
            ) {
                continue;
            }
            let rest = &b[i + 1..];
            let num: Vec<u8> = rest
                .iter()
                .copied()
                .take_while(|d| d.is_ascii_digit() || matches!(d, b'.' | b'-' | b'+' | b' '))
                .filter(|d| *d != b' ')
                .collect();
            if let Some(dot) = num.iter().position(|&d| d == b'.') {
                let digits = num[dot + 1..]
                    .iter()
                    .take_while(|d| d.is_ascii_digit())
                    .count();
                best = best.max(digits as u32);
            }
        }
    }
    if best == 0 { 3 } else { best }
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
    }
    .with_program_files(
        &args.program,
        &args.files.subroutine_path,
        args.files.tool_table.as_deref(),
    )?;
    let (mut tp, _warnings) = read_str(&text, ropts)?;
    tp.tool = tool;
    stock::infer_levels(&mut tp);
    let decimals = args.decimals.unwrap_or_else(|| program_decimals(&text));
    let resolution = stock::gouge_resolution(decimals);
    let selected = super::pocket::parse_select(args.select.as_deref(), loops.len())?;
    let pockets = loops.pockets();
    let chosen: Vec<_> = selected.iter().map(|&i| &pockets[i - 1]).collect();
    let specs: Vec<StockSpec<'_>> = chosen
        .iter()
        .map(|p| StockSpec {
            outer: &p.outer,
            islands: &p.islands,
            wall_stock: args.wall_stock,
        })
        .collect();
    let sim = stock::SimOptions {
        cell: args.cell,
        step: (2.0 * args.cell).max(0.1),
        ..stock::SimOptions::default()
    };
    let pv = stock::verify_part(
        &tp,
        &specs,
        nominal_engagement(s, tool.radius()).to_degrees(),
        &sim,
    );
    let v = pv.total.clone();
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&pv)
            .map_err(|e| Error::internal(format!("report: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    let mut pictures = Vec::new();
    if let Some(out) = &args.svg {
        let outlines: Vec<_> = chosen
            .iter()
            .flat_map(|p| std::iter::once(p.outer.clone()).chain(p.islands.iter().cloned()))
            .collect();
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
    let problems = pv.problems_within(resolution);
    if args.json {
        super::print_json(&serde_json::json!({
            "passed": problems.is_empty(),
            "problems": problems,
            "levels": tp.levels.len(),
            "verification": v,
            "pockets": pv.pockets,
            "cuts_outside": pv.cuts_outside,
            "decimals": decimals,
            "gouge_resolution_mm": resolution,
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
