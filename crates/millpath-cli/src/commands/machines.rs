//! `millpath machines`: the built-in machine presets and their limits.

use super::print;
use millpath::machine::Machine;

/// Arguments of `millpath machines`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Example:\n  millpath machines --json")]
pub struct Args {
    /// Print the presets as JSON.
    #[arg(long)]
    pub json: bool,
}

fn fmt_j(j: f64) -> String {
    if j.is_finite() {
        format!("{j:.0}")
    } else {
        "unlimited".into()
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), millpath::Error> {
    let presets = Machine::presets();
    if args.json {
        let text = serde_json::to_string_pretty(&presets)
            .map_err(|e| millpath::Error::internal(format!("JSON: {e}")))?;
        print(&text);
        return Ok(());
    }
    for m in &presets {
        print(&format!("{} — {}", m.name, m.description));
        for (ax, name) in m.axes.iter().zip(["X", "Y", "Z"]) {
            print(&format!(
                "  {name}: v {:.1} mm/s, a {:.0} mm/s², j {} mm/s³",
                ax.max_velocity,
                ax.max_acceleration,
                fmt_j(ax.max_jerk)
            ));
        }
        print(&format!(
            "  max feed {:.2} mm/s, rapid {:.1}/{:.1}/{:.1} mm/s, path tolerance {} mm, IPO {} ms",
            m.max_feed,
            m.rapid[0],
            m.rapid[1],
            m.rapid[2],
            m.path_tolerance,
            m.ipo_cycle * 1e3
        ));
        print(&format!("  controller {}", m.controller.name()));
    }
    Ok(())
}
