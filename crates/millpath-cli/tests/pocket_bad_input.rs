//! `millpath pocket` on bad input: a clear message naming the value, exit code 2, and no
//! output file (G-code or report) left behind.

mod common;
use common::millpath;

/// Runs `pocket` on `outline` (written to `file`) with `extra` options and checks the refusal:
/// exit code 2, `needle` in the message, no output written.
fn refused(file: &str, outline: &str, extra: &[&str], needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(file), outline).unwrap();
    let mut args = vec![
        "pocket",
        file,
        "--depth",
        "4",
        "--step-down",
        "4",
        "-o",
        "out.ngc",
        "--report",
        "out.json",
    ];
    args.extend_from_slice(extra);
    if !extra.contains(&"--strategy") {
        args.extend_from_slice(&["--strategy", "offset"]);
    }
    let o = millpath(&args, dir.path());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{file} {extra:?}: {err}");
    assert!(err.contains(needle), "{file} {extra:?}: {err}");
    assert!(
        !dir.path().join("out.ngc").exists(),
        "G-code written after an error"
    );
    assert!(
        !dir.path().join("out.json").exists(),
        "report written after an error"
    );
}

const SQUARE: &str = r#"{"outline": [[0,0],[40,0],[40,40],[0,40]]}"#;

#[test]
fn open_outline() {
    refused(
        "open.svg",
        r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 40 0 L 40 40"/></svg>"#,
        &[],
        "open",
    );
}

#[test]
fn self_intersecting_outline() {
    refused(
        "bow.json",
        r#"{"outline": [[0,0],[40,40],[40,0],[0,40]]}"#,
        &[],
        "self-intersecting",
    );
}

#[test]
fn tool_too_large() {
    refused(
        "square.json",
        SQUARE,
        &["--tool-diameter", "50"],
        "tool diameter",
    );
}

#[test]
fn stepover_out_of_range() {
    for s in ["0", "-0.2", "1.5", "20mm"] {
        refused(
            "square.json",
            SQUARE,
            &["--tool-diameter", "10", &format!("--stepover={s}")],
            "stepover",
        );
    }
}

#[test]
fn islands_touching_or_crossing() {
    // Touching the outline, crossing it, and two islands touching each other.
    for islands in [
        "[[[0,10],[10,10],[10,20],[0,20]]]",
        "[[[-5,10],[10,10],[10,20],[-5,20]]]",
        "[[[10,10],[20,10],[20,20],[10,20]], [[20,10],[30,10],[30,20],[20,20]]]",
    ] {
        refused(
            "isl.json",
            &format!(r#"{{"outline": [[0,0],[40,0],[40,40],[0,40]], "islands": {islands}}}"#),
            &["--tool-diameter", "6"],
            "island",
        );
    }
}

#[test]
fn the_fronts_spiral_with_islands_suggests_offset() {
    refused(
        "isl.json",
        r#"{"outline": [[0,0],[60,0],[60,40],[0,40]], "islands": [[[25,15],[35,15],[35,25],[25,25]]]}"#,
        &[
            "--tool-diameter",
            "6",
            "--strategy",
            "spiral",
            "--morph",
            "fronts",
        ],
        "offset",
    );
}

#[test]
fn undercut_draft_is_refused() {
    refused(
        "square.json",
        SQUARE,
        &["--tool-diameter", "6", "--draft=-5"],
        "draft",
    );
}

#[test]
fn bottom_outline_with_another_topology_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bottom.json"),
        r#"{"outline": [[5,5],[35,5],[20,35]]}"#,
    )
    .unwrap();
    std::fs::write(dir.path().join("square.json"), SQUARE).unwrap();
    let o = millpath(
        &[
            "pocket",
            "square.json",
            "--strategy",
            "offset",
            "--tool-diameter",
            "6",
            "--bottom-outline",
            "bottom.json",
            "-o",
            "out.ngc",
        ],
        dir.path(),
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("vertex count"), "{err}");
    assert!(!dir.path().join("out.ngc").exists());
}
