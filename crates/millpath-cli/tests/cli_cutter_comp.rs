//! Cutter radius compensation through `millpath estimate`: a compensated program is timed on
//! the tool centre's path (its length worked out by hand here), and what LinuxCNC refuses is
//! bad input (exit 2) naming the file, the line and the reason.

use std::process::Output;

mod common;
use common::{millpath, stderr};

/// The time at the programmed feed (s) of a run.
fn time_at_feed(o: &Output) -> f64 {
    assert_eq!(o.status.code(), Some(0), "{}", stderr(o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    v["time_at_programmed_feed_s"]
        .as_f64()
        .unwrap_or_else(|| panic!("no time in {v}"))
}

/// A 40 × 30 rectangle from the middle of its left edge, clockwise, entered square to that
/// edge at 600 mm/min; `comp` is the compensation line.
fn rectangle(comp: &str) -> String {
    format!(
        "G21 G17 G90 F600\nT1 M6\nG0 X-10 Y15\n{comp}\nG1 X0 Y15\nG1 X0 Y30\nG1 X40 Y30\n\
         G1 X40 Y0\nG1 X0 Y0\nG1 X0 Y15\nG40\nG1 X-10 Y15\nM2\n"
    )
}

#[test]
fn a_compensated_outline_is_timed_on_the_tool_centre_path() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tool.tbl"), "T1 P1 D6 ;6 mm end mill\n").unwrap();
    std::fs::write(d.join("plain.ngc"), rectangle("")).unwrap();
    std::fs::write(d.join("outside.ngc"), rectangle("G41 D1")).unwrap();
    let args = |f: &'static str| ["estimate", f, "--json", "--tool-table", "tool.tbl"];
    let plain = time_at_feed(&millpath(&args("plain.ngc"), d));
    let outside = time_at_feed(&millpath(&args("outside.ngc"), d));
    // 10 mm in, the 140 mm outline, 10 mm out, at 10 mm/s.
    assert!((plain - 16.0).abs() < 1e-6, "{plain}");
    // The tool (r = 3) enters to (-3, 18), where the entry's offset meets the left edge's,
    // goes round the outline 3 mm out with a quarter circle at each of its four corners
    // (140 - 3 + 2π·3 mm, the last edge ending at (-3, 15)), and leaves 7 mm to (-10, 15).
    let r: f64 = 3.0;
    let path = 7f64.hypot(3.0) + (140.0 - 3.0 + std::f64::consts::TAU * r) + 7.0;
    assert!(
        (outside - path / 10.0).abs() < 1e-6,
        "{outside} vs {}",
        path / 10.0
    );
}

#[test]
fn what_compensation_refuses_is_bad_input_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tool.tbl"), "T1 P1 D6 ;6 mm end mill\n").unwrap();
    for (name, text, reason) in [
        (
            // An inside arc of radius 2 for a 3 mm tool radius, line 6.
            "small_arc.ngc",
            "G21 G17 F600\nT1 M6\nG0 X-10\nG41 D1\nG1 X0 Y0\nG3 X0 Y4 R2\nG40\nM2\n",
            "tool radius not less than arc radius",
        ),
        (
            // A 4 mm notch for a 6 mm tool: the bottom of it reverses, line 9.
            "notch.ngc",
            "G21 G17 F600\nT1 M6\nG0 X-10 Y-10\nG41 D1\nG1 X0 Y0\nG1 X20\nG1 Y-10\n\
             G1 X24\nG1 Y0\nG1 X40\nG40\nM2\n",
            "gouging",
        ),
    ] {
        std::fs::write(d.join(name), text).unwrap();
        let o = millpath(&["estimate", name, "--tool-table", "tool.tbl"], d);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        let line = if name == "notch.ngc" { 9 } else { 6 };
        let e = stderr(&o);
        assert!(
            e.contains(&format!("{name}:{line}")) && e.contains(reason),
            "{name}: {e}"
        );
    }
    // G41 needs the tool's diameter.
    std::fs::write(d.join("no_table.ngc"), rectangle("G41")).unwrap();
    let o = millpath(&["estimate", "no_table.ngc"], d);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("no_table.ngc:4") && stderr(&o).contains("tool table"),
        "{}",
        stderr(&o)
    );
}
