//! Diagnostic: which morph the spiral takes on each pocket of the sample part, and its laps.
//! `cargo run --release --example spiral_stats`
#![allow(clippy::print_stdout)]
use millpath::strategy::pocket::{PocketOptions, builtin, spiral_with_stats};
use millpath::toolpath::Tool;

fn main() {
    let tool = Tool::flat(12.7).expect("tool");
    let opts = PocketOptions::default();
    let mut all = builtin::structural_part();
    all.push(("aerospace".into(), builtin::aerospace_pocket()));
    for (name, shape) in all {
        match spiral_with_stats(&shape, &tool, &opts) {
            Ok((plan, st)) => {
                let len: f64 = plan
                    .cuts
                    .iter()
                    .flat_map(|c| c.path.iter())
                    .map(|s| s.length())
                    .sum();
                let b = shape.outer.bounds();
                println!(
                    "{name}: {:.0}x{:.0} mm, length {len:.0} mm, {st:?}",
                    b.width(),
                    b.height()
                );
            }
            Err(e) => println!("{name}: {e}"),
        }
    }
}
