//! `millpath estimate`: the cycle time of a G-code program on a machine.

use super::print;
use millpath::job::estimate::{Estimate, EstimateSettings};
use millpath::motion::table2;
use millpath::{Error, InputError};
use std::io::IsTerminal;
use std::path::PathBuf;

/// Files larger than this get a progress bar on a terminal.
const PROGRESS_BYTES: u64 = 4 << 20;

/// Arguments of `millpath estimate`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath estimate part.ngc --machine hsm\n  millpath estimate part.nc --dialect fanuc --machine hsm\n  millpath estimate part.ngc --svg part.svg --per-level   # part.svg, part.level1.svg, ...\n  millpath estimate part.ngc --machine my_mill.toml --json --samples traj.csv --rate 2000\n  millpath estimate --table2"
)]
pub struct Args {
    /// The G-code program.
    #[arg(required_unless_present = "table2")]
    pub file: Option<PathBuf>,
    /// A preset name (see `millpath machines`) or a TOML machine profile.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// Print a JSON object on stdout.
    #[arg(long)]
    pub json: bool,
    /// Include per-block times and peak feeds in the JSON output.
    #[arg(long)]
    pub blocks: bool,
    /// Write the sampled trajectory to this file (.csv or .json).
    #[arg(long)]
    pub samples: Option<PathBuf>,
    /// Sampling rate in Hz for --samples and the verifier (at least 1000).
    #[arg(long, default_value_t = 1000.0)]
    pub rate: f64,
    /// Skip the limit verifier (faster on huge programs; `violations` is then null).
    #[arg(long)]
    pub no_verify: bool,
    /// Dialect of the program: linuxcnc, fanuc, sinumerik, grbl, or auto (the default: found
    /// from the file's extension and words, e.g. `.ngc`/`o<sub>`/`#<x>` → linuxcnc,
    /// `%`/`O1234`/`M98`/`WHILE [..] DO1` → fanuc, `.mpf`/`G710`/`G70`/`CYCLE832` →
    /// sinumerik, `;` comments alone → grbl; when that dialect refuses the program, the next
    /// that reads all of it; a `note:` on stderr says which and why).
    #[arg(long, default_value = "auto")]
    pub dialect: String,
    /// Skip unsupported G-code words with a warning instead of refusing them.
    #[arg(long)]
    pub lenient: bool,
    /// Write a self-contained HTML report (summary, viewer with playback, feed plot).
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Write an SVG preview: plan view and side view, moves coloured by the achieved feed
    /// (from the planner), rapids dashed, entries marked; levels found from the retracts.
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// With --svg: also one picture per level, `NAME.level1.svg`, `NAME.level2.svg`, ...
    #[arg(long, requires = "svg")]
    pub per_level: bool,
    /// Print the adaptive-spiral paper's Table 2 (square vs circle) against this machine.
    #[arg(long)]
    pub table2: bool,
    /// Subroutine folders and tool table.
    #[command(flatten)]
    pub files: super::ProgramFiles,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let machine = super::load_machine(&args.machine)?;
    if args.table2 {
        let rows = table2::compare(&machine)?;
        if args.json {
            print(
                &serde_json::to_string_pretty(&rows).map_err(|e| Error::internal(e.to_string()))?,
            );
        } else {
            print(&table2::format_table(&rows));
        }
        return Ok(());
    }
    let Some(path) = &args.file else {
        return Err(InputError::new("FILE", "missing")
            .expected("a G-code file")
            .into());
    };
    let settings = EstimateSettings {
        rate: args.rate,
        verify: !args.no_verify,
        dialect: args.dialect.clone(),
        lenient: args.lenient,
        subroutine_path: args.files.subroutine_path.clone(),
        tool_table: args.files.tool_table.clone(),
        step_budget: args.files.step_budget,
        per_block: args.json && args.blocks,
        // Samples and pictures need the whole plan and every move.
        whole: args.samples.is_some() || args.html.is_some() || args.svg.is_some(),
        ..EstimateSettings::default()
    };
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    let bar = (size > PROGRESS_BYTES && std::io::stderr().is_terminal()).then(|| {
        let b = indicatif::ProgressBar::new(size);
        b.set_message("reading and planning");
        b
    });
    let run = millpath::job::estimate::run(path, &machine, &settings, &mut |n| {
        if let Some(b) = &bar {
            b.set_position(n);
        }
    });
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let run = run?;
    super::dialect_note(&run.dialect);
    let e = &run.estimate;
    let mut pictures = Vec::new();
    if let (Some(plan), Some(tp)) = (&run.plan, &run.toolpath) {
        if let Some(out) = &args.samples {
            let json = out.extension().is_some_and(|e| e == "json");
            let text = millpath::job::estimate::samples_text(plan, args.rate, json)?;
            millpath::io::write_atomic(out, text.as_bytes())?;
        }
        pictures = write_pictures(args, path, &machine, e, plan, tp)?;
    }
    let checked = e.violations.map_or("not checked".into(), |v| v.to_string());
    if args.json {
        let mut obj = serde_json::to_value(e).map_err(|e| Error::internal(e.to_string()))?;
        if run.plan.is_some() {
            obj["pictures"] = serde_json::json!(pictures);
        }
        print(&obj.to_string());
        return Ok(());
    }
    print(&format!(
        "cycle time {:.3} s on {} ({} blocks; {:.3} s at programmed feeds); limit violations: {checked}",
        e.cycle_time_s, machine.name, e.blocks, e.time_at_programmed_feed_s,
    ));
    if !pictures.is_empty() {
        let names: Vec<_> = pictures.iter().map(|p| p.display().to_string()).collect();
        print(&format!("preview: {}", names.join(", ")));
    }
    Ok(())
}

/// Writes `--svg` and `--html`; returns the pictures written.
fn write_pictures(
    args: &Args,
    path: &std::path::Path,
    machine: &millpath::machine::Machine,
    e: &Estimate,
    plan: &millpath::motion::Plan,
    tp: &millpath::Toolpath,
) -> Result<Vec<PathBuf>, Error> {
    let mut pictures = Vec::new();
    if let Some(out) = &args.svg {
        let title = format!(
            "{}: {:.2} s on {}",
            path.display(),
            e.cycle_time_s,
            machine.name
        );
        pictures = super::write_previews(
            out,
            tp,
            &[],
            &millpath::report::PreviewOptions::default()
                .with_title(Some(title))
                .with_achieved_feed(Some(plan.peak_feed_by_move(tp.moves.len()))),
            args.per_level,
        )?;
    }
    if let Some(out) = &args.html {
        let summary = vec![
            super::html::machine_row(machine),
            ("program".to_owned(), path.display().to_string()),
            ("cycle time".to_owned(), format!("{:.3} s", e.cycle_time_s)),
            ("blocks".to_owned(), e.blocks.to_string()),
            (
                "limit violations (1 kHz verifier)".to_owned(),
                e.violations.map_or("not checked".into(), |v| v.to_string()),
            ),
        ];
        let title = format!("millpath estimate {}", path.display());
        let html = super::html::toolpath_report(&title, summary, tp, &[], plan)?;
        super::html::write(out, &html)?;
    }
    Ok(pictures)
}
