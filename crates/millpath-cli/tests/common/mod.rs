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

/// The `cycle_time_s` of a successful run's JSON on stdout.
pub fn json_cycle_time(o: &Output) -> f64 {
    assert_eq!(o.status.code(), Some(0), "{}", stderr(o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    v["cycle_time_s"]
        .as_f64()
        .unwrap_or_else(|| panic!("no time in {v}"))
}

/// The path of a real drawing of `../shared/real-inputs/files/` (kept beside the clone).
pub fn real_input(name: &str) -> String {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(
        d.is_dir(),
        "the real inputs are missing: {} (CI keeps ../shared beside the clone)",
        d.display()
    );
    d.join(name).to_string_lossy().into_owned()
}
