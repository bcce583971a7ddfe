//! The binary's contract: exit 0 on success, 2 on bad input with a message naming the value
//! and where it came from, and no output file after an error.

mod common;
use common::{millpath, stderr};

#[test]
fn machines_json_lists_the_presets() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(&["machines", "--json"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    let text = v.to_string();
    for name in ["hsm", "linuxcnc-sim", "router"] {
        assert!(text.contains(name), "preset {name} missing: {text}");
    }
}

#[test]
fn unknown_gcode_word_is_bad_input_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bad.ngc"),
        "G21 G90\nG1 X1 F600\nG1 X2 Q7\nM2\n",
    )
    .unwrap();
    let o = millpath(&["estimate", "bad.ngc", "--json"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains('Q') && e.contains(":3"),
        "message names the word and line 3: {e}"
    );
    assert!(!e.contains("panicked"), "{e}");
}

#[test]
fn bad_tolerance_leaves_no_output_and_keeps_an_existing_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("old.ngc"), "keep me").unwrap();
    let o = millpath(
        &[
            "contour",
            "--sample",
            "--tolerance=-1",
            "-o",
            "old.ngc",
            "--report",
            "r.json",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("tolerance"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("old.ngc")).unwrap(),
        "keep me"
    );
    assert!(!dir.path().join("r.json").exists());
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "temporary files left: {leftovers:?}");
}

#[test]
fn pocket_stepover_zero_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(
        &[
            "pocket",
            "sample:aerospace",
            "--strategy",
            "offset",
            "--tool-diameter",
            "12.7",
            "--stepover",
            "0",
            "-o",
            "p.ngc",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("stepover"), "{}", stderr(&o));
    assert!(!dir.path().join("p.ngc").exists());
}

#[test]
fn unreadable_input_file_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["estimate", "missing.ngc"][..],
        &["contour", "missing.csv", "-o", "x.ngc"][..],
        &["five-axis", "missing.csv"][..],
    ] {
        let o = millpath(args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("missing."), "{args:?}: {}", stderr(&o));
    }
}

/// A number of end knots past any use is bad input, not hours of planning and gigabytes
/// (`--end-knots 100000000` ran out of memory).
#[test]
fn too_many_end_knots_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(
        &[
            "five-axis",
            "--case",
            "paper",
            "--no-baseline",
            "--end-knots",
            "100000000",
            "--csv",
            "f.csv",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--end-knots"), "{}", stderr(&o));
    assert!(!dir.path().join("f.csv").exists());
}

/// `optimize`'s merge tolerances and five-axis's `--min-interval` out of range are bad input,
/// with no file written.
#[test]
fn optimize_and_five_axis_tolerances_out_of_range_are_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("p.ngc"),
        "G21 G90\nG1 X1 A1 F100\nG1 X2 A2\nM2\n",
    )
    .unwrap();
    for (flag, value) in [
        ("--tolerance", "0"),
        ("--tolerance", "nan"),
        ("--tolerance-deg", "-1"),
        ("--tolerance", "5"),
    ] {
        let o = millpath(
            &["optimize", "p.ngc", "-o", "o.ngc", flag, value],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {}", stderr(&o));
        assert!(stderr(&o).contains(flag), "{}", stderr(&o));
        assert!(!dir.path().join("o.ngc").exists());
    }
    for value in ["-0.1", "2", "inf"] {
        let o = millpath(
            &[
                "five-axis",
                "--case",
                "paper",
                "--no-baseline",
                "--min-interval",
                value,
                "--csv",
                "f.csv",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{value}: {}", stderr(&o));
        assert!(stderr(&o).contains("--min-interval"), "{}", stderr(&o));
        assert!(!dir.path().join("f.csv").exists());
    }
    for value in ["-1", "16", "nan"] {
        let o = millpath(
            &[
                "five-axis",
                "--case",
                "paper",
                "--no-baseline",
                "--tilt-tolerance",
                value,
                "--csv",
                "f.csv",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{value}: {}", stderr(&o));
        assert!(stderr(&o).contains("--tilt-tolerance"), "{}", stderr(&o));
        assert!(!dir.path().join("f.csv").exists());
    }
}

#[test]
fn estimate_writes_a_self_contained_html_report() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("sq.ngc"),
        "G21 G90 G17\nG0 X0 Y0 Z1\nG1 Z0 F1000\nG1 X20\nG1 Y20\nG2 X0 Y20 I-10 J0\nG1 Y0\nM2\n",
    )
    .unwrap();
    let o = millpath(&["estimate", "sq.ngc", "--html", "r.html"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let html = std::fs::read_to_string(dir.path().join("r.html")).expect("report written");
    assert!(
        html.contains("<svg") && html.contains("cycle time"),
        "viewer and summary"
    );
    let external = html
        .match_indices("http")
        .filter(|(i, _)| !html[*i..].starts_with("http://www.w3.org/"))
        .count();
    assert_eq!(external, 0, "the report must not reference the network");
}

/// `sweep` honours the wall flags of `pocket`: with a 10° draft every level's section is
/// smaller, so both strategies take less time (it used to ignore the flag).
#[test]
fn sweep_honours_the_draft() {
    let dir = tempfile::tempdir().unwrap();
    let zigzag = |extra: &[&str]| -> f64 {
        let mut args = vec![
            "sweep",
            "sample:aerospace",
            "--ratios",
            "0.5",
            "--feeds",
            "600",
            "--depth",
            "6",
            "--step-down",
            "3",
            "--json",
        ];
        args.extend_from_slice(extra);
        let o = millpath(&args, dir.path());
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["zigzag_s"][0].as_f64().unwrap()
    };
    let (plain, drafted) = (zigzag(&[]), zigzag(&["--draft", "10"]));
    // Ignoring the flag gives the same time to the last digit; the second level's section is
    // 0.53 mm smaller all round (27.70 s against 27.79 s with rows up to 0.95 r off the walls).
    assert!(drafted < plain - 0.02, "{drafted} vs {plain}");
}

/// A drawing at building scale with the default 12.7 mm tool (`ez_insert_bricscad_level_1.dxf`:
/// six 4.3 × 5.5 m panels, in metres by its header) would plan about 19 km of path per
/// panel and take tens of gigabytes: refused at once, naming the estimate and the units,
/// with every strategy, and no file written.
#[test]
fn a_building_scale_drawing_with_the_default_tool_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let path = common::real_input("ez_insert_bricscad_level_1.dxf");
    for strategy in ["spiral", "adaptive"] {
        let o = millpath(
            &["pocket", &path, "--strategy", strategy, "-o", "p.ngc"],
            dir.path(),
        );
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{strategy}: {e}");
        assert!(e.contains("km") && e.contains("drawing's units"), "{e}");
        assert!(!dir.path().join("p.ngc").exists());
    }
}

/// A region only a plunge reaches at the adaptive's full depth (`wro_Plate_2.DXF`: a cut
/// 0.26 mm long where the tool just fits between the holes) is bad input, exit 2 and no
/// file; the message says how shallow a level must be to ramp into it, and levels that
/// shallow give a program, which the engine has verified (it writes none otherwise).
#[test]
fn a_cut_only_a_plunge_reaches_names_the_step_down_that_ramps_into_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = common::real_input("wro_Plate_2.DXF");
    let o = millpath(
        &["pocket", &path, "--strategy", "adaptive", "-o", "p.ngc"],
        dir.path(),
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(!dir.path().join("p.ngc").exists());
    let at_most: f64 = e
        .split("is at most ")
        .nth(1)
        .and_then(|t| t.split(" mm").next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no descent named: {e}"));
    // The descent is the safe height (1 mm by default) plus the step-down.
    let step_down = format!("{:.3}", 0.9 * (at_most - 1.0));
    assert!(at_most > 2.0 && at_most < 25.0, "{e}");
    let o = millpath(
        &[
            "pocket",
            &path,
            "--strategy",
            "adaptive",
            "--step-down",
            &step_down,
            "-o",
            "p.ngc",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(dir.path().join("p.ngc").exists());
}
