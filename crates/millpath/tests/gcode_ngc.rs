//! The RS274/NGC language (parameters, expressions, O words, offsets), one construct a
//! program, each judged by LinuxCNC's `rs274 -g`: millpath's moves must equal rs274's
//! canonical motions (rs274_common::canon), and what rs274 refuses millpath refuses. Plus
//! what rs274 cannot judge: the step budget, messages, the search path.
//!
//! When `rs274` is missing these tests FAIL (install linuxcnc-uspace; CI does).

mod rs274_common;

use millpath::gcode::{ReadMove, Reader, ReaderOptions};
use rs274_common::canon::{canon_moves, compare};
use rs274_common::rs274_file;
use std::path::Path;
use std::time::Duration;

fn ours(path: &Path) -> Result<Vec<ReadMove>, String> {
    let opts = ReaderOptions::default()
        .with_origin(path.display().to_string())
        .with_subroutine_path(vec![path.parent().unwrap().to_path_buf()]);
    let f = std::fs::File::open(path).unwrap();
    Reader::new(std::io::BufReader::new(f), opts)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())
}

/// Writes `files` (name, text) into a fresh folder and judges `main.ngc`.
fn judge(files: &[(&str, &str)]) {
    let dir = tempfile::tempdir().unwrap();
    for (n, t) in files {
        std::fs::write(dir.path().join(n), t).unwrap();
    }
    let main = dir.path().join("main.ngc");
    let theirs = rs274_file(&main, None, None, Duration::from_secs(20));
    let mine = ours(&main);
    let text = files[0].1;
    match (&mine, theirs.ok) {
        (Ok(moves), true) => {
            let canon = canon_moves(&theirs.canon).unwrap();
            assert!(!canon.is_empty(), "no motion to compare in\n{text}");
            if let Some(d) = compare(moves, &canon, millpath::geom::Point3::ORIGIN) {
                panic!("{d}\n{text}\n{}", theirs.canon);
            }
        }
        (Err(_), false) => {}
        (m, _) => panic!(
            "millpath {}, rs274 {}:\n{text}\nours: {m:?}\nrs274: {}",
            if m.is_ok() { "reads" } else { "refuses" },
            if theirs.ok { "reads" } else { "refuses" },
            theirs.messages
        ),
    }
}

#[test]
fn parameters_and_expressions_as_rs274() {
    for p in [
        "G21 G90\n#1=2 #2=[#1*3]\nG1 X#2 Y[#1**3**2/8] F[100+#1]\nM2\n",
        // Settings take effect after the line: #2 gets the old #1 (0).
        "G21\n#1=5 #2=#1\nG1 X#2 F100\nG1 Y#1\nM2\n",
        "G21\n#<r>=10 #<_g>=3\nG1 X[#<r>*cos[60]] Y[#<r>*sin[60]] Z[-#<_g>] F100\nM2\n",
        "G21\nG1 X[7 mod 3] Y[-1 mod 3] Z[atan[1]/[1]] F100\nG1 X[sqrt[2]*abs[-2]] \
         Y[fix[-1.5]+fup[1.2]+round[2.5]] Z[exp[1]+ln[2]]\nM2\n",
        "G21\nG1 X[1 lt 2 and 3 gt 4] Y[1 eq 1.0000001] Z[2 ge 3 or 1 xor 0] F100\nM2\n",
        "G21\nG1 X[1+2*3-4/2] Y[[1+2]*3] Z[-2**2] F100\nM2\n",
        "G21\n#3=2\n##3=7\nG1 X#2 Y#[1+1] F100\nM2\n",
        "G21\nG1 X#<undefined> F100\nM2\n",
        "G21\nG1 X[1/0] F100\nM2\n",
        "G21\nG1 X[sqrt[-1]] F100\nM2\n",
        "G20\nG0 X1\nG1 X[#<_x>+1] Y#5420 F10\nG21\nG1 X[#<_x>+1] F[#<_feed>]\nM2\n",
        "G21\nG0 X1 Y2\nG91\nG1 X[#<_absolute>+#<_incremental>*2] F100\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
}

#[test]
fn control_flow_as_rs274() {
    for p in [
        // while, nested if/elseif/else
        "G21 F100\n#1=0\no1 while [#1 lt 5]\n o2 if [#1 eq 1]\n  G1 X1\n o2 elseif [#1 eq 2]\n  \
         G1 X2\n o2 else\n  G1 Y#1\n o2 endif\n #1=[#1+1]\no1 endwhile\nM2\n",
        // do/while, repeat, break, continue
        "G21 F100\n#1=0\no3 do\n #1=[#1+1]\n G1 X#1\no3 while [#1 lt 3]\no4 repeat [3]\n \
         G1 Y[#1]\n #1=[#1+1]\no4 endrepeat\nM2\n",
        "G21 F100\n#1=0\no5 while [1]\n #1=[#1+1]\n o6 if [#1 gt 4]\n  o5 break\n o6 endif\n \
         o7 if [#1 eq 2]\n  o5 continue\n o7 endif\n G1 X#1\no5 endwhile\nG1 Y9\nM2\n",
        // subroutines with arguments, locals, return values, nesting, recursion
        "G21 F100\no<sq> sub\n #<s>=#1\n G1 X#<s> Y0\n G1 Y#<s>\n G1 X0\n G1 Y0\no<sq> endsub\n\
         o<dbl> sub\n o<dbl> return [#1*2]\no<dbl> endsub\no<sq> call [5]\no<dbl> call [3]\n\
         o<sq> call [#<_value>]\nM2\n",
        "G21 F100\no<fact> sub\n o1 if [#1 le 1]\n  o<fact> return [1]\n o1 endif\n \
         o<fact> call [#1-1]\n o<fact> return [#1*#<_value>]\no<fact> endsub\n\
         o<fact> call [5]\nG1 X#<_value>\nM2\n",
        // a call before the definition: refused by both
        "G21 F100\no<later> call [2]\nG1 Y1\no<later> sub\n G1 X#1\no<later> endsub\nG1 Z-1\nM2\n",
        // numbered O words
        "G21 F100\no100 sub\n G1 X#1 Y#2\no100 endsub\no100 call [1] [2]\no0100 call [3] [4]\nM2\n",
        // a local is not visible in the called subroutine
        "G21 F100\no<in> sub\n G1 X#<a>\no<in> endsub\n#<a>=1\no<in> call\nM2\n",
        "G21 F100\no9 if [1]\nG1 X1\nM2\n",
        "G21 F100\no9 endwhile\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
}

#[test]
fn subroutine_files_as_rs274() {
    judge(&[
        (
            "main.ngc",
            "G21 F100\no<square> call [4] [1]\no<square> call [2] [3]\nM2\n",
        ),
        (
            "square.ngc",
            "(a square of side #1 at depth -#2)\no<square> sub\nG0 X0 Y0\nG1 Z-#2\n\
             G1 X#1\nG1 Y#1\nG1 X0\nG1 Y0\nG0 Z1\no<square> endsub\nM2\n",
        ),
    ]);
}

#[test]
fn offsets_as_rs274() {
    for p in [
        "G21 G90\nG10 L2 P2 X10 Y20 Z-5\nG0 X1 Y1 Z1\nG55 G0 X1 Y1 Z1\nG10 L2 P0 X5\nG0 X2\n\
         G54 G0 X0\nM2\n",
        "G21 G90\nG0 X10 Y10\nG10 L20 P1 X0 Y0\nG0 X1 Y1\nG92 X100\nG0 X101\nG92.2\nG0 X1\n\
         G92.3\nG0 X102\nG92.1\nG0 X3\nM2\n",
        "G20 G90\nG10 L2 P3 X1 Y2\nG56 G0 X0 Y0\nG21 G0 X0 Y25.4\nG59.3 G0 X1\nM2\n",
        // (#5221.. are read in machine units: rs274 alone has inches, millpath mm; so
        // only unit-free parameters are compared here.)
        "G21 G90\nG10 L2 P2 X1 Y2\nG55 G0 X1 Y1\nG1 X#5220 Y[#5420+#5421] F100\nG53 G0 X0 Y0\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
}

#[test]
fn machine_codes_as_rs274() {
    for p in [
        // G7 diameter mode halves X (absolute and incremental), G8 ends it.
        "G21 G90\nG7 G0 X20 Z1\nG1 X10 Z-1 F100\nG91 G1 X4\nG90 G8 G1 X20\nM2\n",
        // G80 with a motion code in one block: the motion code wins, in either order.
        "G21 G90 G80 G0 X1 Y1\nG0 G80 X2\nG1 G80 X3 F100\nM2\n",
        // Spindle, override and output switches do not move the tool.
        "G21 G90\nG96 D2500 S200 M3\nG1 X5 F100\nG97 S1000\nM48\nM49\nM50 P0\nM51 P1\n\
         M52 P1\nM53 P0\nM62 P1\nM63 P1\nM64 P0\nM65 P0\nG1 X6\nM2\n",
        "G21 G90\nM61 Q0\nG1 X1 F100\nM2\n",
        // G28/G30: a waypoint, then home (machine 0 without a .var file) on the axes named.
        "G21 G90\nG10 L2 P1 X5 Y6 Z7\nG0 X1 Y2 Z3\nG28\nG0 X1 Y2 Z3\nG28 Z10\nG91 G30 X1 Y1\n\
         G90 G0 X4\nG20 G28 Y1\nM2\n",
        // Polar words about the program origin: G90 @ ^, @ alone, ^ alone; G91 increments.
        "G21 G90\nG10 L2 P1 X5 Y-3\nG0 @10 ^30\nG1 @5 F100\nG1 ^-45\nG91 G1 @2 ^10\n\
         G1 ^90 Z-1\nG1 @-1\nG90 G2 @10 ^0 R10\nM2\n",
        // Polar with X or Y, and an angle-less polar move at the origin: refused by both.
        "G21 G90\nG1 X1 @2 F100\nM2\n",
        "G21 G90\nG0 X0 Y0\nG1 @2 F100\nM2\n",
        // M61 without Q: refused by both.
        "G21 G90\nG1 X1 F100\nM61\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
}

#[test]
fn saved_modal_states_as_rs274() {
    for p in [
        // M70 saves, M72 restores (and keeps), M71 forgets (and does not restore).
        "G21 G90 G17 F200 S1000 M3\nM70\nG20 G91 G18\nF5\nG1 X1\nM72\nG1 X5\nG91 F7\n\
         G1 X1\nM71\nG1 X6\nM2\n",
        // M73 in a subroutine: restored at endsub and at return; F comes back as F%.1f.
        "o<s> sub\nM73\nG20 G91\nF5.55\nG1 X1\no1 if [#1 gt 0]\no<s> return\no1 endif\n\
         G1 Y1\no<s> endsub\nG21 G90 F123.45\no<s> call [0]\nG1 X5\no<s> call [1]\n\
         G1 Y5\nM2\n",
        // Restoring without a saved state: refused by both.
        "G21 G90 F100\nM72\nG1 X1\nM2\n",
        "G21 G90 F100\nM70\nM71\nM72\nG1 X1\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
}

#[test]
fn canned_cycles_as_rs274() {
    for p in [
        // G81 from above R, modal repeats, G98 back to the initial level, G91 with L.
        "G21 G17 G90 F100\nG0 Z10\nG81 X1 Y1 Z-5 R1\nX5\nY5 Z-2\nG98 X8\nG91 G81 X3 Z-2 R1 L3\n\
         G90 G80\nG0 X0\nM2\n",
        // Peck cycles, dwell cycles, boring out at feed, in inches and with a work offset.
        "G20 G17 G90\nF10\nG10 L2 P1 X1 Y2 Z0.5\nG0 Z1\nG83 X0 Y0 Z-1 R0.2 Q0.3\n\
         G73 X1 Z-1.05 R0.1 Q0.25\nG82 X2 Z-0.5 R0.1 P0.5\nG89 X3 Z-0.5 R0.1 P1\nG85 X4 Z-0.3 R0.05\n\
         G98 G83 X5 Y5 Z-0.4 R0.3 Q0.1\nG80\nM2\n",
        // A start below R, the XZ and YZ planes, polar positions about the origin.
        "G21 G90 F50\nG0 Z-3\nG81 X2 Y2 Z-6 R2\nG18 G81 X3 Y-5 Z4 R1\nG19 G81 X-1 Y2 Z6 R3\n\
         G17 G0 X10 Y0 Z5\nG91 G81 ^60 Z-3 R-4 L6\nG90 G81 @5 ^45 Z-1 R1\nG80\nM2\n",
        // Refused by both: R below Z, no R, L0, Q0, inverse time.
        "G21 G90 F100\nG81 X1 Z1 R0\nM2\n",
        "G21 G90 F100\nG81 X1 Z-1\nM2\n",
        "G21 G90 F100\nG81 X1 Z-1 R1 L0\nM2\n",
        "G21 G90 F100\nG83 X1 Z-1 R1 Q0\nM2\n",
        "G21 G90 G93\nG81 X1 Z-1 R1 F1\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
}

#[test]
fn rotated_systems_as_rs274() {
    for p in [
        // Absolute and incremental moves, arcs with I J and R, G90.1 centres, polar words,
        // another system, and back to no rotation.
        "G21 G90\nG0 X0\nG10 L2 P1 X5 Y-3 R30\nG0 X1 Y1\nG1 X4 Y2 Z-1 F100\n\
         G91 G1 X1 Y-1\nG90 G2 X7 Y1 I1 J0\nG3 X2 Y2 R3\nG90.1 G2 X4 Y4 I3 J3\nG91.1\n\
         G1 @5 ^20\nG10 L2 P2 X1 R-45\nG55 G0 X2 Y0\nG54 G0 X0 Y0\nG10 L2 P1 R0\nG0 X1\nM2\n",
        "G20 G90\nG10 L2 P0 X-2 Y1 R60\nF10\nG0 X0 Y0 Z0\nG1 X1.5 Y1.5\nG1 X1.5 Y.5\nG3 X.5 Y1.5 J1\n\
         G1 X[#<_x>+1] Y#5421\nM2\n",
    ] {
        judge(&[("main.ngc", p)]);
    }
    // What the reader leaves to unrotated systems is refused by name.
    for (p, word) in [
        (
            "G21 G90\nG10 L2 P1 R30\nG92 X1\nM2\n",
            "G92 in a rotated system",
        ),
        (
            "G21 G90\nG92 X1\nG10 L2 P1 R30 G0 X0\nM2\n",
            "G92 offset in a rotated",
        ),
        (
            "G21 G90\nG10 L2 P1 R30\nG10 L20 P1 X1\nM2\n",
            "G10 L20 in a rotated system",
        ),
        (
            "G21 G90 F100\nG10 L2 P1 R30\nG81 X1 Z-1 R1\nM2\n",
            "canned cycle in a rotated",
        ),
        (
            "G21 G90 F100\nG10 L2 P1 R30\nG18 G2 X1 Z1 R1\nM2\n",
            "outside G17",
        ),
    ] {
        let r: Result<Vec<_>, _> = Reader::new(p.as_bytes(), ReaderOptions::default()).collect();
        let e = r.unwrap_err().to_string();
        assert!(e.contains(word) && e.contains(":3"), "{e}");
    }
}

#[test]
fn endless_loops_stop_at_the_step_budget() {
    let opts = ReaderOptions::default().with_step_budget(100_000);
    let t0 = std::time::Instant::now();
    let r: Result<Vec<_>, _> = Reader::new(
        "G21 F100\no1 while [1]\nG1 X1\nG1 X0\no1 endwhile\nM2\n".as_bytes(),
        opts,
    )
    .collect();
    let e = r.unwrap_err().to_string();
    assert!(
        e.contains("step budget") && (2..=5).any(|l| e.contains(&format!("G-code:{l}"))),
        "{e}"
    );
    assert!(t0.elapsed() < Duration::from_secs(5));
    // Endless recursion stops at the call depth.
    let r: Result<Vec<_>, _> = Reader::new(
        "G21\no<r> sub\no<r> call\no<r> endsub\no<r> call\nM2\n".as_bytes(),
        ReaderOptions::default(),
    )
    .collect();
    assert!(r.unwrap_err().to_string().contains("nested deeper"));
}

#[test]
fn messages_pass_through_with_values() {
    let text = "G21\n#1=2.5 #<d>=3\n(DEBUG, one=#1 d=#<d>)\n(MSG, hello)\n(PRINT,x)\nM2\n";
    let mut r = Reader::new(text.as_bytes(), ReaderOptions::default());
    for m in &mut r {
        m.unwrap();
    }
    let got: Vec<_> = r
        .messages()
        .iter()
        .map(|m| (m.line, m.message.clone()))
        .collect();
    assert_eq!(
        got,
        vec![
            (3, "DEBUG:  one=2.500000 d=3.000000".to_string()),
            (4, "MSG:  hello".to_string()),
            (5, "PRINT: x".to_string()),
        ]
    );
}

#[test]
fn a_missing_subroutine_names_itself_and_the_search() {
    let r: Result<Vec<_>, _> = Reader::new(
        "G21\no<nowhere> call\nM2\n".as_bytes(),
        ReaderOptions::default().with_origin("p.ngc"),
    )
    .collect();
    let e = r.unwrap_err().to_string();
    assert!(
        e.contains("p.ngc:2") && e.contains("o<nowhere>") && e.contains("nowhere.ngc"),
        "{e}"
    );
}
