//! One module per subcommand, each thin over the engine.

pub mod contour;
pub mod demo;
pub mod estimate;
pub mod five_axis;
pub mod html;
pub mod machines;
pub mod pocket;
pub mod sweep;
pub mod verify;

use millpath::{Error, InputError};
use std::io::Write;
use std::path::Path;

/// Prints a line on stdout (the engine never prints; the CLI does, here).
pub fn print(line: &str) {
    let _ = writeln!(std::io::stdout(), "{line}");
}

/// Prints a line on stderr.
pub fn eprint(line: &str) {
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// Reads a whole text file, turning an I/O failure into an input error naming the file.
#[allow(dead_code)] // used by the input-reading commands as they land
pub fn read_text(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path).map_err(|e| {
        Error::Input(
            InputError::new("input file", path.display())
                .expected(format!("a readable text file ({e})")),
        )
    })
}
