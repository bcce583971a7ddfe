//! Diagnostic: where an adaptive program's time goes when the tool is not cutting. Each
//! pocket of the drawing (or `aero`, the aerospace pocket) is planned as `millpath pocket FILE
//! --strategy adaptive` plans it at its defaults and timed on `hsm` move by move; the stock
//! simulation's removal sorts the moves: rapids, entries, cutting (more than 2 % of the
//! diameter times the length, as the reports count), light (0.2–2 %), and the runs of
//! consecutive empty moves (under 0.2 %) by length: under two diameters (links and short
//! stretches of a pass), two to ten, longer.
//! `STEP=` (stepover, as `--stepover`); `RUNS=1` lists each run of empty moves: its time,
//! length, move count, the straight distance between its ends and the turns (degrees) into
//! and out of it.
//! `cargo run --release --example adaptive_air -- FILE|aero`
#![allow(clippy::print_stdout, clippy::print_stderr)]
use millpath::geom::Point3;
use millpath::io::{ImportSettings, read_outline_file};
use millpath::job::pocket::PocketSettings;
use millpath::machine::Machine;
use millpath::stock::{SimOptions, StockSpec, entry_moves, simulate};
use millpath::strategy::pocket::{PocketShape, StrategyKind, nominal_engagement, toolpath};
use millpath::toolpath::MoveKind;

const CLASSES: [&str; 7] = [
    "rapid",
    "entry",
    "cut",
    "light",
    "empty<2D",
    "empty 2-10D",
    "empty>10D",
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(f) = args.first() else {
        eprintln!("usage: adaptive_air FILE|aero");
        std::process::exit(2);
    };
    let mut set = PocketSettings {
        strategy: "adaptive".into(),
        ..PocketSettings::default()
    };
    set.apply_strategy_defaults();
    if let Ok(s) = std::env::var("STEP") {
        set.stepover = s;
    }
    let list_runs = std::env::var("RUNS").is_ok();
    let (tool, opts) = set.options().expect("the options");
    let machine = Machine::preset("hsm").expect("the hsm preset");
    let pockets: Vec<(millpath::geom::Outline, Vec<millpath::geom::Outline>)> = if f == "aero" {
        let a = millpath::strategy::pocket::builtin::aerospace_pocket();
        vec![(a.outer.clone(), a.islands.clone())]
    } else {
        let (loops, _) = read_outline_file(f, &ImportSettings::default()).expect("a drawing");
        loops
            .pockets()
            .into_iter()
            .map(|p| (p.outer, p.islands))
            .collect()
    };
    let d = tool.diameter;
    let nominal = nominal_engagement(opts.stepover_mm(&tool), tool.radius()).to_degrees();
    let mut all = [0.0f64; 7];
    for (k, (outer, islands)) in pockets.into_iter().enumerate() {
        let Ok(shape) = PocketShape::new(outer, islands, "f") else {
            continue;
        };
        let Ok(tp) = toolpath(StrategyKind::Adaptive, &shape, &tool, &opts) else {
            continue;
        };
        let spec = StockSpec {
            outer: &shape.outer,
            islands: &shape.islands,
            wall_stock: 0.0,
        };
        let sim = simulate(&tp, spec, nominal, &SimOptions::default());
        let entry = entry_moves(&tp);
        let plan = millpath::motion::plan_toolpath(&tp, &machine).expect("a plan");
        let mut time = vec![0.0; tp.moves.len()];
        for b in &plan.blocks {
            if let Some(t) = time.get_mut(b.origin) {
                *t += b.time;
            }
        }
        let segs: Vec<(Point3, Point3)> = tp.segments().map(|(a, m)| (a, m.to)).collect();
        let mut class = Vec::with_capacity(segs.len());
        let mut len = Vec::with_capacity(segs.len());
        for (i, ((from, m), e)) in tp.segments().zip(&sim.per_move).enumerate() {
            let l = m.length_from(from);
            let removed = e.map_or(0.0, |e| e.removed_mm2);
            len.push(l);
            class.push(if matches!(m.kind, MoveKind::Rapid) {
                0
            } else if entry[i] {
                1
            } else if removed > 0.02 * d * l {
                2
            } else if removed > 0.002 * d * l {
                3
            } else {
                4
            });
        }
        let heading = |i: usize| {
            let (a, b) = segs[i];
            (b.y - a.y).atan2(b.x - a.x)
        };
        let turn = |i: usize, j: usize| {
            let t = (heading(j) - heading(i)).to_degrees().rem_euclid(360.0);
            if t > 180.0 { 360.0 - t } else { t }
        };
        let mut t = [0.0f64; 7];
        let mut runs = 0;
        let mut i = 0;
        while i < class.len() {
            if class[i] != 4 {
                t[class[i]] += time[i];
                i += 1;
                continue;
            }
            let first = i;
            let (mut run_len, mut run_time) = (0.0, 0.0);
            while i < class.len() && class[i] == 4 {
                run_len += len[i];
                run_time += time[i];
                i += 1;
            }
            runs += 1;
            t[if run_len < 2.0 * d {
                4
            } else if run_len < 10.0 * d {
                5
            } else {
                6
            }] += run_time;
            if list_runs {
                let into = first.checked_sub(1).map_or(-1.0, |p| turn(p, first));
                let out = if i < segs.len() { turn(i - 1, i) } else { -1.0 };
                println!(
                    "  run {:.3} s {:.1} mm {} moves from {} straight {:.1} mm turns {:.0}° {:.0}°",
                    run_time,
                    run_len,
                    i - first,
                    first,
                    segs[first].0.distance(segs[i - 1].1),
                    into,
                    out
                );
            }
        }
        let total: f64 = time.iter().sum();
        let parts: Vec<String> = CLASSES
            .iter()
            .zip(t)
            .map(|(c, v)| format!("{c} {v:.1}"))
            .collect();
        println!(
            "pocket {} {total:.1} s: {} ({runs} empty runs)",
            k + 1,
            parts.join(", ")
        );
        for (a, v) in all.iter_mut().zip(t) {
            *a += v;
        }
    }
    let parts: Vec<String> = CLASSES
        .iter()
        .zip(all)
        .map(|(c, v)| format!("{c} {v:.1}"))
        .collect();
    println!("all: {}", parts.join(", "));
}
