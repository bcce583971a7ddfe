//! Diagnostic: the aerospace pocket's first level coloured by engagement (red above nominal).
//! `cargo run --release --example engagement_map -- spiral out.svg`
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
    let kind = match args.get(1).map(String::as_str) {
        Some("offset") => StrategyKind::Offset,
        Some("zigzag") => StrategyKind::Zigzag,
        _ => StrategyKind::Spiral,
    };
    let out = args.get(2).cloned().unwrap_or_else(|| "eng.svg".into());
    let shape = match args.get(3) {
        Some(name) => builtin::structural_part()
            .into_iter()
            .find(|(n, _)| n.starts_with(name.as_str()))
            .map(|(_, s)| s)
            .expect("pocket name"),
        None => builtin::aerospace_pocket(),
    };
    let tool = Tool::flat(12.7).expect("tool");
    let mut opts = PocketOptions::default();
    if let Some(c) = std::env::var("MILLPATH_C")
        .ok()
        .and_then(|c| c.parse().ok())
    {
        opts.spiral.transition = c;
    }
    let tp = toolpath(kind, &shape, &tool, &opts).expect("toolpath");
    let s = opts.stepover_mm(&tool);
    let nominal = nominal_engagement(s, tool.radius());
    let spec = StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock: 0.0,
    };
    let sim = simulate(&tp, spec, nominal.to_degrees(), &SimOptions::default());
    let z0 = tp.levels.first().map_or(0.0, |l| l.z);
    let mut svg = String::from(
        "<svg xmlns='http://www.w3.org/2000/svg' width='1600' height='1100' viewBox='{vb}'><g transform='scale(1,-1)'>",
    );
    let mut prev = tp.start;
    let (mut above, mut total) = (0.0, 0.0);
    for (m, e) in tp.moves.iter().zip(&sim.per_move) {
        let from = prev;
        prev = m.to;
        if (m.to.z - z0).abs() > 1e-6
            || (from.z - z0).abs() > 1e-6
            || matches!(m.kind, MoveKind::Rapid)
        {
            continue;
        }
        let (col, ang) = match e {
            Some(e) if e.max_angle > nominal + 1e-9 => ("red", e.max_angle.to_degrees()),
            Some(e) => ("black", e.max_angle.to_degrees()),
            None => ("#aaa", 0.0),
        };
        let len = m.length_from(from);
        total += len;
        if col == "red" {
            above += len;
        }
        let _ = writeln!(
            svg,
            "<line x1='{:.3}' y1='{:.3}' x2='{:.3}' y2='{:.3}' stroke='{col}' stroke-width='0.25'><title>{ang:.1}</title></line>",
            from.x, from.y, m.to.x, m.to.y
        );
    }
    svg.push_str("</g></svg>");
    let b = shape.outer.bounds();
    let vb = format!(
        "{:.3} {:.3} {:.3} {:.3}",
        b.min.x - 2.0,
        -b.max.y - 2.0,
        b.width() + 4.0,
        b.height() + 4.0
    );
    let svg = svg.replace("{vb}", &vb);
    std::fs::write(&out, svg).expect("write");
    println!(
        "level 1: {:.0} mm cut, {:.0} mm above nominal ({:.1}%), whole: {:.1}%",
        total,
        above,
        100.0 * above / total.max(1e-9),
        100.0 * sim.share_above_nominal
    );
}
