//! The three roughing strategies side by side on the shape suite (`builtin::shape_suite`):
//! path length, mean engagement, share above nominal, verification, and the cycle time on
//! `hsm` and on the `linuxcnc-time` machine (LinuxCNC's limits: 500 mm/s, 2000 mm/s², jerk
//! unlimited, 1 ms; planned with `G64 P0.01`, the tolerance the programs state), one 5 mm
//! level at 600 in/min, with and without feed modulation; each program made for the machine
//! it is timed on (the spiral's curvature ramps for `hsm`'s jerk limit, none for LinuxCNC's
//! trapezoidal planner, as `--machine` does). Prints tab-separated rows; with a
//! directory argument each program is also written there for
//! `../shared/tools/linuxcnc-time` (`tools/strategy_table.sh` runs both and prints the
//! table of BENCHMARKS.md).
//!
//! `cargo run --release --example strategy_table [-- OUT_DIR]`
#![allow(clippy::print_stdout)]
use millpath::gcode::{WriterOptions, write_program};
use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, builtin};
use millpath::toolpath::Tool;

/// The LinuxCNC judge's profile: 500 mm/s, 2000 mm/s², jerk unlimited, 1 ms.
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

/// The machine with LinuxCNC's limits: the `linuxcnc-time` preset where there is one (its
/// controller model), else the same limits on the generic planner; the programs' `G64 P0.01`.
fn linuxcnc_judge() -> Machine {
    let mut m = Machine::preset("linuxcnc-time")
        .or_else(|_| Machine::from_toml_str(LINUXCNC_LIMITS, "linuxcnc limits"))
        .expect("profile");
    m.path_tolerance = 0.01;
    m
}

fn main() {
    let out_dir = std::env::args().nth(1);
    let hsm = Machine::preset("hsm").expect("hsm");
    let lc = linuxcnc_judge();
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    println!(
        "pocket\tstrategy\tmodulation\tpath_mm\tmean_engagement_deg\tabove_nominal_pct\thsm_s\tlinuxcnc_model_s\tuncut_mm2\tproblems"
    );
    for p in builtin::shape_suite() {
        let tool = Tool::flat(p.tool_diameter).expect("tool");
        for modulate in [true, false] {
            let opts = PocketOptions::default()
                .with_depth(5.0)
                .with_step_down(5.0)
                .with_modulate_feed(modulate);
            for kind in [
                StrategyKind::Spiral,
                StrategyKind::Offset,
                StrategyKind::Zigzag,
            ] {
                let for_lc = opts.clone().with_curvature_ramps(false);
                let (r, r_lc) = match (
                    pocket::generate(kind, &p.shape, &tool, &opts, &sim),
                    pocket::generate(kind, &p.shape, &tool, &for_lc, &sim),
                ) {
                    (Ok(r), Ok(r_lc)) => (r, r_lc),
                    (Err(e), _) | (_, Err(e)) => {
                        println!("{}\t{}\t{modulate}\terror: {e}", p.name, kind.name());
                        continue;
                    }
                };
                let t_hsm = plan_toolpath(&r.toolpath, &hsm).expect("plan").total_time();
                let t_lc = plan_toolpath(&r_lc.toolpath, &lc)
                    .expect("plan")
                    .total_time();
                let v = &r.verification;
                println!(
                    "{}\t{}\t{}\t{:.1}\t{:.1}\t{:.1}\t{:.2}\t{:.2}\t{:.2}\t{}",
                    p.name,
                    kind.name(),
                    if modulate { "on" } else { "off" },
                    r.toolpath.cut_length(),
                    v.mean_engagement_deg,
                    100.0 * v.share_above_nominal,
                    t_hsm,
                    t_lc,
                    v.uncut_area_mm2,
                    millpath::stock::problems_text(&v.problems()),
                );
                if let Some(dir) = &out_dir {
                    let mut wopts = WriterOptions::default();
                    wopts.path_tolerance = Some(0.01);
                    let mut buf = Vec::new();
                    write_program(&r_lc.toolpath, &wopts, &mut buf).expect("write");
                    let name = format!(
                        "{dir}/{}_{}_{}.ngc",
                        p.name.replace([' ', ':'], "_"),
                        kind.name(),
                        if modulate { "on" } else { "off" }
                    );
                    std::fs::write(&name, buf).expect("write file");
                }
            }
        }
    }
}
