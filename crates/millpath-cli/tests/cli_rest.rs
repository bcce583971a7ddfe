//! Rest machining as a user runs it: a 12.7 mm spiral in `sample:aerospace`, then `pocket
//! sample:aerospace --rest-from big.ngc --tool-diameter 4`: the previous tool's diameter is
//! read from the program's header, the pair is judged on the stock simulation ("as drawn"),
//! the rest program alone is short and `verify` (exact clearance, its own reader) finds no
//! move closer to a wall than the small tool's radius. Without a diameter in the header and
//! none given, the run is refused as bad input naming `--rest-from-diameter`, and a rest tool
//! no smaller than the previous one naming `--tool-diameter`; nothing is written.
//!
//! In a job: the aerospace pocket in a plate, a 12.7 mm spiral then a pocket operation with
//! `rest_from` and a 4 mm tool; `verify --job` accepts the job's program (the job means the
//! pocket cleared within the 4 mm tool's reach), and the rest operation's path is a small
//! part of a whole 4 mm pocket's. A `rest_from` naming no earlier pocket operation is refused
//! naming the key and its line.

mod common;
use common::{millpath, real_input, stderr};

const POCKET: &[&str] = &["--depth", "5", "--step-down", "5"];

fn run(args: &[&str], dir: &std::path::Path) -> std::process::Output {
    let mut all = args.to_vec();
    all.extend_from_slice(POCKET);
    millpath(&all, dir)
}

#[test]
fn a_rest_pass_cuts_the_corners_a_large_spiral_left() {
    let dir = tempfile::tempdir().unwrap();
    let big = run(
        &[
            "pocket",
            "sample:aerospace",
            "--tool-diameter",
            "12.7",
            "-o",
            "big.ngc",
        ],
        dir.path(),
    );
    assert_eq!(big.status.code(), Some(0), "{}", stderr(&big));
    let rest = run(
        &[
            "pocket",
            "sample:aerospace",
            "--rest-from",
            "big.ngc",
            "--tool-diameter",
            "4",
            "-o",
            "rest.ngc",
        ],
        dir.path(),
    );
    assert_eq!(rest.status.code(), Some(0), "{}", stderr(&rest));
    let line = String::from_utf8_lossy(&rest.stdout).into_owned();
    assert!(
        line.contains("rest after D12.7 mm") && line.contains("after both programs: as drawn"),
        "{line}"
    );
    let v = millpath(
        &[
            "verify",
            "rest.ngc",
            "--outline",
            "sample:aerospace",
            "--tool-diameter",
            "4",
            "--json",
        ],
        dir.path(),
    );
    let json: serde_json::Value =
        serde_json::from_slice(&v.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&v)));
    let p = &json["pockets"][0];
    let (clear, need) = (
        p["min_clearance_mm"].as_f64().unwrap(),
        p["required_clearance_mm"].as_f64().unwrap(),
    );
    assert!(clear >= need - 1e-3, "{clear} < {need}");
    // Four corners: well under a tenth of the pocket's boundary (500 mm).
    let text = std::fs::read_to_string(dir.path().join("rest.ngc")).unwrap();
    let cuts = text
        .lines()
        .filter(|l| l.starts_with("G2") || l.starts_with("G3"))
        .count();
    assert!(cuts >= 4, "{text}");
    let big_text = std::fs::read_to_string(dir.path().join("big.ngc")).unwrap();
    assert!(
        text.len() * 20 < big_text.len(),
        "{} vs {}",
        text.len(),
        big_text.len()
    );
}

/// A 12.7 mm spiral in `outline`, then a 4 mm rest pass: the rest program's cutting at the
/// floor and what the material left needs of it (`stock::rest_need`, the verifier's lower
/// bound from its own raster, not the generator's), as the run's summary line reports them,
/// and that line.
fn rest_against_need(outline: &str) -> (f64, f64, String) {
    let dir = tempfile::tempdir().unwrap();
    let big = run(
        &[
            "pocket",
            outline,
            "--tool-diameter",
            "12.7",
            "-o",
            "big.ngc",
        ],
        dir.path(),
    );
    assert_eq!(big.status.code(), Some(0), "{}", stderr(&big));
    let rest = run(
        &[
            "pocket",
            outline,
            "--rest-from",
            "big.ngc",
            "--tool-diameter",
            "4",
            "-o",
            "rest.ngc",
        ],
        dir.path(),
    );
    assert_eq!(rest.status.code(), Some(0), "{}", stderr(&rest));
    let line = String::from_utf8_lossy(&rest.stdout).into_owned();
    assert!(line.contains("after both programs: as drawn"), "{line}");
    let number_after = |key: &str| -> f64 {
        line.split(key)
            .nth(1)
            .and_then(|t| t.split_whitespace().next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("no {key:?} in {line}"))
    };
    (
        number_after("cut at the floor "),
        number_after("against a need of "),
        line,
    )
}

/// Issue 41, Done-when 4 (in part): after a 12.7 mm spiral in the aerospace pocket (r 6
/// corners), the 4 mm rest pass cuts its four corners only: at least what they need (the
/// bound holds) and at most 2.3 times it (2.21 measured; runs cut short at 0.1 r past the
/// material gave 1.41 but let a rapid cross material in `rest_machining`; the issue asks
/// 1.2).
#[test]
fn the_aerospace_rest_pass_cuts_little_more_than_its_corners_need() {
    let (cut, need, line) = rest_against_need("sample:aerospace");
    // Four slivers along the r 6 fillets, each a good part of the fillet's arc at the small
    // tool's radius (π/2·(6 − 2) mm; the slivers thin out towards the straight walls).
    assert!(
        need >= 0.6 * 4.0 * std::f64::consts::FRAC_PI_2 * 4.0,
        "{line}"
    );
    assert!(cut >= 0.999 * need && cut <= 2.3 * need, "{line}");
}

/// The same on a real drawing: `ma_support.dxf`, a 450 × 35 mm rectangle with square
/// corners: at most 1.9 times the need (1.80 measured).
#[test]
fn a_real_rectangle_rest_pass_cuts_little_more_than_its_corners_need() {
    let (cut, need, line) = rest_against_need(&real_input("ma_support.dxf"));
    // Four square corners: both walls from the large radius towards the small one, up to
    // 2·(6.35 − 2) mm each, less where the material is thinner than a cell.
    assert!(need >= 0.6 * 4.0 * 2.0 * (6.35 - 2.0), "{line}");
    assert!(cut >= 0.999 * need && cut <= 1.9 * need, "{line}");
}

/// Measures the rest pass against its need on three more real drawings (pockets with narrow
/// parts and holes, where a 12.7 mm tool leaves whole regions): the figures of BENCHMARKS.md.
/// Where the rest pass slots (a part narrower than the old tool, cut at the full width of the
/// small one), it cuts wider than the stepover the need assumes, and may cut less than it.
#[test]
#[allow(clippy::print_stderr)] // the figures
#[ignore = "measurement, run by hand: cargo test --release -p millpath-cli --test cli_rest -- --ignored --nocapture"]
fn rest_passes_on_real_drawings_against_their_need() {
    for f in ["wro_Plate_2.DXF", "pb_key.dxf", "pb_left_drawer.dxf"] {
        let (cut, need, line) = rest_against_need(&real_input(f));
        assert!(cut > 0.0 && need > 0.0, "{f}: {line}");
        eprintln!("{f}: {line}");
    }
}

#[test]
fn a_previous_program_without_its_tool_is_refused_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let program = "G21 G90 G17\nG0 Z5\nG0 X0 Y0\nG1 Z-5 F300\nG1 X10 F600\nG0 Z5\nM2\n";
    std::fs::write(dir.path().join("other.ngc"), program).unwrap();
    let o = run(
        &[
            "pocket",
            "sample:aerospace",
            "--rest-from",
            "other.ngc",
            "--tool-diameter",
            "4",
            "-o",
            "rest.ngc",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--rest-from-diameter"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("rest.ngc").exists());
}

/// The aerospace sample's pocket (150 × 100 mm, 6 mm corner radii) in a plate.
const PLATE: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="190mm" height="140mm" viewBox="0 0 190 140">
  <rect x="0" y="0" width="190" height="140"/>
  <rect x="20" y="20" width="150" height="100" rx="6"/>
</svg>
"#;

/// A job on [`PLATE`]: tool 1 of 12.7 mm, tool 2 of 4 mm, and `operations`.
fn job(operations: &str) -> String {
    format!(
        r#"drawing = "plate.svg"
machine = "hsm"

[stock]
thickness = 10.0

[[tool]]
number = 1
diameter = 12.7
feed = 1500
spindle = 10000

[[tool]]
number = 2
diameter = 4.0
feed = 1000
spindle = 15000
{operations}"#
    )
}

const BIG: &str = r#"
[[operation]]
type = "pocket"
name = "rough"
tool = 1
strategy = "spiral"
depth = 5.0
step_down = 5.0
"#;

#[test]
fn a_job_cuts_what_its_earlier_pocket_left_with_a_rest_operation() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("plate.svg"), PLATE).unwrap();
    let rest = r#"
[[operation]]
type = "pocket"
name = "corners"
tool = 2
rest_from = "rough"
depth = 5.0
step_down = 5.0
"#;
    std::fs::write(dir.path().join("pair.toml"), job(&format!("{BIG}{rest}"))).unwrap();
    let o = millpath(
        &["job", "pair.toml", "-o", "pair.ngc", "--json"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ops = report["operations"].as_array().expect("operations");
    assert_eq!(ops.len(), 2, "{report}");
    let rest_path = ops[1]["path_mm"].as_f64().unwrap();
    let checks = ops[1]["checks"].to_string();
    assert!(
        ops[1]["cut"].as_str().unwrap().contains("rest after rough"),
        "{report}"
    );
    // The spiral left material within the 4 mm tool's reach (its four corners).
    let left: f64 = ops[1]["checks"][0][1]
        .as_str()
        .and_then(|s| s.split(" mm²").next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{checks}"));
    assert!(left > 1.0, "{checks}");

    // The job's own verifier on the written program: the part as the job means it, the
    // pocket cleared to within the 4 mm tool's reach.
    let v = millpath(
        &["verify", "pair.ngc", "--job", "pair.toml", "--json"],
        dir.path(),
    );
    assert_eq!(v.status.code(), Some(0), "{}", stderr(&v));
    let json: serde_json::Value = serde_json::from_slice(&v.stdout).unwrap();
    assert_eq!(json["passed"], true, "{json}");
    assert_eq!(json["sections"].as_array().map(Vec::len), Some(2), "{json}");

    // A whole pocket with the 4 mm tool cuts far more.
    let full = r#"
[[operation]]
type = "pocket"
tool = 2
depth = 5.0
step_down = 5.0
"#;
    std::fs::write(dir.path().join("full.toml"), job(full)).unwrap();
    let o = millpath(
        &["job", "full.toml", "-o", "full.ngc", "--json"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let full_path = report["operations"][0]["path_mm"].as_f64().unwrap();
    assert!(
        rest_path > 0.0 && rest_path * 20.0 < full_path,
        "rest {rest_path} mm, whole pocket {full_path} mm"
    );
}

#[test]
fn a_rest_operation_must_follow_a_larger_pocket_operation() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("plate.svg"), PLATE).unwrap();
    let rest = r#"
[[operation]]
type = "pocket"
tool = 2
rest_from = "roughing"
depth = 5.0
"#;
    std::fs::write(dir.path().join("bad.toml"), job(&format!("{BIG}{rest}"))).unwrap();
    let o = millpath(&["job", "bad.toml", "-o", "bad.ngc"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("rest_from") && e.contains("\"roughing\"") && e.contains("\"rough\""),
        "{e}"
    );
    assert!(e.contains("line 30"), "{e}");
    assert!(!dir.path().join("bad.ngc").exists());
}
