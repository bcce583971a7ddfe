//! `millpath`: the command-line tool over the millpath engine.
//!
//! Exit codes: 0 success, 1 internal error (a bug: please report it), 2 bad input.

mod commands;

use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;

/// millpath: CAM toolpaths that cut faster, with a cycle time you can trust.
#[derive(Debug, Parser)]
#[command(name = "millpath", version, about, long_about = None, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run every capability on the built-in samples and write the results into `out/`.
    Demo(commands::demo::Args),
    /// Free-form contour: scattered points → closed C1 curve → fewest segments → offset → G-code.
    Contour(commands::contour::Args),
    /// Cycle time of a G-code program or toolpath under a machine's limits.
    Estimate(commands::estimate::Args),
    /// List the built-in machine presets and their limits.
    Machines(commands::machines::Args),
    /// 2.5D pocket roughing: zigzag, contour-offset or adaptive spiral.
    Pocket(commands::pocket::Args),
    /// Check a G-code program against an outline: gouges, uncut material, engagement.
    Verify(commands::verify::Args),
    /// Cycle time of the spiral against zigzag over transition ratios and feeds.
    Sweep(commands::sweep::Args),
    /// Five-axis minimum-time trajectory planning with deflection replanning.
    #[command(name = "five-axis")]
    FiveAxis(commands::five_axis::Args),
    /// Print shell completions for bash, zsh, fish, elvish or powershell.
    Completions(CompletionsArgs),
}

#[derive(Debug, clap::Args)]
struct CompletionsArgs {
    /// The shell.
    shell: clap_complete::Shell,
}

fn main() -> ExitCode {
    // A panic is a bug: report it as an internal error with exit code 1, never a backtrace.
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        let loc = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        commands::eprint(&format!(
            "internal error (a bug in millpath, please report it): {msg}{loc}"
        ));
    }));
    let cli = Cli::parse();
    let result = std::panic::catch_unwind(|| run(cli));
    match result {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            commands::eprint(&format!("error: {e}"));
            ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(1))
        }
        Err(_) => ExitCode::from(1),
    }
}

fn run(cli: Cli) -> Result<(), millpath::Error> {
    match cli.command {
        Command::Demo(a) => commands::demo::run(&a),
        Command::Contour(a) => commands::contour::run(&a),
        Command::Estimate(a) => commands::estimate::run(&a),
        Command::Machines(a) => commands::machines::run(&a),
        Command::Pocket(a) => commands::pocket::run(&a),
        Command::Verify(a) => commands::verify::run(&a),
        Command::Sweep(a) => commands::sweep::run(&a),
        Command::FiveAxis(a) => commands::five_axis::run(&a),
        Command::Completions(a) => {
            let mut cmd = Cli::command();
            clap_complete::generate(a.shell, &mut cmd, "millpath", &mut std::io::stdout());
            Ok(())
        }
    }
}
