//! Diagnostic: where an adaptive program runs above 1.1 × its engagement, by the stock
//! simulation (entries aside). Each pocket of the drawing (or `aero`, the aerospace pocket)
//! is planned as `millpath pocket FILE --strategy adaptive` plans it at its defaults, then a
//! line per move above the bound: its ends, the length above and the largest angle.
//! `D=` (tool diameter), `STEP=` (stepover, as `--stepover`), `BOTH=1` (`--both-ways`);
//! `LIB=1` takes the library's options instead (3 mm, the 2.5 mm helix, 10 %, as the suite
//! in `tests/pocket_adaptive.rs`); `CSV=PREFIX` writes every sample (position, angle, entry,
//! move) to `PREFIX.N.csv` for pocket N.
//! `cargo run --release --example adaptive_hotspots -- FILE|aero [POCKET]`
#![allow(clippy::print_stdout)]
use millpath::io::{ImportSettings, read_outline_file};
use millpath::job::pocket::PocketSettings;
use millpath::stock::{SimOptions, StockSpec, engagement_stats, entry_moves, simulate};
use millpath::strategy::pocket::{PocketShape, StrategyKind, nominal_engagement, toolpath};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let f = &args[0];
    let only: Option<usize> = args.get(1).and_then(|s| s.parse().ok());
    let mut set = PocketSettings {
        strategy: "adaptive".into(),
        ..PocketSettings::default()
    };
    if let Ok(d) = std::env::var("D") {
        set.tool_diameter = d.parse().expect("D, a diameter in mm");
    }
    set.apply_strategy_defaults();
    if let Ok(s) = std::env::var("STEP") {
        set.stepover = s;
    }
    if std::env::var("BOTH").is_ok() {
        set.both_ways = true;
    }
    let (tool, mut opts) = set.options().expect("the options");
    if std::env::var("LIB").is_ok() {
        opts = millpath::strategy::pocket::PocketOptions::default()
            .with_depth(3.0)
            .with_step_down(3.0)
            .with_stepover(millpath::strategy::pocket::Stepover::Fraction(0.1))
            .with_both_ways(set.both_ways);
    }
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
    let s = opts.stepover_mm(&tool);
    let nominal = nominal_engagement(s, tool.radius()).to_degrees();
    for (k, (outer, islands)) in pockets.into_iter().enumerate() {
        if only.is_some_and(|o| o != k + 1) {
            continue;
        }
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
        let sim = simulate(
            &tp,
            spec,
            nominal,
            &SimOptions::default().with_record_samples(true),
        );
        let st = engagement_stats(&tp, &sim.samples, 1.1 * nominal);
        let entry = entry_moves(&tp);
        println!(
            "pocket {} cut {:.0} mm above {:.2}% max {:.1} nominal {:.1}",
            k + 1,
            st.cutting_mm,
            100.0 * st.share_above_bound,
            st.max_deg,
            nominal
        );
        // length above per move
        let mut last_at = std::collections::HashMap::new();
        let mut per: std::collections::BTreeMap<usize, (f64, f64)> = Default::default();
        for smp in &sim.samples {
            let prev = last_at.insert(smp.move_index, smp.at).unwrap_or(0.0);
            if entry[smp.move_index] {
                continue;
            }
            let a = smp.angle.to_degrees();
            if a > 1.1 * nominal {
                let e = per.entry(smp.move_index).or_insert((0.0, 0.0));
                e.0 += smp.at - prev;
                e.1 = e.1.max(a);
            }
        }
        let mut from = tp.start;
        let mut ends = Vec::new();
        for m in &tp.moves {
            ends.push((from, m.to, m.kind));
            from = m.to;
        }
        if let Ok(csv) = std::env::var("CSV") {
            let mut out = String::from("x,y,a,entry,move\n");
            for smp in &sim.samples {
                let (a, b, _) = ends[smp.move_index];
                let l = a.distance(b).max(1e-9);
                let t = (smp.at / l).min(1.0);
                out += &format!(
                    "{:.3},{:.3},{:.2},{},{}\n",
                    a.x + (b.x - a.x) * t,
                    a.y + (b.y - a.y) * t,
                    smp.angle.to_degrees(),
                    entry[smp.move_index] as u8,
                    smp.move_index
                );
            }
            std::fs::write(format!("{csv}.{}.csv", k + 1), out).expect("the CSV written");
        }
        for (i, (len, mx)) in per {
            let (a, b, kind) = ends[i];
            let prev = if i > 0 { ends[i - 1].2 } else { kind };
            println!(
                "  move {i} {:?} ({:.2},{:.2},{:.2})->({:.2},{:.2},{:.2}) len {:.2} above {:.2} max {:.1} prev {:?}",
                kind_name(kind),
                a.x,
                a.y,
                a.z,
                b.x,
                b.y,
                b.z,
                a.distance(b),
                len,
                mx,
                kind_name(prev)
            );
        }
    }
}

fn kind_name(k: millpath::toolpath::MoveKind) -> &'static str {
    match k {
        millpath::toolpath::MoveKind::Rapid => "G0",
        millpath::toolpath::MoveKind::Line => "G1",
        _ => "arc",
    }
}
