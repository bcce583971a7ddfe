//! `millpath pocket`.

/// Arguments of `millpath pocket`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("pocket: not implemented yet"))
}
