//! `millpath five-axis`.

/// Arguments of `millpath five-axis`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("five-axis: not implemented yet"))
}
