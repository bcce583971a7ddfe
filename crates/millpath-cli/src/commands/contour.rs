//! `millpath contour`: the free-form contour pipeline.

use std::path::PathBuf;

/// Arguments of `millpath contour`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Points file (CSV `x,y` or JSON).
    pub points: PathBuf,
}

/// Runs the contour pipeline.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("contour: not implemented yet"))
}
