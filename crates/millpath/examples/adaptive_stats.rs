//! Diagnostic: where an adaptive level's length goes, binned by the measured engagement, and
//! the moves with the highest engagement (entries aside).
//! `cargo run --release --example adaptive_stats -- [stepover] [out.svg]`; `SHAPE=dumbbell`
//! takes a pocket of the suite instead of the aerospace pocket (one 3 mm level), `FILE=F
//! POCKET=K D=d` the K-th pocket of a drawing with a tool of diameter d,
//! `KIND=spiral` the spiral instead of adaptive, `BOUND=0.4` the stepover whose straight cut
//! sets the nominal engagement (default: the stepover).
#![allow(clippy::print_stdout)]
use millpath::stock::StockSpec;
use millpath::stock::{SimOptions, simulate};
use millpath::strategy::pocket::{
    PocketOptions, StrategyKind, builtin, nominal_engagement, toolpath,
};
use millpath::toolpath::{MoveKind, Tool};
use std::fmt::Write as _;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let step: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(0.4);
    let (shape, d) = match std::env::var("SHAPE") {
        Ok(name) => builtin::shape_suite()
            .into_iter()
            .find(|s| s.name == name)
            .map(|s| (s.shape, s.tool_diameter))
            .expect("a shape of the suite"),
        Err(_) => match std::env::var("FILE") {
            Ok(f) => {
                let (loops, _) =
                    millpath::io::read_outline_file(&f, &millpath::io::ImportSettings::default())
                        .expect("a drawing");
                let k: usize = std::env::var("POCKET")
                    .ok()
                    .and_then(|s| s.parse().ok())
                    .unwrap_or(1);
                let p = loops.pockets().into_iter().nth(k - 1).expect("pocket");
                let d: f64 = std::env::var("D")
                    .ok()
                    .and_then(|s| s.parse().ok())
                    .expect("D, the tool diameter");
                let shape = millpath::strategy::pocket::PocketShape::new(p.outer, p.islands, "f")
                    .expect("shape");
                (shape, d)
            }
            Err(_) => (builtin::aerospace_pocket(), 12.7),
        },
    };
    let tool = Tool::flat(d).expect("tool");
    let kind = match std::env::var("KIND").as_deref() {
        Ok("spiral") => StrategyKind::Spiral,
        _ => StrategyKind::Adaptive,
    };
    let bound: f64 = std::env::var("BOUND")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(step);
    // `DEPTH=25 HELIX=5.715`: the CLI's defaults for a 12.7 mm tool (one 25 mm level, a
    // helix of 0.45 D), to see what `millpath pocket --strategy adaptive` plans.
    let env = |k: &str| std::env::var(k).ok().and_then(|s| s.parse::<f64>().ok());
    let depth = env("DEPTH").unwrap_or(3.0);
    let mut opts = PocketOptions::default()
        .with_depth(depth)
        .with_step_down(depth)
        .with_stepover(millpath::strategy::pocket::Stepover::Fraction(step))
        .with_both_ways(std::env::var("BOTH").is_ok());
    if let Some(radius) = env("HELIX") {
        opts = opts.with_entry(millpath::strategy::pocket::Entry::Helix {
            radius,
            ramp_angle: 3f64.to_radians(),
        });
    }
    let tp = toolpath(kind, &shape, &tool, &opts).expect("toolpath");
    let s = bound * tool.diameter;
    let nominal = nominal_engagement(s, tool.radius()).to_degrees();
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
    let st = millpath::stock::engagement_stats(&tp, &sim.samples, 1.1 * nominal);
    println!(
        "cut {:.0} mm, mean {:.1}°, p99 {:.1}°, max {:.1}° ({:.2} ×), {:.2} % above 1.1 ×",
        st.cutting_mm,
        st.mean_deg,
        st.p99_deg,
        st.max_deg,
        st.max_deg / nominal,
        100.0 * st.share_above_bound
    );
    let entry = millpath::stock::entry_moves(&tp);
    let mut top: Vec<(f64, usize)> = sim
        .samples
        .iter()
        .filter(|x| !entry.get(x.move_index).copied().unwrap_or(false))
        .map(|x| (x.angle.to_degrees(), x.move_index))
        .collect();
    top.sort_by(|a, b| b.0.total_cmp(&a.0));
    top.dedup_by_key(|t| t.1);
    if let (Ok(ctx), Some(&(_, k))) = (std::env::var("CONTEXT"), top.first()) {
        // The moves round the largest: `CONTEXT=n` of them either side.
        let n: usize = ctx.parse().unwrap_or(3);
        for x in sim.samples.iter().filter(|x| x.move_index == k) {
            println!("    sample at {:.3} mm: {:.1}°", x.at, x.angle.to_degrees());
        }
        for j in k.saturating_sub(n)..(k + n + 1).min(tp.moves.len()) {
            let m = &tp.moves[j];
            println!(
                "    move {j}: to ({:.3}, {:.3}, {:.3}) {:?}",
                m.to.x, m.to.y, m.to.z, m.kind
            );
        }
    }
    for (deg, k) in top.iter().take(6) {
        let from = if *k > 0 { tp.moves[k - 1].to } else { tp.start };
        println!(
            "  {deg:.1}° on move {k} of {} ({:.2}, {:.2}) -> ({:.2}, {:.2}), {:?}",
            tp.moves.len(),
            from.x,
            from.y,
            tp.moves[*k].to.x,
            tp.moves[*k].to.y,
            tp.moves[*k].kind
        );
    }
    let z0 = tp.levels.first().map_or(0.0, |l| l.z);
    let edges = [0.5, 20.0, 40.0, 60.0, 70.0, 80.0, 90.0, 1000.0];
    let mut bins = [0.0; 8];
    let mut prev = tp.start;
    let mut svg = String::new();
    for (m, e) in tp.moves.iter().zip(&sim.per_move) {
        let from = prev;
        prev = m.to;
        if (m.to.z - z0).abs() > 1e-6
            || (from.z - z0).abs() > 1e-6
            || matches!(m.kind, MoveKind::Rapid)
        {
            continue;
        }
        let ang = e.as_ref().map_or(0.0, |e| e.max_angle.to_degrees());
        let len = m.length_from(from);
        let b = edges.iter().position(|&x| ang < x).unwrap_or(7);
        bins[b] += len;
        let col = [
            "#ccc", "#88f", "#44f", "#00a", "#080", "#0c0", "#f80", "red",
        ][b];
        let _ = writeln!(
            svg,
            "<line x1='{:.3}' y1='{:.3}' x2='{:.3}' y2='{:.3}' stroke='{col}' stroke-width='0.4'/>",
            from.x, from.y, m.to.x, m.to.y
        );
    }
    let total: f64 = bins.iter().sum();
    println!("nominal {nominal:.1}°, level path {total:.0} mm");
    let mut lo = 0.0;
    for (k, b) in bins.iter().enumerate() {
        println!("  {lo:>5.1}..{:>6.1}°: {b:>7.0} mm", edges[k]);
        lo = edges[k];
    }
    if let Some(out) = args.get(2) {
        let b = shape.outer.bounds();
        let doc = format!(
            "<svg xmlns='http://www.w3.org/2000/svg' width='1500' height='1000' viewBox='{:.3} {:.3} {:.3} {:.3}'><g transform='scale(1,-1)'>{svg}</g></svg>",
            b.min.x - 2.0,
            -b.max.y - 2.0,
            b.width() + 4.0,
            b.height() + 4.0
        );
        std::fs::write(out, doc).expect("write");
    }
}
