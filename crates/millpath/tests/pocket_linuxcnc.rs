//! The roughing strategies judged by a real controller: the aerospace pocket's three
//! strategies (one 5 mm level, 600 in/min, with and without feed modulation) run through
//! LinuxCNC 2.9's own trajectory planner (`../shared/tools/linuxcnc-time`, 500 mm/s,
//! 2000 mm/s², the programs stating `G64 P0.01`), beside the best peer's program, FreeCAD
//! 0.20's zigzag of the same pocket (`../shared/tools/freecad-pocket/aerospace/`, given
//! `G64 P0.01`). The spiral takes at most 0.90 × offset's time, and our zigzag at most 0.95 ×
//! FreeCAD's. (The zigzag, turning on half circles with no row along the walls, is now the
//! fastest of the three here: the spiral loses a third of its time to slowing down on
//! LinuxCNC, 16.6 s planned against 11.0 s at its feeds.)
//!
//! LinuxCNC runs in simulated real time (about 25 s a program; two at a time). Without
//! `linuxcnc` on the machine the test is skipped, unless `MILLPATH_REQUIRE_LINUXCNC=1` (set by
//! `.ci/run`, which installs it), when it fails.

use millpath::gcode::{WriterOptions, write_program};
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, builtin};
use millpath::toolpath::Tool;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The timing tool beside the repository, if LinuxCNC can run here.
fn linuxcnc_time() -> Option<PathBuf> {
    let tool = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/tools/linuxcnc-time/linuxcnc-time");
    let installed = Command::new("sh")
        .args(["-c", "command -v linuxcnc"])
        .output()
        .is_ok_and(|o| o.status.success());
    let required = std::env::var("MILLPATH_REQUIRE_LINUXCNC").is_ok_and(|v| v == "1");
    if tool.exists() && installed {
        return Some(tool);
    }
    assert!(
        !required,
        "MILLPATH_REQUIRE_LINUXCNC=1 but LinuxCNC cannot run here (tool {} exists: {}, \
         linuxcnc installed: {installed})",
        tool.display(),
        tool.exists()
    );
    None
}

/// LinuxCNC's motion time for `program`, s.
fn time_on_linuxcnc(tool: &Path, program: &Path) -> f64 {
    // The motion is timed in servo cycles, whatever the load; the timeout is generous so
    // that a busy machine (other tests, other runs) does not fail the run. A run whose runner
    // gives up waiting for the machine to come on (seen under heavy load) is run again, twice
    // at most.
    let mut last = String::new();
    for _ in 0..3 {
        let out = Command::new(tool)
            .env("LCNC_TIMEOUT", "300")
            .arg(program)
            .args(["500", "2000"])
            .output()
            .expect("linuxcnc-time runs");
        let text = String::from_utf8_lossy(&out.stdout);
        let t = text
            .trim()
            .lines()
            .last()
            .and_then(|l| l.trim().parse::<f64>().ok());
        match t {
            Some(t) if out.status.success() => return t,
            _ => {
                last = format!("{text}{}", String::from_utf8_lossy(&out.stderr));
            }
        }
    }
    panic!(
        "linuxcnc-time {} failed 3 runs; last: {last}",
        program.display()
    )
}

#[test]
#[allow(clippy::print_stderr)]
fn linuxcnc_times_our_strategies_against_freecads_zigzag() {
    let Some(tool_path) = linuxcnc_time() else {
        eprintln!("skipped: LinuxCNC is not installed");
        return;
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let shape = builtin::aerospace_pocket();
    let tool = Tool::flat(12.7).expect("tool");
    let sim = SimOptions::default().with_cell(0.2).with_step(0.4);
    let mut jobs = Vec::new();
    for modulate in [true, false] {
        // Made for this machine, as `--machine` does: LinuxCNC is trapezoidal, no curvature
        // ramps.
        let opts = PocketOptions::default()
            .with_depth(5.0)
            .with_step_down(5.0)
            .with_modulate_feed(modulate)
            .with_curvature_ramps(false);
        for kind in [
            StrategyKind::Spiral,
            StrategyKind::Offset,
            StrategyKind::Zigzag,
        ] {
            let r = pocket::generate(kind, &shape, &tool, &opts, &sim).expect("pocket");
            assert!(r.verification.problems().is_empty(), "{kind:?}");
            let mut wopts = WriterOptions::default();
            wopts.path_tolerance = Some(0.01);
            let mut buf = Vec::new();
            write_program(&r.toolpath, &wopts, &mut buf).expect("write");
            let path = dir.path().join(format!("{}_{modulate}.ngc", kind.name()));
            std::fs::write(&path, buf).expect("write program");
            jobs.push((modulate, kind, path));
        }
    }
    // Two at a time (each run is mostly the controller's real-time clock).
    let times: Vec<f64> = jobs
        .chunks(2)
        .flat_map(|pair| {
            std::thread::scope(|s| {
                let handles: Vec<_> = pair
                    .iter()
                    .map(|(_, _, p)| s.spawn(|| time_on_linuxcnc(&tool_path, p)))
                    .collect();
                handles
                    .into_iter()
                    .map(|h| h.join().expect("timing thread"))
                    .collect::<Vec<f64>>()
            })
        })
        .collect();
    let peer = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/tools/freecad-pocket/aerospace/pocket_zigzag.ngc");
    let text = std::fs::read_to_string(&peer).expect("FreeCAD's aerospace zigzag");
    let peer_path = dir.path().join("freecad_zigzag.ngc");
    std::fs::write(&peer_path, text.replace("\nG21\n", "\nG21\nG64 P0.01\n"))
        .expect("write the peer's program");
    let fc = time_on_linuxcnc(&tool_path, &peer_path);
    for modulate in [true, false] {
        let t = |kind: StrategyKind| {
            jobs.iter()
                .zip(&times)
                .find(|((m, k, _), _)| *m == modulate && *k == kind)
                .map(|(_, &t)| t)
                .expect("timed")
        };
        let (s, o, z) = (
            t(StrategyKind::Spiral),
            t(StrategyKind::Offset),
            t(StrategyKind::Zigzag),
        );
        eprintln!(
            "LinuxCNC, aerospace, one level, modulation {modulate}: spiral {s:.3} s, offset \
             {o:.3} s, zigzag {z:.3} s"
        );
        assert!(
            s <= 0.90 * o && z <= 0.95 * fc,
            "modulation {modulate}: spiral {s} s, offset {o} s, zigzag {z} s, FreeCAD's \
             zigzag {fc} s"
        );
    }
}
