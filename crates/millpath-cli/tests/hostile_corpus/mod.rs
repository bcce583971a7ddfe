//! The hostile corpus of `cli_hostile.rs`: every command's bad inputs, each with the files it
//! runs beside and the outputs it must not write (the table of `docs/bad-input.md`).

/// One bad input: the command line (run in a temporary directory holding `files`) and the
/// output files it names (which must not appear; `keep.*` files exist beforehand and must
/// keep their content).
pub struct Case {
    pub what: &'static str,
    pub args: &'static [&'static str],
    pub files: &'static [(&'static str, &'static [u8])],
    pub outputs: &'static [&'static str],
}

pub const SQUARE_PTS: &[u8] = b"0,0\n20,-5\n40,0\n45,20\n40,40\n20,45\n0,40\n-5,20\n";
pub const GOOD_NGC: &[u8] =
    b"G21 G90 G17\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 X20 F600\nG1 Y20\nG1 X0\nG1 Y0\nG0 Z5\nM2\n";
pub const BOWTIE_JSON: &[u8] = br#"{"outline": [[0,0],[40,40],[40,0],[0,40]]}"#;
pub const SQUARE_JSON: &[u8] = br#"{"outline": [[0,0],[40,0],[40,40],[0,40]]}"#;
pub const POSES: &[u8] = b"# unit: mm\nx,y,z,i,j,k\n0,0,0,0,0,1\n10,0,0,0,0,1\n20,0,0,0,0,1\n";
pub const KEEP: &[u8] = b"an existing file that an error must not touch\n";

pub fn cases() -> Vec<Case> {
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
            what: "adaptive stepover of a full slot",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "6",
                "--strategy",
                "adaptive",
                "--stepover",
                "1.0",
                "-o",
                "out.ngc",
            ],
            files: &[("sq.json", SQUARE_JSON)],
            outputs: &["out.ngc"],
        },
        Case {
            what: "negative adaptive lift",
            args: &[
                "pocket",
                "sq.json",
                "--tool-diameter",
                "6",
                "--strategy",
                "adaptive",
                "--lift",
                "-0.5",
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
