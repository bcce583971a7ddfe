//! LinuxCNC's standalone interpreter `rs274` (Debian package linuxcnc-uspace; `.ci/run`
//! installs it) as a verifier shared by the G-code and contour tests. When `rs274` is missing
//! the tests that call it FAIL, with an install message.

#![allow(dead_code)]

pub mod canon;

use std::io::Write;
use std::process::Command;

/// A HOME folder of this test process's own for rs274: LinuxCNC's tool data lives in a
/// memory-mapped `$HOME/.tool.mmap` shared by every rs274 running, so rs274 runs of other
/// processes (other test binaries, other clones) truncate each other's (SIGBUS).
fn private_home() -> &'static std::path::Path {
    static HOME: std::sync::OnceLock<tempfile::TempDir> = std::sync::OnceLock::new();
    HOME.get_or_init(|| tempfile::tempdir().unwrap()).path()
}

/// Runs rs274 on `text`; Ok(stdout) or Err(stderr).
pub fn rs274(text: &str) -> Result<String, String> {
    // rs274 instances running at the same time crash each other (status None seen when the
    // tests ran in parallel): one at a time.
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = ONE_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let mut file = tempfile::Builder::new().suffix(".ngc").tempfile().unwrap();
    file.write_all(text.as_bytes()).unwrap();
    file.flush().unwrap();
    let out = Command::new("rs274")
        .env("HOME", private_home())
        .arg("-g")
        .arg(file.path())
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run `rs274` ({e}): LinuxCNC's standalone interpreter is required for this \
             test; install the Debian package linuxcnc-uspace (CI does)"
            )
        });
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    // rs274 prints "executing" on stderr for every run; anything else is a message.
    let messages: Vec<&str> = stderr
        .lines()
        .filter(|l| l.trim() != "executing" && !l.trim().is_empty())
        .collect();
    if out.status.success() && messages.is_empty() {
        Ok(String::from_utf8_lossy(&out.stdout).to_string())
    } else {
        use std::os::unix::process::ExitStatusExt;
        Err(format!(
            "status {:?} (signal {:?}): {}",
            out.status.code(),
            out.status.signal(),
            messages.join("\n")
        ))
    }
}

/// What `rs274 -g` made of a program file.
pub struct Rs274Run {
    /// Exit status 0 and no message on stderr.
    pub ok: bool,
    /// The canonical calls (stdout).
    pub canon: String,
    /// The messages (stderr without its "executing" lines).
    pub messages: String,
}

/// Runs `rs274 -g FILE` in the file's folder (LinuxCNC finds subroutine files in the current
/// folder first), with an INI file `ini` and a tool table `tools` when given; killed after
/// `limit`.
pub fn rs274_file(
    file: &std::path::Path,
    ini: Option<&std::path::Path>,
    tools: Option<&std::path::Path>,
    limit: std::time::Duration,
) -> Rs274Run {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = ONE_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let dir = file.parent().unwrap();
    let mut cmd = Command::new("timeout");
    cmd.env("HOME", private_home());
    cmd.arg(format!("{}", limit.as_secs().max(1))).arg("rs274");
    if let Some(ini) = ini {
        cmd.arg("-i").arg(ini);
    }
    if let Some(t) = tools {
        cmd.arg("-t").arg(t);
    }
    let out = cmd
        .arg("-g")
        .arg(file.file_name().unwrap())
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run `rs274` ({e}): LinuxCNC's standalone interpreter is required for this \
             test; install the Debian package linuxcnc-uspace (CI does)"
            )
        });
    let stderr = String::from_utf8_lossy(&out.stderr);
    let messages: Vec<&str> = stderr
        .lines()
        .filter(|l| l.trim() != "executing" && !l.trim().is_empty())
        .collect();
    Rs274Run {
        ok: out.status.success() && messages.is_empty(),
        canon: String::from_utf8_lossy(&out.stdout).to_string(),
        messages: messages.join("\n"),
    }
}
