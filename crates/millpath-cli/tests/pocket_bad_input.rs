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

/// The largest tool diameter a refusal names ("the largest that fits ... is X mm").
fn largest_named(err: &str) -> f64 {
    let at = err
        .find("the largest that fits")
        .expect("the largest tool named");
    let tail = &err[at..];
    let is = tail.find(" is ").expect("a diameter") + 4;
    let end = tail[is..].find(" mm").expect("mm") + is;
    tail[is..end].parse().expect("a number")
}

/// A tool too large for every pocket is refused with the largest that fits, read from the
/// verifier's reach map: a 40 mm square takes 40 mm less twice the wall stock (none with 25
/// mm of it), a drawing's widest pocket names itself (the first of like ones), and a tool 3 %
/// under the figure is cut and verified.
#[test]
fn tool_too_large_names_the_largest_that_fits() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("square.json"), SQUARE).unwrap();
    std::fs::write(
        dir.path().join("two.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="60mm" viewBox="0 0 100 60">
<rect x="5" y="5" width="20" height="20"/><rect x="40" y="5" width="40" height="40"/></svg>"#,
    )
    .unwrap();
    let run = |args: &[&str]| {
        let o = millpath(args, dir.path());
        (o.status.code(), common::stderr(&o))
    };
    for (stock, want) in [("0", 40.0), ("2", 36.0)] {
        let (code, err) = run(&[
            "pocket",
            "square.json",
            "--tool-diameter",
            "50",
            "--wall-stock",
            stock,
            "--depth",
            "4",
            "-o",
            "x.ngc",
        ]);
        assert_eq!(code, Some(2), "{err}");
        let d = largest_named(&err);
        assert!(
            d <= want && d >= 0.99 * want,
            "stock {stock}: {d} against {want}: {err}"
        );
    }
    let (code, err) = run(&[
        "pocket",
        "square.json",
        "--tool-diameter",
        "10",
        "--wall-stock",
        "25",
        "--depth",
        "4",
        "-o",
        "x.ngc",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("no tool fits with a wall stock of 25 mm"),
        "{err}"
    );
    let (code, err) = run(&[
        "pocket",
        "two.svg",
        "--tool-diameter",
        "45",
        "--depth",
        "3",
        "-o",
        "x.ngc",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("one of these 2 pockets"), "{err}");
    let d = largest_named(&err);
    assert!((39.6..=40.0).contains(&d), "{d}: {err}");
    let list = millpath(&["pocket", "two.svg", "--list"], dir.path());
    let listed = String::from_utf8_lossy(&list.stdout).into_owned() + &common::stderr(&list);
    let widest = listed
        .lines()
        .find(|l| l.contains("area 1600"))
        .and_then(|l| l.strip_prefix("pocket "))
        .and_then(|l| l.split(':').next())
        .expect("the 40 mm square listed");
    assert!(
        err.contains(&format!("(pocket {widest})")),
        "{err}\n{listed}"
    );
    // Thirty like squares: the first of them is named, each read once past the first.
    let rects: String = (0..30)
        .map(|k| {
            format!(
                r#"<rect x="{}" y="{}" width="5" height="5"/>"#,
                (k % 6) * 8,
                (k / 6) * 8
            )
        })
        .collect();
    std::fs::write(
        dir.path().join("many.svg"),
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="60mm" viewBox="0 0 60 60">{rects}</svg>"#
        ),
    )
    .unwrap();
    let (code, many) = run(&["pocket", "many.svg", "--depth", "3", "-o", "x.ngc"]);
    assert_eq!(code, Some(2), "{many}");
    assert!(
        many.contains("one of these 30 pockets") && many.contains("(pocket 1)"),
        "{many}"
    );
    assert!((4.95..=5.0).contains(&largest_named(&many)), "{many}");
    let fits = format!("{:.2}", 0.97 * d);
    let (code, err) = run(&[
        "pocket",
        "two.svg",
        "--tool-diameter",
        &fits,
        "--depth",
        "3",
        "--strategy",
        "offset",
        "-o",
        "fits.ngc",
    ]);
    assert_eq!(code, Some(0), "{fits} mm: {err}");
    let (code, err) = run(&[
        "verify",
        "fits.ngc",
        "--outline",
        "two.svg",
        "--select",
        widest,
    ]);
    assert_eq!(code, Some(0), "{err}");
}

/// Without `--step-down` a level is half the tool's diameter, at most its flute length: a
/// 1 mm tool cuts 3 mm in six levels and the default tool with 2 mm flutes 4 mm in two (both
/// verified), where a fixed 6.35 mm refused them for a flag not given; a step-down beyond
/// the flute length names the flute length.
#[test]
fn default_step_down_follows_the_tool() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("square.json"), SQUARE).unwrap();
    for (args, levels) in [
        (&["--tool-diameter", "1", "--depth", "3"][..], 6),
        (&["--flute-length", "2", "--depth", "4"][..], 2),
    ] {
        let mut all = vec![
            "pocket",
            "square.json",
            "--strategy",
            "offset",
            "-o",
            "p.ngc",
        ];
        all.extend_from_slice(args);
        let o = millpath(&all, dir.path());
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", common::stderr(&o));
        let v = millpath(
            &["verify", "p.ngc", "--outline", "square.json", "--json"],
            dir.path(),
        );
        assert_eq!(v.status.code(), Some(0), "{args:?}: {}", common::stderr(&v));
        let j: serde_json::Value = serde_json::from_slice(&v.stdout).expect("JSON");
        assert_eq!(j["levels"].as_u64(), Some(levels), "{args:?}: {j}");
        assert_eq!(j["passed"].as_bool(), Some(true), "{args:?}: {j}");
    }
    refused(
        "square.json",
        SQUARE,
        &["--flute-length", "2"],
        "at most the flute length, 2 mm",
    );
}
