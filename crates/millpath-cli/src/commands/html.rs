//! `--html OUT.html` for the commands: one self-contained report per run, built from the
//! engine's report pieces (`millpath::report`).

use millpath::Error;
use millpath::report::html::HtmlReport;
use std::path::Path;

pub use millpath::report::html::{machine_row, toolpath_report};

/// Writes `html` to `path` atomically.
pub fn write(path: &Path, html: &HtmlReport) -> Result<(), Error> {
    millpath::io::write_atomic(path, html.to_html().as_bytes())
}
