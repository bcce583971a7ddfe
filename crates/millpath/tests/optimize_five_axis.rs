//! `optimize` on five-axis programs (A/B/C words, trivkins) for the `linuxcnc-time` machine.
//!
//! * `rewrite_keeps_the_path_the_feeds_and_the_joint_limits`: five programs of
//!   `tests/data/five_axis` (the five-axis writer's dense G93 sweep, whose blocks merge; G64 P
//!   with rotary corners, a dense sweep, mixed G93 blocks, arcs turning C) optimized; the
//!   inverse-time rewrite and the kept program read back by the reader (not the rewrite's
//!   code) and compared with the input: every output move the input's next move or a run of
//!   straight blocks whose end points lie within the merge tolerance of its chord (this
//!   test's own point-to-segment distance), the same kind, end point and rotary position, no
//!   feed above the slowest of the run's; every rewritten straight block's
//!   joints within their velocity limits at the feed read back; the per-block peak feed of the
//!   planner (`estimate --blocks`) on the rewrite never above the programmed feed; the kept
//!   program never slower than the input on the controller model.
//! * `loops_are_refused`: a program whose lines run more than once, or that calls a
//!   subroutine, is refused with an `InputError` naming the line.
//! * `linuxcnc_runs_the_rewrite_no_slower`: LinuxCNC 2.9 itself runs three programs and their
//!   rewrites; the rewrite is never slower (by more than a servo cycle), and the merged dense
//!   sweep at least 15 % faster. Skipped without
//!   LinuxCNC unless `MILLPATH_REQUIRE_LINUXCNC=1`.
// The figures are reported on stderr (`cargo test -- --nocapture`).
#![allow(clippy::print_stderr)]

use millpath::gcode::{ReaderOptions, read_str};
use millpath::job::estimate::{EstimateSettings, run_text};
use millpath::job::optimize::{MergeTolerance, OptimizeOptions, optimize_text};
use millpath::machine::Machine;
use millpath::toolpath::Rotary;
use millpath::{Error, MoveKind, Toolpath};
use std::path::{Path, PathBuf};
use std::process::Command;

const PROGRAMS: &[&str] = &[
    "fiveaxis_sweep_ac.ngc",
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

/// Compares `out` with `input`: every output move is the input's next move or, for a straight
/// block, the run of input straight blocks up to the one ending where it ends, every end point
/// in between within the default merge tolerance of its chord (the point-to-segment distance
/// in XYZ, each rotary axis at that point of the chord). Returns, for every output move, the
/// input moves it stands for, and the number of straight blocks whose feed was lowered.
fn same_path(
    input: &Toolpath,
    out: &Toolpath,
    m: &Machine,
    name: &str,
) -> (Vec<std::ops::Range<usize>>, usize) {
    let tol = MergeTolerance::default();
    let (mut rot_in, mut rot_out) = (Rotary::default(), Rotary::default());
    let mut from = input.start;
    let mut lowered = 0;
    let mut ranges = Vec::new();
    let mut i = 0;
    for (k, b) in out.moves.iter().enumerate() {
        let rb = b.rotary.unwrap_or(rot_out);
        let mut j = i;
        let mut r = rot_in;
        loop {
            let a = &input.moves[j];
            let ra = a.rotary.unwrap_or(r);
            if a.to.distance(b.to) <= 1e-9 && ra.distance(rb) <= 1e-12 {
                r = ra;
                break;
            }
            assert!(
                a.kind == MoveKind::Line && b.kind == MoveKind::Line,
                "{name} move {k}: ends where input move {j} does not"
            );
            let ab = b.to - from;
            let u = ((a.to - from).dot(ab) / ab.dot(ab)).clamp(0.0, 1.0);
            let q = from.lerp(b.to, u);
            assert!(
                q.distance(a.to) <= tol.mm * (1.0 + 1e-6),
                "{name} move {k}: input move {j} {} mm off the merged chord",
                q.distance(a.to)
            );
            for (x0, x1, x) in [
                (rot_out.a, rb.a, ra.a),
                (rot_out.b, rb.b, ra.b),
                (rot_out.c, rb.c, ra.c),
            ] {
                assert!(
                    (x0 + u * (x1 - x0) - x).abs() <= tol.rad * (1.0 + 1e-6),
                    "{name} move {k}: input move {j}'s rotary axes off the merged chord"
                );
            }
            r = ra;
            j += 1;
        }
        let a = &input.moves[j];
        assert_eq!(a.kind, b.kind, "{name} move {k}: kind");
        assert_eq!(a.corner, b.corner, "{name} move {k}: path mode");
        let slowest = input.moves[i..=j]
            .iter()
            .map(|a| a.feed)
            .fold(f64::INFINITY, f64::min);
        if a.kind != MoveKind::Rapid {
            assert!(
                b.feed <= slowest * (1.0 + 1e-9),
                "{name} move {k}: feed {} above the programmed {}",
                b.feed,
                slowest
            );
        }
        if a.kind == MoveKind::Line && b.feed < slowest * (1.0 - 1e-9) {
            lowered += 1;
            let d = (b.to - from).to_array();
            let rr = [rb.a - rot_out.a, rb.b - rot_out.b, rb.c - rot_out.c];
            let xyz = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let len = if xyz > 1e-9 {
                xyz
            } else {
                rb.distance(rot_out)
            };
            let t = len / b.feed;
            for (x, l) in d.iter().zip(&m.axes) {
                assert!(
                    x.abs() / t <= l.max_velocity * (1.0 + 1e-6),
                    "{name} move {k}"
                );
            }
            for (x, l) in rr.iter().zip(&m.rotary) {
                let l = l.as_ref().unwrap();
                assert!(
                    x.abs() / t <= l.max_velocity * (1.0 + 1e-6),
                    "{name} move {k}"
                );
            }
        }
        ranges.push(i..j + 1);
        rot_in = r;
        rot_out = rb;
        from = b.to;
        i = j + 1;
    }
    assert_eq!(i, input.moves.len(), "{name}: input moves left over");
    (ranges, lowered)
}

#[test]
fn rewrite_keeps_the_path_the_feeds_and_the_joint_limits() {
    let m = machine();
    for name in PROGRAMS {
        let text = std::fs::read_to_string(data(name)).unwrap();
        let opt = optimize_text(&text, name, &m, &OptimizeOptions::default()).unwrap();
        let input = read(&text);
        assert!(opt.rewritten_blocks > 0, "{name}: nothing rewritten");
        let (ranges, lowered) = same_path(&input, &read(&opt.rewrite), &m, name);
        same_path(&input, &read(&opt.text), &m, name);
        assert_eq!(
            input.moves.len() - ranges.len(),
            opt.merged_blocks,
            "{name}"
        );
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
            let run = &input.moves[ranges[b.origin].clone()];
            let slowest = run.iter().map(|m| m.feed).fold(f64::INFINITY, f64::min);
            if run
                .iter()
                .all(|m| m.kind != MoveKind::Rapid && m.rotary.is_none())
            {
                assert!(
                    b.peak_feed_mm_s <= slowest * (1.0 + 1e-6),
                    "{name} block of move {}: peak {} above {}",
                    b.origin,
                    b.peak_feed_mm_s,
                    slowest
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
            "{name}: {} blocks rewritten ({lowered} lowered, {} merged), model {before:.3} s -> \
             rewrite {rewrite:.3} s, kept {kept:.3} s: {}",
            opt.rewritten_blocks, opt.merged_blocks, opt.outcome
        );
    }
}

#[test]
fn loops_are_refused() {
    let text = "G21 G90 G94\n#1=0\no100 while [#1 LT 3]\nG1 X[#1] A[#1*10] F600\n#1=[#1+1]\n\
                o100 endwhile\nM2\n";
    match optimize_text(text, "loop.ngc", &machine(), &OptimizeOptions::default()) {
        Err(Error::Input(e)) => assert!(e.to_string().contains("line"), "{e}"),
        other => panic!("a loop must be refused: {other:?}"),
    }
    let call = "o<sq> sub\nG1 X#1 A10 F100\no<sq> endsub\nG21 G90 G94\no<sq> call [5]\nM2\n";
    match optimize_text(call, "call.ngc", &machine(), &OptimizeOptions::default()) {
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
    for name in [
        "issue_example.ngc",
        "alternate_3_5.ngc",
        "fiveaxis_sweep_ac.ngc",
    ] {
        let text = std::fs::read_to_string(data(name)).unwrap();
        let opt = optimize_text(&text, name, &machine(), &OptimizeOptions::default()).unwrap();
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
        // The dense sweep's blocks merged: LinuxCNC runs it at least 15 % faster.
        if name == "fiveaxis_sweep_ac.ngc" {
            assert!(after <= 0.85 * before, "{name}: {after} s after {before} s");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A straight line cut into `n` blocks with A turning evenly, `bump` mm off the line in Y at
/// the middle block's end, forwards or backwards.
fn line_program(n: usize, bump: f64, reversed: bool) -> String {
    let mut pts: Vec<(f64, f64, f64)> = (0..=n)
        .map(|k| {
            let u = k as f64 / n as f64;
            let y = if k == n / 2 { bump } else { 0.0 };
            (50.0 * u, y, 30.0 * u)
        })
        .collect();
    if reversed {
        pts.reverse();
    }
    let mut s = format!(
        "G21 G90 G94 G64\nG0 X{:.4} Y{:.4} Z1 A{:.4}\nG1 Z0 F300\n",
        pts[0].0, pts[0].1, pts[0].2
    );
    for p in &pts[1..] {
        s += &format!("G1 X{:.4} Y{:.4} A{:.4} F1500\n", p.0, p.1, p.2);
    }
    s + "G0 Z5\nM2\n"
}

#[test]
fn merging_follows_the_tolerance() {
    let m = machine();
    let mut accepted = 0;
    for reversed in [false, true] {
        // On the line: the 100 blocks become one.
        let text = line_program(100, 0.0, reversed);
        let opt = optimize_text(&text, "line.ngc", &m, &OptimizeOptions::default()).unwrap();
        assert_eq!(opt.merged_blocks, 99, "reversed {reversed}");
        let (ranges, _) = same_path(&read(&text), &read(&opt.rewrite), &m, "line");
        assert!(ranges.iter().any(|r| r.len() == 100));
        assert!(opt.after.cycle_time_s < opt.before.cycle_time_s);
        // 0.01 mm off the line at the middle: over the default 0.001 mm, the middle stays a
        // block end; with a tolerance of 0.05 mm every block merges.
        let text = line_program(100, 0.01, reversed);
        let opt = optimize_text(&text, "bump.ngc", &m, &OptimizeOptions::default()).unwrap();
        let rewrite = read(&opt.rewrite);
        assert!(
            opt.merged_blocks < 99 && opt.merged_blocks >= 95,
            "{}",
            opt.merged_blocks
        );
        assert!(
            rewrite
                .moves
                .iter()
                .any(|mv| (mv.to.x - 25.0).abs() < 1e-9 && (mv.to.y - 0.01).abs() < 1e-9),
            "the bump's vertex is kept"
        );
        same_path(&read(&text), &rewrite, &m, "bump");
        let wide = OptimizeOptions::default().with_merge(Some(MergeTolerance {
            mm: 0.05,
            rad: 0.05f64.to_radians(),
        }));
        let opt = optimize_text(&text, "bump.ngc", &m, &wide).unwrap();
        assert_eq!(opt.merged_blocks, 99);
        // Without merging: every block kept.
        let opt = optimize_text(
            &text,
            "bump.ngc",
            &m,
            &OptimizeOptions::default().with_merge(None),
        )
        .unwrap();
        assert_eq!(opt.merged_blocks, 0);
        accepted += 1;
    }
    assert_eq!(accepted, 2);
    // A line with another word (coolant) ends a run: nothing merges across it.
    let text = line_program(10, 0.0, false).replacen("G1 X25.0000", "M8\nG1 X25.0000", 1);
    let opt = optimize_text(&text, "m8.ngc", &m, &OptimizeOptions::default()).unwrap();
    assert_eq!(opt.merged_blocks, 8, "{}", opt.rewrite);
}

/// A program of `n` G1 blocks along a slowly turning direction with A and C turning, each end
/// point off the smooth curve by up to `noise` mm (and degrees); Y or A left out where they
/// do not change, feeds switching, a coolant line or a path mode change now and then.
fn random_program(
    n: usize,
    turn: f64,
    noise: f64,
    flat_y: bool,
    seeds: &[f64],
    breaks: &[usize],
) -> String {
    let mut s = String::from("G21 G90 G94 G64\nG0 X0 Y0 Z1 A0 C0\nG1 Z0 F300\n");
    let (mut x, mut y, mut a, mut c) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut dir = 0.0f64;
    for k in 0..n {
        let r = |j: usize| seeds[(k * 4 + j) % seeds.len()] - 0.5;
        dir += turn;
        x += 0.3 * dir.cos() + noise * r(0);
        if !flat_y {
            y += 0.3 * dir.sin() + noise * r(1);
        }
        let turn_a = k % 7 != 3;
        if turn_a {
            a += 0.2 + noise * r(2);
        }
        c += 0.5 + noise * r(3);
        match breaks.iter().position(|&b| b == k) {
            Some(0) => s += "M8\n",
            Some(1) => s += "G61\n",
            Some(2) => s += "G64 P0.0005\n",
            _ => {}
        }
        let f = if k % 11 < 6 { 1500 } else { 900 };
        let mut line = format!("G1 X{x:.4}");
        if !flat_y {
            line += &format!(" Y{y:.4}");
        }
        if turn_a {
            line += &format!(" A{a:.4}");
        }
        line += &format!(" C{c:.4} F{f}\n");
        s += &line;
    }
    s + "G0 Z5\nM2\n"
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(39),
        failure_persistence: None,
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// Whatever the program, the merge keeps the path within the tolerance (this file's own
    /// check), never raises a feed, and the kept program is never slower on the model.
    #[test]
    fn merged_programs_keep_their_path(
        n in 10usize..60,
        turn in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0f64..0.05],
        noise in proptest::prop_oneof![
            proptest::strategy::Just(0.0),
            proptest::strategy::Just(0.0004),
            proptest::strategy::Just(0.01)
        ],
        flat_y in proptest::bool::ANY,
        seeds in proptest::collection::vec(0.0f64..1.0, 16),
        breaks in proptest::collection::vec(0usize..60, 0..3),
    ) {
        let text = random_program(n, turn, noise, flat_y, &seeds, &breaks);
        let m = machine();
        let opt = optimize_text(&text, "random.ngc", &m, &OptimizeOptions::default());
        proptest::prop_assert!(opt.is_ok(), "{:?}\n{text}", opt.err());
        let opt = opt.unwrap();
        let input = read(&text);
        let (ranges, _) = same_path(&input, &read(&opt.rewrite), &m, "random");
        proptest::prop_assert_eq!(input.moves.len() - ranges.len(), opt.merged_blocks);
        same_path(&input, &read(&opt.text), &m, "random kept");
        proptest::prop_assert!(opt.after.cycle_time_s.is_finite());
        proptest::prop_assert!(model_time(&opt.text) <= model_time(&text) + 1e-9);
        // On a straight, noiseless line every plain block of a feed merges.
        if turn == 0.0 && noise == 0.0 && breaks.is_empty() {
            proptest::prop_assert!(opt.merged_blocks > 0, "{text}");
        }
    }
}
