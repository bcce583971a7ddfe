//! A real drawing made into a whole job from the drawing alone, as a new user would: `millpath
//! job --init DRAWING -o NAME.toml`, then `millpath job NAME.toml --dialect D -o PROGRAM --json`
//! in each of the four dialects. Each program must be read back by `millpath estimate` to the
//! report's `cycle_time_s` within 1e-6 relative, the LinuxCNC one must pass LinuxCNC's own
//! interpreter `rs274`, `millpath verify --job` must accept each against the job file (the
//! program read back apart from the plan), and the report's whole-job stock check must say the drawn part is
//! left, held by its tabs: every part the job file profiles has a hold row `by N tab(s); free
//! without them` with N ≥ 1, and the parts it does not profile are those the file names as
//! too close to another to cut out. A drawing with no closed outline must be refused by
//! `--init` (exit 2) saying so. Shared by `cli_real_files.rs` (a bounded set, in the release
//! run of `./scripts/test`) and `cli_job_real.rs` (every drawing, ignored); its helpers to
//! run the binary by `cli_real_adaptive.rs` too.

#![allow(dead_code)] // each test binary uses its own share of these

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Mutex;
use std::time::Instant;

#[path = "../../../millpath/tests/rs274_common/mod.rs"]
mod rs274_common;

/// The dialects and the program file's extension in each.
pub const DIALECTS: &[(&str, &str)] = &[
    ("linuxcnc", "ngc"),
    ("fanuc", "nc"),
    ("sinumerik", "mpf"),
    ("grbl", "gcode"),
];

/// Flags a drawing is read with (as in `cli_real_files.rs`): LibreCAD's Tux misses closing
/// its body by 0.1 mm, joined as a programmer would.
pub const READ_FLAGS: &[(&str, &[&str])] = &[("lc_tux.dxf", &["--join-tolerance", "0.15"])];

/// The folder of the real drawings.
pub fn dir() -> PathBuf {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(
        d.is_dir(),
        "the real inputs are missing: {} (CI keeps ../shared beside the clone)",
        d.display()
    );
    d
}

/// Runs the CLI built with the tests in `cwd`.
pub fn millpath(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the millpath binary runs")
}

/// Its standard output and error, together.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// What one drawing gave.
#[derive(Debug, Clone, PartialEq)]
pub struct JobRow {
    /// The drawing's file name.
    pub name: String,
    /// Operations of the job.
    pub operations: usize,
    /// The cycle time (LinuxCNC dialect), s.
    pub cycle_s: f64,
    /// Parts profiled and the tabs holding them.
    pub held: Vec<usize>,
    /// Parts the job file leaves uncut, as too close to another.
    pub left_out: usize,
    /// Wall time of the four runs, s.
    pub wall_s: f64,
    /// `None` for a job made; the refusal's words for a drawing without closed outlines.
    pub refused: Option<String>,
}

impl std::fmt::Display for JobRow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.refused {
            Some(r) => write!(f, "{:<36} refused (exit 2): {r}", self.name),
            None => write!(
                f,
                "{:<36} {} ops, cycle {:.1} s, tabs per part {:?}{}, 4 dialects in {:.1} s",
                self.name,
                self.operations,
                self.cycle_s,
                self.held,
                if self.left_out > 0 {
                    format!(", {} part(s) too close to cut out", self.left_out)
                } else {
                    String::new()
                },
                self.wall_s
            ),
        }
    }
}

fn json(bytes: &[u8], what: &str) -> Result<serde_json::Value, String> {
    serde_json::from_slice(bytes).map_err(|e| format!("{what}: not JSON ({e})"))
}

/// `job --init` and `job` in every dialect on the drawing `name`, checked (module docs).
pub fn job_real(name: &str, work: &Path) -> Result<JobRow, String> {
    let started = Instant::now();
    let path = dir().join(name);
    let path = path.to_str().expect("path");
    let flags: &[&str] = READ_FLAGS.iter().find(|r| r.0 == name).map_or(&[], |r| r.1);
    let toml = work.join(format!("{name}.toml"));
    let toml_s = toml.to_str().expect("path");
    let init = millpath(
        &[&["job", "--init", path, "-o", toml_s], flags].concat(),
        work,
    );
    match init.status.code() {
        Some(0) => {}
        Some(2) if text(&init).contains("0 closed outlines") => {
            if toml.exists() {
                return Err(format!("{name}: --init refused but wrote {toml_s}"));
            }
            let t = text(&init);
            let line = t.lines().find(|l| l.starts_with("error")).unwrap_or("");
            return Ok(JobRow {
                name: name.to_owned(),
                operations: 0,
                cycle_s: 0.0,
                held: Vec::new(),
                left_out: 0,
                wall_s: started.elapsed().as_secs_f64(),
                refused: Some(line.chars().take(90).collect()),
            });
        }
        c => return Err(format!("{name}: job --init exit {c:?}: {}", text(&init))),
    }
    let file = std::fs::read_to_string(&toml).map_err(|e| format!("{name}: {e}"))?;
    let left_out = file
        .lines()
        .filter(|l| l.starts_with("# Part ") && l.contains("is not cut out"))
        .count();
    let mut row = JobRow {
        name: name.to_owned(),
        operations: 0,
        cycle_s: 0.0,
        held: Vec::new(),
        left_out,
        wall_s: 0.0,
        refused: None,
    };
    for (k, (dialect, ext)) in DIALECTS.iter().enumerate() {
        let program = work.join(format!("{name}.{ext}"));
        let program_s = program.to_str().expect("path");
        let run = millpath(
            &[
                "job",
                toml_s,
                "--dialect",
                dialect,
                "-o",
                program_s,
                "--json",
            ],
            work,
        );
        if run.status.code() != Some(0) {
            return Err(format!(
                "{name} ({dialect}): job exit {:?}: {}",
                run.status.code(),
                text(&run)
            ));
        }
        let report = json(&run.stdout, &format!("{name} ({dialect}) report"))?;
        let cycle = report["cycle_time_s"]
            .as_f64()
            .ok_or_else(|| format!("{name}: no cycle_time_s"))?;
        // The report's check: the verdict, and a hold row with tabs for every part cut out.
        let rows: Vec<(String, String)> = report["check"]
            .as_array()
            .ok_or_else(|| format!("{name}: no check"))?
            .iter()
            .map(|r| {
                (
                    r[0].as_str().unwrap_or("").to_owned(),
                    r[1].as_str().unwrap_or("").to_owned(),
                )
            })
            .collect();
        let verdict = rows.iter().find(|r| r.0 == "verdict").map(|r| r.1.as_str());
        // Held by its tabs, or left in the stock where no part is cut out (the hold rows
        // below say which parts are).
        if !verdict.is_some_and(|v| {
            v == "the drawn part, held by its tabs"
                || v == "the drawn part, left in the stock (no profile cuts it out)"
        }) {
            return Err(format!("{name} ({dialect}): verdict {verdict:?}"));
        }
        let mut held = Vec::new();
        for (what, v) in rows.iter().filter(|r| r.0.ends_with(" held")) {
            let n: usize = v
                .strip_prefix("by ")
                .and_then(|s| s.split(' ').next())
                .and_then(|s| s.parse().ok())
                .ok_or_else(|| format!("{name} ({dialect}): {what}: {v}"))?;
            if n == 0 {
                return Err(format!("{name} ({dialect}): {what}: {v}"));
            }
            held.push(n);
        }
        let parts = report["features"][0].as_u64().unwrap_or(0) as usize;
        if held.len() + left_out != parts {
            return Err(format!(
                "{name} ({dialect}): {} part(s) held by tabs and {left_out} left out, of {parts}",
                held.len()
            ));
        }
        // The program read back: its cycle time, and LinuxCNC's interpreter.
        let est = millpath(
            &["estimate", program_s, "--dialect", dialect, "--json"],
            work,
        );
        if est.status.code() != Some(0) {
            return Err(format!("{name} ({dialect}): estimate: {}", text(&est)));
        }
        let t = json(&est.stdout, "estimate")?["cycle_time_s"]
            .as_f64()
            .ok_or_else(|| format!("{name}: estimate has no cycle_time_s"))?;
        if (t - cycle).abs() > 1e-6 * cycle.abs().max(1e-9) {
            return Err(format!(
                "{name} ({dialect}): estimate {t} s against the report's {cycle} s"
            ));
        }
        // The program against the part the job file means, read back apart from the plan.
        let ver = millpath(
            &[
                "verify",
                program_s,
                "--job",
                toml_s,
                "--dialect",
                dialect,
                "--json",
            ],
            work,
        );
        let vj = json(&ver.stdout, &format!("{name} ({dialect}) verify --job"))?;
        if ver.status.code() != Some(0) || vj["passed"] != true {
            return Err(format!(
                "{name} ({dialect}): verify --job exit {:?}: {}",
                ver.status.code(),
                text(&ver)
            ));
        }
        if *dialect == "linuxcnc" {
            // A tool table with every number the job may use (rs274's default has three).
            let table = work.join(format!("{name}.tbl"));
            let rows: String = (1..=32).map(|t| format!("T{t} P{t} D1.0 ;\n")).collect();
            std::fs::write(&table, rows).map_err(|e| format!("{name}: {e}"))?;
            let run = rs274_common::rs274_file(
                &program,
                None,
                Some(&table),
                std::time::Duration::from_secs(300),
            );
            if !run.ok {
                return Err(format!("{name}: rs274: {}", run.messages));
            }
        }
        if k == 0 {
            row.operations = report["operations"].as_array().map_or(0, Vec::len);
            row.cycle_s = cycle;
            row.held = held;
        } else if held != row.held {
            return Err(format!(
                "{name} ({dialect}): tabs {held:?}, in linuxcnc {:?}",
                row.held
            ));
        }
    }
    row.wall_s = started.elapsed().as_secs_f64();
    Ok(row)
}

/// `run` on every item over two threads, each taking the next item from the back of
/// `items`; the results sorted by item.
pub fn on_two_threads<T: Ord + Send, R: Send>(
    items: Vec<T>,
    run: impl Fn(&T) -> R + Sync,
) -> Vec<(T, R)> {
    let queue = Mutex::new(items);
    let results = Mutex::new(Vec::new());
    std::thread::scope(|sc| {
        for _ in 0..2 {
            sc.spawn(|| {
                loop {
                    let Some(f) = queue.lock().expect("queue").pop() else {
                        break;
                    };
                    let r = run(&f);
                    results.lock().expect("results").push((f, r));
                }
            });
        }
    });
    let mut results = results.into_inner().expect("results");
    results.sort_by(|a, b| a.0.cmp(&b.0));
    results
}
