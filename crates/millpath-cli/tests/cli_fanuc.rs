//! Fanuc subprograms and macro B on `estimate`: a program calling a subprogram file (found
//! with `--subroutine-path`) and a G65 macro times exactly as the same moves written out;
//! what cannot run is bad input (exit 2) naming the word and the line.

mod common;
use common::{json_cycle_time as time, millpath, stderr};

#[test]
fn subprograms_and_macros_time_as_the_program_written_out() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("lib")).unwrap();
    std::fs::write(
        d.join("lib/O1000.nc"),
        "%\nO1000 (SQUARE OF SIDE #100)\nG91 G1 X#100 F600.\nY#100\nX-#100\nY-#100\nG90\nM99\n%\n",
    )
    .unwrap();
    std::fs::write(
        d.join("called.nc"),
        "%\nO0001\nG21 G90 G17\nG0 X0 Y0 Z1.\nG1 Z-1. F300.\n#100=10.\nM98 P31000\n\
         G65 P9000 A20.\nG0 Z5.\nM30\nO9000\n#100=#1\nM98 P1000\nM99\n%\n",
    )
    .unwrap();
    let mut inline = String::from("%\nO0002\nG21 G90 G17\nG0 X0 Y0 Z1.\nG1 Z-1. F300.\n");
    for s in [10, 10, 10, 20] {
        inline += &format!("G1 X{s}. F600.\nY{s}.\nX0\nY0\n");
    }
    inline += "G0 Z5.\nM30\n%\n";
    std::fs::write(d.join("inline.nc"), inline).unwrap();

    let o = millpath(
        &["estimate", "called.nc", "--dialect", "fanuc", "--json"],
        d,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("O1000") && stderr(&o).contains(":7"),
        "{}",
        stderr(&o)
    );
    let called = time(&millpath(
        &[
            "estimate",
            "called.nc",
            "--dialect",
            "fanuc",
            "--subroutine-path",
            "lib",
            "--json",
        ],
        d,
    ));
    // The dialect is found from the `%` and the program number too.
    let auto = time(&millpath(
        &[
            "estimate",
            "called.nc",
            "--subroutine-path",
            "lib",
            "--json",
        ],
        d,
    ));
    let inline = time(&millpath(&["estimate", "inline.nc", "--json"], d));
    assert!(inline > 1.0, "{inline}");
    assert!((called - inline).abs() < 1e-9, "{called} != {inline}");
    assert!((auto - inline).abs() < 1e-9, "{auto} != {inline}");
}

#[test]
fn programs_that_cannot_run_exit_2_naming_the_cause() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, text, needles) in [
        (
            "missing.nc",
            "%\nO1\nG0 X1.\nM98 P4321\nM30\n%\n",
            &["O4321", "missing.nc:4"][..],
        ),
        (
            "deep.nc",
            "%\nO1\nM98 P1000\nM30\nO1000\nG91 G0 X1.\nM98 P1000\nM99\n%\n",
            &["M98 P1000", "10 levels", "deep.nc:7"],
        ),
        (
            "endless.nc",
            "%\nO1\nG0 X1.\nN10 #100=#100+1\nM99 P10\n%\n",
            &["step budget", "M99 at line 5"],
        ),
        (
            "unmatched.nc",
            "%\nO1\n#1=0\nWHILE [#1 LT 3] DO1\nG0 X#1\n#1=#1+1\nEND2\nM30\n%\n",
            &["END2", "line 7", "DO1"],
        ),
        (
            "modal.nc",
            "%\nO1\nG66 P9000 A1.\nG0 X1.\nM30\n%\n",
            &["G66", "modal.nc:3", "G65"],
        ),
    ] {
        std::fs::write(d.join(name), text).unwrap();
        let o = millpath(&["estimate", name, "--dialect", "fanuc", "--json"], d);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        for n in needles {
            assert!(
                stderr(&o).contains(n),
                "{name}: '{n}' not in {}",
                stderr(&o)
            );
        }
    }
}
