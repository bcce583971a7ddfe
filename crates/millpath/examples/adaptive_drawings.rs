//! Diagnostic: adaptive clearing on every pocket of drawings, its engagement measured by the
//! stock simulation with the entries aside (as `tests/pocket_adaptive.rs` measures the
//! suite): the share of the cutting length above 1.1 × the stepover's engagement and the
//! largest, per pocket. The tool is sized to the drawing as `cli_real_files` sizes it (a
//! tenth of the largest pocket's smaller side, from 0.5 to 10 mm); one level 3 mm deep
//! (at most the tool's diameter), entered by the CLI's helix (0.45 D).
//! The last column is the engagement the pocket's sharpest corner (or a neck the tool just
//! fits) forces on any program (`pocket::engagement_floor`), as a multiple of the
//! stepover's.
//! `cargo run --release --example adaptive_drawings -- [stepover] FILE...`
#![allow(clippy::print_stdout)]
use millpath::io::{ImportSettings, read_outline_file};
use millpath::stock::{SimOptions, StockSpec, engagement_stats, simulate};
use millpath::strategy::pocket::{
    PocketOptions, PocketShape, Stepover, StrategyKind, engagement_floor, nominal_engagement,
    toolpath,
};
use millpath::toolpath::Tool;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (step, files) = match args.first().and_then(|s| s.parse::<f64>().ok()) {
        Some(s) => (s, &args[1..]),
        None => (0.4, &args[..]),
    };
    println!("| drawing | pocket | tool | cut | p99 | max | above 1.1 × | corner floor |");
    println!("|---|---|---|---|---|---|---|---|");
    for f in files {
        let name = f.rsplit('/').next().unwrap_or(f);
        let loops = match read_outline_file(f, &ImportSettings::default()) {
            Ok((l, _)) => l,
            Err(e) => {
                println!("| {name} | – | – | not read: {e} | | | |");
                continue;
            }
        };
        let pockets = loops.pockets();
        let side = pockets
            .iter()
            .map(|p| {
                let b = p.outer.bounds();
                (b.max.x - b.min.x).min(b.max.y - b.min.y)
            })
            .fold(0.0, f64::max);
        let d = ((side / 10.0).clamp(0.5, 10.0) * 100.0).round() / 100.0;
        let tool = Tool::flat(d).expect("tool");
        let depth = d.min(3.0);
        // The entry as `millpath pocket` makes it: a helix of 0.45 D (the planner is
        // sensitive to where it starts; the library's default helix is 2.5 mm).
        let opts = PocketOptions::default()
            .with_depth(depth)
            .with_step_down(depth)
            .with_stepover(Stepover::Fraction(step))
            .with_entry(millpath::strategy::pocket::Entry::Helix {
                radius: millpath::job::pocket::DEFAULT_HELIX_RADIUS_PER_DIAMETER * d,
                ramp_angle: 3f64.to_radians(),
            });
        let nominal = nominal_engagement(step * d, 0.5 * d).to_degrees();
        for (k, p) in pockets.into_iter().enumerate() {
            let Ok(shape) = PocketShape::new(p.outer, p.islands, name) else {
                continue;
            };
            let tp = match toolpath(StrategyKind::Adaptive, &shape, &tool, &opts) {
                Ok(tp) => tp,
                Err(e) => {
                    let e: String = e.to_string().chars().take(60).collect();
                    println!("| {name} | {} | {d} | {} | | | |", k + 1, e);
                    continue;
                }
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
            let floor = engagement_floor(&shape, &tool, 0.0).to_degrees();
            println!(
                "| {name} | {} | {d} | {:.0} mm | {:.2} × | {:.2} × | {:.2} % | {:.2} × |",
                k + 1,
                st.cutting_mm,
                st.p99_deg / nominal,
                st.max_deg / nominal,
                100.0 * st.share_above_bound,
                floor / nominal
            );
        }
    }
}
