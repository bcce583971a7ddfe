//! `millpath verify PROGRAM --outline X` without `--tool-diameter`: our programs name their
//! tool in the header (`(tool T1: flat end mill D6 mm, 3 flutes)`, in capitals on Fanuc), and
//! verify judges the program with that tool. Shown three ways on one pocket: the program as
//! written passes; the same program whose header names a larger tool fails (its cuts come
//! closer to the walls than that tool's radius: the header's diameter is the one used); with
//! the header's tool line removed and no flag, the run is refused as bad input naming
//! `--tool-diameter` and saying the header names no tool.

mod common;
use common::{millpath, stderr};

/// A 40 × 30 mm rectangle.
const DRAWING: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="30mm" viewBox="0 0 40 30"><rect x="0" y="0" width="40" height="30"/></svg>"#;

/// Writes the drawing and a 6 mm offset pocket of it in `dialect` to `dir`; returns the
/// program's name.
fn program(dir: &std::path::Path, dialect: &str) -> String {
    std::fs::write(dir.join("box.svg"), DRAWING).unwrap();
    let name = format!("box-{dialect}.nc");
    let o = millpath(
        &[
            "pocket",
            "box.svg",
            "--strategy",
            "offset",
            "--tool-diameter",
            "6",
            "--depth",
            "2",
            "--step-down",
            "2",
            "--dialect",
            dialect,
            "-o",
            &name,
        ],
        dir,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    name
}

fn verify(dir: &std::path::Path, program: &str) -> std::process::Output {
    millpath(&["verify", program, "--outline", "box.svg", "--json"], dir)
}

#[test]
fn verify_takes_the_tool_from_the_programs_header() {
    let dir = tempfile::tempdir().unwrap();
    for dialect in ["linuxcnc", "fanuc"] {
        let name = program(dir.path(), dialect);
        let text = std::fs::read_to_string(dir.path().join(&name)).unwrap();
        let tool_line = text
            .lines()
            .position(|l| l.to_ascii_lowercase().contains("flat end mill d6 mm"))
            .unwrap_or_else(|| panic!("{dialect}: no tool in the header:\n{text}"));

        // As written: passes, judged with the 6 mm tool.
        let o = verify(dir.path(), &name);
        assert_eq!(o.status.code(), Some(0), "{dialect}: {}", stderr(&o));
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(json["passed"], true, "{dialect}: {json}");
        let need = json["pockets"][0]["required_clearance_mm"]
            .as_f64()
            .unwrap();
        assert!(
            (need - 3.0).abs() < 0.01,
            "{dialect}: clearance {need} for a 6 mm tool"
        );

        // The header names an 8 mm tool: the same cuts gouge a tool of radius 4.
        let bigger = text.replacen("D6 ", "D8 ", 1);
        assert_ne!(bigger, text);
        std::fs::write(dir.path().join("bigger.nc"), &bigger).unwrap();
        let o = verify(dir.path(), "bigger.nc");
        assert_eq!(o.status.code(), Some(2), "{dialect}: {}", stderr(&o));
        let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(json["passed"], false, "{dialect}: {json}");
        let clear = json["pockets"][0]["min_clearance_mm"].as_f64().unwrap();
        assert!(
            clear < 4.0 - 0.5,
            "{dialect}: clearance {clear} mm for an 8 mm tool"
        );

        // No tool in the header and no flag: refused, naming the flag; nothing judged.
        let bare: String = text
            .lines()
            .enumerate()
            .filter(|(i, _)| *i != tool_line)
            .map(|(_, l)| format!("{l}\n"))
            .collect();
        std::fs::write(dir.path().join("bare.nc"), bare).unwrap();
        let o = verify(dir.path(), "bare.nc");
        assert_eq!(o.status.code(), Some(2), "{dialect}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains("--tool-diameter") && e.contains("header names no tool"),
            "{dialect}: {e}"
        );
        assert!(o.stdout.is_empty(), "{dialect}: judged anyway");
        // With the flag it is judged again.
        let o = millpath(
            &[
                "verify",
                "bare.nc",
                "--outline",
                "box.svg",
                "--tool-diameter",
                "6",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(0), "{dialect}: {}", stderr(&o));
    }
}

/// `verify --machine`: the volume removed, the engagement outside the entries, what the
/// corners force, and the program planned on the machine (its cycle time as `estimate`
/// plans it, the time not cutting, the removal rate), on the rectangle's offset pocket
/// (6 mm tool, 2 mm deep: the rectangle less the four corners a round tool cannot reach,
/// `r²(1 − π/4)` each).
#[test]
fn verify_reports_the_removal_the_time_not_cutting_and_the_corners_floor() {
    let dir = tempfile::tempdir().unwrap();
    let name = program(dir.path(), "linuxcnc");
    let o = millpath(
        &[
            "verify",
            &name,
            "--outline",
            "box.svg",
            "--machine",
            "hsm",
            "--json",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let f = |v: &serde_json::Value| v.as_f64().unwrap_or_else(|| panic!("a number: {r}"));
    let removed = f(&r["verification"]["removed_mm3"]);
    let want = (40.0 * 30.0 - 4.0 * 9.0 * (1.0 - std::f64::consts::FRAC_PI_4)) * 2.0;
    assert!(
        (removed - want).abs() < 0.005 * want,
        "removed {removed:.1} mm³ against {want:.1}"
    );
    // A square corner: acos(√2 − 1) = 65.53°.
    assert!((f(&r["engagement_floor_deg"]) - 65.53).abs() < 0.01, "{r}");
    let e = &r["verification"]["engagement"];
    assert!(
        f(&e["cutting_mm"]) > 0.0 && f(&e["p95_deg"]) <= f(&e["max_deg"]),
        "{r}"
    );
    let t = &r["timing"];
    let (cycle, air, rapid) = (
        f(&t["cycle_time_s"]),
        f(&t["air_time_s"]),
        f(&t["rapid_time_s"]),
    );
    let est = millpath(
        &["estimate", &name, "--machine", "hsm", "--json"],
        dir.path(),
    );
    let est: serde_json::Value = serde_json::from_slice(&est.stdout).expect("estimate JSON");
    let planned = f(&est["cycle_time_s"]);
    assert!(
        (cycle - planned).abs() < 1e-6 * planned,
        "{cycle} against {planned}"
    );
    assert!(0.0 < rapid && rapid <= air && air < cycle, "{t}");
    assert!((f(&t["removal_rate_mm3_s"]) * cycle - removed).abs() < 1e-6 * removed);
    // The text says the same on its second line.
    let o = millpath(
        &["verify", &name, "--outline", "box.svg", "--machine", "hsm"],
        dir.path(),
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.lines()
            .any(|l| l.starts_with("removal ") && l.contains("the sharpest corner forces 65.5°")),
        "{text}"
    );
}
