//! A drawing of several pockets through the binary: `pocket` cuts all of them (or those
//! `--select` names) in one program, `verify` accepts every program `pocket` writes, and the
//! report's cycle time equals `millpath estimate`'s on the written program within 1 %.
//! The real drawings come from `../shared/real-inputs/files/` (sources in its SOURCES.md);
//! the assertions are on the verifier's findings and counts, not on coordinates.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::millpath;

fn ok(o: &Output) -> String {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn real(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(
        dir.is_dir(),
        "the real inputs are missing: {} (CI keeps ../shared beside the clone)",
        dir.display()
    );
    dir.join(name)
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("report")).expect("JSON")
}

/// Pockets `outline` with `extra` flags, checks the report against `estimate` and `verify`;
/// returns the report.
fn cut_and_check(dir: &Path, outline: &str, tag: &str, extra: &[&str]) -> serde_json::Value {
    let ngc = format!("{tag}.ngc");
    let rep = format!("{tag}.json");
    let mut a = vec![
        "pocket", outline, "-o", &ngc, "--report", &rep, "--cell", "0.1",
    ];
    a.extend(extra);
    ok(&millpath(&a, dir));
    let r = json(&dir.join(&rep));
    let est: serde_json::Value = serde_json::from_str(&ok(&millpath(
        &["estimate", &ngc, "--json", "--machine", "hsm"],
        dir,
    )))
    .expect("estimate JSON");
    let (t_rep, t_est) = (
        r["cycle_time_s"].as_f64().expect("report time"),
        est["cycle_time_s"].as_f64().expect("estimate time"),
    );
    assert!(
        (t_rep - t_est).abs() <= 0.01 * t_est,
        "{tag}: report {t_rep} s, estimate {t_est} s"
    );
    let tool = extra
        .windows(2)
        .find(|w| w[0] == "--tool-diameter")
        .map_or("12.7", |w| w[1]);
    let mut v = vec![
        "verify",
        &ngc,
        "--outline",
        outline,
        "--tool-diameter",
        tool,
        "--json",
        "--cell",
        "0.1",
    ];
    if let Some(w) = extra.windows(2).find(|w| w[0] == "--select") {
        v.extend(["--select", w[1]]);
    }
    let out = millpath(&v, dir);
    let vj: serde_json::Value = serde_json::from_slice(&out.stdout).expect("verify JSON");
    let passed = vj["passed"].as_bool().expect("passed");
    let problems = r["problems"].as_array().expect("problems").len();
    // verify agrees with pocket's own verdict, and pocket's verdict on these is a pass.
    assert_eq!(passed, problems == 0, "{tag}: {vj}");
    assert!(passed, "{tag}: {}", vj["problems"]);
    assert_eq!(out.status.code(), Some(0));
    r
}

/// A drawing of three pockets and an island, written as text here: a plate with a round
/// island, a slot of half circles and a square, as LWPOLYLINEs with bulges.
const DRAWING: &str = "  0\nSECTION\n  2\nENTITIES\n\
  0\nLWPOLYLINE\n  8\n0\n 90\n4\n 70\n1\n 10\n0\n 20\n0\n 10\n80\n 20\n0\n 10\n80\n 20\n50\n 10\n0\n 20\n50\n\
  0\nLWPOLYLINE\n  8\n0\n 90\n2\n 70\n1\n 10\n30\n 20\n25\n 42\n1\n 10\n50\n 20\n25\n 42\n1\n\
  0\nLWPOLYLINE\n  8\n0\n 90\n4\n 70\n1\n 10\n100\n 20\n10\n 10\n150\n 20\n10\n 42\n1\n 10\n150\n 20\n40\n 10\n100\n 20\n40\n 42\n1\n\
  0\nLWPOLYLINE\n  8\n0\n 90\n4\n 70\n1\n 10\n10\n 20\n70\n 10\n40\n 20\n70\n 10\n40\n 20\n100\n 10\n10\n 20\n100\n\
  0\nENDSEC\n  0\nEOF\n";

#[test]
fn a_drawing_of_three_pockets_in_one_program_for_every_strategy() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("part.dxf"), DRAWING).unwrap();
    let listed = ok(&millpath(&["pocket", "part.dxf", "--list"], dir.path()));
    assert_eq!(listed.lines().count(), 3, "{listed}");
    let flags = ["--tool-diameter", "6", "--depth", "4", "--step-down", "2"];
    for s in ["offset", "zigzag", "spiral", "auto"] {
        let mut f = flags.to_vec();
        f.extend(["--strategy", s]);
        let r = cut_and_check(dir.path(), "part.dxf", s, &f);
        let pockets = r["pockets"].as_array().expect("pockets");
        assert_eq!(pockets.len(), 3, "{s}");
        let sum: f64 = pockets
            .iter()
            .map(|p| p["cycle_time_s"].as_f64().expect("each timed"))
            .sum();
        // The whole program is each pocket's plus the rapids between them.
        let total = r["cycle_time_s"].as_f64().unwrap();
        assert!(
            total >= 0.97 * sum && total <= 1.2 * sum,
            "{s}: {total} against {sum}"
        );
        assert!(pockets.iter().all(|p| p["verified"] == true), "{s}");
    }
    // --select: two of them.
    let mut f = flags.to_vec();
    f.extend(["--strategy", "offset", "--select", "1,3"]);
    let r = cut_and_check(dir.path(), "part.dxf", "select", &f);
    let idx: Vec<u64> = r["pockets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["index"].as_u64().unwrap())
        .collect();
    let mut sorted = idx.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, [1, 3]);
    // The program of two pockets fails against all three: the third is uncut.
    let out = millpath(
        &[
            "verify",
            "select.ngc",
            "--outline",
            "part.dxf",
            "--tool-diameter",
            "6",
            "--cell",
            "0.1",
        ],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("pocket 2: uncut material"));
    let bad = millpath(&["pocket", "part.dxf", "--select", "4"], dir.path());
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--select"));
}

#[test]
fn real_drawings_of_several_parts_are_cut_whole() {
    let dir = tempfile::tempdir().unwrap();
    // A laser-cut latch (two parts, one inside the other's opening; auto picks per pocket)
    // and the six shapes of an SVG drawing (rect, circle, ellipse, polygon, paths).
    let latch = real("pb_latch_test.dxf");
    let r = cut_and_check(
        dir.path(),
        latch.to_str().unwrap(),
        "latch",
        &[
            "--tool-diameter",
            "6",
            "--depth",
            "3",
            "--step-down",
            "3",
            "--strategy",
            "auto",
        ],
    );
    assert!(r["pockets"].as_array().unwrap().len() >= 2);
    let parts = real("s2g_shapes.svg");
    let r = cut_and_check(
        dir.path(),
        parts.to_str().unwrap(),
        "parts",
        &[
            "--tool-diameter",
            "1",
            "--depth",
            "1",
            "--step-down",
            "1",
            "--strategy",
            "zigzag",
        ],
    );
    assert!(r["pockets"].as_array().unwrap().len() >= 6);
}

#[test]
fn verify_accepts_what_pocket_writes_on_single_pockets() {
    let dir = tempfile::tempdir().unwrap();
    for s in ["offset", "zigzag", "spiral"] {
        cut_and_check(
            dir.path(),
            "sample:aerospace",
            &format!("aero_{s}"),
            &["--depth", "5", "--step-down", "5", "--strategy", s],
        );
    }
    let plate = real("wro_Plate_2.DXF");
    for s in ["offset", "zigzag"] {
        cut_and_check(
            dir.path(),
            plate.to_str().unwrap(),
            &format!("plate_{s}"),
            &[
                "--tool-diameter",
                "3",
                "--depth",
                "2",
                "--step-down",
                "2",
                "--strategy",
                s,
            ],
        );
    }
}
