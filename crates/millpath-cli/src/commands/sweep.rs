//! `millpath sweep`.

/// Arguments of `millpath sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("sweep: not implemented yet"))
}
