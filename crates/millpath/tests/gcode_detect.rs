//! `--dialect auto`: each clue rule alone decides a minimal program and is named in the
//! reason; a dialect whose reader refuses what another reads is never chosen (the fallback);
//! the programs of the issue (LinuxCNC's `factorial.ngc`, a Sinumerik program in inches,
//! LinuxCNC's five-axis demo that starts with `%`) and the dialect checker's own samples are
//! read in their dialects.

mod detect_common;

use detect_common::auto_read;
use millpath::gcode::{
    ClueRule, Dialect, DialectGuess, DialectReason, ReadMove, Reader, ReaderOptions,
};
use millpath::job::estimate::{EstimateSettings, run_text};
use millpath::machine::Machine;
use std::path::Path;

fn data(rel: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(rel)
}

fn read(text: &str, o: ReaderOptions) -> Result<Vec<ReadMove>, String> {
    Reader::new(text.as_bytes(), o)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())
}

/// One rule: a minimal program (and file name) that it alone decides, the dialect it gets,
/// and the same program without the clue, which gets another.
struct RuleCase {
    rule: ClueRule,
    name: &'static str,
    with: &'static str,
    dialect: Dialect,
    without: (&'static str, &'static str),
}

fn rule_cases() -> Vec<RuleCase> {
    use ClueRule as R;
    use Dialect::{Fanuc, Grbl, LinuxCnc, Sinumerik};
    let case = |rule, name, with, dialect, without| RuleCase {
        rule,
        name,
        with,
        dialect,
        without,
    };
    vec![
        // `%` alone says Fanuc; the extension .ngc outweighs it.
        case(
            R::Extension,
            "p.ngc",
            "%\nG0 X1\nM2\n",
            LinuxCnc,
            ("p.nc", "%\nG0 X1\nM2\n"),
        ),
        case(
            R::Extension,
            "p.mpf",
            "G0 X1\nM30\n",
            Sinumerik,
            ("p.nc", "G0 X1\nM30\n"),
        ),
        // `;` alone says Grbl; the LinuxCNC words outweigh it.
        case(
            R::OWord,
            "p.nc",
            "; c\no100 if [1]\nG0 X1\no100 endif\nM2\n",
            LinuxCnc,
            ("p.nc", "; c\nG0 X1\nM2\n"),
        ),
        case(
            R::NamedParameter,
            "p.nc",
            "; c\n#<x> = 1\nG0 X1\nM2\n",
            LinuxCnc,
            ("p.nc", "; c\nG0 X1\nM2\n"),
        ),
        case(
            R::LinuxCncWord,
            "p.nc",
            "; c\nM64 P1\nG0 X1\nM2\n",
            LinuxCnc,
            ("p.nc", "; c\nG0 X1\nM2\n"),
        ),
        case(
            R::NotGrbl,
            "p.nc",
            "; c\nT1 M6\nG0 X1\nM2\n",
            LinuxCnc,
            ("p.nc", "; c\nT1\nG0 X1\nM2\n"),
        ),
        case(
            R::Expression,
            "p.nc",
            "; c\n#1 = 5\nG0 X#1\nM2\n",
            LinuxCnc,
            ("p.nc", "; c\nG0 X5\nM2\n"),
        ),
        case(
            R::ProgramNumber,
            "p.nc",
            "O1234\nG0 X1.\nM30\n",
            Fanuc,
            ("p.nc", "G0 X1.\nM30\n"),
        ),
        case(
            R::MacroB,
            "p.nc",
            "G0 X1.\nGOTO 10\nN10 M30\n",
            Fanuc,
            ("p.nc", "G0 X1.\nN10 M30\n"),
        ),
        case(
            R::FanucCall,
            "p.nc",
            "G0 X1.\nM98 P1000\nM30\n",
            Fanuc,
            ("p.nc", "G0 X1.\nM30\n"),
        ),
        case(
            R::FanucWord,
            "p.nc",
            "G05.1 Q1\nG0 X1.\nM30\n",
            Fanuc,
            ("p.nc", "G0 X1.\nM30\n"),
        ),
        case(
            R::Percent,
            "p.nc",
            "%\nG0 X1.\nM30\n%\n",
            Fanuc,
            ("p.nc", "G0 X1.\nM30\n"),
        ),
        case(
            R::SinumerikCycle,
            "p.nc",
            "CYCLE832(0.01,_FINISH,1)\nG0 X1\nM30\n",
            Sinumerik,
            ("p.nc", "G0 X1\nM30\n"),
        ),
        case(
            R::SinumerikUnits,
            "p.nc",
            "G17 G70 G90\nG0 X1\nM30\n",
            Sinumerik,
            ("p.nc", "G17 G90\nG0 X1\nM30\n"),
        ),
        case(
            R::SinumerikWord,
            "p.nc",
            "G60\nG0 X1\nM30\n",
            Sinumerik,
            ("p.nc", "G0 X1\nM30\n"),
        ),
        case(
            R::Semicolons,
            "p.nc",
            "; c\nG0 X1\nM2\n",
            Grbl,
            ("p.nc", "(c)\nG0 X1\nM2\n"),
        ),
    ]
}

#[test]
fn every_rule_alone_decides_a_minimal_program_and_names_itself() {
    let cases = rule_cases();
    for rule in ClueRule::ALL {
        assert!(
            cases.iter().any(|c| c.rule == rule),
            "no minimal program for {rule:?}"
        );
    }
    for c in &cases {
        let g = DialectGuess::new(Some(Path::new(c.name)), c.with);
        let choice = g.choice();
        assert_eq!(choice.dialect, c.dialect, "{:?}: {}", c.rule, c.with);
        let reason = choice.to_string();
        assert!(
            reason.contains(&c.rule.to_string()),
            "{:?}: the reason does not name the rule: {reason}",
            c.rule
        );
        assert!(reason.starts_with(&format!("dialect {}: found from ", c.dialect)));
        let (name, text) = c.without;
        let other = DialectGuess::new(Some(Path::new(name)), text).best();
        assert_ne!(other, c.dialect, "{:?}: decided without the rule", c.rule);
        // The program reads, in the chosen dialect, as `--dialect auto` reads it.
        let (auto, r) = auto_read(Some(Path::new(c.name)), c.with, &ReaderOptions::default());
        assert_eq!(auto.dialect, c.dialect, "{:?}", c.rule);
        if !matches!(c.rule, ClueRule::FanucCall | ClueRule::MacroB) {
            assert!(r.is_ok(), "{:?}: {r:?}", c.rule);
        }
    }
    // No clue at all: LinuxCNC, the reference dialect, said so.
    let c = DialectGuess::new(None, "G0 X1\nM2\n").choice();
    assert_eq!(c.dialect, Dialect::LinuxCnc);
    assert_eq!(c.reason, DialectReason::NoClue);
    assert!(c.to_string().contains("reference dialect"), "{c}");
}

#[test]
fn a_dialect_that_refuses_what_another_reads_is_never_chosen() {
    // `;` says Grbl, which has no rotary axes; LinuxCNC reads `A5`.
    let text = "; rotary\nG21 G90\nG0 X1 A5\nG1 X2 F600\nM2\n";
    assert!(read(text, ReaderOptions::default().with_dialect(Dialect::Grbl)).is_err());
    let (choice, moves) = auto_read(None, text, &ReaderOptions::default());
    assert_eq!(choice.dialect, Dialect::LinuxCnc);
    let moves = moves.unwrap();
    assert_eq!(moves.len(), 2);
    match &choice.reason {
        DialectReason::Fallback {
            suggested, refusal, ..
        } => {
            assert_eq!(*suggested, Dialect::Grbl);
            assert!(
                refusal.contains("A5") && refusal.contains(":3"),
                "{refusal}"
            );
        }
        r => panic!("not a fallback: {r:?}"),
    }
    let s = choice.to_string();
    assert!(
        s.starts_with("dialect linuxcnc: grbl (suggested by `;` at line 1")
            && s.contains("reads all of it"),
        "{s}"
    );
    // The estimate job does the same, and says it.
    let m = Machine::preset("hsm").unwrap();
    let run = run_text(text, "p", &m, &EstimateSettings::default()).unwrap();
    assert_eq!(run.dialect.dialect, Dialect::LinuxCnc);
    assert!(matches!(
        run.dialect.reason,
        DialectReason::Fallback {
            suggested: Dialect::Grbl,
            ..
        }
    ));
    assert!(run.estimate.cycle_time_s > 0.0);
    // Named, the dialect stays strict.
    let grbl = EstimateSettings {
        dialect: "grbl".into(),
        ..EstimateSettings::default()
    };
    let e = run_text(text, "p", &m, &grbl).unwrap_err().to_string();
    assert!(e.contains("A5") && e.contains("p:3"), "{e}");
    // A program no dialect reads keeps the first candidate's refusal, which says so.
    let bad = "; bad\nG0 X1 A5\nG7 Q\nM2\n";
    let e = run_text(bad, "p", &m, &EstimateSettings::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("p:2") && e.contains("(read as grbl, found from the program; no other"),
        "{e}"
    );
}

/// The three programs of the issue.
#[test]
fn linuxcnc_subroutines_sinumerik_inches_and_a_five_axis_demo_framed_by_percent() {
    // LinuxCNC's factorial.ngc: `;` comments and `o<factorial> sub`.
    let f = data("linuxcnc-nc/nc_files/factorial.ngc");
    let text = std::fs::read_to_string(&f).unwrap();
    let (c, r) = auto_read(Some(&f), &text, &ReaderOptions::default());
    assert_eq!(c.dialect, Dialect::LinuxCnc);
    assert!(c.to_string().contains("`o<factorial> sub`"), "{c}");
    assert!(r.is_ok(), "{r:?}");
    // Grbl, which its `;` once suggested, refuses it.
    assert!(read(&text, ReaderOptions::default().with_dialect(Dialect::Grbl)).is_err());

    // Sinumerik in inches: G70, G60, M30, .mpf. Its X1 is 25.4 mm.
    let sin = "; inch part\nG17 G70 G90 G60\nG0 X1 Y1 Z0.5\nG1 Z-0.1 F10\nG1 X2\nM30\n";
    for name in ["part.mpf", "part.nc"] {
        let (c, r) = auto_read(Some(Path::new(name)), sin, &ReaderOptions::default());
        assert_eq!(c.dialect, Dialect::Sinumerik, "{name}");
        assert!(c.to_string().contains("`G70` at line 2"), "{c}");
        let moves = r.unwrap();
        assert!((moves[2].mv.to.x - 50.8).abs() < 1e-9, "{:?}", moves[2]);
    }
    let e = read(sin, ReaderOptions::default()).unwrap_err();
    assert!(e.contains("G70"), "LinuxCNC refuses Sinumerik's G70: {e}");

    // LinuxCNC's five-axis demo: `%` first, A and C words. Its M428/M429 switch kinematics
    // on that machine (a remap of its configuration): commented out, the program is what
    // any LinuxCNC runs.
    let f = data("linuxcnc-demos/boat-xyzac.ngc");
    let original = std::fs::read_to_string(&f).unwrap();
    let text = original
        .replacen("M428 ;", "(M428) ;", 1)
        .replacen("M429 ;", "(M429) ;", 1);
    let (c, r) = auto_read(Some(&f), &text, &ReaderOptions::default());
    assert_eq!(c.dialect, Dialect::LinuxCnc, "{c}");
    assert!(c.to_string().contains("the file extension .ngc"), "{c}");
    let moves = r.unwrap();
    let named = read(&text, ReaderOptions::default()).unwrap();
    assert!(moves == named && moves.len() > 400, "{}", moves.len());
    // Fanuc, which its `%` alone would suggest, refuses its rotary words.
    let e = read(&text, ReaderOptions::default().with_dialect(Dialect::Fanuc)).unwrap_err();
    assert!(e.contains("A0.") && e.contains(":13"), "{e}");
    // As it is, M428 is refused in every dialect: the refusal is LinuxCNC's, at line 2;
    // lenient, LinuxCNC skips it and reads the rest.
    let (c, r) = auto_read(Some(&f), &original, &ReaderOptions::default());
    assert_eq!(c.dialect, Dialect::LinuxCnc);
    let e = r.unwrap_err().to_string();
    assert!(e.contains("M428") && e.contains(":2"), "{e}");
    let lenient = ReaderOptions::default().with_lenient(true);
    let (c, r) = auto_read(Some(&f), &original, &lenient);
    assert_eq!(c.dialect, Dialect::LinuxCnc);
    assert_eq!(r.map(|m| m.len()).ok(), Some(moves.len()));
}

/// The dialect checker's sample programs (`dialect_check::self_test`) and a program of each
/// dialect as millpath writes it, with its usual extension.
#[test]
fn the_checkers_samples_and_written_programs_are_found() {
    for (text, d) in [
        (
            "; x\nG17 G21 G90 G94\nG0 X0 Y0 Z1\nG1 Z0 F100\nG2 X10 Y0 I5 J0\nM2\n",
            Dialect::Grbl,
        ),
        (
            "%\nO0001 (A)\nG17 G21 G90\nG0 X0. Y0. Z1.\nG1 Z0. F100.\nG3 X10. Y0. I5. J0.\n\
             G04 X0.5\nM30\n%\n",
            Dialect::Fanuc,
        ),
        (
            "; a\nG17 G710 G90\nCYCLE832(0.01,_FINISH,1)\nG0 X0 Y0 Z1\nG1 Z0 F100\n\
             G3 X0 Y0 Z-1 I5 J0 TURN=2\nG4 F0.5\nM30\n",
            Dialect::Sinumerik,
        ),
    ] {
        let (c, r) = auto_read(None, text, &ReaderOptions::default());
        assert_eq!(c.dialect, d, "{text}");
        assert!(r.is_ok(), "{d}: {r:?}");
    }
}
