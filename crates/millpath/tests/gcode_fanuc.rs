//! Fanuc subprograms (M98/M99), macro calls (G65) and custom macro B, written from Fanuc's
//! documented semantics: each program's move end points are computed here independently
//! (own trigonometry, own loops) and compared with what the reader yields. Every program
//! read here in the Fanuc dialect is also read as `--dialect auto` reads it, to the same
//! moves.

mod detect_common;

use millpath::gcode::{Dialect, ReadMove, Reader, ReaderOptions};
use millpath::toolpath::MoveKind;
use std::path::Path;

fn opts() -> ReaderOptions {
    ReaderOptions::default().with_dialect(Dialect::Fanuc)
}

fn read_with(text: &str, o: ReaderOptions) -> Result<Vec<ReadMove>, String> {
    let auto = (o.dialect == Dialect::Fanuc).then(|| detect_common::auto_read(None, text, &o));
    let r = Reader::new(text.as_bytes(), o)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string());
    if let (Some((choice, auto)), Ok(moves)) = (&auto, &r) {
        assert_eq!(
            auto.as_ref().ok(),
            Some(moves),
            "read as {choice}, not as Fanuc reads it:\n{text}"
        );
    }
    r
}

fn read(text: &str) -> Result<Vec<ReadMove>, String> {
    read_with(text, opts())
}

fn read_file(main: &Path, search: &[&Path]) -> Result<Vec<ReadMove>, String> {
    let o = opts()
        .with_origin(main.display().to_string())
        .with_program_files(
            main,
            &search.iter().map(|p| p.to_path_buf()).collect::<Vec<_>>(),
            None,
        )
        .map_err(|e| e.to_string())?;
    let f = std::fs::File::open(main).unwrap();
    Reader::new(std::io::BufReader::new(f), o)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())
}

/// The end points of the motions (dwells left out).
fn ends(moves: &[ReadMove]) -> Vec<[f64; 3]> {
    moves
        .iter()
        .filter(|m| !matches!(m.mv.kind, MoveKind::Dwell { .. }))
        .map(|m| [m.mv.to.x, m.mv.to.y, m.mv.to.z])
        .collect()
}

fn assert_ends(got: &[ReadMove], want: &[[f64; 3]], text: &str) {
    let got = ends(got);
    assert_eq!(got.len(), want.len(), "{got:?}\n{want:?}\n{text}");
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        let d = (0..3).map(|i| (g[i] - w[i]).abs()).fold(0.0, f64::max);
        assert!(d < 1e-9, "move {k}: {g:?} != {w:?}\n{text}");
    }
}

const BOLT_HOLES: &str = "%
O0001 (BOLT HOLES)
G21 G90 G17
G0 Z5.
G65 P9010 X50. Y30. R25. A15. B6. C-3. F300.
G0 Z50.
M30
O9010 (X Y CENTRE, R RADIUS, A FIRST ANGLE, B HOLES, C DEPTH, F FEED)
#10=0
WHILE [#10 LT #2] DO1
#11=#1+#10*360/#2
#12=#24+#18*COS[#11]
#13=#25+#18*SIN[#11]
G0 X#12 Y#13
G1 Z#3 F#9
G0 Z5.
#10=#10+1
END1
M99
%
";

#[test]
fn bolt_hole_circle_by_a_g65_macro_with_a_while_loop() {
    let moves = read(BOLT_HOLES).unwrap();
    let mut want = vec![[0.0, 0.0, 5.0]];
    for k in 0..6 {
        let a = (15.0 + 60.0 * f64::from(k)) * std::f64::consts::PI / 180.0;
        let (x, y) = (50.0 + 25.0 * a.cos(), 30.0 + 25.0 * a.sin());
        want.extend([[x, y, 5.0], [x, y, -3.0], [x, y, 5.0]]);
    }
    want.push([want[want.len() - 1][0], want[want.len() - 1][1], 50.0]);
    assert_ends(&moves, &want, BOLT_HOLES);
    // F#9: 300 mm/min.
    let plunge = moves.iter().find(|m| m.mv.is_feed()).unwrap();
    assert!((plunge.mv.feed - 5.0).abs() < 1e-12, "{}", plunge.mv.feed);
}

#[test]
fn m98_repeats_an_incremental_subprogram_in_both_forms() {
    let mut want = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    for k in 1..=3 {
        let k = f64::from(k);
        want.push([10.0 * k, 5.0 * (k - 1.0), -1.0]);
        want.push([10.0 * k, 5.0 * k, -1.0]);
    }
    want.push([30.0, 15.0, 10.0]);
    // The packed form carries the count above the program number's four digits; the
    // subprogram's number may be written `:1000` as well.
    for (call, sub) in [("M98 P1000 L3", "O1000"), ("M98 P31000", ":1000")] {
        let text = format!(
            "%\nO0002\nG21 G90 G0 X0 Y0 Z1.\nG1 Z-1. F600.\n{call}\nG90 G0 Z10.\nM30\n\
             {sub} (STEP)\nG91 G1 X10. F600.\nY5.\nM99\n%\n"
        );
        assert_ends(&read(&text).unwrap(), &want, &text);
    }
    // L0: not called at all.
    let text = "O1\nG90 G0 X1.\nM98 P1000 L0\nG0 Y1.\nM30\nO1000\nG0 X50.\nM99\n";
    assert_ends(
        &read(text).unwrap(),
        &[[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
        text,
    );
}

#[test]
fn m99_p_returns_to_a_sequence_number_of_the_caller() {
    let text = "O0003\nG90 G0 X0 Y0 Z0\nM98 P2000\nN10 G0 X100.\nN20 G0 Y50.\nM30\n\
                O2000\nG0 X5.\nM99 P20\n";
    assert_ends(
        &read(text).unwrap(),
        &[[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [5.0, 50.0, 0.0]],
        text,
    );
    // A motion in the M99 block runs before the return; a missing N is an error.
    let text = "O3\nG90 G0 X0\nM98 P2000\nM30\nO2000\nG0 X5. M99 P77\n";
    let e = read(text).unwrap_err();
    assert!(e.contains("N77") && e.contains(":6"), "{e}");
}

#[test]
fn nested_subprograms_macro_levels_and_subprogram_files() {
    let dir = tempfile::tempdir().unwrap();
    let lib = dir.path().join("lib");
    std::fs::create_dir(&lib).unwrap();
    // O3000 in its own file on the search path (one program, with its number), calling
    // O3001 back in the main file, which calls 3002.nc (a file without a number).
    std::fs::write(
        lib.join("O3000.nc"),
        "%\nO3000\nG0 X#1\nM98 P3001\nG0 Z#1\nM99\n%\n",
    )
    .unwrap();
    std::fs::write(lib.join("3002.nc"), "G0 Y[#1*10]\nM99\n").unwrap();
    let main = dir.path().join("main.nc");
    let text = "%\nO0004\nG90 G0 X0 Y0 Z0\n#1=7.\nG65 P4000 A2.\nG0 X#1\nM98 P3000\nM30\n\
                O4000\n(#1 IS 2 HERE; M98 SHARES THE MACRO'S LOCALS)\nM98 P4001\nM99\n\
                O4001\nG0 X#1 Y#1\nM99\nO3001\nG0 Y#1\nM98 P3002\nM99\n%\n";
    std::fs::write(&main, text).unwrap();
    let moves = read_file(&main, &[&lib]).unwrap();
    assert_ends(
        &moves,
        &[
            [0.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],  // O4001 at macro level 1: #1 = A = 2
            [7.0, 2.0, 0.0],  // back in the main program: its own #1
            [7.0, 2.0, 0.0],  // O3000: X#1
            [7.0, 7.0, 0.0],  // O3001: Y#1
            [7.0, 70.0, 0.0], // 3002.nc: Y[#1*10]
            [7.0, 70.0, 7.0], // O3000: Z#1
        ],
        text,
    );
    assert!(
        moves[5].line == 1,
        "3002.nc's move is its line 1: {:?}",
        moves[5]
    );
    // Without the search path O3000 is missing: named, with the files looked for.
    let e = read(text).unwrap_err();
    assert!(e.contains("O3000") && e.contains("O3000.nc"), "{e}");
}

#[test]
fn if_goto_loops_and_if_then() {
    let text = "O0005\nG90 G0 X0 Y0 Z0\n#100=0\nN10 #100=#100+1\nG1 X[#100*2] Y[#100*#100] F100.\n\
                IF [#100 LT 5] GOTO 10\nIF [#100 EQ 5] THEN #101=99.\nIF [#100 NE 5] THEN #101=1.\n\
                G0 Y#101\nGOTO 40\nG0 X1000.\nN40 M30\n";
    let mut want = vec![[0.0, 0.0, 0.0]];
    let mut k = 0.0;
    loop {
        k += 1.0;
        want.push([2.0 * k, k * k, 0.0]);
        if k >= 5.0 {
            break;
        }
    }
    want.push([10.0, 99.0, 0.0]);
    assert_ends(&read(text).unwrap(), &want, text);
}

#[test]
fn vacant_variables_as_fanuc_documents_them() {
    let text = "O0006\nG90 G0 X1. Y2. Z3.\nG0 X#1 Y5.\n#2=#1\n#3=#1+#1\nIF [#2 EQ #0] GOTO 20\n\
                G0 X99.\nN20 IF [#3 EQ #0] GOTO 30\nG0 X[#3+7.]\nN30 #4=#0\nG0 Z#4 X[#4-1.]\n\
                IF [#4 GE #0] THEN #5=1.\nIF [#4 GT 0] THEN #5=2.\nG0 Y#5\nM30\n";
    assert_ends(
        &read(text).unwrap(),
        &[
            [1.0, 2.0, 3.0],
            [1.0, 5.0, 3.0],  // X#1 left out: #1 is vacant
            [7.0, 5.0, 3.0],  // #3 = vacant + vacant = 0, not vacant: no jump
            [-1.0, 5.0, 3.0], // Z#4 left out, X[#4-1] = -1
            [-1.0, 1.0, 3.0], // vacant GE vacant, not vacant GT 0
        ],
        text,
    );
}

#[test]
fn nested_while_loops_functions_and_argument_specification_two() {
    // A 3 x 2 grid by two nested loops; then spec II arguments and Fanuc's functions.
    let text = "O7\nG90 G0 X0 Y0 Z0\n#1=0\nWHILE [#1 LT 3] DO1\n#2=0\nWHILE [#2 LT 2] DO2\n\
                G0 X[#1*10] Y[#2*5]\n#2=#2+1\nEND2\n#1=#1+1\nEND1\n\
                G65 P5000 I1. J2. K3. I4. J5. K6.\nM30\nO5000\nG0 X#7 Y#8 Z#9\n\
                G0 X[FIX[-1.7]] Y[FUP[1.2]] Z[ROUND[2.5]]\nG0 X[ATAN[1]/[-1]] Y[ATAN[-1,0]]\n\
                G0 X[SQRT[2]*SQRT[2]] Y[ABS[-4]+[7 MOD 4]] Z[LN[EXP[1.5]]]\nM99\n";
    let mut want = vec![[0.0, 0.0, 0.0]];
    for i in 0..3 {
        for j in 0..2 {
            want.push([f64::from(i) * 10.0, f64::from(j) * 5.0, 0.0]);
        }
    }
    want.push([4.0, 5.0, 6.0]);
    want.push([-1.0, 2.0, 3.0]);
    want.push([135.0, 270.0, 3.0]);
    want.push([2.0, 7.0, 1.5]);
    let got = read(text).unwrap();
    let g = ends(&got);
    assert_eq!(g.len(), want.len(), "{g:?}");
    for (a, b) in g.iter().zip(&want) {
        for i in 0..3 {
            assert!((a[i] - b[i]).abs() < 1e-9, "{a:?} != {b:?}");
        }
    }
}

#[test]
fn m99_in_the_main_program_loops_within_the_step_budget() {
    let text = "O8\nG90 G0 X0 Y0\nG1 X10. F600.\nG1 X0\n/M99\nM30\n";
    // With block delete on, /M99 is skipped and the program ends at M30.
    let on = opts().with_block_delete(true);
    assert_ends(
        &read_with(text, on).unwrap(),
        &[[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        text,
    );
    // Off: M99 goes back to the start for ever; the step budget stops it with a message.
    let off = opts().with_step_budget(1000);
    let mut n = 0;
    let mut err = None;
    for m in Reader::new(text.as_bytes(), off) {
        match m {
            Ok(_) => n += 1,
            Err(e) => err = Some(e.to_string()),
        }
    }
    let e = err.expect("refused");
    assert!(
        e.contains("step budget") && e.contains("M99 at line 5"),
        "{e}"
    );
    // Each pass runs 5 lines again (O8 to /M99: 1000 / 5 = 200 passes) and makes 3 moves,
    // after the first pass's 3.
    assert_eq!(n, 3 + 200 * 3, "moves before the budget ran out");
    // M99 P in the main program jumps to its N.
    let text = "O9\nG90 G0 X0\nN5 G0 X1.\n#100=#100+1\nIF [#100 GE 3] GOTO 99\nM99 P5\nN99 M30\n";
    assert_ends(
        &read(text).unwrap(),
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
        ],
        text,
    );
}

#[test]
fn refusals_name_the_word_and_the_line() {
    for (text, needles) in [
        ("O1\nM98 P1234\nM30\n", &["O1234", ":2", "1234.nc"][..]),
        (
            "O1\nM98 P1000\nM30\nO1000\nM98 P1000\nM99\n",
            &["M98 P1000", "10 levels"],
        ),
        (
            "O1\nG65 P1000\nM30\nO1000\nG65 P1000\nM99\n",
            &["G65 P1000", "5 levels"],
        ),
        (
            "O1\nWHILE [1 LT 2] DO1\nG0 X1.\nM30\n",
            &["DO1", "line 2", "without its END1"],
        ),
        (
            "O1\nG0 X1.\nEND1\nM30\n",
            &["END1", "line 3", "without its DO1"],
        ),
        (
            "O1\nWHILE [1 LT 2] DO1\nWHILE [1 LT 2] DO2\nEND1\nEND2\nM30\n",
            &["END1", "nest"],
        ),
        ("O1\nG66 P1000 A1.\nM30\n", &["G66", ":2", "G65"]),
        ("O1\nGOTO 50\nM30\n", &["GOTO 50", "N50"]),
        ("O1\n#1=#1000\nM30\n", &["#1000", "#100-#199"]),
        ("O1\n#1=BIN[3]\nM30\n", &["BIN", "SIN"]),
        ("O1\n#1=1/0\nM30\n", &["division by zero", ":2"]),
        ("O1\n#3000=1 (TOOL BROKEN)\nM30\n", &["3000", "TOOL BROKEN"]),
        (
            "O1\nM98 P1000\nM30\nO1000\nG0 X1.\n",
            &["O1000", "without M99"],
        ),
        (
            "O1\nDO1\nG0 X1.\nEND1\nM30\n",
            &["step budget", "END1 at line 4"],
        ),
    ] {
        let o = opts().with_step_budget(10_000);
        let e = read_with(text, o).expect_err(text);
        for n in needles {
            assert!(e.contains(n), "'{n}' not in: {e}\n{text}");
        }
    }
}

#[test]
fn plain_fanuc_programs_read_as_before() {
    // No macro words: the same moves as the LinuxCNC reading of the same words.
    let text = "G21 G90 G17\nG0 X1. Y2.\nG1 Z-1. F100.\nG2 X3. Y2. R1.\nM30\n";
    let fanuc = read(text).unwrap();
    let linuxcnc = read_with(text, ReaderOptions::default()).unwrap();
    assert_eq!(ends(&fanuc), ends(&linuxcnc));
}

#[test]
fn hostile_blocks_are_refused_without_panic() {
    let deep = format!("O1\n#1={}1{}\nM30\n", "[".repeat(200), "]".repeat(200));
    let sets: String = (0..11).map(|k| format!(" I{k}. J{k}. K{k}.")).collect();
    let spec2 = format!("O1\nG65 P2{sets}\nM30\nO2\nM99\n");
    for text in [
        deep.as_str(),
        spec2.as_str(),
        "O1\nM98 P-1\nM30\n",
        "O1\nM98 P1.5\nM30\n",
        "O1\nM98\nM30\n",
        "O1\nG65 P2 G1 X1.\nM30\nO2\nM99\n",
        "O1\nM98 P2 M99\nM30\n",
        "O1\nGOTO 1e9\nM30\n",
        "O1\nGOTO [-5]\nM30\n",
        "O1\n#[1e6]=1\nM30\n",
        "O1\n#[-1]=1\nM30\n",
        "O1\n#1=\nM30\n",
        "O1\nIF [1] \nM30\n",
        "O1\nWHILE [1 LT 2]\nM30\n",
        "O1\nEND9\nM30\n",
        "O1\nG1 X[1 EQ]\nM30\n",
        "O1\n#1=EXP[1000]\nM30\n",
        "O1\n#1=[1 AND 2 GT 1]\nG0 X#1 F[1/3]\nM30\n",
        "O1\nM99 P5\n",
        ":\n%\n%\n",
        "O1\nG0 X[ATAN[1]]\nM30\n",
        "O1\nX#1#2\nM30\n",
    ] {
        let r = std::panic::catch_unwind(|| read(text));
        assert!(r.is_ok(), "panicked on\n{text}");
    }
    // A bracket nest deeper than the guard is refused, naming it.
    assert!(read(&deep).unwrap_err().contains("nested deeper"));
    assert!(read(&spec2).unwrap_err().contains("10 sets"));
}
