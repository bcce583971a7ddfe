//! A whole part from a job file (`job::part`): a plate with a pocket, two drilled holes, a
//! bored hole, faced and cut out with two tabs. Every dialect's program passes the job's own
//! whole-stock check and `verify_program` (which reads the program back and shares nothing
//! with the plan), is timed as `estimate` times it, and LinuxCNC's `rs274` reads it; programs
//! with a section left out or cut too deep fail; the job file's mistakes are refused naming
//! the key, the line and the file.

mod job_common;
mod rs274_common;

use job_common::{same, spec};
use millpath::Error;
use millpath::gcode::Dialect;
use millpath::job::part;
use millpath::job::part::OperationKind;
use millpath::job::program_time;

#[test]
fn the_plate_is_made_in_every_dialect_and_verified_apart() {
    let dir = tempfile::tempdir().unwrap();
    for dialect in [
        Dialect::LinuxCnc,
        Dialect::Fanuc,
        Dialect::Sinumerik,
        Dialect::Grbl,
    ] {
        let mut s = spec(dir.path(), same).unwrap();
        s.dialect = dialect;
        let run = part::run_spec(s.clone(), &mut |_| {}).unwrap();
        let rep = &run.report;
        assert_eq!(rep.operations.len(), 5);
        assert_eq!(rep.features, [1, 1, 3], "{rep:?}");
        assert_eq!(
            rep.check.last().map(|(_, v)| v.as_str()),
            Some("the drawn part, held by its tabs"),
            "{dialect}: {:?}",
            rep.check
        );
        assert!(
            rep.check
                .iter()
                .any(|(k, v)| k.contains("outline 1 held") && v.starts_with("by 2 tab"))
        );
        // The per-operation times add up to the program's, which is what `estimate` reads.
        let sum: f64 = rep.operations.iter().map(|o| o.time_s).sum();
        assert!(
            (sum - rep.cycle_time_s).abs() < 1e-6 * rep.cycle_time_s,
            "{sum} vs {}",
            rep.cycle_time_s
        );
        let t = program_time(&run.run.gcode, dialect, "plate", &run.run.machine).unwrap();
        assert!(
            (t - rep.cycle_time_s).abs() <= 1e-9 * t,
            "{dialect}: {t} vs {}",
            rep.cycle_time_s
        );
        // The written program, read back and checked against the job file alone.
        let text = String::from_utf8(run.run.gcode.clone()).unwrap();
        let v = part::verify_program(&s, &text, "plate.nc", "auto").unwrap();
        assert_eq!(v.dialect.dialect, dialect);
        assert!(v.problems().is_empty(), "{dialect}: {:?}", v.problems());
        let tools: Vec<u32> = v.sections.iter().map(|(t, _)| *t).collect();
        assert_eq!(tools, [1, 2, 1], "{dialect}");
        if dialect == Dialect::LinuxCnc {
            let canon = rs274_common::rs274(&text).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(canon.matches("CHANGE_TOOL").count(), 3, "{canon}");
        }
    }
}

/// The plate's pocket cut through as a window by an inside profile with two tabs, before the
/// plate is cut out: the window's slug is not the part (its slot, leads and entry may cut
/// it), its walls are; the job's check and `verify_program` find the part as drawn, the slug
/// held by its two tabs and the plate by its own.
#[test]
fn a_window_cut_through_with_tabs_is_not_the_part() {
    let dir = tempfile::tempdir().unwrap();
    let window = |t: &str| {
        t.replace(
            "type = \"pocket\"\ntool = 1\ndepth = 2.0\nstep_down = 2.0",
            "type = \"profile\"\ntool = 1\nside = \"inside\"\nstep_down = 2.25\ntabs = 2",
        )
    };
    let s = spec(dir.path(), window).unwrap();
    let run = part::run_spec(s.clone(), &mut |_| {}).unwrap();
    let rep = &run.report;
    assert_eq!(
        rep.check.last().map(|(_, v)| v.as_str()),
        Some("the drawn part, held by its tabs"),
        "{:?}",
        rep.check
    );
    let held: Vec<&str> = rep
        .check
        .iter()
        .filter(|(k, _)| k.contains(" held"))
        .map(|(_, v)| v.as_str())
        .collect();
    assert_eq!(held.len(), 2, "{:?}", rep.check);
    assert!(held.iter().all(|v| v.starts_with("by 2 tab")), "{held:?}");
    let text = String::from_utf8(run.run.gcode.clone()).unwrap();
    let v = part::verify_program(&s, &text, "plate.ngc", "auto").unwrap();
    assert!(v.problems().is_empty(), "{:?}", v.problems());
}

/// Square tabs: the tool goes straight down at each tab's end by the tab's height, which the
/// whole-stock check counts apart from the plunges it refuses; the plate is made, held by its
/// two tabs, and `verify_program` accepts the program read back.
#[test]
fn square_tabs_plunge_only_at_their_ends() {
    let dir = tempfile::tempdir().unwrap();
    let square = |t: &str| format!("{t}tab_shape = \"square\"\n");
    let s = spec(dir.path(), square).unwrap();
    let run = part::run_spec(s.clone(), &mut |_| {}).unwrap();
    let rep = &run.report;
    assert_eq!(
        rep.check.last().map(|(_, v)| v.as_str()),
        Some("the drawn part, held by its tabs"),
        "{:?}",
        rep.check
    );
    let profile = rep
        .check
        .iter()
        .find(|(k, _)| k == "profile")
        .map(|(_, v)| v.as_str())
        .unwrap_or_default();
    assert!(
        profile.contains("0 plunges") && profile.contains("at square tabs' ends"),
        "{profile}"
    );
    let text = String::from_utf8(run.run.gcode.clone()).unwrap();
    let v = part::verify_program(&s, &text, "plate.ngc", "auto").unwrap();
    assert!(v.problems().is_empty(), "{:?}", v.problems());
}

/// A job file with no margin: the stock reaches two diameters of the largest end mill beyond
/// the drawing, so the frame the profile's slot leaves holds the plate by its tabs (at the
/// old 5 mm, less than the 6 mm slot, no frame was left: "held by 0 tab bridges", exit 1).
#[test]
fn the_default_margin_leaves_a_frame_for_the_tabs() {
    let dir = tempfile::tempdir().unwrap();
    let s = spec(dir.path(), |t| t.replace("margin = 10.0\n", "")).unwrap();
    assert!((s.stock.margin - 12.0).abs() < 1e-12, "{}", s.stock.margin);
    let run = part::run_spec(s, &mut |_| {}).unwrap();
    assert_held(&run.report.check);
}

/// A margin narrower than the profile's slot (6 mm here) leaves the tabs no frame to hold
/// to: the job is refused as bad input naming the margin and what it needs (it was an
/// internal error, "held by 0 tab bridges"), and 6 mm, the slot exactly, is made.
#[test]
fn a_margin_narrower_than_the_profile_slot_is_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let s = spec(dir.path(), |t| {
        t.replace("margin = 10.0\n", "margin = 4.0\n")
    })
    .unwrap();
    match part::run_spec(s, &mut |_| {}) {
        Err(Error::Input(e)) => {
            let m = e.to_string();
            assert!(
                m.contains("stock margin = 4 mm") && m.contains("at least 6 mm"),
                "{m}"
            );
        }
        other => panic!("{:?}", other.map(|r| r.report.check)),
    }
    let s = spec(dir.path(), |t| {
        t.replace("margin = 10.0\n", "margin = 6.0\n")
    })
    .unwrap();
    let run = part::run_spec(s, &mut |_| {}).unwrap();
    assert_held(&run.report.check);
}

/// The verdict says how the part is left: held by its tabs, cut free where the profile
/// asks for none, or left in the stock where no operation cuts it out (it said "held by
/// its tabs" then too).
#[test]
fn the_verdict_says_how_the_part_is_left() {
    let dir = tempfile::tempdir().unwrap();
    let cut = "[[operation]]\ntype = \"profile\"\ntool = 1\nstep_down = 2.25\ntabs = 2\n";
    for (edit, want, holds) in [
        (
            "",
            "the drawn part, left in the stock (no profile cuts it out)",
            0,
        ),
        (
            "[[operation]]\ntype = \"profile\"\ntool = 1\nstep_down = 2.25\ntabs = 0\n",
            "the drawn part, cut free (no tabs asked for)",
            1,
        ),
        (cut, "the drawn part, held by its tabs", 1),
    ] {
        let s = spec(dir.path(), |t| t.replace(cut, edit)).unwrap();
        let run = part::run_spec(s, &mut |_| {}).unwrap();
        let check = &run.report.check;
        assert_eq!(
            check.last().map(|(_, v)| v.as_str()),
            Some(want),
            "{check:?}"
        );
        let rows = check.iter().filter(|(k, _)| k.ends_with(" held")).count();
        assert_eq!(rows, holds, "{check:?}");
    }
}

/// A program missing its drilling, missing its profile, or with its pocket 0.2 mm too deep
/// is not the part: `verify_program` says which region and how.
#[test]
fn programs_that_do_not_make_the_part_fail() {
    let dir = tempfile::tempdir().unwrap();
    let s = spec(dir.path(), same).unwrap();
    let run = part::run_spec(s.clone(), &mut |_| {}).unwrap();
    let text = String::from_utf8(run.run.gcode).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let at: Vec<usize> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.starts_with("(operation"))
        .map(|(i, _)| i)
        .collect();
    assert_eq!(at.len(), 5);
    let without = |a: usize, b: usize| -> String {
        let mut v: Vec<&str> = lines[..a].to_vec();
        v.extend(&lines[b..]);
        v.join("\n")
    };
    let check = |program: &str| {
        part::verify_program(&s, program, "x.ngc", "linuxcnc")
            .unwrap()
            .problems()
    };
    let no_drill = check(&without(at[3], at[4]));
    assert!(
        no_drill.iter().any(|p| p.contains("uncut material")),
        "{no_drill:?}"
    );
    let no_profile = check(&(without(at[4], lines.len()) + "\nM2\n"));
    assert!(
        no_profile
            .iter()
            .any(|p| p.contains("0 tab bridge(s) for 2 tab(s)")),
        "{no_profile:?}"
    );
    let deep: Vec<String> = lines
        .iter()
        .enumerate()
        .map(|(i, l)| {
            if i > at[1] && i < at[2] {
                l.split(' ')
                    .map(|w| if w == "Z-2" { "Z-2.2" } else { w })
                    .collect::<Vec<_>>()
                    .join(" ")
            } else {
                (*l).to_owned()
            }
        })
        .collect();
    let deep = check(&deep.join("\n"));
    assert!(
        deep.iter().any(|p| p.contains("below its floor")),
        "{deep:?}"
    );
}

fn message(e: &Error) -> String {
    assert_eq!(e.exit_code(), 2, "{e}");
    e.to_string()
}

/// The job file's mistakes are input errors naming the key, its line and the file.
#[test]
fn job_file_mistakes_name_the_key_line_and_file() {
    let dir = tempfile::tempdir().unwrap();
    let e = message(&spec(dir.path(), |j| j.replace("tabs = 2", "tabz = 2")).unwrap_err());
    assert!(
        e.contains("unknown key = tabz") && e.contains("plate.toml line 46"),
        "{e}"
    );
    let e =
        message(&spec(dir.path(), |j| j.replace("tool = 2\nmax", "tool = 7\nmax")).unwrap_err());
    assert!(e.contains("tool = 7") && e.contains("T1, T2"), "{e}");
    let e =
        message(&spec(dir.path(), |j| j.replace("diameter = 4.0", "diameter = -4")).unwrap_err());
    assert!(e.contains("diameter = -4") && e.contains("line 18"), "{e}");
    let e = message(
        &spec(dir.path(), |j| {
            j.replace("thickness = 4.0", "thickness = [4")
        })
        .unwrap_err(),
    );
    assert!(e.contains("plate.toml line"), "{e}");
    // Read, but not doable: a drill with no hole in its range; material above the part's
    // top and no facing first.
    let s = spec(dir.path(), |j| {
        j.replace("max_diameter = 5", "max_diameter = 3")
    })
    .unwrap();
    let e = message(&part::run_spec(s, &mut |_| {}).unwrap_err());
    assert!(
        e.contains("line 37") && e.contains("drill") && e.contains("max_diameter 3"),
        "{e}"
    );
    let s = spec(dir.path(), |j| {
        j.replacen("[[operation]]\ntype = \"face\"\ntool = 1\n", "", 1)
    })
    .unwrap();
    let e = message(&part::run_spec(s, &mut |_| {}).unwrap_err());
    assert!(
        e.contains("[stock] top") && e.contains("face operation first"),
        "{e}"
    );
}

/// The job's check ends with the verdict that the drawn part is held by its tabs.
fn assert_held(check: &[(String, String)]) {
    assert_eq!(
        check.last().map(|(_, v)| v.as_str()),
        Some("the drawn part, held by its tabs"),
        "{check:?}"
    );
}

/// A 60 × 40 mm plate with a bay 4 mm wide and 32 mm deep, cut out by a 6 mm end mill
/// with four tabs: the tool's path cuts across the bay's mouth and never runs along its
/// walls, so no tab goes there (one did, with no lift on the path: "held by 3 tab
/// bridge(s) for 4 tab(s)"); the job's check and `verify_program` find the plate held by
/// its four tabs.
#[test]
fn no_tab_sits_in_a_bay_the_tool_cannot_enter() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bay.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40">
  <polygon points="0,0 60,0 60,40 32,40 32,8 28,8 28,40 0,40"/>
</svg>
"#,
    )
    .unwrap();
    let path = dir.path().join("bay.toml");
    std::fs::write(
        &path,
        "drawing = \"bay.svg\"\nmachine = \"hsm\"\n\n[stock]\nmargin = 10.0\nthickness = 4.0\n\n\
         [[tool]]\nnumber = 1\ndiameter = 6.0\nfeed = 1200\nspindle = 12000\n\n\
         [[operation]]\ntype = \"profile\"\ntool = 1\nstep_down = 2.25\ntabs = 4\n",
    )
    .unwrap();
    let s = part::read_file(&path).unwrap();
    let run = part::run_spec(s.clone(), &mut |_| {}).unwrap_or_else(|e| panic!("{e}"));
    assert_held(&run.report.check);
    assert!(
        run.report
            .check
            .iter()
            .any(|(k, v)| k.contains("outline 1 held") && v.starts_with("by 4 tab")),
        "{:?}",
        run.report.check
    );
    let text = String::from_utf8(run.run.gcode.clone()).unwrap();
    let v = part::verify_program(&s, &text, "bay.ngc", "auto").unwrap();
    assert!(v.problems().is_empty(), "{:?}", v.problems());
}

#[test]
fn an_adaptive_pocket_takes_the_adaptive_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let pocket = |edit: &str| {
        let s = spec(dir.path(), |j| {
            j.replace("depth = 2.0\nstep_down = 2.0", edit)
        })
        .unwrap();
        s.operations
            .iter()
            .find_map(|o| match &o.kind {
                OperationKind::Pocket(p, _) => Some((**p).clone()),
                _ => None,
            })
            .unwrap()
    };
    // The adaptive cuts a flute length (18 mm here) per level at a tenth of the diameter;
    // the other strategies at most a diameter per level, at 0.4.
    let a = pocket("strategy = \"adaptive\"\ndepth = 12.0");
    assert_eq!((a.stepover.as_str(), a.step_down), ("0.1", 12.0));
    let s = pocket("depth = 12.0");
    assert_eq!((s.stepover.as_str(), s.step_down), ("0.4", 6.0));
    let given = pocket(
        "strategy = \"adaptive\"\ndepth = 12.0\nstepover = 0.3\nstep_down = 4.0\nlift = 0.2",
    );
    assert_eq!((given.stepover.as_str(), given.step_down), ("0.3", 4.0));
    assert_eq!((a.lift, given.lift), (0.0, 0.2));
}
