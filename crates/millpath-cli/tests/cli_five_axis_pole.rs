//! `five-axis` on a path passing beside the pole: without a tilt tolerance it says where C
//! turns round and how to avoid it; with one it reports where the axes moved, and the plan
//! runs near its length ÷ feed.

mod common;
use common::{millpath, stderr};

/// The 200-pose tilting sweep turned 0.5° off the pole (`tests/five_axis_pole.rs`'s
/// `sweep_beside`), as a path file.
fn beside_csv() -> String {
    let (c, e) = (std::f64::consts::FRAC_1_SQRT_2, 0.5f64.to_radians());
    let mut out = String::from("# unit: mm\nx,y,z,i,j,k\n");
    for k in 0..200 {
        let u = f64::from(k) / 199.0;
        let t = (-30.0 + 60.0 * u).to_radians();
        let v = [
            t.sin() * c - e.sin() * c * t.cos(),
            t.sin() * c + e.sin() * c * t.cos(),
            t.cos() * e.cos(),
        ];
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        out += &format!(
            "{:.6},0,0,{:.6},{:.6},{:.6}\n",
            -50.0 + 100.0 * u,
            v[0] / n,
            v[1] / n,
            v[2] / n
        );
    }
    out
}

#[test]
fn beside_the_pole_the_tilt_tolerance_is_suggested_then_used() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("beside.csv"), beside_csv()).unwrap();
    let base = [
        "five-axis",
        "beside.csv",
        "--machine",
        "xyzac-trt",
        "--no-baseline",
    ];
    let o = millpath(&base, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        text.contains("hint:") && text.contains("--tilt-tolerance"),
        "{text}"
    );
    let o = millpath(
        &[&base[..], &["--tilt-tolerance", "1"]].concat(),
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        text.contains("near the pole: poses") && !text.contains("hint:"),
        "{text}"
    );
    let o = millpath(
        &[&base[..], &["--tilt-tolerance", "1", "--json"]].concat(),
        dir.path(),
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let windows = v["pole_windows"].as_array().expect("pole_windows");
    assert_eq!(windows.len(), 1);
    let moved = windows[0]["max_axis_change_rad"].as_f64().unwrap();
    assert!(moved > 0.0 && moved <= 1f64.to_radians() + 1e-12, "{moved}");
    let t = v["total_time_s"].as_f64().unwrap();
    assert!(t < 1.1 * 100.0 / 30.0, "{t}");
}

/// The joint program is not written where the planned tip strays from the path (C turning
/// 34° between poses swings the tip 0.42 mm off it); with the tilt tolerance it is.
#[test]
fn a_joint_program_off_the_path_is_not_written() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("beside.csv"), beside_csv()).unwrap();
    let base = [
        "five-axis",
        "beside.csv",
        "--machine",
        "xyzac-trt",
        "--no-baseline",
        "--gcode",
        "p.ngc",
    ];
    let o = millpath(&base, dir.path());
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("--gcode") && e.contains("--tilt-tolerance"),
        "{e}"
    );
    assert!(!dir.path().join("p.ngc").exists());
    let o = millpath(
        &[&base[..], &["--tilt-tolerance", "1"]].concat(),
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("p.ngc")).unwrap();
    assert!(
        text.contains("G93") && text.lines().count() > 50,
        "{}",
        text.len()
    );
}
