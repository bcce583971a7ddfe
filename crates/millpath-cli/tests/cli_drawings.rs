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
