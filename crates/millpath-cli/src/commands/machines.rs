//! `millpath machines`.

/// Arguments of `millpath machines`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("machines: not implemented yet"))
}
