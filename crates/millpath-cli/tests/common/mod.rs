//! What the CLI tests share: running the binary and reading its output.

#![allow(dead_code)] // each test binary uses its own share of these

use std::path::Path;
use std::process::{Command, Output};

/// Runs `millpath ARGS` in `dir`.
pub fn millpath(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_millpath"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the millpath binary runs")
}

/// The standard error of a run, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}
