//! Every program states its path tolerance: the pocket program carries the chosen machine's
//! (`G64 P t` on LinuxCNC; 0.01 mm for a machine of tolerance 0), the contour program the
//! machine's or the contour's where that is tighter; reading the program back gives the
//! tolerance the command timed it with, and LinuxCNC's interpreter `rs274` accepts it. A
//! machine that states none (tolerance 0) never makes a program stop at every corner.

#[path = "../../millpath/tests/rs274_common/mod.rs"]
mod rs274_common;

use millpath::gcode::{ReaderOptions, read_str};
use millpath::toolpath::Corner;
use std::process::Output;

mod common;
use common::millpath;

fn ok(o: &Output) -> serde_json::Value {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

/// The header (the lines before the first motion block).
fn header(text: &str) -> Vec<&str> {
    text.lines()
        .take_while(|l| !l.starts_with("G0 ") && !l.starts_with("G1 "))
        .collect()
}

/// Every feed and rapid move of `text` read back has the corner `want`.
fn corners_read_back(text: &str, want: Corner) {
    let (tp, _) = read_str(text, ReaderOptions::default()).unwrap();
    assert!(!tp.moves.is_empty());
    for (i, m) in tp.moves.iter().enumerate() {
        assert_eq!(m.corner, want, "move {i}");
    }
}

const ZERO_TOLERANCE_MACHINE: &str = "name = \"exact\"\nunits = \"mm\"\nmax_feed = 500.0\n\
    path_tolerance = 0\n[axes.x]\nmax_velocity = 500.0\nmax_acceleration = 2000.0\n\
    max_jerk = \"unlimited\"\n[axes.y]\nmax_velocity = 500.0\nmax_acceleration = 2000.0\n\
    max_jerk = \"unlimited\"\n[axes.z]\nmax_velocity = 500.0\nmax_acceleration = 2000.0\n\
    max_jerk = \"unlimited\"\n";

/// The pocket program's path tolerance: `--tolerance` where given (0: exact stop), else the
/// machine's where above 0, else 0.01 mm (a machine of tolerance 0 read by the LinuxCNC model
/// as `G64` without `P`, exact stop at every corner, ran `sample:aerospace` 4× longer).
#[test]
fn pocket_programs_state_the_machines_path_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("exact.toml"), ZERO_TOLERANCE_MACHINE).unwrap();
    for (machine, tolerance, line, corner) in [
        ("hsm", None, "G64 P0.01", Corner::Blend(0.01)),
        ("linuxcnc-sim", None, "G64 P0.0254", Corner::Blend(0.0254)),
        ("exact.toml", None, "G64 P0.01", Corner::Blend(0.01)),
        ("exact.toml", Some("0"), "G61.1", Corner::ExactStop),
        ("hsm", Some("0"), "G61.1", Corner::ExactStop),
        ("hsm", Some("0.05"), "G64 P0.05", Corner::Blend(0.05)),
        (
            "linuxcnc-sim",
            Some("0.002"),
            "G64 P0.002",
            Corner::Blend(0.002),
        ),
    ] {
        let mut args = vec![
            "pocket",
            "sample:aerospace",
            "--strategy",
            "offset",
            "--depth",
            "5",
            "--step-down",
            "5",
            "--machine",
            machine,
            "-o",
            "p.ngc",
            "--json",
        ];
        if let Some(t) = tolerance {
            args.extend(["--tolerance", t]);
        }
        let rep = ok(&millpath(&args, dir.path()));
        let text = std::fs::read_to_string(dir.path().join("p.ngc")).unwrap();
        assert!(
            header(&text).contains(&line),
            "{machine}: {line} in\n{text}"
        );
        corners_read_back(&text, corner);
        rs274_common::rs274(&text)
            .unwrap_or_else(|e| panic!("{machine} {tolerance:?}: rs274: {e}"));
        // The estimate of the program read back times it with that tolerance: the pocket's
        // own figure within the rounding of the written coordinates and feeds.
        let est = ok(&millpath(
            &["estimate", "p.ngc", "--machine", machine, "--json"],
            dir.path(),
        ));
        let (a, b) = (
            rep["cycle_time_s"].as_f64().unwrap(),
            est["cycle_time_s"].as_f64().unwrap(),
        );
        assert!(
            (a - b).abs() <= 0.01 * a,
            "{machine}: pocket {a} s, estimate {b} s"
        );
        // The time at the programmed feeds lies between the program read back with instant
        // rapids and with rapids at the slowest axis's speed, and below the planned time.
        let programmed = rep["time_at_programmed_feed_s"].as_f64().unwrap();
        if let Ok(m) = millpath::machine::Machine::preset(machine) {
            let (tp, _) = read_str(&text, ReaderOptions::default()).unwrap();
            let slowest = m.rapid.iter().copied().fold(f64::INFINITY, f64::min);
            let (lo, hi) = (
                tp.time_at_programmed_feed(f64::INFINITY),
                tp.time_at_programmed_feed(slowest),
            );
            assert!(
                programmed >= lo - 1e-6 * lo && programmed <= hi + 1e-6 * hi && programmed < a,
                "{machine}: {programmed} s at the programmed feeds, not in [{lo}, {hi}] or not \
                 below {a} s"
            );
        }
    }
}

/// A tolerance that is not a length ≥ 0 is refused before anything is read or written
/// (exit 2, naming `--tolerance` and what it accepts).
#[test]
fn a_negative_or_unreadable_tolerance_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for t in ["-0.01", "NaN", "inf"] {
        let flag = format!("--tolerance={t}");
        let o = millpath(
            &["pocket", "sample:aerospace", &flag, "-o", "p.ngc"],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{t}");
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains("--tolerance") && e.contains("≥ 0"), "{t}: {e}");
        assert!(!dir.path().join("p.ngc").exists());
    }
}

#[test]
fn contour_programs_state_the_tighter_of_the_machine_and_contour_tolerances() {
    let dir = tempfile::tempdir().unwrap();
    for (tolerance, line, t) in [("0.002", "G64 P0.002", 0.002), ("0.05", "G64 P0.01", 0.01)] {
        ok(&millpath(
            &[
                "contour",
                "--sample",
                "--tolerance",
                tolerance,
                "--depth",
                "5",
                "--step-down",
                "5",
                "--machine",
                "hsm",
                "-o",
                "c.ngc",
                "--json",
            ],
            dir.path(),
        ));
        let text = std::fs::read_to_string(dir.path().join("c.ngc")).unwrap();
        assert!(header(&text).contains(&line), "{line} in\n{text}");
        corners_read_back(&text, Corner::Blend(t));
        rs274_common::rs274(&text).unwrap_or_else(|e| panic!("rs274: {e}"));
    }
}

/// A machine that states no path tolerance (the `linuxcnc-time` preset, tolerance 0: the
/// controller's default) gets a stated one in every program, never exact stop: the profile
/// and the contour their `--tolerance`, the drill program the pocket's 0.01 mm. Each is read
/// back blending within it, and `rs274` accepts it.
#[test]
fn programs_for_a_machine_without_a_tolerance_state_their_own() {
    let dir = tempfile::tempdir().unwrap();
    let runs: [(&[&str], &str, f64); 3] = [
        (
            &[
                "profile",
                "sample:part",
                "--tool-diameter",
                "6",
                "--depth",
                "6",
                "--step-down",
                "6",
                "--tolerance",
                "0.02",
            ],
            "G64 P0.02",
            0.02,
        ),
        (
            &["contour", "--sample", "--depth", "5", "--step-down", "5"],
            "G64 P",
            f64::NAN,
        ),
        (
            &[
                "drill",
                "sample:part",
                "--tool-diameter",
                "6",
                "--depth",
                "6",
            ],
            "G64 P0.01",
            0.01,
        ),
    ];
    for (args, line, t) in runs {
        let mut a = args.to_vec();
        a.extend(["--machine", "linuxcnc-time", "-o", "p.ngc", "--json"]);
        ok(&millpath(&a, dir.path()));
        let text = std::fs::read_to_string(dir.path().join("p.ngc")).unwrap();
        let head = header(&text);
        assert!(
            head.iter().any(|l| l.starts_with(line)) && !head.contains(&"G61.1"),
            "{args:?}: {line} in\n{}",
            head.join("\n")
        );
        let (tp, _) = read_str(&text, ReaderOptions::default()).unwrap();
        assert!(!tp.moves.is_empty());
        // Every move blends within the tolerance stated, the canned cycles' aside (the
        // reader gives their moves LinuxCNC's exact path).
        let mut blended = 0;
        for (i, m) in tp.moves.iter().enumerate() {
            match m.corner {
                Corner::Blend(x) | Corner::BlendMerge { tolerance: x, .. } => {
                    assert!(
                        x > 0.0 && (t.is_nan() || (x - t).abs() < 1e-12),
                        "{args:?} move {i}: blend {x}"
                    );
                    blended += 1;
                }
                Corner::ExactPath if args[0] == "drill" => {}
                c => panic!("{args:?} move {i}: {c:?}"),
            }
        }
        assert!(2 * blended > tp.moves.len(), "{args:?}: {blended} blended");
        rs274_common::rs274(&text).unwrap_or_else(|e| panic!("{args:?}: rs274: {e}"));
    }
}
