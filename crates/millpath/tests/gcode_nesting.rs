//! Input nested 100,000 deep never crashes the reader: calls, `if`s, Fanuc subprograms and
//! macros, macro B loops, expressions (brackets, signs, functions, long operator chains) and
//! comments, each generated here and read in the test's own thread (2 MiB of stack, less
//! than the CLI's main thread). Each is refused with a message naming its bound, or read.
//! Where 100,000 levels need a line longer than the reader takes (64 KiB), the line is
//! refused as too long, and the bound itself is tested just below that length.

use millpath::gcode::{Dialect, MAX_LINE_BYTES, ReadMove, Reader, ReaderOptions};

const DEEP: usize = 100_000;

fn read(text: &str, o: ReaderOptions) -> Result<Vec<ReadMove>, String> {
    Reader::new(text.as_bytes(), o)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())
}

fn refused(text: &str, o: ReaderOptions, needles: &[&str]) {
    let e = read(text, o).expect_err("refused");
    // The message quotes the line's start, not all of it.
    assert!(e.len() < 600, "{} bytes: {}…", e.len(), &e[..300]);
    for n in needles {
        assert!(e.contains(n), "'{n}' not in {e}");
    }
}

fn fanuc() -> ReaderOptions {
    ReaderOptions::default().with_dialect(Dialect::Fanuc)
}

#[test]
fn o_word_calls_100000_deep_stop_at_the_call_depth() {
    // o<s0> calls o<s1> … calls o<s99999>: all defined, then called.
    let mut t = String::from("G21\n");
    for k in 0..DEEP {
        t += &format!("o<s{k}> sub\no<s{}> call\no<s{k}> endsub\n", k + 1);
    }
    t += "o<s0> call\nM2\n";
    refused(
        &t,
        ReaderOptions::default(),
        &["calls nested deeper than 100 (o<s100>)"],
    );
}

#[test]
fn o_word_ifs_and_loops_100000_deep_stop_at_the_nesting_bound() {
    for (open, close) in [("if [1]", "endif"), ("while [1]", "endwhile")] {
        let mut t = String::from("G21\n");
        for k in 1..=DEEP {
            t += &format!("o{k} {open}\n");
        }
        t += "G0 X1\n";
        for k in (1..=DEEP).rev() {
            t += &format!("o{k} {close}\n");
        }
        t += "M2\n";
        refused(
            &t,
            ReaderOptions::default(),
            &["o1001", "nested deeper than 1000", "G-code:1002"],
        );
    }
    // Skipped, the same nesting costs nothing: the false `if` skips to its `endif`.
    let mut t = String::from("G21\no1 if [0]\n");
    for k in 2..=DEEP {
        t += &format!("o{k} if [1]\n");
    }
    for k in (2..=DEEP).rev() {
        t += &format!("o{k} endif\n");
    }
    t += "o1 endif\nG0 X1\nM2\n";
    assert_eq!(read(&t, ReaderOptions::default()).unwrap().len(), 1);
}

#[test]
fn fanuc_subprograms_and_macros_100000_deep_stop_at_their_levels() {
    for (call, needle) in [
        ("M98 P", "subprogram calls nested deeper than 10"),
        ("G65 P", "macro calls nested deeper than 5"),
    ] {
        let mut t = String::from("%\nO1\nG21\n");
        t += &format!("{call}2\nM30\n");
        for k in 2..DEEP as u32 + 2 {
            t += &format!("O{k}\n{call}{}\nM99\n", k + 1);
        }
        t += "%\n";
        refused(&t, fanuc(), &[needle]);
    }
}

#[test]
fn macro_b_loops_100000_deep_are_refused_as_unpaired() {
    // DO1 inside DO1 … (the loop numbers are 1 to 3; the pairs must nest).
    let mut t = String::from("O1\n");
    for _ in 0..DEEP {
        t += "WHILE [1 LT 2] DO1\n";
    }
    t += "G0 X1.\n";
    for _ in 0..DEEP {
        t += "END1\n";
    }
    t += "M30\n";
    refused(&t, fanuc(), &["DO1 at line 3 inside another DO1"]);
    // `IF [..] GOTO` is one block; its condition nests as an expression (below).
    let deep_if = format!(
        "O1\nIF {}1{} GOTO 9\nN9 M30\n",
        "[".repeat(60),
        "]".repeat(60)
    );
    refused(&deep_if, fanuc(), &["nested deeper than 64"]);
}

/// An expression `inner` nested `n` deep by `wrap`, in an RS274/NGC and a macro B
/// assignment.
fn assignments(inner: &str) -> [(String, ReaderOptions); 2] {
    [
        (
            format!("G21\n#1 = {inner}\nG0 X#1\nM2\n"),
            ReaderOptions::default(),
        ),
        (format!("O1\n#1={inner}\nG0 X#1\nM30\n"), fanuc()),
    ]
}

#[test]
fn expressions_nested_deep_stop_at_their_depth_or_the_line_length() {
    // Lines that fit 64 KiB: the expression depth (64) refuses them.
    let fits = (MAX_LINE_BYTES as usize - 100) / 6;
    for (what, inner) in [
        (
            "brackets",
            format!("{}1{}", "[".repeat(fits * 3), "]".repeat(fits * 3)),
        ),
        ("signs", format!("[{}1]", "-".repeat(fits * 6))),
        (
            "functions",
            format!("{}1{}", "SIN[".repeat(fits), "]".repeat(fits)),
        ),
        (
            "parameters",
            format!("{}1{}", "#[".repeat(fits * 2), "]".repeat(fits * 2)),
        ),
    ] {
        assert!(inner.len() < MAX_LINE_BYTES as usize - 20, "{what}");
        for (t, o) in assignments(&inner) {
            refused(&t, o, &["nested deeper than 64", ":2"]);
        }
    }
    // 100,000 deep: longer than a line may be.
    for inner in [
        format!("{}1{}", "[".repeat(DEEP), "]".repeat(DEEP)),
        format!("[{}1]", "-".repeat(DEEP)),
        format!("{}1{}", "SIN[".repeat(DEEP), "]".repeat(DEEP)),
    ] {
        for (t, o) in assignments(&inner) {
            refused(&t, o, &["longer than 65536 bytes"]);
        }
    }
}

#[test]
fn long_operator_chains_are_read_without_recursing_per_operator() {
    // As many operators as a line holds: a loop, not a recursion per operator.
    let n = (MAX_LINE_BYTES as usize - 100) / 2;
    for (op, want) in [("+", n as f64), ("*", 1.0), ("-", 2.0 - n as f64)] {
        let chain = format!("[{}1]", format!("1{op}").repeat(n - 1));
        for (t, o) in assignments(&chain) {
            let moves = read(&t, o).unwrap_or_else(|e| panic!("{op}: {e}"));
            assert!(
                (moves[0].mv.to.x - want).abs() < 1e-9,
                "{op}: {:?}",
                moves[0]
            );
        }
    }
    // Precedence climbing: the levels alternate, each returns before the next operator.
    let mixed = format!("[{}1]", "1 ** 1 * 1 + 1 eq 1 and ".repeat(2000));
    assert!(read(&format!("#1 = {mixed}\nM2\n"), ReaderOptions::default()).is_ok());
    let too_long = format!("[{}1]", "1+".repeat(DEEP));
    for (t, o) in assignments(&too_long) {
        refused(&t, o, &["longer than 65536 bytes"]);
    }
}

#[test]
fn comments_nested_deep_are_refused_in_every_dialect() {
    let fits = (MAX_LINE_BYTES as usize - 20) / 2;
    for d in Dialect::ALL {
        let o = ReaderOptions::default().with_dialect(d);
        for depth in [fits, DEEP] {
            let t = format!(
                "G0 X1\nG0 Y1 {}c{}\nM30\n",
                "(".repeat(depth),
                ")".repeat(depth)
            );
            let e = read(&t, o.clone()).expect_err("refused");
            assert!(
                e.contains(":2") && (e.contains("nested '('") || e.contains("longer than")),
                "{d}: {e}"
            );
        }
        // In a `;` comment, parentheses are text.
        let t = format!("G0 X1 ; {}\nM30\n", "(".repeat(fits));
        if d != Dialect::Fanuc {
            assert!(read(&t, o).is_ok(), "{d}");
        }
    }
}
