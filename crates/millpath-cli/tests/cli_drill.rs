//! `millpath drill` through the binary: a real plate's holes in every dialect, each program's
//! cycle time as `millpath estimate` reads it (dialect found from the program) equal to the
//! report's; `--list`; bad flags refused with exit 2 naming the flag, no file written.

use std::path::{Path, PathBuf};

mod common;
use common::{millpath, stderr};

fn real(name: &str) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(
        dir.is_dir(),
        "the real inputs are missing: {} (CI keeps ../shared beside the clone)",
        dir.display()
    );
    dir.join(name).display().to_string()
}

fn json(path: &PathBuf) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("report")).expect("JSON")
}

#[test]
fn every_dialect_drills_the_plate_and_estimate_agrees_with_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let plate = real("wro_Plate_3.DXF");
    for (dialect, file, cycle) in [
        ("linuxcnc", "p.ngc", "G83 "),
        ("fanuc", "p.nc", "G83 "),
        ("sinumerik", "p.mpf", "CYCLE83("),
        ("grbl", "p.gcode", "G1 "),
    ] {
        for extra in [&[][..], &["--units", "in"][..], &["--stay-at-retract"][..]] {
            let mut a = vec![
                "drill",
                &plate,
                "--tool-diameter",
                "3",
                "--depth",
                "5",
                "--through",
                "--peck",
                "2",
                "--dialect",
                dialect,
                "-o",
                file,
                "--report",
                "r.json",
            ];
            a.extend_from_slice(extra);
            let o = millpath(&a, dir.path());
            assert_eq!(o.status.code(), Some(0), "{dialect}: {}", stderr(&o));
            let out = String::from_utf8_lossy(&o.stdout);
            assert!(out.contains("8 drilled, 18 bored, 0 left out"), "{out}");
            let text = std::fs::read_to_string(dir.path().join(file)).unwrap();
            assert!(text.contains(cycle), "{dialect}: no {cycle}");
            let rep = json(&dir.path().join("r.json"));
            assert!(rep["max_center_error_mm"].as_f64().unwrap() <= 0.01);
            assert!(rep["max_diameter_error_mm"].as_f64().unwrap() <= 0.01);
            let est = millpath(
                &["estimate", file, "--json", "--machine", "hsm"],
                dir.path(),
            );
            let t_est = common::json_cycle_time(&est);
            let t_rep = rep["cycle_time_s"].as_f64().unwrap();
            assert!(
                (t_est - t_rep).abs() <= 1e-6 * t_rep,
                "{dialect} {extra:?}: estimate {t_est} s, report {t_rep} s"
            );
        }
    }
}

#[test]
fn list_shows_the_circles() {
    let dir = tempfile::tempdir().unwrap();
    let o = millpath(&["drill", &real("wro_Plate_2.DXF"), "--list"], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(out.lines().count(), 13, "{out}");
    assert!(out.lines().all(|l| l.starts_with("hole ")), "{out}");
}

#[test]
fn bad_flags_exit_2_naming_the_flag_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let plate = real("wro_Plate_2.DXF");
    let cases: &[(&[&str], &str)] = &[
        (&["--peck", "0"], "--peck"),
        (&["--peck", "2", "--chip-break", "1"], "--chip-break"),
        (&["--tool-diameter", "-1"], "--tool-diameter"),
        (
            &["--min-diameter", "5", "--max-diameter", "2"],
            "--min-diameter",
        ),
        (&["--feed", "fast"], "--feed"),
        (&["--bore-feed", "0"], "--bore-feed"),
        (&["--depth", "0"], "--depth"),
        (
            &["--retract", "9", "--clearance-height", "5"],
            "--clearance-height",
        ),
        (&["--pitch", "-1"], "--pitch"),
        (&["--machine", "no-such"], "--machine"),
        (&["--min-diameter", "40"], "--min-diameter"),
        (&["--tool-diameter", "20"], "--tool-diameter"),
    ];
    for (extra, flag) in cases {
        let mut a = vec!["drill", &plate, "-o", "bad.ngc"];
        a.extend_from_slice(extra);
        let o = millpath(&a, dir.path());
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {e}");
        assert!(e.contains(flag), "{extra:?}: {e}");
        assert!(!dir.path().join("bad.ngc").exists(), "{extra:?}");
    }
    let o = millpath(
        &["drill", &real("lc_t-part.dxf"), "-o", "bad.ngc"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("circle"));
}
