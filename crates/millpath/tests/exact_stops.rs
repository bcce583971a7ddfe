//! An exact stop is one notion whichever dialect writes it, and what it costs is the
//! machine's: the same square with each dialect's exact-stop words (LinuxCNC `G61.1`, Fanuc
//! `G61` and `G09`, Sinumerik `G60` and `G9`; Grbl has none) takes the same time on every
//! built-in machine, and on a machine that settles at exact stops the time is the time
//! without settling plus one settling per stop, counted on the moves read.

use millpath::gcode::{Dialect, ReaderOptions, read_str};
use millpath::job::estimate::{EstimateSettings, run_text};
use millpath::machine::{Controller, Machine};
use millpath::toolpath::Corner;

/// A 40 × 20 mm square at F600 between a rapid down to 5 mm and one back up, with `stop`
/// written as each dialect writes exact stops: a modal word on a line of its own or a
/// per-block word on every move. `{u}` is the metric word, `{end}` the end of the program,
/// `{d}` the decimal point Fanuc needs on coordinates.
fn square(dialect: &str, stop: &str, per_block: bool) -> String {
    let (units, end, d) = match dialect {
        "fanuc" => ("G21", "M30", "."),
        "sinumerik" => ("G71", "M30", ""),
        _ => ("G21", "M2", ""),
    };
    let (modal, each) = if per_block {
        (String::new(), format!("{stop} "))
    } else {
        (format!("{stop}\n"), String::new())
    };
    let moves = [
        format!("G0 X0{d} Y0{d} Z5{d}"),
        format!("G1 Z0{d} F600{d}"),
        format!("X40{d}"),
        format!("Y20{d}"),
        format!("X0{d}"),
        format!("Y0{d}"),
        format!("G0 Z5{d}"),
    ];
    let body: String = moves.iter().map(|m| format!("{each}{m}\n")).collect();
    let text = format!("{units} G90 G17\n{modal}{body}{end}\n");
    if dialect == "fanuc" {
        format!("%\nO0001\n{text}%\n")
    } else {
        text
    }
}

/// Each dialect's exact-stop words, as (dialect, word, per block).
const STOPS: [(&str, &str, bool); 5] = [
    ("linuxcnc", "G61.1", false),
    ("fanuc", "G61", false),
    ("fanuc", "G09", true),
    ("sinumerik", "G60", false),
    ("sinumerik", "G9", true),
];

fn time(text: &str, dialect: &str, machine: &Machine) -> f64 {
    let settings = EstimateSettings {
        dialect: dialect.into(),
        ..EstimateSettings::default()
    };
    let run = run_text(text, "square", machine, &settings).expect("the square is read and planned");
    // The limit verifier (which also requires rest at every exact stop) finds nothing.
    if machine.controller != Controller::LinuxCnc {
        assert_eq!(
            run.estimate.violations,
            Some(0),
            "{dialect} on {}",
            machine.name
        );
    }
    run.estimate.cycle_time_s
}

/// The exact stops of a program: junctions where a move whose corner is an exact stop
/// meets the next move, and the end of the program.
fn stops(text: &str, dialect: &str) -> usize {
    let d: Dialect = dialect.parse().expect("a dialect");
    let (tp, _) = read_str(text, ReaderOptions::default().with_dialect(d)).expect("reads");
    let moving: Vec<_> = tp
        .segments()
        .filter(|(f, m)| m.length_from(*f) > 0.0)
        .collect();
    let junctions = moving
        .windows(2)
        .filter(|w| w[0].1.corner == Corner::ExactStop)
        .count();
    junctions + 1
}

#[test]
fn every_dialects_exact_stop_costs_the_same_on_every_machine() {
    let programs: Vec<(&str, &str, String)> = STOPS
        .iter()
        .map(|&(d, w, each)| (d, w, square(d, w, each)))
        .collect();
    // Every program reads as the same seven moves with an exact stop at the end of each.
    for (d, w, text) in &programs {
        assert_eq!(stops(text, d), 7, "{d} {w}:\n{text}");
    }
    for name in Machine::PRESET_NAMES {
        let machine = Machine::preset(name).expect("a preset");
        let times: Vec<f64> = programs
            .iter()
            .map(|(d, _, t)| time(t, d, &machine))
            .collect();
        for ((d, w, _), t) in programs.iter().zip(&times) {
            assert!(
                (t - times[0]).abs() <= 1e-9 * times[0],
                "{name}: {d} {w} takes {t} s, LinuxCNC G61.1 {} s",
                times[0]
            );
        }
    }
}

#[test]
fn a_settling_machine_waits_once_per_exact_stop_in_every_dialect() {
    // The sinumerik model (hsm), its settling as the profile states it; and a generic model
    // (router) given a settling time of its own. The linuxcnc model has none.
    let hsm = Machine::preset("hsm").expect("a preset");
    let router = Machine {
        exact_stop_time: 0.05,
        ..Machine::preset("router").expect("a preset")
    };
    let lcnc = Machine {
        exact_stop_time: 0.05,
        ..Machine::preset("linuxcnc-time").expect("a preset")
    };
    for machine in [&hsm, &router] {
        let settle = machine.exact_stop_time;
        assert!(settle > 0.0);
        let still = Machine {
            exact_stop_time: 0.0,
            ..machine.clone()
        };
        for &(d, w, each) in &STOPS {
            let text = square(d, w, each);
            let n = stops(&text, d) as f64;
            let (t, t0) = (time(&text, d, machine), time(&text, d, &still));
            assert!(
                (t - t0 - n * settle).abs() <= 1e-9 * t,
                "{} {d} {w}: {t} s, {t0} s without settling, {n} stops of {settle} s",
                machine.name
            );
        }
    }
    let text = square("linuxcnc", "G61.1", false);
    let base = Machine::preset("linuxcnc-time").expect("a preset");
    let (t, t0) = (
        time(&text, "linuxcnc", &lcnc),
        time(&text, "linuxcnc", &base),
    );
    assert!((t - t0).abs() <= 1e-12 * t, "linuxcnc settles: {t} vs {t0}");
}

#[test]
fn an_exact_stop_stops_where_the_next_move_goes_straight_on() {
    // Two collinear moves under an exact stop: the axes come to rest between them (and
    // settle there), as a dwell between them makes them; exact path goes straight on.
    let hsm = Machine::preset("hsm").expect("a preset");
    let collinear = "G21 G90 G61.1\nG1 X10 F600\nX20\nM2\n";
    let dwell = "G21 G90 G61.1\nG1 X10 F600\nG4 P0\nX20\nM2\n";
    let path = "G21 G90 G61\nG1 X10 F600\nX20\nM2\n";
    let one = "G21 G90 G61.1\nG1 X20 F600\nM2\n";
    let t = |text: &str| time(text, "linuxcnc", &hsm);
    assert!((t(collinear) - t(dwell)).abs() <= 1e-9 * t(dwell));
    assert!(t(collinear) > t(one) + hsm.exact_stop_time);
    // Exact path: the one move's time, ending in the program's own exact stop.
    assert!((t(path) - t(one)).abs() <= 1e-9 * t(one));
    assert_eq!(stops(collinear, "linuxcnc"), 2);
}

#[test]
fn grbl_has_no_exact_stop_word() {
    // Grbl 1.1 knows none of the other dialects' exact-stop modes: they are refused, naming
    // the word and the line.
    for word in ["G61.1", "G60"] {
        let text = format!("G21 G90\n{word}\nG1 X10 F600\nM2\n");
        let settings = EstimateSettings {
            dialect: "grbl".into(),
            ..EstimateSettings::default()
        };
        let hsm = Machine::preset("hsm").expect("a preset");
        let e = run_text(&text, "grbl", &hsm, &settings).expect_err("refused");
        assert_eq!(e.exit_code(), 2);
        assert!(
            e.to_string().contains(word) && e.to_string().contains("grbl:2"),
            "{e}"
        );
    }
}
