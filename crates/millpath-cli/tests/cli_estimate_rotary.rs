//! `millpath estimate` on a machine profile with a rotary axis: the profile's `[axes.c]`
//! limits (deg/s, deg/s²) time a rotary-only move as the trapezoid worked out by hand, and a
//! bad rotary limit is bad input (exit 2) naming the key and the file, with nothing on stdout.

mod common;
use common::{millpath, stderr};

const PROFILE: &str = r#"
name = "five-axis"
controller = "linuxcnc"
max_feed = 500
ipo_cycle = 0.001
[axes.x]
max_velocity = 500
max_acceleration = 2000
max_jerk = "unlimited"
[axes.y]
max_velocity = 500
max_acceleration = 2000
max_jerk = "unlimited"
[axes.z]
max_velocity = 500
max_acceleration = 2000
max_jerk = "unlimited"
[axes.c]
max_velocity = 45
max_acceleration = 450
"#;

#[test]
fn rotary_limits_of_the_profile_time_the_move() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.toml"), PROFILE).unwrap();
    // F6000 deg/min = 100 deg/s, over the axis's 45 deg/s: 90° at 45 deg/s from rest to rest
    // with 450 deg/s² (an exact stop: the full acceleration) takes 90/45 + 45/450 = 2.1 s.
    std::fs::write(
        dir.path().join("c.ngc"),
        "G21 G90 G61.1\nG1 C90 F6000\nM2\n",
    )
    .unwrap();
    let o = millpath(
        &["estimate", "c.ngc", "--machine", "m.toml", "--json"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    let t = v["cycle_time_s"].as_f64().unwrap();
    assert!((t - 2.1).abs() < 2e-3, "{t}");
}

#[test]
fn a_bad_rotary_limit_is_bad_input_naming_key_and_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bad.toml"),
        PROFILE.replace("max_acceleration = 450", "max_acceleration = -450"),
    )
    .unwrap();
    std::fs::write(dir.path().join("c.ngc"), "G21 G90\nG1 C90 F6000\nM2\n").unwrap();
    let o = millpath(
        &["estimate", "c.ngc", "--machine", "bad.toml", "--json"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("axes.c.max_acceleration") && e.contains("bad.toml"),
        "{e}"
    );
    assert!(o.stdout.is_empty());
}
