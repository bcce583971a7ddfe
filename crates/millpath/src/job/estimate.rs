//! The estimate job behind `millpath estimate`: a G-code file read by the streaming reader
//! (dialect given or found from the program's head), planned on the machine and checked by
//! the limit verifier, into an [`Estimate`]: cycle time, blocks, spans, limit violations and
//! the time at programmed feeds (Σ length / programmed feed over the feed blocks).
//!
//! The dialect, when not named (`auto`), is the best candidate of the program's clues
//! ([`DialectGuess`]: its file extension and first lines); when that dialect's reader refuses
//! the program, the other candidates are read in turn and the first that reads all of it is
//! taken (module [`crate::gcode`]'s `detect`): the estimate's [`EstimateRun::dialect`] says
//! which and why.
//!
//! Two ways through, same figures: streaming (bounded memory: the planner hands out chunks
//! whose boundaries are knots at rest and the verifier checks each chunk as it is timed), or
//! whole ([`EstimateSettings::whole`]: the plan and every move kept, for samples and
//! pictures). The verifier samples at `rate` ≥ 1 kHz; it does not run on the `linuxcnc`
//! controller model, whose plans follow LinuxCNC's rules and are judged against LinuxCNC.
//!
//! Rotary axes (LinuxCNC programs' A, B, C words) are planned by the `linuxcnc` controller
//! model, in joint space with each axis its own joint (trivkins), with the machine's rotary
//! limits ([`Machine::rotary`]): see `crate::motion`'s `linuxcnc` model. The `generic` and
//! `sinumerik` models, and the limit verifier, plan and check the X Y Z path only (a move of
//! rotary axes alone takes no time there).
//! Streaming on two or more cores ([`EstimateSettings::parallel`]), each chunk is verified on
//! a second thread while the next is read and planned: the verifier's work overlaps the
//! planner's, its counts are summed in program order, and the first error is the one the
//! sequential run would meet.

use crate::gcode::{Dialect, DialectChoice, DialectGuess, Reader, ReaderOptions, reads_whole};
use crate::machine::{Controller, Machine};
use crate::motion::stream::{Chunk, StreamOptions, empty_chunk, plan_stream, plan_stream_owned};
use crate::motion::verify::{VerifyOptions, verify_plan};
use crate::motion::{Plan, PlanOptions, plan_moves};
use crate::{Error, InputError, Move, Point3, Toolpath};
use serde::Serialize;
use std::cell::Cell;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Bytes of a program read to find its dialect (`--dialect auto`).
pub const DETECT_BYTES: usize = crate::gcode::DETECT_BYTES;

/// Moves read between two calls of the progress callback.
const PROGRESS_MOVES: u64 = 65_536;

/// An estimate's settings, named as `millpath estimate`'s flags.
#[derive(Debug, Clone, PartialEq)]
pub struct EstimateSettings {
    /// Sampling rate of the verifier (and of samples), Hz; at least 1000.
    pub rate: f64,
    /// Run the limit verifier (`--no-verify` turns it off).
    pub verify: bool,
    /// `auto` or a dialect name.
    pub dialect: String,
    /// Skip unsupported words with a warning instead of refusing them.
    pub lenient: bool,
    /// Folders searched for subroutine files.
    pub subroutine_path: Vec<PathBuf>,
    /// A LinuxCNC tool table.
    pub tool_table: Option<PathBuf>,
    /// Lines the program may run again before it is refused as endless
    /// ([`ReaderOptions::step_budget`]).
    pub step_budget: u64,
    /// Per-block times in the estimate.
    pub per_block: bool,
    /// Keep the whole plan and the toolpath (with its levels) for samples and pictures.
    pub whole: bool,
    /// Verify each timed chunk on a second thread while the next one is read and planned
    /// (streaming runs on a machine with two or more cores; the same figures either way).
    pub parallel: bool,
}

impl Default for EstimateSettings {
    fn default() -> Self {
        EstimateSettings {
            rate: 1000.0,
            verify: true,
            dialect: "auto".into(),
            lenient: false,
            subroutine_path: Vec::new(),
            tool_table: None,
            step_budget: crate::gcode::DEFAULT_STEP_BUDGET,
            per_block: false,
            whole: false,
            parallel: true,
        }
    }
}

/// One block's timing (`--blocks`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BlockTime {
    /// Program time at the block's start, s.
    pub start_s: f64,
    /// The block's time, s.
    pub time_s: f64,
    /// Highest feed reached in the block, mm/s.
    pub peak_feed_mm_s: f64,
    /// Path length, mm.
    pub length_mm: f64,
    /// Index of the move the block comes from.
    #[serde(rename = "move")]
    pub origin: usize,
}

/// What `millpath estimate --json` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// Planned cycle time, s.
    pub cycle_time_s: f64,
    /// Blocks planned.
    pub blocks: usize,
    /// Spans planned.
    pub spans: usize,
    /// Limit violations found by the verifier; `None` when it did not run.
    pub violations: Option<usize>,
    /// The machine's name.
    pub machine: String,
    /// Σ length / programmed feed over the feed blocks, s.
    pub time_at_programmed_feed_s: f64,
    /// Per-block times, when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub per_block: Option<Vec<BlockTime>>,
}

/// An estimate with, when [`EstimateSettings::whole`], the plan and the toolpath read.
#[derive(Debug)]
pub struct EstimateRun {
    /// The figures.
    pub estimate: Estimate,
    /// The whole plan (whole runs only).
    pub plan: Option<Plan>,
    /// The moves read, levels found from the retracts (whole runs only).
    pub toolpath: Option<Toolpath>,
    /// The dialect the program was read in, and why.
    pub dialect: DialectChoice,
}

/// Counts the bytes read, for progress.
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

fn unreadable(path: &Path, what: &str, e: &std::io::Error) -> Error {
    InputError::new("input file", path.display())
        .expected(format!("a {what} G-code file ({e})"))
        .into()
}

/// The dialect named by `spec` (`--dialect`), or for `auto` the one the program's head
/// (its first [`DETECT_BYTES`], cut at a character boundary) suggests.
pub fn dialect(spec: &str, head: &str) -> Result<Dialect, Error> {
    Ok(Choosing::new(spec, None, head)?.first().dialect)
}

/// How a job's dialect is chosen: named (`--dialect fanuc`), or found (`auto`) with the
/// fallback to the other candidates.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Choosing {
    Named(Dialect),
    Auto(DialectGuess),
}

/// A job's failure: the error, and whether the G-code reader raised it (only a reader's
/// refusal makes the fallback try another dialect).
pub(crate) struct Failure {
    pub(crate) error: Error,
    pub(crate) by_reader: bool,
}

impl Choosing {
    /// From `--dialect` (`spec`), the program's file `name` and its `head`.
    pub(crate) fn new(spec: &str, name: Option<&Path>, head: &str) -> Result<Self, Error> {
        Ok(match spec {
            "auto" => Choosing::Auto(DialectGuess::new(name, head)),
            d => Choosing::Named(d.parse::<Dialect>().map_err(|e| e.at("--dialect"))?),
        })
    }

    /// The first dialect to read the program in.
    pub(crate) fn first(&self) -> DialectChoice {
        match self {
            Choosing::Named(d) => DialectChoice {
                dialect: *d,
                reason: crate::gcode::DialectReason::Named,
            },
            Choosing::Auto(g) => g.choice(),
        }
    }

    /// Runs `attempt` in the first dialect; when it was found (not named) and its reader
    /// refused the program, in the first other candidate for which `reads` (the whole
    /// program read in that dialect) is true. A program no candidate reads keeps the first
    /// refusal, which then says which dialect it was read in.
    pub(crate) fn run<T>(
        &self,
        mut attempt: impl FnMut(Dialect) -> Result<T, Failure>,
        reads: impl FnMut(Dialect) -> bool,
    ) -> Result<(T, DialectChoice), Error> {
        let first = self.first();
        let failure = match attempt(first.dialect) {
            Ok(t) => return Ok((t, first)),
            Err(f) => f,
        };
        let Choosing::Auto(guess) = self else {
            return Err(failure.error);
        };
        if !failure.by_reader {
            return Err(failure.error);
        }
        match guess.fall_back(&failure.error, reads) {
            Some(c) => attempt(c.dialect).map(|t| (t, c)).map_err(|f| f.error),
            None => Err(match failure.error {
                Error::Input(mut e) => {
                    let said = e.expected.take().unwrap_or_default();
                    e.expected = Some(format!(
                        "{said} (read as {}, found from the program; no other dialect reads \
                         it either)",
                        first.dialect
                    ));
                    Error::Input(e)
                }
                e => e,
            }),
        }
    }
}

/// Whether the verifier runs on `machine` with `settings`.
fn verifies(settings: &EstimateSettings, machine: &Machine) -> bool {
    settings.verify && machine.controller != Controller::LinuxCnc
}

/// Reads, plans and verifies the program at `path` on `machine`. `progress` is called with
/// the bytes read so far every 65,536 moves. Subroutine files are searched in the program's
/// folder, then in [`EstimateSettings::subroutine_path`].
pub fn run(
    path: &Path,
    machine: &Machine,
    settings: &EstimateSettings,
    progress: &mut dyn FnMut(u64),
) -> Result<EstimateRun, Error> {
    check_rate(settings)?;
    let mut file = std::fs::File::open(path).map_err(|e| unreadable(path, "readable", &e))?;
    let mut head = Vec::new();
    if settings.dialect == "auto" {
        Read::by_ref(&mut file)
            .take(DETECT_BYTES as u64)
            .read_to_end(&mut head)
            .map_err(|e| unreadable(path, "readable", &e))?;
    }
    let choosing = Choosing::new(
        &settings.dialect,
        Some(path),
        &String::from_utf8_lossy(&head),
    )?;
    let opts = |d: Dialect| {
        reader_options(d, path.display().to_string(), machine, settings).with_program_files(
            path,
            &settings.subroutine_path,
            settings.tool_table.as_deref(),
        )
    };
    // The options are checked once, before anything is read.
    opts(Dialect::LinuxCnc)?;
    let mut file = Some(file);
    let (run, choice) = choosing.run(
        |d| {
            let f = match file.take() {
                Some(mut f) => {
                    std::io::Seek::rewind(&mut f).map_err(|e| Failure {
                        error: unreadable(path, "seekable", &e),
                        by_reader: false,
                    })?;
                    f
                }
                None => std::fs::File::open(path).map_err(|e| Failure {
                    error: unreadable(path, "readable", &e),
                    by_reader: false,
                })?,
            };
            let o = opts(d).map_err(|error| Failure {
                error,
                by_reader: false,
            })?;
            run_source(f, o, machine, settings, progress)
        },
        |d| {
            std::fs::File::open(path)
                .is_ok_and(|f| opts(d).is_ok_and(|o| reads_whole(BufReader::new(f), o)))
        },
    )?;
    Ok(EstimateRun {
        dialect: choice,
        ..run
    })
}

/// [`run`] on a program's text, named `origin` in messages. It has no folder of its own:
/// subroutine files are searched in [`EstimateSettings::subroutine_path`] only.
pub fn run_text(
    text: &str,
    origin: &str,
    machine: &Machine,
    settings: &EstimateSettings,
) -> Result<EstimateRun, Error> {
    check_rate(settings)?;
    let choosing = Choosing::new(&settings.dialect, None, text)?;
    let opts = |d: Dialect| {
        reader_options(d, origin.to_owned(), machine, settings).with_program_files(
            Path::new(""),
            &settings.subroutine_path,
            settings.tool_table.as_deref(),
        )
    };
    opts(Dialect::LinuxCnc)?;
    let (run, choice) = choosing.run(
        |d| {
            let o = opts(d).map_err(|error| Failure {
                error,
                by_reader: false,
            })?;
            run_source(text.as_bytes(), o, machine, settings, &mut |_| {})
        },
        |d| opts(d).is_ok_and(|o| reads_whole(text.as_bytes(), o)),
    )?;
    Ok(EstimateRun {
        dialect: choice,
        ..run
    })
}

fn check_rate(settings: &EstimateSettings) -> Result<(), Error> {
    if settings.rate.is_finite() && settings.rate >= 1000.0 {
        Ok(())
    } else {
        Err(InputError::new("rate", settings.rate)
            .at("--rate")
            .expected("a sampling rate of at least 1000 Hz")
            .into())
    }
}

fn reader_options(
    dialect: Dialect,
    origin: String,
    machine: &Machine,
    settings: &EstimateSettings,
) -> ReaderOptions {
    ReaderOptions::default()
        .with_dialect(dialect)
        .with_lenient(settings.lenient)
        .with_step_budget(settings.step_budget)
        .with_origin(origin)
        // LinuxCNC stops where its task waits for motion (spindle, coolant, tool commands).
        .with_sync_points((machine.controller == Controller::LinuxCnc).then_some(machine.sync_wait))
        .with_tool_change_time(Some(machine.tool_change_time))
}

/// The estimate of the program `source` holds, read with `opts`.
fn run_source<R: Read>(
    source: R,
    opts: ReaderOptions,
    machine: &Machine,
    settings: &EstimateSettings,
    progress: &mut dyn FnMut(u64),
) -> Result<EstimateRun, Failure> {
    let refused = Cell::new(false);
    estimate_source(source, opts, machine, settings, progress, &refused).map_err(|error| Failure {
        error,
        by_reader: refused.get(),
    })
}

/// [`run_source`]; `refused` is set when the reader refuses the program.
fn estimate_source<R: Read>(
    source: R,
    opts: ReaderOptions,
    machine: &Machine,
    settings: &EstimateSettings,
    progress: &mut dyn FnMut(u64),
    refused: &Cell<bool>,
) -> Result<EstimateRun, Error> {
    let start = opts.start;
    // Replaced by the caller, which knows why the dialect was chosen.
    let dialect = DialectChoice {
        dialect: opts.dialect,
        reason: crate::gcode::DialectReason::Named,
    };
    let count = Rc::new(Cell::new(0));
    let counting = Counting {
        inner: source,
        count: Rc::clone(&count),
    };
    let mut reader = Reader::new(BufReader::new(counting), opts);
    let mut n_read: u64 = 0;
    let mut at = start;
    // Every move with where it starts, progress reported as the file is read.
    let tracked = std::iter::from_fn(|| {
        let item = reader.next()?;
        refused.set(item.is_err());
        n_read += 1;
        if n_read % PROGRESS_MOVES == 0 {
            progress(count.get());
        }
        Some(item.map(|rm| {
            let f = at;
            at = rm.mv.to;
            (f, rm.mv)
        }))
    });
    if !settings.whole {
        return Ok(EstimateRun {
            estimate: streamed(tracked, machine, settings)?,
            plan: None,
            toolpath: None,
            dialect,
        });
    }
    let mut moves: Vec<(Point3, Move)> = Vec::new();
    let stream = tracked.inspect(|item| {
        if let Ok(x) = item {
            moves.push(*x);
        }
    });
    let plan = plan_moves(stream, machine, &PlanOptions::default())?;
    let violations = if verifies(settings, machine) {
        let opts = VerifyOptions {
            rate: settings.rate,
            ..VerifyOptions::default()
        };
        Some(verify_plan(&plan, &moves, machine, &opts)?.violations)
    } else {
        None
    };
    let mut tp = Toolpath::new(crate::Tool::default(), start);
    tp.moves = moves.iter().map(|(_, m)| *m).collect();
    crate::stock::infer_levels(&mut tp);
    let estimate = Estimate {
        cycle_time_s: plan.total_time(),
        blocks: plan.blocks.len(),
        spans: plan.spans.len(),
        violations,
        machine: machine.name.clone(),
        time_at_programmed_feed_s: plan
            .blocks
            .iter()
            .filter(|b| b.programmed_feed > 0.0)
            .map(|b| b.length / b.programmed_feed)
            .sum(),
        per_block: settings
            .per_block
            .then(|| block_times(&plan.blocks, 0.0).collect()),
    };
    Ok(EstimateRun {
        estimate,
        plan: Some(plan),
        toolpath: Some(tp),
        dialect,
    })
}

fn block_times(
    blocks: &[crate::motion::BlockPlan],
    start: f64,
) -> impl Iterator<Item = BlockTime> + '_ {
    blocks.iter().map(move |b| BlockTime {
        start_s: start + b.start_time,
        time_s: b.time,
        peak_feed_mm_s: b.peak_feed,
        length_mm: b.length,
        origin: b.origin,
    })
}

/// The streaming way: plans in bounded memory ([`plan_stream`]) and verifies each chunk as
/// it is timed (a chunk boundary is a knot where the acceleration is zero; its junction is
/// the one check the chunked verifier does not repeat across chunks). With
/// [`EstimateSettings::parallel`] the chunks are verified on a second thread, in order, while
/// the planner goes on (at most two chunks wait for it: memory stays bounded).
fn streamed<I>(stream: I, machine: &Machine, settings: &EstimateSettings) -> Result<Estimate, Error>
where
    I: Iterator<Item = Result<(Point3, Move), Error>>,
{
    let mut per_block = Vec::new();
    let vopts = VerifyOptions {
        rate: settings.rate,
        ..VerifyOptions::default()
    };
    let verify = verifies(settings, machine);
    let two_cores = std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2);
    let (sum, violations) = if verify && settings.parallel && two_cores {
        verified_beside(stream, machine, &vopts, |chunk| {
            if settings.per_block {
                per_block.extend(block_times(&chunk.plan.blocks, chunk.start_time));
            }
        })?
    } else {
        let mut violations = 0usize;
        let sum = plan_stream(stream, machine, &StreamOptions::default(), |chunk| {
            if verify {
                violations += verify_plan(&chunk.plan, &chunk.moves, machine, &vopts)?.violations;
            }
            if settings.per_block {
                per_block.extend(block_times(&chunk.plan.blocks, chunk.start_time));
            }
            Ok(())
        })?;
        (sum, violations)
    };
    Ok(Estimate {
        cycle_time_s: sum.total_time,
        blocks: sum.blocks,
        spans: sum.spans,
        violations: verify.then_some(violations),
        machine: machine.name.clone(),
        time_at_programmed_feed_s: sum.time_at_programmed_feed,
        per_block: settings.per_block.then_some(per_block),
    })
}

/// Plans `stream` on this thread and verifies its chunks on another, in program order; each
/// chunk goes to `seen` first. Returns the summary and the violations counted. Errors are
/// those of the sequential run: the verifier's on a chunk comes before anything the planner
/// met after handing that chunk over.
fn verified_beside<I>(
    stream: I,
    machine: &Machine,
    vopts: &VerifyOptions,
    mut seen: impl FnMut(&Chunk),
) -> Result<(crate::motion::StreamSummary, usize), Error>
where
    I: Iterator<Item = Result<(Point3, Move), Error>>,
{
    use std::sync::mpsc;
    std::thread::scope(|scope| {
        // Filled chunks to the verifier (one waiting at most), emptied ones back.
        let (to_verifier, filled) = mpsc::sync_channel::<Chunk>(1);
        let (give_back, emptied) = mpsc::channel::<Chunk>();
        let verifier = scope.spawn(move || -> Result<usize, Error> {
            let mut violations = 0;
            for chunk in filled {
                violations += verify_plan(&chunk.plan, &chunk.moves, machine, vopts)?.violations;
                // The planner may have finished: then the chunk is not needed back.
                let _ = give_back.send(chunk);
            }
            Ok(violations)
        });
        let planned = plan_stream_owned(stream, machine, &StreamOptions::default(), |chunk| {
            seen(chunk);
            let mut spare = emptied.try_recv().unwrap_or_else(|_| empty_chunk(machine));
            std::mem::swap(chunk, &mut spare);
            // A closed channel: the verifier stopped at an error, reported below.
            to_verifier
                .send(spare)
                .map_err(|_| Error::internal("the verifier stopped"))
        });
        drop(to_verifier);
        let verified = match verifier.join() {
            Ok(r) => r,
            Err(panic) => std::panic::resume_unwind(panic),
        };
        let violations = verified?;
        Ok((planned?, violations))
    })
}

/// The plan sampled every `1 / rate` s as CSV (`t,block,x,y,z,feed,vx,…,jz`, a header line)
/// or, when `json`, an array of objects.
pub fn samples_text(plan: &Plan, rate: f64, json: bool) -> Result<String, Error> {
    let samples = plan.sample(1.0 / rate)?;
    if json {
        let rows: Vec<_> = samples
            .iter()
            .map(|s| {
                serde_json::json!({"t": s.t, "block": s.block, "pos": s.position.to_array(), "feed": s.feed,
                    "vel": s.vel, "acc": s.acc, "jerk": s.jerk})
            })
            .collect();
        return Ok(serde_json::Value::Array(rows).to_string());
    }
    let mut text = String::from("t,block,x,y,z,feed,vx,vy,vz,ax,ay,az,jx,jy,jz\n");
    for s in &samples {
        let p = s.position;
        let (v, a, j) = (s.vel, s.acc, s.jerk);
        text.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            s.t,
            s.block,
            p.x,
            p.y,
            p.z,
            s.feed,
            v[0],
            v[1],
            v[2],
            a[0],
            a[1],
            a[2],
            j[0],
            j[1],
            j[2]
        ));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 40 × 20 mm rectangle at F600 (10 mm/s) after a rapid: 12 s at programmed feed.
    const RECT: &str = "G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z0 F600\nG1 X40\nY20\nX0\nY0\nG0 Z5\nM2\n";

    fn program(text: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("rect.ngc");
        std::fs::write(&p, text).unwrap();
        (dir, p)
    }

    #[test]
    fn streamed_and_whole_agree_and_pass_the_verifier() {
        let (_d, p) = program(RECT);
        let m = Machine::preset("hsm").unwrap();
        let mut calls = 0;
        let s = run(&p, &m, &EstimateSettings::default(), &mut |_| calls += 1).unwrap();
        let whole = EstimateSettings {
            whole: true,
            per_block: true,
            ..EstimateSettings::default()
        };
        let w = run(&p, &m, &whole, &mut |_| {}).unwrap();
        let (a, b) = (&s.estimate, &w.estimate);
        // The independent 1 kHz verifier finds no limit broken, either way.
        assert_eq!(a.violations, Some(0));
        assert_eq!(b.violations, Some(0));
        assert_eq!(a.blocks, b.blocks);
        assert!((a.cycle_time_s - b.cycle_time_s).abs() < 1e-9 * b.cycle_time_s);
        // Σ length / feed of the feed moves: (5 + 120) mm at 10 mm/s.
        assert!((a.time_at_programmed_feed_s - 12.5).abs() < 1e-9, "{a:?}");
        assert!((b.time_at_programmed_feed_s - 12.5).abs() < 1e-9, "{b:?}");
        // The planned time is the naive one plus the rapids and the time lost at corners.
        assert!(a.cycle_time_s > 12.5, "{a:?}");
        // Per-block times tile the cycle time.
        let per = b.per_block.as_ref().unwrap();
        let last = per.last().unwrap();
        assert!((last.start_s + last.time_s - b.cycle_time_s).abs() < 1e-9);
        assert!(a.per_block.is_none() && calls == 0);
        let tp = w.toolpath.unwrap();
        assert_eq!(tp.moves.len(), per.len());
        // The same time as a program read back from bytes.
        let t = super::super::program_time(RECT.as_bytes(), Dialect::LinuxCnc, "rect", &m).unwrap();
        assert!((t - a.cycle_time_s).abs() < 1e-9 * t);
    }

    /// A program of `n` short G1 moves along a wavy line (several of the stream's chunks),
    /// ending with `tail`.
    fn wavy(n: usize, tail: &str) -> String {
        let mut text = String::from("G21 G90 G64 P0.01\nG0 X0 Y0 Z1\nG1 Z0 F1500\n");
        for i in 1..=n {
            let x = i as f64 * 0.1;
            text.push_str(&format!("X{x:.3} Y{:.3}\n", (x * 0.3).sin() * 5.0));
        }
        text.push_str(tail);
        text
    }

    /// The verifier on a second thread gives the sequential run's estimate (cycle time,
    /// violations, every block's time) and its error, whichever comes first.
    #[test]
    fn verifying_beside_the_planner_changes_nothing() {
        let m = Machine::preset("hsm").unwrap();
        let settings = |parallel| EstimateSettings {
            parallel,
            per_block: true,
            ..EstimateSettings::default()
        };
        let text = wavy(20_000, "M2\n");
        let a = run_text(&text, "wavy", &m, &settings(true))
            .unwrap()
            .estimate;
        let b = run_text(&text, "wavy", &m, &settings(false))
            .unwrap()
            .estimate;
        assert_eq!(a, b);
        assert_eq!(a.violations, Some(0));
        assert_eq!(a.per_block.as_ref().map(Vec::len), Some(20_002));
        // An error after several chunks were handed to the verifier: the same message.
        let bad = wavy(20_000, "G1 X1 E5\nM2\n");
        let ea = run_text(&bad, "wavy", &m, &settings(true)).unwrap_err();
        let eb = run_text(&bad, "wavy", &m, &settings(false)).unwrap_err();
        assert_eq!(ea.to_string(), eb.to_string());
        assert_eq!(ea.exit_code(), 2);
        assert!(ea.to_string().contains("wavy:20004"), "{ea}");
    }

    #[test]
    fn samples_cover_the_plan_at_the_rate() {
        let (_d, p) = program(RECT);
        let m = Machine::preset("hsm").unwrap();
        let whole = EstimateSettings {
            whole: true,
            ..EstimateSettings::default()
        };
        let r = run(&p, &m, &whole, &mut |_| {}).unwrap();
        let plan = r.plan.unwrap();
        let csv = samples_text(&plan, 1000.0, false).unwrap();
        let rows: Vec<&str> = csv.lines().skip(1).collect();
        let expected = (plan.total_time() * 1000.0).floor() as usize;
        assert!(
            rows.len().abs_diff(expected) <= 2,
            "{} vs {expected}",
            rows.len()
        );
        let last_t: f64 = rows
            .last()
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!((last_t - plan.total_time()).abs() <= 1e-3);
        let json: serde_json::Value =
            serde_json::from_str(&samples_text(&plan, 2000.0, true).unwrap()).unwrap();
        assert!(json.as_array().unwrap().len() > rows.len());
    }

    #[test]
    fn bad_settings_are_input_errors_naming_the_flag() {
        let (_d, p) = program(RECT);
        let m = Machine::preset("hsm").unwrap();
        let bad = EstimateSettings {
            rate: 500.0,
            ..EstimateSettings::default()
        };
        let e = run(&p, &m, &bad, &mut |_| {}).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--rate"), "{e}");
        let bad = EstimateSettings {
            dialect: "heidenhain".into(),
            ..EstimateSettings::default()
        };
        let e = run(&p, &m, &bad, &mut |_| {}).unwrap_err();
        assert!(e.to_string().contains("--dialect"), "{e}");
        let e = run(
            Path::new("/nonexistent/p.ngc"),
            &m,
            &EstimateSettings::default(),
            &mut |_| {},
        )
        .unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("/nonexistent/p.ngc"), "{e}");
    }

    #[test]
    fn no_verifier_on_the_linuxcnc_model_and_dialect_from_the_head() {
        let (_d, p) = program(RECT);
        let m = Machine {
            controller: Controller::LinuxCnc,
            ..Machine::preset("linuxcnc-sim").unwrap()
        };
        let r = run(&p, &m, &EstimateSettings::default(), &mut |_| {}).unwrap();
        assert_eq!(r.estimate.violations, None);
        assert_eq!(
            dialect("auto", "%\nO1000\nG0 X0\n").unwrap(),
            Dialect::Fanuc
        );
        assert_eq!(dialect("auto", RECT).unwrap(), Dialect::LinuxCnc);
        assert_eq!(dialect("grbl", RECT).unwrap(), Dialect::Grbl);
    }
}
