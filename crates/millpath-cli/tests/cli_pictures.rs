//! The CLI's pictures and machine-readable output: `--svg` previews of any G-code program
//! (per level too), `--json` on the commands that print results, and the one `--machine`
//! loader (a preset or a TOML profile) on every command with a cycle time.

use std::process::Output;

mod common;
use common::{millpath, stderr};

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| {
        panic!(
            "stdout is not one JSON value ({e}): {}",
            String::from_utf8_lossy(&o.stdout)
        )
    })
}

/// Two levels (z = -1, z = -2), each entered by a helix and left by a retract above z = 0.
const TWO_LEVELS: &str = "G21 G90 G17\nG0 X10 Y0 Z1\n\
G3 X10 Y0 Z-1 I-10 J0 F300\nG1 X30 F1200\nG0 Z1\n\
G0 X10 Y0\nG3 X10 Y0 Z-2 I-10 J0 F300\nG1 X30 F1200\nG0 Z1\nM2\n";

#[test]
fn estimate_draws_any_program_per_level_with_json() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("two.ngc"), TWO_LEVELS).unwrap();
    let o = millpath(
        &[
            "estimate",
            "two.ngc",
            "--svg",
            "two.svg",
            "--per-level",
            "--json",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    assert!(v["cycle_time_s"].as_f64().unwrap() > 0.0);
    let pics: Vec<&str> = v["pictures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_str().unwrap())
        .collect();
    assert_eq!(pics, ["two.svg", "two.level1.svg", "two.level2.svg"]);
    let all = std::fs::read_to_string(dir.path().join("two.svg")).unwrap();
    assert!(all.contains("achieved feed (mm/min)"), "legend");
    assert!(all.contains("stroke-dasharray"), "rapids dashed");
    assert!(all.contains("entry (2)"), "both helices marked");
    assert!(all.contains("side view (X–Z)"), "side strip");
    let second = std::fs::read_to_string(dir.path().join("two.level2.svg")).unwrap();
    assert!(second.contains("level 2 of 2: roughing at z = -2.000 mm"));
    assert!(second.contains("entry (1)"), "only its own helix");
    assert!(!second.contains(r#"data-level="0""#));
}

#[test]
fn machine_accepts_a_toml_profile_everywhere_and_rejects_unknown_names() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("two.ngc"), TWO_LEVELS).unwrap();
    std::fs::write(dir.path().join("pts.csv"), "0,0\n10,0\n10,10\n0,10\n").unwrap();
    // The `hsm` preset written out as a TOML profile.
    let mut toml = String::from(
        "name = \"my-hsm\"\nunits = \"mm\"\nmax_feed = 500.0\npath_tolerance = 0.01\nipo_cycle = 0.002\n\
         curvature_accel_share = 0.8\ncontroller = \"sinumerik\"\nexact_stop_time = 0.03\n",
    );
    for ax in ["x", "y", "z"] {
        toml.push_str(&format!(
            "[axes.{ax}]\nmax_velocity = 500.0\nmax_acceleration = 4500.0\nmax_jerk = 175000.0\nrapid = 500.0\n"
        ));
    }
    std::fs::write(dir.path().join("mill.toml"), toml).unwrap();
    let o = millpath(
        &["estimate", "two.ngc", "--machine", "mill.toml", "--json"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let t_file = json(&o)["cycle_time_s"].as_f64().unwrap();
    let o = millpath(
        &["estimate", "two.ngc", "--machine", "hsm", "--json"],
        dir.path(),
    );
    let t_preset = json(&o)["cycle_time_s"].as_f64().unwrap();
    assert!((t_file - t_preset).abs() < 1e-9, "{t_file} vs {t_preset}");
    for cmd in [
        vec!["estimate", "two.ngc"],
        vec!["contour", "pts.csv"],
        vec!["pocket", "sample:aerospace"],
    ] {
        let mut args = cmd.clone();
        args.extend(["--machine", "no-such-mill"]);
        let o = millpath(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("no-such-mill"),
            "{cmd:?}: {}",
            stderr(&o)
        );
    }
}

#[test]
fn contour_times_on_the_machine_and_prints_json() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("pts.csv"),
        "x,y,group\n60,345,1\n100,325,1\n140,295,1\n180,245,1\n340,205,2\n260,385,2\n140,375,2\n60,345,2\n",
    )
    .unwrap();
    let o = millpath(
        &[
            "contour",
            "pts.csv",
            "--tolerance",
            "0.01",
            "--machine",
            "router",
            "--json",
            "--svg",
            "c.svg",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["machine"], "router");
    let planned = v["cycle_time_s"].as_f64().unwrap();
    let naive = v["time_at_programmed_feed_s"].as_f64().unwrap();
    // The planner never beats the programmed feed (it only slows down).
    assert!(planned >= naive * 0.999, "{planned} < {naive}");
    assert!(v["max_deviation_mm"].as_f64().unwrap() <= 0.01);
    let svg = std::fs::read_to_string(dir.path().join("c.svg")).unwrap();
    assert!(svg.contains("side view"));
}

#[test]
fn verify_json_reports_the_failure_and_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    // Cuts one short line in the aerospace pocket: nearly everything is left uncut.
    std::fs::write(
        dir.path().join("short.ngc"),
        "G21 G90\nG0 X50 Y50 Z1\nG1 Z-6 F300\nG1 X60 F1000\nG0 Z1\nM2\n",
    )
    .unwrap();
    let o = millpath(
        &[
            "verify",
            "short.ngc",
            "--outline",
            "sample:aerospace",
            "--tool-diameter",
            "10",
            "--cell",
            "1",
            "--json",
            "--svg",
            "v.svg",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["passed"], false);
    assert!(v["verification"]["uncut_area_mm2"].as_f64().unwrap() > 100.0);
    assert!(!v["problems"].as_array().unwrap().is_empty());
    assert!(dir.path().join("v.svg").is_file());
}

#[test]
fn sweep_json_and_plot() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(
        &[
            "sweep",
            "sample:aerospace",
            "--depth",
            "6.35",
            "--ratios",
            "0.3,0.6",
            "--feeds",
            "300",
            "--json",
            "--plot",
            "fig10.svg",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["spiral_s"].as_array().unwrap().len(), 2);
    assert!(v["zigzag_s"][0].as_f64().unwrap() > 0.0);
    let svg = std::fs::read_to_string(dir.path().join("fig10.svg")).unwrap();
    assert!(svg.contains("300 in/min") && svg.contains("zigzag dashed"));
    let o = millpath(
        &[
            "sweep",
            "sample:aerospace",
            "--ratios",
            "0.3",
            "--feeds",
            "300",
            "--plot",
            "fig10.gif",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}
