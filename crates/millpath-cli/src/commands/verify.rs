//! `millpath verify`.

/// Arguments of `millpath verify`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("verify: not implemented yet"))
}
