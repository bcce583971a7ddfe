//! End-to-end hostile pass over the built binary: every command (contour, pocket, estimate,
//! verify, five-axis, sweep) on a corpus of bad inputs. Each case must
//!
//! * exit with code 2 (bad input), never 1 (internal) or a signal;
//! * print one message of the shape `error: invalid WHAT = VALUE (from ORIGIN): expected
//!   ACCEPTED` on stderr: the value, where it came from and what would be accepted (the
//!   `(from ORIGIN)` part may be absent only where WHAT is itself the origin: a flag such as
//!   `--dt`, or the input file named on the command line); no panic message, no backtrace;
//! * write no output file, and leave an existing output file of the same name untouched (no
//!   temporary file left beside it either).
//!
//! The cases and the exact messages they get are the table in `docs/bad-input.md`; the test
//! regenerates the table and fails when the document differs, so it cannot drift. After a
//! deliberate change of a message: `MILLPATH_BLESS=1 cargo test -p millpath-cli --test
//! cli_hostile` rewrites the table.

use std::path::{Path, PathBuf};
use std::process::Command;

mod hostile_corpus;
use hostile_corpus::{Case, KEEP, SQUARE_JSON, SQUARE_PTS, cases};

struct Outcome {
    code: Option<i32>,
    message: String,
    problems: Vec<String>,
}

fn run(case: &Case) -> Outcome {
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, body) in case.files {
        std::fs::write(dir.path().join(name), body).expect("write input");
    }
    let before: Vec<PathBuf> = listing(dir.path());
    let o = Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(case.args)
        .current_dir(dir.path())
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the millpath binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let mut problems = Vec::new();
    let code = o.status.code();
    if code != Some(2) {
        problems.push(format!("exit code {code:?}, expected 2"));
    }
    // `note:` lines (what a drawing held, read before the refusal) are information, not the
    // error: the error itself is one line.
    let message = stderr
        .trim_end()
        .lines()
        .filter(|l| !l.starts_with("note: "))
        .collect::<Vec<_>>()
        .join("\n");
    for bad in ["panicked", "backtrace", "internal error", "RUST_BACKTRACE"] {
        if message.contains(bad) {
            problems.push(format!("stderr contains `{bad}`"));
        }
    }
    // The origin is in `(from ...)`, or is the WHAT itself: a flag (`invalid --dt = 0`) or
    // the file named on the command line (`invalid input file = part.dxf`).
    let what = message
        .strip_prefix("error: invalid ")
        .and_then(|r| r.split(" = ").next())
        .unwrap_or("");
    let self_origin = what.starts_with("--") || what.ends_with(" file");
    let shape = message.starts_with("error: invalid ")
        && message.contains(" = ")
        && message.contains(": expected ")
        && (message.contains(" (from ") || self_origin);
    if !shape {
        problems.push(
            "message is not `error: invalid WHAT = VALUE (from ORIGIN): expected ACCEPTED`"
                .to_owned(),
        );
    }
    if message.lines().count() != 1 {
        problems.push("message is not one line".to_owned());
    }
    for out in case.outputs {
        let p = dir.path().join(out);
        if out.starts_with("keep.") {
            if std::fs::read(&p).ok().as_deref() != Some(KEEP) {
                problems.push(format!("existing {out} was modified"));
            }
        } else if p.exists() {
            problems.push(format!("output {out} was written"));
        }
    }
    let after = listing(dir.path());
    if after != before {
        problems.push(format!("files changed: before {before:?}, after {after:?}"));
    }
    Outcome {
        code,
        message,
        problems,
    }
}

fn listing(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.sort();
    v
}

fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The messages name the flag or file:line the value came from and the value as typed (not
/// a converted value, not a neighbouring word): one case per message that once did not.
#[test]
fn messages_name_the_flag_and_the_value_as_typed() {
    let checks: &[(Case, &[&str])] = &[
        (
            Case {
                what: "negative feed in the feed list",
                args: &["sweep", "sq.json", "--feeds", "300,-1", "--csv", "out.csv"],
                files: &[("sq.json", SQUARE_JSON)],
                outputs: &["out.csv"],
            },
            // Was `invalid feed = -0.4233333333333333 (from --feed)`.
            &["feed = -1 ", "(from --feeds)", "> 0 in/min"],
        ),
        (
            Case {
                what: "NaN depth",
                args: &[
                    "contour", "pts.csv", "--curve", "spline", "--depth", "NaN", "-o", "out.ngc",
                ],
                files: &[("pts.csv", SQUARE_PTS)],
                outputs: &["out.ngc"],
            },
            // Was `(from contour options)`.
            &["depth = NaN", "(from --depth)", "> 0 mm"],
        ),
        (
            Case {
                what: "number in exponent notation",
                args: &["estimate", "bad.ngc"],
                files: &[("bad.ngc", b"G21 G90\nG1 X1e400 F600\nM2\n")],
                outputs: &[],
            },
            // Was `invalid G-code word = e400 (from bad.ngc:2)`.
            &["X1e400", "(from bad.ngc:2)", "without exponent"],
        ),
    ];
    let mut failures = Vec::new();
    for (case, needles) in checks {
        let out = run(case);
        for n in *needles {
            if !out.message.contains(n) {
                failures.push(format!("{}: `{n}` missing in `{}`", case.what, out.message));
            }
        }
        failures.extend(out.problems.iter().map(|p| format!("{}: {p}", case.what)));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

const BEGIN: &str = "<!-- BEGIN GENERATED by crates/millpath-cli/tests/cli_hostile.rs -->";
const END: &str = "<!-- END GENERATED -->";

#[test]
fn every_command_refuses_the_hostile_corpus_cleanly() {
    let mut table = String::from("| command | bad input | command line | exit | message |\n");
    table.push_str("|---|---|---|---|---|\n");
    let mut failures = Vec::new();
    for case in cases() {
        let out = run(&case);
        let cmdline = case.args.join(" ");
        if !out.problems.is_empty() {
            failures.push(format!(
                "`millpath {cmdline}` ({}): {}\n    stderr: {}",
                case.what,
                out.problems.join("; "),
                out.message
            ));
        }
        table.push_str(&format!(
            "| {} | {} | `millpath {}` | {} | `{}` |\n",
            case.args[0],
            cell(case.what),
            cell(&cmdline),
            out.code.map_or("signal".into(), |c| c.to_string()),
            cell(&out.message)
        ));
    }
    let doc_path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/bad-input.md");
    let doc = std::fs::read_to_string(&doc_path).unwrap_or_default();
    let generated = format!("{BEGIN}\n{table}{END}");
    let current = match (doc.find(BEGIN), doc.find(END)) {
        (Some(a), Some(b)) if a < b => Some(&doc[a..b + END.len()]),
        _ => None,
    };
    if current != Some(generated.as_str()) {
        if std::env::var_os("MILLPATH_BLESS").is_some() {
            let new = match current {
                Some(c) => doc.replace(c, &generated),
                None => format!("{doc}\n{generated}\n"),
            };
            std::fs::write(&doc_path, new).expect("write docs/bad-input.md");
        } else {
            failures.push(format!(
                "docs/bad-input.md is out of date with the messages; rerun with MILLPATH_BLESS=1. \
                 Generated table:\n{generated}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
