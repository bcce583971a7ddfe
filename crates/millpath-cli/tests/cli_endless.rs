//! `millpath estimate` on programs that never end and on input nested 100,000 deep: exit 2
//! with one message naming the loop's line (or the bound) and the lines run, never a hang or
//! a crash. The tests run the unoptimised binary: loops that move the tool get a small
//! `--step-budget` (the default's time is measured on the release binary, see the commit
//! that set it); the default budget itself is run on loops that cost little per line.

use millpath::gcode::DEFAULT_STEP_BUDGET;
use std::path::Path;
use std::time::{Duration, Instant};

mod common;
use common::{millpath, stderr};

/// Generous: the bound for the release binary, here on the unoptimised one.
const LIMIT: Duration = Duration::from_secs(10);

/// Runs `estimate FILE ARGS` on `text`: exit 2 within [`LIMIT`], one `error:` line holding
/// every needle; returns that line.
fn refused(dir: &Path, name: &str, text: &str, args: &[&str], needles: &[&str]) -> String {
    std::fs::write(dir.join(name), text).unwrap();
    let mut a = vec!["estimate", name];
    a.extend(args);
    let t0 = Instant::now();
    let o = millpath(&a, dir);
    let took = t0.elapsed();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    assert!(took < LIMIT, "{name}: {took:?}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.starts_with("note: ")).collect();
    assert_eq!(lines.len(), 1, "{name}: {err}");
    let line = lines[0];
    assert!(line.starts_with("error: invalid "), "{name}: {line}");
    for n in needles {
        assert!(line.contains(n), "{name}: '{n}' not in {line}");
    }
    line.to_string()
}

#[test]
fn endless_programs_exit_2_naming_the_loop_and_the_lines_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let budget = ["--step-budget", "20000"];
    for (name, text, needles) in [
        (
            "while.ngc",
            "G21 F600\n#1 = 1\no100 while [#1 GT 0]\nG1 X1\nG1 X0\no100 endwhile\nM2\n",
            &["o100 endwhile at line 6", "20001 lines run", "while.ngc:"][..],
        ),
        (
            "do.ngc",
            "G21 F600\no100 do\nG1 X1\nG1 X0\no100 while [1]\nM2\n",
            &["o100 while at line 5", "20001 lines run"],
        ),
        (
            "repeat.ngc",
            "G21 F600\no100 repeat [1000000000]\nG1 X1\nG1 X0\no100 endrepeat\nM2\n",
            &["o100 endrepeat at line 5", "20001 lines run"],
        ),
        (
            "recursive.ngc",
            "G21\no<r> sub\nG0 X1\no<r> call\no<r> endsub\no<r> call\nM2\n",
            &["calls nested deeper than 100", "recursive.ngc:4"],
        ),
        (
            "m99.nc",
            "%\nO1\nG21 G90 F600.\nG1 X1.\nG1 X0\nM99\n%\n",
            &["M99 at line 6", "20001 blocks run"],
        ),
        (
            "goto.nc",
            "%\nO1\nG21 F600.\nN10 G1 X1.\nG1 X0\nGOTO10\nM30\n%\n",
            &["GOTO 10 at line 6", "20001 blocks run"],
        ),
        (
            "while.nc",
            "%\nO1\n#1=1\nWHILE [#1 GT 0] DO1\nG1 X1. F600.\nG1 X0\nEND1\nM30\n%\n",
            &["END1 at line 7", "20001 blocks run"],
        ),
    ] {
        let line = refused(d, name, text, &budget, needles);
        assert!(line.contains("step budget of 20000") || name == "recursive.ngc");
    }
    // The default budget, on loops that cost little per line.
    for (name, text, site) in [
        (
            "empty.ngc",
            "#1 = 1\no100 while [#1 GT 0]\no100 endwhile\nM2\n",
            "o100 endwhile at line 3",
        ),
        (
            "self.nc",
            "%\nO1\nN10 GOTO10\nM30\n%\n",
            "GOTO 10 at line 3",
        ),
    ] {
        let (run, limit) = (
            format!("({} ", DEFAULT_STEP_BUDGET + 1),
            format!("step budget of {DEFAULT_STEP_BUDGET} "),
        );
        refused(d, name, text, &[], &[site, &run, &limit, "--step-budget"]);
    }
    // A budget the program fits in: it reads to its end.
    std::fs::write(
        d.join("ends.ngc"),
        "G21 F600\n#1 = 0\no1 while [#1 LT 100]\nG1 X[#1]\n#1 = [#1 + 1]\no1 endwhile\nM2\n",
    )
    .unwrap();
    let o = millpath(&["estimate", "ends.ngc", "--step-budget", "400"], d);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = millpath(&["estimate", "ends.ngc", "--step-budget", "399"], d);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn input_nested_100000_deep_exits_2_with_a_message() {
    const DEEP: usize = 100_000;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut ifs = String::from("G21\n");
    for k in 1..=DEEP {
        ifs += &format!("o{k} if [1]\n");
    }
    ifs += "G0 X1\n";
    for k in (1..=DEEP).rev() {
        ifs += &format!("o{k} endif\n");
    }
    refused(
        d,
        "ifs.ngc",
        &ifs,
        &[],
        &["nested deeper than 1000", "ifs.ngc:1002"],
    );
    let mut calls = String::from("G21\n");
    for k in 0..DEEP {
        calls += &format!("o<s{k}> sub\no<s{}> call\no<s{k}> endsub\n", k + 1);
    }
    calls += "o<s0> call\nM2\n";
    refused(
        d,
        "calls.ngc",
        &calls,
        &[],
        &["calls nested deeper than 100"],
    );
    let mut subs = String::from("%\nO1\nM98 P2\nM30\n");
    for k in 2..DEEP + 2 {
        subs += &format!("O{k}\nM98 P{}\nM99\n", k + 1);
    }
    subs += "%\n";
    refused(d, "subs.nc", &subs, &[], &["nested deeper than 10 levels"]);
    let brackets = |n: usize| {
        format!(
            "G21\n#1 = {}1{}\nG0 X#1\nM2\n",
            "[".repeat(n),
            "]".repeat(n)
        )
    };
    refused(
        d,
        "deep.ngc",
        &brackets(DEEP),
        &[],
        &["longer than 65536 bytes", "deep.ngc:2"],
    );
    refused(
        d,
        "fits.ngc",
        &brackets(30_000),
        &[],
        &["nested deeper than 64", "fits.ngc:2"],
    );
    let comment = format!("G0 X1 {}c{}\nM2\n", "(".repeat(30_000), ")".repeat(30_000));
    refused(
        d,
        "comment.ngc",
        &comment,
        &[],
        &["nested '('", "comment.ngc:1"],
    );
}
