//! Diagnostic: where an adaptive level's length goes, binned by the measured engagement.
//! `cargo run --release --example adaptive_stats -- [stepover] [out.svg]`
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
    let shape = builtin::aerospace_pocket();
    let tool = Tool::flat(12.7).expect("tool");
    let kind = match std::env::var("KIND").as_deref() {
        Ok("spiral") => StrategyKind::Spiral,
        _ => StrategyKind::Adaptive,
    };
    let bound: f64 = std::env::var("BOUND")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(step);
    let opts = PocketOptions::default()
        .with_depth(5.0)
        .with_step_down(5.0)
        .with_stepover(millpath::strategy::pocket::Stepover::Fraction(step));
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
