//! Diagnostic: adaptive clearing on every pocket of the suite, one line each (time, verdict).

use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, builtin};
use millpath::toolpath::Tool;

fn main() {
    let only = std::env::args().nth(1);
    for s in builtin::shape_suite() {
        if only.as_deref().is_some_and(|o| o != s.name) {
            continue;
        }
        let tool = Tool::flat(s.tool_diameter).unwrap();
        let opts = PocketOptions::default().with_depth(3.0).with_step_down(3.0);
        if let Ok(n) = std::env::var("DUMP").map(|v| v.parse::<usize>().unwrap()) {
            let tp = pocket::toolpath(StrategyKind::Adaptive, &s.shape, &tool, &opts).unwrap();
            for k in n.saturating_sub(4)..(n + 3).min(tp.moves.len()) {
                println!("{k}: {:?}", tp.moves[k]);
            }
        }
        let t = std::time::Instant::now();
        let r = pocket::generate(StrategyKind::Adaptive, &s.shape, &tool, &opts, &SimOptions::default());
        let dt = t.elapsed().as_secs_f64();
        match r {
            Ok(r) => println!(
                "{}: {:.2} s, {} moves, max {:.1}° mean {:.1}° (nominal {:.1})",
                s.name,
                dt,
                r.toolpath.moves.len(),
                r.verification.max_engagement_deg,
                r.verification.mean_engagement_deg,
                r.nominal_engagement_deg
            ),
            Err(e) => println!("{}: {dt:.2} s, ERROR {e}", s.name),
        }
    }
}
