//! `millpath calibrate`: a machine profile fitted to cycle times measured on the machine.

use super::{print, print_json};
use millpath::calibrate::{CalibrateOptions, ParamFit, calibrate, load};
use millpath::{Error, InputError};
use std::path::PathBuf;

/// Arguments of `millpath calibrate`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "TIMES.csv has the header `program,seconds` and one line per program, its path relative to the CSV:\n  program,seconds\n  parts/bracket.ngc,42.7\n\nExample:\n  millpath calibrate times.csv --machine linuxcnc-time -o my-mill.toml"
)]
pub struct Args {
    /// The measured cycle times: a CSV `program,seconds`, paths relative to it.
    pub times: PathBuf,
    /// The starting profile (a preset name or a TOML profile); its controller model, feeds,
    /// velocities and rapids are kept.
    #[arg(long, default_value = "hsm")]
    pub machine: String,
    /// Where to write the fitted profile (TOML).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Name of the fitted machine (default: the start's name with `-fitted`).
    #[arg(long)]
    pub name: Option<String>,
    /// Print the result as JSON.
    #[arg(long)]
    pub json: bool,
}

fn show(p: ParamFit, unit: &str) -> String {
    match p {
        ParamFit::Fitted { value } => format!("{value:.6} {unit} (fitted)"),
        ParamFit::Kept { value } => {
            format!("{value:.6} {unit} (kept: no program's time depends on it)")
        }
        ParamFit::NotApplicable => "unlimited (kept)".into(),
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let start = super::load_machine(&args.machine)?;
    if args.output.as_os_str().is_empty() {
        return Err(InputError::new("output", "")
            .at("-o")
            .expected("a file name for the fitted profile")
            .into());
    }
    let programs = load(&args.times, &start)?;
    let fit = calibrate(&start, &programs, &CalibrateOptions::default())?;
    let mut machine = fit.machine.clone();
    machine.name = args
        .name
        .clone()
        .unwrap_or_else(|| format!("{}-fitted", start.name));
    let toml = format!(
        "# fitted by `millpath calibrate {}` from `{}`\n{}",
        args.times.display(),
        start.name,
        machine.to_toml()
    );
    millpath::io::write_atomic(&args.output, toml.as_bytes())?;
    let errs: Vec<f64> = fit.residuals.iter().map(|r| r.error().abs()).collect();
    let mean = errs.iter().sum::<f64>() / errs.len() as f64;
    let max = errs.iter().copied().fold(0.0, f64::max);
    if args.json {
        return print_json(&serde_json::json!({
            "machine": machine.name,
            "controller": machine.controller.name(),
            "output": args.output.display().to_string(),
            "acceleration_mm_s2": fit.acceleration,
            "jerk_mm_s3": fit.jerk,
            "path_tolerance_mm": fit.tolerance,
            "ipo_cycle_s": fit.ipo_cycle,
            "residuals": fit.residuals.iter().map(|r| serde_json::json!({
                "program": r.program, "measured_s": r.measured, "fitted_s": r.fitted,
                "error": r.error()})).collect::<Vec<_>>(),
            "mean_abs_error": mean,
            "max_abs_error": max,
            "evaluations": fit.evaluations,
        }));
    }
    print(&format!(
        "fitted {} (controller {}) from {} programs, {} evaluations:",
        machine.name,
        machine.controller.name(),
        fit.residuals.len(),
        fit.evaluations
    ));
    print(&format!(
        "  acceleration   {}",
        show(fit.acceleration, "mm/s²")
    ));
    print(&format!("  jerk           {}", show(fit.jerk, "mm/s³")));
    print(&format!("  path tolerance {}", show(fit.tolerance, "mm")));
    print(&format!("  IPO cycle      {}", show(fit.ipo_cycle, "s")));
    for r in &fit.residuals {
        print(&format!(
            "  {}: measured {:.3} s, fitted {:.3} s ({:+.2} %)",
            r.program,
            r.measured,
            r.fitted,
            100.0 * r.error()
        ));
    }
    print(&format!(
        "mean |error| {:.2} %, max {:.2} %; profile written to {}",
        100.0 * mean,
        100.0 * max,
        args.output.display()
    ));
    Ok(())
}
