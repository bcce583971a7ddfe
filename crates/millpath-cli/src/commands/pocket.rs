//! `millpath pocket`.

/// Arguments of `millpath pocket`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs the command.
pub fn run(_args: &Args) -> Result<(), millpath::Error> {
    Err(millpath::Error::internal("pocket: not implemented yet"))
}

/// The demo's pocket rows: (program, cycle time s, blocks, verifier summary).
pub(crate) fn demo_rows(
    _out: &std::path::Path,
    _machine: &millpath::machine::Machine,
) -> Result<Vec<(String, f64, usize, String)>, millpath::Error> {
    Ok(Vec::new())
}
