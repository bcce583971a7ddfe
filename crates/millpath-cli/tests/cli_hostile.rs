//! End-to-end hostile pass over the built binary: every command (contour, pocket, estimate,
//! verify, five-axis, sweep) on a corpus of bad inputs. Each case must
//!
//! * exit with code 2 (bad input), never 1 (internal) or a signal;
//! * print one message of the shape `error: invalid WHAT = VALUE (from ORIGIN): expected
//!   ACCEPTED` on stderr: the value, where it came from and what would be accepted (the
//!   `(from ORIGIN)` part may be absent only where WHAT is itself the origin: a flag such as
//!   `--dt`, or the input file named on the command line); no panic message, no backtrace;
//! * write no output file, and leave an existing output file of the same name untouched (no
//!   temporary file left beside it either).
//!
//! The cases and the exact messages they get are the table in `docs/bad-input.md`; the test
//! regenerates the table and fails when the document differs, so it cannot drift. After a
//! deliberate change of a message: `MILLPATH_BLESS=1 cargo test -p millpath-cli --test
//! cli_hostile` rewrites the table.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One bad input: the command line (run in a temporary directory holding `files`) and the
/// output files it names (which must not appear; `keep.*` files exist beforehand and must
/// keep their content).
struct Case {
    what: &'static str,
    args: &'static [&'static str],
    files: &'static [(&'static str, &'static [u8])],
    outputs: &'static [&'static str],
}

const SQUARE_PTS: &[u8] = b"0,0\n20,-5\n40,0\n45,20\n40,40\n20,45\n0,40\n-5,20\n";
const GOOD_NGC: &[u8] =
    b"G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 F600\nG1 Y20\nG1 X0\nG1 Y0\nG0 Z5\nM2\n";
const BOWTIE_JSON: &[u8] = br#"{"outline": [[0,0],[40,40],[40,0],[0,40]]}"#;
const SQUARE_JSON: &[u8] = br#"{"outline": [[0,0],[40,0],[40,40],[0,40]]}"#;
const POSES: &[u8] = b"# unit: mm\nx,y,z,i,j,k\n0,0,0,0,0,1\n10,0,0,0,0,1\n20,0,0,0,0,1\n";
const KEEP: &[u8] = b"an existing file that an error must not touch\n";

fn cases() -> Vec<Case> {
    vec![
        // contour
        Case {
            what: "points file with a NaN coordinate",
            args: &["contour", "pts.csv", "-o", "out.ngc"],
            files: &[("pts.csv", b"0,0\n40,0\n40,nan\n0,40\n")],
            outputs: &["out.ngc"],
        },
        Case {
            what: "points file with text for a number",
            args: &["contour", "pts.csv", "-o", "out.ngc"],
            files: &[("pts.csv", b"0,0\n40,zero\n40,40\n0,40\n")],
            outputs: &["out.ngc"],
        },
        Case {
            what: "points file with two points",
            args: &["contour", "pts.csv", "--curve", "spline", "-o", "out.ngc"],
            files: &[("pts.csv", b"0,0\n40,0\n")],
            outputs: &["out.ngc"],
        },
        Case {
            what: "empty points file",
            args: &["contour", "pts.csv", "-o", "out.ngc"],
            files: &[("pts.csv", b"")],
            outputs: &["out.ngc"],
        },
        Case {
            what: "points file that is not UTF-8",
            args: &["contour", "pts.csv", "-o", "out.ngc"],
            files: &[("pts.csv", b"0,0\n\xff\xfe,1\n")],
            outputs: &["out.ngc"],
        },
        Case {
            what: "points file that does not exist",
            args: &["contour", "missing.csv", "-o", "out.ngc"],
            files: &[],
            outputs: &["out.ngc"],
        },
        Case {
            what: "negative tool diameter",
            args: &[
                "contour",
                "pts.csv",
                "--curve",
                "spline",
                "--tool-diameter=-3",
                "-o",
                "keep.ngc",
                "--report",
                "out.json",
            ],
            files: &[("pts.csv", SQUARE_PTS), ("keep.ngc", KEEP)],
            outputs: &["keep.ngc", "out.json"],
        },
        Case {
            what: "zero tolerance",
            args: &["contour", "--sample", "--tolerance", "0", "-o", "keep.ngc"],
            files: &[("keep.ngc", KEEP)],
            outputs: &["keep.ngc"],
        },
        Case {
            what: "NaN depth",
            args: &[
                "contour",
                "pts.csv",
                "--curve",
                "spline",
                "--depth",
                "NaN",
                "-o",
                "out.ngc",
            ],
            files: &[("pts.csv", SQUARE_PTS)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "negative step-down",
            args: &[
                "contour",
                "pts.csv",
                "--curve",
                "spline",
                "--step-down=-1",
                "-o",
                "out.ngc",
            ],
            files: &[("pts.csv", SQUARE_PTS)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "tool too large for an inside contour",
            args: &[
                "contour",
                "pts.csv",
                "--curve",
                "spline",
                "--side",
                "inside",
                "--tool-diameter",
                "60",
                "-o",
                "out.ngc",
            ],
            files: &[("pts.csv", SQUARE_PTS)],
            outputs: &["out.ngc"],
        },
        // pocket
        Case {
            what: "self-intersecting outline (bow tie)",
            args: &["pocket", "bowtie.json", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[("bowtie.json", BOWTIE_JSON)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "spiral with the fronts morph into a 6° sliver triangle",
            args: &[
                "pocket",
                "sliver.json",
                "--morph",
                "fronts",
                "--tool-diameter",
                "3",
                "--depth",
                "0.5",
                "--step-down",
                "0.3",
                "-o",
                "out.ngc",
            ],
            files: &[(
                "sliver.json",
                br#"{"outline": [[18.1786, -26.8795], [-56.5653, -75.0708], [39.1783, -26.8795]]}"#,
            )],
            outputs: &["out.ngc"],
        },
        Case {
            what: "bottom outline that moves a slit of material into the pocket above (an undercut)",
            args: &[
                "pocket",
                "slit.json",
                "--bottom-outline",
                "slit-bottom.json",
                "--tool-diameter",
                "3",
                "--depth",
                "6",
                "--step-down",
                "2",
                "-o",
                "keep.ngc",
            ],
            files: &[
                (
                    "slit.json",
                    br#"{"outline": [[0,0],[60,0],[60,29.6],[20,30],[60,30.4],[60,60],[0,60]]}"#,
                ),
                (
                    "slit-bottom.json",
                    br#"{"outline": [[7.4286,6],[55.4286,6],[55.4286,29.68],[23.4286,30],[55.4286,30.32],[55.4286,54],[7.4286,54]]}"#,
                ),
                ("keep.ngc", KEEP),
            ],
            outputs: &["keep.ngc"],
        },
        Case {
            what: "fewer decimals than the pocket's resolution in inches",
            args: &["pocket", "sample:aerospace", "--units", "in", "--decimals", "4", "-o", "keep.nc"],
            files: &[("keep.nc", KEEP)],
            outputs: &["keep.nc"],
        },
        Case {
            what: "five-axis G-code for grbl (no rotary axes)",
            args: &["five-axis", "--case", "paper", "--machine", "xyzac-trt", "--gcode", "out.nc", "--dialect", "grbl"],
            files: &[],
            outputs: &["out.nc"],
        },
        Case {
            what: "safe height of 1e300 mm (the fuzzer's helix of 1e300 turns)",
            args: &["pocket", "sample:aerospace", "--safe-height", "1e300", "-o", "out.ngc"],
            files: &[],
            outputs: &["out.ngc"],
        },
        Case {
            what: "ramp angle of 1e-7 degrees (a helix of millions of turns)",
            args: &["pocket", "sample:aerospace", "--ramp-angle", "0.0000001", "-o", "keep.ngc"],
            files: &[("keep.ngc", KEEP)],
            outputs: &["keep.ngc"],
        },
        Case {
            what: "tool larger than the pocket",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "50",
                "-o",
                "keep.ngc",
            ],
            files: &[("sq.json", SQUARE_JSON), ("keep.ngc", KEEP)],
            outputs: &["keep.ngc"],
        },
        Case {
            what: "stepover of zero",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "6",
                "--stepover",
                "0",
                "-o",
                "out.ngc",
            ],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "stepover that is not a number",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "6",
                "--stepover",
                "lots",
                "-o",
                "out.ngc",
            ],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "negative depth",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "6",
                "--depth=-5",
                "-o",
                "out.ngc",
            ],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "negative feed",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "6",
                "--feed=-600",
                "-o",
                "out.ngc",
            ],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "outline JSON with a vertex at 1e999",
            args: &["pocket", "bad.json", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[("bad.json", br#"{"outline": [[0,0],[40,0],[40,1e999],[0,40]]}"#)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "DXF without a closed outline",
            args: &["pocket", "open.dxf", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[(
                "open.dxf",
                b"0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n0\n20\n0\n11\n40\n21\n0\n0\nENDSEC\n0\nEOF\n",
            )],
            outputs: &["out.ngc"],
        },
        Case {
            what: "pocket --select beyond the drawing's pockets",
            args: &["pocket", "two.svg", "--select", "3", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[(
                "two.svg",
                br#"<svg><path d="M 0 0 L 40 0 L 40 40 L 0 40 Z"/><path d="M 50 0 L 90 0 L 90 40 L 50 40 Z"/></svg>"#,
            )],
            outputs: &["out.ngc"],
        },
        Case {
            what: "SVG path with a huge coordinate",
            args: &["pocket", "huge.svg", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[(
                "huge.svg",
                br#"<svg><path d="M 0 0 L 40 0 L 40 1e9 L 0 40 Z"/></svg>"#,
            )],
            outputs: &["out.ngc"],
        },
        Case {
            what: "SVG elliptical arc of radius 1e55 mm (the fuzzer's 7.5 GB abort)",
            args: &["pocket", "arc.svg", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[(
                "arc.svg",
                br#"<svg><path d="M 0 0 A 1e55 1e11 10 1 1 1000 0 Z"/></svg>"#,
            )],
            outputs: &["out.ngc"],
        },
        Case {
            what: "DXF SPLINE of degree 2 with two control points (the fuzzer's index panic)",
            args: &["pocket", "spline.dxf", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[(
                "spline.dxf",
                b"0\nSECTION\n2\nENTITIES\n0\nSPLINE\n70\n8\n71\n2\n72\n5\n73\n2\n\
                  40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n10\n0\n20\n0\n30\n0\n10\n10\n20\n10\n30\n0\n\
                  0\nENDSEC\n0\nEOF\n",
            )],
            outputs: &["out.ngc"],
        },
        Case {
            what: "outline file that does not exist",
            args: &["pocket", "missing.dxf", "--tool-diameter", "6", "-o", "out.ngc"],
            files: &[],
            outputs: &["out.ngc"],
        },
        // estimate
        Case {
            what: "unsupported G-code word",
            args: &["estimate", "bad.ngc", "--samples", "out.csv"],
            files: &[("bad.ngc", b"G21 G90\nG1 X1 F600\nG1 X2 Q7\nM2\n")],
            outputs: &["out.csv"],
        },
        Case {
            what: "negative feed word",
            args: &["estimate", "bad.ngc", "--html", "out.html"],
            files: &[("bad.ngc", b"G21 G90\nG1 X10 F-100\nM2\n")],
            outputs: &["out.html"],
        },
        Case {
            what: "number in exponent notation (1e400)",
            args: &["estimate", "bad.ngc"],
            files: &[("bad.ngc", b"G21 G90\nG1 X1e400 F600\nM2\n")],
            outputs: &[],
        },
        Case {
            what: "number in exponent notation (1E5, upper case)",
            args: &["estimate", "bad.ngc"],
            files: &[("bad.ngc", b"G21 G90\nG0 X0 Y0\nG1 Y1E5 F600\nM2\n")],
            outputs: &[],
        },
        Case {
            what: "arc whose end is not on its circle",
            args: &["estimate", "bad.ngc"],
            files: &[("bad.ngc", b"G21 G90 G17\nG1 X0 Y0 F600\nG2 X10 Y0 I1 J0\nM2\n")],
            outputs: &[],
        },
        Case {
            what: "binary garbage as a program",
            args: &["estimate", "bad.ngc"],
            files: &[("bad.ngc", b"\x00\x01\x02\xff\xfeG1\x00X\x80\n")],
            outputs: &[],
        },
        Case {
            what: "program that never ends (a while loop)",
            args: &["estimate", "loop.ngc", "--step-budget", "1000"],
            files: &[(
                "loop.ngc",
                b"#1 = 1\no100 while [#1 GT 0]\nG1 X1 F600\nG1 X0\no100 endwhile\nM2\n",
            )],
            outputs: &[],
        },
        Case {
            what: "Fanuc main program that loops by M99",
            args: &["estimate", "loop.nc", "--step-budget", "1000", "--svg", "out.svg"],
            files: &[("loop.nc", b"%\nO1\nG1 X1. F600.\nG1 X0\nM99\n%\n")],
            outputs: &["out.svg"],
        },
        Case {
            what: "sampling rate below 1 kHz",
            args: &["estimate", "ok.ngc", "--rate", "10", "--samples", "out.csv"],
            files: &[("ok.ngc", GOOD_NGC)],
            outputs: &["out.csv"],
        },
        Case {
            what: "unknown machine preset",
            args: &["estimate", "ok.ngc", "--machine", "warp-drive"],
            files: &[("ok.ngc", GOOD_NGC)],
            outputs: &[],
        },
        Case {
            what: "machine profile with a negative acceleration",
            args: &["estimate", "ok.ngc", "--machine", "m.toml"],
            files: &[
                ("ok.ngc", GOOD_NGC),
                (
                    "m.toml",
                    b"name = \"bad\"\nmax_feed = 200.0\n[axes.x]\nmax_velocity = 500.0\nmax_acceleration = -3000.0\nmax_jerk = 50000.0\n[axes.y]\nmax_velocity = 500.0\nmax_acceleration = 3000.0\nmax_jerk = 50000.0\n[axes.z]\nmax_velocity = 200.0\nmax_acceleration = 2000.0\nmax_jerk = 50000.0\n",
                ),
            ],
            outputs: &[],
        },
        Case {
            what: "machine profile with an unknown key",
            args: &["estimate", "ok.ngc", "--machine", "m.toml"],
            files: &[
                ("ok.ngc", GOOD_NGC),
                (
                    "m.toml",
                    b"name = \"bad\"\nmax_feed = 200.0\npath_tolerence = 0.01\n[axes.x]\nmax_velocity = 500.0\nmax_acceleration = 3000.0\nmax_jerk = 50000.0\n[axes.y]\nmax_velocity = 500.0\nmax_acceleration = 3000.0\nmax_jerk = 50000.0\n[axes.z]\nmax_velocity = 200.0\nmax_acceleration = 2000.0\nmax_jerk = 50000.0\n",
                ),
            ],
            outputs: &[],
        },
        Case {
            what: "calibration times without the header",
            args: &["calibrate", "t.csv", "-o", "fit.toml"],
            files: &[("t.csv", b"ok.ngc,1.5\n"), ("ok.ngc", GOOD_NGC)],
            outputs: &["fit.toml"],
        },
        Case {
            what: "calibration program that does not exist",
            args: &["calibrate", "t.csv", "-o", "fit.toml"],
            files: &[("t.csv", b"program,seconds\nmissing.ngc,1.5\n")],
            outputs: &["fit.toml"],
        },
        Case {
            what: "calibration time that is not a number",
            args: &["calibrate", "t.csv", "-o", "fit.toml"],
            files: &[("t.csv", b"program,seconds\nok.ngc,fast\n"), ("ok.ngc", GOOD_NGC)],
            outputs: &["fit.toml"],
        },
        Case {
            what: "program file that does not exist",
            args: &["estimate", "missing.ngc", "--html", "out.html"],
            files: &[],
            outputs: &["out.html"],
        },
        // verify
        Case {
            what: "program with an unsupported word",
            args: &[
                "verify",
                "bad.ngc",
                "--outline",
                "sq.json",
                "--tool-diameter",
                "6",
                "--report",
                "out.json",
            ],
            files: &[
                ("bad.ngc", b"G21 G90\nG1 X1 F600\nG1 X2 Q7\nM2\n"),
                ("sq.json", SQUARE_JSON),
            ],
            outputs: &["out.json"],
        },
        Case {
            what: "program that never ends (a GOTO loop)",
            args: &[
                "verify",
                "loop.nc",
                "--outline",
                "sq.json",
                "--tool-diameter",
                "6",
                "--step-budget",
                "1000",
            ],
            files: &[
                ("loop.nc", b"%\nO1\nN10 G1 X1. F600.\nG1 X0\nGOTO 10\nM30\n%\n"),
                ("sq.json", SQUARE_JSON),
            ],
            outputs: &[],
        },
        Case {
            what: "tool diameter of zero",
            args: &[
                "verify",
                "ok.ngc",
                "--outline",
                "sq.json",
                "--tool-diameter",
                "0",
                "--report",
                "keep.json",
            ],
            files: &[
                ("ok.ngc", GOOD_NGC),
                ("sq.json", SQUARE_JSON),
                ("keep.json", KEEP),
            ],
            outputs: &["keep.json"],
        },
        Case {
            what: "no tool diameter, and a program whose header names no tool",
            args: &["verify", "ok.ngc", "--outline", "sq.json", "--report", "keep.json"],
            files: &[
                ("ok.ngc", GOOD_NGC),
                ("sq.json", SQUARE_JSON),
                ("keep.json", KEEP),
            ],
            outputs: &["keep.json"],
        },
        Case {
            what: "outline file that does not exist",
            args: &[
                "verify",
                "ok.ngc",
                "--outline",
                "missing.json",
                "--tool-diameter",
                "6",
            ],
            files: &[("ok.ngc", GOOD_NGC)],
            outputs: &[],
        },
        // five-axis
        Case {
            what: "pose file with a NaN coordinate",
            args: &["five-axis", "poses.csv", "--csv", "out.csv"],
            files: &[(
                "poses.csv",
                b"# unit: mm\nx,y,z,i,j,k\n0,0,0,0,0,1\n10,nan,0,0,0,1\n20,0,0,0,0,1\n",
            )],
            outputs: &["out.csv"],
        },
        Case {
            what: "pose with a zero tool axis",
            args: &["five-axis", "poses.csv", "--csv", "out.csv"],
            files: &[(
                "poses.csv",
                b"# unit: mm\nx,y,z,i,j,k\n0,0,0,0,0,1\n10,0,0,0,0,0\n20,0,0,0,0,1\n",
            )],
            outputs: &["out.csv"],
        },
        Case {
            what: "unknown built-in case",
            args: &["five-axis", "--case", "moon"],
            files: &[],
            outputs: &[],
        },
        Case {
            what: "unknown machine",
            args: &["five-axis", "poses.csv", "--machine", "hexapod"],
            files: &[("poses.csv", POSES)],
            outputs: &[],
        },
        Case {
            what: "sample step of zero",
            args: &["five-axis", "poses.csv", "--dt", "0", "--csv", "keep.csv"],
            files: &[("poses.csv", POSES), ("keep.csv", KEEP)],
            outputs: &["keep.csv"],
        },
        // sweep
        Case {
            what: "ratio list with text",
            args: &["sweep", "sq.json", "--ratios", "0.2,half", "--csv", "out.csv"],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.csv"],
        },
        Case {
            what: "negative feed in the feed list",
            args: &["sweep", "sq.json", "--feeds", "300,-1", "--csv", "out.csv"],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.csv"],
        },
        Case {
            what: "transition ratio above 1 in the ratio list",
            args: &["sweep", "sq.json", "--ratios", "0.2,1.5", "--csv", "out.csv"],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.csv"],
        },
        Case {
            what: "outline file that does not exist",
            args: &["sweep", "missing.json", "--csv", "out.csv"],
            files: &[],
            outputs: &["out.csv"],
        },
    ]
}

struct Outcome {
    code: Option<i32>,
    message: String,
    problems: Vec<String>,
}

fn run(case: &Case) -> Outcome {
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, body) in case.files {
        std::fs::write(dir.path().join(name), body).expect("write input");
    }
    let before: Vec<PathBuf> = listing(dir.path());
    let o = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(case.args)
        .current_dir(dir.path())
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the millpath binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let mut problems = Vec::new();
    let code = o.status.code();
    if code != Some(2) {
        problems.push(format!("exit code {code:?}, expected 2"));
    }
    // `note:` lines (what a drawing held, read before the refusal) are information, not the
    // error: the error itself is one line.
    let message = stderr
        .trim_end()
        .lines()
        .filter(|l| !l.starts_with("note: "))
        .collect::<Vec<_>>()
        .join("\n");
    for bad in ["panicked", "backtrace", "internal error", "RUST_BACKTRACE"] {
        if message.contains(bad) {
            problems.push(format!("stderr contains `{bad}`"));
        }
    }
    // The origin is in `(from ...)`, or is the WHAT itself: a flag (`invalid --dt = 0`) or
    // the file named on the command line (`invalid input file = part.dxf`).
    let what = message
        .strip_prefix("error: invalid ")
        .and_then(|r| r.split(" = ").next())
        .unwrap_or("");
    let self_origin = what.starts_with("--") || what.ends_with(" file");
    let shape = message.starts_with("error: invalid ")
        && message.contains(" = ")
        && message.contains(": expected ")
        && (message.contains(" (from ") || self_origin);
    if !shape {
        problems.push(
            "message is not `error: invalid WHAT = VALUE (from ORIGIN): expected ACCEPTED`"
                .to_owned(),
        );
    }
    if message.lines().count() != 1 {
        problems.push("message is not one line".to_owned());
    }
    for out in case.outputs {
        let p = dir.path().join(out);
        if out.starts_with("keep.") {
            if std::fs::read(&p).ok().as_deref() != Some(KEEP) {
                problems.push(format!("existing {out} was modified"));
            }
        } else if p.exists() {
            problems.push(format!("output {out} was written"));
        }
    }
    let after = listing(dir.path());
    if after != before {
        problems.push(format!("files changed: before {before:?}, after {after:?}"));
    }
    Outcome {
        code,
        message,
        problems,
    }
}

fn listing(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.sort();
    v
}

fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The messages name the flag or file:line the value came from and the value as typed (not
/// a converted value, not a neighbouring word): one case per message that once did not.
#[test]
fn messages_name_the_flag_and_the_value_as_typed() {
    let checks: &[(Case, &[&str])] = &[
        (
            Case {
                what: "negative feed in the feed list",
                args: &["sweep", "sq.json", "--feeds", "300,-1", "--csv", "out.csv"],
                files: &[("sq.json", SQUARE_JSON)],
                outputs: &["out.csv"],
            },
            // Was `invalid feed = -0.4233333333333333 (from --feed)`.
            &["feed = -1 ", "(from --feeds)", "> 0 in/min"],
        ),
        (
            Case {
                what: "NaN depth",
                args: &[
                    "contour", "pts.csv", "--curve", "spline", "--depth", "NaN", "-o", "out.ngc",
                ],
                files: &[("pts.csv", SQUARE_PTS)],
                outputs: &["out.ngc"],
            },
            // Was `(from contour options)`.
            &["depth = NaN", "(from --depth)", "> 0 mm"],
        ),
        (
            Case {
                what: "number in exponent notation",
                args: &["estimate", "bad.ngc"],
                files: &[("bad.ngc", b"G21 G90\nG1 X1e400 F600\nM2\n")],
                outputs: &[],
            },
            // Was `invalid G-code word = e400 (from bad.ngc:2)`.
            &["X1e400", "(from bad.ngc:2)", "without exponent"],
        ),
    ];
    let mut failures = Vec::new();
    for (case, needles) in checks {
        let out = run(case);
        for n in *needles {
            if !out.message.contains(n) {
                failures.push(format!("{}: `{n}` missing in `{}`", case.what, out.message));
            }
        }
        failures.extend(out.problems.iter().map(|p| format!("{}: {p}", case.what)));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

const BEGIN: &str = "<!-- BEGIN GENERATED by crates/millpath-cli/tests/cli_hostile.rs -->";
const END: &str = "<!-- END GENERATED -->";

#[test]
fn every_command_refuses_the_hostile_corpus_cleanly() {
    let mut table = String::from("| command | bad input | command line | exit | message |\n");
    table.push_str("|---|---|---|---|---|\n");
    let mut failures = Vec::new();
    for case in cases() {
        let out = run(&case);
        let cmdline = case.args.join(" ");
        if !out.problems.is_empty() {
            failures.push(format!(
                "`millpath {cmdline}` ({}): {}\n    stderr: {}",
                case.what,
                out.problems.join("; "),
                out.message
            ));
        }
        table.push_str(&format!(
            "| {} | {} | `millpath {}` | {} | `{}` |\n",
            case.args[0],
            cell(case.what),
            cell(&cmdline),
            out.code.map_or("signal".into(), |c| c.to_string()),
            cell(&out.message)
        ));
    }
    let doc_path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/bad-input.md");
    let doc = std::fs::read_to_string(&doc_path).unwrap_or_default();
    let generated = format!("{BEGIN}\n{table}{END}");
    let current = match (doc.find(BEGIN), doc.find(END)) {
        (Some(a), Some(b)) if a < b => Some(&doc[a..b + END.len()]),
        _ => None,
    };
    if current != Some(generated.as_str()) {
        if std::env::var_os("MILLPATH_BLESS").is_some() {
            let new = match current {
                Some(c) => doc.replace(c, &generated),
                None => format!("{doc}\n{generated}\n"),
            };
            std::fs::write(&doc_path, new).expect("write docs/bad-input.md");
        } else {
            failures.push(format!(
                "docs/bad-input.md is out of date with the messages; rerun with MILLPATH_BLESS=1. \
                 Generated table:\n{generated}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
