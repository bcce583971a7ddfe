//! The three roughing strategies side by side on the shape suite (`samples::shape_suite`):
//! path length, mean engagement, verification, cycle time on `hsm` and on a profile with
//! LinuxCNC's limits (500 mm/s, 2000 mm/s², jerk unlimited, 1 ms), one 5 mm level at
//! 600 in/min, with and without feed modulation. With a directory argument, each program is
//! also written there (`G64 P0.01` stated) for `../shared/tools/linuxcnc-time`.
//!
//! `cargo run --release --example strategy_table [-- OUT_DIR]`
#![allow(clippy::print_stdout)]
use millpath::gcode::{WriterOptions, write_program};
use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, samples};
use millpath::toolpath::Tool;

const LINUXCNC_LIMITS: &str = r#"
name = "linuxcnc-limits"
units = "mm"
max_feed = 500.0
path_tolerance = 0.01
ipo_cycle = 0.001
[axes.x]
max_velocity = 500.0
max_acceleration = 2000.0
max_jerk = "unlimited"
[axes.y]
max_velocity = 500.0
max_acceleration = 2000.0
max_jerk = "unlimited"
[axes.z]
max_velocity = 500.0
max_acceleration = 2000.0
max_jerk = "unlimited"
"#;

fn main() {
    let out_dir = std::env::args().nth(1);
    let hsm = Machine::preset("hsm").expect("hsm");
    let lc = Machine::from_toml_str(LINUXCNC_LIMITS, "linuxcnc limits").expect("profile");
    let sim = SimOptions {
        cell: 0.1,
        step: 0.2,
        ..SimOptions::default()
    };
    println!(
        "{:12} {:8} {:>4} {:>8} {:>6} {:>6} {:>8} {:>8} {:>7}",
        "pocket", "strategy", "mod", "path mm", "eng°", ">nom%", "hsm s", "lcnc s", "uncut"
    );
    for p in samples::shape_suite() {
        let tool = Tool::flat(p.tool_diameter).expect("tool");
        for modulate in [true, false] {
            let opts = PocketOptions {
                depth: 5.0,
                step_down: 5.0,
                modulate_feed: modulate,
                ..PocketOptions::default()
            };
            for kind in [
                StrategyKind::Spiral,
                StrategyKind::Offset,
                StrategyKind::Zigzag,
            ] {
                let r = match pocket::generate(kind, &p.shape, &tool, &opts, &sim) {
                    Ok(r) => r,
                    Err(e) => {
                        println!("{:12} {:8} {e}", p.name, kind.name());
                        continue;
                    }
                };
                let t_hsm = plan_toolpath(&r.toolpath, &hsm).expect("plan").total_time();
                let t_lc = plan_toolpath(&r.toolpath, &lc).expect("plan").total_time();
                let v = &r.verification;
                println!(
                    "{:12} {:8} {:>4} {:8.1} {:6.1} {:6.1} {:8.2} {:8.2} {:7.2}",
                    p.name,
                    kind.name(),
                    if modulate { "on" } else { "off" },
                    r.toolpath.cut_length(),
                    v.mean_engagement_deg,
                    100.0 * v.share_above_nominal,
                    t_hsm,
                    t_lc,
                    v.uncut_area_mm2,
                );
                if let Some(dir) = &out_dir {
                    let wopts = WriterOptions {
                        path_tolerance: Some(0.01),
                        ..WriterOptions::default()
                    };
                    let mut buf = Vec::new();
                    write_program(&r.toolpath, &wopts, &mut buf).expect("write");
                    let name = format!(
                        "{dir}/{}_{}_{}.ngc",
                        p.name.replace([' ', ':'], "_"),
                        kind.name(),
                        if modulate { "mod" } else { "flat" }
                    );
                    std::fs::write(&name, buf).expect("write file");
                }
            }
        }
    }
}
