//! The `linuxcnc` controller model against LinuxCNC 2.9 itself: the same judge the README and
//! BENCHMARKS.md use (`../shared/tools/linuxcnc-time`, LinuxCNC's own motion controller and
//! trajectory planner on the machine of the `linuxcnc-time` preset).
//!
//! The programs are in `tests/data/linuxcnc/` (short chords with and without naive-CAM
//! merging, arcs, plain `G64`, `G64 P`, `G61`, `G61.1`, a helix, a pocket), a few seconds
//! each. `times.csv` beside them holds LinuxCNC's times, recorded on 2026-11-25 with
//! `linuxcnc-time FILE 500 2000` (LinuxCNC 2.9, linuxcnc-uspace).
//!
//! * `model_matches_the_recorded_linuxcnc_times`: the model within 5 % of each recorded time
//!   (always runs).
//! * `model_matches_linuxcnc_now`: runs LinuxCNC on every program (two at a time, about 40 s)
//!   and asserts the model within 5 % of each time it measures now. Without LinuxCNC
//!   (`linuxcnc` not on the PATH, or the tool not beside the repository) it says so on
//!   stderr and checks nothing, unless `MILLPATH_REQUIRE_LINUXCNC=1` (CI sets it), when it
//!   fails.
// The comparisons and the skip are reported on stderr (`cargo test -- --nocapture`).
#![allow(clippy::print_stderr)]

use millpath::gcode::{ReaderOptions, read_str};
use millpath::machine::Machine;
use millpath::motion::{PlanOptions, plan_moves};
use std::path::{Path, PathBuf};
use std::process::Command;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/linuxcnc")
}

fn programs() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(data_dir())
        .expect("tests/data/linuxcnc")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ngc"))
        .collect();
    v.sort();
    v
}

/// The model's cycle time of `path` on the `linuxcnc-time` preset, read as
/// `millpath estimate --machine linuxcnc-time` reads it.
fn model_time(path: &Path) -> f64 {
    let m = Machine::preset("linuxcnc-time").unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let opts = ReaderOptions::default()
        .with_sync_points(Some(m.sync_wait))
        .with_origin(path.display().to_string());
    let (tp, _) = read_str(&text, opts).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let moves: Vec<_> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
    plan_moves(moves.iter().map(|x| Ok(*x)), &m, &PlanOptions::default())
        .unwrap()
        .total_time()
}

fn recorded() -> Vec<(String, f64)> {
    let text = std::fs::read_to_string(data_dir().join("times.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("program,seconds"));
    lines
        .map(|l| {
            let (p, s) = l.split_once(',').unwrap();
            (p.to_string(), s.trim().parse().unwrap())
        })
        .collect()
}

fn check(what: &str, rows: &[(String, f64, f64)]) {
    let mut report = String::new();
    let mut bad = 0;
    for (name, lcnc, model) in rows {
        let err = (model - lcnc) / lcnc;
        if err.abs() > 0.05 {
            bad += 1;
        }
        report.push_str(&format!(
            "{name}: LinuxCNC {lcnc:.3} s, model {model:.3} s, {:+.1} %\n",
            100.0 * err
        ));
    }
    assert_eq!(
        bad, 0,
        "{what}: the model is off by more than 5 %:\n{report}"
    );
    eprintln!("{what}:\n{report}");
}

#[test]
fn model_matches_the_recorded_linuxcnc_times() {
    let rec = recorded();
    let progs = programs();
    assert!(progs.len() >= 10, "{progs:?}");
    assert_eq!(rec.len(), progs.len(), "every program has a recorded time");
    let rows: Vec<_> = rec
        .iter()
        .map(|(name, t)| (name.clone(), *t, model_time(&data_dir().join(name))))
        .collect();
    check("recorded LinuxCNC times", &rows);
}

/// The LinuxCNC cycle-time tool beside the repository, if it and LinuxCNC are installed.
fn linuxcnc_tool() -> Result<PathBuf, String> {
    let tool = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/tools/linuxcnc-time/linuxcnc-time");
    if !tool.is_file() {
        return Err(format!("{} is missing", tool.display()));
    }
    let found = Command::new("sh")
        .args(["-c", "command -v linuxcnc"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        return Err("linuxcnc is not installed (apt-get install linuxcnc-uspace)".into());
    }
    Ok(tool)
}

#[test]
fn model_matches_linuxcnc_now() {
    let tool = match linuxcnc_tool() {
        Ok(t) => t,
        Err(why) => {
            assert!(
                std::env::var("MILLPATH_REQUIRE_LINUXCNC").as_deref() != Ok("1"),
                "MILLPATH_REQUIRE_LINUXCNC=1 but LinuxCNC cannot run: {why}"
            );
            eprintln!("skipped: LinuxCNC cannot run here ({why}); the recorded times still apply");
            return;
        }
    };
    let progs = programs();
    // Two LinuxCNC runs at a time (each runs in real time in its own namespaces).
    let half = progs.len().div_ceil(2);
    let run = |list: Vec<PathBuf>| {
        let tool = tool.clone();
        std::thread::spawn(move || {
            list.into_iter()
                .map(|p| {
                    // A run that records no motion at all (seen about once in a hundred on a
                    // loaded machine), or whose runner times out waiting for the machine to
                    // come on (seen on a machine loaded by other builds), is run again, twice
                    // at most.
                    let mut last = String::new();
                    for _ in 0..3 {
                        let out = Command::new(&tool)
                            .arg(&p)
                            .args(["500", "2000"])
                            .output()
                            .expect("run linuxcnc-time");
                        let text = String::from_utf8_lossy(&out.stdout).trim().to_string();
                        match text.parse::<f64>() {
                            Ok(t) if t > 0.0 => return (p, t),
                            Ok(_) => last = "no motion recorded".to_owned(),
                            Err(_) => {
                                last = format!(
                                    "gave {text:?}: {}",
                                    String::from_utf8_lossy(&out.stderr)
                                );
                            }
                        }
                    }
                    panic!("{}: linuxcnc-time failed 3 runs; last: {last}", p.display())
                })
                .collect::<Vec<_>>()
        })
    };
    let a = run(progs[..half].to_vec());
    let b = run(progs[half..].to_vec());
    let mut times = a.join().expect("LinuxCNC runs");
    times.extend(b.join().expect("LinuxCNC runs"));
    let rows: Vec<_> = times
        .iter()
        .map(|(p, t)| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            (name, *t, model_time(p))
        })
        .collect();
    check("LinuxCNC now", &rows);
}
