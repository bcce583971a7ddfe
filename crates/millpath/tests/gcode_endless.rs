//! Programs that never end stop at the step budget with an input error naming the loop end,
//! jump or call that kept them going (its line, how often it ran) and the lines run: every
//! kind of endless RS274/NGC and Fanuc program, with a small budget set through
//! `ReaderOptions::with_step_budget` (the tests run unoptimised), and the default budget's
//! own message on an empty loop. Endless recursion stops at the call depth instead.

use millpath::gcode::{DEFAULT_STEP_BUDGET, Dialect, Reader, ReaderOptions};

const BUDGET: u64 = 20_000;

/// The refusal of `text` read with `o` (which must refuse it), and the moves before it.
fn refusal(text: &str, o: ReaderOptions) -> (String, usize) {
    let mut moves = 0;
    for m in Reader::new(text.as_bytes(), o) {
        match m {
            Ok(_) => moves += 1,
            Err(e) => {
                assert_eq!(e.exit_code(), 2, "{e}");
                return (e.to_string(), moves);
            }
        }
    }
    panic!("read to its end after {moves} moves:\n{text}");
}

fn ngc() -> ReaderOptions {
    ReaderOptions::default().with_step_budget(BUDGET)
}

fn fanuc() -> ReaderOptions {
    ngc().with_dialect(Dialect::Fanuc)
}

/// `(program, options, what the message must hold)`.
fn endless() -> Vec<(&'static str, &'static str, ReaderOptions, Vec<String>)> {
    let steps = |unit: &str| format!("{} {unit}", BUDGET + 1);
    let lines = steps("lines run in loops and subroutines");
    let blocks = steps("blocks run in subprograms and loops");
    vec![
        (
            "while with a condition that never changes",
            "G21 F600\n#1 = 1\no100 while [#1 GT 0]\nG1 X1\nG1 X0\no100 endwhile\nM2\n",
            ngc(),
            vec![
                "o100 endwhile at line 6 ran 5000 times".into(),
                lines.clone(),
            ],
        ),
        (
            "while with an empty body",
            "#1 = 1\no100 while [#1 GT 0]\no100 endwhile\nM2\n",
            ngc(),
            vec![
                "o100 endwhile at line 3 ran 10000 times".into(),
                lines.clone(),
            ],
        ),
        (
            "do … while [1]",
            "G21 F600\no100 do\nG1 X1\nG1 X0\no100 while [1]\nM2\n",
            ngc(),
            vec!["o100 while at line 5 ran".into(), lines.clone()],
        ),
        (
            "repeat a billion times",
            "G21 F600\no100 repeat [1000000000]\nG1 X1\nG1 X0\no100 endrepeat\nM2\n",
            ngc(),
            vec!["o100 endrepeat at line 5 ran".into(), lines.clone()],
        ),
        (
            "repeat a billion times, empty",
            "o100 repeat [1000000000]\no100 endrepeat\nM2\n",
            ngc(),
            vec![
                "o100 endrepeat at line 2 ran 20000 times".into(),
                lines.clone(),
            ],
        ),
        (
            "a subroutine defined again in an endless loop",
            "o1 while [1]\no<s> sub\nG0 X1\nG0 X2\no<s> endsub\no1 endwhile\nM2\n",
            ngc(),
            vec!["o1 endwhile at line 6 ran".into(), lines.clone()],
        ),
        (
            "a call in an endless loop",
            "G21 F600\no<s> sub\nG1 X1\nG1 X0\no<s> endsub\no1 while [1]\no<s> call\n\
             o1 endwhile\nM2\n",
            ngc(),
            vec!["at line".into(), "ran".into(), lines.clone()],
        ),
        (
            "recursion 40 deep that branches in two (2^40 calls)",
            "o<r> sub\no1 if [#1 LT 40]\no<r> call [#1 + 1]\no<r> call [#1 + 1]\no1 endif\n\
             o<r> endsub\no<r> call [0]\nM2\n",
            ngc(),
            vec!["o<r> call at line 3 ran".into(), lines.clone()],
        ),
        (
            "M99 at the end of the main program",
            "O1\nG21 G90 F600.\nG1 X1.\nG1 X0\nM99\n",
            fanuc(),
            vec!["M99 at line 5 ran".into(), blocks.clone()],
        ),
        (
            "M99 P back to an earlier block",
            "O1\nG21 G90\nN10 G0 X1.\nG0 X0\nM99 P10\n",
            fanuc(),
            vec!["M99 at line 5 ran".into(), blocks.clone()],
        ),
        (
            "GOTO its own block",
            "%\nO1\nN10 GOTO10\nM30\n%\n",
            fanuc(),
            vec!["GOTO 10 at line 3 ran 20001 times".into(), blocks.clone()],
        ),
        (
            "WHILE with a variable that never changes",
            "O1\n#1=1\nWHILE [#1 GT 0] DO1\nG0 X1.\nG0 X0\nEND1\nM30\n",
            fanuc(),
            vec!["END1 at line 6 ran".into(), blocks.clone()],
        ),
        (
            "DO1 … END1 without WHILE",
            "O1\nDO1\nEND1\nM30\n",
            fanuc(),
            vec!["END1 at line 3 ran".into(), blocks.clone()],
        ),
        (
            "a subprogram that jumps back in its caller",
            "O1\nN10 G0 X1.\nM98 P1000\nM30\nO1000\nG0 X2.\nM99 P10\n",
            fanuc(),
            vec!["M98 P1000 at line 3 ran".into(), blocks.clone()],
        ),
    ]
}

#[test]
fn endless_programs_stop_at_the_step_budget_naming_the_loop() {
    for (what, text, o, needles) in endless() {
        let (e, _) = refusal(text, o);
        assert!(
            e.contains("a loop that never ends?")
                && e.contains(&format!("step budget of {BUDGET} "))
                && e.contains("--step-budget"),
            "{what}: {e}"
        );
        for n in &needles {
            assert!(e.contains(n.as_str()), "{what}: '{n}' not in {e}");
        }
    }
}

#[test]
fn the_moves_before_the_budget_are_the_loops_passes() {
    // Each pass runs 4 lines again (the while line and the loop end included) and makes 2
    // moves; the first pass's while line runs before the loop is open.
    let text = "G21 F600\n#1 = 1\no100 while [#1 GT 0]\nG1 X1\nG1 X0\no100 endwhile\nM2\n";
    let (_, moves) = refusal(text, ngc().with_step_budget(3000));
    assert!((1498..=1502).contains(&moves), "{moves}");
}

#[test]
fn endless_recursion_stops_at_the_call_depth() {
    for (text, o, needle) in [
        (
            "o<r> sub\nG0 X1\no<r> call\no<r> endsub\no<r> call\nM2\n",
            ngc(),
            "calls nested deeper than 100 (o<r>)",
        ),
        (
            "O1\nM98 P1000\nM30\nO1000\nG0 X1.\nM98 P1000\nM99\n",
            fanuc(),
            "subprogram calls nested deeper than 10",
        ),
        (
            "O1\nG65 P1000\nM30\nO1000\nG65 P1000\nM99\n",
            fanuc(),
            "macro calls nested deeper than 5",
        ),
    ] {
        let (e, _) = refusal(text, o);
        assert!(e.contains(needle), "{e}");
    }
}

/// The default budget, on loops that cost little per line (the tests run unoptimised).
#[test]
fn the_default_budget_stops_an_empty_loop_and_names_itself() {
    assert_eq!(ReaderOptions::default().step_budget, DEFAULT_STEP_BUDGET);
    for (text, o, site) in [
        (
            "#1 = 1\no100 while [#1 GT 0]\no100 endwhile\nM2\n",
            ReaderOptions::default(),
            "o100 endwhile at line 3",
        ),
        (
            "%\nO1\nN10 GOTO10\nM30\n%\n",
            ReaderOptions::default().with_dialect(Dialect::Fanuc),
            "GOTO 10 at line 3",
        ),
    ] {
        let (e, _) = refusal(text, o);
        assert!(
            e.contains(site)
                && e.contains(&format!("({} ", DEFAULT_STEP_BUDGET + 1))
                && e.contains(&format!("step budget of {DEFAULT_STEP_BUDGET} ")),
            "{e}"
        );
    }
    // A loop that ends within the budget reads to its end. 1000 passes: the first runs 3
    // lines in the open loop, the 999 others 4 (the while line again), and the last while
    // line once more: 4000 lines.
    let text =
        "G21 F600\n#1 = 0\no1 while [#1 LT 1000]\nG1 X[#1]\n#1 = [#1 + 1]\no1 endwhile\nM2\n";
    let n = Reader::new(
        text.as_bytes(),
        ReaderOptions::default().with_step_budget(4000),
    )
    .collect::<Result<Vec<_>, _>>()
    .unwrap()
    .len();
    assert_eq!(n, 1000);
    let (e, _) = refusal(text, ReaderOptions::default().with_step_budget(3999));
    assert!(e.contains("o1 endwhile at line 6 ran 1000 times"), "{e}");
}
