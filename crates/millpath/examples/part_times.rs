//! Diagnostic: cycle time per pocket of the sample part, the three strategies side by side.
//! `cargo run --release --example part_times`
#![allow(clippy::print_stdout)]
use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, builtin};
use millpath::toolpath::Tool;

fn main() {
    let tool = Tool::flat(12.7).expect("tool");
    let opts = PocketOptions::default()
        .with_depth(12.7)
        .with_step_down(6.35);
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    let machine = Machine::preset("hsm").expect("hsm");
    for (name, shape) in builtin::structural_part() {
        let mut row = format!("{name:24}");
        for kind in [
            StrategyKind::Zigzag,
            StrategyKind::Offset,
            StrategyKind::Spiral,
        ] {
            let r = pocket::generate(kind, &shape, &tool, &opts, &sim).expect("pocket");
            let t = plan_toolpath(&r.toolpath, &machine)
                .expect("plan")
                .total_time();
            row.push_str(&format!(
                " {kind:?} {t:6.1} s {:5.1}% |",
                100.0 * r.verification.share_above_nominal
            ));
        }
        println!("{row}");
    }
}
