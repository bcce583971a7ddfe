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
