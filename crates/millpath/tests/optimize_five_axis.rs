//! `optimize` on five-axis programs (A/B/C words, trivkins) for the `linuxcnc-time` machine.
//!
//! * `rewrite_keeps_the_path_the_feeds_and_the_joint_limits`: four programs of
//!   `tests/data/five_axis` (G64 P with rotary corners, a dense sweep, mixed G93 blocks, arcs
//!   turning C) optimized; the inverse-time rewrite and the kept program read back by the
//!   reader (not the rewrite's code) and compared move by move with the input: the same kind,
//!   end point and rotary position, no feed above the input's; every rewritten straight block's
//!   joints within their velocity limits at the feed read back; the per-block peak feed of the
//!   planner (`estimate --blocks`) on the rewrite never above the programmed feed; the kept
//!   program never slower than the input on the controller model.
//! * `loops_are_refused`: a program whose lines run more than once, or that calls a
//!   subroutine, is refused with an `InputError` naming the line.
//! * `linuxcnc_runs_the_rewrite_no_slower`: LinuxCNC 2.9 itself runs two programs and their
//!   rewrites; the rewrite is never slower (by more than a servo cycle). Skipped without
//!   LinuxCNC unless `MILLPATH_REQUIRE_LINUXCNC=1`.
// The figures are reported on stderr (`cargo test -- --nocapture`).
#![allow(clippy::print_stderr)]

use millpath::gcode::{ReaderOptions, read_str};
use millpath::job::estimate::{EstimateSettings, run_text};
use millpath::job::optimize::optimize_text;
use millpath::machine::Machine;
use millpath::toolpath::Rotary;
use millpath::{Error, MoveKind, Toolpath};
use std::path::{Path, PathBuf};
use std::process::Command;

const PROGRAMS: &[&str] = &[
    "alternate_3_5.ngc",
    "sweep_fast_rot.ngc",
    "g93_mixed.ngc",
    "arc_with_c.ngc",
];

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/five_axis")
        .join(name)
}

fn machine() -> Machine {
    Machine::preset("linuxcnc-time").unwrap()
}

fn read(text: &str) -> Toolpath {
    read_str(text, ReaderOptions::default()).unwrap().0
}

fn model_time(text: &str) -> f64 {
    let settings = EstimateSettings {
        dialect: "linuxcnc".into(),
        ..EstimateSettings::default()
    };
    run_text(text, "test", &machine(), &settings)
        .unwrap()
        .estimate
        .cycle_time_s
}

/// Compares `out` with `input` move by move; returns the number of feed blocks whose feed
/// was lowered.
fn same_path(input: &Toolpath, out: &Toolpath, m: &Machine, name: &str) -> usize {
    assert_eq!(input.moves.len(), out.moves.len(), "{name}: move count");
    let (mut rot_in, mut rot_out) = (Rotary::default(), Rotary::default());
    let mut from = input.start;
    let mut lowered = 0;
    for (k, (a, b)) in input.moves.iter().zip(&out.moves).enumerate() {
        let (ra, rb) = (a.rotary.unwrap_or(rot_in), b.rotary.unwrap_or(rot_out));
        assert_eq!(a.kind, b.kind, "{name} move {k}: kind");
        assert!(a.to.distance(b.to) <= 1e-9, "{name} move {k}: end point");
        assert!(ra.distance(rb) <= 1e-12, "{name} move {k}: rotary axes");
        assert_eq!(a.corner, b.corner, "{name} move {k}: path mode");
        if a.kind != MoveKind::Rapid {
            assert!(
                b.feed <= a.feed * (1.0 + 1e-9),
                "{name} move {k}: feed {} above the programmed {}",
                b.feed,
                a.feed
            );
        }
        if a.kind == MoveKind::Line && b.feed < a.feed * (1.0 - 1e-9) {
            lowered += 1;
            let d = (b.to - from).to_array();
            let r = [rb.a - rot_in.a, rb.b - rot_in.b, rb.c - rot_in.c];
            let xyz = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let len = if xyz > 1e-9 { xyz } else { rb.distance(rot_in) };
            let t = len / b.feed;
            for (x, l) in d.iter().zip(&m.axes) {
                assert!(
                    x.abs() / t <= l.max_velocity * (1.0 + 1e-6),
                    "{name} move {k}"
                );
            }
            for (x, l) in r.iter().zip(&m.rotary) {
                let l = l.as_ref().unwrap();
                assert!(
                    x.abs() / t <= l.max_velocity * (1.0 + 1e-6),
                    "{name} move {k}"
                );
            }
        }
        rot_in = ra;
        rot_out = rb;
        from = a.to;
    }
    lowered
}

#[test]
fn rewrite_keeps_the_path_the_feeds_and_the_joint_limits() {
    let m = machine();
    for name in PROGRAMS {
        let text = std::fs::read_to_string(data(name)).unwrap();
        let opt = optimize_text(&text, name, &m).unwrap();
        let input = read(&text);
        assert!(opt.rewritten_blocks > 0, "{name}: nothing rewritten");
        let lowered = same_path(&input, &read(&opt.rewrite), &m, name);
        same_path(&input, &read(&opt.text), &m, name);
        // The planner's own per-block peak feed on the rewrite, against the programmed one.
        let settings = EstimateSettings {
            dialect: "linuxcnc".into(),
            per_block: true,
            ..EstimateSettings::default()
        };
        let est = run_text(&opt.rewrite, name, &m, &settings)
            .unwrap()
            .estimate;
        let blocks = est.per_block.unwrap();
        assert!(!blocks.is_empty());
        for b in &blocks {
            let mv = &input.moves[b.origin];
            if mv.kind != MoveKind::Rapid && mv.rotary.is_none() {
                assert!(
                    b.peak_feed_mm_s <= mv.feed * (1.0 + 1e-6),
                    "{name} block of move {}: peak {} above {}",
                    b.origin,
                    b.peak_feed_mm_s,
                    mv.feed
                );
            }
        }
        let (before, kept, rewrite) = (
            model_time(&text),
            model_time(&opt.text),
            model_time(&opt.rewrite),
        );
        assert!(kept <= before + 1e-9, "{name}: {kept} s after {before} s");
        assert!((before - opt.before.cycle_time_s).abs() < 1e-9);
        assert!((rewrite - opt.after.cycle_time_s).abs() < 1e-9);
        eprintln!(
            "{name}: {} blocks rewritten ({lowered} lowered), model {before:.3} s -> rewrite \
             {rewrite:.3} s, kept {kept:.3} s: {}",
            opt.rewritten_blocks, opt.outcome
        );
    }
}

#[test]
fn loops_are_refused() {
    let text = "G21 G90 G94\n#1=0\no100 while [#1 LT 3]\nG1 X[#1] A[#1*10] F600\n#1=[#1+1]\n\
                o100 endwhile\nM2\n";
    match optimize_text(text, "loop.ngc", &machine()) {
        Err(Error::Input(e)) => assert!(e.to_string().contains("line"), "{e}"),
        other => panic!("a loop must be refused: {other:?}"),
    }
    let call = "o<sq> sub\nG1 X#1 A10 F100\no<sq> endsub\nG21 G90 G94\no<sq> call [5]\nM2\n";
    match optimize_text(call, "call.ngc", &machine()) {
        Err(Error::Input(e)) => {
            let msg = e.to_string();
            assert!(
                msg.contains("line 5") && msg.contains("subroutine call"),
                "{msg}"
            );
        }
        other => panic!("a subroutine call must be refused: {other:?}"),
    }
}

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

fn linuxcnc_time(tool: &Path, file: &Path) -> f64 {
    let mut last = String::new();
    for _ in 0..3 {
        let out = Command::new(tool)
            .env("LCNC_AXES", "XYZAC")
            .arg(file)
            .args(["500", "2000"])
            .output()
            .expect("run linuxcnc-time");
        let text = String::from_utf8_lossy(&out.stdout).trim().to_string();
        match text.parse::<f64>() {
            Ok(t) if t > 0.0 => return t,
            _ => last = format!("{text} {}", String::from_utf8_lossy(&out.stderr)),
        }
    }
    panic!("{}: LinuxCNC gave no time: {last}", file.display());
}

#[test]
fn linuxcnc_runs_the_rewrite_no_slower() {
    let tool = match linuxcnc_tool() {
        Ok(t) => t,
        Err(why) => {
            assert!(
                std::env::var("MILLPATH_REQUIRE_LINUXCNC").as_deref() != Ok("1"),
                "MILLPATH_REQUIRE_LINUXCNC=1 but LinuxCNC cannot run: {why}"
            );
            eprintln!("skipped: LinuxCNC cannot run here ({why})");
            return;
        }
    };
    let dir = std::env::temp_dir().join(format!("millpath-optimize-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut jobs = Vec::new();
    for name in ["issue_example.ngc", "alternate_3_5.ngc"] {
        let text = std::fs::read_to_string(data(name)).unwrap();
        let opt = optimize_text(&text, name, &machine()).unwrap();
        let out = dir.join(name);
        std::fs::write(&out, &opt.rewrite).unwrap();
        let (tool, input) = (tool.clone(), data(name));
        // Input and rewrite side by side (each run in its own namespaces, in real time).
        let t_in = std::thread::spawn({
            let tool = tool.clone();
            move || linuxcnc_time(&tool, &input)
        });
        let t_out = linuxcnc_time(&tool, &out);
        jobs.push((name, t_in.join().unwrap(), t_out));
    }
    for (name, before, after) in jobs {
        eprintln!("{name}: LinuxCNC {before:.3} s, rewrite {after:.3} s");
        assert!(
            after <= before + 0.002,
            "{name}: {after} s after {before} s"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
