//! `millpath`: the command-line tool over the millpath engine.
//!
//! Exit codes: 0 success, 1 internal error (a bug: please report it), 2 bad input.
//!
//! Every subcommand accepts negative numbers as flag values (`--angle -30`, not only
//! `--angle=-30`): [`command`] sets clap's `allow_negative_numbers` on each of them. No flag
//! is a dash followed by a digit, so nothing becomes ambiguous.

mod commands;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
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
    /// Rewrite a LinuxCNC program's feeds to what the joints allow, kept when it runs faster.
    Optimize(commands::optimize::Args),
    /// Fit a machine profile to cycle times measured on the machine.
    Calibrate(commands::calibrate::Args),
    /// 2.5D pocket roughing: zigzag, contour-offset or adaptive spiral.
    Pocket(commands::pocket::Args),
    /// A drawing's circles drilled with canned cycles or helix-bored, in a short order.
    Drill(commands::drill::Args),
    /// Cut a drawing's outlines out: outside, inside or on the line, with leads and tabs.
    Profile(commands::profile::Args),
    /// A whole part from a job file: face, pockets, holes, profile with tabs, several tools.
    Job(commands::job::Args),
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
#[command(
    after_help = "Examples:\n  millpath completions bash > ~/.local/share/bash-completion/completions/millpath\n  millpath completions zsh > ~/.zfunc/_millpath"
)]
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
    let cli = match command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        // Usage errors are bad input (exit 2, clap's own convention too); --help and
        // --version print and exit 0.
        Err(e) => e.exit(),
    };
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

/// The clap command with `allow_negative_numbers` on every subcommand.
fn command() -> clap::Command {
    let mut cmd = Cli::command();
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|c| c.get_name().to_owned())
        .collect();
    for name in names {
        cmd = cmd.mut_subcommand(name, |c| c.allow_negative_numbers(true));
    }
    cmd
}

fn run(cli: Cli) -> Result<(), millpath::Error> {
    match cli.command {
        Command::Demo(a) => commands::demo::run(&a),
        Command::Contour(a) => commands::contour::run(&a),
        Command::Estimate(a) => commands::estimate::run(&a),
        Command::Machines(a) => commands::machines::run(&a),
        Command::Optimize(a) => commands::optimize::run(&a),
        Command::Calibrate(a) => commands::calibrate::run(&a),
        Command::Pocket(a) => commands::pocket::run(&a),
        Command::Drill(a) => commands::drill::run(&a),
        Command::Profile(a) => commands::profile::run(&a),
        Command::Job(a) => commands::job::run(&a),
        Command::Verify(a) => commands::verify::run(&a),
        Command::Sweep(a) => commands::sweep::run(&a),
        Command::FiveAxis(a) => commands::five_axis::run(&a),
        Command::Completions(a) => {
            let mut cmd = command();
            clap_complete::generate(a.shell, &mut cmd, "millpath", &mut std::io::stdout());
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_has_an_example_and_the_cli_is_consistent() {
        let cmd = command();
        cmd.clone().debug_assert();
        for sub in cmd.get_subcommands() {
            let help = sub
                .get_after_help()
                .map(ToString::to_string)
                .unwrap_or_default();
            assert!(
                help.contains("Example") && help.contains(&format!("millpath {}", sub.get_name())),
                "`millpath {} --help` has no example: {help:?}",
                sub.get_name()
            );
        }
    }

    #[test]
    fn negative_numbers_parse_as_values() {
        let m = command()
            .try_get_matches_from(["millpath", "pocket", "sample:aerospace", "--angle", "-30"])
            .unwrap();
        let cli = Cli::from_arg_matches(&m).unwrap();
        let Command::Pocket(a) = cli.command else {
            panic!("not pocket")
        };
        assert!((a.common.angle + 30.0).abs() < 1e-12, "{}", a.common.angle);
    }

    #[test]
    fn machine_flag_on_every_command_with_a_cycle_time() {
        // One shared flag name and meaning: a preset or a TOML profile (five-axis takes a
        // kinematic chain and is documented apart).
        let cmd = command();
        for name in [
            "demo", "contour", "estimate", "pocket", "profile", "sweep", "drill",
        ] {
            let sub = cmd.find_subcommand(name).unwrap();
            assert!(
                sub.get_arguments().any(|a| a.get_long() == Some("machine")),
                "{name} lacks --machine"
            );
        }
        for name in [
            "demo",
            "contour",
            "estimate",
            "machines",
            "verify",
            "sweep",
            "five-axis",
            "pocket",
            "drill",
            "profile",
        ] {
            let sub = cmd.find_subcommand(name).unwrap();
            assert!(
                sub.get_arguments().any(|a| a.get_long() == Some("json")),
                "{name} lacks --json"
            );
        }
    }
}
