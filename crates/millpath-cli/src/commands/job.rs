//! `millpath job`: a whole part from a job file (a drawing, the stock, a tool table and the
//! operations), and `--init` to write a starting job file for a drawing (the job itself is
//! [`millpath::job::part`]).

use millpath::Error;
use millpath::gcode::Dialect;
use millpath::job::part;
use std::path::{Path, PathBuf};

/// Arguments of `millpath job`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath job --init part.dxf                 # writes part.toml: every feature, tools sized from the drawing\n  millpath job part.toml -o part.ngc --html part.html\n  millpath job part.toml --dialect fanuc -o part.nc --report part.json\n\nThe job file (TOML) names the drawing, the stock ([stock] margin, thickness, top), the\ntools ([[tool]] number, type, diameter, flutes, flute_length, spindle, feed, plunge_feed)\nand the operations in order ([[operation]] type = face | pocket | profile | drill | bore,\ntool = N, and the operation's settings: a pocket's are `millpath pocket`'s flags).\nZ = 0 is the finished part's top."
)]
pub struct Args {
    /// The job file (TOML).
    #[arg(required_unless_present = "init", conflicts_with = "init")]
    pub job: Option<PathBuf>,
    /// Write a starting job file for this drawing (DXF or SVG) to `-o` (default: the
    /// drawing's name with `.toml`, in the current folder, never over an existing file).
    #[arg(long, value_name = "DRAWING")]
    pub init: Option<PathBuf>,
    /// The program (or, with --init, the job file) to write.
    #[arg(short = 'o', long)]
    pub output: Option<PathBuf>,
    /// JSON report output.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// A self-contained HTML report: the setup sheet, the toolpath viewer with playback.
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Print the report as one JSON object on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// The dialect, over the job file's `dialect`.
    #[arg(long)]
    pub dialect: Option<Dialect>,
    /// The machine for the cycle time, over the job file's `machine`.
    #[arg(long)]
    pub machine: Option<String>,
    /// How the drawing is read (with --init; a job file says it with its own keys).
    #[command(flatten)]
    pub import: super::outline_input::ImportArgs,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    if let Some(drawing) = &args.init {
        return init(args, drawing);
    }
    let Some(path) = &args.job else {
        return Err(millpath::InputError::new("job file", "none")
            .expected("a job file, or --init DRAWING")
            .into());
    };
    let run = part::run_file(path, args.dialect, args.machine.as_deref(), &mut |n| {
        super::eprint(&format!("note: {n}"));
    })?;
    if let Some(out) = &args.output {
        millpath::io::write_atomic(out, &run.run.gcode)?;
    }
    if let Some(p) = &args.report {
        let text = serde_json::to_string_pretty(&run.report)
            .map_err(|e| Error::internal(format!("report serialisation: {e}")))?;
        millpath::io::write_atomic(p, text.as_bytes())?;
    }
    if let Some(p) = &args.html {
        write_html(p, &run)?;
    }
    if args.json {
        return super::print_json(&run.report);
    }
    for o in &run.report.operations {
        super::print(&format!(
            "{}: {} with T{}, {}, {:.2} s",
            o.name, o.kind, o.tool, o.cut, o.time_s
        ));
    }
    super::print(&format!(
        "job: cycle time {:.2} s on {} ({} tool change(s)), {} operation(s); {}",
        run.report.cycle_time_s,
        run.report.machine,
        run.report.tool_changes,
        run.report.operations.len(),
        run.report
            .check
            .last()
            .map_or(String::new(), |(_, v)| v.clone())
    ));
    Ok(())
}

/// The self-contained HTML report: the setup sheet, the viewer, the feed plot.
fn write_html(path: &Path, run: &part::FileRun) -> Result<(), Error> {
    let plan = run.run.plan()?;
    let tp = run.run.toolpath();
    let mut html =
        millpath::report::html::HtmlReport::new(format!("millpath job {}", run.report.job));
    part::setup_sheet(&mut html, &run.report);
    html.toolpath_viewer("the whole job", &tp, &run.run.model.parts, &plan)?;
    super::html::write(path, &html)
}

/// `--init`: the starting job file.
fn init(args: &Args, drawing: &Path) -> Result<(), Error> {
    let out = match &args.output {
        Some(o) => o.clone(),
        None => {
            let stem = drawing
                .file_stem()
                .map_or("job".into(), |s| s.to_string_lossy().into_owned());
            let p = PathBuf::from(format!("{stem}.toml"));
            if p.exists() {
                return Err(millpath::InputError::new("job file", p.display())
                    .at("--init without -o")
                    .expected("a file that does not exist yet: give -o to write over it")
                    .into());
            }
            p
        }
    };
    let text = part::init_file(
        drawing,
        &out,
        &args.import.settings(),
        args.dialect.unwrap_or(Dialect::LinuxCnc),
        args.machine.as_deref().unwrap_or("hsm"),
        &mut |n| super::eprint(&format!("note: {n}")),
    )?;
    millpath::io::write_atomic(&out, text.as_bytes())?;
    super::eprint(&format!(
        "note: wrote {}; check it, then: millpath job {} -o part.ngc --html part.html",
        out.display(),
        out.display()
    ));
    Ok(())
}
