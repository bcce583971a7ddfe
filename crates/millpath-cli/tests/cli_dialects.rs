//! The shared G-code output flags on `contour`, `pocket`, `profile` and `five-axis`: the same names on
//! every command, every dialect written, `millpath estimate` reading each back (its dialect
//! found from the program) with the cycle time `pocket` planned and `millpath verify`
//! passing it, and what a dialect cannot express refused with exit 2 and no file. Programs
//! of LinuxCNC, Sinumerik and Fanuc read with the dialect found, which a note names.

use std::process::Output;

mod common;
use common::{millpath, stderr};

/// The number after `cycle time ` in a line of output.
fn cycle_time(o: &Output) -> f64 {
    let out = String::from_utf8_lossy(&o.stdout);
    let at = out.find("cycle time ").expect("a cycle time") + "cycle time ".len();
    out[at..]
        .split_whitespace()
        .next()
        .and_then(|s| s.parse().ok())
        .expect("a number")
}

const OUTPUT_FLAGS: [&str; 7] = [
    "--dialect",
    "--units",
    "--decimals",
    "--tool-number",
    "--spindle",
    "--coolant",
    "--line-numbers",
];

#[test]
fn every_program_command_takes_the_same_output_flags_and_shows_a_dialect_example() {
    let dir = tempfile::tempdir().unwrap();
    for cmd in ["contour", "pocket", "profile", "five-axis"] {
        let o = millpath(&[cmd, "--help"], dir.path());
        assert_eq!(o.status.code(), Some(0));
        let help = String::from_utf8_lossy(&o.stdout);
        for flag in OUTPUT_FLAGS {
            assert!(help.contains(flag), "{cmd} --help lacks {flag}");
        }
        let examples = help.split("Examples:").nth(1).unwrap_or("");
        assert!(
            examples.contains("--dialect "),
            "{cmd} --help has no example with --dialect"
        );
    }
}

#[test]
fn pocket_writes_every_dialect_and_estimate_and_verify_read_each_back() {
    let dir = tempfile::tempdir().unwrap();
    let common = [
        "pocket",
        "sample:aerospace",
        "--depth",
        "5",
        "--step-down",
        "5",
        "--cell",
        "0.2",
    ];
    for (dialect, file, tolerance_word) in [
        ("linuxcnc", "p.ngc", "G64 P0.01"),
        ("fanuc", "p.nc", "G05.1 Q1"),
        ("sinumerik", "p.mpf", "CYCLE832(0.01,_FINISH,1)"),
        ("grbl", "p.gcode", "; path tolerance 0.01 mm"),
    ] {
        let mut args = common.to_vec();
        args.extend(["--dialect", dialect, "--tool-number", "7", "-o", file]);
        let o = millpath(&args, dir.path());
        assert_eq!(o.status.code(), Some(0), "{dialect}: {}", stderr(&o));
        let planned = cycle_time(&o);
        let text = std::fs::read_to_string(dir.path().join(file)).unwrap();
        assert!(text.contains(tolerance_word), "{dialect}: {tolerance_word}");
        assert!(text.contains("T7"), "{dialect}: tool number");
        let e = millpath(&["estimate", file], dir.path());
        assert_eq!(e.status.code(), Some(0), "{dialect}: {}", stderr(&e));
        assert!(
            stderr(&e).contains(&format!("note: dialect {dialect}: found from ")),
            "{}",
            stderr(&e)
        );
        let read = cycle_time(&e);
        assert!(
            (read / planned - 1.0).abs() <= 0.005,
            "{dialect}: pocket planned {planned} s, estimate read {read} s"
        );
        // What it writes, `millpath verify` accepts: the dialect found from the program, and
        // named.
        for named in [None, Some(dialect)] {
            let mut v = vec![
                "verify",
                file,
                "--outline",
                "sample:aerospace",
                "--tool-diameter",
                "12.7",
                "--cell",
                "0.2",
                "--json",
            ];
            v.extend(named.iter().flat_map(|d| ["--dialect", *d]));
            let o = millpath(&v, dir.path());
            assert_eq!(o.status.code(), Some(0), "{dialect} verify: {}", stderr(&o));
            // Found, the dialect is named in a note with why; named, no note.
            let note = format!("note: dialect {dialect}: found from ");
            assert_eq!(
                stderr(&o).contains(&note),
                named.is_none(),
                "{}",
                stderr(&o)
            );
            let js: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            assert_eq!(js["passed"], true, "{dialect}: {js}");
        }
    }
}

#[test]
fn what_a_dialect_cannot_express_is_refused_without_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(
        &[
            "five-axis",
            "--case",
            "paper",
            "--machine",
            "xyzac-trt",
            "--no-baseline",
            "--gcode",
            "f.nc",
            "--dialect",
            "grbl",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("grbl") && stderr(&o).contains("rotary"));
    assert!(!dir.path().join("f.nc").exists());
    // Too few decimals for the pocket's resolution, named with the least that would do.
    let o = millpath(
        &[
            "pocket",
            "sample:aerospace",
            "--depth",
            "5",
            "--step-down",
            "5",
            "--units",
            "in",
            "--decimals",
            "4",
            "-o",
            "p.nc",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--decimals") && stderr(&o).contains("at least 5 decimals in inches")
    );
    assert!(!dir.path().join("p.nc").exists());
    let o = millpath(
        &[
            "pocket",
            "sample:aerospace",
            "--coolant",
            "oil",
            "-o",
            "p.nc",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("oil"));
}

#[test]
fn five_axis_writes_fanuc_and_sinumerik_programs() {
    let dir = tempfile::tempdir().unwrap();
    for (dialect, units, word) in [
        ("fanuc", "mm", "O0001"),
        ("sinumerik", "in", "G700"),
        ("linuxcnc", "in", "G20"),
    ] {
        let o = millpath(
            &[
                "five-axis",
                "--case",
                "paper",
                "--machine",
                "xyzbc-trt",
                "--no-baseline",
                "--no-deflection",
                "--gcode",
                "f.nc",
                "--dialect",
                dialect,
                "--units",
                units,
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(0), "{dialect}: {}", stderr(&o));
        let text = std::fs::read_to_string(dir.path().join("f.nc")).unwrap();
        assert!(text.contains(word) && text.contains("G93") && text.contains(" B"));
    }
}

/// A file of the engine's test data.
fn engine_data(rel: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../millpath/tests/data")
        .join(rel)
}

/// The `note: dialect …` line of a run.
fn dialect_note(o: &Output) -> String {
    stderr(o)
        .lines()
        .find(|l| l.starts_with("note: dialect "))
        .unwrap_or_default()
        .to_string()
}

#[test]
fn estimate_finds_the_dialect_of_each_controllers_programs_and_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (from, to) in [
        ("linuxcnc-nc/nc_files/factorial.ngc", "factorial.ngc"),
        ("linuxcnc-demos/boat-xyzac.ngc", "boat-xyzac.ngc"),
    ] {
        std::fs::copy(engine_data(from), d.join(to)).unwrap();
    }
    let sin = "; inch part\nG17 G70 G90 G60\nG0 X1 Y1 Z0.5\nG1 Z-0.1 F10\nG1 X2\nM30\n";
    std::fs::write(d.join("inch.mpf"), sin).unwrap();
    let fanuc =
        "%\nO0001\nG21 G90\n#1=0\nWHILE [#1 LT 3] DO1\nG1 X#1 F600.\n#1=#1+1\nEND1\nM30\n%\n";
    std::fs::write(d.join("loop.nc"), fanuc).unwrap();
    for (file, extra, dialect, why) in [
        (
            "factorial.ngc",
            None,
            "linuxcnc",
            "`o<factorial> sub` at line 3",
        ),
        ("inch.mpf", None, "sinumerik", "`G70` at line 2"),
        (
            "boat-xyzac.ngc",
            Some("--lenient"),
            "linuxcnc",
            "the file extension .ngc",
        ),
        ("loop.nc", None, "fanuc", "`O0001` at line 2"),
    ] {
        let mut args = vec!["estimate", file, "--json"];
        args.extend(extra);
        let auto = millpath(&args, d);
        assert_eq!(auto.status.code(), Some(0), "{file}: {}", stderr(&auto));
        let note = dialect_note(&auto);
        assert!(
            note.starts_with(&format!("note: dialect {dialect}: found from "))
                && note.contains(why),
            "{file}: {note}"
        );
        args.extend(["--dialect", dialect]);
        let named = millpath(&args, d);
        assert_eq!(auto.stdout, named.stdout, "{file}");
        assert_eq!(dialect_note(&named), "", "{file}");
    }
    // Grbl, which `;` comments suggest, has no rotary axes; LinuxCNC reads the program.
    std::fs::write(
        d.join("rotary.nc"),
        "; c\nG21 G90\nG0 X1 A5\nG1 X2 F600\nM2\n",
    )
    .unwrap();
    let o = millpath(&["estimate", "rotary.nc"], d);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let note = dialect_note(&o);
    assert!(
        note.starts_with("note: dialect linuxcnc: grbl (suggested by `;` at line 1")
            && note.contains("A5")
            && note.ends_with("this dialect reads all of it"),
        "{note}"
    );
    let o = millpath(&["estimate", "rotary.nc", "--dialect", "grbl"], d);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("A5") && stderr(&o).contains("rotary.nc:3"));
}
