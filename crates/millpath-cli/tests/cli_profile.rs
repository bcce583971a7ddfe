//! `millpath profile`: the cycle time `millpath estimate` reads back from every written
//! dialect equals the report's; bad flags exit 2 naming the flag, with no file written.

use std::path::PathBuf;

mod common;
use common::{json_cycle_time, millpath, stderr};

fn t_part() -> String {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(d.is_dir(), "{} is missing", d.display());
    d.join("lc_t-part.dxf").to_string_lossy().into_owned()
}

#[test]
fn estimate_reads_back_the_reports_cycle_time_in_every_dialect() {
    let dir = tempfile::tempdir().unwrap();
    let part = t_part();
    for dialect in ["linuxcnc", "fanuc", "sinumerik", "grbl"] {
        let file = format!("part.{dialect}.nc");
        let o = millpath(
            &[
                "profile",
                &part,
                "--tabs",
                "auto",
                "--dialect",
                dialect,
                "-o",
                &file,
                "--json",
            ],
            dir.path(),
        );
        let reported = json_cycle_time(&o);
        let e = millpath(
            &["estimate", &file, "--dialect", dialect, "--json"],
            dir.path(),
        );
        let read = json_cycle_time(&e);
        assert!(
            (read - reported).abs() <= 1e-9 * reported,
            "{dialect}: report {reported} s, estimate {read} s"
        );
    }
}

#[test]
fn bad_flags_exit_2_naming_the_flag_without_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let part = t_part();
    for (flag, value) in [
        ("--tabs", "many"),
        ("--side", "left"),
        ("--entry", "plunge"),
        ("--tab-shape", "round"),
        ("--tool-diameter", "-1"),
        ("--tolerance", "0"),
        ("--step-down", "0"),
        ("--tab-height", "9"),
        ("--ramp-angle", "90"),
    ] {
        // With tabs (a tab height is checked against the stock only then).
        let tabs: &[&str] = if flag == "--tabs" {
            &[]
        } else {
            &["--tabs", "2"]
        };
        let mut args = vec!["profile", part.as_str()];
        args.extend_from_slice(tabs);
        args.extend([flag, value, "-o", "x.ngc"]);
        let o = millpath(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {}", stderr(&o));
        assert!(stderr(&o).contains(flag), "{flag} {value}: {}", stderr(&o));
        assert!(
            !dir.path().join("x.ngc").exists(),
            "{flag}: a file was written"
        );
    }
    // Too few decimals for the tolerance, and a drawing with --sample.
    let o = millpath(
        &["profile", &part, "--tolerance", "0.001", "--decimals", "3"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--decimals"), "{}", stderr(&o));
    let o = millpath(&["profile", &part, "--sample"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}
