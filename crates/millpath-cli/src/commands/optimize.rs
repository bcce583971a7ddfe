//! `millpath optimize`: a LinuxCNC program's runs of straight blocks merged within a
//! tolerance and its straight feed blocks rewritten in inverse time at what the machine's
//! joints allow, kept when the machine's controller model runs it faster.

use super::print;
use millpath::job::optimize::{MergeTolerance, OptimizeOptions, optimize_text};
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Arguments of `millpath optimize`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath optimize part.ngc --machine linuxcnc-time -o faster.ngc\n  millpath optimize part.ngc --machine my_mill.toml -o faster.ngc --json"
)]
pub struct Args {
    /// The LinuxCNC program.
    pub file: PathBuf,
    /// A preset name (see `millpath machines`) or a TOML machine profile.
    #[arg(long, default_value = "linuxcnc-time")]
    pub machine: String,
    /// Where to write the program (the input's text when nothing is gained).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Also write the inverse-time rewrite here, kept or not (to run it on the controller).
    #[arg(long)]
    pub rewrite: Option<PathBuf>,
    /// Print a JSON object (before, after, outcome) on stdout.
    #[arg(long)]
    pub json: bool,
    /// Merge consecutive straight blocks whose end points lie within this distance of one
    /// chord, mm (a block's `G64 P` where smaller).
    #[arg(long, default_value_t = 0.001)]
    pub tolerance: f64,
    /// The same for each rotary axis, degrees.
    #[arg(long, default_value_t = 0.001)]
    pub tolerance_deg: f64,
    /// Keep every block: only the feed words are rewritten.
    #[arg(long)]
    pub no_merge: bool,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let machine = super::load_machine(&args.machine)?;
    let text = std::fs::read_to_string(&args.file).map_err(|e| {
        Error::from(
            InputError::new("input file", args.file.display())
                .expected(format!("a readable G-code file ({e})")),
        )
    })?;
    let origin = args.file.display().to_string();
    for (flag, v) in [
        ("--tolerance", args.tolerance),
        ("--tolerance-deg", args.tolerance_deg),
    ] {
        if !(v.is_finite() && v > 0.0 && v <= 1.0) {
            return Err(InputError::new(flag, v)
                .expected("a tolerance > 0 and at most 1 (mm or degrees)")
                .into());
        }
    }
    let merge = (!args.no_merge).then(|| MergeTolerance {
        mm: args.tolerance,
        rad: args.tolerance_deg.to_radians(),
    });
    let opts = OptimizeOptions::default().with_merge(merge);
    let opt = optimize_text(&text, &origin, &machine, &opts)?;
    millpath::io::write_atomic(&args.output, opt.text.as_bytes())?;
    if let Some(path) = &args.rewrite {
        millpath::io::write_atomic(path, opt.rewrite.as_bytes())?;
    }
    if args.json {
        let v = serde_json::json!({
            "before": opt.before,
            "after": opt.after,
            "rewritten_blocks": opt.rewritten_blocks,
            "merged_blocks": opt.merged_blocks,
            "outcome": opt.outcome.to_string(),
            "kept_rewrite": opt.text == opt.rewrite,
        });
        print(&serde_json::to_string_pretty(&v).map_err(|e| Error::internal(e.to_string()))?);
    } else {
        print(&format!(
            "before {:.3} s, rewrite {:.3} s ({} blocks in inverse time, {} merged into the \
             block after them): {}",
            opt.before.cycle_time_s,
            opt.after.cycle_time_s,
            opt.rewritten_blocks,
            opt.merged_blocks,
            opt.outcome
        ));
    }
    Ok(())
}
