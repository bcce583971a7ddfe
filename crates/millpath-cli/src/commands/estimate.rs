//! `millpath estimate`: the cycle time of a G-code program on a machine.

use super::print;
use millpath::gcode::{Dialect, Reader, ReaderOptions};
use millpath::motion::table2;
use millpath::motion::verify::{VerifyOptions, verify_plan};
use millpath::motion::{PlanOptions, plan_moves};
use millpath::{Error, InputError, Point3};
use std::cell::Cell;
use std::io::{BufReader, IsTerminal, Read};
use std::path::PathBuf;
use std::rc::Rc;

/// Counts the bytes read, for the progress bar.
struct Counting<R> {
    inner: R,
    count: Rc<Cell<u64>>,
}

impl<R: Read> Read for Counting<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.count.set(self.count.get() + n as u64);
        Ok(n)
    }
}

/// Files larger than this get a progress bar on a terminal.
const PROGRESS_BYTES: u64 = 4 << 20;

/// Bytes of a program read to find its dialect (`--dialect auto`).
const DETECT_BYTES: usize = 8192;

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
    /// from the program's first lines: `%`/`O` number → fanuc, `G710`/`G700`/`CYCLE832` →
    /// sinumerik, `;` comments → grbl, else linuxcnc).
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
/// Whether the limit verifier runs: not with `--no-verify`, nor on the `linuxcnc` controller
/// model, whose plans follow LinuxCNC's rules (kinks within its ratio, parabolic blends), not
/// the verifier's, and are judged against LinuxCNC itself (`violations` is then null).
fn verifies(args: &Args, machine: &millpath::machine::Machine) -> bool {
    !args.no_verify && machine.controller != millpath::machine::Controller::LinuxCnc
}

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
    if !(args.rate.is_finite() && args.rate >= 1000.0) {
        return Err(InputError::new("rate", args.rate)
            .at("--rate")
            .expected("a sampling rate of at least 1000 Hz")
            .into());
    }
    let Some(path) = &args.file else {
        return Err(InputError::new("FILE", "missing")
            .expected("a G-code file")
            .into());
    };
    let file = std::fs::File::open(path).map_err(|e| {
        Error::Input(
            InputError::new("input file", path.display())
                .expected(format!("a readable G-code file ({e})")),
        )
    })?;
    let dialect = match args.dialect.as_str() {
        "auto" => {
            let mut head = Vec::with_capacity(DETECT_BYTES);
            Read::by_ref(&mut &file)
                .take(DETECT_BYTES as u64)
                .read_to_end(&mut head)
                .map_err(|e| {
                    Error::Input(
                        InputError::new("input file", path.display())
                            .expected(format!("a readable G-code file ({e})")),
                    )
                })?;
            std::io::Seek::rewind(&mut &file).map_err(|e| {
                Error::Input(
                    InputError::new("input file", path.display())
                        .expected(format!("a seekable G-code file ({e})")),
                )
            })?;
            Dialect::detect(&String::from_utf8_lossy(&head))
        }
        d => d.parse::<Dialect>().map_err(|e| e.at("--dialect"))?,
    };
    let opts = ReaderOptions {
        dialect,
        lenient: args.lenient,
        origin: path.display().to_string(),
        // LinuxCNC stops where its task waits for motion (spindle, coolant, tool commands).
        sync_points: (machine.controller == millpath::machine::Controller::LinuxCnc)
            .then_some(machine.sync_wait),
        ..ReaderOptions::default()
    }
    .with_program_files(
        path,
        &args.files.subroutine_path,
        args.files.tool_table.as_deref(),
    )?;
    let start = opts.start;
    let size = file.metadata().map_or(0, |m| m.len());
    let count = Rc::new(Cell::new(0));
    let bar = (size > PROGRESS_BYTES && std::io::stderr().is_terminal()).then(|| {
        let b = indicatif::ProgressBar::new(size);
        b.set_message("reading and planning");
        b
    });
    let counting = Counting {
        inner: file,
        count: Rc::clone(&count),
    };
    let mut reader = Reader::new(BufReader::new(counting), opts);
    let mut n_read: u64 = 0;
    let mut at = start;
    // Every move with where it starts, the progress bar advanced as the file is read.
    let tracked = std::iter::from_fn(|| {
        let item = reader.next()?;
        n_read += 1;
        if let Some(b) = &bar
            && n_read % 65_536 == 0
        {
            b.set_position(count.get());
        }
        Some(item.map(|rm| {
            let f = at;
            at = rm.mv.to;
            (f, rm.mv)
        }))
    });
    if args.samples.is_none() && args.html.is_none() && args.svg.is_none() {
        // Bounded memory: the planner streams, the verifier checks each chunk as it is timed.
        let streamed = run_streaming(tracked, &machine, args);
        if let Some(b) = &bar {
            b.finish_and_clear();
        }
        return streamed;
    }
    // Samples and pictures need the whole plan and every move (so does the verifier then).
    let mut moves: Vec<(Point3, millpath::Move)> = Vec::new();
    let stream = tracked.inspect(|item| {
        if let Ok(x) = item {
            moves.push(*x);
        }
    });
    let plan = plan_moves(stream, &machine, &PlanOptions::default())?;
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let violations = if !verifies(args, &machine) {
        None
    } else {
        let rep = verify_plan(
            &plan,
            &moves,
            &machine,
            &VerifyOptions {
                rate: args.rate,
                ..VerifyOptions::default()
            },
        )?;
        Some(rep.violations)
    };
    if let Some(out) = &args.samples {
        write_samples(&plan, out, args.rate)?;
    }
    let mut tp = millpath::Toolpath::new(millpath::Tool::default(), start);
    if args.html.is_some() || args.svg.is_some() {
        tp.moves = moves.iter().map(|(_, m)| *m).collect();
        millpath::stock::infer_levels(&mut tp);
    }
    let mut pictures = Vec::new();
    if let Some(out) = &args.svg {
        pictures = super::write_previews(
            out,
            &tp,
            &[],
            &millpath::report::PreviewOptions {
                title: Some(format!(
                    "{}: {:.2} s on {}",
                    path.display(),
                    plan.total_time(),
                    machine.name
                )),
                achieved_feed: Some(plan.peak_feed_by_move(tp.moves.len())),
                ..millpath::report::PreviewOptions::default()
            },
            args.per_level,
        )?;
    }
    if let Some(out) = &args.html {
        let summary = vec![
            super::html::machine_row(&machine),
            ("program".to_owned(), path.display().to_string()),
            (
                "cycle time".to_owned(),
                format!("{:.3} s", plan.total_time()),
            ),
            ("blocks".to_owned(), plan.blocks.len().to_string()),
            (
                "limit violations (1 kHz verifier)".to_owned(),
                violations.map_or("not checked".into(), |v| v.to_string()),
            ),
        ];
        let html = super::html::toolpath_report(
            &format!("millpath estimate {}", path.display()),
            summary,
            &tp,
            &[],
            &plan,
        )?;
        super::html::write(out, &html)?;
    }
    let naive: f64 = plan
        .blocks
        .iter()
        .filter(|b| b.programmed_feed > 0.0)
        .map(|b| b.length / b.programmed_feed)
        .sum();
    if args.json {
        let mut obj = serde_json::json!({
            "cycle_time_s": plan.total_time(),
            "blocks": plan.blocks.len(),
            "spans": plan.spans.len(),
            "violations": violations,
            "machine": machine.name,
            "time_at_programmed_feed_s": naive,
            "pictures": pictures,
        });
        if args.blocks {
            let per: Vec<_> = plan
                .blocks
                .iter()
                .map(|b| serde_json::json!({"start_s": b.start_time, "time_s": b.time, "peak_feed_mm_s": b.peak_feed, "length_mm": b.length, "move": b.origin}))
                .collect();
            obj["per_block"] = serde_json::Value::Array(per);
        }
        print(&obj.to_string());
    } else {
        print(&format!(
            "cycle time {:.3} s on {} ({} blocks; {:.3} s at programmed feeds); limit violations: {}",
            plan.total_time(),
            machine.name,
            plan.blocks.len(),
            naive,
            violations.map_or("not checked".into(), |v| v.to_string())
        ));
        if !pictures.is_empty() {
            print(&format!(
                "preview: {}",
                pictures
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    Ok(())
}

/// `estimate` without `--samples` or `--html`: plans in bounded memory
/// ([`millpath::motion::stream::plan_stream`]) and verifies each chunk as it is timed (a
/// chunk boundary is a knot where the acceleration is zero; its junction is the one check the
/// chunked verifier does not repeat across chunks). Same output as the whole-program path.
fn run_streaming<I>(
    stream: I,
    machine: &millpath::machine::Machine,
    args: &Args,
) -> Result<(), Error>
where
    I: Iterator<Item = Result<(Point3, millpath::Move), Error>>,
{
    use millpath::motion::stream::{StreamOptions, plan_stream};
    let mut violations = 0usize;
    let mut per_block = Vec::new();
    let vopts = VerifyOptions {
        rate: args.rate,
        ..VerifyOptions::default()
    };
    let sum = plan_stream(stream, machine, &StreamOptions::default(), |chunk| {
        if verifies(args, machine) {
            violations += verify_plan(&chunk.plan, &chunk.moves, machine, &vopts)?.violations;
        }
        if args.json && args.blocks {
            per_block.extend(chunk.plan.blocks.iter().map(|b| {
                serde_json::json!({"start_s": chunk.start_time + b.start_time, "time_s": b.time,
                    "peak_feed_mm_s": b.peak_feed, "length_mm": b.length, "move": b.origin})
            }));
        }
        Ok(())
    })?;
    let violations = verifies(args, machine).then_some(violations);
    if args.json {
        let mut obj = serde_json::json!({
            "cycle_time_s": sum.total_time,
            "blocks": sum.blocks,
            "spans": sum.spans,
            "violations": violations,
            "machine": machine.name,
            "time_at_programmed_feed_s": sum.time_at_programmed_feed,
        });
        if args.blocks {
            obj["per_block"] = serde_json::Value::Array(per_block);
        }
        print(&obj.to_string());
    } else {
        print(&format!(
            "cycle time {:.3} s on {} ({} blocks; {:.3} s at programmed feeds); limit violations: {}",
            sum.total_time,
            machine.name,
            sum.blocks,
            sum.time_at_programmed_feed,
            violations.map_or("not checked".into(), |v| v.to_string())
        ));
    }
    Ok(())
}

fn write_samples(
    plan: &millpath::motion::Plan,
    out: &std::path::Path,
    rate: f64,
) -> Result<(), Error> {
    let samples = plan.sample(1.0 / rate)?;
    let json = out.extension().is_some_and(|e| e == "json");
    let mut text = String::new();
    if json {
        let rows: Vec<_> = samples
            .iter()
            .map(|s| {
                serde_json::json!({"t": s.t, "block": s.block, "pos": s.position.to_array(), "feed": s.feed,
                    "vel": s.vel, "acc": s.acc, "jerk": s.jerk})
            })
            .collect();
        text = serde_json::Value::Array(rows).to_string();
    } else {
        text.push_str("t,block,x,y,z,feed,vx,vy,vz,ax,ay,az,jx,jy,jz\n");
        for s in &samples {
            let p = s.position;
            text.push_str(&format!(
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                s.t,
                s.block,
                p.x,
                p.y,
                p.z,
                s.feed,
                s.vel[0],
                s.vel[1],
                s.vel[2],
                s.acc[0],
                s.acc[1],
                s.acc[2],
                s.jerk[0],
                s.jerk[1],
                s.jerk[2]
            ));
        }
    }
    millpath::io::write_atomic(out, text.as_bytes())
}
