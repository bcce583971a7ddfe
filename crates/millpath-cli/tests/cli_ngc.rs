//! `--subroutine-path` and `--tool-table` on `estimate` and `verify`: an RS274/NGC program
//! calling a subroutine file times exactly as the same program with the subroutine written
//! out by hand; what cannot be found is bad input (exit 2) naming it.

mod common;
use common::{json_cycle_time as time, millpath, stderr};

#[test]
fn subroutine_files_time_as_the_program_written_out() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("lib")).unwrap();
    std::fs::write(
        d.join("lib/square.ngc"),
        "o<square> sub\nG1 X#1 Y0\nG1 Y#1\nG1 X0\nG1 Y0\no<square> endsub\n",
    )
    .unwrap();
    std::fs::write(
        d.join("called.ngc"),
        "G21 G90 G64 P0.01\nT1 M6 G43\nG0 Z1\nG1 Z-1 F300\n#1=0\no1 repeat [3]\n\
         #1=[#1+10]\no<square> call [#1]\no1 endrepeat\nG0 Z5\nM2\n",
    )
    .unwrap();
    let mut inline = String::from("G21 G90 G64 P0.01\nT1 M6 G43\nG0 Z1\nG1 Z-1 F300\n");
    for s in [10, 20, 30] {
        inline += &format!("G1 X{s} Y0\nG1 Y{s}\nG1 X0\nG1 Y0\n");
    }
    inline += "G0 Z5\nM2\n";
    std::fs::write(d.join("inline.ngc"), inline).unwrap();
    std::fs::write(d.join("tool.tbl"), "T1 P1 Z25 D6 ;6 mm end mill\n").unwrap();

    let o = millpath(&["estimate", "called.ngc", "--json"], d);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("o<square>") && stderr(&o).contains("square.ngc"),
        "{}",
        stderr(&o)
    );
    let called = time(&millpath(
        &[
            "estimate",
            "called.ngc",
            "--json",
            "--subroutine-path",
            "lib",
            "--tool-table",
            "tool.tbl",
        ],
        d,
    ));
    let written = time(&millpath(
        &[
            "estimate",
            "inline.ngc",
            "--json",
            "--tool-table",
            "tool.tbl",
        ],
        d,
    ));
    assert!(
        called > 0.0 && (called - written).abs() < 1e-9,
        "{called} vs {written}"
    );

    let o = millpath(
        &["estimate", "called.ngc", "--subroutine-path", "nowhere"],
        d,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("nowhere") && stderr(&o).contains("--subroutine-path"));
    std::fs::write(d.join("t9.ngc"), "G21\nT9 M6\nM2\n").unwrap();
    let o = millpath(&["estimate", "t9.ngc", "--tool-table", "tool.tbl"], d);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("T9") && stderr(&o).contains("t9.ngc:2"),
        "{}",
        stderr(&o)
    );
    let o = millpath(&["estimate", "t9.ngc", "--tool-table", "missing.tbl"], d);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("missing.tbl"), "{}", stderr(&o));
}
