//! `millpath pocket` on real drawings (`../shared/real-inputs/files/`): the note on stderr
//! says the units and extents read and what was skipped; `--layer`, `--join-tolerance` and
//! `--drawing-units` refuse bad values with exit code 2 and write nothing.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn real(name: &str) -> String {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(d.is_dir(), "{} is missing", d.display());
    d.join(name).to_string_lossy().into_owned()
}

fn pocket(file: &str, extra: &[&str], dir: &Path) -> Output {
    let mut args = vec![
        "pocket".to_owned(),
        real(file),
        "--strategy".into(),
        "offset".into(),
        "--tool-diameter".into(),
        "1".into(),
        "--depth".into(),
        "1".into(),
        "--step-down".into(),
        "1".into(),
        "-o".into(),
        "out.ngc".into(),
    ];
    args.extend(extra.iter().map(|s| (*s).to_owned()));
    Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(&args)
        .current_dir(dir)
        .output()
        .expect("the millpath binary runs")
}

/// SOLIDWORKS's brake arm ($INSUNITS = 4, two MTEXT): the note names the units, the extents
/// ($EXTMIN/$EXTMAX: (−5.9806, −3) to (3, 30.9104)) and the skipped text; the program's
/// moves stay within those extents.
#[test]
fn pocket_reports_what_the_drawing_held() {
    let dir = tempfile::tempdir().unwrap();
    let o = pocket("wro_Braking_Arm.DXF", &["--layer", "0"], dir.path());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    for w in [
        "note:",
        "mm ($INSUNITS = 4)",
        "extents (-5.9806, -3.0000) to (3.0000, 30.9104) mm",
        "skipped 2 MTEXT (text)",
        "layer \"0\"",
    ] {
        assert!(err.contains(w), "{w:?} not in {err}");
    }
    let g = std::fs::read_to_string(dir.path().join("out.ngc")).unwrap();
    for word in g.split_whitespace() {
        let v = |p: char| word.strip_prefix(p).and_then(|v| v.parse::<f64>().ok());
        if let Some(x) = v('X') {
            assert!((-5.9806..=3.0).contains(&x), "{word}");
        }
        if let Some(y) = v('Y') {
            assert!((-3.0..=30.9104).contains(&y), "{word}");
        }
    }
}

#[test]
fn bad_drawing_flags_are_refused() {
    for (file, extra, needle) in [
        ("wro_Braking_Arm.DXF", &["--layer", "nope"][..], "layers: 0"),
        ("ma_support.dxf", &["--layer", "0"][..], "layers: VISIBLE"),
        (
            "wro_Braking_Arm.DXF",
            &["--drawing-units", "parsec"][..],
            "--drawing-units",
        ),
        (
            "wro_Braking_Arm.DXF",
            &["--join-tolerance", "-1"][..],
            "join tolerance",
        ),
        ("lc_tux.dxf", &[][..], "--join-tolerance 0.1010"),
        ("s2g_use_symbol.svg", &[][..], "closed outlines = 0"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let o = pocket(file, extra, dir.path());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{file} {extra:?}: {err}");
        assert!(
            err.contains(needle),
            "{file} {extra:?}: {needle:?} not in {err}"
        );
        assert!(!dir.path().join("out.ngc").exists());
    }
}

/// Drawings nested 100,000 levels deep through the binary's main thread: SVG groups around one
/// square are cut (exit 0, a program `verify` accepts); DXF blocks inserting blocks are
/// refused by name (exit 2), nothing written.
#[test]
fn drawings_nested_100000_deep_are_read_or_refused_never_a_crash() {
    const DEPTH: usize = 100_000;
    let dir = tempfile::tempdir().unwrap();
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">{}<rect x="10" y="10" width="50" height="30"/>{}</svg>"#,
        "<g>".repeat(DEPTH),
        "</g>".repeat(DEPTH)
    );
    std::fs::write(dir.path().join("deep.svg"), svg).unwrap();
    let args = ["--tool-diameter", "6", "--depth", "2", "--step-down", "2"];
    let mut pocket = vec!["pocket", "deep.svg", "-o", "deep.ngc"];
    pocket.extend(args);
    let o = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(&pocket)
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let mut verify = vec!["verify", "deep.ngc", "--outline", "deep.svg"];
    verify.extend(&args[..2]);
    let v = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(&verify)
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_eq!(
        v.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&v.stderr)
    );

    let mut dxf = String::from("0\nSECTION\n2\nBLOCKS\n");
    for i in 0..DEPTH {
        dxf.push_str(&format!("0\nBLOCK\n2\nB{i}\n10\n0\n20\n0\n"));
        dxf.push_str(&format!("0\nINSERT\n2\nB{}\n10\n1\n20\n0\n", i + 1));
        dxf.push_str("0\nENDBLK\n");
    }
    dxf.push_str("0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nB0\n0\nENDSEC\n0\nEOF\n");
    std::fs::write(dir.path().join("deep.dxf"), dxf).unwrap();
    let mut pocket = vec!["pocket", "deep.dxf", "-o", "dxf.ngc"];
    pocket.extend(args);
    let o = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(&pocket)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("INSERT nesting"), "{err}");
    assert!(!dir.path().join("dxf.ngc").exists());
}
