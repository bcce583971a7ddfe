//! `millpath verify`: checks a G-code program against a pocket outline.

use millpath::job::verify::VerifySettings;
use millpath::stock;
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Arguments of `millpath verify`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath verify pocket.ngc --outline sample:aerospace --tool-diameter 12.7\n  millpath verify pocket.ngc --outline sample:aerospace   # the tool its header names (millpath's programs)\n  millpath verify pocket.ngc --outline part.dxf --tool-diameter 10 --json --svg pocket.svg --per-level\n  millpath verify other-cam.nc --outline part.dxf --tool-diameter 10 --machine hsm   # removal rate, time not cutting\n  millpath verify pocket.nc --dialect fanuc --outline sample:aerospace --tool-diameter 12.7\n\nExit code 2 when the program fails verification (the findings are printed first)."
)]
pub struct Args {
    /// The G-code program.
    pub program: PathBuf,
    /// Dialect of the program: linuxcnc, fanuc, sinumerik, grbl, or auto (the default: found
    /// from the program's extension and words, falling back to the next dialect that reads
    /// all of it, as `millpath estimate` does; a `note:` on stderr says which and why).
    #[arg(long, default_value = "auto")]
    pub dialect: String,
    /// Subroutine folders and tool table.
    #[command(flatten)]
    pub files: super::ProgramFiles,
    /// The pocket outline (.json, .dxf, .svg, sample:aerospace or sample:part).
    #[arg(long, required_unless_present = "job")]
    pub outline: Option<String>,
    /// Check the program against a job file instead (`millpath job`): the part it means to
    /// make, cut section by section (one per tool) into one stock, held by its tabs.
    #[arg(long, conflicts_with_all = ["outline", "tool_diameter", "select", "svg"])]
    pub job: Option<PathBuf>,
    /// How a DXF or SVG drawing is read.
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
    /// Tool diameter, mm [default: the tool the program's header names, `(tool T1: flat end
    /// mill D6 mm, ...)` in millpath's programs]
    #[arg(long)]
    pub tool_diameter: Option<f64>,
    /// Wall stock the program must leave, mm.
    #[arg(long, default_value_t = 0.0)]
    pub wall_stock: f64,
    /// The nominal stepover, for the share above the nominal engagement.
    #[arg(long, default_value = "0.4")]
    pub stepover: String,
    /// Raster cell of the stock simulation, mm [default: 0.05 up to a 12.7 mm tool, then
    /// 1/254 of the diameter: the simulation's resolution, like every tolerance, scales
    /// with the tool above 12.7 mm]
    #[arg(long)]
    pub cell: Option<f64>,
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
    /// Also plan the program on this machine (a preset, `millpath machines`, or a TOML
    /// file): its cycle time, the time not cutting and the removal rate.
    #[arg(long)]
    pub machine: Option<String>,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    if let Some(job) = &args.job {
        return run_job(args, job);
    }
    let Some(outline) = &args.outline else {
        return Err(InputError::new("outline", "missing")
            .expected("--outline, or --job")
            .into());
    };
    let text = super::read_text(&args.program)?;
    let origin = args.program.display().to_string();
    let tool_diameter = millpath::job::verify::tool_diameter(args.tool_diameter, &text, &origin)?;
    let settings = VerifySettings {
        tool_diameter,
        wall_stock: args.wall_stock,
        stepover: args.stepover.clone(),
        cell: args.cell,
        decimals: args.decimals,
        select: args.select.clone(),
        subroutine_path: args.files.subroutine_path.clone(),
        tool_table: args.files.tool_table.clone(),
        step_budget: args.files.step_budget,
        dialect: args.dialect.clone(),
        machine: args.machine.clone(),
    };
    settings.check()?;
    let loops = super::pocket::load_outline(outline, &args.import)?;
    let job = millpath::job::verify::run(&loops, &text, &origin, &settings)?;
    super::dialect_note(&job.dialect);
    let (tp, pv, problems) = (&job.toolpath, &job.part, &job.problems);
    let v = pv.total.clone();
    let pockets = loops.pockets();
    let chosen: Vec<_> = job.selected.iter().map(|&i| &pockets[i - 1]).collect();
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
            tp,
            &outlines,
            &millpath::report::PreviewOptions::default().with_title(Some(format!(
                "{} over {}",
                args.program.display(),
                outline
            ))),
            args.per_level,
        )?;
    }
    if args.json {
        let mut j = job.json();
        j["pictures"] = serde_json::json!(pictures);
        super::print_json(&j)?;
    } else {
        print_text(tp, &v);
        print_removal(&v, &job);
        for k in &pv.unreachable {
            super::print(&format!(
                "pocket {}: not reachable with this tool (no position of a {} mm tool fits \
                 inside it), left uncut",
                k + 1,
                settings.tool_diameter
            ));
        }
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
                stock::problems_text(problems)
            ))
            .into())
    }
}

/// `--job`: the program against the part a job file means to make.
fn run_job(args: &Args, job: &std::path::Path) -> Result<(), Error> {
    let spec = millpath::job::part::read_file(job)?;
    let text = super::read_text(&args.program)?;
    let run = millpath::job::part::verify_program(
        &spec,
        &text,
        &args.program.display().to_string(),
        &args.dialect,
    )?;
    super::dialect_note(&run.dialect);
    let problems = run.problems();
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&run.json())
            .map_err(|e| Error::internal(format!("report: {e}")))?;
        millpath::io::write_atomic(path, text.as_bytes())?;
    }
    if args.json {
        super::print_json(&run.json())?;
    } else {
        for (k, v) in run.check.rows() {
            super::print(&format!("{k}: {v}"));
        }
    }
    if problems.is_empty() {
        if !args.json {
            super::print("verification passed");
        }
        Ok(())
    } else {
        Err(InputError::new("program", args.program.display())
            .expected(format!(
                "a program that makes the part {} means: {}",
                job.display(),
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

fn print_removal(v: &stock::Verification, job: &millpath::job::verify::VerifyRun) {
    let e = &v.engagement;
    let timing = job.timing.as_ref().map_or(String::new(), |t| {
        format!(
            "; on {}: cycle time {:.2} s, entries {:.2} s, not cutting {:.2} s (rapids {:.2} s), \
             removal {:.0} mm³/s",
            t.machine,
            t.cycle_time_s,
            t.entry_time_s,
            t.air_time_s,
            t.rapid_time_s,
            t.removal_rate_mm3_s
        )
    });
    super::print(&format!(
        "removal {:.0} mm³; engagement outside entries mean {:.1}° p95 {:.1}° max {:.1}°, {:.2}% \
         above 1.1 × nominal; the sharpest corner forces {:.1}°{timing}",
        v.removed_mm3,
        e.mean_deg,
        e.p95_deg,
        e.max_deg,
        100.0 * e.share_above_bound,
        job.engagement_floor_deg
    ));
}
