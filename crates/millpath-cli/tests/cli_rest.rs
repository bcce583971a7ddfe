//! Rest machining as a user runs it: a 12.7 mm spiral in `sample:aerospace`, then `pocket
//! sample:aerospace --rest-from big.ngc --tool-diameter 4`: the previous tool's diameter is
//! read from the program's header, the pair is judged on the stock simulation ("as drawn"),
//! the rest program alone is short and `verify` (exact clearance, its own reader) finds no
//! move closer to a wall than the small tool's radius. Without a diameter in the header and
//! none given, the run is refused as bad input naming `--rest-from-diameter`, and a rest tool
//! no smaller than the previous one naming `--tool-diameter`; nothing is written.

mod common;
use common::{millpath, stderr};

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
