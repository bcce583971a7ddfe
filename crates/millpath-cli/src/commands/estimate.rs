//! `millpath estimate`.

/// Arguments of `millpath estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("estimate: not implemented yet"))
}
